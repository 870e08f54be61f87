// The bad-input matrix: malformed invocations of every subcommand, one ctest per subcommand (the
// cases named by its prefix, run one after the other in one process, each in a working folder
// holding the fixture alone; a failure names its case). Every one must
// exit 2, print nothing on stdout and exactly one stderr line "glintlab: error: ..." that names
// the option (or the value) at fault, and leave the working folder exactly as it was (no output,
// no staging or temporary file). The harness itself is tested below: a good invocation fed to it
// must be reported as "not an error".
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <ostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;

// Files every case starts with (a name ending in '/' is a folder); the same set must be there,
// and nothing else, after the run.
const std::vector<std::pair<std::string, std::string>> kFixture = {
    {"q.csv",
     "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\nggx,0.3,0.3,0,0.6,0.8,0.6,0,0.8\n"},
    {"q_alpha_huge.csv",
     "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\nggx,1e308,0.3,0,0.6,0.8,0.6,0,0.8\n"},
    {"q_alpha_zero.csv",
     "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\nggx,0,0.3,0,0.6,0.8,0.6,0,0.8\n"},
    {"q_opposite.csv",
     "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\nggx,0.3,0.3,0,0.6,0.8,0,-0.6,-0.8\n"},
    {"q_alpha_tiny.csv",
     "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\nggx,1e-300,1e-300,0,0.6,0.8,0.6,0,0.8\n"},
    {"q_nan.csv",
     "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\nggx,0.3,0.3,nan,0.6,0.8,0.6,0,0.8\n"},
    {"q_missing.csv",
     "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y\nggx,0.3,0.3,0,0.6,0.8,0.6,0\n"},
    {"q_empty.csv", ""},
    {"q_fields.csv", "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\nggx,0.3,0.3,0,0.6\n"},
    {"m_notunit.csv", "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n0,0,2,0,0,1\n"},
    {"m_unknown.csv", "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,foo\n0,0,1,0,0,1,3\n"},
    {"m_light.csv",
     "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,light_cos_half_angle,light_intensity\n0,0,1,0,0,1,2,1\n"},
    {"blocker", "a file where a folder is expected\n"},
    {"bad.exr", "not an EXR file\n"},
    {"emptydir/", ""},
};

struct Case {
  std::string name;               // its subcommand's prefix (the ctest name's suffix), '_', more
  std::vector<std::string> args;  // glintlab's arguments
  std::string needle;             // must appear in the message: the option or value at fault
};

std::vector<std::string> join(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

std::vector<Case> cases() {
  std::vector<Case> c;
  const auto add = [&](std::string name, std::vector<std::string> args, std::string needle) {
    c.push_back({std::move(name), std::move(args), std::move(needle)});
  };

  // --- top level
  add("top_none", {}, "subcommand");
  add("top_unknown", {"nosuch"}, "nosuch");
  add("top_typo", {"evall"}, "evall");
  add("top_option", {"--bogus"}, "--bogus");
  add("top_option_before", {"-x", "eval"}, "-x");

  // --- eval
  const std::vector<std::string> ev = {"eval", "--in", "q.csv", "--out", "r.csv"};
  add("eval_no_out", {"eval", "--in", "q.csv"}, "--out");
  add("eval_no_in", {"eval", "--out", "r.csv"}, "--in");
  add("eval_in_no_value", {"eval", "--out", "r.csv", "--in"}, "--in");
  add("eval_out_no_value", {"eval", "--in", "q.csv", "--out"}, "--out");
  add("eval_in_missing", {"eval", "--in", "missing.csv", "--out", "r.csv"}, "missing.csv");
  add("eval_out_twice", join(ev, {"--out", "s.csv"}), "--out");
  add("eval_in_twice", join(ev, {"--in", "q.csv"}), "--in");
  add("eval_threads_word", join(ev, {"--threads", "two"}), "--threads");
  add("eval_threads_negative", join(ev, {"--threads", "-1"}), "--threads");
  add("eval_threads_fraction", join(ev, {"--threads", "1.5"}), "--threads");
  add("eval_threads_huge", join(ev, {"--threads", "99999"}), "--threads");
  add("eval_threads_empty", join(ev, {"--threads", ""}), "--threads");
  add("eval_grid_without_model", join(ev, {"--grid", "theta_i=0:90:3"}), "--grid");
  add("eval_isa_without_model", join(ev, {"--isa", "scalar"}), "--isa");
  add("eval_param_without_model", join(ev, {"--param", "alpha_x=1"}), "--param");
  add("eval_alpha_huge", {"eval", "--in", "q_alpha_huge.csv", "--out", "r.csv"}, "alpha_x");
  add("eval_alpha_zero", {"eval", "--in", "q_alpha_zero.csv", "--out", "r.csv"}, "alpha_x");
  add("eval_opposite_directions", {"eval", "--in", "q_opposite.csv", "--out", "r.csv"}, "wo = -wi");
  add("eval_alpha_tiny", {"eval", "--in", "q_alpha_tiny.csv", "--out", "r.csv"}, "alpha_x");
  add("eval_nan", {"eval", "--in", "q_nan.csv", "--out", "r.csv"}, "wi_x");
  add("eval_missing_column", {"eval", "--in", "q_missing.csv", "--out", "r.csv"}, "wo_z");
  add("eval_empty_file", {"eval", "--in", "q_empty.csv", "--out", "r.csv"}, "q_empty.csv");
  add("eval_short_row", {"eval", "--in", "q_fields.csv", "--out", "r.csv"}, "fields");
  add("eval_extra_argument", join(ev, {"extra"}), "extra");
  add("eval_unknown_option", join(ev, {"--bogus"}), "--bogus");
  add("eval_out_under_file", {"eval", "--in", "q.csv", "--out", "blocker/r.csv"}, "--out");
  add("eval_out_unwritable", {"eval", "--in", "q.csv", "--out", "/proc/x/r.csv"}, "--out");
  add("eval_out_is_folder", {"eval", "--in", "q.csv", "--out", "emptydir"}, "--out");
  const std::vector<std::string> em = {"eval", "--model", "smooth_ggx", "--out", "r.csv"};
  add("eval_model_unknown",
      {"eval", "--model", "nosuch", "--grid", "theta_i=0:90:3", "--out", "r.csv"}, "nosuch");
  add("eval_model_empty", {"eval", "--model", "", "--grid", "theta_i=0:90:3", "--out", "r.csv"},
      "--model");
  add("eval_grid_theta_range", join(em, {"--grid", "theta_i=0:200:3"}), "theta_i");
  add("eval_grid_count_zero", join(em, {"--grid", "theta_i=0:90:0"}), "theta_i");
  add("eval_grid_count_fraction", join(em, {"--grid", "theta_i=0:90:2.5"}), "theta_i");
  add("eval_grid_unknown_axis", join(em, {"--grid", "bogus=1:2:3"}), "bogus");
  add("eval_grid_no_count", join(em, {"--grid", "theta_i=0:90"}), "theta_i");
  add("eval_grid_twice", join(em, {"--grid", "theta_i=0:90:3,theta_i=0:90:3"}), "twice");
  add("eval_grid_too_many_rows",
      join(em, {"--grid", "theta_i=0:90:10000,phi_i=0:1:10000,theta_o=0:1:2"}), "rows");
  add("eval_grid_empty", join(em, {"--grid", ""}), "--grid");
  add("eval_grid_nan", join(em, {"--grid", "theta_i=nan:90:3"}), "theta_i");
  add("eval_grid_inf", join(em, {"--grid", "phi_i=0:inf:3"}), "phi_i");
  add("eval_grid_and_in", join(em, {"--grid", "theta_i=0:90:3", "--in", "q.csv"}), "--grid");
  add("eval_model_no_input", em, "--in");
  add("eval_param_zero", join(em, {"--grid", "theta_i=0:90:3", "--param", "alpha_x=0"}), "alpha_x");
  add("eval_param_nan", join(em, {"--grid", "theta_i=0:90:3", "--param", "alpha_x=nan"}),
      "--param alpha_x: 'nan' is not finite");
  add("eval_param_tiny", join(em, {"--grid", "theta_i=0:90:3", "--param", "alpha_x=1e-300"}),
      "alpha_x");
  add("eval_param_huge", join(em, {"--grid", "theta_i=0:90:3", "--param", "alpha_x=1e300"}),
      "alpha_x");
  add("eval_param_old_spelling", join(em, {"--grid", "theta_i=0:90:3", "--param", "sampler=caps"}),
      "sampler");
  add("eval_param_unknown", join(em, {"--grid", "theta_i=0:90:3", "--param", "nosuch=1"}),
      "nosuch");
  add("eval_param_no_value", join(em, {"--grid", "theta_i=0:90:3", "--param", "alpha_x"}),
      "--param");
  add("eval_param_twice",
      join(em, {"--grid", "theta_i=0:90:3", "--param", "alpha_x=1", "--param", "alpha_x=2"}),
      "twice");
  add("eval_isa_unknown", join(em, {"--grid", "theta_i=0:90:3", "--isa", "bogus"}), "--isa");
  add("eval_precision_unknown", join(em, {"--grid", "theta_i=0:90:3", "--precision", "half"}),
      "--precision");
  add("eval_math_fast_double", join(em, {"--grid", "theta_i=0:90:3", "--math", "fast"}), "--math");
  add("eval_model_threads_huge", join(em, {"--grid", "theta_i=0:90:3", "--threads", "2000"}),
      "--threads");
  add("eval_model_not_unit", join(em, {"--in", "m_notunit.csv"}), "wi");
  add("eval_model_unknown_column", join(em, {"--in", "m_unknown.csv"}), "foo");
  add("eval_model_light_range", join(em, {"--in", "m_light.csv"}), "light_cos_half_angle");

  // --- sample
  const std::vector<std::string> sa = {"sample", "--ndf", "ggx", "--wi",  "0,0,1", "--sampler",
                                       "vndf",   "--n",   "10",  "--out", "s.csv"};
  const auto alpha = [&](std::string a) { return join(sa, {"--alpha", std::move(a)}); };
  const std::vector<std::string> s3 = alpha("0.3");
  add("sample_alpha_huge", alpha("1e300"), "--alpha");
  add("sample_alpha_zero", alpha("0"), "--alpha");
  add("sample_alpha_negative", alpha("-1"), "--alpha");
  add("sample_alpha_nan", alpha("nan"), "--alpha");
  add("sample_alpha_inf", alpha("inf"), "--alpha");
  add("sample_alpha_three", alpha("0.3,0.3,0.3"), "--alpha");
  add("sample_alpha_empty", alpha(""), "--alpha");
  add("sample_alpha_word", alpha("rough"), "--alpha");
  add("sample_alpha_overflow", alpha("1e400"), "--alpha");
  add("sample_alpha_y_huge", alpha("0.3,1e300"), "--alpha");
  add("sample_no_alpha", sa, "--alpha");
  add("sample_ndf_unknown",
      {"sample", "--ndf", "phong", "--alpha", "0.3", "--wi", "0,0,1", "--sampler", "vndf", "--n",
       "10", "--out", "s.csv"},
      "phong");
  add("sample_ndf_empty",
      {"sample", "--ndf", "", "--alpha", "0.3", "--wi", "0,0,1", "--sampler", "vndf", "--n", "10",
       "--out", "s.csv"},
      "--ndf");
  add("sample_caps_beckmann",
      {"sample", "--ndf", "beckmann", "--alpha", "0.3", "--wi", "0,0,1", "--sampler",
       "spherical_caps", "--n", "10", "--out", "s.csv"},
      "--sampler");
  const auto with = [&](std::vector<std::string> extra) { return join(s3, extra); };
  add("sample_wi_not_unit", join(alpha("0.3"), {"--wi", "0,0,2"}), "--wi");
  add("sample_wi_two_values",
      {"sample", "--ndf", "ggx", "--alpha", "0.3", "--wi", "0,1", "--sampler", "vndf", "--n", "10",
       "--out", "s.csv"},
      "--wi");
  add("sample_wi_words",
      {"sample", "--ndf", "ggx", "--alpha", "0.3", "--wi", "x,y,z", "--sampler", "vndf", "--n",
       "10", "--out", "s.csv"},
      "--wi");
  add("sample_wi_below_vndf",
      {"sample", "--ndf", "ggx", "--alpha", "0.3", "--wi=1,0,0", "--sampler", "vndf", "--n", "10",
       "--out", "s.csv"},
      "--wi");
  add("sample_sampler_unknown",
      {"sample", "--ndf", "ggx", "--alpha", "0.3", "--wi", "0,0,1", "--sampler", "bogus", "--n",
       "10", "--out", "s.csv"},
      "bogus");
  add("sample_bound_without_bounded", with({"--bound", "exact_isotropic"}), "--bound");
  add("sample_bound_unknown",
      {"sample", "--ndf", "ggx", "--alpha", "0.3", "--wi", "0,0,1", "--sampler", "bounded_caps",
       "--bound", "bogus", "--n", "10", "--out", "s.csv"},
      "bogus");
  const auto n = [&](std::string v) {
    return std::vector<std::string>{"sample", "--ndf", "ggx",       "--alpha", "0.3",
                                    "--wi",   "0,0,1", "--sampler", "vndf",    "--out",
                                    "s.csv",  "--n",   std::move(v)};
  };
  add("sample_n_zero", n("0"), "--n");
  add("sample_n_negative", n("-5"), "--n");
  add("sample_n_fraction", n("1.5"), "--n");
  add("sample_n_exponent", n("1e3"), "--n");
  add("sample_n_too_many", n("1000000001"), "--n");
  add("sample_n_overflow", n("99999999999999999999"), "--n");
  add("sample_n_plus", n("+5"), "--n");
  add("sample_seed_negative", with({"--seed", "-1"}), "--seed");
  add("sample_seed_overflow", with({"--seed", "99999999999999999999"}), "--seed");
  add("sample_seed_fraction", with({"--seed", "1.9"}), "--seed");
  add("sample_seed_word", with({"--seed", "x"}), "--seed");
  add("sample_threads_word", with({"--threads", "two"}), "--threads");
  add("sample_threads_twice", with({"--threads", "1", "--threads", "2"}), "--threads");
  add("sample_isa_without_model", with({"--isa", "scalar"}), "--isa");
  add("sample_param_without_model", with({"--param", "alpha_x=1"}), "--param");
  add("sample_query_without_model", with({"--query", "u=1"}), "--query");
  add("sample_out_under_file",
      {"sample", "--ndf", "ggx", "--alpha", "0.3", "--wi", "0,0,1", "--sampler", "vndf", "--n",
       "10", "--out", "blocker/s.csv"},
      "--out");
  add("sample_out_unwritable",
      {"sample", "--ndf", "ggx", "--alpha", "0.3", "--wi", "0,0,1", "--sampler", "vndf", "--n",
       "10", "--out", "/proc/x.csv"},
      "--out");
  add("sample_no_out",
      {"sample", "--ndf", "ggx", "--alpha", "0.3", "--wi", "0,0,1", "--sampler", "vndf", "--n",
       "10"},
      "--out");
  const std::vector<std::string> sm = {"sample", "--wi",  "0,0,1", "--n",
                                       "10",     "--out", "s.csv", "--model"};
  add("sample_model_footprint_missing", join(sm, {"deliot_belcour"}), "--query");
  add("sample_model_footprint_partial", join(sm, {"deliot_belcour", "--query", "u=0.5"}), "dudx");
  add("sample_model_query_not_needed", join(sm, {"smooth_ggx", "--query", "u=1"}), "--query");
  add("sample_model_query_empty", join(sm, {"smooth_ggx", "--query", ""}), "--query");
  add("sample_model_with_ndf", join(sm, {"smooth_ggx", "--ndf", "ggx"}), "--ndf");
  add("sample_model_unknown", join(sm, {"nosuch"}), "nosuch");
  add("sample_model_param_huge", join(sm, {"smooth_ggx", "--param", "alpha_x=1e300"}), "alpha_x");
  add("sample_model_param_fractional_seed", join(sm, {"kemppinen_ggx", "--param", "seed=1.9"}),
      "seed");
  add("sample_model_seed_negative", join(sm, {"smooth_ggx", "--seed", "-1"}), "--seed");
  add("sample_model_math_unknown", join(sm, {"smooth_ggx", "--precision", "float", "--math", "x"}),
      "--math");
  add("sample_model_no_wi", {"sample", "--n", "10", "--out", "s.csv", "--model", "smooth_ggx"},
      "--wi");

  // --- verify (every case fails before a claim runs)
  const std::vector<std::string> ve = {"verify", "--claims", "eto.bound-is-infimum", "--out", "v"};
  add("verify_budget_unknown", join(ve, {"--budget", "medium"}), "medium");
  add("verify_budget_empty", join(ve, {"--budget", ""}), "--budget");
  add("verify_budget_contradiction", join(ve, {"--budget", "full", "--quick"}), "--quick");
  add("verify_threads_word", join(ve, {"--threads", "two"}), "--threads");
  add("verify_threads_negative", join(ve, {"--threads", "-1"}), "--threads");
  add("verify_threads_fraction", join(ve, {"--threads", "1.5"}), "--threads");
  add("verify_threads_huge", join(ve, {"--threads", "1025"}), "--threads");
  add("verify_threads_twice", join(ve, {"--threads", "1", "--threads", "2"}), "--threads");
  add("verify_claims_empty", {"verify", "--claims", "", "--out", "v"}, "--claims");
  add("verify_claims_nosuch", {"verify", "--claims", "nosuch", "--out", "v"}, "nosuch");
  add("verify_claims_one_unmatched",
      {"verify", "--claims", "eto.bound-is-infimum,nosuch", "--out", "v"}, "nosuch");
  add("verify_claims_spaced_unmatched",
      {"verify", "--claims", "eto.bound-is-infimum, nosuch", "--out", "v"}, "nosuch");
  add("verify_claims_empty_item", {"verify", "--claims", "eto.*,,smooth.*", "--out", "v"},
      "--claims");
  add("verify_claims_only_commas", {"verify", "--claims", " , ", "--out", "v"}, "--claims");
  add("verify_runs_one", join(ve, {"--runs", "1"}), "--runs");
  add("verify_runs_word", join(ve, {"--runs", "x"}), "--runs");
  add("verify_runs_huge", join(ve, {"--runs", "1000000000"}), "--runs");
  add("verify_level_zero", join(ve, {"--level", "0"}), "--level");
  add("verify_level_one", join(ve, {"--level", "1"}), "--level");
  add("verify_level_nan", join(ve, {"--level", "nan"}), "--level");
  add("verify_level_word", join(ve, {"--level", "x"}), "--level");
  add("verify_calibrate_unknown", join(ve, {"--calibrate", "nosuch"}), "nosuch");
  add("verify_calibrate_empty", join(ve, {"--calibrate", ""}), "--calibrate");
  add("verify_list_with_value", {"verify", "--list=3"}, "--list");
  add("verify_unknown_option", join(ve, {"--bogus"}), "--bogus");
  add("verify_extra_argument", join(ve, {"extra"}), "extra");
  add("verify_out_under_file", {"verify", "--claims", "eto.bound-is-infimum", "--out", "blocker/v"},
      "--out");
  add("verify_out_unwritable", {"verify", "--claims", "eto.bound-is-infimum", "--out", "/proc/x"},
      "--out");

  // --- figure (every case fails before the experiment runs)
  const std::vector<std::string> fi = {"figure", "eto2023-fig4", "--out", "f"};
  add("figure_no_id", {"figure", "--out", "f"}, "figure id");
  add("figure_unknown_id", {"figure", "nosuch", "--out", "f"}, "nosuch");
  add("figure_list_and_id", {"figure", "--list", "eto2023-fig4"}, "--list");
  add("figure_list_with_value", {"figure", "--list=1"}, "--list");
  add("figure_quick_with_value", join(fi, {"--quick=1"}), "--quick");
  add("figure_budget_unknown", join(fi, {"--budget", "medium"}), "medium");
  add("figure_budget_contradiction", join(fi, {"--budget", "full", "--quick"}), "--quick");
  add("figure_threads_word", join(fi, {"--threads", "x"}), "--threads");
  add("figure_threads_negative", join(fi, {"--threads", "-1"}), "--threads");
  add("figure_threads_huge", join(fi, {"--threads", "2000"}), "--threads");
  add("figure_out_under_file",
      {"figure", "eto2023-fig4", "--budget", "quick", "--out", "blocker/f"}, "--out");
  add("figure_out_unwritable", {"figure", "eto2023-fig4", "--budget", "quick", "--out", "/proc/x"},
      "--out");
  add("figure_env_missing", join(fi, {"--budget", "quick", "--env", "missing.exr"}), "--env");
  add("figure_env_not_exr", join(fi, {"--budget", "quick", "--env", "bad.exr"}), "--env");
  add("figure_env_empty", join(fi, {"--budget", "quick", "--env", ""}), "--env");
  add("figure_out_empty", {"figure", "eto2023-fig4", "--budget", "quick", "--out", ""}, "--out");
  add("figure_extra_argument", join(fi, {"extra"}), "extra");
  add("figure_unknown_option", join(fi, {"--bogus"}), "--bogus");

  // --- compare (every case fails before a model is measured)
  const std::vector<std::string> co = {"compare", "--budget", "quick", "--out", "c"};
  add("compare_models_empty", join(co, {"--models", ""}), "--models");
  add("compare_models_nosuch", join(co, {"--models", "nosuch"}), "nosuch");
  add("compare_models_one_unmatched", join(co, {"--models", "smooth_ggx,nosuch"}), "nosuch");
  add("compare_models_trailing_comma", join(co, {"--models", "smooth_ggx,"}), "--models");
  add("compare_budget_unknown", {"compare", "--budget", "x", "--out", "c"}, "--budget");
  add("compare_threads_word", join(co, {"--threads", "x"}), "--threads");
  add("compare_claims_from_missing", join(co, {"--claims-from", "missing"}), "--claims-from");
  add("compare_sweeps_from_missing", join(co, {"--sweeps-from", "missing"}), "--sweeps-from");
  add("compare_out_under_file", {"compare", "--budget", "quick", "--out", "blocker/c"}, "--out");
  add("compare_out_unwritable", {"compare", "--budget", "quick", "--out", "/proc/x"}, "--out");
  add("compare_extra_argument", join(co, {"extra"}), "extra");

  // --- models
  add("models_extra_argument", {"models", "extra"}, "extra");
  add("models_unknown_option", {"models", "--bogus"}, "--bogus");

  // --- sweep (every case fails before a plane is swept)
  const std::vector<std::string> sw = {"sweep", "--budget", "quick", "--out", "s"};
  add("sweep_models_empty", join(sw, {"--models", ""}), "--models");
  add("sweep_models_nosuch", join(sw, {"--models", "nosuch"}), "nosuch");
  add("sweep_models_one_unmatched", join(sw, {"--models", "smooth_ggx,nosuch"}), "nosuch");
  add("sweep_models_trailing_comma", join(sw, {"--models", "smooth_ggx,"}), "--models");
  add("sweep_budget_unknown", {"sweep", "--budget", "x", "--out", "s"}, "--budget");
  add("sweep_budget_contradiction", {"sweep", "--budget", "full", "--quick", "--out", "s"},
      "--quick");
  add("sweep_threads_negative", join(sw, {"--threads", "-1"}), "--threads");
  add("sweep_threads_word", join(sw, {"--threads", "x"}), "--threads");
  add("sweep_out_under_file", {"sweep", "--budget", "quick", "--out", "blocker/s"}, "--out");
  add("sweep_out_unwritable", {"sweep", "--budget", "quick", "--out", "/proc/x"}, "--out");
  add("sweep_extra_argument", join(sw, {"extra"}), "extra");

  // --- report (every case fails before a part runs)
  const std::vector<std::string> re = {"report", "--out", "r"};
  add("report_budget_unknown", join(re, {"--budget", "x"}), "--budget");
  add("report_threads_word", join(re, {"--threads", "x"}), "--threads");
  add("report_claims_empty", join(re, {"--claims", ""}), "--claims");
  add("report_claims_nosuch", join(re, {"--claims", "nosuch"}), "nosuch");
  add("report_claims_one_unmatched", join(re, {"--claims", "eto.*,nosuch"}), "nosuch");
  add("report_figures_nosuch", join(re, {"--figures", "nosuch"}), "nosuch");
  add("report_figures_empty", join(re, {"--figures", ""}), "--figures");
  add("report_skip_unknown", join(re, {"--skip", "bogus"}), "bogus");
  add("report_conformance_nosuch", join(re, {"--conformance", "nosuch"}), "nosuch");
  add("report_conformance_empty", join(re, {"--conformance", ""}), "--conformance");
  add("report_skip_empty", join(re, {"--skip", ""}), "--skip");
  add("report_skip_empty_item", join(re, {"--skip", "claims,,bench"}), "--skip");
  add("report_reuse_empty_folder", {"report", "--reuse", "--out", "emptydir"}, "--reuse");
  add("report_reuse_new_folder", {"report", "--reuse", "--out", "new"}, "--reuse");
  add("report_reuse_with_value", {"report", "--reuse=2", "--out", "r"}, "--reuse");
  add("report_claims_from_nowhere", join(re, {"--claims-from", "nowhere"}), "--claims-from");
  add("report_claims_from_empty", join(re, {"--claims-from", ""}), "--claims-from");
  add("report_gpu_from_nowhere", join(re, {"--gpu-from", "nowhere"}), "--gpu-from");
  add("report_gpu_from_empty", join(re, {"--gpu-from", ""}), "--gpu-from");
  add("report_gpu_from_emptydir", join(re, {"--gpu-from", "emptydir"}), "results.json");
  add("report_out_under_file", {"report", "--out", "blocker/r"}, "--out");
  add("report_out_unwritable", {"report", "--out", "/proc/x"}, "--out");
  add("report_out_dot", {"report", "--out", "."}, "--out");
  add("report_extra_argument", join(re, {"extra"}), "extra");

  // --- ltc-fit (every case fails before the fit starts)
  const std::vector<std::string> lt = {"ltc-fit", "--out", "l"};
  add("ltc_size_one", join(lt, {"--size", "1"}), "--size");
  add("ltc_size_huge", join(lt, {"--size", "257"}), "--size");
  add("ltc_size_word", join(lt, {"--size", "x"}), "--size");
  add("ltc_size_fraction", join(lt, {"--size", "1.5"}), "--size");
  add("ltc_samples_small", join(lt, {"--samples", "3"}), "--samples");
  add("ltc_samples_huge", join(lt, {"--samples", "2000"}), "--samples");
  add("ltc_threads_negative", join(lt, {"--threads", "-1"}), "--threads");
  add("ltc_threads_word", join(lt, {"--threads", "x"}), "--threads");
  add("ltc_out_unwritable", {"ltc-fit", "--out", "/proc/x"}, "--out");
  add("ltc_out_under_file", {"ltc-fit", "--out", "blocker/l"}, "--out");
  add("ltc_extra_argument", join(lt, {"extra"}), "extra");

  // --- chermain-dictionary
  const std::vector<std::string> ch = {"chermain-dictionary", "--out", "d.exr"};
  add("chermain_no_out", {"chermain-dictionary"}, "--out");
  add("chermain_seed_negative", join(ch, {"--seed", "-1"}), "--seed");
  add("chermain_seed_overflow", join(ch, {"--seed", "99999999999999999999"}), "--seed");
  add("chermain_seed_fraction", join(ch, {"--seed", "1.9"}), "--seed");
  add("chermain_seed_word", join(ch, {"--seed", "x"}), "--seed");
  add("chermain_distributions_not_multiple", join(ch, {"--distributions", "4"}), "distributions");
  add("chermain_distributions_zero", join(ch, {"--distributions", "0"}), "--distributions");
  add("chermain_distributions_negative", join(ch, {"--distributions", "-3"}), "--distributions");
  add("chermain_levels_zero", join(ch, {"--levels", "0"}), "--levels");
  add("chermain_levels_huge", join(ch, {"--levels", "21"}), "--levels");
  add("chermain_resolution_not_power", join(ch, {"--resolution", "5"}), "resolution");
  add("chermain_resolution_huge", join(ch, {"--resolution", "8192"}), "--resolution");
  add("chermain_alpha_zero", join(ch, {"--alpha-dict", "0"}), "alpha");
  add("chermain_alpha_nan", join(ch, {"--alpha-dict", "nan"}), "--alpha-dict");
  add("chermain_alpha_word", join(ch, {"--alpha-dict", "x"}), "--alpha-dict");
  add("chermain_lobe_std_zero", join(ch, {"--lobe-std", "0"}), "lobe");
  add("chermain_lobe_std_inf", join(ch, {"--lobe-std", "inf"}), "--lobe-std");
  add("chermain_threads_word", join(ch, {"--threads", "x"}), "--threads");
  add("chermain_out_unwritable", {"chermain-dictionary", "--out", "/proc/x.exr"}, "--out");
  add("chermain_out_under_file", {"chermain-dictionary", "--out", "blocker/d.exr"}, "--out");
  add("chermain_out_is_folder", {"chermain-dictionary", "--out", "emptydir"}, "--out");
  return c;
}

// The checks every case gets; a separate function so that the harness test below can feed it a
// good invocation.
void expect_rejected(const RunResult& r, const std::string& needle, const fs::path& work) {
  EXPECT_EQ(r.exit_code, 2) << "not an error: the invocation was accepted or failed otherwise; "
                               "stderr: "
                            << r.err;
  EXPECT_EQ(r.out, "") << "a rejected invocation printed on stdout";
  const std::vector<std::string> lines = lines_of(r.err);
  EXPECT_EQ(lines.size(), 1u) << "stderr must be exactly one line: " << r.err;
  if (!lines.empty()) {
    EXPECT_EQ(lines[0].rfind("glintlab: error: ", 0), 0u) << lines[0];
    EXPECT_NE(lines[0].find(needle), std::string::npos)
        << "the message does not name '" << needle << "': " << lines[0];
  }
  std::set<std::string> expected;
  for (const auto& [name, text] : kFixture)
    expected.insert(name.back() == '/' ? name.substr(0, name.size() - 1) : name);
  EXPECT_EQ(unexpected_files(work, expected), std::vector<std::string>{})
      << "a rejected invocation left files behind";
}

// The cases whose names start with the same prefix (up to the first '_': the subcommand, or
// "top" for the invocations without one), in the order of cases().
struct CaseGroup {
  std::string prefix;
  std::vector<Case> cases;
};

// How GoogleTest prints a group in the ctest name's "GetParam() = ..." comment (by default the
// object's bytes, pointers included, which would change the name from one build to the next).
void PrintTo(const CaseGroup& g, std::ostream* os) {
  *os << g.prefix << ": " << g.cases.size() << " cases";
}

std::vector<CaseGroup> case_groups() {
  std::vector<CaseGroup> groups;
  for (const Case& c : cases()) {
    const std::string prefix = c.name.substr(0, c.name.find('_'));
    auto g = std::find_if(groups.begin(), groups.end(),
                          [&](const CaseGroup& x) { return x.prefix == prefix; });
    if (g == groups.end()) g = groups.insert(groups.end(), CaseGroup{prefix, {}});
    g->cases.push_back(c);
  }
  return groups;
}

// The working folder holding the fixture's files alone.
class BadInputFixture : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    write_fixture();
  }
  void write_fixture() const {
    for (const auto& [name, text] : kFixture) {
      if (name.back() == '/') {
        fs::create_directories(path(name.substr(0, name.size() - 1)));
      } else {
        write_text(path(name), text);
      }
    }
  }
  // Empties the working folder and writes the fixture again: each case starts as if alone.
  void reset_work() const {
    for (const auto& e : fs::directory_iterator(work())) fs::remove_all(e.path());
    write_fixture();
  }
};

class BadInputMatrix : public BadInputFixture, public ::testing::WithParamInterface<CaseGroup> {};

TEST_P(BadInputMatrix, Rejected) {
  for (const Case& c : GetParam().cases) {
    std::string invocation = "glintlab";
    for (const std::string& a : c.args) invocation += " '" + a + "'";
    SCOPED_TRACE("case " + c.name + ": " + invocation);
    reset_work();
    expect_rejected(run(c.args), c.needle, work());
  }
}

INSTANTIATE_TEST_SUITE_P(Cli, BadInputMatrix, ::testing::ValuesIn(case_groups()),
                         [](const ::testing::TestParamInfo<CaseGroup>& p) { return p.param.prefix; });

TEST(BadInputMatrixSize, AtLeast150CasesOverEverySubcommand) {
  const std::vector<Case> all = cases();
  EXPECT_GE(all.size(), 150u);
  std::set<std::string> names;
  for (const Case& c : all) {
    EXPECT_TRUE(names.insert(c.name).second) << "duplicate case name " << c.name;
  }
  // Every case is run in one group, and the groups are a few ctest tests.
  std::size_t grouped = 0;
  for (const CaseGroup& g : case_groups()) grouped += g.cases.size();
  EXPECT_EQ(grouped, all.size());
  EXPECT_LE(case_groups().size(), 20u);
  for (const std::string sub : {"eval", "sample", "verify", "figure", "models", "sweep", "report",
                                "ltc-fit", "chermain-dictionary", "compare"}) {
    bool seen = false;
    for (const Case& c : all) seen = seen || (!c.args.empty() && c.args[0] == sub);
    EXPECT_TRUE(seen) << "no malformed invocation of " << sub;
  }
}

// The harness catches an accepted invocation: a good one run through expect_rejected fails as
// "not an error", and one that writes its output fails as "left files behind".
using BadInputHarness = BadInputFixture;

// The failure messages expect_rejected reports for `r` (intercepted, so they do not fail this
// test).
std::string failures_of(const RunResult& r, const std::string& needle, const fs::path& work) {
  ::testing::TestPartResultArray results;
  {
    ::testing::ScopedFakeTestPartResultReporter reporter(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
    expect_rejected(r, needle, work);
  }
  std::string all;
  for (int i = 0; i < results.size(); ++i)
    all += std::string(results.GetTestPartResult(i).message()) + "\n";
  return all;
}

TEST_F(BadInputHarness, AcceptedInvocationIsCaughtAsNotAnError) {
  const RunResult good = run({"models"});
  ASSERT_EQ(good.exit_code, 0);
  EXPECT_NE(failures_of(good, "models", work()).find("not an error"), std::string::npos);
}

TEST_F(BadInputHarness, AcceptedInvocationThatWritesIsCaughtAsLeavingFiles) {
  const RunResult good = run({"eval", "--in", "q.csv", "--out", "r.csv"});
  ASSERT_EQ(good.exit_code, 0) << good.err;
  const std::string f = failures_of(good, "--out", work());
  EXPECT_NE(f.find("not an error"), std::string::npos) << f;
  EXPECT_NE(f.find("left files behind"), std::string::npos) << f;
}

TEST_F(BadInputHarness, MessageWithoutTheOptionIsCaught) {
  const RunResult bad = run({"sample", "--ndf", "ggx", "--alpha", "0", "--wi", "0,0,1", "--sampler",
                             "vndf", "--n", "10", "--out", "s.csv"});
  const std::string f = failures_of(bad, "--threads", work());
  EXPECT_NE(f.find("does not name"), std::string::npos) << f;
  EXPECT_EQ(f.find("not an error"), std::string::npos) << f;
}

// Output larger than the free space is refused before anything is written (only where the file
// system has less room than the ~160 GB a billion rows would take, so a big disk is not filled).
TEST_F(BadInputHarness, OutputLargerThanFreeSpaceIsRefused) {
  struct statvfs s {};
  ASSERT_EQ(::statvfs(work().c_str(), &s), 0);
  const double free_gb = double(s.f_bavail) * double(s.f_frsize) / 1e9;
  if (free_gb > 100) GTEST_SKIP() << "the disk has " << free_gb << " GB free";
  expect_rejected(run({"sample", "--ndf", "ggx", "--alpha", "0.3", "--wi", "0,0,1", "--sampler",
                       "vndf", "--n", "1000000000", "--out", "s.csv"}),
                  "--out", work());
  expect_rejected(run({"sample", "--model", "smooth_ggx", "--wi", "0,0,1", "--n", "1000000000",
                       "--out", "s.csv"}),
                  "--out", work());
}

}  // namespace
}  // namespace glintlab::cli_test

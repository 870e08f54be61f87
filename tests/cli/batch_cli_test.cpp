// The batched CLI forms: `glintlab eval --model` (--in or --grid) and `glintlab sample --model`
// with --isa/--precision/--math/--threads: values of the model, identical output for any thread
// count, one-line errors.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "cli/cli_test_util.h"
#include "core/math/rng.h"
#include "core/model_registry.h"
#include "core/simd/batch.h"

namespace glintlab::cli_test {
namespace {

using BatchCliTest = CliTest;

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST_F(BatchCliTest, GridRowsAndColumnsAreTheModel) {
  const RunResult r = run({"eval", "--model", "smooth_beckmann", "--param", "alpha_x=0.2", "--grid",
                           "theta_i=0:60:3,theta_o=0:90:4,phi_o=0:180:2", "--out", "g.csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::CsvTable t = io::read_csv(path("g.csv"));
  ASSERT_EQ(t.num_rows(), 3u * 4u * 2u);
  EXPECT_EQ(t.header().front(), "theta_i");
  // Row 13: theta_i = 30 (second), theta_o = 60 (third), phi_o = 180 (second).
  EXPECT_EQ(cell_value(t, 13, t.column("theta_i")), 30.0);
  EXPECT_EQ(cell_value(t, 13, t.column("theta_o")), 60.0);
  EXPECT_EQ(cell_value(t, 13, t.column("phi_o")), 180.0);
  const ModelEntry& m = find_model("smooth_beckmann");
  const std::vector<double> params = resolve_params(m, {{"alpha_x", "0.2"}});
  ModelQuery<double> q{};
  q.wi = {cell_value(t, 13, t.column("wi_x")), cell_value(t, 13, t.column("wi_y")),
          cell_value(t, 13, t.column("wi_z"))};
  q.wo = {cell_value(t, 13, t.column("wo_x")), cell_value(t, 13, t.column("wo_y")),
          cell_value(t, 13, t.column("wo_z"))};
  q.light = {1, 1};
  const ErasedEval e = m.eval(params, q);
  // Batched (exp/erfc of xsimd): within the Beckmann budget of tests/simd/ (128 double ulps).
  EXPECT_NEAR(cell_value(t, 13, t.column("value")), e.value, 1e-13 * e.value);
  EXPECT_NEAR(cell_value(t, 13, t.column("pdf")), e.pdf, 1e-13 * e.pdf);
}

TEST_F(BatchCliTest, EvalOutputIsTheSameForAnyThreadCountAndGgxForAnyIsa) {
  const std::vector<std::string> base = {"eval", "--model", "smooth_ggx", "--grid",
                                         "theta_i=0:89:40,theta_o=0:180:60,phi_o=0:360:7"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = base;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  ASSERT_EQ(run(with({"--threads", "1", "--out", "t1.csv"})).exit_code, 0);
  ASSERT_EQ(run(with({"--threads", "2", "--out", "t2.csv"})).exit_code, 0);
  EXPECT_EQ(slurp(path("t1.csv")), slurp(path("t2.csv")));
  // GGX is bit-identical between the scalar kernels and every ISA (IEEE ops only): the default
  // (the best this CPU has) and each ISA by name.
  ASSERT_EQ(run(with({"--isa", "scalar", "--out", "s.csv"})).exit_code, 0);
  EXPECT_EQ(slurp(path("s.csv")), slurp(path("t1.csv")));
  for (simd::Isa isa : {simd::Isa::kSse42, simd::Isa::kAvx2, simd::Isa::kAvx512}) {
    const std::string name(simd::isa_name(isa));
    if (!simd::isa_supported(isa)) {
      std::printf("%s: this CPU lacks it, its CLI output is not compared\n", name.c_str());
      continue;
    }
    ASSERT_EQ(run(with({"--isa", name, "--out", name + ".csv"})).exit_code, 0);
    EXPECT_EQ(slurp(path("s.csv")), slurp(path(name + ".csv"))) << name;
  }
  // A different precision is a different file (the control of the comparisons above).
  ASSERT_EQ(run(with({"--precision", "float", "--out", "f.csv"})).exit_code, 0);
  EXPECT_NE(slurp(path("f.csv")), slurp(path("t1.csv")));
}

TEST_F(BatchCliTest, SampleModelIsTheModelsSamplerForAnyThreadCount) {
  const std::vector<std::string> base = {"sample",      "--model", "smooth_ggx", "--param",
                                         "sampler=ndf", "--wi",    "0.6,0,0.8",  "--n",
                                         "20000",       "--seed",  "7"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = base;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  ASSERT_EQ(run(with({"--threads", "1", "--out", "a.csv"})).exit_code, 0);
  ASSERT_EQ(run(with({"--threads", "2", "--out", "b.csv"})).exit_code, 0);
  EXPECT_EQ(slurp(path("a.csv")), slurp(path("b.csv")));
  ASSERT_EQ(run(with({"--isa", "scalar", "--out", "c.csv"})).exit_code, 0);
  const io::CsvTable t = io::read_csv(path("c.csv"));
  ASSERT_EQ(t.num_rows(), 20000u);
  const ModelEntry& m = find_model("smooth_ggx");
  const std::vector<double> params = resolve_params(m, {{"sampler", "ndf"}});
  ModelQuery<double> q{};
  q.wi = {0.6, 0, 0.8};
  q.light = {1, 1};
  for (std::size_t i : {std::size_t(0), std::size_t(4097), std::size_t(19999)}) {
    const Vec2<double> u{counter_uniform<double>(7, i, 0), counter_uniform<double>(7, i, 1)};
    const ModelSample<double> s = m.sample(params, q, u);
    EXPECT_EQ(cell_value(t, i, t.column("wo_x")), s.wo.x) << i;
    EXPECT_EQ(cell_value(t, i, t.column("pdf")), s.pdf) << i;
    EXPECT_EQ(cell_value(t, i, t.column("weight")), s.weight) << i;
  }
}

TEST_F(BatchCliTest, BadBatchArgumentsAreOneLine) {
  write_text(path("q.csv"), "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n0,0,1,0,0,1\n");
  expect_input_error(run({"eval", "--model", "smooth_ggx", "--in", "q.csv", "--grid",
                          "theta_i=0:1:2", "--out", "r.csv"}),
                     {"--grid", "--in"}, {"q.csv"});
  expect_input_error(
      run({"eval", "--model", "smooth_ggx", "--grid", "theta_i=0:200:2", "--out", "r.csv"}),
      {"--grid theta_i", "out of range", "[0, 180]"}, {"q.csv"});
  expect_input_error(
      run({"eval", "--model", "smooth_ggx", "--grid", "theta_i=0:10:0", "--out", "r.csv"}),
      {"--grid theta_i", "out of range"}, {"q.csv"});
  expect_input_error(
      run({"eval", "--model", "smooth_ggx", "--grid", "theta_x=0:10:2", "--out", "r.csv"}),
      {"--grid", "theta_x", "theta_i, phi_i, theta_o, phi_o"}, {"q.csv"});
  expect_input_error(
      run({"eval", "--model", "smooth_ggx", "--in", "q.csv", "--isa", "avx9", "--out", "r.csv"}),
      {"--isa", "'avx9'", "scalar, sse4.2, avx2, avx512"}, {"q.csv"});
  expect_input_error(
      run({"eval", "--model", "smooth_ggx", "--in", "q.csv", "--math", "fast", "--out", "r.csv"}),
      {"--math", "--precision float"}, {"q.csv"});
  expect_input_error(
      run({"eval", "--model", "smooth_ggx", "--in", "q.csv", "--threads", "-1", "--out", "r.csv"}),
      {"--threads", "[0, 1024]"}, {"q.csv"});
  expect_input_error(run({"eval", "--in", "q.csv", "--isa", "avx2", "--out", "r.csv"}),
                     {"needs --model"}, {"q.csv"});
  expect_input_error(run({"sample", "--model", "smooth_ggx", "--sampler", "vndf", "--wi", "0,0,1",
                          "--n", "3", "--out", "r.csv"}),
                     {"--sampler", "does not apply with --model"}, {"q.csv"});
  expect_input_error(run({"sample", "--model", "smooth_ggx", "--n", "3", "--out", "r.csv"}),
                     {"--wi", "required"}, {"q.csv"});
  expect_input_error(
      run({"sample", "--model", "smooth_ggx", "--wi", "0,0,2", "--n", "3", "--out", "r.csv"}),
      {"--wi"}, {"q.csv"});
  for (simd::Isa isa : simd::kAllIsas) {
    if (simd::isa_supported(isa)) continue;
    expect_input_error(run({"eval", "--model", "smooth_ggx", "--in", "q.csv", "--isa",
                            std::string(simd::isa_name(isa)), "--out", "r.csv"}),
                       {"--isa", "not supported by this CPU"}, {"q.csv"});
  }
}

}  // namespace
}  // namespace glintlab::cli_test

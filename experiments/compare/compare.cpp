#include "experiments/compare/compare.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "core/io/atomic_file.h"
#include "core/math/rng.h"
#include "core/model_registry.h"
#include "experiments/compare/albedo_estimates.h"
#include "experiments/compare/eval_timing.h"
#include "experiments/compare/model_findings.h"
#include "experiments/sweeps/stability_run.h"
#include "verify/conformance/common.h"
#include "verify/stability/sweep.h"

namespace glintlab::experiments::compare {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

fs::path claims_name(const CompareOptions& o) {
  return o.claims_shown_as.empty() ? o.claims_from : o.claims_shown_as;
}
fs::path conformance_name(const CompareOptions& o) {
  return o.conformance_shown_as.empty() ? o.conformance_from : o.conformance_shown_as;
}
fs::path sweeps_name(const CompareOptions& o) {
  return o.sweeps_shown_as.empty() ? o.sweeps_from : o.sweeps_shown_as;
}

// A JSON number, or null where it is not finite (JSON has no NaN).
json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

std::uint64_t seed_of(const ModelEntry& m, std::string_view what) {
  return hash_string(fmt::format("compare.{}.{}", m.name, what).c_str());
}

std::string light_of(const ModelEntry& m) {
  return (m.needs & kNeedsAreaLight) ? "1° cone" : "delta";
}

json model_json(const ModelEntry& m, const CompareOptions& o, const CompareBudget& b) {
  const auto step = [&](const std::string& what) {
    if (o.progress) o.progress(fmt::format("{} {}", m.name, what));
  };
  json j;
  j["name"] = m.name;
  j["source"] = m.source;
  j["footprint"] = (m.needs & kNeedsFootprint) != 0;
  j["light"] = light_of(m);
  j["smooth_limit"] = m.smooth_limit.empty() ? json(nullptr) : json(m.smooth_limit);

  step("conformance");
  json verdicts = json::array();
  std::vector<ClaimsFolder> folders;
  if (!o.conformance_from.empty()) folders.push_back({o.conformance_from, conformance_name(o)});
  if (!o.claims_from.empty()) folders.push_back({o.claims_from, claims_name(o)});
  for (const PropertyVerdict& v : conformance_verdicts(m, o.budget, folders, o.measure_missing))
    verdicts.push_back({{"property", v.property},
                        {"verdict", v.verdict},
                        {"origin", v.origin},
                        {"control_rejected",
                         v.control_rejected ? json(*v.control_rejected) : json(nullptr)},
                        {"detail", v.detail}});
  j["conformance"] = verdicts;

  step("timing");
  const EvalTiming t = time_evaluations(m, b);
  j["timing"] = {{"scalar_ns_per_eval", t.scalar_ns},
                 {"best_isa", t.best_isa},
                 {"best_ns_per_eval", t.best_ns},
                 {"batched", t.batched}};

  step("reference");
  std::vector<AlbedoReference> refs;
  json references = json::array();
  for (double theta : b.thetas_deg) {
    refs.push_back(reference_albedo(m, theta, b, seed_of(m, fmt::format("reference.{:g}", theta))));
    const AlbedoReference& r = refs.back();
    // A reference that did not converge is flagged, and its value withheld.
    references.push_back({{"theta_deg", theta},
                          {"method", r.method},
                          {"converged", r.converged},
                          {"albedo", r.converged ? number(r.value) : json(nullptr)},
                          {"error", r.converged ? number(r.error) : json(nullptr)}});
  }
  j["reference"] = references;

  step("equal-time curve");
  const EqualTimeCurve c = equal_time_curve(m, refs, b, seed_of(m, "sampler"));
  json points = json::array();
  for (const EqualTimePoint& p : c.points)
    points.push_back(
        {{"samples", p.samples}, {"seconds", p.seconds}, {"relative_rmse", number(p.relative_rmse)}});
  j["equal_time"] = {{"isa", c.isa},
                     {"points", points},
                     {"reference_relative_error",
                      c.reason.empty() ? number(c.reference_relative_error) : json(nullptr)},
                     {"relative_bias", c.reason.empty() ? number(c.relative_bias) : json(nullptr)},
                     {"relative_bias_se",
                      c.reason.empty() ? number(c.relative_bias_se) : json(nullptr)},
                     {"not_shown", c.reason.empty() ? json(nullptr) : json(c.reason)}};

  step("stability");
  json stability = json::array();
  for (const StabilityFinding& s : stability_findings(m, o.budget, o.sweeps_from, sweeps_name(o),
                                                            o.measure_missing))
    stability.push_back({{"sampler", s.sampler},
                         {"verdict", s.verdict},
                         {"origin", s.origin},
                         {"failure_region", s.failure_region}});
  j["stability"] = stability;
  return j;
}

// "holds 7, fails 1, not-claimed 2" over a model's conformance rows.
std::string verdict_counts(const json& verdicts) {
  std::vector<std::pair<std::string, int>> counts;
  for (const json& v : verdicts) {
    const std::string origin = v.at("origin");
    const std::string verdict =
        v.at("verdict").get<std::string>() + (origin == kMeasured ? "" : " (" + origin + ")");
    auto it = std::find_if(counts.begin(), counts.end(),
                           [&](const auto& c) { return c.first == verdict; });
    if (it == counts.end())
      counts.emplace_back(verdict, 1);
    else
      ++it->second;
  }
  std::string out;
  for (const auto& [v, n] : counts) out += fmt::format("{}{} {}", out.empty() ? "" : "; ", v, n);
  return out;
}

std::string csv_field(const std::string& s) {
  std::string q = "\"";
  for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

std::string csv_number(const json& x) { return x.is_null() ? "" : fmt::format("{:.6g}", x.get<double>()); }

std::string models_csv(const json& models) {
  std::ostringstream s;
  s << "model,conformance,scalar_ns_per_eval,best_isa,best_ns_per_eval,reference_converged,"
       "relative_rmse_at_max_samples,relative_bias,relative_bias_se,stability\n";
  for (const json& m : models) {
    bool converged = true;
    for (const json& r : m["reference"]) converged = converged && r["converged"].get<bool>();
    const json& points = m["equal_time"]["points"];
    std::string stability;
    for (const json& st : m["stability"])
      stability += fmt::format("{}{}: {}", stability.empty() ? "" : "; ",
                               st["sampler"].get<std::string>(), st["verdict"].get<std::string>());
    s << m["name"].get<std::string>() << ',' << csv_field(verdict_counts(m["conformance"])) << ','
      << csv_number(m["timing"]["scalar_ns_per_eval"]) << ','
      << m["timing"]["best_isa"].get<std::string>() << ','
      << csv_number(m["timing"]["best_ns_per_eval"]) << ',' << (converged ? "yes" : "no") << ','
      << (points.empty() ? "" : csv_number(points.back()["relative_rmse"])) << ','
      << csv_number(m["equal_time"]["relative_bias"]) << ','
      << csv_number(m["equal_time"]["relative_bias_se"]) << ',' << csv_field(stability) << '\n';
  }
  return s.str();
}

std::string equal_time_csv(const json& models) {
  std::ostringstream s;
  s << "model,samples,seconds,relative_rmse\n";
  for (const json& m : models)
    for (const json& p : m["equal_time"]["points"])
      s << m["name"].get<std::string>() << ',' << p["samples"].get<std::uint64_t>() << ','
        << fmt::format("{:.6g}", p["seconds"].get<double>()) << ','
        << csv_number(p["relative_rmse"]) << '\n';
  return s.str();
}

json settings_json(const CompareOptions& o, const CompareBudget& b) {
  json s = {{"budget", o.budget == verify::Budget::kQuick ? "quick" : "full"},
          {"theta_deg", b.thetas_deg},
          {"footprint_side_uv", kSceneFootprint},
          {"quantity", "albedo: ∫ value dωo over the upper hemisphere (white furnace)"},
          {"reference_monte_carlo_block", verify::conformance::reference_block(o.budget)},
          {"reference_monte_carlo_max_blocks", verify::conformance::kMaxReferenceBlocks},
          {"reference_monte_carlo_target_relative_error",
           verify::conformance::kReferenceRelativeError},
          {"cubature_converged_relative_error", b.cubature_converged_rel},
          {"monte_carlo_converged_relative_error", b.monte_carlo_converged_rel},
          {"max_samples", b.max_samples},
          {"repetitions", b.repetitions},
          {"timing_rows", b.timing_rows},
          {"timing_seconds_per_round", b.timing_seconds},
          {"claims_from", o.claims_from.empty() ? json(nullptr) : json(claims_name(o).string())},
          {"sweeps_from", o.sweeps_from.empty() ? json(nullptr) : json(sweeps_name(o).string())}};
  if (!o.conformance_from.empty()) s["conformance_from"] = conformance_name(o).string();
  return s;
}

}  // namespace

CompareFiles run_compare(const fs::path& dir, const CompareOptions& o) {
  const CompareBudget b = compare_budget(o.budget);
  // A model's stability is swept once: by its conformance suite's stability property where that
  // runs here, and the same sweep gives the failure regions.
  const verify::stability::SweepReuse one_sweep_per_model;
  json models = json::array();
  for (const std::string& name : o.models) models.push_back(model_json(find_model(name), o, b));
  json doc;
  doc["machine"] = machine_name();
  doc["settings"] = settings_json(o, b);
  doc["models"] = models;
  const CompareFiles files{dir / "compare.json", dir / "compare.csv", dir / "equal_time.csv"};
  io::write_file_atomic(files.json, doc.dump(1) + "\n");
  io::write_file_atomic(files.csv, models_csv(models));
  io::write_file_atomic(files.equal_time_csv, equal_time_csv(models));
  return files;
}

}  // namespace glintlab::experiments::compare

#include "experiments/compare/model_findings.h"

#include <fmt/format.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "core/model_list.h"
#include "verify/conformance/conformance.h"
#include "verify/stability/failure_region.h"
#include "verify/stability/sweep.h"
#include "verify/stability/sweep_plan.h"

namespace glintlab::experiments::compare {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json read_json(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);  // the CLI checked that the file exists; a parse error is reported
}

// The models compiled into glintlab (the first BuiltinModels::kSize entries of the registry) have
// recorded conformance verdicts; a plug-in has none.
bool is_builtin(const ModelEntry& m) {
  const auto& all = registered_models();
  for (std::size_t i = 0; i < BuiltinModels::kSize && i < all.size(); ++i)
    if (&all[i] == &m) return true;
  return false;
}

std::string check_id(const ModelEntry& m, std::string_view property) {
  return fmt::format("model.{}.{}", m.name, property);
}

}  // namespace

std::vector<PropertyVerdict> conformance_verdicts(
    const ModelEntry& m, verify::Budget b, const std::vector<ClaimsFolder>& folders, bool measure,
    const std::map<std::string, verify::CheckResult>& measured) {
  std::map<std::string, json> read;
  std::string looked;  // the claims.json files read, as shown
  for (const ClaimsFolder& f : folders) {
    for (const json& row : read_json(f.read_from / "claims.json"))
      read.emplace(row.value("id", std::string()), row);  // an earlier folder's row wins
    looked += fmt::format("{}{}", looked.empty() ? "" : " and ",
                          ((f.shown_as.empty() ? f.read_from : f.shown_as) / "claims.json").string());
  }
  std::vector<PropertyVerdict> out;
  std::vector<verify::Check> checks;
  const bool run_here = folders.empty() && measure;
  if (run_here) checks = verify::conformance_checks(m);
  for (std::string_view property : verify::conformance::kProperties) {
    if (!verify::conformance::applies(property, m)) continue;
    const std::string id = check_id(m, property);
    PropertyVerdict v{std::string(property), "", "", "", std::nullopt};
    if (auto it = read.find(id); it != read.end()) {
      v.verdict = it->second.value("verdict", std::string());
      v.origin = kRead;
      v.detail = it->second.value("detail", std::string());
      v.control_rejected = it->second.value("control_rejected", false);
    } else if (run_here) {
      for (const verify::Check& c : checks) {
        if (c.id != id) continue;
        const auto done = measured.find(id);
        const verify::CheckResult r = done != measured.end() ? done->second : c.run(b);
        v.verdict = verify::to_string(r.verdict);
        v.origin = kMeasured;
        v.detail = r.detail;
        v.control_rejected = r.control_rejected;
      }
    } else if (auto reason = verify::conformance::not_claimed_reason(property, m)) {
      v.verdict = verify::to_string(verify::Verdict::kNotClaimed);
      v.origin = kDeclared;
      v.detail = *reason;
    } else if (is_builtin(m)) {
      for (const verify::Check& c : verify::conformance_checks(m))
        if (c.id == id) v.verdict = verify::to_string(c.expected_for(b));
      v.origin = kRecorded;
      v.detail = folders.empty()
                     ? std::string("the verdict recorded for this budget; not measured here")
                     : fmt::format("the verdict recorded for this budget; {} has no row {}",
                                   looked, id);
    } else {
      v.verdict = "-";
      v.origin = kNotMeasured;
      v.detail = fmt::format("not measured here and no recorded verdict (run glintlab verify "
                             "--claims 'model.{}.*')",
                             m.name);
    }
    out.push_back(std::move(v));
  }
  return out;
}

std::vector<StabilityFinding> stability_findings(const ModelEntry& m, verify::Budget b,
                                                 const fs::path& sweeps_from,
                                                 const fs::path& shown_as, bool measure) {
  std::vector<StabilityFinding> out;
  if (sweeps_from.empty() && !measure)
    return {{"-", "-", "no stability sweep in this run", kNotMeasured}};
  if (!sweeps_from.empty()) {
    const json doc = read_json(sweeps_from / "stability.json");
    for (const json& e : doc.at("models"))
      if (e.value("model", std::string()) == m.name)
        out.push_back({e.value("sampler", std::string()), e.value("verdict", std::string()),
                       e.value("failure_region", std::string()), kRead});
    if (out.empty())
      out.push_back({"-", "-",
                     fmt::format("{} has no entry for this model",
                                 (shown_as / "stability.json").string()),
                     kNotMeasured});
    return out;
  }
  namespace st = verify::stability;
  for (const st::SweepTarget& t : st::sweep_targets(std::string(m.name))) {
    if (t.model != &m) continue;
    const st::ModelSweep s = st::sweep_model(t, b);
    out.push_back({t.sampler, verify::to_string(st::stability_verdict(s)),
                   st::describe_failure_region(s), kMeasured});
  }
  return out;
}

}  // namespace glintlab::experiments::compare

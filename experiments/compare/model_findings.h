// A model's conformance verdicts and stability failure regions for the comparison, each labelled
// with where it comes from: measured in this run, read from an earlier run's output folder, or the
// registry's recorded verdict (never passed off as measured).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/model_registry.h"
#include "verify/check.h"

namespace glintlab::experiments::compare {

// Where a verdict shown by compare comes from.
inline constexpr const char* kMeasured = "measured";  // by this compare run
inline constexpr const char* kRead = "read";          // from a glintlab verify / sweep --out folder
inline constexpr const char* kRecorded = "recorded";  // the registry's recorded verdict
inline constexpr const char* kDeclared = "declared";  // a property the model does not claim
inline constexpr const char* kNotMeasured = "not measured";  // nothing measured nor recorded

struct PropertyVerdict {
  std::string property, verdict, origin, detail;
  std::optional<bool> control_rejected;  // measured or read rows only
};

// A `glintlab verify --out` folder whose claims.json rows compare reads, and how the outputs name
// it (the report reads its staging folder but shows the folder it becomes).
struct ClaimsFolder {
  std::filesystem::path read_from, shown_as;
};

// Every conformance property of `m` (kProperties order, those that apply): the row of the first
// folder's claims.json that has it; otherwise, with no folder and with `measure`, measured here by
// the model's own conformance checks; otherwise "not-claimed" where the model declares so, the
// verdict recorded for budget b for a built-in model, and nothing for a plug-in. Messages name the
// folders as shown.
// `measured`: the results of m's conformance checks already run (by check id), used instead of
// running a check again where one is to be measured here.
std::vector<PropertyVerdict> conformance_verdicts(
    const ModelEntry& m, verify::Budget b, const std::vector<ClaimsFolder>& folders, bool measure,
    const std::map<std::string, verify::CheckResult>& measured = {});

struct StabilityFinding {
  std::string sampler, verdict, failure_region, origin;
};

// Per sampler of `m`: the entries of stability.json in `sweeps_from`, else (with `measure`) the
// sweep run here, else one "not measured" row.
std::vector<StabilityFinding> stability_findings(const ModelEntry& m, verify::Budget b,
                                                 const std::filesystem::path& sweeps_from,
                                                 const std::filesystem::path& shown_as,
                                                 bool measure);

}  // namespace glintlab::experiments::compare

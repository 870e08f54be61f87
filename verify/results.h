// Serialisation of a verify run: claims.json (for tools and the report), claims.csv, claims.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "verify/check.h"

namespace glintlab::verify {

struct RunRecord {
  const Check* check;
  CheckResult result;
  double seconds;
  Budget budget = Budget::kQuick;
  // Holm–Šidák adjusted p-value over every statistical check of this run (at kFamilyWiseRate);
  // empty for deterministic checks. See adjust_for_suite.
  std::optional<double> suite_adjusted_p = {};
};

struct RunInfo {
  std::string budget;   // quick | full
  int threads;          // worker threads the run was allowed
  std::string machine;  // a short description of the machine
};

std::string to_json(const std::vector<RunRecord>& records, const RunInfo& info);
// What the registry says of each check, nothing measured (glintlab verify --list --json): id,
// paper, source, kind, family, statistical, the recorded verdict per budget and why they differ,
// paper_quote, stronger_reading, the reviewed alternatives and the correction. The tools that
// document the claims (scripts/claims_doc.py) read this instead of the C++ sources.
std::string registry_to_json(const std::vector<const Check*>& checks);
std::string to_csv(const std::vector<RunRecord>& records);
std::string to_markdown(const std::vector<RunRecord>& records, const RunInfo& info);

// Fills suite_adjusted_p: Holm–Šidák over the p-values of the run's statistical checks, family by
// family (Check::family). Each check
// already holds its own p-value to check_level(), the single-step Šidák share of the suite's rate,
// which Holm–Šidák never rejects less than; the adjusted values show how far each result is from
// the suite's threshold.
void adjust_for_suite(std::vector<RunRecord>& records);

// "recorded <quick> at the quick budget and <full> at the full budget: <why>" for a check whose
// budgets record different verdicts (Check::budget_note).
std::string budget_note(const Check& c);

// True when the verdict is the one recorded for the check and its control was rejected.
bool as_expected(const RunRecord& r);

}  // namespace glintlab::verify

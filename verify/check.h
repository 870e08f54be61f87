// A registered check of one paper claim: what it measures, its verdict, and the negative control
// it must reject. The statistical engine of the verification issue grows this; the checks here are
// deterministic (cubature and exact-recomputation error bounds).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace glintlab::verify {

enum class Budget { kQuick, kFull };

// Verdicts as CLAIMS.md defines them.
enum class Verdict { kHolds, kHoldsWithin, kHoldsOnlyIn, kFails, kInconclusive };
const char* to_string(Verdict v);

struct CheckResult {
  Verdict verdict = Verdict::kInconclusive;
  std::string statistic;   // what was measured, e.g. "max |∫ D cos − 1|"
  double value = 0;        // the measured statistic
  double bound = 0;        // the error bound or tolerance it is compared with
  std::string evidence;    // one sentence a person reads: where, how much, how many configurations
  std::string control;     // the negative control, and what it measured
  bool control_rejected = false;
  int configurations = 0;
};

struct Check {
  std::string id;      // the id in shared/CLAIMS.md
  std::string paper;   // paper (and baseline) it comes from
  std::string source;  // equation / figure
  std::function<CheckResult(Budget)> run;
};

// Every registered check, in a stable order.
const std::vector<Check>& registered_checks();

// A seed derived from the check id and a configuration index, never hand-picked.
std::uint64_t check_seed(const std::string& id, std::uint64_t configuration);

}  // namespace glintlab::verify

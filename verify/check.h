// A registered check of one paper claim: what it measures, its verdict, and the negative control
// it must reject. Deterministic checks (cubature, exact recomputation) report an error bound;
// statistical checks report p-values, corrected for the number of configurations they test.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "verify/claims/paper_reading.h"

namespace glintlab::verify {

enum class Budget { kQuick, kFull };

// Verdicts as docs/verification.md defines them. kNotClaimed: a conformance property the model
// declares it does not claim (core/model.h NotClaimed); nothing is measured, the detail gives the
// model's reason, and it never counts as holding. kError: the check could not compute its
// statistic (an exception escaped its run, e.g. from a plug-in's eval, or it measured NaN/Inf
// where a number is required); the detail names the model or claim and the cause, nothing else
// is reported, and it never equals a recorded verdict.
enum class Verdict {
  kHolds,
  kHoldsWithin,
  kHoldsInRegime,
  kFails,
  kInconclusive,
  kNotClaimed,
  kError
};
const char* to_string(Verdict v);  // "holds", "holds-within", "holds-in-regime", "fails", ...,
                                   // "not-claimed", "error"

struct CheckResult {
  Verdict verdict = Verdict::kInconclusive;
  std::string detail;                // one line a person reads: where, how much, how many
  std::string statistic;             // what was measured, e.g. "max |∫ D cos − 1|"
  double value = 0;                  // the measured statistic
  std::optional<double> bound;       // error bound / tolerance it is held to, where one applies
  std::optional<double> p_value;     // combined (corrected) p-value, for statistical checks
  std::vector<double> raw_p_values;  // every configuration's raw p-value, kept
  std::string control;               // the negative control and what it measured
  std::optional<double> control_p_value;
  bool control_rejected = false;
  // The verdict the check's own measure and decide steps give the control's deliberately wrong
  // input (or, where the paper is wrong, its corrected formula). Set by the runner
  // (verify/claim_runner.h); empty for a check whose control is still a separate rule.
  std::optional<Verdict> control_verdict;
  // The parameter region a holds-in-regime verdict speaks for, written in the check's code before
  // anything is measured (e.g. "α★ ≤ 0.01, θh ≤ 20°"); empty for the other verdicts.
  std::string regime;
  std::string power;  // smallest effect detected at 90 % power, where computed
  int configurations = 0;
  // The check's own decision where the finding rule (verify/finding_rule.h) changed it: a
  // "fails" with a competing cause not excluded is reported inconclusive, and what the check
  // measured is kept here. Empty when the reported verdict is the measured one.
  std::optional<Verdict> measured_verdict = {};
};

// holds, holds-within or holds-in-regime.
inline bool is_holding(Verdict v) {
  return v == Verdict::kHolds || v == Verdict::kHoldsWithin || v == Verdict::kHoldsInRegime;
}

// A control rejects a check when its verdict is the opposite one: a claim that holds (in any form)
// has a control that fails; a claim that fails has a control (the corrected input) that holds. A
// claim the check cannot decide at this budget has nothing to oppose; its control must then be
// decided, which shows the check can decide where the effect is clear.
inline bool control_opposes(Verdict genuine, Verdict control) {
  if (is_holding(genuine)) return control == Verdict::kFails;
  if (genuine == Verdict::kFails) return is_holding(control);
  return control != Verdict::kInconclusive;
}

// The result of a check that could not compute its statistic: verdict kError, `what` (which model
// or claim, and why) as its detail, no control.
CheckResult error_result(const std::string& what);

// `run` with any exception that escapes it (one thrown inside a parallel loop reaches the caller)
// reported as error_result("<subject>: exception: <its message>") instead of ending the process,
// so the other checks of a run still run and its files are still written.
std::function<CheckResult(Budget)> contained(std::string subject,
                                             std::function<CheckResult(Budget)> run);

struct Check {
  std::string id;      // the id docs/claims.md lists
  std::string paper;   // paper (and baseline) it comes from
  std::string source;  // equation / figure
  Verdict expected;    // the verdict recorded for it today; a change is a regression or a finding
  std::function<CheckResult(Budget)> run;
  // For statistical checks: one run of the test on a known-correct input with the given seed,
  // returning its raw p-value (uniform on [0, 1] when the test is calibrated). Empty for
  // deterministic checks.
  std::function<double(std::uint64_t seed)> calibration = {};
  // The verdict recorded for the full budget where it differs from `expected` (the quick one):
  // a denser grid or 100× the samples can see what the quick budget cannot.
  std::optional<Verdict> expected_full = {};
  // Why the two budgets record different verdicts (with expected_full): which grid points or
  // sample counts only one of them has. Printed with every run of the check, so a quick run says
  // what the full budget sees and why this run cannot.
  std::string budget_note = {};
  // The false-positive family the check belongs to: empty for the papers' claims (one family,
  // check_level()); "model.<name>" for a model's conformance checks (verify/conformance/), each
  // model's its own family, so adding a model or a plug-in changes no other check's level.
  std::string family = {};
  // The paper's own sentence the claim tests, and what the check tests beyond it, from the claim
  // type (kQuote, kStrongerReading); for a model's conformance check, its property's statement,
  // marked as not a paper's claim (verify/conformance/conformance.cpp).
  std::string paper_quote = {};
  std::string stronger_reading = {};
  // glintlab's own rule (the all.* stability rules, adequacy), not a paper's claim: its "fails"
  // is never reported as a paper found wrong.
  bool glintlab_rule = false;
  // The competing causes of a "fails" reviewed for this claim (its type's alternatives()).
  std::vector<Alternative> alternatives = {};
  std::string correction = {};  // the smallest change to the paper that makes it hold
  // False for a run-time model's conformance check (a plug-in, a Python model): nothing is
  // recorded for it, and `expected` is what a conforming model gives.
  bool recorded = true;

  Verdict expected_for(Budget b) const {
    return b == Budget::kFull && expected_full ? *expected_full : expected;
  }
};

// Every registered check, in a stable order.
const std::vector<Check>& registered_checks();

// A seed derived from the check id and a configuration index, never hand-picked.
std::uint64_t check_seed(const std::string& id, std::uint64_t configuration);

// True for a check that tests a hypothesis (it has a calibration function): it takes a share of
// its family's false-positive rate.
inline bool is_statistical(const Check& c) { return static_cast<bool>(c.calibration); }

// Whether a run of the check gave what is recorded for it: its recorded verdict, and a control
// that opposes it (a not-claimed property runs nothing, so it has no control to reject).
inline bool control_ok(const CheckResult& r) {
  return r.verdict == Verdict::kNotClaimed || r.control_rejected;
}

// The significance level one statistical check holds its configuration-corrected p-value to: the
// suite's family-wise rate kFamilyWiseRate (verify/stats/multiple_testing.h) split by Šidák over
// every statistical check of the papers' claims registered (Check::family empty), so that a run of
// the whole suite rejects any true claim with probability at most kFamilyWiseRate. Inside a check,
// its configurations are corrected by Holm–Šidák at this level. The level does not depend on which
// claims a run selects.
double check_level();

}  // namespace glintlab::verify

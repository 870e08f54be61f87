// A claim is a type. It says what it tests (static id, paper, source, statistic, and kQuote: the
// paper's own sentence or equation it is judged against), what it expects
// (the verdict per budget), how much it measures (its sizes per budget and a probe size for
// tests), and four steps that the one runner, run_claim<C> (verify/claim_runner.h), strings
// together for every claim the same way:
//
//   observe(sizes, configuration, seed) → Evidence   per configuration: the costly part (renders,
//                                                    searches), made once and shared by the
//                                                    genuine input and its control
//   measure(sizes, evidence, input)     → Measured   the statistic over every configuration, for
//                                                    the genuine input or a control
//   decide(sizes, measured)             → Decision   verdict, value, bound, p-values
//   describe(sizes, measured, input)    → string     the detail line (genuine) or the control's
//
// plus `power(sizes, genuine, control)` (the detectable effect, as text), `beside_control(sizes,
// control)` (what else the control's measurement shows, appended to the control's text after its
// verdict), `control_p_value(sizes, control)` (the p-value reported for the control where that is
// not its decision's combined p), `control_text(sizes, control, input, verdict)` (the control's
// whole line, where the claim words it itself), `control_sensitive(sizes, control)` (false where a
// control of several inputs — the corrected formula, and near-truth errors the check must be seen
// to catch — is not caught in every part: it then does not oppose) and, for a statistical claim,
// `calibrate(seed)` (one raw p-value on a known-correct input), all optional. The configurations are enumerable
// (`configurations(sizes)`, then an index), so a run can be split by configuration. The control
// rule is the runner's alone: a claim that holds is shown to fail on a perturbed input, one that
// does not hold to hold on the corrected input (Input::kCorrected, where the claim has one:
// kHasCorrectedControl). Beside its quote a claim may say what it tests beyond it
// (kStrongerReading), that the quote is glintlab's own rule (kGlintlabRule), and, where it can
// measure "fails", the competing causes reviewed (alternatives()) and the smallest correction
// (kCorrection) that the finding rule (verify/finding_rule.h) reads.
//
// Adding a claim: one file verify/claims/<paper>/<claim>.cpp that defines the type and ends in
// GLINTLAB_CLAIM(Type), and one line in its paper's list (verify/claims/<paper>/list.h).
#pragma once

#include <concepts>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "verify/check.h"
#include "verify/control_rule.h"

namespace glintlab::verify {

// The verdicts recorded for a claim: at the quick budget, at the full budget where it differs
// (with the reason, printed with every run), and at the probe size the tests run.
struct Expected {
  Verdict quick;
  std::optional<Verdict> full = {};
  std::string_view why_full_differs = {};
  Verdict probe = quick;
};

// What decide() returns: the verdict and the numbers reported with it. The statistic the value
// measures (with its unit) is the claim's static kStatistic; the regime a holds-in-regime verdict
// speaks for is its static kRegime (or regime(sizes), where it names the sizes), declared before
// anything is measured.
struct Decision {
  Verdict verdict = Verdict::kInconclusive;
  double value = 0;
  std::optional<double> bound = {};
  std::optional<double> p_value = {};     // combined (corrected), for statistical claims
  std::vector<double> raw_p_values = {};  // every configuration's
  int configurations = 0;                 // how many configurations the verdict speaks for
  // Where a rule of the claim's own reports another verdict than the one it measured (e.g. "not
  // a separate finding: the cause is another claim's"): the measured one. The runner picks and
  // judges the control against it, as the finding rule (verify/finding_rule.h) keeps a control's
  // standing, and reports `verdict` with this kept as CheckResult::measured_verdict.
  std::optional<Verdict> measured_verdict = {};
};

template <typename C>
concept Claim = requires(Budget budget, const typename C::Sizes& z, int configuration,
                         std::uint64_t seed, std::span<const typename C::Evidence> evidence,
                         Input input, const typename C::Measured& m) {
  { C::kId } -> std::convertible_to<std::string_view>;
  { C::kPaper } -> std::convertible_to<std::string_view>;
  { C::kSource } -> std::convertible_to<std::string_view>;
  { C::kQuote } -> std::convertible_to<std::string_view>;
  { C::kStatistic } -> std::convertible_to<std::string_view>;
  { C::kExpected } -> std::convertible_to<Expected>;
  { C::sizes(budget) } -> std::same_as<typename C::Sizes>;
  { C::probe_sizes() } -> std::same_as<typename C::Sizes>;
  { C::configurations(z) } -> std::same_as<int>;
  { C::observe(z, configuration, seed) } -> std::same_as<typename C::Evidence>;
  { C::measure(z, evidence, input) } -> std::same_as<typename C::Measured>;
  { C::decide(z, m) } -> std::same_as<Decision>;
  { C::describe(z, m, input) } -> std::same_as<std::string>;
  requires std::default_initializable<typename C::Evidence>;
};

// What a claim's tests read at its probe size: the runner's result, and the verdict of each
// control input the claim has (the perturbed one always, the corrected one where it has one).
struct ClaimProbe {
  std::string id;
  Expected expected;
  CheckResult result;
  Verdict perturbed = Verdict::kInconclusive;
  std::optional<Verdict> corrected = {};
};

// The registry's entry of a claim and its run at the probe size. Declared here for a claim type
// that need not be complete (a paper's list names its claims only); defined in
// verify/claim_runner.h and instantiated by GLINTLAB_CLAIM in the claim's own file.
template <typename C>
Check claim_check();
template <typename C>
ClaimProbe probe_claim();

// A paper's claims, in registry order (verify/claims/<paper>/list.h).
template <typename... Cs>
struct ClaimList {};

template <typename... Cs>
std::vector<Check> checks_of(ClaimList<Cs...>) {
  return {claim_check<Cs>()...};
}
// The same as a plain function, for verify/registry.cpp's list of lists.
template <typename List>
std::vector<Check> list_checks() {
  return checks_of(List{});
}

}  // namespace glintlab::verify

// run_claim<C>: the one protocol every Claim (verify/claim.h) is run by. Observes every
// configuration once, measures and decides the genuine input, picks the control by the one rule
// (a holding claim gets the perturbed input, any other the corrected one where the claim has it),
// measures and decides the control from the same evidence, and fills the CheckResult: verdict,
// value, p-values, regime, the control's verdict and whether it opposes (then, where the claim has
// one, what is measured beside the control: beside_control), power. A decision that reports another
// verdict than it measured (Decision::measured_verdict) has its control picked and judged against
// the measured one. Included only by the claims' own files, which end in GLINTLAB_CLAIM(Type).
#pragma once

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <span>
#include <string>
#include <vector>

#include "verify/claim.h"
#include "verify/control_rule.h"

namespace glintlab::verify {

template <typename C>
constexpr bool has_corrected_control() {
  if constexpr (requires { C::kHasCorrectedControl; })
    return C::kHasCorrectedControl;
  else
    return false;
}

template <typename C>
Input control_input(Verdict genuine) {
  return control_input(genuine, has_corrected_control<C>());
}

namespace detail {

// Every configuration's evidence, in parallel; the result does not depend on the thread count
// (each configuration's evidence is a function of its index and seed).
template <Claim C>
std::vector<typename C::Evidence> observe_all(const typename C::Sizes& z) {
  std::vector<typename C::Evidence> evidence(static_cast<std::size_t>(C::configurations(z)));
  tbb::parallel_for(0, int(evidence.size()), [&](int k) {
    evidence[std::size_t(k)] = C::observe(z, k, check_seed(std::string(C::kId), std::uint64_t(k)));
  });
  return evidence;
}

template <Claim C>
CheckResult decide_all(const typename C::Sizes& z, std::span<const typename C::Evidence> evidence) {
  const typename C::Measured genuine = C::measure(z, evidence, Input::kGenuine);
  const Decision d = C::decide(z, genuine);
  CheckResult r;
  r.verdict = d.measured_verdict.value_or(d.verdict);  // the control is judged against this one
  r.statistic = std::string(C::kStatistic);
  r.value = d.value;
  r.bound = d.bound;
  r.p_value = d.p_value;
  r.raw_p_values = d.raw_p_values;
  r.configurations = d.configurations;
  if constexpr (requires { C::kRegime; })
    if (d.verdict == Verdict::kHoldsInRegime) r.regime = std::string(C::kRegime);
  // A regime that names the sizes it was measured at: the claim's regime(sizes).
  if constexpr (requires { C::regime(z); })
    if (d.verdict == Verdict::kHoldsInRegime) r.regime = C::regime(z);
  r.detail = C::describe(z, genuine, Input::kGenuine);

  const Input input = control_input<C>(r.verdict);
  const typename C::Measured control = C::measure(z, evidence, input);
  const Decision c = C::decide(z, control);
  record_control(r, c.verdict);
  // A control made of more than one input (a corrected formula, and beside it the near-truth errors
  // the check must be seen to catch) opposes only where every part does: control_sensitive.
  if constexpr (requires { C::control_sensitive(z, control); })
    r.control_rejected = r.control_rejected && C::control_sensitive(z, control);
  // The control's p-value is its decision's combined p, unless the claim reports another one (a
  // statistical claim whose control is one test among its family: control_p_value).
  if constexpr (requires { C::control_p_value(z, control); })
    r.control_p_value = C::control_p_value(z, control);
  else
    r.control_p_value = c.p_value;
  // The control's line: the claim's own where it words it itself (control_text, e.g. the sweep
  // claims' "<control>: verdict <v>; <targets>"), else "<describe> → <verdict> (rejected)".
  if constexpr (requires { C::control_text(z, control, input, c.verdict); })
    r.control = C::control_text(z, control, input, c.verdict);
  else
    r.control = fmt::format("{} → {} ({})", C::describe(z, control, input), to_string(c.verdict),
                            r.control_rejected ? "rejected" : "NOT rejected");
  if constexpr (requires { C::beside_control(z, control); })
    r.control += ". " + C::beside_control(z, control);
  if constexpr (requires { C::power(z, genuine, control); })
    r.power = C::power(z, genuine, control);
  if (d.measured_verdict) r.measured_verdict = d.measured_verdict, r.verdict = d.verdict;
  return r;
}

}  // namespace detail

template <Claim C>
CheckResult run_claim(const typename C::Sizes& z) {
  const std::vector<typename C::Evidence> evidence = detail::observe_all<C>(z);
  return detail::decide_all<C>(z, evidence);
}

template <typename C>
Check claim_check() {
  static_assert(Claim<C>);
  Check c{std::string(C::kId), std::string(C::kPaper), std::string(C::kSource), C::kExpected.quick,
          [](Budget b) { return run_claim<C>(C::sizes(b)); }};
  c.expected_full = C::kExpected.full;
  c.budget_note = std::string(C::kExpected.why_full_differs);
  c.paper_quote = std::string(C::kQuote);
  if constexpr (requires { C::kStrongerReading; })
    c.stronger_reading = std::string(C::kStrongerReading);
  if constexpr (requires { C::kGlintlabRule; }) c.glintlab_rule = C::kGlintlabRule;
  if constexpr (requires { C::alternatives(); }) c.alternatives = C::alternatives();
  if constexpr (requires { C::kCorrection; }) c.correction = std::string(C::kCorrection);
  if constexpr (requires(std::uint64_t seed) { C::calibrate(seed); })
    c.calibration = [](std::uint64_t seed) { return C::calibrate(seed); };
  return c;
}

template <typename C>
ClaimProbe probe_claim() {
  static_assert(Claim<C>);
  const typename C::Sizes z = C::probe_sizes();
  const std::vector<typename C::Evidence> evidence = detail::observe_all<C>(z);
  ClaimProbe p{.id = std::string(C::kId),
               .expected = C::kExpected,
               .result = detail::decide_all<C>(z, evidence)};
  p.perturbed = C::decide(z, C::measure(z, evidence, Input::kPerturbed)).verdict;
  if constexpr (has_corrected_control<C>())
    p.corrected = C::decide(z, C::measure(z, evidence, Input::kCorrected)).verdict;
  return p;
}

}  // namespace glintlab::verify

// Ends a claim's file: checks the type against the Claim concept and instantiates its registry
// entry and its probe run here, for the paper's list (which names the type only) to link.
#define GLINTLAB_CLAIM(Type)                                                \
  static_assert(::glintlab::verify::Claim<Type>);                           \
  template ::glintlab::verify::Check glintlab::verify::claim_check<Type>(); \
  template ::glintlab::verify::ClaimProbe glintlab::verify::probe_claim<Type>()

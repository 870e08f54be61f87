// The control rule, the one piece of the claim protocol the conformance suite shares with the
// claims (verify/claim_runner.h): which input a control measures and how its verdict is recorded.
// Kept apart from the Claim concept so the conformance suite, whose subject is a model known only
// at run time, depends on the rule and not on the concept.
#pragma once

#include "verify/check.h"

namespace glintlab::verify {

// Which input a claim measures: the genuine one (the paper's method or formula), a perturbed one
// (deliberately wrong by a little, which a holding claim must be seen to fail on) or the corrected
// one (which a claim that does not hold must be seen to hold on).
enum class Input { kGenuine, kPerturbed, kCorrected };

// The control rule, written once: "the control is the corrected input when the claim fails (or is
// undecided), a perturbed one when it holds". A check without a corrected input keeps its
// perturbed one, and its control then cannot oppose a genuine "fails" (the tests see that).
inline Input control_input(Verdict genuine, bool has_corrected) {
  return is_holding(genuine) || !has_corrected ? Input::kPerturbed : Input::kCorrected;
}

// Records the control's verdict (decided by the same function as the genuine one) and whether it
// opposes the genuine verdict; after r.verdict is set.
inline void record_control(CheckResult& r, Verdict control) {
  r.control_verdict = control;
  r.control_rejected = control_opposes(r.verdict, control);
}

// The control step of a check whose subject is a value known only at run time, not a Claim type (a
// registered model's property, plug-ins included: verify/conformance). `measure_control(input)`
// measures and decides the input the rule picks for the genuine verdict already in r, filling the
// control's text and p-value, and returns its verdict; the runner records it as run_claim does.
template <typename MeasureControl>
void run_control(CheckResult& r, bool has_corrected, MeasureControl&& measure_control) {
  record_control(r, measure_control(control_input(r.verdict, has_corrected)));
}

}  // namespace glintlab::verify

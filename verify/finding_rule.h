// The finding rule: a claim "fails" only when every competing cause of the failure reviewed for it
// (Check::alternatives) is excluded — our bug, our scene or reference, our convention, our
// tolerance. A measured "fails" with a cause still open, or with none reviewed, is reported as
// inconclusive with the open causes as its reason, and the measurement is kept.
#pragma once

#include <string>

#include "verify/check.h"

namespace glintlab::verify {

// Applies the rule to a result of check c (the papers' claims and glintlab's rules; a model's
// conformance checks, Check::family non-empty, are left as measured).
void apply_finding_rule(const Check& c, CheckResult& r);

// "cause (how); cause (how)" over the alternatives with the given exclusion state.
std::string alternatives_text(const Check& c, bool excluded);

}  // namespace glintlab::verify

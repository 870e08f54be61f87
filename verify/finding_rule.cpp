#include "verify/finding_rule.h"

#include <fmt/format.h>

#include <algorithm>

namespace glintlab::verify {

std::string alternatives_text(const Check& c, bool excluded) {
  std::string out;
  for (const Alternative& a : c.alternatives) {
    if (a.excluded != excluded) continue;
    if (!out.empty()) out += "; ";
    out += fmt::format("{} ({})", a.cause, a.how);
  }
  return out;
}

void apply_finding_rule(const Check& c, CheckResult& r) {
  if (!c.family.empty() || r.verdict != Verdict::kFails) return;
  const bool all_excluded =
      !c.alternatives.empty() && std::all_of(c.alternatives.begin(), c.alternatives.end(),
                                             [](const Alternative& a) { return a.excluded; });
  if (all_excluded) return;
  r.measured_verdict = r.verdict;
  r.verdict = Verdict::kInconclusive;
  const std::string open = c.alternatives.empty() ? std::string("no competing cause reviewed")
                                                  : alternatives_text(c, false);
  r.detail = fmt::format(
      "inconclusive: the check measured \"fails\", but a competing cause is not excluded: {}. "
      "Measured: {}",
      open, r.detail);
  // The control keeps its standing: a control that opposed "fails" (it holds) is decided, so it
  // opposes "inconclusive" too, and one that did not oppose stays not rejected.
}

}  // namespace glintlab::verify

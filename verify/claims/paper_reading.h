// What a claim's verdict is judged against: the paper's own sentence (a claim type's kQuote), and
// for a claim that fails, the causes other than the paper being wrong that the check ruled out or
// could not rule out (its alternatives()). A "fails" stands only when every competing cause is
// excluded; otherwise the claim is inconclusive with the open causes as its reason
// (verify/finding_rule.h).
#pragma once

#include <string_view>

namespace glintlab::verify {

// A cause other than the paper being wrong that could produce a "fails".
struct Alternative {
  std::string_view cause;  // "implementation bug", "scene or reference mismatch", "convention", ...
  std::string_view how;    // how it was ruled out (excluded) or why it could not be (open)
  bool excluded = false;
};

}  // namespace glintlab::verify

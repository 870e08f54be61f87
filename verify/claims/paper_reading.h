// What a claim's verdict is judged against: the paper's own sentence (paper_quotes.cpp), and for a
// claim that fails, the causes other than the paper being wrong that the check ruled out or could
// not rule out (failure_reviews.cpp). A "fails" stands only when every competing cause is excluded;
// otherwise the claim is inconclusive with the open causes as its reason.
#pragma once

#include <string_view>
#include <vector>

namespace glintlab::verify {

struct PaperQuote {
  std::string_view id;     // the claim id
  std::string_view quote;  // the paper's sentence or equation in its own words, with its section
  // Empty when the check tests exactly the quoted sentence; otherwise what the check tests beyond
  // it (a tighter tolerance, another scene, a stronger reading), so a verdict on that reading is
  // never reported as the paper failing.
  std::string_view stronger_reading = {};
  // True for glintlab's own rules (all.*, adequacy.*): the quote is the rule, not a paper's words.
  bool glintlab_rule = false;
};

// Every papers' claim's quote, one entry per registered claim of the papers (Check::family empty).
const std::vector<PaperQuote>& paper_quotes();

// A cause other than the paper being wrong that could produce a "fails".
struct Alternative {
  std::string_view cause;  // "implementation bug", "scene or reference mismatch", "convention", ...
  std::string_view how;    // how it was ruled out (excluded) or why it could not be (open)
  bool excluded = false;
};

struct FailureReview {
  std::string_view id;
  std::vector<Alternative> alternatives;
  // For a finding (every cause excluded): the smallest change to the paper that makes the claim
  // hold — the corrected equation or the regime — as the check's control measures it.
  std::string_view correction = {};
};

// The reviewed alternatives of every claim whose check can say "fails".
const std::vector<FailureReview>& failure_reviews();

}  // namespace glintlab::verify

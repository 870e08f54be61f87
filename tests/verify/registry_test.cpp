// The claim registry: every check has a CLAIMS.md-style id, reaches the verdict it reaches today
// at the quick budget, and rejects its negative control. A verdict that changes is a regression or
// a discovery; either way this test makes a person look.
#include <gtest/gtest.h>

#include <set>
#include <cctype>
#include <string>

#include "verify/check.h"

namespace glintlab::verify {
namespace {


TEST(Registry, IdsUniqueAndExpected) {
  std::set<std::string> seen;
  for (const Check& c : registered_checks()) {
    EXPECT_TRUE(seen.insert(c.id).second) << "duplicate id " << c.id;
    EXPECT_NE(c.id.find('.'), std::string::npos) << c.id;
    EXPECT_FALSE(c.paper.empty()) << c.id;
    EXPECT_FALSE(c.source.empty()) << c.id;
  }
}

TEST(Registry, SeedsDependOnIdAndConfiguration) {
  EXPECT_NE(check_seed("a.b", 0), check_seed("a.b", 1));
  EXPECT_NE(check_seed("a.b", 0), check_seed("a.c", 0));
  EXPECT_EQ(check_seed("a.b", 7), check_seed("a.b", 7));
}

class QuickBudget : public ::testing::TestWithParam<std::string> {};

TEST_P(QuickBudget, VerdictAndControl) {
  for (const Check& c : registered_checks()) {
    if (c.id != GetParam()) continue;
    const CheckResult r = c.run(Budget::kQuick);
    EXPECT_EQ(std::string(to_string(r.verdict)), to_string(c.expected)) << r.detail;
    EXPECT_TRUE(r.control_rejected) << r.control;
    EXPECT_GT(r.configurations, 0);
    return;
  }
  FAIL() << "not registered: " << GetParam();
}

std::vector<std::string> all_ids() {
  std::vector<std::string> ids;
  for (const Check& c : registered_checks()) ids.push_back(c.id);
  return ids;
}

INSTANTIATE_TEST_SUITE_P(Checks, QuickBudget, ::testing::ValuesIn(all_ids()),
                         [](const auto& param_info) {
                           std::string n = param_info.param;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

}  // namespace
}  // namespace glintlab::verify

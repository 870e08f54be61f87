// The chi-square claims' negative controls (kemppinen.jacobian; smooth.sampler-matches-pdf's and
// eto.pdf-matches's in ClaimProbes.*, at the same sizes): every control variant is rejected and
// the correct samplers it is built on are not, at reduced sample counts; outcomes are identical
// with 1 and 2 threads (on a few configurations and controls of each); calibration runs give
// valid p-values. The full quick checks run once in registry_test.cpp.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "verify/check.h"
#include "verify/claims/gof_family.h"

namespace glintlab::verify {
namespace {

// The configurations a spec's controls are built on, with the controls' plan_of remapped, so the
// controls run without the rest of the grid.
GofSpec controls_only(const GofSpec& s) {
  std::map<int, int> index;
  GofSpec out;
  for (const GofControl& c : s.controls)
    for (const GofControlCase& cc : c.cases)
      if (cc.plan_of >= 0 && !index.count(cc.plan_of)) {
        index[cc.plan_of] = int(out.cases.size());
        out.cases.push_back(s.cases[std::size_t(cc.plan_of)]);
      }
  out.controls = s.controls;
  for (GofControl& c : out.controls)
    for (GofControlCase& cc : c.cases)
      if (cc.plan_of >= 0) cc.plan_of = index.at(cc.plan_of);
  return out;
}

// Correct configurations: 3·10^4 samples; subtle controls: 3·10^5 (a 2 % error then gives a
// non-centrality ≈ 120 against ≈ 90 needed); gross controls at 3·10^4.
constexpr GofSize kReduced{30'000, 300'000, 500};

void expect_controls_rejected(const std::string& id, const GofSpec& spec) {
  const GofSpec s = controls_only(spec);
  ASSERT_FALSE(s.controls.empty());
  const GofOutcome o = run_gof_family(id, s.cases, s.controls, kReduced);
  for (std::size_t i = 0; i < o.results.size(); ++i) {
    EXPECT_FALSE(o.results[i].rejects(o.configuration_level))
        << s.cases[i].label << ": " << o.results[i].summary();
    EXPECT_FALSE(o.results[i].inconclusive) << s.cases[i].label << ": " << o.results[i].reason;
  }
  for (std::size_t c = 0; c < s.controls.size(); ++c)
    for (std::size_t k = 0; k < s.controls[c].cases.size(); ++k)
      EXPECT_TRUE(o.control_results[c][k].rejects(o.configuration_level))
          << s.controls[c].name << " — " << s.controls[c].cases[k].wrong.label << ": "
          << o.control_results[c][k].summary();
}

TEST(ChiSquareClaims, KemppinenControlsRejected) {
  expect_controls_rejected("kemppinen.jacobian", kemppinen_spec(Budget::kQuick));
}

// Every control of every budget is built on configurations of that budget's grid.
TEST(ChiSquareClaims, ControlsReferToTheirGrid) {
  for (Budget b : {Budget::kQuick, Budget::kFull}) {
    EXPECT_NO_THROW(smooth_sampler_spec(b));
    EXPECT_NO_THROW(eto_pdf_spec(b));
  }
  for (Budget b : {Budget::kQuick, Budget::kFull})
    for (const GofSpec& s : {smooth_sampler_spec(b), eto_pdf_spec(b), kemppinen_spec(b)})
      for (const GofControl& c : s.controls) {
        EXPECT_FALSE(c.cases.empty()) << c.name;
        for (const GofControlCase& cc : c.cases) {
          EXPECT_LT(cc.plan_of, int(s.cases.size())) << cc.wrong.label;
          if (cc.plan_of < 0) {
            EXPECT_TRUE(cc.wrong.direction_pdf || cc.wrong.point_pdf) << cc.wrong.label;
          }
        }
      }
}

// The controls of smooth.sampler-matches-pdf and eto.pdf-matches are decided as their family, each
// case in place of a configuration of the grid: every case names one.
TEST(ChiSquareClaims, ControlCasesTakeAConfigurationsPlace) {
  for (Budget b : {Budget::kQuick, Budget::kFull})
    for (const GofSpec& s : {smooth_sampler_spec(b), eto_pdf_spec(b)})
      for (const GofControl& c : s.controls)
        for (const GofControlCase& cc : c.cases) {
          EXPECT_GE(cc.position(), 0) << cc.wrong.label;
          EXPECT_LT(cc.position(), int(s.cases.size())) << cc.wrong.label;
        }
}

ChiSquareResult result_with_p(double p) {
  ChiSquareResult r;
  r.p_value = p;
  return r;
}

// decide_gof: Holm–Šidák over the configurations at check_level(); a hard failure fails, an
// undecided configuration makes the family inconclusive. decide_gof_controls: a case fails only
// where, in its configuration's place, it makes the family fail.
TEST(ChiSquareClaims, FamilyAndControlsDecidedAlike) {
  const double level = check_level();
  std::vector<ChiSquareResult> family(10, result_with_p(0.5));
  EXPECT_EQ(decide_gof(family), Verdict::kHolds);
  family[3] = result_with_p(0.5 * sidak_level(level, 10));
  EXPECT_EQ(decide_gof(family), Verdict::kFails);
  family[3] = result_with_p(0.5);
  family[3].inconclusive = true;
  EXPECT_EQ(decide_gof(family), Verdict::kInconclusive);
  family[3].hard_fail = true;
  EXPECT_EQ(decide_gof(family), Verdict::kFails);

  GofOutcome o;
  o.results.assign(10, result_with_p(0.5));
  // One control with a case caught and one not: only the first control is rejected.
  o.control_results = {{result_with_p(0.1 * sidak_level(level, 10))},
                       {result_with_p(2 * sidak_level(level, 10))}};
  o.control_p = {0, 0};
  std::vector<GofControl> controls(2);
  controls[0].cases.push_back({{}, 2, 1.02});
  controls[1].cases.push_back({{}, -1, 1, 7});
  const GofControlVerdicts cv = decide_gof_controls(o, controls);
  EXPECT_EQ(cv.cases[0][0], Verdict::kFails);
  EXPECT_EQ(cv.cases[1][0], Verdict::kHolds);
  EXPECT_TRUE(cv.rejected(0));
  EXPECT_FALSE(cv.rejected(1));
  EXPECT_EQ(cv.verdict, Verdict::kHolds);
  // A case that replaces no configuration is a mistake in the check.
  controls[1].cases[0].replaces = -1;
  EXPECT_THROW(decide_gof_controls(o, controls), std::logic_error);
  EXPECT_EQ(control_verdict_of_cases({Verdict::kFails, Verdict::kFails}), Verdict::kFails);
  EXPECT_EQ(control_verdict_of_cases({Verdict::kFails, Verdict::kInconclusive}),
            Verdict::kInconclusive);
}

// The spec with only its first `kept` controls, each case's first `cases_each` cases.
GofSpec first_controls(GofSpec s, std::size_t kept, std::size_t cases_each) {
  s.controls.resize(std::min(kept, s.controls.size()));
  for (GofControl& c : s.controls) c.cases.resize(std::min(cases_each, c.cases.size()));
  return s;
}

// Families with their controls give bit-identical p-values with 1 and 2 threads. What can depend
// on the thread count is the order of the parallel loops (over configurations, the plans that
// controls share or replan, control cases, and sample chunks), not the sample count or the number
// of configurations. So a few of each suffice: together the families below have several
// configurations (kemppinen.jacobian, smooth.sampler-matches-pdf), controls of every kind (a
// scaled shared plan, a shared plan, a replanned case) and more than one chunk of samples each
// (GofSize::n above ChiSquareOptions::chunk), on the disk (kemppinen.jacobian), the sphere
// (eto.pdf-matches) and through a batched sampler (smooth.sampler-matches-pdf).
TEST(ChiSquareClaims, IdenticalWithOneAndTwoThreads) {
  const GofSpec k = controls_only(kemppinen_spec(Budget::kQuick));
  const GofSpec e = controls_only(first_controls(eto_pdf_spec(Budget::kQuick), 3, 1));
  const GofSpec m = controls_only(first_controls(smooth_sampler_spec(Budget::kQuick), 2, 1));
  constexpr GofSize kSmall{20'000, 20'000, 300};
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    std::vector<double> p;
    for (const GofSpec* x : {&k, &e, &m}) {
      const GofOutcome o = run_gof_family("threads.test", x->cases, x->controls, kSmall);
      for (const ChiSquareResult& r : o.results) {
        p.push_back(r.p_value);
        for (const ChiSquareResolution& res : r.resolutions) p.push_back(res.statistic);
      }
      for (double q : o.control_p) p.push_back(q);
    }
    return p;
  };
  const std::vector<double> one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i)
    EXPECT_TRUE(one[i] == two[i] || (std::isnan(one[i]) && std::isnan(two[i])))
        << i << ": " << one[i] << " vs " << two[i];
}

// The calibration functions return p-values in [0, 1] that depend on the seed only.
TEST(ChiSquareClaims, CalibrationRunsAreValidAndDeterministic) {
  for (const Check& c : registered_checks()) {
    if (c.id != "smooth.sampler-matches-pdf" && c.id != "eto.pdf-matches" &&
        c.id != "kemppinen.jacobian")
      continue;
    ASSERT_TRUE(is_statistical(c)) << c.id;
    const double a = c.calibration(1), b = c.calibration(2), a2 = c.calibration(1);
    EXPECT_GE(a, 0);
    EXPECT_LE(a, 1);
    EXPECT_GE(b, 0);
    EXPECT_LE(b, 1);
    EXPECT_EQ(a, a2) << c.id;
    EXPECT_NE(a, b) << c.id;
  }
}

}  // namespace
}  // namespace glintlab::verify

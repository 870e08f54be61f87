// Calibration of statistical checks: a calibrated test is found calibrated, a miscalibrated one
// (the negative control) is not, the interval arithmetic matches known values, and the outcome does
// not depend on the thread count.
#include "verify/calibration.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/math/ops.h"
#include "core/math/rng.h"
#include "verify/stats/mean_tests.h"

namespace glintlab::verify {
namespace {

// A z test of 64 normal draws (inverse-CDF from the counter RNG) against mean 0 with σ = 1. With
// `shift` ≠ 0 or `spread` ≠ 1 the draws violate the null the test assumes.
double z_test_run(std::uint64_t seed, double shift, double spread) {
  MeanAccumulator a;
  for (std::uint64_t i = 0; i < 64; ++i) {
    const double u = counter_uniform<double>(seed, i, 0);
    const double x = std::sqrt(2.0) * erfinv(2 * u - 1);
    a.add(shift + spread * x);
  }
  return z_test(a, 0.0, 1.0).p_value;
}

TEST(Calibration, CalibratedTestIsCalibrated) {
  const auto r = calibrate("test.calibrated", [](std::uint64_t s) { return z_test_run(s, 0, 1); }, 2000);
  EXPECT_TRUE(r.calibrated) << summary(r);
  EXPECT_TRUE(r.valid);
  EXPECT_STREQ(r.status(), "calibrated");
  EXPECT_EQ(r.non_finite, 0u);
  EXPECT_LE(r.rate_low, 0.05);
  EXPECT_GE(r.rate_high, 0.05);
}

// Negative controls: a test whose null is false for its input (too wide a spread: anti-conservative)
// and one that is too conservative (narrower spread) must both be flagged.
TEST(Calibration, MiscalibratedTestsAreFlagged) {
  const auto wide = calibrate("test.wide", [](std::uint64_t s) { return z_test_run(s, 0, 1.3); }, 2000);
  EXPECT_FALSE(wide.calibrated) << summary(wide);
  EXPECT_FALSE(wide.valid);
  EXPECT_GT(wide.rate_low, 0.05);
  const auto narrow = calibrate("test.narrow", [](std::uint64_t s) { return z_test_run(s, 0, 0.7); }, 2000);
  EXPECT_FALSE(narrow.calibrated) << summary(narrow);
  EXPECT_TRUE(narrow.valid) << "too-large p-values are conservative, not broken";
  EXPECT_STREQ(narrow.status(), "conservative");
  EXPECT_LT(narrow.rate_high, 0.05);
}

// A Šidák-combined minimum of two strongly dependent exact tests is conservative, and is classified
// so; the plain minimum (no correction) is anti-conservative.
TEST(Calibration, CombinedMinimaAreConservativeUncorrectedMinimaAreNot) {
  auto two = [](std::uint64_t s, bool correct) {
    const double p1 = z_test_run(s, 0, 1), p2 = z_test_run(s ^ 0x5555, 0, 1);
    const double p = std::min(p1, std::min(p2, 0.5 * (p1 + p2)));  // three dependent tests
    return correct ? 1 - std::pow(1 - p, 3) : p;
  };
  const auto sidak = calibrate("test.sidak", [&](std::uint64_t s) { return two(s, true); }, 2000);
  EXPECT_TRUE(sidak.valid) << summary(sidak);
  EXPECT_FALSE(sidak.calibrated) << summary(sidak);
  const auto raw = calibrate("test.rawmin", [&](std::uint64_t s) { return two(s, false); }, 2000);
  EXPECT_FALSE(raw.valid) << summary(raw);
}

// Smirnov's one-sided distribution: n = 1 gives P(D+ ≥ d) = 1 − d; large n approaches exp(−2nd²).
TEST(Calibration, OneSidedKsKnownValues) {
  EXPECT_NEAR(ks_one_sided_sf(0.3, 1), 0.7, 1e-12);
  EXPECT_NEAR(ks_one_sided_sf(0.05, 2000), std::exp(-2 * 2000 * 0.05 * 0.05), 0.2 * std::exp(-2 * 2000 * 0.05 * 0.05));
  EXPECT_EQ(ks_one_sided_sf(0, 10), 1.0);
  EXPECT_EQ(ks_one_sided_sf(1, 10), 0.0);
}

TEST(Calibration, NonFinitePValuesAreABrokenTest) {
  const auto r = calibrate("test.nan", [](std::uint64_t s) { return s % 7 == 0 ? NAN : 0.5; }, 100);
  EXPECT_FALSE(r.calibrated);
  EXPECT_GT(r.non_finite, 0u);
}

TEST(Calibration, IdenticalForAnyThreadCount) {
  auto run = [](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    return calibrate("test.threads", [](std::uint64_t s) { return z_test_run(s, 0, 1); }, 300);
  };
  const auto a = run(1), b = run(2);
  EXPECT_EQ(a.p_values, b.p_values);
  EXPECT_EQ(a.seeds, b.seeds);
  EXPECT_EQ(a.ks_p_value, b.ks_p_value);
}

TEST(Calibration, SeedsAreDerivedAndDistinct) {
  EXPECT_NE(calibration_seed("a.b", 0), calibration_seed("a.b", 1));
  EXPECT_NE(calibration_seed("a.b", 0), check_seed("a.b", 0));
  EXPECT_EQ(calibration_seed("a.b", 3), calibration_seed("a.b", 3));
}

// Clopper–Pearson against closed forms: k = 0 gives [0, 1 − (a/2)^{1/n}], and the symmetric case
// 5 of 10 at 95 % is [0.187086, 0.812914] (tabulated).
TEST(Calibration, ClopperPearsonKnownValues) {
  double lo, hi;
  clopper_pearson(0, 10, 0.95, lo, hi);
  EXPECT_EQ(lo, 0);
  EXPECT_NEAR(hi, 1 - std::pow(0.025, 0.1), 1e-12);
  clopper_pearson(5, 10, 0.95, lo, hi);
  EXPECT_NEAR(lo, 0.187086, 1e-6);
  EXPECT_NEAR(hi, 0.812914, 1e-6);
  clopper_pearson(10, 10, 0.95, lo, hi);
  EXPECT_EQ(hi, 1);
  EXPECT_NEAR(lo, std::pow(0.025, 0.1), 1e-12);
}

TEST(Calibration, BadArguments) {
  auto ok = [](std::uint64_t) { return 0.5; };
  EXPECT_THROW(calibrate("x.y", ok, 1), std::invalid_argument);
  EXPECT_THROW(calibrate("x.y", ok, 10, 0.0), std::invalid_argument);
  EXPECT_THROW(calibrate("x.y", ok, 10, 1.0), std::invalid_argument);
  const Check deterministic{"x.det", "p", "s", Verdict::kHolds, [](Budget) { return CheckResult{}; }};
  EXPECT_THROW(calibrate(deterministic, 10), std::invalid_argument);
}

}  // namespace
}  // namespace glintlab::verify

// The adequacy chooser's closed forms (core/glints/adequacy.h): the real-time count's moments
// against draws of binomial_realtime, the exact count's CV and P(no glint) against the binomial
// pmf, and the chooser's level at clear-cut footprints.
#include "core/glints/adequacy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/math/rng.h"

namespace glintlab {
namespace {

// Mean, second moment and fourth central moment of binomial_realtime(n, p) over `draws`
// counter-RNG uniforms.
struct Drawn {
  double mean, second, m4;
};
Drawn drawn_realtime_moments(double n, double p, int draws, std::uint64_t seed) {
  std::vector<double> x(std::size_t(draws), 0.0);
  double s = 0, s2 = 0;
  for (int i = 0; i < draws; ++i) {
    x[std::size_t(i)] =
        binomial_realtime(n, p, counter_uniform<double>(seed, std::uint64_t(i), 0),
                          counter_uniform<double>(seed, std::uint64_t(i), 1));
    s += x[std::size_t(i)], s2 += x[std::size_t(i)] * x[std::size_t(i)];
  }
  const double mean = s / draws;
  double m4 = 0;
  for (double v : x) m4 += std::pow(v - mean, 4);
  return {mean, s2 / draws, m4 / draws};
}

TEST(AdequacyClosedForms, RealtimeMomentsMatchItsDraws) {
  const int draws = 400000;
  std::uint64_t seed = 7;
  for (double n : {1.0, 2.0, 5.0, 30.0, 1000.0}) {
    for (double p : {0.001, 0.05, 0.3, 0.9}) {
      const CountMoments<double> c = realtime_count_moments(n, p);
      const Drawn d = drawn_realtime_moments(n, p, draws, seed++);
      // Five standard errors of the drawn mean and of the drawn variance ((μ4 − σ⁴)/draws).
      const double var = std::max(c.second - c.mean * c.mean, 0.0);
      EXPECT_NEAR(d.mean, c.mean, 5 * std::sqrt(var / draws) + 1e-12) << n << " " << p;
      EXPECT_NEAR(d.second - d.mean * d.mean, var,
                  5 * std::sqrt(std::max(d.m4 - var * var, 0.0) / draws) + 1e-12)
          << n << " " << p;
    }
  }
}

TEST(AdequacyClosedForms, RealtimeMomentsTellAWrongCountApart) {
  // The check above can fail: the moments of n + 1 trials are far outside its tolerance.
  const CountMoments<double> c = realtime_count_moments(6.0, 0.3);
  const Drawn d = drawn_realtime_moments(5.0, 0.3, 400000, 3);
  const double sd = std::sqrt(c.second - c.mean * c.mean);
  EXPECT_GT(std::abs(d.mean - c.mean), 5 * sd / std::sqrt(400000.0));
}

TEST(AdequacyClosedForms, OneTrialIsABernoulli) {
  const CountMoments<double> c = realtime_count_moments(1.0, 0.2);
  EXPECT_NEAR(c.mean, 0.2, 1e-15);
  EXPECT_NEAR(c.second, 0.2, 1e-15);
}

TEST(AdequacyClosedForms, BinomialCvAndZeroProbability) {
  EXPECT_NEAR(binomial_count_cv(100.0, 0.2), std::sqrt(0.8 / 20), 1e-15);
  EXPECT_NEAR(binomial_zero_probability(10.0, 0.1), std::pow(0.9, 10), 1e-15);
  EXPECT_EQ(binomial_count_cv(0.0, 0.2), 0.0);
}

using L = BinomialLevel;
L choose(double n, double p, double tau) { return L(int(choose_binomial_level(n, p, tau))); }

TEST(AdequacyChooser, ClearCutFootprints) {
  // CV √(0.5/(1e8·0.5)) = 1e-4: nothing to see.
  EXPECT_EQ(choose(1e8, 0.5, 0.02), L::kSmooth);
  // One facet at p = 0.01: the pixel is either dark or 100× the mean; only the exact count's
  // single Bernoulli is right (the real-time gate is that Bernoulli as well: n = 1 makes it exact).
  EXPECT_EQ(choose(1, 0.01, 0.02), L::kRealTime);
  // Two facets at p = 0.01: the real-time Gaussian's clamp biases the mean by ~4 %.
  EXPECT_EQ(choose(2, 0.01, 0.02), L::kSmallCount);
  // About 30 reflecting facets: beyond the 16-term inversion, not yet a plain normal, and the
  // real-time count's mean (1 − q^n)(1 + (n − 1)p) ≈ N p + 1 − p is 3 % high.
  EXPECT_EQ(choose(3000, 0.01, 0.02), L::kExact);
  // 1000 reflecting facets: the real-time bias is 0.1 %, the CV 3 % (visible).
  EXPECT_EQ(choose(1e5, 0.01, 0.02), L::kRealTime);
  // p = 1 (deliot_belcour on its peak): every facet reflects, b/(N p) = 1.
  EXPECT_EQ(choose(10, 1.0, 0.02), L::kSmooth);
  EXPECT_EQ(choose(0, 0.3, 0.02), L::kRealTime);
  EXPECT_EQ(choose(100, 0.0, 0.02), L::kSmooth);
}

TEST(AdequacyChooser, LargerThresholdNeverChoosesAMoreCompleteLevel) {
  for (double n : {1.0, 3.0, 10.0, 100.0, 1e4, 1e6, 1e8})
    for (double p : {1e-5, 1e-3, 0.05, 0.5})
      EXPECT_LE(int(choose(n, p, 0.2)), int(choose(n, p, 0.02))) << n << " " << p;
}

TEST(AdequacyChooser, SmoothExactlyWhereTheCvIsBelowHalfTau) {
  const double p = 0.01, tau = 0.02;
  const double n_star = (1 - p) / (p * std::pow(kChooserMargin * tau, 2));
  EXPECT_EQ(choose(std::ceil(n_star * 1.001), p, tau), L::kSmooth);
  EXPECT_NE(choose(std::floor(n_star * 0.999), p, tau), L::kSmooth);
}

// The chooser for measured costs takes the adequate level of least cost: with the GPU order as
// costs it is the GPU chooser; with this CPU's order (the exact count cheaper than the real-time
// and small-count ones, adequacy/ benchmark rows) it never takes a level dearer than exact.
TEST(AdequacyChooser, ByCostIsTheCheapestAdequateLevel) {
  const std::array<double, kBinomialLevels> gpu = {0, 1, 2, 3};
  const std::array<double, kBinomialLevels> cpu = {25, 85, 90, 50};  // smooth < exact < rt < sc
  for (double n : {0.0, 0.5, 1.0, 2.0, 3.0, 10.0, 100.0, 3000.0, 1e4, 1e5, 1e6, 1e8})
    for (double p : {0.0, 1e-5, 1e-3, 0.01, 0.05, 0.5, 1.0})
      for (double tau : {0.02, 0.2}) {
        EXPECT_EQ(choose_binomial_level_by_cost(n, p, tau, gpu), choose_binomial_level(n, p, tau))
            << n << " " << p << " " << tau;
        const auto a = adequate_binomial_levels(n, p, tau);
        const double by_cpu = choose_binomial_level_by_cost(n, p, tau, cpu);
        const L expected = a.smooth ? L::kSmooth : L::kExact;  // rt and sc cost more than exact
        EXPECT_EQ(L(int(by_cpu)), expected) << n << " " << p << " " << tau;
      }
  // The levels a cost table can reach are the adequate ones: with the exact count dearest, the
  // choice is the GPU chooser's wherever the GPU order agrees.
  const std::array<double, kBinomialLevels> exact_dear = {1, 2, 3, 100};
  EXPECT_EQ(L(int(choose_binomial_level_by_cost(2.0, 0.01, 0.02, exact_dear))), L::kSmallCount);
  EXPECT_EQ(L(int(choose_binomial_level_by_cost(1e5, 0.01, 0.02, exact_dear))), L::kRealTime);
  EXPECT_EQ(L(int(choose_binomial_level_by_cost(3000.0, 0.01, 0.02, exact_dear))), L::kExact);
}

}  // namespace
}  // namespace glintlab

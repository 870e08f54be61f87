// Tests of core/glints/binomial.h and binomial_distribution.h: the exact sampler follows
// Binomial(n, p) (and rejects Binomial(n, 1.05 p)), the approximations' analytic distributions
// match their samplers, and the error measures behave as the limits demand; the exact kernel
// (binomial_kernel.h) draws binomial_exact's counts from its uniforms, and the glint models' draws
// from hash32 keys follow the same distributions.
#include "core/glints/binomial.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/glints/binomial_distribution.h"
#include "core/math/hash32_stream.h"
#include "verify/stats/count_tests.h"

namespace glintlab {
namespace {

std::vector<std::uint64_t> draw_exact(std::uint64_t n, double p, int m, std::uint64_t seed) {
  std::vector<std::uint64_t> v(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i) v[std::size_t(i)] = binomial_exact(n, p, seed, std::uint64_t(i));
  return v;
}

TEST(BinomialPmf, SumsToOneAndMatchesDirectForm) {
  for (auto [n, p] : std::vector<std::pair<std::uint64_t, double>>{
           {1, 0.3}, {10, 0.5}, {50, 0.01}, {1000, 0.2}, {1000000000ULL, 1e-4}}) {
    const BinomialPmf e = binomial_pmf(n, p);
    double s = 0;
    for (double f : e.f) s += f;
    EXPECT_NEAR(s, 1, 1e-12) << n << " " << p;
  }
  const BinomialPmf e = binomial_pmf(10, 0.3);
  for (std::size_t k = 0; k <= 10; ++k) {
    const double direct = std::tgamma(11) /
                          (std::tgamma(double(k) + 1) * std::tgamma(11 - double(k))) *
                          std::pow(0.3, double(k)) * std::pow(0.7, 10 - double(k));
    EXPECT_NEAR(e.f[k - e.lo], direct, 1e-14);
  }
}

TEST(BinomialExact, FollowsBinomialAndRejectsInflatedP) {
  // Inversion (np < 10), BTRS (np ≥ 10), the symmetric branch (p > ½), and n ~ 1e12.
  const std::vector<std::pair<std::uint64_t, double>> cases = {
      {7, 0.2}, {200, 0.02}, {300, 0.3}, {40, 0.9}, {1000000, 0.001}, {1000000000000ULL, 3e-9}};
  std::uint64_t seed = hash_string("binomial_exact");
  for (auto [n, p] : cases) {
    const auto v = draw_exact(n, p, 20000, seed++);
    EXPECT_GT(verify::binomial_counts_test(v, n, p).p_value, 1e-4) << n << " " << p;
    // Negative control: the same counts are not Binomial(n, p / 1.05) — i.e. counts from 1.05 p.
    const auto w = draw_exact(n, std::min(1.0, 1.05 * p), 20000, seed++);
    if (double(n) * p > 5) {
      EXPECT_LT(verify::binomial_counts_test(w, n, p).p_value, 1e-6) << n << " " << p;
    }
  }
}

// draw_binomial(sampler, n, p, key) with key = hash32_key(seed, i) for i < m: the glint models'
// draws (their keys nest the footprint's coordinates the same way).
std::vector<double> draw_hashed(BinomialSampler sampler, double n, double p, int m,
                                std::uint32_t seed) {
  std::vector<double> v(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i)
    v[std::size_t(i)] = draw_binomial(sampler, n, p, hash32_key(seed, std::uint32_t(i)));
  return v;
}

const std::vector<std::pair<std::uint64_t, double>> kExactCases = {
    {7, 0.2}, {200, 0.02}, {300, 0.3}, {40, 0.9}, {1000000, 0.001}, {1000000000000ULL, 3e-9}};

// Total-variation distance between the empirical distribution of the counts x and the pmf e
// (mass outside e's support counted in full).
double empirical_tv(const BinomialPmf& e, const std::vector<double>& x) {
  std::vector<double> hist(e.f.size(), 0.0);
  double outside = 0;
  const double w = 1.0 / double(x.size());
  for (double xi : x) {
    const double j = xi - double(e.lo);
    if (j >= 0 && j < double(hist.size()))
      hist[std::size_t(j)] += w;
    else
      outside += w;
  }
  double tv = outside;
  for (std::size_t i = 0; i < hist.size(); ++i) tv += std::abs(hist[i] - e.f[i]);
  return 0.5 * tv;
}

TEST(BinomialExactKernel, DrawsTheHostCountsFromTheHostUniforms) {
  // The masked-loop kernel on a scalar double with binomial_exact's uniforms (CounterStream) gives
  // binomial_exact's count, draw for draw, on every branch and edge, and on a hash32 stream
  // binomial_exact_from's (the glint models' scalar draw); a stream one index off does not (the
  // control).
  auto cases = kExactCases;
  cases.insert(cases.end(), {{12, 0.97}, {0, 0.3}, {10, 0.0}, {10, 1.0}, {1000, 0.5}});
  const std::uint64_t seed = hash_string("binomial_kernel");
  for (auto [n, p] : cases) {
    int differ = 0, differ_shifted = 0;
    for (std::uint64_t i = 0; i < 2000; ++i) {
      const HashStream<double> hashed{hash32_key(7u, std::uint32_t(i))};
      differ += detail::binomial_exact_double_lanes(double(n), p, hashed) !=
                double(binomial_exact_from(n, p, hashed));
      const double host = double(binomial_exact(n, p, seed, i));
      differ += detail::binomial_exact_double_lanes(double(n), p,
                                                    CounterStream<double>{seed, i}) != host;
      differ_shifted += detail::binomial_exact_double_lanes(
                            double(n), p, CounterStream<double>{seed, i + 1}) != host;
    }
    EXPECT_EQ(differ, 0) << n << " " << p;
    if (double(n) * std::min(p, 1 - p) > 5) {
      EXPECT_GT(differ_shifted, 1000) << n << " " << p;
    }
  }
}

TEST(BinomialDrawHash32, ExactFollowsBinomialAndRejectsInflatedP) {
  // The glint models' exact draws (hash32 uniforms, 32 bits in double): the cases of the host
  // sampler's test, with its control.
  std::uint32_t seed = 77;
  for (auto [n, p] : kExactCases) {
    const auto to_counts = [](const std::vector<double>& x) {
      return std::vector<std::uint64_t>(x.begin(), x.end());
    };
    const auto v = to_counts(draw_hashed(BinomialSampler::kExact, double(n), p, 20000, seed++));
    EXPECT_GT(verify::binomial_counts_test(v, n, p).p_value, 1e-4) << n << " " << p;
    const auto w = to_counts(
        draw_hashed(BinomialSampler::kExact, double(n), std::min(1.0, 1.05 * p), 20000, seed++));
    if (double(n) * p > 5) {
      EXPECT_LT(verify::binomial_counts_test(w, n, p).p_value, 1e-6) << n << " " << p;
    }
  }
}

TEST(BinomialDrawHash32, RealTimeAndSmallCountFollowTheirDistributions) {
  // The real-time sampler's CDF and the small-count sampler's pmf (binomial_distribution.h)
  // against the glint models' hash32 draws; the controls, drawn at 1.2 p, fail.
  for (auto [n, p] : std::vector<std::pair<double, double>>{{100, 0.05}, {5000, 0.3}, {20, 0.01}}) {
    const int m = 40000;
    const auto x = draw_hashed(BinomialSampler::kRealTime, n, p, m, 9);
    const auto y = draw_hashed(BinomialSampler::kRealTime, n, 1.2 * p, m, 10);
    const auto frac_below = [](const std::vector<double>& v, double q) {
      double below = 0;
      for (double xi : v) below += xi <= q;
      return below / double(v.size());
    };
    for (double q : {0.0, 1.0, n * p, n * p + std::sqrt(n * p), n - 0.5}) {
      const double f = realtime_cdf(n, p, q);
      EXPECT_NEAR(frac_below(x, q), f, 5 * std::sqrt(f * (1 - f) / m) + 1e-3) << n << " " << p << " " << q;
    }
    const double f = realtime_cdf(n, p, n * p);
    EXPECT_GT(std::abs(frac_below(y, n * p) - f), 5 * std::sqrt(f * (1 - f) / m) + 1e-3) << n << " " << p;
  }
  const std::uint64_t n = 300;
  const double p = 0.1;
  const int m = 50000;
  const BinomialPmf e = binomial_pmf(n, p);
  const auto tv_of = [&](const std::vector<double>& x) { return empirical_tv(e, x); };
  // As SamplerFollowsItsAnalyticPmf: sampling inflates the empirical TV by about 0.03.
  EXPECT_NEAR(tv_of(draw_hashed(BinomialSampler::kSmallCount, double(n), p, m, 6)),
              small_count_error(n, p).tv, 0.04);
  EXPECT_GT(tv_of(draw_hashed(BinomialSampler::kSmallCount, double(n), 1.2 * p, m, 7)),
            small_count_error(n, p).tv + 0.04);
}

TEST(BinomialExact, DeterministicAndEdgeCases) {
  EXPECT_EQ(binomial_exact(1000, 0.3, 5, 17), binomial_exact(1000, 0.3, 5, 17));
  EXPECT_EQ(binomial_exact(0, 0.3, 5, 1), 0u);
  EXPECT_EQ(binomial_exact(10, 0.0, 5, 1), 0u);
  EXPECT_EQ(binomial_exact(10, 1.0, 5, 1), 10u);
  for (std::uint64_t i = 0; i < 1000; ++i) EXPECT_LE(binomial_exact(12, 0.97, 3, i), 12u);
}

TEST(BinomialRealTime, CdfMatchesItsSampler) {
  for (auto [n, p] : std::vector<std::pair<double, double>>{{100, 0.05}, {5000, 0.3}, {20, 0.01}}) {
    const int m = 40000;
    std::vector<double> x(m);
    for (int i = 0; i < m; ++i)
      x[std::size_t(i)] = binomial_realtime(n, p, counter_uniform<double>(9, std::uint64_t(i), 0),
                                            counter_uniform<double>(9, std::uint64_t(i), 1));
    for (double q : {0.0, 1.0, n * p, n * p + std::sqrt(n * p), n - 0.5}) {
      double below = 0;
      for (double xi : x) below += xi <= q;
      const double f = realtime_cdf(n, p, q);
      EXPECT_NEAR(below / m, f, 5 * std::sqrt(f * (1 - f) / m) + 1e-3) << n << " " << p << " " << q;
    }
    double mean = 0;
    for (double xi : x) mean += xi / m;
    EXPECT_NEAR(mean / realtime_mean(n, p), 1, 0.02);
  }
}

TEST(BinomialRealTime, ErrorShrinksWithCount) {
  // Gaussian approximation: KS → 0 as n p (1 − p) grows; large at n p ~ 1 (the gate carries it).
  const double ks_small = realtime_error(10, 0.3).ks;
  const double ks_large = realtime_error(1000000, 0.3).ks;
  EXPECT_GT(ks_small, 10 * ks_large);
  EXPECT_LT(ks_large, 1e-2);
  // The gate is exact for the zero count, P(X = 0) = (1 − p)^n; what remains is the single-facet
  // mass the continuous 1 + clamp(Y) spreads above 1 (half of it at n p ≪ 1): KS ≈ P(X ≥ 1)/2.
  const double p_any = -std::expm1(1000 * std::log1p(-1e-6));
  EXPECT_NEAR(realtime_error(1000, 1e-6).ks, 0.5 * p_any, 0.02 * p_any);
}

TEST(BinomialSmallCount, ExactWhereInversionCovers) {
  // n p ≪ K: TV ≈ 0 (all mass below K); the sampler equals the exact inversion for the same u.
  EXPECT_LT(small_count_error(100000, 1e-5).tv, 1e-12);
  for (std::uint64_t i = 0; i < 2000; ++i) {
    const double u = counter_uniform<double>(4, i, 0);
    EXPECT_EQ(binomial_small_count(200.0, 0.01, u),
              double(detail::binomial_inversion(200, 0.01, u)));
  }
  // Its analytic pmf matches its sampler where the normal branch is used (n p = 30 > K).
  const BinomialError e = small_count_error(300, 0.1);
  EXPECT_GT(e.tv, 0);
  EXPECT_LT(e.tv, 0.2);
}

TEST(BinomialSmallCount, SamplerFollowsItsAnalyticPmf) {
  const std::uint64_t n = 300;
  const double p = 0.1;
  const int m = 50000;
  // Empirical TV against the exact binomial should match the analytic TV up to sampling noise.
  std::vector<double> x(std::size_t(m), 0.0);
  for (int i = 0; i < m; ++i)
    x[std::size_t(i)] =
        binomial_small_count(double(n), p, counter_uniform<double>(6, std::uint64_t(i), 0));
  // Sampling inflates the empirical TV by about Σ sqrt(f/m) ~ 0.03 here.
  EXPECT_NEAR(empirical_tv(binomial_pmf(n, p), x), small_count_error(n, p).tv, 0.04);
}

}  // namespace
}  // namespace glintlab

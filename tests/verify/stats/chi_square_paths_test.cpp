// The chi-square test's other outcomes: inconclusive when the cubature cannot resolve a bin, hard
// failure when a sample lands where the pdf is 0, defective densities, determinism across thread
// counts, and calibration of its p-values under the null.
#include <tbb/global_control.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <functional>
#include <span>
#include <cstring>
#include <iostream>
#include <vector>

#include "verify/stats/chi_square.h"
#include "verify/stats/ks.h"
#include "verify/stats/stats_test_samplers.h"

namespace glintlab::verify {
namespace {

using testing::kPi;

// Density with a step across the plane x = 0.3 (which no bin edge follows): 1 below, 1.5 above,
// normalised; sampled exactly by rejection from the uniform sphere.
struct StepDensity {
  double norm = 1 / (4 * kPi + 0.5 * 2 * kPi * (1 - 0.3));
  double operator()(const Vec3<double>& w) const { return norm * (w.x > 0.3 ? 1.5 : 1.0); }
  Vec3<double> sample(std::uint64_t seed, std::uint64_t i) const {
    for (std::uint64_t k = 0;; ++k) {
      const double z = 1 - 2 * testing::uniform(seed, i, 3 * k), phi = 2 * kPi * testing::uniform(seed, i, 3 * k + 1);
      const double r = std::sqrt(std::max(0.0, 1 - z * z));
      const Vec3<double> w{r * std::cos(phi), r * std::sin(phi), z};
      if (1.5 * testing::uniform(seed, i, 3 * k + 2) < (w.x > 0.3 ? 1.5 : 1.0)) return w;
    }
  }
};

// With no subdivisions allowed, the 15-point rules across the step leave errors far above the
// Poisson noise of the expected counts: inconclusive, neither pass nor fail. With the default
// budget the nested cubature isolates the step and the test is conclusive.
TEST(ChiSquarePaths, InconclusiveWhenCubatureCannotResolveABin) {
  const StepDensity step;
  const auto sampler = [&](std::uint64_t i) { return step.sample(31, i); };
  ChiSquareOptions o;
  o.layout = BinLayout::kEqualArea;
  o.max_subdivisions = 0;
  const ChiSquareResult r = chi_square_sphere(sampler, 200'000, step, o);
  std::cout << "step pdf, no subdivision: " << r.summary() << "\n";
  EXPECT_TRUE(r.inconclusive);
  EXPECT_FALSE(r.hard_fail);
  EXPECT_FALSE(r.rejects(kFamilyWiseRate));
  EXPECT_GT(r.max_error_ratio, 0.01);
  EXPECT_NE(r.reason.find("quadrature error"), std::string::npos) << r.reason;

  o.max_subdivisions = ChiSquareOptions{}.max_subdivisions;
  const ChiSquareResult d = chi_square_sphere(sampler, 200'000, step, o);
  std::cout << "step pdf, default budget: " << d.summary() << "\n";
  EXPECT_FALSE(d.inconclusive) << d.reason;
  EXPECT_GT(d.p_value, kFamilyWiseRate);
  EXPECT_NEAR(d.mass, 1.0, 1e-6);
}

TEST(ChiSquarePaths, InconclusiveWhenThePdfIsNotFinite) {
  const ChiSquareResult r = chi_square_sphere(
      [](std::uint64_t i) { return testing::uniform_sphere(32, i); }, 10'000,
      [](const Vec3<double>& w) { return w.z > 0.5 ? std::nan("") : 1 / (4 * kPi); });
  EXPECT_TRUE(r.inconclusive);
  EXPECT_FALSE(r.rejects(kFamilyWiseRate));
  std::cout << "NaN pdf: " << r.summary() << "\n";
}

// A spike of width 1e-4 rad in the lower hemisphere, away from the lobe axis and every breakpoint:
// the per-bin rules never evaluate the pdf near it, so its bins get expectation 0. Samples land
// there where the pdf is positive: the cubature missed mass, the test is inconclusive (not failed).
TEST(ChiSquarePaths, InconclusiveWhenTheCubatureMissesASpike) {
  const testing::VonMisesFisher spike(1e8, testing::unit({0.5, 0.6, -0.62}));
  const auto pdf = [&](const Vec3<double>& w) { return 0.9 * testing::cosine_pdf(w) + 0.1 * spike.pdf(w); };
  const auto sampler = [&](std::uint64_t i) {
    return testing::uniform(33, i, 5) < 0.9 ? testing::cosine_hemisphere(33, i) : spike.sample(34, i);
  };
  ChiSquareOptions o;
  o.layout = BinLayout::kEqualArea;
  const ChiSquareResult r = chi_square_sphere(sampler, 100'000, pdf, o);
  std::cout << "missed spike: " << r.summary() << "\n";
  EXPECT_TRUE(r.inconclusive);
  EXPECT_FALSE(r.hard_fail);
  EXPECT_NE(r.reason.find("cubature gave 0 where the pdf is positive"), std::string::npos) << r.reason;
  EXPECT_NEAR(r.mass, 0.9, 1e-6);  // the mass it could see
}

// Hard failures: p = 0 whatever the statistic.
TEST(ChiSquarePaths, HardFailWhenASampleLandsWhereThePdfIsZero) {
  // A hemisphere sampler that puts one sample in 10^4 below the horizon.
  const ChiSquareResult h = chi_square_hemisphere(
      [](std::uint64_t i) {
        Vec3<double> w = testing::cosine_hemisphere(35, i);
        if (i % 10'000 == 7) w.z = -w.z;
        return w;
      },
      100'000, testing::cosine_pdf);
  std::cout << "below the horizon: " << h.summary() << "\n";
  EXPECT_TRUE(h.hard_fail);
  EXPECT_EQ(h.p_value, 0.0);
  EXPECT_EQ(h.first_bad_sample, 7u);
  EXPECT_TRUE(h.rejects(kFamilyWiseRate));

  // A pdf that is 0 on the cap z > 0.9 while the sampler covers the whole sphere: the
  // equal-probability layout makes the cap one zero-expectation bin.
  const double cap = 2 * kPi * 0.1;
  const ChiSquareResult s = chi_square_sphere(
      [](std::uint64_t i) { return testing::uniform_sphere(36, i); }, 100'000,
      [&](const Vec3<double>& w) { return w.z > 0.9 ? 0.0 : 1 / (4 * kPi - cap); });
  std::cout << "sample in a zero-pdf cap: " << s.summary() << "\n";
  EXPECT_TRUE(s.hard_fail);
  EXPECT_EQ(s.p_value, 0.0);
  EXPECT_NE(s.hard_fail_reason.find("pdf is 0"), std::string::npos) << s.hard_fail_reason;

  // "No sample" results while the pdf claims all the mass.
  const ChiSquareResult ns = chi_square_sphere(
      [](std::uint64_t i) { return i == 123 ? Vec3<double>{0, 0, 0} : testing::uniform_sphere(37, i); }, 10'000,
      [](const Vec3<double>&) { return 1 / (4 * kPi); });
  EXPECT_TRUE(ns.hard_fail);
  EXPECT_EQ(ns.first_bad_sample, 123u);

  // A disk point outside the disk, and a malformed direction.
  const ChiSquareResult dk = chi_square_disk(
      [](std::uint64_t i) { return i == 5 ? Vec2<double>{0.95, 0.95} : testing::uniform_disk_polar(38, i); },
      10'000, testing::disk_pdf);
  EXPECT_TRUE(dk.hard_fail);
  EXPECT_EQ(dk.first_bad_sample, 5u);
  const ChiSquareResult mf = chi_square_sphere(
      [](std::uint64_t i) { return i == 9 ? Vec3<double>{0, 0, 2} : testing::uniform_sphere(39, i); }, 10'000,
      [](const Vec3<double>&) { return 1 / (4 * kPi); });
  EXPECT_TRUE(mf.hard_fail);
  EXPECT_NE(mf.hard_fail_reason.find("malformed"), std::string::npos);
}

// A defective density (the sampler fails 10 % of the time, the pdf integrates to 0.9) is accepted
// with its "no sample" cell; a pdf claiming failures that never happen is rejected.
TEST(ChiSquarePaths, DefectiveDensity) {
  const auto pdf = [](const Vec3<double>&) { return 0.9 / (4 * kPi); };
  const auto failing = [](std::uint64_t i) {
    return testing::uniform(40, i, 7) < 0.1 ? Vec3<double>{0, 0, 0} : testing::uniform_sphere(40, i);
  };
  const ChiSquareResult ok = chi_square_sphere(failing, 200'000, pdf);
  std::cout << "defective density: " << ok.summary() << "\n";
  EXPECT_FALSE(ok.rejects(kFamilyWiseRate)) << ok.summary();
  EXPECT_FALSE(ok.inconclusive);
  EXPECT_NEAR(ok.mass, 0.9, 1e-9);
  EXPECT_NEAR(double(ok.no_samples), 20'000, 600);
  const ChiSquareResult bad = chi_square_sphere([](std::uint64_t i) { return testing::uniform_sphere(41, i); },
                                                200'000, pdf);
  EXPECT_TRUE(bad.rejects(kFamilyWiseRate));
  EXPECT_FALSE(bad.hard_fail);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

TEST(ChiSquarePaths, BitIdenticalForOneAndTwoThreads) {
  const testing::VonMisesFisher vmf(1e4, testing::unit({-0.2, 0.4, 0.9}));
  ChiSquareOptions o;
  o.lobe = vmf.frame.z;
  o.chunk = 1000;
  auto run = [&](int threads) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    const ChiSquarePlan plan = plan_direction_chi_square(
        SampleDomain::kSphere, [&](const Vec3<double>& w) { return vmf.pdf(w); }, 200'000, o);
    return std::make_pair(plan, run_direction_chi_square(plan, [&](std::uint64_t i) { return vmf.sample(42, i); }));
  };
  const auto [p1, r1] = run(1);
  const auto [p2, r2] = run(2);
  ASSERT_EQ(p1.grids.size(), p2.grids.size());
  for (std::size_t g = 0; g < p1.grids.size(); ++g) {
    ASSERT_EQ(p1.grids[g].t_edges.size(), p2.grids[g].t_edges.size());
    for (std::size_t i = 0; i < p1.grids[g].t_edges.size(); ++i)
      EXPECT_TRUE(same_bits(p1.grids[g].t_edges[i], p2.grids[g].t_edges[i]));
    for (std::size_t b = 0; b < p1.grids[g].bins(); ++b) {
      EXPECT_TRUE(same_bits(p1.grids[g].expected[b], p2.grids[g].expected[b]));
      EXPECT_TRUE(same_bits(p1.grids[g].error[b], p2.grids[g].error[b]));
    }
  }
  ASSERT_EQ(r1.resolutions.size(), r2.resolutions.size());
  for (std::size_t g = 0; g < r1.resolutions.size(); ++g) {
    EXPECT_TRUE(same_bits(r1.resolutions[g].statistic, r2.resolutions[g].statistic));
    EXPECT_TRUE(same_bits(r1.resolutions[g].p_value, r2.resolutions[g].p_value));
    EXPECT_EQ(r1.resolutions[g].cells, r2.resolutions[g].cells);
  }
  EXPECT_TRUE(same_bits(r1.p_value, r2.p_value));
  EXPECT_TRUE(same_bits(r1.mass, r2.mass));
}

// A pdf given over many directions per call (ChiSquareOptions::direction_pdf_rows, what a Python
// model's pdf is given as) plans the same bins and expectations, bit for bit, as the pdf called one
// direction at a time, with far fewer calls: on the sphere about a tilted lobe (a kink the breaks
// do not follow), on a tilted hemisphere (the horizon's split and the mask below it), and on a
// pdf that is NaN somewhere (the same inconclusive plan).
TEST(ChiSquarePaths, PdfRowsPlanTheSameBitForBit) {
  const Vec3<double> lobe = testing::unit({0.5, -0.3, 0.8});
  const auto kinked = [](const Vec3<double>& w) { return w.z > 0 ? w.z / kPi : 0.0; };
  const auto nan_above = [](const Vec3<double>& w) { return w.z > 0.9 ? std::nan("") : 1 / (4 * kPi); };
  struct Case {
    SampleDomain domain;
    std::function<double(const Vec3<double>&)> pdf;
  };
  for (const Case& c : {Case{SampleDomain::kSphere, kinked}, Case{SampleDomain::kHemisphere, kinked},
                        Case{SampleDomain::kSphere, nan_above}}) {
    ChiSquareOptions o;
    o.lobe = lobe;
    o.coarse_bins = 64;
    o.fine_max_bins = 256;
    o.rel_tol = 1e-5;
    o.max_subdivisions = 40;
    std::atomic<long> one_calls = 0, rows_calls = 0, rows_points = 0;
    const ChiSquarePlan one = plan_direction_chi_square(
        c.domain,
        [&](const Vec3<double>& w) {
          ++one_calls;
          return c.pdf(w);
        },
        100'000, o);
    o.direction_pdf_rows = [&](std::span<const Vec3<double>> w, std::span<double> out) {
      ++rows_calls;
      rows_points += long(w.size());
      for (std::size_t i = 0; i < w.size(); ++i) out[i] = c.pdf(w[i]);
    };
    const ChiSquarePlan rows = plan_direction_chi_square(c.domain, c.pdf, 100'000, o);
    EXPECT_EQ(one.inconclusive, rows.inconclusive);
    EXPECT_EQ(one.reason, rows.reason);
    ASSERT_EQ(one.grids.size(), rows.grids.size());
    for (std::size_t g = 0; g < one.grids.size(); ++g) {
      ASSERT_EQ(one.grids[g].t_edges.size(), rows.grids[g].t_edges.size());
      for (std::size_t i = 0; i < one.grids[g].t_edges.size(); ++i)
        EXPECT_TRUE(same_bits(one.grids[g].t_edges[i], rows.grids[g].t_edges[i]));
      ASSERT_EQ(one.grids[g].bins(), rows.grids[g].bins());
      for (std::size_t b = 0; b < one.grids[g].bins(); ++b) {
        EXPECT_TRUE(same_bits(one.grids[g].expected[b], rows.grids[g].expected[b])) << g << " " << b;
        EXPECT_TRUE(same_bits(one.grids[g].error[b], rows.grids[g].error[b])) << g << " " << b;
      }
    }
    if (one.inconclusive) continue;
    // Every point the one-at-a-time cubature asks for, the rows route asks for too, and no more
    // (the tilted hemisphere's points below the horizon are 0 without a call on either route).
    EXPECT_EQ(rows_points.load(), one_calls.load());
    EXPECT_LT(rows_calls.load() * 20, one_calls.load());
  }
}

// Under the null the raw p-values of each resolution are uniform: 120 seeds of a cosine-lobe
// sampler with N = 1e4 (coarse 100 bins, fine 200), one plan, KS test of each resolution's p.
TEST(ChiSquarePaths, PValuesAreCalibrated) {
  const std::uint64_t n = 10'000;
  const ChiSquarePlan plan = plan_direction_chi_square(SampleDomain::kHemisphere, testing::cosine_pdf, n);
  ASSERT_EQ(plan.grids.size(), 2u);
  std::vector<double> coarse, fine, combined;
  for (std::uint64_t s = 0; s < 120; ++s) {
    const ChiSquareResult r =
        run_direction_chi_square(plan, [s](std::uint64_t i) { return testing::cosine_hemisphere(1000 + s, i); });
    ASSERT_FALSE(r.inconclusive) << r.reason;
    coarse.push_back(r.raw_p_values[0]);
    fine.push_back(r.raw_p_values[1]);
    combined.push_back(r.p_value);
  }
  const KsResult kc = ks_test_uniform(coarse), kf = ks_test_uniform(fine);
  std::cout << "calibration, 120 seeds: KS of coarse p: D=" << kc.statistic << " p=" << kc.p_value
            << "; fine p: D=" << kf.statistic << " p=" << kf.p_value << "\n";
  EXPECT_GT(kc.p_value, 1e-3);
  EXPECT_GT(kf.p_value, 1e-3);
  // Šidák over positively dependent tests is conservative: no more small combined p than α.
  std::size_t below = 0;
  for (double p : combined) below += p < 0.05 ? 1 : 0;
  EXPECT_LE(below, 14u);  // 6 expected at exactly 5 %; binomial 99.9 % bound
}

}  // namespace
}  // namespace glintlab::verify

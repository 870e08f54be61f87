// Chi-square goodness of fit of correct samplers: the test must not reject them, and the expected
// counts must account for all of the density.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>

#include "verify/stats/chi_square.h"
#include "verify/stats/stats_test_samplers.h"

namespace glintlab::verify {
namespace {

using testing::kPi;

void report(const char* name, const ChiSquareResult& r, double seconds) {
  std::cout << name << ": " << r.summary() << " [" << seconds << " s]\n";
}

template <class F>
ChiSquareResult timed(const char* name, F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  ChiSquareResult r = f();
  report(name, r, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return r;
}

void expect_accepted(const ChiSquareResult& r) {
  EXPECT_FALSE(r.hard_fail) << r.hard_fail_reason;
  EXPECT_FALSE(r.inconclusive) << r.reason;
  EXPECT_GT(r.p_value, kFamilyWiseRate) << r.summary();
  EXPECT_FALSE(r.rejects(kFamilyWiseRate));
  EXPECT_EQ(r.resolutions.size(), 2u);
}

TEST(ChiSquareSamplers, UniformSphere) {
  for (BinLayout layout : {BinLayout::kEqualArea, BinLayout::kEqualProbability}) {
    ChiSquareOptions o;
    o.layout = layout;
    const std::uint64_t n = layout == BinLayout::kEqualArea ? 1'000'000 : 200'000;
    const auto r = timed(layout == BinLayout::kEqualArea ? "uniform sphere, equal area"
                                                         : "uniform sphere, equal probability",
                         [&] {
                           return chi_square_sphere(
                               [](std::uint64_t i) { return testing::uniform_sphere(1, i); }, n,
                               [](const Vec3<double>&) { return 1 / (4 * kPi); }, o);
                         });
    expect_accepted(r);
    EXPECT_NEAR(r.mass, 1.0, 1e-9);
    EXPECT_EQ(r.resolutions[0].bins, 102u);  // 6 rings × 17 sectors
    EXPECT_EQ(r.resolutions[1].bins, n == 1'000'000 ? 4104u : 3996u);  // 36 × 114 (capped), 36 × 111
  }
}

TEST(ChiSquareSamplers, CosineHemisphere) {
  const auto r = timed("cosine hemisphere", [] {
    return chi_square_hemisphere([](std::uint64_t i) { return testing::cosine_hemisphere(2, i); }, 1'000'000,
                                 testing::cosine_pdf);
  });
  expect_accepted(r);
  EXPECT_NEAR(r.mass, 1.0, 1e-9);
}

// The same hemisphere sampler binned about a tilted lobe: bins straddle the horizon, the cubature
// splits at it, and bins below it have zero expectation.
TEST(ChiSquareSamplers, CosineHemisphereTiltedFrame) {
  ChiSquareOptions o;
  o.lobe = {0.6, 0.0, 0.8};
  const auto r = timed("cosine hemisphere, tilted bins", [&] {
    return chi_square_hemisphere([](std::uint64_t i) { return testing::cosine_hemisphere(3, i); }, 300'000,
                                 testing::cosine_pdf, o);
  });
  expect_accepted(r);
  EXPECT_NEAR(r.mass, 1.0, 1e-9);
}

// A von Mises–Fisher lobe of width 1e-3 rad (κ = 1e6) about a generic direction, sampled exactly:
// the equal-probability rings spread it over every bin.
TEST(ChiSquareSamplers, NarrowVonMisesFisherLobe) {
  const testing::VonMisesFisher vmf(1e6, testing::unit({0.3, -0.5, 0.8}));
  ChiSquareOptions o;
  o.lobe = vmf.frame.z;
  const auto r = timed("vMF κ = 1e6", [&] {
    return chi_square_sphere([&](std::uint64_t i) { return vmf.sample(4, i); }, 1'000'000,
                             [&](const Vec3<double>& w) { return vmf.pdf(w); }, o);
  });
  expect_accepted(r);
  EXPECT_NEAR(r.mass, 1.0, 1e-9);
  // Bins hold their share: the coarse resolution has ≈ 100 cells of ≈ 1e4 expected samples.
  EXPECT_GE(r.resolutions[0].cells, 90u);
}

TEST(ChiSquareSamplers, UniformDisk) {
  for (int which = 0; which < 2; ++which) {
    const auto r = timed(which == 0 ? "disk, polar" : "disk, concentric", [&] {
      return chi_square_disk(
          [which](std::uint64_t i) {
            return which == 0 ? testing::uniform_disk_polar(5, i) : testing::uniform_disk_concentric(6, i);
          },
          which == 0 ? 200'000 : 1'000'000, testing::disk_pdf);
    });
    expect_accepted(r);
    EXPECT_NEAR(r.mass, 1.0, 1e-9);
  }
}

// A non-uniform disk density, pdf = (32/π)·r² about the centre, sampled exactly (r = ½ξ^{1/4}),
// with equal-probability rings; and the uniform sampler against it is rejected.
TEST(ChiSquareSamplers, DiskRadialDensityEqualProbability) {
  const auto pdf = [](const Vec2<double>& p) {
    const double r2 = (p.x - 0.5) * (p.x - 0.5) + (p.y - 0.5) * (p.y - 0.5);
    return r2 <= 0.25 ? 32 / kPi * r2 : 0.0;
  };
  ChiSquareOptions o;
  o.layout = BinLayout::kEqualProbability;
  const ChiSquarePlan plan = plan_disk_chi_square(pdf, 200'000, o);
  const ChiSquareResult r = run_disk_chi_square(plan, [](std::uint64_t i) {
    const double rr = 0.5 * std::pow(testing::uniform(7, i, 0), 0.25), phi = 2 * kPi * testing::uniform(7, i, 1);
    return Vec2<double>{0.5 + rr * std::cos(phi), 0.5 + rr * std::sin(phi)};
  });
  report("disk r² density, equal probability", r, 0);
  expect_accepted(r);
  EXPECT_NEAR(r.mass, 1.0, 1e-9);
  // Equal-probability rings: the innermost ring is wide, the outermost narrow.
  const BinGrid& g = plan.grids[0];
  EXPECT_GT(g.t_edges[1] - g.t_edges[0], 2 * (g.t_edges.back() - g.t_edges[g.rings() - 1]));
  const ChiSquareResult bad =
      run_disk_chi_square(plan, [](std::uint64_t i) { return testing::uniform_disk_polar(8, i); });
  EXPECT_TRUE(bad.rejects(kFamilyWiseRate));
}

}  // namespace
}  // namespace glintlab::verify

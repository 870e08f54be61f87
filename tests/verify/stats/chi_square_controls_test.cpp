// Negative controls of the chi-square test: wrong pdfs and wrong samplers it must reject, and a
// localized error that only the fine resolution can see.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>

#include "verify/stats/chi_square.h"
#include "verify/stats/stats_test_samplers.h"

namespace glintlab::verify {
namespace {

using testing::kPi;

void report(const char* name, const ChiSquareResult& r) {
  std::cout << name << ": " << r.summary() << "\n";
  for (std::size_t g = 0; g < r.resolutions.size(); ++g)
    std::cout << "    " << (g == 0 ? "coarse" : "fine") << ": smallest effect at 90 % power: δ = "
              << r.resolutions[g].detectable_global << " everywhere, " << r.resolutions[g].detectable_one_cell
              << " in one cell (λ_min = " << r.resolutions[g].min_noncentrality << ")\n";
}

// The claimed pdf is 2 % too large everywhere (mass 1.02): λ ≈ N·0.02²/1.02 ≈ 392.
TEST(ChiSquareControls, PdfScaledBy102) {
  const ChiSquareResult r = chi_square_sphere([](std::uint64_t i) { return testing::uniform_sphere(21, i); },
                                              1'000'000, [](const Vec3<double>&) { return 1.02 / (4 * kPi); });
  report("pdf × 1.02", r);
  EXPECT_FALSE(r.inconclusive) << r.reason;
  EXPECT_FALSE(r.hard_fail);
  EXPECT_NEAR(r.mass, 1.02, 1e-9);
  EXPECT_TRUE(r.rejects(kFamilyWiseRate));
  EXPECT_LT(r.raw_p_values[0], 1e-20);
  // The power report says a 2 % error is well within reach of the coarse resolution.
  EXPECT_LT(r.resolutions[0].detectable_global, 0.02);
}

// A von Mises–Fisher lobe of width 1e-3 sampled about an axis tilted by 3e-5 rad (3 % of its
// width) from the claimed one.
TEST(ChiSquareControls, LobeShiftedBySmallAngle) {
  const Vec3<double> axis = testing::unit({0.3, -0.5, 0.8});
  const testing::VonMisesFisher claimed(1e6, axis);
  const double shift = 3e-5;
  const testing::VonMisesFisher actual(
      1e6, testing::unit(std::cos(shift) * claimed.frame.z + std::sin(shift) * claimed.frame.x));
  ChiSquareOptions o;
  o.lobe = axis;
  const ChiSquareResult r = chi_square_sphere([&](std::uint64_t i) { return actual.sample(22, i); }, 1'000'000,
                                              [&](const Vec3<double>& w) { return claimed.pdf(w); }, o);
  report("vMF shifted by 3e-5 rad", r);
  EXPECT_FALSE(r.inconclusive) << r.reason;
  EXPECT_TRUE(r.rejects(kFamilyWiseRate));
  // The unshifted sampler on the same plan is accepted.
  const ChiSquarePlan plan = plan_direction_chi_square(
      SampleDomain::kSphere, [&](const Vec3<double>& w) { return claimed.pdf(w); }, 1'000'000, o);
  const ChiSquareResult ok = run_direction_chi_square(plan, [&](std::uint64_t i) { return claimed.sample(22, i); });
  report("vMF unshifted, same seed", ok);
  EXPECT_FALSE(ok.rejects(kFamilyWiseRate));
}

// A localized, mass-preserving error: inside a cap of radius 0.14 rad (0.49 % of the sphere) in the
// middle of one coarse bin, the sampler moves 60 % of the samples of one half of the cap into the
// other half (density ×0.4 on one half, ×1.6 on the other). The coarse bin's count is unchanged, so
// the coarse resolution cannot see it (λ = 0); the fine bins (≈ 15 inside the cap) see
// λ ≈ N·f·0.6² ≈ 1.8e3 before edge losses, against λ_min ≈ 430.
TEST(ChiSquareControls, LocalizedErrorSeenOnlyByTheFineResolution) {
  const auto pdf = [](const Vec3<double>&) { return 1 / (4 * kPi); };
  const std::uint64_t n = 1'000'000;
  const ChiSquarePlan plan = plan_direction_chi_square(SampleDomain::kSphere, pdf, n);
  ASSERT_EQ(plan.grids.size(), 2u);
  const BinGrid& coarse = plan.grids[0];
  // Centre of ring 3, sector 0 of the coarse grid (frame = world for the default lobe +z).
  const std::size_t ring = 3;
  const double t = 0.5 * (coarse.t_edges[ring] + coarse.t_edges[ring + 1]);
  const double phi = kPi / double(coarse.sectors[ring]);
  const Vec3<double> c{std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t)};
  const Vec3<double> a{-std::sin(phi), std::cos(phi), 0.0};  // splits the cap along φ
  const double rho = 0.14, q = 0.6;
  // The cap lies inside the coarse bin.
  ASSERT_GT(t - rho, coarse.t_edges[ring]);
  ASSERT_LT(t + rho, coarse.t_edges[ring + 1]);
  ASSERT_LT(rho / std::sin(t), phi);
  const auto sampler = [&](std::uint64_t i) {
    Vec3<double> w = testing::uniform_sphere(23, i);
    if (dot(w, c) >= std::cos(rho) && dot(w, a) < 0 && testing::uniform(23, i, 2) < q)
      w = w - (2 * dot(w, a)) * a;
    return w;
  };
  const ChiSquareResult r = run_direction_chi_square(plan, sampler);
  report("localized ±60 % dipole", r);
  EXPECT_FALSE(r.inconclusive) << r.reason;
  EXPECT_GT(r.raw_p_values[0], kFamilyWiseRate);  // coarse: blind by construction
  EXPECT_LT(r.raw_p_values[1], 1e-6);             // fine: sees it
  EXPECT_TRUE(r.rejects(kFamilyWiseRate));
}

// Wrong disk sampler: r = ½ξ instead of ½√ξ (density ∝ 1/r).
TEST(ChiSquareControls, DiskWithoutSquareRoot) {
  const ChiSquareResult r = chi_square_disk(
      [](std::uint64_t i) {
        const double rr = 0.5 * testing::uniform(24, i, 0), phi = 2 * kPi * testing::uniform(24, i, 1);
        return Vec2<double>{0.5 + rr * std::cos(phi), 0.5 + rr * std::sin(phi)};
      },
      100'000, testing::disk_pdf);
  report("disk r = ξ/2", r);
  EXPECT_TRUE(r.rejects(kFamilyWiseRate));
  EXPECT_FALSE(r.hard_fail);
}

}  // namespace
}  // namespace glintlab::verify

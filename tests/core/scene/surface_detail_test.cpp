// Tests of the procedural height fields and the mip-mapped slope moments for LEAN mapping:
// analytic slopes against finite differences, box-filtered levels against the average of the fine
// ones, the coarsest level against the fields' closed-form slope covariance, the anisotropic
// field's rotated, anisotropic covariance, trilinear lookups and footprint LOD, and LEAN σ/ρ
// recovering a known Gaussian slope field (and rejecting a wrong ρ).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>

#include "core/math/rng.h"
#include "core/scene/lean.h"
#include "core/scene/sine_height_field.h"
#include "core/scene/slope_moment_map.h"
#include "verify/check.h"

namespace glintlab {
namespace {

using V2 = Vec2<double>;
constexpr double kPiD = std::numbers::pi;

SlopeMomentMap::SlopeField slopes_of(const SineHeightField<double>& f) {
  return [f](double u, double v) {
    const auto p = f.eval(u, v);
    return V2{p.slope_u, p.slope_v};
  };
}

TEST(SurfaceDetail, SlopesAndNormalsMatchFiniteDifferences) {
  for (const auto& f : {isotropic_sine_bumps(0.2), brushed_grooves(0.2, 8)}) {
    const std::uint64_t seed = verify::check_seed("scene.finite_differences", 0);
    for (std::uint64_t i = 0; i < 200; ++i) {
      const double u = counter_uniform<double>(seed, i, 0), v = counter_uniform<double>(seed, i, 1);
      const double h = 1e-6;
      const auto p = f.eval(u, v);
      const double du = (f.eval(u + h, v).height - f.eval(u - h, v).height) / (2 * h);
      const double dv = (f.eval(u, v + h).height - f.eval(u, v - h).height) / (2 * h);
      EXPECT_NEAR(p.slope_u, du, 1e-6 * (1 + std::abs(du)));
      EXPECT_NEAR(p.slope_v, dv, 1e-6 * (1 + std::abs(dv)));
      EXPECT_NEAR(length(p.normal), 1.0, 1e-14);
      EXPECT_NEAR(p.normal.x / p.normal.z, -p.slope_u, 1e-12);
      EXPECT_NEAR(p.normal.y / p.normal.z, -p.slope_v, 1e-12);
      // It tiles the unit square.
      EXPECT_NEAR(f.eval(u + 1, v - 1).height, p.height, 1e-12);
    }
  }
  EXPECT_THROW(isotropic_sine_bumps(0), ParameterError);
  EXPECT_THROW(brushed_grooves(0.1, 0.5), ParameterError);
}

TEST(SurfaceDetail, CovarianceIsIsotropicForBumpsAndRotatedAnisotropicForGrooves) {
  const Vec3<double> ci = isotropic_sine_bumps(0.2).slope_covariance();
  EXPECT_NEAR(ci.x, 0.04, 1e-15);
  EXPECT_NEAR(ci.y, 0.04, 1e-15);
  EXPECT_NEAR(ci.z, 0.0, 1e-15);
  const Vec3<double> cg = brushed_grooves(0.2, 8).slope_covariance();
  // Eigenvalues of [[xx, xy], [xy, yy]]: their ratio is the anisotropy squared.
  const double tr = cg.x + cg.y, det = cg.x * cg.y - cg.z * cg.z;
  const double disc = std::sqrt(tr * tr / 4 - det);
  const double l1 = tr / 2 + disc, l2 = tr / 2 - disc;
  std::cout << "grooves: covariance (" << cg.x << ", " << cg.y << ", " << cg.z
            << "), eigenvalue ratio " << l1 / l2 << "\n";
  EXPECT_NEAR(l1 / l2, 64.0, 1e-9);
  EXPECT_GT(std::abs(cg.z / std::sqrt(cg.x * cg.y)), 0.5);  // the covariance is rotated: ρ ≠ 0
}

TEST(SurfaceDetail, CoarseLevelsAreTheAverageOfFineOnes) {
  const SlopeMomentMap map(slopes_of(brushed_grooves(0.2, 8)), 64, 2);
  ASSERT_EQ(map.levels(), 7);
  double worst = 0;
  for (int l = 1; l < map.levels(); ++l) {
    const int n = map.level_size(l);
    const int k = 1 << l;  // level-0 texels per side of one level-l texel
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        SlopeMoments<double> avg{0, 0, 0, 0, 0};
        for (int b = 0; b < k; ++b)
          for (int a = 0; a < k; ++a) {
            const auto& t = map.texel(0, i * k + a, j * k + b);
            avg = {avg.mean_x + t.mean_x, avg.mean_y + t.mean_y, avg.xx + t.xx, avg.yy + t.yy,
                   avg.xy + t.xy};
          }
        const double s = 1.0 / (k * k);
        const auto& c = map.texel(l, i, j);
        worst = std::max({worst, std::abs(c.mean_x - s * avg.mean_x),
                          std::abs(c.mean_y - s * avg.mean_y), std::abs(c.xx - s * avg.xx),
                          std::abs(c.yy - s * avg.yy), std::abs(c.xy - s * avg.xy)});
      }
  }
  EXPECT_LT(worst, 1e-14);
}

// At the coarsest level (one texel over the whole period) the moments are the field's: E[s] = 0
// and Σ of slope_covariance(), exactly, because a uniform grid of more than 2·max|k| points per
// axis integrates the products of the sines exactly.
TEST(SurfaceDetail, CoarsestLevelEqualsTheClosedFormMoments) {
  for (const auto& f : {isotropic_sine_bumps(0.2), brushed_grooves(0.2, 8)}) {
    const SlopeMomentMap map(slopes_of(f), 32, 4);  // 128 points per axis > 2 · 69
    const auto& m = map.texel(map.levels() - 1, 0, 0);
    const Vec3<double> c = f.slope_covariance();
    EXPECT_NEAR(m.mean_x, 0.0, 1e-12);
    EXPECT_NEAR(m.mean_y, 0.0, 1e-12);
    EXPECT_NEAR(m.xx / c.x, 1.0, 1e-10);
    EXPECT_NEAR(m.yy / c.y, 1.0, 1e-10);
    EXPECT_NEAR(m.xy, c.z, 1e-10 * c.x);
    const auto lean = lean_parameters(m);
    EXPECT_NEAR(lean.sigma_x, std::sqrt(c.x), 1e-9);
    EXPECT_NEAR(lean.rho, c.z / std::sqrt(c.x * c.y), 1e-9);
  }
}

TEST(SurfaceDetail, TrilinearLookupAndFootprintLod) {
  const SlopeMomentMap map(slopes_of(isotropic_sine_bumps(0.2)), 16, 2);
  // At a texel centre and an integer level, the lookup returns the texel.
  const auto& t = map.texel(2, 1, 3);
  const auto a = map.trilinear(1.5 / 4, 3.5 / 4, 2.0);
  EXPECT_NEAR(a.xx, t.xx, 1e-15);
  EXPECT_NEAR(a.xy, t.xy, 1e-15);
  // Half-way between levels: the mean of the two bilinear lookups.
  const auto b = map.trilinear(0.3, 0.7, 1.5);
  const auto b1 = map.bilinear(1, 0.3, 0.7), b2 = map.bilinear(2, 0.3, 0.7);
  EXPECT_NEAR(b.yy, 0.5 * (b1.yy + b2.yy), 1e-15);
  // Periodic: u and u + 1 agree.
  EXPECT_NEAR(map.bilinear(0, 0.01, 0.99).xx, map.bilinear(0, 1.01, -0.01).xx, 1e-14);
  // Footprint of 4 texels → λ = 2; below one texel → 0; beyond the pyramid → clamped.
  EXPECT_NEAR(map.lod(V2{4.0 / 16, 0}, V2{0, 1.0 / 16}), 2.0, 1e-12);
  EXPECT_EQ(map.lod(V2{1e-4, 0}, V2{0, 1e-4}), 0.0);
  const auto far = map.lookup(0.2, 0.4, V2{100.0, 0}, V2{0, 100.0});
  EXPECT_NEAR(far.xx, map.texel(map.levels() - 1, 0, 0).xx, 1e-15);
  EXPECT_THROW(SlopeMomentMap(slopes_of(isotropic_sine_bumps(0.2)), 12), ParameterError);
  EXPECT_THROW(SlopeMomentMap(slopes_of(isotropic_sine_bumps(0.2)), 0), ParameterError);
  EXPECT_THROW(SlopeMomentMap(slopes_of(isotropic_sine_bumps(0.2)), 16, 0), ParameterError);
}

// A Gaussian slope field with known σ_x, σ_y, ρ (one independent draw per level-0 sample point,
// by Box–Muller from counter uniforms and the Cholesky factor of Σ): LEAN's σ and ρ at the coarsest
// level recover them within 4 standard errors of the M-sample estimates (SE(σ) ≈ σ/√(2M),
// SE(ρ) ≈ (1 − ρ²)/√M), and the same tolerance rejects ρ = 0 (LEAN without the correlation, the
// error Chermain et al. 2021 Fig. 7 shows).
TEST(SurfaceDetail, LeanRecoversAGaussianSlopeField) {
  const double sx = 0.3, sy = 0.1, rho = 0.6, base_alpha = 0.05;
  const int size = 128, ss = 2, grid = size * ss;
  const std::uint64_t seed = verify::check_seed("scene.lean_gaussian", 0);
  const auto field = [&](double u, double v) {
    const auto i = std::uint64_t(std::floor(u * grid)), j = std::uint64_t(std::floor(v * grid));
    const std::uint64_t idx = j * grid + i;
    const double r = std::sqrt(-2 * std::log1p(-counter_uniform<double>(seed, idx, 0)));
    const double phi = 2 * kPiD * counter_uniform<double>(seed, idx, 1);
    const double z1 = r * std::cos(phi), z2 = r * std::sin(phi);
    return V2{0.05 + sx * z1, -0.02 + sy * (rho * z1 + std::sqrt(1 - rho * rho) * z2)};
  };
  const SlopeMomentMap map(field, size, ss);
  const auto m = map.texel(map.levels() - 1, 0, 0);
  const auto lean = lean_parameters(m, base_alpha);
  const double base = 0.5 * base_alpha * base_alpha;
  const double M = double(grid) * grid;
  const double ex = std::sqrt(sx * sx + base), ey = std::sqrt(sy * sy + base);
  const double erho = rho * sx * sy / (ex * ey);
  const double tol_rho = 4 * (1 - erho * erho) / std::sqrt(M);
  std::cout << "LEAN: σx " << lean.sigma_x << " (" << ex << "), σy " << lean.sigma_y << " (" << ey
            << "), ρ " << lean.rho << " (" << erho << ", tol " << tol_rho << ")\n";
  EXPECT_NEAR(lean.sigma_x, ex, 4 * sx / std::sqrt(2 * M));
  EXPECT_NEAR(lean.sigma_y, ey, 4 * sy / std::sqrt(2 * M));
  EXPECT_NEAR(lean.rho, erho, tol_rho);
  EXPECT_NEAR(lean.mean_x, 0.05, 4 * sx / std::sqrt(M));
  EXPECT_NEAR(lean.mean_y, -0.02, 4 * sy / std::sqrt(M));
  EXPECT_GT(std::abs(0.0 - erho), tol_rho);  // negative control: ρ = 0 would fail
  // A finer level still sees the same distribution, with more noise: one level-3 texel.
  const auto l3 = lean_parameters(map.texel(map.levels() - 4, 2, 5), base_alpha);
  EXPECT_NEAR(l3.rho, erho, 4 * (1 - erho * erho) / std::sqrt(M / 64));
}

}  // namespace
}  // namespace glintlab

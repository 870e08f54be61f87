// Tests of the GGX NDF→disk map T = L∘M̃ (Kemppinen et al. 2025 Sec. 3.2.1, Eq. 3, 6, 7).
// Round trips, true Jacobian vs finite differences, containment, float stability, and the paper's
// Jacobian (Eq. 3, Eq. 6 as printed) measured against the true one.
#include "core/maps/ggx_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/maps/map_checks.h"
#include "verify/stats/sphere_cubature.h"

namespace glintlab {
namespace {

using namespace maptest;

// Angular scale over which M̃ is near linear at ω: the relative change of Mᵀω is at most
// δ/(α_lo ‖Mᵀω‖); Lambert is smooth on the whole hemisphere.
double ggx_scale(const GGX<double>& g, V3 w) {
  return std::min(1.0, std::min(g.alpha_x, g.alpha_y) * std::sqrt(ggx_stretch_norm2(g, w)));
}

MapFns ggx_fns(const GGX<double>& g) {
  return {[g](V3 w) { return map_to_square(g, w); }, [g](V2 p) { return map_from_square(g, p); },
          [g](V3 w) { return map_jacobian_true(g, w); }, [g](V3 w) { return ggx_scale(g, w); }};
}

// Mutants, each must be rejected by the check it targets.
// (a) inverse with αx and αy swapped; (b) the printed Eq. 6 power, ⅛|M|/‖Mᵀω‖⁴;
// (c) the paper's Eq. 3 factor D/|U_Ω|; (d) the unscaled equal-area Lambert √(2/(1+z))(x, y).
MapFns ggx_swapped_inverse(const GGX<double>& g) {
  MapFns m = ggx_fns(g);
  m.from = [g](V2 p) { return map_from_square(GGX<double>{g.alpha_y, g.alpha_x}, p); };
  return m;
}
MapFns ggx_eq6_jacobian(const GGX<double>& g) {
  MapFns m = ggx_fns(g);
  m.jacobian = [g](V3 w) { return 0.125 * ggx_stretch_jacobian_eq6(g, w); };
  return m;
}
MapFns ggx_paper_jacobian(const GGX<double>& g) {
  MapFns m = ggx_fns(g);
  m.jacobian = [g](V3 w) { return map_jacobian_paper(g, w); };
  return m;
}
MapFns ggx_unscaled_lambert(const GGX<double>& g) {
  MapFns m = ggx_fns(g);
  m.to = [g](V3 w) {
    const V3 u = ggx_stretch(g, w);
    const double s = std::sqrt(2 / (1 + u.z));
    return disk_to_square(V2{s * u.x, s * u.y});
  };
  return m;
}

bool anisotropic(const Alpha& a) { return a.x != a.y; }

TEST(GgxMap, RoundTripSquareToDirectionToSquare) {
  for (const Alpha& a : kAlphas) {
    const GGX<double> g{a.x, a.y};
    EXPECT_LT(roundtrip_square_error(ggx_fns(g), disk_points()), 1e-14) << a.x << " " << a.y;
    if (anisotropic(a)) {
      EXPECT_GT(roundtrip_square_error(ggx_swapped_inverse(g), disk_points()), 1e-3);
    }
  }
}

TEST(GgxMap, RoundTripDirectionToSquareToDirection) {
  // M̃⁻¹ amplifies a rounding of u by up to max(1, 1/α_lo, hi/lo): at grazing ω, ωz ∝ u_z/α.
  for (const Alpha& a : kAlphas) {
    const GGX<double> g{a.x, a.y};
    const double lo = std::min(a.x, a.y), hi = std::max(a.x, a.y);
    const double tol = 1e-14 * std::max({1.0, 1 / lo, hi / lo});
    EXPECT_LT(roundtrip_direction_error(ggx_fns(g), directions()), tol) << a.x << " " << a.y;
    if (anisotropic(a)) {
      EXPECT_GT(roundtrip_direction_error(ggx_swapped_inverse(g), directions()), 1e-3);
    }
  }
}

TEST(GgxMap, TrueJacobianMatchesFiniteDifferences) {
  double worst = 0;
  for (const Alpha& a : kAlphas) {
    const GGX<double> g{a.x, a.y};
    const double fd = jacobian_fd_rel_error(ggx_fns(g), directions());
    worst = std::max(worst, fd);
    EXPECT_LT(fd, 1e-6) << a.x << " " << a.y;
    // The Eq. 3 factor is not the Jacobian of this map anywhere near +z (factor 32/π²); the printed
    // Eq. 6 differs from the true one by 1/‖Mᵀω‖, which is 1 everywhere only for α = 1.
    EXPECT_GT(jacobian_fd_rel_error(ggx_paper_jacobian(g), directions()), 1.0);
    if (a.x != 1 || a.y != 1) {
      EXPECT_GT(jacobian_fd_rel_error(ggx_eq6_jacobian(g), directions()), 0.1);
    }
  }
  std::printf("GGX map: max |log(J_fd/J_true)| = %.3g\n", worst);
}

TEST(GgxMap, StaysInsideInscribedDisk) {
  std::vector<V3> dirs = hemisphere_directions();
  dirs.push_back({1, 0, 0});  // exactly on the horizon
  dirs.push_back({0, -1, 0});
  for (const Alpha& a : kAlphas) {
    const GGX<double> g{a.x, a.y};
    EXPECT_LE(outside_disk_excess(ggx_fns(g), dirs), 1e-15);
    EXPECT_GT(outside_disk_excess(ggx_unscaled_lambert(g), dirs), 0.1);
  }
}

// M = diag(1/αx, 1/αy, 1) is the right stretch: M̃ carries the GGX projected-area density D·cosθ
// to the α = 1 one, u_z/π, i.e. D(ω) ωz = (M̃(ω)_z/π) |J_M̃(ω)|; and Eq. 6 as printed is π D.
// The same identity with M = diag(αx, αy, 1) fails.
TEST(GgxMap, StretchTakesGgxToUniformConfiguration) {
  for (const Alpha& a : kAlphas) {
    const GGX<double> g{a.x, a.y};
    const GGX<double> wrong{1 / a.x, 1 / a.y};
    double err = 0, err_wrong = 0, err_eq6 = 0;
    for (V3 w : directions()) {
      const double lhs = g.D(w) * w.z;
      err = std::max(err, std::abs(ggx_stretch(g, w).z / std::numbers::pi *
                                       ggx_stretch_jacobian_true(g, w) / lhs -
                                   1));
      err_wrong = std::max(err_wrong, std::abs(ggx_stretch(wrong, w).z / std::numbers::pi *
                                                   ggx_stretch_jacobian_true(wrong, w) / lhs -
                                               1));
      err_eq6 = std::max(
          err_eq6, std::abs(ggx_stretch_jacobian_eq6(g, w) / (std::numbers::pi * g.D(w)) - 1));
    }
    EXPECT_LT(err, 1e-12);
    EXPECT_LT(err_eq6, 1e-12);
    if (a.x != 1 || a.y != 1) {
      EXPECT_GT(err_wrong, 0.1);
    }
  }
}

// ∫_H |J_T| dω = |U_Ω| = π/4 for the true Jacobian (T is a bijection onto the disk); the Eq. 3
// factor integrates to D_H/|U_Ω| instead. Prints the ratio paper/true = 32/(π² ‖Mᵀω‖).
TEST(GgxMap, JacobianPaperVersusTrue) {
  for (const Alpha& a : {Alpha{0.05, 0.05}, Alpha{0.3, 0.3}, Alpha{1, 1}, Alpha{0.1, 0.5}}) {
    const GGX<double> g{a.x, a.y};
    verify::SphereCubatureOptions o;
    o.theta_max = std::numbers::pi / 2;
    o.theta_breaks = verify::lobe_theta_breaks(std::min(a.x, a.y), 0, o.theta_max);
    if (a.x != a.y) o.phi_breaks = verify::anisotropy_phi_breaks(a.x, a.y);
    o.rel_tol = 1e-10;
    const double it =
        verify::integrate_sphere([&](const V3& w) { return map_jacobian_true(g, w); }, o).value;
    const double ip =
        verify::integrate_sphere([&](const V3& w) { return map_jacobian_paper(g, w); }, o).value;
    EXPECT_NEAR(it, std::numbers::pi / 4, 1e-8);
    std::printf("GGX a=(%g,%g): int J_true = %.10f (pi/4 = %.10f), int J_paper = %.6f\n", a.x, a.y,
                it, std::numbers::pi / 4, ip);
    for (double deg : {0.0, 30.0, 60.0, 85.0, 89.9}) {
      const V3 w = direction(deg * std::numbers::pi / 180, 0.4);
      const double ratio = map_jacobian_paper(g, w) / map_jacobian_true(g, w);
      const double expect =
          32 / (std::numbers::pi * std::numbers::pi * std::sqrt(ggx_stretch_norm2(g, w)));
      EXPECT_NEAR(ratio / expect, 1, 1e-12);
      std::printf("  theta=%5.1f  J_paper=%.6g  J_true=%.6g  paper/true=%.6g\n", deg,
                  map_jacobian_paper(g, w), map_jacobian_true(g, w), ratio);
    }
  }
}

TEST(GgxMap, FloatStable) { check_float_stable<GGX<float>>(true); }

}  // namespace
}  // namespace glintlab

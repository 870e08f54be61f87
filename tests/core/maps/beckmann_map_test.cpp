// Tests of the Beckmann NDF→disk map (Kemppinen et al. 2025 Sec. 3.2.2, Eq. 3).
// Round trips, true Jacobian vs finite differences, containment, float stability, and the paper's
// Jacobian (Eq. 3) measured against the true one.
#include "core/maps/beckmann_map.h"

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

// t = |(ωx/αx, ωy/αy)|²/ωz², the squared stretched slope.
double slope_t(const Beckmann<double>& b, V3 w) {
  return (std::pow(w.x / b.alpha_x, 2) + std::pow(w.y / b.alpha_y, 2)) / (w.z * w.z);
}

// Angular scale over which T is near linear at ω: the slope tanθ varies on the scale ωz, the
// stretched slope q = s/α by δ/(α_lo ωz²), and B1⁻¹ is near linear in q over min(1, 1/|q|).
double beckmann_scale(const Beckmann<double>& b, V3 w) {
  const double q = std::sqrt(slope_t(b, w));
  return std::min(w.z, w.z * w.z * std::min(b.alpha_x, b.alpha_y) * std::min(1.0, 1 / q));
}

MapFns beckmann_fns(const Beckmann<double>& b) {
  return {[b](V3 w) { return map_to_square(b, w); }, [b](V2 p) { return map_from_square(b, p); },
          [b](V3 w) { return map_jacobian_true(b, w); },
          [b](V3 w) { return beckmann_scale(b, w); }};
}

// Mutants: (a) an inverse that scales both axes by αx; (b) the paper's Eq. 3 factor D/|U_Ω|;
// (c) |U_Ω|·D, i.e. the true Jacobian without its cosθ; (d) a map left in the unit disk,
// without the (q + 1)/2 of the unit-square convention.
MapFns beckmann_one_alpha_inverse(const Beckmann<double>& b) {
  MapFns m = beckmann_fns(b);
  m.from = [b](V2 p) { return map_from_square(Beckmann<double>{b.alpha_x, b.alpha_x}, p); };
  return m;
}
MapFns beckmann_paper_jacobian(const Beckmann<double>& b) {
  MapFns m = beckmann_fns(b);
  m.jacobian = [b](V3 w) { return map_jacobian_paper(b, w); };
  return m;
}
MapFns beckmann_no_cos_jacobian(const Beckmann<double>& b) {
  MapFns m = beckmann_fns(b);
  m.jacobian = [b](V3 w) { return std::numbers::pi / 4 * b.D(w); };
  return m;
}
MapFns beckmann_disk_not_square(const Beckmann<double>& b) {
  MapFns m = beckmann_fns(b);
  m.to = [b](V3 w) { return square_to_disk(map_to_square(b, w)); };
  return m;
}

// Directions where the map is well conditioned in double: t ≤ 10, i.e. e^{−t} ≥ 4.5e-5 (beyond,
// 1 − r² = e^{−t} keeps only ε·e^{t} relative precision, an inherent property of T).
std::vector<V3> conditioned(const Beckmann<double>& b) {
  std::vector<V3> d;
  for (V3 w : directions())
    if (slope_t(b, w) <= 10) d.push_back(w);
  return d;
}

TEST(BeckmannMap, RoundTripSquareToDirectionToSquare) {
  for (const Alpha& a : kAlphas) {
    const Beckmann<double> b{a.x, a.y};
    EXPECT_LT(roundtrip_square_error(beckmann_fns(b), disk_points()), 1e-14) << a.x << " " << a.y;
    if (a.x != a.y) {
      EXPECT_GT(roundtrip_square_error(beckmann_one_alpha_inverse(b), disk_points()), 1e-3);
    }
  }
}

TEST(BeckmannMap, RoundTripDirectionToSquareToDirection) {
  for (const Alpha& a : kAlphas) {
    const Beckmann<double> b{a.x, a.y};
    const auto dirs = conditioned(b);
    ASSERT_GE(dirs.size(), 12u);
    EXPECT_LT(roundtrip_direction_error(beckmann_fns(b), dirs), 1e-9) << a.x << " " << a.y;
    if (a.x != a.y) {
      EXPECT_GT(roundtrip_direction_error(beckmann_one_alpha_inverse(b), dirs), 1e-4);
    }
  }
}

TEST(BeckmannMap, TrueJacobianMatchesFiniteDifferences) {
  double worst = 0;
  for (const Alpha& a : kAlphas) {
    const Beckmann<double> b{a.x, a.y};
    const auto dirs = conditioned(b);
    const double fd = jacobian_fd_rel_error(beckmann_fns(b), dirs);
    worst = std::max(worst, fd);
    EXPECT_LT(fd, 1e-6) << a.x << " " << a.y;
    // The Eq. 3 factor is off by 16/(π² ωz) ≥ 1.62 everywhere.
    EXPECT_GT(jacobian_fd_rel_error(beckmann_paper_jacobian(b), dirs), 0.4);
    // Dropping the cosθ is visible wherever the tested directions leave the pole.
    double max_log_sec = 0;
    for (V3 w : dirs) max_log_sec = std::max(max_log_sec, -std::log(w.z));
    if (max_log_sec > 1e-3) {
      EXPECT_GT(jacobian_fd_rel_error(beckmann_no_cos_jacobian(b), dirs), 0.5 * max_log_sec);
    }
  }
  std::printf("Beckmann map: max |log(J_fd/J_true)| = %.3g\n", worst);
}

TEST(BeckmannMap, StaysInsideInscribedDisk) {
  std::vector<V3> dirs = hemisphere_directions();
  dirs.push_back({1, 0, 0});
  dirs.push_back({0, -1, 0});
  for (const Alpha& a : kAlphas) {
    const Beckmann<double> b{a.x, a.y};
    EXPECT_LE(outside_disk_excess(beckmann_fns(b), dirs), 1e-15);
    EXPECT_GT(outside_disk_excess(beckmann_disk_not_square(b), dirs), 0.1);
  }
}

// The fused map equals the composition of the paper's stages B1⁻¹ ∘ B2⁻¹ and B2 ∘ B1, and its
// Jacobian the product of theirs.
TEST(BeckmannMap, FusedMapEqualsStages) {
  for (const Alpha& a : kAlphas) {
    const Beckmann<double> b{a.x, a.y};
    for (V3 w : directions()) {
      const V2 staged = disk_to_square(beckmann_b1_inverse(b, beckmann_b2_inverse(w)));
      EXPECT_LT(dist(map_to_square(b, w), staged), 1e-15);
      // The true Jacobian is the product of the stage Jacobians (¼ for the square).
      if (slope_t(b, w) > 50) continue;
      const double j = 0.25 * beckmann_b1_inverse_jacobian(b, beckmann_b2_inverse(w)) *
                       beckmann_b2_inverse_jacobian(w);
      EXPECT_NEAR(map_jacobian_true(b, w) / j, 1, 1e-14);
    }
    for (V2 p : disk_points()) {
      const V2 q = square_to_disk(p);
      if (dot(q, q) >= 1 - 1e-6) continue;  // B1 is infinite at the rim
      EXPECT_LT(dist(map_from_square(b, p), beckmann_b2(beckmann_b1(b, q))), 1e-14);
    }
  }
}

// The true Jacobian is |U_Ω|·D(ω)·ωz: T pushes the projected-area density D·cosθ to the uniform
// disk. ∫ J_true dω = π/4; the Eq. 3 factor integrates to D_H/|U_Ω|. Prints paper/true =
// 16/(π² ωz).
TEST(BeckmannMap, JacobianPaperVersusTrue) {
  for (const Alpha& a : kAlphas) {
    const Beckmann<double> b{a.x, a.y};
    for (V3 w : directions()) {
      const double d = b.D(w);
      if (d < 1e-300) continue;
      EXPECT_NEAR(map_jacobian_true(b, w) / (std::numbers::pi / 4 * d * w.z), 1, 1e-12);
    }
  }
  for (const Alpha& a : {Alpha{0.05, 0.05}, Alpha{0.3, 0.3}, Alpha{1, 1}, Alpha{0.1, 0.5}}) {
    const Beckmann<double> b{a.x, a.y};
    verify::SphereCubatureOptions o;
    o.theta_max = std::numbers::pi / 2;
    o.theta_breaks = verify::lobe_theta_breaks(std::min(a.x, a.y), 0, o.theta_max);
    if (a.x != a.y) o.phi_breaks = verify::anisotropy_phi_breaks(a.x, a.y);
    o.rel_tol = 1e-10;
    const double it =
        verify::integrate_sphere([&](const V3& w) { return map_jacobian_true(b, w); }, o).value;
    const double ip =
        verify::integrate_sphere([&](const V3& w) { return map_jacobian_paper(b, w); }, o).value;
    EXPECT_NEAR(it, std::numbers::pi / 4, 1e-8);
    std::printf("Beckmann a=(%g,%g): int J_true = %.10f (pi/4 = %.10f), int J_paper = %.6f\n", a.x,
                a.y, it, std::numbers::pi / 4, ip);
    for (double deg : {0.0, 30.0, 60.0, 85.0}) {
      const V3 w = direction(deg * std::numbers::pi / 180, 0.4);
      const double ratio = map_jacobian_paper(b, w) / map_jacobian_true(b, w);
      if (!std::isfinite(ratio)) continue;
      EXPECT_NEAR(ratio * std::numbers::pi * std::numbers::pi * w.z / 16, 1, 1e-12);
      std::printf("  theta=%5.1f  J_paper=%.6g  J_true=%.6g  paper/true=%.6g\n", deg,
                  map_jacobian_paper(b, w), map_jacobian_true(b, w), ratio);
    }
  }
}

TEST(BeckmannMap, FloatStable) { check_float_stable<Beckmann<float>>(false); }

}  // namespace
}  // namespace glintlab

// Tests of the total microfacet area D_H (Kneiphof & Klein 2024 Appendix B, Eq. 29–31).
// Eq. 29, Eq. 30 and our anisotropic extension against adaptive cubature of ∫ D dω; Eq. 31's error.
#include "core/ndf/total_area.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "verify/stats/sphere_cubature.h"

namespace glintlab {
namespace {

using V = Vec3<double>;

// D_H − 1 = ∫_H D (1 − cosθ) dω, since ∫_H D cosθ dω = 1: the excess is integrated directly so a
// relative tolerance on it stays meaningful at α = 1e-3, where D_H − 1 ≈ 1e-5. 1 − cosθ is
// written as (wx² + wy²)/(1 + wz), without cancellation.
template <class Ndf>
verify::Integral cubature_excess(const Ndf& ndf, double ax, double ay) {
  verify::SphereCubatureOptions o;
  o.theta_max = std::numbers::pi / 2;
  o.theta_breaks = verify::lobe_theta_breaks(std::min(ax, ay), 0, o.theta_max);
  const auto more = verify::lobe_theta_breaks(std::max(ax, ay), 0, o.theta_max);
  o.theta_breaks.insert(o.theta_breaks.end(), more.begin(), more.end());
  if (ax != ay) o.phi_breaks = verify::anisotropy_phi_breaks(ax, ay);
  o.rel_tol = 1e-10;
  return verify::integrate_sphere(
      [&](const V& w) { return ndf.D(w) * (w.x * w.x + w.y * w.y) / (1 + w.z); }, o);
}

TEST(TotalArea, GaussLegendreTableIsExactToDegree63) {
  for (int k = 0; k <= 63; ++k) {
    double s = 0;
    for (int i = 0; i < kGaussLegendre32Half; ++i) {
      const double x = gauss_legendre32_node(i), w = gauss_legendre32_weight(i);
      s += w * (std::pow(x, k) + std::pow(-x, k));
    }
    const double exact = k % 2 ? 0.0 : 2.0 / (k + 1);
    EXPECT_NEAR(s, exact, 4e-16) << "degree " << k;
  }
}

const std::vector<double> kIsoAlphas = {1e-3, 3e-3,  0.01, 0.05,  0.1, 0.3, 0.5,
                                        0.9,  0.999, 1,    1.001, 1.5, 2};

// Eq. 29 (with its continuation to α ≥ 1) and Eq. 30 against cubature, on the excess D_H − 1.
TEST(TotalArea, IsotropicClosedFormsMatchCubature) {
  double worst_ggx = 0, worst_beck = 0;
  for (double a : kIsoAlphas) {
    const auto cg = cubature_excess(GGX<double>{a, a}, a, a);
    const auto cb = cubature_excess(Beckmann<double>{a, a}, a, a);
    const double eg = std::abs((total_area_ggx_eq29(a) - 1) / cg.value - 1);
    const double eb = std::abs((total_area_beckmann_eq30(a) - 1) / cb.value - 1);
    worst_ggx = std::max(worst_ggx, eg);
    worst_beck = std::max(worst_beck, eb);
    EXPECT_LT(eg, 1e-8) << "GGX alpha " << a;
    EXPECT_LT(eb, 1e-8) << "Beckmann alpha " << a;
    // The isotropic case of the anisotropic quadrature is the closed form.
    EXPECT_NEAR(total_area(GGX<double>{a, a}) / total_area_ggx_eq29(a), 1, 2e-15);
    EXPECT_NEAR(total_area(Beckmann<double>{a, a}) / total_area_beckmann_eq30(a), 1, 2e-15);
  }
  std::printf("Eq. 29 vs cubature: max rel. error of D_H - 1 = %.3g; Eq. 30: %.3g\n", worst_ggx,
              worst_beck);
}

// A mutant of Eq. 29 that drops the α² factor (a plausible transcription slip) is rejected by the
// same comparison.
TEST(TotalArea, CubatureRejectsMutantEq29) {
  double worst = 0;
  for (double a : {0.1, 0.5, 1.5}) {
    const double mutant = total_area_ggx_eq29(a) - 1;
    const double no_a2 = mutant / (a * a);
    worst = std::max(worst, std::abs(no_a2 / cubature_excess(GGX<double>{a, a}, a, a).value - 1));
  }
  EXPECT_GT(worst, 1e-2);
}

// Eq. 29 around α = 1 (series for |1 − α²| < 1e-4, closed forms on either side) against a long
// double reference 1 + a·atanh(√x)/√x (x = 1 − a > 0) or 1 + a·atan(√−x)/√−x (x < 0): continuous,
// no 0/0, a few ulp in double and float on both sides of the switch.
long double ggx_area_reference(long double a) {
  const long double x = 1 - a;
  if (x == 0) return 2;
  const long double r = std::sqrt(std::abs(x));
  return 1 + a * (x > 0 ? std::atanh(r) : std::atan(r)) / r;
}

TEST(TotalArea, Eq29StableAroundAlphaOne) {
  EXPECT_EQ(total_area_ggx_eq29(1.0), 2.0);
  EXPECT_EQ(total_area_ggx_eq29(1.0f), 2.0f);
  double worst_d = 0, worst_f = 0;
  for (double d : {1e-15, 1e-12, 1e-9, 1e-6, 3e-5, 9.9e-5, 9.99999e-5, 1.00001e-4, 1.01e-4, 1e-3,
                   1e-2, 0.1, 0.5}) {
    for (double s : {-1.0, 1.0}) {
      const double a = 1 + s * d;  // a = α²
      worst_d =
          std::max(worst_d, double(std::abs(total_area_ggx_iso_a2(a) / ggx_area_reference(a) - 1)));
      const float af = float(a);
      worst_f = std::max(worst_f,
                         double(std::abs(total_area_ggx_iso_a2(af) / ggx_area_reference(af) - 1)));
      const double alpha = std::sqrt(a);
      EXPECT_NEAR(double(total_area_ggx_eq29(alpha) / ggx_area_reference(alpha * alpha)), 1, 1e-15);
    }
  }
  EXPECT_LT(worst_d, 4 * 2.2e-16);
  EXPECT_LT(worst_f, 4 * 1.2e-7);
}

// The anisotropic extension against cubature, anisotropy to 1:1000 both ways.
TEST(TotalArea, AnisotropicMatchesCubature) {
  struct A {
    double x, y;
  };
  double worst = 0;
  for (A a : {A{1e-3, 1}, A{1, 1e-3}, A{1e-3, 1e-2}, A{0.1, 0.5}, A{2, 2e-3}, A{0.3, 1.7}}) {
    const auto cg = cubature_excess(GGX<double>{a.x, a.y}, a.x, a.y);
    const auto cb = cubature_excess(Beckmann<double>{a.x, a.y}, a.x, a.y);
    const double eg = std::abs((total_area(GGX<double>{a.x, a.y}) - 1) / cg.value - 1);
    const double eb = std::abs((total_area(Beckmann<double>{a.x, a.y}) - 1) / cb.value - 1);
    worst = std::max({worst, eg, eb});
    EXPECT_LT(eg, 1e-8) << a.x << " " << a.y << " (cubature error estimate " << cg.error << ")";
    EXPECT_LT(eb, 1e-8) << a.x << " " << a.y << " (cubature error estimate " << cb.error << ")";
    // Symmetric in the two axes.
    EXPECT_NEAR(total_area(GGX<double>{a.x, a.y}), total_area(GGX<double>{a.y, a.x}), 1e-15);
  }
  std::printf("anisotropic D_H vs cubature: max rel. error of D_H - 1 = %.3g\n", worst);
}

// Eq. 31 (the quadratic fit) against Eq. 30 over α ∈ (0, 1], measured. As printed, in α, it is
// far from Eq. 30 (≈ 0.098 absolute near α = 0.45: Eq. 30 is 1 + α²/2 + O(α⁴) at small α, the fit
// linear); read as a polynomial in α², 1 + 0.466 α² − 0.091 α⁴, it matches Eq. 30 to ~4e-3, so the
// fit was presumably made against α² (a roughness r with α = √r). Both readings are asserted.
TEST(TotalArea, Eq31FitErrorAgainstEq30) {
  struct Err {
    double abs = 0, at_abs = 0, rel = 0, at_rel = 0;
  } printed, squared;
  const int n = 100000;
  for (int i = 1; i <= n; ++i) {
    const double a = double(i) / n;
    const double exact = total_area_beckmann_eq30(a);
    auto update = [&](Err& e, double fit) {
      const double d = std::abs(fit - exact);
      if (d > e.abs) e.abs = d, e.at_abs = a;
      if (d / exact > e.rel) e.rel = d / exact, e.at_rel = a;
    };
    update(printed, total_area_beckmann_eq31(a));
    update(squared, total_area_beckmann_eq31(a * a));
  }
  std::printf(
      "Eq. 31 vs Eq. 30 on (0, 1], as printed: max abs error %.4g at alpha = %.4f, max rel "
      "error %.4g at alpha = %.4f\n",
      printed.abs, printed.at_abs, printed.rel, printed.at_rel);
  std::printf(
      "Eq. 31 in alpha^2 vs Eq. 30 on (0, 1]: max abs error %.4g at alpha = %.4f, max rel "
      "error %.4g at alpha = %.4f\n",
      squared.abs, squared.at_abs, squared.rel, squared.at_rel);
  EXPECT_NEAR(printed.abs, 0.0981, 5e-4);
  EXPECT_LT(squared.abs, 5e-3);
}

// Eq. 30 without overflow: finite for α down to 1e-4 in double and float, → 1 + α²/2.
TEST(TotalArea, Eq30SmallAlphaNoOverflow) {
  for (double a : {1e-4, 1e-3, 0.01, 0.03, 0.05}) {
    const double d = total_area_beckmann_eq30(a);
    ASSERT_TRUE(std::isfinite(d));
    // (√π/2)α erfcx(1/α) = (α²/2)(1 − α²/2 + 3α⁴/4 − 15α⁶/8 + …), asymptotic.
    // d − 1 carries the absolute rounding of d (~ε), hence the 4ε/α² term.
    EXPECT_NEAR((d - 1) / (a * a / 2 * (1 - a * a / 2 + 0.75 * std::pow(a, 4))), 1,
                2 * std::pow(a, 6) + 9e-16 / (a * a));
    const float f = total_area_beckmann_eq30(float(a));
    ASSERT_TRUE(std::isfinite(f));
    EXPECT_NEAR(f, d, 2e-7);
  }
}

// erfcx against exp(x²)·erfc(x) in long double (range to x ≈ 106), in double ulps.
TEST(TotalArea, ErfcxAccurate) {
  double worst = 0;
  for (int i = 0; i <= 4000; ++i) {
    const double x = i < 2000 ? i * 0.005 : 10 * std::pow(10.0, (i - 2000) / 2000.0);  // 0..10..100
    const long double xl = x;
    const long double ref = std::exp(xl * xl) * boost::math::erfc(xl);
    const double got = erfcx(x);
    worst = std::max(worst, double(std::abs((got - ref) / ref)) / 2.220446049250313e-16);
  }
  std::printf("erfcx(double): max error %.2f ulp\n", worst);
  EXPECT_LT(worst, 8);
}

}  // namespace
}  // namespace glintlab

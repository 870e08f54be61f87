// Tests: float instantiation of every sampler and pdf against double, within a conditioning budget.
// Inputs are identical (α, wi and u rounded to float first).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/core/samplers/sampler_checks.h"

namespace glintlab {
namespace {

using namespace sampler_checks;

constexpr double kEpsF = 5.9604644775390625e-8;  // 2^-24, the unit roundoff of float

// Budgets. A float kernel cannot beat the conditioning of its own problem, so each error is
// compared with eps_f + Δ, where Δ is what the double kernel does under a perturbation of its
// input at float resolution:
//  - sample: Δ_u = max |wo_d(u') − wo_d(u)| over u' = u moved by 2 float ulps in either
//    coordinate; error = |wo_f − wo_d|;
//  - pdf: Δ_p = max |p_d(w') − p_d(w)| / p_d(w) over w' = w moved by 2 float ulps (1.2e-7 rad)
//    along 4 tangent directions (1 where the support ends nearby); error = |p_f(w) − p_d(w)| /
//    p_d(w) at the float-representable w = (float)wo_d, for samples that are not rejected.
// Measured maxima of error / (eps_f + Δ) over the grid (α 1e-3..2, 1:1000, θ up to 180°, 10×10
// u): sample: walter 8.6, heitz 12.2, beckmann_vndf 8.1, caps 14.1, bounded 14.7; pdf: 5.8–10.7.
// Budget C = 32 (≈ 2.2× the worst). Excluded: u coordinates exactly 0 or 1 − 2^-24 (each type
// clamps its quantiles at its own resolution there, and at u2 → 1 the cap map meets its
// singular point ô = −î, where 1 ulp of ô turns m̂ around); the finite-weight test covers them.
constexpr double kBudgetC = 32;

struct FloatReport {
  double sample_c = 0, pdf_c = 0;
  std::string sample_worst, pdf_worst;
};

double sample_sensitivity(Kind k, const Config& c, Vec2<float> uf, const V3& wo) {
  double m = 0;
  for (int axis = 0; axis < 2; ++axis)
    for (float toward : {0.0f, 1.0f}) {
      Vec2<float> v = uf;
      float& x = axis ? v.y : v.x;
      x = std::nextafter(std::nextafter(x, toward), toward);
      if (!(x < 1.0f)) continue;
      m = std::max(m, length(draw<double>(k, c.ax, c.ay, c.wi, V2{v.x, v.y}).wo - wo));
    }
  return m;
}

template <class PdfD>
double pdf_sensitivity(PdfD&& pdf_d, const V3& w, double p0) {
  const V3 t1 = normalize(cross(w, std::abs(w.z) < 0.9 ? V3{0, 0, 1} : V3{1, 0, 0}));
  const V3 t2 = cross(w, t1);
  double m = 0;
  for (const V3& t : {t1, t2, -t1, -t2}) {
    const double p = pdf_d(normalize(w + (2 * kEpsF) * t));
    m = std::max(m, p0 == 0 ? (p == 0 ? 0.0 : 1.0) : std::abs(p - p0) / p0);
  }
  return m;
}

// Worst error / (eps_f + Δ) of a float sampler and pdf against the double ones.
template <class DrawF, class PdfF, class PdfD>
FloatReport compare(Kind k, DrawF&& draw_f, PdfF&& pdf_f, PdfD&& pdf_d) {
  FloatReport rep;
  for (Config c : grid(handles_backfacing(k))) {
    c.ax = through_float(c.ax);
    c.ay = through_float(c.ay);
    c.wi = through_float(c.wi);
    const auto pd_at = [&](const V3& w) { return pdf_d(c, w); };
    for (const Vec2<float>& uf : u_grid<float>(8)) {
      if (uf.x == 0 || uf.y == 0 || uf.x == 1 - kEpsF || uf.y == 1 - kEpsF) continue;
      const V2 ud{uf.x, uf.y};
      const MicrofacetSample<double> sd = draw<double>(k, c.ax, c.ay, c.wi, ud);
      const MicrofacetSample<float> sf = draw_f(c, uf);
      const double err = length(cast<double>(sf.wo) - sd.wo);
      const double rs = err / (kEpsF + sample_sensitivity(k, c, uf, sd.wo));
      if (!(rs <= rep.sample_c)) {
        rep.sample_c = std::isnan(rs) ? std::numeric_limits<double>::infinity() : rs;
        rep.sample_worst =
            describe(c) + " u=(" + std::to_string(ud.x) + "," + std::to_string(ud.y) + ")";
      }
      if (sd.rejected) continue;
      const V3 w = through_float(sd.wo);
      const Vec3<float> wf = cast<float>(w);  // exact: w is float-representable
      const double pf = pdf_f(c, wf), p0 = pd_at(w);
      const double rel = (pf == 0 && p0 == 0) ? 0 : std::abs(pf - p0) / std::max(p0, 1e-300);
      const double rp = rel / (kEpsF + pdf_sensitivity(pd_at, w, p0));
      if (!(rp <= rep.pdf_c)) {
        rep.pdf_c = std::isnan(rp) ? std::numeric_limits<double>::infinity() : rp;
        rep.pdf_worst = describe(c) + " u=(" + std::to_string(ud.x) + "," + std::to_string(ud.y) +
                        ") pf=" + std::to_string(pf) + " pd=" + std::to_string(p0);
      }
    }
  }
  return rep;
}

FloatReport compare_kind(Kind k) {
  return compare(
      k,
      [&](const Config& c, Vec2<float> u) {
        return draw<float>(k, float(c.ax), float(c.ay), cast<float>(c.wi), u);
      },
      [&](const Config& c, Vec3<float> wo) {
        return double(density<float>(k, float(c.ax), float(c.ay), cast<float>(c.wi), wo));
      },
      [&](const Config& c, const V3& wo) { return density<double>(k, c.ax, c.ay, c.wi, wo); });
}

TEST(SamplerFloatVsDouble, WithinConditioningBudget) {
  for (Kind k : kAllKinds) {
    const FloatReport r = compare_kind(k);
    std::printf("%-16s sample C=%.2f  pdf C=%.2f\n", name(k), r.sample_c, r.pdf_c);
    EXPECT_LE(r.sample_c, kBudgetC) << name(k) << " sample, worst at " << r.sample_worst;
    EXPECT_LE(r.pdf_c, kBudgetC) << name(k) << " pdf, worst at " << r.pdf_worst;
  }
}

// Mutant pdf: Eq. 7 evaluated as printed (i_z + t cancels for a back-facing wi) in float, against
// the double stable form — rejected by the same budget.
TEST(SamplerFloatVsDouble, MutantEq7AsPrintedIsRejected) {
  const FloatReport r = compare(
      Kind::kCaps,
      [&](const Config& c, Vec2<float> u) {
        return draw<float>(Kind::kCaps, float(c.ax), float(c.ay), cast<float>(c.wi), u);
      },
      [&](const Config& c, Vec3<float> wo) {
        return double(
            pdf_vndf_backfacing_eq7(GGX<float>{float(c.ax), float(c.ay)}, cast<float>(c.wi), wo));
      },
      [&](const Config& c, const V3& wo) {
        return pdf_spherical_caps(GGX<double>{c.ax, c.ay}, c.wi, wo);
      });
  std::printf("eq7-as-printed float pdf: C=%.3g\n", r.pdf_c);
  EXPECT_GT(r.pdf_c, kBudgetC) << "worst at " << r.pdf_worst;
}

// Mutant sampler: the spherical cap with Listing 1's arithmetic taken literally
// (ô_z = (1 − u2)(1 + î_z) − î_z, sinθ = √(1 − ô_z²), m̂ = î + ô), which loses the cap of height
// ~1e-8 of a back-facing wi at tiny α in float — rejected by the same budget.
template <class T>
MicrofacetSample<T> caps_literal(const GGX<T>& g, Vec3<T> wi, Vec2<T> u) {
  const Vec3<T> is = normalize(Vec3<T>{g.alpha_x * wi.x, g.alpha_y * wi.y, wi.z});
  const T phi = T(2 * kPi<T>) * u.x;
  const T z = (T(1) - u.y) * (T(1) + is.z) - is.z;
  const T st = std::sqrt(std::max(T(1) - z * z, T(0)));
  const Vec3<T> ms = is + Vec3<T>{st * std::cos(phi), st * std::sin(phi), z};
  const Vec3<T> m = normalize(Vec3<T>{g.alpha_x * ms.x, g.alpha_y * ms.y, ms.z});
  const Vec3<T> wo = reflect(wi, m);
  return {wo, m, pdf_spherical_caps(g, wi, wo), wo.z <= 0};
}

TEST(SamplerFloatVsDouble, MutantLiteralCapArithmeticIsRejected) {
  const FloatReport r = compare(
      Kind::kCaps,
      [&](const Config& c, Vec2<float> u) {
        return caps_literal(GGX<float>{float(c.ax), float(c.ay)}, cast<float>(c.wi), u);
      },
      [&](const Config& c, Vec3<float> wo) {
        return double(
            pdf_spherical_caps(GGX<float>{float(c.ax), float(c.ay)}, cast<float>(c.wi), wo));
      },
      [&](const Config& c, const V3& wo) {
        return pdf_spherical_caps(GGX<double>{c.ax, c.ay}, c.wi, wo);
      });
  std::printf("literal-cap float sampler: C=%.3g\n", r.sample_c);
  EXPECT_GT(r.sample_c, kBudgetC) << "worst at " << r.sample_worst;
}

}  // namespace
}  // namespace glintlab

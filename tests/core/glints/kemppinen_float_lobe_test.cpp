// Kemppinen et al. 2025 Eq. 4/11 lobes in float: N(·; Σ) of a glint of microroughness 1e-9 (σ ≈
// 1e-15, |Σ| = σ⁴ below float's range) is finite, and the double results are bit-identical to the
// printed formula exp(−½ dᵀΣ⁻¹d)/(2π√|Σ|) the kernel used before.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/glints/kemppinen.h"
#include "core/math/rng.h"
#include "core/models/kemppinen_beckmann.h"

namespace glintlab {
namespace {

// The normal density exactly as kemppinen2025::normal2 computed it before the power-of-two scaling.
double normal2_unscaled(Vec2<double> d, const kemppinen2025::Sym2<double>& s) {
  const double det = s.xx * s.yy - sqr(s.xy);
  const double q = (s.yy * sqr(d.x) - 2.0 * s.xy * d.x * d.y + s.xx * sqr(d.y)) / det;
  return std::exp(-0.5 * q) * (0.15915494309189533577 * (1.0 / std::sqrt(det)));
}

TEST(KemppinenFloatLobe, DoubleIsBitIdenticalToThePrintedFormula) {
  // σ from 1e-16 to 1e2 (both scaling thresholds and neither), anisotropic and correlated.
  for (std::uint64_t i = 0; i < 20000; ++i) {
    const double sx = std::pow(10.0, -16 + 18 * counter_uniform<double>(11, i, 0));
    const double sy = sx * std::pow(10.0, -1 + 2 * counter_uniform<double>(11, i, 1));
    const double rho = 0.9 * (2 * counter_uniform<double>(11, i, 2) - 1);
    const kemppinen2025::Sym2<double> s{sx * sx, rho * sx * sy, sy * sy};
    const double r = std::pow(10.0, -3 + 3 * counter_uniform<double>(11, i, 3));
    const Vec2<double> d{r * sx * (2 * counter_uniform<double>(11, i, 4) - 1),
                         r * sy * (2 * counter_uniform<double>(11, i, 5) - 1)};
    const double a = kemppinen2025::normal2(d, s), b = normal2_unscaled(d, s);
    ASSERT_EQ(std::bit_cast<std::uint64_t>(a), std::bit_cast<std::uint64_t>(b))
        << "sigma " << sx << ", " << sy << " rho " << rho << ": " << a << " vs " << b;
  }
}

TEST(KemppinenFloatLobe, TinyLobesAreFiniteInFloat) {
  const float sigma = 1.12838e-15f;  // α★ = 1e-9 at the floored D (measured in the sweep's NaN)
  const kemppinen2025::Sym2<float> s{sigma * sigma, 0.0f, sigma * sigma};
  EXPECT_EQ(kemppinen2025::normal2(Vec2<float>{0.1f, 0.2f}, s),
            0.0f);  // far outside the lobe: 0, not 0·∞
  // At the lobe's centre: 1/(2π σ²) ≈ 1.25e29, representable in float.
  const float peak = kemppinen2025::normal2(Vec2<float>{0.0f, 0.0f}, s);
  EXPECT_TRUE(std::isfinite(peak));
  EXPECT_NEAR(peak / (1.0f / (2.0f * 3.14159265f * sigma * sigma)), 1.0f, 1e-5f);
  // One σ off-centre in x: exp(−½) of the peak.
  EXPECT_NEAR(kemppinen2025::normal2(Vec2<float>{sigma, 0.0f}, s) / peak, std::exp(-0.5f), 1e-5f);
}

// The sweep's cell (microroughness 1e-9, α = 0.1, footprint 1e-3): the float instantiation gave
// NaN in 45 % of uniform directions at θi = 0 (D★^f's explicit sum, N = 0·∞) and must give none.
TEST(KemppinenFloatLobe, BeckmannFloatHasNoNanAtMicroroughness1e9) {
  std::vector<double> v;
  for (const ParamSpec& p : KemppinenBeckmann::kParams) v.push_back(p.default_value);
  v[0] = v[1] = 0.1;
  v[3] = 1e-9;
  const auto pf = KemppinenBeckmann::params<float>(v);
  int nan = 0, n = 0;
  for (double theta : {0.0, 45.0, 85.0, 89.9}) {
    const double t = theta * 3.14159265358979323846 / 180;
    const Vec3<float> wi{float(std::sin(t) * std::cos(0.7)), float(std::sin(t) * std::sin(0.7)),
                         float(std::cos(t))};
    for (std::uint64_t i = 0; i < 2000; ++i) {
      const double z = 1 - 2 * counter_uniform<double>(7, i, 0);
      const double r = std::sqrt(std::max(0.0, 1 - z * z));
      const double phi = 2 * 3.14159265358979323846 * counter_uniform<double>(7, i, 1);
      ModelQuery<float> q{};
      q.wi = wi;
      q.wo = {float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)};
      q.footprint = {
          {float(counter_uniform<double>(7, i, 2)), float(counter_uniform<double>(7, i, 3))},
          {1e-3f, 0.0f},
          {0.0f, 1e-3f}};
      q.light = {1.0f, 1.0f};
      const auto e = KemppinenBeckmann::eval(pf, q);
      ++n;
      nan += std::isnan(e.value) || std::isnan(e.pdf);
    }
  }
  EXPECT_EQ(nan, 0) << "of " << n;
}

// Algorithm 2's marginal density in float where a point sits on the rim of U_Ω: its D underflows
// to 0 there (σ = 0) while its spatial weight is 0, and 0 · N(0/0) made the whole pdf NaN (found
// by the stability sweep at density 2.14e7, θi 15°, 2 of 400 000 sampled directions). The query
// is one of those directions; the masked density is finite and positive.
TEST(KemppinenFloatLobe, CollapsedRimPointLeavesTheSamplerPdfFinite) {
  using M = KemppinenBeckmann;
  std::vector<double> v;
  for (const auto& s : M::kParams) v.push_back(s.default_value);
  for (std::size_t i = 0; i < M::kParams.size(); ++i)
    if (M::kParams[i].name == "density") v[i] = 2.14e7;
  const auto p = M::params<float>(v);
  const double th = 15 * 3.14159265358979323846 / 180;
  ModelQuery<float> q{};
  q.wi = {float(std::sin(th) * std::cos(0.3)), float(std::sin(th) * std::sin(0.3)),
          float(std::cos(th))};
  q.footprint.uv = {0.456078231f, 0.308296621f};
  q.footprint.duv_dx = {1e-3f, 0.0f};
  q.footprint.duv_dy = {0.0f, 1e-3f};
  q.light = {1.0f, 1.0f};
  q.wo = {0.323492527f, 0.190587431f, 0.926838279f};
  const float pdf = M::pdf(p, q);
  EXPECT_TRUE(std::isfinite(pdf)) << pdf;
  EXPECT_GT(pdf, 0.0f);
}

}  // namespace
}  // namespace glintlab

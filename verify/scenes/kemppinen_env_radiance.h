// Reflected radiance of a glinty plane (Kemppinen et al. 2025, Eq. 1 with D★^f of Eq. 11, G2 and
// F as the models kemppinen_ggx / kemppinen_beckmann use them) under an environment light, by
// BSDF importance sampling: the mixture of core/glints/kemppinen_full_sampling.h (exact and
// printed density), smooth-NDF sampling (ω_h ~ D cosθ), and an independent stratified reference.
//
// L_o(v) = ∫ f(v, l) L(l) cosθ_l dω_l with f = F G2 D★^f / (4 cosθ_v cosθ_l) and l = reflect(v,
// ω_h), dω_l = 4 |v·ω_h| dω_h (Walter et al. 2007 Eq. 14), so in ω_h:
//   L_o(v) = ∫_Ω D★^f(ω_h) G2(v, l, ω_h) F L(l) |v·ω_h| / cosθ_v dω_h,   F = 1 (as the models).
// Every estimator below is a one-sample estimate of this integral; luminance of D★^f (the models'
// value), per channel of L.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/glints/kemppinen_full_sampling.h"
#include "core/lights/environment_map.h"
#include "core/lights/procedural_sky.h"
#include "core/math/rng.h"
#include "core/ndf/microfacet.h"

namespace glintlab::kemppinen2025 {

// The integrand above at ω_h, and D★^f's luminance there (0 where l or ω_h is below the surface).
template <class Ndf>
Vec3<double> env_integrand(const Params<double>& p, const Ndf& ndf,
                           const FootprintQuery<double>& fp, const EnvironmentMap& env,
                           Vec3<double> v, Vec3<double> h) {
  const Vec3<double> zero{0, 0, 0};
  if (!(h.z > 0) || !(v.z > 0)) return zero;
  const double vh = dot(v, h);
  if (!(vh > 0)) return zero;
  const Vec3<double> l = reflect(v, h);
  if (!(l.z > 0)) return zero;
  const double d = luminance(eval(p, ndf, fp, h).d);
  const double g2 = smith_g2_height_correlated(ndf, v, l, h);
  return (d * g2 * vh / v.z) * env.radiance(Vec3<double>{0, 0, 0}, l);
}

struct EnvMixtureEstimate {
  Vec3<double> exact, printed;  // f L cos / p with the exact and with the printed mixture density
  bool from_explicit;
};

// One sample of the mixture (probability q of Algorithm 2), both densities on the same direction.
template <class Ndf>
EnvMixtureEstimate env_estimate_mixture(const Params<double>& p, const Ndf& ndf,
                                        const FootprintQuery<double>& fp, const EnvironmentMap& env,
                                        Vec3<double> v, std::uint64_t key, double q) {
  EnvMixtureEstimate e{{0, 0, 0}, {0, 0, 0}, false};
  const FullSample<double> s = sample_full(p, ndf, fp, key, q);
  e.from_explicit = s.from_explicit;
  if (!s.ok) return e;
  const Vec3<double> g = env_integrand(p, ndf, fp, env, v, s.h);
  e.exact = (1 / s.pdf_h) * g;
  if (s.pdf_printed_h > 0) e.printed = (1 / s.pdf_printed_h) * g;
  return e;
}

// One sample of the smooth NDF's sampler, ω_h ~ D cosθ (Walter et al. 2007 Eq. 28–29, 35–36).
template <class Ndf>
Vec3<double> env_estimate_smooth(const Params<double>& p, const Ndf& ndf,
                                 const FootprintQuery<double>& fp, const EnvironmentMap& env,
                                 Vec3<double> v, Vec2<double> u) {
  const Vec3<double> h = sample_normal_walter(ndf, u);
  const double pdf = ndf.D(h) * h.z;
  if (!(pdf > 0)) return {0, 0, 0};
  return (1 / pdf) * env_integrand(p, ndf, fp, env, v, h);
}

// Equal-area square → hemisphere: Shirley & Chiu's concentric map onto the unit disk, then
// Lambert's azimuthal equal-area projection (z = 1 − r², radius r √(2 − r²)). Each square area A
// maps to solid angle 2π A with strata of bounded aspect ratio, also at the pole.
inline Vec3<double> equal_area_hemisphere(Vec2<double> u) {
  const double a = 2 * u.x - 1, b = 2 * u.y - 1;
  const double quarter = 0.78539816339744830962;
  double r = 0, phi = 0;
  if (a * a > b * b) {
    r = a;
    phi = quarter * (b / a);
  } else if (b != 0) {
    r = b;
    phi = 2 * quarter - quarter * (a / b);
  }
  const double r2 = r * r, s = r * std::sqrt(std::max(0.0, 2 - r2));
  return {s * std::cos(phi), s * std::sin(phi), 1 - r2};
}

// The independent reference: stratified quadrature of the ω_h integral over the hemisphere in
// n × n equal-solid-angle strata (2π/n² sr each, equal_area_hemisphere), two jittered points per
// stratum, so that the estimate is unbiased and its variance is estimated per stratum:
// Var = Σ_s (Ω_s (g₁ − g₂)/2)². Uses no sampler and no map of the glint model.
struct EnvReference {
  Vec3<double> mean{0, 0, 0};
  Vec3<double> variance{0, 0, 0};  // of `mean`, per channel
  double luminance_variance = 0;   // of the luminance of `mean`
  std::uint64_t evaluations = 0;
};

template <class Ndf>
EnvReference env_reference(const Params<double>& p, const Ndf& ndf,
                           const FootprintQuery<double>& fp, const EnvironmentMap& env,
                           Vec3<double> v, int n, std::uint64_t seed) {
  EnvReference r;
  const double omega = 6.28318530717958647692 / (double(n) * double(n));
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const std::uint64_t s = std::uint64_t(a) * std::uint64_t(n) + std::uint64_t(b);
      Vec3<double> g[2];
      for (int k = 0; k < 2; ++k) {
        const Vec2<double> u{(a + counter_uniform<double>(seed, s, 2 * std::uint64_t(k))) / n,
                             (b + counter_uniform<double>(seed, s, 2 * std::uint64_t(k) + 1)) / n};
        g[k] = env_integrand(p, ndf, fp, env, v, equal_area_hemisphere(u));
      }
      const Vec3<double> m = (0.5 * omega) * (g[0] + g[1]);
      const Vec3<double> d = (0.5 * omega) * (g[0] - g[1]);
      r.mean = r.mean + m;
      r.variance = r.variance + Vec3<double>{d.x * d.x, d.y * d.y, d.z * d.z};
      r.luminance_variance += sqr(luminance(d));
    }
  r.evaluations = 2 * std::uint64_t(n) * std::uint64_t(n);
  return r;
}

// The environment of the kemppinen.sampling-unbiased claim and the kemppinen2025-fig7 figure:
// the procedural sky (core/lights/procedural_sky.h) with a soft sun (half angle 0.2 rad, radiance
// 10) 30° from the zenith at azimuth 0, the mirror direction of PlaneView's camera, as a
// 64 × 32 lat-long map (piecewise constant: the reference integrates the map, not the sky).
inline LatLongImage env_sky() {
  SkyParameters sky;
  sky.sun_half_angle = 0.2;
  sky.sun_radiance = {10, 10, 10};
  return make_procedural_sky(sky, 64, 32);
}

// The per-sample estimates of one pixel: n samples of the mixture (both densities on the same
// directions, q = mixture_probability) and n independent samples of D cosθ, all from
// `seed` (sample i: mixture key mix64(seed ^ mix64(i + 1)), smooth uniforms (seed, i, 0..1)).
struct EnvSamples {
  std::vector<Vec3<double>> exact, printed, smooth;
  double q = 0;
  std::uint64_t from_explicit = 0;  // mixture samples drawn by Algorithm 2
};

template <class Ndf>
EnvSamples env_samples(const Params<double>& p, const Ndf& ndf, const FootprintQuery<double>& fp,
                       const EnvironmentMap& env, Vec3<double> v, std::uint64_t n,
                       std::uint64_t seed) {
  EnvSamples out;
  out.q = mixture_probability(p, ndf, fp);
  out.exact.resize(n);
  out.printed.resize(n);
  out.smooth.resize(n);
  for (std::uint64_t i = 0; i < n; ++i) {
    const EnvMixtureEstimate e =
        env_estimate_mixture(p, ndf, fp, env, v, mix64(seed ^ mix64(i + 1)), out.q);
    out.exact[i] = e.exact;
    out.printed[i] = e.printed;
    out.from_explicit += e.from_explicit ? 1 : 0;
    out.smooth[i] = env_estimate_smooth(
        p, ndf, fp, env, v,
        Vec2<double>{counter_uniform<double>(seed, i, 0), counter_uniform<double>(seed, i, 1)});
  }
  return out;
}

// A glinty plane z = 0 under an orthographic camera at polar angle θ_v and azimuth π (so that its
// mirror direction is at azimuth 0, where the procedural sky has its sun): pixel (i, j) looks at
// uv = origin + ((i + ½) d / cos θ_v, (j + ½) d) with footprint J_uv = diag(d / cos θ_v, d).
struct PlaneView {
  double theta_v;       // rad
  Vec2<double> origin;  // uv of the image corner
  double pixel_uv;      // d: a pixel's side in uv across the view direction
  Vec3<double> view() const { return {-std::sin(theta_v), 0, std::cos(theta_v)}; }
  FootprintQuery<double> pixel(int i, int j) const {
    const double dx = pixel_uv / std::cos(theta_v);
    return {{origin.x + (i + 0.5) * dx, origin.y + (j + 0.5) * pixel_uv}, {dx, 0}, {0, pixel_uv}};
  }
};

}  // namespace glintlab::kemppinen2025

// Monte Carlo reference for one shading point under one light: L_o(ωo) = ∫ f(ωo, ωi) L(ωi) cos θi
// dωi, by light sampling, BSDF sampling, or both combined with multiple importance sampling
// (Veach & Guibas 1995, "Optimally combining sampling techniques", Eq. 8 (multi-sample MIS
// estimator, one sample per technique), balance heuristic Eq. 9, power heuristic β = 2 Sec. 4.2).
// Deterministic: sample i uses the counter-based uniforms (seed, i, dims 0–3) only, and the moments
// are accumulated serially in index order, so a value depends only on (seed, sample count).
//
// Light: any type with the interface of core/lights/light_sample.h (sample, pdf, radiance), in
// world space.
// Bsdf: in the local shading frame (z = normal), ωo towards the viewer, ωi towards the light:
//   T f(Vec3<T> wo, Vec3<T> wi) const;                  // BRDF value, 1/sr (cos θi not included)
//   BsdfSample<T> sample(Vec3<T> wo, Vec2<T> u) const;  // {wi, pdf per solid angle, rejected}
//   T pdf(Vec3<T> wo, Vec3<T> wi) const;                // the density sample() draws wi from
// A rejected sample contributes 0 (it is still counted: the estimator divides by every sample).
#pragma once

#include <cmath>
#include <concepts>
#include <cstdint>

#include "core/lights/light_sample.h"
#include "core/math/orthonormal_basis.h"
#include "core/math/rng.h"

namespace glintlab {

template <class T>
struct BsdfSample {
  Vec3<T> wi;  // local frame
  T pdf;       // per unit solid angle
  Mask<T> rejected;
};

template <class B, class T>
concept ReferenceBsdf = requires(const B& b, Vec3<T> w, Vec2<T> u) {
  { b.f(w, w) } -> std::convertible_to<T>;
  { b.sample(w, u) } -> std::convertible_to<BsdfSample<T>>;
  { b.pdf(w, w) } -> std::convertible_to<T>;
};

template <class L, class T>
concept ReferenceLight = requires(const L& l, Vec3<T> p, Vec2<T> u) {
  { l.sample(p, u) } -> std::convertible_to<LightSample<T>>;
  { l.pdf(p, p) } -> std::convertible_to<T>;
  { l.radiance(p, p) } -> std::convertible_to<Vec3<T>>;
};

enum class ReferenceStrategy { kMis, kLightOnly, kBsdfOnly };
enum class MisHeuristic {
  kBalance,  // w_a = p_a / (p_a + p_b) (Veach & Guibas 1995 Eq. 9)
  kPower,    // w_a = p_a² / (p_a² + p_b²) (β = 2, Veach & Guibas 1995 Sec. 4.2)
};

template <class T>
struct ShadingPoint {
  Vec3<T> position;
  OrthonormalBasis<T> frame;  // frame.z: the shading normal
};

// MIS weight of technique a against b; 0 where both densities vanish.
template <class T>
GLINTLAB_FN T mis_weight(T pa, T pb, MisHeuristic h) {
  const T a = h == MisHeuristic::kPower ? pa * pa : pa;
  const T b = h == MisHeuristic::kPower ? pb * pb : pb;
  const T s = a + b;
  return select(s > T(0), a / select(s > T(0), s, T(1)), T(0));
}

// One sample of the estimator (RGB): the light technique with u_light and the BSDF technique with
// u_bsdf, each weighted (Veach & Guibas Eq. 8 with n_light = n_bsdf = 1), or one technique alone.
template <class T, class Light, class Bsdf>
GLINTLAB_FN Vec3<T> reference_sample(const Light& light, const Bsdf& bsdf,
                                     const ShadingPoint<T>& sp, Vec3<T> wo, Vec2<T> u_light,
                                     Vec2<T> u_bsdf, ReferenceStrategy strategy,
                                     MisHeuristic heuristic) {
  Vec3<T> sum{T(0), T(0), T(0)};
  if (strategy != ReferenceStrategy::kBsdfOnly) {  // a per-call constant, not a per-lane value
    const LightSample<T> ls = light.sample(sp.position, u_light);
    const Vec3<T> wi = sp.frame.to_local(ls.wi);
    const T cos_i = max(wi.z, T(0));
    const Mask<T> ok = ls.valid && (ls.pdf > T(0)) && (cos_i > T(0));
    const T w = strategy == ReferenceStrategy::kMis
                    ? mis_weight(ls.pdf, T(bsdf.pdf(wo, wi)), heuristic)
                    : T(1);
    const T scale = select(ok, w * T(bsdf.f(wo, wi)) * cos_i / select(ok, ls.pdf, T(1)), T(0));
    sum = sum + scale * ls.radiance;
  }
  if (strategy != ReferenceStrategy::kLightOnly) {
    const BsdfSample<T> bs = bsdf.sample(wo, u_bsdf);
    const Vec3<T> wi_world = sp.frame.to_world(bs.wi);
    const T cos_i = max(bs.wi.z, T(0));
    const Mask<T> ok = (!bs.rejected) && (bs.pdf > T(0)) && (cos_i > T(0));
    const T w = strategy == ReferenceStrategy::kMis
                    ? mis_weight(bs.pdf, T(light.pdf(sp.position, wi_world)), heuristic)
                    : T(1);
    const T scale = select(ok, w * T(bsdf.f(wo, bs.wi)) * cos_i / select(ok, bs.pdf, T(1)), T(0));
    sum = sum + scale * light.radiance(sp.position, wi_world);
  }
  return sum;
}

struct ReferenceOptions {
  std::uint64_t samples = 1 << 16;
  std::uint64_t seed = 0;
  ReferenceStrategy strategy = ReferenceStrategy::kMis;
  MisHeuristic heuristic = MisHeuristic::kPower;
};

struct ReferenceEstimate {
  Vec3<double> mean{0, 0, 0};       // the estimate of L_o, RGB
  Vec3<double> variance{0, 0, 0};   // sample variance of one sample (n − 1 denominator)
  Vec3<double> std_error{0, 0, 0};  // √(variance / n)
  std::uint64_t samples = 0;
};

// L_o at one shading point for ωo (local frame, unit), `options.samples` samples with uniforms
// (seed, i, 0..1) for the light and (seed, i, 2..3) for the BSDF. Welford moments, serial in i.
template <class Light, class Bsdf>
requires ReferenceLight<Light, double> && ReferenceBsdf<Bsdf, double> ReferenceEstimate
area_light_reference(const Light& light, const Bsdf& bsdf, const ShadingPoint<double>& sp,
                     Vec3<double> wo, const ReferenceOptions& options) {
  ReferenceEstimate e;
  Vec3<double> m2{0, 0, 0};
  for (std::uint64_t i = 0; i < options.samples; ++i) {
    const Vec2<double> ul{counter_uniform<double>(options.seed, i, 0),
                          counter_uniform<double>(options.seed, i, 1)};
    const Vec2<double> ub{counter_uniform<double>(options.seed, i, 2),
                          counter_uniform<double>(options.seed, i, 3)};
    const Vec3<double> x =
        reference_sample(light, bsdf, sp, wo, ul, ub, options.strategy, options.heuristic);
    const double k = double(i + 1);
    const Vec3<double> d = x - e.mean;
    e.mean = e.mean + (1 / k) * d;
    const Vec3<double> d2 = x - e.mean;
    m2 = m2 + Vec3<double>{d.x * d2.x, d.y * d2.y, d.z * d2.z};
  }
  e.samples = options.samples;
  if (options.samples > 1) {
    const double n = double(options.samples);
    e.variance = (1 / (n - 1)) * m2;
    e.std_error = {std::sqrt(e.variance.x / n), std::sqrt(e.variance.y / n),
                   std::sqrt(e.variance.z / n)};
  }
  return e;
}

}  // namespace glintlab

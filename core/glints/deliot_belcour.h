// Deliot & Belcour 2023 binomial glints as Kneiphof & Klein 2024 (Sec. 3 "Differentiation from
// previous work", Sec. 5–6) and Kemppinen et al. 2025 (Sec. 2) describe them: the footprint's facet
// count N_P from a log-density, the ad-hoc probability p = R·D(h)/D(n), a binomial count b and the
// smooth GGX BRDF scaled by b/(N_P·p) (Kneiphof & Klein Eq. 16 with Deliot & Belcour's p).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string_view>
#include <type_traits>

#include "core/glints/binomial.h"
#include "core/math/hash32_stream.h"
#include "core/math/rng.h"
#include "core/model.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/heitz_vndf.h"

namespace glintlab {

// Facets in a pixel footprint: N_P = |det ∂uv/∂(x, y)| · 10^density (density = log10 facets per
// unit uv area), rounded to the nearest integer (the counting model needs whole trials);
// density_scale = 10^density.
template <class T>
GLINTLAB_FN T footprint_facet_count_scaled(const FootprintQuery<T>& f, T density_scale) {
  const T area = abs(f.duv_dx.x * f.duv_dy.y - f.duv_dx.y * f.duv_dy.x);
  return floor(fma(area, density_scale, T(0.5)));
}
template <class T>
GLINTLAB_FN T footprint_facet_count(const FootprintQuery<T>& f, T log10_density) {
  return footprint_facet_count_scaled(f, exp(log10_density * T(2.30258509299404568402)));
}

// 10^density exactly as footprint_facet_count computes it for T, evaluated once on the host: the
// density is uniform over a batch, so its lanes share the scalar exp (a batch exp differs from it
// by an ulp, which moves N_P = floor(area·10^density + ½) across an integer on ~ulp·N_P rows).
template <class T>
inline T facet_density_scale(double log10_density) {
  using S = Scalar<T>;
  return T(std::exp(S(log10_density) * S(2.30258509299404568402)));
}

// A footprint coordinate quantized to 2^-24 as a 32-bit hash counter: floor(x·2^24) mod 2^32,
// from x's integer part i and its fraction (x − i exact; (x − i)·2^24 < 2^24 truncated) in the
// integer lanes, so it wraps rather than saturates. Exact for |x| < 2^31 (beyond, i counts as 0);
// a float x and the same value in double give the same counter.
template <class T>
GLINTLAB_FN HashLanes<T> footprint_hash_coordinate(T x) {
  using U = HashLanes<T>;
  const T i = floor(x);
  return detail::wrap32(hash32_index(i) * U(16777216u) + hash32_index((x - i) * T(16777216)));
}

// The hash32 key of a footprint's counts (core/math/hash32.h; each lane its own, computed on the
// batch's integer lanes): the seed, then its centre's u and v quantized to 2^-24, nested, so a
// pixel's count is the same whatever order pixels are shaded in, and nearby footprints get
// unrelated counts, as Deliot & Belcour's per-cell random numbers do at the finest level. The
// seed enters modulo 2^32 (the parameter's range is 0..2^32 − 1).
template <class T>
GLINTLAB_FN HashLanes<T> footprint_hash_key(const FootprintQuery<T>& f, std::uint64_t seed) {
  using U = HashLanes<T>;
  return hash32_nest(hash32_key(U(static_cast<std::uint32_t>(seed)), footprint_hash_coordinate(f.uv.x)),
                     footprint_hash_coordinate(f.uv.y));
}

// The 64-bit counter-RNG index of a footprint (core/math/rng.h), its centre's uv quantized to
// 2^-24: the key of kneiphof_klein_area's host-side Monte Carlo light samples.
template <class T>
std::uint64_t footprint_rng_index(const FootprintQuery<T>& f) {
  static_assert(std::is_floating_point_v<T>, "footprint_rng_index is host-side (scalar)");
  const auto q = [](T x) {
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(double(x) * 16777216.0));
  };
  return mix64(q(f.uv.x) * 0x9e3779b97f4a7c15ULL ^ q(f.uv.y));
}

// b/(N·p): the factor Kneiphof & Klein Eq. 16 applies to the smooth radiance; 0 without facets.
template <class T>
GLINTLAB_FN T binomial_radiance_factor(T count, T n, T p) {
  return safe_div(count, n * p);
}

// The counting steps every binomial glint model shares, whatever its reflection probability:
// N_P from the footprint, p = saturate(p_raw), b ~ Binomial(N_P, p) drawn from the footprint's
// hash32 stream (footprint_hash_key) and the factor b/(N_P·p) of Kneiphof & Klein Eq. 16 (Deliot
// & Belcour 2023's scheme).
template <class T>
struct BinomialGlintCount {
  T n;       // N_P
  T p;       // the clamped probability
  T count;   // b
  T factor;  // b/(N_P·p)
};

template <class T>
GLINTLAB_FN BinomialGlintCount<T> binomial_glint_count(const FootprintQuery<T>& f, T density_scale,
                                                       T p_raw, BinomialSampler sampler,
                                                       std::uint64_t seed) {
  const T n = footprint_facet_count_scaled(f, density_scale);
  const T prob = saturate(p_raw);
  const T count = draw_binomial(sampler, n, prob, footprint_hash_key(f, seed));
  return {n, prob, count, binomial_radiance_factor(count, n, prob)};
}

// Neither paper has a glint sampler: ωo from the smooth GGX VNDF of the model's base roughness
// (Heitz 2018) with its pdf, weighted by the glinty value there (0 where rejected). M::Params<T>
// has the GGX as `ggx`.
template <class M, class T>
GLINTLAB_FN ModelSample<T> sample_binomial_glints_vndf(const typename M::template Params<T>& p,
                                                       const ModelQuery<T>& q, Vec2<T> u) {
  const MicrofacetSample<T> s = sample_heitz_vndf(p.ggx, q.wi, u);
  ModelQuery<T> at = q;
  at.wo = s.wo;
  const T value = M::eval(p, at).value;
  return {s.wo, s.pdf, select(s.rejected, T(0), safe_div(value, s.pdf)), s.rejected};
}

// The parameters the binomial glint models share (Kneiphof & Klein's and Deliot & Belcour's).
inline constexpr ParamSpec kBinomialGlintDensity{
    "density",
    6.0,
    0.0,
    15.0,
    false,
    false,
    "log10 of the microfacets per unit uv area (N_P = footprint area x 10^density)"};
inline constexpr ParamSpec kBinomialGlintSampler{
    "binomial",
    0.0,
    0.0,
    2.0,
    false,
    false,
    "binomial sampler: exact, realtime (gated Bernoulli + clamped Gaussian), small_count",
    kBinomialSamplerNames};
inline constexpr ParamSpec kBinomialGlintSeed{
    "seed", 0.0, 0.0, 4294967295.0, false, false, "seed of the counter RNG (integer)", {}, true};

// kParams of a point-light binomial glint model: alpha_x, alpha_y, density, the model's own
// parameter of its probability p, binomial, seed.
constexpr std::array<ParamSpec, 6> binomial_glint_params(const ParamSpec& probability_param) {
  return {{{"alpha_x", 0.25, 1e-4, 4.0, false, false, "GGX roughness along the tangent (x)"},
           {"alpha_y", 0.25, 1e-4, 4.0, false, false, "GGX roughness along the bitangent (y)"},
           kBinomialGlintDensity,
           probability_param,
           kBinomialGlintSampler,
           kBinomialGlintSeed}};
}

struct DeliotBelcour {
  static constexpr std::string_view kName = "deliot_belcour";
  // The smooth model its footprint average tends to (conformance: converges-to-smooth).
  static constexpr std::string_view kSmoothLimit = "smooth_ggx";
  static constexpr std::string_view kDescription =
      "Deliot & Belcour 2023 binomial glints on isotropic/anisotropic GGX: N_P from the footprint "
      "and a log10 density, p = R D(h)/D(n) clamped to [0, 1], count b ~ Binomial(N_P, p) by the "
      "chosen sampler, value = smooth GGX (F = 1) x b/(N_P p); no glint sampler in the paper: "
      "samples the smooth VNDF (Heitz 2018) and returns its pdf";
  static constexpr std::string_view kSource =
      "Deliot & Belcour 2023 as described by Kneiphof & Klein 2024 Sec. 3, 6 (p = R D(h)/D(n)) "
      "and Eq. 16; Kemppinen et al. 2025 Sec. 2";
  static constexpr unsigned kNeeds = kNeedsFootprint | kNeedsPointLight;
  static constexpr std::array<ParamSpec, 6> kParams = binomial_glint_params(
      {"r", 1.0, 0.0, 100.0, false, false,
       "Deliot & Belcour's R in p = R D(h)/D(n) (p is clamped to 1 where R D(h)/D(n) > 1)"});
  static constexpr std::array<std::string_view, 8> kIntermediates = {
      "N_P", "p_unclamped", "p", "p_clamped", "count", "factor", "smooth", "D"};

  template <class T>
  struct Params {
    GGX<T> ggx;
    T log10_density, r;
    BinomialSampler sampler;
    std::uint64_t seed;
    T density_scale;  // 10^log10_density (facet_density_scale)
  };

  template <class T>
  static Params<T> params(std::span<const double> v) {
    const double density = v[param_index<DeliotBelcour>("density")];
    return {GGX<T>{T(v[param_index<DeliotBelcour>("alpha_x")]),
                   T(v[param_index<DeliotBelcour>("alpha_y")])},
            T(density),
            T(v[param_index<DeliotBelcour>("r")]),
            static_cast<BinomialSampler>(int(v[param_index<DeliotBelcour>("binomial")])),
            static_cast<std::uint64_t>(v[param_index<DeliotBelcour>("seed")]),
            facet_density_scale<T>(density)};
  }

  template <class T>
  GLINTLAB_FN static T pdf(const Params<T>& p, const ModelQuery<T>& q) {
    return pdf_heitz_vndf(p.ggx, q.wi, q.wo);
  }

  template <class T>
  GLINTLAB_FN static ModelEval<T, kIntermediates.size()> eval(const Params<T>& p,
                                                              const ModelQuery<T>& q) {
    const Vec3<T> h = half_vector(q.wi, q.wo);
    const T d = p.ggx.D(h);
    const T d_n = T(kInvPi<T>) / (p.ggx.alpha_x * p.ggx.alpha_y);  // D(n), the NDF's maximum
    const T smooth = microfacet_brdf(p.ggx, q.wi, q.wo, T(1)) * max(q.wo.z, T(0));
    const T p_raw = p.r * d / d_n;
    const BinomialGlintCount<T> b =
        binomial_glint_count(q.footprint, p.density_scale, p_raw, p.sampler, p.seed);
    return {smooth * b.factor,
            pdf(p, q),
            {b.n, p_raw, b.p, select(p_raw > T(1), T(1), T(0)), b.count, b.factor, smooth, d}};
  }

  template <class T>
  GLINTLAB_FN static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    return sample_binomial_glints_vndf<DeliotBelcour>(p, q, u);
  }
};

static_assert(Model<DeliotBelcour>);

}  // namespace glintlab

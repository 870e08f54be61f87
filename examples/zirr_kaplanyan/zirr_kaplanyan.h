// Zirr & Kaplanyan 2016, "Real-time rendering of procedural multiscale materials" (I3D '16,
// pp. 139–148, doi 10.1145/2856400.2856409), as a glintlab model built outside the library.
//
// The model: a surface covered by glossy microdetails whose orientations follow a smooth base NDF
// (here anisotropic GGX). A pixel footprint holds N_P of them; each reflects the light into the
// viewer with probability p, so the footprint's reflecting count is Binomial(N_P, p), drawn from
// random numbers hashed on a multiscale grid so that a glint stays put while the footprint moves or
// shrinks. The glinty NDF is the smooth one scaled by count/(N_P·p), whose mean is 1: as N_P grows
// the model tends to the smooth microfacet BRDF.
//
// Sources for the formulas. The binomial counting model and the factor b/(N_P·p) are written as
// Kneiphof & Klein 2024 state them (Eq. 6–16; they name ZK16 and Deliot & Belcour 2023 as its
// origin). ZK16's normal approximation of the count, its glossy microdetails (a microdetail
// reflects over a lobe, not a single direction: the paper's "biscale" NDF) and its multiscale
// grid of hashed random numbers are from the paper itself; the paper's full text was not at hand
// while this was written (only its first page), so its equation numbers are not cited and every
// point where this file had to fix a detail is marked "choice:". Kemppinen et al. 2025 (Sec. 2,
// Fig. 15) report that this model gains energy; the clamped normal approximation below does.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <span>
#include <string_view>
#include <type_traits>

#include "core/glints/binomial.h"
#include "core/math/lane_rng.h"
#include "core/math/rng.h"
#include "core/model.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/heitz_vndf.h"

namespace glintlab::zk16 {

// How the footprint's reflecting count is drawn from its cell's uniforms.
enum class CountApproximation : int {
  kNormal = 0,      // ZK16: the normal approximation N(N p, N p (1 − p)), clamped to [0, N]
  kSmallCount = 1,  // inverse binomial CDF for the first 16 counts, normal quantile beyond
};
inline constexpr std::array<std::string_view, 2> kCountApproximationNames = {"normal",
                                                                             "small_count"};

// The number of independent counts blended per evaluation: 2 grid levels × 4 slope cells.
inline constexpr int kDraws = 8;

// Levels outside this range would make a cell index overflow 64 bits (fine levels) or span more
// than the whole uv plane (coarse levels); footprints that small or large are clamped to them.
inline constexpr double kFinestLevel = 40.0;
inline constexpr double kCoarsestLevel = -30.0;

// ---- Counting (Kneiphof & Klein 2024 Eq. 11 and 16, with ZK16's approximation) ----------------

// One count of reflecting microdetails among n, each reflecting with probability p, from a
// standard normal variate z (the paper's normal approximation): x = n p + sqrt(n p (1 − p)) z,
// clamped to [0, n]. choice: the count is not rounded to an integer (it is a radiance multiplier,
// as on the GPU). The clamp at 0 makes the mean exceed n p where n p is small (the energy gain).
template <class T>
GLINTLAB_FN T count_normal(T n, T p, T z) {
  const T mean = n * p;
  const T sd = sqrt(mean * max(T(1) - p, T(0)));
  return clamp(fma(sd, z, mean), T(0), n);
}

// A standard normal variate from two uniforms in [0, 1): Box & Muller 1958,
// z = √(−2 ln(1 − u₀)) cos(2π u₁). choice: Box–Muller, not the quantile Φ⁻¹(u) — the same normal
// distribution at about a tenth of the cost (Φ⁻¹ is an erfinv with Newton steps in double).
template <class T>
GLINTLAB_FN T standard_normal(Vec2<T> u) {
  return sqrt(T(-2) * log(T(1) - u.x)) * cos(T(2 * std::numbers::pi) * u.y);
}

template <class T>
GLINTLAB_FN T count_draw(CountApproximation a, T n, T p, Vec2<T> u) {
  return a == CountApproximation::kNormal ? count_normal(n, p, standard_normal(u))
                                          : binomial_small_count(n, p, u.x);
}

// The mean of count_normal over z, in closed form (for the tests and the report):
// E[clamp(X, 0, n)] for X ~ N(μ, σ²) is ∫₀ⁿ P(X > x) dx = σ·[G(μ/σ) − G((μ − n)/σ)] with
// G(a) = ∫_{−∞}^{a} Φ(s) ds = a·Φ(a) + φ(a). Host-side, double.
inline double count_normal_mean(double n, double p) {
  const double mu = n * p, sd = std::sqrt(n * p * (1 - p));
  if (!(sd > 0)) return std::fmin(std::fmax(mu, 0.0), n);
  const auto big_phi = [](double a) { return 0.5 * std::erfc(-a / std::numbers::sqrt2); };
  const auto small_phi = [](double a) {
    return std::exp(-0.5 * a * a) * 0.5 * std::numbers::inv_sqrtpi * std::numbers::sqrt2;
  };
  const auto g = [&](double a) { return a * big_phi(a) + small_phi(a); };
  return sd * (g(mu / sd) - g((mu - n) / sd));
}

// ---- The multiscale grid ----------------------------------------------------------------------

// The two uniforms of one grid cell: counter-RNG values keyed by the level, the footprint centre's
// cell at that level and the half vector's slope cell. Computed per lane in double, so a float
// and a double evaluation of the same query hash the same cell (the cell index at level l is
// floor(uv·2^l), exact by ldexp). On a batch, one key per lane.
namespace detail {
inline std::uint64_t cell_key(double level, double u, double v, double sx, double sy) {
  const auto whole = [](double x) {
    // NaN and out-of-range values land on a bound: the cast must stay defined.
    return static_cast<std::uint64_t>(
        static_cast<std::int64_t>(std::fmin(std::fmax(x, -4.0e18), 4.0e18)));
  };
  const int l = static_cast<int>(std::fmin(std::fmax(level, kCoarsestLevel), kFinestLevel + 1));
  std::uint64_t h = mix64(whole(level) + 0x9e3779b97f4a7c15ULL);
  h = mix64(h ^ whole(std::floor(std::ldexp(u, l))));
  h = mix64(h ^ (whole(std::floor(std::ldexp(v, l))) * 0xd1b54a32d192ed03ULL));
  h = mix64(h ^ (whole(sx) * 0x632be59bd9b4e019ULL));
  return mix64(h ^ (whole(sy) * 0x8cb92ba72f3d8dd7ULL));
}
}  // namespace detail

template <class T>
GLINTLAB_FN Vec2<T> cell_uniforms(std::uint64_t seed, T level, Vec2<T> uv, T slope_cell_x,
                                  T slope_cell_y) {
  if constexpr (std::is_floating_point_v<T>) {
    const std::uint64_t key = detail::cell_key(level, uv.x, uv.y, slope_cell_x, slope_cell_y);
    return {counter_uniform<T>(seed, key, 0), counter_uniform<T>(seed, key, 1)};
  } else {
    constexpr std::size_t kL = LaneTraits<T>::kLanes;
    alignas(64) Scalar<T> l[kL], u[kL], v[kL], sx[kL], sy[kL], out0[kL], out1[kL];
    LaneTraits<T>::store(level, l);
    LaneTraits<T>::store(uv.x, u);
    LaneTraits<T>::store(uv.y, v);
    LaneTraits<T>::store(slope_cell_x, sx);
    LaneTraits<T>::store(slope_cell_y, sy);
    for (std::size_t i = 0; i < kL; ++i) {
      const std::uint64_t key = detail::cell_key(l[i], u[i], v[i], sx[i], sy[i]);
      out0[i] = counter_uniform<Scalar<T>>(seed, key, 0);
      out1[i] = counter_uniform<Scalar<T>>(seed, key, 1);
    }
    return {LaneTraits<T>::load(out0), LaneTraits<T>::load(out1)};
  }
}

// ---- The model --------------------------------------------------------------------------------

struct ZirrKaplanyan {
  static constexpr std::string_view kName = "zirr_kaplanyan";
  static constexpr std::string_view kDescription =
      "Zirr & Kaplanyan 2016 procedural multiscale glints on anisotropic GGX: N_P = footprint "
      "area x 10^density glossy microdetails, p = pi beta^2 P22(slope of h) (a microdetail "
      "reflects over a slope disk of radius beta = microroughness), count by the normal "
      "approximation of Binomial(N_P, p) (or small_count) from uniforms hashed on a multiscale "
      "uv grid x slope grid, value = smooth GGX (F = 1) x count/(N_P p); no sampler in the paper: "
      "samples the smooth VNDF (Heitz 2018) and returns its pdf";
  static constexpr std::string_view kSource =
      "Zirr & Kaplanyan 2016 (I3D) Sec. on biscale NDF, binomial counting and multiscale noise; "
      "counting model and factor b/(N_P p) as Kneiphof & Klein 2024 Eq. 6-16 write them";
  static constexpr unsigned kNeeds = kNeedsFootprint | kNeedsPointLight;

  // The smooth model this one tends to as N_P grows (its alpha_x, alpha_y are ours by name).
  static constexpr std::string_view kSmoothLimit = "smooth_ggx";
  // small_count is a configuration of the conformance suite's float-vs-double (every declared
  // choice is); its inverse-CDF count is a discrete decision that float rounding moves.
  static constexpr std::array<NotClaimed, 2> kNotClaimed = {{
      {"energy",
       "the paper's clamped normal approximation of the count has a mean above N_P p where N_P p "
       "is small (E[max(0, X)] > E[X]), so the white-furnace albedo exceeds the smooth GGX one "
       "there (Kemppinen et al. 2025 Fig. 15 report the same gain for this model); "
       "binomial=small_count removes it"},
      {"float-vs-double",
       "small_count draws the count by inverting the binomial CDF at a uniform, a discrete "
       "decision whose steps the float path's rounding of the CDF sums moves (measured at the "
       "quick budget: 4 of 2500 queries beyond 1e-3 relative, allowed 1e-3)",
       "binomial=small_count"},
  }};

  static constexpr std::array<ParamSpec, 6> kParams = {{
      {"alpha_x", 0.25, 1e-4, 4.0, false, false, "GGX roughness of the base NDF along x"},
      {"alpha_y", 0.25, 1e-4, 4.0, false, false, "GGX roughness of the base NDF along y"},
      {"density", 6.0, 0.0, 15.0, false, false,
       "log10 of the microdetails per unit uv area (N_P = footprint area x 10^density)"},
      {"microroughness", 0.05, 1e-3, 1.0, false, false,
       "slope-space radius beta of one microdetail's reflection lobe (p = pi beta^2 P22)"},
      {"binomial", 0.0, 0.0, 1.0, false, false,
       "count approximation: normal (the paper's, clamped to [0, N_P]) or small_count (inverse "
       "binomial CDF to 16, normal beyond)",
       kCountApproximationNames},
      {"seed", 0.0, 0.0, 4294967295.0, false, false, "seed of the hashed grid (integer)", {}, true},
  }};
  // p is a probability (saturated); variance_factor = Σ w² of the blend weights: the blended
  // count's variance over that of one draw.
  static constexpr std::array<std::string_view, 9> kIntermediates = {
      "N_P", "p", "expected_count", "count", "factor", "lod", "variance_factor", "smooth", "D"};

  template <class T>
  struct Params {
    GGX<T> ggx;
    T microroughness;
    CountApproximation count;  // uniform over a batch: branching on it is allowed
    std::uint64_t seed;
    T density_scale;  // 10^density, once on the host (the same value in every lane)
  };

  template <class T>
  static Params<T> params(std::span<const double> v) {
    return {GGX<T>{T(v[param_index<ZirrKaplanyan>("alpha_x")]),
                   T(v[param_index<ZirrKaplanyan>("alpha_y")])},
            T(v[param_index<ZirrKaplanyan>("microroughness")]),
            static_cast<CountApproximation>(int(v[param_index<ZirrKaplanyan>("binomial")])),
            static_cast<std::uint64_t>(v[param_index<ZirrKaplanyan>("seed")]),
            T(Scalar<T>(std::pow(10.0, v[param_index<ZirrKaplanyan>("density")])))};
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
    const T smooth = microfacet_brdf(p.ggx, q.wi, q.wo, T(1)) * max(q.wo.z, T(0));

    // Probability that one microdetail reflects ωi into ωo. Its lobe covers a disk of radius β in
    // slope space around its own slope, so it reflects into h when its slope lies within β of
    // h's slope s_h: p = ∫_{|s − s_h| < β} P22(s) ds ≈ π β² P22(s_h), with the slope distribution
    // P22(s) = D(h) h_z⁴ (choice: the first-order, point-evaluated form of that integral; the
    // paper's glossy microdetails, whose lobe width is its second roughness). Saturated to 1.
    const T hz = max(h.z, T(0));
    const T hz2 = hz * hz;
    const T p_raw = T(kPi<T>) * sqr(p.microroughness) * d * hz2 * hz2;
    const T prob = saturate(p_raw);

    // N_P = footprint area × density, whole microdetails (the count needs whole trials).
    const FootprintQuery<T>& f = q.footprint;
    const T area = abs(f.duv_dx.x * f.duv_dy.y - f.duv_dx.y * f.duv_dy.x);
    const T n = floor(fma(area, p.density_scale, T(0.5)));

    // Spatial LOD: level l has cells of side 2^-l in uv. λ = −½ log2(area), the level whose cell
    // side equals the footprint's side √area; the count is blended between levels ⌊λ⌋ and
    // ⌊λ⌋ + 1 by t = λ − ⌊λ⌋. choice: the footprint centre's cell at each level (no spatial
    // interpolation inside a level), and the footprint's size as √area (isotropic, as the paper's
    // LOD is; anisotropic footprints are measured by their area).
    const T lod = clamp(T(-0.5 / 0.69314718055994530942) * log(max(area, T(1e-30))),
                        T(kCoarsestLevel), T(kFinestLevel));
    const T level0 = floor(lod);
    const T t = lod - level0;

    // Angular grid: microdetails whose lobes do not overlap reflect independently, so the
    // uniforms are also keyed by h's cell on a slope grid of pitch 2β (choice: one lobe diameter)
    // and blended bilinearly over the four cells around s_h, keeping the glints continuous in h.
    // Blending independent counts keeps the binomial's mean but scales its variance by Σ w²
    // (reported as variance_factor): the incorrect statistics of interpolated counts that Deliot
    // & Belcour 2023 (abstract) set out to correct.
    const T inv_pitch = T(0.5) / p.microroughness;
    const T safe_hz = max(hz, T(1e-30));
    const T gx = clamp(-h.x / safe_hz * inv_pitch - T(0.5), T(-1e15), T(1e15));
    const T gy = clamp(-h.y / safe_hz * inv_pitch - T(0.5), T(-1e15), T(1e15));
    const T jx = floor(gx), jy = floor(gy);
    const T fx = gx - jx, fy = gy - jy;

    T count = T(0);
    T weight_sq = T(0);
    for (int level = 0; level < 2; ++level) {
      const T wl = level == 0 ? T(1) - t : t;
      for (int corner = 0; corner < 4; ++corner) {
        const int cx = corner & 1, cy = corner >> 1;
        const T w = wl * (cx ? fx : T(1) - fx) * (cy ? fy : T(1) - fy);
        const Vec2<T> u = cell_uniforms(p.seed, level0 + T(level), f.uv, jx + T(cx), jy + T(cy));
        count = fma(w, count_draw(p.count, n, prob, u), count);
        weight_sq = fma(w, w, weight_sq);
      }
    }

    // Kneiphof & Klein 2024 Eq. 16: the smooth value times b/(N_P p); 0 without microdetails.
    const T factor = safe_div(count, n * prob);
    return {smooth * factor,
            pdf(p, q),
            {n, prob, n * prob, count, factor, lod, weight_sq, smooth, d}};
  }

  // No sampler in the paper: ωo from the base GGX's VNDF (Heitz 2018) with its pdf; the weight is
  // the glinty value over that pdf, 0 where the sampler rejects ωo (below the horizon).
  template <class T>
  GLINTLAB_FN static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    const MicrofacetSample<T> s = sample_heitz_vndf(p.ggx, q.wi, u);
    ModelQuery<T> at = q;
    at.wo = s.wo;
    const T value = eval(p, at).value;
    return {s.wo, s.pdf, select(s.rejected, T(0), safe_div(value, s.pdf)), s.rejected};
  }
};

static_assert(Model<ZirrKaplanyan>);

}  // namespace glintlab::zk16

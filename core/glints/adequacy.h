// Which level of the binomial glint family a pixel needs: the cheapest of smooth, real-time count,
// small-count count and exact count whose pixel value no one could tell from the exact count's
// (mean and coefficient of variation over surface positions within TAU). The closed forms below
// predict each level's count distribution; the measured table (`glintlab adequacy`,
// verify/adequacy/) checks them. docs/adequacy.md explains the criterion and the default TAU.
//
// The pixel value of deliot_belcour and kneiphof_klein is smooth · b/(N_P p): all levels share the
// smooth factor, so the distribution over surface positions is that of the count b (Kneiphof &
// Klein 2024 Eq. 16). Exact: b ~ Binomial(N_P, p), mean N_P p, CV √((1 − p)/(N_P p)), P(b = 0) =
// (1 − p)^N_P. Smooth: b/(N_P p) = 1, CV 0.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "core/glints/binomial.h"
#include "core/glints/deliot_belcour.h"
#include "core/glints/kemppinen.h"
#include "core/glints/kneiphof.h"
#include "core/math/ops.h"
#include "core/models/kemppinen_model.h"

namespace glintlab {

// The levels, cheapest first (the order of the measured cost per evaluation; docs/adequacy.md).
// The values are stored as a float in the chooser's lanes.
enum class BinomialLevel : int { kSmooth = 0, kRealTime = 1, kSmallCount = 2, kExact = 3 };
inline constexpr int kBinomialLevels = 4;
inline constexpr std::array<std::string_view, 4> kBinomialLevelNames = {"smooth", "realtime",
                                                                        "small_count", "exact"};

// The levels of the Kemppinen family (kemppinen_ggx, kemppinen_beckmann; Kemppinen et al. 2025),
// cheapest first in the cost order of a GPU lane: the smooth NDF (D★^f replaced by D), then
// Algorithm 1 with k = 1, 4, 9, 16 neighbours in space and in angle (2k² points per evaluation),
// each with the rational erf (A&S 7.1.28, no exp) before the exact one in the compensation
// (Eq. 10). The most complete level is k = 16 with the exact erf.
enum class KemppinenLevel : int {
  kSmooth = 0,
  kK1Rational = 1,
  kK1Exact = 2,
  kK4Rational = 3,
  kK4Exact = 4,
  kK9Rational = 5,
  kK9Exact = 6,
  kK16Rational = 7,
  kK16Exact = 8
};
inline constexpr int kKemppinenLevels = 9;
inline constexpr std::array<std::string_view, kKemppinenLevels> kKemppinenLevelNames = {
    "smooth",     "k1_rational", "k1_exact",     "k4_rational", "k4_exact",
    "k9_rational", "k9_exact",   "k16_rational", "k16_exact"};
// √k of a counting level (1 … 4; 0 for the smooth level) and whether it uses the rational erf.
inline constexpr int kemppinen_level_side(KemppinenLevel l) { return (int(l) + 1) / 2; }
inline constexpr bool kemppinen_level_rational(KemppinenLevel l) { return int(l) % 2 == 1; }

// The chooser takes a level only where its predicted difference is at most this fraction of TAU:
// the closed forms are exact for the exact and smooth levels but the real-time one neglects the
// quantile clamp at 1e-12, and the measured table decides with a confidence bound, so a predicted
// difference right at TAU could be measured above it.
inline constexpr double kChooserMargin = 0.5;

// Standard normal density and distribution function.
template <class T>
GLINTLAB_FN T standard_normal_pdf(T x) {
  return T(0.39894228040143267794) * exp(T(-0.5) * x * x);
}
template <class T>
GLINTLAB_FN T standard_normal_cdf(T x) {
  return T(0.5) * erfc(T(-0.70710678118654752440) * x);
}

// Mean and second moment of a count.
template <class T>
struct CountMoments {
  T mean, second;
};

// The exact count's CV √((1 − p)/(N_P p)) (0 where N_P p = 0).
template <class T>
GLINTLAB_FN T binomial_count_cv(T n, T p) {
  return safe_sqrt(safe_div(T(1) - p, n * p));
}

// P(b = 0) = (1 − p)^N_P.
template <class T>
GLINTLAB_FN T binomial_zero_probability(T n, T p) {
  return exp(n * log(max(T(1) - p, T(1e-300))));
}

// The moments of binomial_realtime's X = G·(1 + clamp(Y, 0, m)), G ~ Bernoulli(1 − (1 − p)^n)
// independent of Y ~ N(m p, m p (1 − p)), m = n − 1 (the clamped normal's moments in closed form:
// E C = μ(Φ(b) − Φ(a)) + σ(φ(a) − φ(b)) + m(1 − Φ(b)), E C² = (μ² + σ²)(Φ(b) − Φ(a)) +
// 2μσ(φ(a) − φ(b)) + σ²(a φ(a) − b φ(b)) + m²(1 − Φ(b)), a = −μ/σ, b = (m − μ)/σ).
template <class T>
GLINTLAB_FN CountMoments<T> realtime_count_moments(T n, T p) {
  const T q = max(T(1) - p, T(0));
  // log(1 − p) as log1p(−p): 1 − p rounds to float's spacing near 1 (6e-8), which at the small p
  // of a narrow light cone (1e-6 … 1e-4) would put percents of error into P(any) and the mean;
  // −690.8 = log(1e-300) keeps p = 1 finite (P(any) = 1, and 0 · it = 0 where N_P = 0).
  const T p_any = -expm1(n * max(log1p(-min(p, T(1))), T(-690.77552789821368)));
  const T m = max(n - T(1), T(0));
  const T mu = m * p, sigma = sqrt(m * p * q);
  const Mask<T> spread = sigma > T(0);
  const T s = select(spread, sigma, T(1));
  const T a = -mu / s, b = (m - mu) / s;
  const T pa = standard_normal_cdf(a), pb = standard_normal_cdf(b);
  const T fa = standard_normal_pdf(a), fb = standard_normal_pdf(b);
  const T inside = pb - pa, above = T(1) - pb;
  const T ec_spread = mu * inside + s * (fa - fb) + m * above;
  const T ec2_spread = (mu * mu + s * s) * inside + T(2) * mu * s * (fa - fb) +
                       s * s * (a * fa - b * fb) + m * m * above;
  const T ec = select(spread, ec_spread, mu);  // σ = 0: C = μ exactly
  const T ec2 = select(spread, ec2_spread, mu * mu);
  const Mask<T> any = n >= T(1);
  return {select(any, p_any * (T(1) + ec), T(0)),
          select(any, p_any * (T(1) + T(2) * ec + ec2), T(0))};
}

// CV of a count from its moments (0 where the mean is 0).
template <class T>
GLINTLAB_FN T count_cv(const CountMoments<T>& c) {
  return safe_div(safe_sqrt(c.second - c.mean * c.mean), c.mean);
}

// Which levels are adequate for a footprint of N_P facets and reflection probability p (clamped
// to [0, 1], as the models clamp it), at threshold tau. A level is adequate where its predicted
// relative difference of the means and its difference of the CVs from the exact count's are both
// at most kChooserMargin · tau:
//   smooth       mean exact; CV difference = the exact CV.
//   real-time    realtime_count_moments against N_P p and N_P p (1 − p).
//   small-count  identical to the exact count where its 16-term inversion covers the count
//                (N_P p + 6σ ≤ 15.5: the rest has probability < 1e-9), and a rounded normal where the
//                count starts beyond it (N_P p − 6σ ≥ 16; rounding adds 1/12 to the variance); in
//                between it is not adequate (the mixture has no closed form here).
//   exact        always.
// N_P < 1 or p = 0: every count is 0, so the real-time level (whose gate returns 0 where N_P = 0)
// is adequate where N_P < 1, and the smooth one where p = 0 (D(h) = 0: its value is 0 too).
template <class T>
struct AdequateLevels {
  Mask<T> smooth, realtime, small_count;
};
template <class T>
GLINTLAB_FN AdequateLevels<T> adequate_binomial_levels(T n, T p_raw, T tau) {
  const T p = saturate(p_raw);
  const T limit = T(kChooserMargin) * tau;
  const T np = n * p, var = np * (T(1) - p);
  const T cv_exact = binomial_count_cv(n, p);
  const CountMoments<T> rt = realtime_count_moments(n, p);
  const T rt_mean_diff = abs(safe_div(rt.mean, np) - T(1));
  const T rt_cv_diff = abs(count_cv(rt) - cv_exact);
  const T sd = sqrt(var);
  const T cv_rounded = safe_div(sqrt(var + T(1.0 / 12)), np);
  const Mask<T> no_facets = n < T(1), no_probability = p <= T(0);
  // The smooth level needs the count's CV small, which fewer than one facet never gives (the
  // closed form's 0/0 there is not a small CV).
  return {(cv_exact <= limit && !no_facets) || no_probability,
          (rt_mean_diff <= limit && rt_cv_diff <= limit) || no_facets,
          np + T(6) * sd <= T(kSmallCountTerms - 0.5) ||
              (np - T(6) * sd >= T(kSmallCountTerms) && abs(cv_rounded - cv_exact) <= limit)};
}

// The chooser in the cost order of a GPU lane (smooth < real-time < small-count < exact: the exact
// count's variable loop is the costly one there): the first adequate level. Returns the level's
// BinomialLevel value as T.
template <class T>
GLINTLAB_FN T choose_binomial_level(T n, T p_raw, T tau) {
  const AdequateLevels<T> a = adequate_binomial_levels(n, p_raw, tau);
  const Mask<T> no_facets = n < T(1), no_probability = saturate(p_raw) <= T(0);
  T level = T(int(BinomialLevel::kExact));
  level = select(a.small_count, T(int(BinomialLevel::kSmallCount)), level);
  level = select(a.realtime, T(int(BinomialLevel::kRealTime)), level);
  level = select(a.smooth, T(int(BinomialLevel::kSmooth)), level);
  // No facets: every count is 0, the real-time gate included (but no probability wins: D(h) = 0,
  // the smooth value is 0 as well).
  level = select(no_facets, T(int(BinomialLevel::kRealTime)), level);
  return select(no_probability, T(int(BinomialLevel::kSmooth)), level);
}

// The chooser for measured costs (ns per evaluation, indexed by BinomialLevel: from the benchmark
// JSON of the machine it runs on, `glintlab adequacy --bench-from`): the adequate level of least
// cost; a tie goes to the cheaper one in the GPU order. Branch-free on lanes.
template <class T>
GLINTLAB_FN T choose_binomial_level_by_cost(T n, T p_raw, T tau,
                                            const std::array<double, kBinomialLevels>& cost) {
  const AdequateLevels<T> a = adequate_binomial_levels(n, p_raw, tau);
  T level = T(int(BinomialLevel::kExact));
  T best = T(cost[std::size_t(BinomialLevel::kExact)]);
  const auto consider = [&](const Mask<T>& adequate, BinomialLevel l) {
    const Mask<T> take = adequate && T(cost[std::size_t(l)]) <= best;
    level = select(take, T(int(l)), level);
    best = select(take, T(cost[std::size_t(l)]), best);
  };
  consider(a.small_count, BinomialLevel::kSmallCount);
  consider(a.realtime, BinomialLevel::kRealTime);
  consider(a.smooth, BinomialLevel::kSmooth);
  return level;
}

// The chooser on what a shader of deliot_belcour has: its parameters and the query (footprint,
// directions). N_P and p exactly as DeliotBelcour::eval computes them.
template <class T>
GLINTLAB_FN T choose_deliot_belcour_level(const DeliotBelcour::Params<T>& params,
                                          const ModelQuery<T>& q, T tau) {
  const Vec3<T> h = half_vector(q.wi, q.wo);
  const T d_n = T(kInvPi<T>) / (params.ggx.alpha_x * params.ggx.alpha_y);
  const T n = footprint_facet_count_scaled(q.footprint, params.density_scale);
  return choose_binomial_level(n, params.r * params.ggx.D(h) / d_n, tau);
}

// The same for kneiphof_klein: the light's cap (the query's cone, else the model's gamma).
template <class T>
GLINTLAB_FN T choose_kneiphof_klein_level(const kneiphof2024::KneiphofKlein::Params<T>& params,
                                          const ModelQuery<T>& q, T tau) {
  const T omc = select(q.light.cos_half_angle < T(1), T(1) - q.light.cos_half_angle,
                       params.one_minus_cos_gamma);
  const T n = footprint_facet_count_scaled(q.footprint, params.density_scale);
  return choose_binomial_level(
      n, kneiphof2024::cap_probability_eq20(params.ggx, q.wi, q.wo, omc, params.total_area), tau);
}

// ---- The Kemppinen family ---------------------------------------------------------------------
//
// What Algorithm 1 (Kemppinen et al. 2025, core/glints/kemppinen.h) does at side n (k = n²) and
// MIP level l, with weight w_l: the points of the n × n spatial cells around x_s times the n × n
// angular cells around x_a = T(ω_h), each N_s(x_s − g_s) N_a(x_a − g_a) / K_P with g uniform in its
// cell, plus the compensation: the angular lobe's mass over the unit square outside the angular
// block (Eq. 10). Relative to D, over surface positions (the fractional offset u of x_s in its
// cell uniform, as the measured table moves the footprint):
//   mean_n = A − Σ_l w_l a_n(l) (1 − s_n(l))
// with A the lobe's mass over the square, a_n(l) its mass over the angular block and s_n(l) the
// spatial filter's mass over the spatial block, averaged over u (the block misses filter mass that
// nothing compensates). The spread: the points, cell by cell independent, add at most
// E[X²] = (1/K_P) ∫_cell N_s² ∫_cell N_a² each (E[R²] ≤ E[R] = w_l for the roulette), i.e.
//   var_points_n ≤ Σ_l w_l a'_n(l) s'_n(l) / (K_P · 4π σ_sx σ_sy · 4π σ_ax σ_ay)
// (a', s': the masses of the √2-narrower Gaussians, N² = N(σ/√2) / (4π σ_x σ_y)), and the
// conditional mean moves with u by sd_u(s_n(l)) a_n(l) at most. The blocks are nested (k = 1 ⊂ 4
// ⊂ 16, 9 ⊂ 16), so level n against k = 16 differs by the points of 16's block outside n's:
// sd(D★_16 − D★_n) ≤ √(var_points_16 − var_points_n) + the two positional spreads.
// Approximations: the spatial covariance taken as diagonal (exact for axis-aligned footprints), the
// lobe's points outside the disk U_Ω (rejected) neglected, the roulette's mean taken as w_l, and
// the rational erf's error (≤ 3e-7 per mass, A&S) bounded by 1e-5 of the mean.

// The position-averaged masses of a 1D Gaussian of standard deviation `sigma` over the block of n
// cells of size `cell` that Algorithm 1 visits around the position (block_start: floor(x/cell −
// (n − 1)/2)), the offset u of the block uniform: E_u m, E_u m² and E_u m' (σ/√2). Midpoint rule.
template <class T>
struct BlockMassMoments {
  T mean, second, narrow;
};
inline constexpr int kKemppinenChooserNodes = 16;
template <class T>
GLINTLAB_FN BlockMassMoments<T> kemppinen_block_mass(int n, T cell, T sigma) {
  T m1 = T(0), m2 = T(0), mn = T(0);
  const T inv = T(1) / sigma, inv_narrow = T(1.41421356237309504880) / sigma;
  for (int q = 0; q < kKemppinenChooserNodes; ++q) {
    const T u = T((q + 0.5) / kKemppinenChooserNodes);
    const T left = (u + T(0.5 * (n - 1))) * cell, right = (T(0.5 * (n + 1)) - u) * cell;
    const T m = standard_normal_cdf(right * inv) - standard_normal_cdf(-left * inv);
    m1 = m1 + m;
    m2 = m2 + m * m;
    mn = mn + standard_normal_cdf(right * inv_narrow) - standard_normal_cdf(-left * inv_narrow);
  }
  const T w = T(1.0 / kKemppinenChooserNodes);
  return {m1 * w, m2 * w, mn * w};
}

// Predicted statistics of the sides n = 1 … 4 at one query, relative to D: the mean, the points'
// variance bound (var_points), the positional spread bound (position_sd).
template <class T>
struct KemppinenMoments {
  std::array<T, 4> mean, var_points, position_sd;
  Mask<T> valid;  // ω_h up and D > 0 (elsewhere every level is 0)
};

template <class Ndf, class T>
GLINTLAB_FN KemppinenMoments<T> kemppinen_level_moments(const kemppinen2025::Params<T>& p,
                                                        const Ndf& ndf,
                                                        const FootprintQuery<T>& fp, Vec3<T> h) {
  using namespace kemppinen2025;
  const Angular<T> ang = angular(p, ndf, h);
  const T res = base_resolution(p);
  const Sym2<T> sigma_s = spatial_covariance(p, fp, res);
  const T lambda = lod(sigma_s, res);
  const T fl = min(floor(lambda), T(kMaxLevel - 1));
  const LaneInt<T, int> l0 = floor_int<T, int>(fl);
  const T w1 = lambda - fl, w0 = T(1) - w1;
  const T sx = sqrt(sigma_s.xx), sy = sqrt(sigma_s.yy);
  const Vec2<T> sa = ang.sigma_a, sa_narrow{sa.x * T(0.70710678118654752440),
                                            sa.y * T(0.70710678118654752440)};
  const T whole = gaussian_rect_mass(Vec2<T>{T(0), T(0)}, Vec2<T>{T(1), T(1)}, ang.x_a, sa,
                                     Erf::kExact);
  // 1 / (K_P 4π σ_sx σ_sy 4π σ_ax σ_ay): E[X²] summed over a block per unit of a' s'.
  const T points_scale =
      T(1) / (sqr(res) * T(157.91367041742973790) * sx * sy * sa.x * sa.y);
  KemppinenMoments<T> out;
  out.valid = ang.valid;
  for (int n = 1; n <= 4; ++n) {
    T mean = whole, var = T(0), pos = T(0);
    for (int step = 0; step < 2; ++step) {
      const LaneInt<T, int> level = l0 + step;
      const T w = step == 0 ? w0 : w1;
      // The angular block, clipped to the square, as Algorithm 1 visits it.
      const T res_a = angular_resolution<T>(level);
      const LaneInt<T> n_a = level_cells<T>(level);
      const LaneInt<T> ax0 = block_start(ang.x_a.x * res_a, n);
      const LaneInt<T> ay0 = block_start(ang.x_a.y * res_a, n);
      const Vec2<T> lo{int_to_float<T>(int_max(ax0, std::int64_t(0))) / res_a,
                       int_to_float<T>(int_max(ay0, std::int64_t(0))) / res_a};
      const Vec2<T> hi{int_to_float<T>(int_min(ax0 + n, n_a)) / res_a,
                       int_to_float<T>(int_min(ay0 + n, n_a)) / res_a};
      const T a = gaussian_rect_mass(lo, hi, ang.x_a, sa, Erf::kExact);
      const T a_narrow = gaussian_rect_mass(lo, hi, ang.x_a, sa_narrow, Erf::kExact);
      // The spatial block: n cells of 2^l / res per axis.
      const T cell = res_a / res;
      const BlockMassMoments<T> mx = kemppinen_block_mass(n, cell, sx);
      const BlockMassMoments<T> my = kemppinen_block_mass(n, cell, sy);
      const T s = mx.mean * my.mean;
      const T s_sd = safe_sqrt(mx.second * my.second - sqr(s));
      mean = mean - w * a * (T(1) - s);
      var = var + w * a_narrow * mx.narrow * my.narrow * points_scale;
      pos = pos + w * a * s_sd;
    }
    out.mean[std::size_t(n - 1)] = mean;
    out.var_points[std::size_t(n - 1)] = var;
    out.position_sd[std::size_t(n - 1)] = pos;
  }
  return out;
}

// Which Kemppinen levels are adequate (predicted differences from k = 16 exact at most
// kChooserMargin · tau): per side n = 1 … 4, and the smooth level. A rational level is adequate
// where the exact one of its k is (their difference is below 1e-5 of the mean).
template <class T>
struct AdequateKemppinenLevels {
  Mask<T> smooth;
  std::array<Mask<T>, 4> side;
};
template <class T>
GLINTLAB_FN AdequateKemppinenLevels<T> adequate_kemppinen_levels(const KemppinenMoments<T>& m,
                                                                 T tau) {
  const T limit = T(kChooserMargin) * tau - T(1e-5);
  const T ref = max(m.mean[3], T(1e-30));
  const T ref_sd = sqrt(m.var_points[3]) + m.position_sd[3];
  AdequateKemppinenLevels<T> out;
  // Smooth: D itself against k = 16's mean and spread.
  out.smooth = (abs(T(1) / ref - T(1)) <= limit && ref_sd / ref <= limit) || !m.valid;
  for (std::size_t n = 0; n < 4; ++n) {
    const T mean = max(m.mean[n], T(1e-30));
    const T cv = (sqrt(m.var_points[n]) + m.position_sd[n]) / mean;
    const T sd_diff = safe_sqrt(m.var_points[3] - m.var_points[n]) + m.position_sd[n] +
                      m.position_sd[3];
    const T mean_diff = abs(mean / ref - T(1));
    const T cv_diff = sd_diff / ref + cv * abs(ref - mean) / ref;
    out.side[n] = (mean_diff <= limit && cv_diff <= limit) || !m.valid;
  }
  out.side[3] = Mask<T>(true);
  return out;
}

// The chooser in the GPU-lane order of KemppinenLevel: the first adequate level (the rational
// twin of a side, never its exact one). Returns the level's KemppinenLevel value as T.
template <class Ndf, class T>
GLINTLAB_FN T choose_kemppinen_level(const kemppinen2025::Params<T>& p, const Ndf& ndf,
                                     const FootprintQuery<T>& fp, Vec3<T> h, T tau) {
  const AdequateKemppinenLevels<T> a =
      adequate_kemppinen_levels(kemppinen_level_moments(p, ndf, fp, h), tau);
  T level = T(int(KemppinenLevel::kK16Rational));
  level = select(a.side[2], T(int(KemppinenLevel::kK9Rational)), level);
  level = select(a.side[1], T(int(KemppinenLevel::kK4Rational)), level);
  level = select(a.side[0], T(int(KemppinenLevel::kK1Rational)), level);
  return select(a.smooth, T(int(KemppinenLevel::kSmooth)), level);
}

// The same on what a shader of kemppinen_ggx / kemppinen_beckmann has (uv mapping): its
// parameters and the query.
template <class Ndf, class T>
GLINTLAB_FN T choose_kemppinen_model_level(const detail::KemppinenModelParams<Ndf, T>& params,
                                           const ModelQuery<T>& q, T tau) {
  return choose_kemppinen_level(params.glint, params.ndf, q.footprint, half_vector(q.wi, q.wo),
                                tau);
}

}  // namespace glintlab

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
#include "core/glints/kneiphof.h"
#include "core/math/ops.h"

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
  const T p_any = -expm1(n * log(max(q, T(1e-300))));
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

}  // namespace glintlab

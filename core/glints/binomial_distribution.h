// The exact distributions of the binomial samplers of core/glints/binomial.h (Binomial(n, p),
// Deliot & Belcour 2023's gated Bernoulli + clamped Gaussian, the small-count inverse CDF), and
// their distances from the exact binomial: Kolmogorov–Smirnov distance sup|F − A| and, for the
// discrete ones, total variation. Host-side, double; no sampling noise.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/glints/binomial.h"

namespace glintlab {

namespace detail {
// Stirling's error δ(x) = log x! − (x + ½) log x + x − ½ log 2π (x > 0): the series 1/(12x) −
// 1/(360x³) + 1/(1260x⁵) for x ≥ 16 (error < 1e-16 relative), lgamma below.
inline double stirling_error(double x) {
  if (x < 16) return std::lgamma(x + 1) - (x + 0.5) * std::log(x) + x - 0.91893853320467274178;
  const double ix = 1 / x, ix2 = ix * ix;
  return ix * (1.0 / 12 - ix2 * (1.0 / 360 - ix2 * (1.0 / 1260)));
}
// bd0(x, M) = x log(x/M) + M − x, without the cancellation near x = M (Loader 2000, "Fast and
// accurate computation of binomial probabilities": the series in v = (x − M)/(x + M)).
inline double deviance_bd0(double x, double mean) {
  if (std::abs(x - mean) < 0.1 * (x + mean)) {
    const double v = (x - mean) / (x + mean), v2 = v * v;
    double s = (x - mean) * v, ej = 2 * x * v;
    for (int j = 1; j < 1000; ++j) {
      ej *= v2;
      const double s1 = s + ej / (2 * j + 1);
      if (s1 == s) return s1;
      s = s1;
    }
    return s;
  }
  return x * std::log(x / mean) + mean - x;
}
// log P(X = k) for X ~ Binomial(n, p), 0 < p < 1, by Loader's saddle-point form: relative error
// ~1e-15 in P whatever n (log k! differences of numbers ~1e13 would lose 1e-3).
inline double binomial_log_pmf(double n, double p, double k) {
  const double q = 1 - p;
  if (k == 0) return n * std::log1p(-p);
  if (k == n) return n * std::log(p);
  return stirling_error(n) - stirling_error(k) - stirling_error(n - k) - deviance_bd0(k, n * p) -
         deviance_bd0(n - k, n * q) + 0.5 * std::log(n / (6.28318530717958647692 * k * (n - k)));
}
}  // namespace detail

// The Binomial(n, p) pmf on the window [lo, hi] that holds all but < 1e-18 of the mass (mean ±
// (40σ + 40)), by log-recurrence from the mode's value f(m) (Loader's form, detail above).
struct BinomialPmf {
  std::uint64_t lo = 0;
  std::vector<double> f;  // f[i] = P(X = lo + i)
};

inline BinomialPmf binomial_pmf(std::uint64_t n, double p) {
  BinomialPmf r;
  if (n == 0 || p <= 0) return {0, {1.0}};
  if (p >= 1) return {n, {1.0}};
  const double nd = double(n), q = 1 - p, sd = std::sqrt(nd * p * q);
  const double m = std::floor((nd + 1) * p);
  const double lo = std::max(0.0, std::floor(nd * p - 40 * sd - 40));
  const double hi = std::min(nd, std::ceil(nd * p + 40 * sd + 40));
  // log f(m) = log n! − log m! − log (n − m)! + m log p + (n − m) log q
  const double lfm = detail::binomial_log_pmf(nd, p, m);
  r.lo = std::uint64_t(lo);
  r.f.assign(std::size_t(hi - lo + 1), 0.0);
  const double lr = std::log(p / q);
  double l = lfm;
  for (double k = m; k <= hi; ++k) {  // upward from the mode
    r.f[std::size_t(k - lo)] = std::exp(l);
    l += std::log((nd - k) / (k + 1)) + lr;
  }
  l = lfm;
  for (double k = m; k > lo;) {  // downward
    l -= std::log((nd - (k - 1)) / k) + lr;
    --k;
    r.f[std::size_t(k - lo)] = std::exp(l);
  }
  return r;
}

inline double normal_cdf(double x) { return 0.5 * std::erfc(-x / 1.41421356237309504880); }
inline double normal_pdf(double x) { return 0.39894228040143267794 * std::exp(-0.5 * x * x); }

// CDF of the real-time approximation X = G·(1 + clamp(Y, 0, n − 1)) at x (right-continuous).
inline double realtime_cdf(double n, double p, double x) {
  if (x < 0) return 0;
  const double p_any = -std::expm1(n * std::log1p(-std::min(p, 1 - 1e-16)));
  const double m = n - 1, mu = m * p, sd = std::sqrt(m * p * (1 - p));
  double c;  // P(1 + clamp(Y) ≤ x)
  if (x < 1)
    c = 0;
  else if (x >= n)
    c = 1;
  else
    c = sd > 0 ? normal_cdf((x - 1 - mu) / sd) : (x - 1 >= mu ? 1.0 : 0.0);
  return (1 - p_any) + p_any * c;
}

// E[X] of the real-time approximation: p_any·(1 + E[clamp(Y, 0, n − 1)]), the clamped-normal mean
// a Φ(α) + b(1 − Φ(β)) + μ(Φ(β) − Φ(α)) + σ(φ(α) − φ(β)), α = (a − μ)/σ, β = (b − μ)/σ.
inline double realtime_mean(double n, double p) {
  const double p_any = -std::expm1(n * std::log1p(-std::min(p, 1 - 1e-16)));
  const double m = n - 1, mu = m * p, sd = std::sqrt(m * p * (1 - p));
  if (!(sd > 0)) return p_any * (1 + std::clamp(mu, 0.0, std::max(m, 0.0)));
  const double al = (0 - mu) / sd, be = (m - mu) / sd;
  const double ec = m * (1 - normal_cdf(be)) + mu * (normal_cdf(be) - normal_cdf(al)) +
                    sd * (normal_pdf(al) - normal_pdf(be));
  return p_any * (1 + ec);
}

struct BinomialError {
  double ks = 0;        // sup_x |F_exact(x) − F_approx(x)|
  double tv = 0;        // total variation (discrete approximations only; NaN otherwise)
  double mean_rel = 0;  // E[X_approx]/(np) − 1
};

// KS distance and mean error of the real-time approximation against Binomial(n, p). F_exact is a
// step function and the approximation's CDF is non-decreasing, so the supremum is reached at an
// integer k or just below k + 1: both ends of every step are compared (and the atoms at 0, 1, n
// are the jumps of realtime_cdf).
inline BinomialError realtime_error(std::uint64_t n, double p) {
  const BinomialPmf e = binomial_pmf(n, p);
  const double nd = double(n);
  BinomialError r;
  double F = 0;
  // below the window F_exact < 1e-18: compare at the window's lower end only.
  r.ks = std::abs(realtime_cdf(nd, p, double(e.lo) - 0.5));
  for (std::size_t i = 0; i < e.f.size(); ++i) {
    const double k = double(e.lo + i);
    F += e.f[i];
    r.ks = std::max(r.ks, std::abs(F - realtime_cdf(nd, p, k)));
    const double next = std::nextafter(k + 1, 0.0);
    r.ks = std::max(r.ks, std::abs(F - realtime_cdf(nd, p, std::min(next, nd))));
  }
  r.tv = std::nan("");
  r.mean_rel = realtime_mean(nd, p) / (nd * p) - 1;
  return r;
}

// The pmf of binomial_small_count (same u drives both branches): for k < K the exact f(k); past
// F(K − 1) the rounded normal quantile, j ∈ [K, n] taking u ∈ (max(F(K−1), Φ((j − ½ − μ)/σ)),
// Φ((j + ½ − μ)/σ)] (the ends j = K and j = n absorb the clamped tails). Window as binomial_pmf's.
inline BinomialError small_count_error(std::uint64_t n, double p) {
  const BinomialPmf e = binomial_pmf(n, p);
  const double nd = double(n), mu = nd * p, sd = std::sqrt(nd * p * (1 - p));
  const double K = kSmallCountTerms;
  // F(K − 1) of the exact binomial, summed over the window.
  double FK = 0;
  for (std::size_t i = 0; i < e.f.size(); ++i)
    if (double(e.lo + i) < K) FK += e.f[i];
  if (double(e.lo) >= K) FK = 0;
  auto approx_pmf = [&](double j) {
    if (j < K) return j <= nd ? -1.0 : 0.0;  // -1: exact f(j) (same as the binomial)
    if (j > nd) return 0.0;
    const double lo_u = j == K ? FK : std::max(FK, sd > 0 ? normal_cdf((j - 0.5 - mu) / sd) : 0);
    const double hi_u = j == nd ? 1.0 : (sd > 0 ? normal_cdf((j + 0.5 - mu) / sd) : 1.0);
    return std::max(0.0, hi_u - lo_u);
  };
  BinomialError r;
  // The approximation's mass below the window: the rounded normal's values j in [K, lo).
  const double lo = double(e.lo);
  const double below =
      lo > K ? std::max(0.0, (sd > 0 ? normal_cdf((lo - 0.5 - mu) / sd) : 0.0) - FK) : 0.0;
  double F = 0, A = below, mean = below * K, tv = below;
  r.ks = below;
  for (std::size_t i = 0; i < e.f.size(); ++i) {
    const double k = lo + double(i);
    const double a = approx_pmf(k) < 0 ? e.f[i] : approx_pmf(k);
    F += e.f[i];
    A += a;
    mean += k * a;
    tv += std::abs(a - e.f[i]);
    r.ks = std::max(r.ks, std::abs(F - A));
  }
  tv += std::max(0.0, 1 - A);  // the normal's mass above the window (the exact one has < 1e-18)
  r.tv = 0.5 * tv;
  r.mean_rel = mean / (nd * p) - 1;
  return r;
}

}  // namespace glintlab

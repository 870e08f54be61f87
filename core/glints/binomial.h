// Binomial counts of reflecting microfacets (the counting model of Zirr & Kaplanyan 2016 and
// Deliot & Belcour 2023, used by Kneiphof & Klein 2024 Eq. 11): an exact sampler, Deliot &
// Belcour's real-time approximation and a small-count inverse CDF, plus their exact distributions
// so that the approximations' error can be measured without sampling noise.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string_view>
#include <type_traits>

#include "core/glints/binomial_kernel.h"
#include "core/math/hash32_stream.h"
#include "core/math/ops.h"
#include "core/math/rng.h"

namespace glintlab {

// Which binomial sampler a glint model draws its count with.
enum class BinomialSampler : int {
  kExact = 0,       // binomial_exact: inverse CDF / Hörmann's BTRS, exact in double
  kRealTime = 1,    // binomial_realtime: gated Bernoulli + clamped Gaussian (Deliot & Belcour 2023)
  kSmallCount = 2,  // binomial_small_count: K-term inverse CDF, normal quantile beyond
};

namespace detail {

// log(k!) for k ≥ 0: a table to 15, then Stirling's series with three correction terms (error
// below 1e-16 relative to log k! for k ≥ 16; Abramowitz & Stegun 6.1.41).
GLINTLAB_FN double log_factorial(double k) {
  if (k < 16) return std::lgamma(k + 1);
  const double x = k + 1, ix = 1 / x, ix2 = ix * ix;
  return (x - 0.5) * std::log(x) - x + 0.91893853320467274178 +
         ix * (1.0 / 12 - ix2 * (1.0 / 360 - ix2 * (1.0 / 1260)));
}

// log(a!) − log(b!) without the cancellation of two huge numbers: for a, b ≥ 16 the Stirling
// forms are differenced term by term ((a − b)·log(a + 1) + (b + ½)·log1p((a − b)/(b + 1)) −
// (a − b) plus the difference of the corrections), so the result keeps an absolute error of
// ~1e-16 × its own size (+ (a − b)·log a) rather than of log a!. Needed by BTRS's acceptance test
// at N ~ 1e12, where log N! ≈ 3e13 would otherwise lose 3e-3 of the log-acceptance.
GLINTLAB_FN double log_factorial_ratio(double a, double b) {
  if (a < 16 || b < 16) return log_factorial(a) - log_factorial(b);
  const double xa = a + 1, xb = b + 1, d = a - b;
  auto corr = [](double x) {
    const double ix = 1 / x, ix2 = ix * ix;
    return ix * (1.0 / 12 - ix2 * (1.0 / 360 - ix2 * (1.0 / 1260)));
  };
  return d * std::log(xa) + (xb - 0.5) * std::log1p(d / xb) - d + corr(xa) - corr(xb);
}

// Sequential inverse CDF for n·p < 10 (p ≤ ½): k = min{k : u ≤ F(k)} with the pmf by its
// recurrence f(k+1) = f(k)·(n − k)/(k + 1)·p/q from f(0) = exp(n·log1p(−p)) (≥ e^-20: no
// underflow). Stops once the remaining mass is below rounding (f negligible past the mean).
GLINTLAB_FN std::uint64_t binomial_inversion(std::uint64_t n, double p, double u) {
  const double q = 1 - p, r = p / q, nd = double(n);
  double f = std::exp(nd * std::log1p(-p)), cdf = f;
  std::uint64_t k = 0;
  while (u > cdf && k < n) {
    f *= (nd - double(k)) / double(k + 1) * r;
    ++k;
    cdf += f;
    if (double(k) > nd * p + 1 && f < 1e-18 * cdf) break;  // u fell in the rounding of 1 − F
  }
  return k;
}

// Hörmann 1993, "The generation of binomial random variates", J. Statist. Comput. Simul. 46, BTRS
// (transformed rejection with squeeze), for n·p ≥ 10, p ≤ ½. Exact: the acceptance test compares
// against the pmf ratio f(k)/f(m) computed by log_factorial_ratio. Uniforms come from the stream
// (binomial_kernel.h) at dims 2j, 2j + 1 of attempt j, so the result depends only on its key.
template <class Stream>
GLINTLAB_FN std::uint64_t binomial_btrs(std::uint64_t n, double p, const Stream& stream) {
  const double nd = double(n), q = 1 - p;
  const double spq = std::sqrt(nd * p * q);
  const double b = 1.15 + 2.53 * spq;
  const double a = -0.0873 + 0.0248 * b + 0.01 * p;
  const double c = nd * p + 0.5;
  const double vr = 0.92 - 4.2 / b;
  const double alpha = (2.83 + 5.1 / b) * spq;
  const double lpq = std::log(p / q);
  const double m = std::floor((nd + 1) * p);
  for (std::uint64_t j = 0;; ++j) {
    const double u = stream.uniform(std::uint32_t(2 * j)) - 0.5;
    const double v = stream.uniform(std::uint32_t(2 * j + 1));
    const double us = 0.5 - std::abs(u);
    const double kd = std::floor((2 * a / us + b) * u + c);
    if (kd < 0 || kd > nd) continue;
    if (us >= 0.07 && v <= vr) return std::uint64_t(kd);
    const double lv = std::log(v * alpha / (a / (us * us) + b));
    // log f(k)/f(m) = log m!/k! + log (n−m)!/(n−k)! + (k − m) log(p/q)
    const double lr =
        log_factorial_ratio(m, kd) + log_factorial_ratio(nd - m, nd - kd) + (kd - m) * lpq;
    if (lv <= lr) return std::uint64_t(kd);
  }
}

}  // namespace detail

// An exact Binomial(n, p) draw from a stream of uniforms (binomial_kernel.h: dim 0 for the
// inversion, dims 2j, 2j + 1 for BTRS's attempt j): by symmetry p ≤ ½ (n − X for p > ½), then the
// inverse CDF for n·p < 10 and Hörmann's BTRS otherwise. A variable number of uniforms: on the
// CPU's batches binomial_exact_lanes is its kernel form; one scalar per thread (a device thread,
// the scalar instantiation) runs it as it is.
template <class Stream>
GLINTLAB_FN std::uint64_t binomial_exact_from(std::uint64_t n, double p, const Stream& stream) {
  if (n == 0 || !(p > 0)) return 0;
  if (p >= 1) return n;
  const bool flip = p > 0.5;
  const double pp = flip ? 1 - p : p;
  std::uint64_t k;
  if (double(n) * pp < 10)
    k = detail::binomial_inversion(n, pp, stream.uniform(0));
  else
    k = detail::binomial_btrs(n, pp, stream);
  return flip ? n - k : k;
}

// binomial_exact_from on core/math/rng.h's 64-bit counters: deterministic in (seed, index).
inline std::uint64_t binomial_exact(std::uint64_t n, double p, std::uint64_t seed,
                                    std::uint64_t index) {
  return binomial_exact_from(n, p, CounterStream<double>{seed, index});
}

// The guard that keeps log(1 − p) finite: 1e-300 in double; in float that literal rounds to 0, so
// float keeps 0 (written as 0: a float literal out of range is an error under nvcc).
template <class T>
GLINTLAB_FN T log_guard() {
  return T(sizeof(Scalar<T>) > 4 ? 1e-300 : 0.0);
}

// The standard normal quantile Φ⁻¹(u) = √2·erfinv(2u − 1).
template <class T>
GLINTLAB_FN T normal_quantile(T u) {
  return T(1.41421356237309504880) * erfinv(fma(T(2), u, T(-1)));
}

// Deliot & Belcour 2023's real-time binomial (as Kneiphof & Klein Sec. 3 and Kemppinen et al.
// Sec. 2 describe it): a gate G ~ Bernoulli(1 − (1 − p)^n) decides whether at least one facet
// reflects, and the remaining n − 1 trials are a Gaussian of mean (n − 1)p, variance
// (n − 1)p(1 − p), clamped to [0, n − 1]: X = G·(1 + clamp(Y, 0, n − 1)). X is continuous (not
// rounded), as a radiance multiplier on the GPU. u_gate and u_gauss are uniforms in [0, 1).
template <class T>
GLINTLAB_FN T binomial_realtime(T n, T p, T u_gate, T u_gauss) {
  const T one_minus_p = max(T(1) - p, T(0));
  // 1 − (1 − p)^n as −expm1(n log1p(−p)): keeps n·p when that is tiny.
  const T p_any = -expm1(n * log(max(one_minus_p, log_guard<T>())));
  const T m = max(n - T(1), T(0));
  const T y = fma(sqrt(m * p * one_minus_p),
                  normal_quantile(min(max(u_gauss, T(1e-12)), T(1) - T(1e-12))), m * p);
  const T x = T(1) + clamp(y, T(0), m);
  return select(u_gate < p_any && n >= T(1), x, T(0));
}

// Small-count inverse CDF (the approach of Zirr & Kaplanyan 2016 as Kemppinen et al. Sec. 2 and
// Deliot & Belcour summarise it: invert the binomial CDF term by term where counts are small):
// X = min{k < kTerms : u ≤ F(k)}; where u lies beyond F(kTerms − 1), the normal quantile
// round(np + √(npq)·Φ⁻¹(u)) clamped to [kTerms, n] (the same u, so X stays monotone in u). A fixed
// loop of kTerms steps with select(): a kernel. kTerms is our choice (ZK16 is not among the
// shared papers); 16 makes the inversion exact whenever F(15) ≥ u.
inline constexpr int kSmallCountTerms = 16;
template <class T>
GLINTLAB_FN T binomial_small_count(T n, T p, T u) {
  const T q = max(T(1) - p, T(0));
  T f = exp(n * log(max(q, log_guard<T>())));  // f(0) = q^n
  T cdf = f;
  T k = T(0);
  Mask<T> found = u <= cdf;
  const T r = p / max(q, log_guard<T>());
  for (int j = 1; j < kSmallCountTerms; ++j) {
    f = f * max(n - T(j - 1), T(0)) / T(j) * r;
    cdf = cdf + f;
    const Mask<T> here = (!found) && (u <= cdf);
    k = select(here, T(j), k);
    found = found || here;
  }
  const T z = normal_quantile(min(max(u, T(1e-12)), T(1) - T(1e-12)));
  const T tail = clamp(floor(fma(sqrt(n * p * q), z, n * p) + T(0.5)), T(kSmallCountTerms),
                       max(n, T(kSmallCountTerms)));
  return min(select(found, k, tail), n);
}

// One count drawn with the chosen sampler for n trials of probability p, from the hash32 stream
// of each lane's key (core/math/hash32_stream.h: hash32_key and hash32_nest; dims 0.., computed
// on the batch's own integer lanes). The exact sampler is double precision with a variable number of
// uniforms: binomial_exact_from on scalars, its masked-loop form (core/glints/binomial_kernel.h,
// the same draw per lane) on batches; the others are kernels on T.
template <class T>
GLINTLAB_FN T draw_binomial(BinomialSampler sampler, T n, T p, const HashLanes<T>& key) {
  const HashStream<T> stream{key};
  switch (sampler) {
    case BinomialSampler::kExact:
      if constexpr (std::is_floating_point_v<T>) {
        return T(binomial_exact_from(std::uint64_t(n), double(p), HashStream<double>{key}));
      } else {
        return binomial_exact_lanes(n, p, key);
      }
    case BinomialSampler::kRealTime:
      return binomial_realtime(n, p, stream.uniform(0), stream.uniform(1));
    default:
      return binomial_small_count(n, p, stream.uniform(0));
  }
}

inline constexpr std::array<std::string_view, 3> kBinomialSamplerNames = {"exact", "realtime",
                                                                          "small_count"};

}  // namespace glintlab

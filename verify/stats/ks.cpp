// Kolmogorov–Smirnov statistic and distribution; see ks.h.
#include "verify/stats/ks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace glintlab::verify {
namespace {

// The theta-function form of P(K ≤ x), accurate for small x where the alternating series for Q
// converges slowly.
double kolmogorov_cdf_small(double x) {
  const double pi = std::numbers::pi;
  const double c = -pi * pi / (8 * x * x);
  double sum = 0;
  for (int k = 1; k < 100; ++k) {
    const double j = 2.0 * k - 1;
    const double term = std::exp(c * j * j);
    sum += term;
    if (term <= 1e-17 * sum) break;
  }
  return std::sqrt(2 * pi) / x * sum;
}

double kolmogorov_sf_large(double x) {
  double sum = 0;
  for (int k = 1; k < 100; ++k) {
    const double term = std::exp(-2.0 * k * k * x * x);
    sum += (k % 2 == 1) ? term : -term;
    if (term <= 1e-17 * std::abs(sum)) break;
  }
  return std::clamp(2 * sum, 0.0, 1.0);
}

// Dense square matrix with a power-of-ten exponent kept aside, so H^n neither overflows nor
// underflows (the entries of H^n grow like n^n / n!).
struct ScaledMatrix {
  std::size_t m = 0;
  std::vector<double> a;  // row-major
  long exponent10 = 0;
  double& at(std::size_t i, std::size_t j) { return a[i * m + j]; }
  double at(std::size_t i, std::size_t j) const { return a[i * m + j]; }
};

ScaledMatrix multiply(const ScaledMatrix& x, const ScaledMatrix& y) {
  ScaledMatrix r{x.m, std::vector<double>(x.m * x.m, 0.0), x.exponent10 + y.exponent10};
  const std::size_t m = x.m;
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t l = 0; l < m; ++l) {
      const double xil = x.a[i * m + l];
      if (xil == 0) continue;
      const double* yrow = &y.a[l * m];
      double* rrow = &r.a[i * m];
      for (std::size_t j = 0; j < m; ++j) rrow[j] += xil * yrow[j];
    }
  double big = 0;
  for (double v : r.a) big = std::max(big, std::abs(v));
  if (big > 1e140) {
    for (double& v : r.a) v *= 1e-140;
    r.exponent10 += 140;
  }
  return r;
}

}  // namespace

double kolmogorov_cdf(double x) {
  if (!(x > 0)) return std::isnan(x) ? x : 0.0;
  if (x < 1) return kolmogorov_cdf_small(x);
  return 1 - kolmogorov_sf_large(x);
}

double kolmogorov_sf(double x) {
  if (!(x > 0)) return std::isnan(x) ? x : 1.0;
  if (x < 1) return 1 - kolmogorov_cdf_small(x);
  return kolmogorov_sf_large(x);
}

// Marsaglia, Tsang & Wang (2003), "Evaluating Kolmogorov's distribution", J. Stat. Softw. 8(18):
// with k = ⌊n·d⌋ + 1, m = 2k − 1, h = k − n·d, the m×m matrix
//   H_ij = [i − j + 1 ≥ 0] / (i − j + 1)!  (0-based), with the first column reduced by h^{i+1}, the
//   last row by h^{m−j}, the corner increased by (2h − 1)^m when 2h > 1,
// gives P(D_n < d) = n!/n^n · (H^n)_{k−1,k−1}.
double ks_cdf_exact(double d, std::size_t n) {
  if (std::isnan(d)) return d;
  if (n == 0) return 1.0;
  const double nd = static_cast<double>(n) * d;
  if (nd <= 0.5) return 0.0;  // D_n ≥ 1/(2n) always
  if (d >= 1) return 1.0;
  const auto k = static_cast<std::size_t>(std::floor(nd)) + 1;
  const std::size_t m = 2 * k - 1;
  const double h = static_cast<double>(k) - nd;
  ScaledMatrix H{m, std::vector<double>(m * m, 0.0), 0};
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < m; ++j)
      if (i + 1 >= j) H.at(i, j) = 1;
  for (std::size_t i = 0; i < m; ++i) {
    H.at(i, 0) -= std::pow(h, static_cast<double>(i + 1));
    H.at(m - 1, i) -= std::pow(h, static_cast<double>(m - i));
  }
  if (2 * h - 1 > 0) H.at(m - 1, 0) += std::pow(2 * h - 1, static_cast<double>(m));
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < m; ++j)
      if (i + 1 > j)
        for (std::size_t g = 1; g <= i + 1 - j; ++g) H.at(i, j) /= static_cast<double>(g);

  // Binary powering; the exponent of ten travels with each factor.
  ScaledMatrix result{m, std::vector<double>(m * m, 0.0), 0};
  for (std::size_t i = 0; i < m; ++i) result.at(i, i) = 1;
  ScaledMatrix base = H;
  for (std::size_t e = n;;) {
    if (e & 1) result = multiply(result, base);
    e >>= 1;
    if (e == 0) break;
    base = multiply(base, base);
  }
  double s = result.at(k - 1, k - 1);
  long e10 = result.exponent10;
  const double dn = static_cast<double>(n);
  for (std::size_t i = 1; i <= n; ++i) {
    s = s * static_cast<double>(i) / dn;
    if (s < 1e-140) {
      s *= 1e140;
      e10 -= 140;
    }
  }
  const double p = s * std::pow(10.0, static_cast<double>(e10));
  return std::clamp(p, 0.0, 1.0);
}

double ks_sf_asymptotic(double d, std::size_t n) {
  if (n == 0) return 1.0;
  const double dn = static_cast<double>(n), sn = std::sqrt(dn), x = sn * d;
  return kolmogorov_sf(x + 1 / (6 * sn) + (x - 1) / (4 * dn));
}

namespace {
bool exact_feasible(double d, std::size_t n) {
  const double nd = static_cast<double>(n) * d;
  if (!(nd < 1e6)) return false;
  return 2 * static_cast<std::size_t>(std::floor(nd)) + 1 <= kKsExactMaxOrder;
}
}  // namespace

double ks_sf(double d, std::size_t n) {
  if (std::isnan(d)) return d;
  if (n == 0 || d <= 0) return 1.0;
  if (d >= 1) return 0.0;
  if (exact_feasible(d, n)) return std::clamp(1.0 - ks_cdf_exact(d, n), 0.0, 1.0);
  return ks_sf_asymptotic(d, n);
}

KsResult ks_test(std::span<const double> samples, const std::function<double(double)>& cdf) {
  KsResult r;
  r.n = samples.size();
  if (r.n == 0) return r;
  std::vector<double> x(samples.begin(), samples.end());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double v : x)
    if (std::isnan(v)) {
      r.statistic = r.d_plus = r.d_minus = r.p_value = nan;
      return r;
    }
  std::sort(x.begin(), x.end());
  const double n = static_cast<double>(r.n);
  for (std::size_t i = 0; i < r.n; ++i) {
    const double f = cdf(x[i]);
    if (std::isnan(f)) {
      r.statistic = r.d_plus = r.d_minus = r.p_value = nan;
      return r;
    }
    r.d_plus = std::max(r.d_plus, static_cast<double>(i + 1) / n - f);
    r.d_minus = std::max(r.d_minus, f - static_cast<double>(i) / n);
  }
  r.statistic = std::max(r.d_plus, r.d_minus);
  r.exact = r.statistic > 0 && r.statistic < 1 && exact_feasible(r.statistic, r.n);
  r.p_value = ks_sf(r.statistic, r.n);
  return r;
}

KsResult ks_test_uniform(std::span<const double> values) {
  return ks_test(values, [](double v) { return std::clamp(v, 0.0, 1.0); });
}

}  // namespace glintlab::verify

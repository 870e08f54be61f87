// z, t and Welch tests of means; see mean_tests.h.
#include "verify/stats/mean_tests.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <vector>

namespace glintlab::verify {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The statistic and two-sided p from a difference and its standard error, with the degenerate
// zero-error case handled; dof = infinity means normal.
MeanTestResult finish(double diff, double se, double dof) {
  MeanTestResult r;
  r.estimate = diff;
  r.std_error = se;
  r.dof = dof;
  if (std::isnan(diff) || std::isnan(se) || std::isnan(dof)) {
    r.statistic = r.p_value = kNaN;
    return r;
  }
  if (se == 0) {
    r.statistic = diff == 0 ? 0.0 : std::copysign(kInf, diff);
    r.p_value = diff == 0 ? 1.0 : 0.0;
    return r;
  }
  r.statistic = diff / se;
  const double a = std::abs(r.statistic);
  if (std::isinf(dof)) {
    r.p_value = 2 * boost::math::cdf(boost::math::complement(boost::math::normal_distribution<double>(), a));
  } else {
    r.p_value = 2 * boost::math::cdf(boost::math::complement(boost::math::students_t_distribution<double>(dof), a));
  }
  r.p_value = std::min(1.0, r.p_value);
  return r;
}

}  // namespace

void MeanAccumulator::add(double x) {
  ++n;
  const double d = x - mean;
  mean += d / static_cast<double>(n);
  m2 += d * (x - mean);
}

void MeanAccumulator::merge(const MeanAccumulator& o) {
  if (o.n == 0) return;
  if (n == 0) {
    *this = o;
    return;
  }
  const double na = static_cast<double>(n), nb = static_cast<double>(o.n), nt = na + nb;
  const double d = o.mean - mean;
  mean += d * (nb / nt);
  m2 += o.m2 + d * d * (na * nb / nt);
  n += o.n;
}

double MeanAccumulator::variance() const {
  return n < 2 ? 0.0 : m2 / static_cast<double>(n - 1);
}

MeanAccumulator MeanAccumulator::from_sums(std::uint64_t n, double sum, double sum_of_squares) {
  MeanAccumulator a;
  a.n = n;
  if (n == 0) return a;
  a.mean = sum / static_cast<double>(n);
  a.m2 = std::max(0.0, sum_of_squares - sum * a.mean);
  return a;
}

MeanAccumulator accumulate_mean(const std::function<double(std::uint64_t)>& f, std::uint64_t n,
                                std::uint64_t chunk) {
  if (chunk == 0) chunk = 1;
  const std::uint64_t chunks = (n + chunk - 1) / chunk;
  std::vector<MeanAccumulator> parts(chunks);
  tbb::parallel_for(std::uint64_t(0), chunks, [&](std::uint64_t c) {
    MeanAccumulator a;
    const std::uint64_t end = std::min(n, (c + 1) * chunk);
    for (std::uint64_t i = c * chunk; i < end; ++i) a.add(f(i));
    parts[c] = a;
  });
  MeanAccumulator total;
  for (const MeanAccumulator& a : parts) total.merge(a);
  return total;
}

MeanTestResult z_test(const MeanAccumulator& a, double mu0, double sigma) {
  if (a.n == 0) return finish(kNaN, kNaN, kInf);
  return finish(a.mean - mu0, sigma / std::sqrt(static_cast<double>(a.n)), kInf);
}

MeanTestResult z_test(const MeanAccumulator& a, double mu0) {
  if (a.n < 2) return finish(kNaN, kNaN, kInf);
  return finish(a.mean - mu0, std::sqrt(a.variance() / static_cast<double>(a.n)), kInf);
}

MeanTestResult t_test(const MeanAccumulator& a, double mu0) {
  if (a.n < 2) return finish(kNaN, kNaN, kNaN);
  return finish(a.mean - mu0, std::sqrt(a.variance() / static_cast<double>(a.n)),
                static_cast<double>(a.n - 1));
}

MeanTestResult welch_t_test(const MeanAccumulator& a, const MeanAccumulator& b) {
  if (a.n < 2 || b.n < 2) return finish(kNaN, kNaN, kNaN);
  const double va = a.variance() / static_cast<double>(a.n);
  const double vb = b.variance() / static_cast<double>(b.n);
  const double v = va + vb;
  // Welch–Satterthwaite: (va + vb)² / (va²/(na − 1) + vb²/(nb − 1)).
  const double denom = va * va / static_cast<double>(a.n - 1) + vb * vb / static_cast<double>(b.n - 1);
  const double dof = denom > 0 ? v * v / denom : kInf;
  return finish(a.mean - b.mean, std::sqrt(v), dof);
}

double normal_quantile(double p) { return boost::math::quantile(boost::math::normal(), p); }

double student_t_quantile(double p, double dof) {
  return boost::math::quantile(boost::math::students_t(dof), p);
}

}  // namespace glintlab::verify

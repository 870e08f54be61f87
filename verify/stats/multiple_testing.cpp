// Holm–Šidák and Šidák combinations; see multiple_testing.h.
#include "verify/stats/multiple_testing.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace glintlab::verify {

double sidak(double p_min, std::size_t k) {
  if (std::isnan(p_min)) return 1.0;
  if (k == 0) return 1.0;
  p_min = std::clamp(p_min, 0.0, 1.0);
  if (p_min >= 1.0) return 1.0;
  return std::min(1.0, -std::expm1(static_cast<double>(k) * std::log1p(-p_min)));
}

double sidak_min(std::span<const double> p) {
  if (p.empty()) return 1.0;
  double m = 1.0;
  for (double q : p) m = std::min(m, std::isnan(q) ? 1.0 : q);
  return sidak(m, p.size());
}

double sidak_level(double alpha, std::size_t k) {
  if (k == 0) return alpha;
  return -std::expm1(std::log1p(-alpha) / static_cast<double>(k));
}

HolmSidakResult holm_sidak(std::span<const double> p, double alpha) {
  HolmSidakResult r;
  r.alpha = alpha;
  r.raw.assign(p.begin(), p.end());
  const std::size_t m = p.size();
  auto clean = [&](std::size_t i) { return std::isnan(p[i]) ? 1.0 : std::clamp(p[i], 0.0, 1.0); };
  std::vector<std::size_t> order(m);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return clean(a) < clean(b); });
  r.adjusted.assign(m, 1.0);
  r.reject.assign(m, false);
  double running = 0;
  for (std::size_t j = 0; j < m; ++j) {
    running = std::max(running, sidak(clean(order[j]), m - j));
    r.adjusted[order[j]] = running;
  }
  for (std::size_t i = 0; i < m; ++i) {
    r.reject[i] = r.adjusted[i] <= alpha;
    r.rejections += r.reject[i] ? 1 : 0;
  }
  return r;
}

}  // namespace glintlab::verify

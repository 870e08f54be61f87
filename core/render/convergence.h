// RMSE of a Monte Carlo estimator against a reference as a function of samples per pixel (the
// RMSE-vs-spp log-log plots of Kemppinen et al. 2025 Fig. 7 and Eto & Tokuyoshi 2023 Fig. 4),
// from one stream of independent samples per pixel cut into batches, and its log-log slope.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace glintlab {

struct RmseAtSpp {
  int spp = 0;
  double rmse = 0;       // √(mean over pixels and batches of (batch mean − reference)²)
  double std_error = 0;  // of rmse, by the delta method from the spread of the squared errors
  std::size_t batches = 0;
};

// Squared errors of s-spp batch means against the reference, summed: what an RmseAtSpp is
// computed from. Sums of disjoint sets of batches add, so they can be kept per row of an image
// and added in row order (deterministic for any thread count).
struct BatchErrorSums {
  double sum = 0, sum2 = 0;  // of e² and of e⁴
  std::size_t batches = 0;
  void add(double e2) {
    sum += e2;
    sum2 += e2 * e2;
    ++batches;
  }
  void add(const BatchErrorSums& o) {
    sum += o.sum;
    sum2 += o.sum2;
    batches += o.batches;
  }
};

inline RmseAtSpp rmse_from_batch_errors(int spp, const BatchErrorSums& e) {
  RmseAtSpp r;
  r.spp = spp;
  r.batches = e.batches;
  if (e.batches > 0) {
    const double m = double(e.batches), mse = e.sum / m;
    const double var = e.batches > 1 ? std::max(0.0, (e.sum2 - m * mse * mse) / (m - 1)) : 0;
    r.rmse = std::sqrt(mse);
    r.std_error = r.rmse > 0 ? std::sqrt(var / m) / (2 * r.rmse) : 0;
  }
  return r;
}

// For each spp s: pixel p's samples x_p[0..n_p) are cut into ⌊n_p/s⌋ disjoint batches of s
// consecutive samples, each batch mean an independent s-spp estimate; the squared errors against
// ref[p] are averaged over every batch of every pixel in index order (deterministic).
inline std::vector<RmseAtSpp> rmse_at_spp(const std::vector<std::vector<double>>& samples,
                                          const std::vector<double>& ref,
                                          const std::vector<int>& spps) {
  std::vector<RmseAtSpp> out;
  for (int s : spps) {
    BatchErrorSums e;
    for (std::size_t p = 0; p < samples.size(); ++p) {
      const std::size_t nb = samples[p].size() / std::size_t(s);
      for (std::size_t b = 0; b < nb; ++b) {
        double mean = 0;
        for (int k = 0; k < s; ++k) mean += samples[p][b * std::size_t(s) + std::size_t(k)];
        e.add((mean / s - ref[p]) * (mean / s - ref[p]));
      }
    }
    out.push_back(rmse_from_batch_errors(s, e));
  }
  return out;
}

// Least-squares slope of log RMSE against log spp (−½ for an unbiased estimator whose reference
// error is negligible; flattening toward 0 where a bias dominates). NaN with fewer than 2 points.
inline double loglog_slope(const std::vector<RmseAtSpp>& r) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (const RmseAtSpp& a : r) {
    if (!(a.rmse > 0)) continue;
    const double lx = std::log(double(a.spp)), ly = std::log(a.rmse);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, n += 1;
  }
  if (n < 2) return std::nan("");
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace glintlab

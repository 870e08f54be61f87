// Calibration of statistical checks over derived seeds; see calibration.h.
#include "verify/calibration.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <boost/math/distributions/beta.hpp>
#include <algorithm>
#include <cmath>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "verify/stats/ks.h"

namespace glintlab::verify {

std::uint64_t calibration_seed(const std::string& id, std::uint64_t run) {
  return check_seed(id + "#calibration", run);
}

void clopper_pearson(std::size_t successes, std::size_t trials, double confidence, double& low,
                     double& high) {
  const double a = (1 - confidence) / 2;
  const auto k = static_cast<double>(successes), n = static_cast<double>(trials);
  // The exact interval from Beta quantiles: low = B⁻¹(a; k, n − k + 1), high = B⁻¹(1 − a; k + 1, n − k).
  low = successes == 0 ? 0.0 : boost::math::quantile(boost::math::beta_distribution<>(k, n - k + 1), a);
  high = successes == trials ? 1.0
                             : boost::math::quantile(boost::math::beta_distribution<>(k + 1, n - k), 1 - a);
}

CalibrationResult calibrate(const std::string& id, const std::function<double(std::uint64_t)>& test,
                            std::size_t runs, double level, double confidence,
                            const std::function<void()>& on_run) {
  if (runs < 2) throw std::invalid_argument(fmt::format("--runs: {} is out of range (2 or more)", runs));
  if (!(level > 0 && level < 1))
    throw std::invalid_argument(fmt::format("--level: {} is out of range (0, 1)", level));
  CalibrationResult r;
  r.id = id;
  r.runs = runs;
  r.level = level;
  r.confidence = confidence;
  r.p_values.resize(runs);
  r.seeds.resize(runs);
  std::mutex progress;
  tbb::parallel_for(std::size_t(0), runs, [&](std::size_t i) {
    r.seeds[i] = calibration_seed(id, i);
    r.p_values[i] = test(r.seeds[i]);
    if (on_run) {
      const std::lock_guard<std::mutex> lock(progress);
      on_run();
    }
  });
  std::vector<double> finite;
  for (double p : r.p_values) {
    if (!std::isfinite(p) || p < 0 || p > 1) {
      ++r.non_finite;
      continue;
    }
    finite.push_back(p);
    if (p < level) ++r.rejections;
  }
  r.rate = double(r.rejections) / double(runs);
  clopper_pearson(r.rejections, runs, confidence, r.rate_low, r.rate_high);
  const KsResult ks = ks_test_uniform(finite);
  r.ks_statistic = ks.statistic;
  r.ks_p_value = ks.p_value;
  r.ks_plus_p_value = ks_one_sided_sf(ks.d_plus, finite.size());
  const double alpha = 1 - confidence;
  r.calibrated = r.non_finite == 0 && level >= r.rate_low && level <= r.rate_high &&
                 r.ks_p_value >= alpha;
  r.valid = r.calibrated ||
            (r.non_finite == 0 && level >= r.rate_low && r.ks_plus_p_value >= alpha);
  return r;
}

CalibrationResult calibrate(const Check& check, std::size_t runs, double level, double confidence,
                            const std::function<void()>& on_run) {
  if (!is_statistical(check))
    throw std::invalid_argument(fmt::format(
        "--calibrate: '{}' is a deterministic check (an error bound, no p-value) and has nothing to "
        "calibrate",
        check.id));
  return calibrate(check.id, check.calibration, runs, level, confidence, on_run);
}

double ks_one_sided_sf(double d, std::size_t n) {
  if (n == 0 || d <= 0) return 1;
  if (d >= 1) return 0;
  const double nn = double(n);
  double sum = 0;
  const auto jmax = std::size_t(std::floor(nn * (1 - d)));
  for (std::size_t j = 0; j <= jmax; ++j) {
    const double jj = double(j);
    const double a = 1 - d - jj / nn;
    if (a <= 0) continue;
    const double log_term = std::lgamma(nn + 1) - std::lgamma(jj + 1) - std::lgamma(nn - jj + 1) +
                            (nn - jj) * std::log(a) + (jj - 1) * std::log(d + jj / nn);
    sum += std::exp(log_term);
  }
  return std::clamp(d * sum, 0.0, 1.0);
}

std::string to_json(const CalibrationResult& r) {
  const nlohmann::json j = {{"id", r.id},
                            {"runs", r.runs},
                            {"level", r.level},
                            {"confidence", r.confidence},
                            {"rejections", r.rejections},
                            {"false_positive_rate", r.rate},
                            {"rate_interval", {r.rate_low, r.rate_high}},
                            {"ks_statistic", r.ks_statistic},
                            {"ks_p_value", r.ks_p_value},
                            {"non_finite", r.non_finite},
                            {"ks_plus_p_value", r.ks_plus_p_value},
                            {"calibrated", r.calibrated},
                            {"valid", r.valid},
                            {"status", r.status()},
                            {"p_values", r.p_values},
                            {"seeds", r.seeds}};
  return j.dump(2) + "\n";
}

std::string summary(const CalibrationResult& r) {
  return fmt::format(
      "{}: {} runs, false-positive rate at level {:g} = {}/{} = {:.4f}, {:g} % interval [{:.4f}, "
      "{:.4f}] ({} the nominal rate); KS uniformity of p-values D = {:.4f}, p = {:.3g}; one-sided "
      "(too many small p) p = {:.3g}{} → {}",
      r.id, r.runs, r.level, r.rejections, r.runs, r.rate, 100 * r.confidence, r.rate_low,
      r.rate_high,
      (r.level >= r.rate_low && r.level <= r.rate_high) ? "contains" : "EXCLUDES", r.ks_statistic,
      r.ks_p_value, r.ks_plus_p_value,
      r.non_finite ? fmt::format("; {} non-finite p-values", r.non_finite) : "", r.status());
}

}  // namespace glintlab::verify

// Calibration of a statistical check: run its test on a known-correct input over many derived seeds
// and measure whether its p-values are uniform (Kolmogorov–Smirnov) and whether its false-positive
// rate at a nominal level is what the level promises.
//
// Under the null hypothesis a calibrated test's p-value is uniform on [0, 1], so the number of runs
// with p < level is Binomial(runs, level). The measured rate is reported with its two-sided
// Clopper–Pearson interval (confidence `confidence`, 99 % by default).
//
// Three outcomes, at significance 1 − confidence each:
//   * calibrated: the nominal level lies inside the rate's interval and the two-sided KS test does
//     not reject uniformity of the p-values;
//   * conservative (valid): the p-values are not uniform, but only because they are too large —
//     the one-sided KS test for too many small p-values (D+, Smirnov's exact one-sided
//     distribution, Birnbaum & Tingey 1951) does not reject, nor is the rate above its interval.
//     A Šidák-combined minimum over positively dependent tests (the two chi-square resolutions) or
//     a discrete test is conservative by construction: its false-positive rate is below nominal,
//     its power a little lower than an exact combination's;
//   * anti-conservative (broken): too many small p-values (D+ rejects, or the nominal level is
//     below the rate's interval), or a NaN/out-of-range p-value.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "verify/check.h"

namespace glintlab::verify {

struct CalibrationResult {
  std::string id;
  std::size_t runs = 0;
  double level = 0.05;          // nominal level the false-positive rate is measured at
  double confidence = 0.99;     // of the interval around the measured rate
  std::size_t rejections = 0;   // runs with p < level
  double rate = 0;              // rejections / runs
  double rate_low = 0, rate_high = 1;  // Clopper–Pearson interval of the rate
  double ks_statistic = 0;
  double ks_p_value = 1;        // uniformity of the p-values
  std::size_t non_finite = 0;   // runs that returned a NaN/inf p-value (a broken test)
  double ks_plus_p_value = 1;   // one-sided: too many small p-values
  bool calibrated = false;      // uniform: level inside [rate_low, rate_high], KS p ≥ 1 − confidence
  bool valid = false;           // calibrated or conservative: the false-positive rate is not above nominal
  const char* status() const {
    return calibrated ? "calibrated" : valid ? "conservative" : "ANTI-CONSERVATIVE";
  }
  std::vector<double> p_values; // in run order
  std::vector<std::uint64_t> seeds;
};

// The seed of calibration run `run` of check `id`: derived like every other seed, from a name that
// no check run uses, so calibration never reuses the suite's own draws.
std::uint64_t calibration_seed(const std::string& id, std::uint64_t run);

// Runs `test(seed)` for runs 0..runs−1 (in parallel over runs; each result stored by run index, so
// the outcome is identical for any thread count) and evaluates the p-values. `on_run` is called
// after each run, from worker threads but never concurrently (for progress).
CalibrationResult calibrate(const std::string& id, const std::function<double(std::uint64_t)>& test,
                            std::size_t runs, double level = 0.05, double confidence = 0.99,
                            const std::function<void()>& on_run = {});

// The same for a registered check; the check must be statistical (is_statistical).
CalibrationResult calibrate(const Check& check, std::size_t runs, double level = 0.05,
                            double confidence = 0.99, const std::function<void()>& on_run = {});

// Two-sided Clopper–Pearson interval for a binomial proportion: successes out of trials at the
// given confidence.
void clopper_pearson(std::size_t successes, std::size_t trials, double confidence, double& low,
                     double& high);

// P(D+_n ≥ d) for the one-sided KS statistic D+ = max_i (i/n − F(x_(i))) of n uniform samples:
// Birnbaum & Tingey (1951), d Σ_{j=0}^{⌊n(1−d)⌋} C(n, j) (1 − d − j/n)^{n−j} (d + j/n)^{j−1},
// summed in logarithms.
double ks_one_sided_sf(double d, std::size_t n);

std::string to_json(const CalibrationResult& r);
std::string summary(const CalibrationResult& r);  // one line

}  // namespace glintlab::verify

// Cheap probes of what the claims in smooth_consistency.cpp and eto.cpp decide: each
// runs one check's statistic on one correct and one deliberately wrong input, at a small size, so
// tests can assert that the correct input passes and the control is rejected without running the
// whole check.
#pragma once

#include <cstddef>

namespace glintlab::verify {

struct ControlProbe {
  double correct = 0;    // the statistic on the correct input (p-value, or error)
  double control = 0;    // the same statistic on the deliberately wrong input
  double threshold = 0;  // the check's level (statistical) or tolerance (deterministic)
  bool statistical = false;
  bool correct_passes() const { return statistical ? correct > threshold : correct <= threshold; }
  bool control_rejected() const { return statistical ? control <= threshold : control > threshold; }
};

// smooth.eval-pdf-consistency for one sampler of sampler_table(): control 0 = the pdf recomputed
// with α × 1.02, control 1 = G1(ωi) dropped from eval.
ControlProbe probe_eval_pdf_consistency(std::size_t sampler, int control);
// eto.unbiased, one configuration: smallest of the Welch and one-sample p; control pdf × 1.02.
ControlProbe probe_eto_unbiased();
// eto.bound-is-infimum, one configuration: |searched infimum − (−k î_z)|; control k × 0.97.
ControlProbe probe_eto_bound_is_infimum();
// eto.fewer-rejections at α = 1, θi = 0: binomial p against ½; control: against 0.52.
ControlProbe probe_eto_fewer_rejections();
// eto.variance-rough at α = 1, θi = 0: minus the lower end of the measured RMSE-reduction
// interval against −5 %; control: a 2 % RMSE reduction (the caps sampler against an independent
// run of itself with its RMSE × 0.98).
ControlProbe probe_eto_variance_rough();
// eto.backfacing-stable-pdf on a small grid: max relative error of the stable form; control: the
// stable form × 1.02.
ControlProbe probe_eto_backfacing_stable_pdf();

}  // namespace glintlab::verify

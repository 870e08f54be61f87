// Cheap probes of what the claims in smooth_consistency.cpp decide: each runs one check's
// statistic on one correct and one deliberately wrong input, at a small size, so
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

}  // namespace glintlab::verify

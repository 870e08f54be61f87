// Cheap probes of what a check decides (verify/claims/kemppinen_probes.h): each runs one check's
// statistic on one correct and one deliberately wrong input, at a small size, so tests can assert
// that the correct input passes and the control is rejected without running the whole check.
#pragma once

namespace glintlab::verify {

struct ControlProbe {
  double correct = 0;    // the statistic on the correct input (p-value, or error)
  double control = 0;    // the same statistic on the deliberately wrong input
  double threshold = 0;  // the check's level (statistical) or tolerance (deterministic)
  bool statistical = false;
  bool correct_passes() const { return statistical ? correct > threshold : correct <= threshold; }
  bool control_rejected() const { return statistical ? control <= threshold : control > threshold; }
};

}  // namespace glintlab::verify

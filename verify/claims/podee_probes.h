// Cheap probes of what the podee.* claims (verify/claims/podee.cpp) decide, on small inputs, so
// tests can assert that the correct input passes and each negative control is rejected.
#pragma once

#include "verify/check.h"
#include "verify/claims/control_probes.h"

namespace glintlab::verify {

// podee.brightest-vector on `configs` bilinear reflection spaces: the largest excess of the
// selected point's distance over the brute-force minimum (in quad sizes); control: the selected
// point moved 2 % of the quad size towards the quad's centroid. Threshold: the tolerance.
ControlProbe probe_podee_brightest_vector(int configs);
// podee.rmse's measure and decide at one distance on a `size`² crop (the regime then covers it):
// the genuine verdict; with an independent 64-spp reference × 1.03 in place of both baselines
// (must fail); with it in place of the method (must hold).
struct PodeeRmseProbe {
  Verdict genuine, baselines_near_truth, method_near_truth;
};
PodeeRmseProbe probe_podee_rmse(double distance, int size);
// podee.stability: flicker(podee) / flicker(centre) over `frames` frames (passes below 1);
// control: flicker(podee) / the flicker of a near-truth pan (a 64-spp reference × 1.03).
ControlProbe probe_podee_stability(int size, int frames);

}  // namespace glintlab::verify

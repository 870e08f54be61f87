// Error metrics shared by every experiment, over a set of channels and an optional pixel mask.
//
// rmse:    √( Σ (x − r)² / K ), K = number of (pixel, channel) values compared.
// rel_mse: Σ (x − r)² / (r² + ε) / K with ε = 0.01: the relative MSE of Rousselle, Knaus &
//          Zwicker 2011 ("Adaptive sampling and reconstruction using greedy error minimization",
//          Sec. 6), ε keeping dark pixels from dominating.
// No FLIP-like perceptual error: FLIP (Andersson et al. 2020) is defined by its specific
// contrast-sensitivity filters in YyCxCz, a Hunt-adjusted L*a*b* colour difference and a
// feature (edge/point) detector, all tied to an assumed viewing distance and display; a
// "FLIP-like" variant without those pieces measures nothing FLIP's validation supports, and the
// full definition could not be checked against the reference implementation here (no copy, no
// test vectors), so glintlab reports RMSE and relMSE only.
// Sums run serially in pixel order, so a metric is bit-identical for any thread count.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/render/image.h"

namespace glintlab {

struct MetricOptions {
  std::vector<std::string> channels = {"R", "G", "B"};
  const std::vector<std::uint8_t>* mask = nullptr;  // non-zero = compared; null = every pixel
};

inline constexpr double kRelMseEpsilon = 0.01;

// Both images must have the same size and the named channels; throws std::invalid_argument
// otherwise, or when the mask selects no pixel.
double rmse(const Image& x, const Image& ref, const MetricOptions& options = {});
double rel_mse(const Image& x, const Image& ref, const MetricOptions& options = {});

}  // namespace glintlab

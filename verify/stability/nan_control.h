// The negative controls of the all.* stability checks: copies of registered models, each wrong in
// one way that a working sweep must find inside the core domain (so the check's verdict becomes
// `fails`), or corrected in one way where the genuine verdict is `fails`.
#pragma once

#include <string_view>

#include "core/model_registry.h"

namespace glintlab::verify::stability {

inline constexpr double kNanControlAlpha = 0.01;
inline constexpr double kSparseNanRate = 5e-4;     // the share of eval calls the sparse copy breaks
inline constexpr double kGainControlScale = 1.03;  // the energy-gain copy's value scale
inline constexpr double kProbabilityControlScale = 1.05;  // the probability copy's p scale
inline constexpr double kSpikeRate = 2e-3;   // the heavy-tailed copy's share of spiked samples
inline constexpr double kSpikeWeight = 300;  // and their weight scale (rate × weight < 1)

// smooth_ggx with value × √(αx − 0.01)/√(αx − 0.01): NaN for αx < 0.01, exactly 1 elsewhere
// ("nan_control_ggx"; the sweep's own test of where it finds a failure region).
const ModelEntry& nan_control_model();
// smooth_ggx whose eval value is NaN in about kSparseNanRate of calls, picked by a hash of the
// query's directions ("sparse_nan_ggx"): a defect as rare as the one a sweep must not miss.
const ModelEntry& sparse_nan_control_model();
// smooth_ggx with its value and sample weight × kGainControlScale ("gain_control_ggx").
const ModelEntry& gain_control_model();
// smooth_ggx whose sample weight is × kSpikeWeight in about kSpikeRate of samples (picked by a
// hash of u) and scaled down elsewhere to keep its mean ("spike_control_ggx"): a variance blow-up.
const ModelEntry& spike_control_model();
// `base` with every probability intermediate (p, p_*) × kProbabilityControlScale (scale > 1), or
// clamped to [0, 1] (scale = 0): the probability check's control.
ModelEntry probability_control_model(std::string_view base, double scale);

}  // namespace glintlab::verify::stability

// The negative control of all.stability: a deliberately broken copy of the registered smooth_ggx
// model whose eval value carries a normalisation written as √(αx − 0.01)/√(αx − 0.01) — NaN for
// αx < 0.01, exactly 1 elsewhere — inside the core domain, so a working sweep must find NaN and
// the verdict must be `fails`.
#pragma once

#include "core/model_registry.h"

namespace glintlab::verify::stability {

inline constexpr double kNanControlAlpha = 0.01;

// The broken entry, named "nan_control_ggx" (not registered).
const ModelEntry& nan_control_model();

}  // namespace glintlab::verify::stability

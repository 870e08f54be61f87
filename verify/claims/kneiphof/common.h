// What Kneiphof & Klein's claims share: the paper's name, the roughness grid of the
// binomial-counting claims, and the scene of kneiphof.subdivision and kneiphof.convergence (a
// square light above the shading point, the viewer at 30°). The LTC claim's cells are
// ltc_cells.h.
#pragma once

#include <array>
#include <string_view>

#include "core/math/vec.h"

namespace glintlab::verify::kneiphof_claims {

inline constexpr std::string_view kPaper = "Kneiphof & Klein 2024";

// √α = 0.1, 0.5, 0.9: discrete-ndf-mean's quick grid and convergence's roughnesses.
inline constexpr double kNdfAlphas[] = {0.01, 0.25, 0.81};

// A square of half-width `w` centred at (0.3, 0, 1), counter-clockwise seen from below (it emits
// downward, towards the shading point at the origin).
std::array<Vec3<double>, 4> quad_above(double w);
// The viewer at θ = 30°, opposite the light's offset.
Vec3<double> view_30();

}  // namespace glintlab::verify::kneiphof_claims

// The Kemppinen et al. 2025 setting shared by the kemppinen.* claims and the kemppinen2025-*
// figures: the glint parameters they all start from, and a footprint sized in level-0 cells.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/glints/kemppinen.h"

namespace glintlab::kemppinen2025 {

// Density 1e4 points per unit uv, isotropic, filter f = 0.5, roulette blending (Eq. 8), exact erf
// (Eq. 10), the corrected normalisation, white facets; `side` = √k neighbours per axis.
inline Params<double> preset_params(int side, double alpha_star, std::uint64_t seed) {
  Params<double> p{};
  p.density = 1e4;
  p.microroughness = alpha_star;
  p.anisotropy = 1;
  p.filter = 0.5;
  p.side = side;
  p.blend = Blend::kRoulette;
  p.erf = Erf::kExact;
  p.normalization = Normalization::kCorrected;
  p.colors = Colors::kWhite;
  p.seed = seed;
  return p;
}

// A footprint at uv whose filter standard deviation is `cells` level-0 cells (LOD λ = log2(2
// cells)): Σ_s = f² J Jᵀ with J = d·I.
inline FootprintQuery<double> footprint_cells(Vec2<double> uv, double cells,
                                              const Params<double>& p) {
  const double d = cells / std::sqrt(p.density) / p.filter;
  return {uv, {d, 0}, {0, d}};
}

}  // namespace glintlab::kemppinen2025

// Random kernel inputs over each Domain's edge cases, for the equivalence tests and benchmarks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace glintlab::simd {

// One column per entry of `domains` (core/simd/kernels.h Domain, as int), n rows; row i depends
// only on (seed, i). Drawn per row:
//   roughness: α log-uniform in [1e-3, 2]; 30 % isotropic, else αy = αx · 10^U(−3, 3) clamped
//     to [1e-3, 2] (anisotropy up to 1:1000);
//   wi: 40 % cosθ uniform in (0, 1], 25 % grazing θ in [80°, 89.9°], 20 % back-facing
//     (cosθ in [−1, 0)), 5 % exactly +z, 10 % θ in [89.9°, 90°);
//   m: 50 % drawn from the row's GGX NDF (Walter's sampler), 30 % uniform on the upper
//     hemisphere, 20 % uniform on the sphere;
//   wo: 50 % the mirror of wi about the NDF-drawn m, 50 % uniform on the sphere;
//   u1, u2: 95 % uniform in [0, 1), 5 % one of the edges 0, 2^-24, ½, 1 − 2^-24;
//   p: uniform on the map's disk (radius ½ at (½, ½)), 10 % within 1e-4 of its rim;
//   F0 in [0, 1], η in [0.2, 3], κ in [0, 5].
std::vector<std::vector<double>> make_inputs(std::span<const int> domains, std::size_t n,
                                             std::uint64_t seed);

// The scene columns a model with ModelNeeds `needs` (core/model.h) reads, written into `query`:
// the kQueryColumnsWithCorners columns of core/simd/model_batch.h, n rows each, whose ω_o
// (columns 9–11) is already set and is taken as the light's centre. Row i depends only on
// (seed, i, its ω_o). Drawn per row:
//   footprint (kNeedsFootprint): uv uniform in [0, 4) (5 % exactly 0); Jacobian columns of
//     lengths s, s·t (t log-uniform in [0.1, 10]) at angles a, b (b − a in [0.2, 2.9] rad) with
//     the area log-uniform in [1e-14, 1e-2] (with 10^density ∈ [1, 1e15], N_P runs from 0 through
//     the inverse-CDF range to 1e13, the BTRS range), 4 % zero area;
//   light (kNeedsPointLight, kNeedsAreaLight): 20 % a delta (cos γ = 1), else the cone's
//     half-angle γ log-uniform in [1e-4, 0.5] rad;
//   corners (kNeedsPixelCorners): 80 % a jittered quad of half-size log-uniform in [1e-4, 0.3]
//     around the light's centre, shifted off it by up to 3 half-sizes; 5 % all four at the
//     centre, 5 % all four at one random direction (degenerate quads), 10 % four directions
//     uniform on the sphere (r·l < 0 included).
void add_scene_columns(unsigned needs, std::vector<std::vector<double>>& query, std::uint64_t seed);

}  // namespace glintlab::simd

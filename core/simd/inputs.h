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

}  // namespace glintlab::simd

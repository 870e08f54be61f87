// The fixed query set of the device check: n rows of query columns (core/model_layout.h order) and
// the sampler's uniforms, drawn from counter-based random numbers (core/math/rng.h) so that any
// machine draws the same set. The device check writes the set it ran beside its results, and the
// CPU comparison reads it from there (a host's sin/cos may differ by an ulp between C libraries).
//
// Half of the rows put ω_o near the mirror direction of ω_i (within about 10°), where a lobe's
// value, pdf and intermediates are non-zero and their rounding is what the comparison sees; the
// other half spread ω_o over the upper hemisphere (and a few below it: the models' zero branch).
// Every row also carries a disk light of 0.5° to 5° half-angle about ω_o and four pixel-corner
// reflection vectors (read only by Podee et al.'s model): on the near-mirror rows the corners
// surround ω_o (a pixel that sees the light), on the others they surround the mirror direction.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/math/orthonormal_basis.h"
#include "core/math/rng.h"
#include "core/model_layout.h"

namespace glintlab::gpu {

struct QuerySet {
  std::size_t rows = 0;
  // columns[k][i]: column k of kQueryLayout for row i.
  std::vector<std::vector<double>> columns;
  std::vector<double> u1, u2;  // the sampler's uniforms, in [0, 1)
};

inline QuerySet make_query_set(std::size_t rows, std::uint64_t seed) {
  constexpr double kPi = 3.14159265358979323846;
  QuerySet set;
  set.rows = rows;
  set.columns.assign(kQueryLayout.size(), std::vector<double>(rows));
  set.u1.resize(rows);
  set.u2.resize(rows);
  const auto spherical = [](double cos_theta, double phi) {
    const double sin_theta = std::sqrt(std::fmax(0.0, 1.0 - cos_theta * cos_theta));
    return Vec3<double>{sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
  };
  for (std::size_t i = 0; i < rows; ++i) {
    const auto u = [&](std::uint64_t dim) { return counter_uniform<double>(seed, i, dim); };
    ModelQuery<double> q{};
    // ω_i up to 85° from the normal.
    q.wi = spherical(1.0 - u(0) * (1.0 - std::cos(85.0 * kPi / 180.0)), 2.0 * kPi * u(1));
    if (i % 2 == 0) {
      // Near the mirror direction: the mirror vector tilted by up to ~10° and renormalised.
      const Vec3<double> r{-q.wi.x, -q.wi.y, q.wi.z};
      const Vec3<double> d{(u(2) - 0.5) * 0.35, (u(3) - 0.5) * 0.35, (u(4) - 0.5) * 0.35};
      const Vec3<double> w{r.x + d.x, r.y + d.y, r.z + d.z};
      const double len = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
      q.wo = Vec3<double>{w.x / len, w.y / len, w.z / len};
    } else {
      // Uniform in z over [-0.1, 1): mostly the upper hemisphere, a few rows just below it.
      q.wo = spherical(-0.1 + 1.1 * u(2), 2.0 * kPi * u(3));
    }
    // A footprint of 1e-4 to 1e-2 of the texture per pixel about a point in the unit square, and
    // the default light (delta, intensity 1): read only by the models that need them.
    q.footprint.uv = Vec2<double>{u(5), u(6)};
    const double scale = std::pow(10.0, -4.0 + 2.0 * u(7));
    q.footprint.duv_dx = Vec2<double>{scale, 0.25 * scale * (u(8) - 0.5)};
    q.footprint.duv_dy = Vec2<double>{0.25 * scale * (u(9) - 0.5), scale};
    q.light = LightQuery<double>{std::cos((0.5 + 4.5 * u(12)) * kPi / 180.0), 1.0};
    // Pixel corners (core/scene/footprint.h's order) 0.2° to 10° about a centre, each jittered.
    const Vec3<double> mirror{-q.wi.x, -q.wi.y, q.wi.z};
    const OrthonormalBasis<double> frame = basis_from_z(i % 2 == 0 ? q.wo : mirror);
    const double spread = std::tan((0.2 + 9.8 * u(13)) * kPi / 180.0);
    for (int c = 0; c < 4; ++c) {
      const double sx = (c % 2 == 0 ? -1.0 : 1.0) * spread * (1.0 + 0.3 * (u(14 + 2 * c) - 0.5));
      const double sy = (c < 2 ? -1.0 : 1.0) * spread * (1.0 + 0.3 * (u(15 + 2 * c) - 0.5));
      const Vec3<double> w = frame.to_world(Vec3<double>{sx, sy, 1.0});
      const double len = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
      q.footprint.corner_r[std::size_t(c)] = Vec3<double>{w.x / len, w.y / len, w.z / len};
    }
    const QueryRow<double> row = to_row(q);
    for (std::size_t k = 0; k < row.size(); ++k) set.columns[k][i] = row[k];
    set.u1[i] = u(10);
    set.u2[i] = u(11);
  }
  return set;
}

}  // namespace glintlab::gpu

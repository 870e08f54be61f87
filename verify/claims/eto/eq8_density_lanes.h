// Eq8ReflectionPdf's density over rows of directions in double lanes W (a Wide of an xsimd batch):
// eq8_front_density for i_z > 0, Eq. 7 (pdf_vndf_backfacing_eq7) otherwise; for the per-ISA units
// eq8_density_{sse42,avx2,avx512}.cpp, each compiled with its ISA's flags and without contraction,
// so the lanes round as the scalar density does.
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>

#include "core/simd/wide.h"
#include "verify/claims/eto/eq8_density.h"

namespace glintlab::verify::eto_claims {

template <class W>
void eq8_density_lanes(const Eq8Incidence& a, std::span<const Vec3<double>> wo,
                             std::span<double> out) {
  constexpr std::size_t kLanes = W::kLanes;
  using Lanes = LaneAccess<W>;
  const GGX<W> g{W(a.ax), W(a.ay)};
  const Vec3<W> i{W(a.i.x), W(a.i.y), W(a.i.z)};
  const Vec3<W> i_std{W(a.i_std.x), W(a.i_std.y), W(a.i_std.z)};
  const W k(a.k), t(a.t);
  alignas(64) double x[kLanes], y[kLanes], z[kLanes], d[kLanes];
  for (std::size_t begin = 0; begin < wo.size(); begin += kLanes) {
    const std::size_t n = std::min(kLanes, wo.size() - begin);
    // The last rows padded with the last direction; only the first n lanes are written out.
    for (std::size_t l = 0; l < kLanes; ++l) {
      const Vec3<double>& w = wo[begin + std::min(l, n - 1)];
      x[l] = w.x;
      y[l] = w.y;
      z[l] = w.z;
    }
    const Vec3<W> o{Lanes::load(x), Lanes::load(y), Lanes::load(z)};
    Lanes::store(a.i.z > 0 ? eq8_front_density(g, i, k, t, i_std, o)
                           : pdf_vndf_backfacing_eq7(g, i, o),
                 d);
    std::copy(d, d + n, out.begin() + std::ptrdiff_t(begin));
  }
}

}  // namespace glintlab::verify::eto_claims

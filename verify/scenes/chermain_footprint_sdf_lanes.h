// glint_values (verify/scenes/chermain_footprint_sdf.h) in double lanes W (a Wide of an xsimd
// batch with fused multiply-add), for the per-ISA units chermain_footprint_sdf_{avx2,avx512}.cpp,
// each compiled with its ISA's flags and without contraction: every operation here is exactly
// rounded (no transcendental: the cells' sincos were drawn on the host), and the table lookups are
// core's own templates on W, so each lane rounds as the scalar glint_value_of does.
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>

#include "core/simd/wide.h"
#include "verify/scenes/chermain_footprint_sdf.h"

namespace glintlab::verify::detail {

// The BRDF of the samples in lanes; terms(begin, n, add) calls add(w, base_x, base_y, cos θ,
// sin θ) for each term of the lanes' samples begin … begin + n − 1, in each sample's order.
template <class W, class Terms>
void glint_values_lanes(const chermain2021::SdfParams& p, const chermain2021::Matrix& M,
                        const GlintSamples& s, const Terms& terms, std::span<double> out) {
  constexpr std::size_t kLanes = W::kLanes;
  using Lanes = LaneAccess<W>;
  const chermain2021::Table table = p.dictionary->table();
  alignas(64) double column[8][kLanes], value[kLanes];
  const std::vector<double>* columns[8] = {&s.wi_x, &s.wi_y, &s.wi_z,    &s.wl_x,
                                           &s.wl_y, &s.wl_z, &s.shift_x, &s.shift_y};
  for (std::size_t begin = 0; begin < s.size(); begin += kLanes) {
    const std::size_t n = std::min(kLanes, s.size() - begin);
    // The last lanes padded with the last sample; only the first n are written out.
    for (std::size_t c = 0; c < 8; ++c)
      for (std::size_t l = 0; l < kLanes; ++l)
        column[c][l] = (*columns[c])[begin + std::min(l, n - 1)];
    const Vec3<W> wi{Lanes::load(column[0]), Lanes::load(column[1]), Lanes::load(column[2])};
    const Vec3<W> wl{Lanes::load(column[3]), Lanes::load(column[4]), Lanes::load(column[5])};
    const Vec3<W> h = half_vector(wi, wl);
    const auto ok = wi.z > W(0) && wl.z > W(0) && h.z > W(0);
    // Lanes the scalar code returns 0 for look up the slope 0 (a finite texel address).
    const W mx0 = select(ok, -h.x / h.z - Lanes::load(column[6]), W(0));
    const W my0 = select(ok, -h.y / h.z - Lanes::load(column[7]), W(0));
    // FootprintSdf::operator() on the lanes (no smooth term: glint_values checks).
    const W mx = W(M.i00) * mx0 + W(M.i01) * my0, my = W(M.i11) * my0;
    W total(0);
    terms(begin, n, [&](W w, W base_x, W base_y, W cos_t, W sin_t) {
      const W xo = cos_t * mx + sin_t * my, yo = -sin_t * mx + cos_t * my;
      const W px = chermain2021::lookup_lod(table, base_x, xo, 0, p.wrap);
      const W py = chermain2021::lookup_lod(table, base_y, yo, 0, p.wrap);
      total = total + w * px * py / W(M.det);
    });
    const W z2 = h.z * h.z;
    const W D = total / (z2 * z2);
    Lanes::store(select(ok, D * chermain2021::v_cavity_g2(wi, wl, h) / (W(4) * wi.z), W(0)), value);
    std::copy(value, value + n, out.begin() + std::ptrdiff_t(begin));
  }
}

// One footprint for every sample: its terms in every lane.
template <class W>
void glint_values_lanes(const FootprintSdf& sdf, const GlintSamples& s, std::span<double> out) {
  glint_values_lanes<W>(
      sdf.params(), sdf.matrix(), s,
      [&](std::size_t, std::size_t, auto&& add) {
        for (const FootprintSdf::Term& t : sdf.terms())
          add(W(t.w), W(t.base_x), W(t.base_y), W(t.cos_t), W(t.sin_t));
      },
      out);
}

// A footprint per sample: slot t of the lanes' samples, up to the largest count among them (the
// slots past a sample's count add +0).
template <class W>
void glint_values_lanes(const SampleFootprints& f, const GlintSamples& s, std::span<double> out) {
  constexpr std::size_t kLanes = W::kLanes;
  using Lanes = LaneAccess<W>;
  const chermain2021::SdfParams& p = f.params();
  const chermain2021::Matrix M =
      chermain2021::matrix(p.sigma_x, p.sigma_y, p.rho, p.dictionary->sigma_o(), p.with_rho);
  alignas(64) double slot[5][kLanes];
  glint_values_lanes<W>(
      p, M, s,
      [&](std::size_t begin, std::size_t n, auto&& add) {
        int slots = 0;
        for (std::size_t l = 0; l < n; ++l) slots = std::max(slots, f.count(begin + l));
        for (int t = 0; t < slots; ++t) {
          const double* from[5] = {f.w(t), f.base_x(t), f.base_y(t), f.cos_t(t), f.sin_t(t)};
          for (std::size_t c = 0; c < 5; ++c)
            for (std::size_t l = 0; l < kLanes; ++l) slot[c][l] = l < n ? from[c][begin + l] : 0.0;
          add(Lanes::load(slot[0]), Lanes::load(slot[1]), Lanes::load(slot[2]),
              Lanes::load(slot[3]), Lanes::load(slot[4]));
        }
      },
      out);
}

}  // namespace glintlab::verify::detail

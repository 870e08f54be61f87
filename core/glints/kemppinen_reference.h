// Brute-force ground truth for Kemppinen et al. 2025: D★ of Eq. 4 averaged over a spatial region
// and the filtered D★^f of Eq. 5, by summing every point of the implicit grid (kemppinen_grid.h)
// that can contribute, with neither the k-neighbourhood truncation nor the compensation of Eq. 11.
// The same points, colours and roulette numbers as Algorithm 1 (core/glints/kemppinen.h).
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/glints/kemppinen.h"

namespace glintlab::kemppinen2025 {

// Points farther than this many standard deviations (of the lobe or of the pixel filter) are
// skipped: their weight is below exp(−kKemppinenReferenceSigmas²/2) = e^{−32} of the peak.
inline constexpr double kReferenceSigmas = 8.0;

// Eq. 5 at one level, split as Algorithm 1 splits it: every point (total), the points whose angular
// cell lies in Algorithm 1's B(k) (neighbourhood, any spatial cell), and those of B(k) whose
// spatial cell also lies in its k spatial cells (block: Algorithm 1's explicit sum, the same
// points). k = side².
template <class T>
struct ReferenceParts {
  Vec3<T> total, neighbourhood, block;
};

// Eq. 5 at one level with weight w_l (roulette or linear as in the params): every point whose
// spatial cell lies within `sigmas` standard deviations of the filter or in the k spatial cells,
// and whose angular cell lies within that many lobe widths of x_a or in B(k) (the whole square
// when `whole_square`). Adds the number of (spatial cell, angular cell) pairs it visits to
// *visited when given (the cost measure of kemppinen.constant-time, comparable to
// Result::points).
template <class T>
ReferenceParts<T> reference_level_parts(const Params<T>& p, const Angular<T>& ang, Vec2<T> x_s,
                                        const Sym2<T>& sigma_s, T res, int level, T w_l, int side,
                                        T sigmas, bool whole_square = false,
                                        std::int64_t* visited = nullptr) {
  const T res_a = angular_resolution<T>(level);
  const T res_s = res / res_a;
  const std::int64_t n_a = std::int64_t(1) << level;
  const T r = sigmas;
  const T sx = sqrt(sigma_s.xx) * r, sy = sqrt(sigma_s.yy) * r;
  // Algorithm 1's k cells in space and in angle (kemppinen.h `level`).
  const std::int64_t bx0 = block_start(x_s.x * res_s, side);
  const std::int64_t by0 = block_start(x_s.y * res_s, side);
  const std::int64_t kx0 = block_start(ang.x_a.x * res_a, side);
  const std::int64_t ky0 = block_start(ang.x_a.y * res_a, side);
  const std::int64_t sx0 = std::min(std::int64_t(floor((x_s.x - sx) * res_s)), bx0);
  const std::int64_t sx1 = std::max(std::int64_t(floor((x_s.x + sx) * res_s)), bx0 + side - 1);
  const std::int64_t sy0 = std::min(std::int64_t(floor((x_s.y - sy) * res_s)), by0);
  const std::int64_t sy1 = std::max(std::int64_t(floor((x_s.y + sy) * res_s)), by0 + side - 1);
  auto clip = [&](T v) {
    const T c = floor(v * res_a);
    return std::int64_t(clamp(c, T(0), T(n_a - 1)));
  };
  auto clip_cell = [&](std::int64_t c) { return std::clamp<std::int64_t>(c, 0, n_a - 1); };
  const std::int64_t ax0 =
      whole_square ? 0 : std::min(clip(ang.x_a.x - r * ang.sigma_a.x), clip_cell(kx0));
  const std::int64_t ax1 =
      whole_square ? n_a - 1
                   : std::max(clip(ang.x_a.x + r * ang.sigma_a.x), clip_cell(kx0 + side - 1));
  const std::int64_t ay0 =
      whole_square ? 0 : std::min(clip(ang.x_a.y - r * ang.sigma_a.y), clip_cell(ky0));
  const std::int64_t ay1 =
      whole_square ? n_a - 1
                   : std::max(clip(ang.x_a.y + r * ang.sigma_a.y), clip_cell(ky0 + side - 1));
  const Sym2<T> sigma_a2{sqr(ang.sigma_a.x), T(0), sqr(ang.sigma_a.y)};
  if (visited) *visited += (sx1 - sx0 + 1) * (sy1 - sy0 + 1) * (ax1 - ax0 + 1) * (ay1 - ay0 + 1);
  ReferenceParts<T> sum{{T(0), T(0), T(0)}, {T(0), T(0), T(0)}, {T(0), T(0), T(0)}};
  // cell_index(Cell{i, j, a, b, level, 0}) (kemppinen_grid.h), its chain's steps hoisted out of
  // the loops that do not change their inputs: the same bits, three fewer mixes per point.
  for (std::int64_t i = sx0; i <= sx1; ++i) {
    const std::uint64_t hash_i = cell_chain_sx(i);
    for (std::int64_t j = sy0; j <= sy1; ++j) {
      const std::uint64_t hash_ij = cell_chain_sy(hash_i, j);
      const bool in_block = i >= bx0 && i < bx0 + side && j >= by0 && j < by0 + side;
      for (std::int64_t a = ax0; a <= ax1; ++a) {
        const std::uint64_t hash_ija = cell_chain_ax(hash_ij, a);
        for (std::int64_t b = ay0; b <= ay1; ++b) {
          const std::uint64_t ci = cell_chain_level(cell_chain_ay(hash_ija, b), level, 0);
          const Vec2<T> g_a{(T(a) + cell_uniform<T>(p.seed, ci, kKemppinenDimAngularX)) / res_a,
                            (T(b) + cell_uniform<T>(p.seed, ci, kKemppinenDimAngularY)) / res_a};
          if (sqr(g_a.x - T(0.5)) + sqr(g_a.y - T(0.5)) > T(0.25)) continue;
          const T rr = cell_uniform<T>(p.seed, ci, kKemppinenDimRoulette);
          const T blend = p.blend == Blend::kRoulette ? roulette(rr, w_l) : w_l;
          if (blend == T(0)) continue;
          const Vec2<T> g_s{(T(i) + cell_uniform<T>(p.seed, ci, kKemppinenDimSpatialX)) / res_s,
                            (T(j) + cell_uniform<T>(p.seed, ci, kKemppinenDimSpatialY)) / res_s};
          const T w = blend * normal2(x_s - g_s, sigma_s) * normal2(ang.x_a - g_a, sigma_a2);
          const Vec3<T> v =
              p.colors == Colors::kWhite
                  ? Vec3<T>{w, w, w}
                  : w * color(p.colors, cell_uniform<T>(p.seed, ci, kKemppinenDimColor));
          sum.total = sum.total + v;
          if (a >= kx0 && a < kx0 + side && b >= ky0 && b < ky0 + side) {
            sum.neighbourhood = sum.neighbourhood + v;
            if (in_block) sum.block = sum.block + v;
          }
        }
      }
    }
  }
  const T k = T(1) / sqr(res);
  return {k * sum.total, k * sum.neighbourhood, k * sum.block};
}

// Eq. 5 at one level, every point within kReferenceSigmas (see reference_level_parts).
template <class T>
Vec3<T> reference_level(const Params<T>& p, const Angular<T>& ang, Vec2<T> x_s,
                        const Sym2<T>& sigma_s, T res, int level, T w_l, bool whole_square = false,
                        std::int64_t* visited = nullptr) {
  return reference_level_parts(p, ang, x_s, sigma_s, res, level, w_l, 1, T(kReferenceSigmas),
                               whole_square, visited)
      .total;
}

// Eq. 5, D★^f(x, ω_h) = prefactor/K_P Σ_i N(T(ω_h), μ_i, σ) f(x_i − x, Σ_s), over the points of
// levels ⌊λ⌋ and ⌊λ⌋+1 blended as Algorithm 1 blends them; every contributing point summed
// (their count added to *visited when given).
template <class Ndf, class T>
Vec3<T> reference_filtered(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp,
                           Vec3<T> h, bool whole_square = false, std::int64_t* visited = nullptr) {
  const Angular<T> ang = angular(p, ndf, h);
  if (!ang.valid) return {T(0), T(0), T(0)};
  const T res = base_resolution(p);
  const Vec2<T> x_s = spatial_position(p, fp.uv);
  const Sym2<T> sigma_s = spatial_covariance(p, fp, res);
  const T lambda = lod(sigma_s, res);
  const T fl = min(floor(lambda), T(kMaxLevel - 1));
  const int l0 = static_cast<int>(fl);
  const T w1 = lambda - fl;
  const Vec3<T> s0 =
      reference_level(p, ang, x_s, sigma_s, res, l0, T(1) - w1, whole_square, visited);
  const Vec3<T> s1 = reference_level(p, ang, x_s, sigma_s, res, l0 + 1, w1, whole_square, visited);
  return ang.prefactor * (s0 + s1);
}

// Eq. 5 split by Algorithm 1's k-neighbourhoods (reference_level_parts) at both levels, each
// point within `sigmas` standard deviations (of the filter, of the lobe) or in the k cells. A
// level of weight 0 is skipped: its roulette weight R(r, 0) and its linear weight are exactly 0.
// Adds the (spatial cell, angular cell) pairs visited to *visited when given.
template <class Ndf, class T>
ReferenceParts<T> reference_filtered_parts(const Params<T>& p, const Ndf& ndf,
                                           const FootprintQuery<T>& fp, Vec3<T> h, int side,
                                           T sigmas, std::int64_t* visited = nullptr) {
  ReferenceParts<T> out{{T(0), T(0), T(0)}, {T(0), T(0), T(0)}, {T(0), T(0), T(0)}};
  const Angular<T> ang = angular(p, ndf, h);
  if (!ang.valid) return out;
  const T res = base_resolution(p);
  const Vec2<T> x_s = spatial_position(p, fp.uv);
  const Sym2<T> sigma_s = spatial_covariance(p, fp, res);
  const T lambda = lod(sigma_s, res);
  const T fl = min(floor(lambda), T(kMaxLevel - 1));
  const T w[2] = {T(1) - (lambda - fl), lambda - fl};
  for (int l = 0; l < 2; ++l) {
    if (w[l] == T(0)) continue;
    const ReferenceParts<T> s = reference_level_parts(
        p, ang, x_s, sigma_s, res, static_cast<int>(fl) + l, w[l], side, sigmas, false, visited);
    out.total = out.total + ang.prefactor * s.total;
    out.neighbourhood = out.neighbourhood + ang.prefactor * s.neighbourhood;
    out.block = out.block + ang.prefactor * s.block;
  }
  return out;
}

// Eq. 4 averaged over the region of `cells` × `cells` spatial cells of level `level` starting at
// cell (cx, cy): (1/|X|) ∫_X D★(x, ω_h) dx = prefactor/(K_P |X|) Σ_{x_i ∈ X} N(T(ω_h), μ_i, σ),
// every point of the region whose angular cell lies within kReferenceSigmas lobe widths
// of x_a. The lobes' normalisation gives the far-field mean prefactor × (lobe mass inside U_Ω).
template <class Ndf, class T>
T region_mean(const Params<T>& p, const Ndf& ndf, Vec3<T> h, int level, std::int64_t cx,
              std::int64_t cy, std::int64_t cells) {
  const Angular<T> ang = angular(p, ndf, h);
  if (!ang.valid) return T(0);
  const T res_a = angular_resolution<T>(level);
  const std::int64_t n_a = std::int64_t(1) << level;
  const T r = T(kReferenceSigmas);
  auto clip = [&](T v) { return std::int64_t(clamp(floor(v * res_a), T(0), T(n_a - 1))); };
  const std::int64_t ax0 = clip(ang.x_a.x - r * ang.sigma_a.x);
  const std::int64_t ax1 = clip(ang.x_a.x + r * ang.sigma_a.x);
  const std::int64_t ay0 = clip(ang.x_a.y - r * ang.sigma_a.y);
  const std::int64_t ay1 = clip(ang.x_a.y + r * ang.sigma_a.y);
  const Sym2<T> sigma_a2{sqr(ang.sigma_a.x), T(0), sqr(ang.sigma_a.y)};
  T sum = T(0);
  for (std::int64_t i = cx; i < cx + cells; ++i)
    for (std::int64_t j = cy; j < cy + cells; ++j)
      for (std::int64_t a = ax0; a <= ax1; ++a)
        for (std::int64_t b = ay0; b <= ay1; ++b) {
          const Cell c{i, j, a, b, level, 0};
          const std::uint64_t ci = kemppinen2025::cell_index(c);
          const Vec2<T> g_a{(T(a) + cell_uniform<T>(p.seed, ci, kKemppinenDimAngularX)) / res_a,
                            (T(b) + cell_uniform<T>(p.seed, ci, kKemppinenDimAngularY)) / res_a};
          if (sqr(g_a.x - T(0.5)) + sqr(g_a.y - T(0.5)) > T(0.25)) continue;
          sum += normal2(ang.x_a - g_a, sigma_a2);
        }
  // Each spatial cell holds res_a² angular cells: Σ/(cells² res_a²) is the mean lobe value.
  return ang.prefactor * sum / (T(cells * cells) * sqr(res_a));
}

// The far-field value of region_mean: prefactor × ∫_{U_Ω} N(μ; x_a, Σ_a) dμ, the lobe's
// mass inside the disk: rows of the lobe's ±8σ box (clipped to □), each row's x-extent the disk's
// chord at the row's middle, integrated exactly by erf (error O(row height²) at the rim).
template <class Ndf, class T>
T area_mean_expected(const Params<T>& p, const Ndf& ndf, Vec3<T> h) {
  const Angular<T> ang = angular(p, ndf, h);
  if (!ang.valid) return T(0);
  const T r = T(kReferenceSigmas);
  const T y0 = max(T(0), ang.x_a.y - r * ang.sigma_a.y),
          y1 = min(T(1), ang.x_a.y + r * ang.sigma_a.y);
  constexpr int kRows = 512;
  T mass = T(0);
  for (int k = 0; k < kRows; ++k) {
    const T ya = y0 + (y1 - y0) * T(k) / T(kRows), yb = y0 + (y1 - y0) * T(k + 1) / T(kRows);
    const T ym = T(0.5) * (ya + yb);
    const T half = safe_sqrt(T(0.25) - sqr(ym - T(0.5)));
    const T mx =
        gaussian_interval_mass(T(0.5) - half, T(0.5) + half, ang.x_a.x, ang.sigma_a.x, Erf::kExact);
    mass += mx * gaussian_interval_mass(ya, yb, ang.x_a.y, ang.sigma_a.y, Erf::kExact);
  }
  return ang.prefactor * mass;
}

}  // namespace glintlab::kemppinen2025

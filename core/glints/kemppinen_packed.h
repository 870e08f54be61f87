// The marginal density of Algorithm 2 (sample_density_square, kemppinen_sampling.h) on a SIMD
// batch with the work of its points packed by (point, lane): the same bits in every lane that the
// result depends on, for a fraction of the work.
//
// Why: the batch's lanes are unrelated rows, each at its own level and angular cell. Unpacked,
// level_points computes a point's lobe width (the map's inverse and D), its N_j(x) and its masses
// in the blocks (erfs) on every lane whenever one lane needs them. Most lanes need few: at level 0
// (every query whose footprint is below a cell, most of a typical call) only the centre cell of a
// point's 3 × 3 angular cells exists, and the upper level of such a row has weight 0. Here the
// cheap part of every point (its cell hash, angular position and whether it exists) stays on the
// batch's lanes; the (point, lane) pairs that exist and lie in a block the lane uses are then
// gathered into full vectors, which compute the rest: spatial weight s_j, σ_j, s_j N_j(x) and the
// masses along x and y over the block starts that lane uses. The arithmetic of each pair is that of
// candidate(), level_points() and mass_along() on its lane's inputs, and SIMD arithmetic is lane by
// lane, so each value is the unpacked one bit for bit; a pair's s_j, term and masses are 0 where it
// was not packed, which gives the same sums in every lane whose block is used (see
// packed_block_density), and the other lanes' results are discarded by sample_density_square.
// tests/simd/kemppinen_packed_density_test.cpp pins it to the unpacked loops on every ISA.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "core/glints/kemppinen_sampling.h"

namespace glintlab::kemppinen2025 {

// The values of one level's points (LevelPoints' indexing) per lane, 0 where not packed.
template <class T>
struct PackedLevelPoints {
  using S = Scalar<T>;
  static constexpr std::size_t kLanes = kLaneCount<T>;
  static constexpr std::size_t kCount = LevelPoints<T>::kCount;
  S s[kCount][kLanes];     // Candidate::s
  S term[kCount][kLanes];  // LevelPoints::term
  // mass_along: axis (0: x, 1: y), start offset slot d + n − 1, point, lane.
  S mass[2][kMaxSide][kCount][kLanes];
  int n = 0;
  GLINTLAB_FN std::size_t index(int i, int j, int a, int b) const {
    const int span = 2 * n - 1;
    return std::size_t(((i * n + j) * span + (a + n - 1)) * span + (b + n - 1));
  }
};

// The per-lane inputs of a level that a packed pair reads from its lane.
template <class T>
struct PackedLevelInputs {
  using S = Scalar<T>;
  static constexpr std::size_t kLanes = kLaneCount<T>;
  S x_s_x[kLanes], x_s_y[kLanes];
  S lobe_xx[kLanes], lobe_xy[kLanes], lobe_yy[kLanes], lobe_c[kLanes], lobe_det[kLanes],
      lobe_peak[kLanes];
  S res_s[kLanes], w_l[kLanes], x_x[kLanes], x_y[kLanes];
  S microroughness[kLanes], anisotropy[kLanes], alpha_x[kLanes], alpha_y[kLanes];
  std::int64_t sx0[kLanes], sy0[kLanes];
  // The block bounds along each axis per start offset slot (level_block_density's lo, hi).
  S lo[2][kMaxSide][kLanes], hi[2][kMaxSide][kLanes];
  // Per angular offset (a, b) of a point from x's cell (index (a + n − 1)(2n − 1) + b + n − 1):
  // the lanes that use a block holding it (bit per lane), and per lane the masses it needs there
  // (bit axis · kMaxSide + start slot: a block (dx, dy) that the lane uses holds the point where
  // dx ≤ a ≤ dx + n − 1 and dy ≤ b ≤ dy + n − 1).
  static constexpr std::size_t kOffsets = (2 * kMaxSide - 1) * (2 * kMaxSide - 1);
  std::uint32_t lanes_at[kOffsets];
  std::uint32_t masses_at[kOffsets][kLanes];
};

// Pairs waiting for a full vector: point `at` (cell offsets i, j, a, b) in lane `lane`, its cell
// key and angular position, and the (axis, slot) masses its lane needs (bit axis · kMaxSide + slot).
template <class T>
struct PackedPairs {
  using S = Scalar<T>;
  static constexpr std::size_t kLanes = kLaneCount<T>;
  static constexpr std::size_t kCapacity = 2 * kLanes;
  std::size_t count = 0;
  std::uint32_t at[kCapacity];
  std::int32_t i[kCapacity], j[kCapacity];
  std::uint32_t lane[kCapacity], masses[kCapacity];
  std::uint64_t key[kCapacity];
  alignas(64) S g_x[kCapacity];
  alignas(64) S g_y[kCapacity];
};

// Pairs of positive weight (s ≠ 0) waiting for a full vector: their σ_j, s_j N_j(x) and masses.
template <class T>
struct LivePairs {
  using S = Scalar<T>;
  static constexpr std::size_t kLanes = kLaneCount<T>;
  static constexpr std::size_t kCapacity = 2 * kLanes;
  std::size_t count = 0;
  std::uint32_t at[kCapacity];
  std::uint32_t lane[kCapacity], masses[kCapacity];
  alignas(64) S g_x[kCapacity];
  alignas(64) S g_y[kCapacity];
  alignas(64) S s[kCapacity];
  GLINTLAB_FN void copy(std::size_t to, std::size_t from) {
    at[to] = at[from];
    lane[to] = lane[from];
    masses[to] = masses[from];
    g_x[to] = g_x[from];
    g_y[to] = g_y[from];
    s[to] = s[from];
  }
};

// The live pairs' σ_j (point_sigma), level_points' term s_j N_j(x) and mass_along over the block
// starts their lane uses, on the first `count` ≤ kLanes pairs (the pairs past them, up to kLanes,
// copies of pair 0: computed and not written back).
template <class Ndf, class T>
GLINTLAB_FN void live_pairs_compute(const Params<T>& p, const Ndf& ndf,
                                    const PackedLevelInputs<T>& in, const LivePairs<T>& pr,
                                    std::size_t count, PackedLevelPoints<T>& out) {
  using S = Scalar<T>;
  constexpr std::size_t kLanes = kLaneCount<T>;
  const auto gather = [&](const S* per_lane) {
    alignas(64) S v[kLanes];
    for (std::size_t l = 0; l < kLanes; ++l) v[l] = per_lane[pr.lane[l]];
    return LaneAccess<T>::load(v);
  };
  const Vec2<T> g_a{LaneAccess<T>::load(pr.g_x), LaneAccess<T>::load(pr.g_y)};
  const T s = LaneAccess<T>::load(pr.s);
  Params<T> lane_p = p;
  lane_p.microroughness = gather(in.microroughness);
  lane_p.anisotropy = gather(in.anisotropy);
  Ndf lane_ndf = ndf;
  lane_ndf.alpha_x = gather(in.alpha_x);
  lane_ndf.alpha_y = gather(in.alpha_y);
  const Vec2<T> sigma = point_sigma(lane_p, lane_ndf, g_a);
  // level_points' term.
  const Mask<T> live = (s > T(0)) && (sigma.x > T(0)) && (sigma.y > T(0));
  if (any_lane<T>(live)) {
    const Vec2<T> x{gather(in.x_x), gather(in.x_y)};
    const T term =
        select(live, s * normal2(x - g_a, Sym2<T>{sqr(sigma.x), T(0), sqr(sigma.y)}), T(0));
    const LanesOf<T> term_lanes(term);
    for (std::size_t l = 0; l < count; ++l) out.term[pr.at[l]][pr.lane[l]] = term_lanes[l];
  }
  // mass_along, over the block starts of a block that the pair's lane uses.
  for (int axis = 0; axis < 2; ++axis)
    for (int slot = 0; slot < out.n; ++slot) {
      const std::uint32_t bit = std::uint32_t(1) << (axis * kMaxSide + slot);
      bool any = false;
      for (std::size_t l = 0; l < count; ++l) any = any || (pr.masses[l] & bit) != 0;
      if (!any) continue;
      const T lo = gather(in.lo[axis][slot]), hi = gather(in.hi[axis][slot]);
      const T m = axis == 0 ? gaussian_interval_mass(lo, hi, g_a.x, sigma.x, Erf::kExact)
                            : gaussian_interval_mass(lo, hi, g_a.y, sigma.y, Erf::kExact);
      const LanesOf<T> m_lanes(m);
      for (std::size_t l = 0; l < count; ++l)
        if (pr.masses[l] & bit) out.mass[axis][slot][pr.at[l]][pr.lane[l]] = m_lanes[l];
    }
}

// The pairs' candidate() values past the angular position, s_j N_j(x) and their masses, on the
// first `count` ≤ kLanes pairs (the pairs past them, up to kLanes, copies of pair 0: computed and not
// written back).
template <class Ndf, class T>
GLINTLAB_FN void packed_pairs_compute(const Params<T>& p, const Ndf& ndf,
                                      const PackedLevelInputs<T>& in, const PackedPairs<T>& pr,
                                      std::size_t count, LivePairs<T>& live,
                                      PackedLevelPoints<T>& out) {
  using S = Scalar<T>;
  constexpr std::size_t kLanes = kLaneCount<T>;
  // Each vector from kLanes pairs: those past `count` are copies of pair 0 (see the caller).
  const auto gather = [&](const S* per_lane) {
    alignas(64) S v[kLanes];
    for (std::size_t l = 0; l < kLanes; ++l) v[l] = per_lane[pr.lane[l]];
    return LaneAccess<T>::load(v);
  };
  LaneInt<T, std::uint64_t> key;
  LaneInt<T> sx, sy;
  for (std::size_t l = 0; l < kLanes; ++l) {
    key.v[l] = pr.key[l];
    sx.v[l] = in.sx0[pr.lane[l]] + std::int64_t(pr.i[l]);
    sy.v[l] = in.sy0[pr.lane[l]] + std::int64_t(pr.j[l]);
  }
  const T res_s = gather(in.res_s), w_l = gather(in.w_l);
  const Vec2<T> x_s{gather(in.x_s_x), gather(in.x_s_y)};
  const Normal2Form<T> lobe{
      {gather(in.lobe_xx), gather(in.lobe_xy), gather(in.lobe_yy)},
      gather(in.lobe_c),
      gather(in.lobe_det),
      gather(in.lobe_peak)};
  // candidate(), where the point exists.
  const Vec2<T> g_s{
      (int_to_float<T>(sx) + key_uniform<T>(key, kKemppinenDimSpatialX)) / res_s,
      (int_to_float<T>(sy) + key_uniform<T>(key, kKemppinenDimSpatialY)) / res_s};
  const T r = key_uniform<T>(key, kKemppinenDimRoulette);
  const T blend = p.blend == Blend::kRoulette ? roulette(r, w_l) : w_l;
  const Vec3<T> col = color(p.colors, key_uniform<T>(key, kKemppinenDimColor));
  const T s = blend * normal2_at(lobe, x_s - g_s) * luminance(col);
  const LanesOf<T> s_lanes(s);
  for (std::size_t l = 0; l < count; ++l) {
    out.s[pr.at[l]][pr.lane[l]] = s_lanes[l];
    // A pair of weight 0 needs neither its lobe nor its masses (adds_weight); the others go on.
    if (s_lanes[l] == S(0)) continue;
    const std::size_t k = live.count++;
    live.at[k] = pr.at[l];
    live.lane[k] = pr.lane[l];
    live.masses[k] = pr.masses[l];
    live.g_x[k] = pr.g_x[l];
    live.g_y[k] = pr.g_y[l];
    live.s[k] = s_lanes[l];
  }
  if (live.count >= kLanes) {
    live_pairs_compute(p, ndf, in, live, kLanes, out);
    const std::size_t rest = live.count - kLanes;
    for (std::size_t k = 0; k < rest; ++k) live.copy(k, kLanes + k);
    live.count = rest;
  }
}

// The points of a level around x's angular cell (cx, cy), as level_points and mass_along give
// them, for the pairs whose lane uses a block that holds them (in.lanes_at); 0 elsewhere.
template <class Ndf, class T>
GLINTLAB_FN void packed_level_points(const Params<T>& p, const Ndf& ndf, const Spatial<T>& sp,
                                     const LaneInt<T, int>& level, const LaneInt<T>& cx,
                                     const LaneInt<T>& cy, const PackedLevelInputs<T>& in,
                                     PackedLevelPoints<T>& out, int process) {
  using S = Scalar<T>;
  constexpr std::size_t kLanes = kLaneCount<T>;
  const int n = p.side;
  out.n = n;
  const std::size_t points = std::size_t(n * n * (2 * n - 1) * (2 * n - 1));
  std::memset(out.s, 0, points * sizeof out.s[0]);
  std::memset(out.term, 0, points * sizeof out.term[0]);
  for (int axis = 0; axis < 2; ++axis)
    for (int slot = 0; slot < n; ++slot)
      std::memset(out.mass[axis][slot], 0, points * sizeof out.mass[0][0][0]);
  const T res_a = angular_resolution<T>(level);
  const LaneInt<T> n_a = level_cells<T>(level);
  const LaneInt<T> sx0 = block_start(sp.x_s.x * (sp.res / res_a), n);
  const LaneInt<T> sy0 = block_start(sp.x_s.y * (sp.res / res_a), n);
  const std::uint64_t seed_key = cell_seed_key(p.seed);
  PackedPairs<T> pairs;
  LivePairs<T> live;
  // The angular cells' coordinates, as floats, and whether they lie in the square, per offset:
  // the same for every spatial cell.
  constexpr int kSpan = 2 * kMaxSide - 1;
  LaneInt<T> ax[kSpan], ay[kSpan];
  T fax[kSpan], fay[kSpan];
  Mask<T> in_x[kSpan], in_y[kSpan];
  for (int a = 1 - n; a <= n - 1; ++a) {
    const std::size_t k = std::size_t(a + n - 1);
    ax[k] = cx + a;
    ay[k] = cy + a;
    fax[k] = int_to_float<T>(ax[k]);
    fay[k] = int_to_float<T>(ay[k]);
    in_x[k] = mask_lanes<T>(
        [&](std::size_t l) { return lane(ax[k], l) >= 0 && lane(ax[k], l) < lane(n_a, l); });
    in_y[k] = mask_lanes<T>(
        [&](std::size_t l) { return lane(ay[k], l) >= 0 && lane(ay[k], l) < lane(n_a, l); });
  }
  for (int i = 0; i < n; ++i) {
    const LaneInt<T> sx = sx0 + i;
    const LaneInt<T, std::uint64_t> hash_i = cell_chain_sx_lanes<T>(sx);
    for (int j = 0; j < n; ++j) {
      const LaneInt<T> sy = sy0 + j;
      const LaneInt<T, std::uint64_t> hash_ij = cell_chain_sy_lanes<T>(hash_i, sy);
      for (int a = 1 - n; a <= n - 1; ++a) {
        const std::size_t ka = std::size_t(a + n - 1);
        const LaneInt<T, std::uint64_t> hash_ija = cell_chain_ax_vector<T>(hash_ij, ax[ka]);
        for (int b = 1 - n; b <= n - 1; ++b) {
          const std::size_t kb = std::size_t(b + n - 1);
          const std::size_t ab = ka * std::size_t(2 * n - 1) + kb;
          if (in.lanes_at[ab] == 0) continue;  // in no block that a lane uses
          // candidate() up to whether the point exists.
          const LaneInt<T, std::uint64_t> key = cell_key<T>(
              seed_key, cell_chain_ay_level_vector<T>(hash_ija, ay[kb], level, process));
          const Vec2<T> g_a{(fax[ka] + key_uniform<T>(key, kKemppinenDimAngularX)) / res_a,
                            (fay[kb] + key_uniform<T>(key, kKemppinenDimAngularY)) / res_a};
          const Mask<T> valid =
              in_x[ka] && in_y[kb] && (sqr(g_a.x - T(0.5)) + sqr(g_a.y - T(0.5)) <= T(0.25));
          if (!any_lane<T>(valid)) continue;
          const MaskLanesOf<T> valid_lanes(valid);
          std::uint32_t todo = 0;
          for (std::size_t l = 0; l < kLanes; ++l) todo |= std::uint32_t(valid_lanes[l]) << l;
          todo &= in.lanes_at[ab];
          if (todo == 0) continue;
          const LanesOf<T> gx(g_a.x), gy(g_a.y);
          const std::uint32_t at = std::uint32_t(out.index(i, j, a, b));
          for (; todo != 0; todo &= todo - 1) {
            const std::size_t l = std::size_t(std::countr_zero(todo));
            const std::size_t k = pairs.count++;
            pairs.at[k] = at;
            pairs.i[k] = i;
            pairs.j[k] = j;
            pairs.lane[k] = std::uint32_t(l);
            pairs.masses[k] = in.masses_at[ab][l];
            pairs.key[k] = lane(key, l);
            pairs.g_x[k] = gx[l];
            pairs.g_y[k] = gy[l];
          }
          if (pairs.count >= kLanes) {
            packed_pairs_compute(p, ndf, in, pairs, kLanes, live, out);
            // Move the pairs past the first kLanes to the front.
            const std::size_t rest = pairs.count - kLanes;
            for (std::size_t k = 0; k < rest; ++k) {
              pairs.at[k] = pairs.at[kLanes + k];
              pairs.i[k] = pairs.i[kLanes + k];
              pairs.j[k] = pairs.j[kLanes + k];
              pairs.lane[k] = pairs.lane[kLanes + k];
              pairs.masses[k] = pairs.masses[kLanes + k];
              pairs.key[k] = pairs.key[kLanes + k];
              pairs.g_x[k] = pairs.g_x[kLanes + k];
              pairs.g_y[k] = pairs.g_y[kLanes + k];
            }
            pairs.count = rest;
          }
        }
      }
    }
  }
  if (pairs.count > 0) {
    for (std::size_t k = pairs.count; k < kLanes; ++k) {
      pairs.at[k] = pairs.at[0];
      pairs.i[k] = pairs.i[0];
      pairs.j[k] = pairs.j[0];
      pairs.lane[k] = pairs.lane[0];
      pairs.masses[k] = pairs.masses[0];
      pairs.key[k] = pairs.key[0];
      pairs.g_x[k] = pairs.g_x[0];
      pairs.g_y[k] = pairs.g_y[0];
    }
    packed_pairs_compute(p, ndf, in, pairs, pairs.count, live, out);
  }
  if (live.count > 0) {
    for (std::size_t k = live.count; k < kLanes; ++k) live.copy(k, 0);
    live_pairs_compute(p, ndf, in, live, live.count, out);
  }
  (void)sizeof(S);
}

// level_block_density of the block with angular start (cx + dx, cy + dy) from packed points: the
// same bits in every lane that uses the block. A lane's pair that was not packed (the point does
// not exist there, or adds no weight, or lies in no block the lane uses) has s = term = mass = 0,
// where the unpacked sum adds s·m = ±0 and a term of 0, so each used lane's sums are the same.
template <class T>
GLINTLAB_FN T packed_block_density(const PackedLevelPoints<T>& pts, const LaneInt<T, int>& level,
                                   const LaneInt<T>& cx, const LaneInt<T>& cy, int dx, int dy,
                                   Vec2<T> x) {
  const int n = pts.n;
  const T res_a = angular_resolution<T>(level);
  const LaneInt<T> n_a = level_cells<T>(level);
  const LaneInt<T> ax0 = cx + dx, ay0 = cy + dy;
  const Vec2<T> lo{int_to_float<T>(int_max(ax0, std::int64_t(0))) / res_a,
                   int_to_float<T>(int_max(ay0, std::int64_t(0))) / res_a};
  const Vec2<T> hi{int_to_float<T>(int_min(ax0 + n, n_a)) / res_a,
                   int_to_float<T>(int_min(ay0 + n, n_a)) / res_a};
  const std::size_t slot_x = std::size_t(dx + n - 1), slot_y = std::size_t(dy + n - 1);
  T total = T(0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          const std::size_t at = pts.index(i, j, dx + a, dy + b);
          const T m = LaneAccess<T>::load(pts.mass[0][slot_x][at]) *
                      LaneAccess<T>::load(pts.mass[1][slot_y][at]);
          total += LaneAccess<T>::load(pts.s[at]) * m;
        }
  const Mask<T> inside = (total > T(0)) && !(x.x < lo.x || x.x > hi.x || x.y < lo.y || x.y > hi.y);
  if (!any_lane<T>(inside)) return T(0);
  T sum = T(0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
          sum += LaneAccess<T>::load(pts.term[pts.index(i, j, dx + a, dy + b)]);
  return select(inside, sum / total, T(0));
}

// sample_density_square on a batch (more than one lane), its points packed.
template <class Ndf, class T>
GLINTLAB_FN T sample_density_square_packed(const Params<T>& p, const Ndf& ndf,
                                           const FootprintQuery<T>& fp, Vec2<T> x, int process) {
  constexpr std::size_t kLanes = kLaneCount<T>;
  const Mask<T> in_disk = !(sqr(x.x - T(0.5)) + sqr(x.y - T(0.5)) > T(0.25));
  if (!any_lane<T>(in_disk)) return T(0);
  const Spatial<T> sp = spatial(p, fp);
  const int n = p.side;
  // On the stack, as LevelPoints in sample_density_square.
  PackedLevelPoints<T> points;
  PackedLevelInputs<T> in;
  LaneAccess<T>::store(sp.x_s.x, in.x_s_x);
  LaneAccess<T>::store(sp.x_s.y, in.x_s_y);
  const Normal2Form<T> spatial_lobe = normal2_form(sp.sigma_s);
  LaneAccess<T>::store(spatial_lobe.sc.xx, in.lobe_xx);
  LaneAccess<T>::store(spatial_lobe.sc.xy, in.lobe_xy);
  LaneAccess<T>::store(spatial_lobe.sc.yy, in.lobe_yy);
  LaneAccess<T>::store(spatial_lobe.c, in.lobe_c);
  LaneAccess<T>::store(spatial_lobe.det, in.lobe_det);
  LaneAccess<T>::store(spatial_lobe.peak, in.lobe_peak);
  LaneAccess<T>::store(x.x, in.x_x);
  LaneAccess<T>::store(x.y, in.x_y);
  LaneAccess<T>::store(p.microroughness, in.microroughness);
  LaneAccess<T>::store(p.anisotropy, in.anisotropy);
  LaneAccess<T>::store(ndf.alpha_x, in.alpha_x);
  LaneAccess<T>::store(ndf.alpha_y, in.alpha_y);
  T total = T(0);
  for (int up = 0; up < 2; ++up) {
    const LaneInt<T, int> level = sp.l0 + up;
    const T w_l = up ? sp.w1 : T(1) - sp.w1;
    const Mask<T> w_positive = w_l > T(0);
    if (!any_lane<T>(w_positive)) continue;
    const T res_a = angular_resolution<T>(level);
    const LaneInt<T> cx = floor_int<T>(x.x * res_a);
    const LaneInt<T> cy = floor_int<T>(x.y * res_a);
    // Every block's area and use first, so that only the pairs in used blocks are packed.
    T area[kMaxSide][kMaxSide];
    Mask<T> use[kMaxSide][kMaxSide];
    bool any_use = false;
    const std::size_t span = std::size_t(2 * n - 1);
    for (std::size_t ab = 0; ab < span * span; ++ab) {
      in.lanes_at[ab] = 0;
      for (std::size_t l = 0; l < kLanes; ++l) in.masses_at[ab][l] = 0;
    }
    for (int dx = 1 - n; dx <= 0; ++dx)
      for (int dy = 1 - n; dy <= 0; ++dy) {
        const LaneInt<T> bx = cx + dx, by = cy + dy;
        // x_a selects start b where x_a·res_a ∈ [b + (n−1)/2, b + (n+1)/2).
        const T half = T(0.5) * T(n - 1);
        const T fx = int_to_float<T>(bx) + half, fy = int_to_float<T>(by) + half;
        const LanesOf<T> x0(fx / res_a), x1((fx + T(1)) / res_a), y0(fy / res_a),
            y1((fy + T(1)) / res_a);
        const std::size_t sx = std::size_t(dx + n - 1), sy = std::size_t(dy + n - 1);
        area[sx][sy] = lane_square_disk_areas<T>(x0, x1, y0, y1);
        use[sx][sy] = w_positive && (area[sx][sy] > T(0));
        if (!any_lane<T>(use[sx][sy])) continue;
        any_use = true;
        const MaskLanesOf<T> use_lanes(use[sx][sy]);
        const std::uint32_t bits =
            (std::uint32_t(1) << sx) | (std::uint32_t(1) << (kMaxSide + sy));
        for (int a = dx; a <= dx + n - 1; ++a)
          for (int b = dy; b <= dy + n - 1; ++b) {
            const std::size_t ab = std::size_t(a + n - 1) * span + std::size_t(b + n - 1);
            for (std::size_t l = 0; l < kLanes; ++l)
              if (use_lanes[l]) {
                in.lanes_at[ab] |= std::uint32_t(1) << l;
                in.masses_at[ab][l] |= bits;
              }
          }
      }
    if (!any_use) continue;
    LaneAccess<T>::store(sp.res / res_a, in.res_s);
    LaneAccess<T>::store(w_l, in.w_l);
    const LaneInt<T> n_a = level_cells<T>(level);
    const LaneInt<T> sx0 = block_start(sp.x_s.x * (sp.res / res_a), n);
    const LaneInt<T> sy0 = block_start(sp.x_s.y * (sp.res / res_a), n);
    for (std::size_t l = 0; l < kLanes; ++l) {
      in.sx0[l] = lane(sx0, l);
      in.sy0[l] = lane(sy0, l);
    }
    for (int d = 1 - n; d <= 0; ++d) {
      const std::size_t slot = std::size_t(d + n - 1);
      const LaneInt<T> ax0 = cx + d, ay0 = cy + d;
      LaneAccess<T>::store(int_to_float<T>(int_max(ax0, std::int64_t(0))) / res_a, in.lo[0][slot]);
      LaneAccess<T>::store(int_to_float<T>(int_max(ay0, std::int64_t(0))) / res_a, in.lo[1][slot]);
      LaneAccess<T>::store(int_to_float<T>(int_min(ax0 + n, n_a)) / res_a, in.hi[0][slot]);
      LaneAccess<T>::store(int_to_float<T>(int_min(ay0 + n, n_a)) / res_a, in.hi[1][slot]);
    }
    packed_level_points(p, ndf, sp, level, cx, cy, in, points, process);
    for (int dx = 1 - n; dx <= 0; ++dx)
      for (int dy = 1 - n; dy <= 0; ++dy) {
        const std::size_t sx = std::size_t(dx + n - 1), sy = std::size_t(dy + n - 1);
        if (!any_lane<T>(use[sx][sy])) continue;
        total += select(use[sx][sy],
                        w_l * area[sx][sy] / T(kMapDomainArea<T>) *
                            packed_block_density(points, level, cx, cy, dx, dy, x),
                        T(0));
      }
  }
  return select(in_disk, total, T(0));
}

}  // namespace glintlab::kemppinen2025

// The marginal density of Algorithm 2 (sample_density_square, kemppinen_sampling.h) on a SIMD
// batch, per level either with the work of its points packed by (point, lane) or with every point
// computed on every lane (the unpacked loops): the same bits in every lane that the result depends
// on either way.
//
// Why: unpacked, level_points computes a point's lobe width (the map's inverse and D), its N_j(x)
// and its masses in the blocks (erfs) on every lane whenever one lane needs them. Where a batch's
// lanes are unrelated rows, each at its own level and angular cell, most lanes need few of them:
// at level 0 (every query whose footprint is below a cell, most of a typical call) only the centre
// cell of a point's 3 × 3 angular cells exists, and the upper level of such a row has weight 0.
// Packed, the cheap part of every point (its cell hash, angular position and whether it exists)
// stays on the batch's lanes; the (point, lane) pairs that exist and lie in a block the lane uses
// are then gathered into full vectors, which compute the rest: spatial weight s_j, σ_j, s_j N_j(x)
// and the masses along x and y over the block starts that lane uses. But where the lanes are
// neighbouring pixels of a frame they share their level, and most lanes need most of the points
// that any lane needs: packing then only adds its bookkeeping (a Table 3 frame at 25° took 30–45 %
// longer packed). So each level counts, from the angular cells that lie in the square and the
// blocks each lane uses (no hashing), the (offset, lane) pairs the lanes need against the offsets
// any lane needs, and packs only where the pairs fill less than kPackBelow of those offsets' lanes
// (use_packed_level).
//
// The packed arithmetic of each pair is that of candidate(), level_points() and mass_along() on its
// lane's inputs, and SIMD arithmetic is lane by lane, so each value is the unpacked one bit for
// bit; a pair's s_j, term and masses are 0 where it was not packed, which gives the same sums in
// every lane whose block is used (see packed_block_density), and the other lanes' results are
// discarded by sample_density_square. tests/simd/kemppinen_packed_density_test.cpp pins it to the
// unpacked loops with every level packed, every level unpacked and the choice.
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

// The bit of a mass needed along `axis` over the blocks of start offset slot `slot`.
GLINTLAB_INLINE std::uint32_t mass_bit(int axis, int slot) {
  return std::uint32_t(1) << (axis * kMaxSide + slot);
}

// The per-lane inputs of a level that a point's work reads from its lane.
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
  // (mass_bit: a block (dx, dy) that the lane uses holds the point where dx ≤ a ≤ dx + n − 1 and
  // dy ≤ b ≤ dy + n − 1).
  static constexpr std::size_t kOffsets = (2 * kMaxSide - 1) * (2 * kMaxSide - 1);
  std::uint32_t lanes_at[kOffsets];
  std::uint32_t masses_at[kOffsets][kLanes];
};

// The bits of the lanes where m is set.
template <class T>
GLINTLAB_INLINE std::uint32_t lane_bits(const Mask<T>& m) {
  const MaskLanesOf<T> ml(m);
  std::uint32_t bits = 0;
  for (std::size_t l = 0; l < kLaneCount<T>; ++l) bits |= std::uint32_t(ml[l]) << l;
  return bits;
}

// Pairs waiting for a full vector: point `at` in lane `lane`, its angular position and the masses
// its lane needs (mass_bit); PackedPairs and LivePairs add what their stage reads.
template <class T>
struct PairQueue {
  using S = Scalar<T>;
  static constexpr std::size_t kLanes = kLaneCount<T>;
  static constexpr std::size_t kCapacity = 2 * kLanes;
  std::size_t count = 0;
  std::uint32_t at[kCapacity];
  std::uint32_t lane[kCapacity], masses[kCapacity];
  alignas(64) S g_x[kCapacity];
  alignas(64) S g_y[kCapacity];
  GLINTLAB_FN void copy_pair(std::size_t to, std::size_t from) {
    at[to] = at[from];
    lane[to] = lane[from];
    masses[to] = masses[from];
    g_x[to] = g_x[from];
    g_y[to] = g_y[from];
  }
};

// Pairs that exist: also their cell offsets (i, j) and cell key.
template <class T>
struct PackedPairs : PairQueue<T> {
  using Base = PairQueue<T>;
  std::int32_t i[Base::kCapacity], j[Base::kCapacity];
  std::uint64_t key[Base::kCapacity];
  GLINTLAB_FN void copy(std::size_t to, std::size_t from) {
    this->copy_pair(to, from);
    i[to] = i[from];
    j[to] = j[from];
    key[to] = key[from];
  }
};

// Pairs of positive weight (s ≠ 0): also their s_j.
template <class T>
struct LivePairs : PairQueue<T> {
  using Base = PairQueue<T>;
  alignas(64) Scalar<T> s[Base::kCapacity];
  GLINTLAB_FN void copy(std::size_t to, std::size_t from) {
    this->copy_pair(to, from);
    s[to] = s[from];
  }
};

// After a vector of the first kLanes pairs: the pairs past them moved to the front.
template <class Pairs>
GLINTLAB_FN void drop_computed_pairs(Pairs& pr) {
  constexpr std::size_t kLanes = Pairs::kLanes;
  const std::size_t rest = pr.count - kLanes;
  for (std::size_t k = 0; k < rest; ++k) pr.copy(k, kLanes + k);
  pr.count = rest;
}

// Before a vector of fewer than kLanes pairs: the lanes past them filled with copies of pair 0
// (computed and not written back).
template <class Pairs>
GLINTLAB_FN void pad_pairs(Pairs& pr) {
  for (std::size_t k = pr.count; k < Pairs::kLanes; ++k) pr.copy(k, 0);
}

// The level's per-lane inputs gathered from lanes `lane` (one per vector lane).
template <class T>
struct LaneGather {
  const std::uint32_t* lane;
  GLINTLAB_FN T operator()(const Scalar<T>* per_lane) const {
    alignas(64) Scalar<T> v[kLaneCount<T>];
    for (std::size_t l = 0; l < kLaneCount<T>; ++l) v[l] = per_lane[lane[l]];
    return LaneAccess<T>::load(v);
  }
};

// The live pairs' σ_j, term s_j N_j(x) and mass_along over the block starts their lane uses, on
// the first `count` ≤ kLanes pairs (the pairs past them, up to kLanes, copies of pair 0).
template <class Ndf, class T>
GLINTLAB_FN void live_pairs_compute(const Params<T>& p, const Ndf& ndf,
                                    const PackedLevelInputs<T>& in, const LivePairs<T>& pr,
                                    std::size_t count, PackedLevelPoints<T>& out) {
  const LaneGather<T> gather{pr.lane};
  const Vec2<T> g_a{LaneAccess<T>::load(pr.g_x), LaneAccess<T>::load(pr.g_y)};
  Params<T> lane_p = p;
  lane_p.microroughness = gather(in.microroughness);
  lane_p.anisotropy = gather(in.anisotropy);
  Ndf lane_ndf = ndf;
  lane_ndf.alpha_x = gather(in.alpha_x);
  lane_ndf.alpha_y = gather(in.alpha_y);
  const T s = LaneAccess<T>::load(pr.s);
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
      const std::uint32_t bit = mass_bit(axis, slot);
      bool any = false;
      for (std::size_t l = 0; l < count; ++l) any = any || (pr.masses[l] & bit) != 0;
      if (!any) continue;
      const T lo = gather(in.lo[axis][slot]), hi = gather(in.hi[axis][slot]);
      const LanesOf<T> m_lanes(
          axis == 0 ? gaussian_interval_mass(lo, hi, g_a.x, sigma.x, Erf::kExact)
                    : gaussian_interval_mass(lo, hi, g_a.y, sigma.y, Erf::kExact));
      for (std::size_t l = 0; l < count; ++l)
        if (pr.masses[l] & bit) out.mass[axis][slot][pr.at[l]][pr.lane[l]] = m_lanes[l];
    }
}

// Pair (at, lane) of weight s at (g_x, g_y) queued for live_pairs_compute, which runs when a
// vector is full.
template <class Ndf, class T>
GLINTLAB_FN void queue_live_pair(const Params<T>& p, const Ndf& ndf,
                                 const PackedLevelInputs<T>& in, std::uint32_t at,
                                 std::uint32_t lane, std::uint32_t masses, Scalar<T> g_x,
                                 Scalar<T> g_y, Scalar<T> s, LivePairs<T>& live,
                                 PackedLevelPoints<T>& out) {
  const std::size_t k = live.count++;
  live.at[k] = at;
  live.lane[k] = lane;
  live.masses[k] = masses;
  live.g_x[k] = g_x;
  live.g_y[k] = g_y;
  live.s[k] = s;
  if (live.count < kLaneCount<T>) return;
  live_pairs_compute(p, ndf, in, live, kLaneCount<T>, out);
  drop_computed_pairs(live);
}

// The pairs' candidate() weight s_j, on the first `count` ≤ kLanes pairs (the pairs past them, up
// to kLanes, copies of pair 0); those of s_j ≠ 0 queued for their lobes and masses.
template <class Ndf, class T>
GLINTLAB_FN void packed_pairs_compute(const Params<T>& p, const Ndf& ndf,
                                      const PackedLevelInputs<T>& in, const PackedPairs<T>& pr,
                                      std::size_t count, LivePairs<T>& live,
                                      PackedLevelPoints<T>& out) {
  using S = Scalar<T>;
  constexpr std::size_t kLanes = kLaneCount<T>;
  const LaneGather<T> gather{pr.lane};
  LaneInt<T, std::uint64_t> key;
  LaneInt<T> sx, sy;
  for (std::size_t l = 0; l < kLanes; ++l) {
    key.v[l] = pr.key[l];
    sx.v[l] = in.sx0[pr.lane[l]] + std::int64_t(pr.i[l]);
    sy.v[l] = in.sy0[pr.lane[l]] + std::int64_t(pr.j[l]);
  }
  const Normal2Form<T> lobe{
      {gather(in.lobe_xx), gather(in.lobe_xy), gather(in.lobe_yy)},
      gather(in.lobe_c),
      gather(in.lobe_det),
      gather(in.lobe_peak)};
  const LanesOf<T> s_lanes(point_weight(p, key, sx, sy, gather(in.res_s), gather(in.w_l),
                                        Vec2<T>{gather(in.x_s_x), gather(in.x_s_y)}, lobe));
  for (std::size_t l = 0; l < count; ++l) {
    out.s[pr.at[l]][pr.lane[l]] = s_lanes[l];
    // A pair of weight 0 needs neither its lobe nor its masses (adds_weight).
    if (s_lanes[l] == S(0)) continue;
    queue_live_pair(p, ndf, in, pr.at[l], pr.lane[l], pr.masses[l], pr.g_x[l], pr.g_y[l],
                    s_lanes[l], live, out);
  }
}

// The points of a level around x's angular cell (cx, cy), as level_points and mass_along give
// them, for the lanes that use a block that holds them (in.lanes_at); 0 elsewhere.
template <class Ndf, class T>
GLINTLAB_FN void packed_level_points(const Params<T>& p, const Ndf& ndf,
                                     const LaneInt<T, int>& level, const LaneInt<T>& cx,
                                     const LaneInt<T>& cy, const PackedLevelInputs<T>& in,
                                     PackedLevelPoints<T>& out, int process) {
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
  LaneInt<T> sx0, sy0;
  for (std::size_t l = 0; l < kLanes; ++l) {
    sx0.v[l] = in.sx0[l];
    sy0.v[l] = in.sy0[l];
  }
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
          const std::uint32_t todo = lane_bits<T>(valid) & in.lanes_at[ab];
          if (todo == 0) continue;
          const std::uint32_t at = std::uint32_t(out.index(i, j, a, b));
          const LanesOf<T> gx(g_a.x), gy(g_a.y);
          for (std::uint32_t rest = todo; rest != 0; rest &= rest - 1) {
            const std::size_t l = std::size_t(std::countr_zero(rest));
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
            drop_computed_pairs(pairs);
          }
        }
      }
    }
  }
  if (pairs.count > 0) {
    pad_pairs(pairs);
    packed_pairs_compute(p, ndf, in, pairs, pairs.count, live, out);
  }
  if (live.count > 0) {
    pad_pairs(live);
    live_pairs_compute(p, ndf, in, live, live.count, out);
  }
}

// level_block_density of the block with angular start (cx + dx, cy + dy) from packed points: the
// same bits in every lane that uses the block. A lane's pair that was not computed (the point does
// not exist there, or adds no weight, or lies in no block the lane uses) has s = term = mass = 0,
// where the unpacked sum adds s·m = ±0 and a term of 0, so each used lane's sums are the same.
template <class T>
GLINTLAB_FN T packed_block_density(const PackedLevelPoints<T>& pts, const LaneInt<T, int>& level,
                                   const LaneInt<T>& cx, const LaneInt<T>& cy, int dx, int dy,
                                   Vec2<T> x) {
  const int n = pts.n;
  const BlockBounds<T> bounds =
      block_bounds(cx + dx, cy + dy, n, level_cells<T>(level), angular_resolution<T>(level));
  const Vec2<T> lo = bounds.lo, hi = bounds.hi;
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

// Per angular offset a ∈ [1 − n, n − 1] (index a + n − 1): the bits of the lanes where the cell
// cx + a lies in the level's cells [0, n_a).
template <class T>
GLINTLAB_FN void cells_in_square(const LaneInt<T>& cx, const LaneInt<T>& n_a, int n,
                                 std::uint32_t (&out)[2 * kMaxSide - 1]) {
  for (int a = 1 - n; a <= n - 1; ++a) {
    std::uint32_t bits = 0;
    for (std::size_t l = 0; l < kLaneCount<T>; ++l) {
      const std::int64_t c = lane(cx, l) + a;
      bits |= std::uint32_t(c >= 0 && c < lane(n_a, l)) << l;
    }
    out[a + n - 1] = bits;
  }
}

// Packing pays where the (offset, lane) pairs that the lanes need fill less than this share of the
// lanes of the offsets that some lane needs. Not tuned: the lanes of a Table 3 frame's level need
// nearly every offset that any lane needs, while unrelated rows are at their own levels and cells;
// with 0.5 the frames run at the unpacked loops' speed and glintlab_bench_models' random rows on
// AVX-512 at the packed loops' (docs/benchmarks.md).
inline constexpr double kPackBelow = 0.5;

// Whether a level's points are packed: the angular offsets (a, b) whose cell lies in the square in
// some lane that uses a block holding it (in.lanes_at), and the pairs of such lanes, counted.
template <class T>
GLINTLAB_FN bool use_packed_level(const PackedLevelInputs<T>& in, const LaneInt<T>& cx,
                                  const LaneInt<T>& cy, const LaneInt<T>& n_a, int n) {
  std::uint32_t in_x[2 * kMaxSide - 1], in_y[2 * kMaxSide - 1];
  cells_in_square<T>(cx, n_a, n, in_x);
  cells_in_square<T>(cy, n_a, n, in_y);
  const std::size_t span = std::size_t(2 * n - 1);
  std::size_t offsets = 0, pairs = 0;
  for (std::size_t ka = 0; ka < span; ++ka)
    for (std::size_t kb = 0; kb < span; ++kb) {
      const std::uint32_t lanes = in.lanes_at[ka * span + kb] & in_x[ka] & in_y[kb];
      offsets += lanes != 0;
      pairs += std::size_t(std::popcount(lanes));
    }
  // No point in any lane: packed, nothing past the hashes is computed.
  return offsets == 0 || double(pairs) < kPackBelow * double(offsets * kLaneCount<T>);
}

// sample_density_square on a batch (more than one lane): each level packed or unpacked (`path`).
template <class Ndf, class T>
GLINTLAB_FN T sample_density_square_packed(const Params<T>& p, const Ndf& ndf,
                                           const FootprintQuery<T>& fp, Vec2<T> x, int process,
                                           DensityPath path) {
  constexpr std::size_t kLanes = kLaneCount<T>;
  using A = LaneAccess<T>;
  const Mask<T> in_disk = !(sqr(x.x - T(0.5)) + sqr(x.y - T(0.5)) > T(0.25));
  if (!any_lane<T>(in_disk)) return T(0);
  const Spatial<T> sp = spatial(p, fp);
  const int n = p.side;
  const std::size_t span = std::size_t(2 * n - 1);
  PackedLevelInputs<T> in;
  T total = T(0);
  for (int up = 0; up < 2; ++up) {
    const DensityLevel<T> d = density_level(sp, up, x);
    if (!any_lane<T>(d.w_positive)) continue;
    // Every block's area and use first, so that only the pairs in used blocks are packed.
    LevelBlocks<T> blocks;
    level_blocks(d, n, blocks);
    if (!blocks.any_use) continue;
    std::uint32_t use_bits[kMaxSide][kMaxSide];
    for (std::size_t ab = 0; ab < span * span; ++ab) in.lanes_at[ab] = 0;
    for (int dx = 1 - n; dx <= 0; ++dx)
      for (int dy = 1 - n; dy <= 0; ++dy) {
        const int sx = dx + n - 1, sy = dy + n - 1;
        use_bits[sx][sy] = lane_bits<T>(blocks.use[sx][sy]);
        for (int a = dx; a <= dx + n - 1; ++a)
          for (int b = dy; b <= dy + n - 1; ++b)
            in.lanes_at[std::size_t(a + n - 1) * span + std::size_t(b + n - 1)] |=
                use_bits[sx][sy];
      }
    const LaneInt<T> n_a = level_cells<T>(d.level);
    const bool packed = path == DensityPath::kChoose ? use_packed_level(in, d.cx, d.cy, n_a, n)
                                                     : path == DensityPath::kPacked;
    if (!packed) {
      add_level_density_unpacked(p, ndf, sp, d, blocks, x, process, total);
      continue;
    }
    for (std::size_t ab = 0; ab < span * span; ++ab)
      for (std::size_t l = 0; l < kLanes; ++l) in.masses_at[ab][l] = 0;
    for (int dx = 1 - n; dx <= 0; ++dx)
      for (int dy = 1 - n; dy <= 0; ++dy) {
        const int sx = dx + n - 1, sy = dy + n - 1;
        const std::uint32_t bits = mass_bit(0, sx) | mass_bit(1, sy);
        for (int a = dx; a <= dx + n - 1; ++a)
          for (int b = dy; b <= dy + n - 1; ++b) {
            const std::size_t ab = std::size_t(a + n - 1) * span + std::size_t(b + n - 1);
            for (std::uint32_t rest = use_bits[sx][sy]; rest != 0; rest &= rest - 1)
              in.masses_at[ab][std::countr_zero(rest)] |= bits;
          }
      }
    A::store(sp.x_s.x, in.x_s_x);
    A::store(sp.x_s.y, in.x_s_y);
    const Normal2Form<T> spatial_lobe = normal2_form(sp.sigma_s);
    A::store(spatial_lobe.sc.xx, in.lobe_xx);
    A::store(spatial_lobe.sc.xy, in.lobe_xy);
    A::store(spatial_lobe.sc.yy, in.lobe_yy);
    A::store(spatial_lobe.c, in.lobe_c);
    A::store(spatial_lobe.det, in.lobe_det);
    A::store(spatial_lobe.peak, in.lobe_peak);
    A::store(x.x, in.x_x);
    A::store(x.y, in.x_y);
    A::store(p.microroughness, in.microroughness);
    A::store(p.anisotropy, in.anisotropy);
    A::store(ndf.alpha_x, in.alpha_x);
    A::store(ndf.alpha_y, in.alpha_y);
    const T res_s = sp.res / d.res_a;
    A::store(res_s, in.res_s);
    A::store(d.w_l, in.w_l);
    const LaneInt<T> sx0 = block_start(sp.x_s.x * res_s, n);
    const LaneInt<T> sy0 = block_start(sp.x_s.y * res_s, n);
    for (std::size_t l = 0; l < kLanes; ++l) {
      in.sx0[l] = lane(sx0, l);
      in.sy0[l] = lane(sy0, l);
    }
    for (int off = 1 - n; off <= 0; ++off) {
      const std::size_t slot = std::size_t(off + n - 1);
      const BlockBounds<T> bounds = block_bounds(d.cx + off, d.cy + off, n, n_a, d.res_a);
      A::store(bounds.lo.x, in.lo[0][slot]);
      A::store(bounds.lo.y, in.lo[1][slot]);
      A::store(bounds.hi.x, in.hi[0][slot]);
      A::store(bounds.hi.y, in.hi[1][slot]);
    }
    // On the stack, as LevelPoints in add_level_density_unpacked.
    PackedLevelPoints<T> points;
    packed_level_points(p, ndf, d.level, d.cx, d.cy, in, points, process);
    add_block_terms(
        d, blocks, n,
        [&](int dx, int dy) {
          return packed_block_density(points, d.level, d.cx, d.cy, dx, dy, x);
        },
        total);
  }
  return select(in_disk, total, T(0));
}

}  // namespace glintlab::kemppinen2025

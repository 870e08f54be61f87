// The implicit 4D jittered grid of Kemppinen et al. 2025 Sec. 3.3.1–3.3.2: one point per cell of
// [0,1)² (space, repeated over the plane) × [0,1)² (the angular square holding U_Ω), its random
// numbers from a counter hash of the cell index, and the k-neighbouring cells of Algorithm 1.
//
// Cell indices are integers per query: on a SIMD batch they are per-lane integers (LaneInt of
// core/math/lanes.h). The chain steps here hash them lane by lane with the scalar code
// (cell_chain_*_lanes); the batch kernels' later steps (ax, ay and level), cell keys and uniforms
// run on vector registers (kemppinen_lanes.h), the same bits lane by lane.
#pragma once

#include <cstdint>

#include "core/math/lanes.h"
#include "core/math/ops.h"
#include "core/math/rng.h"
#include "core/math/vec.h"

namespace glintlab::kemppinen2025 {

// The cell (i_s, i_a, l) of Algorithm 1 lines 15–17: spatial cell (sx, sy) and angular cell
// (ax, ay) at MIP level l, plus the triplanar process index (Sec. 3.3.6, 0 for plain uv).
struct Cell {
  std::int64_t sx, sy, ax, ay;
  int level;
  int process;
};

// The random-number dimensions of one cell (Rand2D twice, Rand1D for the roulette, GlintColor).
enum Dim : std::uint64_t {
  kKemppinenDimSpatialX = 0,
  kKemppinenDimSpatialY = 1,
  kKemppinenDimAngularX = 2,
  kKemppinenDimAngularY = 3,
  kKemppinenDimRoulette = 4,
  kKemppinenDimColor = 5,
};

// The counter index of a cell: the paper seeds an RNG with the cell index (Sec. 3.3.1, "a
// congruential RNG as they are fast to seed"); here the SplitMix64 finalizer of core/math/rng.h
// chained over the six integers, so neighbouring cells get unrelated streams. One step per
// coordinate, named so that a loop over cells can hoist the steps whose inputs it does not change
// (the reference sum, kemppinen_reference.h).
GLINTLAB_FN std::uint64_t cell_chain_sx(std::int64_t sx) {
  return mix64(static_cast<std::uint64_t>(sx) + 0x9e3779b97f4a7c15ULL);
}
GLINTLAB_FN std::uint64_t cell_chain_sy(std::uint64_t h, std::int64_t sy) {
  return mix64(h ^ (static_cast<std::uint64_t>(sy) * 0xd1b54a32d192ed03ULL));
}
GLINTLAB_FN std::uint64_t cell_chain_ax(std::uint64_t h, std::int64_t ax) {
  return mix64(h ^ (static_cast<std::uint64_t>(ax) * 0x8cb92ba72f3d8dd7ULL));
}
GLINTLAB_FN std::uint64_t cell_chain_ay(std::uint64_t h, std::int64_t ay) {
  return mix64(h ^ (static_cast<std::uint64_t>(ay) * 0xabc98388fb8fac03ULL));
}
GLINTLAB_FN std::uint64_t cell_chain_level(std::uint64_t h, int level, int process) {
  return mix64(h ^ (static_cast<std::uint64_t>(level) << 8) ^ static_cast<std::uint64_t>(process));
}
GLINTLAB_FN std::uint64_t cell_index(const Cell& c) {
  return cell_chain_level(
      cell_chain_ay(cell_chain_ax(cell_chain_sy(cell_chain_sx(c.sx), c.sy), c.ax), c.ay), c.level,
      c.process);
}

// The uniform number of dimension `dim` of the point of the cell with index
// kemppinen2025::cell_index(c): r ∈ [0,1) (Sec. 3.3.1).
template <class T>
GLINTLAB_FN T cell_uniform(std::uint64_t seed, std::uint64_t cell_index, std::uint64_t dim) {
  return counter_uniform<T>(seed, cell_index, dim);
}
// The same for a batch: the cell index of each lane.
template <class T, class I, std::size_t N>
GLINTLAB_FN T cell_uniform(std::uint64_t seed, const IntLanes<I, N>& cell_index,
                           std::uint64_t dim) {
  return float_lanes<T>(
      [&](std::size_t l) { return counter_uniform<Scalar<T>>(seed, cell_index.v[l], dim); });
}

// kemppinen2025::cell_index of the cell (sx, sy, ax, ay, level, process) in every lane of T.
template <class T, class C, class L>
GLINTLAB_FN LaneInt<T, std::uint64_t> cell_index_lanes(const C& sx, const C& sy, const C& ax,
                                                       const C& ay, const L& level, int process) {
  return int_lanes<T, std::uint64_t>([&](std::size_t l) {
    return kemppinen2025::cell_index(
        Cell{lane(sx, l), lane(sy, l), lane(ax, l), lane(ay, l), lane(level, l), process});
  });
}

// The chain steps of cell_index in every lane, so that a loop over the cells of a block hashes
// each spatial row and column once rather than once per cell (cell_index_lanes = level step of the
// ay step of the ax step of the sy step of the sx step, bit for bit).
template <class T, class C>
GLINTLAB_FN LaneInt<T, std::uint64_t> cell_chain_sx_lanes(const C& sx) {
  return int_lanes<T, std::uint64_t>([&](std::size_t l) { return cell_chain_sx(lane(sx, l)); });
}
template <class T, class H, class C>
GLINTLAB_FN LaneInt<T, std::uint64_t> cell_chain_sy_lanes(const H& h, const C& sy) {
  return int_lanes<T, std::uint64_t>(
      [&](std::size_t l) { return cell_chain_sy(lane(h, l), lane(sy, l)); });
}
template <class T, class H, class C>
GLINTLAB_FN LaneInt<T, std::uint64_t> cell_chain_ax_lanes(const H& h, const C& ax) {
  return int_lanes<T, std::uint64_t>(
      [&](std::size_t l) { return cell_chain_ax(lane(h, l), lane(ax, l)); });
}
template <class T, class H, class C, class L>
GLINTLAB_FN LaneInt<T, std::uint64_t> cell_chain_ay_level_lanes(const H& h, const C& ay,
                                                                const L& level, int process) {
  return int_lanes<T, std::uint64_t>([&](std::size_t l) {
    return cell_chain_level(cell_chain_ay(lane(h, l), lane(ay, l)), lane(level, l), process);
  });
}

// First cell index of the n consecutive cells closest to coordinate `x` (in cells) along one
// axis: floor(x − (n − 1)/2). n odd: centred on the cell holding x; n even: the n cells whose
// centre block is nearest x (the k-NeighbouringCells of Algorithm 1 lines 13–14, k = n²).
template <class T>
GLINTLAB_FN LaneInt<T> block_start(T x_cells, int n) {
  return floor_int<T>(x_cells - T(0.5) * T(n - 1));
}

// The valid k of Algorithm 1 (Sec. 3.3.4): 1, 4, 9, 16 neighbours, i.e. blocks of side 1…4.
inline constexpr int kMaxSide = 4;

}  // namespace glintlab::kemppinen2025

// Importance sampling of D★^f, Kemppinen et al. 2025 Sec. 3.3.5 and Algorithm 2, with two pdfs:
// the one Algorithm 2 returns (lines 16–17), a function of the draw x_a, and the marginal density
// of what the sampler produces (over x_a, the level and every other random choice).
//
// Algorithm 2: x_a uniform on U_Ω (line 2); level ⌈λ⌉ with probability λ − ⌊λ⌋, else ⌊λ⌋
// (lines 4–6); over the k×k cells around x_s and the k angular cells B(k) around x_a, point j gets
// the reservoir weight w★_j = R(r_j, w_λ) N(Σ_s, x_s − g_s) Luminance(c_j) ∫_{B} N_j (line 12);
// one point is kept with probability w★_j/Σw★ (lines 13–15, reservoir = inverse CDF of one draw
// here), then x ~ N_j truncated to B (line 14) and ω_h = T⁻¹(x). The compensation term is not
// sampled (Sec. 3.3.5). Choice: each point's lobe width is Σ_a at its own centre g_j (Algorithm 2
// only says "same as Algorithm 1", whose Σ_a depends on the evaluated ω_h, unknown before
// sampling); with it the conditional density given x_a is constant over each region of x_a that
// selects the same B(k), so the marginal is a finite sum.
//
// The printed pdf (lines 16–17): the text of these lines is damaged in our copy; legible are
// "pdf += w★ Area(B(x_a)) PDF(N_{Σa,ga})(x)" and "pdf · |J_T(ω_h)| |ω_h·ω_g| w_λ". Implemented as
// exactly those factors: Σ_j (w★_j/Σw★) N_j(x)/∫_B N_j (the truncated mixture the sampler draws
// from, given x_a and the level) × Area(B(x_a)) × |J_T(ω_h)| × cosθ_h × w_λ, with |J_T| = D/|U_Ω|
// as Eq. 3 defines it. It depends on the draw x_a, so it is not a function of ω_h;
// kemppinen.sampling-unbiased measures the bias of the estimator it gives.
//
// The marginal: p(x) = Σ_l P(l) Σ_{B ∋ x} |R_B ∩ U_Ω|/|U_Ω| · Σ_{j∈B} s_j N_j(x)/W_B for x ∈ U_Ω,
// with R_B the cell-sized square of x_a that selects B, s_j = w★_j/∫_B N_j and W_B = Σ w★; in ω_h
// times the true Jacobian of T (core/maps: map_jacobian_true). Samples landing outside U_Ω, or
// with Σw★ = 0, are rejected (the density is defective by that probability).
//
// Generic over T (float, double, a SIMD batch): per-lane levels and cell indices are LaneInt
// (core/math/lanes.h); a block keeps all k² candidates with a validity mask (the scalar code's
// skipped cells contribute exact zeros); the reservoir choice is a masked running select; the
// `if (!any_lane<T>(...))` early-outs are uniform (all lanes), never per-lane branches.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core/glints/kemppinen.h"
#include "core/glints/kemppinen_lanes.h"
#include "core/math/disk_rect_area.h"
#include "core/ndf/microfacet.h"

namespace glintlab::kemppinen2025 {

// One candidate point of a block B(k) (Algorithm 2 lines 11–12).
template <class T>
struct Candidate {
  Vec2<T> g_a;
  Vec2<T> sigma;  // the lobe's; left 0 where s = 0 in every lane (each use is weighted by s)
  T s;            // R(r, w_λ) N(Σ_s, x_s − g_s) Luminance(c): the weight before the lobe's mass
  T m;            // ∫_B N_j; left 0 where s = 0 in every lane (it only adds s·m = 0)
  Mask<T> valid;  // the cell is inside □ and its point inside U_Ω (else s = m = 0)
};

template <class T>
struct Block {
  std::array<Candidate<T>, kMaxSide * kMaxSide * kMaxSide * kMaxSide> c;
  int count = 0;
  Vec2<T> lo, hi;  // B(k) clipped to □
  T total = T(0);  // Σ w★ = Σ s_j m_j
};

// The spatial frame of a query, as Algorithm 1 lines 1–5 compute it.
template <class T>
struct Spatial {
  Vec2<T> x_s;
  Sym2<T> sigma_s;
  T res, lambda, w1;
  LaneInt<T, int> l0;
};

template <class T>
GLINTLAB_FN Spatial<T> spatial(const Params<T>& p, const FootprintQuery<T>& fp) {
  Spatial<T> s;
  s.res = base_resolution(p);
  s.x_s = spatial_position(p, fp.uv);
  s.sigma_s = spatial_covariance(p, fp, s.res);
  s.lambda = lod(s.sigma_s, s.res);
  const T fl = min(floor(s.lambda), T(kMaxLevel - 1));
  s.l0 = floor_int<T, int>(fl);
  s.w1 = s.lambda - fl;
  return s;
}

// Lobe standard deviations of a point at g_a (Σ_a of Algorithm 1 line 12 at ω = T⁻¹(g_a)).
template <class Ndf, class T>
GLINTLAB_FN Vec2<T> point_sigma(const Params<T>& p, const Ndf& ndf, Vec2<T> g_a) {
  const Vec3<T> w = map_from_square(ndf, g_a);
  const T sigma = p.microroughness * sqrt(ndf.D(w) / T(kMapDomainArea<T>));
  const T sa = sqrt(p.anisotropy);
  return {sigma / sa, sigma * sa};
}

// The weight of Algorithm 2 line 12 before the lobe's mass, R(r, w_λ) N(Σ_s, x_s − g_s)
// Luminance(c), of the point of cell key `key` (cell_key) in spatial cell (sx, sy); res_s is the
// level's spatial resolution, spatial_lobe normal2_form(sp.sigma_s). candidate() and the packed
// loops (kemppinen_packed.h) share it, so that their weights are the same bits.
template <class T>
GLINTLAB_INLINE T point_weight(const Params<T>& p, const LaneInt<T, std::uint64_t>& key,
                               const LaneInt<T>& sx, const LaneInt<T>& sy, T res_s, T w_l,
                               Vec2<T> x_s, const Normal2Form<T>& spatial_lobe) {
  const Vec2<T> g_s{(int_to_float<T>(sx) + key_uniform<T>(key, kKemppinenDimSpatialX)) / res_s,
                    (int_to_float<T>(sy) + key_uniform<T>(key, kKemppinenDimSpatialY)) / res_s};
  const T r = key_uniform<T>(key, kKemppinenDimRoulette);
  const T blend = p.blend == Blend::kRoulette ? roulette(r, w_l) : w_l;
  const Vec3<T> col = color(p.colors, key_uniform<T>(key, kKemppinenDimColor));
  return blend * normal2_at(spatial_lobe, x_s - g_s) * luminance(col);
}

// The bounds of the block of side n with angular start cell (ax0, ay0), clipped to □ (n_a cells
// of side 1/res_a per axis).
template <class T>
struct BlockBounds {
  Vec2<T> lo, hi;
};
template <class T>
GLINTLAB_INLINE BlockBounds<T> block_bounds(const LaneInt<T>& ax0, const LaneInt<T>& ay0, int n,
                                            const LaneInt<T>& n_a, T res_a) {
  return {{int_to_float<T>(int_max(ax0, std::int64_t(0))) / res_a,
           int_to_float<T>(int_max(ay0, std::int64_t(0))) / res_a},
          {int_to_float<T>(int_min(ax0 + n, n_a)) / res_a,
           int_to_float<T>(int_min(ay0 + n, n_a)) / res_a}};
}

// The candidate of spatial cell (sx, sy) and angular cell (ax, ay), cell index ci (of its level
// and point process: cell_index_lanes), at level weight w_l (Algorithm 2 lines 11–12): everything
// but its mass in a block (m = 0). res_a, res_s and n_a are the level's (angular_resolution,
// sp.res / res_a, level_cells), spatial_lobe normal2_form(sp.sigma_s).
// (Forced inline: its Vec2 and lane-integer arguments would otherwise pass through memory.)
template <class Ndf, class T>
GLINTLAB_INLINE Candidate<T> candidate(const Params<T>& p, const Ndf& ndf, const Spatial<T>& sp,
                                   const Normal2Form<T>& spatial_lobe, T w_l, T res_a, T res_s,
                                   const LaneInt<T>& n_a, const LaneInt<T>& sx,
                                   const LaneInt<T>& sy, const LaneInt<T>& ax,
                                   const LaneInt<T>& ay, const LaneInt<T, std::uint64_t>& ci) {
  // Its uniforms from one key per cell (kemppinen_lanes.h).
  const LaneInt<T, std::uint64_t> key = cell_key<T>(cell_seed_key(p.seed), ci);
  Candidate<T> k;
  k.valid = mask_lanes<T>([&](std::size_t l) {
    return lane(ax, l) >= 0 && lane(ax, l) < lane(n_a, l) && lane(ay, l) >= 0 &&
           lane(ay, l) < lane(n_a, l);
  });
  k.g_a = {(int_to_float<T>(ax) + key_uniform<T>(key, kKemppinenDimAngularX)) / res_a,
           (int_to_float<T>(ay) + key_uniform<T>(key, kKemppinenDimAngularY)) / res_a};
  k.valid = k.valid && (sqr(k.g_a.x - T(0.5)) + sqr(k.g_a.y - T(0.5)) <= T(0.25));
  k.s = T(0);
  k.m = T(0);
  k.sigma = {T(0), T(0)};
  if (any_lane<T>(k.valid)) {  // uniform: some lane has the point
    k.s = select(k.valid, point_weight(p, key, sx, sy, res_s, w_l, sp.x_s, spatial_lobe), T(0));
    // A point the roulette gives weight 0 (w_l below r − ε, Eq. 8) needs no lobe.
    if (any_lane<T>(k.valid && !(k.s == T(0)))) k.sigma = point_sigma(p, ndf, k.g_a);
  }
  return k;
}

// Whether candidate k adds anything to a block's Σw★ (s ≠ 0 in some lane where it exists): else
// its mass is not needed.
template <class T>
GLINTLAB_FN bool adds_weight(const Candidate<T>& k) {
  return any_lane<T>(k.valid && !(k.s == T(0)));
}

// The candidates of block B with angular start cell (ax0, ay0) at `level` (weight w_l), of point
// process `process` (0 = uv; the triplanar planes: triplanar_process).
template <class Ndf, class T>
GLINTLAB_FN void block(const Params<T>& p, const Ndf& ndf, const Spatial<T>& sp, const LaneInt<T, int>& level,
           T w_l, const LaneInt<T>& ax0, const LaneInt<T>& ay0, Block<T>& out, int process = 0) {
  const int n = p.side;
  const T res_a = angular_resolution<T>(level);
  const T res_s = sp.res / res_a;
  const LaneInt<T> n_a = level_cells<T>(level);
  const LaneInt<T> sx0 = block_start(sp.x_s.x * res_s, n);
  const LaneInt<T> sy0 = block_start(sp.x_s.y * res_s, n);
  const Normal2Form<T> spatial_lobe = normal2_form(sp.sigma_s);
  const BlockBounds<T> bounds = block_bounds(ax0, ay0, n, n_a, res_a);
  out.lo = bounds.lo;
  out.hi = bounds.hi;
  out.count = 0;
  out.total = T(0);
  for (int i = 0; i < n; ++i) {
    const LaneInt<T> sx = sx0 + i;
    const LaneInt<T, std::uint64_t> hash_i = cell_chain_sx_lanes<T>(sx);
    for (int j = 0; j < n; ++j) {
      const LaneInt<T> sy = sy0 + j;
      const LaneInt<T, std::uint64_t> hash_ij = cell_chain_sy_lanes<T>(hash_i, sy);
      for (int a = 0; a < n; ++a) {
        const LaneInt<T> ax = ax0 + a;
        const LaneInt<T, std::uint64_t> hash_ija = cell_chain_ax_lanes<T>(hash_ij, ax);
        for (int b = 0; b < n; ++b) {
          const LaneInt<T> ay = ay0 + b;
          Candidate<T> k =
              candidate(p, ndf, sp, spatial_lobe, w_l, res_a, res_s, n_a, sx, sy, ax, ay,
                        cell_chain_ay_level_vector<T>(hash_ija, ay, level, process));
          if (adds_weight(k))
            k.m = select(k.valid, gaussian_rect_mass(out.lo, out.hi, k.g_a, k.sigma, Erf::kExact),
                         T(0));
          // Invalid lanes and those of weight 0 add ±0 (m is finite: max(v, 0) drops a NaN), so
          // the sum is unchanged.
          out.total += k.s * k.m;
          out.c[std::size_t(out.count++)] = k;
        }
      }
    }
  }
}

// Σ_j s_j N_j(x) / W over a block: the density in the square of the sample given the block.
template <class T>
GLINTLAB_FN T block_density(const Block<T>& b, Vec2<T> x) {
  const Mask<T> inside =
      (b.total > T(0)) && !(x.x < b.lo.x || x.x > b.hi.x || x.y < b.lo.y || x.y > b.hi.y);
  if (!any_lane<T>(inside)) return T(0);
  T sum = T(0);
  for (int j = 0; j < b.count; ++j) {
    const Candidate<T>& k = b.c[std::size_t(j)];
    // A point of zero spatial weight adds nothing, and a point whose lobe collapsed (σ = 0: D
    // underflowed to 0 at g_a on the rim of U_Ω, in float well before double) is a delta that
    // adds nothing at any other x; masked, or 0 · N(0/0) made the density NaN (stability sweep,
    // float pdf at density ≥ 2.1e7). Every result that was finite before is unchanged.
    const Mask<T> live = k.valid && (k.s > T(0)) && (k.sigma.x > T(0)) && (k.sigma.y > T(0));
    if (!any_lane<T>(live)) continue;  // it adds +0
    const T t = k.s * normal2(x - k.g_a, Sym2<T>{sqr(k.sigma.x), T(0), sqr(k.sigma.y)});
    sum += select(live, t, T(0));
  }
  return select(inside, sum / b.total, T(0));
}

// One draw of the 1D normal N(m, s²) truncated to [lo, hi] by inverting its CDF with erf/erfinv.
template <class T>
GLINTLAB_FN T truncated_normal(T lo, T hi, T m, T s, T u) {
  const T k = T(0.70710678118654752440) / s;
  const T ea = erf((lo - m) * k), eb = erf((hi - m) * k);
  const T z = erfinv(clamp(ea + u * (eb - ea), T(-1) + T(1e-16), T(1) - T(1e-16)));
  return clamp(m + z / k, lo, hi);
}

template <class T>
struct HalfSample {
  Vec2<T> x;            // the point in □ (T(ω_h))
  Vec3<T> h;            // ω_h = T⁻¹(x)
  T pdf_printed_h;      // Algorithm 2's pdf (lines 16–17, as read above), per steradian of ω_h
  T pdf_conditional_x;  // density in □ given x_a and the level
  LaneInt<T, int> level;
  Mask<T> ok;  // false: Σw★ = 0 or x outside U_Ω (no direction)
};

// The random number `dim` of one sampler call keyed by `key`.
template <class T>
GLINTLAB_FN T sampler_uniform(std::uint64_t key, std::uint64_t dim) {
  return counter_uniform<T>(key, 0x6b656d70ULL, dim);
}
// The same for a batch: the key of each lane.
template <class T, class I, std::size_t N>
GLINTLAB_FN T sampler_uniform(const IntLanes<I, N>& key, std::uint64_t dim) {
  return float_lanes<T>(
      [&](std::size_t l) { return counter_uniform<Scalar<T>>(key.v[l], 0x6b656d70ULL, dim); });
}

// Algorithm 2: one ω_h from D★^f of point process `process` at the footprint, random numbers
// from `key`.
template <class Ndf, class T>
GLINTLAB_FN HalfSample<T> sample_half(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp,
                          const LaneInt<T, std::uint64_t>& key, int process = 0) {
  const Mask<T> kNone = T(0) > T(1);
  HalfSample<T> out;
  out.x = {T(0), T(0)};
  out.h = {T(0), T(0), T(0)};
  out.pdf_printed_h = T(0);
  out.pdf_conditional_x = T(0);
  out.ok = kNone;
  const Spatial<T> sp = spatial(p, fp);
  // Line 2: uniform on the disk of radius ½ at (½, ½).
  const T ur = sqrt(sampler_uniform<T>(key, 0));
  const T phi = T(2) * T(kPi<T>) * sampler_uniform<T>(key, 1);
  const Vec2<T> x_a{T(0.5) + T(0.5) * ur * cos(phi), T(0.5) + T(0.5) * ur * sin(phi)};
  // Lines 4–6.
  const Mask<T> up = sampler_uniform<T>(key, 2) < sp.w1;
  out.level = sp.l0 + mask_to_int<T>(up);
  const T w_l = select(up, sp.w1, T(1) - sp.w1);
  const T res_a = angular_resolution<T>(out.level);
  // On the stack, as LevelPoints in sample_density_square (static TLS would grow every thread's
  // stack, and a device thread has none): block() writes every field it reads.
  Block<T> block;
  kemppinen2025::block(p, ndf, sp, out.level, w_l, block_start(x_a.x * res_a, p.side),
                       block_start(x_a.y * res_a, p.side), block, process);
  const Mask<T> has = block.total > T(0);
  if (!any_lane<T>(has)) return out;
  // Lines 13–15: keep point j with probability w★_j/Σw★: the first j whose running sum exceeds
  // the pick; where rounding leaves none, the last point of positive weight.
  const auto select2 = [](const Mask<T>& m, Vec2<T> a, Vec2<T> b) {
    return Vec2<T>{select(m, a.x, b.x), select(m, a.y, b.y)};
  };
  const T pick = sampler_uniform<T>(key, 3) * block.total;
  T acc = T(0);
  Mask<T> found = kNone;
  Vec2<T> hit_g = block.c[0].g_a, hit_sigma = block.c[0].sigma;
  Vec2<T> last_g = hit_g, last_sigma = hit_sigma;
  for (int j = 0; j < block.count; ++j) {
    const Candidate<T>& c = block.c[std::size_t(j)];
    acc += c.s * c.m;
    const Mask<T> hit = !found && (pick < acc);
    hit_g = select2(hit, c.g_a, hit_g);
    hit_sigma = select2(hit, c.sigma, hit_sigma);
    found = found || hit;
    const Mask<T> positive = c.m * c.s > T(0);
    last_g = select2(positive, c.g_a, last_g);
    last_sigma = select2(positive, c.sigma, last_sigma);
  }
  const Vec2<T> g = select2(found, hit_g, last_g), sigma = select2(found, hit_sigma, last_sigma);
  // Line 14: x ~ 1_B N_j.
  const Vec2<T> x{
      truncated_normal(block.lo.x, block.hi.x, g.x, sigma.x, sampler_uniform<T>(key, 4)),
      truncated_normal(block.lo.y, block.hi.y, g.y, sigma.y, sampler_uniform<T>(key, 5))};
  out.x = select2(has, x, out.x);
  const Mask<T> in_disk = has && !(sqr(x.x - T(0.5)) + sqr(x.y - T(0.5)) > T(0.25));
  if (!any_lane<T>(in_disk)) return out;
  const Vec3<T> h = map_from_square(ndf, x);
  const T pdf_x = block_density(block, x);
  const T area_b = (block.hi.x - block.lo.x) * (block.hi.y - block.lo.y);
  const T pdf_printed = pdf_x * area_b * map_jacobian_paper(ndf, h) * h.z * w_l;
  out.h = select(in_disk, h, out.h);
  out.pdf_conditional_x = select(in_disk, pdf_x, T(0));
  out.pdf_printed_h = select(in_disk, pdf_printed, T(0));
  out.ok = in_disk && (h.z > T(0));
  return out;
}

// Every point of the blocks sample_density_square visits at one level, each computed once: a point
// lies in up to n² of those blocks, and all of it but its mass in the block (∫_B N_j) is the same
// in each. Spatial cell (i, j) of the level's n×n block, angular cell x's cell + (a, b) with
// a, b ∈ [1−n, n−1]. Each candidate holds block()'s values bit for bit (m unused), and `term` is
// block_density's summand s_j N_j(x), masked as there. A point's mass in a block, ∫_B N_j, is the
// product of its mass along x over the block's columns and along y over its rows
// (gaussian_rect_mass), and every block of the same start column (cx + dx) shares the x factor,
// every block of the same start row the y factor: each factor is computed once per point and start
// (mass_along), the erf pairs a block-by-block computation repeats up to n times.
template <class T>
struct LevelPoints {
  static constexpr int kSpan = 2 * kMaxSide - 1;
  static constexpr std::size_t kCount = kMaxSide * kMaxSide * kSpan * kSpan;
  std::array<Candidate<T>, kCount> c;
  std::array<T, kCount> term;
  // Per point and start offset d + n − 1 (d ∈ [1 − n, 0]): the mass along x (axis 0) or y (1)
  // over the blocks of that start, valid where `known`.
  std::array<std::array<std::array<T, kMaxSide>, kCount>, 2> mass;
  std::array<std::array<std::array<bool, kMaxSide>, kCount>, 2> known;
  int n = 0;
  GLINTLAB_FN std::size_t index(int i, int j, int a, int b) const {
    const int span = 2 * n - 1;
    return std::size_t(((i * n + j) * span + (a + n - 1)) * span + (b + n - 1));
  }
};

// disk_rect_area(x0, x1, y0, y1, ½, ½, ½) (core/math/disk_rect_area.h), the area of the rectangle
// inside U_Ω, bit for bit: where the rectangle lies inside the disk, or outside it, by a relative
// margin of 10⁻⁶ in squared distance (far above the rounding of the function's breakpoints and
// chords), the function takes one piece with no circular part (hy·w − ly·w) or adds none (0), and
// that is computed here without its call; elsewhere (the rectangle meets the circle, or an input
// is not finite) the function itself. Most of the marginal pdf's selecting squares are cells far
// smaller than U_Ω, and the function's atan2s were a fifth of a batched eval. Forced inline: an
// out-of-line copy would be a weak symbol that each ISA unit compiles with its own flags.
GLINTLAB_INLINE double square_disk_area(double x0, double x1, double y0, double y1) {
  const double cx = 0.5, cy = 0.5, r = 0.5;
  const double ax = x0 - cx, bx = x1 - cx, ly = y0 - cy, hy = y1 - cy;
  const bool finite =
      std::isfinite(ax) && std::isfinite(bx) && std::isfinite(ly) && std::isfinite(hy);
  if (finite && bx > ax && hy > ly) {
    const double far_x = std::max(ax * ax, bx * bx), far_y = std::max(ly * ly, hy * hy);
    if (far_x + far_y < r * r * (1.0 - 1e-6)) {
      const double w = bx - ax;  // the one piece [a, b] = [x0 − cx, x1 − cx]
      return hy * w - ly * w;
    }
    const double near_x = ax > 0.0 ? ax : (bx < 0.0 ? -bx : 0.0);
    const double near_y = ly > 0.0 ? ly : (hy < 0.0 ? -hy : 0.0);
    if (near_x * near_x + near_y * near_y > r * r * (1.0 + 1e-6)) return 0.0;
  }
  return disk_rect_area_in_kernel(x0, x1, y0, y1, cx, cy, r);
}

// square_disk_area of each lane's square [x0, x1] × [y0, y1], computed once per distinct square
// (lanes with the same four values' bits take the first such lane's area).
template <class T>
GLINTLAB_INLINE T lane_square_disk_areas(const LanesOf<T>& x0, const LanesOf<T>& x1,
                                         const LanesOf<T>& y0, const LanesOf<T>& y1) {
  using S = Scalar<T>;
  using Bits = std::conditional_t<sizeof(S) == 4, std::uint32_t, std::uint64_t>;
  const auto same = [](S a, S b) { return std::bit_cast<Bits>(a) == std::bit_cast<Bits>(b); };
  S area[kLaneCount<T>];
  for (std::size_t l = 0; l < kLaneCount<T>; ++l) {
    std::size_t first = l;
    for (std::size_t m = 0; m < l; ++m)
      if (same(x0[m], x0[l]) && same(x1[m], x1[l]) && same(y0[m], y0[l]) && same(y1[m], y1[l])) {
        first = m;
        break;
      }
    area[l] = first < l ? area[first]
                        : S(square_disk_area(double(x0[l]), double(x1[l]), double(y0[l]),
                                             double(y1[l])));
  }
  return LaneAccess<T>::load(area);
}

// One of the two levels sample_density_square visits (up = 0: ⌊λ⌋, 1: ⌊λ⌋ + 1): its weight
// and x's angular cell (cx, cy) there.
template <class T>
struct DensityLevel {
  LaneInt<T, int> level;
  T w_l, res_a;
  Mask<T> w_positive;
  LaneInt<T> cx, cy;
};
template <class T>
GLINTLAB_INLINE DensityLevel<T> density_level(const Spatial<T>& sp, int up, Vec2<T> x) {
  DensityLevel<T> d;
  d.level = sp.l0 + up;
  d.w_l = up ? sp.w1 : T(1) - sp.w1;
  d.w_positive = d.w_l > T(0);
  d.res_a = angular_resolution<T>(d.level);
  d.cx = floor_int<T>(x.x * d.res_a);
  d.cy = floor_int<T>(x.y * d.res_a);
  return d;
}

// The area in U_Ω of the square of x_a that selects the block with angular start (bx, by)
// (x_a·res_a ∈ [b + (n−1)/2, b + (n+1)/2) per axis), lane by lane: the exact disk ∩ rectangle
// area, the scalar code only where the square meets the circle (square_disk_area), once per
// distinct square: at the low levels, where the squares are large and meet the circle, a level
// has few cells, so lanes share them.
template <class T>
GLINTLAB_INLINE T selecting_square_area(const LaneInt<T>& bx, const LaneInt<T>& by, int n,
                                        T res_a) {
  const T half = T(0.5) * T(n - 1);
  const T fx = int_to_float<T>(bx) + half, fy = int_to_float<T>(by) + half;
  const LanesOf<T> x0(fx / res_a), x1((fx + T(1)) / res_a), y0(fy / res_a),
      y1((fy + T(1)) / res_a);
  return lane_square_disk_areas<T>(x0, x1, y0, y1);
}

// The blocks of a level that sample_density_square visits, per start offset slot (dx + n − 1,
// dy + n − 1): the area of their selecting square in U_Ω and the lanes that use them (w_l > 0 and
// an area > 0).
template <class T>
struct LevelBlocks {
  T area[kMaxSide][kMaxSide];
  Mask<T> use[kMaxSide][kMaxSide];
  bool any_use = false;
};
template <class T>
GLINTLAB_FN void level_blocks(const DensityLevel<T>& d, int n, LevelBlocks<T>& out) {
  out.any_use = false;
  for (int dx = 1 - n; dx <= 0; ++dx)
    for (int dy = 1 - n; dy <= 0; ++dy) {
      const std::size_t sx = std::size_t(dx + n - 1), sy = std::size_t(dy + n - 1);
      out.area[sx][sy] = selecting_square_area(d.cx + dx, d.cy + dy, n, d.res_a);
      out.use[sx][sy] = d.w_positive && (out.area[sx][sy] > T(0));
      out.any_use = out.any_use || any_lane<T>(out.use[sx][sy]);
    }
}

// The points of LevelPoints around x's angular cell (cx, cy) at `level` (weight w_l): the same
// arithmetic as block() and block_density(), in the same lane order.
template <class Ndf, class T>
GLINTLAB_FN void level_points(const Params<T>& p, const Ndf& ndf, const Spatial<T>& sp,
                  const LaneInt<T, int>& level, T w_l, const LaneInt<T>& cx, const LaneInt<T>& cy,
                  Vec2<T> x, LevelPoints<T>& out, int process) {
  const int n = p.side;
  out.n = n;
  const T res_a = angular_resolution<T>(level);
  const T res_s = sp.res / res_a;
  const LaneInt<T> n_a = level_cells<T>(level);
  const LaneInt<T> sx0 = block_start(sp.x_s.x * res_s, n);
  const LaneInt<T> sy0 = block_start(sp.x_s.y * res_s, n);
  const Normal2Form<T> spatial_lobe = normal2_form(sp.sigma_s);
  for (int i = 0; i < n; ++i) {
    const LaneInt<T> sx = sx0 + i;
    const LaneInt<T, std::uint64_t> hash_i = cell_chain_sx_lanes<T>(sx);
    for (int j = 0; j < n; ++j) {
      const LaneInt<T> sy = sy0 + j;
      const LaneInt<T, std::uint64_t> hash_ij = cell_chain_sy_lanes<T>(hash_i, sy);
      for (int a = 1 - n; a <= n - 1; ++a) {
        const LaneInt<T> ax = cx + a;
        const LaneInt<T, std::uint64_t> hash_ija = cell_chain_ax_lanes<T>(hash_ij, ax);
        for (int b = 1 - n; b <= n - 1; ++b) {
          const LaneInt<T> ay = cy + b;
          const Candidate<T> k =
              candidate(p, ndf, sp, spatial_lobe, w_l, res_a, res_s, n_a, sx, sy, ax, ay,
                        cell_chain_ay_level_vector<T>(hash_ija, ay, level, process));
          const Mask<T> live = k.valid && (k.s > T(0)) && (k.sigma.x > T(0)) && (k.sigma.y > T(0));
          const std::size_t at = out.index(i, j, a, b);
          out.c[at] = k;
          out.term[at] =
              any_lane<T>(live)
                  ? select(live,
                           k.s * normal2(x - k.g_a, Sym2<T>{sqr(k.sigma.x), T(0), sqr(k.sigma.y)}),
                           T(0))
                  : T(0);
          out.known[0][at].fill(false);
          out.known[1][at].fill(false);
        }
      }
    }
  }
}

// The point at `at`'s mass along `axis` over [lo, hi], the range of the blocks whose start on that
// axis is offset d from x's cell: gaussian_interval_mass, computed at its first use.
template <class T>
GLINTLAB_FN T mass_along(LevelPoints<T>& pts, std::size_t at, int axis, int d, T lo, T hi) {
  const std::size_t k = std::size_t(d + pts.n - 1);
  if (!pts.known[std::size_t(axis)][at][k]) {
    const Candidate<T>& c = pts.c[at];
    pts.mass[std::size_t(axis)][at][k] =
        axis == 0 ? gaussian_interval_mass(lo, hi, c.g_a.x, c.sigma.x, Erf::kExact)
                  : gaussian_interval_mass(lo, hi, c.g_a.y, c.sigma.y, Erf::kExact);
    pts.known[std::size_t(axis)][at][k] = true;
  }
  return pts.mass[std::size_t(axis)][at][k];
}

// block_density() of the block with angular start (cx + dx, cy + dy), from the level's points:
// Σw★ and Σ s_j N_j(x) summed in block()'s order, so the result is the same bits.
template <class T>
GLINTLAB_FN T level_block_density(LevelPoints<T>& pts, const LaneInt<T, int>& level, const LaneInt<T>& cx,
                      const LaneInt<T>& cy, int dx, int dy, Vec2<T> x) {
  const int n = pts.n;
  const T res_a = angular_resolution<T>(level);
  const LaneInt<T> n_a = level_cells<T>(level);
  const BlockBounds<T> bounds = block_bounds(cx + dx, cy + dy, n, n_a, res_a);
  const Vec2<T> lo = bounds.lo, hi = bounds.hi;
  T total = T(0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          const std::size_t at = pts.index(i, j, dx + a, dy + b);
          const Candidate<T>& k = pts.c[at];
          // gaussian_rect_mass(lo, hi, k.g_a, k.sigma, Erf::kExact), its factors shared.
          const T m = adds_weight(k)
                          ? select(k.valid,
                                   mass_along(pts, at, 0, dx, lo.x, hi.x) *
                                       mass_along(pts, at, 1, dy, lo.y, hi.y),
                                   T(0))
                          : T(0);
          total += k.s * m;
        }
  const Mask<T> inside = (total > T(0)) && !(x.x < lo.x || x.x > hi.x || x.y < lo.y || x.y > hi.y);
  if (!any_lane<T>(inside)) return T(0);
  T sum = T(0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) sum += pts.term[pts.index(i, j, dx + a, dy + b)];
  return select(inside, sum / total, T(0));
}

// Each used block's term of a level, w_l |R_B ∩ U_Ω|/|U_Ω| × density_of(dx, dy) (the density in □
// given the block with angular start (cx + dx, cy + dy)), added to `total` in block order.
template <class T, class DensityOf>
GLINTLAB_FN void add_block_terms(const DensityLevel<T>& d, const LevelBlocks<T>& blocks, int n,
                                 DensityOf density_of, T& total) {
  for (int dx = 1 - n; dx <= 0; ++dx)
    for (int dy = 1 - n; dy <= 0; ++dy) {
      const std::size_t sx = std::size_t(dx + n - 1), sy = std::size_t(dy + n - 1);
      if (!any_lane<T>(blocks.use[sx][sy])) continue;
      total += select(blocks.use[sx][sy],
                      d.w_l * blocks.area[sx][sy] / T(kMapDomainArea<T>) * density_of(dx, dy),
                      T(0));
    }
}

// One level's term of the marginal density in □ (blocks: level_blocks, some used), every lane's
// points computed on every lane, added to `total` block by block.
template <class Ndf, class T>
GLINTLAB_FN void add_level_density_unpacked(const Params<T>& p, const Ndf& ndf,
                                            const Spatial<T>& sp, const DensityLevel<T>& d,
                                            const LevelBlocks<T>& blocks, Vec2<T> x, int process,
                                            T& total) {
  const int n = p.side;
  // On the stack, not thread_local: static TLS is reserved in every thread's stack at its start,
  // and this table at every (Ndf, T) would outgrow a worker thread's stack (pthread_create EINVAL).
  LevelPoints<T> points;
  level_points(p, ndf, sp, d.level, d.w_l, d.cx, d.cy, x, points, process);
  add_block_terms(
      d, blocks, n,
      [&](int dx, int dy) { return level_block_density(points, d.level, d.cx, d.cy, dx, dy, x); },
      total);
}

// The marginal density in □ of sample_half's x (defective: rejections excluded), every lane's
// points computed on every lane: the loops sample_density_square takes on scalars (and the
// reference of the packed batch loops).
template <class Ndf, class T>
GLINTLAB_FN T sample_density_square_unpacked(const Params<T>& p, const Ndf& ndf,
                                             const FootprintQuery<T>& fp, Vec2<T> x,
                                             int process = 0) {
  const Mask<T> in_disk = !(sqr(x.x - T(0.5)) + sqr(x.y - T(0.5)) > T(0.25));
  if (!any_lane<T>(in_disk)) return T(0);
  const Spatial<T> sp = spatial(p, fp);
  T total = T(0);
  for (int up = 0; up < 2; ++up) {
    const DensityLevel<T> d = density_level(sp, up, x);
    if (!any_lane<T>(d.w_positive)) continue;
    LevelBlocks<T> blocks;
    level_blocks(d, p.side, blocks);
    if (blocks.any_use) add_level_density_unpacked(p, ndf, sp, d, blocks, x, process, total);
  }
  return select(in_disk, total, T(0));
}

// sample_density_square on a batch: per level, its points' work packed by (point, lane) where the
// lanes need few of the points that some lane needs, else every point on every lane
// (kemppinen_packed.h); `path` forces one of the two at every level (the tests compare them).
enum class DensityPath { kChoose, kPacked, kUnpacked };
template <class Ndf, class T>
GLINTLAB_FN T sample_density_square_packed(const Params<T>& p, const Ndf& ndf,
                                           const FootprintQuery<T>& fp, Vec2<T> x, int process,
                                           DensityPath path = DensityPath::kChoose);

// The marginal density in □ of sample_half's x (defective: rejections excluded). Every block
// B(k) whose selecting square of x_a meets U_Ω, at both levels; their points are computed once
// per level (level_points). A batch takes the loops of kemppinen_packed.h, which pack each level's
// points by (point, lane) where that pays (the same bits).
template <class Ndf, class T>
GLINTLAB_FN T sample_density_square(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp, Vec2<T> x,
                        int process = 0) {
  if constexpr (kLaneCount<T> > 1) {
    return sample_density_square_packed(p, ndf, fp, x, process);
  } else {
    return sample_density_square_unpacked(p, ndf, fp, x, process);
  }
}

// The marginal density of ω_h per steradian: the density in □ at T(ω_h) times |det dT/dω|.
template <class Ndf, class T>
GLINTLAB_FN T sample_density_half(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp, Vec3<T> h,
                      int process = 0) {
  const Mask<T> up = h.z > T(0);
  if (!any_lane<T>(up)) return T(0);
  return select(
      up,
      sample_density_square(p, ndf, fp, map_to_square(ndf, h), process) * map_jacobian_true(ndf, h),
      T(0));
}

// A sampler key from the two uniforms of a model's sample(): their bit patterns hashed.
template <class T>
GLINTLAB_FN LaneInt<T, std::uint64_t> key_from_uniforms(Vec2<T> u) {
  const LanesOf<T> ux(u.x), uy(u.y);
  return int_lanes<T, std::uint64_t>([&](std::size_t l) {
    const double a = double(ux[l]), b = double(uy[l]);
    std::uint64_t ia = 0, ib = 0;
    std::memcpy(&ia, &a, sizeof ia);
    std::memcpy(&ib, &b, sizeof ib);
    return mix64(mix64(ia + 0x9e3779b97f4a7c15ULL) ^ ib);
  });
}

}  // namespace glintlab::kemppinen2025

// The packed batch loops (they include this header first).
#include "core/glints/kemppinen_packed.h"

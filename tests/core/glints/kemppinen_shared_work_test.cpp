// The Kemppinen kernels' hoisted forms give the bits of the loops they replaced: eval (Algorithm 1
// with the compensation of Eq. 10), Algorithm 2's draw, its marginal density, the printed pdf at
// ω_h and the mixture's explicit share, each against a copy of the code as it was before the
// per-row and per-point work was shared (Σ factors of both lobes once per query, the cell hash
// chain once per spatial row and column, the lobe, mass and term of a point of roulette weight 0
// skipped, and the erfs shared by a lobe's mass over □ and over B(k)), on random queries for
// GGX and Beckmann, every k, float and double.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

#include "core/glints/kemppinen.h"
#include "core/glints/kemppinen_full_sampling.h"
#include "core/glints/kemppinen_lanes.h"
#include "core/glints/kemppinen_sampling.h"
#include "core/math/disk_rect_area.h"
#include "core/math/rng.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"

namespace glintlab::kemppinen2025::before_sharing {

// The functions as they were (renamed old_*), verbatim otherwise.
template <class T>
T old_compensation(Vec2<T> x_a, Vec2<T> sigma_a, Vec2<T> b_lo, Vec2<T> b_hi, Erf variant) {
  const T whole =
      gaussian_rect_mass(Vec2<T>{T(0), T(0)}, Vec2<T>{T(1), T(1)}, x_a, sigma_a, variant);
  const T near = gaussian_rect_mass(b_lo, b_hi, x_a, sigma_a, variant);
  return max(whole - near, T(0));
}

template <class T>
void old_level(const Params<T>& p, const Angular<T>& ang, Vec2<T> x_s, const Sym2<T>& sigma_s,
               T res, const LaneInt<T, int>& level, T w_l, int process, Vec3<T>& explicit_sum,
               Vec3<T>& compensation) {
  const int n = p.side;
  const T res_a = angular_resolution<T>(level);
  const T res_s = res / res_a;
  const T inv_rho = T(1) / sqr(res);  // 1/(res_s² res_a²): one point per 4D cell
  const LaneInt<T> n_a = level_cells<T>(level);
  const LaneInt<T> sx0 = block_start(x_s.x * res_s, n);
  const LaneInt<T> sy0 = block_start(x_s.y * res_s, n);
  const LaneInt<T> ax0 = block_start(ang.x_a.x * res_a, n);
  const LaneInt<T> ay0 = block_start(ang.x_a.y * res_a, n);
  const Sym2<T> sigma_a2{sqr(ang.sigma_a.x), T(0), sqr(ang.sigma_a.y)};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          const LaneInt<T> sx = sx0 + i, sy = sy0 + j, ax = ax0 + a, ay = ay0 + b;
          const LaneInt<T, std::uint64_t> ci = cell_index_lanes<T>(sx, sy, ax, ay, level, process);
          const Mask<T> in_square = mask_lanes<T>([&](std::size_t l) {
            return lane(ax, l) >= 0 && lane(ax, l) < lane(n_a, l) && lane(ay, l) >= 0 &&
                   lane(ay, l) < lane(n_a, l);
          });
          const Vec2<T> g_s{
              (int_to_float<T>(sx) + cell_uniform<T>(p.seed, ci, kKemppinenDimSpatialX)) / res_s,
              (int_to_float<T>(sy) + cell_uniform<T>(p.seed, ci, kKemppinenDimSpatialY)) / res_s};
          const Vec2<T> g_a{
              (int_to_float<T>(ax) + cell_uniform<T>(p.seed, ci, kKemppinenDimAngularX)) / res_a,
              (int_to_float<T>(ay) + cell_uniform<T>(p.seed, ci, kKemppinenDimAngularY)) / res_a};
          // Points outside U_Ω are rejected (Sec. 3.3.1).
          const Mask<T> in_disk = sqr(g_a.x - T(0.5)) + sqr(g_a.y - T(0.5)) <= T(0.25);
          const T r = cell_uniform<T>(p.seed, ci, kKemppinenDimRoulette);
          const T blend = p.blend == Blend::kRoulette ? roulette(r, w_l) : w_l;
          const T w =
              blend * normal2(x_s - g_s, sigma_s) * normal2(ang.x_a - g_a, sigma_a2) * inv_rho;
          const Vec3<T> col = color(p.colors, cell_uniform<T>(p.seed, ci, kKemppinenDimColor));
          explicit_sum = explicit_sum + select(in_disk && in_square, w, T(0)) * col;
        }
  // B(k) clipped to the square: the cells that exist.
  const Vec2<T> b_lo{int_to_float<T>(int_max(ax0, std::int64_t(0))) / res_a,
                     int_to_float<T>(int_max(ay0, std::int64_t(0))) / res_a};
  const Vec2<T> b_hi{int_to_float<T>(int_min(ax0 + n, n_a)) / res_a,
                     int_to_float<T>(int_min(ay0 + n, n_a)) / res_a};
  const T cmp = p.compensate ? old_compensation(ang.x_a, ang.sigma_a, b_lo, b_hi, p.erf) : T(0);
  compensation = compensation + (w_l * cmp) * expected_color<T>(p.colors);
}

template <class Ndf, class T>
Result<T> old_eval_process(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp,
                           Vec3<T> h, int process, T process_w) {
  const Angular<T> ang = angular(p, ndf, h);
  const T res = base_resolution(p);
  const Vec2<T> x_s = spatial_position(p, fp.uv);
  const Sym2<T> sigma_s = spatial_covariance(p, fp, res);
  const T lambda = lod(sigma_s, res);
  const T fl = min(floor(lambda), T(kMaxLevel - 1));
  const LaneInt<T, int> l0 = floor_int<T, int>(fl);
  const T w1 = lambda - fl, w0 = T(1) - w1;
  Vec3<T> ex{T(0), T(0), T(0)}, cp{T(0), T(0), T(0)};
  old_level(p, ang, x_s, sigma_s, res, l0, w0 * process_w, process, ex, cp);
  old_level(p, ang, x_s, sigma_s, res, l0 + 1, w1 * process_w, process, ex, cp);
  const T k = select(ang.valid, ang.prefactor, T(0));
  Result<T> out;
  out.explicit_part = k * ex;
  out.compensation_part = k * cp;
  out.d = out.explicit_part + out.compensation_part;
  out.smooth_d = select(ang.valid, ang.d, T(0));
  out.lambda = lambda;
  out.w0 = w0;
  out.w1 = w1;
  out.level0 = l0;
  out.points = 2 * p.side * p.side * p.side * p.side;
  return out;
}

template <class Ndf, class T>
Candidate<T> old_candidate(const Params<T>& p, const Ndf& ndf, const Spatial<T>& sp,
                           const LaneInt<T, int>& level, T w_l, T res_a, T res_s,
                           const LaneInt<T>& n_a, const LaneInt<T>& sx, const LaneInt<T>& sy,
                           const LaneInt<T>& ax, const LaneInt<T>& ay, int process) {
  const LaneInt<T, std::uint64_t> ci = cell_index_lanes<T>(sx, sy, ax, ay, level, process);
  Candidate<T> k;
  k.valid = mask_lanes<T>([&](std::size_t l) {
    return lane(ax, l) >= 0 && lane(ax, l) < lane(n_a, l) && lane(ay, l) >= 0 &&
           lane(ay, l) < lane(n_a, l);
  });
  k.g_a = {(int_to_float<T>(ax) + cell_uniform<T>(p.seed, ci, kKemppinenDimAngularX)) / res_a,
           (int_to_float<T>(ay) + cell_uniform<T>(p.seed, ci, kKemppinenDimAngularY)) / res_a};
  k.valid = k.valid && (sqr(k.g_a.x - T(0.5)) + sqr(k.g_a.y - T(0.5)) <= T(0.25));
  k.s = T(0);
  k.m = T(0);
  k.sigma = {T(0), T(0)};
  if (any_lane<T>(k.valid)) {  // uniform: some lane has the point
    const Vec2<T> g_s{
        (int_to_float<T>(sx) + cell_uniform<T>(p.seed, ci, kKemppinenDimSpatialX)) / res_s,
        (int_to_float<T>(sy) + cell_uniform<T>(p.seed, ci, kKemppinenDimSpatialY)) / res_s};
    const T r = cell_uniform<T>(p.seed, ci, kKemppinenDimRoulette);
    const T blend = p.blend == Blend::kRoulette ? roulette(r, w_l) : w_l;
    const Vec3<T> col = color(p.colors, cell_uniform<T>(p.seed, ci, kKemppinenDimColor));
    k.sigma = point_sigma(p, ndf, k.g_a);
    k.s = select(k.valid, blend * normal2(sp.x_s - g_s, sp.sigma_s) * luminance(col), T(0));
  }
  return k;
}

template <class Ndf, class T>
void old_block(const Params<T>& p, const Ndf& ndf, const Spatial<T>& sp,
               const LaneInt<T, int>& level, T w_l, const LaneInt<T>& ax0, const LaneInt<T>& ay0,
               Block<T>& out, int process = 0) {
  const int n = p.side;
  const T res_a = angular_resolution<T>(level);
  const T res_s = sp.res / res_a;
  const LaneInt<T> n_a = level_cells<T>(level);
  const LaneInt<T> sx0 = block_start(sp.x_s.x * res_s, n);
  const LaneInt<T> sy0 = block_start(sp.x_s.y * res_s, n);
  out.lo = {int_to_float<T>(int_max(ax0, std::int64_t(0))) / res_a,
            int_to_float<T>(int_max(ay0, std::int64_t(0))) / res_a};
  out.hi = {int_to_float<T>(int_min(ax0 + n, n_a)) / res_a,
            int_to_float<T>(int_min(ay0 + n, n_a)) / res_a};
  out.count = 0;
  out.total = T(0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          Candidate<T> k = old_candidate(p, ndf, sp, level, w_l, res_a, res_s, n_a, sx0 + i,
                                         sy0 + j, ax0 + a, ay0 + b, process);
          if (any_lane<T>(k.valid))
            k.m = select(k.valid, gaussian_rect_mass(out.lo, out.hi, k.g_a, k.sigma, Erf::kExact),
                         T(0));
          out.total += k.s * k.m;  // invalid lanes add +0: the scalar sum is unchanged
          out.c[std::size_t(out.count++)] = k;
        }
}

template <class T>
T old_block_density(const Block<T>& b, Vec2<T> x) {
  const Mask<T> inside =
      (b.total > T(0)) && !(x.x < b.lo.x || x.x > b.hi.x || x.y < b.lo.y || x.y > b.hi.y);
  if (!any_lane<T>(inside)) return T(0);
  T sum = T(0);
  for (int j = 0; j < b.count; ++j) {
    const Candidate<T>& k = b.c[std::size_t(j)];
    const T t = k.s * normal2(x - k.g_a, Sym2<T>{sqr(k.sigma.x), T(0), sqr(k.sigma.y)});
    // A point of zero spatial weight adds nothing, and a point whose lobe collapsed (σ = 0: D
    // underflowed to 0 at g_a on the rim of U_Ω, in float well before double) is a delta that
    // adds nothing at any other x; masked, or 0 · N(0/0) made the density NaN (stability sweep,
    // float pdf at density ≥ 2.1e7). Every result that was finite before is unchanged.
    const Mask<T> live = k.valid && (k.s > T(0)) && (k.sigma.x > T(0)) && (k.sigma.y > T(0));
    sum += select(live, t, T(0));
  }
  return select(inside, sum / b.total, T(0));
}

template <class Ndf, class T>
HalfSample<T> old_sample_half(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp,
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
  // On the stack, as LevelPoints in old_sample_density_square (static TLS would grow every thread's
  // stack, and a device thread has none): old_block() writes every field it reads.
  Block<T> block;
  old_block(p, ndf, sp, out.level, w_l, block_start(x_a.x * res_a, p.side),
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
  const T pdf_x = old_block_density(block, x);
  const T area_b = (block.hi.x - block.lo.x) * (block.hi.y - block.lo.y);
  const T pdf_printed = pdf_x * area_b * map_jacobian_paper(ndf, h) * h.z * w_l;
  out.h = select(in_disk, h, out.h);
  out.pdf_conditional_x = select(in_disk, pdf_x, T(0));
  out.pdf_printed_h = select(in_disk, pdf_printed, T(0));
  out.ok = in_disk && (h.z > T(0));
  return out;
}

template <class Ndf, class T>
void old_level_points(const Params<T>& p, const Ndf& ndf, const Spatial<T>& sp,
                      const LaneInt<T, int>& level, T w_l, const LaneInt<T>& cx,
                      const LaneInt<T>& cy, Vec2<T> x, LevelPoints<T>& out, int process) {
  const int n = p.side;
  out.n = n;
  const T res_a = angular_resolution<T>(level);
  const T res_s = sp.res / res_a;
  const LaneInt<T> n_a = level_cells<T>(level);
  const LaneInt<T> sx0 = block_start(sp.x_s.x * res_s, n);
  const LaneInt<T> sy0 = block_start(sp.x_s.y * res_s, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int a = 1 - n; a <= n - 1; ++a)
        for (int b = 1 - n; b <= n - 1; ++b) {
          const Candidate<T> k = old_candidate(p, ndf, sp, level, w_l, res_a, res_s, n_a, sx0 + i,
                                               sy0 + j, cx + a, cy + b, process);
          const T t = k.s * normal2(x - k.g_a, Sym2<T>{sqr(k.sigma.x), T(0), sqr(k.sigma.y)});
          const Mask<T> live = k.valid && (k.s > T(0)) && (k.sigma.x > T(0)) && (k.sigma.y > T(0));
          const std::size_t at = out.index(i, j, a, b);
          out.c[at] = k;
          out.term[at] = select(live, t, T(0));
          out.known[0][at].fill(false);
          out.known[1][at].fill(false);
        }
}

template <class T>
T old_mass_along(LevelPoints<T>& pts, std::size_t at, int axis, int d, T lo, T hi) {
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

template <class T>
T old_level_block_density(LevelPoints<T>& pts, const LaneInt<T, int>& level, const LaneInt<T>& cx,
                          const LaneInt<T>& cy, int dx, int dy, Vec2<T> x) {
  const int n = pts.n;
  const T res_a = angular_resolution<T>(level);
  const LaneInt<T> n_a = level_cells<T>(level);
  const LaneInt<T> ax0 = cx + dx, ay0 = cy + dy;
  const Vec2<T> lo{int_to_float<T>(int_max(ax0, std::int64_t(0))) / res_a,
                   int_to_float<T>(int_max(ay0, std::int64_t(0))) / res_a};
  const Vec2<T> hi{int_to_float<T>(int_min(ax0 + n, n_a)) / res_a,
                   int_to_float<T>(int_min(ay0 + n, n_a)) / res_a};
  T total = T(0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          const std::size_t at = pts.index(i, j, dx + a, dy + b);
          const Candidate<T>& k = pts.c[at];
          // gaussian_rect_mass(lo, hi, k.g_a, k.sigma, Erf::kExact), its factors shared.
          const T m = any_lane<T>(k.valid) ? select(k.valid,
                                                    old_mass_along(pts, at, 0, dx, lo.x, hi.x) *
                                                        old_mass_along(pts, at, 1, dy, lo.y, hi.y),
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

template <class Ndf, class T>
T old_sample_density_square(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp,
                            Vec2<T> x, int process = 0) {
  const Mask<T> in_disk = !(sqr(x.x - T(0.5)) + sqr(x.y - T(0.5)) > T(0.25));
  if (!any_lane<T>(in_disk)) return T(0);
  const Spatial<T> sp = spatial(p, fp);
  const int n = p.side;
  // On the stack, not thread_local: static TLS is reserved in every thread's stack at its start,
  // and this table at every (Ndf, T) would outgrow a worker thread's stack (pthread_create EINVAL).
  LevelPoints<T> points;
  T total = T(0);
  for (int up = 0; up < 2; ++up) {
    const LaneInt<T, int> level = sp.l0 + up;
    const T w_l = up ? sp.w1 : T(1) - sp.w1;
    const Mask<T> w_positive = w_l > T(0);
    if (!any_lane<T>(w_positive)) continue;
    const T res_a = angular_resolution<T>(level);
    const LaneInt<T> cx = floor_int<T>(x.x * res_a);
    const LaneInt<T> cy = floor_int<T>(x.y * res_a);
    bool have_points = false;
    for (int dx = 1 - n; dx <= 0; ++dx)
      for (int dy = 1 - n; dy <= 0; ++dy) {
        const LaneInt<T> bx = cx + dx, by = cy + dy;
        // x_a selects start b where x_a·res_a ∈ [b + (n−1)/2, b + (n+1)/2).
        const T half = T(0.5) * T(n - 1);
        const T fx = int_to_float<T>(bx) + half, fy = int_to_float<T>(by) + half;
        const LanesOf<T> x0(fx / res_a), x1((fx + T(1)) / res_a), y0(fy / res_a),
            y1((fy + T(1)) / res_a);
        // The exact disk ∩ rectangle area (scalar code, core/math/disk_rect_area.h), lane by
        // lane.
        const T area = float_lanes<T>([&](std::size_t l) {
          return Scalar<T>(disk_rect_area_in_kernel(double(x0[l]), double(x1[l]), double(y0[l]),
                                                    double(y1[l]), 0.5, 0.5, 0.5));
        });
        const Mask<T> use = w_positive && (area > T(0));
        if (!any_lane<T>(use)) continue;
        if (!have_points) old_level_points(p, ndf, sp, level, w_l, cx, cy, x, points, process);
        have_points = true;
        total += select(use,
                        w_l * area / T(kMapDomainArea<T>) *
                            old_level_block_density(points, level, cx, cy, dx, dy, x),
                        T(0));
      }
  }
  return select(in_disk, total, T(0));
}

template <class Ndf, class T>
T old_level_explicit_share(const Params<T>& p, const Ndf& ndf, const LaneInt<T, int>& level) {
  const LaneInt<T> n_a = level_cells<T>(level);
  const T res_a = angular_resolution<T>(level);
  const T c = max(floor(res_a * T(0.5)) - T(1), T(0));
  T near_sum = T(0), whole_sum = T(0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const Vec2<T> x_a{(c + (T(i) + T(0.5)) / T(4)) / res_a, (c + (T(j) + T(0.5)) / T(4)) / res_a};
      const Vec2<T> sigma = point_sigma(p, ndf, x_a);
      const LaneInt<T> ax0 = block_start(x_a.x * res_a, p.side);
      const LaneInt<T> ay0 = block_start(x_a.y * res_a, p.side);
      const Vec2<T> lo{int_to_float<T>(int_max(ax0, std::int64_t(0))) / res_a,
                       int_to_float<T>(int_max(ay0, std::int64_t(0))) / res_a};
      const Vec2<T> hi{int_to_float<T>(int_min(ax0 + p.side, n_a)) / res_a,
                       int_to_float<T>(int_min(ay0 + p.side, n_a)) / res_a};
      near_sum += gaussian_rect_mass(lo, hi, x_a, sigma, Erf::kExact);
      whole_sum +=
          gaussian_rect_mass(Vec2<T>{T(0), T(0)}, Vec2<T>{T(1), T(1)}, x_a, sigma, Erf::kExact);
    }
  const Mask<T> has = whole_sum > T(0);
  return select(has, near_sum / select(has, whole_sum, T(1)), T(1));
}

template <class Ndf, class T>
T old_explicit_share(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp) {
  const Spatial<T> sp = spatial(p, fp);
  return (T(1) - sp.w1) * old_level_explicit_share(p, ndf, sp.l0) +
         sp.w1 * old_level_explicit_share(p, ndf, sp.l0 + 1);
}

template <class Ndf, class T>
T old_printed_pdf_at(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp, Vec3<T> h,
                     int process = 0) {
  const Mask<T> up = h.z > T(0);
  if (!any_lane<T>(up)) return T(0);
  const Vec2<T> x = map_to_square(ndf, select(up, h, Vec3<T>{T(0), T(0), T(1)}));
  const Mask<T> in_disk = up && !(sqr(x.x - T(0.5)) + sqr(x.y - T(0.5)) > T(0.25));
  if (!any_lane<T>(in_disk)) return T(0);
  const Spatial<T> sp = spatial(p, fp);
  Block<T> block;  // on the stack, as in sample_half
  T total = T(0);
  for (int upper = 0; upper < 2; ++upper) {
    const LaneInt<T, int> level = sp.l0 + upper;
    const T w_l = upper ? sp.w1 : T(1) - sp.w1;
    const Mask<T> w_positive = w_l > T(0);
    if (!any_lane<T>(w_positive)) continue;
    const T res_a = angular_resolution<T>(level);
    old_block(p, ndf, sp, level, w_l, block_start(x.x * res_a, p.side),
              block_start(x.y * res_a, p.side), block, process);
    const T area_b = (block.hi.x - block.lo.x) * (block.hi.y - block.lo.y);
    total += select(w_positive, old_block_density(block, x) * area_b * w_l, T(0));
  }
  return select(in_disk, total * map_jacobian_paper(ndf, h) * h.z, T(0));
}

}  // namespace glintlab::kemppinen2025::before_sharing

namespace glintlab {
namespace {

using namespace kemppinen2025;
using namespace kemppinen2025::before_sharing;

template <class T>
bool same_bits(T a, T b) {
  if constexpr (sizeof(T) == 4)
    return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
  else
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
template <class T>
bool same_bits(Vec3<T> a, Vec3<T> b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

// A random query of row i: parameters spread over the regimes (LOD levels 0 to ~12, narrow to
// wide lobes, both blends and erfs, anisotropy, colours, compensation on and off).
template <class T>
struct Query {
  Params<T> p;
  T alpha_x, alpha_y;
  FootprintQuery<T> fp;
  Vec3<T> h;
  Vec2<T> x;
  std::uint64_t key;
};

template <class T>
Query<T> random_query(std::uint64_t i, int side) {
  const auto u = [i](std::uint64_t dim) { return counter_uniform<double>(0x6b656d, i, dim); };
  const auto log_uniform = [](double v, double lo, double hi) {
    return std::pow(10.0, lo + (hi - lo) * v);
  };
  Query<T> q{};
  q.p.density = T(log_uniform(u(0), 0.5, 6.5));
  q.p.microroughness = T(log_uniform(u(1), -4.0, -0.5));
  q.p.anisotropy = u(2) < 0.5 ? T(1) : T(log_uniform(u(3), -0.5, 0.5));
  q.p.filter = T(0.3 + 1.7 * u(4));
  q.p.side = side;
  q.p.blend = u(5) < 0.75 ? Blend::kRoulette : Blend::kLinear;
  q.p.erf = u(6) < 0.5 ? Erf::kExact : Erf::kRational;
  q.p.normalization = u(7) < 0.5 ? Normalization::kCorrected : Normalization::kPrinted;
  q.p.colors = u(8) < 0.5 ? Colors::kWhite : Colors::kRedYellow;
  q.p.seed = mix64(i + 17);
  q.p.compensate = u(9) < 0.8;
  q.alpha_x = T(log_uniform(u(10), -2.0, 0.0));
  q.alpha_y = u(11) < 0.5 ? q.alpha_x : T(log_uniform(u(12), -2.0, 0.0));
  q.fp.uv = {T(10 * u(13) - 5), T(10 * u(14) - 5)};
  const double scale = log_uniform(u(15), -6.0, 0.0);
  q.fp.duv_dx = {T(scale * (2 * u(16) - 1)), T(scale * (2 * u(17) - 1))};
  q.fp.duv_dy = {T(scale * (2 * u(18) - 1)), T(scale * (2 * u(19) - 1))};
  // ω_h mostly in the upper hemisphere, concentrated towards the normal as the lobes are.
  const double cos_theta = u(20) < 0.05 ? -0.3 : std::pow(u(21), 0.25);
  const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
  const double phi = 2 * 3.14159265358979323846 * u(22);
  q.h = {T(sin_theta * std::cos(phi)), T(sin_theta * std::sin(phi)), T(cos_theta)};
  // x in □, half of them near its centre where the lobes are.
  const double spread = u(23) < 0.5 ? 1.0 : 0.2;
  q.x = {T(0.5 + spread * (u(24) - 0.5)), T(0.5 + spread * (u(25) - 0.5))};
  q.key = mix64(i * 31 + 7);
  return q;
}

template <class T, class Ndf>
void expect_identical(int side, int queries, const char* ndf_name) {
  for (int i = 0; i < queries; ++i) {
    const Query<T> q = random_query<T>(std::uint64_t(side * 100000 + i), side);
    const Ndf ndf{q.alpha_x, q.alpha_y};
    const std::string where =
        std::string(ndf_name) + " k=" + std::to_string(side * side) + " query " + std::to_string(i);
    const Result<T> a = kemppinen2025::eval(q.p, ndf, q.fp, q.h);
    const Result<T> b = old_eval_process(q.p, ndf, q.fp, q.h, 0, T(1));
    ASSERT_TRUE(same_bits(a.d, b.d) && same_bits(a.explicit_part, b.explicit_part) &&
                same_bits(a.compensation_part, b.compensation_part))
        << where << ": eval " << a.d.x << " vs " << b.d.x;
    ASSERT_TRUE(same_bits(kemppinen2025::sample_density_square(q.p, ndf, q.fp, q.x),
                          old_sample_density_square(q.p, ndf, q.fp, q.x, 0)))
        << where << ": sample_density_square";
    const HalfSample<T> s = kemppinen2025::sample_half(q.p, ndf, q.fp, q.key);
    const HalfSample<T> t = old_sample_half(q.p, ndf, q.fp, q.key, 0);
    ASSERT_TRUE(same_bits(s.x.x, t.x.x) && same_bits(s.x.y, t.x.y) && same_bits(s.h, t.h) &&
                same_bits(s.pdf_printed_h, t.pdf_printed_h) &&
                same_bits(s.pdf_conditional_x, t.pdf_conditional_x) && s.ok == t.ok &&
                s.level == t.level)
        << where << ": sample_half";
    ASSERT_TRUE(same_bits(kemppinen2025::printed_pdf_at(q.p, ndf, q.fp, q.h),
                          old_printed_pdf_at(q.p, ndf, q.fp, q.h, 0)))
        << where << ": printed_pdf_at";
    ASSERT_TRUE(same_bits(kemppinen2025::explicit_share(q.p, ndf, q.fp),
                          old_explicit_share(q.p, ndf, q.fp)))
        << where << ": explicit_share";
  }
}

TEST(KemppinenSharedWork, GgxDoubleIsBitIdenticalToTheLoopsItReplaced) {
  for (int side = 1; side <= kMaxSide; ++side)
    expect_identical<double, GGX<double>>(side, 200, "GGX");
}
TEST(KemppinenSharedWork, BeckmannDoubleIsBitIdenticalToTheLoopsItReplaced) {
  for (int side = 1; side <= kMaxSide; ++side)
    expect_identical<double, Beckmann<double>>(side, 200, "Beckmann");
}
TEST(KemppinenSharedWork, GgxFloatIsBitIdenticalToTheLoopsItReplaced) {
  for (int side = 1; side <= kMaxSide; ++side) expect_identical<float, GGX<float>>(side, 200, "GGX");
}
TEST(KemppinenSharedWork, BeckmannFloatIsBitIdenticalToTheLoopsItReplaced) {
  for (int side = 1; side <= kMaxSide; ++side)
    expect_identical<float, Beckmann<float>>(side, 200, "Beckmann");
}

// The compensation of Eq. 10 with B(k) at the square's edges (the erfs it shares) and inside.
TEST(KemppinenSharedWork, CompensationIsBitIdenticalAtAndInsideTheSquaresEdges) {
  for (std::uint64_t i = 0; i < 20000; ++i) {
    const auto u = [i](std::uint64_t dim) { return counter_uniform<double>(0x636f6d70, i, dim); };
    const double res = double(std::uint64_t(1) << (i % 8));
    const auto bound = [&](std::uint64_t dim, bool low) {
      const double c = std::floor(u(dim) * (res + 1));
      return low ? std::min(c, res - 1) / res : std::max(c, 1.0) / res;
    };
    const Vec2<double> lo{bound(0, true), bound(1, true)}, hi{bound(2, false), bound(3, false)};
    const Vec2<double> m{u(4), u(5)};
    const Vec2<double> s{std::pow(10.0, -4 + 4 * u(6)), std::pow(10.0, -4 + 4 * u(7))};
    for (const Erf e : {Erf::kExact, Erf::kRational}) {
      ASSERT_TRUE(same_bits(kemppinen2025::compensation(m, s, lo, hi, e),
                            old_compensation(m, s, lo, hi, e)))
          << i;
      const Vec2<float> mf{float(m.x), float(m.y)}, sf{float(s.x), float(s.y)};
      const Vec2<float> lof{float(lo.x), float(lo.y)}, hif{float(hi.x), float(hi.y)};
      ASSERT_TRUE(same_bits(kemppinen2025::compensation(mf, sf, lof, hif, e),
                            old_compensation(mf, sf, lof, hif, e)))
          << i;
    }
  }
}


// The marginal pdf's disk ∩ square area with its closed-form shortcuts is the exact function's
// bits: squares of the marginal's kind (cells of levels 0–20 at random offsets, inside, across and
// outside U_Ω), squares grazing the circle within 10⁻⁷, and random rectangles.
TEST(KemppinenSharedWork, SquareDiskAreaIsTheExactFunctionsBits) {
  int inside = 0, outside = 0;
  for (std::uint64_t i = 0; i < 400000; ++i) {
    const auto u = [i](std::uint64_t dim) { return counter_uniform<double>(0x61726561, i, dim); };
    const double side = std::ldexp(1.0, -int(i % 21));
    double x0 = u(0) * 1.2 - 0.1, y0 = u(1) * 1.2 - 0.1;
    double x1 = x0 + side, y1 = y0 + side;
    if (i % 5 == 3) {  // a corner within 1e-7 of the circle
      const double phi = 6.283185307179586 * u(2), d = 1e-7 * (2 * u(3) - 1);
      x0 = 0.5 + (0.5 + d) * std::cos(phi);
      y0 = 0.5 + (0.5 + d) * std::sin(phi);
      x1 = x0 + side;
      y1 = y0 + side;
    } else if (i % 5 == 4) {  // any rectangle
      x1 = u(4) * 1.2 - 0.1;
      y1 = u(5) * 1.2 - 0.1;
    }
    for (const float f : {0.0f, 1.0f}) {  // double inputs, and the float marginal's
      const double a = f != 0 ? double(float(x0)) : x0, b = f != 0 ? double(float(x1)) : x1;
      const double c = f != 0 ? double(float(y0)) : y0, d = f != 0 ? double(float(y1)) : y1;
      const double fast = kemppinen2025::square_disk_area(a, b, c, d);
      ASSERT_TRUE(same_bits(fast, disk_rect_area(a, b, c, d, 0.5, 0.5, 0.5)))
          << i << ": " << a << " " << b << " " << c << " " << d;
      inside += fast > 0 && fast == (d - 0.5) * (b - a) - (c - 0.5) * (b - a);
      outside += fast == 0;
    }
  }
  // Both shortcuts are taken (and so checked) many times.
  EXPECT_GT(inside, 100000);
  EXPECT_GT(outside, 100000);
}


// kemppinen_lanes.h's split of the hash gives rng.h's and kemppinen_grid.h's bits: a cell key's
// uniforms are counter_uniform's, and the vector chain step is cell_chain_level ∘ cell_chain_ay.
TEST(KemppinenSharedWork, CellKeysGiveTheCounterUniformsBits) {
  for (std::uint64_t i = 0; i < 100000; ++i) {
    const std::uint64_t seed = mix64(i * 3 + 1), ci = mix64(i * 5 + 2);
    const std::uint64_t key = kemppinen2025::cell_key<double>(kemppinen2025::cell_seed_key(seed), ci);
    for (std::uint64_t dim = 0; dim < 8; ++dim) {
      ASSERT_TRUE(same_bits(kemppinen2025::key_uniform<double>(key, dim),
                            counter_uniform<double>(seed, ci, dim)))
          << i << " " << dim;
      ASSERT_TRUE(same_bits(kemppinen2025::key_uniform<float>(key, dim),
                            counter_uniform<float>(seed, ci, dim)))
          << i << " " << dim;
    }
    const std::int64_t ay = std::int64_t(mix64(i)) >> (i % 60);
    const int level = int(i % 21), process = int(i % 3);
    ASSERT_EQ(kemppinen2025::cell_chain_ay_level_vector<double>(ci, ay, level, process),
              kemppinen2025::cell_chain_level(kemppinen2025::cell_chain_ay(ci, ay), level, process))
        << i;
  }
}

}  // namespace
}  // namespace glintlab

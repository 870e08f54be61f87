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
#pragma once

#include <array>
#include <cstdint>
#include <cstring>

#include "core/glints/kemppinen.h"
#include "core/math/disk_rect_area.h"
#include "core/ndf/microfacet.h"

namespace glintlab {

// One candidate point of a block B(k) (Algorithm 2 lines 11–12).
template <class T>
struct KemppinenCandidate {
  Vec2<T> g_a, sigma;
  T s;  // R(r, w_λ) N(Σ_s, x_s − g_s) Luminance(c): the weight before the lobe's mass
  T m;  // ∫_B N_j
};

template <class T>
struct KemppinenBlock {
  std::array<KemppinenCandidate<T>,
             kKemppinenMaxSide * kKemppinenMaxSide * kKemppinenMaxSide * kKemppinenMaxSide>
      c;
  int count = 0;
  Vec2<T> lo, hi;  // B(k) clipped to □
  T total = T(0);  // Σ w★ = Σ s_j m_j
};

// The spatial frame of a query, as Algorithm 1 lines 1–5 compute it.
template <class T>
struct KemppinenSpatial {
  Vec2<T> x_s;
  Sym2<T> sigma_s;
  T res, lambda, w1;
  int l0;
};

template <class T>
KemppinenSpatial<T> kemppinen_spatial(const KemppinenParams<T>& p, const FootprintQuery<T>& fp) {
  KemppinenSpatial<T> s;
  s.res = kemppinen_base_resolution(p);
  s.x_s = kemppinen_spatial_position(p, fp.uv);
  s.sigma_s = kemppinen_spatial_covariance(p, fp, s.res);
  s.lambda = kemppinen_lod(s.sigma_s, s.res);
  const T fl = min(floor(s.lambda), T(kKemppinenMaxLevel - 1));
  s.l0 = static_cast<int>(fl);
  s.w1 = s.lambda - fl;
  return s;
}

// Lobe standard deviations of a point at g_a (Σ_a of Algorithm 1 line 12 at ω = T⁻¹(g_a)).
template <class Ndf, class T>
Vec2<T> kemppinen_point_sigma(const KemppinenParams<T>& p, const Ndf& ndf, Vec2<T> g_a) {
  const Vec3<T> w = map_from_square(ndf, g_a);
  const T sigma = p.microroughness * sqrt(ndf.D(w) / T(kMapDomainArea<T>));
  const T sa = sqrt(p.anisotropy);
  return {sigma / sa, sigma * sa};
}

// The candidates of block B with angular start cell (ax0, ay0) at `level` (weight w_l), of point
// process `process` (0 = uv; the triplanar planes: kKemppinenTriplanarProcess).
template <class Ndf, class T>
void kemppinen_block(const KemppinenParams<T>& p, const Ndf& ndf, const KemppinenSpatial<T>& sp,
                     int level, T w_l, std::int64_t ax0, std::int64_t ay0, KemppinenBlock<T>& out,
                     int process = 0) {
  const int n = p.side;
  const T res_a = kemppinen_angular_resolution<T>(level);
  const T res_s = sp.res / res_a;
  const std::int64_t n_a = std::int64_t(1) << level;
  const std::int64_t sx0 = kemppinen_block_start(sp.x_s.x * res_s, n);
  const std::int64_t sy0 = kemppinen_block_start(sp.x_s.y * res_s, n);
  out.lo = {T(std::max<std::int64_t>(ax0, 0)) / res_a, T(std::max<std::int64_t>(ay0, 0)) / res_a};
  out.hi = {T(std::min<std::int64_t>(ax0 + n, n_a)) / res_a,
            T(std::min<std::int64_t>(ay0 + n, n_a)) / res_a};
  out.count = 0;
  out.total = T(0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          const KemppinenCell c{sx0 + i, sy0 + j, ax0 + a, ay0 + b, level, process};
          const std::uint64_t ci = kemppinen_cell_index(c);
          if (c.ax < 0 || c.ax >= n_a || c.ay < 0 || c.ay >= n_a) continue;
          const Vec2<T> g_a{
              (T(c.ax) + kemppinen_cell_uniform<T>(p.seed, ci, kKemppinenDimAngularX)) / res_a,
              (T(c.ay) + kemppinen_cell_uniform<T>(p.seed, ci, kKemppinenDimAngularY)) / res_a};
          if (sqr(g_a.x - T(0.5)) + sqr(g_a.y - T(0.5)) > T(0.25)) continue;
          const Vec2<T> g_s{
              (T(c.sx) + kemppinen_cell_uniform<T>(p.seed, ci, kKemppinenDimSpatialX)) / res_s,
              (T(c.sy) + kemppinen_cell_uniform<T>(p.seed, ci, kKemppinenDimSpatialY)) / res_s};
          const T r = kemppinen_cell_uniform<T>(p.seed, ci, kKemppinenDimRoulette);
          const T blend = p.blend == KemppinenBlend::kRoulette ? kemppinen_roulette(r, w_l) : w_l;
          const Vec3<T> col =
              kemppinen_color(p.colors, kemppinen_cell_uniform<T>(p.seed, ci, kKemppinenDimColor));
          KemppinenCandidate<T> k;
          k.g_a = g_a;
          k.sigma = kemppinen_point_sigma(p, ndf, g_a);
          k.s = blend * normal2(sp.x_s - g_s, sp.sigma_s) * kemppinen_luminance(col);
          k.m = gaussian_rect_mass(out.lo, out.hi, g_a, k.sigma, KemppinenErf::kExact);
          out.total += k.s * k.m;
          out.c[std::size_t(out.count++)] = k;
        }
}

// Σ_j s_j N_j(x) / W over a block: the density in the square of the sample given the block.
template <class T>
T kemppinen_block_density(const KemppinenBlock<T>& b, Vec2<T> x) {
  if (!(b.total > T(0))) return T(0);
  if (x.x < b.lo.x || x.x > b.hi.x || x.y < b.lo.y || x.y > b.hi.y) return T(0);
  T sum = T(0);
  for (int j = 0; j < b.count; ++j) {
    const KemppinenCandidate<T>& k = b.c[std::size_t(j)];
    sum += k.s * normal2(x - k.g_a, Sym2<T>{sqr(k.sigma.x), T(0), sqr(k.sigma.y)});
  }
  return sum / b.total;
}

// One draw of the 1D normal N(m, s²) truncated to [lo, hi] by inverting its CDF with erf/erfinv.
template <class T>
T truncated_normal(T lo, T hi, T m, T s, T u) {
  const T k = T(0.70710678118654752440) / s;
  const T ea = erf((lo - m) * k), eb = erf((hi - m) * k);
  const T z = erfinv(clamp(ea + u * (eb - ea), T(-1) + T(1e-16), T(1) - T(1e-16)));
  return clamp(m + z / k, lo, hi);
}

template <class T>
struct KemppinenHalfSample {
  Vec2<T> x;            // the point in □ (T(ω_h))
  Vec3<T> h;            // ω_h = T⁻¹(x)
  T pdf_printed_h;      // Algorithm 2's pdf (lines 16–17, as read above), per steradian of ω_h
  T pdf_conditional_x;  // density in □ given x_a and the level
  int level;
  bool ok;  // false: Σw★ = 0 or x outside U_Ω (no direction)
};

// The random number `dim` of one sampler call keyed by `key`.
template <class T>
T kemppinen_sampler_uniform(std::uint64_t key, std::uint64_t dim) {
  return counter_uniform<T>(key, 0x6b656d70ULL, dim);
}

// Algorithm 2: one ω_h from D★^f of point process `process` at the footprint, random numbers
// from `key`.
template <class Ndf, class T>
KemppinenHalfSample<T> kemppinen_sample_half(const KemppinenParams<T>& p, const Ndf& ndf,
                                             const FootprintQuery<T>& fp, std::uint64_t key,
                                             int process = 0) {
  KemppinenHalfSample<T> out{};
  const KemppinenSpatial<T> sp = kemppinen_spatial(p, fp);
  // Line 2: uniform on the disk of radius ½ at (½, ½).
  const T ur = sqrt(kemppinen_sampler_uniform<T>(key, 0));
  const T phi = T(2) * T(kPi<T>) * kemppinen_sampler_uniform<T>(key, 1);
  const Vec2<T> x_a{T(0.5) + T(0.5) * ur * cos(phi), T(0.5) + T(0.5) * ur * sin(phi)};
  // Lines 4–6.
  const bool up = kemppinen_sampler_uniform<T>(key, 2) < sp.w1;
  out.level = sp.l0 + (up ? 1 : 0);
  const T w_l = up ? sp.w1 : T(1) - sp.w1;
  const T res_a = kemppinen_angular_resolution<T>(out.level);
  static thread_local KemppinenBlock<T> block;
  kemppinen_block(p, ndf, sp, out.level, w_l, kemppinen_block_start(x_a.x * res_a, p.side),
                  kemppinen_block_start(x_a.y * res_a, p.side), block, process);
  if (!(block.total > T(0))) return out;
  // Lines 13–15: keep point j with probability w★_j/Σw★.
  const T pick = kemppinen_sampler_uniform<T>(key, 3) * block.total;
  T acc = T(0);
  int chosen = block.count - 1;
  for (int j = 0; j < block.count; ++j) {
    acc += block.c[std::size_t(j)].s * block.c[std::size_t(j)].m;
    if (pick < acc) {
      chosen = j;
      break;
    }
  }
  while (chosen > 0 && !(block.c[std::size_t(chosen)].m * block.c[std::size_t(chosen)].s > T(0)))
    --chosen;
  const KemppinenCandidate<T>& k = block.c[std::size_t(chosen)];
  // Line 14: x ~ 1_B N_j.
  out.x = {truncated_normal(block.lo.x, block.hi.x, k.g_a.x, k.sigma.x,
                            kemppinen_sampler_uniform<T>(key, 4)),
           truncated_normal(block.lo.y, block.hi.y, k.g_a.y, k.sigma.y,
                            kemppinen_sampler_uniform<T>(key, 5))};
  if (sqr(out.x.x - T(0.5)) + sqr(out.x.y - T(0.5)) > T(0.25)) return out;
  out.h = map_from_square(ndf, out.x);
  out.pdf_conditional_x = kemppinen_block_density(block, out.x);
  const T area_b = (block.hi.x - block.lo.x) * (block.hi.y - block.lo.y);
  out.pdf_printed_h =
      out.pdf_conditional_x * area_b * map_jacobian_paper(ndf, out.h) * out.h.z * w_l;
  out.ok = out.h.z > T(0);
  return out;
}

// The marginal density in □ of kemppinen_sample_half's x (defective: rejections excluded).
template <class Ndf, class T>
T kemppinen_sample_density_square(const KemppinenParams<T>& p, const Ndf& ndf,
                                  const FootprintQuery<T>& fp, Vec2<T> x, int process = 0) {
  if (sqr(x.x - T(0.5)) + sqr(x.y - T(0.5)) > T(0.25)) return T(0);
  const KemppinenSpatial<T> sp = kemppinen_spatial(p, fp);
  const int n = p.side;
  static thread_local KemppinenBlock<T> block;
  T total = T(0);
  for (int up = 0; up < 2; ++up) {
    const int level = sp.l0 + up;
    const T w_l = up ? sp.w1 : T(1) - sp.w1;
    if (!(w_l > T(0))) continue;
    const T res_a = kemppinen_angular_resolution<T>(level);
    const std::int64_t cx = static_cast<std::int64_t>(floor(x.x * res_a));
    const std::int64_t cy = static_cast<std::int64_t>(floor(x.y * res_a));
    for (std::int64_t bx = cx - n + 1; bx <= cx; ++bx)
      for (std::int64_t by = cy - n + 1; by <= cy; ++by) {
        // x_a selects start b where x_a·res_a ∈ [b + (n−1)/2, b + (n+1)/2).
        const T half = T(0.5) * T(n - 1);
        const T area = T(disk_rect_area(
            double((T(bx) + half) / res_a), double((T(bx) + half + T(1)) / res_a),
            double((T(by) + half) / res_a), double((T(by) + half + T(1)) / res_a), 0.5, 0.5, 0.5));
        if (!(area > T(0))) continue;
        kemppinen_block(p, ndf, sp, level, w_l, bx, by, block, process);
        total += w_l * area / T(kMapDomainArea<T>) * kemppinen_block_density(block, x);
      }
  }
  return total;
}

// The marginal density of ω_h per steradian: the density in □ at T(ω_h) times |det dT/dω|.
template <class Ndf, class T>
T kemppinen_sample_density_half(const KemppinenParams<T>& p, const Ndf& ndf,
                                const FootprintQuery<T>& fp, Vec3<T> h, int process = 0) {
  if (!(h.z > T(0))) return T(0);
  return kemppinen_sample_density_square(p, ndf, fp, map_to_square(ndf, h), process) *
         map_jacobian_true(ndf, h);
}

// A sampler key from the two uniforms of a model's sample(): their bit patterns hashed.
template <class T>
std::uint64_t kemppinen_key_from_uniforms(Vec2<T> u) {
  const double a = double(u.x), b = double(u.y);
  std::uint64_t ia = 0, ib = 0;
  std::memcpy(&ia, &a, sizeof ia);
  std::memcpy(&ib, &b, sizeof ib);
  return mix64(mix64(ia + 0x9e3779b97f4a7c15ULL) ^ ib);
}

}  // namespace glintlab

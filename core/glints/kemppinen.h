// Kemppinen et al. 2025 "Evaluating and Sampling Glinty NDFs in Constant Time": the filtered glinty
// NDF D★^f of Eq. 11 by Algorithm 1 (implicit jittered 4D grid, LOD from the pixel footprint, k
// neighbours in space and angle, Gaussian pixel filter, roulette MIP blending Eq. 8, compensation
// Eq. 9–10, anisotropy, per-facet colours, triplanar UV-free mode), for any NDF with a map T of
// core/maps (GGX: Sec. 3.2.1, Beckmann: Sec. 3.2.2).
//
// Conventions (the paper leaves them open or prints them inconsistently; each is a choice here):
// * Angular space is the unit square of core/maps/disk_square.h; U_Ω the disk of radius ½ in it.
//   Spatial space is x_s = A★·uv with A★ = diag(√a, 1/√a) (det 1, so `density` stays the number of
//   points per unit uv area; Algorithm 1 line 1 scales res by det A★⁻¹ instead).
// * N is the normalised 2D normal density (Eq. 4 prints a 1D normalisation 1/(σ√2π), under which
//   a lobe does not integrate to a constant). Lobe width σ = α★√|J_T| with |J_T| = D/|U_Ω| as
//   Eq. 3–4 print it; anisotropic lobes Σ_a = σ² A★⁻² (Algorithm 1 line 12).
// * Normalisation of Eq. 4/11: kPrinted uses the prefactor |J_T| = D/|U_Ω| of Eq. 3 with K_P the
//   number of cells, under which the area mean is D/|U_Ω| = 4D/π, not D (Eq. 2 fails);
//   kCorrected uses the prefactor D, under which the area mean of the explicit points is
//   D times the lobe's mass inside U_Ω (kemppinen.convergence).
// * LOD: λ = log2(2 σ_max res), σ_max the larger standard deviation of the spatial filter in
//   x_s, clamped to [0, kMaxLevel]: at ⌊λ⌋ the filter's 2σ spans one to two cells
//   (Sec. 3.3.2). Both ⌊λ⌋ and ⌊λ⌋+1 are always visited (weight 1 − frac, frac), so the number of
//   points visited is 2k² for every query (constant time).
//
// The kernel is generic over T (float, double, a SIMD batch): cell indices and MIP levels are
// per-lane integers (core/math/lanes.h), per-lane choices are selects, and the parameters it
// branches on (k, blending, erf, colours) are uniform, never per-lane values.
#pragma once

#include <cstdint>

#include "core/glints/kemppinen_compensation.h"
#include "core/glints/kemppinen_grid.h"
#include "core/glints/kemppinen_lanes.h"
#include "core/maps/beckmann_map.h"
#include "core/maps/disk_square.h"
#include "core/maps/ggx_map.h"
#include "core/model.h"

namespace glintlab::kemppinen2025 {

enum class Blend { kRoulette = 0, kLinear = 1 };
enum class Normalization { kCorrected = 0, kPrinted = 1 };
enum class Colors { kWhite = 0, kRedYellow = 1 };

inline constexpr int kMaxLevel = 20;
// ε of Eq. 8 ("We use ε = 0.1 for all of our results").
inline constexpr double kRouletteEpsilon = 0.1;

template <class T>
struct Params {
  T density;         // K_P, points per unit uv area (Table 1)
  T microroughness;  // α★ (Eq. 4)
  T anisotropy;      // a of A★ = diag(√a, 1/√a) (Sec. 3.3.6)
  T filter;          // f, the pixel filter's standard deviation in pixels (Alg. 1 line 11)
  int side;          // √k: k = side² neighbours in space and in angle
  Blend blend;
  Erf erf;
  Normalization normalization;
  Colors colors;
  std::uint64_t seed;
  bool compensate = true;  // false: Eq. 11 without C (ablation and negative controls)
};

// What one evaluation produced (the model's intermediates).
template <class T>
struct Result {
  Vec3<T> d;                  // D★^f (Eq. 11), per colour channel
  Vec3<T> explicit_part;      // the sum over B(k) of Eq. 11, times the prefactor
  Vec3<T> compensation_part;  // prefactor × Σ_l w_l E[c] C (Eq. 10)
  T smooth_d;                 // D(ω_h) of the base NDF
  T lambda, w0, w1;           // LOD λ and the weights of levels ⌊λ⌋ and ⌊λ⌋+1
  LaneInt<T, int> level0;
  int points;  // (spatial cell, angular cell) pairs visited
};

// ---- Pieces of Algorithm 1 -----------------------------------------------------------------

// x_s = A★·uv (Algorithm 1 line 2).
template <class T>
GLINTLAB_FN Vec2<T> spatial_position(const Params<T>& p, Vec2<T> uv) {
  const T s = sqrt(p.anisotropy);
  return {uv.x * s, uv.y / s};
}

// Symmetric 2×2 matrix (xx, xy, yy).
template <class T>
struct Sym2 {
  T xx, xy, yy;
};

// Σ_s = f² (A★ J_uv)(A★ J_uv)ᵀ (Algorithm 1 line 11, in x_s), J_uv = [duv_dx duv_dy]; floored at
// (10⁻³ of a level-0 cell)² so a zero footprint stays a (very narrow) Gaussian.
template <class T>
GLINTLAB_FN Sym2<T> spatial_covariance(const Params<T>& p, const FootprintQuery<T>& fp, T res) {
  const T f2 = sqr(p.filter);
  const T a = p.anisotropy;
  const T floor2 = sqr(T(1e-3) / res);
  return {f2 * a * (sqr(fp.duv_dx.x) + sqr(fp.duv_dy.x)) + floor2,
          f2 * (fp.duv_dx.x * fp.duv_dx.y + fp.duv_dy.x * fp.duv_dy.y),
          f2 / a * (sqr(fp.duv_dx.y) + sqr(fp.duv_dy.y)) + floor2};
}

// Implicit grid base resolution (Algorithm 1 line 1): √K_P cells per unit of x_s at level 0.
template <class T>
GLINTLAB_FN T base_resolution(const Params<T>& p) {
  return sqrt(p.density);
}

// LOD λ (Algorithm 1 line 5, Sec. 3.3.2): log2(2 σ_max res), clamped to [0, kMaxLevel].
template <class T>
GLINTLAB_FN T lod(const Sym2<T>& s, T res) {
  const T mean = T(0.5) * (s.xx + s.yy);
  const T dev = sqrt(sqr(T(0.5) * (s.xx - s.yy)) + sqr(s.xy));
  const T sigma_max = sqrt(mean + dev);
  const T lambda = log(T(2) * sigma_max * res) * T(1.44269504088896340736);  // / ln 2
  return clamp(lambda, T(0), T(kMaxLevel));
}

// The normalised 2D normal density N(d; Σ) = exp(−½ dᵀΣ⁻¹d)/(2π√|Σ|) (the lobes of Eq. 4/11).
// Σ is first scaled by c = 2^64 or 2^96 where its trace is below 2^-40 or 2^-104, and c is taken
// out again: |Σ| of a glint lobe is σ⁴, which underflows float to 0 for σ < 10⁻¹¹ (α★ = 10⁻⁹:
// σ ≈ 10⁻¹⁵), and made q = x/0 and rsqrt(0) = ∞, so N = 0·∞ = NaN. Multiplying by a power of two
// is exact, so where nothing underflows (every double input) the result is bit-identical.
template <class T>
GLINTLAB_FN T normal2(Vec2<T> d, const Sym2<T>& s) {
  const T trace = s.xx + s.yy;
  const T c1 = select(trace < T(0x1p-40), T(0x1p64), T(1));
  const T c = select(trace < T(0x1p-104), T(0x1p96), c1);
  const Sym2<T> sc{s.xx * c, s.xy * c, s.yy * c};
  const T det = sc.xx * sc.yy - sqr(sc.xy);
  const T q = (sc.yy * sqr(d.x) - T(2) * sc.xy * d.x * d.y + sc.xx * sqr(d.y)) / det * c;
  return exp(T(-0.5) * q) * (T(0.15915494309189533577) * rsqrt(det) * c);
}

// normal2 with Σ fixed and d varying: the factors of Σ alone (its power-of-two scaling, |Σ| and
// the peak 1/(2π√|Σ|)) computed once, then normal2_at(form, d) = normal2(d, Σ) bit for bit (the
// same operations in the same order). The spatial lobe of a query and its angular lobe in Eq. 11
// have one Σ for every point of the neighbourhood.
template <class T>
struct Normal2Form {
  Sym2<T> sc;  // Σ·c
  T c, det, peak;
};

template <class T>
GLINTLAB_FN Normal2Form<T> normal2_form(const Sym2<T>& s) {
  const T trace = s.xx + s.yy;
  const T c1 = select(trace < T(0x1p-40), T(0x1p64), T(1));
  const T c = select(trace < T(0x1p-104), T(0x1p96), c1);
  const Sym2<T> sc{s.xx * c, s.xy * c, s.yy * c};
  const T det = sc.xx * sc.yy - sqr(sc.xy);
  return {sc, c, det, T(0.15915494309189533577) * rsqrt(det) * c};
}

// The exponent's quadratic form dᵀΣ⁻¹d of normal2 (as normal2 rounds it).
template <class T>
GLINTLAB_FN T normal2_quadratic(const Normal2Form<T>& f, Vec2<T> d) {
  return (f.sc.yy * sqr(d.x) - T(2) * f.sc.xy * d.x * d.y + f.sc.xx * sqr(d.y)) / f.det * f.c;
}

template <class T>
GLINTLAB_FN T normal2_at(const Normal2Form<T>& f, Vec2<T> d) {
  return exp(T(-0.5) * normal2_quadratic(f, d)) * f.peak;
}

// Eq. 8: R(r, w) = smoothstep(max(0, r − ε), min(1, r + ε), w), the mollified roulette.
template <class T>
GLINTLAB_FN T roulette(T r, T w) {
  const T eps = T(kRouletteEpsilon);
  const T e0 = max(T(0), r - eps), e1 = min(T(1), r + eps);
  const T t = saturate((w - e0) / (e1 - e0));
  return t * t * (T(3) - T(2) * t);
}

// GlintColor (Algorithm 1 line 17, Sec. 3.3.6 "Colors"): white, or red/yellow with probability ½.
template <class T>
GLINTLAB_FN Vec3<T> color(Colors colors, T r) {
  const Vec3<T> red{T(1), T(0.08), T(0.03)}, yellow{T(1), T(0.75), T(0.1)};
  const Vec3<T> c = select(r < T(0.5), red, yellow);
  return colors == Colors::kWhite ? Vec3<T>{T(1), T(1), T(1)} : c;
}

// E[GlintColor], the colour of the compensation term (Algorithm 1 line 20).
template <class T>
GLINTLAB_FN Vec3<T> expected_color(Colors colors) {
  return colors == Colors::kWhite ? Vec3<T>{T(1), T(1), T(1)} : Vec3<T>{T(1), T(0.415), T(0.065)};
}

// Rec. 709 luminance (Algorithm 2 line 12 "Luminance(c)").
template <class T>
GLINTLAB_FN T luminance(Vec3<T> c) {
  return T(0.2126) * c.x + T(0.7152) * c.y + T(0.0722) * c.z;
}

// The angular frame of one query: x_a = T(ω_h) (Alg. 1 line 3), d = D(ω_h) (line 4), the lobe
// standard deviations of Σ_a (line 12, Eq. 4) and the prefactor of Eq. 11.
template <class T>
struct Angular {
  Vec2<T> x_a;
  Vec2<T> sigma_a;
  T d, prefactor;
  Mask<T> valid;  // ω_h in the upper hemisphere with D > 0
};

template <class Ndf, class T>
GLINTLAB_FN Angular<T> angular(const Params<T>& p, const Ndf& ndf, Vec3<T> h) {
  const Mask<T> up = h.z > T(0);
  const Vec3<T> hs = select(up, h, Vec3<T>{T(0), T(0), T(1)});
  const T d = ndf.D(hs);
  const T j_paper = d / T(kMapDomainArea<T>);  // |J_T| as Eq. 3 prints it
  // Lobe width from D floored at 10⁻¹²: where D underflows to 0 (Beckmann near the horizon) σ = 0
  // made N(·; Σ_a) 0/0 and D★^f NaN; U_Ω holds less than 10⁻¹² of the points there.
  const T sigma = p.microroughness * sqrt(max(j_paper, T(1e-12) / T(kMapDomainArea<T>)));
  const T sa = sqrt(p.anisotropy);
  const T prefactor = p.normalization == Normalization::kPrinted ? j_paper : d;
  const Mask<T> valid = up && (d > T(0));
  return {map_to_square(ndf, hs), {sigma / sa, sigma * sa}, d, prefactor, valid};
}

// 2^l per lane: the angular cells per axis at level l (Alg. 1 lines 9–10).
template <class T>
GLINTLAB_INLINE LaneInt<T> level_cells(const LaneInt<T, int>& level) {
  return int_lanes<T>([&](std::size_t l) { return std::int64_t(1) << lane(level, l); });
}

// Cell side of the angular grid and of the spatial grid at level l (Alg. 1 lines 9–10).
template <class T>
GLINTLAB_INLINE T angular_resolution(const LaneInt<T, int>& level) {
  return int_to_float<T>(level_cells<T>(level));
}

// ---- Algorithm 1 -----------------------------------------------------------------------------

// One level l with weight w_l, one point process (`process`, weight `process_w` for the triplanar
// blend): adds the explicit points of B(k) in space × angle and the compensation (Eq. 10).
template <class T>
GLINTLAB_FN void level(const Params<T>& p, const Angular<T>& ang, Vec2<T> x_s,
                       const Sym2<T>& sigma_s, T res, const LaneInt<T, int>& level, T w_l,
                       int process, Vec3<T>& explicit_sum, Vec3<T>& compensation) {
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
  // Both lobes have one Σ for every point (normal2_form), and a cell's hash chain is shared along
  // its spatial row and column (cell_chain_*_lanes).
  const Normal2Form<T> spatial_lobe = normal2_form(sigma_s);
  const Normal2Form<T> angular_lobe = normal2_form(sigma_a2);
  // A point whose roulette weight is 0 adds blend · N_s · N_a · 1/ρ = +0 when every factor is
  // finite: each lobe is exp(−q/2) · peak with q ≥ 0 (exp ≤ 1) and a finite peak; its exps are
  // skipped. (x − x == 0: x finite.)
  const Mask<T> finite_factors = (spatial_lobe.peak - spatial_lobe.peak == T(0)) &&
                                 (angular_lobe.peak - angular_lobe.peak == T(0)) &&
                                 (inv_rho - inv_rho == T(0));
  // The uniforms of a point share the seed's and the cell's hash steps (kemppinen_lanes.h).
  const std::uint64_t seed_key = cell_seed_key(p.seed);
  // Each cell coordinate as a float, and whether an angular one lies in the square, once per
  // coordinate rather than once per cell (lane by lane, the same values).
  LaneInt<T> ay[kMaxSide];
  T fay[kMaxSide];
  Mask<T> in_y[kMaxSide];
  for (int b = 0; b < n; ++b) {
    ay[b] = ay0 + b;
    fay[b] = int_to_float<T>(ay[b]);
    in_y[b] = mask_lanes<T>(
        [&](std::size_t l) { return lane(ay[b], l) >= 0 && lane(ay[b], l) < lane(n_a, l); });
  }
  for (int i = 0; i < n; ++i) {
    const LaneInt<T> sx = sx0 + i;
    const T fsx = int_to_float<T>(sx);
    const LaneInt<T, std::uint64_t> hash_i = cell_chain_sx_lanes<T>(sx);
    for (int j = 0; j < n; ++j) {
      const LaneInt<T> sy = sy0 + j;
      const T fsy = int_to_float<T>(sy);
      const LaneInt<T, std::uint64_t> hash_ij = cell_chain_sy_lanes<T>(hash_i, sy);
      for (int a = 0; a < n; ++a) {
        const LaneInt<T> ax = ax0 + a;
        const T fax = int_to_float<T>(ax);
        const Mask<T> in_x = mask_lanes<T>(
            [&](std::size_t l) { return lane(ax, l) >= 0 && lane(ax, l) < lane(n_a, l); });
        const LaneInt<T, std::uint64_t> hash_ija = cell_chain_ax_vector<T>(hash_ij, ax);
        for (int b = 0; b < n; ++b) {
          const LaneInt<T, std::uint64_t> key = cell_key<T>(
              seed_key, cell_chain_ay_level_vector<T>(hash_ija, ay[b], level, process));
          const Mask<T> in_square = in_x && in_y[b];
          const Vec2<T> g_s{(fsx + key_uniform<T>(key, kKemppinenDimSpatialX)) / res_s,
                            (fsy + key_uniform<T>(key, kKemppinenDimSpatialY)) / res_s};
          const Vec2<T> g_a{(fax + key_uniform<T>(key, kKemppinenDimAngularX)) / res_a,
                            (fay[b] + key_uniform<T>(key, kKemppinenDimAngularY)) / res_a};
          // Points outside U_Ω are rejected (Sec. 3.3.1).
          const Mask<T> in_disk = sqr(g_a.x - T(0.5)) + sqr(g_a.y - T(0.5)) <= T(0.25);
          const T r = key_uniform<T>(key, kKemppinenDimRoulette);
          const T blend = p.blend == Blend::kRoulette ? roulette(r, w_l) : w_l;
          const T q_s = normal2_quadratic(spatial_lobe, x_s - g_s);
          const T q_a = normal2_quadratic(angular_lobe, ang.x_a - g_a);
          const Mask<T> adds_zero =
              (blend == T(0)) && finite_factors && (q_s >= T(0)) && (q_a >= T(0));
          T w = T(0);
          if (any_lane<T>(!adds_zero))  // uniform: some lane's point has weight
            w = blend * (exp(T(-0.5) * q_s) * spatial_lobe.peak) *
                (exp(T(-0.5) * q_a) * angular_lobe.peak) * inv_rho;
          const Vec3<T> col = color(p.colors, key_uniform<T>(key, kKemppinenDimColor));
          explicit_sum = explicit_sum + select(in_disk && in_square, w, T(0)) * col;
        }
      }
    }
  }
  // B(k) clipped to the square: the cells that exist.
  const Vec2<T> b_lo{int_to_float<T>(int_max(ax0, std::int64_t(0))) / res_a,
                     int_to_float<T>(int_max(ay0, std::int64_t(0))) / res_a};
  const Vec2<T> b_hi{int_to_float<T>(int_min(ax0 + n, n_a)) / res_a,
                     int_to_float<T>(int_min(ay0 + n, n_a)) / res_a};
  const T cmp =
      p.compensate ? kemppinen2025::compensation(ang.x_a, ang.sigma_a, b_lo, b_hi, p.erf) : T(0);
  compensation = compensation + (w_l * cmp) * expected_color<T>(p.colors);
}

// D★^f of one point process at footprint `fp` (Algorithm 1), with an extra weight on its levels
// (1 for plain uv; the triplanar plane weight otherwise, applied inside the roulette).
template <class Ndf, class T>
GLINTLAB_FN Result<T> eval_process(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp,
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
  kemppinen2025::level(p, ang, x_s, sigma_s, res, l0, w0 * process_w, process, ex, cp);
  kemppinen2025::level(p, ang, x_s, sigma_s, res, l0 + 1, w1 * process_w, process, ex, cp);
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

// D★^f(x, ω_h) of Eq. 11 by Algorithm 1, at the footprint's uv.
template <class Ndf, class T>
GLINTLAB_FN Result<T> eval(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp,
                           Vec3<T> h) {
  return eval_process(p, ndf, fp, h, 0, T(1));
}

// The triplanar blend weights (Sec. 3.3.6): |n_axis| / Σ|n| for the planes ⊥ x, y, z. The paper
// prints the weight as |n · plane normal| alone, whose sum runs from 1 (axis-aligned) to √3
// (diagonal) and would brighten diagonal surfaces by up to √3; normalised here so they sum to 1.
template <class T>
GLINTLAB_FN Vec3<T> triplanar_weights(Vec3<T> n_geo) {
  const Vec3<T> a{abs(n_geo.x), abs(n_geo.y), abs(n_geo.z)};
  return (T(1) / (a.x + a.y + a.z)) * a;
}

// The point process of each triplanar plane: ⊥ z is process 0, the uv process, so on a plane
// ⊥ z at uv = (x, y) the triplanar glints are the uv glints; ⊥ x and ⊥ y are 1 and 2.
// (A function rather than a constant array: a device kernel cannot index a host array.)
GLINTLAB_FN constexpr int triplanar_process(int axis) {
  return axis == 0 ? 1 : axis == 1 ? 2 : 0;
}

// The footprint of triplanar plane `axis` (⊥ x, y, z) at object-space position `pos` with screen
// derivatives dpos_dx, dpos_dy: uv = (p.y, p.z), (p.z, p.x), (p.x, p.y).
template <class T>
GLINTLAB_FN FootprintQuery<T> triplanar_footprint(int axis, Vec3<T> pos, Vec3<T> dpos_dx,
                                                  Vec3<T> dpos_dy) {
  const auto pick = [axis](Vec3<T> v) {
    return axis == 0 ? Vec2<T>{v.y, v.z} : axis == 1 ? Vec2<T>{v.z, v.x} : Vec2<T>{v.x, v.y};
  };
  return {pick(pos), pick(dpos_dx), pick(dpos_dy)};
}

// UV-free rendering by triplanar mapping (Sec. 3.3.6): three point processes on the planes
// ⊥ x, y, z of object space, at uv = (p.y, p.z), (p.z, p.x), (p.x, p.y) with footprints from the
// position derivatives, weighted by triplanar_weights through the same roulette. λ, the
// level weights and level0 are those of the heaviest plane; points counts all three. Anisotropy
// is the caller's to disable (the paper: triplanar "prevents a simple definition of anisotropy").
template <class Ndf, class T>
GLINTLAB_FN Result<T> eval_triplanar(const Params<T>& p, const Ndf& ndf, Vec3<T> pos,
                                     Vec3<T> dpos_dx, Vec3<T> dpos_dy, Vec3<T> n_geo, Vec3<T> h) {
  const Vec3<T> wv = triplanar_weights(n_geo);
  const T w[3] = {wv.x, wv.y, wv.z};
  Result<T> out = eval_process(p, ndf, triplanar_footprint(0, pos, dpos_dx, dpos_dy), h,
                               triplanar_process(0), w[0]);
  T w_best = w[0];
  for (int i = 1; i < 3; ++i) {
    const Result<T> r = eval_process(p, ndf, triplanar_footprint(i, pos, dpos_dx, dpos_dy), h,
                                     triplanar_process(i), w[i]);
    out.explicit_part = out.explicit_part + r.explicit_part;
    out.compensation_part = out.compensation_part + r.compensation_part;
    out.points += r.points;
    const Mask<T> heavier = w[i] > w_best;
    out.lambda = select(heavier, r.lambda, out.lambda);
    out.w0 = select(heavier, r.w0, out.w0);
    out.w1 = select(heavier, r.w1, out.w1);
    out.level0 = int_select<T>(heavier, r.level0, out.level0);
    w_best = max(w_best, w[i]);
  }
  out.d = out.explicit_part + out.compensation_part;
  return out;
}

}  // namespace glintlab::kemppinen2025

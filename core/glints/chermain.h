// The procedural glinty patch-SDF and BRDF of Chermain et al. 2020 as recapitulated in Chermain et
// al. 2021 Sec. 3 (Eq. 1–6), with the slope correlation matrix M (2021 Eq. 16–18) and geometric
// glint anti-aliasing (GGAA, 2021 Eq. 9–15 and 19–21), V-cavity masking (Heitz 2014 Sec. 3).
//
// Virtual MIP hierarchy (2021 Eq. 3): at LOD l (any integer, clamped to [−20, 40]) the uv plane is
// cut into square cells of side 2^l; the footprint's LOD is l_P = log2 max(‖∂uv/∂x‖, ‖∂uv/∂y‖)
// (the isotropic texture-LOD rule), w(⌊l_P⌋) = 1 − frac(l_P), w(⌊l_P⌋+1) = frac(l_P), and at each
// LOD the four cells nearest uv get bilinear weights W_P (they sum to 1), as in texture filtering.
// A cell at LOD l holds density·4^l microfacets; its marginals come from dictionary level
// k = ⌊l + ½ log2 density⌋ (2^k lobes per marginal, so about 4^k lobes in the 2D product), clamped
// below at 0; for k ≥ L the cell uses the smooth limit, the Gaussian (Beckmann) SDF of covariance Σ
// (Eq. 16). Per cell, a counter hash of the cell's lower-left corner (in units of 2^-20, so a
// coarse cell shares its draws with its lower-left child) picks a rotation θ and the two marginal
// indices. M_cell = M R(θ) with M of Eq. 18; P_M = P_o(R(−θ) M⁻¹ m̃)/det M (Eq. 4–6). GGAA (Eq. 19):
// each marginal is read with textureGrad (core/glints/chermain_lookup.h), the derivatives s_K
// R(−θ) M⁻¹ dh/dx, s_K R(−θ) M⁻¹ dh/dy, dh the screen-space derivative of the half slope h̃ (Eq. 20)
// or of the projected half vector h⊥ = (x_h, y_h) (Eq. 21, the default). The smooth fallback is not
// filtered (its lobe is far wider than any kernel GGAA is meant for).
//
// Kernels generic over the float type (scalar and core/simd Wide<> batches): the 2 LODs × 4 cells
// are masks (a zero weight adds nothing), the smooth fallback a per-lane select, the cell hash and
// the texel fetches in vector registers on the batches (core/glints/chermain_lanes.h: the integer
// mixer on 64-bit lanes, hardware gathers; per-lane code elsewhere, core/math/lanes.h). The scalar
// double instantiation is the host code this model always had, op for op; the model is offered in
// double only (kDoubleOnly): cell coordinates at LOD −20 are uv·2^20, whose bilinear weights float
// would round to 2^−3 at uv ≈ 1 (batched on Wide<double>, core/simd/instantiate.h).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string_view>
#include <type_traits>

#include "core/glints/chermain_dictionary.h"
#include "core/glints/chermain_lanes.h"
#include "core/glints/chermain_lookup.h"
#include "core/math/lane_rng.h"
#include "core/math/lanes.h"
#include "core/math/ops.h"
#include "core/math/rng.h"
#include "core/model.h"
#include "core/ndf/microfacet.h"

namespace glintlab::chermain2021 {

// Which screen-space derivative sets the GGAA kernel (2021 Sec. 6.1).
enum Kernel { kNoGgaa = 0, kHalfSlope = 1, kProjectedHalf = 2 };

// The 2×2 matrix M of 2021 Eq. 18, stored with its inverse and determinant:
// M = (1/σ_o) [[σ_x √(1−ρ²), ρ σ_x], [0, σ_y]], so that M Σ_o Mᵀ = Σ (Eq. 16, 17).
// `with_rho = false` gives the 2020 form diag(σ_x, σ_y)/σ_o (ρ ignored), the control of
// chermain.correlation. Uniform over a batch: host doubles.
struct Matrix {
  double m00, m01, m10, m11;
  double i00, i01, i10, i11;
  double det;
};

inline Matrix matrix(double sigma_x, double sigma_y, double rho, double sigma_o,
                     bool with_rho = true) {
  const double r = with_rho ? rho : 0.0;
  const double c = std::sqrt(1 - r * r);
  Matrix M{};
  M.m00 = sigma_x * c / sigma_o, M.m01 = r * sigma_x / sigma_o;
  M.m10 = 0, M.m11 = sigma_y / sigma_o;
  M.det = M.m00 * M.m11;
  M.i00 = M.m11 / M.det, M.i01 = -M.m01 / M.det;
  M.i10 = 0, M.i11 = M.m00 / M.det;
  return M;
}

// The model's parameters (uniform over a batch).
struct SdfParams {
  const Dictionary* dictionary;
  double sigma_x, sigma_y, rho;  // Σ of Eq. 16 (slope standard deviations and correlation)
  double log2_density;           // log2 of microfacets per unit uv area
  int kernel;                    // Kernel
  double s_k;                    // kernel scale s_K (Eq. 19)
  std::uint64_t seed;            // of the per-cell draws
  bool with_rho = true;          // false: the 2020 matrix (control)
  TableWrap wrap = TableWrap::kMirroredRepeat;
};

// What one patch-SDF evaluation used (the model's intermediates).
template <class T>
struct SdfInfoT {
  T lod = T(0);           // l_P
  T dict_level = T(0);    // k at LOD ⌊l_P⌋ (= L for the smooth fallback)
  T mip_lambda = T(0);    // weighted mean textureGrad level of detail over the lookups
  T kernel_width = T(0);  // s_K max(‖dh/dx‖, ‖dh/dy‖): the kernel extent in h̃ space
};
using SdfInfo = SdfInfoT<double>;

// One cell's draws: rotation and the two marginals (2020: "randomly picked", 2021 Sec. 3); the
// marginal indices as integer-valued T.
template <class T>
struct Cell {
  T cos_t, sin_t;
  T nx, ny;
};

// The counter key of the cell with lower-left corner (ci, cj) in units of 2^-20.
GLINTLAB_FN std::uint64_t cell_key(std::int64_t ci, std::int64_t cj) {
  return mix64(std::uint64_t(ci) * 0x9e3779b97f4a7c15ULL) ^ std::uint64_t(cj);
}

// The keys of the cells with corners (cu, cv)·2^l per lane, cu, cv integer-valued and
// scale = 2^(l+20) (their products are exact), as per-lane counter indices.
template <class T>
GLINTLAB_FN RngIndex<T> cell_keys(const T& cu, const T& cv, const T& scale) {
  const LanesOf<T> a(cu), b(cv), s(scale);
  RngIndex<T> r;
  if constexpr (std::is_floating_point_v<T>) {
    r = cell_key(std::int64_t(a[0] * s[0]), std::int64_t(b[0] * s[0]));
  } else {
    for (std::size_t l = 0; l < kLaneCount<T>; ++l)
      r[l] = cell_key(std::int64_t(a[l] * s[l]), std::int64_t(b[l] * s[l]));
  }
  return r;
}

// θ = 2π u_0 and the marginals ⌊u_d N⌋ (d = 1, 2, at most N − 1) from the cell's counters.
template <class T>
GLINTLAB_FN Cell<T> cell_from_uniforms(const lanes::CellUniforms<T>& u, int n) {
  const T theta = T(2 * kPi<double>) * u.u0;
  Cell<T> c;
  sincos(theta, &c.sin_t, &c.cos_t);
  const T last = T(n - 1);
  c.nx = std_min(floor(u.u1 * T(n)), last);
  c.ny = std_min(floor(u.u2 * T(n)), last);
  return c;
}
template <class T>
GLINTLAB_FN Cell<T> cell(std::uint64_t seed, const RngIndex<T>& key, int n) {
  return cell_from_uniforms<T>(
      {lane_uniform<T>(seed, key, 0), lane_uniform<T>(seed, key, 1), lane_uniform<T>(seed, key, 2)},
      n);
}

// The draws of the cells with corners (cu, cv)·2^l (scale = 2^(l+20)): cell(seed, cell_keys(…), n),
// on the batches with the key and the counter mixing in vector registers (core/glints/
// chermain_lanes.h, the same bits).
template <class T>
GLINTLAB_FN Cell<T> cell_at(std::uint64_t seed, const T& cu, const T& cv, const T& scale, int n) {
  if constexpr (lanes::kVectorDoubles < T >> 0) {
    lanes::CellUniforms<T> u;
    if (lanes::cell_uniforms(seed, cu, cv, scale, &u)) return cell_from_uniforms(u, n);
  }
  return cell<T>(seed, cell_keys(cu, cv, scale), n);
}

// Dictionary level of a cell at LOD l (integer-valued): it holds density·4^l microfacets, about
// 4^k lobes in the product of two level-k marginals, so k = ⌊l + ½ log2 density⌋, at least 0.
template <class T>
GLINTLAB_FN T dictionary_level(T l, double log2_density) {
  return std_max(T(0), floor(l + T(0.5 * log2_density)));
}

// The smooth limit: the centred Gaussian slope density of covariance Σ (Eq. 16), the Beckmann
// SDF with correlation.
template <class T>
GLINTLAB_FN T gaussian_sdf(T x, T y, double sx, double sy, double rho) {
  const double c = 1 - rho * rho;
  const T a = x / T(sx), b = y / T(sy);
  const T q = (a * a - T(2 * rho) * a * b + b * b) / T(c);
  return exp(T(-0.5) * q) / T(2 * kPi<double> * sx * sy * std::sqrt(c));
}

// Screen-space derivatives of the quantity Eq. 20 (h̃) or Eq. 21 (h⊥) filters with, from the half
// vector h (local frame, h_z > 0) and its derivatives dh/dx, dh/dy (core/scene/footprint.h).
template <class T>
struct SlopeDerivativesT {
  T dx_x, dx_y, dy_x, dy_y;  // d(·)/dx and d(·)/dy, components x and y
};
using SlopeDerivatives = SlopeDerivativesT<double>;

template <class T>
GLINTLAB_FN SlopeDerivativesT<T> slope_derivatives(Vec3<T> h, Vec3<T> dh_dx, Vec3<T> dh_dy,
                                                   int kernel) {
  if (kernel == kProjectedHalf) return {dh_dx.x, dh_dx.y, dh_dy.x, dh_dy.y};
  if (kernel == kNoGgaa) return {T(0), T(0), T(0), T(0)};
  // h̃ = (−x/z, −y/z): dh̃ = −(dx z − x dz)/z², likewise for y.
  const T z2 = h.z * h.z;
  const auto d = [&](Vec3<T> dv, T c, T dc) { return -(dc * h.z - c * dv.z) / z2; };
  return {d(dh_dx, h.x, dh_dx.x), d(dh_dx, h.y, dh_dx.y), d(dh_dy, h.x, dh_dy.x),
          d(dh_dy, h.y, dh_dy.y)};
}

// The footprint's continuous LOD l_P = log2 max(‖∂uv/∂x‖, ‖∂uv/∂y‖), clamped to [−20, 39].
template <class T>
GLINTLAB_FN T lod(const FootprintQuery<T>& fp) {
  const T foot = sqrt(std_max(dot(fp.duv_dx, fp.duv_dx), dot(fp.duv_dy, fp.duv_dy)));
  const Mask<T> pos = foot > T(0);
  return std_clamp(select(pos, log2(select(pos, foot, T(1))), T(-20)), T(-20), T(39));
}

// 2^e per lane for an integer-valued e (exact; e in [−1022, 1023]).
template <class T>
GLINTLAB_FN T exp2_int(const T& e) {
  return lanes::exp2_int(e);
}

// The shared key parts of a LOD's four cells on a vector path (an empty struct elsewhere).
template <class T, bool = (lanes::kVectorDoubles<T> > 0)>
struct BlockKeysOf {
  struct type {};
};
template <class T>
struct BlockKeysOf<T, true> {
  using type = lanes::CellBlockKeys<T>;
};
template <class T>
using BlockKeys = typename BlockKeysOf<T>::type;

// Visits the terms of Eq. 3 / Eq. 10: visit(active, weight, k, cell) for each of the two LODs and
// four cells, `active` where w(l) W_P(l, s_0) > 0 (its weights sum to 1 per lane). k ≥ L marks the
// smooth fallback, visited once per LOD before that LOD's four cells (which are then inactive;
// cell unused), so each lane sees its terms in the order of the scalar loop.
// `lod` is chermain2021::lod(fp).
template <class T, class Visit>
GLINTLAB_FN void for_each_cell(const SdfParams& p, const FootprintQuery<T>& fp, const T& lod,
                               Visit&& visit) {
  const Dictionary& dict = *p.dictionary;
  const T levels = T(dict.levels());
  const T l0 = floor(lod);
  const T frac = lod - l0;
  for (int li = 0; li < 2; ++li) {
    const T l = l0 + T(li);
    const T wl = li == 0 ? T(1) - frac : frac;
    const Mask<T> lod_on = wl != T(0);
    const T k = dictionary_level(l, p.log2_density);
    const Mask<T> smooth = k >= levels;  // past the last level: the smooth Beckmann SDF
    visit(lod_on && smooth, wl, k, Cell<T>{T(1), T(0), T(0), T(0)});
    const Mask<T> cells_on = lod_on && !smooth;
    if (!any_lane<T>(cells_on)) continue;
    const T inv_cell = exp2_int(-l);      // uv / 2^l = uv · 2^−l exactly
    const T scale = exp2_int(l + T(20));  // corners in units of 2^-20
    const T su = fp.uv.x * inv_cell - T(0.5), sv = fp.uv.y * inv_cell - T(0.5);
    const T fu = floor(su), fv = floor(sv);
    const T tu = su - fu, tv = sv - fv;
    // On the batches the four cells' keys share their column and row parts (cell_block_keys).
    [[maybe_unused]] bool block = false;
    [[maybe_unused]] BlockKeys<T> keys{};
    if constexpr (lanes::kVectorDoubles < T >> 0)
      block = lanes::cell_block_keys(p.seed, fu, fv, scale, &keys);
    for (int c = 0; c < 4; ++c) {
      const int di = c & 1, dj = c >> 1;
      const T wu = di ? tu : T(1) - tu, wv = dj ? tv : T(1) - tv;
      const T W = wu * wv;
      Cell<T> s;
      if constexpr (lanes::kVectorDoubles < T >> 0) {
        s = block
                ? cell_from_uniforms(lanes::block_cell_uniforms(keys, di, dj), dict.distributions())
                : cell_at<T>(p.seed, fu + T(di), fv + T(dj), scale, dict.distributions());
      } else {
        s = cell_at<T>(p.seed, fu + T(di), fv + T(dj), scale, dict.distributions());
      }
      visit(cells_on && W != T(0), wl * W, k, s);
    }
  }
}

template <class T, class Visit>
GLINTLAB_FN void for_each_cell(const SdfParams& p, const FootprintQuery<T>& fp, Visit&& visit) {
  for_each_cell(p, fp, chermain2021::lod(fp), visit);
}

// The (filtered) procedural patch-SDF at slope m̃ (2021 Eq. 3 without GGAA, Eq. 10 and 19 with
// it), for the footprint `fp` and the slope derivatives `d` (ignored when kernel = 0).
template <class T>
GLINTLAB_FN T patch_sdf(const SdfParams& p, Vec2<T> m, const FootprintQuery<T>& fp,
                        const SlopeDerivativesT<T>& d, SdfInfoT<T>* info = nullptr) {
  const Dictionary& dict = *p.dictionary;
  const Table table = dict.table();
  const Matrix M = matrix(p.sigma_x, p.sigma_y, p.rho, dict.sigma_o(), p.with_rho);
  const double rho_used = p.with_rho ? p.rho : 0.0;
  const bool ggaa = p.kernel != kNoGgaa;
  const T sk = T(ggaa ? p.s_k : 0.0);
  const T last_level = T(dict.levels() - 1);
  // M⁻¹ applied once per pixel (Eq. 20/21); the per-cell rotation below.
  const T ax = sk * (T(M.i00) * d.dx_x + T(M.i01) * d.dx_y), ay = sk * (T(M.i11) * d.dx_y);
  const T bx = sk * (T(M.i00) * d.dy_x + T(M.i01) * d.dy_y), by = sk * (T(M.i11) * d.dy_y);
  const T mx = T(M.i00) * m.x + T(M.i01) * m.y, my = T(M.i11) * m.y;  // M⁻¹ m̃
  // The smooth limit at m̃, computed when a lane first needs it (rarely: only footprints whose
  // dictionary level passes the last).
  T gauss = T(0);
  bool have_gauss = false;
  T total = T(0), lambda_sum = T(0), lambda_weight = T(0);
  const T lod = chermain2021::lod(fp);
  for_each_cell(p, fp, lod, [&](Mask<T> on, T w, T k, const Cell<T>& s) {
    if (!any_lane<T>(on)) return;
    const Mask<T> smooth = k > last_level;
    const Mask<T> cell_on = on && !smooth;
    if (any_lane<T>(on && smooth)) {
      if (!have_gauss) gauss = gaussian_sdf(m.x, m.y, p.sigma_x, p.sigma_y, rho_used);
      have_gauss = true;
      total = select(on && smooth, total + w * gauss, total);
    }
    if (!any_lane<T>(cell_on)) return;
    const T kc = std_min(k, last_level);  // in range on the smooth lanes too (discarded)
    const T base_x = table_base(table, s.nx, kc);
    const T base_y = table_base(table, s.ny, kc);
    // R(−θ) applied to M⁻¹ m̃ and to the derivatives.
    const T xo = s.cos_t * mx + s.sin_t * my, yo = -s.sin_t * mx + s.cos_t * my;
    T px, py;
    if (ggaa) {
      const Grad<T> fx = chermain2021::lookup_grad(table, base_x, xo, s.cos_t * ax + s.sin_t * ay,
                                                   s.cos_t * bx + s.sin_t * by, p.wrap, 16);
      const Grad<T> fy = chermain2021::lookup_grad(table, base_y, yo, -s.sin_t * ax + s.cos_t * ay,
                                                   -s.sin_t * bx + s.cos_t * by, p.wrap, 16);
      px = fx.value, py = fy.value;
      lambda_sum = select(cell_on, lambda_sum + w * T(0.5) * (fx.lambda + fy.lambda), lambda_sum);
      lambda_weight = select(cell_on, lambda_weight + w, lambda_weight);
    } else {
      px = chermain2021::lookup_lod(table, base_x, xo, 0, p.wrap);
      py = chermain2021::lookup_lod(table, base_y, yo, 0, p.wrap);
    }
    total = select(cell_on, total + w * px * py / T(M.det), total);
  });
  if (info) {
    info->lod = lod;
    info->dict_level = std_min(dictionary_level(floor(lod), p.log2_density), T(dict.levels()));
    const Mask<T> weighted = lambda_weight > T(0);
    info->mip_lambda = select(weighted, lambda_sum / select(weighted, lambda_weight, T(1)), T(0));
    info->kernel_width =
        sk * sqrt(std_max(d.dx_x * d.dx_x + d.dx_y * d.dx_y, d.dy_x * d.dy_x + d.dy_y * d.dy_y));
  }
  return total;
}

// Mass, mean and covariance of the patch-SDF over the slope plane by the midpoint rule on a
// `grid` × `grid` lattice of the square |m̃_x|, |m̃_y| ≤ R, R = 4√2 σ_o ‖M‖_F (covers every cell's
// support M_cell [−4σ_o, 4σ_o]² and, as ‖M‖_F σ_o ≥ max(σ_x, σ_y), the smooth limit to 5.6 σ).
// For chermain.kernel-normalized (mass = 1, Eq. 15) and chermain.correlation (covariance = Σ).
struct SlopeMoments2 {
  double mass, mean_x, mean_y, xx, yy, xy;  // xx, yy, xy: central second moments / mass
};

inline SlopeMoments2 patch_moments(const SdfParams& p, const FootprintQuery<double>& fp,
                                   const SlopeDerivatives& d, int grid) {
  const double so = p.dictionary->sigma_o();
  const Matrix M = matrix(p.sigma_x, p.sigma_y, p.rho, so, p.with_rho);
  const double R =
      4 * std::sqrt(2.0) * so * std::sqrt(M.m00 * M.m00 + M.m01 * M.m01 + M.m11 * M.m11);
  const double h = 2 * R / grid;
  double s0 = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  for (int j = 0; j < grid; ++j) {
    const double y = -R + (j + 0.5) * h;
    for (int i = 0; i < grid; ++i) {
      const double x = -R + (i + 0.5) * h;
      const double v = patch_sdf(p, Vec2<double>{x, y}, fp, d);
      s0 += v, sx += v * x, sy += v * y, sxx += v * x * x, syy += v * y * y, sxy += v * x * y;
    }
  }
  const double mx = sx / s0, my = sy / s0;
  return {s0 * h * h, mx, my, sxx / s0 - mx * mx, syy / s0 - my * my, sxy / s0 - mx * my};
}

// V-cavity masking-shadowing G2 = min(1, 2(n·h)(n·ωi)/(ωi·h), 2(n·h)(n·ωo)/(ωo·h)) (Heitz 2014
// Sec. 3.1, the only masking the 2020 BRDF supports; 2021 Sec. 7); 0 unless ωi·h, ωo·h, h_z > 0.
template <class T>
GLINTLAB_FN T v_cavity_g2(Vec3<T> wi, Vec3<T> wo, Vec3<T> h) {
  const T a = dot(wi, h), b = dot(wo, h);
  const Mask<T> ok = a > T(0) && b > T(0) && h.z > T(0);
  const T gi = T(2) * h.z * wi.z / select(ok, a, T(1));
  const T go = T(2) * h.z * wo.z / select(ok, b, T(1));
  return select(ok, std_min(std_min(T(1), gi), go), T(0));
}

// The registered model: the BRDF of 2021 Eq. 1 with D from the patch-SDF (Eq. 2 or Eq. 8), F = 1.
struct Chermain {
  // Offered in double only (see the file comment); the batch API runs it on Wide<double>
  // whatever the column type.
  static constexpr bool kDoubleOnly = true;
  static constexpr std::string_view kName = "chermain";
  // Conformance (verify/conformance/): what the model does not claim.
  static constexpr std::array<NotClaimed, 2> kNotClaimed = {{
      {"float-vs-double",
       "double only (kDoubleOnly): cell coordinates at LOD -20 are uv 2^20, beyond float's "
       "precision"},
      {"converges-to-smooth",
       "its smooth limit is the correlated Beckmann NDF (rho) with the V-cavity G2 of Chermain et "
       "al. 2020, which no registered model evaluates: smooth_beckmann has Smith's "
       "height-correlated G2 and no correlation"},
  }};
  static constexpr std::string_view kDescription =
      "procedural glinty BRDF (Chermain et al. 2020) with slope correlation rho and geometric "
      "glint anti-aliasing (Chermain et al. 2021), V-cavity G2, F = 1; the GGAA kernel is given "
      "as the screen-space derivatives of h~ or h_perp (params dh_*); no sampler in the paper: "
      "samples the smooth correlated Beckmann NDF (slope space, Walter-style) and returns its pdf";
  static constexpr std::string_view kSource =
      "Chermain et al. 2021 Eq. 1-6 (2020 patch-SDF), Eq. 9-15, 19-21 (GGAA), Eq. 16-18 (rho); "
      "Heitz 2014 Sec. 3.1 (V-cavity)";
  static constexpr unsigned kNeeds = kNeedsFootprint;

  static constexpr std::array<std::string_view, 3> kKernelNames = {"off", "half_slope",
                                                                   "projected_half"};
  static constexpr std::array<ParamSpec, 11> kParams = {{
      {"alpha_x", 0.5, 0.0, 2.0, true, false,
       "Beckmann roughness along x; slope std sigma_x = alpha_x/sqrt(2) (Eq. 16)"},
      {"alpha_y", 0.5, 0.0, 2.0, true, false,
       "Beckmann roughness along y (sigma_y = alpha_y/sqrt(2))"},
      {"rho", 0.0, -1.0, 1.0, true, true, "slope correlation factor (Eq. 16, 18)"},
      {"density", 3.269017e6, 1.0, 1e24, false, false,
       "microfacets per unit uv area (default e^15, Fig. 10 top)"},
      {"ggaa", 2.0, 0.0, 2.0, false, false,
       "GGAA kernel: off, half_slope (Eq. 20), projected_half (Eq. 21, the paper's default)",
       kKernelNames},
      {"s_k", 0.5, 0.0, 4.0, true, false, "kernel scale s_K (Eq. 19)"},
      {"dh_dx_x", 0.0, -100.0, 100.0, false, false,
       "x component of d/dx (pixel) of h~ (half_slope) or h_perp (projected_half)"},
      {"dh_dx_y", 0.0, -100.0, 100.0, false, false, "y component of the d/dx derivative"},
      {"dh_dy_x", 0.0, -100.0, 100.0, false, false, "x component of the d/dy derivative"},
      {"dh_dy_y", 0.0, -100.0, 100.0, false, false, "y component of the d/dy derivative"},
      {"seed", 0.0, 0.0, 1e9, false, false, "seed of the per-cell draws (integer)", {}, true},
  }};
  static constexpr std::array<std::string_view, 8> kIntermediates = {
      "P22", "lod", "dict_level", "kernel_width", "mip_lambda", "D", "G2", "brdf"};

  template <class T>
  struct Params {
    SdfParams sdf;
    SlopeDerivatives d;  // of h~ or h_perp as the `ggaa` choice reads them
  };

  template <class T>
  static Params<T> params(std::span<const double> v) {
    const double sqrt_half = 0.70710678118654752440;
    Params<T> p{};
    using M = Chermain;
    p.sdf = {&default_chermain_dictionary(),
             v[param_index<M>("alpha_x")] * sqrt_half,
             v[param_index<M>("alpha_y")] * sqrt_half,
             v[param_index<M>("rho")],
             std::log2(v[param_index<M>("density")]),
             static_cast<int>(v[param_index<M>("ggaa")]),
             v[param_index<M>("s_k")],
             static_cast<std::uint64_t>(v[param_index<M>("seed")])};
    p.d = {v[param_index<M>("dh_dx_x")], v[param_index<M>("dh_dx_y")], v[param_index<M>("dh_dy_x")],
           v[param_index<M>("dh_dy_y")]};
    return p;
  }

  // The smooth correlated Beckmann NDF of covariance Σ in slope space, D = P22/cos⁴θ.
  template <class T>
  static GLINTLAB_FN T smooth_d(const SdfParams& p, Vec3<T> h) {
    const Mask<T> up = h.z > T(0);
    const T hz = select(up, h.z, T(1));
    const T z2 = h.z * h.z;
    const T g = gaussian_sdf(-h.x / hz, -h.y / hz, p.sigma_x, p.sigma_y, p.with_rho ? p.rho : 0.0) /
                (z2 * z2);
    return select(up, g, T(0));
  }

  template <class T>
  static GLINTLAB_FN T pdf(const Params<T>& p, const ModelQuery<T>& q) {
    const Mask<T> ok = q.wi.z > T(0) && q.wo.z > T(0);
    const Vec3<T> h = half_vector(q.wi, q.wo);
    return select(ok, smooth_d(p.sdf, h) * h.z * reflection_jacobian(q.wo, h), T(0));
  }

  template <class T>
  static GLINTLAB_FN ModelEval<T, kIntermediates.size()> eval(const Params<T>& p,
                                                              const ModelQuery<T>& q) {
    ModelEval<T, kIntermediates.size()> r{};
    const Vec3<T> h = half_vector(q.wi, q.wo);
    const Mask<T> ok = q.wi.z > T(0) && q.wo.z > T(0) && h.z > T(0);
    SdfInfoT<T> info;
    T P22 = T(0), D = T(0), G2 = T(0), f = T(0);
    if (any_lane<T>(ok)) {
      const T hz = select(ok, h.z, T(1));
      const SlopeDerivativesT<T> d{T(p.d.dx_x), T(p.d.dx_y), T(p.d.dy_x), T(p.d.dy_y)};
      P22 =
          select(ok, patch_sdf(p.sdf, Vec2<T>{-h.x / hz, -h.y / hz}, q.footprint, d, &info), T(0));
      info.lod = select(ok, info.lod, T(0));
      info.dict_level = select(ok, info.dict_level, T(0));
      info.mip_lambda = select(ok, info.mip_lambda, T(0));
      info.kernel_width = select(ok, info.kernel_width, T(0));
      const T z2 = h.z * h.z;
      D = select(ok, P22 / (z2 * z2), T(0));  // Eq. 2 / Eq. 8
      G2 = select(ok, v_cavity_g2(q.wi, q.wo, h), T(0));
      const T den = T(4) * q.wi.z * q.wo.z;
      f = select(ok, D * G2 / select(ok, den, T(1)), T(0));  // Eq. 1, F = 1
    }
    r.value = f * std_max(q.wo.z, T(0));
    r.pdf = pdf(p, q);
    r.intermediates = {P22, info.lod, info.dict_level, info.kernel_width, info.mip_lambda, D,
                       G2,  f};
    return r;
  }

  // Slope m̃ = L z, L the Cholesky factor of Σ and z a Box–Muller normal pair; ω_o = reflect(ω_i,
  // h) with h ∝ (−m̃_x, −m̃_y, 1); pdf = D h_z / (4 |ω_o·h|) (Walter et al. 2007 Eq. 14, 24).
  template <class T>
  static GLINTLAB_FN ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    const T tiny = T(sizeof(Scalar<T>) > 4 ? 1e-300 : 1e-37);  // keeps log finite at u = 1
    const T r = sqrt(T(-2) * log(std_max(T(1) - u.x, tiny)));
    const T phi = T(2 * kPi<double>) * u.y;
    T sp, cp;
    sincos(phi, &sp, &cp);
    const T z0 = r * cp, z1 = r * sp;
    const double rho = p.sdf.with_rho ? p.sdf.rho : 0.0;
    const T mx = T(p.sdf.sigma_x) * z0;
    const T my = T(p.sdf.sigma_y) * (T(rho) * z0 + T(std::sqrt(1 - rho * rho)) * z1);
    const Vec3<T> h = normalize(Vec3<T>{-mx, -my, T(1)});
    ModelSample<T> s{};
    s.wo = reflect(q.wi, h);
    s.rejected = !(s.wo.z > T(0) && q.wi.z > T(0));
    s.pdf = T(0);
    s.weight = T(0);
    if (!any_lane<T>(!s.rejected)) return s;
    ModelQuery<T> qq = q;
    qq.wo = s.wo;
    const ModelEval<T, kIntermediates.size()> e = eval(p, qq);  // its pdf is pdf(p, qq)
    const T pdf_o = e.pdf;
    const T v = e.value;
    const Mask<T> pos = pdf_o > T(0);
    s.pdf = select(s.rejected, T(0), pdf_o);
    s.weight = select(s.rejected || !pos, T(0), v / select(pos, pdf_o, T(1)));
    return s;
  }
};

static_assert(Model<Chermain>);

}  // namespace glintlab::chermain2021

namespace glintlab {
// Registered models are named in namespace glintlab, like every other model (core/model_list.h).
using chermain2021::Chermain;
}  // namespace glintlab

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
// each marginal is read with textureGrad (ChermainDictionary::lookup_grad), the derivatives s_K
// R(−θ) M⁻¹ dh/dx, s_K R(−θ) M⁻¹ dh/dy, dh the screen-space derivative of the half slope h̃ (Eq. 20)
// or of the projected half vector h⊥ = (x_h, y_h) (Eq. 21, the default). The smooth fallback is not
// filtered (its lobe is far wider than any kernel GGAA is meant for). Scalar kernels only: the
// tables are gathered per cell, which has no Wide<> path yet.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string_view>

#include "core/glints/chermain_dictionary.h"
#include "core/math/ops.h"
#include "core/math/rng.h"
#include "core/model.h"
#include "core/ndf/microfacet.h"

namespace glintlab {

// Which screen-space derivative sets the GGAA kernel (2021 Sec. 6.1).
enum ChermainKernel { kChermainNoGgaa = 0, kChermainHalfSlope = 1, kChermainProjectedHalf = 2 };

// The 2×2 matrix M of 2021 Eq. 18, stored with its inverse and determinant:
// M = (1/σ_o) [[σ_x √(1−ρ²), ρ σ_x], [0, σ_y]], so that M Σ_o Mᵀ = Σ (Eq. 16, 17).
// `with_rho = false` gives the 2020 form diag(σ_x, σ_y)/σ_o (ρ ignored), the control of
// chermain.correlation.
struct ChermainMatrix {
  double m00, m01, m10, m11;
  double i00, i01, i10, i11;
  double det;
};

inline ChermainMatrix chermain_matrix(double sigma_x, double sigma_y, double rho, double sigma_o,
                                      bool with_rho = true) {
  const double r = with_rho ? rho : 0.0;
  const double c = std::sqrt(1 - r * r);
  ChermainMatrix M{};
  M.m00 = sigma_x * c / sigma_o, M.m01 = r * sigma_x / sigma_o;
  M.m10 = 0, M.m11 = sigma_y / sigma_o;
  M.det = M.m00 * M.m11;
  M.i00 = M.m11 / M.det, M.i01 = -M.m01 / M.det;
  M.i10 = 0, M.i11 = M.m00 / M.det;
  return M;
}

struct ChermainSdfParams {
  const ChermainDictionary* dictionary;
  double sigma_x, sigma_y, rho;  // Σ of Eq. 16 (slope standard deviations and correlation)
  double log2_density;           // log2 of microfacets per unit uv area
  int kernel;                    // ChermainKernel
  double s_k;                    // kernel scale s_K (Eq. 19)
  std::uint64_t seed;            // of the per-cell draws
  bool with_rho = true;          // false: the 2020 matrix (control)
  TableWrap wrap = TableWrap::kMirroredRepeat;
};

// What one patch-SDF evaluation used (the model's intermediates).
struct ChermainSdfInfo {
  double lod = 0;           // l_P
  double dict_level = 0;    // k at LOD ⌊l_P⌋ (= L for the smooth fallback)
  double mip_lambda = 0;    // weighted mean textureGrad level of detail over the lookups
  double kernel_width = 0;  // s_K max(‖dh/dx‖, ‖dh/dy‖): the kernel extent in h̃ space
};

// One cell's draws: rotation and the two marginals (2020: "randomly picked", 2021 Sec. 3).
struct ChermainCell {
  double cos_t, sin_t;
  int nx, ny;
};

inline ChermainCell chermain_cell(std::uint64_t seed, std::int64_t ci, std::int64_t cj, int n) {
  const std::uint64_t key = mix64(std::uint64_t(ci) * 0x9e3779b97f4a7c15ULL) ^ std::uint64_t(cj);
  const double theta = 2 * kPi<double> * counter_uniform<double>(seed, key, 0);
  const int nx = int(counter_uniform<double>(seed, key, 1) * n);
  const int ny = int(counter_uniform<double>(seed, key, 2) * n);
  return {std::cos(theta), std::sin(theta), std::min(nx, n - 1), std::min(ny, n - 1)};
}

// Dictionary level of a cell at LOD l: it holds density·4^l microfacets, about 4^k lobes in the
// product of two level-k marginals, so k = ⌊l + ½ log2 density⌋, at least 0.
inline int chermain_dictionary_level(int l, double log2_density) {
  return std::max(0, int(std::floor(l + 0.5 * log2_density)));
}

// The smooth limit: the centred Gaussian slope density of covariance Σ (Eq. 16), the Beckmann
// SDF with correlation.
inline double chermain_gaussian_sdf(double x, double y, double sx, double sy, double rho) {
  const double c = 1 - rho * rho;
  const double a = x / sx, b = y / sy;
  const double q = (a * a - 2 * rho * a * b + b * b) / c;
  return std::exp(-0.5 * q) / (2 * kPi<double> * sx * sy * std::sqrt(c));
}

// Screen-space derivatives of the quantity Eq. 20 (h̃) or Eq. 21 (h⊥) filters with, from the half
// vector h (local frame, h_z > 0) and its derivatives dh/dx, dh/dy (core/scene/footprint.h).
struct SlopeDerivatives {
  double dx_x, dx_y, dy_x, dy_y;  // d(·)/dx and d(·)/dy, components x and y
};

inline SlopeDerivatives chermain_slope_derivatives(Vec3<double> h, Vec3<double> dh_dx,
                                                   Vec3<double> dh_dy, int kernel) {
  if (kernel == kChermainProjectedHalf) return {dh_dx.x, dh_dx.y, dh_dy.x, dh_dy.y};
  if (kernel == kChermainNoGgaa) return {0, 0, 0, 0};
  // h̃ = (−x/z, −y/z): dh̃ = −(dx z − x dz)/z², likewise for y.
  const double z2 = h.z * h.z;
  const auto d = [&](Vec3<double> dv, double c, double dc) { return -(dc * h.z - c * dv.z) / z2; };
  return {d(dh_dx, h.x, dh_dx.x), d(dh_dx, h.y, dh_dx.y), d(dh_dy, h.x, dh_dy.x),
          d(dh_dy, h.y, dh_dy.y)};
}

// The footprint's continuous LOD l_P = log2 max(‖∂uv/∂x‖, ‖∂uv/∂y‖), clamped to [−20, 39].
inline double chermain_lod(const FootprintQuery<double>& fp) {
  const double foot = std::sqrt(std::max(dot(fp.duv_dx, fp.duv_dx), dot(fp.duv_dy, fp.duv_dy)));
  return std::clamp(foot > 0 ? std::log2(foot) : -20.0, -20.0, 39.0);
}

// Visits the terms of Eq. 3 / Eq. 10: visit(weight, k, cell) for each of the (up to) two LODs and
// four cells with w(l) W_P(l, s_0) > 0; weight sums to 1. k ≥ L marks the smooth fallback (one
// visit per LOD, cell unused).
template <class Visit>
void chermain_for_each_cell(const ChermainSdfParams& p, const FootprintQuery<double>& fp,
                            Visit&& visit) {
  const ChermainDictionary& dict = *p.dictionary;
  const double lod = chermain_lod(fp);
  const int l0 = int(std::floor(lod));
  const double frac = lod - l0;
  for (int li = 0; li < 2; ++li) {
    const int l = l0 + li;
    const double wl = li == 0 ? 1 - frac : frac;
    if (wl == 0) continue;
    const int k = chermain_dictionary_level(l, p.log2_density);
    if (k >= dict.levels()) {  // past the last level: the smooth Beckmann SDF
      visit(wl, k, ChermainCell{1, 0, 0, 0});
      continue;
    }
    const double cell = std::ldexp(1.0, l);
    const double su = fp.uv.x / cell - 0.5, sv = fp.uv.y / cell - 0.5;
    const double fu = std::floor(su), fv = std::floor(sv);
    const double tu = su - fu, tv = sv - fv;
    for (int c = 0; c < 4; ++c) {
      const int di = c & 1, dj = c >> 1;
      const double W = (di ? tu : 1 - tu) * (dj ? tv : 1 - tv);
      if (W == 0) continue;
      // The cell's corner in units of 2^-20 (exact in double for the clamped LOD range).
      const auto ci = std::int64_t(std::ldexp(fu + di, l + 20));
      const auto cj = std::int64_t(std::ldexp(fv + dj, l + 20));
      visit(wl * W, k, chermain_cell(p.seed, ci, cj, dict.distributions()));
    }
  }
}

// The (filtered) procedural patch-SDF at slope m̃ (2021 Eq. 3 without GGAA, Eq. 10 and 19 with
// it), for the footprint `fp` and the slope derivatives `d` (ignored when kernel = 0).
inline double chermain_patch_sdf(const ChermainSdfParams& p, Vec2<double> m,
                                 const FootprintQuery<double>& fp, const SlopeDerivatives& d,
                                 ChermainSdfInfo* info = nullptr) {
  const ChermainDictionary& dict = *p.dictionary;
  const ChermainMatrix M = chermain_matrix(p.sigma_x, p.sigma_y, p.rho, dict.sigma_o(), p.with_rho);
  const double rho_used = p.with_rho ? p.rho : 0.0;
  const bool ggaa = p.kernel != kChermainNoGgaa;
  const double sk = ggaa ? p.s_k : 0.0;
  // M⁻¹ applied once per pixel (Eq. 20/21); the per-cell rotation below.
  const double ax = sk * (M.i00 * d.dx_x + M.i01 * d.dx_y), ay = sk * (M.i11 * d.dx_y);
  const double bx = sk * (M.i00 * d.dy_x + M.i01 * d.dy_y), by = sk * (M.i11 * d.dy_y);
  const double mx = M.i00 * m.x + M.i01 * m.y, my = M.i11 * m.y;  // M⁻¹ m̃
  double total = 0, lambda_sum = 0, lambda_weight = 0;
  chermain_for_each_cell(p, fp, [&](double w, int k, const ChermainCell& s) {
    if (k >= dict.levels()) {
      total += w * chermain_gaussian_sdf(m.x, m.y, p.sigma_x, p.sigma_y, rho_used);
      return;
    }
    // R(−θ) applied to M⁻¹ m̃ and to the derivatives.
    const double xo = s.cos_t * mx + s.sin_t * my, yo = -s.sin_t * mx + s.cos_t * my;
    double px, py;
    if (ggaa) {
      TableFilter fx, fy;
      px = dict.lookup_grad(s.nx, k, xo, s.cos_t * ax + s.sin_t * ay, s.cos_t * bx + s.sin_t * by,
                            p.wrap, 16, &fx);
      py = dict.lookup_grad(s.ny, k, yo, -s.sin_t * ax + s.cos_t * ay, -s.sin_t * bx + s.cos_t * by,
                            p.wrap, 16, &fy);
      lambda_sum += w * 0.5 * (fx.lambda + fy.lambda);
      lambda_weight += w;
    } else {
      px = dict.lookup_lod(s.nx, k, xo, 0, p.wrap);
      py = dict.lookup_lod(s.ny, k, yo, 0, p.wrap);
    }
    total += w * px * py / M.det;
  });
  if (info) {
    const double lod = chermain_lod(fp);
    info->lod = lod;
    info->dict_level =
        std::min(chermain_dictionary_level(int(std::floor(lod)), p.log2_density), dict.levels());
    info->mip_lambda = lambda_weight > 0 ? lambda_sum / lambda_weight : 0.0;
    info->kernel_width = sk * std::sqrt(std::max(d.dx_x * d.dx_x + d.dx_y * d.dx_y,
                                                 d.dy_x * d.dy_x + d.dy_y * d.dy_y));
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

inline SlopeMoments2 chermain_patch_moments(const ChermainSdfParams& p,
                                            const FootprintQuery<double>& fp,
                                            const SlopeDerivatives& d, int grid) {
  const double so = p.dictionary->sigma_o();
  const ChermainMatrix M = chermain_matrix(p.sigma_x, p.sigma_y, p.rho, so, p.with_rho);
  const double R =
      4 * std::sqrt(2.0) * so * std::sqrt(M.m00 * M.m00 + M.m01 * M.m01 + M.m11 * M.m11);
  const double h = 2 * R / grid;
  double s0 = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  for (int j = 0; j < grid; ++j) {
    const double y = -R + (j + 0.5) * h;
    for (int i = 0; i < grid; ++i) {
      const double x = -R + (i + 0.5) * h;
      const double v = chermain_patch_sdf(p, {x, y}, fp, d);
      s0 += v, sx += v * x, sy += v * y, sxx += v * x * x, syy += v * y * y, sxy += v * x * y;
    }
  }
  const double mx = sx / s0, my = sy / s0;
  return {s0 * h * h, mx, my, sxx / s0 - mx * mx, syy / s0 - my * my, sxy / s0 - mx * my};
}

// V-cavity masking-shadowing G2 = min(1, 2(n·h)(n·ωi)/(ωi·h), 2(n·h)(n·ωo)/(ωo·h)) (Heitz 2014
// Sec. 3.1, the only masking the 2020 BRDF supports; 2021 Sec. 7).
inline double v_cavity_g2(Vec3<double> wi, Vec3<double> wo, Vec3<double> h) {
  const double a = dot(wi, h), b = dot(wo, h);
  if (!(a > 0 && b > 0 && h.z > 0)) return 0;
  return std::min({1.0, 2 * h.z * wi.z / a, 2 * h.z * wo.z / b});
}

// The registered model: the BRDF of 2021 Eq. 1 with D from the patch-SDF (Eq. 2 or Eq. 8), F = 1.
struct Chermain {
  // The patch-SDF and its dictionary are double-only (host tables); no float instantiation.
  static constexpr bool kDoubleOnly = true;
  static constexpr std::string_view kName = "chermain";
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
      {"seed", 0.0, 0.0, 1e9, false, false, "seed of the per-cell draws (integer part)"},
  }};
  static constexpr std::array<std::string_view, 8> kIntermediates = {
      "P22", "lod", "dict_level", "kernel_width", "mip_lambda", "D", "G2", "brdf"};

  template <class T>
  struct Params {
    ChermainSdfParams sdf;
    SlopeDerivatives d;  // of h~ or h_perp as the `ggaa` choice reads them
  };

  template <class T>
  static Params<T> params(std::span<const double> v) {
    const double sqrt_half = 0.70710678118654752440;
    Params<T> p{};
    p.sdf = {&default_chermain_dictionary(),
             v[0] * sqrt_half,
             v[1] * sqrt_half,
             v[2],
             std::log2(v[3]),
             static_cast<int>(v[4]),
             v[5],
             static_cast<std::uint64_t>(v[10])};
    p.d = {v[6], v[7], v[8], v[9]};
    return p;
  }

  // The smooth correlated Beckmann NDF of covariance Σ in slope space, D = P22/cos⁴θ.
  static double smooth_d(const ChermainSdfParams& p, Vec3<double> h) {
    if (!(h.z > 0)) return 0;
    const double z2 = h.z * h.z;
    return chermain_gaussian_sdf(-h.x / h.z, -h.y / h.z, p.sigma_x, p.sigma_y,
                                 p.with_rho ? p.rho : 0.0) /
           (z2 * z2);
  }

  template <class T>
  static T pdf(const Params<T>& p, const ModelQuery<T>& q) {
    if (!(q.wi.z > 0 && q.wo.z > 0)) return T(0);
    const Vec3<double> h = half_vector(q.wi, q.wo);
    return T(smooth_d(p.sdf, h) * h.z * reflection_jacobian(q.wo, h));
  }

  template <class T>
  static ModelEval<T, kIntermediates.size()> eval(const Params<T>& p, const ModelQuery<T>& q) {
    ModelEval<T, kIntermediates.size()> r{};
    const Vec3<double> h = half_vector(q.wi, q.wo);
    ChermainSdfInfo info;
    double P22 = 0, D = 0, G2 = 0, f = 0;
    if (q.wi.z > 0 && q.wo.z > 0 && h.z > 0) {
      P22 = chermain_patch_sdf(p.sdf, {-h.x / h.z, -h.y / h.z}, q.footprint, p.d, &info);
      const double z2 = h.z * h.z;
      D = P22 / (z2 * z2);  // Eq. 2 / Eq. 8
      G2 = v_cavity_g2(q.wi, q.wo, h);
      f = D * G2 / (4 * q.wi.z * q.wo.z);  // Eq. 1, F = 1
    }
    r.value = T(f * std::max(q.wo.z, 0.0));
    r.pdf = pdf(p, q);
    r.intermediates = {
        T(P22), T(info.lod), T(info.dict_level), T(info.kernel_width), T(info.mip_lambda), T(D),
        T(G2),  T(f)};
    return r;
  }

  // Slope m̃ = L z, L the Cholesky factor of Σ and z a Box–Muller normal pair; ω_o = reflect(ω_i,
  // h) with h ∝ (−m̃_x, −m̃_y, 1); pdf = D h_z / (4 |ω_o·h|) (Walter et al. 2007 Eq. 14, 24).
  template <class T>
  static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    const double r = std::sqrt(-2 * std::log(std::max(1.0 - double(u.x), 1e-300)));
    const double phi = 2 * kPi<double> * double(u.y);
    const double z0 = r * std::cos(phi), z1 = r * std::sin(phi);
    const double rho = p.sdf.with_rho ? p.sdf.rho : 0.0;
    const double mx = p.sdf.sigma_x * z0;
    const double my = p.sdf.sigma_y * (rho * z0 + std::sqrt(1 - rho * rho) * z1);
    const Vec3<double> h = normalize(Vec3<double>{-mx, -my, 1.0});
    const Vec3<double> wo = reflect(Vec3<double>{q.wi.x, q.wi.y, q.wi.z}, h);
    ModelSample<T> s{};
    s.wo = {T(wo.x), T(wo.y), T(wo.z)};
    s.rejected = !(wo.z > 0 && q.wi.z > 0);
    if (s.rejected) return s;
    ModelQuery<T> qq = q;
    qq.wo = s.wo;
    s.pdf = pdf(p, qq);
    const double v = double(eval(p, qq).value);
    s.weight = s.pdf > 0 ? T(v / double(s.pdf)) : T(0);
    return s;
  }
};

static_assert(Model<Chermain>);

}  // namespace glintlab

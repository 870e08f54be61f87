// The host code of the Chermain model as it was before its kernels became generic over the float
// type (commit 170b3c6, core/glints/chermain.h and chermain_dictionary.cpp), frozen as the oracle
// of tests/core/glints/chermain_scalar_identity_test.cpp: the scalar double instantiation of the
// new kernels must reproduce it bit for bit. Test-only; not a second implementation to maintain.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/glints/chermain.h"

namespace glintlab::test::chermain_host {

struct HostInfo {
  double lod = 0, dict_level = 0, mip_lambda = 0, kernel_width = 0;
};

inline double host_fetch(const chermain2021::Dictionary& d, int n, int k, int mip, long i,
                         chermain2021::TableWrap wrap) {
  const long size = long(d.resolution() >> mip);
  if (wrap == chermain2021::TableWrap::kClampToEdge) {
    i = std::clamp(i, 0L, size - 1);
  } else {  // mirrored repeat: period 2·size, the second half reversed
    i = ((i % (2 * size)) + 2 * size) % (2 * size);
    if (i >= size) i = 2 * size - 1 - i;
  }
  return double(d.texel(n, k, mip, int(i)));
}

inline double host_trilinear(const chermain2021::Dictionary& d, int n, int k, double u,
                             double lambda, chermain2021::TableWrap wrap);
inline double host_lookup_lod(
    const chermain2021::Dictionary& d, int n, int k, double x, double mip = 0,
    chermain2021::TableWrap wrap = chermain2021::TableWrap::kMirroredRepeat) {
  if (!(std::abs(x) < d.extent())) return 0;
  return host_trilinear(d, n, k, x / d.extent(), mip, wrap);
}

inline double host_trilinear(const chermain2021::Dictionary& d, int n, int k, double u,
                             double lambda, chermain2021::TableWrap wrap) {
  const double l = std::clamp(lambda, 0.0, double(d.mip_levels() - 1));
  const int m0 = int(std::floor(l));
  const int m1 = std::min(m0 + 1, d.mip_levels() - 1);
  const auto linear = [&](int m) {
    const double s = u * double(d.resolution() >> m) - 0.5;
    const double f = std::floor(s);
    const double t = s - f;
    const long i = long(f);
    return (1 - t) * host_fetch(d, n, k, m, i, wrap) + t * host_fetch(d, n, k, m, i + 1, wrap);
  };
  const double a = linear(m0);
  if (m1 == m0) return a;
  return a + (l - m0) * (linear(m1) - a);
}

inline double host_lookup_grad(
    const chermain2021::Dictionary& d, int n, int k, double x, double dx_dpx, double dx_dpy,
    chermain2021::TableWrap wrap = chermain2021::TableWrap::kMirroredRepeat,
    int max_anisotropy = 16, chermain2021::TableFilter* filter = nullptr) {
  const double scale = double(d.resolution()) / d.extent();  // texels per slope unit
  const double px = std::abs(dx_dpx) * scale, py = std::abs(dx_dpy) * scale;
  const double pmax = std::max(px, py), pmin = std::min(px, py);
  const double major = px >= py ? dx_dpx : dx_dpy;  // slope units per pixel
  int probes = 1;
  if (pmin > 0) {
    probes = int(std::min(std::ceil(pmax / pmin), double(max_anisotropy)));
  } else if (pmax > 0) {
    probes = max_anisotropy;
  }
  probes = std::max(probes, 1);
  const double lambda = pmax > 0 ? std::max(0.0, std::log2(pmax / probes)) : 0.0;
  if (filter) *filter = {std::min(lambda, double(d.mip_levels() - 1)), probes};
  if (!(std::abs(x) < d.extent())) return 0;
  double sum = 0;
  for (int i = 0; i < probes; ++i) {
    const double xi = x + ((i + 0.5) / probes - 0.5) * major;
    sum += host_trilinear(d, n, k, xi / d.extent(), lambda, wrap);
  }
  return sum / probes;
}

struct HostCell {
  double cos_t, sin_t;
  int nx, ny;
};

inline HostCell host_cell(std::uint64_t seed, std::int64_t ci, std::int64_t cj, int n) {
  const std::uint64_t key = mix64(std::uint64_t(ci) * 0x9e3779b97f4a7c15ULL) ^ std::uint64_t(cj);
  const double theta = 2 * kPi<double> * counter_uniform<double>(seed, key, 0);
  const int nx = int(counter_uniform<double>(seed, key, 1) * n);
  const int ny = int(counter_uniform<double>(seed, key, 2) * n);
  return {std::cos(theta), std::sin(theta), std::min(nx, n - 1), std::min(ny, n - 1)};
}

// Dictionary level of a cell at LOD l: it holds density·4^l microfacets, about 4^k lobes in the
// product of two level-k marginals, so k = ⌊l + ½ log2 density⌋, at least 0.
inline int host_dictionary_level(int l, double log2_density) {
  return std::max(0, int(std::floor(l + 0.5 * log2_density)));
}

// The smooth limit: the centred Gaussian slope density of covariance Σ (Eq. 16), the Beckmann
// SDF with correlation.
inline double host_gaussian_sdf(double x, double y, double sx, double sy, double rho) {
  const double c = 1 - rho * rho;
  const double a = x / sx, b = y / sy;
  const double q = (a * a - 2 * rho * a * b + b * b) / c;
  return std::exp(-0.5 * q) / (2 * kPi<double> * sx * sy * std::sqrt(c));
}

// The footprint's continuous LOD l_P = log2 max(‖∂uv/∂x‖, ‖∂uv/∂y‖), clamped to [−20, 39].
inline double host_lod(const FootprintQuery<double>& fp) {
  const double foot = std::sqrt(std::max(dot(fp.duv_dx, fp.duv_dx), dot(fp.duv_dy, fp.duv_dy)));
  return std::clamp(foot > 0 ? std::log2(foot) : -20.0, -20.0, 39.0);
}

// Visits the terms of Eq. 3 / Eq. 10: visit(weight, k, cell) for each of the (up to) two LODs and
// four cells with w(l) W_P(l, s_0) > 0; weight sums to 1. k ≥ L marks the smooth fallback (one
// visit per LOD, cell unused).
template <class Visit>
void host_for_each_cell(const chermain2021::SdfParams& p, const FootprintQuery<double>& fp,
                        Visit&& visit) {
  const chermain2021::Dictionary& dict = *p.dictionary;
  const double lod = host_lod(fp);
  const int l0 = int(std::floor(lod));
  const double frac = lod - l0;
  for (int li = 0; li < 2; ++li) {
    const int l = l0 + li;
    const double wl = li == 0 ? 1 - frac : frac;
    if (wl == 0) continue;
    const int k = host_dictionary_level(l, p.log2_density);
    if (k >= dict.levels()) {  // past the last level: the smooth Beckmann SDF
      visit(wl, k, HostCell{1, 0, 0, 0});
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
      visit(wl * W, k, host_cell(p.seed, ci, cj, dict.distributions()));
    }
  }
}

// The (filtered) procedural patch-SDF at slope m̃ (2021 Eq. 3 without GGAA, Eq. 10 and 19 with
// it), for the footprint `fp` and the slope derivatives `d` (ignored when kernel = 0).
inline double host_patch_sdf(const chermain2021::SdfParams& p, Vec2<double> m,
                             const FootprintQuery<double>& fp,
                             const chermain2021::SlopeDerivatives& d, HostInfo* info = nullptr) {
  const chermain2021::Dictionary& dict = *p.dictionary;
  const chermain2021::Matrix M =
      chermain2021::matrix(p.sigma_x, p.sigma_y, p.rho, dict.sigma_o(), p.with_rho);
  const double rho_used = p.with_rho ? p.rho : 0.0;
  const bool ggaa = p.kernel != chermain2021::kNoGgaa;
  const double sk = ggaa ? p.s_k : 0.0;
  // M⁻¹ applied once per pixel (Eq. 20/21); the per-cell rotation below.
  const double ax = sk * (M.i00 * d.dx_x + M.i01 * d.dx_y), ay = sk * (M.i11 * d.dx_y);
  const double bx = sk * (M.i00 * d.dy_x + M.i01 * d.dy_y), by = sk * (M.i11 * d.dy_y);
  const double mx = M.i00 * m.x + M.i01 * m.y, my = M.i11 * m.y;  // M⁻¹ m̃
  double total = 0, lambda_sum = 0, lambda_weight = 0;
  host_for_each_cell(p, fp, [&](double w, int k, const HostCell& s) {
    if (k >= dict.levels()) {
      total += w * host_gaussian_sdf(m.x, m.y, p.sigma_x, p.sigma_y, rho_used);
      return;
    }
    // R(−θ) applied to M⁻¹ m̃ and to the derivatives.
    const double xo = s.cos_t * mx + s.sin_t * my, yo = -s.sin_t * mx + s.cos_t * my;
    double px, py;
    if (ggaa) {
      chermain2021::TableFilter fx, fy;
      px = host_lookup_grad(dict, s.nx, k, xo, s.cos_t * ax + s.sin_t * ay,
                            s.cos_t * bx + s.sin_t * by, p.wrap, 16, &fx);
      py = host_lookup_grad(dict, s.ny, k, yo, -s.sin_t * ax + s.cos_t * ay,
                            -s.sin_t * bx + s.cos_t * by, p.wrap, 16, &fy);
      lambda_sum += w * 0.5 * (fx.lambda + fy.lambda);
      lambda_weight += w;
    } else {
      px = host_lookup_lod(dict, s.nx, k, xo, 0, p.wrap);
      py = host_lookup_lod(dict, s.ny, k, yo, 0, p.wrap);
    }
    total += w * px * py / M.det;
  });
  if (info) {
    const double lod = host_lod(fp);
    info->lod = lod;
    info->dict_level =
        std::min(host_dictionary_level(int(std::floor(lod)), p.log2_density), dict.levels());
    info->mip_lambda = lambda_weight > 0 ? lambda_sum / lambda_weight : 0.0;
    info->kernel_width = sk * std::sqrt(std::max(d.dx_x * d.dx_x + d.dx_y * d.dx_y,
                                                 d.dy_x * d.dy_x + d.dy_y * d.dy_y));
  }
  return total;
}

inline double host_v_cavity_g2(Vec3<double> wi, Vec3<double> wo, Vec3<double> h) {
  const double a = dot(wi, h), b = dot(wo, h);
  if (!(a > 0 && b > 0 && h.z > 0)) return 0;
  return std::min({1.0, 2 * h.z * wi.z / a, 2 * h.z * wo.z / b});
}

// The smooth correlated Beckmann NDF of covariance Σ in slope space, D = P22/cos⁴θ.
inline double host_smooth_d(const chermain2021::SdfParams& p, Vec3<double> h) {
  if (!(h.z > 0)) return 0;
  const double z2 = h.z * h.z;
  return host_gaussian_sdf(-h.x / h.z, -h.y / h.z, p.sigma_x, p.sigma_y, p.with_rho ? p.rho : 0.0) /
         (z2 * z2);
}

template <class T>
T host_pdf(const Chermain::Params<T>& p, const ModelQuery<T>& q) {
  if (!(q.wi.z > 0 && q.wo.z > 0)) return T(0);
  const Vec3<double> h = half_vector(q.wi, q.wo);
  return T(host_smooth_d(p.sdf, h) * h.z * reflection_jacobian(q.wo, h));
}

template <class T>
ModelEval<T, 8> host_eval(const Chermain::Params<T>& p, const ModelQuery<T>& q) {
  ModelEval<T, 8> r{};
  const Vec3<double> h = half_vector(q.wi, q.wo);
  HostInfo info;
  double P22 = 0, D = 0, G2 = 0, f = 0;
  if (q.wi.z > 0 && q.wo.z > 0 && h.z > 0) {
    P22 = host_patch_sdf(p.sdf, {-h.x / h.z, -h.y / h.z}, q.footprint, p.d, &info);
    const double z2 = h.z * h.z;
    D = P22 / (z2 * z2);  // Eq. 2 / Eq. 8
    G2 = host_v_cavity_g2(q.wi, q.wo, h);
    f = D * G2 / (4 * q.wi.z * q.wo.z);  // Eq. 1, F = 1
  }
  r.value = T(f * std::max(q.wo.z, 0.0));
  r.pdf = host_pdf(p, q);
  r.intermediates = {
      T(P22), T(info.lod), T(info.dict_level), T(info.kernel_width), T(info.mip_lambda), T(D),
      T(G2),  T(f)};
  return r;
}

// Slope m̃ = L z, L the Cholesky factor of Σ and z a Box–Muller normal pair; ω_o = reflect(ω_i,
// h) with h ∝ (−m̃_x, −m̃_y, 1); pdf = D h_z / (4 |ω_o·h|) (Walter et al. 2007 Eq. 14, 24).
template <class T>
ModelSample<T> host_sample(const Chermain::Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
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
  s.pdf = host_pdf(p, qq);
  const double v = double(host_eval(p, qq).value);
  s.weight = s.pdf > 0 ? T(v / double(s.pdf)) : T(0);
  return s;
}

}  // namespace glintlab::test::chermain_host

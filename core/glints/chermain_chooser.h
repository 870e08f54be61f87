// Which level of the Chermain family (model `chermain`: Chermain et al. 2020's procedural
// patch-SDF with 2021's slope correlation and GGAA, core/glints/chermain.h) a pixel needs: the
// cheapest of the smooth / LEAN fallback and the model with a dictionary of its first 4, 8, 12 or
// 16 levels, GGAA off or on, that no one could tell from the most complete one (all the
// dictionary's levels, GGAA as the shader's parameters say). The measured table (`glintlab
// adequacy`, verify/adequacy/chermain_adequacy.h) checks it; docs/adequacy.md "The Chermain
// chooser".
//
// What the construction says (2021 Eq. 3 with k = ⌊l + ½ log2 density⌋, chermain.h):
// - A dictionary of L levels is the whole dictionary, bit for bit, wherever every LOD with a
//   non-zero weight uses a level below L or past the whole dictionary's last (both the smooth
//   fallback there): its tables are the whole dictionary's prefix (chermain_dictionary.h). GGAA off
//   is GGAA on bit for bit where the kernel is empty (no screen-space derivative). No margin: these
//   are identities.
// - The smooth level (the Gaussian of covariance Σ, Eq. 16) is the whole model bit for bit where
//   both weighted LODs are past the last level, and adequate where the model's CV over surface
//   positions is small: that CV follows from the dictionary's construction in closed form
//   (chermain_smooth_prediction below), and the smooth level is taken where it and the smooth
//   level's mean difference are at most kChooserMargin · TAU, as the other choosers take their
//   levels. The mean difference is the lookup filter's: the dictionary's lobe mixture converges to
//   the Gaussian (the means drawn from N(0, σ_o² − s²)), but the texels and GGAA's kernel widen it,
//   which matters in the lobe's tail (the smooth fallback is not filtered).
// - GGAA off where the kernel filters: the same closed form without the kernel's widening of the
//   lobes, at the same LODs; GGAA off is taken where its mean and CV differences from GGAA on are
//   at most kChooserMargin · TAU (chermain_ggaa_off_adequate).
#pragma once

#include <array>
#include <cmath>
#include <string_view>

#include "core/glints/adequacy.h"
#include "core/glints/chermain.h"

namespace glintlab {

// The levels, cheapest first in the order of a GPU lane (texture memory first, then the filter).
// The values are stored as a float in the chooser's lanes.
enum class ChermainLevel : int {
  kSmooth = 0,
  kDict4,
  kDict4Ggaa,
  kDict8,
  kDict8Ggaa,
  kDict12,
  kDict12Ggaa,
  kDict16,
  kDict16Ggaa,
};
inline constexpr int kChermainLevels = 9;
inline constexpr std::array<std::string_view, kChermainLevels> kChermainLevelNames = {
    "smooth", "dict4",       "dict4_ggaa", "dict8",      "dict8_ggaa",
    "dict12", "dict12_ggaa", "dict16",     "dict16_ggaa"};
inline constexpr ChermainLevel kChermainMostComplete = ChermainLevel::kDict16Ggaa;
// The dictionary levels a counting level keeps (0 for the smooth level).
constexpr int chermain_dictionary_levels(ChermainLevel l) {
  return l == ChermainLevel::kSmooth ? 0 : 4 * ((int(l) + 1) / 2);
}
constexpr bool chermain_level_ggaa(ChermainLevel l) {
  return l != ChermainLevel::kSmooth && int(l) % 2 == 0;
}

// E[Σ W_0 W_1] over the fine and coarse cells that share their draws (a coarse cell shares its
// draws with its lower-left child, chermain.h), the bilinear weights over a position uniform on the
// coarse cell: 0.364583… per axis (a midpoint rule of 4096 nodes, as chermain_exact_moments
// computes it), squared for the two axes.
inline constexpr double kChermainSharedWeight = 0.13292100332263446;
// θ nodes of the rotation average on [0, π/2) (the marginals are even: a quarter turn suffices).
inline constexpr int kChermainChooserNodes = 16;

// The construction at one query: the footprint's LOD l_P, the dictionary level k of its two LODs
// (integer-valued), the coarser LOD's weight frac(l_P).
template <class T>
struct ChermainLods {
  T k_fine, k_coarse, w_coarse;
};
template <class T>
GLINTLAB_FN ChermainLods<T> chermain_lods(const chermain2021::SdfParams& p,
                                          const FootprintQuery<T>& fp) {
  const T lod = chermain2021::lod(fp);
  const T l0 = floor(lod);
  return {chermain2021::dictionary_level(l0, p.log2_density),
          chermain2021::dictionary_level(l0 + T(1), p.log2_density), lod - l0};
}

// The variance of one marginal over the dictionary's distributions and the mean, at slope x (in
// the dictionary's units), per lobe (Var ψ for one symmetrized lobe pair ψ = (φ_s(x − μ) +
// φ_s(x + μ))/2, μ ~ N(0, v), v = σ_o² − s²; a level of 2^k pairs has Var ψ / 2^k) and the mean
// ḡ = φ(x; σ_o):
//   E φ_s(x − μ)² = φ(x; √(v + s²/2)) / (2√π s),
//   E φ_s(x − μ) φ_s(x + μ) = exp(−x²/s²) / (2π s² √(1 + 2v/s²)).
// The lobe std s is widened by the lookup's filter as a Gaussian would be: the texels' mass and
// the linear interpolation (Δ²/4 at the MIP level's texel Δ) and GGAA's anisotropic probes along
// the major axis (a box: its length² / 12; chermain_lookup.h's textureGrad rule).
template <class T>
struct MarginalMoments {
  T mean, var;
};
template <class T>
GLINTLAB_FN MarginalMoments<T> chermain_marginal(T x, T widening2, double sigma_o, double lobe) {
  const T s2 = T(lobe * lobe) + widening2;
  const T v = T(sigma_o * sigma_o - lobe * lobe);
  const T x2 = x * x;
  const T var_mean = v + s2;
  const T var_sq = v + T(0.5) * s2;
  const T inv_2pi = T(0.15915494309189533577);
  const T mean = exp(T(-0.5) * x2 / var_mean) * sqrt(inv_2pi / var_mean);
  const T a = exp(T(-0.5) * x2 / var_sq) * sqrt(inv_2pi / var_sq) /
              (T(3.5449077018110320546) * sqrt(s2));  // 2√π s
  const T b = exp(-x2 / s2) * inv_2pi / (s2 * sqrt(T(1) + T(2) * v / s2));
  return {mean, max(T(0.5) * (a + b) - mean * mean, T(0))};
}

// The filter's variance added to a lobe (in slope units²) by a lookup with derivatives (dx, dy)
// per pixel: textureLod (dx = dy = 0) the MIP-0 texels, textureGrad the probes and the MIP level
// of chermain2021::lookup_grad.
template <class T>
GLINTLAB_FN T chermain_filter_widening(const chermain2021::Dictionary& dict, T dx, T dy) {
  const double texel = dict.extent() / dict.resolution();
  const T px = abs(dx) / T(texel), py = abs(dy) / T(texel);  // in texels
  const T pmax = max(px, py), pmin = min(px, py);
  const Mask<T> has_min = pmin > T(0), has_max = pmax > T(0);
  const T ratio = pmax / select(has_min, pmin, T(1));
  T probes = select(has_min, min(-floor(-ratio), T(16)), select(has_max, T(16), T(1)));
  probes = max(probes, T(1));
  const T lambda = min(
      select(has_max, max(T(0), chermain2021::log2(select(has_max, pmax, T(1)) / probes)), T(0)),
      T(dict.mip_levels() - 1));
  const T mip_texel = T(texel) * exp(lambda * T(0.69314718055994530942));
  return T(0.25) * mip_texel * mip_texel + sqr(pmax * T(texel)) / T(12);
}

// The mean and CV of the patch-SDF (2021 Eq. 3) over surface positions at slope m̃, by the
// construction: per cell X = P_o(R(−θ) M⁻¹ m̃)/det M (Eq. 4–6), θ uniform, the two marginals
// independent draws from the dictionary's ensemble (chermain_marginal), so with ḡ and V the
// marginal's mean and per-pair variance and a = 2^(−k) the level's share: E[X] = E_θ[ḡ_x ḡ_y]/det,
// E[X²] − E[X]² = (a P + a² Q)/det², P = E_θ[ḡ_x² V_y + V_x ḡ_y²], Q = E_θ[V_x V_y]; a coarse cell
// shares its draws with its lower-left fine child
// (levels k and k + 1: a prefix, covariance with a = 2^(−k−1)); the bilinear weights over positions
// give E Σ W² = 4/9 per LOD and kChermainSharedWeight for the shared pair, so
//   Var = (4/9)(w_0² v_0 + w_1² v_1) + 2 w_0 w_1 kChermainSharedWeight c_01,
// and the mean w_0 μ_0 + w_1 μ_1. A LOD past the dictionary's last level is the smooth fallback
// (a = 0, μ the unfiltered Gaussian). The lookup's filter widens ḡ too (texels; GGAA's kernel,
// which the smooth fallback does not get): the smooth level's mean difference g/mean − 1, g the
// unfiltered Gaussian ḡ(x)ḡ(y)/det = the smooth level's value, grows in the lobe's tail (about
// (x²/σ_o² − 1) w²/(2σ_o²) per marginal for a widening w²). What verify/adequacy's
// chermain_exact_moments computes from the dictionary's own tables, here from the ensemble it is
// drawn from (its 192 distributions taken as many, the lobe means as untruncated), so a shader
// needs no table for it.
template <class T>
struct ChermainSmoothPrediction {
  T cv, mean_diff;
};
template <class T>
GLINTLAB_FN ChermainSmoothPrediction<T> chermain_smooth_prediction(
    const chermain2021::SdfParams& p, const chermain2021::SlopeDerivatives& d, Vec2<T> m,
    const ChermainLods<T>& lods) {
  const chermain2021::Dictionary& dict = *p.dictionary;
  const chermain2021::Matrix M =
      chermain2021::matrix(p.sigma_x, p.sigma_y, p.rho, dict.sigma_o(), p.with_rho);
  const double sk = p.kernel != chermain2021::kNoGgaa ? p.s_k : 0.0;
  const chermain2021::SlopeDerivatives dd =
      p.kernel == chermain2021::kNoGgaa ? chermain2021::SlopeDerivatives{0, 0, 0, 0} : d;
  const double ax = sk * (M.i00 * dd.dx_x + M.i01 * dd.dx_y), ay = sk * (M.i11 * dd.dx_y);
  const double bx = sk * (M.i00 * dd.dy_x + M.i01 * dd.dy_y), by = sk * (M.i11 * dd.dy_y);
  const T mx = T(M.i00) * m.x + T(M.i01) * m.y, my = T(M.i11) * m.y;
  const double so = dict.sigma_o(), lobe = dict.config().lobe_std;
  T P = T(0), Q = T(0), G = T(0);
  for (int t = 0; t < kChermainChooserNodes; ++t) {
    const double theta = 1.5707963267948966192 * (t + 0.5) / kChermainChooserNodes;
    const double ct = std::cos(theta), st = std::sin(theta);
    const T xo = T(ct) * mx + T(st) * my, yo = T(-st) * mx + T(ct) * my;
    const T wx = chermain_filter_widening(dict, T(ct * ax + st * ay), T(ct * bx + st * by));
    const T wy = chermain_filter_widening(dict, T(-st * ax + ct * ay), T(-st * bx + ct * by));
    const MarginalMoments<T> gx = chermain_marginal(xo, wx, so, lobe);
    const MarginalMoments<T> gy = chermain_marginal(yo, wy, so, lobe);
    P = P + gx.mean * gx.mean * gy.var + gx.var * gy.mean * gy.mean;
    Q = Q + gx.var * gy.var;
    G = G + gx.mean * gy.mean;
  }
  const T inv = T(1.0 / kChermainChooserNodes);
  P = P * inv, Q = Q * inv, G = G * inv;
  // a = 2^(−k) below the last level, 0 past it (the smooth fallback).
  const T last = T(dict.levels());
  const auto share = [&](T k) {
    return select(k < last, exp(-min(k, last) * T(0.69314718055994530942)), T(0));
  };
  const T a0 = share(lods.k_fine), a1 = share(lods.k_coarse), ac = min(a0, a1);
  const T w1 = lods.w_coarse, w0 = T(1) - w1;
  const T var =
      T(4.0 / 9.0) * (w0 * w0 * (a0 * P + a0 * a0 * Q) + w1 * w1 * (a1 * P + a1 * a1 * Q)) +
      T(2 * kChermainSharedWeight) * w0 * w1 * (ac * P + ac * ac * Q);
  // The unfiltered Gaussian (the smooth level and the fallback's value) and each LOD's mean.
  const T g = exp(T(-0.5 / (so * so)) * (mx * mx + my * my)) * T(1 / (6.283185307179586 * so * so));
  const T mean = w0 * select(lods.k_fine < last, G, g) + w1 * select(lods.k_coarse < last, G, g);
  return {safe_div(safe_sqrt(var), mean), safe_div(g, mean) - T(1)};
}

// GGAA off against GGAA on where GGAA filters (a kernel and a derivative): both from the closed
// form above, with and without the kernel's widening of the lobes, at the same LODs — the mean of
// GGAA off relative to GGAA on's minus 1, and the difference of their CVs. GGAA off is adequate
// where both are at most kChooserMargin · TAU (chermain_ggaa_off_adequate; the choosers take it
// through chermain_level_adequacy, docs/adequacy.md "The Chermain chooser").
template <class T>
struct ChermainGgaaOffPrediction {
  T mean_diff, cv_diff;
};
// From the closed form with GGAA (`on`, the shader's parameters) and without it (`off`).
template <class T>
GLINTLAB_FN ChermainGgaaOffPrediction<T> chermain_ggaa_off_difference(
    const ChermainSmoothPrediction<T>& on, const ChermainSmoothPrediction<T>& off) {
  // mean = g / (1 + mean_diff) for each, g the same smooth value.
  return {safe_div(T(1) + on.mean_diff, T(1) + off.mean_diff) - T(1), off.cv - on.cv};
}
template <class T>
GLINTLAB_FN ChermainGgaaOffPrediction<T> chermain_ggaa_off_prediction(
    const chermain2021::SdfParams& p, const chermain2021::SlopeDerivatives& d, Vec2<T> m,
    const ChermainLods<T>& lods) {
  chermain2021::SdfParams off = p;
  off.kernel = chermain2021::kNoGgaa;
  return chermain_ggaa_off_difference(chermain_smooth_prediction(p, d, m, lods),
                                      chermain_smooth_prediction(off, d, m, lods));
}

// Whether GGAA filters at all: a kernel and a screen-space derivative (uniform per batch: the
// shader's parameters). Where it does not, GGAA off is GGAA on bit for bit.
inline bool chermain_ggaa_filters(const chermain2021::SdfParams& p,
                                  const chermain2021::SlopeDerivatives& d) {
  return p.kernel != chermain2021::kNoGgaa && p.s_k != 0 &&
         (d.dx_x != 0 || d.dx_y != 0 || d.dy_x != 0 || d.dy_y != 0);
}

// Whether GGAA off is predicted adequate at a query (true where GGAA does not filter: then it is
// GGAA on bit for bit; below the horizon every level is 0).
template <class T>
GLINTLAB_FN Mask<T> chermain_ggaa_off_adequate(const chermain2021::SdfParams& p,
                                               const chermain2021::SlopeDerivatives& d,
                                               const ModelQuery<T>& q, T tau) {
  if (!chermain_ggaa_filters(p, d)) return Mask<T>(true);
  const Vec3<T> h = half_vector(q.wi, q.wo);
  const Mask<T> up = q.wi.z > T(0) && q.wo.z > T(0) && h.z > T(0);
  const T hz = select(up, h.z, T(1));
  const ChermainGgaaOffPrediction<T> g = chermain_ggaa_off_prediction(
      p, d, Vec2<T>{-h.x / hz, -h.y / hz}, chermain_lods(p, q.footprint));
  const T limit = T(kChooserMargin) * tau;
  return (abs(g.mean_diff) <= limit && abs(g.cv_diff) <= limit) || !up;
}

// The CV alone (the chooser's tests and verify's table).
template <class T>
GLINTLAB_FN T chermain_smooth_cv(const chermain2021::SdfParams& p,
                                 const chermain2021::SlopeDerivatives& d, Vec2<T> m,
                                 const ChermainLods<T>& lods) {
  return chermain_smooth_prediction(p, d, m, lods).cv;
}

// Each ChermainLevel's predicted adequacy at a query (`p`: the shader's parameters of the most
// complete level, its whole dictionary and GGAA as it renders with): dictL with GGAA on where it
// is the most complete level bit for bit (the dictionary's boundary), dictL with GGAA off there
// too where GGAA does not filter or its predicted differences from GGAA on are at most
// kChooserMargin · tau (chermain_ggaa_off_adequate: dictL off is dict16 off there, the same
// LODs), the smooth level where its predicted CV and mean difference are at most
// kChooserMargin · tau, every level below the horizon (all are 0 there), dict16_ggaa always.
// choose_chermain_level takes the first; the choosers for given costs the cheapest.
template <class T>
GLINTLAB_FN std::array<Mask<T>, kChermainLevels> chermain_level_adequacy(
    const chermain2021::SdfParams& p, const chermain2021::SlopeDerivatives& d,
    const ModelQuery<T>& q, T tau) {
  const Vec3<T> h = half_vector(q.wi, q.wo);
  const Mask<T> up = q.wi.z > T(0) && q.wo.z > T(0) && h.z > T(0);
  const T hz = select(up, h.z, T(1));
  const Vec2<T> m{-h.x / hz, -h.y / hz};
  const ChermainLods<T> lods = chermain_lods(p, q.footprint);
  const T last = T(p.dictionary->levels());
  const Mask<T> coarse_on = lods.w_coarse > T(0);
  const auto same = [&](T k, int L) { return k < T(L) || k >= last; };
  const auto identical = [&](int L) {
    return same(lods.k_fine, L) && (!coarse_on || same(lods.k_coarse, L));
  };
  const Mask<T> all_smooth = lods.k_fine >= last && (!coarse_on || lods.k_coarse >= last);
  const ChermainSmoothPrediction<T> sp = chermain_smooth_prediction(p, d, m, lods);
  const T limit = T(kChooserMargin) * tau;
  // GGAA off is GGAA on bit for bit where it does not filter (uniform per batch: no lane
  // branch), else adequate where the closed form without the kernel stays within the margin
  // (chermain_ggaa_off_adequate, sharing the closed form with GGAA computed above).
  Mask<T> off_too = Mask<T>(true);
  if (chermain_ggaa_filters(p, d)) {
    chermain2021::SdfParams off = p;
    off.kernel = chermain2021::kNoGgaa;
    const ChermainGgaaOffPrediction<T> g =
        chermain_ggaa_off_difference(sp, chermain_smooth_prediction(off, d, m, lods));
    off_too = abs(g.mean_diff) <= limit && abs(g.cv_diff) <= limit;
  }
  const Mask<T> smooth = all_smooth || (sp.cv <= limit && abs(sp.mean_diff) <= limit);
  const Mask<T> down = !up;
  const Mask<T> i4 = identical(4), i8 = identical(8), i12 = identical(12);
  return {smooth || down, (i4 && off_too) || down,  i4 || down,  (i8 && off_too) || down,
          i8 || down,     (i12 && off_too) || down, i12 || down, off_too || down,
          Mask<T>(true)};
}

// The chooser: the first adequate level in ChermainLevel order (chermain_level_adequacy), the one
// a GPU lane pays least for. Returns the level as T.
template <class T>
GLINTLAB_FN T choose_chermain_level(const chermain2021::SdfParams& p,
                                    const chermain2021::SlopeDerivatives& d, const ModelQuery<T>& q,
                                    T tau) {
  const std::array<Mask<T>, kChermainLevels> adequate = chermain_level_adequacy(p, d, q, tau);
  T level = T(kChermainLevels - 1);
  for (int l = kChermainLevels - 2; l >= 0; --l)
    level = select(adequate[std::size_t(l)], T(l), level);
  return level;
}

// The same on what a shader of the model has: its parameters and the query.
template <class T>
GLINTLAB_FN T choose_chermain_model_level(const Chermain::Params<T>& params, const ModelQuery<T>& q,
                                          T tau) {
  return choose_chermain_level(params.sdf, params.d, q, tau);
}

}  // namespace glintlab

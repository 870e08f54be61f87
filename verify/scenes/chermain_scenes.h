// The two test scenes of Chermain et al. 2021 that the chermain.* claims (verify/claims/chermain/)
// and the figures chermain2021-fig7/8/9 render: curved glinty tubes under a point light (Figs. 8–9)
// and a plane with an anisotropic normal map under a directional light (Fig. 7). Only the glinty
// specular component is rendered (as the paper's RMSEs, Sec. 6), one sample per pixel at the pixel
// centre for the methods, and a stratified N-spp pixel average for the references.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/glints/chermain.h"
#include "core/render/image.h"

namespace glintlab::verify {

// --- Curved tubes (Figs. 8, 9) ---------------------------------------------------------------
struct TubeSceneOptions {
  int width = 96, height = 64;
  double camera_shift = 0;      // camera moved along its right axis by this many pixel widths
  double density = 1.6e5;       // microfacets per unit uv area
  double alpha = 0.35;          // isotropic Beckmann roughness of the glinty SDF
  std::uint64_t sdf_seed = 11;  // seed of the patch-SDF's cell randomization (the glint layout)
  int threads = 0;
};

// One method: kernel = chermain2021::kNoGgaa / chermain2021::kHalfSlope (Eq. 20) /
// chermain2021::kProjectedHalf (Eq. 21), s_k the kernel scale. 1 spp at pixel centres.
Image render_tubes(const TubeSceneOptions& o, int kernel, double s_k);
// The reference: `spp` stratified positions per pixel, each shading with its own view, light and
// half vector but the pixel's footprint P (so the same patch-SDF), without GGAA: the pixel
// integral that GGAA approximates (2021 Sec. 4.1, Fig. 4a).
Image render_tubes_reference(const TubeSceneOptions& o, int spp, std::uint64_t seed);

// --- Normal-mapped tubes (Fig. 9's regime) --------------------------------------------------
// The tubes of Fig. 8 with a procedural bump map, so that the shading normal varies within a
// pixel as on Fig. 9's lion head. The bump map is a solid texture: the height
// H(p) = a Σ_j sin(k d_j·p + φ_j) over six directions d_j ∝ (±1, 1, 0), (1, 0, ±1), (0, 1, ±1)
// (Σ d_j d_jᵀ = 2 I, so the slope ∇H·t has rms a·k along every tangent t), k = 2π / wavelength;
// its gradient projected on the tube's tangent frame gives the tangent-space slopes, and the
// shading normal is (−s_t, −s_b, 1)/‖·‖ in that frame (normal mapping without LEAN filtering).
struct BumpyTubeOptions {
  TubeSceneOptions tubes;
  double bump_wavelength_px = 4;  // the bumps' wavelength, in pixels of the view at the origin
  double bump_slope_rms = 0.1;    // rms tangent-space slope of the bump map along any direction
};

// One method at 1 spp at pixel centres (channel 0; channel 3 holds the GGAA kernel width, 0
// without GGAA). As Sec. 6.2 says for normal maps, the half vector is taken in the shading frame
// of the mapped normal, and the GGAA derivatives are its finite differences between the pixel's
// corners, each corner in its own mapped frame (the corner scheme of core/scene/footprint.h).
Image render_bumpy_tubes(const BumpyTubeOptions& o, int kernel, double s_k);

// The reference: `spp` stratified positions per pixel, each shaded with its own mapped normal,
// view, light, half vector and its own footprint centred at its own uv: the pixel's footprint
// divided by kBumpyReferenceStrata per axis (the stratum of a 1,024-spp supersampled render, the
// paper's reference), never finer than one microfacet (LOD ≥ −½ log2 density, dictionary level 0:
// below it the model has no finer structure), no GGAA. It estimates the pixel's average of that
// 1,024-stratum render without bias at any spp.
// kPixelSized is the other reading of a 1,024-spp reference: 1,024 jittered 1-spp frames, each
// sample's footprint the size of the pixel's but centred at the sample's own uv (the glints then
// come from the same LOD, the same realization, as the methods'); the per-pixel box average of
// that is wider than the pixel.
enum class BumpyReference { kFinest, kPixelSized };
inline constexpr int kBumpyReferenceStrata = 32;
Image render_bumpy_tubes_reference(const BumpyTubeOptions& o, int spp, std::uint64_t seed,
                                   BumpyReference kind = BumpyReference::kFinest);

// --- Anisotropic normal map (Fig. 7) ---------------------------------------------------------
struct NormalMapSceneOptions {
  int width = 96, height = 64;
  int map_size = 256;  // slope moment map texels
  int groove_p = 1,
      groove_q = 2;        // grooves perpendicular to (p, q) (core/scene/sine_height_field.h)
  double slope_rms = 0.2;  // of the normal map
  double anisotropy = 8;
  double base_alpha = 0.08;  // roughness of the microsurface ("little roughness", Sec. 6.4)
  double density = 1e9;
  int threads = 0;
};

enum class NormalMapMethod { kNoLean = 0, kLeanRhoZero = 1, kLean = 2 };

// Slope-space normal mapping: the glinty SDF (base roughness) centred on the normal map's slope.
// kNoLean: centred on the footprint's mean slope, base roughness only; kLeanRhoZero: LEAN σ_x, σ_y
// (Olano & Baker 2010) with ρ = 0; kLean: with ρ through M of Eq. 18. GGAA off (the kernel from
// curvature is zero on the plane).
Image render_normal_map(const NormalMapSceneOptions& o, NormalMapMethod method);
// The reference: `spp` stratified positions per pixel, each with the finest slope of the height
// field at its own uv, base roughness, the pixel's footprint P.
Image render_normal_map_reference(const NormalMapSceneOptions& o, int spp, std::uint64_t seed);

// --- What the figures measure on these scenes (chermain2021-fig7/8/9) -------------------------
// The pan of the shimmer measurements, in pixels per frame (chermain.ggaa-shimmer and Fig. 9).
inline constexpr double kGgaaPan = 0.37;

struct GgaaBudget {
  int width, height;
  int reference_spp;
  int frames;   // camera-pan frames for the frame-to-frame variance
  int threads;  // 0 = all cores
};
struct GgaaMeasurement {
  Image reference, none, half05, half1, proj05, proj1;  // 1 spp; half = Eq. 20, proj = Eq. 21
  std::vector<Image> frames_none, frames05, frames1;    // projected half vector, s_K 0.5 and 1
};
struct GgaaVerdict {
  double rmse_none = 0, rmse_half05 = 0, rmse_half1 = 0, rmse_proj05 = 0, rmse_proj1 = 0;
  double flicker_none = 0, flicker05 = 0, flicker1 = 0;
  bool ggaa_lowers = false, projected_beats_half = false;
  bool small_kernel_lower_rmse = false, small_kernel_shimmers_more = false;
};
// The display RMSE % of every method against `reference`, the shimmer of the pans, and Fig. 9's
// orderings read off them (one render each: no replicates, no intervals).
GgaaVerdict judge_ggaa(const GgaaMeasurement& m, const Image& reference);

struct LeanBudget {
  int width, height;
  int reference_spp;
  int groove_p, groove_q;  // grooves perpendicular to (p, q)
  int threads;
};
struct LeanMeasurement {
  Image reference, no_lean, lean_rho0, lean;
  double rmse_no_lean = 0, rmse_lean_rho0 = 0, rmse_lean = 0;  // display RMSE %
};
// The normal-map scene at `b`: its reference (seed), the three methods and their display RMSE %.
LeanMeasurement measure_lean(const LeanBudget& b, std::uint64_t seed);

// --- Metrics ---------------------------------------------------------------------------------
// The RMSE of the paper's figures, in %: both images scaled by one exposure that maps the
// reference's mean over lit pixels (reference > 0) to 0.18, clamped to [0, 1] (a display image),
// RMSE over the lit pixels × 100.
double display_rmse_percent(const Image& x, const Image& reference);
// The per-pixel |x − reference| on that display scale, over the lit pixels in row order (what
// display_rmse_percent is the RMS of, / 100).
std::vector<double> display_abs_errors(const Image& x, const Image& reference);
// Frame-to-frame variance (shimmer): mean over pixels and consecutive frames of (I_{t+1} − I_t)²,
// on the same display scale as display_rmse_percent (exposure from `reference`), × 10^4.
double frame_to_frame_variance(const std::vector<Image>& frames, const Image& reference);

}  // namespace glintlab::verify

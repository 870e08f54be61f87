// The measurements behind chermain.ggaa-* and chermain.lean-correlation (shared with the
// figures chermain2021-fig7/8/9) and cheap probes of what each chermain.* check decides, so tests
// can assert that the correct input passes and the negative control is rejected.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/render/image.h"
#include "verify/check.h"
#include "verify/claims/control_probes.h"

namespace glintlab::verify {

// --- chermain.ggaa-error (Figs. 8, 9) ---
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

GgaaMeasurement measure_ggaa(const GgaaBudget& b, std::uint64_t seed);
GgaaVerdict judge_ggaa(const GgaaMeasurement& m, const Image& reference);

// The checks chermain.ggaa-error and -shimmer: `replicates` independent replicates of the tube
// scene (glint layout, sub-pixel camera offset and reference seed from check_seed(id, k)), each
// with the display RMSE % without GGAA and with GGAA, and the shimmer of s_K 0.5 and 1.
struct GgaaReplicateBudget {
  int width, height;
  int reference_spp;
  int frames;
  int replicates;
  int threads;  // 0 = all cores
};
struct GgaaReplicate {
  double none = 0, proj05 = 0;  // display RMSE %: no GGAA, Eq. 21 at s_K 0.5
  double near_truth = 0;  // control: an independent reference × (1 + kGgaaNearTruthBias)
  double flicker05 = 0, flicker1 = 0;  // frame-to-frame variance × 1e4, projected half vector
  double flicker1_slow = 0;            // control: s_K 1 under a pan kGgaaSlowPan slower
};
// Fixed before measuring: the confidence of each ordering's t interval (Šidák over a claim's
// parts), the control's near-truth bias and slower pan, the pan per frame (pixels).
inline constexpr double kGgaaConfidence = 0.99;
inline constexpr double kGgaaNearTruthBias = 0.03;
inline constexpr double kGgaaSlowPan = 0.05;
inline constexpr double kGgaaPan = 0.37;

GgaaReplicate measure_ggaa_replicate(const GgaaReplicateBudget& b, const std::string& id, int k);

struct PairedComparison {
  int n = 0;
  double mean = 0, se = 0, t = 0, lo = 0, hi = 0;
  double detectable = 0;  // (t + 1.28) · SE: the difference detected at 90 % power
};
PairedComparison compare_paired(const std::vector<double>& differences, double confidence);
// Each part: per-replicate differences (claimed higher − claimed lower). holds when every part's
// Šidák-corrected kGgaaConfidence interval lies above 0, fails when one lies below 0, else
// inconclusive (a tie within the noise).
Verdict decide_ggaa(const std::vector<std::vector<double>>& parts);

// --- chermain.ggaa-derivatives and chermain.ggaa-sk (Fig. 9) ---
// Both claims on one replicated measurement of the normal-mapped tubes (BumpyTubeOptions of
// chermain_scenes.h) against the per-sample-footprint reference; each replicate has its own glint
// layout, sub-pixel camera offset and two independent references (the second gives the
// reference's own error and the control's near-truth image).
struct BumpyGgaaBudget {
  int width, height;
  int reference_spp;
  int replicates;
  int threads;  // 0 = all cores
};
struct BumpyGgaaReplicate {
  // Display RMSE % against the reference; Eq. 20 (half slope) and Eq. 21 (projected half vector)
  // at s_K 0.5 and 1, and Eq. 21 at the s_K that matches Eq. 20's mean kernel width at s_K 0.5.
  double none = 0, half05 = 0, half1 = 0, proj05 = 0, proj1 = 0, proj_matched = 0;
  // The same four against the second, independent reference.
  double half05_alt = 0, half1_alt = 0, proj05_alt = 0, proj1_alt = 0;
  double near_truth = 0;       // control: the second reference × (1 + kGgaaNearTruthBias)
  double reference_error = 0;  // display RMSE % of the second reference against the first / √2
  // Median over the pixels of Eq. 20's GGAA kernel width / Eq. 21's at s_K 0.5, and the s_K of
  // Eq. 21 that matches Eq. 20's width at s_K 0.5 (0.5 × that ratio).
  double width_ratio = 0, matched_s_k = 0;
  // Diagnostics of the reference: the smooth limit (the glinty BRDF's expectation, no glints at
  // all) against it, and every method against the other reading of the paper's reference
  // (BumpyReference::kPixelSized).
  double smooth = 0;
  double none_px = 0, half05_px = 0, half1_px = 0, proj05_px = 0, proj1_px = 0, smooth_px = 0;
};
// Fixed before measuring: an ordering reversed by less than this many display-RMSE points (or
// than the reference's own error of the compared difference, where larger) is a tie, not a
// failure: Fig. 9's smallest reported ordering is 0.10 points (7.527 vs 7.425 %).
inline constexpr double kPairTolerance = 0.1;

BumpyGgaaReplicate measure_bumpy_ggaa_replicate(const BumpyGgaaBudget& b, const std::string& id,
                                                int k);
// Each part: per-replicate differences (claimed higher − claimed lower). holds when every part's
// Šidák-corrected kGgaaConfidence interval lies above 0, fails when one lies below −tolerance,
// else inconclusive (a tie, or a reversal the tolerance cannot tell from one).
Verdict decide_ordering(const std::vector<std::vector<double>>& parts, double tolerance);

// --- chermain.lean-correlation (Fig. 7) ---
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

// LEAN with ρ must beat both others by this factor (fixed before measuring).
inline constexpr double kLeanMargin = 0.95;

LeanMeasurement measure_lean(const LeanBudget& b, std::uint64_t seed);
bool lean_holds(const LeanMeasurement& m);
// chermain.lean-correlation's measure and decide on `replicates` replicates of budget `b`: the
// genuine verdict and the control's (a near-truth image, an independent reference of at least 256
// spp × 1.03, in place of both other methods), with the control's mean margin (negative: LEAN with
// rho is not below 0.95 × the near-truth image's RMSE).
struct LeanDecisionProbe {
  Verdict genuine, near_truth;
  double control_margin = 0;
  std::string control;  // what the control measured
};
LeanDecisionProbe probe_chermain_lean(const LeanBudget& b, int replicates);

// Probes: correct = the check's statistic on the correct input, control = on its negative control.
ControlProbe probe_chermain_kernel_normalized();     // |∫−1|; control: every texel × 1.02
ControlProbe probe_chermain_dictionary_converges();  // last-level L1; control: means × 1.02
ControlProbe probe_chermain_correlation();           // |ρ̂ − ρ|; control: ρ off by 0.03

}  // namespace glintlab::verify

// What Chermain et al.'s claims share: the paper's name, the paired t intervals the replicated
// render claims are decided by, and the two replicated measurements that two claims each read
// (made once per process): the tube scene's (chermain.ggaa-error, chermain.ggaa-shimmer) and the
// normal-mapped tubes' (chermain.ggaa-derivatives, chermain.ggaa-sk). The scenes themselves are
// verify/scenes/chermain_scenes.h (the figures render them too).
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "verify/check.h"
#include "verify/claim.h"

namespace glintlab::verify::chermain_claims {

inline constexpr std::string_view kPaper = "Chermain et al. 2021";

// Fixed before measuring: the confidence of each ordering's t interval (Šidák over a claim's
// parts), the controls' near-truth bias (an independent reference × 1.03) and slower pan.
inline constexpr double kGgaaConfidence = 0.99;
inline constexpr double kGgaaNearTruthBias = 0.03;
inline constexpr double kGgaaSlowPan = 0.05;

// kGgaaConfidence shared by `parts` comparisons (Šidák).
inline double sidak_confidence(std::size_t parts) {
  return std::pow(kGgaaConfidence, 1.0 / double(parts));
}

// The t interval of the mean of per-replicate differences.
struct PairedComparison {
  int n = 0;
  double mean = 0, se = 0, t = 0, lo = 0, hi = 0;
  double detectable = 0;  // (t + 1.28) · SE: the difference detected at 90 % power
};
PairedComparison compare_paired(const std::vector<double>& differences, double confidence);

// Each part: per-replicate differences (claimed higher − claimed lower). holds when every part's
// Šidák-corrected kGgaaConfidence interval lies above 0, fails when one lies below −tolerance,
// else inconclusive (a tie, or a reversal the tolerance cannot tell from one).
Verdict decide_paired(const std::vector<std::vector<double>>& parts, double tolerance = 0);

// The largest detectable difference over the parts, at their Šidák confidence.
double largest_detectable(const std::vector<std::vector<double>>& parts);

// "a (claimed higher) vs b" in words: as claimed, reversed or a tie within the noise.
std::string_view reading(const PairedComparison& c);
// The power of a claim decided by decide_paired over `replicates` replicates: the largest
// difference detected at 90 % power, in `unit`.
std::string paired_power(const std::vector<std::vector<double>>& parts, std::string_view unit,
                         int replicates);

// --- The tube scene's replicates (chermain.ggaa-error, chermain.ggaa-shimmer) -----------------
// K independent replicates of the tube scene (glint layout, sub-pixel camera offset and reference
// seed from check_seed("chermain.ggaa", k)), each with the display RMSE % without GGAA and with
// GGAA, and the shimmer of s_K 0.5 and 1.
struct GgaaReplicateBudget {
  int width, height;
  int reference_spp;
  int frames;
  int replicates;
  int threads;  // 0 = all cores
};
struct GgaaReplicate {
  double none = 0, proj05 = 0;  // display RMSE %: no GGAA, Eq. 21 at s_K 0.5
  double near_truth = 0;        // control: an independent reference × (1 + kGgaaNearTruthBias)
  double flicker05 = 0, flicker1 = 0;  // frame-to-frame variance × 1e4, projected half vector
  double flicker1_slow = 0;            // control: s_K 1 under a pan kGgaaSlowPan slower
};
GgaaReplicate measure_ggaa_replicate(const GgaaReplicateBudget& b, const std::string& id, int k);
// Replicate k of "chermain.ggaa" at `b`, measured once per process.
GgaaReplicate replicate(const GgaaReplicateBudget& b, int k);

// A claim "a < b" in every part (RMSE: a is more accurate; shimmer: b shimmers more), decided on
// the per-replicate differences b − a. The control puts `control` in place of b when the genuine
// verdict holds (Input::kPerturbed: the claim must then fail) and in place of a when it does not
// (Input::kCorrected: the claim must then hold).
struct GgaaPart {
  const char* a_name;
  double GgaaReplicate::*a;
  const char* b_name;
  double GgaaReplicate::*b;
};
struct GgaaOrdering {
  std::vector<GgaaPart> parts;
  double GgaaReplicate::*control;
  const char* control_name;
  const char* unit;
};
struct GgaaMeasured {
  std::vector<GgaaReplicate> reps = {};
  Input input = Input::kGenuine;
  std::vector<std::vector<double>> diffs = {};  // per part, per replicate: b − a
};
GgaaMeasured measure_ordering(const GgaaOrdering& o, std::span<const GgaaReplicate> reps,
                              Input input);
Decision decide_ordering(const GgaaOrdering& o, const GgaaMeasured& m);
// The genuine measurement's detail, or the control's text.
std::string describe_ordering(const GgaaOrdering& o, const GgaaReplicateBudget& g,
                              const GgaaMeasured& m);

// --- The normal-mapped tubes' replicates (chermain.ggaa-derivatives, chermain.ggaa-sk) --------
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
// Replicate k of "chermain.ggaa-fig9" at `b`, measured once per process.
BumpyGgaaReplicate replicate(const BumpyGgaaBudget& b, int k);

using BumpyField = double BumpyGgaaReplicate::*;
// "a has the lower RMSE" for one part: a and b against the reference, and against the second one.
struct OrderingPart {
  const char* a_name;
  BumpyField a, a_alt;
  const char* b_name;
  BumpyField b, b_alt;
};
struct Ordering {
  std::vector<OrderingPart> parts;
  static constexpr std::string_view unit = "% RMSE";
  // Per part, per replicate: b − a, with the near-truth image in place of a (replace_a: the
  // corrected input, which must hold) or of b (replace_b: the perturbed one, which must fail).
  std::vector<std::vector<double>> diffs(std::span<const BumpyGgaaReplicate> reps,
                                         bool replace_a = false, bool replace_b = false) const;
  // The reference's own error of the compared difference: the RMS over replicates of its change
  // between the two independent references, / √2 (one reference's share), largest over parts.
  double reference_error(std::span<const BumpyGgaaReplicate> reps) const;
  // kPairTolerance or the reference's own error, whichever is larger.
  double tolerance(std::span<const BumpyGgaaReplicate> reps) const;
};
struct OrderingMeasured {
  std::vector<BumpyGgaaReplicate> reps = {};
  Input input = Input::kGenuine;
  double reference_error = 0, tolerance = 0;
  std::vector<std::vector<double>> diffs = {};
};
OrderingMeasured measure_ordering(const Ordering& o, std::span<const BumpyGgaaReplicate> reps,
                                  Input input);
Decision decide_ordering(const Ordering& o, const OrderingMeasured& m);
// The genuine measurement's detail, or the control's text.
std::string describe_ordering(const Ordering& o, const BumpyGgaaBudget& g,
                              const OrderingMeasured& m);
double mean_field(std::span<const BumpyGgaaReplicate> reps, BumpyField f);

// The sizes of a replicated measurement, per budget and at the probe size: the tube scene's
// (GgaaReplicateBudget) quick 64×44, 32-spp references, 3 frames, 6 replicates, full 128×88,
// 64 spp, 4 frames, 10; the normal-mapped tubes' (BumpyGgaaBudget) quick 64×44, 256-spp
// references, 6 replicates, full 128×88, 1,024 spp, 10.
template <typename Sizes>
Sizes replicate_budget(Budget b);
template <typename Sizes>
Sizes replicate_probe_budget();
template <>
GgaaReplicateBudget replicate_budget<GgaaReplicateBudget>(Budget b);
template <>
GgaaReplicateBudget replicate_probe_budget<GgaaReplicateBudget>();
template <>
BumpyGgaaBudget replicate_budget<BumpyGgaaBudget>(Budget b);
template <>
BumpyGgaaBudget replicate_probe_budget<BumpyGgaaBudget>();

// What the replicated ordering claims have in common as claims (verify/claim.h): chermain.ggaa-
// error and -shimmer on the tube scene's replicates (GgaaOrderingClaim), chermain.ggaa-derivatives
// and -sk on the normal-mapped tubes' (BumpyOrderingClaim). Everything but their names and
// Self::ordering(); a claim may replace any step.
template <typename Self, typename SizesT, typename Replicate, typename MeasuredT>
struct ReplicatedOrderingClaim {
  static constexpr bool kHasCorrectedControl = true;
  using Sizes = SizesT;
  static Sizes sizes(Budget b) { return replicate_budget<Sizes>(b); }
  static Sizes probe_sizes() { return replicate_probe_budget<Sizes>(); }
  static int configurations(const Sizes& z) { return z.replicates; }
  using Evidence = Replicate;  // replicate k, made once for the claims that share it
  static Evidence observe(const Sizes& z, int k, std::uint64_t) { return replicate(z, k); }
  using Measured = MeasuredT;
  static Measured measure(const Sizes&, std::span<const Evidence> all, Input input) {
    return measure_ordering(Self::ordering(), all, input);
  }
  static Decision decide(const Sizes&, const Measured& m) {
    return decide_ordering(Self::ordering(), m);
  }
  static std::string describe(const Sizes& z, const Measured& m, Input) {
    return describe_ordering(Self::ordering(), z, m);
  }
  static std::string power(const Sizes& z, const Measured& m, const Measured&) {
    return paired_power(m.diffs, Self::ordering().unit, z.replicates);
  }
};
template <typename Self>
using GgaaOrderingClaim =
    ReplicatedOrderingClaim<Self, GgaaReplicateBudget, GgaaReplicate, GgaaMeasured>;
template <typename Self>
using BumpyOrderingClaim =
    ReplicatedOrderingClaim<Self, BumpyGgaaBudget, BumpyGgaaReplicate, OrderingMeasured>;

// The two orderings of Fig. 9: chermain.ggaa-sk's (s_K 0.5 below s_K 1, for both derivative
// variants), which chermain.ggaa-derivatives also reads (ggaa_sk.cpp), and the derivatives' own
// (ggaa_derivatives.cpp).
extern const Ordering kSkOrdering;

}  // namespace glintlab::verify::chermain_claims

// What eto.variance-rough and eto.variance-smooth share: one measurement (the seeds are
// variance-rough's, so both claims read the same numbers) and one decision, on two regimes.
//
// The paper, Sec. 4: the bounded sampler lowers the error at equal sample count "especially for
// high-roughness surfaces (α_x = α_y = 0.8 in Fig. 4)", while "the quality difference is
// insignificant for low roughness (α_x = α_y = 0.2 in Fig. 4)".
//
// On the upper hemisphere the bounded density is the caps density divided by
// c = (k i_z + t)/(i_z + t) (Eq. 8 over Eq. 7), so for ANY incident radiance the second moments
// of the two estimators of ∫ f L cos dωo satisfy M2_b = c·M2_c with equal means: the RMSE
// reduction 1 − √(M2_b/M2_c) is the one that holds when lighting dominates the variance (the
// environment-lit renders of Figs. 4–6). It is measured from both samplers' weights, with its
// interval; c is printed beside it for comparison.
//
// Decide: a "material" gain is an RMSE reduction of at least kMaterialGain; a configuration is
// within/beyond by its interval (Šidák over the configurations). Controls, through the same
// measurement and decision, near the 5 % line rather than near the truth: no 1–5 % change of the
// bounded estimator's RMSE crosses the line from the rough regime's 13 %+ reductions, so the
// gain's control is an estimator with a reduction of 2 % (the spherical-cap sampler against an
// independent run of itself, its second moment × 0.98²); the no-gain control is the bounded
// estimator with a 4 % lower RMSE (second moment × 0.96²), which takes α = 0.2's reduction of
// ≈ 2 % past the line.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "verify/claim.h"
#include "verify/claims/eto/common.h"

namespace glintlab::verify::eto_claims {

inline constexpr double kMaterialGain = 0.05;  // an RMSE reduction of 5 % (≈ 10 % fewer samples)
// The regimes, from the paper's words: "high-roughness" (Fig. 4's α = 0.8 and above), "low
// anisotropy" (isotropic), at incidence up to 60° (towards grazing c → 1 for every α, see above).
inline constexpr std::string_view kRoughRegime = "isotropic α ≥ 0.8, θi ≤ 60°";
inline constexpr std::string_view kSmoothRegime = "isotropic α = 0.2, θi ≤ 60°";

// Configuration i's second moments of both samplers' weights (and of the caps sampler against an
// independent run of itself).
struct GainMeasured {
  Config c;
  double ratio = 1, log_se = 0;          // M2_b / M2_c and the standard error of its log
  double ratio_off = 1, log_se_off = 0;  // the caps sampler against an independent run of itself
  double c_analytic = 1;
};

struct GainSizes {
  std::vector<Config> grid;
  std::uint64_t n;  // samples per sampler and configuration
};
// The quick grid holds the full grid's extremes (α 0.05 and 1, αx/αy 1 and 10, θi 0° and 89°).
GainSizes gain_sizes(Budget b);
// Kept per process: the claim that runs second in a process reads the first one's measurement.
GainMeasured observe_gain(const GainSizes& z, int configuration);

// The RMSE-reduction interval of a configuration: lower end, measured, upper end.
struct GainInterval {
  double lo, mid, hi;
};

// rough: the claim is a material gain inside kRoughRegime; otherwise its absence inside
// kSmoothRegime. The genuine input is the bounded sampler against the caps sampler; the perturbed
// one the gain's control (rough) or the no-gain control (smooth).
struct GainMeasurement {
  std::vector<GainMeasured> ms = {};
  double z = 0;                 // the interval's quantile (Šidák over the configurations)
  int in = 0, yes = 0, no = 0;  // regime configurations: the claim shown, its opposite shown
  GainInterval worst{0, 0, 0};  // the regime configuration least favourable to the claim
  std::string worst_at = {};
  Verdict verdict = Verdict::kInconclusive;
};
GainMeasurement measure_gain(std::span<const GainMeasured> ms, Input input, bool rough);
Decision decide_gain(const GainMeasurement& m, bool rough);
std::string describe_gain(const GainSizes& z, const GainMeasurement& m, Input input, bool rough);
std::string gain_power(const GainMeasurement& m, bool rough);

// The steps of both claim types (verify/claim.h), which differ only in the regime they read; each
// claim's file adds its id, source, statistic, regime, expected verdict and probe size.
template <bool kRough>
struct GainSteps {
  static constexpr std::string_view kPaper = kPaperVsCaps;

  using Sizes = GainSizes;
  static Sizes sizes(Budget b) { return gain_sizes(b); }

  using Evidence = GainMeasured;
  static int configurations(const Sizes& z) { return int(z.grid.size()); }
  static Evidence observe(const Sizes& z, int k, std::uint64_t) { return observe_gain(z, k); }

  using Measured = GainMeasurement;
  static Measured measure(const Sizes&, std::span<const Evidence> e, Input input) {
    return measure_gain(e, input, kRough);
  }
  static Decision decide(const Sizes&, const Measured& m) { return decide_gain(m, kRough); }
  static std::string describe(const Sizes& z, const Measured& m, Input input) {
    return describe_gain(z, m, input, kRough);
  }
  static std::string power(const Sizes&, const Measured& m, const Measured&) {
    return gain_power(m, kRough);
  }
};

}  // namespace glintlab::verify::eto_claims

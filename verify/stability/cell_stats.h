// One cell of a stability map (claim all.stability): a model evaluated and sampled at one
// parameter setting and one incidence, and what went wrong there — NaN, Inf and negative values
// of eval's value and pdf and of sample()'s record (double and float instantiations), the white
// furnace albedo and its error, probabilities above one, and the relative variance of the weight.
//
// Conventions. Probability intermediate: an entry of kIntermediates named `p` or starting with
// `p_` (p_clamped, p_glint, ...) is a probability, except one ending in `_unclamped` (the raw value
// a model clamps, which may exceed 1 by design); a value above 1 there is counted. Energy gain:
// the directional albedo ρ(ωi) = ∫ f cos dωo (the white furnace with F = 1) estimated as the mean
// sample weight (rejected samples count 0) and, independently, as 4π × the mean value at uniform
// directions; a gain is significant where an estimate exceeds 1 by more than kGainSigmas standard
// errors plus kGainRounding. Models that need an area light (kNeedsAreaLight) return L_o/L_i, the
// BRDF integrated over the light's cone of solid angle Ω, not f cos: their two estimates are
// divided by Ω (furnace_light_solid_angle). Models that need the pixel-corner reflection vectors
// get those of pixel_corner_reflections.
//
// Variance blow-up: the relative variance Var(w)/E(w)² of the sample weight a renderer averages at
// one pixel, so measured at a fixed surface position (and footprint), drawing only the sampler's
// random numbers: at each of kVariancePositions positions per cell, uniform on [0, 1)² and fixed
// before sampling, budget.samples samples; the worst position is the cell's. A position whose
// estimate exceeds the bound is measured again with kVarianceConfirmFactor times as many fresh
// samples, and that estimate is the position's: a heavy-tailed weight below the bound exceeds it
// now and then in one estimate of a few hundred samples, and rarely twice. Drawing a new
// position per sample instead (as the furnace estimates above do) would add the spatial variance
// of a glint model's reflectance — one glint at a few positions in a hundred — which a renderer
// resolves by its pixels, not by its sampler. The weight is the furnace's (divided by Ω for
// area lights), so E(w) is the pixel's value on a scale where a white surface is 1, and a position
// darker than kDarkAlbedo (one step of an 8-bit display of that white; no glint in the footprint
// there, or only the far tails of its lobes, E(w) ~ 1e-26) is judged against kDarkAlbedo instead of
// its own vanishing mean: the cell's statistic is Var(w)/max(E(w), kDarkAlbedo)². The bound: N
// samples give a pixel the relative standard error √(Var(w)/E(w)² / N), and a blow-up is a weight
// whose pixel is still noisier than kReferenceRelativeError at kReferenceSpp samples, the
// reference renders of Kemppinen et al. 2025 Fig. 7 (the papers' largest sample count, used there
// to validate glint importance sampling).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include "verify/stability/sweep_plan.h"

namespace glintlab::verify::stability {

inline constexpr double kGainSigmas = 4;
inline constexpr double kGainRounding = 1e-9;
inline constexpr double kReferenceSpp = 8192;
inline constexpr double kReferenceRelativeError = 0.1;
inline constexpr double kVarianceBlowup =
    kReferenceSpp * kReferenceRelativeError * kReferenceRelativeError;  // 81.92
inline constexpr double kDarkAlbedo = 1.0 / 256;
inline constexpr std::uint64_t kVariancePositions = 4;
inline constexpr std::uint64_t kVarianceConfirmFactor = 4;

// True for an intermediate name that is a probability (see above).
bool is_probability_name(std::string_view name);

struct Defects {
  std::uint64_t nan = 0, inf = 0, negative = 0;
  void add(double x) {
    if (x != x)
      ++nan;
    else if (x == std::numeric_limits<double>::infinity() ||
             x == -std::numeric_limits<double>::infinity())
      ++inf;
    else if (x < 0)
      ++negative;
  }
  // One record of several numbers: counts once per kind present among them.
  void add_record(std::initializer_list<double> xs, std::initializer_list<double> signed_free);
  bool any() const { return nan + inf + negative > 0; }
};

struct CellStats {
  std::uint64_t evals = 0;           // eval calls (uniform directions, special ones, sampled ones)
  std::uint64_t samples = 0;         // sample() calls
  Defects value, pdf, sample;        // double: eval value; eval pdf and pdf(); sample record
  Defects value_f, pdf_f, sample_f;  // the float instantiation (zero counts where absent)
  std::uint64_t evals_f = 0, samples_f = 0;
  std::uint64_t pdf_calls = 0, pdf_calls_f = 0;  // eval's pdf plus pdf() at sampled directions
  std::uint64_t p_evals = 0, p_above_one = 0;    // probability intermediates checked / above 1
  double p_max = 0;                              // largest probability seen (finite ones)
  std::uint64_t accepted = 0;                    // samples not rejected
  double albedo = 0, albedo_error = 0;           // mean weight and its standard error
  double albedo_uniform = 0, albedo_uniform_error = 0;  // 4π mean value at uniform directions
  // Var(w)/max(E(w), kDarkAlbedo)² at the worst of the fixed positions, and the positions at
  // least kDarkAlbedo bright (E(w) ≥ kDarkAlbedo); zero until measure_fixed_position_variance.
  double relative_variance = 0;
  std::uint64_t variance_samples = 0, positions_reflecting = 0;
  double weight_max = 0;
  double light_solid_angle = 0;  // Ω the furnace estimates are divided by (area lights), else 0

  double gain() const;  // largest significant albedo − 1 of the two estimates, else 0
  bool energy_gain() const { return gain() > 0; }
  bool variance_blowup() const { return relative_variance > kVarianceBlowup; }
  bool double_defect() const { return value.any() || pdf.any() || sample.any(); }
  bool float_defect() const { return value_f.any() || pdf_f.any() || sample_f.any(); }
};

struct CellBudget {
  std::uint64_t uniform_evals;  // eval at uniformly distributed ωo on the sphere
  std::uint64_t samples;        // sample(), then eval and pdf() at each sampled ωo; and sample()
                                // at each of the kVariancePositions fixed positions
};

// The incidence at polar angle θ (degrees) and a generic azimuth off the anisotropy axes: the
// incidence() of verify/claims/gof_family.h, shared with the chi-square claims.
Vec3<double> incidence_at(double theta_deg);

// The footprint's corner reflection vectors (core/model.h FootprintQuery::corner_r) the sweep
// gives kNeedsPixelCorners models: ωi mirrored about the normals at the pixel corners of a mirror
// of unit curvature whose footprint has side s, normalize(±s/2, ±s/2, 1); the reflection space
// spans about 2s radians about the mirror direction (a zero s: one direction).
std::array<Vec3<double>, 4> pixel_corner_reflections(const Vec3<double>& wi, double s);

// Ω of the light an area-light model integrates over: its intermediate `solid_angle` where it has
// one (a light it builds itself, evaluated at ωo = +z), else the query's cone 2π(1 − cos γ); 0 for
// models without kNeedsAreaLight.
double furnace_light_solid_angle(const ModelEntry& m, const std::vector<double>& values,
                                 const ModelQuery<double>& q);

// Measures one cell, all but the fixed-position variance. The query's footprint and light follow
// the plane's axis and `row`. Deterministic: every random number is counter_uniform(seed, i, d).
CellStats measure_cell(const SweepTarget& target, const SweepPlane& plane, double row,
                       double theta_deg, const CellBudget& budget, std::uint64_t seed);

// Adds the variance blow-up's measurement (relative_variance, variance_samples,
// positions_reflecting) to a cell measure_cell measured with the same arguments. Its own counter
// indices and dimensions: the cell's other numbers are the same with or without it, in any order.
void measure_fixed_position_variance(CellStats& c, const SweepTarget& target,
                                     const SweepPlane& plane, double row, double theta_deg,
                                     const CellBudget& budget, std::uint64_t seed);

}  // namespace glintlab::verify::stability

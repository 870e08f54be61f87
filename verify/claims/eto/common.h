// What Eto & Tokuyoshi's claims share: the paper's name, the configuration grid, the two samplers
// compared (Dupuy & Benyoub's spherical caps and Listing 1's bounded caps), and the exact albedo,
// second moments and rejection rate by cubature that the Monte Carlo measurements are held to.
// eto.variance-rough and eto.variance-smooth share their measurement too: gain.h.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/math/vec.h"
#include "core/models/smooth_ggx.h"
#include "core/ndf/ggx.h"
#include "core/samplers/sample.h"
#include "verify/check.h"
#include "verify/stats/mean_tests.h"

namespace glintlab::verify::eto_claims {

inline constexpr std::string_view kPaper = "Eto & Tokuyoshi 2023";
// The estimator claims compare the bounded sampler with the one it modifies.
inline constexpr std::string_view kPaperVsCaps = "Eto & Tokuyoshi 2023 (vs Dupuy & Benyoub 2023)";

struct Config {
  double ax, ay, theta_deg;
  GGX<double> ggx() const { return {ax, ay}; }
};

// Incidence at polar angle θ (degrees) and a generic azimuth (so anisotropy is not axis-aligned).
Vec3<double> incidence(double theta_deg);
// The direction at polar angle θ and azimuth φ (radians).
Vec3<double> direction(double theta, double phi);

std::string describe_config(const Config& c);  // "αx=… αy=… θi=…°"

// Every α × anisotropy αx/αy × incidence θi (degrees), in that order.
std::vector<Config> grid_of(const std::vector<double>& alphas, const std::vector<double>& ratios,
                            const std::vector<double>& thetas);
// α ∈ [0.05, 1] × anisotropy αx/αy × incidence θi, for the estimator checks.
std::vector<Config> estimator_grid(Budget b);

// The two samplers Eto & Tokuyoshi compare, as their rows of smooth_ggx's sampler list
// (core/samplers/sampler_list.h): Dupuy & Benyoub 2023's spherical caps and Listing 1's bound.
enum class Technique : int {
  kSphericalCaps = SmoothGGX::Choices::find("spherical_caps"),
  kBounded = SmoothGGX::Choices::find("bounded_caps", "listing1"),
};
std::string_view to_string(Technique t);  // the smooth_ggx `sampler` value

// Sample i of a technique for the given seed (counter RNG: the value depends on (seed, i) only).
MicrofacetSample<double> draw(Technique t, const Config& c, std::uint64_t seed, std::uint64_t i);
// Its Monte Carlo weight f·cos/pdf with F = 1 (0 for a rejected sample).
double weight(Technique t, const Config& c, std::uint64_t seed, std::uint64_t i);
// Samples first … first + count − 1 of a technique in one call of the smooth_ggx model's SIMD
// batch (core/simd/model_batch.h sample_batch, double, on simd::default_isa(): GLINTLAB_ISA or
// the widest ISA of this CPU), with draw()'s uniforms: weight[j] and rejected[j] (1 or 0) are
// weight(t, c, seed, first + j) and draw(…).rejected bit for bit on the scalar ISA and within the
// batches' budgets (docs/simd.md "Equivalence budgets") on the others.
void draw_batch(Technique t, const Config& c, std::uint64_t seed, std::uint64_t first,
                std::size_t count, double* weight, double* rejected);
// Samples 0 … n − 1 of a technique in chunks of kBatchChunk (one draw_batch each, run in parallel),
// merged in chunk order, so the result does not depend on the thread count: the accumulated
// weights (power 1) or squared weights (power 2), and the number of rejected samples.
inline constexpr std::uint64_t kBatchChunk = 4096;
inline constexpr std::size_t kChunksPerTask = 4;  // accumulate_weights: chunks summed side by side
MeanAccumulator accumulate_weights(Technique t, const Config& c, std::uint64_t seed,
                                   std::uint64_t n, int power);
std::uint64_t count_rejected(Technique t, const Config& c, std::uint64_t seed, std::uint64_t n);

// Exact quantities by adaptive cubature over the half vector (dωo = 4 (ωi·h) dh), each with its
// error estimate: the albedo E = ∫ f cos dωo, and the second moments ∫ (f cos)²/p dωo of both
// techniques' weights (so the exact per-sample variance is M2 − E²).
struct Moments {
  double albedo = 0, albedo_error = 0;
  double m2_caps = 0, m2_caps_error = 0;
  double m2_bounded = 0, m2_bounded_error = 0;
};
Moments moments_by_cubature(const Config& c, bool second_moments);

// Exact probability that the spherical-cap sampler's ωo lies below the surface: ∫ of its
// density (Eq. 7 × 1/(4|o·m|)) over the lower hemisphere, by cubature; and its error estimate.
struct Rate {
  double value = 0, error = 0;
};
Rate caps_rejection_by_cubature(const Config& c);

}  // namespace glintlab::verify::eto_claims

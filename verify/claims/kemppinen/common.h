// What Kemppinen et al.'s claims share: the paper's name, the directions and positions the glint
// claims evaluate D★ at, the two NDFs, the interval test against a tolerance band, the relative
// bias against the brute-force Eq. 5, and the measurement of Eq. 11 against Eq. 5 per setting that
// kemppinen.compensation and kemppinen.compensation-k16 both make (core/glints/kemppinen*.h).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/glints/kemppinen.h"
#include "core/math/vec.h"
#include "core/ndf/ndf_kind.h"

namespace glintlab::verify::kemppinen_claims {

inline constexpr std::string_view kPaper = "Kemppinen et al. 2025";

using V2 = Vec2<double>;
using V3 = Vec3<double>;
using P = kemppinen2025::Params<double>;

// The direction at polar angle theta_deg and the azimuth kIncidencePhi (verify/claims/gof_family.h).
V3 direction(double theta_deg);

// A uniform position in a 1000 × 1000 uv square (far larger than any footprint used).
V2 position(std::uint64_t seed, std::uint64_t i);

struct Ndfs {
  bool ggx;
  double alpha;
};

// f(GGX<double>{α, α}) or f(Beckmann<double>{α, α}).
template <class F>
decltype(auto) with_ndf(const Ndfs& n, F&& f) {
  return glintlab::with_ndf(ndf_kind(n.ggx), n.alpha, n.alpha, std::forward<F>(f));
}

const char* ndf_name(const Ndfs& n);

// An interval test against a tolerance band: within when the whole interval is inside it, beyond
// when the whole interval is outside, undecided (inconclusive) otherwise.
enum class Band { kWithin, kUndecided, kBeyond };
Band band(double estimate, double half_width, double tolerance);

// A relative bias Σ(model − ref)/Σ ref over positions and its standard error (the ratio
// estimator's linearisation).
struct RelBias {
  double bias = 0, se = 0;
};
RelBias rel_bias(const std::vector<double>& model, const std::vector<double>& ref);

// ---- Eq. 11 against the brute-force Eq. 5 (kemppinen.compensation, .compensation-k16) ---------

// ±3 %: about the smallest brightness step seen between neighbouring regions of a smooth
// background (the Weber fraction of luminance is 1–2 % at best), the scale at which "works well"
// and "good enough", judged by eye on images (Fig. 2), can be read.
inline constexpr double kCompTolerance = 0.03;
// The brute force sums every point within this many standard deviations of the filter and of the
// lobe: what it leaves out is below 1.2e-6 of either Gaussian's mass, against a tolerance of 3e-2.
inline constexpr double kCompReferenceSigmas = 5;
inline constexpr int kCompSide = 2;  // k = side², the paper's k = 4

struct CompConfig {
  Ndfs ndf;
  double alpha_star, theta, cells;  // cells: the filter's σ in level-0 cells
};

// "GGX α★=0.02 θ=30° footprint 16 cells".
std::string comp_setting(const CompConfig& c);

// The cost of one setting: the brute force's (spatial cell, angular cell) pairs to spend, and the
// fewest and most positions.
struct CompSize {
  double pairs;
  std::uint64_t min, max;
};

// One setting's evaluations per position (channel x; white facets).
struct CompSamples {
  std::vector<double> ref;    // Eq. 5, every point
  std::vector<double> whole;  // Eq. 11, k = side², B(k) over the whole filter + C
  std::vector<double> block;  // Algorithm 1 as implemented: B(k) × 2×2 spatial cells + C
  std::vector<double> no_c;   // Eq. 11 without C
  double explicit_whole = 0;  // Σ of B(k)'s points over the whole filter
  double explicit_block = 0;  // Σ of B(k)'s points in the 2×2 block
  double c_sum = 0;           // Σ C
  double cross_check = 0;     // max |block sum − Algorithm 1's explicit part| / max Eq. 5
};

// Positions for one setting: as many as sz.pairs of the brute force's (spatial cell, angular cell)
// pairs allow at the first position, within [sz.min, sz.max].
std::uint64_t comp_positions(const CompConfig& c, const CompSize& sz, std::uint64_t seed);

// The n positions of `seed`, with k = side² (the same points for every side).
CompSamples sample_comp(const CompConfig& c, std::uint64_t n, std::uint64_t seed, int side);

}  // namespace glintlab::verify::kemppinen_claims

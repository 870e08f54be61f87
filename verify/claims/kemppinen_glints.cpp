// The claims of Kemppinen et al. 2025 on the glinty NDF itself (core/glints/kemppinen*.h):
// kemppinen.convergence (Eq. 2), .compensation (Eq. 9–11, Fig. 14), .roulette (Eq. 8, Fig. 6),
// .furnace (Fig. 15), .constant-time and .sampling-unbiased (Algorithm 2, Fig. 7).
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "core/glints/kemppinen.h"
#include "core/glints/kemppinen_full_sampling.h"
#include "core/glints/kemppinen_reference.h"
#include "core/glints/kemppinen_sampling.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/ndf/ndf_kind.h"
#include "core/render/convergence.h"
#include "core/samplers/walter.h"
#include "verify/claims/claims.h"
#include "verify/claims/gof_family.h"
#include "verify/claims/kemppinen_probes.h"
#include "verify/scenes/kemppinen_env_radiance.h"
#include "verify/scenes/kemppinen_furnace.h"
#include "verify/scenes/kemppinen_presets.h"
#include "verify/stats/mean_tests.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify {
namespace {

using V2 = Vec2<double>;
using V3 = Vec3<double>;
using P = kemppinen2025::Params<double>;
constexpr double kPi = std::numbers::pi;

V3 direction(double theta_deg) {
  const double t = theta_deg * kPi / 180;
  return {std::sin(t) * std::cos(kIncidencePhi), std::sin(t) * std::sin(kIncidencePhi),
          std::cos(t)};
}

// A uniform position in a 1000 × 1000 uv square (far larger than any footprint used).
V2 position(std::uint64_t seed, std::uint64_t i) {
  return {1000 * counter_uniform<double>(seed, i, 0), 1000 * counter_uniform<double>(seed, i, 1)};
}

struct Ndfs {
  bool ggx;
  double alpha;
};

template <class F>
decltype(auto) with_ndf(const Ndfs& n, F&& f) {
  return glintlab::with_ndf(ndf_kind(n.ggx), n.alpha, n.alpha, std::forward<F>(f));
}

const char* ndf_name(const Ndfs& n) { return n.ggx ? "GGX" : "Beckmann"; }

// ---- kemppinen.convergence (Eq. 2) ------------------------------------------------------------
//
// Measure: the mean of D★ (Eq. 4, every grid point summed) over square regions of growing area,
// divided by D(ω_h). Decide: inside the regime, the largest area's mean lies within
// ±kConvergenceTolerance of D (confidence interval, Šidák over the configurations) and the spread
// of region means falls as area^−½ (the pooled slope's interval within ±kSlopeTolerance of −½).
// Control: the same measurement with the prefactor as printed (|J_T| = D/|U_Ω|, Eq. 3–4).

const std::string kConvergence = "kemppinen.convergence";
constexpr double kConvergenceTolerance = 0.02;  // |area mean / D − 1| at the largest area
constexpr double kSlopeTolerance = 0.1;         // |slope of spread vs area + ½|
// The regime, fixed before measuring: Eq. 4's Gaussian lobes are normalised over the whole plane,
// so their area mean can reach D only where the lobe around T(ω_h) lies inside U_Ω. Inside: T(ω_h)
// at least this many lobe widths σ_a from the rim (less than 0.14 % of the mass beyond it).
constexpr double kConvergenceRegimeWidths = 3;
const char* const kConvergenceRegime = "the lobe inside U_Ω: T(ω_h) at least 3 σ_a from the rim";

struct ConvConfig {
  Ndfs ndf;
  double alpha_star, theta;
};

std::vector<ConvConfig> conv_configs() {
  std::vector<ConvConfig> out;
  for (bool ggx : {true, false})
    for (double s : {0.01, 0.05, 0.2})
      // θ up to 35°: at α = 0.3 Beckmann's D is e^{−5.4} there, past 60° below 1e-14.
      for (double t : {0.0, 20.0, 35.0}) out.push_back({{ggx, 0.3}, s, t});
  return out;
}

// The level whose angular cells are about one lobe width: res_a σ ∈ [½, 1).
template <class Ndf>
int conv_level(const P& p, const Ndf& ndf, const V3& h) {
  const auto a = kemppinen2025::angular(p, ndf, h);
  const double s = std::min(a.sigma_a.x, a.sigma_a.y);
  return std::clamp(int(std::floor(std::log2(1 / s))) - 1, 0, 12);
}

struct ConvSize {
  std::vector<int> cells;  // region sides, in cells of the chosen level
  int regions;
};
ConvSize conv_size(Budget b) {
  return b == Budget::kQuick ? ConvSize{{8, 16, 32}, 96} : ConvSize{{8, 16, 32, 64, 128}, 96};
}

struct ConvMeasured {
  double rim_widths = 0;       // distance of T(ω_h) to the rim of U_Ω, in lobe widths
  MeanAccumulator ratio;       // region mean / D at the largest area, one value per region
  std::vector<double> spread;  // per area: standard deviation of region mean / D over the regions
  double slope = 0, slope_se = 0;  // of log spread against log area, and its standard error
};

bool in_convergence_regime(const ConvMeasured& m) {
  return m.rim_widths >= kConvergenceRegimeWidths;
}

// Weighted least squares of log spread on log area; each log standard deviation from n regions
// has variance ≈ 1/(2(n − 1)) (normal samples).
void fit_spread_slope(ConvMeasured& m, const ConvSize& sz) {
  const std::size_t k = sz.cells.size();
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < k; ++i) {
    mx += std::log(sqr(double(sz.cells[i]))) / double(k);
    my += std::log(m.spread[i]) / double(k);
  }
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const double x = std::log(sqr(double(sz.cells[i]))) - mx;
    sxx += x * x;
    sxy += x * (std::log(m.spread[i]) - my);
  }
  m.slope = sxy / sxx;
  m.slope_se = std::sqrt(1 / (2.0 * (sz.regions - 1)) / sxx);
}

ConvMeasured measure_conv(const ConvConfig& c, const ConvSize& sz, std::uint64_t seed,
                          kemppinen2025::Normalization norm) {
  P p = kemppinen2025::preset_params(1, c.alpha_star, seed);
  p.normalization = norm;
  const V3 h = direction(c.theta);
  return with_ndf(c.ndf, [&](const auto& ndf) {
    ConvMeasured m;
    const auto ang = kemppinen2025::angular(p, ndf, h);
    const double to_rim = 0.5 - std::hypot(ang.x_a.x - 0.5, ang.x_a.y - 0.5);
    m.rim_widths = to_rim / std::max(ang.sigma_a.x, ang.sigma_a.y);
    const double d = ndf.D(h);
    const int level = conv_level(p, ndf, h);
    for (int cells : sz.cells) {
      MeanAccumulator acc;
      for (int k = 0; k < sz.regions; ++k)
        acc.add(kemppinen2025::region_mean(p, ndf, h, level, std::int64_t(k) * 100000, 7, cells) /
                d);
      m.spread.push_back(std::sqrt(acc.variance()));
      if (cells == sz.cells.back()) m.ratio = acc;
    }
    fit_spread_slope(m, sz);
    return m;
  });
}

struct ConvDecision {
  Verdict verdict = Verdict::kInconclusive;
  double z = 0;         // two-sided normal quantile of the per-configuration level
  double worst_in = 0;  // largest |bias| + z·SE inside the regime (the interval's far end)
  double least_in = 0;  // largest |bias| − z·SE inside the regime (the interval's near end)
  double pooled_slope = 0, pooled_slope_se = 0;  // inside the regime, inverse-variance weighted
  bool all_within = false;  // every configuration's bias interval inside ±tolerance
};

double bias_se(const ConvMeasured& m) { return std::sqrt(m.ratio.variance() / double(m.ratio.n)); }

// The far end of one configuration's bias interval: within tolerance when ≤ kConvergenceTolerance.
double bias_bound(const ConvMeasured& m, double z) {
  return std::abs(m.ratio.mean - 1) + z * bias_se(m);
}

// An interval test against a tolerance band: within when the whole interval is inside it, beyond
// when the whole interval is outside, undecided (inconclusive) otherwise.
enum class Band { kWithin, kUndecided, kBeyond };
Band band(double estimate, double half_width, double tolerance) {
  if (std::abs(estimate) + half_width <= tolerance) return Band::kWithin;
  if (std::abs(estimate) - half_width > tolerance) return Band::kBeyond;
  return Band::kUndecided;
}

ConvDecision decide_convergence(const std::vector<ConvMeasured>& ms) {
  ConvDecision d;
  d.z = normal_quantile(1 - sidak_level(check_level(), ms.size()) / 2);
  double sum_w = 0;
  int in = 0;
  Band bias = Band::kWithin;
  d.all_within = true;
  for (const ConvMeasured& m : ms) {
    const Band b = band(m.ratio.mean - 1, d.z * bias_se(m), kConvergenceTolerance);
    d.all_within = d.all_within && b == Band::kWithin;
    if (!in_convergence_regime(m)) continue;
    ++in;
    bias = std::max(bias, b);
    d.worst_in = std::max(d.worst_in, bias_bound(m, d.z));
    d.least_in = std::max(d.least_in, std::abs(m.ratio.mean - 1) - d.z * bias_se(m));
    const double w = 1 / sqr(m.slope_se);
    sum_w += w;
    d.pooled_slope += w * m.slope;
  }
  if (in == 0) return d;  // nothing measured inside the regime: inconclusive
  d.pooled_slope /= sum_w;
  d.pooled_slope_se = 1 / std::sqrt(sum_w);
  const Band slope = band(d.pooled_slope + 0.5, d.z * d.pooled_slope_se, kSlopeTolerance);
  const Band worst = std::max(bias, slope);
  if (worst == Band::kBeyond)
    d.verdict = Verdict::kFails;
  else if (worst == Band::kUndecided)
    d.verdict = Verdict::kInconclusive;
  else
    d.verdict = d.all_within ? Verdict::kHoldsWithin : Verdict::kHoldsInRegime;
  return d;
}

std::string describe_convergence(const std::vector<ConvConfig>& cfg,
                                 const std::vector<ConvMeasured>& ms, const ConvDecision& d,
                                 const ConvSize& sz) {
  int in = 0;
  double worst_out = 0;
  std::string worst_out_at;
  for (std::size_t i = 0; i < ms.size(); ++i) {
    if (in_convergence_regime(ms[i])) {
      ++in;
      continue;
    }
    const double bias = ms[i].ratio.mean - 1;
    if (std::abs(bias) > std::abs(worst_out)) {
      worst_out = bias;
      worst_out_at =
          fmt::format("{} α★={:g} θ={:g}°, T(ω_h) {:.2g} σ_a from the rim", ndf_name(cfg[i].ndf),
                      cfg[i].alpha_star, cfg[i].theta, ms[i].rim_widths);
    }
  }
  std::string outside = in == int(ms.size())
                            ? std::string("every configuration is inside the regime")
                            : fmt::format(
                                  "outside the regime ({} configurations) the mean stays "
                                  "below D: worst bias {:+.3g} at {}",
                                  ms.size() - in, worst_out, worst_out_at);
  return fmt::format(
      "area mean of D★ / D over {} regions of up to {}² cells, {} configurations, {} inside the "
      "regime: there |bias| ≤ {:.3g} (bound at z = {:.2f}; tolerance {:g}) and the spread of "
      "region means falls with area as area^{:.3f} ± {:.3f} (−½ expected, tolerance ±{:g}); {}",
      sz.regions, sz.cells.back(), ms.size(), in, d.worst_in, d.z, kConvergenceTolerance,
      d.pooled_slope, d.pooled_slope_se, kSlopeTolerance, outside);
}

std::vector<ConvMeasured> measure_convergence(Budget b, kemppinen2025::Normalization norm) {
  const auto cfg = conv_configs();
  const ConvSize sz = conv_size(b);
  std::vector<ConvMeasured> ms(cfg.size());
  tbb::parallel_for(std::size_t(0), cfg.size(), [&](std::size_t i) {
    ms[i] = measure_conv(cfg[i], sz, check_seed(kConvergence, i), norm);
  });
  return ms;
}

CheckResult run_convergence(Budget b) {
  const auto cfg = conv_configs();
  const ConvSize sz = conv_size(b);
  const auto ms = measure_convergence(b, kemppinen2025::Normalization::kCorrected);
  const ConvDecision d = decide_convergence(ms);
  const auto printed = measure_convergence(b, kemppinen2025::Normalization::kPrinted);
  const ConvDecision dc = decide_convergence(printed);
  CheckResult r;
  r.configurations = int(cfg.size());
  r.verdict = d.verdict;
  if (d.verdict == Verdict::kHoldsInRegime) r.regime = kConvergenceRegime;
  r.statistic = "largest |area mean of D★ / D − 1| + z·SE inside the regime, largest area";
  r.value = d.worst_in;
  r.bound = kConvergenceTolerance;
  double se_max = 0;
  for (const ConvMeasured& m : ms)
    if (in_convergence_regime(m)) se_max = std::max(se_max, bias_se(m));
  r.power = fmt::format(
      "a remaining bias of {:.3g} (tolerance + (z + 1.28)·SE, largest SE in the regime {:.2g}) is "
      "detected with 90 % power; a slope off −½ by {:.3g}",
      kConvergenceTolerance + (d.z + 1.2816) * se_max, se_max,
      kSlopeTolerance + (d.z + 1.2816) * d.pooled_slope_se);
  r.control = fmt::format(
      "prefactor as printed (|J_T| = D/|U_Ω|, Eq. 3–4): inside the regime |bias| ≤ {:.3g}, "
      "slope {:.3f}",
      dc.worst_in, dc.pooled_slope);
  record_control(r, dc.verdict);
  r.detail = describe_convergence(cfg, ms, d, sz);
  return r;
}

// ---- kemppinen.compensation (Eq. 9–11, Sec. 3.3.4) ----------------------------------------------
//
// Measure: per setting, over random positions, Eq. 11 with k = 4 (the points of B(k), the
// compensation C of Eq. 10 for the rest) against the brute-force Eq. 5: every point, the same
// points, the same Gaussian filter and LOD (core/glints/kemppinen_reference.h); the relative bias
// Σ(D★^f − Eq. 5) / Σ Eq. 5. The explicit sum over B(k) runs over the whole filter, as Sec. 3.3.4
// assumes ("the small spatial neighborhood is always large enough to cover the pixel filter"), so
// the error measured is that of the angular approximation the sentence is about; the spatial
// truncation (Algorithm 1's 2×2 block against the whole filter) is measured beside it, not judged.
// Decide: "most cases" is more than half of the settings where C carries at least
// kCompActiveShare of D★^f (elsewhere B(k) holds the lobe and Eq. 11 is Eq. 5), each classed by
// its interval (Šidák) against ±kCompTolerance. Control: Eq. 5 itself kCompControlFar too bright
// (a claim that holds must fail) or kCompControlNear (a claim that fails must hold), through the
// same decision.

const std::string kCompensation = "kemppinen.compensation";
// ±3 %: about the smallest brightness step seen between neighbouring regions of a smooth
// background (the Weber fraction of luminance is 1–2 % at best), the scale at which "works well"
// and "good enough", judged by eye on images (Fig. 2), can be read. Shares at ±1 % and ±10 % are
// reported beside it.
constexpr double kCompTolerance = 0.03;
constexpr double kCompMost = 0.5;          // "most": more than this share of the judged settings
constexpr double kCompActiveShare = 0.05;  // C's share of D★^f for a setting to be judged
constexpr double kCompControlFar = 0.04;   // the control's offset from Eq. 5 (claim holding)
constexpr double kCompControlNear = 0.01;  // the control's offset from Eq. 5 (claim failing)
// The brute force sums every point within this many standard deviations of the filter and of the
// lobe: what it leaves out is below 1.2e-6 of either Gaussian's mass, against a tolerance of 3e-2.
constexpr double kCompReferenceSigmas = 5;
constexpr int kCompSide = 2;  // k = side², the paper's k = 4

struct CompConfig {
  Ndfs ndf;
  double alpha_star, theta, cells;  // cells: the filter's σ in level-0 cells
};

// The grid, declared before measuring: GGX and Beckmann (α = 0.3); α★ from highly specular to
// rough particles; θ taking T(ω_h) from the centre of U_Ω to near its rim; footprints from the
// near field (the lobe inside B(k)) to where C carries nearly all of D★^f. The brute force's cost
// grows as (α★ · footprint)², which bounds the footprints.
std::vector<CompConfig> comp_configs(Budget b) {
  std::vector<CompConfig> out;
  const std::vector<double> cells = b == Budget::kQuick
                                        ? std::vector<double>{4, 16, 64}
                                        : std::vector<double>{2, 4, 8, 16, 32, 64, 128};
  for (bool ggx : {true, false})
    for (double s : {0.005, 0.02, 0.1})
      for (double t : ggx ? std::vector<double>{0, 30, 60} : std::vector<double>{0, 20, 40})
        for (double c : cells) out.push_back({{ggx, 0.3}, s, t, c});
  return out;
}

// The cost of one setting: the brute force's (spatial cell, angular cell) pairs to spend, and the
// fewest and most positions.
struct CompSize {
  double pairs;
  std::uint64_t min, max;
};
CompSize comp_size(Budget b) {
  return b == Budget::kQuick ? CompSize{1.5e7, 24, 400} : CompSize{6e7, 48, 2000};
}

// A relative bias Σ(model − ref)/Σ ref over positions and its standard error (the ratio
// estimator's linearisation).
struct RelBias {
  double bias = 0, se = 0;
};
RelBias rel_bias(const std::vector<double>& model, const std::vector<double>& ref) {
  const std::size_t n = ref.size();
  double sm = 0, sr = 0;
  for (std::size_t i = 0; i < n; ++i) sm += model[i], sr += ref[i];
  if (n < 2 || sr <= 0) return {};
  const double bias = (sm - sr) / sr;
  double ss = 0;
  for (std::size_t i = 0; i < n; ++i) ss += sqr(model[i] - ref[i] - bias * ref[i]);
  return {bias, std::sqrt(ss / double(n * (n - 1))) / (sr / double(n))};
}

// One setting's evaluations per position (channel x; white facets).
struct CompSamples {
  std::vector<double> ref;    // Eq. 5, every point
  std::vector<double> whole;  // Eq. 11, k = 4, B(k) over the whole filter + C
  std::vector<double> block;  // Algorithm 1 as implemented: B(k) × 2×2 spatial cells + C
  std::vector<double> no_c;   // Eq. 11 without C (the broken input of the tests)
  double explicit_whole = 0;  // Σ of B(k)'s points over the whole filter
  double explicit_block = 0;  // Σ of B(k)'s points in the 2×2 block
  double c_sum = 0;           // Σ C
  double cross_check = 0;     // max |block sum − Algorithm 1's explicit part| / max Eq. 5
};

// Positions for one setting: as many as sz.pairs of the brute force's (spatial cell, angular cell)
// pairs allow at the first position, within [sz.min, sz.max].
std::uint64_t comp_positions(const CompConfig& c, const CompSize& sz, std::uint64_t seed) {
  const P p = kemppinen2025::preset_params(kCompSide, c.alpha_star, seed);
  return with_ndf(c.ndf, [&](const auto& ndf) {
    std::int64_t visited = 0;
    kemppinen2025::reference_filtered_parts(
        p, ndf, kemppinen2025::footprint_cells(position(seed, 0), c.cells, p), direction(c.theta),
        kCompSide, kCompReferenceSigmas, &visited);
    const double n = sz.pairs / double(std::max<std::int64_t>(visited, 1));
    return std::clamp<std::uint64_t>(std::uint64_t(n), sz.min, sz.max);
  });
}

// The n positions of `seed`, with k = side² (the same points for every side).
CompSamples sample_comp(const CompConfig& c, std::uint64_t n, std::uint64_t seed, int side) {
  CompSamples s;
  const P p = kemppinen2025::preset_params(side, c.alpha_star, seed);
  const V3 h = direction(c.theta);
  with_ndf(c.ndf, [&](const auto& ndf) {
    double peak = 0, worst = 0;
    for (std::uint64_t i = 0; i < n; ++i) {
      const auto fp = kemppinen2025::footprint_cells(position(seed, i), c.cells, p);
      const auto ref =
          kemppinen2025::reference_filtered_parts(p, ndf, fp, h, side, kCompReferenceSigmas);
      const auto r = kemppinen2025::eval(p, ndf, fp, h);
      s.ref.push_back(ref.total.x);
      s.whole.push_back(ref.neighbourhood.x + r.compensation_part.x);
      s.block.push_back(r.d.x);
      s.no_c.push_back(ref.neighbourhood.x);
      s.explicit_whole += ref.neighbourhood.x;
      s.explicit_block += ref.block.x;
      s.c_sum += r.compensation_part.x;
      peak = std::max(peak, ref.total.x);
      worst = std::max(worst, std::abs(ref.block.x - r.explicit_part.x));
    }
    s.cross_check = peak > 0 ? worst / peak : 0;
    return 0;
  });
  return s;
}

struct CompMeasured {
  CompConfig c;
  std::size_t n = 0;
  double c_share = 0;      // Σ C / Σ D★^f (whole filter)
  double block_share = 0;  // Σ explicit in the 2×2 block / Σ explicit over the whole filter
  double cross_check = 0;
  RelBias whole, block, no_c;  // against Eq. 5
};

CompMeasured measure_comp(const CompConfig& c, const CompSize& sz, std::uint64_t seed) {
  const CompSamples s = sample_comp(c, comp_positions(c, sz, seed), seed, kCompSide);
  CompMeasured m;
  m.c = c;
  m.n = s.ref.size();
  double whole = 0;
  for (double v : s.whole) whole += v;
  m.c_share = whole > 0 ? s.c_sum / whole : 0;
  m.block_share = s.explicit_whole > 0 ? s.explicit_block / s.explicit_whole : 1;
  m.cross_check = s.cross_check;
  m.whole = rel_bias(s.whole, s.ref);
  m.block = rel_bias(s.block, s.ref);
  m.no_c = rel_bias(s.no_c, s.ref);
  return m;
}

bool comp_judged(const CompMeasured& m) { return m.c_share >= kCompActiveShare; }

// What is decided: Eq. 11 (the claim), Eq. 5 offset by a share (the controls), or Eq. 11 without
// C (a deliberately broken input, for the tests).
struct CompInput {
  enum Kind { kEq11, kOffset, kNoC } kind = kEq11;
  double offset = 0;
};

RelBias comp_input(const CompMeasured& m, CompInput in) {
  if (in.kind == CompInput::kOffset) return {in.offset, 0};
  return in.kind == CompInput::kNoC ? m.no_c : m.whole;
}

struct CompDecision {
  Verdict verdict = Verdict::kInconclusive;
  double z = 0;
  int judged = 0, within = 0, beyond = 0;
  RelBias worst;
  std::string worst_at;
};

std::string comp_setting(const CompConfig& c) {
  return fmt::format("{} α★={:g} θ={:g}° footprint {:g} cells", ndf_name(c.ndf), c.alpha_star,
                     c.theta, c.cells);
}

CompDecision decide_compensation(const std::vector<CompMeasured>& ms, CompInput in) {
  CompDecision d;
  for (const CompMeasured& m : ms) d.judged += comp_judged(m);
  if (d.judged == 0) return d;
  d.z = normal_quantile(1 - sidak_level(check_level(), std::size_t(d.judged)) / 2);
  for (const CompMeasured& m : ms) {
    if (!comp_judged(m)) continue;
    const RelBias r = comp_input(m, in);
    const Band b = band(r.bias, d.z * r.se, kCompTolerance);
    d.within += b == Band::kWithin;
    d.beyond += b == Band::kBeyond;
    if (d.worst_at.empty() || std::abs(r.bias) > std::abs(d.worst.bias)) {
      d.worst = r;
      d.worst_at = comp_setting(m.c);
    }
  }
  const double need = kCompMost * d.judged;  // within must exceed it
  if (d.within > need)
    d.verdict = Verdict::kHolds;
  else if (d.judged - d.beyond <= need)
    d.verdict = Verdict::kFails;
  return d;
}

std::string describe_compensation(const std::vector<CompMeasured>& ms, const CompDecision& d) {
  const auto share_within = [&](double tol) {
    int w = 0;
    for (const CompMeasured& m : ms)
      if (comp_judged(m)) w += band(m.whole.bias, d.z * m.whole.se, tol) == Band::kWithin;
    return fmt::format("{} of {}", w, d.judged);
  };
  double idle_worst = 0, cross = 0, share_lo = 1, share_hi = 0, share_sum = 0, block_lo = 1e300,
         block_hi = -1e300;
  std::size_t n_lo = ~std::size_t(0), n_hi = 0;
  std::vector<double> shares;
  for (const CompMeasured& m : ms) {
    cross = std::max(cross, m.cross_check);
    n_lo = std::min(n_lo, m.n);
    n_hi = std::max(n_hi, m.n);
    if (!comp_judged(m)) idle_worst = std::max(idle_worst, std::abs(m.whole.bias));
    if (!comp_judged(m)) continue;
    share_lo = std::min(share_lo, m.block_share);
    share_hi = std::max(share_hi, m.block_share);
    share_sum += m.block_share;
    block_lo = std::min(block_lo, m.block.bias);
    block_hi = std::max(block_hi, m.block.bias);
  }
  std::string beyond_list;
  for (const CompMeasured& m : ms)
    if (comp_judged(m) && band(m.whole.bias, d.z * m.whole.se, kCompTolerance) == Band::kBeyond)
      beyond_list += fmt::format("{}{} {:+.3g}", beyond_list.empty() ? "" : "; ", comp_setting(m.c),
                                 m.whole.bias);
  return fmt::format(
      "Eq. 11 with k = 4 (B(k)'s points over the whole filter, plus C) against the brute-force "
      "Eq. 5 (every point within {:g} σ of filter and lobe, the same points, filter and LOD), {} "
      "settings, {}–{} positions each; C carries ≥ {:.0f} % of D★^f in {} (judged): {} within "
      "±{:g} %, {} beyond (interval at z = {:.2f}); most = more than half. Worst {:+.3g} ± {:.2g} "
      "at {}. Beyond: {}. Within ±1 %: {}; ±3 %: {}; ±10 %: {}. Where C carries less, B(k) holds "
      "the lobe and |bias| ≤ {:.2g}. Measured beside it, not judged — the spatial truncation, in "
      "the judged settings: Algorithm 1's 2×2 spatial block holds {:.1f} % ({:.1f}–{:.1f} % by "
      "setting) of B(k)'s explicit sum over the whole filter (LOD λ = log2(2σ·res): σ is ½ to 1 "
      "cell), and D★^f as implemented (block + C) is off Eq. 5 by {:+.3g} to {:+.3g}. The block's "
      "sum equals Algorithm 1's explicit part to {:.1g} of the largest Eq. 5 value",
      kCompReferenceSigmas, ms.size(), n_lo, n_hi, 100 * kCompActiveShare, d.judged, d.within,
      100 * kCompTolerance, d.beyond, d.z, d.worst.bias, d.worst.se, d.worst_at,
      beyond_list.empty() ? std::string("none") : beyond_list, share_within(0.01),
      share_within(kCompTolerance), share_within(0.1), idle_worst,
      100 * share_sum / std::max(d.judged, 1), 100 * share_lo, 100 * share_hi, block_lo, block_hi,
      cross);
}

std::vector<CompMeasured> measure_compensation(const std::vector<CompConfig>& cfg,
                                               const CompSize& sz, const std::string& id) {
  std::vector<CompMeasured> ms(cfg.size());
  tbb::parallel_for(std::size_t(0), cfg.size(),
                    [&](std::size_t i) { ms[i] = measure_comp(cfg[i], sz, check_seed(id, i)); });
  return ms;
}

CheckResult run_compensation(Budget b) {
  const auto cfg = comp_configs(b);
  const auto ms = measure_compensation(cfg, comp_size(b), kCompensation);
  const CompDecision d = decide_compensation(ms, {CompInput::kEq11});
  const bool holding = is_holding(d.verdict);
  const double offset = holding ? kCompControlFar : kCompControlNear;
  const CompDecision dc = decide_compensation(ms, {CompInput::kOffset, offset});
  CheckResult r;
  r.configurations = int(cfg.size());
  r.verdict = d.verdict;
  r.statistic = fmt::format(
      "share of the settings where C carries ≥ {:.0f} % of D★^f whose k = 4 bias against Eq. 5 "
      "is within ±{:g} % (more than {:g} required)",
      100 * kCompActiveShare, 100 * kCompTolerance, kCompMost);
  r.value = d.judged ? double(d.within) / d.judged : 0;
  r.bound = kCompMost;
  double se_max = 0;
  for (const CompMeasured& m : ms)
    if (comp_judged(m)) se_max = std::max(se_max, m.whole.se);
  r.power = fmt::format(
      "a setting biased by {:.3g} (tolerance + (z + 1.28)·SE, largest SE {:.2g}) is classed "
      "beyond with 90 % power",
      kCompTolerance + (d.z + 1.2816) * se_max, se_max);
  r.control = fmt::format(
      "Eq. 5 itself {:g} % too bright in place of Eq. 11, through the same decision: {} of {} "
      "within ±{:g} %",
      100 * offset, dc.within, dc.judged, 100 * kCompTolerance);
  record_control(r, dc.verdict);
  r.detail = describe_compensation(ms, d);
  return r;
}

// ---- kemppinen.compensation-k16 (Fig. 14 left, Sec. 6) ----------------------------------------
//
// "There are settings where this does not hold, causing the background to brighten before the
// points uniformly cover the surface (far left, using k=4 points), which can be mitigated by
// consider a larger neighborhood (middle left, with k=16 points)"; Sec. 6: "When the
// microroughness is too large, it considers areas outside of U_Ω and becomes visible before the
// glints converge to a uniform mass". The regime, declared before measuring from those sentences:
// T(ω_h) near the rim of U_Ω (at most kK16RimWidths lobe widths from it, so the lobe reaches into
// □ \ U_Ω, where Eq. 10 counts mass no point has); moderate α★; mid-field footprints, where the
// lobe's σ_a is at most kK16MidCells angular cells of level ⌊λ⌋ (the points are not yet a
// uniform mass, and B(16), two cells either side of x_a, holds the lobe's ±2 σ_a where B(4) holds
// ±1 σ_a); and where a pilot on other positions puts k = 4 above Eq. 5 by more than
// kCompTolerance (the brightening). Candidates with σ_a of 1–2 cells are measured and reported
// apart, not judged: there B(16) holds only ±1 σ_a. Measure: the relative bias
// against Eq. 5 of k = 4 and k = 16 (B(k) over the whole filter, as for kemppinen.compensation) on
// the same positions. Decide: k = 16 mitigates a setting when it removes at least kMitigates of
// k = 4's bias (interval of the difference, Šidák over the settings); holds if it does in every
// setting, fails if the interval excludes it in one.

const std::string kCompensationK16 = "kemppinen.compensation-k16";
constexpr double kMitigates = 0.1;  // a tenth of the k = 4 error removed
// The control's distance from kMitigates, in shares of k = 4's error.
constexpr double kK16ControlMargin = 0.02;
constexpr double kK16RimWidths = 3;
constexpr double kK16MidCells = 1;
constexpr double kK16WideCells = 2;  // candidates up to this σ_a, the wider ones reported apart
const char* const kK16Regime =
    "T(ω_h) within 3 σ_a of the rim of U_Ω, α★ 0.05–0.1, σ_a at most one angular cell of level "
    "⌊λ⌋ (mid-field), and k = 4 above Eq. 5 by more than 3 % in a pilot";

// Candidates: T(ω_h) near the rim (GGX θ = 60°, 70°; Beckmann θ = 20°, 30°, 40°), α★ 0.05 and
// 0.1, footprints of 1–64 level-0 cells; the geometry of the regime is checked per candidate.
std::vector<CompConfig> k16_candidates(Budget b) {
  std::vector<CompConfig> out;
  const std::vector<double> cells = b == Budget::kQuick
                                        ? std::vector<double>{2, 4, 16, 64}
                                        : std::vector<double>{1, 2, 4, 8, 16, 32, 64};
  for (bool ggx : {true, false})
    for (double s : {0.05, 0.1})
      for (double t : ggx ? std::vector<double>{60, 70} : std::vector<double>{20, 30, 40})
        for (double c : cells) out.push_back({{ggx, 0.3}, s, t, c});
  return out;
}

// The lobe's σ_a in angular cells of level ⌊λ⌋ where T(ω_h) is near the rim (geometry, without
// measuring); 0 where it is not.
double k16_lobe_cells(const CompConfig& c) {
  const P p = kemppinen2025::preset_params(kCompSide, c.alpha_star, 0);
  return with_ndf(c.ndf, [&](const auto& ndf) {
    const auto ang = kemppinen2025::angular(p, ndf, direction(c.theta));
    const double sigma = std::max(ang.sigma_a.x, ang.sigma_a.y);
    const double rim = 0.5 - std::hypot(ang.x_a.x - 0.5, ang.x_a.y - 0.5);
    const double res_a = std::exp2(std::floor(std::log2(2 * c.cells)));  // 2^⌊λ⌋
    return rim <= kK16RimWidths * sigma ? sigma * res_a : 0.0;
  });
}

struct K16Measured {
  CompConfig c;
  std::size_t n = 0;
  double lobe_cells = 0;        // σ_a in angular cells of level ⌊λ⌋
  double pilot = 0;             // k = 4's bias against Eq. 5 on the pilot's positions
  RelBias k4, k16;              // against Eq. 5, B(k) over the whole filter
  RelBias k4_block, k16_block;  // as implemented (Algorithm 1's spatial blocks)
  RelBias gap;                  // |k4| − |k16| − kMitigates·|k4|, paired over the positions
};

struct K16Gap {
  double gap, se;
};

bool k16_brightens(const K16Measured& m) { return m.pilot > kCompTolerance && m.n > 0; }
bool k16_judged(const K16Measured& m) { return k16_brightens(m) && m.lobe_cells <= kK16MidCells; }

constexpr std::uint64_t kK16PilotSalt = 0x9e3779b97f4a7c15ULL;

K16Measured measure_k16_setting(const CompConfig& c, const CompSize& sz, std::uint64_t seed) {
  K16Measured m;
  m.c = c;
  const CompSize pilot_size{sz.pairs / 4, sz.min, sz.max / 4};
  const std::uint64_t pilot_seed = seed ^ kK16PilotSalt;
  const CompSamples pilot =
      sample_comp(c, comp_positions(c, pilot_size, pilot_seed), pilot_seed, kCompSide);
  m.pilot = rel_bias(pilot.whole, pilot.ref).bias;
  if (m.pilot <= kCompTolerance) return m;  // no brightening: outside the regime
  const std::uint64_t n = comp_positions(c, sz, seed);
  const CompSamples s4 = sample_comp(c, n, seed, 2), s16 = sample_comp(c, n, seed, 4);
  m.n = n;
  m.k4 = rel_bias(s4.whole, s4.ref);
  m.k16 = rel_bias(s16.whole, s16.ref);
  m.k4_block = rel_bias(s4.block, s4.ref);
  m.k16_block = rel_bias(s16.block, s16.ref);
  // The gap as one ratio over the same positions: Eq. 5 + s4·0.9·(k4 − Eq. 5) − s16·(k16 − Eq. 5),
  // s the signs of the biases, so its standard error is the paired one.
  const double sign4 = m.k4.bias < 0 ? -1 : 1, sign16 = m.k16.bias < 0 ? -1 : 1;
  std::vector<double> combined(n);
  for (std::size_t i = 0; i < n; ++i)
    combined[i] = s4.ref[i] + sign4 * (1 - kMitigates) * (s4.whole[i] - s4.ref[i]) -
                  sign16 * (s16.whole[i] - s4.ref[i]);
  m.gap = rel_bias(combined, s4.ref);
  return m;
}

std::vector<K16Measured> measure_k16(Budget b) {
  std::vector<CompConfig> cfg;
  std::vector<double> lobe;
  for (const CompConfig& c : k16_candidates(b)) {
    const double cells = k16_lobe_cells(c);
    if (cells > 0 && cells <= kK16WideCells) cfg.push_back(c), lobe.push_back(cells);
  }
  std::vector<K16Measured> out(cfg.size());
  const CompSize sz = comp_size(b);
  tbb::parallel_for(std::size_t(0), cfg.size(), [&](std::size_t i) {
    out[i] = measure_k16_setting(cfg[i], sz, check_seed(kCompensationK16, i));
    out[i].lobe_cells = lobe[i];
  });
  return out;
}

// The error k = 16 removes, minus the required tenth of k = 4's, with its standard error (paired
// over the positions). With `removed` set, k = 16 is replaced by k = 4's result with that share of
// its error removed (the controls): the gap is (removed − kMitigates)·|k4|, its error alike.
K16Gap k16_gap(const K16Measured& m, std::optional<double> removed = std::nullopt) {
  if (!removed) return {m.gap.bias, m.gap.se};
  return {(*removed - kMitigates) * std::abs(m.k4.bias), std::abs(*removed - kMitigates) * m.k4.se};
}

int k16_count(const std::vector<K16Measured>& ms) {
  return int(std::count_if(ms.begin(), ms.end(), k16_judged));
}

Verdict decide_k16(const std::vector<K16Measured>& ms, std::optional<double> removed, double z) {
  bool all = true, any = false;
  for (const K16Measured& m : ms) {
    if (!k16_judged(m)) continue;
    any = true;
    const K16Gap g = k16_gap(m, removed);
    if (g.gap + z * g.se < 0) return Verdict::kFails;
    all = all && g.gap - z * g.se > 0;
  }
  return any && all ? Verdict::kHoldsInRegime : Verdict::kInconclusive;
}

CheckResult run_compensation_k16(Budget b) {
  const std::vector<K16Measured> ms = measure_k16(b);
  const int judged = k16_count(ms);
  const double z =
      normal_quantile(1 - sidak_level(check_level(), std::size_t(std::max(judged, 1))) / 2);
  CheckResult r;
  r.configurations = int(ms.size());
  r.verdict = decide_k16(ms, std::nullopt, z);
  if (r.verdict == Verdict::kHoldsInRegime) r.regime = kK16Regime;
  // The control, near the decision's edge: k = 16 replaced by k = 4's result with
  // kK16ControlMargin less (a claim that holds: it must fail) or more (a claim that fails: it must
  // hold) of its error removed than the tenth the claim requires.
  const bool holding = is_holding(r.verdict);
  const double removed = kMitigates + (holding ? -kK16ControlMargin : kK16ControlMargin);
  record_control(r, decide_k16(ms, removed, z));
  r.control = fmt::format(
      "k = 4's result with {:.0f} % of its error removed ({} than the {:.0f} % required) in place "
      "of k = 16: {}",
      100 * removed, holding ? "less" : "more", 100 * kMitigates, to_string(*r.control_verdict));
  double worst = 1e300, se = 0, e4_min = 1e300;
  std::string at, rows, wide;
  int brighten = 0;
  for (const K16Measured& m : ms) {
    if (!k16_brightens(m)) continue;
    ++brighten;
    const std::string row = fmt::format(
        "{} (σ_a {:.2g} cells): k = 4 {:+.3g}, k = 16 {:+.3g} (as implemented {:+.3g}, {:+.3g})",
        comp_setting(m.c), m.lobe_cells, m.k4.bias, m.k16.bias, m.k4_block.bias, m.k16_block.bias);
    if (!k16_judged(m)) {
      wide += (wide.empty() ? "" : "; ") + row;
      continue;
    }
    const K16Gap g = k16_gap(m);
    se = std::max(se, g.se);
    e4_min = std::min(e4_min, std::abs(m.k4.bias));
    rows += (rows.empty() ? "" : "; ") + row;
    if (g.gap < worst) worst = g.gap, at = row;
  }
  r.statistic =
      "smallest (|bias k=4| − |bias k=16| − 0.1·|bias k=4|) against Eq. 5 over the regime's "
      "settings";
  r.value = judged ? worst : 0;
  r.bound = 0;
  r.power = judged ? fmt::format(
                         "a removal of {:.2g} beyond the tenth of k = 4's error ({:.2g} % of the "
                         "smallest k = 4 error, {:.3g}) is detected with 90 % power (largest SE "
                         "{:.2g})",
                         (z + 1.2816) * se, 100 * (z + 1.2816) * se / e4_min, e4_min, se)
                   : std::string("no setting in the regime");
  r.detail = fmt::format(
      "regime: {}. Of {} candidates with T(ω_h) near the rim and σ_a ≤ {:g} cells, {} brighten "
      "by more than {:g} % in the pilot, {} of them with σ_a ≤ {:g} cell (judged). Relative bias "
      "against the brute-force Eq. 5 (same points, filter and LOD) on the same positions, B(k) "
      "over the whole filter: {}; k = 16 must remove at least {:.0f} % of k = 4's error in every "
      "setting (interval at z = {:.2f}); least favourable: {}. Not judged (σ_a of 1–2 cells, "
      "wider than B(16) holds): {}",
      kK16Regime, ms.size(), kK16WideCells, brighten, 100 * kCompTolerance, judged, kK16MidCells,
      rows.empty() ? "—" : rows, 100 * kMitigates, z, at.empty() ? "—" : at,
      wide.empty() ? "none" : wide);
  return r;
}

// ---- kemppinen.roulette (Eq. 8, Fig. 6) -------------------------------------------------------
//
// Measure: E_r[s·R(r, w)] − w by the midpoint rule in r (deterministic), and over random positions
// at λ = 2.5 (both levels weighted ½) the paired difference of the explicit D★^f with roulette
// (every point's weight × s) and with linear blending; s = 1 for Eq. 8. Decide: holds-within when
// the expectation is w to kRouletteExact on w ∈ [2ε, 1 − 2ε] and the paired test does not reject
// at the check's level; fails otherwise. Control: the roulette weight off by kRouletteControl
// (s = 1 + kRouletteControl), through the same measure and decision.

const std::string kRoulette = "kemppinen.roulette";
constexpr double kRouletteExact = 1e-4;    // |E_r[R(r, w)] − w|, w ∈ [2ε, 1 − 2ε]
constexpr double kRouletteControl = 0.02;  // the control's relative error of the roulette weight
constexpr double kRouletteLambda = 2.5;    // both levels weighted ½

// max_w |E_r[scale·R(r, w)] − w| over w ∈ [w_lo, w_hi] by the midpoint rule in r.
double roulette_expectation_error(double scale, double w_lo, double w_hi) {
  double worst = 0;
  for (int i = 0; i <= 100; ++i) {
    const double w = w_lo + (w_hi - w_lo) * i / 100;
    double m = 0;
    const int n = 20000;
    for (int j = 0; j < n; ++j) m += scale * kemppinen2025::roulette((j + 0.5) / n, w);
    worst = std::max(worst, std::abs(m / n - w));
  }
  return worst;
}

struct RouletteStats {
  std::uint64_t n = 0;            // positions
  MeanTestResult paired;          // mean(roulette − linear) of the explicit part = 0
  MeanTestResult paired_control;  // the same with the roulette weight × (1 + kRouletteControl)
  double linear_mean = 0;         // mean explicit part with linear blending
  double mid_share_roulette = 0, mid_share_linear = 0;  // points with weight in (0.1, 0.9)·peak
  double peak_roulette = 0, peak_linear = 0;            // mean weight of points with weight > 0.01
};

RouletteStats run_roulette_stats(std::uint64_t n, std::uint64_t seed) {
  RouletteStats s;
  s.n = n;
  P p = kemppinen2025::preset_params(2, 0.02, seed);
  const GGX<double> ggx{0.3, 0.3};
  const V3 h = direction(20);
  const double cells = std::exp2(kRouletteLambda) / 2;
  MeanAccumulator diff, diff_c, lin_acc;
  for (std::uint64_t i = 0; i < n; ++i) {
    const FootprintQuery<double> fp = kemppinen2025::footprint_cells(position(seed, i), cells, p);
    p.blend = kemppinen2025::Blend::kRoulette;
    const double rou = kemppinen2025::eval(p, ggx, fp, h).explicit_part.x;
    p.blend = kemppinen2025::Blend::kLinear;
    const double lin = kemppinen2025::eval(p, ggx, fp, h).explicit_part.x;
    diff.add(rou - lin);
    diff_c.add((1 + kRouletteControl) * rou - lin);
    lin_acc.add(lin);
  }
  s.paired = t_test(diff, 0);
  s.paired_control = t_test(diff_c, 0);
  s.linear_mean = lin_acc.mean;
  // Per-point weights at w = ½: roulette R(r, ½) against linear blending's ½.
  int mid_r = 0, vis_r = 0, mid_l = 0, vis_l = 0;
  double sum_r = 0, sum_l = 0;
  const int m = 100000;
  for (int j = 0; j < m; ++j) {
    const double w =
        kemppinen2025::roulette(counter_uniform<double>(seed, std::uint64_t(j), 7), 0.5);
    mid_r += w > 0.1 && w < 0.9;
    if (w > 0.01) ++vis_r, sum_r += w;
    const double wl = 0.5;  // linear blending gives every point the level's weight
    mid_l += wl > 0.1 && wl < 0.9;
    if (wl > 0.01) ++vis_l, sum_l += wl;
  }
  s.mid_share_roulette = double(mid_r) / m;
  s.mid_share_linear = double(mid_l) / m;
  s.peak_roulette = sum_r / vis_r;
  s.peak_linear = sum_l / vis_l;
  return s;
}

struct RouletteMeasured {
  double exact_err = 0;   // max |E_r[s·R] − w| on [2ε, 1 − 2ε]
  double end_err = 0;     // the same on [0, 1] (the window clipped at 0 or 1)
  MeanTestResult paired;  // roulette (× s) − linear
};

RouletteMeasured roulette_measured(const RouletteStats& s, double scale) {
  const double lo = 2 * kemppinen2025::kRouletteEpsilon;
  return {roulette_expectation_error(scale, lo, 1 - lo), roulette_expectation_error(scale, 0, 1),
          scale == 1 ? s.paired : s.paired_control};
}

Verdict decide_roulette(const RouletteMeasured& m, double level) {
  return m.paired.p_value > level && m.exact_err < kRouletteExact ? Verdict::kHoldsWithin
                                                                  : Verdict::kFails;
}

std::string describe_roulette(const RouletteMeasured& m, const RouletteStats& s) {
  return fmt::format(
      "E_r[R(r, w)] = w to {:.1e} for w ∈ [2ε, 1 − 2ε]; outside, where the window [r − ε, r + ε] "
      "is clipped at 0 or 1, it is off by up to {:.3g}; over {} positions at λ = {:g} the "
      "explicit D★^f with roulette differs from linear blending by {:+.3g} ± {:.2g} (relative "
      "{:+.2g} ± {:.2g}, p {:.3g}); per glint at w = ½: roulette leaves {:.0f} % of the points "
      "partly faded (weight in (0.1, 0.9)), linear {:.0f} %, and visible glints keep mean weight "
      "{:.2f} (linear {:.2f})",
      m.exact_err, m.end_err, s.n, kRouletteLambda, m.paired.estimate, m.paired.std_error,
      m.paired.estimate / s.linear_mean, m.paired.std_error / s.linear_mean, m.paired.p_value,
      100 * s.mid_share_roulette, 100 * s.mid_share_linear, s.peak_roulette, s.peak_linear);
}

CheckResult run_roulette(Budget b) {
  const std::uint64_t n = b == Budget::kQuick ? 3000 : 100000;
  const RouletteStats s = run_roulette_stats(n, check_seed(kRoulette, 0));
  const RouletteMeasured m = roulette_measured(s, 1);
  const RouletteMeasured mc = roulette_measured(s, 1 + kRouletteControl);
  const double level = check_level();
  CheckResult r;
  r.configurations = 1;
  r.statistic =
      "paired t test: mean over positions of the explicit D★^f, roulette − linear, at "
      "w = ½";
  r.value = m.paired.p_value;
  r.p_value = m.paired.p_value;
  r.raw_p_values = {m.paired.p_value};
  r.bound = level;
  r.verdict = decide_roulette(m, level);
  r.control = fmt::format(
      "roulette weight × {:g}: max |E[R] − w| {:.3g} on [2ε, 1 − 2ε] (tolerance {:g}); paired "
      "difference to linear {:+.3g} ± {:.2g}, p {:.3g} (level {:.2g})",
      1 + kRouletteControl, mc.exact_err, kRouletteExact, mc.paired.estimate, mc.paired.std_error,
      mc.paired.p_value, level);
  r.control_p_value = mc.paired.p_value;
  record_control(r, decide_roulette(mc, level));
  r.power = fmt::format(
      "a mean difference roulette − linear of {:.2g} (relative {:.2g}; SE {:.2g}, two-sided at "
      "the check's level) is detected with 90 % power; E[R] − w to {:g} deterministically (a "
      "roulette weight off by {:.2g} % at w = 1 − 2ε)",
      (normal_quantile(1 - level / 2) + 1.2816) * m.paired.std_error,
      (normal_quantile(1 - level / 2) + 1.2816) * m.paired.std_error / s.linear_mean,
      m.paired.std_error, kRouletteExact,
      100 * kRouletteExact / (1 - 2 * kemppinen2025::kRouletteEpsilon));
  r.detail = describe_roulette(m, s);
  return r;
}

double calibrate_roulette(std::uint64_t seed) {
  return run_roulette_stats(3000, seed).paired.p_value;
}

// ---- kemppinen.furnace (Fig. 15) --------------------------------------------------------------

const std::string kFurnace = "kemppinen.furnace";

struct FurnConfig {
  Ndfs ndf;
  double alpha_star, theta;
};

// The quick grid holds the full grid's extremes (θo 0° and 85°).
std::vector<FurnConfig> furn_configs(Budget b) {
  std::vector<FurnConfig> out;
  const std::vector<double> thetas = b == Budget::kQuick
                                         ? std::vector<double>{0, 45, 85}
                                         : std::vector<double>{0, 20, 40, 60, 75, 85};
  for (bool ggx : {true, false})
    for (double a : {0.1, 0.5})
      for (double s : {0.02, 0.2})
        for (double t : thetas) out.push_back({{ggx, a}, s, t});
  return out;
}

// Measure: per setting, the area-averaged white furnace of the glinty NDF and of the smooth one
// on the same sampled directions. Decide: fails when any setting gains energy significantly
// (glinty − smooth > 0, or glinty > 1; one-sided, Holm–Šidák over the settings), holds otherwise.
// Control: the same decision on the glinty estimator rescaled to gain kFurnaceControlGain over
// the smooth NDF in every setting (a near-miss normalisation).
constexpr double kFurnaceControlGain = 0.03;

struct FurnRow {
  FurnConfig c;
  MeanAccumulator glint, smooth, diff;
  std::vector<double> g, s;  // per sample, to build the control's rescaled differences
};

FurnRow run_furn(const FurnConfig& c, std::uint64_t n, std::uint64_t seed) {
  FurnRow row{c, {}, {}, {}, {}, {}};
  P p = kemppinen2025::preset_params(2, c.alpha_star, seed);
  const V3 wi = direction(c.theta);
  with_ndf(c.ndf, [&](const auto& ndf) {
    for (std::uint64_t i = 0; i < n; ++i) {
      const V2 u{counter_uniform<double>(seed, i, 2), counter_uniform<double>(seed, i, 3)};
      const kemppinen2025::FurnaceSample f =
          kemppinen2025::furnace_sample(p, ndf, wi, position(seed, i), u);
      const double g = f.glint, s = f.smooth;
      row.glint.add(g);
      row.smooth.add(s);
      row.diff.add(g - s);
      row.g.push_back(g);
      row.s.push_back(s);
    }
    return 0;
  });
  return row;
}

// One-sided p of a positive mean.
double p_positive(const MeanAccumulator& a, double mu0) {
  const MeanTestResult t = t_test(a, mu0);
  return t.statistic > 0 ? t.p_value / 2 : 1 - t.p_value / 2;
}

struct FurnDecision {
  Verdict verdict = Verdict::kInconclusive;
  std::vector<double> p_gain;  // per setting: min of the two one-sided p (gain over smooth, > 1)
  int gains = 0;               // settings that gain significantly (Holm–Šidák)
};

FurnDecision decide_furnace(const std::vector<MeanAccumulator>& diff,
                            const std::vector<MeanAccumulator>& glint) {
  FurnDecision d;
  for (std::size_t i = 0; i < diff.size(); ++i)
    d.p_gain.push_back(
        std::min(1.0, 2 * std::min(p_positive(diff[i], 0), p_positive(glint[i], 1))));
  d.gains = int(holm_sidak(d.p_gain, check_level()).rejections);
  d.verdict = d.gains == 0 ? Verdict::kHolds : Verdict::kFails;
  return d;
}

// The control's rows: glinty weights rescaled so each setting's mean gains kFurnaceControlGain
// over the smooth NDF's, the sample noise kept.
void control_rows(const std::vector<FurnRow>& rows, std::vector<MeanAccumulator>& diff,
                  std::vector<MeanAccumulator>& glint) {
  for (const FurnRow& row : rows) {
    const double k =
        row.glint.mean > 0 ? (1 + kFurnaceControlGain) * row.smooth.mean / row.glint.mean : 0;
    MeanAccumulator d, g;
    for (std::size_t j = 0; j < row.g.size(); ++j) {
      d.add(k * row.g[j] - row.s[j]);
      g.add(k * row.g[j]);
    }
    diff.push_back(d);
    glint.push_back(g);
  }
}

CheckResult run_furnace(Budget b) {
  const auto cfg = furn_configs(b);
  const std::uint64_t n = b == Budget::kQuick ? 1500 : 40000;
  std::vector<FurnRow> rows(cfg.size());
  tbb::parallel_for(std::size_t(0), cfg.size(),
                    [&](std::size_t i) { rows[i] = run_furn(cfg[i], n, check_seed(kFurnace, i)); });
  std::vector<MeanAccumulator> diff, glint, cdiff, cglint;
  for (const FurnRow& row : rows) diff.push_back(row.diff), glint.push_back(row.glint);
  control_rows(rows, cdiff, cglint);
  const FurnDecision d = decide_furnace(diff, glint);
  const FurnDecision dc = decide_furnace(cdiff, cglint);
  double max_e = 0, worst_gain = -1, worst_loss = 0, se_max = 0, se_min = 1e300;
  std::string gain_at, loss_at;
  for (const FurnRow& row : rows) {
    max_e = std::max(max_e, row.glint.mean);
    se_max =
        std::max(se_max, std::sqrt(row.diff.variance() / double(row.diff.n)) / row.smooth.mean);
    const double rel = row.glint.mean / row.smooth.mean - 1;
    const std::string at = fmt::format("{} α={:g} α★={:g} θo={:g}°", ndf_name(row.c.ndf),
                                       row.c.ndf.alpha, row.c.alpha_star, row.c.theta);
    if (rel > worst_gain) worst_gain = rel, gain_at = at;
    if (rel < worst_loss) worst_loss = rel, loss_at = at;
  }
  CheckResult r;
  r.configurations = int(cfg.size());
  r.raw_p_values = d.p_gain;
  r.p_value = sidak_min(d.p_gain);
  r.statistic = "one-sided t tests of an energy gain: E_glint − E_smooth > 0 or E_glint > 1";
  r.value = r.p_value.value_or(1);
  r.bound = check_level();
  r.verdict = d.verdict;
  r.control = fmt::format(
      "glinty estimator rescaled to gain {:.0f} % over the smooth NDF in every setting: {} of {} "
      "settings gain significantly, smallest p {:.3g}",
      100 * kFurnaceControlGain, dc.gains, cfg.size(), sidak_min(dc.p_gain));
  r.control_p_value = sidak_min(dc.p_gain);
  record_control(r, dc.verdict);
  const double z = normal_quantile(1 - sidak_level(check_level(), cfg.size()));
  r.power = fmt::format(
      "a gain over the smooth NDF's energy of {:.2g} (quietest setting) to {:.2g} (noisiest) is "
      "detected with 90 % power: (z + 1.28)·SE, one-sided",
      (z + 1.2816) * se_min, (z + 1.2816) * se_max);
  r.detail = fmt::format(
      "white furnace averaged over {} positions × NDF-sampled directions per setting, footprint 16 "
      "cells, k = 4: largest energy {:.4f}; glinty against smooth from {:+.3g} ({}) to {:+.3g} "
      "({}); {} of {} settings gain significantly",
      n, max_e, worst_loss, loss_at, worst_gain, gain_at, d.gains, cfg.size());
  return r;
}

double calibrate_furnace(std::uint64_t seed) {
  // A true null with the check's own heavy-tailed weights: for the same sampled ω_h, the glinty
  // furnace weight at two independent positions has a difference of mean exactly 0 (the check's
  // own difference glinty − smooth has a negative mean at every setting, so it cannot serve).
  const Ndfs nd{true, 0.5};
  const P p = kemppinen2025::preset_params(2, 0.02, seed);
  const V3 wi = direction(0.0);
  MeanAccumulator d;
  with_ndf(nd, [&](const auto& ndf) {
    for (std::uint64_t i = 0; i < 1500; ++i) {
      const V2 u{counter_uniform<double>(seed, i, 2), counter_uniform<double>(seed, i, 3)};
      const auto at = [&](const V2& x) {
        return kemppinen2025::furnace_sample(p, ndf, wi, x, u).glint;
      };
      d.add(at(position(seed, i)) - at(position(mix64(seed ^ 0x5eed), i)));
    }
    return 0;
  });
  const MeanTestResult t = t_test(d, 0);
  return t.statistic > 0 ? t.p_value / 2 : 1 - t.p_value / 2;
}

// ---- kemppinen.constant-time --------------------------------------------------------------------
//
// Measure: the number of (spatial, angular) cells an evaluation visits, per k, over a sweep of
// footprints (0.01 … 10⁶ level-0 cells) and anisotropies (0.05 … 20). Decide: holds when, for every
// k, the count is the same over the whole sweep (exact counts); fails otherwise. Control: an
// evaluation that picks its LOD kConstantLodDrift · λ levels too fine (λ' = (1 − drift) λ, off by a
// fraction of a level that grows with the footprint) and so must widen its spatial block by
// 2^(λ − λ') per axis, rounded up to whole cells, to cover the same filter.

const std::string kConstant = "kemppinen.constant-time";
constexpr double kConstantLodDrift = 0.02;
const std::vector<double> kConstantCells = {0.01, 1.0, 10.0, 100.0, 1e3, 1e4, 1e6};
const std::vector<double> kConstantAniso = {0.05, 1.0, 20.0};
constexpr int kConstantSides[] = {1, 2, 3, 4};

// Cells visited by one evaluation at footprint fp.
using VisitCount = std::function<int(const P&, const FootprintQuery<double>&)>;

struct ConstantMeasured {
  std::vector<int> lo, hi;  // per k (kConstantSides): fewest and most cells visited
  double lod_max = 0;       // the largest LOD λ over the sweep
  int settings = 0;
};

ConstantMeasured measure_constant(const VisitCount& count) {
  ConstantMeasured m;
  for (int side : kConstantSides) {
    int lo = 1 << 30, hi = 0;
    for (double cells : kConstantCells)
      for (double aniso : kConstantAniso) {
        P p = kemppinen2025::preset_params(side, 0.02, check_seed(kConstant, 0));
        p.anisotropy = aniso;
        const FootprintQuery<double> fp = kemppinen2025::footprint_cells({0.3, 0.4}, cells, p);
        const int c = count(p, fp);
        lo = std::min(lo, c);
        hi = std::max(hi, c);
        const double res = kemppinen2025::base_resolution(p);
        m.lod_max = std::max(
            m.lod_max, kemppinen2025::lod(kemppinen2025::spatial_covariance(p, fp, res), res));
        ++m.settings;
      }
    m.lo.push_back(lo);
    m.hi.push_back(hi);
  }
  return m;
}

// The largest growth of the visited cells over the sweep, max over k of most/fewest.
double constant_growth(const ConstantMeasured& m) {
  double g = 1;
  for (std::size_t i = 0; i < m.lo.size(); ++i) g = std::max(g, double(m.hi[i]) / m.lo[i]);
  return g;
}

Verdict decide_constant(const ConstantMeasured& m) {
  return constant_growth(m) == 1 ? Verdict::kHolds : Verdict::kFails;
}

std::string describe_counts(const ConstantMeasured& m) {
  std::string out;
  for (std::size_t i = 0; i < m.lo.size(); ++i) {
    const int k = kConstantSides[i] * kConstantSides[i];
    out += fmt::format(
        "{}k = {}: {}", out.empty() ? "" : ", ", k,
        m.lo[i] == m.hi[i] ? fmt::format("{}", m.lo[i]) : fmt::format("{} … {}", m.lo[i], m.hi[i]));
  }
  return out;
}

std::string describe_constant(const ConstantMeasured& m) {
  return fmt::format(
      "cells visited per evaluation (Algorithm 1's result.points) over {} settings (footprints "
      "{:g} … {:g} level-0 cells, LOD up to {:.3g}, anisotropy {:g} … {:g}): {}; the largest "
      "growth over the sweep within one k is ×{:.3g}. Time per evaluation is measured by the "
      "Google Benchmark "
      "experiments/bench/kemppinen2025_bench.cpp (BM_KemppinenEval: k × footprint), not asserted "
      "here",
      m.settings, kConstantCells.front(), kConstantCells.back(), m.lod_max, kConstantAniso.front(),
      kConstantAniso.back(), describe_counts(m), constant_growth(m));
}

CheckResult run_constant(Budget) {
  const GGX<double> ggx{0.3, 0.3};
  const V3 h = direction(30);
  const ConstantMeasured m = measure_constant([&](const P& p, const FootprintQuery<double>& fp) {
    return kemppinen2025::eval(p, ggx, fp, h).points;
  });
  const ConstantMeasured mc = measure_constant([](const P& p, const FootprintQuery<double>& fp) {
    const double res = kemppinen2025::base_resolution(p);
    const double lambda = kemppinen2025::lod(kemppinen2025::spatial_covariance(p, fp, res), res);
    const double finer = kConstantLodDrift * lambda;  // λ − λ'
    const int side = int(std::ceil(p.side * std::exp2(finer)));
    return 2 * side * side * p.side * p.side;  // two levels, side² spatial × k angular cells
  });
  CheckResult r;
  r.configurations = m.settings;
  r.statistic =
      "max/min number of (spatial, angular) cells visited per evaluation, per k, over "
      "footprints 0.01 … 10⁶ cells and anisotropy 0.05 … 20";
  r.value = constant_growth(m);
  r.bound = 1;
  r.verdict = decide_constant(m);
  r.control = fmt::format(
      "LOD {:g} % of λ too fine (λ' = {:g} λ, at most {:.2g} of a level over the sweep), the "
      "spatial block widened to cover the same filter: {}; growth ×{:.3g}",
      100 * kConstantLodDrift, 1 - kConstantLodDrift, kConstantLodDrift * mc.lod_max,
      describe_counts(mc), constant_growth(mc));
  record_control(r, decide_constant(mc));
  r.power =
      "exact counts: growth by a single visited cell anywhere in the sweep is detected (a LOD "
      "that drifts finer with the footprint by any fraction of a level adds a row of cells once it "
      "rounds up)";
  r.detail = describe_constant(m);
  return r;
}

// ---- kemppinen.sampling-unbiased (Algorithm 2, Fig. 7) --------------------------------------

const std::string kSampling = "kemppinen.sampling-unbiased";
// The sensitivity's scales of the exact densities (see run_sampling): the marginal density in the
// quietest estimator configuration (the quick budget detects about 4 % there with 90 % power), and
// the mixture density in one rendered configuration (the quick budget detects about 16 %, the full
// one about 6 %: a 1–5 % error of the rendered estimate is below what either resolves).
constexpr double kSampSensitivity = 1.05;
constexpr double kSampRenderSensitivity = 1.2;
constexpr std::size_t kSampRenderControl = 2;  // the k = 4 rendered configuration

struct SampConfig {
  Ndfs ndf;
  double alpha_star, cells;
  int side;
};

std::vector<SampConfig> samp_configs() {
  return {{{true, 0.3}, 0.05, 2.5, 1},
          {{false, 0.3}, 0.05, 2.5, 1},
          {{true, 0.2}, 0.02, 12, 1},
          {{false, 0.5}, 0.1, 12, 1},
          {{true, 0.3}, 0.05, 5, 2}};
}

GofCase samp_case(const SampConfig& c, std::uint64_t seed_process, double pdf_scale = 1) {
  const P p = kemppinen2025::preset_params(c.side, c.alpha_star, seed_process);
  const FootprintQuery<double> fp = kemppinen2025::footprint_cells({0.37, 0.61}, c.cells, p);
  GofCase g;
  g.label = fmt::format("{} α={:g} α★={:g} footprint {:g} cells k={}", ndf_name(c.ndf), c.ndf.alpha,
                        c.alpha_star, c.cells, c.side * c.side);
  g.domain = SampleDomain::kDisk;
  const Ndfs nd = c.ndf;
  g.point_pdf = [p, fp, nd, pdf_scale](const V2& x) {
    return pdf_scale * with_ndf(nd, [&](const auto& ndf) {
             return kemppinen2025::sample_density_square(p, ndf, fp, x);
           });
  };
  g.points = [p, fp, nd](std::uint64_t seed, std::uint64_t i) {
    return with_ndf(nd, [&](const auto& ndf) {
      const auto s = kemppinen2025::sample_half(p, ndf, fp, mix64(seed ^ mix64(i + 1)));
      return s.ok ? s.x : V2{std::nan(""), std::nan("")};
    });
  };
  return g;
}

// Monte Carlo of I = ∫ g(ω_h) dω_h with g the explicit part of D★^f times a smooth "sky"
// L(ω_h) = 1 + ½ ω_x + ω_z², from Algorithm 2's samples with a given pdf, and from the smooth
// NDF's samples (Walter: ω_h ~ D cosθ) as the independent reference.
struct SampEstimate {
  MeanAccumulator marginal, printed, smooth;
};

double sky(const V3& w) { return 1 + 0.5 * w.x + w.z * w.z; }

SampEstimate run_estimates(const SampConfig& c, std::uint64_t n, std::uint64_t seed) {
  SampEstimate e;
  const P p = kemppinen2025::preset_params(c.side, c.alpha_star, seed);
  const FootprintQuery<double> fp = kemppinen2025::footprint_cells({0.37, 0.61}, c.cells, p);
  with_ndf(c.ndf, [&](const auto& ndf) {
    for (std::uint64_t i = 0; i < n; ++i) {
      const auto s = kemppinen2025::sample_half(p, ndf, fp, mix64(seed ^ mix64(i + 7)));
      double m = 0, pr = 0;
      if (s.ok) {
        const double g = kemppinen2025::eval(p, ndf, fp, s.h).explicit_part.x * sky(s.h);
        const double pm = kemppinen2025::sample_density_half(p, ndf, fp, s.h);
        m = pm > 0 ? g / pm : 0;
        pr = s.pdf_printed_h > 0 ? g / s.pdf_printed_h : 0;
      }
      e.marginal.add(m);
      e.printed.add(pr);
      // Smooth NDF sampling: ω_h of density D cosθ (Walter et al. 2007 Eq. 28–29, 35–36).
      const V2 u{counter_uniform<double>(seed, i, 11), counter_uniform<double>(seed, i, 12)};
      const V3 h = sample_normal_walter(ndf, u);
      const double pdf = ndf.D(h) * h.z;
      e.smooth.add(pdf > 0 ? kemppinen2025::eval(p, ndf, fp, h).explicit_part.x * sky(h) / pdf : 0);
    }
    return 0;
  });
  return e;
}

constexpr GofSize kSampFull{2'000'000, 2'000'000, 400};

// The estimator configurations (the chi-square runs at the full budget on the k = 1 ones: its
// cubature of a density with jumps at every cell edge is slow).
// "GGX α = 0.3, α★ = 0.05, k = 1; …": the configurations in words, for the detail.
std::string describe_samp_configs(const std::vector<SampConfig>& cs) {
  std::string out;
  for (const SampConfig& c : cs)
    out += fmt::format("{}{} α = {:g}, α★ = {:g}, k = {}", out.empty() ? "" : "; ", ndf_name(c.ndf),
                       c.ndf.alpha, c.alpha_star, c.side * c.side);
  return out;
}

std::vector<SampConfig> est_configs() {
  return {{{true, 0.3}, 0.05, 2.5, 1},
          {{false, 0.3}, 0.05, 2.5, 1},
          {{true, 0.3}, 0.05, 5, 2},
          {{false, 0.3}, 0.05, 5, 2}};
}

// ---- The rendered estimate under an environment light (Fig. 7) -------------------------------
//
// Reflected radiance (luminance) of a glinty plane with the full BRDF of the models (D★^f, G2,
// F = 1) under kemppinen2025::env_sky(), viewed from θ_v = 30°, over a set of pixels at random uv:
// (a) the mixture of Algorithm 2 and D cosθ with its exact density, (b) the same samples with
// Algorithm 2's printed pdf in the mixture, (c) D cosθ alone; each against the stratified
// quadrature reference of verify/scenes/kemppinen_env_radiance.h (2 n² evaluations per pixel).

struct RenderConfig {
  Ndfs ndf;
  double alpha_star, cells;
  int side;
};

std::vector<RenderConfig> render_configs(Budget b) {
  std::vector<RenderConfig> c = {
      {{true, 0.3}, 0.02, 2.5, 1}, {{false, 0.3}, 0.02, 2.5, 1}, {{true, 0.2}, 0.02, 1, 2}};
  if (b == Budget::kFull) {
    c.push_back({{false, 0.2}, 0.02, 1, 2});
    c.push_back({{true, 0.3}, 0.05, 2.5, 1});
  }
  return c;
}

struct RenderSize {
  int pixels;
  std::uint64_t n_k1, n_k4;  // samples per pixel and strategy for k = 1 and k > 1
  int ref_n;                 // reference strata per axis
};

RenderSize render_size(Budget b) {
  return b == Budget::kQuick ? RenderSize{4, 4096, 2048, 256} : RenderSize{4, 65536, 16384, 768};
}

struct Moments {
  double mean = 0, var = 0;  // pixel-set mean and its variance
};

struct RenderRow {
  RenderConfig c;
  double q = 0, explicit_fraction = 0;
  std::uint64_t n = 0;
  double ref = 0, ref_var = 0;
  Moments exact, printed, smooth;
  double p_exact = 1, p_printed = 1, p_smooth = 1, p_control = 1;
  double slope_exact = 0, slope_printed = 0, slope_smooth = 0;
};

// Two-sided normal p of (estimate − reference) with both variances.
double bias_p(const Moments& m, double ref, double ref_var) {
  const double se = std::sqrt(m.var + ref_var);
  return se > 0 ? std::erfc(std::abs(m.mean - ref) / se / std::numbers::sqrt2) : 1.0;
}

RenderRow run_render(const RenderConfig& c, const RenderSize& sz, std::uint64_t seed) {
  RenderRow row;
  row.c = c;
  row.n = c.side == 1 ? sz.n_k1 : sz.n_k4;
  const P p = kemppinen2025::preset_params(c.side, c.alpha_star, seed);
  const EnvironmentMap env(kemppinen2025::env_sky());
  const kemppinen2025::PlaneView view{30 * kPi / 180, {0, 0}, 0};
  const V3 v = view.view();
  const std::size_t np = std::size_t(sz.pixels);
  std::vector<kemppinen2025::EnvReference> refs(np);
  std::vector<kemppinen2025::EnvSamples> smp(np);
  tbb::parallel_for(std::size_t(0), 2 * np, [&](std::size_t t) {
    const std::size_t i = t % np;
    const FootprintQuery<double> fp = kemppinen2025::footprint_cells(position(seed, i), c.cells, p);
    with_ndf(c.ndf, [&](const auto& ndf) {
      if (t < np)
        refs[i] =
            kemppinen2025::env_reference(p, ndf, fp, env, v, sz.ref_n, mix64(seed ^ (i + 17)));
      else
        smp[i] = kemppinen2025::env_samples(p, ndf, fp, env, v, row.n, mix64(seed ^ (i + 29)));
      return 0;
    });
  });
  std::vector<std::vector<double>> lum[3];
  std::vector<double> ref_pixels;
  Moments* mom[3] = {&row.exact, &row.printed, &row.smooth};
  std::uint64_t explicit_count = 0;
  for (std::size_t i = 0; i < np; ++i) {
    const double inv = 1.0 / double(np);
    ref_pixels.push_back(kemppinen2025::luminance(refs[i].mean));
    row.ref += inv * ref_pixels.back();
    row.ref_var += inv * inv * refs[i].luminance_variance;
    const std::vector<Vec3<double>>* src[3] = {&smp[i].exact, &smp[i].printed, &smp[i].smooth};
    for (int k = 0; k < 3; ++k) {
      MeanAccumulator acc;
      std::vector<double> y;
      for (const Vec3<double>& e : *src[k]) {
        y.push_back(kemppinen2025::luminance(e));
        acc.add(y.back());
      }
      mom[k]->mean += inv * acc.mean;
      mom[k]->var += inv * inv * acc.variance() / double(acc.n);
      lum[k].push_back(std::move(y));
    }
    row.q = smp[i].q;
    explicit_count += smp[i].from_explicit;
  }
  row.explicit_fraction = double(explicit_count) / double(row.n * np);
  row.p_exact = bias_p(row.exact, row.ref, row.ref_var);
  row.p_printed = bias_p(row.printed, row.ref, row.ref_var);
  row.p_smooth = bias_p(row.smooth, row.ref, row.ref_var);
  // Sensitivity: the exact mixture density × kSampRenderSensitivity (every estimate divided).
  row.p_control =
      bias_p({row.exact.mean / kSampRenderSensitivity, row.exact.var / sqr(kSampRenderSensitivity)},
             row.ref, row.ref_var);
  std::vector<int> spps;
  for (std::uint64_t s = 1; s * 16 <= row.n; s *= 4) spps.push_back(int(s));
  row.slope_exact = loglog_slope(rmse_at_spp(lum[0], ref_pixels, spps));
  row.slope_printed = loglog_slope(rmse_at_spp(lum[1], ref_pixels, spps));
  row.slope_smooth = loglog_slope(rmse_at_spp(lum[2], ref_pixels, spps));
  return row;
}

std::string render_label(const RenderConfig& c) {
  return fmt::format("{} α={:g} α★={:g} {:g} cells k={}", ndf_name(c.ndf), c.ndf.alpha,
                     c.alpha_star, c.cells, c.side * c.side);
}

// ---- The claim: measure, decide, describe ---------------------------------------------------
//
// Measure: (full budget) the chi-square of Algorithm 2's samples against their marginal density;
// per estimator configuration, the IS estimates with the exact marginal density, with the printed
// pdf and with smooth-NDF sampling; per rendered configuration, the three rendered estimates and
// the stratified reference. Decide: fails when the printed pdf biases an estimate (Welch or normal
// p at or below one Šidák level shared by every test of unbiasedness) while the exact densities do
// not; holds when nothing is biased; inconclusive when the chi-square family cannot decide or
// smooth-NDF sampling disagrees with the reference. Control: a claim that fails has the exact
// densities in place of the printed pdf (must hold); a claim that holds has them scaled (must
// fail): the marginal density × kSampSensitivity in the quietest estimator configuration and the
// mixture density × kSampRenderSensitivity in one rendered configuration. The scaled densities
// are reported as the sensitivity either way.

struct SampMeasured {
  bool chi_run = false;  // the chi-square family runs at the full budget only
  std::vector<GofCase> chi_cases;
  std::vector<GofControl> chi_controls;
  GofOutcome chi;
  Verdict family = Verdict::kHolds;  // the chi-square family's verdict (holds where not run)
  double family_p = 1;               // its corrected p
  std::uint64_t n = 0;               // samples per estimator
  std::vector<SampConfig> cfg;
  std::vector<SampEstimate> est;
  RenderSize rsz{};
  std::vector<RenderRow> rows;
};

SampMeasured measure_sampling(Budget b) {
  SampMeasured m;
  if (b == Budget::kFull) {
    m.chi_run = true;
    const auto cfg = samp_configs();
    for (std::size_t i = 0; i < 2; ++i)
      m.chi_cases.push_back(samp_case(cfg[i], check_seed(kSampling, 100 + i)));
    GofControl scaled{"marginal density × 1.02", {}};
    for (int i : {0, 1})
      scaled.cases.push_back(
          {samp_case(cfg[std::size_t(i)], check_seed(kSampling, 100 + std::size_t(i))), i, 1.02});
    m.chi_controls = {scaled};
    m.chi = run_gof_family(kSampling, m.chi_cases, m.chi_controls, kSampFull);
  }
  m.cfg = est_configs();
  m.n = b == Budget::kQuick ? 10000 : 400000;
  m.est.resize(m.cfg.size());
  tbb::parallel_for(std::size_t(0), m.cfg.size(), [&](std::size_t i) {
    m.est[i] = run_estimates(m.cfg[i], m.n, check_seed(kSampling, 200 + i));
  });
  const auto rcfg = render_configs(b);
  m.rsz = render_size(b);
  m.rows.resize(rcfg.size());
  for (std::size_t i = 0; i < rcfg.size(); ++i)
    m.rows[i] = run_render(rcfg[i], m.rsz, check_seed(kSampling, 300 + i));
  return m;
}

// Which densities the tests use: Algorithm 2's printed pdf (the claim), the exact marginal and
// mixture densities in its place (the corrected input), or those scaled (the sensitivity).
enum class SampInput { kPrinted, kCorrected, kScaled };

// The p-values of the tests of unbiasedness, for one input.
struct SampTests {
  std::vector<double> marginal, printed;  // per estimator configuration: Welch p against smooth
  std::vector<double> mixture, mixture_printed, smooth;  // per rendered configuration
};

// The marginal estimator with its density × s: every estimate / s.
MeanAccumulator scaled_estimate(const MeanAccumulator& a, double s) {
  MeanAccumulator out = a;
  out.mean /= s;
  out.m2 /= s * s;
  return out;
}

SampTests sampling_tests(const SampMeasured& m, SampInput in) {
  SampTests t;
  for (std::size_t i = 0; i < m.est.size(); ++i) {
    const SampEstimate& e = m.est[i];
    const bool scale = in == SampInput::kScaled && i + 1 == m.est.size();
    t.marginal.push_back(
        welch_t_test(scale ? scaled_estimate(e.marginal, kSampSensitivity) : e.marginal, e.smooth)
            .p_value);
    t.printed.push_back(in == SampInput::kPrinted ? welch_t_test(e.printed, e.smooth).p_value
                                                  : t.marginal.back());
  }
  for (std::size_t i = 0; i < m.rows.size(); ++i) {
    const RenderRow& w = m.rows[i];
    const bool scale = in == SampInput::kScaled && i == kSampRenderControl;
    t.mixture.push_back(scale ? w.p_control : w.p_exact);
    t.mixture_printed.push_back(in == SampInput::kPrinted ? w.p_printed : t.mixture.back());
    t.smooth.push_back(w.p_smooth);
  }
  return t;
}

// Every hypothesis of unbiasedness shares one Šidák level: the sampler-alone marginal tests, and
// per rendered configuration the exact mixture and smooth-NDF sampling.
std::vector<double> unbiased_ps(const SampTests& t) {
  std::vector<double> u = t.marginal;
  for (std::size_t i = 0; i < t.mixture.size(); ++i) {
    u.push_back(t.mixture[i]);
    u.push_back(t.smooth[i]);
  }
  return u;
}

double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

struct SampDecision {
  Verdict verdict = Verdict::kInconclusive;
  double level = 0;
  double pm_min = 1, pp_min = 1, pe_min = 1, pr_min = 1, ps_min = 1;
  bool marginal_ok = false, printed_ok = false, mixture_ok = false, printed_render_ok = false,
       reference_ok = false;
};

SampDecision decide_sampling(const SampMeasured& m, SampInput in) {
  const SampTests t = sampling_tests(m, in);
  SampDecision d;
  d.level = sidak_level(check_level(), unbiased_ps(t).size());
  d.pm_min = min_of(t.marginal);
  d.pp_min = min_of(t.printed);
  d.pe_min = min_of(t.mixture);
  d.pr_min = min_of(t.mixture_printed);
  d.ps_min = min_of(t.smooth);
  d.marginal_ok = m.family == Verdict::kHolds && d.pm_min > d.level;
  d.printed_ok = d.pp_min > d.level;
  d.mixture_ok = d.pe_min > d.level;
  d.printed_render_ok = d.pr_min > d.level;
  d.reference_ok = d.ps_min > d.level;  // smooth-NDF IS agrees with the reference
  d.verdict = m.family == Verdict::kInconclusive || !d.reference_ok ? Verdict::kInconclusive
              : d.printed_ok && d.marginal_ok && d.mixture_ok && d.printed_render_ok
                  ? Verdict::kHolds
                  : Verdict::kFails;
  return d;
}

std::string describe_sampling(const SampMeasured& m, const SampDecision& d) {
  const std::string chi =
      m.chi_run
          ? fmt::format(
                "chi-square of the samples against the marginal density: {} of {} "
                "configurations rejected (corrected p {:.3g}, {} samples)",
                m.chi.family.rejections, m.chi.results.size(), m.family_p, kSampFull.n)
          : std::string("chi-square of the samples against the marginal density: full budget only");
  double ratio_lo = 1e300, ratio_hi = 0, var_lo = 1e300, var_hi = 0;
  for (const SampEstimate& e : m.est) {
    const double ratio = e.printed.mean / e.smooth.mean;
    ratio_lo = std::min(ratio_lo, ratio);
    ratio_hi = std::max(ratio_hi, ratio);
    const double vr = e.smooth.variance() / std::max(e.marginal.variance(), 1e-300);
    var_lo = std::min(var_lo, vr);
    var_hi = std::max(var_hi, vr);
  }
  std::string rtext;
  for (const RenderRow& w : m.rows)
    rtext += fmt::format(
        "; {} (q {:.3g}, {} spp × {} pixels): reference {:.4g} ± {:.2g}, (a) exact mixture "
        "{:+.3g}% (p {:.3g}), (b) printed-pdf mixture {:+.3g}% (p {:.3g}), (c) D cosθ {:+.3g}% (p "
        "{:.3g}); RMSE-vs-spp slopes (a) {:.3f} (b) {:.3f} (c) {:.3f}; variance (c)/(a) {:.3g}",
        render_label(w.c), w.q, w.n, m.rsz.pixels, w.ref, std::sqrt(w.ref_var),
        100 * (w.exact.mean / w.ref - 1), w.p_exact, 100 * (w.printed.mean / w.ref - 1),
        w.p_printed, 100 * (w.smooth.mean / w.ref - 1), w.p_smooth, w.slope_exact, w.slope_printed,
        w.slope_smooth, w.smooth.var / std::max(w.exact.var, 1e-300));
  return fmt::format(
      "sampler alone: {}; the estimator with the marginal density (over x_a, level and point "
      "choice) {} smooth-NDF sampling of the explicit D★^f × sky (smallest Welch p {:.3g}, {}; "
      "level {:.3g}), smooth-NDF variance / its variance {:.3g} … {:.3g}; with the pdf of lines "
      "16–17 as legible (Area(B), |J_T| = D/|U_Ω|, cosθ, w_λ) the estimate is {:.3g} … {:.3g}× "
      "the true integral (smallest Welch p {:.3g}): {}. The compensation term is not sampled "
      "(Sec. 3.3.5), so only the explicit part is estimated there; {} samples per estimator, {} "
      "configurations ({}). Rendered estimate of the whole D★^f (full BRDF: D★^f, "
      "height-correlated G2, F = 1) under a 64 × 32 lat-long sky with a soft sun at the mirror "
      "direction, θ_v = 30°, the reference a stratified quadrature over ω_h ({}² "
      "equal-solid-angle strata × 2 jittered points per pixel, no sampler involved): the mixture "
      "of Algorithm 2 (probability q) and D cosθ with the exact mixture density is {} (smallest p "
      "{:.3g}), with Algorithm 2's printed pdf in the mixture it is {} (smallest p {:.3g}), D cosθ "
      "alone smallest p {:.3g}{}",
      chi, d.marginal_ok ? "matches" : "does not match", d.pm_min,
      d.marginal_ok ? "unbiased" : "BIASED", d.level, var_lo, var_hi, ratio_lo, ratio_hi, d.pp_min,
      d.printed_ok ? "unbiased" : "biased — the printed pdf does not give the integral", m.n,
      m.cfg.size(), describe_samp_configs(m.cfg), m.rsz.ref_n, d.mixture_ok ? "unbiased" : "BIASED",
      d.pe_min, d.printed_render_ok ? "unbiased" : "biased", d.pr_min, d.ps_min, rtext);
}

CheckResult run_sampling(Budget b) {
  SampMeasured m = measure_sampling(b);
  CheckResult r;
  if (m.chi_run) {
    std::size_t worst = 0;
    m.family = summarize_gof(m.chi, m.chi_controls, r, worst);
    m.family_p = r.p_value.value_or(1);
  }
  // The claim is the sampler's (Sec. 3.3.5, Fig. 7: Algorithm 2 draws from D★^f), decided with
  // its exact marginal and mixture densities. The pdf printed in lines 16–17 is measured beside
  // it and reported as its own measurement, not as the claim's verdict: its single-level bias is
  // Eq. 3's Jacobian ratio (a finding of kemppinen.jacobian) and its w_λ factor is illegible in
  // the source (core/glints/kemppinen_sampling.h), so it cannot be read as the paper's pdf.
  const SampDecision d = decide_sampling(m, SampInput::kCorrected);
  const SampDecision printed = decide_sampling(m, SampInput::kPrinted);
  const SampTests t = sampling_tests(m, SampInput::kPrinted);
  const SampTests ts = sampling_tests(m, SampInput::kScaled);
  const SampDecision ds = decide_sampling(m, SampInput::kScaled);
  const double pc = ts.marginal.back(), prc = ts.mixture[kSampRenderControl];
  const std::string sensitivity = fmt::format(
      "marginal density × {:g} (quietest configuration): Welch p {:.3g} (level {:.3g}); rendered: "
      "exact mixture density × {:g}: p {:.3g} ({}); decided: {}",
      kSampSensitivity, pc, d.level, kSampRenderSensitivity, prc,
      render_label(m.rows[kSampRenderControl].c), to_string(ds.verdict));
  if (!m.chi_run) {
    r.raw_p_values = unbiased_ps(t);
    r.p_value = sidak_min(r.raw_p_values);
    r.configurations = int(r.raw_p_values.size());
    r.control = sensitivity;
    r.control_p_value = std::max(pc, prc);
  } else {
    r.control += "; " + sensitivity;
  }
  r.statistic =
      "Welch t test: IS estimate with Algorithm 2's marginal density vs smooth-NDF "
      "sampling of the same integral; rendered: (estimate − stratified reference)/se, normal p";
  r.value = std::min(d.pm_min, d.pe_min);
  r.bound = d.level;
  r.verdict = d.verdict;
  double rel_se = 0;  // largest relative SE of a rendered estimate against its reference
  for (const RenderRow& w : m.rows)
    rel_se = std::max(rel_se, std::sqrt(w.exact.var + w.ref_var) / w.ref);
  double est_lo = 1e300, est_hi = 0;  // relative SE of marginal − smooth, sampler alone
  for (const SampEstimate& e : m.est) {
    const double se = std::sqrt((e.marginal.variance() + e.smooth.variance()) / double(m.n)) /
                      std::abs(e.smooth.mean);
    est_lo = std::min(est_lo, se);
    est_hi = std::max(est_hi, se);
  }
  const double zq = normal_quantile(1 - d.level / 2) + 1.2816;
  r.power = fmt::format(
      "a relative bias of the rendered estimate of {:.2g} (largest relative SE {:.2g}, at the "
      "Šidák level {:.2g}) is detected with 90 % power; sampler alone, a relative bias of {:.2g} "
      "(quietest configuration) to {:.2g} (noisiest)",
      zq * rel_se, rel_se, d.level, zq * est_lo, zq * est_hi);
  // The control: the same exact densities scaled (near the truth), through the same decision.
  record_control(r, ds.verdict);
  r.detail = fmt::format(
      "the sampler with its exact density: {}. Measured beside it, not the verdict: the pdf "
      "printed in lines 16–17 (as legible) {} — its single-level bias is Eq. 3's Jacobian ratio "
      "(kemppinen.jacobian), and its w_λ factor is illegible in the source, so this measurement "
      "is inconclusive about the paper's pdf. {}",
      d.verdict == Verdict::kHolds ? "unbiased" : to_string(d.verdict),
      printed.printed_ok && printed.printed_render_ok ? "gives the integral"
                                                      : "biases the estimate",
      describe_sampling(m, printed));
  return r;
}

double calibrate_sampling(std::uint64_t seed) {
  const SampEstimate e = run_estimates(est_configs().back(), 4000, seed);
  return welch_t_test(e.marginal, e.smooth).p_value;
}

}  // namespace

// ---- Probes for tests/verify/claims (reduced sizes) -----------------------------------------

ControlProbe probe_kemppinen_convergence() {
  // GGX, α★ = 0.01, normal incidence: inside the regime. Statistic: the bias bound against D.
  const ConvConfig c{{true, 0.3}, 0.01, 0.0};
  const ConvSize sz{{8, 32}, 96};
  const double z = normal_quantile(1 - sidak_level(check_level(), 18) / 2);
  return {bias_bound(measure_conv(c, sz, 99, kemppinen2025::Normalization::kCorrected), z),
          bias_bound(measure_conv(c, sz, 99, kemppinen2025::Normalization::kPrinted), z),
          kConvergenceTolerance, false};
}

ControlProbe probe_kemppinen_compensation() {
  // GGX α★ = 0.02, θ = 0, 16 cells (C carries 71 % of D★^f): |bias of Eq. 11 (k = 4) against
  // Eq. 5|; control: Eq. 11 without C.
  const CompMeasured m = measure_comp({{true, 0.3}, 0.02, 0.0, 16}, {2e6, 100, 100}, 5);
  return {std::abs(m.whole.bias), std::abs(m.no_c.bias), kCompTolerance, false};
}

std::pair<Verdict, Verdict> probe_kemppinen_compensation_verdicts() {
  // A reduced grid where C carries 70–98 % of D★^f: GGX and Beckmann, α★ 0.005 and 0.02, θ = 0,
  // 16 and 64 cells.
  std::vector<CompConfig> cfg;
  for (bool ggx : {true, false})
    for (double s : {0.005, 0.02})
      for (double c : {16.0, 64.0}) cfg.push_back({{ggx, 0.3}, s, 0.0, c});
  const auto ms = measure_compensation(cfg, {2e6, 60, 60}, "probe.kemppinen.compensation");
  return {decide_compensation(ms, {CompInput::kEq11}).verdict,
          decide_compensation(ms, {CompInput::kNoC}).verdict};
}

ControlProbe probe_kemppinen_compensation_k16() {
  // Beckmann α★ = 0.1, θ = 40°, 64 cells: T(ω_h) at the rim, the lobe about one angular cell
  // wide; k = 4 brightens. Statistic: −(the error k = 16 removes beyond a tenth of k = 4's);
  // control: k = 4's result with 8 % of its error removed in place of k = 16.
  const K16Measured m = measure_k16_setting({{false, 0.3}, 0.1, 40.0, 64}, {2e6, 40, 40}, 11);
  return {-k16_gap(m).gap, -k16_gap(m, kMitigates - kK16ControlMargin).gap, 0, false};
}

ControlProbe probe_kemppinen_furnace() {
  const std::vector<FurnRow> rows{run_furn({{true, 0.5}, 0.02, 45.0}, 10000, 21)};
  std::vector<MeanAccumulator> cdiff, cglint;
  control_rows(rows, cdiff, cglint);
  return {decide_furnace({rows[0].diff}, {rows[0].glint}).p_gain[0],
          decide_furnace(cdiff, cglint).p_gain[0], check_level(), true};
}

ControlProbe probe_kemppinen_roulette() {
  // The deterministic half of the decision, which carries the control at every budget.
  const double lo = 2 * kemppinen2025::kRouletteEpsilon;
  return {roulette_expectation_error(1, lo, 1 - lo),
          roulette_expectation_error(1 + kRouletteControl, lo, 1 - lo), kRouletteExact, false};
}

ControlProbe probe_kemppinen_roulette_paired() {
  const RouletteStats s = run_roulette_stats(1500, 17);
  return {s.paired.p_value, s.paired_control.p_value, check_level(), true};
}

ControlProbe probe_kemppinen_sampling() {
  const SampEstimate e = run_estimates(est_configs().back(), 10000, 3);
  return {welch_t_test(e.marginal, e.smooth).p_value,
          welch_t_test(scaled_estimate(e.marginal, kSampSensitivity), e.smooth).p_value,
          sidak_level(check_level(), 4), true};
}

ControlProbe probe_kemppinen_sampling_render(bool printed) {
  // GGX α = 0.2, α★ = 0.02, 1 cell, k = 4 (the quick budget's k = 4 rendered configuration).
  const RenderRow w =
      run_render({{true, 0.2}, 0.02, 1, 2}, {4, 0, 2048, 128}, check_seed(kSampling, 900));
  return {w.p_exact, printed ? w.p_printed : w.p_control, sidak_level(check_level(), 14), true};
}

std::vector<Check> kemppinen_glint_checks() {
  const std::string paper = "Kemppinen et al. 2025";
  return {
      {kConvergence, paper, "Eq. 2 (with Eq. 4)", Verdict::kHoldsInRegime, run_convergence},
      {kCompensation, paper, "Eq. 9–11, Sec. 3.3.4", Verdict::kHolds, run_compensation},
      {kCompensationK16, paper, "Fig. 14 left, Sec. 6", Verdict::kHoldsInRegime,
       run_compensation_k16},
      {kRoulette, paper, "Eq. 8, Sec. 3.3.3, Fig. 6", Verdict::kHoldsWithin, run_roulette,
       calibrate_roulette},
      {kFurnace, paper, "Fig. 15, Sec. 5", Verdict::kHolds, run_furnace, calibrate_furnace},
      {kConstant, paper, "Sec. 3.3.2–3.3.4, Table 2", Verdict::kHolds, run_constant},
      {kSampling, paper, "Algorithm 2, Sec. 3.3.5, Fig. 7", Verdict::kHolds,
       run_sampling, calibrate_sampling},
  };
}

}  // namespace glintlab::verify

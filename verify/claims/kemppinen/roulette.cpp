// kemppinen.roulette — Kemppinen et al. 2025, Eq. 8, Sec. 3.3.3, Fig. 6.
//
// The paper, Sec. 3.3.3: "we use a linearly blended weight for a per-point Russian roulette
// (Figure 5), so that on expectation we get linear blending but individual points get quickly
// enabled and disabled instead of being smoothly blended"; Eq. 8: R(r, w) = smoothstep(max(0,
// r − ε), min(1, r + ε), w), "We use ε = 0.1".
//
// Measured: E_r[s·R(r, w)] − w by the midpoint rule in r (deterministic), and over random positions
// at λ = 2.5 (both levels weighted ½) the paired difference of the explicit D★^f with roulette
// (every point's weight × s) and with linear blending; s = 1 for Eq. 8. Beside it, per glint at
// w = ½, the share of partly faded points and the mean weight of visible ones.
// Decided: holds within when the expectation is w to 1e-4 on w ∈ [2ε, 1 − 2ε] and the paired t
// test does not reject at the check's level; fails otherwise.
// Control (perturbed): the roulette weight off by 2 % (s = 1.02), through the same measure and
// decision.
// Regime: none (within: the expectation is exact away from the clipped ends of the window).
#include <fmt/format.h>

#include <cmath>
#include <span>
#include <string>

#include "core/glints/kemppinen.h"
#include "core/math/rng.h"
#include "core/ndf/ggx.h"
#include "verify/claim_runner.h"
#include "verify/claims/kemppinen/common.h"
#include "verify/claims/kemppinen/list.h"
#include "verify/scenes/kemppinen_presets.h"
#include "verify/stats/mean_tests.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::kemppinen_claims {
namespace {

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
  RouletteStats s;
};

RouletteMeasured roulette_measured(const RouletteStats& s, double scale) {
  const double lo = 2 * kemppinen2025::kRouletteEpsilon;
  return {roulette_expectation_error(scale, lo, 1 - lo), roulette_expectation_error(scale, 0, 1),
          scale == 1 ? s.paired : s.paired_control, s};
}

Verdict decide_roulette(const RouletteMeasured& m, double level) {
  return m.paired.p_value > level && m.exact_err < kRouletteExact ? Verdict::kHoldsWithin
                                                                  : Verdict::kFails;
}

std::string describe_roulette(const RouletteMeasured& m) {
  const RouletteStats& s = m.s;
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

}  // namespace

struct Roulette {
  static constexpr std::string_view kId = "kemppinen.roulette";
  static constexpr std::string_view kPaper = kemppinen_claims::kPaper;
  static constexpr std::string_view kSource = "Eq. 8, Sec. 3.3.3, Fig. 6";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Sec. 3.3.3: \"we use a linearly blended weight for a per-point Russian roulette "
      "(Figure 5), so that on expectation we get linear blending but individual points "
      "get quickly enabled and disabled instead of being smoothly blended\"; Eq. 8: "
      "R(r, w) = smoothstep(max(0, r − ε), min(1, r + ε), w), \"We use ε = 0.1\"";
  static constexpr std::string_view kStatistic =
      "paired t test: mean over positions of the explicit D★^f, roulette − linear, at w = ½";
  static constexpr Expected kExpected{.quick = Verdict::kHoldsWithin};

  struct Sizes {
    std::uint64_t positions;
  };
  static Sizes sizes(Budget b) { return {b == Budget::kQuick ? 3000u : 100000u}; }
  static Sizes probe_sizes() { return {1500}; }

  using Evidence = RouletteStats;  // the paired differences over the positions, both weights
  static int configurations(const Sizes&) { return 1; }
  static Evidence observe(const Sizes& z, int, std::uint64_t seed) {
    return run_roulette_stats(z.positions, seed);
  }

  // Genuine: Eq. 8's weight; perturbed: the weight × 1.02.
  using Measured = RouletteMeasured;
  static Measured measure(const Sizes&, std::span<const Evidence> evidence, Input input) {
    return roulette_measured(evidence.front(), input == Input::kGenuine ? 1 : 1 + kRouletteControl);
  }
  static Decision decide(const Sizes&, const Measured& m) {
    return {.verdict = decide_roulette(m, check_level()),
            .value = m.paired.p_value,
            .bound = check_level(),
            .p_value = m.paired.p_value,
            .raw_p_values = {m.paired.p_value},
            .configurations = 1};
  }
  static std::string describe(const Sizes&, const Measured& m, Input) {
    return describe_roulette(m);
  }
  static std::string control_text(const Sizes&, const Measured& m, Input, Verdict) {
    return fmt::format(
        "roulette weight × {:g}: max |E[R] − w| {:.3g} on [2ε, 1 − 2ε] (tolerance {:g}); paired "
        "difference to linear {:+.3g} ± {:.2g}, p {:.3g} (level {:.2g})",
        1 + kRouletteControl, m.exact_err, kRouletteExact, m.paired.estimate, m.paired.std_error,
        m.paired.p_value, check_level());
  }
  static std::string power(const Sizes&, const Measured& m, const Measured&) {
    const double level = check_level();
    return fmt::format(
        "a mean difference roulette − linear of {:.2g} (relative {:.2g}; SE {:.2g}, two-sided at "
        "the check's level) is detected with 90 % power; E[R] − w to {:g} deterministically (a "
        "roulette weight off by {:.2g} % at w = 1 − 2ε)",
        (normal_quantile(1 - level / 2) + 1.2816) * m.paired.std_error,
        (normal_quantile(1 - level / 2) + 1.2816) * m.paired.std_error / m.s.linear_mean,
        m.paired.std_error, kRouletteExact,
        100 * kRouletteExact / (1 - 2 * kemppinen2025::kRouletteEpsilon));
  }
  static double calibrate(std::uint64_t seed) { return run_roulette_stats(3000, seed).paired.p_value; }
};

}  // namespace glintlab::verify::kemppinen_claims

GLINTLAB_CLAIM(glintlab::verify::kemppinen_claims::Roulette);

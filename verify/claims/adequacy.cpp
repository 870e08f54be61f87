// Claim adequacy.prediction-matches-measurement: the closed forms the adequacy chooser
// (core/glints/adequacy.h) is built on — the count's CV √((1 − p)/(N_P p)) and P(no glint) =
// (1 − p)^N_P — match the pixel values the binomial glint models give over surface positions
// (verify/adequacy/binomial_adequacy.h), at the exact counting level, from N_P = 1 to 10^8; and the
// boundary they predict, where the smooth level becomes indistinguishable (the CV falls to TAU:
// N* = (1 − p)/(p·TAU²)), lies inside the confidence interval of the boundary measured on a ladder
// of footprints around it.
//
// Claim adequacy.choice-is-safe: on scenes the grid was not measured on (verify/claims/
// adequacy_scenes.h), a pixel rendered with the level the engine chooser picks differs from the
// exact level by more than TAU in no more lit pixels than safe choices would give.
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "verify/adequacy/binomial_adequacy.h"
#include "verify/claims/adequacy_scenes.h"
#include "verify/claims/claims.h"
#include "verify/stats/count_tests.h"
#include "verify/stats/mean_tests.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify {
namespace {

using adequacy::Cell;

constexpr const char* kPrediction = "adequacy.prediction-matches-measurement";
// The control's prediction takes N_P this much too large (5 %: CV 2.4 % low, P(no glint) shifted
// by 5 % of its log).
constexpr double kControlFacetScale = 1.05;
// The CV test needs the count's moments to be well estimated: only where N_P p ≥ this.
constexpr double kMinExpectedCount = 1;
// The boundary's threshold (the adequacy default) and the ladder of footprints N* · r measured
// around the predicted boundary; the control moves the prediction by 5 %.
constexpr double kBoundaryTau = adequacy::kDefaultThreshold;
constexpr double kBoundaryLadder[] = {0.5, 0.70710678118654752, 1.0, 1.4142135623730951, 2.0};
constexpr double kControlBoundaryScale = 1.05;

// Cells away from the degenerate p = 1 of deliot_belcour's peak: its off-peak half-vector
// (θ_h = atan 2α, p ≈ 0.04) and kneiphof_klein's 1° cap (p ≈ 1e-3 on the peak side).
std::vector<Cell> prediction_cells() {
  std::vector<Cell> cells;
  for (double n : {1.0, 10.0, 100.0, 1e3, 1e4, 1e6, 1e8}) {
    cells.push_back({"deliot_belcour", n, 0.1, 0, 30, std::atan(0.2) * 180 / std::numbers::pi, 2});
    cells.push_back({"kneiphof_klein", n, 0.1, 1, 30, std::atan(0.1) * 180 / std::numbers::pi, 1});
  }
  return cells;
}

struct PredictionRow {
  Cell cell;
  double p = 0;
  double cv = 0, cv_se = 0;  // measured CV and its delta-method standard error
  std::uint64_t zeros = 0, samples = 0;
  double p_cv = 1, p_zero = 1;                  // two-sided p-values against the prediction
  double control_p_cv = 1, control_p_zero = 1;  // against the prediction with N_P × 1.05
};

// One setting's smooth-level boundary: the exact level's CV on the ladder, the crossing of
// log CV = log TAU by a weighted least-squares line through (log N, log CV), and its standard
// error by the delta method; the crossing is tested against log N* (and log 1.05 N*, the
// control).
struct BoundaryRow {
  Cell cell;  // at N*
  double p = 0, predicted = 0, measured = 0, log_se = 0;
  double p_value = 1, control_p_value = 1;
};

struct PredictionMeasured {
  std::vector<PredictionRow> rows;
  std::vector<BoundaryRow> boundaries;
  HolmSidakResult genuine, control;
  double worst_cv_rel = 0;  // max |CV/CV_pred − 1|
};

double two_sided_z(double z) { return std::erfc(std::abs(z) / std::sqrt(2.0)); }

// The measured CV of `x` and its standard error (influence function of s/m).
std::pair<double, double> cv_and_se(const std::vector<double>& x) {
  const double n = double(x.size());
  double m = 0;
  for (double v : x) m += v;
  m /= n;
  double var = 0;
  for (double v : x) var += (v - m) * (v - m);
  var /= n;
  if (!(m > 0) || !(var > 0)) return {0, 0};
  const double cv = std::sqrt(var) / m;
  double s = 0, ss = 0;
  for (double v : x) {
    const double d = v - m, inf = cv * ((d * d - var) / (2 * var) - d / m);
    s += inf, ss += inf * inf;
  }
  return {cv, std::sqrt(std::max(ss / n - (s / n) * (s / n), 0.0) / n)};
}

// The two p-values of one cell's measurement against the prediction for N_P × scale.
std::pair<double, double> test_row(const PredictionRow& r, double scale) {
  const double n = r.cell.facets * scale;
  double p_cv = 1;
  if (r.cell.facets * r.p >= kMinExpectedCount && r.cv_se > 0)
    p_cv = two_sided_z((r.cv - binomial_count_cv(n, r.p)) / r.cv_se);
  const double p0 = binomial_zero_probability(n, r.p);
  const double p_zero = p0 > 0 && p0 < 1 ? binomial_test(r.zeros, r.samples, p0).p_value : 1;
  return {p_cv, p_zero};
}

PredictionRow measure_row(const Cell& c, int samples, std::uint64_t seed) {
  PredictionRow r;
  r.cell = c;
  r.p = adequacy::cell_probability_and_smooth(c).first;
  std::vector<double> x;
  adequacy::level_values(c, BinomialLevel::kExact, samples, seed, x);
  std::tie(r.cv, r.cv_se) = cv_and_se(x);
  for (double v : x) r.zeros += v == 0 ? 1 : 0;
  r.samples = x.size();
  std::tie(r.p_cv, r.p_zero) = test_row(r, 1);
  std::tie(r.control_p_cv, r.control_p_zero) = test_row(r, kControlFacetScale);
  return r;
}

// The settings whose boundary is measured: the two families' cells of prediction_cells (their
// N_P set to N*).
std::vector<Cell> boundary_cells() {
  return {{"deliot_belcour", 0, 0.1, 0, 30, std::atan(0.2) * 180 / std::numbers::pi, 2},
          {"kneiphof_klein", 0, 0.1, 1, 30, std::atan(0.1) * 180 / std::numbers::pi, 1}};
}

BoundaryRow measure_boundary(Cell c, int samples, std::uint64_t seed) {
  BoundaryRow r;
  r.p = adequacy::cell_probability_and_smooth(c).first;
  r.predicted = (1 - r.p) / (r.p * kBoundaryTau * kBoundaryTau);
  c.facets = r.predicted;
  r.cell = c;
  // Weighted least squares of y = log CV on x = log(N / N*), weights 1 / Var(log CV).
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  std::vector<double> x;
  for (std::size_t k = 0; k < std::size(kBoundaryLadder); ++k) {
    Cell at = c;
    at.facets = r.predicted * kBoundaryLadder[k];
    adequacy::level_values(at, BinomialLevel::kExact, samples, seed + k, x);
    const auto [cv, se] = cv_and_se(x);
    if (!(cv > 0) || !(se > 0)) return r;  // untestable: p-values stay 1
    const double w = (cv / se) * (cv / se), lx = std::log(kBoundaryLadder[k]), ly = std::log(cv);
    sw += w, sx += w * lx, sy += w * ly, sxx += w * lx * lx, sxy += w * lx * ly;
  }
  const double det = sw * sxx - sx * sx;
  const double slope = (sw * sxy - sx * sy) / det, intercept = (sxx * sy - sx * sxy) / det;
  const double var_a = sxx / det, var_b = sw / det, cov_ab = -sx / det;
  const double crossing = (std::log(kBoundaryTau) - intercept) / slope;  // log(N̂ / N*)
  // ∂crossing/∂a = −1/slope, ∂crossing/∂b = −crossing/slope.
  const double ga = -1 / slope, gb = -crossing / slope;
  r.log_se = std::sqrt(std::max(ga * ga * var_a + 2 * ga * gb * cov_ab + gb * gb * var_b, 0.0));
  r.measured = r.predicted * std::exp(crossing);
  r.p_value = two_sided_z(crossing / r.log_se);
  r.control_p_value = two_sided_z((crossing - std::log(kControlBoundaryScale)) / r.log_se);
  return r;
}

PredictionMeasured measure_prediction(Budget b) {
  const int samples = b == Budget::kQuick ? 100000 : 1000000;
  const std::vector<Cell> cells = prediction_cells();
  PredictionMeasured m;
  m.rows.resize(cells.size());
  tbb::parallel_for(std::size_t(0), cells.size(), [&](std::size_t i) {
    m.rows[i] = measure_row(cells[i], samples, check_seed(kPrediction, i));
  });
  const std::vector<Cell> settings = boundary_cells();
  m.boundaries.resize(settings.size());
  tbb::parallel_for(std::size_t(0), settings.size(), [&](std::size_t i) {
    m.boundaries[i] = measure_boundary(settings[i], samples, check_seed(kPrediction, 100 + 10 * i));
  });
  std::vector<double> genuine, control;
  for (const BoundaryRow& r : m.boundaries) {
    genuine.push_back(r.p_value);
    control.push_back(r.control_p_value);
  }
  for (const PredictionRow& r : m.rows) {
    genuine.insert(genuine.end(), {r.p_cv, r.p_zero});
    control.insert(control.end(), {r.control_p_cv, r.control_p_zero});
    const double pred = binomial_count_cv(r.cell.facets, r.p);
    if (pred > 0 && r.cell.facets * r.p >= kMinExpectedCount)
      m.worst_cv_rel = std::max(m.worst_cv_rel, std::abs(r.cv / pred - 1));
  }
  m.genuine = holm_sidak(genuine, check_level());
  m.control = holm_sidak(control, check_level());
  return m;
}

Verdict decide_prediction(const HolmSidakResult& hs) {
  return hs.rejections == 0 ? Verdict::kHoldsInRegime : Verdict::kFails;
}

std::string describe_boundary(const BoundaryRow& r) {
  const double z = normal_quantile(1 - check_level() / 2);
  return fmt::format("{} (p = {:.4g}): predicted N* = {:.4g}, measured {:.4g} (CI {:.4g}–{:.4g}, "
                     "p = {:.3g})",
                     r.cell.model, r.p, r.predicted, r.measured, r.measured * std::exp(-z * r.log_se),
                     r.measured * std::exp(z * r.log_se), r.p_value);
}

std::string describe_prediction(const PredictionMeasured& m) {
  std::string boundaries;
  for (const BoundaryRow& r : m.boundaries)
    boundaries += (boundaries.empty() ? "" : "; ") + describe_boundary(r);
  return fmt::format(
      "{} cells (deliot_belcour off-peak, kneiphof_klein 1° cap; N_P 1..1e8), {} positions each, "
      "exact counting: CV and P(no glint) against the closed forms; the smooth level's boundary "
      "(CV = TAU = {}) where the exact CV crosses TAU on N*·{{0.5, 0.71, 1, 1.41, 2}} ({} "
      "positions each; two-sided intervals at the per-test level): {}; {} of {} p-values rejected "
      "(Holm–Šidák at {:.2e}); max |CV/CV_pred − 1| = {:.4f} where N_P p ≥ 1; the real-time and "
      "small-count levels are not binomial and are outside this regime (their differences are "
      "the adequacy table's)",
      m.rows.size(), m.rows.empty() ? 0 : m.rows.front().samples, kBoundaryTau,
      m.rows.empty() ? 0 : m.rows.front().samples, boundaries, m.genuine.rejections,
      m.genuine.raw.size(), check_level(), m.worst_cv_rel);
}

CheckResult run_prediction(Budget b) {
  CheckResult r;
  r.regime = "the exact counting level (its count is Binomial(N_P, p)); N_P in [1, 1e8]; CV "
             "tested where N_P p >= 1, P(no glint) everywhere; the smooth level's boundary at "
             "TAU = 0.02 for the same two settings";
  const PredictionMeasured m = measure_prediction(b);
  r.verdict = decide_prediction(m.genuine);
  r.detail = describe_prediction(m);
  r.statistic = "max |CV_measured / CV_predicted − 1| where N_P p ≥ 1, exact counting (the p-value: "
                "Holm–Šidák over CV and P(no glint) tests)";
  r.p_value = m.genuine.raw.empty()
                  ? 1.0
                  : *std::min_element(m.genuine.adjusted.begin(), m.genuine.adjusted.end());
  r.value = m.worst_cv_rel;
  r.raw_p_values = m.genuine.raw;
  r.configurations = int(m.genuine.raw.size());
  r.control_p_value = *std::min_element(m.control.adjusted.begin(), m.control.adjusted.end());
  // The boundary tests come first in the family.
  std::size_t boundary_rejections = 0;
  for (std::size_t i = 0; i < m.boundaries.size(); ++i)
    boundary_rejections += m.control.reject[i] ? 1 : 0;
  r.control = fmt::format(
      "the prediction with N_P × {:.2f} and the boundary at N* × {:.2f}: {} of {} p-values "
      "rejected (min adjusted p = {:.3g}), the boundary's {} of {}",
      kControlFacetScale, kControlBoundaryScale, m.control.rejections, m.control.raw.size(),
      *r.control_p_value, boundary_rejections, m.boundaries.size());
  record_control(r, decide_prediction(m.control));
  return r;
}

// One run on a known-correct input: a mid-size footprint's CV against its prediction.
double calibrate_prediction(std::uint64_t seed) {
  const Cell c{"deliot_belcour", 1000, 0.1, 0, 30, std::atan(0.2) * 180 / std::numbers::pi, 2};
  return measure_row(c, 20000, seed).p_cv;
}

// ---- adequacy.choice-is-safe ----------------------------------------------------------------

constexpr const char* kChoiceSafe = "adequacy.choice-is-safe";
// The control runs the chooser at TAU × this: it then takes cheaper levels where they differ from
// the exact one by up to 10 TAU (the smooth level up to a CV of 0.1), which must be caught.
constexpr double kControlTauScale = 10;

adequacy::SceneOptions choice_options(Budget b) {
  adequacy::SceneOptions o;
  o.width = o.height = b == Budget::kQuick ? 64 : 128;
  o.realisations = b == Budget::kQuick ? 256 : 1024;
  return o;
}

struct ChoiceMeasured {
  std::vector<adequacy::SafetyTally> scenes;
  adequacy::SafetyTally total;
  adequacy::SafetyDecision decision;
};

// Every scene rendered with the engine chooser at `chooser_tau`, differences compared with the
// rule's TAU, decided at the suite's per-check level.
ChoiceMeasured measure_choice(const adequacy::SceneOptions& base, double chooser_tau) {
  ChoiceMeasured m;
  const std::vector<adequacy::ChoiceScene> scenes = adequacy::choice_scenes();
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    adequacy::SceneOptions o = base;
    o.chooser_tau = chooser_tau;
    o.seed = check_seed(kChoiceSafe, i);
    m.scenes.push_back(adequacy::tally(adequacy::render_choice_scene(scenes[i], o)));
    adequacy::add(m.total, m.scenes.back());
  }
  m.decision = adequacy::decide_choice_safety(m.total, check_level());
  return m;
}

std::string describe_choice(const ChoiceMeasured& m) {
  const std::vector<adequacy::ChoiceScene> scenes = adequacy::choice_scenes();
  std::string per_scene;
  for (std::size_t i = 0; i < m.scenes.size(); ++i) {
    const adequacy::SafetyTally& t = m.scenes[i];
    per_scene +=
        fmt::format("{}{} ({}): {} lit, {} cheaper, {} exceed", per_scene.empty() ? "" : "; ",
                    scenes[i].name, scenes[i].model, t.lit, t.cheaper, t.exceeds);
  }
  std::string levels;
  for (int l = 0; l < kBinomialLevels; ++l)
    levels += fmt::format("{}{} {}", l ? ", " : "", kBinomialLevelNames[std::size_t(l)],
                          m.total.by_level[std::size_t(l)]);
  return fmt::format(
      "{} of {} lit pixels exceed TAU (fraction {:.4g}; allowed ≤ {} = {:.4g}, "
      "one-sided exact binomial p = {:.3g} against rate ≤ {}); chosen levels of "
      "the lit pixels: {}; {}",
      m.total.exceeds, m.total.lit, m.decision.fraction, m.decision.allowed,
      m.decision.allowed_fraction, m.decision.p_value, adequacy::kPixelFlagRate, levels, per_scene);
}

CheckResult run_choice(Budget b) {
  CheckResult r;
  const adequacy::SceneOptions o = choice_options(b);
  r.regime = fmt::format(
      "the binomial family (deliot_belcour, kneiphof_klein; levels smooth, realtime, small_count, "
      "exact) and its engine chooser at TAU = {}, GGX alpha = {}, on six scenes outside the "
      "adequacy grid (a plane from 1.6 to 30 units under a point light and under a spherical "
      "light, a sphere under a point light, each at two facet densities), {}x{} pixels, {} "
      "realisations per pixel; the other families have no measured levels",
      o.tau, adequacy::kSceneAlpha, o.width, o.height, o.realisations);
  r.statistic = fmt::format(
      "fraction of lit pixels (exact level non-zero at >= {} of the realisations) whose chosen "
      "level's mean or CV differs from the exact level's by more than TAU (a lower bound at "
      "one-sided {} each above TAU)",
      adequacy::kMinLitPositions, adequacy::kPixelFlagRate / 2);
  const ChoiceMeasured m = measure_choice(o, o.tau);
  r.verdict = m.decision.verdict;
  r.value = m.decision.fraction;
  r.bound = m.decision.allowed_fraction;
  r.configurations = int(m.total.lit);
  r.detail = describe_choice(m);
  const ChoiceMeasured c = measure_choice(o, o.tau * kControlTauScale);
  r.control =
      fmt::format("the chooser run with TAU × {:g}: {}", kControlTauScale, describe_choice(c));
  record_control(r, c.decision.verdict);
  r.power = fmt::format(
      "rejects once more than {} of the {} lit pixels ({:.3g}) exceed TAU, where safe choices "
      "flag at most a fraction {}; the TAU × {:g} chooser makes {:.3g} exceed",
      m.decision.allowed, m.total.lit, m.decision.allowed_fraction, adequacy::kPixelFlagRate,
      kControlTauScale, c.decision.fraction);
  return r;
}

}  // namespace

std::vector<Check> adequacy_checks() {
  return {{kPrediction, "glintlab (adequacy of the binomial family)",
           "Kneiphof & Klein 2024 Eq. 11, 16; Deliot & Belcour 2023", Verdict::kHoldsInRegime,
           run_prediction, calibrate_prediction},
          // The decision is a count against the exact binomial test's critical count, reported as
          // a bound (the test's p-value is in the detail): a p-valued check would take a share of
          // check_level() and move every recorded claim's level.
          {kChoiceSafe, "glintlab (adequacy of the binomial family)",
           "core/glints/adequacy.h chooser; Kneiphof & Klein 2024 Eq. 16; Deliot & Belcour 2023",
           Verdict::kHoldsInRegime, run_choice}};
}

}  // namespace glintlab::verify

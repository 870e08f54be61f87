// The measurements of adequacy.prediction-matches-measurement (verify/claims/adequacy/common.h).
#include "verify/claims/adequacy/common.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "verify/check.h"
#include "verify/stats/count_tests.h"
#include "verify/stats/mean_tests.h"

namespace glintlab::verify::adequacy_claims {
double two_sided_z(double z) { return std::erfc(std::abs(z) / std::sqrt(2.0)); }

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

PairedDifference paired_difference(const std::vector<double>& x, const std::vector<double>& ref) {
  PairedDifference r;
  const double n = double(x.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i], my += ref[i];
  mx /= n, my /= n;
  double vx = 0, vy = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    vx += (x[i] - mx) * (x[i] - mx), vy += (ref[i] - my) * (ref[i] - my);
  vx /= n, vy /= n;
  if (!(mx > 0) || !(my > 0) || !(vx > 0) || !(vy > 0)) return r;
  const double cx = std::sqrt(vx) / mx, cy = std::sqrt(vy) / my;
  double sm = 0, smm = 0, sc = 0, scc = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double dx = x[i] - mx, dy = ref[i] - my;
    const double im = (dx - (mx / my) * dy) / my;
    const double ic =
        cx * ((dx * dx - vx) / (2 * vx) - dx / mx) - cy * ((dy * dy - vy) / (2 * vy) - dy / my);
    sm += im, smm += im * im, sc += ic, scc += ic * ic;
  }
  r.ok = true;
  r.mean_diff = mx / my - 1;
  r.cv_diff = cx - cy;
  r.mean_diff_se = std::sqrt(std::max(smm / n - (sm / n) * (sm / n), 0.0) / n);
  r.cv_diff_se = std::sqrt(std::max(scc / n - (sc / n) * (sc / n), 0.0) / n);
  return r;
}

namespace {

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

}  // namespace

LadderFit fit_crossing(std::span<const double> ladder,
                       const std::vector<std::pair<double, double>>& cv_se, double tau) {
  LadderFit f;
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < ladder.size(); ++k) {
    const auto [cv, se] = cv_se[k];
    if (!(cv > 0) || !(se > 0)) return f;  // untestable
    const double w = (cv / se) * (cv / se), lx = std::log(ladder[k]), ly = std::log(cv);
    sw += w, sx += w * lx, sy += w * ly, sxx += w * lx * lx, sxy += w * lx * ly;
  }
  const double det = sw * sxx - sx * sx;
  const double slope = (sw * sxy - sx * sy) / det, intercept = (sxx * sy - sx * sxy) / det;
  const double var_a = sxx / det, var_b = sw / det, cov_ab = -sx / det;
  f.crossing = (std::log(tau) - intercept) / slope;  // log(N̂ / N_ref)
  // ∂crossing/∂a = −1/slope, ∂crossing/∂b = −crossing/slope.
  const double ga = -1 / slope, gb = -f.crossing / slope;
  f.log_se = std::sqrt(std::max(ga * ga * var_a + 2 * ga * gb * cov_ab + gb * gb * var_b, 0.0));
  f.slope = slope;
  f.ok = true;
  return f;
}

namespace {

// The ladder fit of k16_exact's CV around `predicted`, and the smooth level's largest mean
// difference on it.
LadderFit kemppinen_ladder(const adequacy::KemppinenCell& row, double predicted, int samples,
                           std::uint64_t seed, double& max_mean_diff) {
  std::vector<std::pair<double, double>> cv_se;
  std::vector<double> x, smooth;
  for (std::size_t k = 0; k < std::size(kKemppinenLadder); ++k) {
    adequacy::KemppinenCell at = row;
    at.points = predicted * kKemppinenLadder[k];
    adequacy::kemppinen_level_values(at, KemppinenLevel::kK16Exact, samples, seed + k, x);
    adequacy::kemppinen_level_values(at, KemppinenLevel::kSmooth, 1, seed + k, smooth);
    cv_se.push_back(cv_and_se(x));
    double mean = 0;
    for (double v : x) mean += v;
    mean /= double(x.size());
    if (mean > 0) max_mean_diff = std::max(max_mean_diff, std::abs(smooth[0] / mean - 1));
  }
  return fit_crossing(kKemppinenLadder, cv_se, kBoundaryTau);
}

}  // namespace

std::vector<Cell> prediction_cells() {
  std::vector<Cell> cells;
  for (double n : {1.0, 10.0, 100.0, 1e3, 1e4, 1e6, 1e8}) {
    cells.push_back({"deliot_belcour", n, 0.1, 0, 30, std::atan(0.2) * 180 / std::numbers::pi, 2});
    cells.push_back({"kneiphof_klein", n, 0.1, 1, 30, std::atan(0.1) * 180 / std::numbers::pi, 1});
  }
  // The area family after them (so the cells above keep their configurations and seeds).
  for (double n : {1.0, 10.0, 100.0, 1e3, 1e4, 1e6, 1e8})
    cells.push_back(
        {"kneiphof_klein_area", n, 0.1, 1, 30, std::atan(0.1) * 180 / std::numbers::pi, 1});
  return cells;
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

std::vector<Cell> boundary_cells() {
  return {{"deliot_belcour", 0, 0.1, 0, 30, std::atan(0.2) * 180 / std::numbers::pi, 2},
          {"kneiphof_klein", 0, 0.1, 1, 30, std::atan(0.1) * 180 / std::numbers::pi, 1},
          {"kneiphof_klein_area", 0, 0.1, 1, 30, std::atan(0.1) * 180 / std::numbers::pi, 1}};
}

BoundaryRow measure_boundary(Cell c, int samples, std::uint64_t seed) {
  BoundaryRow r;
  r.p = adequacy::cell_probability_and_smooth(c).first;
  r.predicted = (1 - r.p) / (r.p * kBoundaryTau * kBoundaryTau);
  c.facets = r.predicted;
  r.cell = c;
  std::vector<std::pair<double, double>> cv_se;
  std::vector<double> x;
  for (std::size_t k = 0; k < std::size(kBoundaryLadder); ++k) {
    Cell at = c;
    at.facets = r.predicted * kBoundaryLadder[k];
    adequacy::level_values(at, BinomialLevel::kExact, samples, seed + k, x);
    cv_se.push_back(cv_and_se(x));
    if (!(cv_se.back().first > 0) || !(cv_se.back().second > 0)) return r;  // p-values stay 1
  }
  const LadderFit f = fit_crossing(kBoundaryLadder, cv_se, kBoundaryTau);
  r.log_se = f.log_se;
  r.measured = r.predicted * std::exp(f.crossing);
  r.p_value = two_sided_z(f.crossing / r.log_se);
  r.control_p_value = two_sided_z((f.crossing - std::log(kControlBoundaryScale)) / r.log_se);
  return r;
}

std::vector<adequacy::KemppinenCell> kemppinen_boundary_rows() {
  adequacy::KemppinenGridAxes axes;
  axes.points = {1};
  axes.alpha = {0.1, 0.3};
  axes.theta_i_deg = {0, 60};
  return adequacy::make_kemppinen_grid({"kemppinen_ggx"}, axes);
}

KemppinenBoundaryRow measure_kemppinen_boundary(const adequacy::KemppinenCell& row, int samples,
                                                std::uint64_t seed, double predicted_scale,
                                                double bound_scale) {
  KemppinenBoundaryRow r;
  r.row = row;
  const double exact =
      adequacy::kemppinen_exact_cv_boundary(row, KemppinenLevel::kK16Exact, kBoundaryTau);
  r.predicted = exact * predicted_scale;
  r.bound = adequacy::kemppinen_predicted_boundaries(row, kBoundaryTau)[0] * bound_scale;
  if (!(exact > 0)) return r;  // no prediction: p-values stay 1
  adequacy::KemppinenCell at = row;
  at.points = exact;
  r.predicted_mean = adequacy::kemppinen_exact_moments(at, KemppinenLevel::kK16Exact).mean;
  // The prediction passed through the measurement's estimator: the same line fitted through the
  // construction's CV at the ladder's points (equal weights: the measured CVs' relative errors
  // are alike). The CV is curved in log N there, so the line's crossing is not N_pred itself
  // (within ±1.2 % on the quick grid's rows).
  std::vector<std::pair<double, double>> predicted_cv;
  for (double f : kKemppinenLadder) {
    at.points = exact * f;
    const double cv = adequacy::kemppinen_exact_moments(at, KemppinenLevel::kK16Exact).cv();
    predicted_cv.emplace_back(cv, cv);
  }
  const LadderFit pf = fit_crossing(kKemppinenLadder, predicted_cv, kBoundaryTau);
  if (!pf.ok) return r;
  r.predicted_fit = exact * std::exp(pf.crossing) * predicted_scale;
  const LadderFit f = kemppinen_ladder(row, r.predicted, samples, seed, r.max_mean_diff);
  const LadderFit g =
      kemppinen_ladder(row, r.predicted, samples, seed + kReplicateSeed, r.max_mean_diff);
  if (!f.ok || !g.ok) return r;
  r.log_se = f.log_se;
  r.slope = f.slope;
  r.measured = r.predicted * std::exp(f.crossing);
  r.replicate = r.predicted * std::exp(g.crossing);
  r.replicate_log_se = g.log_se;
  // log(measured / predicted through the fit), the ladder centred on the prediction.
  const double off = std::log(r.measured / r.predicted_fit);
  r.p_value = two_sided_z(off / r.log_se);
  r.moved_p_value = two_sided_z((off - std::log(kKemppinenControlScale)) / r.log_se);
  r.replicate_p_value = two_sided_z((f.crossing - g.crossing) / std::hypot(f.log_se, g.log_se));
  // One-sided: the bound is refuted where log(measured / bound) is significantly above 0.
  const auto above = [&](double bound) {
    return bound > 0 ? 0.5 * std::erfc(std::log(r.measured / bound) / r.log_se / std::sqrt(2.0))
                     : 1.0;
  };
  r.bound_p_value = above(r.bound);
  r.moved_bound_p_value = above(r.predicted_fit * kKemppinenBoundControlScale);
  return r;
}

std::vector<std::pair<adequacy::KemppinenCell, KemppinenLevel>> kemppinen_side_rows() {
  std::vector<std::pair<adequacy::KemppinenCell, KemppinenLevel>> out;
  for (const adequacy::KemppinenCell& row : kemppinen_boundary_rows())
    for (KemppinenLevel l : kKemppinenSideLevels) out.emplace_back(row, l);
  return out;
}

KemppinenSideRow measure_kemppinen_side(const adequacy::KemppinenCell& row, KemppinenLevel level,
                                        int samples, std::uint64_t seed) {
  KemppinenSideRow r;
  r.row = row;
  r.level = level;
  r.predicted = adequacy::kemppinen_exact_level_boundary(row, level, kBoundaryTau);
  const std::size_t side = std::size_t(kemppinen_level_side(level));  // kKemppinenBoundaryLevels
  r.bound = adequacy::kemppinen_predicted_boundaries(row, kBoundaryTau)[side];
  if (!(r.predicted > 0.01)) return r;  // no boundary in the scan: p-values stay 1
  r.row.points = r.predicted;
  r.expected = adequacy::kemppinen_exact_difference(r.row, level);
  adequacy::KemppinenCell moved = r.row;
  moved.points = r.predicted * kKemppinenSideControlScale;
  r.moved = adequacy::kemppinen_exact_difference(moved, level);
  std::vector<double> x, ref;
  adequacy::kemppinen_level_values(r.row, KemppinenLevel::kK16Exact, samples, seed, ref);
  adequacy::kemppinen_level_values(r.row, level, samples, seed, x);
  // The signed statistics and their errors by the empirical influence functions over the paired
  // positions (as compare_to_exact bounds them).
  test_sides(r, paired_difference(x, ref));
  return r;
}

std::size_t tail_rejections(const HolmSidakResult& hs, std::size_t count) {
  std::size_t n = 0;
  for (std::size_t i = hs.reject.size() - count; i < hs.reject.size(); ++i)
    n += hs.reject[i] ? 1 : 0;
  return n;
}

std::string describe_kemppinen_sides(int samples, std::span<const KemppinenSideRow> sides,
                                     std::size_t rejected) {
  std::string rows;
  double worst_mean = 0, worst_cv = 0, ratio_lo = INFINITY, ratio_hi = 0;
  for (const KemppinenSideRow& r : sides) {
    rows += fmt::format(
        "{}θ_i {:g}° α {:g} θ_h {:.1f}° {}: N_pred {:.4g} (bound {:.4g}); mean diff {:+.4f} "
        "predicted {:+.4f} (se {:.4f}), CV diff {:+.4f} predicted {:+.4f} (se {:.4f})",
        rows.empty() ? "" : "; ", r.row.theta_i_deg, r.row.alpha, r.row.theta_h_deg,
        kKemppinenLevelNames[std::size_t(r.level)], r.predicted, r.bound, r.mean_diff,
        r.expected.mean_diff, r.mean_diff_se, r.cv_diff, r.expected.cv_diff, r.cv_diff_se);
    if (r.mean_diff_se > 0)
      worst_mean = std::max(worst_mean, std::abs(r.mean_diff - r.expected.mean_diff));
    if (r.cv_diff_se > 0) worst_cv = std::max(worst_cv, std::abs(r.cv_diff - r.expected.cv_diff));
    if (r.predicted > 0) {
      ratio_lo = std::min(ratio_lo, r.bound / r.predicted);
      ratio_hi = std::max(ratio_hi, r.bound / r.predicted);
    }
  }
  return fmt::format(
      "Kemppinen sides k = 1, 4, 9 (exact erf) against k16_exact: each side's boundary predicted "
      "by the construction's exact moments (both statistics within TAU from there on), the "
      "side and k16_exact measured at it at the same {} positions, the signed mean difference "
      "and CV difference tested against their predicted values, {} sides: {}; max |measured − "
      "predicted| {:.4f} (mean difference), {:.4f} (CV difference); the chooser's boundary / "
      "the predicted one {:.3g} to {:.3g}; {} of {} p-values rejected",
      samples, sides.size(), rows, worst_mean, worst_cv, ratio_lo, ratio_hi, rejected,
      2 * sides.size());
}

std::string describe_kemppinen_boundaries(int samples,
                                          std::span<const KemppinenBoundaryRow> rows_in,
                                          std::size_t point_rejected, std::size_t bound_rejected) {
  const double q = normal_quantile(1 - check_level() / 2);
  std::string rows;
  double lo = INFINITY, hi = 0, raw_lo = INFINITY, raw_hi = 0, bound_lo = INFINITY, bound_hi = 0,
         max_mean = 0, pred_mean = 0, slope_lo = 0, slope_hi = -INFINITY;
  for (const KemppinenBoundaryRow& r : rows_in) {
    slope_lo = std::min(slope_lo, r.slope);
    slope_hi = std::max(slope_hi, r.slope);
    rows += fmt::format(
        "{}θ_i {:g}° α {:g} θ_h {:.1f}°: predicted {:.4g} (through the line fit {:.4g}), "
        "measured {:.4g} (CI {:.4g}–{:.4g}, p = {:.3g}), bound {:.4g} (one-sided p = {:.3g})",
        rows.empty() ? "" : "; ", r.row.theta_i_deg, r.row.alpha, r.row.theta_h_deg, r.predicted,
        r.predicted_fit, r.measured, r.measured * std::exp(-q * r.log_se),
        r.measured * std::exp(q * r.log_se), r.p_value, r.bound, r.bound_p_value);
    if (r.measured > 0) {
      lo = std::min(lo, r.predicted_fit / r.measured);
      hi = std::max(hi, r.predicted_fit / r.measured);
      raw_lo = std::min(raw_lo, r.predicted / r.measured);
      raw_hi = std::max(raw_hi, r.predicted / r.measured);
      bound_lo = std::min(bound_lo, r.bound / r.measured);
      bound_hi = std::max(bound_hi, r.bound / r.measured);
    }
    max_mean = std::max(max_mean, r.max_mean_diff);
    pred_mean = std::max(pred_mean, std::abs(1 / r.predicted_mean - 1));
  }
  const std::size_t n = rows_in.size();
  return fmt::format(
      "Kemppinen family (kemppinen_ggx, the smooth level against k16_exact): the points per "
      "footprint where k16_exact's CV crosses TAU, fitted on N_pred·{{0.95, 0.975, 1, 1.025, "
      "1.05}} ({} positions each), against the construction's exact CV (the point prediction, "
      "passed through the same line fit, two-sided) and the chooser's bound (one-sided), {} "
      "rows: {}; predicted through the fit / measured {:.4f} to {:.4f} (the prediction itself "
      "/ measured {:.4f} to {:.4f}); the chooser's bound / measured {:.3g} to {:.3g} (how "
      "conservative it is); "
      "fitted d log CV / d log N {:.3g} to {:.3g}; the smooth level's mean difference at most "
      "{:.3g} on the ladders, {:.3g} by the construction at the prediction (the CV decides); {} "
      "of {} point predictions and {} of {} bounds rejected",
      samples, n, rows, lo, hi, raw_lo, raw_hi, bound_lo, bound_hi, slope_lo, slope_hi, max_mean,
      pred_mean, point_rejected, n, bound_rejected, n);
}

}  // namespace glintlab::verify::adequacy_claims

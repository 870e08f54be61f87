// The measurements of adequacy.prediction-matches-measurement (verify/claims/adequacy/common.h).
#include "verify/claims/adequacy/common.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "verify/stats/count_tests.h"

namespace glintlab::verify::adequacy_claims {
namespace {

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

// The crossing of log CV = log TAU by a weighted least-squares line through (log r, log CV) over
// a ladder of footprints r × N_ref (weights 1 / Var(log CV)), as log(N̂ / N_ref), and its
// standard error by the delta method. `ok` is false where a CV is not measurable.
struct LadderFit {
  bool ok = false;
  double crossing = 0, log_se = 0;
  double slope = 0;  // d log CV / d log N
};
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
  r.mean_diff = mx / my - 1;
  r.cv_diff = cx - cy;
  r.mean_diff_se = std::sqrt(std::max(smm / n - (sm / n) * (sm / n), 0.0) / n);
  r.cv_diff_se = std::sqrt(std::max(scc / n - (sc / n) * (sc / n), 0.0) / n);
  const auto p = [](double measured, double predicted, double se) {
    return se > 0 ? two_sided_z((measured - predicted) / se) : 1.0;
  };
  r.p_mean = p(r.mean_diff, r.expected.mean_diff, r.mean_diff_se);
  r.p_cv = p(r.cv_diff, r.expected.cv_diff, r.cv_diff_se);
  r.moved_p_mean = p(r.mean_diff, r.moved.mean_diff, r.mean_diff_se);
  r.moved_p_cv = p(r.cv_diff, r.moved.cv_diff, r.cv_diff_se);
  return r;
}

std::size_t tail_rejections(const HolmSidakResult& hs, std::size_t count) {
  std::size_t n = 0;
  for (std::size_t i = hs.reject.size() - count; i < hs.reject.size(); ++i)
    n += hs.reject[i] ? 1 : 0;
  return n;
}

}  // namespace glintlab::verify::adequacy_claims

// The Chermain family's part of adequacy.prediction-matches-measurement
// (verify/claims/adequacy/chermain_prediction.h).
#include "verify/claims/adequacy/chermain_prediction.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "verify/check.h"
#include "verify/claims/adequacy/common.h"
#include "verify/stats/mean_tests.h"

namespace glintlab::verify::adequacy_claims {

using adequacy::ChermainCell;

std::vector<ChermainCell> chermain_boundary_rows() {
  std::vector<ChermainCell> rows;
  for (double dh : {0.0, 0.02})
    for (double ti : {0.0, 60.0})
      for (int h : {0, 2})
        rows.push_back(
            {"chermain", 1, 0.1, ti, std::atan(0.1 * h) * 180 / std::numbers::pi, h, dh});
  return rows;
}

std::vector<std::pair<ChermainCell, ChermainLevel>> chermain_dictionary_rows() {
  std::vector<std::pair<ChermainCell, ChermainLevel>> out;
  for (const ChermainCell& row : chermain_boundary_rows())
    for (ChermainLevel l : kChermainDictionaryLevels)
      out.emplace_back(row, row.dh > 0 ? ChermainLevel(int(l) + 1) : l);
  return out;
}

ChermainSmoothRow measure_chermain_smooth_row(const ChermainCell& row, int samples,
                                              std::uint64_t seed) {
  ChermainSmoothRow r;
  r.row = row;
  r.predicted = adequacy::chermain_smooth_boundary(row, kBoundaryTau, kChermainRotations);
  if (!(r.predicted > 0)) return r;
  ChermainCell at = row;
  at.facets = r.predicted;
  r.predicted_mean_diff = adequacy::chermain_exact_moments(at, kChermainRotations).mean_diff();
  // The prediction through the measurement's estimator (equal weights, as the Kemppinen part).
  std::vector<std::pair<double, double>> predicted_cv, measured_cv;
  std::vector<double> x;
  for (std::size_t k = 0; k < std::size(kChermainLadder); ++k) {
    at.facets = r.predicted * kChermainLadder[k];
    const double cv = adequacy::chermain_exact_moments(at, kChermainRotations).cv();
    predicted_cv.emplace_back(cv, cv);
    adequacy::chermain_level_values(at, kChermainMostComplete, samples, seed + k, x);
    measured_cv.push_back(cv_and_se(x));
  }
  const LadderFit pf = fit_crossing(kChermainLadder, predicted_cv, kBoundaryTau);
  const LadderFit f = fit_crossing(kChermainLadder, measured_cv, kBoundaryTau);
  if (!pf.ok || !f.ok) return r;
  r.predicted_fit = r.predicted * std::exp(pf.crossing);
  r.measured = r.predicted * std::exp(f.crossing);
  r.log_se = f.log_se;
  r.slope = f.slope;
  const double off = std::log(r.measured / r.predicted_fit);
  r.p_value = two_sided_z(off / r.log_se);
  r.moved_p_value = two_sided_z((off - std::log(kChermainControlScale)) / r.log_se);
  return r;
}

ChermainDictionaryRow measure_chermain_dictionary_row(const ChermainCell& row, ChermainLevel level,
                                                      int samples, std::uint64_t seed) {
  ChermainDictionaryRow r;
  r.row = row;
  r.level = level;
  r.identical_facets =
      adequacy::chermain_identical_facets(chermain_dictionary_levels(level), row.theta_i_deg);
  // The identity, on every position just below it.
  std::vector<double> x, ref;
  ChermainCell at = row;
  at.facets = r.identical_facets * kChermainIdentityScale;
  adequacy::chermain_level_values(at, level, samples, seed, x);
  adequacy::chermain_level_values(at, kChermainMostComplete, samples, seed, ref);
  r.identical = x == ref;
  r.predicted =
      adequacy::chermain_dictionary_boundary(row, level, kBoundaryTau, kChermainRotations);
  if (!r.identical) {
    r.p_mean = r.p_cv = r.moved_p_mean = r.moved_p_cv = 0;  // a failed construction
    return r;
  }
  if (!(r.predicted > 0)) return r;  // no boundary within the LOD: p-values stay 1
  r.row.facets = r.predicted;
  r.expected = adequacy::chermain_exact_difference(r.row, level, kChermainRotations);
  at.facets = r.predicted * kChermainControlScale;
  r.moved = adequacy::chermain_exact_difference(at, level, kChermainRotations);
  adequacy::chermain_level_values(r.row, level, samples, seed + 1, x);
  adequacy::chermain_level_values(r.row, kChermainMostComplete, samples, seed + 1, ref);
  test_sides(r, paired_difference(x, ref));
  return r;
}

void append_chermain_p_values(std::span<const ChermainSmoothRow> smooth,
                              std::span<const ChermainDictionaryRow> dict,
                              std::vector<double>& genuine, std::vector<double>& moved) {
  for (const ChermainSmoothRow& r : smooth) {
    genuine.push_back(r.p_value);
    moved.push_back(r.moved_p_value);
  }
  for (const ChermainDictionaryRow& r : dict) {
    genuine.insert(genuine.end(), {r.p_mean, r.p_cv});
    moved.insert(moved.end(), {r.moved_p_mean, r.moved_p_cv});
  }
}

namespace {
std::size_t rejections(const HolmSidakResult& hs, std::size_t begin, std::size_t count) {
  std::size_t n = 0;
  for (std::size_t i = begin; i < begin + count && i < hs.reject.size(); ++i)
    n += hs.reject[i] ? 1 : 0;
  return n;
}
}  // namespace

std::string describe_chermain(std::span<const ChermainSmoothRow> smooth,
                              std::span<const ChermainDictionaryRow> dict, int samples,
                              const HolmSidakResult& hs, std::size_t begin) {
  const double q = normal_quantile(1 - check_level() / 2);
  std::string rows, sides;
  double lo = INFINITY, hi = 0, max_mean = 0;
  for (const ChermainSmoothRow& r : smooth) {
    rows += fmt::format(
        "{}θ_i {:g}° θ_h {:.1f}° dh {:g}: predicted {:.4g} (through the line fit {:.4g}), "
        "measured {:.4g} (CI {:.4g}–{:.4g}, p = {:.3g})",
        rows.empty() ? "" : "; ", r.row.theta_i_deg, r.row.theta_h_deg, r.row.dh, r.predicted,
        r.predicted_fit, r.measured, r.measured * std::exp(-q * r.log_se),
        r.measured * std::exp(q * r.log_se), r.p_value);
    if (r.measured > 0) {
      lo = std::min(lo, r.predicted_fit / r.measured);
      hi = std::max(hi, r.predicted_fit / r.measured);
    }
    max_mean = std::max(max_mean, std::abs(r.predicted_mean_diff));
  }
  std::size_t identical = 0;
  for (const ChermainDictionaryRow& r : dict) {
    identical += r.identical ? 1 : 0;
    sides += fmt::format(
        "{}θ_i {:g}° θ_h {:.1f}° {}: identical below {:.4g} ({}), boundary {:.4g}; mean diff "
        "{:+.4f} predicted {:+.4f} (se {:.4f}), CV diff {:+.4f} predicted {:+.4f} (se {:.4f})",
        sides.empty() ? "" : "; ", r.row.theta_i_deg, r.row.theta_h_deg,
        kChermainLevelNames[std::size_t(r.level)], r.identical_facets,
        r.identical ? "bit for bit" : "NOT identical", r.predicted, r.mean_diff,
        r.expected.mean_diff, r.mean_diff_se, r.cv_diff, r.expected.cv_diff, r.cv_diff_se);
  }
  return fmt::format(
      "Chermain family (chermain, default material, α 0.1): the smooth level's boundary, where "
      "dict16_ggaa's CV crosses TAU, fitted on N_pred·{{0.95, 0.975, 1, 1.025, 1.05}} ({} "
      "positions each), against the construction's exact moments (through the same line fit, "
      "two-sided), {} rows: {}; predicted through the fit / measured {:.4f} to {:.4f}; the smooth "
      "level's mean difference by the construction at most {:.3g} there (the CV decides); {} of "
      "{} rejected. Dictionaries: dictL identical to dict16_ggaa below density·4^(L−11)·cos θ_i "
      "(checked at 0.99 times it at every position: {} of {}), the boundary past it where the "
      "construction's |mean diff| or |CV diff| reaches TAU, the two signed statistics measured "
      "there ({} positions, dictL and dict16_ggaa at the same ones) against the construction's: "
      "{}; {} of {} p-values rejected",
      samples, smooth.size(), rows, lo, hi, max_mean, rejections(hs, begin, smooth.size()),
      smooth.size(), identical, dict.size(), samples, sides,
      rejections(hs, begin + smooth.size(), 2 * dict.size()), 2 * dict.size());
}

std::string chermain_moved_text(std::span<const ChermainSmoothRow> smooth,
                                std::span<const ChermainDictionaryRow> dict,
                                const HolmSidakResult& hs, std::size_t begin) {
  return fmt::format(
      "the Chermain smooth boundaries at N_pred × {:.2f}: {} of {} rejected; the dictionary "
      "statistics predicted at N_pred × {:.2f}: {} of {}",
      kChermainControlScale, rejections(hs, begin, smooth.size()), smooth.size(),
      kChermainControlScale, rejections(hs, begin + smooth.size(), 2 * dict.size()),
      2 * dict.size());
}

}  // namespace glintlab::verify::adequacy_claims

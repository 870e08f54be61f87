// The Chermain family's part of adequacy.prediction-matches-measurement: the construction's
// boundaries (verify/adequacy/chermain_adequacy.h) against the measured ones, row by row.
//
// - The smooth level's boundary: where dict16_ggaa's CV over positions falls to TAU, predicted by
//   the construction's exact moments (chermain_smooth_boundary: the dictionary's own tables, Eq.
//   3–6, both LODs, the shared draws), measured as the crossing of a weighted least-squares line
//   through (log N, log CV) on the ladder N_pred × {0.95, 0.975, 1, 1.025, 1.05} (narrow: the CV is
//   a sawtooth in N, one tooth per LOD), the prediction passed through the same line fit (the
//   construction's CV at the ladder's points), tested two-sided.
// - Each dictionary's boundary (dict4, dict8, dict12; GGAA as the row's dh asks): dictL is
//   dict16_ggaa bit for bit below chermain_identical_facets(L, θ_i) — checked at 0.99 times it on
//   every position (a difference there is a failed construction: both p-values 0) — and past it the
//   coarser LOD's weight brings in the level dictL replaces by the smooth fallback: the boundary is
//   where the construction's exact moments put max(|mean_L/mean_16 − 1|, |CV_L − CV_16|) at TAU
//   (chermain_dictionary_boundary). Measured there at the same positions for both levels, the two
//   signed statistics tested against their predicted values (two-sided, paired delta-method
//   errors). The measured boundary lies in (identity, prediction] when both hold.
// Control: every prediction moved by kChermainControlScale (the smooth boundary's crossing against
// N_pred × 1.25, the dictionary statistics predicted at N_pred × 1.25) must be rejected.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "verify/adequacy/chermain_adequacy.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::adequacy_claims {

inline constexpr double kChermainLadder[] = {0.95, 0.975, 1.0, 1.025, 1.05};
inline constexpr double kChermainControlScale = 1.25;
inline constexpr double kChermainIdentityScale = 0.99;
inline constexpr int kChermainRotations = 256;  // the exact moments' rotation nodes
inline constexpr ChermainLevel kChermainDictionaryLevels[] = {
    ChermainLevel::kDict4, ChermainLevel::kDict8, ChermainLevel::kDict12};

// The rows, declared before measuring: θ_i 0°, 60°; θ_h on the peak and atan 2α; flat (dh 0) and
// curved (dh 0.02); α 0.1 (the quick grid's axes; the flat smooth boundary does not depend on α).
std::vector<adequacy::ChermainCell> chermain_boundary_rows();
// The rows × dict4, dict8, dict12 (the GGAA twin where dh > 0), rows outermost.
std::vector<std::pair<adequacy::ChermainCell, ChermainLevel>> chermain_dictionary_rows();

struct ChermainSmoothRow {
  adequacy::ChermainCell row;
  double predicted = NAN, predicted_fit = NAN, predicted_mean_diff = NAN;
  double measured = NAN, log_se = 0, slope = 0;
  double p_value = 1, moved_p_value = 1;
};
struct ChermainDictionaryRow {
  adequacy::ChermainCell row;  // its facets: the predicted boundary
  ChermainLevel level = ChermainLevel::kDict4;
  double identical_facets = NAN, predicted = NAN;
  bool identical = false;  // dictL == dict16_ggaa at every position at 0.99 × identical_facets
  adequacy::ChermainExactDifference expected, moved;  // at N_pred and N_pred × 1.25
  double mean_diff = 0, mean_diff_se = 0, cv_diff = 0, cv_diff_se = 0;  // measured, signed
  double p_mean = 1, p_cv = 1, moved_p_mean = 1, moved_p_cv = 1;
};

ChermainSmoothRow measure_chermain_smooth_row(const adequacy::ChermainCell& row, int samples,
                                              std::uint64_t seed);
ChermainDictionaryRow measure_chermain_dictionary_row(const adequacy::ChermainCell& row,
                                                      ChermainLevel level, int samples,
                                                      std::uint64_t seed);

// The family's p-values of the part, in order (the smooth boundaries, then each dictionary's two
// statistics), genuine and moved.
void append_chermain_p_values(std::span<const ChermainSmoothRow> smooth,
                              std::span<const ChermainDictionaryRow> dict,
                              std::vector<double>& genuine, std::vector<double>& moved);
// The part's sentence (`begin`: its first p-value in the family `hs`), and the control's counts.
std::string describe_chermain(std::span<const ChermainSmoothRow> smooth,
                              std::span<const ChermainDictionaryRow> dict, int samples,
                              const HolmSidakResult& hs, std::size_t begin);
std::string chermain_moved_text(std::span<const ChermainSmoothRow> smooth,
                                std::span<const ChermainDictionaryRow> dict,
                                const HolmSidakResult& hs, std::size_t begin);

}  // namespace glintlab::verify::adequacy_claims

// Where a cheaper level of the binomial glint family (deliot_belcour, kneiphof_klein: smooth,
// real-time, small-count and exact counting) is indistinguishable from the exact count: per cell
// of a grid (footprint size in expected facets N_P, roughness, light half-angle, incidence, the
// half-vector's angle from the normal) the pixel value over many surface positions, its mean, CV
// and P(value = 0) per level, the decision with confidence bounds, the closed-form prediction and
// the time per evaluation. `glintlab adequacy` writes it (experiments/adequacy/); claim
// adequacy.prediction-matches-measurement checks the prediction (verify/claims/adequacy/).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/glints/adequacy.h"
#include "verify/check.h"

namespace glintlab::verify::adequacy {

// Default TAU: luminance discrimination (the Weber fraction) is about 1–2 % of the background, so
// a pixel whose mean and fluctuation change by less than 2 % is not told apart.
inline constexpr double kDefaultThreshold = 0.02;

// The models of the family, in order.
inline constexpr std::array<std::string_view, 2> kBinomialFamilyModels = {"deliot_belcour",
                                                                          "kneiphof_klein"};

// One grid cell. The half-vector lies at theta_h_deg from the normal, tilted out of the plane of
// incidence (so ω_o stays above the surface for θ_h < 45°); light_half_angle_deg = 0 is a delta
// light (kneiphof_klein then widens it to its default cap of 0.26°, Sec. 5; deliot_belcour never
// uses the light's size).
struct Cell {
  std::string model;
  double facets;  // N_P, the footprint's expected facet count
  double alpha;   // isotropic GGX roughness
  double light_half_angle_deg;
  double theta_i_deg;
  double theta_h_deg;
  int theta_h_index;  // 0 = on the specular peak (θ_h = 0), 1 = atan(α), 2 = atan(2α)
};

struct GridAxes {
  std::vector<double> facets, alpha, light_half_angle_deg, theta_i_deg;
  int theta_h_count = 3;
  int samples = 0;  // surface positions per cell
};
GridAxes grid_axes(Budget b);
std::vector<Cell> make_grid(const std::vector<std::string>& models, const GridAxes& axes);

// The fewest lit (non-zero) positions a sample needs for its bounds: with fewer, the delta
// method's normal approximation of a mostly-dark sample is not trusted and the cell is undecided
// (the exact level is kept).
inline constexpr double kMinLitPositions = 100;

// A level's pixel values against the exact level's at the same positions.
struct LevelStats {
  double mean = 0, cv = 0, p_zero = 0;
  // |mean/mean_exact − 1| and |CV − CV_exact|, each with its upper confidence bound (estimate +
  // z · standard error by the delta method on the paired samples) and lower bound.
  double mean_diff = 0, mean_diff_ucb = 0, mean_diff_lcb = 0;
  double cv_diff = 0, cv_diff_ucb = 0, cv_diff_lcb = 0;
  bool adequate = false;      // both upper bounds below TAU (the exact level: always)
  bool undecided = false;     // too few lit positions to bound the differences
  double ns_per_eval = 0;     // measured time of the level's evaluation loop (not deterministic)
};

struct CellResult {
  Cell cell;
  double p = 0;       // the clamped reflection probability
  double smooth = 0;  // the smooth value (the family's shared factor)
  std::array<LevelStats, kBinomialLevels> levels{};
  // The cheapest adequate level in the order of core/glints/adequacy.h (smooth, realtime,
  // small_count, exact: the order on a GPU lane, where the exact count's variable loop is the
  // costly one), and the adequate level with the least measured time here (not deterministic).
  int chosen = int(BinomialLevel::kExact);
  int cheapest_measured = int(BinomialLevel::kExact);
  double cv_predicted = 0, p_zero_predicted = 0;
  // The engine chooser at TAU: choose_binomial_level (core/glints/adequacy.h); for the area family
  // choose_kneiphof_klein_area_model_level (core/glints/area_chooser.h, area_cell_chooser).
  int chooser = int(BinomialLevel::kExact);
  bool chooser_refuted = false;  // the chooser's level differs by more than TAU for sure (a
                                 // lower bound above TAU)
};

struct Decision {
  double threshold = kDefaultThreshold;
  double z = 0;  // the one-sided normal quantile of the bound's level
};

// The bound's level: the suite's family-wise false-positive rate kFamilyWiseRate split by Šidák
// over every (cell, cheaper level) decision, so that the whole table declares a level adequate that
// is not with probability at most kFamilyWiseRate (asymptotically: the bounds are delta-method).
Decision decision_for(std::size_t cells, double threshold);
// The same over `decisions` decisions in all (a table of several families: each family's cells
// times its cheaper levels).
Decision decision_for_decisions(std::size_t decisions, double threshold);
// The decision whose bounds have one-sided level `level` (z = Φ⁻¹(1 − level)).
Decision decision_at_level(double level, double threshold);

// The pixel values of one level at `samples` surface positions (the footprint centre moved over a
// 2-d low-discrepancy set; the counter RNG is keyed by it), with the model seed `seed`; returns the
// loop's nanoseconds per evaluation. A cell of kneiphof_klein_area (the area family) is handed to
// area_level_values (area_adequacy.h), as are level_param_values and cell_probability_and_smooth.
double level_values(const Cell& cell, BinomialLevel level, int samples, std::uint64_t seed,
                    std::vector<double>& out);
// The surface position of sample i (the footprint centre; a 2-d low-discrepancy set), the query of
// a cell there, and the cell's model's parameter values (its ModelEntry::params order) for a
// counting level (not kSmooth: that level is the smooth GGX value) — what level_values evaluates.
Vec2<double> surface_position(int i);
ModelQuery<double> cell_query(const Cell& c, double u, double v);
std::vector<double> level_param_values(const Cell& cell, BinomialLevel level, std::uint64_t seed);
// The model's `binomial` sampler of a counting level (kSmooth: none; the exact one is returned).
BinomialSampler binomial_sampler_of(BinomialLevel level);
// The clamped p and the smooth value of a cell.
std::pair<double, double> cell_probability_and_smooth(const Cell& cell);

// Statistics of `x` against the exact level's `ref` (paired by position).
LevelStats compare_to_exact(const std::vector<double>& x, const std::vector<double>& ref,
                            const Decision& d);

// Every level of a cell compared with the family's most complete level `most` at the same
// positions: `values(level, out)` fills a level's values and returns its ns per evaluation,
// `edit(level, values)` sees each cheaper level's values before they are compared (the tests'
// broken levels). The most complete level is adequate by definition, with its own time.
template <std::size_t N, class Values, class Edit>
std::array<LevelStats, N> measure_levels(int most, const Decision& d, Values&& values,
                                         Edit&& edit) {
  std::array<LevelStats, N> levels{};
  std::vector<double> ref, x;
  const double t_ref = values(most, ref);
  for (int l = 0; l < int(N); ++l) {
    LevelStats& s = levels[std::size_t(l)];
    if (l == most) {
      s = compare_to_exact(ref, ref, d);
      s.adequate = true;  // the reference itself
      s.undecided = false;
      s.ns_per_eval = t_ref;
      continue;
    }
    const double t = values(l, x);
    edit(l, x);
    s = compare_to_exact(x, ref, d);
    s.ns_per_eval = t;
  }
  return levels;
}

// The cheapest adequate level in the family's order (the first adequate one; `most` when none
// is) and the adequate level with the least measured time (not deterministic).
template <std::size_t N>
std::pair<int, int> chosen_and_cheapest_measured(const std::array<LevelStats, N>& levels,
                                                 int most) {
  int chosen = most, cheapest = most;
  for (int l = int(N); l-- > 0;)
    if (levels[std::size_t(l)].adequate) chosen = l;
  for (int l = 0; l < int(N); ++l)
    if (levels[std::size_t(l)].adequate &&
        levels[std::size_t(l)].ns_per_eval < levels[std::size_t(cheapest)].ns_per_eval)
      cheapest = l;
  return {chosen, cheapest};
}

// One cell: every level measured and compared, the decision, the prediction and the chooser.
CellResult measure_cell(const Cell& cell, int samples, std::uint64_t seed, const Decision& d);

// Every cell, in parallel (TBB); the order and every value but ns_per_eval do not depend on the
// thread count. `progress` (optional) is called once per finished cell.
std::vector<CellResult> measure_grid(const std::vector<Cell>& cells, int samples,
                                     const Decision& d,
                                     const std::function<void()>& progress = {});
// The cells at `positions` (indices into `cells`, the whole grid) alone, in that order, each with
// the seed of its position in the grid (check_seed(seed_name, position)): a shard's cell is bit
// for bit the unsharded run's. The area family (area_adequacy.h) seeds its grid under its own name.
std::vector<CellResult> measure_grid_at(const std::vector<Cell>& cells,
                                        const std::vector<std::size_t>& positions, int samples,
                                        const Decision& d,
                                        const std::function<void()>& progress = {},
                                        const char* seed_name = "adequacy.table");

}  // namespace glintlab::verify::adequacy

// Where a cheaper level of the Kemppinen family (kemppinen_ggx: the smooth NDF,
// Algorithm 1 with k = 1, 4, 9, 16 neighbours, each with the rational or the exact erf in the
// compensation) is indistinguishable from the most complete one (k = 16, exact erf): per cell of a
// grid (footprint size in expected points, roughness, incidence, the half-vector's angle from the
// normal) the pixel value over many surface positions, its mean, CV and P(value = 0) per level,
// and the binomial family's decision (compare_to_exact, binomial_adequacy.h) against k = 16 exact.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/glints/adequacy.h"
#include "verify/adequacy/binomial_adequacy.h"

namespace glintlab::verify::adequacy {

// The models measured: kemppinen_ggx and kemppinen_beckmann (the same levels on the Beckmann base
// NDF; the chooser and the moments take either NDF).
inline constexpr std::array<std::string_view, 2> kKemppinenFamilyModels = {"kemppinen_ggx",
                                                                           "kemppinen_beckmann"};

// The material every cell shares: the models' defaults (K_P = 10⁴ points per unit uv area,
// α★ = 0.02, pixel filter f = 0.5, isotropic, roulette blending, corrected normalisation, white).
// The footprint is a rectangle of area points / K_P in uv, its side along the plane of incidence
// 1/cos θ_i times the other (a pixel's footprint on a surface seen at θ_i; the incidence changes
// nothing else the levels do not share: G2 / (4 cos θ_i) scales every level alike), so `points`
// = K_P × its area, the expected number of points of the implicit grid per pixel footprint (the
// binomial family's N_P).
inline constexpr double kKemppinenDensity = 1e4;

struct KemppinenCell {
  std::string model;
  double points;  // expected points per footprint (K_P × footprint area)
  double alpha;   // isotropic base roughness
  double theta_i_deg;
  double theta_h_deg;
  int theta_h_index;  // 0 = on the peak, 1 = atan(α), 2 = atan(2α)
};

struct KemppinenGridAxes {
  std::vector<double> points, alpha, theta_i_deg;
  int theta_h_count = 3;
  int samples = 0;  // surface positions per cell
};
KemppinenGridAxes kemppinen_grid_axes(Budget b);
// Cells in the order model, θ_i, α, θ_h, points (points fastest).
std::vector<KemppinenCell> make_kemppinen_grid(const std::vector<std::string>& models,
                                               const KemppinenGridAxes& axes);

struct KemppinenCellResult {
  KemppinenCell cell;
  double smooth = 0;  // the smooth level's value G2 D(h) / (4 cos θ_i)
  double lambda = 0;  // the LOD λ of Algorithm 1 at this footprint
  std::array<LevelStats, kKemppinenLevels> levels{};
  // The cheapest adequate level in KemppinenLevel order (the GPU-lane order), and the adequate
  // level with the least measured time here (not deterministic).
  int chosen = int(KemppinenLevel::kK16Exact);
  int cheapest_measured = int(KemppinenLevel::kK16Exact);
  // choose_kemppinen_model_level at TAU (core/glints/adequacy.h), and whether the table refutes it
  // (its level's lower bound above TAU); the chooser's bound on k = 16's CV
  // ((√var_points + position_sd) / mean of kemppinen_level_moments).
  int chooser = int(KemppinenLevel::kK16Rational);
  bool chooser_refuted = false;
  double cv_bound = 0;
};

// The surface position of sample i for a cell: the R2 set of binomial_adequacy.h spread over a
// square whose side is kKemppinenSpread cells of the coarser level Algorithm 1 visits, so that
// positions (about 22 such cells apart at 8000 positions, 11 at 32000; the nearest pair of the
// 8000 12.8) never share a cell of any k's neighbourhood (at most 4 cells of the coarser level):
// each position is another realisation of the same material.
inline constexpr double kKemppinenSpread = 2048;
Vec2<double> kemppinen_surface_position(const KemppinenCell& c, int i);
ModelQuery<double> kemppinen_cell_query(const KemppinenCell& c, Vec2<double> uv);
// The model's parameter values (its kParams order) for a counting level (not kSmooth).
std::vector<double> kemppinen_level_param_values(const KemppinenCell& c, KemppinenLevel level,
                                                 std::uint64_t seed);

// The pixel values of one level at `samples` positions; returns the loop's ns per evaluation.
double kemppinen_level_values(const KemppinenCell& cell, KemppinenLevel level, int samples,
                              std::uint64_t seed, std::vector<double>& out);

// A change made to a cheaper level's values before they are compared (the tests' broken levels).
using KemppinenLevelEdit = std::function<void(KemppinenLevel, std::vector<double>&)>;

// One cell: every level measured and compared with k = 16 exact, and the decision.
KemppinenCellResult measure_kemppinen_cell(const KemppinenCell& cell, int samples,
                                           std::uint64_t seed, const Decision& d,
                                           const KemppinenLevelEdit& edit = {});

// Every cell, in parallel (TBB); the order and every value but ns_per_eval do not depend on the
// thread count. `progress` (optional) is called once per finished cell.
std::vector<KemppinenCellResult> measure_kemppinen_grid(const std::vector<KemppinenCell>& cells,
                                                        int samples, const Decision& d,
                                                        const std::function<void()>& progress = {});
// The cells at `positions` (indices into `cells`, the whole grid) alone, in that order, each with
// the seed of its position in the grid (a shard's cells; measure_grid_at).
std::vector<KemppinenCellResult> measure_kemppinen_grid_at(
    const std::vector<KemppinenCell>& cells, const std::vector<std::size_t>& positions, int samples,
    const Decision& d, const std::function<void()>& progress = {});

// The construction-derived boundary against the measured one, per row of the grid (model, θ_i, α,
// θ_h) and cheaper level (smooth, k1_rational, k4_rational, k9_rational; an exact-erf level's
// boundary is its rational twin's, k16_rational is adequate everywhere). Predicted: the fewest
// expected points from which the level stays adequate for every larger footprint by the chooser's
// moments (kemppinen_level_moments) with the differences at TAU itself (no margin), scanned in
// steps of 1/100 decade down from 10⁹. Measured: between the largest grid footprint where the
// table's level is not adequate and the next one (the level is adequate there and at every larger
// cell).
struct KemppinenBoundary {
  KemppinenCell row;  // the row's first cell (its points the grid's smallest)
  KemppinenLevel level;
  double predicted = NAN;      // NaN: not adequate even at 10⁹ points
  double measured_low = 0;     // 0: adequate in every cell of the row
  double measured_high = NAN;  // NaN: not adequate at the row's largest cell
};
std::vector<KemppinenBoundary> kemppinen_boundaries(const std::vector<KemppinenCellResult>& rows,
                                                    const KemppinenGridAxes& axes, double tau);
// The levels kemppinen_boundaries reports, in its order.
inline constexpr std::array<KemppinenLevel, 4> kKemppinenBoundaryLevels = {
    KemppinenLevel::kSmooth, KemppinenLevel::kK1Rational, KemppinenLevel::kK4Rational,
    KemppinenLevel::kK9Rational};
// The predicted boundaries alone, for one row (`row`'s points are ignored), in the order of
// kKemppinenBoundaryLevels (NaN: not adequate even at 10⁹ points; 0.01 … : adequate down to the
// scan's end, 10⁻² points).
std::array<double, kKemppinenBoundaryLevels.size()> kemppinen_predicted_boundaries(
    KemppinenCell row, double tau);

// The exact first two moments of a counting level over surface positions, from the construction
// of Algorithm 1 (core/glints/kemppinen.h, `level`) rather than the chooser's bounds
// (kemppinen_level_moments, core/glints/adequacy.h): relative to D, the mean and the standard
// deviation of D★^f / D over positions. Per visited 4D cell the point's term X = R N_s(x_s − g_s)
// N_a(x_a − g_a) / K_P, g uniform in its cell, R the roulette of Eq. 8 (E[R], E[R²] by quadrature
// over its uniform r): E[X] = E[R] m_s m_a and E[X²] = E[R²] m'_s m'_a / (K_P 16π² σ_sx σ_sy σ_ax
// σ_ay) (m: the cell's mass of the lobe, m': of the √2-narrower one), cells independent, so
// Var(D★ | x) = Σ (E[X²] − E[X]²); over the position x (uniform over the coarser level's cell,
// both levels' blocks following it) the law of total variance adds Var_x E[D★ | x], by a
// midpoint rule per axis (x and y independent). Exact for the axis-aligned footprints of the grid
// (the spatial covariance diagonal), white points and no anisotropy, but for the points outside
// the disk U_Ω (rejected by the model, counted here) — the chooser's bounds are not used.
struct KemppinenExactMoments {
  double mean = 0, sd = 0;  // of D★^f / D over positions
  double cv() const { return mean > 0 ? sd / mean : INFINITY; }
};
KemppinenExactMoments kemppinen_exact_moments(const KemppinenCell& c, KemppinenLevel level);
// The expected points per footprint where `level`'s exact CV (kemppinen_exact_moments) falls to
// `tau`: the largest of a scan down from 10⁹ in steps of 1/50 decade at which the CV is above
// tau, refined by bisection in log points to 10⁻⁶ of a decade (NaN: above tau even at 10⁹; the
// scan's end, 10⁻², where it never is).
double kemppinen_exact_cv_boundary(KemppinenCell c, KemppinenLevel level, double tau);
// A counting level against k16_exact by the construction's exact moments, the adequacy table's two
// statistics signed: mean_n / mean_16 − 1 and CV_n − CV_16 (compare_to_exact takes their absolute
// values).
struct KemppinenExactDifference {
  double mean_diff = 0, cv_diff = 0;
};
KemppinenExactDifference kemppinen_exact_difference(const KemppinenCell& c, KemppinenLevel level);
// The expected points per footprint from which `level` stays within `tau` of k16_exact in both
// statistics (max(|mean_diff|, |cv_diff|) ≤ tau) by kemppinen_exact_difference, scanned as
// kemppinen_exact_cv_boundary.
double kemppinen_exact_level_boundary(KemppinenCell c, KemppinenLevel level, double tau);

}  // namespace glintlab::verify::adequacy

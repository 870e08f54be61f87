// Where a cheaper level of the Chermain family (chermain: Chermain et al. 2020's procedural
// patch-SDF with 2021's GGAA and slope correlation, core/glints/chermain.h) is indistinguishable
// from the most complete one (all 16 dictionary levels, GGAA on): per cell of a grid (footprint
// size in expected microfacets, roughness, incidence, the half-vector's angle from the normal, the
// screen-space derivative of the projected half vector that GGAA filters with) the pixel value over
// many surface positions, its mean, CV and P(value = 0) per level, and the binomial family's
// decision (compare_to_exact, binomial_adequacy.h) against the most complete level.
//
// The levels, cheapest first (the order on a GPU lane: texture memory, then the filter):
// - smooth: the smooth limit the model falls back to past its last dictionary level, the Gaussian
//   (Beckmann) slope density of covariance Σ (2021 Eq. 16; the LEAN-mapping lobe, Sec. 5) with the
//   V-cavity G2: what a shader without glints evaluates (one exp);
// - dictL (L = 4, 8, 12, 16), then dictL_ggaa: the model with a dictionary of its first L levels
//   (2^k lobes per marginal at level k < L; the cells whose level k = ⌊l + ½ log2 density⌋ is L or
//   more take the smooth fallback, 2021 Sec. 3 and 5), its marginals read with textureLod (GGAA
//   off) or textureGrad (GGAA on, Eq. 19 with the kernel of Eq. 21, the paper's default). A
//   dictionary of L levels is a prefix of the default one (core/glints/chermain_dictionary.h: level
//   k's lobes are the first 2^k of one fixed sequence per distribution, the same seed), so where
//   the footprint's two LODs both use levels below L, dictL is the most complete level's value
//   bit for bit (GGAA as it); texture memory grows as L (the MIP chains of L levels).
// dict16_ggaa is the most complete: the model with its defaults (the default dictionary, GGAA on).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/glints/chermain.h"
#include "core/glints/chermain_chooser.h"
#include "verify/adequacy/binomial_adequacy.h"

namespace glintlab::verify::adequacy {

inline constexpr std::array<std::string_view, 1> kChermainFamilyModels = {"chermain"};

// The levels (ChermainLevel, their names, the most complete one) are the engine chooser's
// (core/glints/chermain_chooser.h).
using ::glintlab::chermain_dictionary_levels;
using ::glintlab::chermain_level_ggaa;
using ::glintlab::ChermainLevel;
using ::glintlab::kChermainLevelNames;
using ::glintlab::kChermainLevels;
using ::glintlab::kChermainMostComplete;

// The material every cell shares: the model's defaults (density e^15 microfacets per unit uv area,
// the default dictionary: 192 distributions, 16 levels, α_dict 0.5, lobe std 0.02; ρ = 0; the GGAA
// kernel of Eq. 21 at s_K = 0.5) with isotropic roughness α. The footprint is a rectangle of area
// facets / density in uv, its side along the plane of incidence 1/cos θ_i times the other (as the
// Kemppinen grid's), so `facets` is the expected number of microfacets per pixel footprint; the
// model's LOD follows the longer side (2021 Eq. 3, the isotropic texture-LOD rule).
inline constexpr double kChermainDensity = 3.269017e6;

struct ChermainCell {
  std::string model;
  double facets;  // expected microfacets per footprint (density × footprint area)
  double alpha;   // isotropic Beckmann roughness (slope std α/√2)
  double theta_i_deg;
  double theta_h_deg;
  int theta_h_index;  // 0 = on the peak, 1 = atan(α), 2 = atan(2α)
  // |∂h⊥/∂x| = |∂h⊥/∂y| per pixel (isotropic: ∂h⊥/∂x along x, ∂h⊥/∂y along y), the screen-space
  // derivative of the projected half vector GGAA filters with (Eq. 21): 0 on a flat surface under
  // a distant light and camera (GGAA then changes nothing), larger where the surface curves
  // within a pixel (2021 Sec. 4).
  double dh;
};

struct ChermainGridAxes {
  std::vector<double> facets, alpha, theta_i_deg, dh;
  int theta_h_count = 3;
  int samples = 0;  // surface positions per cell
};
ChermainGridAxes chermain_grid_axes(Budget b);
// Cells in the order model, dh, θ_i, α, θ_h, facets (facets fastest).
std::vector<ChermainCell> make_chermain_grid(const std::vector<std::string>& models,
                                             const ChermainGridAxes& axes);

struct ChermainCellResult {
  ChermainCell cell;
  double smooth = 0;  // the smooth level's value
  double lod = 0;     // the footprint's continuous LOD l_P
  std::array<LevelStats, kChermainLevels> levels{};
  // The cheapest adequate level in ChermainLevel order, and the adequate level with the least
  // measured time here (not deterministic).
  int chosen = int(kChermainMostComplete);
  int cheapest_measured = int(kChermainMostComplete);
  // The construction's choice (chermain_identical_level): the cheapest level that is the most
  // complete one bit for bit at this footprint, and whether the table refutes it (its level's
  // lower bound above TAU: the construction would be wrong).
  int construction = int(kChermainMostComplete);
  bool construction_refuted = false;
  // The engine chooser's level (choose_chermain_model_level, core/glints/chermain_chooser.h: the
  // construction's identical level, or the smooth one where its closed-form CV is at most
  // kChooserMargin · TAU), whether the table refutes it, and that CV (cv_predicted).
  int chooser = int(kChermainMostComplete);
  bool chooser_refuted = false;
  double cv_predicted = 0;
};

// The construction's boundaries (2021 Eq. 3 with the dictionary level k = ⌊l + ½ log2 density⌋ of
// core/glints/chermain.h): the footprint LOD l_P (log2 of the longer footprint side, the cell side
// at LOD l being 2^l) and the dictionary level of each of the two LODs the footprint blends; a
// dictionary of L levels is the whole dictionary wherever the coarser LOD with a non-zero weight
// uses a level below L. With kDict16Ggaa's GGAA: off is the same where dh = 0.
struct ChermainConstruction {
  double lod = 0;                  // l_P
  int level_fine = 0;              // k at ⌊l_P⌋ (16 or more: the smooth fallback)
  int level_coarse = 0;            // k at ⌊l_P⌋ + 1
  bool coarse_weighted = true;     // frac(l_P) > 0
  double cells_per_footprint = 0;  // footprint area / the fine LOD's cell area (2^⌊l_P⌋)²
  double lobes_per_cell = 0;       // 4^k at the fine LOD (2^k per marginal, k < 16)
};
ChermainConstruction chermain_construction(const ChermainCell& c);
// The cheapest level that equals the most complete one bit for bit by construction: dictL with
// every weighted LOD's level below L (GGAA off where dh = 0), else the most complete level.
ChermainLevel chermain_identical_level(const ChermainCell& c);
// The largest expected facets per footprint at which a dictionary of L levels is still the whole
// dictionary for a cell of this θ_i (the coarser LOD's level below L): the footprint's longer side
// below 2^(L − 1 − ⌊½ log2 density⌋), so facets < density 4^(L − 1 − ⌊½ log2 density⌋) cos θ_i.
double chermain_identical_facets(int dictionary_levels, double theta_i_deg);

// The construction's first two moments of the most complete level (dict16_ggaa) over surface
// positions, computed from the dictionary rather than measured: per cell X = P_o(R(−θ) M⁻¹ m̃) /
// det M (Eq. 4–6) with θ uniform (a midpoint rule of `rotations` nodes) and the two marginals
// uniform over the N distributions (each read as the model reads it: textureLod, or textureGrad
// with the cell's rotated GGAA derivatives), so E[X] = E_θ[ḡ(x_o) ḡ(y_o)], E[X²] = E_θ[s(x_o)
// s(y_o)] (ḡ, s the mean over distributions of p and p²); the patch-SDF of Eq. 3 is w_0 Σ W X_0 +
// w_1 Σ W X_1 over the two LODs' 2 × 2 cells, cells independent but for the coarse cell that shares
// its draws with its lower-left fine child (E[X_0 X_1] likewise), the bilinear weights W over a
// position uniform on the cell lattice (E Σ W² = 4/9 per LOD; the shared pair's E[W_0 W_1] by a
// midpoint rule); a level past the 16th is the constant Gaussian. So mean = w_0 μ_0 + w_1 μ_1 and
// Var = (4/9)(w_0² σ_0² + w_1² σ_1²) + 2 w_0 w_1 Cov(X_0, X_1) E[Σ_shared W_0 W_1]. In slope space
// (P22); `smooth` the Gaussian the smooth level evaluates. The positions' share of the variance
// (the conditional mean does not depend on the position) is none. `shared_draws = false` drops the
// coarse cell's shared draws (the tests' broken construction).
struct ChermainExactMoments {
  double mean = 0, sd = 0, smooth = 0;
  double cv() const { return mean > 0 ? sd / mean : INFINITY; }
  double mean_diff() const { return mean > 0 ? smooth / mean - 1 : INFINITY; }
};
// `level` another counting level's moments the same way (dictL: its LODs at level L or more the
// smooth fallback; GGAA as the level says).
ChermainExactMoments chermain_exact_moments(const ChermainCell& c, int rotations = 1024,
                                            bool shared_draws = true,
                                            ChermainLevel level = kChermainMostComplete);
// The table's two statistics of a counting level against dict16_ggaa by the construction's exact
// moments: mean_L / mean_16 − 1 and CV_L − CV_16 (signed).
struct ChermainExactDifference {
  double mean_diff = 0, cv_diff = 0;
};
ChermainExactDifference chermain_exact_difference(const ChermainCell& c, ChermainLevel level,
                                                  int rotations = 1024);
// A dictionary's boundary by the construction: dictL (L = 4, 8, 12) is dict16_ggaa bit for bit
// below chermain_identical_facets(L, θ_i), where the longer footprint side is 2^(L − 11) (LOD
// l_0 = L − 11: the finer LOD at level L − 1, the coarser at L, which dictL replaces by the smooth
// fallback); past it the coarser LOD's weight w_1 = frac(l_P) grows and with it the two statistics.
// Returns the fewest microfacets past the identity where max(|mean_diff|, |cv_diff|) exceeds
// `tau` (w_1 in 1/1024 steps; NaN where it stays within tau over the whole LOD).
double chermain_dictionary_boundary(const ChermainCell& c, ChermainLevel level, double tau,
                                    int rotations = 1024);
// The fewest expected microfacets per footprint from which the smooth level stays within `tau` of
// dict16_ggaa by the construction's moments (max(|mean_diff|, CV) ≤ tau at every larger
// footprint): the moments once per integer LOD (w_1 = frac(l_P) then enters in closed form),
// scanned down from where both LODs are past the 16th level, each LOD's fraction in 1/256 steps.
double chermain_smooth_boundary(ChermainCell c, double tau, int rotations = 1024);
// The engine chooser at a cell (its first position, the most complete level's parameters) and its
// closed-form CV of dict16_ggaa (chermain_smooth_cv).
int chermain_chooser_level(const ChermainCell& c, double tau);
double chermain_chooser_cv(const ChermainCell& c);

// The surface position of sample i: the R2 set of binomial_adequacy.h spread over a square
// kChermainSpread cells of the footprint's coarser LOD wide, so that positions (about 22 such
// cells apart at 8000 positions) never share a cell of either LOD (the model visits the 2 × 2 cells
// nearest the position at each): each position is another realisation of the same material.
inline constexpr double kChermainSpread = 2048;
Vec2<double> chermain_surface_position(const ChermainCell& c, int i);
ModelQuery<double> chermain_cell_query(const ChermainCell& c, Vec2<double> uv);
// The model's parameters for a counting level (not kSmooth): the defaults with the cell's α, the
// level's dictionary and GGAA kernel, the cell's dh and the seed.
Chermain::Params<double> chermain_level_params(const ChermainCell& c, ChermainLevel level,
                                               std::uint64_t seed);
// The dictionary of a counting level's L levels (the default one for L = 16), generated once.
const chermain2021::Dictionary& chermain_level_dictionary(int levels);

// The smooth level's value at a query: the Gaussian slope density of covariance Σ with the model's
// V-cavity G2 (what the model falls back to past its last level), times cos θ_o as the model's.
double chermain_smooth_value(const Chermain::Params<double>& p, const ModelQuery<double>& q);

// The pixel values of one level at `samples` positions; returns the loop's ns per evaluation.
double chermain_level_values(const ChermainCell& cell, ChermainLevel level, int samples,
                             std::uint64_t seed, std::vector<double>& out);

// A change made to a cheaper level's values before they are compared (the tests' broken levels).
using ChermainLevelEdit = std::function<void(ChermainLevel, std::vector<double>&)>;

// One cell: every level measured and compared with the most complete one, and the decision.
ChermainCellResult measure_chermain_cell(const ChermainCell& cell, int samples, std::uint64_t seed,
                                         const Decision& d, const ChermainLevelEdit& edit = {});

// The cells at `positions` (indices into `cells`, the whole grid) alone, in that order, each with
// the seed of its position in the grid (check_seed("adequacy.chermain", position)), in parallel
// (TBB); every value but ns_per_eval independent of the thread count. `progress` (optional) is
// called once per finished cell.
std::vector<ChermainCellResult> measure_chermain_grid_at(
    const std::vector<ChermainCell>& cells, const std::vector<std::size_t>& positions, int samples,
    const Decision& d, const std::function<void()>& progress = {});
std::vector<ChermainCellResult> measure_chermain_grid(const std::vector<ChermainCell>& cells,
                                                      int samples, const Decision& d,
                                                      const std::function<void()>& progress = {});

}  // namespace glintlab::verify::adequacy

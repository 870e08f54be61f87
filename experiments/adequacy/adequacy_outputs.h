// `glintlab adequacy` as files: the measured table of verify/adequacy/ for every family selected
// (the binomial family, the Kemppinen family and the area family, kneiphof_klein_area under a
// square light; adequacy.csv, one row per cell with its
// `family`; adequacy.json, the same with the decision's settings and a cost summary) and per
// model × light × incidence (Kemppinen: model × incidence) one map of the chosen level over
// footprint size × (roughness, half-vector angle): EXR (chosen level, chooser, measured and
// predicted CV and P(no glint)), its cells in adequacy-levels.csv and a chart spec
// (<map>.chart.json) from which reports/figure_charts.py draws the labelled <map>.png with the
// predicted boundary over the measured levels (binomial: CV_pred = TAU; Kemppinen: the smooth
// level's, kemppinen_boundaries); `glintlab adequacy` runs it on the output folder.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string_view>
#include <string>
#include <vector>

#include "core/math/vec.h"
#include "core/render/image.h"
#include "experiments/adequacy/level_costs.h"
#include "verify/adequacy/area_adequacy.h"
#include "verify/adequacy/binomial_adequacy.h"
#include "verify/adequacy/chermain_adequacy.h"
#include "verify/adequacy/decision_calibration.h"
#include "verify/adequacy/kemppinen_adequacy.h"

namespace glintlab::experiments {

// The colours of the binomial levels (smooth, realtime, small_count, exact) in every adequacy map.
inline constexpr std::array<Vec3<double>, 4> kAdequacyLevelColors = {
    Vec3<double>{0.35, 0.75, 0.35}, Vec3<double>{0.35, 0.55, 0.9}, Vec3<double>{0.95, 0.65, 0.2},
    Vec3<double>{0.85, 0.25, 0.25}};

// The colours of the Kemppinen levels (smooth, then k = 1, 4, 9, 16 rational and exact: the exact
// erf a darker shade of its k's colour) in every adequacy map.
inline constexpr std::array<Vec3<double>, 9> kKemppinenLevelColors = {
    Vec3<double>{0.35, 0.75, 0.35}, Vec3<double>{0.55, 0.75, 0.95}, Vec3<double>{0.3, 0.5, 0.85},
    Vec3<double>{0.95, 0.8, 0.4},   Vec3<double>{0.85, 0.6, 0.15},  Vec3<double>{0.85, 0.6, 0.85},
    Vec3<double>{0.6, 0.3, 0.65},   Vec3<double>{0.95, 0.45, 0.45}, Vec3<double>{0.75, 0.15, 0.15}};

// The colours of the Chermain levels (smooth, then dictionaries of 4, 8, 12, 16 levels, GGAA off
// and on: GGAA a darker shade of its dictionary's colour), the Kemppinen levels' colours in order.
inline constexpr std::array<Vec3<double>, 9> kChermainLevelColors = kKemppinenLevelColors;

// The family names in the table's `family` column.
inline constexpr std::string_view kBinomialFamily = "binomial", kKemppinenFamily = "kemppinen",
                                  kAreaFamily = "area", kChermainFamily = "chermain";

struct AdequacyOptions {
  // Models of any family (verify::adequacy::kBinomialFamilyModels, kKemppinenFamilyModels,
  // kAreaFamilyModels).
  std::vector<std::string> models;
  double threshold = verify::adequacy::kDefaultThreshold;
  verify::Budget budget = verify::Budget::kQuick;
  std::function<void()> progress;  // once per measured cell, from any thread
  // Each level's cost from the benchmark JSON (`--bench-from`); unset: the table prices the levels
  // only by the GPU order and the in-process timing.
  std::optional<LevelCosts> costs;
  // The Kemppinen family's grid; unset: the budget's (kemppinen_grid_axes). Set by the tests, whose
  // time does not allow the budget's grid.
  std::optional<verify::adequacy::KemppinenGridAxes> kemppinen_axes;
  // The area family's grid; unset: the budget's (area_grid_axes). Set by the tests.
  std::optional<verify::adequacy::GridAxes> area_axes;
  // The Chermain family's grid; unset: the budget's (chermain_grid_axes). Set by the tests.
  std::optional<verify::adequacy::ChermainGridAxes> chermain_axes;
  // The binomial family's grid; unset: the budget's (grid_axes).
  std::optional<verify::adequacy::GridAxes> binomial_axes;
};

// Every family's grid as `o` has it, measured at `positions` surface positions per cell instead
// of the budget's (quick 8000, full 32000): `glintlab adequacy --positions`.
void set_positions_per_cell(AdequacyOptions& o, int positions);

// A family's cells priced by the benchmark (--bench-from): Σ over cells of the benchmark's ns per
// evaluation for the family's most complete level everywhere (exact, k16_exact, dict16_ggaa), the
// chosen level (the GPU order) and the adequate level of least benchmark cost, with how many cells
// each level is that for (the family's level order). `priced` false: no costs given, or none for
// the family's models.
struct BenchSums {
  bool priced = false;
  double most_complete_ns = 0, chosen_ns = 0, cheapest_ns = 0;
  std::vector<std::size_t> cheapest_by_benchmark;
  // The Kemppinen and Chermain families: the engine chooser for these costs
  // (core/glints/cost_chooser.h) at each cell, Σ of its level's cost, the cells per level it
  // takes and where the table refutes it (its level's lower bound above TAU). `engine` false in
  // the other families.
  bool engine = false;
  double engine_ns = 0;
  std::vector<std::size_t> engine_by_cost;
  std::size_t engine_refuted = 0;
  double engine_saved() const {
    return most_complete_ns > 0 ? 1 - engine_ns / most_complete_ns : 0;
  }
  double chosen_saved() const { return most_complete_ns > 0 ? 1 - chosen_ns / most_complete_ns : 0; }
  double cheapest_saved() const {
    return most_complete_ns > 0 ? 1 - cheapest_ns / most_complete_ns : 0;
  }
};

struct AdequacySummary {
  std::filesystem::path json, csv;
  std::vector<std::string> maps;  // PNG paths relative to the output folder
  std::size_t cells = 0;
  std::array<std::size_t, 4> chosen{};  // cells per cheapest adequate level
  std::size_t chooser_refuted = 0;      // cells where the chooser's level is surely over TAU
  std::size_t chooser_matches = 0;      // cells where the chooser picks the measured level
  std::size_t undecided = 0;            // cells too dark at the exact level to bound
  // Σ over cells of the time per evaluation: the exact level everywhere, the chosen level, and the
  // adequate level measured cheapest in each cell (on a CPU the exact count is often cheaper than
  // the approximations; docs/benchmarks.md), with how many cells each level is that for.
  double exact_ns = 0, chosen_ns = 0, cheapest_ns = 0;
  std::array<std::size_t, 4> cheapest_measured{};
  // With benchmark costs: the binomial family's cells priced (BenchSums).
  BenchSums bench;
  // The decision's bounds: z of the Šidák split over every decision of the table (all families).
  std::size_t decisions = 0;
  double z = 0;
  // The Kemppinen family (zero cells when none of its models is selected): cells per cheapest
  // adequate level (KemppinenLevel order), undecided cells, and Σ over cells of the in-process time
  // per evaluation for k = 16 exact everywhere, the chosen level and the measured-cheapest one.
  struct Kemppinen {
    std::size_t cells = 0, undecided = 0;
    std::size_t chooser_matches = 0, chooser_refuted = 0;  // as the binomial family's
    std::array<std::size_t, kKemppinenLevels> chosen{}, cheapest_measured{};
    double most_complete_ns = 0, chosen_ns = 0, cheapest_ns = 0;
    BenchSums bench;  // with benchmark costs: its adequacy/kemppinen_*/ rows
  } kemppinen;
  // The area family (kneiphof_klein_area; zero cells when it is not selected): as the binomial
  // family's, with the in-process times and, with benchmark costs, the benchmark's sums (its own
  // adequacy/kneiphof_klein_area/ rows; not in the binomial family's sums).
  struct Area {
    std::size_t cells = 0, undecided = 0;
    std::size_t chooser_matches = 0, chooser_refuted = 0;
    std::array<std::size_t, kBinomialLevels> chosen{}, cheapest_measured{};
    double exact_ns = 0, chosen_ns = 0, cheapest_ns = 0;
    BenchSums bench;
  } area;
  // The Chermain family (zero cells when chermain is not selected): as the Kemppinen family's, the
  // most complete level dict16_ggaa; `construction_*` the construction's identical level
  // (chermain_identical_level) against the table.
  struct Chermain {
    std::size_t cells = 0, undecided = 0;
    std::size_t construction_matches = 0, construction_refuted = 0;
    std::size_t chooser_matches = 0, chooser_refuted = 0;  // the engine chooser
    std::array<std::size_t, verify::adequacy::kChermainLevels> chosen{}, cheapest_measured{};
    double most_complete_ns = 0, chosen_ns = 0, cheapest_ns = 0;
    BenchSums bench;  // with benchmark costs: its adequacy/chermain/ rows
  } chermain;
};

// The summary line `glintlab adequacy --bench-from` prints for a family (`family` as the line
// names it, `levels` its level names): its benchmark sums against its most complete level, the
// cells per level of least benchmark cost, or that the costs (`source`, rows of `isa`) do not
// price it.
std::string bench_sums_line(std::string_view family, const BenchSums& b,
                            std::span<const std::string_view> levels, std::string_view source,
                            std::string_view isa);

// Measures every cell and writes the files into `out` (created), each atomically.
AdequacySummary run_adequacy(const std::filesystem::path& out, const AdequacyOptions& o);

// A run's measured cells: each family's whole grid in its order (make_grid, make_kemppinen_grid,
// make_grid over area_grid_axes).
struct AdequacyCells {
  std::vector<verify::adequacy::CellResult> binomial;
  std::vector<verify::adequacy::KemppinenCellResult> kemppinen;
  std::vector<verify::adequacy::CellResult> area;
  std::vector<verify::adequacy::ChermainCellResult> chermain;
};
// The files of run_adequacy from cells measured already (by run_adequacy, or by the shards of a
// run joined: experiments/adequacy/adequacy_shards.h).
AdequacySummary write_adequacy(const std::filesystem::path& out, const AdequacyOptions& o,
                               const AdequacyCells& cells);
// The binomial family's grid axes for `o`: its override, else the budget's.
verify::adequacy::GridAxes binomial_axes_of(const AdequacyOptions& o);
// The Kemppinen family's grid axes for `o`: its override, else the budget's.
verify::adequacy::KemppinenGridAxes kemppinen_axes_of(const AdequacyOptions& o);
// The area family's grid axes for `o`: its override, else the budget's.
verify::adequacy::GridAxes area_axes_of(const AdequacyOptions& o);
// The Chermain family's grid axes for `o`: its override, else the budget's.
verify::adequacy::ChermainGridAxes chermain_axes_of(const AdequacyOptions& o);

// The table alone (for the tests and the maps figure): the binomial family's cells of the budget's
// grid for `models`, measured with the decision of the whole table (table_decision).
std::vector<verify::adequacy::CellResult> measure_adequacy(const AdequacyOptions& o);
// The Kemppinen family's cells of the budget's grid for `models`, measured likewise.
std::vector<verify::adequacy::KemppinenCellResult> measure_kemppinen_adequacy(
    const AdequacyOptions& o);
// The models of `models` in each family, in the families' order.
std::vector<std::string> binomial_models(const std::vector<std::string>& models);
std::vector<std::string> kemppinen_models(const std::vector<std::string>& models);
std::vector<std::string> area_models(const std::vector<std::string>& models);
std::vector<std::string> chermain_models(const std::vector<std::string>& models);
// The models of `models` whose levels the benchmark prices (adequacy/<model>/level=<level>/<isa>
// rows of glintlab_bench_glints): every family's (binomial, Kemppinen, area, Chermain), in the
// families' order.
std::vector<std::string> priced_models(const std::vector<std::string>& models);
// The decision of the whole table for `o`: z by Šidák over every (cell, cheaper level) decision
// of every family selected (binomial: 3 per cell, Kemppinen: 8 per cell, area: 3 per cell,
// Chermain: 8 per cell).
verify::adequacy::Decision table_decision(const AdequacyOptions& o);
std::size_t table_decisions(const AdequacyOptions& o);

// A map of the level chosen per cell, as its chart draws it: cells over footprint sizes (columns,
// log-spaced) × rows (bottom to top), each in its level's colour, and per row the predicted
// boundary as a footprint size.
struct LevelChart {
  std::string title;
  std::string x_label, y_label;  // with their units in brackets
  std::vector<double> columns;   // the footprint size of each column
  std::vector<std::string> row_labels;
  std::vector<std::string> category_names;
  std::vector<Vec3<double>> category_colors;
  std::vector<std::vector<int>> cells;  // [row][column] level index (-1: none, drawn grey)
  std::vector<double> marker;           // per row: the predicted boundary (NaN: none)
  std::string marker_name;
};

// One map of the measured table, per model × light × incidence: the chosen level over footprint
// size N_P (columns) × (α, θ_h) (rows, bottom to top) as a labelled category map with the predicted
// smooth boundary CV_pred = TAU drawn per row, and as an EXR of one pixel per cell (channels
// chosen, chooser, cv_exact, cv_predicted, p_zero, p_zero_predicted; row 0 the bottom row).
struct AdequacyLevelMap {
  std::string stem;  // adequacy_<model>_light<deg>_theta<deg>
  std::string model;
  double light_half_angle_deg = 0, theta_i_deg = 0;
  double ggaa_dh = 0;  // the Chermain maps' GGAA derivative per pixel
  LevelChart map;
  Image exr;
};

// The maps' cells as data, one CSV row per cell (map = the stem, row, row_label, footprint,
// level, level_name, boundary: nan where the row has none), written atomically.
void write_level_maps_csv(const std::filesystem::path& csv,
                          const std::vector<const AdequacyLevelMap*>& maps);
// The chart spec of `png` (written beside it as NAME.chart.json, atomically): `maps`, one panel
// each (columns panels per row) under `title`, drawn from `csv_name` (write_level_maps_csv, in
// the same folder) as maps of categories by reports/figure_charts.py.
void write_level_maps_chart(const std::filesystem::path& png, const std::string& csv_name,
                            const std::string& title,
                            const std::vector<const AdequacyLevelMap*>& maps, int columns = 1);
// `rows` in make_grid's order for `axes` (the area family's rows too: their titles name the square
// light by the cone whose solid angle it has).
std::vector<AdequacyLevelMap> adequacy_level_maps(
    const std::vector<verify::adequacy::CellResult>& rows, const verify::adequacy::GridAxes& axes,
    double threshold);

// The Kemppinen maps, per model × incidence: the chosen level over expected points per footprint
// (columns) × (α, θ_h) (rows, bottom to top), and an EXR of one pixel per cell (channels chosen,
// chooser, cv_most_complete, lambda). `rows` in make_kemppinen_grid's order for `axes`.
// `boundaries` (kemppinen_boundaries of the same rows; may be empty) draws each row's predicted
// smooth boundary.
std::vector<AdequacyLevelMap> kemppinen_level_maps(
    const std::vector<verify::adequacy::KemppinenCellResult>& rows,
    const verify::adequacy::KemppinenGridAxes& axes, double threshold,
    const std::vector<verify::adequacy::KemppinenBoundary>& boundaries = {});

// The Chermain maps, per model × dh × incidence: the chosen level over expected microfacets per
// footprint (columns) × (α, θ_h) (rows, bottom to top), with the construction's smooth fallback
// (the coarser LOD past the 16th level, chermain_identical_facets(16, θ_i)) drawn per row, and an
// EXR of one pixel per cell (channels chosen, construction, cv_most_complete, lod). `rows` in
// make_chermain_grid's order for `axes`.
std::vector<AdequacyLevelMap> chermain_level_maps(
    const std::vector<verify::adequacy::ChermainCellResult>& rows,
    const verify::adequacy::ChermainGridAxes& axes, double threshold);

// `glintlab adequacy --calibrate`: the decision rule's false-adequate rate (and, on truly
// adequate cells, its power) on synthetic cells whose truth is known
// (verify/adequacy/decision_calibration.h), at the budget's positions per cell and the number of
// decisions of the budget's table for `models`. Writes adequacy-calibration.csv (one row per case,
// δ and nominal level) and adequacy-calibration.json (the same with the settings, the pooled and
// the family-wise rows), each atomically.
struct AdequacyCalibrationOptions {
  std::vector<std::string> models;
  double threshold = verify::adequacy::kDefaultThreshold;
  verify::Budget budget = verify::Budget::kQuick;
  std::size_t runs = 2000;          // synthetic cells per (case, δ)
  std::size_t tables = 20;          // whole tables per family-wise δ
  std::optional<int> positions;     // positions per synthetic cell; unset: the budget's
  std::function<void()> progress;   // once per synthetic cell, never concurrently
};

struct AdequacyCalibrationSummary {
  std::filesystem::path json, csv;
  verify::adequacy::DecisionCalibration calibration;
};

// The options a calibration run uses for `o` (the grid's positions and decision count).
verify::adequacy::DecisionCalibrationOptions decision_calibration_options(
    const AdequacyCalibrationOptions& o);

AdequacyCalibrationSummary run_adequacy_calibration(const std::filesystem::path& out,
                                                    const AdequacyCalibrationOptions& o);

}  // namespace glintlab::experiments

// Figure adequacy-maps: the adequacy table of every family — the binomial family, the Kemppinen
// family (kemppinen_ggx, kemppinen_beckmann: smooth, k = 1, 4, 9, 16, rational or exact erf), the
// area family (kneiphof_klein_area under square lights, the binomial levels) and the Chermain
// family (chermain: smooth, dictionaries of 4 … 16 levels, GGAA off / on) — measured at the
// budget's grids (the table `glintlab adequacy` writes: one decision, z split over the four
// families' decisions; at quick the Kemppinen cells at kQuickKemppinenPositions positions, below),
// drawn by matplotlib as one labelled sheet (adequacy-maps.png: a title, then each model × light ×
// incidence map — Kemppinen: model × incidence; Chermain: GGAA derivative × incidence — with its
// own title, axes with units, the levels' colour scale and the predicted boundary), each map's PNG
// and EXR, a CSV of every cell's chosen level and the chooser's per family (adequacy-maps.csv: the
// binomial and area cells; adequacy-maps-kemppinen.csv; adequacy-maps-chermain.csv with the
// construction's level), the maps' cells as drawn (adequacy-maps-levels.csv, with the chart specs)
// and summary.md with every map's family and the counts per model and level.
#include "experiments/figures/adequacy_maps.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/io/exr.h"
#include "experiments/adequacy/adequacy_outputs.h"

namespace glintlab::experiments {
namespace {

namespace adq = verify::adequacy;

constexpr std::string_view kId = "adequacy-maps";

// Surface positions per Kemppinen cell at quick. `glintlab adequacy --budget quick` measures 8000,
// which costs the Kemppinen family some 56 CPU-seconds (Algorithm 1's points, scalar; 111 when
// each exact-erf level was evaluated again for its rational twin, both at a load of 6 to 8 on 2
// shared cores), more than the three other families together; the figure's quick run (a preview,
// and a ctest) takes an eighth of them. The decision's z is still the whole table's (it counts decisions, not
// positions); fewer positions widen the bounds, so a cell can keep a more complete level than at
// 8000 (docs/adequacy.md, the figure adequacy-maps). The full budget measures glintlab adequacy's.
constexpr int kQuickKemppinenPositions = 1000;

// A family's cells per model: how many, how many chose each of its Levels levels, how often the
// chooser agreed with the measurement or was refuted, how many stayed undecided.
template <std::size_t Levels>
struct LevelCounts {
  std::array<std::size_t, Levels> chosen{};
  std::size_t cells = 0, matches = 0, refuted = 0, undecided = 0;
};
template <std::size_t Levels, class Rows>
std::map<std::string, LevelCounts<Levels>> counts_per_model(const Rows& rows) {
  std::map<std::string, LevelCounts<Levels>> out;
  for (const auto& r : rows) {
    LevelCounts<Levels>& c = out[r.cell.model];
    ++c.cells;
    ++c.chosen[std::size_t(r.chosen)];
    c.matches += r.chooser == r.chosen ? 1 : 0;
    c.refuted += r.chooser_refuted ? 1 : 0;
    c.undecided += r.levels[0].undecided ? 1 : 0;
  }
  return out;
}

void run_adequacy_maps(const FigureContext& ctx) {
  std::unique_ptr<tbb::global_control> limit;
  if (ctx.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  std::size_t(ctx.threads));
  AdequacyOptions o;
  o.models.assign(adq::kBinomialFamilyModels.begin(), adq::kBinomialFamilyModels.end());
  o.models.insert(o.models.end(), adq::kKemppinenFamilyModels.begin(),
                  adq::kKemppinenFamilyModels.end());
  o.models.insert(o.models.end(), adq::kAreaFamilyModels.begin(), adq::kAreaFamilyModels.end());
  o.models.insert(o.models.end(), adq::kChermainFamilyModels.begin(),
                  adq::kChermainFamilyModels.end());
  o.budget = ctx.quick ? verify::Budget::kQuick : verify::Budget::kFull;
  if (ctx.quick) {
    o.kemppinen_axes = kemppinen_axes_of(o);
    o.kemppinen_axes->samples = kQuickKemppinenPositions;
  }
  const adq::GridAxes axes = binomial_axes_of(o);
  const adq::KemppinenGridAxes kemppinen_axes = kemppinen_axes_of(o);
  const adq::GridAxes area_axes = area_axes_of(o);
  const std::vector<adq::Cell> area_cells = adq::make_grid(area_models(o.models), area_axes);
  const adq::ChermainGridAxes chermain_axes = chermain_axes_of(o);
  const std::vector<adq::ChermainCell> chermain_cells =
      adq::make_chermain_grid(chermain_models(o.models), chermain_axes);
  const std::size_t total =
      adq::make_grid(binomial_models(o.models), axes).size() +
      adq::make_kemppinen_grid(kemppinen_models(o.models), kemppinen_axes).size() +
      area_cells.size() + chermain_cells.size();
  std::atomic<long> done{0};
  std::mutex progress_mutex;
  o.progress = [&] {
    const long d = ++done;
    if (ctx.progress && (d % 64 == 0 || d == long(total))) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      ctx.progress("adequacy-maps: cells", d, long(total));
    }
  };
  // The families at the decision of their one table, measured as `glintlab adequacy` measures them
  // (measure_adequacy, measure_kemppinen_adequacy; the area and Chermain cells seeded by their
  // position in their family's grid), side by side: each family's cells are parallel already, but
  // the families one after another leave threads idle at each family's last cells.
  std::vector<adq::CellResult> rows, area_rows;
  std::vector<adq::KemppinenCellResult> kemppinen_rows;
  std::vector<adq::ChermainCellResult> chermain_rows;
  const adq::Decision decision = table_decision(o);
  tbb::parallel_invoke(
      [&] { rows = measure_adequacy(o); },
      [&] { kemppinen_rows = measure_kemppinen_adequacy(o); },
      [&] {
        std::vector<std::size_t> all(area_cells.size());
        for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
        area_rows = adq::measure_area_grid_at(area_cells, all, area_axes.samples, decision,
                                              o.progress);
      },
      [&] {
        chermain_rows = adq::measure_chermain_grid(chermain_cells, chermain_axes.samples, decision,
                                                   o.progress);
      });
  std::vector<AdequacyLevelMap> maps = adequacy_level_maps(rows, axes, o.threshold);
  const std::size_t binomial_maps = maps.size();
  for (AdequacyLevelMap& m : kemppinen_level_maps(
           kemppinen_rows, kemppinen_axes, o.threshold,
           adq::kemppinen_boundaries(kemppinen_rows, kemppinen_axes, o.threshold)))
    maps.push_back(std::move(m));
  const std::size_t kemppinen_maps = maps.size() - binomial_maps;
  for (AdequacyLevelMap& m : adequacy_level_maps(area_rows, area_axes, o.threshold))
    maps.push_back(std::move(m));
  const std::size_t counting_maps = maps.size();
  for (AdequacyLevelMap& m : chermain_level_maps(chermain_rows, chermain_axes, o.threshold))
    maps.push_back(std::move(m));
  // Each map's family, as summary.md and the CSVs name it.
  const auto family_of = [&](std::size_t i) {
    if (i >= counting_maps) return kChermainFamily;
    if (i >= binomial_maps && i < binomial_maps + kemppinen_maps) return kKemppinenFamily;
    return i < binomial_maps ? kBinomialFamily : kAreaFamily;
  };
  rows.insert(rows.end(), area_rows.begin(), area_rows.end());

  // The maps' cells as data; each map's chart and the sheet of all of them drawn from it by
  // reports/figure_charts.py (FigureContext::finish).
  const std::string levels_csv = "adequacy-maps-levels.csv";
  std::vector<const AdequacyLevelMap*> every_map;
  for (const AdequacyLevelMap& m : maps) every_map.push_back(&m);
  write_level_maps_csv(ctx.dir / levels_csv, every_map);
  const std::string title = fmt::format(
      "adequacy-maps: binomial, Kemppinen, area and Chermain families, cheapest level within "
      "TAU = {:g} per cell ({} positions per cell, Kemppinen {})",
      o.threshold, axes.samples, kemppinen_axes.samples);
  write_level_maps_chart(ctx.dir / "adequacy-maps.png", levels_csv, title, every_map, 2);
  // What differs between the families' maps: the chart's title, the EXR's column axis and levels.
  struct FamilyMapText {
    std::string title, columns, levels;
  };
  const auto text_of = [&](std::string_view family) -> FamilyMapText {
    const std::string per_cell = "adequacy-maps: cheapest adequate level per cell, ";
    if (family == kKemppinenFamily)
      return {per_cell + "Kemppinen family",
              "expected points: " + fmt::format("{}", fmt::join(kemppinen_axes.points, ", ")),
              "0 smooth, 1 k1_rational, 2 k1_exact, 3 k4_rational, 4 k4_exact, 5 k9_rational, "
              "6 k9_exact, 7 k16_rational, 8 k16_exact"};
    if (family == kChermainFamily)
      return {per_cell + "Chermain family",
              "expected microfacets: " + fmt::format("{}", fmt::join(chermain_axes.facets, ", ")),
              "0 smooth, 1 dict4, 2 dict4_ggaa, 3 dict8, 4 dict8_ggaa, 5 dict12, 6 dict12_ggaa, "
              "7 dict16, 8 dict16_ggaa"};
    const bool area = family == kAreaFamily;
    return {per_cell + (area ? "area family" : "binomial family"),
            "N_P: " + fmt::format("{}", fmt::join(area ? area_axes.facets : axes.facets, ", ")),
            "0 smooth, 1 realtime, 2 small_count, 3 exact"};
  };
  for (std::size_t i = 0; i < maps.size(); ++i) {
    const AdequacyLevelMap& m = maps[i];
    const std::string_view family = family_of(i);
    const FamilyMapText text = text_of(family);
    write_level_maps_chart(ctx.dir / (m.stem + ".png"), levels_csv, text.title, {&m});
    io::ExrAttributes attributes = {
        {"glintlab_figure", std::string(kId)},
        {"glintlab_version", std::string(glintlab_version())},
        {"glintlab_family", std::string(family)},
        {"glintlab_columns", text.columns},
        {"glintlab_rows", fmt::format("{}", fmt::join(m.map.row_labels, "; "))},
        {"glintlab_levels", text.levels}};
    if (family == kChermainFamily)
      attributes.emplace_back("glintlab_ggaa_dh", fmt::format("{:g}", m.ggaa_dh));
    io::write_exr(ctx.dir / (m.stem + ".exr"), m.exr, attributes);
  }
  io::write_csv_atomic(
      ctx.dir / "adequacy-maps.csv",
      {"family", "model", "light_half_angle_deg", "theta_i_deg", "alpha", "theta_h_deg", "facets", "p",
       "chosen", "chooser", "chooser_refuted", "undecided"},
      [&](io::CsvWriter& w) {
        for (const adq::CellResult& r : rows) {
          const bool area = std::find(adq::kAreaFamilyModels.begin(), adq::kAreaFamilyModels.end(),
                                      r.cell.model) != adq::kAreaFamilyModels.end();
          w.cell(area ? kAreaFamily : kBinomialFamily);
          w.cell(r.cell.model).cell(r.cell.light_half_angle_deg).cell(r.cell.theta_i_deg);
          w.cell(r.cell.alpha).cell(r.cell.theta_h_deg).cell(r.cell.facets).cell(r.p);
          w.cell(kBinomialLevelNames[std::size_t(r.chosen)]);
          w.cell(kBinomialLevelNames[std::size_t(r.chooser)]);
          w.cell_int(r.chooser_refuted ? 1 : 0).cell_int(r.levels[0].undecided ? 1 : 0);
          w.end_row();
        }
      });

  // Every map with its family (the report's adequacy section names the families from it).
  io::write_csv_atomic(
      ctx.dir / "adequacy-maps-index.csv",
      {"map", "family", "model", "theta_i_deg", "light_half_angle_deg", "ggaa_dh", "png", "exr"},
      [&](io::CsvWriter& w) {
        for (std::size_t i = 0; i < maps.size(); ++i) {
          const AdequacyLevelMap& m = maps[i];
          const std::string_view family = family_of(i);
          const bool lit = family == kBinomialFamily || family == kAreaFamily;
          w.cell(m.stem).cell(family).cell(m.model).cell(m.theta_i_deg);
          w.cell(lit ? m.light_half_angle_deg : NAN);
          w.cell(family == kChermainFamily ? m.ggaa_dh : NAN);
          w.cell(m.stem + ".png").cell(m.stem + ".exr");
          w.end_row();
        }
      });

  // The Kemppinen cells, with their own levels and the Kemppinen chooser's level.
  io::write_csv_atomic(
      ctx.dir / "adequacy-maps-kemppinen.csv",
      {"family", "model", "theta_i_deg", "alpha", "theta_h_deg", "points", "lambda", "chosen",
       "chooser", "chooser_refuted", "undecided"},
      [&](io::CsvWriter& w) {
        for (const adq::KemppinenCellResult& r : kemppinen_rows) {
          w.cell(kKemppinenFamily).cell(r.cell.model).cell(r.cell.theta_i_deg).cell(r.cell.alpha);
          w.cell(r.cell.theta_h_deg).cell(r.cell.points).cell(r.lambda);
          w.cell(kKemppinenLevelNames[std::size_t(r.chosen)]);
          w.cell(kKemppinenLevelNames[std::size_t(r.chooser)]);
          w.cell_int(r.chooser_refuted ? 1 : 0).cell_int(r.levels[0].undecided ? 1 : 0);
          w.end_row();
        }
      });

  // The Chermain cells, with their own levels and the construction's level (`chooser`).
  io::write_csv_atomic(
      ctx.dir / "adequacy-maps-chermain.csv",
      {"family", "model", "ggaa_dh", "theta_i_deg", "alpha", "theta_h_deg", "facets", "chosen", "chooser",
       "chooser_refuted", "undecided"},
      [&](io::CsvWriter& w) {
        for (const adq::ChermainCellResult& r : chermain_rows) {
          w.cell(kChermainFamily).cell(r.cell.model).cell(r.cell.dh).cell(r.cell.theta_i_deg).cell(r.cell.alpha);
          w.cell(r.cell.theta_h_deg).cell(r.cell.facets);
          w.cell(adq::kChermainLevelNames[std::size_t(r.chosen)]);
          w.cell(adq::kChermainLevelNames[std::size_t(r.construction)]);
          w.cell_int(r.construction_refuted ? 1 : 0).cell_int(r.levels[0].undecided ? 1 : 0);
          w.end_row();
        }
      });

  const auto per_model = counts_per_model<4>(rows);
  std::string md =
      "# adequacy-maps\n\nEvery map, its family and its files (<map>.png, <map>.exr, its cells in "
      "adequacy-maps-levels.csv):\n\n| map | family | model | incidence θ_i [deg] | light "
      "half-angle [deg] / GGAA dh [1/px] |\n|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < maps.size(); ++i) {
    const AdequacyLevelMap& m = maps[i];
    const std::string_view family = family_of(i);
    md += fmt::format(
        "| {} | {} | {} | {:g} | {} |\n", m.stem, family, m.model, m.theta_i_deg,
        family == kKemppinenFamily
            ? std::string("none (a direction, no light)")
            : family == kChermainFamily ? fmt::format("dh {:g}", m.ggaa_dh)
                                        : fmt::format("light {:g}", m.light_half_angle_deg));
  }
  md += fmt::format(
      "\nThe cheapest level of the binomial glint family (deliot_belcour, "
      "kneiphof_klein: smooth, realtime, small_count, exact) and of the area family "
      "(kneiphof_klein_area under a square light whose solid angle is the light half-angle's "
      "cone's, the same levels) whose mean and CV over {} surface positions are within TAU = {:g} "
      "of exact counting, per cell of the adequacy grid (footprint size N_P × roughness α × "
      "half-vector angle θ_h, one map per model, light half-angle and incidence θ_i; "
      "docs/adequacy.md), each decided at the one z of the four families' decisions ({:.3f}). "
      "The black bar on each row is the predicted smooth boundary N* = (1 − p)/(p TAU²) (the "
      "area family's p by the LTC). The Kemppinen and Chermain families' maps are below.\n\n"
      "| model | cells | smooth | realtime | small_count | exact | undecided | chooser = measured "
      "| "
      "chooser refuted |\n|---|---|---|---|---|---|---|---|---|\n",
      axes.samples, o.threshold, table_decision(o).z);
  for (const auto& [model, c] : per_model)
    md +=
        fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", model, c.cells, c.chosen[0],
                    c.chosen[1], c.chosen[2], c.chosen[3], c.undecided, c.matches, c.refuted);
  const auto per_kemppinen_model = counts_per_model<kKemppinenLevels>(kemppinen_rows);
  const auto header_rule = [](std::size_t columns) {
    std::string s = "|";
    for (std::size_t c = 0; c < columns; ++c) s += "---|";
    return s;
  };
  md += fmt::format(
      "\nThe Kemppinen family (kemppinen_ggx, kemppinen_beckmann; one map per model and incidence, "
      "x the expected points per footprint, {} surface positions per cell{}): the cheapest level "
      "within TAU of k16_exact (Algorithm 1 with k = 16 neighbours and the exact erf); the levels "
      "smooth (the base NDF), then k = 1, 4, 9, 16, each with the rational erf before the exact "
      "one. The black bar on each row is the predicted smooth boundary (kemppinen_boundaries). "
      "`chooser` is the Kemppinen engine chooser's level (core/glints/adequacy.h).\n\n"
      "| model | cells | {} | undecided | chooser = measured | chooser refuted |\n{}\n",
      kemppinen_axes.samples,
      ctx.quick ? " at quick, an eighth of glintlab adequacy --budget quick's 8000" : "",
      fmt::join(kKemppinenLevelNames, " | "), header_rule(kKemppinenLevels + 5));
  for (const auto& [model, c] : per_kemppinen_model)
    md += fmt::format("| {} | {} | {} | {} | {} | {} |\n", model, c.cells,
                      fmt::join(c.chosen, " | "), c.undecided, c.matches, c.refuted);
  std::array<std::size_t, adq::kChermainLevels> chermain_chosen{};
  std::size_t construction_matches = 0, construction_refuted = 0;
  for (const adq::ChermainCellResult& r : chermain_rows) {
    ++chermain_chosen[std::size_t(r.chosen)];
    construction_matches += r.construction == r.chosen ? 1 : 0;
    construction_refuted += r.construction_refuted ? 1 : 0;
  }
  md += fmt::format(
      "\nThe Chermain family (chermain; one map per GGAA derivative |dh_perp/dx| per pixel and "
      "incidence, x the expected microfacets per footprint): the cheapest level within TAU of "
      "dict16_ggaa (all 16 dictionary levels, GGAA on); the black bar is where the construction's "
      "smooth fallback begins (the coarser LOD past the 16th level). The construction's level "
      "(the cheapest equal to dict16_ggaa bit for bit) is the measured one in {} of {} cells and "
      "refuted in {}.\n\n| level | {} |\n|---|{}\n| cells | {} |\n",
      construction_matches, chermain_rows.size(), construction_refuted,
      fmt::join(adq::kChermainLevelNames, " | "),
      [] {
        std::string s;
        for (int l = 0; l < adq::kChermainLevels; ++l) s += "---|";
        return s;
      }(),
      fmt::join(chermain_chosen, " | "));
  md +=
      "\nadequacy-maps.png: every map on one sheet; adequacy-maps-index.csv every map with its "
      "family, model and files; <map>.png and <map>.exr one map each (EXR "
      "channels chosen, chooser, cv_exact, cv_predicted, p_zero, p_zero_predicted; one pixel per "
      "cell, x = N_P, row 0 = the bottom row; the EXR attribute glintlab_family names its "
      "family); adequacy-maps.csv every cell's family, chosen level and the chooser's (the "
      "binomial family's cells, then the area family's: light_half_angle_deg the square's "
      "cone-equivalent half-angle); adequacy-maps-kemppinen.csv the Kemppinen cells (x = the "
      "expected points, lambda Algorithm 1's LOD; Kemppinen EXR channels chosen, chooser, "
      "cv_most_complete, lambda); adequacy-maps-chermain.csv the Chermain cells (chooser: the "
      "construction's level; Chermain EXR channels chosen, construction, cv_most_complete, "
      "lod).\n";
  io::write_file_atomic(ctx.dir / "summary.md", md);
}

}  // namespace

FigureEntry adequacy_maps_entry() {
  return {kId, "glintlab (adequacy of the binomial family)", "docs/adequacy.md, the grid",
          "the cheapest adequate level per family over the adequacy grid's axes, with the "
          "predicted smooth boundary",
          run_adequacy_maps};
}

}  // namespace glintlab::experiments

#include "experiments/adequacy/adequacy_outputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string_view>
#include <type_traits>

#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/io/exr.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::experiments {
namespace {

using verify::adequacy::CellResult;
using verify::adequacy::ChermainCellResult;
using verify::adequacy::kChermainLevelNames;
using verify::adequacy::kChermainLevels;
using verify::adequacy::KemppinenCellResult;
using verify::adequacy::LevelStats;

const std::array<Vec3<double>, 4>& kLevelColors = kAdequacyLevelColors;

// The cells of every map of a run (write_level_maps_csv), which their chart specs draw.
constexpr const char* kLevelsCsv = "adequacy-levels.csv";

// The adequate level of least benchmark cost in a cell of any family, and the costs of its model
// (its family's levels in order, the most complete last).
struct BenchPrice {
  int cheapest = 0;
  std::span<const double> ns;
  double most_complete() const { return ns.back(); }
};
// Unset without costs or where they lack the cell's model.
template <class Row>
std::optional<BenchPrice> bench_price(const Row& r, const std::optional<LevelCosts>& costs) {
  if (!costs) return std::nullopt;
  const auto it = costs->ns.find(r.cell.model);
  if (it == costs->ns.end() || it->second.size() != r.levels.size()) return std::nullopt;
  std::array<bool, std::tuple_size_v<decltype(r.levels)>> adequate{};
  for (std::size_t l = 0; l < adequate.size(); ++l) adequate[l] = r.levels[l].adequate;
  return BenchPrice{cheapest_adequate(adequate, it->second), it->second};
}

// A cell's benchmark prices added to its family's sums; `engine_level(ns)`, where given, is the
// engine chooser's level for these costs at the cell.
template <class Row, class EngineLevel = std::nullptr_t>
void add_bench_price(BenchSums& into, const Row& r, const std::optional<LevelCosts>& costs,
                     double threshold = 0, EngineLevel engine_level = nullptr) {
  const std::optional<BenchPrice> b = bench_price(r, costs);
  if (!b) return;
  into.priced = true;
  into.cheapest_by_benchmark.resize(b->ns.size());
  into.most_complete_ns += b->most_complete();
  into.chosen_ns += b->ns[std::size_t(r.chosen)];
  into.cheapest_ns += b->ns[std::size_t(b->cheapest)];
  ++into.cheapest_by_benchmark[std::size_t(b->cheapest)];
  if constexpr (!std::is_same_v<EngineLevel, std::nullptr_t>) {
    const int level = engine_level(b->ns);
    const LevelStats& s = r.levels[std::size_t(level)];
    into.engine = true;
    into.engine_by_cost.resize(b->ns.size());
    into.engine_ns += b->ns[std::size_t(level)];
    ++into.engine_by_cost[std::size_t(level)];
    into.engine_refuted += s.mean_diff_lcb > threshold || s.cv_diff_lcb > threshold ? 1 : 0;
  }
}

// A family's benchmark sums in adequacy.json (`levels`: the family's level names).
nlohmann::json bench_sums_json(const BenchSums& b, const LevelCosts& costs,
                               std::span<const std::string_view> levels) {
  nlohmann::json by = nlohmann::json::object();
  for (std::size_t l = 0; l < levels.size(); ++l)
    by[std::string(levels[l])] = l < b.cheapest_by_benchmark.size() ? b.cheapest_by_benchmark[l] : 0;
  nlohmann::json j = {{"source", costs.source},
                      {"isa", costs.isa},
                      {"most_complete", levels.back()},
                      {"most_complete_ns_total", b.most_complete_ns},
                      {"chosen_ns_total", b.chosen_ns},
                      {"chosen_saved_fraction", b.chosen_saved()},
                      {"cheapest_ns_total", b.cheapest_ns},
                      {"cheapest_saved_fraction", b.cheapest_saved()},
                      {"cheapest_by_benchmark", by}};
  if (b.engine) {
    nlohmann::json e = nlohmann::json::object();
    for (std::size_t l = 0; l < levels.size(); ++l)
      e[std::string(levels[l])] = l < b.engine_by_cost.size() ? b.engine_by_cost[l] : 0;
    j["engine_by_cost"] = {{"ns_total", b.engine_ns},
                           {"saved_fraction", b.engine_saved()},
                           {"refuted", b.engine_refuted},
                           {"levels", e}};
  }
  return j;
}

// The level names a table's columns carry: the binomial levels where that family is in the table,
// then the Kemppinen levels, then the Chermain levels (a family's smooth level shares the `smooth`
// columns of a family before it: the same meaning, the family's smooth limit).
std::vector<std::string_view> table_levels(bool binomial, bool kemppinen, bool chermain) {
  std::vector<std::string_view> out;
  const auto add = [&](const auto& names) {
    for (std::string_view l : names)
      if (std::find(out.begin(), out.end(), l) == out.end()) out.push_back(l);
  };
  if (binomial) add(kBinomialLevelNames);
  if (kemppinen) add(kKemppinenLevelNames);
  if (chermain) add(kChermainLevelNames);
  return out;
}

void write_csv(const std::filesystem::path& path, const std::vector<CellResult>& rows,
               const std::vector<KemppinenCellResult>& kemppinen_rows,
               const std::vector<CellResult>& area_rows,
               const std::vector<ChermainCellResult>& chermain_rows,
               const std::optional<LevelCosts>& costs) {
  std::vector<std::string> names = {"family",       "model",            "facets",
                                    "alpha",        "light_half_angle_deg", "theta_i_deg",
                                    "theta_h_deg",  "p",                "smooth",
                                    "cv_predicted", "p_zero_predicted", "chosen",
                                    "chooser",      "chooser_refuted"};
  // The Chermain family's GGAA derivative |dh_perp/dx| per pixel, after theta_h_deg, only where
  // that family is in the table (nan in the other families' rows).
  const bool with_dh = !chermain_rows.empty();
  if (with_dh) names.insert(names.begin() + 7, "ggaa_dh");
  const std::array<std::string_view, 8> per_level = {
      "mean", "cv", "p_zero", "mean_diff", "mean_diff_ucb", "cv_diff", "cv_diff_ucb", "adequate"};
  // The area family's levels are the binomial ones (the same columns).
  const std::vector<std::string_view> levels = table_levels(
      !rows.empty() || !area_rows.empty(), !kemppinen_rows.empty(), !chermain_rows.empty());
  for (std::string_view l : levels)
    for (std::string_view q : per_level) names.push_back(fmt::format("{}_{}", l, q));
  // Timing last: the only columns that change from run to run.
  for (std::string_view l : levels) names.push_back(fmt::format("{}_ns", l));
  names.push_back("cheapest_measured");
  names.push_back("time_saved_ns");
  // With --bench-from: the levels priced by the benchmark (the same on every run of that file;
  // bench_exact_ns is the family's most complete level: exact, k16_exact or dict16_ggaa; `none`
  // and `nan` in the rows of a model the costs do not price).
  if (costs)
    for (const char* n : {"cheapest_by_benchmark", "bench_exact_ns", "bench_chosen_ns",
                          "bench_cheapest_ns"})
      names.push_back(n);
  std::vector<std::string_view> header(names.begin(), names.end());
  // A family's row: its levels' statistics in their columns, `nan` where the level is another
  // family's (the project's CSV has a value in every field).
  const auto level_cells = [&](io::CsvWriter& w, const auto& row_levels, const auto& row_names) {
    const auto find = [&](std::string_view l) -> const LevelStats* {
      for (std::size_t i = 0; i < row_names.size(); ++i)
        if (row_names[i] == l) return &row_levels[i];
      return nullptr;
    };
    for (std::string_view l : levels) {
      if (const LevelStats* s = find(l)) {
        w.cell(s->mean).cell(s->cv).cell(s->p_zero).cell(s->mean_diff).cell(s->mean_diff_ucb);
        w.cell(s->cv_diff).cell(s->cv_diff_ucb).cell_int(s->adequate ? 1 : 0);
      } else {
        for (std::size_t k = 0; k < per_level.size(); ++k) w.cell(NAN);
      }
    }
    for (std::string_view l : levels) {
      if (const LevelStats* s = find(l))
        w.cell(s->ns_per_eval);
      else
        w.cell(NAN);
    }
  };
  // The benchmark's columns of a row of any family (`level_names`: its level names).
  const auto bench_cells = [&](io::CsvWriter& w, const auto& r, const auto& level_names) {
    if (!costs) return;
    if (const std::optional<BenchPrice> b = bench_price(r, costs)) {
      w.cell(level_names[std::size_t(b->cheapest)]).cell(b->most_complete());
      w.cell(b->ns[std::size_t(r.chosen)]).cell(b->ns[std::size_t(b->cheapest)]);
    } else {
      w.cell("none").cell(NAN).cell(NAN).cell(NAN);
    }
  };
  // A row of the binomial levels: the binomial family's, or the area family's (its light the
  // square's cone-equivalent half-angle).
  const auto counting_row = [&](io::CsvWriter& w, const CellResult& r, std::string_view family) {
    w.cell(family).cell(r.cell.model).cell(r.cell.facets).cell(r.cell.alpha);
    w.cell(r.cell.light_half_angle_deg).cell(r.cell.theta_i_deg).cell(r.cell.theta_h_deg);
    if (with_dh) w.cell(NAN);
    w.cell(r.p).cell(r.smooth).cell(r.cv_predicted).cell(r.p_zero_predicted);
    w.cell(kBinomialLevelNames[std::size_t(r.chosen)]);
    w.cell(kBinomialLevelNames[std::size_t(r.chooser)]);
    w.cell_int(r.chooser_refuted ? 1 : 0);
    level_cells(w, r.levels, kBinomialLevelNames);
    w.cell(kBinomialLevelNames[std::size_t(r.cheapest_measured)]);
    w.cell(r.levels[3].ns_per_eval - r.levels[std::size_t(r.cheapest_measured)].ns_per_eval);
    bench_cells(w, r, kBinomialLevelNames);
    w.end_row();
  };
  io::write_csv_atomic(path, header, [&](io::CsvWriter& w) {
    for (const CellResult& r : rows) counting_row(w, r, kBinomialFamily);
    constexpr auto kRef = std::size_t(KemppinenLevel::kK16Exact);
    for (const KemppinenCellResult& r : kemppinen_rows) {
      // No light size (the model has none) nor p: nan; cv_predicted is the chooser's bound on
      // k16_exact's CV; no predicted P(0) (nan).
      w.cell(kKemppinenFamily).cell(r.cell.model).cell(r.cell.points).cell(r.cell.alpha);
      w.cell(NAN).cell(r.cell.theta_i_deg).cell(r.cell.theta_h_deg);
      if (with_dh) w.cell(NAN);
      w.cell(NAN).cell(r.smooth).cell(r.cv_bound).cell(NAN);
      w.cell(kKemppinenLevelNames[std::size_t(r.chosen)]);
      w.cell(kKemppinenLevelNames[std::size_t(r.chooser)]).cell_int(r.chooser_refuted ? 1 : 0);
      level_cells(w, r.levels, kKemppinenLevelNames);
      w.cell(kKemppinenLevelNames[std::size_t(r.cheapest_measured)]);
      w.cell(r.levels[kRef].ns_per_eval - r.levels[std::size_t(r.cheapest_measured)].ns_per_eval);
      bench_cells(w, r, kKemppinenLevelNames);
      w.end_row();
    }
    for (const CellResult& r : area_rows) counting_row(w, r, kAreaFamily);
    constexpr auto kMost = std::size_t(verify::adequacy::kChermainMostComplete);
    for (const ChermainCellResult& r : chermain_rows) {
      // No light size nor p: nan; cv_predicted the engine chooser's closed-form CV of dict16_ggaa,
      // no predicted P(0) (nan); `chooser` the engine chooser's level (choose_chermain_model_level:
      // the construction's identical level, GGAA off by its prediction, or the smooth one by that
      // CV), `chooser_refuted` the table refuting it.
      w.cell(kChermainFamily).cell(r.cell.model).cell(r.cell.facets).cell(r.cell.alpha);
      w.cell(NAN).cell(r.cell.theta_i_deg).cell(r.cell.theta_h_deg).cell(r.cell.dh);
      w.cell(NAN).cell(r.smooth).cell(r.cv_predicted).cell(NAN);
      w.cell(kChermainLevelNames[std::size_t(r.chosen)]);
      w.cell(kChermainLevelNames[std::size_t(r.chooser)]);
      w.cell_int(r.chooser_refuted ? 1 : 0);
      level_cells(w, r.levels, kChermainLevelNames);
      w.cell(kChermainLevelNames[std::size_t(r.cheapest_measured)]);
      w.cell(r.levels[kMost].ns_per_eval - r.levels[std::size_t(r.cheapest_measured)].ns_per_eval);
      bench_cells(w, r, kChermainLevelNames);
      w.end_row();
    }
  });
}

nlohmann::json level_json(const LevelStats& s) {
  return {{"mean", s.mean},
          {"cv", s.cv},
          {"p_zero", s.p_zero},
          {"mean_diff", s.mean_diff},
          {"mean_diff_ucb", s.mean_diff_ucb},
          {"cv_diff", s.cv_diff},
          {"cv_diff_ucb", s.cv_diff_ucb},
          {"adequate", s.adequate},
          {"undecided", s.undecided},
          {"ns_per_eval", s.ns_per_eval}};
}

// One measured rate of the decision calibration (a case's row or a pooled one): false adequate
// for δ ≥ 0, the power for δ < 0.
nlohmann::json rate_json(const verify::adequacy::DecisionRateRow& r) {
  return {{"delta", r.delta},
          {"nominal", r.nominal},
          {"z", r.z},
          {"table_level", r.table_level},
          {"truly_adequate", r.truly_adequate},
          {"decisions", r.decisions},
          {"declared_adequate", r.declared_adequate},
          {"rate", r.rate},
          {"rate_low", r.rate_low},
          {"rate_high", r.rate_high},
          {"verdict", verify::adequacy::kRateVerdictNames[std::size_t(r.verdict)]}};
}

}  // namespace

void write_level_maps_csv(const std::filesystem::path& csv,
                          const std::vector<const AdequacyLevelMap*>& maps) {
  io::write_csv_atomic(
      csv, {"map", "row", "row_label", "footprint", "level", "level_name", "boundary"},
      [&](io::CsvWriter& w) {
        for (const AdequacyLevelMap* m : maps) {
          const LevelChart& c = m->map;
          for (std::size_t r = 0; r < c.cells.size(); ++r)
            for (std::size_t k = 0; k < c.cells[r].size(); ++k) {
              const int level = c.cells[r][k];
              if (level < 0) continue;  // no value: the chart draws the cell grey
              w.cell(m->stem).cell_int((long long)r).cell(c.row_labels[r]).cell(c.columns[k]);
              w.cell_int(level).cell(c.category_names[std::size_t(level)]);
              w.cell(c.marker[r]).end_row();  // nan: no predicted boundary in the row
            }
        }
      });
}

void write_level_maps_chart(const std::filesystem::path& png, const std::string& csv_name,
                            const std::string& title,
                            const std::vector<const AdequacyLevelMap*>& maps, int columns) {
  nlohmann::json panels = nlohmann::json::array();
  for (const AdequacyLevelMap* m : maps) {
    const LevelChart& c = m->map;
    nlohmann::json categories = nlohmann::json::array();
    for (std::size_t l = 0; l < c.category_names.size(); ++l) {
      const Vec3<double> rgb = c.category_colors[l];
      categories.push_back(
          {{"value", l}, {"label", c.category_names[l]}, {"color", {rgb.x, rgb.y, rgb.z}}});
    }
    panels.push_back(
        {{"title", c.title},
         {"where", {{"map", m->stem}}},
         {"x", {{"column", "footprint"}, {"label", c.x_label}, {"log", true}}},
         {"y",
          {{"columns", {"row", "row_label"}}, {"format", "{row_label}"}, {"label", c.y_label}}},
         {"value", {{"column", "level"}, {"label", "cheapest adequate level"}}},
         {"categories", categories},
         {"marker", {{"column", "boundary"}, {"label", c.marker_name}}}});
  }
  nlohmann::json spec = {
      {"kind", "categories"}, {"image", png.filename().string()}, {"title", title},
      {"csv", csv_name},      {"columns", std::max(1, columns)},  {"panels", panels}};
  std::filesystem::path sidecar = png;
  io::write_file_atomic(sidecar.replace_extension(".chart.json"), spec.dump(1) + "\n");
}

std::vector<AdequacyLevelMap> adequacy_level_maps(const std::vector<CellResult>& rows,
                                                  const verify::adequacy::GridAxes& axes,
                                                  double threshold) {
  // Per model × light × incidence, rows (α, θ_h) bottom to top, columns N_P.
  std::vector<AdequacyLevelMap> out;
  const std::size_t n_cols = axes.facets.size();
  const std::size_t n_rows = axes.alpha.size() * std::size_t(axes.theta_h_count);
  const std::size_t per_map = n_cols * n_rows;
  for (std::size_t start = 0; start + per_map <= rows.size(); start += per_map) {
    const CellResult& first = rows[start];
    AdequacyLevelMap m;
    m.model = first.cell.model;
    m.light_half_angle_deg = first.cell.light_half_angle_deg;
    m.theta_i_deg = first.cell.theta_i_deg;
    m.stem = fmt::format("adequacy_{}_light{:g}_theta{:g}", first.cell.model,
                         first.cell.light_half_angle_deg, first.cell.theta_i_deg);
    LevelChart& map = m.map;
    const bool square = first.cell.model == verify::adequacy::kAreaFamilyModels[0];
    map.title = fmt::format(
        "{}: cheapest level within TAU = {:g} ({} {:g} deg, theta_i {:g} deg)", first.cell.model,
        threshold, square ? "square light as cone" : "light",
        first.cell.light_half_angle_deg, first.cell.theta_i_deg);
    map.x_label = "footprint size N_P [expected facets]";
    map.y_label = "alpha [1], theta_h [deg]";
    map.columns = axes.facets;
    for (std::string_view l : kBinomialLevelNames) map.category_names.emplace_back(l);
    map.category_colors.assign(kLevelColors.begin(), kLevelColors.end());
    map.marker_name = "predicted: CV = TAU";
    m.exr = Image(int(n_cols), int(n_rows),
                  {"chosen", "chooser", "cv_exact", "cv_predicted", "p_zero", "p_zero_predicted"});
    for (std::size_t r = 0; r < n_rows; ++r) {
      const CellResult& row0 = rows[start + r * n_cols];
      map.row_labels.push_back(
          fmt::format("a={:g} th={:.1f}", row0.cell.alpha, row0.cell.theta_h_deg));
      std::vector<int> cats;
      for (std::size_t k = 0; k < n_cols; ++k) {
        const CellResult& c = rows[start + r * n_cols + k];
        cats.push_back(c.chosen);
        const double v[] = {double(c.chosen), double(c.chooser),        c.levels[3].cv,
                            c.cv_predicted,   c.levels[3].p_zero,       c.p_zero_predicted};
        for (std::size_t ch = 0; ch < 6; ++ch) m.exr.at(int(k), int(r), ch) = v[ch];
      }
      map.cells.push_back(cats);
      // The predicted boundary: CV_pred = TAU at N* = (1 − p)/(p TAU²).
      const double p = row0.p;
      map.marker.push_back(p > 0 && p < 1 ? (1 - p) / (p * threshold * threshold) : NAN);
    }
    out.push_back(std::move(m));
  }
  return out;
}

std::string bench_sums_line(std::string_view family, const BenchSums& b,
                            std::span<const std::string_view> levels, std::string_view source,
                            std::string_view isa) {
  if (!b.priced)
    return fmt::format("{}: no benchmark costs ({} prices none of its models)", family,
                       source);
  std::vector<std::string> cells;
  for (std::size_t l = 0; l < levels.size(); ++l)
    cells.push_back(fmt::format(
        "{} {}", levels[l], l < b.cheapest_by_benchmark.size() ? b.cheapest_by_benchmark[l] : 0));
  std::string line = fmt::format(
      "{}: time per evaluation summed over cells (benchmark {}, {}): {} everywhere {:.0f} ns; "
      "chosen level {:.0f} ns ({:.1f} % saved); cheapest adequate level by the benchmark {:.0f} "
      "ns ({:.1f} % saved; {} cells)",
      family, source, isa, levels.back(), b.most_complete_ns, b.chosen_ns,
      100 * b.chosen_saved(), b.cheapest_ns, 100 * b.cheapest_saved(), fmt::join(cells, ", "));
  if (b.engine) {
    std::vector<std::string> engine;
    for (std::size_t l = 0; l < levels.size(); ++l)
      engine.push_back(
          fmt::format("{} {}", levels[l], l < b.engine_by_cost.size() ? b.engine_by_cost[l] : 0));
    line += fmt::format(
        "; engine chooser for these costs {:.0f} ns ({:.1f} % saved; refuted in {} cells; {} "
        "cells)",
        b.engine_ns, 100 * b.engine_saved(), b.engine_refuted, fmt::join(engine, ", "));
  }
  return line;
}

std::vector<std::string> binomial_models(const std::vector<std::string>& models) {
  std::vector<std::string> out;
  for (std::string_view m : verify::adequacy::kBinomialFamilyModels)
    if (std::find(models.begin(), models.end(), m) != models.end()) out.emplace_back(m);
  return out;
}

std::vector<std::string> priced_models(const std::vector<std::string>& models) {
  std::vector<std::string> out = binomial_models(models);
  for (auto* family : {&kemppinen_models, &area_models, &chermain_models})
    for (std::string& m : (*family)(models)) out.push_back(std::move(m));
  return out;
}

std::vector<std::string> kemppinen_models(const std::vector<std::string>& models) {
  std::vector<std::string> out;
  for (std::string_view m : verify::adequacy::kKemppinenFamilyModels)
    if (std::find(models.begin(), models.end(), m) != models.end()) out.emplace_back(m);
  return out;
}

std::vector<std::string> area_models(const std::vector<std::string>& models) {
  std::vector<std::string> out;
  for (std::string_view m : verify::adequacy::kAreaFamilyModels)
    if (std::find(models.begin(), models.end(), m) != models.end()) out.emplace_back(m);
  return out;
}

std::vector<std::string> chermain_models(const std::vector<std::string>& models) {
  std::vector<std::string> out;
  for (std::string_view m : verify::adequacy::kChermainFamilyModels)
    if (std::find(models.begin(), models.end(), m) != models.end()) out.emplace_back(m);
  return out;
}

verify::adequacy::ChermainGridAxes chermain_axes_of(const AdequacyOptions& o) {
  return o.chermain_axes ? *o.chermain_axes : verify::adequacy::chermain_grid_axes(o.budget);
}

verify::adequacy::GridAxes area_axes_of(const AdequacyOptions& o) {
  return o.area_axes ? *o.area_axes : verify::adequacy::area_grid_axes(o.budget);
}

verify::adequacy::KemppinenGridAxes kemppinen_axes_of(const AdequacyOptions& o) {
  return o.kemppinen_axes ? *o.kemppinen_axes : verify::adequacy::kemppinen_grid_axes(o.budget);
}

verify::adequacy::GridAxes binomial_axes_of(const AdequacyOptions& o) {
  return o.binomial_axes ? *o.binomial_axes : verify::adequacy::grid_axes(o.budget);
}

void set_positions_per_cell(AdequacyOptions& o, int positions) {
  o.binomial_axes = binomial_axes_of(o);
  o.kemppinen_axes = kemppinen_axes_of(o);
  o.area_axes = area_axes_of(o);
  o.chermain_axes = chermain_axes_of(o);
  o.binomial_axes->samples = o.kemppinen_axes->samples = o.area_axes->samples =
      o.chermain_axes->samples = positions;
}

std::size_t table_decisions(const AdequacyOptions& o) {
  const std::size_t binomial =
      verify::adequacy::make_grid(binomial_models(o.models), binomial_axes_of(o))
          .size();
  const std::size_t kemppinen =
      verify::adequacy::make_kemppinen_grid(kemppinen_models(o.models),
                                            kemppinen_axes_of(o))
          .size();
  const std::size_t area =
      verify::adequacy::make_grid(area_models(o.models), area_axes_of(o)).size();
  const std::size_t chermain =
      verify::adequacy::make_chermain_grid(chermain_models(o.models), chermain_axes_of(o)).size();
  return (binomial + area) * std::size_t(kBinomialLevels - 1) +
         kemppinen * std::size_t(kKemppinenLevels - 1) +
         chermain * std::size_t(kChermainLevels - 1);
}

verify::adequacy::Decision table_decision(const AdequacyOptions& o) {
  return verify::adequacy::decision_for_decisions(table_decisions(o), o.threshold);
}

std::vector<CellResult> measure_adequacy(const AdequacyOptions& o) {
  const verify::adequacy::GridAxes axes = binomial_axes_of(o);
  const auto cells = verify::adequacy::make_grid(binomial_models(o.models), axes);
  return verify::adequacy::measure_grid(cells, axes.samples, table_decision(o), o.progress);
}

std::vector<KemppinenCellResult> measure_kemppinen_adequacy(const AdequacyOptions& o) {
  const verify::adequacy::KemppinenGridAxes axes = kemppinen_axes_of(o);
  const auto cells = verify::adequacy::make_kemppinen_grid(kemppinen_models(o.models), axes);
  return verify::adequacy::measure_kemppinen_grid(cells, axes.samples, table_decision(o),
                                                  o.progress);
}

std::vector<AdequacyLevelMap> kemppinen_level_maps(
    const std::vector<KemppinenCellResult>& rows, const verify::adequacy::KemppinenGridAxes& axes,
    double threshold, const std::vector<verify::adequacy::KemppinenBoundary>& boundaries) {
  // Per model × incidence, rows (α, θ_h) bottom to top, columns the expected points.
  std::vector<AdequacyLevelMap> out;
  const std::size_t n_cols = axes.points.size();
  const std::size_t n_rows = axes.alpha.size() * std::size_t(axes.theta_h_count);
  const std::size_t per_map = n_cols * n_rows;
  constexpr auto kRef = std::size_t(KemppinenLevel::kK16Exact);
  for (std::size_t start = 0; start + per_map <= rows.size(); start += per_map) {
    const KemppinenCellResult& first = rows[start];
    AdequacyLevelMap m;
    m.model = first.cell.model;
    m.theta_i_deg = first.cell.theta_i_deg;
    m.stem = fmt::format("adequacy_{}_theta{:g}", first.cell.model, first.cell.theta_i_deg);
    LevelChart& map = m.map;
    map.title = fmt::format("{}: cheapest level within TAU = {:g} of k16_exact (theta_i {:g} deg)",
                            first.cell.model, threshold, first.cell.theta_i_deg);
    map.x_label = "footprint size [expected points]";
    map.y_label = "alpha [1], theta_h [deg]";
    map.columns = axes.points;
    for (std::string_view l : kKemppinenLevelNames) map.category_names.emplace_back(l);
    map.category_colors.assign(kKemppinenLevelColors.begin(), kKemppinenLevelColors.end());
    map.marker_name = "predicted: smooth adequate";
    m.exr = Image(int(n_cols), int(n_rows), {"chosen", "chooser", "cv_most_complete", "lambda"});
    for (std::size_t r = 0; r < n_rows; ++r) {
      const KemppinenCellResult& row0 = rows[start + r * n_cols];
      map.row_labels.push_back(
          fmt::format("a={:g} th={:.1f}", row0.cell.alpha, row0.cell.theta_h_deg));
      std::vector<int> cats;
      for (std::size_t k = 0; k < n_cols; ++k) {
        const KemppinenCellResult& c = rows[start + r * n_cols + k];
        cats.push_back(c.chosen);
        const double v[] = {double(c.chosen), double(c.chooser), c.levels[kRef].cv, c.lambda};
        for (std::size_t ch = 0; ch < 4; ++ch) m.exr.at(int(k), int(r), ch) = v[ch];
      }
      map.cells.push_back(cats);
      // The predicted smooth boundary (kemppinen_boundaries).
      const std::size_t global_row = start / n_cols + r;
      const std::size_t per_row = verify::adequacy::kKemppinenBoundaryLevels.size();
      double marker = NAN;
      if (global_row * per_row < boundaries.size()) {
        const double star = boundaries[global_row * per_row].predicted;  // smooth first
        if (star > 0) marker = star;
      }
      map.marker.push_back(marker);
    }
    out.push_back(std::move(m));
  }
  return out;
}

std::vector<AdequacyLevelMap> chermain_level_maps(const std::vector<ChermainCellResult>& rows,
                                                   const verify::adequacy::ChermainGridAxes& axes,
                                                   double threshold) {
  // Per model × dh × incidence, rows (α, θ_h) bottom to top, columns the expected microfacets.
  std::vector<AdequacyLevelMap> out;
  const std::size_t n_cols = axes.facets.size();
  const std::size_t n_rows = axes.alpha.size() * std::size_t(axes.theta_h_count);
  const std::size_t per_map = n_cols * n_rows;
  constexpr auto kMost = std::size_t(verify::adequacy::kChermainMostComplete);
  for (std::size_t start = 0; start + per_map <= rows.size(); start += per_map) {
    const ChermainCellResult& first = rows[start];
    AdequacyLevelMap m;
    m.model = first.cell.model;
    m.theta_i_deg = first.cell.theta_i_deg;
    m.ggaa_dh = first.cell.dh;
    m.stem = fmt::format("adequacy_{}_dh{:g}_theta{:g}", first.cell.model, first.cell.dh,
                         first.cell.theta_i_deg);
    LevelChart& map = m.map;
    map.title = fmt::format(
        "{}: cheapest within TAU = {:g} of dict16_ggaa (dh {:g}/px, theta_i {:g} deg)",
        first.cell.model, threshold, first.cell.dh, first.cell.theta_i_deg);
    map.x_label = "footprint size [expected microfacets]";
    map.y_label = "alpha [1], theta_h [deg]";
    map.columns = axes.facets;
    for (std::string_view l : kChermainLevelNames) map.category_names.emplace_back(l);
    map.category_colors.assign(kChermainLevelColors.begin(), kChermainLevelColors.end());
    map.marker_name = "construction: smooth fallback from here";
    m.exr = Image(int(n_cols), int(n_rows), {"chosen", "construction", "cv_most_complete", "lod"});
    for (std::size_t r = 0; r < n_rows; ++r) {
      const ChermainCellResult& row0 = rows[start + r * n_cols];
      map.row_labels.push_back(
          fmt::format("a={:g} th={:.1f}", row0.cell.alpha, row0.cell.theta_h_deg));
      std::vector<int> cats;
      for (std::size_t k = 0; k < n_cols; ++k) {
        const ChermainCellResult& c = rows[start + r * n_cols + k];
        cats.push_back(c.chosen);
        const double v[] = {double(c.chosen), double(c.construction), c.levels[kMost].cv, c.lod};
        for (std::size_t ch = 0; ch < 4; ++ch) m.exr.at(int(k), int(r), ch) = v[ch];
      }
      map.cells.push_back(cats);
      map.marker.push_back(verify::adequacy::chermain_identical_facets(16, row0.cell.theta_i_deg));
    }
    out.push_back(std::move(m));
  }
  return out;
}

AdequacySummary run_adequacy(const std::filesystem::path& out, const AdequacyOptions& o) {
  const verify::adequacy::GridAxes axes = binomial_axes_of(o);
  const verify::adequacy::KemppinenGridAxes kemppinen_axes = kemppinen_axes_of(o);
  const auto decision = table_decision(o);
  AdequacyCells cells;
  cells.binomial =
      verify::adequacy::measure_grid(verify::adequacy::make_grid(binomial_models(o.models), axes),
                                     axes.samples, decision, o.progress);
  cells.kemppinen = verify::adequacy::measure_kemppinen_grid(
      verify::adequacy::make_kemppinen_grid(kemppinen_models(o.models), kemppinen_axes),
      kemppinen_axes.samples, decision, o.progress);
  const verify::adequacy::GridAxes area_axes = area_axes_of(o);
  const auto area_cells = verify::adequacy::make_grid(area_models(o.models), area_axes);
  std::vector<std::size_t> all(area_cells.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  cells.area = verify::adequacy::measure_area_grid_at(area_cells, all, area_axes.samples, decision,
                                                      o.progress);
  const verify::adequacy::ChermainGridAxes chermain_axes = chermain_axes_of(o);
  cells.chermain = verify::adequacy::measure_chermain_grid(
      verify::adequacy::make_chermain_grid(chermain_models(o.models), chermain_axes),
      chermain_axes.samples, decision, o.progress);
  return write_adequacy(out, o, cells);
}

AdequacySummary write_adequacy(const std::filesystem::path& out, const AdequacyOptions& o,
                               const AdequacyCells& cells) {
  const verify::adequacy::GridAxes axes = binomial_axes_of(o);
  const verify::adequacy::KemppinenGridAxes kemppinen_axes = kemppinen_axes_of(o);
  const auto decision = table_decision(o);
  const std::vector<CellResult>& rows = cells.binomial;
  const std::vector<KemppinenCellResult>& kemppinen_rows = cells.kemppinen;

  AdequacySummary sum;
  sum.cells = rows.size();
  for (const CellResult& r : rows) {
    ++sum.chosen[std::size_t(r.chosen)];
    sum.chooser_refuted += r.chooser_refuted ? 1 : 0;
    sum.chooser_matches += r.chooser == r.chosen ? 1 : 0;
    sum.exact_ns += r.levels[3].ns_per_eval;
    sum.chosen_ns += r.levels[std::size_t(r.chosen)].ns_per_eval;
    sum.cheapest_ns += r.levels[std::size_t(r.cheapest_measured)].ns_per_eval;
    ++sum.cheapest_measured[std::size_t(r.cheapest_measured)];
    sum.undecided += r.levels[0].undecided ? 1 : 0;
    add_bench_price(sum.bench, r, o.costs);
  }
  sum.decisions = table_decisions(o);
  sum.z = decision.z;
  constexpr auto kRef = std::size_t(KemppinenLevel::kK16Exact);
  for (const KemppinenCellResult& r : kemppinen_rows) {
    auto& k = sum.kemppinen;
    ++k.cells;
    ++k.chosen[std::size_t(r.chosen)];
    ++k.cheapest_measured[std::size_t(r.cheapest_measured)];
    k.chooser_matches += r.chooser == r.chosen ? 1 : 0;
    k.chooser_refuted += r.chooser_refuted ? 1 : 0;
    k.undecided += r.levels[0].undecided ? 1 : 0;
    k.most_complete_ns += r.levels[kRef].ns_per_eval;
    k.chosen_ns += r.levels[std::size_t(r.chosen)].ns_per_eval;
    k.cheapest_ns += r.levels[std::size_t(r.cheapest_measured)].ns_per_eval;
    add_bench_price(k.bench, r, o.costs, o.threshold, [&](std::span<const double> ns) {
      return kemppinen_engine_level_by_cost(r.cell, o.threshold, ns);
    });
  }
  const verify::adequacy::GridAxes area_axes = area_axes_of(o);
  for (const CellResult& r : cells.area) {
    auto& a = sum.area;
    ++a.cells;
    ++a.chosen[std::size_t(r.chosen)];
    ++a.cheapest_measured[std::size_t(r.cheapest_measured)];
    a.chooser_matches += r.chooser == r.chosen ? 1 : 0;
    a.chooser_refuted += r.chooser_refuted ? 1 : 0;
    a.undecided += r.levels[0].undecided ? 1 : 0;
    a.exact_ns += r.levels[3].ns_per_eval;
    a.chosen_ns += r.levels[std::size_t(r.chosen)].ns_per_eval;
    a.cheapest_ns += r.levels[std::size_t(r.cheapest_measured)].ns_per_eval;
    add_bench_price(a.bench, r, o.costs);
  }
  const verify::adequacy::ChermainGridAxes chermain_axes = chermain_axes_of(o);
  constexpr auto kMost = std::size_t(verify::adequacy::kChermainMostComplete);
  for (const ChermainCellResult& r : cells.chermain) {
    auto& c = sum.chermain;
    ++c.cells;
    ++c.chosen[std::size_t(r.chosen)];
    ++c.cheapest_measured[std::size_t(r.cheapest_measured)];
    c.construction_matches += r.construction == r.chosen ? 1 : 0;
    c.construction_refuted += r.construction_refuted ? 1 : 0;
    c.chooser_matches += r.chooser == r.chosen ? 1 : 0;
    c.chooser_refuted += r.chooser_refuted ? 1 : 0;
    c.undecided += r.levels[0].undecided ? 1 : 0;
    c.most_complete_ns += r.levels[kMost].ns_per_eval;
    c.chosen_ns += r.levels[std::size_t(r.chosen)].ns_per_eval;
    c.cheapest_ns += r.levels[std::size_t(r.cheapest_measured)].ns_per_eval;
    add_bench_price(c.bench, r, o.costs, o.threshold, [&](std::span<const double> ns) {
      return chermain_engine_level_by_cost(r.cell, o.threshold, ns);
    });
  }
  std::filesystem::create_directories(out);
  sum.csv = out / "adequacy.csv";
  sum.json = out / "adequacy.json";
  write_csv(sum.csv, rows, kemppinen_rows, cells.area, cells.chermain, o.costs);

  const std::vector<AdequacyLevelMap> binomial_maps = adequacy_level_maps(rows, axes, o.threshold);
  const std::vector<verify::adequacy::KemppinenBoundary> boundaries =
      verify::adequacy::kemppinen_boundaries(kemppinen_rows, kemppinen_axes, o.threshold);
  const std::vector<AdequacyLevelMap> kemppinen_maps =
      kemppinen_level_maps(kemppinen_rows, kemppinen_axes, o.threshold, boundaries);
  const std::vector<AdequacyLevelMap> area_maps =
      adequacy_level_maps(cells.area, area_axes, o.threshold);
  const std::vector<AdequacyLevelMap> chermain_maps =
      chermain_level_maps(cells.chermain, chermain_axes, o.threshold);
  std::vector<const AdequacyLevelMap*> every_map;
  for (const auto* family : {&binomial_maps, &kemppinen_maps, &area_maps, &chermain_maps})
    for (const AdequacyLevelMap& m : *family) every_map.push_back(&m);
  if (!every_map.empty()) write_level_maps_csv(out / kLevelsCsv, every_map);
  nlohmann::json maps = nlohmann::json::array();
  for (const AdequacyLevelMap& m : binomial_maps) {
    // EXR rows: row 0 = the first (α, θ_h) row, as the PNG's bottom row.
    io::write_exr(out / (m.stem + ".exr"), m.exr,
                  {{"glintlab_columns", "N_P: " + fmt::format("{}", fmt::join(axes.facets, ", "))},
                   {"glintlab_rows", fmt::format("{}", fmt::join(m.map.row_labels, "; "))},
                   {"glintlab_levels", "0 smooth, 1 realtime, 2 small_count, 3 exact"}});
    write_level_maps_chart(out / (m.stem + ".png"), kLevelsCsv,
                           "cheapest adequate level per cell, binomial family", {&m});
    sum.maps.push_back(m.stem + ".png");
    maps.push_back({{"family", kBinomialFamily},
                    {"model", m.model},
                    {"light_half_angle_deg", m.light_half_angle_deg},
                    {"theta_i_deg", m.theta_i_deg},
                    {"png", m.stem + ".png"},
                    {"exr", m.stem + ".exr"}});
  }
  for (const AdequacyLevelMap& m : kemppinen_maps) {
    io::write_exr(
        out / (m.stem + ".exr"), m.exr,
        {{"glintlab_columns",
          "expected points: " + fmt::format("{}", fmt::join(kemppinen_axes.points, ", "))},
         {"glintlab_rows", fmt::format("{}", fmt::join(m.map.row_labels, "; "))},
         {"glintlab_levels", "0 smooth, 1 k1_rational, 2 k1_exact, 3 k4_rational, 4 k4_exact, "
                             "5 k9_rational, 6 k9_exact, 7 k16_rational, 8 k16_exact"}});
    write_level_maps_chart(out / (m.stem + ".png"), kLevelsCsv,
                           "cheapest adequate level per cell, Kemppinen family", {&m});
    sum.maps.push_back(m.stem + ".png");
    maps.push_back({{"family", kKemppinenFamily},
                    {"model", m.model},
                    {"theta_i_deg", m.theta_i_deg},
                    {"png", m.stem + ".png"},
                    {"exr", m.stem + ".exr"}});
  }

  for (const AdequacyLevelMap& m : area_maps) {
    io::write_exr(out / (m.stem + ".exr"), m.exr,
                  {{"glintlab_columns",
                    "N_P: " + fmt::format("{}", fmt::join(area_axes.facets, ", "))},
                   {"glintlab_rows", fmt::format("{}", fmt::join(m.map.row_labels, "; "))},
                   {"glintlab_levels", "0 smooth, 1 realtime, 2 small_count, 3 exact"},
                   {"glintlab_light",
                    fmt::format("square of side {:g} at distance {:g}, the solid angle of a cone "
                                "of half-angle {:g} deg",
                                verify::adequacy::square_light_side(m.light_half_angle_deg),
                                verify::adequacy::kAreaLightDistance, m.light_half_angle_deg)}});
    write_level_maps_chart(out / (m.stem + ".png"), kLevelsCsv,
                           "cheapest adequate level per cell, area family (square light of a cone's solid "
                           "angle)",
                           {&m});
    sum.maps.push_back(m.stem + ".png");
    maps.push_back({{"family", kAreaFamily},
                    {"model", m.model},
                    {"light_half_angle_deg", m.light_half_angle_deg},
                    {"theta_i_deg", m.theta_i_deg},
                    {"png", m.stem + ".png"},
                    {"exr", m.stem + ".exr"}});
  }
  for (const AdequacyLevelMap& m : chermain_maps) {
    io::write_exr(
        out / (m.stem + ".exr"), m.exr,
        {{"glintlab_columns",
          "expected microfacets: " + fmt::format("{}", fmt::join(chermain_axes.facets, ", "))},
         {"glintlab_rows", fmt::format("{}", fmt::join(m.map.row_labels, "; "))},
         {"glintlab_levels", "0 smooth, 1 dict4, 2 dict4_ggaa, 3 dict8, 4 dict8_ggaa, 5 dict12, "
                             "6 dict12_ggaa, 7 dict16, 8 dict16_ggaa"},
         {"glintlab_ggaa_dh", fmt::format("{:g}", m.ggaa_dh)}});
    write_level_maps_chart(out / (m.stem + ".png"), kLevelsCsv,
                           "cheapest adequate level per cell, Chermain family", {&m});
    sum.maps.push_back(m.stem + ".png");
    maps.push_back({{"family", kChermainFamily},
                    {"model", m.model},
                    {"ggaa_dh", m.ggaa_dh},
                    {"theta_i_deg", m.theta_i_deg},
                    {"png", m.stem + ".png"},
                    {"exr", m.stem + ".exr"}});
  }

  nlohmann::json doc;
  doc["budget"] = o.budget == verify::Budget::kQuick ? "quick" : "full";
  doc["threshold"] = o.threshold;
  doc["levels"] = kBinomialLevelNames;
  doc["models"] = o.models;
  doc["samples_per_cell"] = axes.samples;
  doc["bound"] = {{"family_wise_rate", verify::kFamilyWiseRate},
                  {"z", decision.z},
                  {"decisions", sum.decisions},
                  {"method", "delta method on paired positions, one-sided, Sidak over every "
                             "(cell, cheaper level) of every family"}};
  doc["difference"] = {
      {"mean", "|mean_level / mean_exact - 1|"},
      {"cv", "|CV_level - CV_exact| (absolute: the smooth level's CV is 0)"}};
  doc["summary"] = {{"cells", sum.cells},
                    {"chosen", {{"smooth", sum.chosen[0]},
                                {"realtime", sum.chosen[1]},
                                {"small_count", sum.chosen[2]},
                                {"exact", sum.chosen[3]}}},
                    {"chooser_matches", sum.chooser_matches},
                    {"chooser_refuted", sum.chooser_refuted},
                    {"exact_ns_total", sum.exact_ns},
                    {"chosen_ns_total", sum.chosen_ns},
                    {"cheapest_measured_ns_total", sum.cheapest_ns},
                    {"undecided", sum.undecided},
                    {"timing_note", "ns columns are measured in-process and vary run to run"}};
  if (o.costs) {
    // Every priced model's levels (each family's own names), and the binomial family's sums (each
    // family's are under families.<family>.benchmark_costs).
    nlohmann::json per_model = nlohmann::json::object();
    for (const auto& [model, ns] : o.costs->ns) {
      const std::span<const std::string_view> names = adequacy_level_names(model);
      nlohmann::json levels = nlohmann::json::object();
      for (std::size_t l = 0; l < ns.size() && l < names.size(); ++l)
        levels[std::string(names[l])] = ns[l];
      per_model[model] = levels;
    }
    nlohmann::json b = bench_sums_json(sum.bench, *o.costs, kBinomialLevelNames);
    b["ns_per_eval"] = per_model;
    b["exact_ns_total"] = sum.bench.most_complete_ns;
    doc["benchmark_costs"] = b;
  } else {
    doc["benchmark_costs"] = nullptr;
  }
  doc["maps"] = maps;
  nlohmann::json table = nlohmann::json::array();
  // A cell of the binomial levels (the binomial or the area family's).
  const auto counting_cell = [](const CellResult& r, std::string_view family) {
    nlohmann::json levels = nlohmann::json::object();
    for (std::size_t l = 0; l < 4; ++l)
      levels[std::string(kBinomialLevelNames[l])] = level_json(r.levels[l]);
    return nlohmann::json{{"family", family},
                     {"model", r.cell.model},
                     {"facets", r.cell.facets},
                     {"alpha", r.cell.alpha},
                     {"light_half_angle_deg", r.cell.light_half_angle_deg},
                     {"theta_i_deg", r.cell.theta_i_deg},
                     {"theta_h_deg", r.cell.theta_h_deg},
                     {"p", r.p},
                     {"cv_predicted", r.cv_predicted},
                     {"p_zero_predicted", r.p_zero_predicted},
                     {"chosen", kBinomialLevelNames[std::size_t(r.chosen)]},
                     {"chooser", kBinomialLevelNames[std::size_t(r.chooser)]},
                     {"chooser_refuted", r.chooser_refuted},
                     {"cheapest_measured", kBinomialLevelNames[std::size_t(r.cheapest_measured)]},
                     {"levels", levels}};
  };
  // A cell's level of least benchmark cost, where the costs price its model.
  const auto add_cheapest_by_benchmark = [&](const auto& r, const auto& names) {
    if (const std::optional<BenchPrice> b = bench_price(r, o.costs))
      table.back()["cheapest_by_benchmark"] = names[std::size_t(b->cheapest)];
  };
  for (const CellResult& r : rows) {
    table.push_back(counting_cell(r, kBinomialFamily));
    add_cheapest_by_benchmark(r, kBinomialLevelNames);
  }
  {
    nlohmann::json chosen = nlohmann::json::object(), cheapest = nlohmann::json::object();
    for (std::size_t l = 0; l < std::size_t(kKemppinenLevels); ++l) {
      chosen[std::string(kKemppinenLevelNames[l])] = sum.kemppinen.chosen[l];
      cheapest[std::string(kKemppinenLevelNames[l])] = sum.kemppinen.cheapest_measured[l];
    }
    // NaN (no boundary) and infinity as null in JSON.
    const auto finite_or_null = [](double x) -> nlohmann::json {
      return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
    };
    nlohmann::json bounds = nlohmann::json::array();
    for (const verify::adequacy::KemppinenBoundary& b : boundaries)
      bounds.push_back({{"model", b.row.model},
                        {"theta_i_deg", b.row.theta_i_deg},
                        {"alpha", b.row.alpha},
                        {"theta_h_deg", b.row.theta_h_deg},
                        {"level", kKemppinenLevelNames[std::size_t(b.level)]},
                        {"predicted", finite_or_null(b.predicted)},
                        {"measured_low", b.measured_low},
                        {"measured_high", finite_or_null(b.measured_high)}});
    doc["families"] = {
        {kBinomialFamily,
         {{"models", binomial_models(o.models)},
          {"levels", kBinomialLevelNames},
          {"most_complete", "exact"},
          {"cells", sum.cells},
          {"samples_per_cell", axes.samples}}},
        {kKemppinenFamily,
         {{"models", kemppinen_models(o.models)},
          {"levels", kKemppinenLevelNames},
          {"most_complete", "k16_exact"},
          {"cells", sum.kemppinen.cells},
          {"samples_per_cell", kemppinen_axes.samples},
          {"material", {{"density", verify::adequacy::kKemppinenDensity},
                        {"microroughness", "model default"},
                        {"filter", "model default"}}},
          {"facets", "expected points per footprint (density x footprint area); the footprint "
                     "stretched by 1/cos(theta_i) along the plane of incidence"},
          {"boundaries", bounds},
          {"boundary",
           "per row and level: predicted, the fewest expected points from which the level stays "
           "adequate by the chooser's moments at TAU (no margin); measured, between measured_low "
           "(the largest grid footprint where it is not adequate; 0: none) and measured_high (the "
           "next; null: not adequate at the largest)"},
          {"summary",
           {{"cells", sum.kemppinen.cells},
            {"chosen", chosen},
            {"cheapest_measured", cheapest},
            {"undecided", sum.kemppinen.undecided},
            {"chooser_matches", sum.kemppinen.chooser_matches},
            {"chooser_refuted", sum.kemppinen.chooser_refuted},
            {"most_complete_ns_total", sum.kemppinen.most_complete_ns},
            {"chosen_ns_total", sum.kemppinen.chosen_ns},
            {"cheapest_measured_ns_total", sum.kemppinen.cheapest_ns}}}}}};
    const auto& a = sum.area;
    nlohmann::json sides = nlohmann::json::array(), solid = nlohmann::json::array();
    for (double g : area_axes.light_half_angle_deg) {
      sides.push_back(verify::adequacy::square_light_side(g));
      solid.push_back(verify::adequacy::square_solid_angle(verify::adequacy::square_light_side(g)));
    }
    const auto per_level = [](const std::array<std::size_t, kBinomialLevels>& n) {
      nlohmann::json j = nlohmann::json::object();
      for (std::size_t l = 0; l < n.size(); ++l) j[std::string(kBinomialLevelNames[l])] = n[l];
      return j;
    };
    doc["families"][std::string(kAreaFamily)] = {
        {"models", area_models(o.models)},
        {"levels", kBinomialLevelNames},
        {"most_complete", "exact"},
        {"cells", a.cells},
        {"samples_per_cell", area_axes.samples},
        {"light",
         {{"shape", "square facing the shading point, centred along omega_o (not turned, not "
                    "tilted); side chosen so that its solid angle 4 asin(w^2/(w^2 + 4 d^2)) is "
                    "the cone's 2 pi (1 - cos gamma)"},
          {"distance", verify::adequacy::kAreaLightDistance},
          {"half_angle_deg", area_axes.light_half_angle_deg},
          {"side", sides},
          {"solid_angle_sr", solid},
          {"p", "D_Omega_h / D_H, D_Omega_h = D_PR x the BRDF LTC lobe's polygon integral "
                "(area_p = ltc); smooth = L_o/L_i by the same lobe (area_lo = ltc)"}}},
        {"chooser", "choose_binomial_level(N_P, p) of core/glints/adequacy.h with the area p: "
                    "the binomial chooser applied to this family, not yet an engine chooser"},
        {"summary",
         {{"cells", a.cells},
          {"chosen", per_level(a.chosen)},
          {"cheapest_measured", per_level(a.cheapest_measured)},
          {"undecided", a.undecided},
          {"chooser_matches", a.chooser_matches},
          {"chooser_refuted", a.chooser_refuted},
          {"exact_ns_total", a.exact_ns},
          {"chosen_ns_total", a.chosen_ns},
          {"cheapest_measured_ns_total", a.cheapest_ns}}}};
    // Each family's benchmark sums where the costs price its models.
    const auto family_costs = [&](std::string_view family, const BenchSums& b,
                                  std::span<const std::string_view> levels) {
      if (b.priced)
        doc["families"][std::string(family)]["benchmark_costs"] =
            bench_sums_json(b, *o.costs, levels);
    };
    family_costs(kBinomialFamily, sum.bench, kBinomialLevelNames);
    family_costs(kKemppinenFamily, sum.kemppinen.bench, kKemppinenLevelNames);
    family_costs(kAreaFamily, a.bench, kBinomialLevelNames);
  }
  if (!chermain_models(o.models).empty()) {
    const auto& c = sum.chermain;
    nlohmann::json chosen = nlohmann::json::object(), cheapest = nlohmann::json::object();
    for (std::size_t l = 0; l < std::size_t(kChermainLevels); ++l) {
      chosen[std::string(kChermainLevelNames[l])] = c.chosen[l];
      cheapest[std::string(kChermainLevelNames[l])] = c.cheapest_measured[l];
    }
    nlohmann::json identical = nlohmann::json::array();
    for (double ti : chermain_axes.theta_i_deg)
      for (int L : {4, 8, 12, 16})
        identical.push_back({{"theta_i_deg", ti},
                             {"dictionary_levels", L},
                             {"facets", verify::adequacy::chermain_identical_facets(L, ti)}});
    doc["families"][std::string(kChermainFamily)] = {
        {"models", chermain_models(o.models)},
        {"levels", kChermainLevelNames},
        {"most_complete", kChermainLevelNames[kMost]},
        {"cells", c.cells},
        {"samples_per_cell", chermain_axes.samples},
        {"material",
         {{"density", verify::adequacy::kChermainDensity},
          {"dictionary", "model default (192 distributions, 16 levels, alpha_dict 0.5, lobe std "
                         "0.02); dictL its first L levels (the same tables), the smooth fallback "
                         "past them"},
          {"ggaa", "projected_half (Eq. 21), s_K model default; off: textureLod"}}},
        {"facets", "expected microfacets per footprint (density x footprint area); the footprint "
                   "stretched by 1/cos(theta_i) along the plane of incidence"},
        {"ggaa_dh", "|d h_perp / dx| = |d h_perp / dy| per pixel (dx along x, dy along y)"},
        {"construction",
         "the cheapest level equal to dict16_ggaa bit for bit by construction (every "
         "weighted LOD's dictionary level below L; GGAA off where ggaa_dh = 0)"},
        {"chooser",
         "choose_chermain_model_level of core/glints/chermain_chooser.h: the construction's "
         "identical level (GGAA off where the closed form predicts it within kChooserMargin x "
         "TAU of GGAA on), or smooth where the closed-form CV of dict16_ggaa (cv_predicted) is at "
         "most kChooserMargin x TAU"},
        {"identical_up_to", identical},
        {"summary",
         {{"cells", c.cells},
          {"chosen", chosen},
          {"cheapest_measured", cheapest},
          {"undecided", c.undecided},
          {"construction_matches", c.construction_matches},
          {"construction_refuted", c.construction_refuted},
          {"chooser_matches", c.chooser_matches},
          {"chooser_refuted", c.chooser_refuted},
          {"most_complete_ns_total", c.most_complete_ns},
          {"chosen_ns_total", c.chosen_ns},
          {"cheapest_measured_ns_total", c.cheapest_ns}}}};
    if (c.bench.priced)
      doc["families"][std::string(kChermainFamily)]["benchmark_costs"] =
          bench_sums_json(c.bench, *o.costs, kChermainLevelNames);
  }
  for (const KemppinenCellResult& r : kemppinen_rows) {
    nlohmann::json levels = nlohmann::json::object();
    for (std::size_t l = 0; l < std::size_t(kKemppinenLevels); ++l)
      levels[std::string(kKemppinenLevelNames[l])] = level_json(r.levels[l]);
    table.push_back({{"family", kKemppinenFamily},
                     {"model", r.cell.model},
                     {"facets", r.cell.points},
                     {"alpha", r.cell.alpha},
                     {"theta_i_deg", r.cell.theta_i_deg},
                     {"theta_h_deg", r.cell.theta_h_deg},
                     {"lambda", r.lambda},
                     {"smooth", r.smooth},
                     {"chosen", kKemppinenLevelNames[std::size_t(r.chosen)]},
                     {"chooser", kKemppinenLevelNames[std::size_t(r.chooser)]},
                     {"chooser_refuted", r.chooser_refuted},
                     {"cv_bound", r.cv_bound},
                     {"cheapest_measured", kKemppinenLevelNames[std::size_t(r.cheapest_measured)]},
                     {"levels", levels}});
    add_cheapest_by_benchmark(r, kKemppinenLevelNames);
  }
  for (const CellResult& r : cells.area) {
    table.push_back(counting_cell(r, kAreaFamily));
    table.back()["light_side"] = verify::adequacy::square_light_side(r.cell.light_half_angle_deg);
    add_cheapest_by_benchmark(r, kBinomialLevelNames);
  }
  for (const ChermainCellResult& r : cells.chermain) {
    nlohmann::json levels = nlohmann::json::object();
    for (std::size_t l = 0; l < std::size_t(kChermainLevels); ++l)
      levels[std::string(kChermainLevelNames[l])] = level_json(r.levels[l]);
    table.push_back({{"family", kChermainFamily},
                     {"model", r.cell.model},
                     {"facets", r.cell.facets},
                     {"alpha", r.cell.alpha},
                     {"theta_i_deg", r.cell.theta_i_deg},
                     {"theta_h_deg", r.cell.theta_h_deg},
                     {"ggaa_dh", r.cell.dh},
                     {"lod", r.lod},
                     {"smooth", r.smooth},
                     {"chosen", kChermainLevelNames[std::size_t(r.chosen)]},
                     {"chooser", kChermainLevelNames[std::size_t(r.chooser)]},
                     {"chooser_refuted", r.chooser_refuted},
                     {"cv_predicted", r.cv_predicted},
                     {"construction", kChermainLevelNames[std::size_t(r.construction)]},
                     {"construction_refuted", r.construction_refuted},
                     {"cheapest_measured", kChermainLevelNames[std::size_t(r.cheapest_measured)]},
                     {"levels", levels}});
    add_cheapest_by_benchmark(r, kChermainLevelNames);
  }
  doc["cells"] = table;
  io::write_file_atomic(sum.json, doc.dump(1) + "\n");
  return sum;
}

verify::adequacy::DecisionCalibrationOptions decision_calibration_options(
    const AdequacyCalibrationOptions& o) {
  const verify::adequacy::GridAxes axes = verify::adequacy::grid_axes(o.budget);
  verify::adequacy::DecisionCalibrationOptions c;
  c.threshold = o.threshold;
  c.samples = o.positions.value_or(axes.samples);
  AdequacyOptions table;
  table.models = o.models;
  table.budget = o.budget;
  c.table_decisions = table_decisions(table);
  c.runs = o.runs;
  c.tables = o.tables;
  c.progress = o.progress;
  return c;
}

AdequacyCalibrationSummary run_adequacy_calibration(const std::filesystem::path& out,
                                                    const AdequacyCalibrationOptions& o) {
  using verify::adequacy::DecisionRateRow;
  using verify::adequacy::kRateVerdictNames;
  using verify::adequacy::kTruthKindNames;
  AdequacyCalibrationSummary sum;
  sum.calibration = verify::adequacy::calibrate_decision(decision_calibration_options(o));
  const verify::adequacy::DecisionCalibration& cal = sum.calibration;
  std::filesystem::create_directories(out);
  sum.csv = out / "adequacy-calibration.csv";
  sum.json = out / "adequacy-calibration.json";
  const std::vector<std::string_view> header = {
      "kind",      "cv_exact",       "trials",            "delta",
      "true_difference", "truly_adequate", "nominal",       "z",
      "table_level", "decisions",      "declared_adequate", "rate",
      "rate_low",  "rate_high",      "verdict"};
  io::write_csv_atomic(sum.csv, header, [&](io::CsvWriter& w) {
    for (const DecisionRateRow& r : cal.rows) {
      w.cell(kTruthKindNames[std::size_t(r.truth.kind)]).cell(r.truth.cv_exact);
      w.cell_int(std::int64_t(r.truth.trials)).cell(r.delta).cell(cal.options.threshold * (1 + r.delta));
      w.cell_int(r.truly_adequate ? 1 : 0).cell(r.nominal).cell(r.z).cell_int(r.table_level ? 1 : 0);
      w.cell_int(std::int64_t(r.decisions)).cell_int(std::int64_t(r.declared_adequate));
      w.cell(r.rate).cell(r.rate_low).cell(r.rate_high);
      w.cell(kRateVerdictNames[std::size_t(r.verdict)]);
      w.end_row();
    }
  });
  nlohmann::json doc;
  doc["threshold"] = cal.options.threshold;
  doc["positions_per_cell"] = cal.options.samples;
  doc["table_decisions"] = cal.options.table_decisions;
  doc["table_z"] = cal.table_decision.z;
  doc["family_wise_rate"] = verify::kFamilyWiseRate;
  doc["runs_per_case"] = cal.options.runs;
  doc["confidence"] = cal.options.confidence;
  doc["truth"] = {
      {"exact", "Binomial(trials, p)/(trials p), p = 1/(1 + trials cv_exact^2)"},
      {"mean", "an independent draw of the exact count times 1 + TAU (1 + delta)"},
      {"cv", "an independent Binomial(trials, p')/(trials p') of CV cv_exact + TAU (1 + delta)"},
      {"smooth", "the constant 1 against an exact level of CV TAU (1 + delta)"}};
  doc["deltas"] = cal.options.deltas;
  doc["tables_per_delta"] = cal.options.tables;
  nlohmann::json family_wise = nlohmann::json::array();
  for (const verify::adequacy::FamilyWiseRow& fw : cal.family_wise)
    family_wise.push_back({{"delta", fw.delta},
                           {"table_decisions", fw.table_decisions},
                           {"tables", fw.tables},
                           {"tables_with_false_adequate", fw.tables_with_false_adequate},
                           {"false_adequate", fw.false_adequate},
                           {"rate", fw.rate},
                           {"rate_low", fw.rate_low},
                           {"rate_high", fw.rate_high},
                           {"nominal", fw.nominal},
                           {"verdict", kRateVerdictNames[std::size_t(fw.verdict)]}});
  doc["family_wise"] = family_wise;
  doc["family_wise_tables"] = "tables of table_decisions decisions at the table's z, every one at "
                              "TAU (1 + delta), the pooled cases in turn";
  nlohmann::json rows = nlohmann::json::array();
  for (const DecisionRateRow& r : cal.rows) {
    nlohmann::json row = rate_json(r);
    row["kind"] = kTruthKindNames[std::size_t(r.truth.kind)];
    row["cv_exact"] = r.truth.cv_exact;
    row["trials"] = r.truth.trials;
    rows.push_back(std::move(row));
  }
  doc["rows"] = rows;
  nlohmann::json pooled = nlohmann::json::array();
  for (const DecisionRateRow& r : cal.pooled) pooled.push_back(rate_json(r));
  doc["pooled"] = pooled;
  doc["pooled_cases"] = "the cases whose other difference's bound is not alone wider than TAU "
                        "(all but mean and cv at cv_exact 1)";
  io::write_file_atomic(sum.json, doc.dump(1) + "\n");
  return sum;
}

}  // namespace glintlab::experiments

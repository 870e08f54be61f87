// Stability maps as EXR + CSV files and chart specs (the PNGs drawn by matplotlib), one set per
// plane of a swept model × sampler.
#include "experiments/sweeps/stability_maps.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/io/exr.h"
#include "experiments/figures/chart_spec.h"

namespace glintlab::experiments {
namespace {

using verify::stability::CellStats;
using verify::stability::Defects;
using verify::stability::ModelSweep;
using verify::stability::SweepMap;

double frac(std::uint64_t k, std::uint64_t n) { return n ? double(k) / double(n) : 0; }

struct Channel {
  std::string name;
  std::function<double(const CellStats&)> get;
};

// The EXR channels of a quantity, the number its map shows and whether a cell fails (what the
// sweep flags), with their labels.
struct QuantitySpec {
  std::vector<Channel> channels;
  Channel shown;            // the CSV column and value of the map
  std::string shown_label;  // its colour bar, with its unit
  bool log = false;         // a log colour scale
  std::function<bool(const CellStats&)> fails;
  std::string fails_label;  // what a flagged cell is
};

QuantitySpec defect_spec(const std::string& q, std::uint64_t Defects::*f, bool with_float) {
  QuantitySpec s;
  s.channels = {
      {q + "_value", [=](const CellStats& c) { return frac(c.value.*f, c.evals); }},
      {q + "_pdf", [=](const CellStats& c) { return frac(c.pdf.*f, c.pdf_calls); }},
      {q + "_sample", [=](const CellStats& c) { return frac(c.sample.*f, c.samples); }},
  };
  if (with_float) {
    s.channels.push_back(
        {q + "_value_float", [=](const CellStats& c) { return frac(c.value_f.*f, c.evals_f); }});
    s.channels.push_back(
        {q + "_pdf_float", [=](const CellStats& c) { return frac(c.pdf_f.*f, c.pdf_calls_f); }});
    s.channels.push_back({q + "_sample_float",
                          [=](const CellStats& c) { return frac(c.sample_f.*f, c.samples_f); }});
  }
  const auto channels = s.channels;
  const auto largest = [channels](const CellStats& c) {
    double m = 0;
    for (const Channel& ch : channels) m = std::max(m, ch.get(c));
    return m;
  };
  const std::string name = q == "nan" ? "NaN" : q == "inf" ? "Inf" : "negative";
  s.shown = {q + "_fraction", largest};
  s.shown_label = fmt::format("{} fraction of calls [1]", name);
  s.fails = [largest](const CellStats& c) { return largest(c) > 0; };  // a single one fails
  s.fails_label = fmt::format("a {} value, pdf or sample seen", name);
  return s;
}

QuantitySpec quantity_spec(const std::string& q, bool with_float) {
  if (q == "nan") return defect_spec(q, &Defects::nan, with_float);
  if (q == "inf") return defect_spec(q, &Defects::inf, with_float);
  if (q == "negative") return defect_spec(q, &Defects::negative, with_float);
  QuantitySpec s;
  if (q == "energy_gain") {
    s.channels = {
        {"albedo_minus_1", [](const CellStats& c) { return c.albedo - 1; }},
        {"albedo_error", [](const CellStats& c) { return c.albedo_error; }},
        {"albedo_uniform_minus_1", [](const CellStats& c) { return c.albedo_uniform - 1; }},
        {"albedo_uniform_error", [](const CellStats& c) { return c.albedo_uniform_error; }},
        {"gain", [](const CellStats& c) { return c.gain(); }},
    };
    s.shown = {"albedo", [](const CellStats& c) { return c.albedo; }};
    s.shown_label = "white-furnace albedo [1]";
    s.fails = [](const CellStats& c) { return c.energy_gain(); };
    s.fails_label = fmt::format("energy gain: albedo > 1 beyond {:g} standard errors",
                                verify::stability::kGainSigmas);
  } else if (q == "p_gt_1") {
    s.channels = {
        {"p_gt_1", [](const CellStats& c) { return frac(c.p_above_one, c.p_evals); }},
        {"p_max", [](const CellStats& c) { return c.p_max; }},
    };
    s.shown = {"p_max", [](const CellStats& c) { return c.p_max; }};
    s.shown_label = "largest probability p seen [1]";
    s.fails = [](const CellStats& c) { return c.p_above_one > 0; };
    s.fails_label = "p > 1 seen";
  } else {  // variance
    s.channels = {
        {"relative_variance", [](const CellStats& c) { return c.relative_variance; }},
        {"weight_max", [](const CellStats& c) { return c.weight_max; }},
        {"accepted_fraction", [](const CellStats& c) { return frac(c.accepted, c.samples); }},
    };
    s.shown = {"relative_variance", [](const CellStats& c) { return c.relative_variance; }};
    s.shown_label = "Var(w)/E(w)^2 of the sample weight [1] (log scale)";
    s.log = true;
    s.fails = [](const CellStats& c) { return c.variance_blowup(); };
    s.fails_label =
        fmt::format("variance blow-up: Var(w)/E(w)^2 > {:g}", verify::stability::kVarianceBlowup);
  }
  return s;
}

// The y axis of a plane's maps: its row value with its unit.
std::string row_axis_label(const verify::stability::SweepPlane& p) {
  using verify::stability::Axis;
  if (p.axis == Axis::kLightSize) return "light cone half-angle [deg]";
  if (p.axis == Axis::kFootprint) return "footprint size s [uv per pixel]";
  return p.row_label + " [1]";
}

// A CSV of one row per cell of `m` (row-major, as m.cells), each written by
// row(writer, cell, row index, column index), written atomically to `path`.
void write_cells_csv(
    const SweepMap& m, const std::vector<std::string>& header, const std::filesystem::path& path,
    const std::function<void(io::CsvWriter&, const CellStats&, std::size_t, std::size_t)>& row) {
  std::vector<std::string_view> views(header.begin(), header.end());
  std::ostringstream text;
  {
    io::CsvWriter w(text, views);
    const std::size_t cols = m.plane.theta_deg.size();
    for (std::size_t i = 0; i < m.cells.size(); ++i) {
      row(w, m.cells[i], i / cols, i % cols);
      w.end_row();
    }
    w.flush();
  }
  io::write_file_atomic(path, text.str());
}

// PLANE_maps.csv: per cell (rows as PLANE.csv's) the number each quantity's map shows and
// whether the cell fails; the maps' charts read it.
void write_map_csv(const SweepMap& m, const std::vector<std::string>& quantities,
                   const std::vector<QuantitySpec>& specs, const std::filesystem::path& path) {
  std::vector<std::string> header = {"row_index", "column_index", m.plane.name, "theta_i_deg"};
  for (std::size_t k = 0; k < specs.size(); ++k) {
    header.push_back(specs[k].shown.name);
    header.push_back(quantities[k] + "_fails");
  }
  write_cells_csv(m, header, path,
                  [&](io::CsvWriter& w, const CellStats& c, std::size_t i, std::size_t j) {
                    w.cell_int(static_cast<long long>(i)).cell_int(static_cast<long long>(j));
                    w.cell(m.plane.rows[i]).cell(m.plane.theta_deg[j]);
                    for (const QuantitySpec& q : specs)
                      w.cell(q.shown.get(c)).cell_int(q.fails(c) ? 1 : 0);
                  });
}

// PLANE_QUANTITY.chart.json: the quantity's map over (θi, the plane's rows), failing cells
// outlined, drawn by reports/figure_charts.py into PLANE_QUANTITY.png.
void write_map_spec(const SweepMap& m, const ModelSweep& s, const std::string& q,
                    const QuantitySpec& spec, const std::string& csv,
                    const std::filesystem::path& png) {
  std::size_t failing = 0;
  for (const CellStats& c : m.cells) failing += spec.fails(c) ? 1 : 0;
  nlohmann::json value = {{"column", spec.shown.name}, {"label", spec.shown_label}};
  if (spec.log) value["log"] = true;
  const nlohmann::json panel = {
      {"title", fmt::format("{}: {} of {} cells fail", q, failing, m.cells.size())},
      {"x", {{"column", "theta_i_deg"}, {"label", "incidence angle theta_i [deg]"}}},
      {"y",
       {{"columns", {m.plane.name}},
        {"format", fmt::format("{{{}:.3g}}", m.plane.name)},
        {"label", row_axis_label(m.plane)}}},
      {"value", value},
      {"flags",
       {{{"column", q + "_fails"},
         {"value", 1},
         {"label", spec.fails_label},
         {"color", {1.0, 0.0, 0.0}},
         {"style", "outline"}}}},
      {"empty_label", "no value (not finite, or zero on a log scale)"}};
  write_chart_json(png, {
      {"kind", "heatmap"},
      {"title", fmt::format("stability sweep of {} (sampler {}): {}\nplane {} x theta_i",
                            s.target.model->name, s.target.sampler, q, m.plane.name)},
      {"csv", csv},
      {"panels", {panel}}});
}

void write_csv(const SweepMap& m, const ModelSweep& s, const std::filesystem::path& path) {
  const std::string row_col = m.plane.name;
  std::vector<std::string> header = {"model",     "sampler",     "row_index",      "column_index",
                                     row_col,     "theta_i_deg", "in_core_domain", "evals",
                                     "pdf_calls", "samples",     "accepted"};
  for (std::string q : {"nan", "inf", "negative"})
    for (std::string c : {"value", "pdf", "sample"}) {
      header.push_back(q + "_" + c + "_fraction");
      header.push_back(q + "_" + c + "_float_fraction");
    }
  for (std::string h : {"p_evals", "p_gt_1_fraction", "p_max", "albedo", "albedo_error",
                        "albedo_uniform", "albedo_uniform_error", "energy_gain",
                        "relative_variance", "variance_blowup", "weight_max", "float_swept"})
    header.push_back(h);
  write_cells_csv(
      m, header, path, [&](io::CsvWriter& w, const CellStats& c, std::size_t i, std::size_t j) {
        const double row = m.plane.rows[i], th = m.plane.theta_deg[j];
        w.cell(std::string_view(s.target.model->name)).cell(s.target.sampler);
        w.cell_int(static_cast<long long>(i)).cell_int(static_cast<long long>(j));
        w.cell(row).cell(th);
        w.cell_int(verify::stability::in_core_domain(m.plane, row, th) ? 1 : 0);
        w.cell_int(static_cast<long long>(c.evals)).cell_int(static_cast<long long>(c.pdf_calls));
        w.cell_int(static_cast<long long>(c.samples)).cell_int(static_cast<long long>(c.accepted));
        for (auto f : {&Defects::nan, &Defects::inf, &Defects::negative}) {
          w.cell(frac(c.value.*f, c.evals)).cell(frac(c.value_f.*f, c.evals_f));
          w.cell(frac(c.pdf.*f, c.pdf_calls)).cell(frac(c.pdf_f.*f, c.pdf_calls_f));
          w.cell(frac(c.sample.*f, c.samples)).cell(frac(c.sample_f.*f, c.samples_f));
        }
        w.cell_int(static_cast<long long>(c.p_evals)).cell(frac(c.p_above_one, c.p_evals));
        w.cell(c.p_max).cell(c.albedo).cell(c.albedo_error).cell(c.albedo_uniform);
        w.cell(c.albedo_uniform_error).cell(c.gain()).cell(c.relative_variance);
        w.cell_int(c.variance_blowup() ? 1 : 0).cell(c.weight_max).cell_int(s.has_float ? 1 : 0);
      });
}

}  // namespace

std::vector<std::string> map_quantities(const ModelSweep& s) {
  std::vector<std::string> q = {"nan", "inf", "negative", "energy_gain"};
  if (s.has_probability) q.push_back("p_gt_1");
  q.push_back("variance");
  return q;
}

std::vector<MapFile> write_stability_maps(const ModelSweep& s, const std::filesystem::path& root,
                                          const std::filesystem::path& rel) {
  std::filesystem::create_directories(root / rel);
  std::vector<MapFile> files;
  const std::vector<std::string> quantities = map_quantities(s);
  std::vector<QuantitySpec> specs;
  for (const std::string& q : quantities) specs.push_back(quantity_spec(q, s.has_float));
  for (const SweepMap& m : s.maps) {
    const std::string csv = (rel / (m.plane.name + ".csv")).generic_string();
    write_csv(m, s, root / csv);
    const std::string map_csv = m.plane.name + "_maps.csv";
    write_map_csv(m, quantities, specs, root / rel / map_csv);
    const int w = int(m.plane.theta_deg.size()), h = int(m.plane.rows.size());
    for (std::size_t qi = 0; qi < quantities.size(); ++qi) {
      const std::string& q = quantities[qi];
      const QuantitySpec& spec = specs[qi];
      std::vector<std::string> names;
      for (const auto& ch : spec.channels) names.push_back(ch.name);
      Image exr(w, h, names);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const CellStats& c = m.at(std::size_t(y), std::size_t(x));
          for (std::size_t k = 0; k < spec.channels.size(); ++k)
            exr.at(x, y, k) = spec.channels[k].get(c);
        }
      const std::string stem = m.plane.name + "_" + q;
      const std::string exr_path = (rel / (stem + ".exr")).generic_string();
      const std::string png_path = (rel / (stem + ".png")).generic_string();
      std::string rows, cols;
      for (double r : m.plane.rows) rows += fmt::format("{}{:g}", rows.empty() ? "" : ",", r);
      for (double t : m.plane.theta_deg) cols += fmt::format("{}{:g}", cols.empty() ? "" : ",", t);
      io::write_exr(root / exr_path, exr,
                    {{"glintlab_model", std::string(s.target.model->name)},
                     {"glintlab_sampler", s.target.sampler},
                     {"glintlab_quantity", q},
                     {"glintlab_rows", m.plane.row_label + ": " + rows},
                     {"glintlab_columns", "theta_i_deg: " + cols}});
      write_map_spec(m, s, q, spec, map_csv, root / png_path);
      files.push_back({q, m.plane.name, png_path, exr_path, csv});
    }
  }
  return files;
}

}  // namespace glintlab::experiments

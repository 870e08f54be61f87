// NAME.chart.json beside a chart PNG, and the heat maps of image channels (chart_spec.h).
#include "experiments/figures/chart_spec.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/io/atomic_file.h"
#include "core/io/csv.h"

namespace glintlab::experiments {
namespace {

using nlohmann::json;

json where_json(const ChartWhere& w) {
  json j = json::object();
  for (const auto& [column, value] : w) j[column] = value;
  return j;
}

json axis_json(const ChartAxis& a) {
  json j = {{"label", a.label}, {"log", a.log}};
  if (!a.column.empty()) j["column"] = a.column;
  if (a.range) j["range"] = {(*a.range)[0], (*a.range)[1]};
  return j;
}

json series_json(const ChartSeriesSpec& s) {
  json j = {{"label", s.label}, {"where", where_json(s.where)},
            {"y", s.y},         {"color", {s.color[0], s.color[1], s.color[2]}},
            {"line", s.line},   {"marker", s.marker}};
  if (!s.y_error.empty()) j["yerr"] = s.y_error, j["yerr_scale"] = s.y_error_scale;
  if (!s.point_label.empty()) j["point_label"] = s.point_label;
  if (!s.mark.empty()) j["mark"] = s.mark, j["mark_label"] = s.mark_label;
  return j;
}

}  // namespace

void write_chart_spec(const std::filesystem::path& png, const ChartSpec& spec) {
  json panels = json::array();
  for (const ChartPanel& p : spec.panels) {
    json series = json::array(), lines = json::array();
    for (const ChartSeriesSpec& s : p.series) series.push_back(series_json(s));
    for (const ChartLine& l : p.hlines) lines.push_back({{"y", l.y}, {"label", l.label}});
    panels.push_back({{"title", p.title},
                      {"where", where_json(p.where)},
                      {"x", axis_json(p.x)},
                      {"y", axis_json(p.y)},
                      {"series", series},
                      {"hlines", lines}});
    if (!p.guide_label.empty())
      panels.back()["slope_guide"] = {{"slope", p.guide_slope}, {"label", p.guide_label}};
  }
  json j = {{"title", spec.title}, {"csv", spec.csv}, {"panels", panels}};
  if (spec.columns > 0) j["columns"] = spec.columns;
  write_chart_json(png, std::move(j));
}

void write_chart_json(const std::filesystem::path& png, nlohmann::json spec) {
  spec["image"] = png.filename().string();
  std::filesystem::path sidecar = png;
  io::write_file_atomic(sidecar.replace_extension(".chart.json"), spec.dump(1) + "\n");
}

ImageMapPanel image_map_panel(std::string key, std::string title, const Image* image,
                              std::string channel) {
  ImageMapPanel p;
  p.key = std::move(key), p.title = std::move(title), p.image = image;
  p.channel = std::move(channel);
  return p;
}

void write_image_maps(const std::filesystem::path& png, const std::string& title,
                      const std::vector<ImageMapPanel>& panels, int columns,
                      const std::string& value_column) {
  const std::string stem = png.stem().string(), csv = stem + "_map.csv";
  nlohmann::json specs = nlohmann::json::array();
  io::write_csv_atomic(png.parent_path() / csv, {"panel", "x", "y", value_column},
                       [&](io::CsvWriter& w) {
                         for (const ImageMapPanel& m : panels) {
                           const Image& img = *m.image;
                           const int block = (std::max(img.width, img.height) + 127) / 128;
                           const std::size_t c = img.channel(m.channel);
                           for (int cy = 0; cy * block < img.height; ++cy)
                             for (int cx = 0; cx * block < img.width; ++cx) {
                               double sum = 0;
                               int n = 0;
                               for (int y = cy * block; y < std::min(img.height, (cy + 1) * block);
                                    ++y)
                                 for (int x = cx * block;
                                      x < std::min(img.width, (cx + 1) * block); ++x) {
                                   const double v = img.at(x, y, c);
                                   if (!m.inside.empty() &&
                                       !(img.at(x, y, img.channel(m.inside)) > 0))
                                     continue;
                                   if (std::isfinite(v)) sum += v, ++n;
                                 }
                               if (n == 0) continue;
                               // The block's centre: the mean of its pixel indices.
                               const double i = cx * block + (block - 1) / 2.0,
                                            j = cy * block + (block - 1) / 2.0;
                               w.cell(m.key).cell(m.x0 + m.dx * i).cell(m.y0 + m.dy * j);
                               w.cell(sum / n).end_row();
                             }
                         }
                       });
  for (const ImageMapPanel& m : panels)
    specs.push_back({{"title", m.title},
                     {"where", {{"panel", m.key}}},
                     {"x", {{"column", "x"}, {"label", m.x_label}}},
                     {"y", {{"columns", {"y"}}, {"format", "{y:.3g}"}, {"label", m.y_label},
                            {"invert", m.top_down}}},
                     {"value", {{"column", value_column}, {"label", m.value_label},
                                {"range", {m.range[0], m.range[1]}}}},
                     {"empty_label", "outside the map (no pixel)"}});
  write_chart_json(png, {{"kind", "heatmap"},
                         {"title", title},
                         {"csv", csv},
                         {"columns", columns},
                         {"panels", specs}});
}

}  // namespace glintlab::experiments

// NAME.chart.json beside a chart PNG (chart_spec.h).
#include "experiments/figures/chart_spec.h"

#include <nlohmann/json.hpp>

#include "core/io/atomic_file.h"

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

}  // namespace glintlab::experiments

// What a figure's line chart shows, written beside NAME.png as NAME.chart.json: the figure writes
// the numbers (a CSV) and this spec, and reports/figure_charts.py draws the chart with matplotlib
// into NAME.png (`glintlab figure` runs it on the staging folder), with the report's labelling
// rules: a title, axis labels with their units, a legend. No chart is drawn in C++.
#pragma once

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/render/image.h"

namespace glintlab::experiments {

// Rows of the CSV a panel or series takes: every column equal to its value (as text, or as a
// number where both are numbers).
using ChartWhere = std::vector<std::pair<std::string, std::string>>;

struct ChartAxis {
  std::string column{};  // x only: the CSV column on this axis (a series names its own y)
  std::string label{};   // with its unit in brackets, e.g. "time per evaluation [ns]"
  bool log = false;
  std::optional<std::array<double, 2>> range{};  // none: matplotlib's from the data
};

struct ChartSeriesSpec {
  std::string label{};  // in the legend
  ChartWhere where{};
  std::string y{};        // the CSV column on the y axis
  std::string y_error{};  // optional: error bar half-length column, times y_error_scale
  double y_error_scale = 1;
  std::array<double, 3> color{0, 0, 0};  // linear 0..1 RGB as matplotlib takes it
  std::string line = "solid";            // solid, dashed, dotted or none (points only)
  std::string marker = "o";              // a matplotlib marker
  std::string point_label{};  // optional: a Python str.format template over the row, e.g. "{k}"
  std::string mark{};         // optional: a 0/1 column; its 1 rows ringed and joined, dashed
  std::string mark_label{};   // what the marked rows are, e.g. "Pareto front"
};

struct ChartLine {
  double y{};
  std::string label{};
};

struct ChartPanel {
  std::string title{};
  ChartWhere where{};
  ChartAxis x{}, y{};
  std::vector<ChartSeriesSpec> series{};
  std::vector<ChartLine> hlines{};  // horizontal reference lines
  // A power law x^slope through the first series' first point (e.g. -1/2: unbiased Monte Carlo),
  // when guide_label is not empty.
  double guide_slope = 0;
  std::string guide_label{};
};

struct ChartSpec {
  std::string title{};  // what the whole chart shows
  std::string csv{};    // the CSV's file name, in the same folder
  int columns = 0;      // panels per row (0: all in one row)
  std::vector<ChartPanel> panels{};
};

// Writes NAME.chart.json beside `png` = NAME.png (atomic); the PNG itself is drawn later, by
// reports/figure_charts.py. Throws std::runtime_error naming the file on failure.
void write_chart_spec(const std::filesystem::path& png, const ChartSpec& spec);

// Writes a spec given as JSON (a heat map's or a map of categories', reports/figure_charts.py's
// other kinds) as NAME.chart.json beside `png` = NAME.png, with "image" set to the PNG's name.
void write_chart_json(const std::filesystem::path& png, nlohmann::json spec);

// One panel of a heat map of an image channel: the pixel at column i, row j sits at
// (x0 + dx i, y0 + dy j) on the panel's axes; `inside` (optional) keeps the pixels of the map (the
// others are cells without a value).
struct ImageMapPanel {
  std::string key, title;  // the CSV's panel column; the panel's title
  const Image* image = nullptr;
  std::string channel;
  double x0 = 0, dx = 1, y0 = 0, dy = 1;
  std::string x_label, y_label, value_label;  // each with its unit
  std::array<double, 2> range{0, 1};          // the colour bar's
  std::string inside;                         // a 0/1 channel, or empty: every pixel
  bool top_down = true;                       // the image's first row at the top of the map
};

ImageMapPanel image_map_panel(std::string key, std::string title, const Image* image,
                              std::string channel);

// NAME_map.csv (panel, x, y, `value_column`: per cell the mean of its finite pixels, at most
// 128 x 128 cells a panel, each a block of pixels; a cell without one is left out) and the
// heat-map spec of NAME.png, one panel per ImageMapPanel, `columns` to a row: reports/
// figure_charts.py draws it. A map of numbers is this heat map, not a grey montage.
void write_image_maps(const std::filesystem::path& png, const std::string& title,
                      const std::vector<ImageMapPanel>& panels, int columns,
                      const std::string& value_column);

}  // namespace glintlab::experiments

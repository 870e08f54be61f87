// A raster log-log scatter chart for the figures' PNG previews (speed vs accuracy, cost vs
// footprint): decade grid with tick labels, one colour per series, labelled points, a polyline per
// series (e.g. its Pareto front), drawn with a built-in 5×7 pixel font (no font files needed).
#pragma once

#include <string>
#include <vector>

#include "core/math/vec.h"
#include "core/render/image.h"

namespace glintlab::experiments {

struct ChartPoint {
  double x, y;          // > 0 (points with x or y ≤ 0 or non-finite are skipped)
  std::string label;    // drawn beside the point ("" = none)
  bool ringed = false;  // drawn with a black ring (e.g. on the Pareto front)
};

struct ChartSeries {
  std::string name;  // in the legend
  Vec3<double> color;
  std::vector<ChartPoint> points;
  // Joined by a line in this order (e.g. the front sorted by x, or a curve over x).
  std::vector<Vec2<double>> line;
};

struct LogChart {
  std::string title, x_label, y_label;
  std::vector<ChartSeries> series;
};

// The chart as an RGB image of width × height pixels; axes span the data's decades.
Image draw_log_chart(const LogChart& chart, int width = 640, int height = 440);

// A labelled map of categories: one block per cell (rows bottom to top, columns left to right),
// column tick labels under the x axis, row labels left of the y axis, a legend of the categories
// and, per row, an optional black bar at a fractional column position (e.g. a predicted boundary,
// named by marker_name in the legend). Used for the adequacy maps.
struct CategoryMap {
  std::string title, x_label, y_label;
  std::vector<std::string> column_labels, row_labels;
  std::vector<std::string> category_names;
  std::vector<Vec3<double>> category_colors;
  std::vector<std::vector<int>> cells;  // [row][column] category index (-1 = none, drawn grey)
  std::vector<double> marker_column;    // per row: the bar's column position (NaN = none)
  std::string marker_name;
};
Image draw_category_map(const CategoryMap& map, int cell_width = 40, int cell_height = 22);

// Indices (into `xy`, input order) of the points no other point beats in both coordinates (lower
// x and lower y are better; ties kept): the Pareto front of time against error.
std::vector<std::size_t> pareto_front(const std::vector<Vec2<double>>& xy);

// `text` drawn into the first three channels of `image` in the charts' 5×7 pixel font (lower case
// as upper), its top-left corner at (x, y), 6 pixels per character; pixels outside are skipped.
void draw_text(Image& image, int x, int y, const std::string& text, Vec3<double> color);

}  // namespace glintlab::experiments

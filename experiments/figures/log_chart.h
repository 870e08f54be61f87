// The raster category map and text of the adequacy outputs (adequacy maps and the adequacy-scene
// sheet), drawn with a built-in 5×7 pixel font (no font files needed). The figures' line charts
// are drawn by matplotlib from their chart specs (chart_spec.h); these go the same way next.
#pragma once

#include <string>
#include <vector>

#include "core/math/vec.h"
#include "core/render/image.h"

namespace glintlab::experiments {

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

// `text` drawn into the first three channels of `image` in the charts' 5×7 pixel font (lower case
// as upper), its top-left corner at (x, y), 6 pixels per character; pixels outside are skipped.
void draw_text(Image& image, int x, int y, const std::string& text, Vec3<double> color);

}  // namespace glintlab::experiments

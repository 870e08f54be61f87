// draw_category_map (experiments/figures/log_chart.h), the adequacy maps' labelled heatmap: each
// cell is drawn in its category's colour, rows bottom to top, and the marker bar is black.
#include <gtest/gtest.h>

#include <cmath>

#include "experiments/figures/log_chart.h"

namespace glintlab::experiments {
namespace {

CategoryMap two_by_three() {
  CategoryMap m;
  m.title = "T";
  m.x_label = "X";
  m.y_label = "Y";
  m.column_labels = {"1", "10", "100"};
  m.row_labels = {"low", "high"};
  m.category_names = {"a", "b"};
  m.category_colors = {{1, 0, 0}, {0, 0, 1}};
  m.cells = {{0, 0, 1}, {1, 1, 1}};
  m.marker_column = {NAN, NAN};
  return m;
}

// The colour at the centre of cell (row, column) of a map drawn with 40 × 22 cells.
Vec3<double> cell_colour(const Image& img, const CategoryMap& m, int row, int col) {
  std::size_t chars = 0;
  for (const auto& l : m.row_labels) chars = std::max(chars, l.size());
  const int left = 24 + 6 * int(chars), top = 28, rows = int(m.row_labels.size());
  const int x = left + col * 40 + 20, y = top + rows * 22 - row * 22 - 11;
  return {img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)};
}

TEST(CategoryMap, CellsTakeTheirCategoryColourRowsBottomUp) {
  const CategoryMap m = two_by_three();
  const Image img = draw_category_map(m);
  EXPECT_EQ(cell_colour(img, m, 0, 0).x, 1);  // row 0 (bottom), column 0: category a (red)
  EXPECT_EQ(cell_colour(img, m, 0, 2).z, 1);  // category b (blue)
  EXPECT_EQ(cell_colour(img, m, 1, 0).z, 1);
  EXPECT_EQ(cell_colour(img, m, 1, 0).x, 0);
}

TEST(CategoryMap, MarkerIsDrawnAtItsColumn) {
  CategoryMap m = two_by_three();
  m.marker_column = {1.0, NAN};
  const Image img = draw_category_map(m);
  const Vec3<double> c = cell_colour(img, m, 0, 1);  // the bar runs through the cell's centre
  EXPECT_EQ(c.x + c.y + c.z, 0);
  const Vec3<double> d = cell_colour(img, m, 1, 1);  // no bar on the other row
  EXPECT_EQ(d.z, 1);
}

}  // namespace
}  // namespace glintlab::experiments

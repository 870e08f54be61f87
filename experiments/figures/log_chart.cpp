// The raster category map and text of log_chart.h.
#include "experiments/figures/log_chart.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace glintlab::experiments {
namespace {

// 5×7 glyphs, one byte per row (top first), bit 4 the leftmost column; lower case drawn as upper.
struct Glyph {
  char c;
  std::array<std::uint8_t, 7> rows;
};
constexpr Glyph kGlyphs[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
    {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
    {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
    {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
    {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
    {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'A', {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'B', {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}},
    {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}},
    {'D', {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}},
    {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}},
    {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}},
    {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}},
    {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}},
    {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}},
    {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}},
    {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}},
    {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
    {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
    {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}},
    {'Q', {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}},
    {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}},
    {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}},
    {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
    {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}},
    {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
    {'Y', {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}},
    {'Z', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}},
    {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}},
    {',', {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}},
    {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}},
    {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}},
    {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
    {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},
    {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F}},
    {'*', {0x00, 0x04, 0x15, 0x0E, 0x15, 0x04, 0x00}},
    {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
    {'|', {0x04, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
};

class Canvas {
 public:
  Canvas(int w, int h) : img_(w, h, {"R", "G", "B"}) {
    std::fill(img_.data.begin(), img_.data.end(), 1.0);
  }
  void set(int x, int y, Vec3<double> c) {
    if (x < 0 || y < 0 || x >= img_.width || y >= img_.height) return;
    img_.at(x, y, 0) = c.x, img_.at(x, y, 1) = c.y, img_.at(x, y, 2) = c.z;
  }
  void rect(int x0, int y0, int x1, int y1, Vec3<double> c) {
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) set(x, y, c);
  }
  void line(double x0, double y0, double x1, double y1, Vec3<double> c, bool dashed = false) {
    const int n = int(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
    for (int i = 0; i <= n; ++i) {
      if (dashed && (i / 4) % 2 == 1) continue;
      const double t = double(i) / n;
      const int x = int(std::lround(x0 + t * (x1 - x0))), y = int(std::lround(y0 + t * (y1 - y0)));
      set(x, y, c);
      set(x, y + 1, c);
    }
  }
  // Text with its top-left corner at (x, y); `vertical` runs it bottom to top.
  void text(int x, int y, const std::string& s, Vec3<double> c, bool vertical = false) {
    int k = 0;
    for (char ch : s) {
      const char u = (ch >= 'a' && ch <= 'z') ? char(ch - 'a' + 'A') : ch;
      for (const Glyph& g : kGlyphs) {
        if (g.c != u) continue;
        for (int r = 0; r < 7; ++r)
          for (int col = 0; col < 5; ++col) {
            if (!((g.rows[std::size_t(r)] >> (4 - col)) & 1)) continue;
            if (vertical)
              set(x + r, y - 6 * k - col, c);
            else
              set(x + 6 * k + col, y + r, c);
          }
      }
      ++k;
    }
  }
  Image take() { return std::move(img_); }

 private:
  Image img_;
};

}  // namespace

Image draw_category_map(const CategoryMap& map, int cell_width, int cell_height) {
  const int cols = int(map.column_labels.size()), rows = int(map.row_labels.size());
  std::size_t row_label_chars = 0;
  for (const std::string& l : map.row_labels) row_label_chars = std::max(row_label_chars, l.size());
  const int left = 24 + 6 * int(row_label_chars), top = 28, legend_w = 170, bottom = 44;
  const int width = left + cols * cell_width + 16 + legend_w;
  const int height = top + std::max(rows * cell_height, 14 * int(map.category_names.size()) + 30) +
                     bottom;
  Canvas c(width, height);
  const Vec3<double> ink{0, 0, 0}, none{0.8, 0.8, 0.8};
  const int plot_bottom = top + rows * cell_height;
  for (int r = 0; r < rows; ++r) {
    const int y1 = plot_bottom - r * cell_height - 1, y0 = y1 - cell_height + 2;
    for (int k = 0; k < cols; ++k) {
      const int cat = map.cells[std::size_t(r)][std::size_t(k)];
      const Vec3<double> col =
          cat >= 0 && cat < int(map.category_colors.size()) ? map.category_colors[std::size_t(cat)]
                                                            : none;
      c.rect(left + k * cell_width + 1, y0, left + (k + 1) * cell_width - 1, y1, col);
    }
    c.text(left - 6 * int(map.row_labels[std::size_t(r)].size()) - 4, y0 + cell_height / 2 - 4,
           map.row_labels[std::size_t(r)], ink);
    if (std::size_t(r) < map.marker_column.size() && std::isfinite(map.marker_column[std::size_t(r)])) {
      const double x = left + (map.marker_column[std::size_t(r)] + 0.5) * cell_width;
      if (x >= left && x <= left + cols * cell_width) {
        c.rect(int(x) - 1, y0 - 1, int(x) + 1, y1 + 1, ink);
      }
    }
  }
  for (int k = 0; k < cols; ++k)
    c.text(left + k * cell_width + cell_width / 2 - 3 * int(map.column_labels[std::size_t(k)].size()),
           plot_bottom + 5, map.column_labels[std::size_t(k)], ink);
  c.line(left, top, left, plot_bottom, ink);
  c.line(left, plot_bottom, left + cols * cell_width, plot_bottom, ink);
  c.text(8, 8, map.title, ink);
  c.text(left + cols * cell_width / 2 - 3 * int(map.x_label.size()), plot_bottom + 22, map.x_label,
         ink);
  c.text(4, top + rows * cell_height / 2 + 3 * int(map.y_label.size()), map.y_label, ink, true);
  int ly = top + 4;
  const int lx = left + cols * cell_width + 16;
  for (std::size_t k = 0; k < map.category_names.size(); ++k) {
    c.rect(lx, ly, lx + 10, ly + 8, map.category_colors[k]);
    c.text(lx + 16, ly + 1, map.category_names[k], ink);
    ly += 14;
  }
  if (!map.marker_name.empty()) {
    c.rect(lx + 4, ly - 1, lx + 6, ly + 9, ink);
    c.text(lx + 16, ly + 1, map.marker_name, ink);
  }
  return c.take();
}

void draw_text(Image& image, int x, int y, const std::string& text, Vec3<double> color) {
  int k = 0;
  for (char ch : text) {
    const char u = (ch >= 'a' && ch <= 'z') ? char(ch - 'a' + 'A') : ch;
    for (const Glyph& g : kGlyphs) {
      if (g.c != u) continue;
      for (int r = 0; r < 7; ++r)
        for (int col = 0; col < 5; ++col) {
          const int px = x + 6 * k + col, py = y + r;
          if (!((g.rows[std::size_t(r)] >> (4 - col)) & 1) || px < 0 || py < 0 ||
              px >= image.width || py >= image.height)
            continue;
          image.at(px, py, 0) = color.x, image.at(px, py, 1) = color.y,
                           image.at(px, py, 2) = color.z;
        }
    }
    ++k;
  }
}

}  // namespace glintlab::experiments

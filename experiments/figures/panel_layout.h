// What the panels of a figure's montage PNG show, written beside NAME.png as NAME.panels.json,
// so that the report draws each panel enlarged under its own label (reports/charts.py,
// panel_chart) instead of showing an unlabelled strip of small renders.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace glintlab::experiments {

// Axes of panels that are maps of a quantity over two parameters (left empty for renders): a
// panel's left and right edges are at x_min and x_max, its bottom and top edges at y_min and
// y_max, and a pixel shows clamp(exposure · value) through the sRGB curve (io::write_png_preview).
struct PanelAxes {
  std::string x_label, y_label, value_label;  // each with its unit
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;
  double exposure = 1;
};

// A montage: panels of equal size in a grid, row by row from the top left, `gap` pixels apart.
struct PanelLayout {
  std::string title;  // what the whole image shows
  int columns = 1;
  int gap = 0;
  std::vector<std::string> labels;  // one per panel, in montage order
  PanelAxes axes;                   // for maps; unused when axes.x_label is empty
};

// Writes NAME.panels.json beside `png` = NAME.png (atomic). Throws std::runtime_error naming the
// file on failure.
void write_panel_layout(const std::filesystem::path& png, const PanelLayout& layout);

}  // namespace glintlab::experiments

// What the panels of a figure's montage PNG show, written beside NAME.png as NAME.panels.json,
// so that the report draws each panel enlarged under its own label (reports/charts.py,
// panel_chart) instead of showing an unlabelled strip of small renders.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace glintlab::experiments {

// A montage of renders (a map of numbers is a heat map drawn from its CSV, not a montage): panels
// of equal size in a grid, row by row from the top left, `gap` pixels apart.
struct PanelLayout {
  std::string title;  // what the whole image shows
  int columns = 1;
  int gap = 0;
  std::vector<std::string> labels;  // one per panel, in montage order
};

// Writes NAME.panels.json beside `png` = NAME.png (atomic). Throws std::runtime_error naming the
// file on failure.
void write_panel_layout(const std::filesystem::path& png, const PanelLayout& layout);

}  // namespace glintlab::experiments

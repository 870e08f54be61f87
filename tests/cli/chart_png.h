// What a chart PNG drawn by reports/figure_charts.py shows, read back from the PNG itself (its
// "glintlab:chart" text chunk: title, per axes its title, labels, legend), and the check that a
// figure's chart is labelled as the report's are (a title, axis labels with units, a legend).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

namespace glintlab::cli_test {

// The chunk's JSON; null when the file is not a PNG or has no such chunk.
nlohmann::json chart_manifest(const std::filesystem::path& png);

// Expects `png` to carry a manifest with a title and `axes` axes, each with a title, x and y
// labels with a unit in brackets, and a legend (for a map: its colour bar).
void expect_labelled_chart(const std::filesystem::path& png, std::size_t axes);

}  // namespace glintlab::cli_test

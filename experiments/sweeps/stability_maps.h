// Stability maps as files (claim all.stability): for one swept model × sampler, per plane one CSV
// of every measured number per cell (PLANE.csv) and, per quantity, an EXR (one float channel per
// component, one pixel per cell) and a heat map PLANE_QUANTITY.png: its chart spec
// (PLANE_QUANTITY.chart.json) over PLANE_maps.csv (per cell the number each map shows and whether
// the cell fails), drawn by reports/figure_charts.py (`glintlab sweep` runs it on each target's
// folder before the sweep's files are moved into place). No map is drawn in C++.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "verify/stability/sweep.h"

namespace glintlab::experiments {

struct MapFile {
  std::string quantity;       // nan, inf, negative, energy_gain, p_gt_1, variance
  std::string axis;           // the plane: alpha, anisotropy, density, ...
  std::string png, exr, csv;  // paths relative to the output folder
};

// The quantities written for a sweep (p_gt_1 only where the model has a probability
// intermediate).
std::vector<std::string> map_quantities(const verify::stability::ModelSweep& s);

// Writes every map of `s` under `root / rel` (created): the CSVs, EXRs and chart specs; returns the
// files, paths relative to root (the PNGs to be drawn from the specs).
std::vector<MapFile> write_stability_maps(const verify::stability::ModelSweep& s,
                                          const std::filesystem::path& root,
                                          const std::filesystem::path& rel);

}  // namespace glintlab::experiments

// Stability maps as files (claim all.stability): for one swept model × sampler, per plane one CSV
// of every measured number per cell and, per quantity, an EXR (one float channel per component,
// one pixel per cell) and a PNG preview (cells as blocks; clean cells dark, flagged cells yellow
// to red with the size of the defect).
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

// Writes every map of `s` under `root / rel` (created); returns the files, paths relative to root.
std::vector<MapFile> write_stability_maps(const verify::stability::ModelSweep& s,
                                          const std::filesystem::path& root,
                                          const std::filesystem::path& rel);

}  // namespace glintlab::experiments

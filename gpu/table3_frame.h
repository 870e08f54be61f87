// The Table 3 analogue of Kemppinen et al. 2025 on the device: every cell of
// experiments/bench/kemppinen2025_table3_scene.h (NDF × plane angle × roughness, the glint model
// and the smooth NDF for scale) rendered as a whole 1920×1080 frame with 3 point lights, one
// thread per pixel running the same shade_pixel as the CPU benchmark, in double.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "gpu/device_timing.h"

namespace glintlab::gpu {

struct Table3FrameRun {
  std::string cell;                   // kemppinen_table3::cell_name
  DeviceTiming timing;                // one launch renders the whole frame
  std::vector<std::uint64_t> pixels;  // the pixels written out: kemppinen_table3::pixel_of(n)
  std::vector<double> radiance;       // their radiance
};

// Every cell, each timed over `repetitions` frames after one untimed frame; the radiance of the
// first `sampled_pixels` pixels of pixel_of's order kept for the comparison with the CPU.
// Throws DeviceError (gpu/device_models.h) for a CUDA failure.
std::vector<Table3FrameRun> run_table3_frames(int repetitions, std::size_t sampled_pixels);

}  // namespace glintlab::gpu

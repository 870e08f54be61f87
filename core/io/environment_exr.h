// Reads a lat-long environment map from an OpenEXR file into the image EnvironmentMap
// (core/lights/environment_map.h) is built from: R, G, B as radiance, row 0 at the zenith.
#pragma once

#include <filesystem>

#include "core/io/exr.h"
#include "core/lights/environment_map.h"

namespace glintlab::io {

// The file must hold channels R, G and B, be a lat-long map (width = 2 × height, at least 2 × 1)
// and have finite, non-negative values; anything else throws ExrError with one line naming the
// file, the offending property and its valid range.
LatLongImage read_latlong_exr(const std::filesystem::path& path);

// read_latlong_exr, then EnvironmentMap's own validation; every failure is an ExrError.
EnvironmentMap load_environment_map(const std::filesystem::path& path);

}  // namespace glintlab::io

// Lat-long environment maps from EXR; see environment_exr.h.
#include "core/io/environment_exr.h"

#include <fmt/format.h>

#include <cmath>

namespace glintlab::io {

LatLongImage read_latlong_exr(const std::filesystem::path& path) {
  const ExrFile f = read_exr(path);
  const Image& im = f.image;
  const std::string name = path.string();
  std::size_t c[3];
  const char* rgb[3] = {"R", "G", "B"};
  for (int k = 0; k < 3; ++k) {
    bool found = false;
    for (std::size_t i = 0; i < im.channels.size(); ++i)
      if (im.channels[i] == rgb[k]) {
        c[k] = i;
        found = true;
      }
    if (!found)
      throw ExrError(fmt::format("environment map {}: no channel {} (valid: an RGB image with channels R, G, B)",
                                 name, rgb[k]));
  }
  if (im.height < 1 || im.width != 2 * im.height)
    throw ExrError(fmt::format(
        "environment map {}: {}x{} pixels is not a lat-long map (valid: width = 2 x height)", name,
        im.width, im.height));
  LatLongImage out{im.width, im.height, std::vector<float>(3 * std::size_t(im.width) * im.height)};
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x)
      for (int k = 0; k < 3; ++k) {
        const double v = im.at(x, y, c[k]);
        if (!(std::isfinite(v) && v >= 0))
          throw ExrError(fmt::format(
              "environment map {}: pixel ({}, {}) channel {} = {} is out of range (valid: finite, >= 0)",
              name, x, y, rgb[k], v));
        out.rgb[3 * (std::size_t(y) * im.width + x) + k] = static_cast<float>(v);
      }
  return out;
}

EnvironmentMap load_environment_map(const std::filesystem::path& path) {
  try {
    return EnvironmentMap(read_latlong_exr(path));
  } catch (const ParameterError& e) {
    throw ExrError(fmt::format("{}: {}", path.string(), e.what()));
  }
}

}  // namespace glintlab::io

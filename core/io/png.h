// Tonemapped 8-bit sRGB PNG preview of an image's R, G, B channels (libpng; atomic write).
#pragma once

#include <filesystem>

#include "core/render/image.h"

namespace glintlab::io {

// Tonemap: v = exposure · x, clamped to [0, 1], then the sRGB transfer function (IEC 61966-2-1)
// and rounding to 8 bits. Throws std::runtime_error naming the file on failure.
void write_png_preview(const std::filesystem::path& path, const Image& image,
                       double exposure = 1.0);

}  // namespace glintlab::io

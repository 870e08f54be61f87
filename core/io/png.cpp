// PNG preview; see png.h.
#include "core/io/png.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <stdexcept>
#include <vector>

#include "core/io/atomic_file.h"

namespace glintlab::io {
namespace {

void write_to_stream(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::ofstream*>(png_get_io_ptr(png));
  out->write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
}
void flush_stream(png_structp png) { static_cast<std::ofstream*>(png_get_io_ptr(png))->flush(); }

std::uint8_t srgb8(double x) {
  const double c = std::clamp(x, 0.0, 1.0);
  const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(s * 255.0));
}

// libpng reports errors by longjmp; this writes the rows, returns false on failure.
bool encode(png_structp png, png_infop info, std::ofstream& out, int w, int h,
            std::vector<png_bytep>& rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, &out, write_to_stream, flush_stream);
  png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  return true;
}

}  // namespace

void write_png_preview(const std::filesystem::path& path, const Image& image, double exposure) {
  const std::size_t r = image.channel("R"), g = image.channel("G"), b = image.channel("B");
  const int w = image.width, h = image.height;
  std::vector<png_byte> pixels(static_cast<std::size_t>(w) * h * 3);
  std::vector<png_bytep> rows(static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y) {
    rows[y] = pixels.data() + static_cast<std::size_t>(y) * w * 3;
    for (int x = 0; x < w; ++x) {
      rows[y][3 * x + 0] = srgb8(exposure * image.at(x, y, r));
      rows[y][3 * x + 1] = srgb8(exposure * image.at(x, y, g));
      rows[y][3 * x + 2] = srgb8(exposure * image.at(x, y, b));
    }
  }
  AtomicFile file(path);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  const bool ok = info && encode(png, info, file.stream(), w, h, rows);
  png_destroy_write_struct(&png, &info);
  if (!ok) throw std::runtime_error("cannot write PNG '" + path.string() + "'");
  file.commit();
}

}  // namespace glintlab::io

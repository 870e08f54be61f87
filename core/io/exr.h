// OpenEXR images: write (float channels, string header attributes; atomic) and read (every
// channel as float, every string attribute), with one-line errors naming the file.
#pragma once

#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/render/image.h"

namespace glintlab::io {

// A missing, unreadable or malformed EXR file, or a failed write; one line naming the file.
struct ExrError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using ExrAttributes = std::vector<std::pair<std::string, std::string>>;

// Writes every channel of `image` as 32-bit float (ZIP compression, scanlines) with the string
// attributes `attributes` in the header; to `<path>.tmp.<pid>`, then renamed into place.
void write_exr(const std::filesystem::path& path, const Image& image,
               const ExrAttributes& attributes);

struct ExrFile {
  Image image;                                    // channels in the file's (alphabetical) order
  std::map<std::string, std::string> attributes;  // the string attributes of the header
};

// Reads an EXR file (its data window, every channel converted to float); throws ExrError.
ExrFile read_exr(const std::filesystem::path& path);

}  // namespace glintlab::io

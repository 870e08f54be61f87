// OpenEXR read/write; see exr.h.
#include "core/io/exr.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <ImfStringAttribute.h>

#include <exception>
#include <system_error>

#include "core/io/atomic_file.h"

namespace glintlab::io {
namespace {

std::string one_line(std::string s) {
  for (char& c : s) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return s;
}

}  // namespace

void write_exr(const std::filesystem::path& path, const Image& image,
               const ExrAttributes& attributes) {
  if (image.width <= 0 || image.height <= 0 || image.channels.empty()) {
    throw ExrError("cannot write EXR '" + path.string() + "': empty image");
  }
  const std::size_t nc = image.num_channels();
  const std::size_t n = static_cast<std::size_t>(image.width) * image.height;
  // Planar float copies: EXR stores float, the image keeps double.
  std::vector<std::vector<float>> planes(nc, std::vector<float>(n));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < nc; ++c) planes[c][i] = static_cast<float>(image.data[i * nc + c]);
  }
  try {
    AtomicFile file(path);
    {
      Imf::Header header(image.width, image.height);
      header.compression() = Imf::ZIP_COMPRESSION;
      for (const auto& [key, value] : attributes) {
        header.insert(key, Imf::StringAttribute(value));
      }
      Imf::FrameBuffer fb;
      for (std::size_t c = 0; c < nc; ++c) {
        header.channels().insert(image.channels[c], Imf::Channel(Imf::FLOAT));
        fb.insert(image.channels[c],
                  Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(planes[c].data()), sizeof(float),
                             sizeof(float) * static_cast<std::size_t>(image.width)));
      }
      Imf::StdOFStream stream(file.stream(), path.string().c_str());
      Imf::OutputFile out(stream, header, 1);
      out.setFrameBuffer(fb);
      out.writePixels(image.height);
    }
    file.commit();
  } catch (const ExrError&) {
    throw;
  } catch (const std::exception& e) {
    throw ExrError("cannot write EXR '" + path.string() + "': " + one_line(e.what()));
  }
}

ExrFile read_exr(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw ExrError("cannot read EXR '" + path.string() + "': no such file");
  }
  try {
    Imf::InputFile in(path.string().c_str(), 1);
    const Imf::Header& header = in.header();
    const Imath::Box2i dw = header.dataWindow();
    const int w = dw.max.x - dw.min.x + 1;
    const int h = dw.max.y - dw.min.y + 1;
    ExrFile out;
    std::vector<std::string> names;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
      names.emplace_back(it.name());
    }
    if (names.empty()) throw ExrError("cannot read EXR '" + path.string() + "': no channels");
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    std::vector<std::vector<float>> planes(names.size(), std::vector<float>(n));
    Imf::FrameBuffer fb;
    for (std::size_t c = 0; c < names.size(); ++c) {
      // Slice base for a data window not at the origin, as the OpenEXR API expects.
      char* base =
          reinterpret_cast<char*>(planes[c].data()) -
          (static_cast<std::ptrdiff_t>(dw.min.x) + static_cast<std::ptrdiff_t>(dw.min.y) * w) *
              static_cast<std::ptrdiff_t>(sizeof(float));
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                     sizeof(float) * static_cast<std::size_t>(w)));
    }
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    out.image = Image(w, h, names);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t c = 0; c < names.size(); ++c) {
        out.image.data[i * names.size() + c] = planes[c][i];
      }
    }
    for (auto it = header.begin(); it != header.end(); ++it) {
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) {
        out.attributes[it.name()] = s->value();
      }
    }
    return out;
  } catch (const ExrError&) {
    throw;
  } catch (const std::exception& e) {
    throw ExrError("cannot read EXR '" + path.string() + "': " + one_line(e.what()));
  }
}

}  // namespace glintlab::io

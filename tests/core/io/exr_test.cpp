// EXR write/read round trip with attributes, and one-line errors for missing, malformed and
// unwritable files with no partial output left behind.
#include "core/io/exr.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/io/png.h"

namespace glintlab::io {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("glintlab_io_" + name + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

Image test_image() {
  Image img(5, 3, {"R", "G", "B", "extra"});
  for (std::size_t i = 0; i < img.data.size(); ++i) img.data[i] = 0.25 * static_cast<double>(i) - 3;
  return img;
}

TEST(Exr, RoundTripsChannelsAndAttributes) {
  const fs::path d = temp_dir("exr");
  const Image img = test_image();
  write_exr(d / "a.exr", img, {{"glintlab_model", "smooth_ggx"}, {"glintlab_spp", "16"}});
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
  const ExrFile f = read_exr(d / "a.exr");
  EXPECT_EQ(f.image.width, 5);
  EXPECT_EQ(f.image.height, 3);
  EXPECT_EQ(f.attributes.at("glintlab_model"), "smooth_ggx");
  EXPECT_EQ(f.attributes.at("glintlab_spp"), "16");
  for (const std::string c : {"R", "G", "B", "extra"}) {
    const std::size_t a = img.channel(c), b = f.image.channel(c);
    for (int y = 0; y < 3; ++y) {
      for (int x = 0; x < 5; ++x)
        EXPECT_EQ(f.image.at(x, y, b), static_cast<float>(img.at(x, y, a)));
    }
  }
  fs::remove_all(d);
}

std::string read_error(const fs::path& p) {
  try {
    read_exr(p);
  } catch (const ExrError& e) {
    return e.what();
  }
  return "";
}

TEST(Exr, MissingAndMalformedFilesGiveOneLineErrors) {
  const fs::path d = temp_dir("exr_bad");
  const std::string missing = read_error(d / "none.exr");
  EXPECT_NE(missing.find("none.exr"), std::string::npos);
  EXPECT_NE(missing.find("no such file"), std::string::npos);
  { std::ofstream(d / "junk.exr") << "this is not an EXR file at all\n"; }
  const std::string junk = read_error(d / "junk.exr");
  EXPECT_NE(junk.find("junk.exr"), std::string::npos);
  EXPECT_EQ(junk.find('\n'), std::string::npos);
  // A truncated real file.
  write_exr(d / "ok.exr", test_image(), {});
  const auto size = fs::file_size(d / "ok.exr");
  fs::resize_file(d / "ok.exr", size / 2);
  EXPECT_NE(read_error(d / "ok.exr"), "");
  fs::remove_all(d);
}

TEST(Exr, UnwritableTargetLeavesNothing) {
  const fs::path d = temp_dir("exr_unwritable");
  EXPECT_THROW(write_exr(d / "no_such_dir" / "a.exr", test_image(), {}), ExrError);
  EXPECT_THROW(write_exr(d / "empty.exr", Image(), {}), ExrError);
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 0);
  fs::remove_all(d);
}

TEST(Png, WritesAnRgbPngOfTheImageSize) {
  const fs::path d = temp_dir("png");
  write_png_preview(d / "a.png", test_image());
  std::ifstream in(d / "a.png", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 33u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  const auto be32 = [&](std::size_t o) {
    return (static_cast<unsigned char>(bytes[o]) << 24) |
           (static_cast<unsigned char>(bytes[o + 1]) << 16) |
           (static_cast<unsigned char>(bytes[o + 2]) << 8) |
           static_cast<unsigned char>(bytes[o + 3]);
  };
  EXPECT_EQ(be32(16), 5u);
  EXPECT_EQ(be32(20), 3u);
  EXPECT_EQ(bytes[25], 2);  // colour type RGB
  Image no_rgb(2, 2, {"Y"});
  EXPECT_THROW(write_png_preview(d / "b.png", no_rgb), std::out_of_range);
  EXPECT_FALSE(fs::exists(d / "b.png"));
  fs::remove_all(d);
}

}  // namespace
}  // namespace glintlab::io

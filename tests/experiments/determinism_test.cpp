// A tiny orb rendered with 1 and 2 threads gives identical EXR bytes; a different seed (control)
// gives different bytes, so the comparison can fail.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/io/exr.h"
#include "core/lights/procedural_sky.h"
#include "core/models/smooth_ggx.h"
#include "experiments/figures/orb_render.h"

namespace glintlab::experiments {
namespace {

namespace fs = std::filesystem;

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string render_bytes(int threads, std::uint64_t seed, const fs::path& dir) {
  const OrbScene scene = make_orb_scene(16, 12);
  const EnvironmentMap sky(make_procedural_sky(SkyParameters{}, 64, 32));
  const SmoothGGX::Params<double> p{GGX<double>{0.8, 0.8},
                                    SmoothGGX::Choices::find("bounded_caps", "listing1")};
  const Image img = render_orb<SmoothGGX>(scene, p, sky, 4, seed, threads);
  const fs::path path = dir / ("t" + std::to_string(threads) + "_" + std::to_string(seed) + ".exr");
  io::write_exr(path, img, {{"glintlab_seed", std::to_string(seed)}});
  return bytes_of(path);
}

TEST(Determinism, OneAndTwoThreadsGiveIdenticalBytes) {
  const fs::path dir = fs::temp_directory_path() / ("glintlab_det_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string one = render_bytes(1, 11, dir);
  const std::string two = render_bytes(2, 11, dir);
  ASSERT_GT(one.size(), 100u);
  EXPECT_TRUE(one == two) << "1-thread and 2-thread renders differ";
  EXPECT_FALSE(one == render_bytes(2, 12, dir)) << "control: another seed must change the bytes";
  fs::remove_all(dir);
}

TEST(OrbRender, UniformSkyGivesTheAlbedoAndBackground) {
  // Under a uniform white sky the orb's pixels estimate the directional albedo (<= 1) and the
  // background pixels are exactly 1; the rejected fraction is in [0, 1].
  struct White {
    Vec3<double> radiance(Vec3<double>, Vec3<double>) const { return {1, 1, 1}; }
  };
  const OrbScene scene = make_orb_scene(24, 24);
  const SmoothGGX::Params<double> p{GGX<double>{0.3, 0.3}, SmoothGGX::Choices::find("vndf")};
  const Image img = render_orb<SmoothGGX>(scene, p, White{}, 16, 5, 2);
  EXPECT_EQ(img.at(0, 0, 0), 1.0);
  EXPECT_EQ(img.at(0, 0, 3), 0.0);  // coverage
  const double centre = img.at(12, 12, 0);
  EXPECT_EQ(img.at(12, 12, 3), 1.0);
  EXPECT_GT(centre, 0.8);
  EXPECT_LE(centre, 1.0 + 1e-12);
}

}  // namespace
}  // namespace glintlab::experiments

// Tests of the lat-long environment light and the procedural sky: parameter errors, the pdf's
// normalisation (exact sum and cubature), the sampler's chi-square fit with the pixel edges as
// cubature breakpoints, and a negative control that forgets the sin θ (pixel solid angle) factor.
#include "core/lights/environment_map.h"

#include <gtest/gtest.h>

#include <iostream>

#include "core/lights/procedural_sky.h"
#include "light_checks.h"

namespace glintlab {
namespace {

using namespace light_checks;

SkyParameters test_sky() {
  SkyParameters s;
  s.sun_direction = {0.4, -0.3, 0.8};
  s.sun_half_angle = 12 * kPiD / 180;  // large enough to shape a 16 × 8 map
  s.sun_radiance = {30, 28, 25};
  return s;
}

TEST(EnvironmentMap, ParameterErrors) {
  const auto msg = [](LatLongImage img) -> std::string {
    try {
      EnvironmentMap m(std::move(img));
    } catch (const ParameterError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(msg({0, 4, {}}).find("width"), std::string::npos);
  EXPECT_NE(msg({4, 0, {}}).find("height"), std::string::npos);
  EXPECT_NE(msg({2, 1, {1, 1, 1}}).find("pixel values"), std::string::npos);
  EXPECT_NE(msg({1, 1, {1, -1, 1}}).find("channel 1 = -1"), std::string::npos);
  EXPECT_THROW(make_procedural_sky(SkyParameters{}, 0, 8), ParameterError);
  SkyParameters bad;
  bad.sun_half_angle = 0;
  EXPECT_THROW(make_procedural_sky(bad, 16, 8), ParameterError);
  bad = SkyParameters{};
  bad.zenith = {-1, 0, 0};
  EXPECT_THROW(make_procedural_sky(bad, 16, 8), ParameterError);
}

TEST(EnvironmentMap, SkyImageKeepsTheAnalyticEnergy) {
  // Σ pixel Ω_pixel against the closed form ∫ L dω, with a sun-sized disc much smaller than a
  // pixel.
  const SkyParameters s;  // the default sun: 0.2667°
  const LatLongImage img = make_procedural_sky(s, 64, 32);
  Vec3<double> sum{0, 0, 0};
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 64; ++i) {
      const double om = 2 * kPiD / 64 * (std::cos(kPiD * j / 32) - std::cos(kPiD * (j + 1) / 32));
      const float* px = &img.rgb[3 * (j * 64 + i)];
      sum = sum + om * Vec3<double>{px[0], px[1], px[2]};
    }
  const Vec3<double> exact = sky_integral(s);
  std::cout << "sky energy ratio: " << sum.x / exact.x << " " << sum.y / exact.y << " "
            << sum.z / exact.z << "\n";
  EXPECT_NEAR(sum.x / exact.x, 1.0, 1e-6);
  EXPECT_NEAR(sum.z / exact.z, 1.0, 1e-6);
}

TEST(EnvironmentMap, PdfIsNormalisedAndMatchesSamples) {
  const EnvironmentMap env(make_procedural_sky(test_sky(), 16, 8));
  // Exact: Σ pdf_ij Ω_ij = 1.
  double total = 0;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 16; ++i) {
      const double th = kPiD * (j + 0.5) / 8, ph = 2 * kPiD * (i + 0.5) / 16;
      const V3 w{std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)};
      total += env.pdf(V3{0, 0, 0}, w) * 2 * kPiD / 16 *
               (std::cos(kPiD * j / 8) - std::cos(kPiD * (j + 1) / 8));
    }
  EXPECT_NEAR(total, 1.0, 1e-12);
  verify::SphereCubatureOptions o;
  for (int j = 1; j < 8; ++j) o.theta_breaks.push_back(kPiD * j / 8);
  for (int i = 1; i < 16; ++i) o.phi_breaks.push_back(2 * kPiD * i / 16);
  const auto integral = verify::integrate_sphere([&](const V3& w) { return env.pdf(V3{}, w); }, o);
  EXPECT_NEAR(integral.value, 1.0, 1e-8);
  const std::uint64_t seed = verify::check_seed("lights.environment.records", 0);
  for (std::uint64_t i = 0; i < 5000; ++i) {
    const auto s = env.sample(V3{}, u2(seed, i));
    ASSERT_TRUE(s.valid);
    EXPECT_NEAR(length(s.wi), 1.0, 1e-12);
    EXPECT_NEAR(s.pdf / env.pdf(V3{}, s.wi), 1.0, 1e-12) << i;
    EXPECT_EQ(s.radiance.x, env.radiance(V3{}, s.wi).x);
  }
  // A black map is uniform over the sphere and radiates nothing.
  const EnvironmentMap black(LatLongImage{4, 2, std::vector<float>(24, 0.0f)});
  EXPECT_NEAR(black.pdf(V3{}, V3{0, 0, 1}), 1 / (4 * kPiD), 1e-15);
  EXPECT_EQ(black.sample(V3{}, V2{0.3, 0.7}).radiance.y, 0.0);
}

TEST(EnvironmentMap, ChiSquareFitAndNegativeControl) {
  const LatLongImage img = make_procedural_sky(test_sky(), 16, 8);
  const EnvironmentMap env(img);
  verify::ChiSquareOptions o;
  o.layout = verify::BinLayout::kEqualArea;
  for (int j = 1; j < 8; ++j) o.radial_breaks.push_back(kPiD * j / 8);
  for (int i = 1; i < 16; ++i) o.phi_breaks.push_back(2 * kPiD * i / 16);
  o.fine_max_bins = 512;
  const std::uint64_t n = 100'000;
  const auto sampler = [&](std::uint64_t i) {
    const auto s = env.sample(V3{}, u2(verify::check_seed("lights.environment.chi_square", 0), i));
    return s.valid ? s.wi : V3{0, 0, 0};
  };
  const auto r = verify::chi_square_sphere(
      sampler, n, [&](const V3& w) { return env.pdf(V3{}, w); }, o);
  std::cout << "environment: " << r.summary() << "\n";
  EXPECT_FALSE(r.rejects(level())) << r.summary();
  EXPECT_FALSE(r.inconclusive) << r.reason;
  // Control: the density a sampler would have without the pixel solid-angle (sin θ) weight,
  // pdf ∝ Y_ij / Ω_ij (normalised); the real sampler must be rejected against it.
  std::vector<double> wrong(16 * 8);
  double norm = 0;
  for (int k = 0; k < 16 * 8; ++k) {
    wrong[k] = EnvironmentMap::luminance(img.rgb[3 * k], img.rgb[3 * k + 1], img.rgb[3 * k + 2]);
    norm += wrong[k];
  }
  const auto wrong_pdf = [&](const V3& w) {
    int i, j;
    env.pixel_of(w, &i, &j);
    const double om = 2 * kPiD / 16 * (std::cos(kPiD * j / 8) - std::cos(kPiD * (j + 1) / 8));
    return wrong[j * 16 + i] / norm / om;
  };
  const auto c = verify::chi_square_sphere(
      [&](std::uint64_t i) {
        const auto s = env.sample(V3{}, u2(verify::check_seed("lights.environment.control", 0), i));
        return s.valid ? s.wi : V3{0, 0, 0};
      },
      n, wrong_pdf, o);
  std::cout << "environment control: " << c.summary() << "\n";
  EXPECT_TRUE(c.rejects(level())) << c.summary();
}

}  // namespace
}  // namespace glintlab

// FootprintSdf (verify/scenes/chermain_footprint_sdf.h) against chermain2021::patch_sdf without
// GGAA: bit for bit, over footprints from LOD −20 to past the last dictionary level (the smooth
// fallback, LOD blending), with and without ρ, both wraps, at slopes across the lobes; and the
// comparison is not vacuous (most values are non-zero, another cell seed changes them).
// glint_values on every ISA this CPU has against glint_value_of one sample at a time, bit for bit,
// with one footprint for every sample and with a footprint per sample.
#include "verify/scenes/chermain_footprint_sdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/glints/chermain.h"
#include "core/math/rng.h"

namespace glintlab::verify {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(FootprintSdf, EqualsPatchSdfBitForBit) {
  const chermain2021::SlopeDerivatives zero{0, 0, 0, 0};
  const chermain2021::Dictionary& dict = chermain2021::default_chermain_dictionary();
  int compared = 0, non_zero = 0, seed_changes = 0;
  for (std::uint64_t c = 0; c < 400; ++c) {
    const auto u = [&](std::uint64_t d) { return counter_uniform<double>(7, c, d); };
    const double sx = 0.03 + 0.4 * u(0), sy = 0.03 + 0.4 * u(1);
    chermain2021::SdfParams p{&dict, sx, sy, 1.8 * u(2) - 0.9, 4 + 26 * u(3), chermain2021::kNoGgaa,
                              0.5,   5};
    p.with_rho = c % 5 != 0;
    p.wrap = c % 7 == 0 ? chermain2021::TableWrap::kClampToEdge
                        : chermain2021::TableWrap::kMirroredRepeat;
    FootprintQuery<double> fp{};
    fp.uv = {4 * u(4) - 2, 4 * u(5) - 2};
    const double size = std::exp2(-20 + 34 * u(6));  // LOD −20 to 14, past the last level
    fp.duv_dx = {size * (u(7) - 0.5), size * u(8)};
    fp.duv_dy = {size * u(9), size * (0.5 - u(10))};
    const FootprintSdf sdf(p, fp);
    chermain2021::SdfParams other = p;
    other.seed = 6;
    const FootprintSdf other_sdf(other, fp);
    for (std::uint64_t k = 0; k < 64; ++k) {
      const double r = 3 * std::max(sx, sy) * counter_uniform<double>(8, c * 64 + k, 0);
      const double a = 2 * kPi<double> * counter_uniform<double>(8, c * 64 + k, 1);
      const Vec2<double> m{r * std::cos(a), r * std::sin(a)};
      const double expected = chermain2021::patch_sdf(p, m, fp, zero);
      ASSERT_TRUE(same_bits(sdf(m), expected))
          << "configuration " << c << " slope " << k << ": " << sdf(m) << " vs " << expected;
      ++compared;
      non_zero += expected != 0;
      seed_changes += !same_bits(other_sdf(m), expected);
    }
  }
  EXPECT_EQ(compared, 400 * 64);
  EXPECT_GT(non_zero, compared / 2);
  EXPECT_GT(seed_changes, compared / 4);
}

TEST(FootprintSdf, GlintValuesOnEveryIsaEqualTheScalarValue) {
  const chermain2021::Dictionary& dict = chermain2021::default_chermain_dictionary();
  int compared = 0, non_zero = 0, lane_isas = 0;
  for (std::uint64_t c = 0; c < 60; ++c) {
    const auto u = [&](std::uint64_t d) { return counter_uniform<double>(9, c, d); };
    chermain2021::SdfParams p{&dict,
                              0.02 + 0.3 * u(0),
                              0.02 + 0.3 * u(1),
                              1.6 * u(2) - 0.8,
                              std::log2(1e9),
                              chermain2021::kNoGgaa,
                              0.5,
                              5};
    p.wrap = c % 7 == 0 ? chermain2021::TableWrap::kClampToEdge
                        : chermain2021::TableWrap::kMirroredRepeat;
    FootprintQuery<double> fp{};
    fp.uv = {u(3), u(4)};
    const double size = std::exp2(-18 + 20 * u(5));  // the smooth limit at the largest
    fp.duv_dx = {size, 0.3 * size * u(6)};
    fp.duv_dy = {-0.2 * size * u(7), size};
    const FootprintSdf sdf(p, fp);
    // 37 samples (a partial last batch on every width), some facing away or below the horizon.
    GlintSamples samples;
    for (std::uint64_t k = 0; k < 37; ++k) {
      const auto v = [&](std::uint64_t d) { return counter_uniform<double>(10, c * 64 + k, d); };
      const Vec3<double> wi = normalize(Vec3<double>{v(0) - 0.5, v(1) - 0.5, v(2) - 0.1});
      const Vec3<double> wl = normalize(Vec3<double>{v(3) - 0.5, v(4) - 0.5, v(5) - 0.1});
      samples.push(wi, wl, {0.3 * (v(6) - 0.5), 0.3 * (v(7) - 0.5)});
    }
    std::vector<double> expected(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
      expected[i] = glint_value_of(sdf, {samples.wi_x[i], samples.wi_y[i], samples.wi_z[i]},
                                   {samples.wl_x[i], samples.wl_y[i], samples.wl_z[i]},
                                   {samples.shift_x[i], samples.shift_y[i]});
      non_zero += expected[i] != 0;
    }
    for (const simd::Isa isa : simd::kAllIsas) {
      if (!simd::isa_supported(isa)) continue;
      lane_isas += c == 0 && (isa == simd::Isa::kAvx2 || isa == simd::Isa::kAvx512);
      std::vector<double> got(samples.size());
      glint_values(sdf, samples, got, isa);
      for (std::size_t i = 0; i < got.size(); ++i, ++compared)
        ASSERT_TRUE(same_bits(got[i], expected[i]))
            << simd::isa_name(isa) << " configuration " << c << " sample " << i << ": " << got[i]
            << " vs " << expected[i];
    }
  }
  EXPECT_GT(non_zero, 60 * 37 / 4);
  EXPECT_GT(compared, 0);
  if (lane_isas == 0) GTEST_SKIP() << "this CPU has neither AVX2 nor AVX-512: scalar only";
}

TEST(FootprintSdf, GlintValuesWithAFootprintPerSampleEqualTheScalarValue) {
  const chermain2021::Dictionary& dict = chermain2021::default_chermain_dictionary();
  int compared = 0, non_zero = 0, smooth = 0;
  for (std::uint64_t c = 0; c < 40; ++c) {
    const auto u = [&](std::uint64_t d) { return counter_uniform<double>(11, c, d); };
    const chermain2021::SdfParams p{&dict,
                                    0.02 + 0.3 * u(0),
                                    0.02 + 0.3 * u(1),
                                    1.6 * u(2) - 0.8,
                                    std::log2(1.6e5),
                                    chermain2021::kNoGgaa,
                                    0.5,
                                    5};
    // Sub-pixel footprints at their own uv, and every 5th sample a footprint past the last level.
    SampleFootprints footprints(p);
    GlintSamples samples;
    std::vector<FootprintQuery<double>> fps;
    for (std::uint64_t k = 0; k < 45; ++k) {
      const auto v = [&](std::uint64_t d) { return counter_uniform<double>(12, c * 64 + k, d); };
      FootprintQuery<double> fp{};
      fp.uv = {v(0), v(1)};
      const double size = k % 5 == 4 ? 4096.0 : std::exp2(-14 + 8 * u(3));
      fp.duv_dx = {size, 0.3 * size * v(2)};
      fp.duv_dy = {-0.2 * size * v(3), size};
      fps.push_back(fp);
      footprints.push(fp);
      smooth += footprints.smooth(k);
      samples.push(normalize(Vec3<double>{v(4) - 0.5, v(5) - 0.5, v(6) - 0.1}),
                   normalize(Vec3<double>{v(7) - 0.5, v(8) - 0.5, v(9) - 0.1}), {0, 0});
    }
    std::vector<double> expected(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const chermain2021::SlopeDerivatives zero{0, 0, 0, 0};
      expected[i] = glint_value_of(
          [&](Vec2<double> m) { return chermain2021::patch_sdf(p, m, fps[i], zero); },
          {samples.wi_x[i], samples.wi_y[i], samples.wi_z[i]},
          {samples.wl_x[i], samples.wl_y[i], samples.wl_z[i]}, {0, 0});
      non_zero += expected[i] != 0;
    }
    for (const simd::Isa isa : simd::kAllIsas) {
      if (!simd::isa_supported(isa)) continue;
      std::vector<double> got(samples.size());
      glint_values(footprints, samples, got, isa);
      for (std::size_t i = 0; i < got.size(); ++i, ++compared)
        ASSERT_TRUE(same_bits(got[i], expected[i]))
            << simd::isa_name(isa) << " configuration " << c << " sample " << i << ": " << got[i]
            << " vs " << expected[i];
    }
  }
  EXPECT_GT(non_zero, 40 * 45 / 8);
  EXPECT_GT(smooth, 0);
  EXPECT_GT(compared, 0);
}

TEST(FootprintSdf, RefusesGgaaKernels) {
  // Refused before the dictionary is read.
  const chermain2021::SdfParams p{nullptr, 0.1, 0.1, 0, 20, chermain2021::kProjectedHalf, 0.5, 5};
  EXPECT_THROW(FootprintSdf(p, FootprintQuery<double>{}), std::invalid_argument);
}

}  // namespace
}  // namespace glintlab::verify

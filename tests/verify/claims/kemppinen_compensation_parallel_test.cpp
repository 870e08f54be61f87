// kemppinen.compensation and .compensation-k16 measure Eq. 11 against the brute-force Eq. 5
// (core/glints/kemppinen_reference.h) position by position in parallel (verify/claims/kemppinen/
// common.h sample_comp). The brute force's loop hoists the cell hash and skips the points of
// roulette weight 0: its sums are those of the point-by-point sum below (the loop before that
// change) bit for bit, and sample_comp's results do not depend on the thread count.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/glints/kemppinen_reference.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "verify/claims/kemppinen/common.h"
#include "verify/scenes/kemppinen_presets.h"

namespace glintlab::verify::kemppinen_claims {
namespace {

using kemppinen2025::Angular;
using kemppinen2025::ReferenceParts;
using kemppinen2025::Sym2;

// reference_level_parts as it was: every point of the box, cell_index and both Gaussians for
// each, the colour drawn even when white.
ReferenceParts<double> point_by_point_parts(const P& p, const Angular<double>& ang, V2 x_s,
                                            const Sym2<double>& sigma_s, double res, int level,
                                            double w_l, int side, double sigmas,
                                            bool whole_square) {
  using namespace kemppinen2025;
  const double res_a = angular_resolution<double>(level);
  const double res_s = res / res_a;
  const std::int64_t n_a = std::int64_t(1) << level;
  const double r = sigmas;
  const double sx = std::sqrt(sigma_s.xx) * r, sy = std::sqrt(sigma_s.yy) * r;
  const std::int64_t bx0 = block_start(x_s.x * res_s, side);
  const std::int64_t by0 = block_start(x_s.y * res_s, side);
  const std::int64_t kx0 = block_start(ang.x_a.x * res_a, side);
  const std::int64_t ky0 = block_start(ang.x_a.y * res_a, side);
  const std::int64_t sx0 = std::min(std::int64_t(std::floor((x_s.x - sx) * res_s)), bx0);
  const std::int64_t sx1 = std::max(std::int64_t(std::floor((x_s.x + sx) * res_s)), bx0 + side - 1);
  const std::int64_t sy0 = std::min(std::int64_t(std::floor((x_s.y - sy) * res_s)), by0);
  const std::int64_t sy1 = std::max(std::int64_t(std::floor((x_s.y + sy) * res_s)), by0 + side - 1);
  auto clip = [&](double v) {
    return std::int64_t(std::clamp(std::floor(v * res_a), 0.0, double(n_a - 1)));
  };
  auto clip_cell = [&](std::int64_t c) { return std::clamp<std::int64_t>(c, 0, n_a - 1); };
  const std::int64_t ax0 =
      whole_square ? 0 : std::min(clip(ang.x_a.x - r * ang.sigma_a.x), clip_cell(kx0));
  const std::int64_t ax1 =
      whole_square ? n_a - 1
                   : std::max(clip(ang.x_a.x + r * ang.sigma_a.x), clip_cell(kx0 + side - 1));
  const std::int64_t ay0 =
      whole_square ? 0 : std::min(clip(ang.x_a.y - r * ang.sigma_a.y), clip_cell(ky0));
  const std::int64_t ay1 =
      whole_square ? n_a - 1
                   : std::max(clip(ang.x_a.y + r * ang.sigma_a.y), clip_cell(ky0 + side - 1));
  const Sym2<double> sigma_a2{sqr(ang.sigma_a.x), 0, sqr(ang.sigma_a.y)};
  ReferenceParts<double> sum{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (std::int64_t i = sx0; i <= sx1; ++i)
    for (std::int64_t j = sy0; j <= sy1; ++j) {
      const bool in_block = i >= bx0 && i < bx0 + side && j >= by0 && j < by0 + side;
      for (std::int64_t a = ax0; a <= ax1; ++a)
        for (std::int64_t b = ay0; b <= ay1; ++b) {
          const std::uint64_t ci = cell_index(Cell{i, j, a, b, level, 0});
          const V2 g_a{
              (double(a) + cell_uniform<double>(p.seed, ci, kKemppinenDimAngularX)) / res_a,
              (double(b) + cell_uniform<double>(p.seed, ci, kKemppinenDimAngularY)) / res_a};
          if (sqr(g_a.x - 0.5) + sqr(g_a.y - 0.5) > 0.25) continue;
          const V2 g_s{
              (double(i) + cell_uniform<double>(p.seed, ci, kKemppinenDimSpatialX)) / res_s,
              (double(j) + cell_uniform<double>(p.seed, ci, kKemppinenDimSpatialY)) / res_s};
          const double rr = cell_uniform<double>(p.seed, ci, kKemppinenDimRoulette);
          const double blend = p.blend == Blend::kRoulette ? roulette(rr, w_l) : w_l;
          const double w = blend * normal2(x_s - g_s, sigma_s) * normal2(ang.x_a - g_a, sigma_a2);
          const V3 v = w * color(p.colors, cell_uniform<double>(p.seed, ci, kKemppinenDimColor));
          sum.total = sum.total + v;
          if (a >= kx0 && a < kx0 + side && b >= ky0 && b < ky0 + side) {
            sum.neighbourhood = sum.neighbourhood + v;
            if (in_block) sum.block = sum.block + v;
          }
        }
    }
  const double k = 1 / sqr(res);
  return {k * sum.total, k * sum.neighbourhood, k * sum.block};
}

void expect_same_bits(const V3& a, const V3& b, const char* part) {
  EXPECT_EQ(a.x, b.x) << part;
  EXPECT_EQ(a.y, b.y) << part;
  EXPECT_EQ(a.z, b.z) << part;
}

// Both levels of a footprint (weights 1 − frac and frac, so one of them small), both blendings,
// both colourings, the box and the whole square, both NDFs.
TEST(KemppinenReferenceLoop, PartsAreThePointByPointSumBitForBit) {
  int compared = 0;
  double largest = 0;
  for (bool ggx : {true, false})
    for (auto blend : {kemppinen2025::Blend::kRoulette, kemppinen2025::Blend::kLinear})
      for (auto colors : {kemppinen2025::Colors::kWhite, kemppinen2025::Colors::kRedYellow})
        for (double cells : {1.3, 5.7})
          for (bool whole_square : {false, true})
            for (std::uint64_t i = 0; i < 3; ++i) {
              P p = kemppinen2025::preset_params(2, 0.02, 17);
              p.blend = blend;
              p.colors = colors;
              const auto fp = kemppinen2025::footprint_cells(position(17, i), cells, p);
              const V3 h = direction(10.0 + 15.0 * double(i));
              with_ndf(Ndfs{ggx, 0.3}, [&](const auto& ndf) {
                const Angular<double> ang = kemppinen2025::angular(p, ndf, h);
                const double res = kemppinen2025::base_resolution(p);
                const V2 x_s = kemppinen2025::spatial_position(p, fp.uv);
                const Sym2<double> sigma_s = kemppinen2025::spatial_covariance(p, fp, res);
                const double lambda = kemppinen2025::lod(sigma_s, res);
                const int l0 = int(std::floor(lambda));
                for (int l = 0; l < 2; ++l) {
                  const double w = l == 0 ? 1 - (lambda - l0) : lambda - l0;
                  const int side = whole_square ? 1 : 2;
                  const double sigmas = whole_square ? 8 : 5;
                  const ReferenceParts<double> now = kemppinen2025::reference_level_parts(
                      p, ang, x_s, sigma_s, res, l0 + l, w, side, sigmas, whole_square);
                  const ReferenceParts<double> before = point_by_point_parts(
                      p, ang, x_s, sigma_s, res, l0 + l, w, side, sigmas, whole_square);
                  expect_same_bits(now.total, before.total, "total");
                  expect_same_bits(now.neighbourhood, before.neighbourhood, "neighbourhood");
                  expect_same_bits(now.block, before.block, "block");
                  largest = std::max(largest, before.total.x);
                  ++compared;
                }
                return 0;
              });
            }
  EXPECT_EQ(compared, 192);
  EXPECT_GT(largest, 0) << "some points were hit";
}

// One setting's measurement with one worker thread and with two: the same bits.
TEST(KemppinenCompensationSamples, DoNotDependOnTheThreadCount) {
  const CompConfig c{{true, 0.3}, 0.02, 30, 4};
  const auto measure = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return sample_comp(c, 40, 99, kCompSide);
  };
  const CompSamples one = measure(1), two = measure(2);
  EXPECT_EQ(one.ref, two.ref);
  EXPECT_EQ(one.whole, two.whole);
  EXPECT_EQ(one.block, two.block);
  EXPECT_EQ(one.no_c, two.no_c);
  EXPECT_EQ(one.explicit_whole, two.explicit_whole);
  EXPECT_EQ(one.explicit_block, two.explicit_block);
  EXPECT_EQ(one.c_sum, two.c_sum);
  EXPECT_EQ(one.cross_check, two.cross_check);
  ASSERT_EQ(one.ref.size(), 40u);
  EXPECT_GT(one.c_sum, 0);
}

}  // namespace
}  // namespace glintlab::verify::kemppinen_claims

// Stratified supersampling (one sample per equal cell, unbiased for every N), the threaded image
// loop (identical for any thread count), and the error metrics against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "core/render/metrics.h"
#include "core/render/supersample.h"

namespace glintlab {
namespace {

TEST(Stratified, GridHasEqualCellsForEveryCount) {
  EXPECT_EQ(strata_columns(16), 4);
  EXPECT_EQ(strata_columns(8), 2);
  EXPECT_EQ(strata_columns(7), 1);
  EXPECT_EQ(strata_columns(1024), 32);
  for (int n : {1, 5, 12, 64}) {
    const int nx = strata_columns(n), ny = n / nx;
    EXPECT_EQ(nx * ny, n);
    std::set<std::pair<int, int>> cells;
    for (int s = 0; s < n; ++s) {
      const Vec2<double> o = stratified_offset(99, 1000 + s, s, n);
      ASSERT_GE(o.x, 0.0);
      ASSERT_LT(o.x, 1.0);
      cells.insert({static_cast<int>(o.x * nx), static_cast<int>(o.y * ny)});
    }
    EXPECT_EQ(static_cast<int>(cells.size()), n);  // one sample per cell
  }
}

TEST(Stratified, PixelAverageIsUnbiased) {
  // ∫∫ x² y over the unit square = 1/6. N = 7 (prime: a 1 × 7 grid) averaged over many pixels
  // converges to it; the control, the naive ⌈√7⌉ × ⌈√7⌉ grid filled in order (two cells left
  // empty), does not.
  double sum = 0, naive = 0;
  const int pixels = 20000, n = 7;
  for (int p = 0; p < pixels; ++p) {
    for (int s = 0; s < n; ++s) {
      const std::uint64_t index = static_cast<std::uint64_t>(p) * n + s;
      const Vec2<double> o = stratified_offset(5, index, s, n);
      sum += o.x * o.x * o.y;
      const double nx = (s % 3 + counter_uniform<double>(5, index, 0)) / 3;
      const double ny = (s / 3 + counter_uniform<double>(5, index, 1)) / 3;
      naive += nx * nx * ny;
    }
  }
  EXPECT_NEAR(sum / (pixels * n), 1.0 / 6.0, 1e-3);
  EXPECT_GT(std::abs(naive / (pixels * n) - 1.0 / 6.0), 5e-3);
}

TEST(RenderImage, IdenticalForAnyThreadCount) {
  const auto pixel = [](int x, int y, double* out) {
    double s = 0;
    for (int i = 0; i < 50; ++i) {
      s += counter_uniform<double>(3, static_cast<std::uint64_t>(y * 37 + x) * 50 + i, 0);
    }
    out[0] = s;
    out[1] = x - y;
  };
  const Image a = render_image(37, 23, {"A", "B"}, 1, pixel);
  const Image b = render_image(37, 23, {"A", "B"}, 2, pixel);
  const Image c = render_image(37, 23, {"A", "B"}, 5, pixel);
  EXPECT_EQ(a.data, b.data);
  EXPECT_EQ(a.data, c.data);
  EXPECT_EQ(a.at(3, 2, 1), 1.0);
  long rows = 0;
  render_image(8, 9, {"A", "B"}, 2, pixel, [&](long done, long total) {
    EXPECT_EQ(total, 9);
    rows = std::max(rows, done);
  });
  EXPECT_EQ(rows, 9);
}

TEST(RenderSupersampled, AveragesStratifiedFilmSamples) {
  // f = film x: each pixel averages N positions inside its own column, so the value lies in
  // [x, x + 1) and, over the image, deviates from the centre x + ½ only by the jitter's noise.
  // The channel "n" counts samples: exactly 1 after the division by N.
  const auto f = [](Vec2<double> film, std::uint64_t, double* acc) {
    acc[0] += film.x;
    acc[1] += 1;
  };
  const Image a = render_supersampled(20, 10, {"x", "n"}, 6, 17, 1, f);
  const Image b = render_supersampled(20, 10, {"x", "n"}, 6, 17, 2, f);
  EXPECT_EQ(a.data, b.data);
  double dev = 0;
  for (int y = 0; y < 10; ++y) {
    for (int x = 0; x < 20; ++x) {
      ASSERT_GE(a.at(x, y, 0), x);
      ASSERT_LT(a.at(x, y, 0), x + 1);
      EXPECT_EQ(a.at(x, y, 1), 1.0);
      dev += a.at(x, y, 0) - x - 0.5;
    }
  }
  // The x offsets of a 2 × 3 grid: per pixel the mean of 2 strata centres ± jitter/(2·√3·√6).
  EXPECT_LT(std::abs(dev / 200), 5 * 0.5 / std::sqrt(12.0 * 6 * 200));
}

TEST(Metrics, RmseAndRelMseByHand) {
  Image x(2, 1, {"R", "G", "B"}), r(2, 1, {"R", "G", "B"});
  r.data = {1, 1, 1, 0, 0, 0};
  x.data = {2, 1, 1, 0, 0, 3};
  EXPECT_DOUBLE_EQ(rmse(x, r), std::sqrt((1.0 + 9.0) / 6.0));
  EXPECT_DOUBLE_EQ(rel_mse(x, r), (1.0 / 1.01 + 9.0 / 0.01) / 6.0);
  const std::vector<std::uint8_t> first{1, 0};
  EXPECT_DOUBLE_EQ(rmse(x, r, {{"R", "G", "B"}, &first}), std::sqrt(1.0 / 3.0));
  EXPECT_DOUBLE_EQ(rmse(x, r, {{"B"}, nullptr}), std::sqrt(9.0 / 2.0));
  EXPECT_EQ(rmse(r, r), 0.0);
  const std::vector<std::uint8_t> none{0, 0};
  EXPECT_THROW(rmse(x, r, {{"R"}, &none}), std::invalid_argument);
  EXPECT_THROW(rmse(x, Image(3, 1, {"R", "G", "B"})), std::invalid_argument);
}

}  // namespace
}  // namespace glintlab

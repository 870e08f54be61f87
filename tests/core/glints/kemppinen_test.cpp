// Tests of Kemppinen et al. 2025 (core/glints/kemppinen*.h): Algorithm 1 against the brute-force
// Eq. 5, the pieces of Eq. 8–10, the grid, the triplanar mode and Algorithm 2's marginal density.
#include "core/glints/kemppinen.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>

#include "core/glints/kemppinen_reference.h"
#include "core/glints/kemppinen_sampling.h"
#include "core/math/disk_rect_area.h"
#include "core/model_registry.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"

namespace glintlab {
namespace {

using V2 = Vec2<double>;
using V3 = Vec3<double>;

kemppinen2025::Params<double> base_params(int side = 2) {
  kemppinen2025::Params<double> p{};
  p.density = 1e4;
  p.microroughness = 0.02;
  p.anisotropy = 1;
  p.filter = 0.5;
  p.side = side;
  p.blend = kemppinen2025::Blend::kRoulette;
  p.erf = kemppinen2025::Erf::kExact;
  p.normalization = kemppinen2025::Normalization::kCorrected;
  p.colors = kemppinen2025::Colors::kWhite;
  p.seed = 7;
  return p;
}

// A footprint whose filter standard deviation is `cells` level-0 cells at uv.
FootprintQuery<double> footprint(V2 uv, double cells, const kemppinen2025::Params<double>& p) {
  const double d = cells / std::sqrt(p.density) / p.filter;
  return {uv, {d, 0}, {0, d}};
}

TEST(KemppinenErf, RationalWithinAbramowitzStegunBound) {
  double worst = 0;
  for (double x = -6; x <= 6; x += 1e-3)
    worst = std::max(worst, std::abs(kemppinen2025::erf_rational(x) - std::erf(x)));
  EXPECT_LT(worst, 3e-7);
  EXPECT_GT(worst, 1e-9);  // it is an approximation, not std::erf
}

TEST(KemppinenRoulette, ExpectationIsTheWeightAwayFromTheEnds) {
  for (double w : {0.2, 0.25, 0.5, 0.75, 0.8}) {  // [2ε, 1 − 2ε]: the window is never clipped
    double mean = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) mean += kemppinen2025::roulette((i + 0.5) / n, w);
    EXPECT_NEAR(mean / n, w, 1e-6) << w;
  }
  EXPECT_EQ(kemppinen2025::roulette(0.5, 1.0), 1.0);
  EXPECT_EQ(kemppinen2025::roulette(0.5, 0.0), 0.0);
}

TEST(KemppinenGrid, BlockStartCoversTheNearestCells) {
  EXPECT_EQ(kemppinen2025::block_start(3.7, 1), 3);
  EXPECT_EQ(kemppinen2025::block_start(3.7, 2), 3);
  EXPECT_EQ(kemppinen2025::block_start(3.2, 2), 2);
  EXPECT_EQ(kemppinen2025::block_start(3.2, 3), 2);
  EXPECT_EQ(kemppinen2025::block_start(3.7, 4), 2);
  EXPECT_EQ(kemppinen2025::block_start(-0.2, 1), -1);
}

// The cell index is the SplitMix64 chain over (sx, sy, ax, ay, level, process) whichever way it is
// written: the values an independent implementation of that chain gives (Python, outside this
// code), so a change of the chain, which would move every point, is caught.
TEST(KemppinenGrid, CellIndexIsTheRecordedChain) {
  using kemppinen2025::Cell;
  EXPECT_EQ(kemppinen2025::cell_index(Cell{3, -7, 12, 0, 5, 0}), 0xf1fd9281f8a04ef7ULL);
  EXPECT_EQ(kemppinen2025::cell_index(Cell{-1, std::int64_t(1) << 40, -3, 9, 19, 2}),
            0x95d6d183b9c1b5deULL);
}

TEST(DiskRectArea, KnownAreas) {
  const double pi = std::numbers::pi;
  EXPECT_NEAR(disk_rect_area(0, 1, 0, 1, 0.5, 0.5, 0.5), pi / 4, 1e-14);
  EXPECT_NEAR(disk_rect_area(0.5, 1, 0.5, 1, 0.5, 0.5, 0.5), pi / 16, 1e-14);
  EXPECT_NEAR(disk_rect_area(0.4, 0.6, 0.4, 0.6, 0.5, 0.5, 0.5), 0.04, 1e-15);
  EXPECT_EQ(disk_rect_area(0, 0.1, 0, 0.1, 0.5, 0.5, 0.5), 0.0);
  // Against a fine midpoint rule on a rectangle the circle cuts twice.
  const double x0 = 0.8, x1 = 1.0, y0 = 0.3, y1 = 0.75;
  double ref = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = x0 + (x1 - x0) * (i + 0.5) / n, y = y0 + (y1 - y0) * (j + 0.5) / n;
      ref += (x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5) <= 0.25;
    }
  ref *= (x1 - x0) * (y1 - y0) / (double(n) * n);
  EXPECT_NEAR(disk_rect_area(x0, x1, y0, y1, 0.5, 0.5, 0.5), ref, 2e-5);
}

TEST(Kemppinen, LodPutsTheFilterOnOneToTwoCells) {
  const kemppinen2025::Params<double> p = base_params();
  const double res = std::sqrt(p.density);
  for (double cells : {1.0, 3.0, 17.0, 100.0}) {
    const FootprintQuery<double> fp = footprint({0.3, 0.6}, cells, p);
    const double lambda = kemppinen2025::lod(kemppinen2025::spatial_covariance(p, fp, res), res);
    const double cell = std::exp2(std::floor(lambda)) / res;  // cell size at ⌊λ⌋
    const double two_sigma = 2 * cells / res;
    EXPECT_GE(two_sigma / cell, 1 - 1e-9) << cells;
    EXPECT_LT(two_sigma / cell, 2 + 1e-9) << cells;
  }
}

TEST(Kemppinen, ConstantPointsVisitedAndLevelWeights) {
  for (int side : {1, 2, 3, 4}) {
    const kemppinen2025::Params<double> p = base_params(side);
    for (double cells : {0.1, 1.0, 30.0, 1e4}) {
      const auto r = kemppinen2025::eval(p, GGX<double>{0.3, 0.3}, footprint({0.2, 0.1}, cells, p),
                                         V3{0.1, 0.05, 0.99});
      EXPECT_EQ(r.points, 2 * side * side * side * side);
      EXPECT_NEAR(r.w0 + r.w1, 1, 1e-15);
      EXPECT_GE(r.w1, 0);
    }
  }
}

// Close up (λ = 0: one angular cell holds the whole square, so B(k) = □ and C = 0) with k = 16
// the 4×4 spatial block holds the filter: Eq. 11 equals the brute-force Eq. 5.
TEST(Kemppinen, MatchesBruteForceEq5CloseUp) {
  const kemppinen2025::Params<double> p = base_params(4);
  const GGX<double> ggx{0.2, 0.2};
  double worst = 0, peak = 0;
  for (int i = 0; i < 40; ++i) {
    const V2 uv{0.013 * i, 0.021 * i + 0.3};
    const FootprintQuery<double> fp = footprint(uv, 0.3, p);
    for (double t : {0.0, 0.05, 0.1}) {
      const V3 h = normalize(V3{t, 0.5 * t, 1});
      const auto r = kemppinen2025::eval(p, ggx, fp, h);
      const V3 ref = kemppinen2025::reference_filtered(p, ggx, fp, h);
      EXPECT_EQ(r.lambda, 0.0);
      EXPECT_NEAR(r.compensation_part.x, 0, 1e-12);
      worst = std::max(worst, std::abs(r.d.x - ref.x));
      peak = std::max(peak, ref.x);
    }
  }
  EXPECT_GT(peak, 1.0);  // some glints were hit
  EXPECT_LT(worst, 1e-3 * peak);
}

// Far away the explicit points are few and the compensation carries the mean: the average of
// D★^f over positions approaches D (corrected normalisation), and without C it does not.
TEST(Kemppinen, FarFieldMeanOverPositionsApproachesD) {
  for (int side : {2, 4}) {
    kemppinen2025::Params<double> p = base_params(side);
    const GGX<double> ggx{0.3, 0.3};
    const V3 h = normalize(V3{0.2, -0.1, 1});
    double mean = 0, mean_nc = 0;
    const int n = 4000;
    for (int i = 0; i < n; ++i) {
      const V2 uv{counter_uniform<double>(3, std::uint64_t(i), 0) * 50,
                  counter_uniform<double>(3, std::uint64_t(i), 1) * 50};
      const FootprintQuery<double> fp = footprint(uv, 300, p);
      p.compensate = true;
      mean += kemppinen2025::eval(p, ggx, fp, h).d.x;
      p.compensate = false;
      mean_nc += kemppinen2025::eval(p, ggx, fp, h).d.x;
    }
    mean /= n;
    mean_nc /= n;
    const double d = ggx.D(h);
    EXPECT_NEAR(mean / d, 1, 0.05) << side;
    EXPECT_LT(mean_nc / d, 0.5) << side;
  }
}

TEST(Kemppinen, PrintedNormalizationIsFourOverPiBrighter) {
  kemppinen2025::Params<double> p = base_params();
  const GGX<double> ggx{0.3, 0.3};
  const FootprintQuery<double> fp = footprint({0.4, 0.4}, 2, p);
  const V3 h = normalize(V3{0.1, 0.1, 1});
  const double c = kemppinen2025::eval(p, ggx, fp, h).d.x;
  p.normalization = kemppinen2025::Normalization::kPrinted;
  const double pr = kemppinen2025::eval(p, ggx, fp, h).d.x;
  EXPECT_NEAR(pr / c, 4 / std::numbers::pi, 1e-12);
}

// Found by kemppinen2025-fig2-3: Beckmann's D underflows to 0 near the horizon, where σ = 0 made
// the angular Gaussian 0/0 and D★^f NaN. It must be finite there (0 where D = 0) for every query.
TEST(Kemppinen, FiniteWhereTheNdfUnderflows) {
  const kemppinen2025::Params<double> p = base_params();
  const Beckmann<double> beckmann{0.5, 0.5};
  for (double t : {1.45, 1.5, 1.55, 1.57}) {
    const V3 h{std::sin(t), 0, std::cos(t)};
    for (double cells : {1.0, 8.0, 1e3}) {
      const auto r = kemppinen2025::eval(p, beckmann, footprint({0.5, 0.5}, cells, p), h);
      EXPECT_TRUE(std::isfinite(r.d.x)) << "theta " << t << " cells " << cells;
      if (beckmann.D(h) == 0) {
        EXPECT_EQ(r.d.x, 0.0);
      }
    }
  }
}

TEST(Kemppinen, ColorsAndExpectedColor) {
  kemppinen2025::Params<double> p = base_params();
  p.colors = kemppinen2025::Colors::kRedYellow;
  V3 mean{0, 0, 0};
  const int n = 100000;
  for (int i = 0; i < n; ++i)
    mean = mean + kemppinen2025::color(p.colors, counter_uniform<double>(1, std::uint64_t(i), 0));
  const V3 e = kemppinen2025::expected_color<double>(p.colors);
  EXPECT_NEAR(mean.x / n, e.x, 1e-12);
  EXPECT_NEAR(mean.y / n, e.y, 0.005);
  EXPECT_NEAR(mean.z / n, e.z, 0.001);
  // Far field: the colour of D★^f is the expected colour.
  const auto r = kemppinen2025::eval(p, Beckmann<double>{0.3, 0.3}, footprint({0.3, 0.3}, 1e4, p),
                                     V3{0, 0, 1});
  EXPECT_NEAR(r.d.y / r.d.x, e.y, 0.02);
}

TEST(Kemppinen, TriplanarOnAnAxisPlaneIsOneProcess) {
  const kemppinen2025::Params<double> p = base_params();
  const GGX<double> ggx{0.3, 0.3};
  const V3 pos{0.3, 0.7, 0.2}, dx{1e-3, 0, 0}, dy{0, 1e-3, 0};
  const auto r = kemppinen2025::eval_triplanar(p, ggx, pos, dx, dy, V3{0, 0, 1}, V3{0, 0, 1});
  EXPECT_EQ(r.points, 3 * 2 * 16);
  // Only the z plane has weight: its value is the uv process (process 0) at uv = (x, y).
  const auto one = kemppinen2025::eval_process(p, ggx, {{pos.x, pos.y}, {dx.x, dx.y}, {dy.x, dy.y}},
                                               V3{0, 0, 1}, 0, 1.0);
  EXPECT_EQ(r.d.x, one.d.x);
}

TEST(KemppinenSampling, MarginalDensityIntegratesToAcceptanceRate) {
  kemppinen2025::Params<double> p = base_params(1);
  p.microroughness = 0.05;
  const GGX<double> ggx{0.4, 0.4};
  const FootprintQuery<double> fp = footprint({0.41, 0.37}, 2.5, p);
  // ∫ p(x) dx over the disk by a midpoint rule in □ against the accepted fraction of samples.
  const int m = 300;
  double integral = 0;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      integral +=
          kemppinen2025::sample_density_square(p, ggx, fp, V2{(i + 0.5) / m, (j + 0.5) / m});
  integral /= double(m) * m;
  int ok = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i)
    ok += kemppinen2025::sample_half(p, ggx, fp, mix64(std::uint64_t(i) + 1)).ok;
  EXPECT_GT(integral, 0.5);
  EXPECT_LE(integral, 1 + 1e-3);
  EXPECT_NEAR(integral, double(ok) / n, 0.02);
}

// The marginal density as its definition reads: every block B(k) that x's angular cell lies in,
// at both levels, built by block() and summed by block_density(), one block at a time.
template <class Ndf, class T>
T density_block_by_block(const kemppinen2025::Params<T>& p, const Ndf& ndf,
                         const FootprintQuery<T>& fp, Vec2<T> x) {
  namespace k = kemppinen2025;
  if (sqr(x.x - T(0.5)) + sqr(x.y - T(0.5)) > T(0.25)) return T(0);
  const k::Spatial<T> sp = k::spatial(p, fp);
  const int n = p.side;
  static k::Block<T> block;
  T total = T(0);
  for (int up = 0; up < 2; ++up) {
    const int level = sp.l0 + up;
    const T w_l = up ? sp.w1 : T(1) - sp.w1;
    if (!(w_l > T(0))) continue;
    const T res_a = k::angular_resolution<T>(level);
    const std::int64_t cx = std::int64_t(std::floor(x.x * res_a));
    const std::int64_t cy = std::int64_t(std::floor(x.y * res_a));
    for (int dx = 1 - n; dx <= 0; ++dx)
      for (int dy = 1 - n; dy <= 0; ++dy) {
        const T half = T(0.5) * T(n - 1);
        const T fx = T(cx + dx) + half, fy = T(cy + dy) + half;
        const T area = T(disk_rect_area(double(fx / res_a), double((fx + T(1)) / res_a),
                                        double(fy / res_a), double((fy + T(1)) / res_a), 0.5, 0.5,
                                        0.5));
        if (!(area > T(0))) continue;
        k::block(p, ndf, sp, level, w_l, cx + dx, cy + dy, block);
        total += w_l * area / T(kMapDomainArea<T>) * k::block_density(block, x);
      }
  }
  return total;
}

// sample_density_square computes each point once per level instead of once per block: the same
// bits as the block-by-block sum, for every k, both NDFs, both blends, float and double.
template <class T>
void expect_density_is_block_by_block() {
  const kemppinen2025::Params<double> b = base_params();
  kemppinen2025::Params<T> p{};
  p.density = T(b.density);
  p.microroughness = T(0.05);
  p.anisotropy = T(1.5);
  p.filter = T(b.filter);
  p.erf = kemppinen2025::Erf::kExact;
  p.normalization = b.normalization;
  p.colors = kemppinen2025::Colors::kRedYellow;
  p.seed = 11;
  const GGX<T> ggx{T(0.3), T(0.5)};
  const Beckmann<T> beckmann{T(0.2), T(0.2)};
  int nonzero = 0;
  for (int side = 1; side <= kemppinen2025::kMaxSide; ++side) {
    p.side = side;
    for (int q = 0; q < 40; ++q) {
      const auto frac = [](double t) { return t - std::floor(t); };
      const double cells = 0.3 + 4.0 * frac(q * 0.5698);
      const FootprintQuery<double> f =
          footprint({0.1 + 0.8 * frac(q * 0.618034), 0.1 + 0.8 * frac(q * 0.754878)}, cells, b);
      const FootprintQuery<T> fp{{T(f.uv.x), T(f.uv.y)},
                                 {T(f.duv_dx.x), T(f.duv_dx.y)},
                                 {T(f.duv_dy.x), T(f.duv_dy.y)}};
      p.blend = q % 2 ? kemppinen2025::Blend::kLinear : kemppinen2025::Blend::kRoulette;
      for (int r = 0; r < 12; ++r) {
        const double rad = 0.49 * (r + 1) / 12.0, phi = 0.7 * r + q;
        const Vec2<T> x{T(0.5 + rad * std::cos(phi)), T(0.5 + rad * std::sin(phi))};
        const T a = kemppinen2025::sample_density_square(p, ggx, fp, x);
        const T a_ref = density_block_by_block(p, ggx, fp, x);
        const T c = kemppinen2025::sample_density_square(p, beckmann, fp, x);
        const T c_ref = density_block_by_block(p, beckmann, fp, x);
        ASSERT_EQ(std::memcmp(&a, &a_ref, sizeof a), 0) << side << " " << q << " " << r;
        ASSERT_EQ(std::memcmp(&c, &c_ref, sizeof c), 0) << side << " " << q << " " << r;
        nonzero += (a > T(0)) + (c > T(0));
      }
    }
  }
  EXPECT_GT(nonzero, 4 * 40 * 12);  // most queries see points: the comparison is not of zeros
}

TEST(KemppinenSampling, MarginalDensityIsTheBlockByBlockSumBitForBit) {
  expect_density_is_block_by_block<double>();
  expect_density_is_block_by_block<float>();
}

TEST(KemppinenModel, RegisteredWithRangeChecks) {
  for (const char* name : {"kemppinen_ggx", "kemppinen_beckmann"}) {
    const ModelEntry& m = find_model(name);
    EXPECT_THROW(resolve_params(m, {{"density", "0"}}), ModelParamError);
    EXPECT_THROW(resolve_params(m, {{"microroughness", "0"}}), ModelParamError);
    EXPECT_THROW(resolve_params(m, {{"k", "5"}}), ModelParamError);
    EXPECT_THROW(resolve_params(m, {{"density", "inf"}}), ModelParamError);
    const auto v = resolve_params(m, {{"k", "16"}, {"blending", "linear"}});
    ModelQuery<double> q{};
    q.footprint = {{0.3, 0.2}, {1e-3, 0}, {0, 1e-3}};
    q.wi = normalize(V3{0.3, 0.1, 1});
    q.wo = normalize(V3{-0.3, -0.1, 1});
    const ErasedEval e = m.eval(v, q);
    EXPECT_EQ(e.intermediates.size(), m.intermediates.size());
    EXPECT_EQ(e.intermediates[8], 2.0 * 256);  // points visited, k = 16
    EXPECT_EQ(m.eval(v, q).value, e.value);    // deterministic
  }
}

}  // namespace
}  // namespace glintlab

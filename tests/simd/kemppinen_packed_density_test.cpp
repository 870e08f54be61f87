// The marginal pdf of Kemppinen's Algorithm 2 on a batch, the work of its points packed by (point,
// lane) or not, per level (core/glints/kemppinen_packed.h), against the loops that compute every
// point on every lane (sample_density_square_unpacked), bit for bit, on this unit's
// SSE2 batches (4 float, 2 double lanes): every side k, both NDFs, the three point processes,
// roulette and linear blending, both colour sets; lanes of one batch at different levels, cells and
// parameters, and lanes of one footprint at neighbouring x (a frame's pixels, three lights); every
// level packed, every level unpacked, and the choice. The model's outputs on every ISA
// are compared by tests/simd/kemppinen_equivalence_test.cpp.
#define GLINTLAB_SIMD_TU kemppinen_packed_test
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

#include "core/glints/kemppinen_sampling.h"
#include "core/math/lanes.h"
#include "core/math/rng.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/simd/instantiate.h"

namespace glintlab::kemppinen2025 {
namespace {

template <class W>
struct Case {
  Params<W> p;
  W alpha_x, alpha_y;
  FootprintQuery<W> fp;
  Vec2<W> x;
};

// Lane l of query `row`: footprints from 10⁻⁹ to 1 (λ from 0 to beyond the top level), x in and
// around U_Ω, per-lane roughness, microroughness and anisotropy.
template <class W>
Case<W> make_case(std::uint64_t row, int side, bool linear, bool colored) {
  using S = Scalar<W>;
  const auto u = [&](std::size_t l, std::uint64_t d) {
    return counter_uniform<double>(0x7061636bULL, row * 64 + l, d);
  };
  const auto lanes = [&](auto f) { return float_lanes<W>([&](std::size_t l) { return S(f(l)); }); };
  Case<W> c;
  c.p.density = lanes([&](std::size_t l) { return std::pow(10.0, 2 + 5 * u(l, 0)); });
  c.p.microroughness = lanes([&](std::size_t l) { return std::pow(10.0, -3 + 2 * u(l, 1)); });
  c.p.anisotropy = lanes([&](std::size_t l) { return u(l, 2) < 0.5 ? 1.0 : 0.3 + 3 * u(l, 3); });
  c.p.filter = W(S(0.5));
  c.p.side = side;
  c.p.blend = linear ? Blend::kLinear : Blend::kRoulette;
  c.p.erf = Erf::kExact;
  c.p.normalization = Normalization::kCorrected;
  c.p.colors = colored ? Colors::kRedYellow : Colors::kWhite;
  c.p.seed = row % 7;
  c.alpha_x = lanes([&](std::size_t l) { return 0.05 + 0.6 * u(l, 4); });
  c.alpha_y = lanes([&](std::size_t l) { return 0.05 + 0.6 * u(l, 5); });
  const auto size = [&](std::size_t l) {
    return u(l, 6) < 0.05 ? 0.0 : std::pow(10.0, -9 + 9 * u(l, 7));
  };
  c.fp.uv = {lanes([&](std::size_t l) { return 4 * u(l, 8); }),
             lanes([&](std::size_t l) { return 4 * u(l, 9); })};
  c.fp.duv_dx = {lanes([&](std::size_t l) { return size(l) * (u(l, 10) - 0.5); }),
                 lanes([&](std::size_t l) { return size(l) * (u(l, 11) - 0.5); })};
  c.fp.duv_dy = {lanes([&](std::size_t l) { return size(l) * (u(l, 12) - 0.5); }),
                 lanes([&](std::size_t l) { return size(l) * (u(l, 13) - 0.5); })};
  c.x = {lanes([&](std::size_t l) { return -0.05 + 1.1 * u(l, 14); }),
         lanes([&](std::size_t l) { return -0.05 + 1.1 * u(l, 15); })};
  return c;
}

// Lane l of query `row` as a frame has it: lane 0's parameters and footprint in every lane, the uv
// of neighbouring pixels, and x at one of three nearby points (three lights) moved a little per
// pixel, so that lanes mostly share their level and angular cells.
template <class W>
Case<W> make_coherent_case(std::uint64_t row, int side, bool linear, bool colored) {
  using S = Scalar<W>;
  Case<W> c = make_case<W>(row, side, linear, colored);
  const auto first = [](const W& v) { return LanesOf<W>(v)[0]; };
  const auto same = [&](const W& v) { return W(first(v)); };
  const auto step = [&](const W& v, double by) {
    const S v0 = first(v);
    return float_lanes<W>([&](std::size_t l) { return S(v0 + by * double(l / 3)); });
  };
  c.p.density = same(c.p.density);
  c.p.microroughness = same(c.p.microroughness);
  c.p.anisotropy = same(c.p.anisotropy);
  c.alpha_x = same(c.alpha_x);
  c.alpha_y = same(c.alpha_y);
  c.fp.uv = {step(c.fp.uv.x, 1e-3 * first(c.fp.duv_dx.x)), same(c.fp.uv.y)};
  c.fp.duv_dx = {same(c.fp.duv_dx.x), same(c.fp.duv_dx.y)};
  c.fp.duv_dy = {same(c.fp.duv_dy.x), same(c.fp.duv_dy.y)};
  // Inside U_Ω, so that most rows have a density.
  const double x0 = 0.25 + 0.4 * (double(first(c.x.x)) + 0.05),
               y0 = 0.25 + 0.4 * (double(first(c.x.y)) + 0.05);
  c.x = {float_lanes<W>(
             [&](std::size_t l) { return S(x0 + 0.03 * double(l % 3) + 1e-4 * double(l / 3)); }),
         float_lanes<W>([&](std::size_t l) { return S(y0 + 0.02 * double(l % 3)); })};
  return c;
}

template <class W>
bool same_lanes(const W& a, const W& b) {
  using S = Scalar<W>;
  using Bits = std::conditional_t<sizeof(S) == 4, std::uint32_t, std::uint64_t>;
  const LanesOf<W> x(a), y(b);
  for (std::size_t l = 0; l < kLaneCount<W>; ++l)
    if (std::bit_cast<Bits>(x[l]) != std::bit_cast<Bits>(y[l])) return false;
  return true;
}

// Rows whose density differs in any bit from the unpacked one, with every level packed, every
// level unpacked (through the batch's level loop) and the choice (through sample_density_square),
// and rows with a nonzero density (the comparison must see some).
template <class W, template <class> class Ndf>
void expect_packed_is_unpacked(const char* name, bool coherent) {
  int compared = 0, nonzero = 0, differ[3] = {0, 0, 0};
  for (int side = 1; side <= 4; ++side)
    for (int variant = 0; variant < 4; ++variant) {
      const int rows = side <= 2 ? 200 : 40;
      for (int row = 0; row < rows; ++row) {
        const std::uint64_t id = std::uint64_t(row + 1000 * side);
        const Case<W> c = coherent ? make_coherent_case<W>(id, side, variant & 1, variant & 2)
                                   : make_case<W>(id, side, variant & 1, variant & 2);
        const Ndf<W> ndf{c.alpha_x, c.alpha_y};
        const int process = row % 3;
        const W unpacked = sample_density_square_unpacked(c.p, ndf, c.fp, c.x, process);
        const W results[3] = {
            sample_density_square_packed(c.p, ndf, c.fp, c.x, process, DensityPath::kPacked),
            sample_density_square_packed(c.p, ndf, c.fp, c.x, process, DensityPath::kUnpacked),
            sample_density_square(c.p, ndf, c.fp, c.x, process)};
        ++compared;
        for (int k = 0; k < 3; ++k)
          if (!same_lanes(results[k], unpacked)) ++differ[k];
        if (any_lane<W>(unpacked > W(0))) ++nonzero;
      }
    }
  const char* ways[3] = {"every level packed", "every level unpacked", "the choice"};
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(differ[k], 0) << name << ", " << ways[k] << ": " << differ[k] << " of " << compared
                            << " batches differ";
  // (A frame-like batch has one footprint in every lane, so fewer have a density.)
  EXPECT_GT(nonzero, compared / (coherent ? 8 : 4)) << name << ": too few batches with a density";
}

using F = Wide<xsimd::batch<float, xsimd::sse2>, ExactMath>;
using D = Wide<xsimd::batch<double, xsimd::sse2>, ExactMath>;

TEST(KemppinenPackedDensity, GgxFloatIsTheUnpackedLoopsBits) {
  expect_packed_is_unpacked<F, GGX>("ggx float", false);
}
TEST(KemppinenPackedDensity, BeckmannFloatIsTheUnpackedLoopsBits) {
  expect_packed_is_unpacked<F, Beckmann>("beckmann float", false);
}
TEST(KemppinenPackedDensity, GgxDoubleIsTheUnpackedLoopsBits) {
  expect_packed_is_unpacked<D, GGX>("ggx double", false);
}
TEST(KemppinenPackedDensity, FrameLikeLanesGgxFloatAreTheUnpackedLoopsBits) {
  expect_packed_is_unpacked<F, GGX>("ggx float, frame-like lanes", true);
}
TEST(KemppinenPackedDensity, FrameLikeLanesBeckmannDoubleAreTheUnpackedLoopsBits) {
  expect_packed_is_unpacked<D, Beckmann>("beckmann double, frame-like lanes", true);
}

// Control: the comparison sees a one-ulp change of x in one lane.
TEST(KemppinenPackedDensity, ComparisonSeesAnUlpOfX) {
  int seen = 0;
  for (int row = 0; row < 200; ++row) {
    const Case<F> c = make_case<F>(std::uint64_t(row + 1000), 2, false, false);
    const GGX<F> ndf{c.alpha_x, c.alpha_y};
    Vec2<F> x = c.x;
    const LanesOf<F> xx(x.x);
    x.x =
        float_lanes<F>([&](std::size_t l) { return l == 0 ? std::nextafter(xx[l], 2.0f) : xx[l]; });
    const F a = sample_density_square(c.p, ndf, c.fp, c.x, 0);
    const F b = sample_density_square_unpacked(c.p, ndf, c.fp, x, 0);
    if (!same_lanes(a, b)) ++seen;
  }
  EXPECT_GT(seen, 20);
}

}  // namespace
}  // namespace glintlab::kemppinen2025

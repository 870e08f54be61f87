// podee::shade (Podee et al. Sec. 3, core/shading/podee_shade.h) instantiates on the SIMD float
// types: Wide<float, ExactMath> gives the scalar float result bit for bit, and an xsimd batch (the
// baseline ISA of this build) gives every lane's scalar result to rounding.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>

#include "core/math/rng.h"
#include "core/shading/podee_shade.h"
#include "core/simd/wide.h"

namespace glintlab {
namespace {

struct Case {
  std::array<Vec3<float>, 4> r;
  Vec3<float> l;
};

Case make_case(std::uint64_t i) {
  const auto u = [&](int d) { return counter_uniform<double>(31, i, std::uint64_t(d)); };
  const Vec3<double> l = normalize(Vec3<double>{0.3 * u(0), 0.3 * u(1), 1});
  const OrthonormalBasis<double> b = basis_from_z(l);
  Case c{};
  for (int k = 0; k < 4; ++k) {
    const Vec3<double> r =
        normalize(l + (0.2 * u(2 + 2 * k) - 0.1) * b.x + (0.2 * u(3 + 2 * k) - 0.1) * b.y);
    c.r[std::size_t(k)] = {float(r.x), float(r.y), float(r.z)};
  }
  c.l = {float(l.x), float(l.y), float(l.z)};
  return c;
}

TEST(PodeeWide, ExactWideFloatMatchesScalarBitForBit) {
  using W = Wide<float, ExactMath>;
  for (std::uint64_t i = 0; i < 500; ++i) {
    const Case c = make_case(i);
    for (int w = 0; w < 3; ++w) {
      const podee::Result<float> s = podee::shade(c.r, c.l, 0.05f, podee::Weighting(w));
      std::array<Vec3<W>, 4> rw{};
      for (int k = 0; k < 4; ++k)
        rw[std::size_t(k)] = {W(c.r[std::size_t(k)].x), W(c.r[std::size_t(k)].y),
                              W(c.r[std::size_t(k)].z)};
      const podee::Result<W> v =
          podee::shade(rw, Vec3<W>{W(c.l.x), W(c.l.y), W(c.l.z)}, W(0.05f), podee::Weighting(w));
      EXPECT_EQ(std::bit_cast<std::uint32_t>(s.weight), std::bit_cast<std::uint32_t>(v.weight.v));
      EXPECT_EQ(std::bit_cast<std::uint32_t>(s.r.x), std::bit_cast<std::uint32_t>(v.r.x.v));
    }
  }
}

TEST(PodeeWide, BatchLanesMatchScalar) {
  using B = xsimd::batch<float>;
  using W = Wide<B, ExactMath>;
  constexpr std::size_t n = B::size;
  for (std::uint64_t g = 0; g < 100; ++g) {
    alignas(64) float lane[12][n], light[3][n];
    std::array<Case, n> cases{};
    for (std::size_t j = 0; j < n; ++j) {
      cases[j] = make_case(1000 + g * n + j);
      for (int k = 0; k < 4; ++k) {
        lane[3 * k][j] = cases[j].r[std::size_t(k)].x;
        lane[3 * k + 1][j] = cases[j].r[std::size_t(k)].y;
        lane[3 * k + 2][j] = cases[j].r[std::size_t(k)].z;
      }
      light[0][j] = cases[j].l.x, light[1][j] = cases[j].l.y, light[2][j] = cases[j].l.z;
    }
    const auto load = [](const float* p) { return W(B::load_aligned(p)); };
    std::array<Vec3<W>, 4> rw{};
    for (int k = 0; k < 4; ++k)
      rw[std::size_t(k)] = {load(lane[3 * k]), load(lane[3 * k + 1]), load(lane[3 * k + 2])};
    const podee::Result<W> v =
        podee::shade(rw, Vec3<W>{load(light[0]), load(light[1]), load(light[2])}, W(0.05f));
    alignas(64) float weight[n], dist[n];
    v.weight.v.store_aligned(weight);
    v.distance.v.store_aligned(dist);
    for (std::size_t j = 0; j < n; ++j) {
      const podee::Result<float> s = podee::shade(cases[j].r, cases[j].l, 0.05f);
      EXPECT_NEAR(weight[j], s.weight, 2e-5f) << g << " " << j;
      EXPECT_NEAR(dist[j], s.distance, 1e-5f) << g << " " << j;
    }
  }
}

}  // namespace
}  // namespace glintlab

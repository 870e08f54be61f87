// The Chermain kernels generic over the float type (core/glints/chermain.h, chermain_lookup.h) at
// T = double against the host code they replaced (tests/core/glints/chermain_host_reference.h):
// bit for bit on random queries that span every LOD, dictionary level, probe count and wrap.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/glints/chermain.h"
#include "core/math/rng.h"
#include "tests/core/glints/chermain_host_reference.h"

namespace glintlab {
namespace {

namespace host = test::chermain_host;

bool same(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

double u01(std::uint64_t i, std::uint64_t dim) {
  return counter_uniform<double>(hash_string("chermain_scalar_identity"), i, dim);
}

// A random direction: 20 % below the horizon, 10 % within 0.5° of it, else the upper hemisphere.
Vec3<double> direction(std::uint64_t i, std::uint64_t dim) {
  const double sel = u01(i, dim), phi = 6.283185307179586 * u01(i, dim + 1);
  const double z = sel < 0.2   ? -u01(i, dim + 2)
                   : sel < 0.3 ? 0.0087 * u01(i, dim + 2)
                               : u01(i, dim + 2);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

TEST(ChermainScalarIdentity, LookupsMatchTheHostCode) {
  const chermain2021::Dictionary& d = chermain2021::default_chermain_dictionary();
  std::size_t bad = 0;
  for (std::uint64_t i = 0; i < 200000; ++i) {
    const int n = int(u01(i, 0) * d.distributions()), k = int(u01(i, 1) * d.levels());
    const double x = (2.2 * u01(i, 2) - 1.1) * d.extent();
    const double g = std::pow(10.0, -6 + 7 * u01(i, 3));
    const double gx = u01(i, 4) < 0.1 ? 0.0 : g * (u01(i, 5) - 0.5);
    const double gy = u01(i, 6) < 0.1 ? 0.0 : g * (u01(i, 7) - 0.5);
    const chermain2021::TableWrap wrap =
        i % 2 ? chermain2021::TableWrap::kClampToEdge : chermain2021::TableWrap::kMirroredRepeat;
    const double mip = i % 7 == 0 ? 0.0 : 7 * u01(i, 8);
    bad += !same(d.lookup_lod(n, k, x, mip, wrap), host::host_lookup_lod(d, n, k, x, mip, wrap));
    chermain2021::TableFilter a, b;
    bad += !same(d.lookup_grad(n, k, x, gx, gy, wrap, 16, &a),
                 host::host_lookup_grad(d, n, k, x, gx, gy, wrap, 16, &b));
    bad += !same(a.lambda, b.lambda) || a.probes != b.probes;
  }
  EXPECT_EQ(bad, 0u);
}

// The model's eval, pdf and sample (through Chermain:: and the patch-SDF with its info).
TEST(ChermainScalarIdentity, ModelMatchesTheHostCode) {
  std::size_t bad = 0, glinty = 0, smooth = 0;
  for (std::uint64_t i = 0; i < 40000; ++i) {
    const std::uint64_t s = i / 64;  // one parameter vector per 64 queries
    const auto us = [&](std::uint64_t dim) { return u01(s + 1000000, dim); };
    const double density = std::exp(std::log(1.0) + us(3) * std::log(1e14));
    const double g = std::pow(10.0, -5 + 6 * us(5));
    const std::vector<double> v = {0.01 + 1.2 * us(0),
                                   0.01 + 1.2 * us(1),
                                   s % 4 ? 1.96 * us(2) - 0.98 : 0.0,
                                   density,
                                   double(s % 3),
                                   0.05 + 3 * us(4),
                                   g * (us(6) - 0.5),
                                   g * (us(7) - 0.5),
                                   s % 5 ? g * (us(8) - 0.5) : 0.0,
                                   g * (us(9) - 0.5),
                                   double(s)};
    auto p = Chermain::params<double>(v);
    if (s % 7 == 3) p.sdf.wrap = chermain2021::TableWrap::kClampToEdge;
    if (s % 11 == 5) p.sdf.with_rho = false;
    ModelQuery<double> q{};
    const double level = -2 + 20 * u01(i, 10);
    const double foot =
        u01(i, 11) < 0.05 ? 0.0 : std::exp2(level - 0.5 * std::log2(density) + 0.4 * u01(i, 12));
    const double a = 6.283185307179586 * u01(i, 13);
    q.footprint.uv = {8 * u01(i, 14) - 4, 8 * u01(i, 15) - 4};
    q.footprint.duv_dx = {foot * std::cos(a), foot * std::sin(a)};
    q.footprint.duv_dy = {-foot * 0.6 * std::sin(a), foot * 0.6 * std::cos(a)};
    q.wi = direction(i, 20);
    q.wo = u01(i, 30) < 0.5 ? reflect(q.wi, normalize(Vec3<double>{0.2 * (u01(i, 31) - 0.5),
                                                                   0.2 * (u01(i, 32) - 0.5), 1.0}))
                            : direction(i, 33);
    q.light = {1, 1};
    const auto e = Chermain::eval<double>(p, q);
    const auto h = host::host_eval<double>(p, q);
    bad += !same(e.value, h.value) || !same(e.pdf, h.pdf);
    for (std::size_t c = 0; c < e.intermediates.size(); ++c)
      bad += !same(e.intermediates[c], h.intermediates[c]);
    glinty += e.intermediates[0] > 0 && e.intermediates[2] < 16 ? 1 : 0;
    smooth += e.intermediates[2] >= 16 ? 1 : 0;
    const Vec2<double> u{i % 97 == 0 ? 1.0 : u01(i, 40), u01(i, 41)};
    const ModelSample<double> a1 = Chermain::sample<double>(p, q, u);
    const ModelSample<double> b1 = host::host_sample<double>(p, q, u);
    bad += !same(a1.wo.x, b1.wo.x) || !same(a1.wo.y, b1.wo.y) || !same(a1.wo.z, b1.wo.z) ||
           !same(a1.pdf, b1.pdf) || !same(a1.weight, b1.weight) || a1.rejected != b1.rejected;
  }
  EXPECT_EQ(bad, 0u);
  EXPECT_GT(glinty, 2000u);  // the case reaches the dictionary …
  EXPECT_GT(smooth, 2000u);  // … and the smooth fallback
}

}  // namespace
}  // namespace glintlab

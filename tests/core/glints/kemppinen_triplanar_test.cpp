// Tests of the triplanar (UV-free) mode of Kemppinen et al. 2025 Sec. 3.3.6 as the models expose
// it (core/glints/kemppinen_triplanar.h, `mapping=triplanar`): equal to the uv path on the plane
// ⊥ z, a single other process on the planes ⊥ x and ⊥ y, blend weights summing to 1, and the
// mixture sampler's density integrating to its acceptance rate.
#include "core/glints/kemppinen_triplanar.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/math/rng.h"
#include "core/model_registry.h"
#include "core/models/kemppinen_beckmann.h"
#include "core/models/kemppinen_ggx.h"
#include "core/ndf/ggx.h"

namespace glintlab {
namespace {

using V2 = Vec2<double>;
using V3 = Vec3<double>;

std::vector<double> values(double mapping, double theta, double phi) {
  std::vector<double> v;
  for (const ParamSpec& s : KemppinenGGX::kParams) {
    double x = s.default_value;
    const std::string n(s.name);
    if (n == "mapping") x = mapping;
    if (n == "normal_theta") x = theta;
    if (n == "normal_phi") x = phi;
    if (n == "k") x = 1;  // k = 4
    v.push_back(x);
  }
  return v;
}

// A query at footprint uv with `cells` level-0 cells (density 1e4, filter 0.5: the defaults).
ModelQuery<double> query(std::uint64_t i, double cells) {
  const double d = cells / 100.0 / 0.5;
  const double u = counter_uniform<double>(11, i, 0), v = counter_uniform<double>(11, i, 1);
  const V3 wi = normalize(V3{0.3 * counter_uniform<double>(11, i, 2), 0.1, 1});
  const V3 wo = normalize(V3{-0.2, -0.1 * counter_uniform<double>(11, i, 3), 1});
  return {{{u * 10 - 5, v * 10 - 5}, {d, 0.1 * d}, {-0.2 * d, d}}, wi, wo, {1, 1}};
}

template <class M>
void expect_z_plane_is_uv() {
  const auto uv = M::template params<double>(values(0, 0, 0));
  const auto tri = M::template params<double>(values(1, 0, 0));
  for (std::uint64_t i = 0; i < 40; ++i) {
    const ModelQuery<double> q = query(i, std::pow(2.0, double(i % 10) - 2));
    const auto a = M::eval(uv, q), b = M::eval(tri, q);
    EXPECT_EQ(a.value, b.value) << i;
    EXPECT_EQ(a.pdf, b.pdf) << i;
    for (std::size_t k = 0; k < M::kIntermediates.size(); ++k) {
      if (M::kIntermediates[k] == "points_visited") {
        EXPECT_EQ(3 * a.intermediates[k], b.intermediates[k]);  // three processes evaluated
      } else {
        EXPECT_EQ(a.intermediates[k], b.intermediates[k]) << M::kIntermediates[k] << " " << i;
      }
    }
    const V2 u{counter_uniform<double>(12, i, 0), counter_uniform<double>(12, i, 1)};
    const auto sa = M::sample(uv, q, u), sb = M::sample(tri, q, u);
    EXPECT_EQ(sa.wo.x, sb.wo.x);
    EXPECT_EQ(sa.wo.y, sb.wo.y);
    EXPECT_EQ(sa.pdf, sb.pdf);
  }
}

TEST(KemppinenTriplanar, PlaneNormalToZEqualsTheUvPath) {
  expect_z_plane_is_uv<KemppinenGGX>();
  expect_z_plane_is_uv<KemppinenBeckmann>();
}

// Negative control of the equality: on a tilted plane the triplanar value is another one.
TEST(KemppinenTriplanar, TiltedPlaneDiffersFromTheUvPath) {
  const auto uv = KemppinenGGX::params<double>(values(0, 0, 0));
  const auto tri = KemppinenGGX::params<double>(values(1, 50, 30));
  int differ = 0;
  for (std::uint64_t i = 0; i < 40; ++i) {
    const ModelQuery<double> q = query(i, 0.5);
    differ += KemppinenGGX::eval(uv, q).value != KemppinenGGX::eval(tri, q).value;
  }
  EXPECT_GT(differ, 30);
}

// On the plane ⊥ x (θ = 90°, φ = 0) the blend is the single process 1 at uv = (p.y, p.z).
TEST(KemppinenTriplanar, PlaneNormalToXIsProcessOne) {
  const auto tri = KemppinenGGX::params<double>(values(1, 90, 0));
  for (std::uint64_t i = 0; i < 20; ++i) {
    const ModelQuery<double> q = query(i, 1.5);
    const kemppinen2025::TriplanarInput<double> in =
        kemppinen2025::triplanar_input(q.footprint, tri.normal);
    EXPECT_NEAR(in.pos.x, 0, 1e-15);
    const V3 h = half_vector(q.wi, q.wo);
    const auto r = kemppinen2025::eval_triplanar(tri.glint, tri.ndf, in, h);
    const auto one = kemppinen2025::eval_process(
        tri.glint, tri.ndf, kemppinen2025::triplanar_footprint(0, in.pos, in.dpos_dx, in.dpos_dy),
        h, kemppinen2025::triplanar_process(0), 1.0);
    EXPECT_NEAR(r.d.x, one.d.x, 1e-9 * (1 + one.d.x)) << i;
    EXPECT_EQ(r.lambda, one.lambda);
  }
}

TEST(KemppinenTriplanar, BlendWeightsSumToOne) {
  for (std::uint64_t i = 0; i < 1000; ++i) {
    const V3 n = kemppinen2025::object_normal(180 * counter_uniform<double>(13, i, 0),
                                              360 * counter_uniform<double>(13, i, 1));
    const V3 w = kemppinen2025::triplanar_weights(n);
    EXPECT_NEAR(w.x + w.y + w.z, 1.0, 1e-15);
    EXPECT_GE(w.x, 0);
    EXPECT_GE(w.y, 0);
    EXPECT_GE(w.z, 0);
    const V3 wm = kemppinen2025::triplanar_weights(-1.0 * n);  // the back side blends alike
    EXPECT_EQ(w.x, wm.x);
    EXPECT_EQ(w.z, wm.z);
  }
  const V3 z = kemppinen2025::triplanar_weights(V3{0, 0, 1});
  EXPECT_EQ(z.x, 0);
  EXPECT_EQ(z.z, 1);
}

// The mixture sampler on a diagonal plane: its density over the disk (midpoint rule in □, the
// three planes' marginals weighted by w_i) integrates to the fraction of accepted samples.
TEST(KemppinenTriplanar, MixtureDensityIntegratesToAcceptanceRate) {
  auto v = values(1, 54.7356, 45);
  auto m = KemppinenGGX::params<double>(v);
  m.glint.side = 1;
  m.glint.microroughness = 0.05;
  const ModelQuery<double> q = query(3, 2.5);
  const kemppinen2025::TriplanarInput<double> in =
      kemppinen2025::triplanar_input(q.footprint, m.normal);
  const V3 w = kemppinen2025::triplanar_weights(in.normal);
  EXPECT_NEAR(w.x, 1.0 / 3, 1e-5);
  const int g = 120;
  double integral = 0;
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j) {
      const V2 x{(i + 0.5) / g, (j + 0.5) / g};
      const double wa[3] = {w.x, w.y, w.z};
      for (int a = 0; a < 3; ++a)
        integral +=
            wa[a] * kemppinen2025::sample_density_square(
                        m.glint, m.ndf,
                        kemppinen2025::triplanar_footprint(a, in.pos, in.dpos_dx, in.dpos_dy), x,
                        kemppinen2025::triplanar_process(a));
    }
  integral /= double(g) * g;
  int ok = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i)
    ok += kemppinen2025::triplanar_sample_half(m.glint, m.ndf, in, mix64(std::uint64_t(i) + 1)).ok;
  EXPECT_GT(integral, 0.2);  // not trivially empty
  EXPECT_NEAR(integral, double(ok) / n, 0.02);
}

}  // namespace
}  // namespace glintlab

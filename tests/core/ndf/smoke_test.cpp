#include <gtest/gtest.h>
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/ndf/fresnel.h"
#include "core/math/rng.h"
#include "verify/stats/sphere_cubature.h"
using namespace glintlab;
TEST(Smoke, Compiles) {
  GGX<double> g{0.3, 0.3};
  Beckmann<float> b{0.3f, 0.5f};
  EXPECT_GT(g.D({0, 0, 1}), 0);
  EXPECT_GT(b.D({0, 0, 1}), 0);
  EXPECT_GT(vndf(g, Vec3<double>{0, 0, 1}, Vec3<double>{0, 0, 1}), 0);
  EXPECT_GT(erfinv(0.5), 0);
  auto r = verify::integrate_sphere([&](const Vec3<double>& m) { return g.D(m) * m.z; }, {});
  EXPECT_NEAR(r.value, 1.0, 1e-8);
}

// The views of the full-budget Podee panels (experiments/figures/podee.h): view k's normal map is
// the experiment's map translated by (k mod n, k div n) / n of a tile, slopes and LEAN moments
// alike, and view 0 is the experiment's map itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "experiments/figures/podee.h"
#include "verify/scenes/podee_scene.h"

namespace glintlab::experiments {
namespace {

// Slopes of `map` at the sphere's uv, with the tile coordinates shifted by (du, dv).
Vec2<double> shifted_slopes(const podee::NormalMap& map, Vec2<double> uv, double du, double dv) {
  return map.slopes({uv.x + du / map.tiles_u, uv.y + dv / map.tiles_v});
}

TEST(PodeeViews, ViewZeroIsTheExperimentsMap) {
  const auto base = podee::normal_map();
  const auto view0 = podee_view_normal_map(0, 4);
  for (const Vec2<double> uv : {Vec2<double>{0.01, 0.5}, Vec2<double>{0.37, 0.21}}) {
    const Vec2<double> a = base->slopes(uv), b = view0->slopes(uv);
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
  }
  EXPECT_EQ(view0->moments.texel(0, 17, 93).xx, base->moments.texel(0, 17, 93).xx);
}

TEST(PodeeViews, EachViewIsTheMapTranslatedByAFractionOfATile) {
  const auto base = podee::normal_map();
  constexpr int kViews = 4;
  for (int view : {1, 6, 15}) {
    const double du = double(view % kViews) / kViews, dv = double(view / kViews) / kViews;
    const auto m = podee_view_normal_map(view, kViews);
    ASSERT_EQ(m->tiles_u, base->tiles_u);
    ASSERT_EQ(m->tiles_v, base->tiles_v);
    double moved = 0;
    for (int i = 0; i < 50; ++i) {
      const Vec2<double> uv{0.013 + 0.0191 * i, 0.31 + 0.0077 * i};
      const Vec2<double> got = m->slopes(uv), want = shifted_slopes(*base, uv, du, dv);
      EXPECT_NEAR(got.x, want.x, 1e-9) << view;
      EXPECT_NEAR(got.y, want.y, 1e-9) << view;
      // A map left in place would equal the base at the same uv instead.
      moved = std::max(moved, std::abs(got.x - base->slopes(uv).x));
    }
    EXPECT_GT(moved, 0.05) << "view " << view << " shows the same part of the bumps as view 0";
    // The LEAN moments follow: (du, dv) of a tile is a whole number of level-0 texels.
    const int n = base->moments.size();
    const int si = int(du * n), sj = int(dv * n);
    for (int j = 0; j < n; j += 37)
      for (int i = 0; i < n; i += 29) {
        const SlopeMoments<double>& got = m->moments.texel(0, i, j);
        const SlopeMoments<double>& want = base->moments.texel(0, (i + si) % n, (j + sj) % n);
        EXPECT_NEAR(got.mean_x, want.mean_x, 1e-9);
        EXPECT_NEAR(got.mean_y, want.mean_y, 1e-9);
        EXPECT_NEAR(got.xx, want.xx, 1e-9);
        EXPECT_NEAR(got.yy, want.yy, 1e-9);
        EXPECT_NEAR(got.xy, want.xy, 1e-9);
      }
  }
}

}  // namespace
}  // namespace glintlab::experiments

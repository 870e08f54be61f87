// Tests of core/glints/kneiphof_ltc.h: the facing rectangle is a valid LTC polygon seen from its
// front; the LTC D_Ωh (Kneiphof & Klein 2024 Sec. 4, Eq. 13 with the D_PR scale of Eq. 19) is
// near the Monte Carlo one where the lobe is well fitted; the model kneiphof_klein_area's
// intermediates agree with Eq. 16 and its bad parameters are one-line errors.
#include "core/glints/kneiphof_ltc.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/ltc/ltc_polygon_check.h"
#include "core/model_registry.h"

namespace glintlab {
namespace {

Vec3<double> dir(double theta_deg, double phi_deg) {
  const double t = theta_deg * std::numbers::pi / 180, p = phi_deg * std::numbers::pi / 180;
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

TEST(KneiphofLtc, FacingRectangleIsAValidFrontFacingPolygon) {
  for (double theta : {0.0, 30.0, 80.0})
    for (double tilt : {-60.0, 0.0, 45.0}) {
      const auto v =
          kneiphof2024::facing_rectangle(dir(theta, 20), 2.0, 0.5, 0.2, 0.3, tilt * 0.0174533);
      const PolygonLight<double> checked =
          make_polygon_light(std::span<const Vec3<double>>(v), {1, 1, 1});
      EXPECT_NO_THROW(check_ltc_polygon(v));
      const PolygonLight<double> fast = kneiphof2024::rectangle_polygon_light(v);
      EXPECT_TRUE(static_cast<bool>(fast.in_front({0, 0, 0})));
      EXPECT_NEAR(fast.area, 0.1, 1e-12);
      EXPECT_NEAR(length(fast.normal - checked.normal), 0, 1e-12);
      EXPECT_NEAR(fast.area, checked.area, 1e-12);
      EXPECT_NEAR(fast.fan_cdf[0], checked.fan_cdf[0], 1e-12);
    }
}

TEST(KneiphofLtc, LtcProbabilityAndRadianceAreNearMonteCarlo) {
  const double alpha = 0.25;
  const GGX<double> g{alpha, alpha};
  const Vec3<double> wi = dir(40, 180), mirror = dir(40, 0);
  const auto v = kneiphof2024::facing_rectangle(mirror, 1.0, 0.5, 0.5, 0, 0);
  const kneiphof2024::AreaLightTerms mc = kneiphof2024::area_light_terms_mc(
      g, wi, kneiphof2024::rectangle_polygon_light(v), {0, 0, 0}, 1 << 16, 11, 0);
  const LtcTableView& t = ltc_ggx_table_view();
  const auto brdf =
      kneiphof2024::area_light_terms_ltc(t, alpha, wi, v.data(), 4, kneiphof2024::AreaP::kBrdfLobe);
  const auto ndf =
      kneiphof2024::area_light_terms_ltc(t, alpha, wi, v.data(), 4, kneiphof2024::AreaP::kNdfLobe);
  EXPECT_NEAR(brdf.d_omega_h / mc.d_omega_h, 1, 0.1);
  EXPECT_NEAR(ndf.d_omega_h / mc.d_omega_h, 1, 0.1);
  EXPECT_NEAR(brdf.lo_over_li / mc.lo_over_li, 1, 0.1);
  // Below the horizon the view sees nothing.
  EXPECT_EQ(kneiphof2024::area_light_terms_ltc(t, alpha, dir(95, 0), v.data(), 4,
                                               kneiphof2024::AreaP::kBrdfLobe)
                .d_omega_h,
            0.0);
}

TEST(KneiphofKleinArea, IntermediatesFollowEq16) {
  const ModelEntry& m = find_model("kneiphof_klein_area");
  for (const char* area_p : {"ltc", "ltc_ndf", "mc"}) {
    const auto values = resolve_params(m, {{"area_p", area_p}, {"alpha", "0.09"}});
    ModelQuery<double> q{};
    q.footprint = {{0.3, 0.7}, {1e-3, 0}, {0, 1e-3}};
    q.wi = dir(30, 180);
    q.wo = dir(30, 0);
    q.light = {1, 1};
    const ErasedEval e = m.eval(values, q);
    const auto& x = e.intermediates;  // N_P, p_unclamped, p, p_clamped, count, factor, smooth, ...
    EXPECT_EQ(x[0], 1.0);             // 1e-6 uv area × 10^6
    EXPECT_GT(x[1], 0.0);
    EXPECT_EQ(x[2], std::min(1.0, x[1]));
    EXPECT_NEAR(x[5], x[4] / (x[0] * x[2]), 1e-12);
    EXPECT_NEAR(e.value, x[6] * x[5], 1e-12 * (1 + e.value)) << area_p;
    EXPECT_NEAR(x[7] / x[9], x[1], 1e-12);  // p = D_Ωh/D_H
  }
}

TEST(KneiphofKleinArea, BadParametersAreOneLineErrors) {
  const ModelEntry& m = find_model("kneiphof_klein_area");
  for (auto [name, bad] :
       std::vector<std::pair<std::string, std::string>>{{"light_tilt_deg", "90"},
                                                        {"light_width", "0"},
                                                        {"light_distance", "0"},
                                                        {"alpha", "2"},
                                                        {"area_p", "cubature"}}) {
    try {
      resolve_params(m, {{name, bad}});
      FAIL() << name << "=" << bad;
    } catch (const ModelParamError& e) {
      const std::string w = e.what();
      EXPECT_NE(w.find(name), std::string::npos) << w;
      EXPECT_EQ(w.find('\n'), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace glintlab

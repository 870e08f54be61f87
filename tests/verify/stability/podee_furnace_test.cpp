// The white furnace of the stability sweep on Podee et al.'s mirror pixel (Sec. 3.1–3.2): with the
// pixel-corner reflection vectors supplied and L_o/L_i divided by the light's solid angle Ω, a
// mirror (F = 1) reflects ρ = ∫ (L_o/L_i) dωo / Ω = 1 exactly where the light cone around the
// mirror direction stays above the horizon. Before, the sweep passed four zero corner vectors
// (a degenerate reflection space at the light's centre: lit from every ωo, value 1) and measured
// ∫ value dωo = 2π.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "verify/stability/cell_stats.h"
#include "verify/stability/sweep_plan.h"

namespace glintlab::verify::stability {
namespace {

const SweepPlane& plane_named(const std::vector<SweepPlane>& planes, const std::string& name) {
  for (const SweepPlane& p : planes)
    if (p.name == name) return p;
  ADD_FAILURE() << "no plane " << name;
  return planes.front();
}

TEST(PodeeFurnace, CornerReflectionsSpanTheFootprintAboutTheMirrorDirection) {
  const Vec3<double> wi{0.6, 0.0, 0.8};
  for (const Vec3<double>& r : pixel_corner_reflections(wi, 0.0)) {
    EXPECT_NEAR(r.x, -0.6, 1e-15);
    EXPECT_NEAR(r.z, 0.8, 1e-15);
  }
  const auto r = pixel_corner_reflections(wi, 1e-3);
  for (const Vec3<double>& c : r) EXPECT_NEAR(length(c), 1.0, 1e-12);
  EXPECT_GT(length(r[3] - r[0]), 1e-3);  // normals tilted by ±s/2: reflections by about ±s
  EXPECT_LT(length(r[3] - r[0]), 4e-3);
}

TEST(PodeeFurnace, MirrorAlbedoIsOneUnderADiskLight) {
  const std::vector<SweepTarget> targets = sweep_targets("podee");
  ASSERT_EQ(targets.size(), 1u);
  const std::vector<SweepPlane> planes = sweep_planes(*targets[0].model, true);
  const SweepPlane& light = plane_named(planes, "light_size");
  const CellBudget budget{4096, 4096};
  for (double theta : {0.0, 60.0}) {
    const CellStats c = measure_cell(targets[0], light, 10.0, theta, budget, 1234);
    const double omega = 2 * std::numbers::pi * (1 - std::cos(10.0 * std::numbers::pi / 180));
    EXPECT_NEAR(c.light_solid_angle, omega, 1e-15);
    // Both estimators of ρ = 1 (4 standard errors), and no energy gain flagged.
    EXPECT_LT(c.albedo_error, 0.1);
    EXPECT_NEAR(c.albedo, 1.0, 4 * c.albedo_error) << "theta " << theta;
    EXPECT_NEAR(c.albedo_uniform, 1.0, 4 * c.albedo_uniform_error + 0.05) << "theta " << theta;
    EXPECT_FALSE(c.energy_gain()) << "theta " << theta << " albedo " << c.albedo;
  }
}

TEST(PodeeFurnace, NoEnergyGainAtTheDefaultLight) {
  const std::vector<SweepTarget> targets = sweep_targets("podee");
  ASSERT_EQ(targets.size(), 1u);
  const std::vector<SweepPlane> planes = sweep_planes(*targets[0].model, true);
  const SweepPlane& alpha = plane_named(planes, "alpha");
  for (double theta : {0.0, 45.0, 85.0})
    EXPECT_FALSE(measure_cell(targets[0], alpha, 0.05, theta, {64, 64}, 99).energy_gain())
        << "theta " << theta;
}

}  // namespace
}  // namespace glintlab::verify::stability

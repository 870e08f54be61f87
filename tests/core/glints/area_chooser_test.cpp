// The area family's engine chooser (core/glints/area_chooser.h): its N_P and p are the model's own
// (kneiphof_klein_area's eval intermediates N_P and p_unclamped, bit for bit) over random queries
// and parameters, both LTC lobes, lights turned and tilted; its level is the binomial chooser's on
// them; the polygon form on a light given by its vertices is the model form's. The check can fail:
// told the other LTC lobe, the p differs.
#include "core/glints/area_chooser.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/math/rng.h"

namespace glintlab {
namespace {

struct Case {
  KneiphofKleinArea::Params<double> params;
  ModelQuery<double> q;
};

// Case i: α in [0.02, 0.8], density 10^4 … 10^9, light 0.1 … 3 units away, 0.01 … 2 wide and
// high, turned and tilted, either LTC lobe; ω_i up to 85°, ω_o anywhere above the horizon; a
// footprint of 10^-8 … 10^-3 per side.
Case random_case(std::uint64_t i) {
  const auto u = [&](int d) { return counter_uniform<double>(61, i, std::uint64_t(d)); };
  using M = KneiphofKleinArea;
  std::vector<double> v;
  for (const ParamSpec& s : M::kParams) v.push_back(s.default_value);
  v[param_index<M>("alpha")] = 0.02 + 0.78 * u(0);
  v[param_index<M>("density")] = 4 + 5 * u(1);
  v[param_index<M>("light_distance")] = 0.1 + 2.9 * u(2);
  v[param_index<M>("light_width")] = 0.01 + 1.99 * u(3);
  v[param_index<M>("light_height")] = 0.01 + 1.99 * u(4);
  v[param_index<M>("light_rotation_deg")] = -180 + 360 * u(5);
  v[param_index<M>("light_tilt_deg")] = -80 + 160 * u(6);
  v[param_index<M>("area_p")] = u(7) < 0.5 ? 0 : 1;
  Case c{M::params<double>(v), {}};
  const double ti = 1.48 * u(8), to = 1.5 * u(9), phi = 6.283185307179586 * u(10);
  c.q.wi = {std::sin(ti), 0, std::cos(ti)};
  c.q.wo = {std::sin(to) * std::cos(phi), std::sin(to) * std::sin(phi), std::cos(to)};
  const double side = std::pow(10.0, -8 + 5 * u(11));
  c.q.footprint.uv = {u(12), u(13)};
  c.q.footprint.duv_dx = {side, 0.3 * side * u(14)};
  c.q.footprint.duv_dy = {0, side * (0.5 + u(15))};
  return c;
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

TEST(AreaChooserInputs, AreTheModelsOwnAndTheLevelIsTheBinomialChoosers) {
  int other_lobe_differs = 0, levels_seen[kBinomialLevels] = {};
  for (std::uint64_t i = 0; i < 2000; ++i) {
    const Case c = random_case(i);
    const auto e = KneiphofKleinArea::eval<double>(c.params, c.q);
    const AreaCountInputs<double> in = kneiphof_klein_area_model_count_inputs(c.params, c.q);
    EXPECT_TRUE(same_bits(in.facets, e.intermediates[0])) << i << " " << in.facets;
    EXPECT_TRUE(same_bits(in.p, e.intermediates[1]))
        << i << " " << in.p << " " << e.intermediates[1];
    const double level = choose_kneiphof_klein_area_model_level(c.params, c.q, 0.02);
    EXPECT_EQ(level, choose_binomial_level(e.intermediates[0], e.intermediates[2], 0.02)) << i;
    ++levels_seen[int(level)];
    // The polygon form on the model's rectangle.
    const auto rect =
        kneiphof2024::facing_rectangle(c.q.wo, c.params.distance, c.params.width, c.params.height,
                                       c.params.rotation, c.params.tilt);
    EXPECT_EQ(level, choose_kneiphof_klein_area_level(
                         *c.params.table, c.params.alpha, c.params.total_area,
                         facet_density_scale<double>(c.params.log10_density), c.q.footprint, c.q.wi,
                         rect.data(), 4, 0.02, c.params.area_p))
        << i;
    // The control: the other lobe's p is not the model's.
    auto other = c.params;
    other.area_p = c.params.area_p == kneiphof2024::AreaP::kBrdfLobe
                       ? kneiphof2024::AreaP::kNdfLobe
                       : kneiphof2024::AreaP::kBrdfLobe;
    other_lobe_differs +=
        same_bits(kneiphof_klein_area_model_count_inputs(other, c.q).p, e.intermediates[1]) ? 0 : 1;
  }
  EXPECT_GT(other_lobe_differs, 1000);
  for (int s : levels_seen) EXPECT_GT(s, 0);
}

}  // namespace
}  // namespace glintlab

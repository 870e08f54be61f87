// The Chermain family's chooser (core/glints/chermain_chooser.h) on SIMD batches: every lane of an
// xsimd batch (the baseline ISA of this build) and of Wide<double> chooses the level the scalar
// double chooser chooses for that lane's inputs, through the model-level wrapper a shader calls,
// flat (no GGAA kernel) and curved (a GGAA derivative).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/glints/chermain_chooser.h"
#include "core/math/rng.h"
#include "core/simd/wide.h"
#include "core/simd/wide_lanes.h"

namespace glintlab {
namespace {

// Footprints of 1 … 10¹¹ expected microfacets (side log-uniform, stretched up to 4×), ω_i up to
// 70° and ω_h up to 40° off the normal in any azimuth, TAU in [0.005, 0.2]; α in [0.05, 0.5] and
// the GGAA derivative per group.
template <class W>
void expect_chermain_lanes_match_scalar(double dh) {
  using S = typename W::ScalarType;
  constexpr std::size_t kL = LaneTraits<W>::kLanes;
  const double density = 3.269017e6;
  int smooth = 0, total = 0;
  for (std::uint64_t g = 0; g < 300; ++g) {
    alignas(64) S side[kL], stretch[kL], ti[kL], hx[kL], hy[kL], tau[kL], out[kL];
    const double alpha = 0.05 + 0.45 * counter_uniform<double>(47, g, 0);
    for (std::size_t l = 0; l < kL; ++l) {
      const auto u = [&](int d) {
        return counter_uniform<double>(53, g * kL + l, std::uint64_t(d));
      };
      side[l] = S(std::sqrt(std::pow(10.0, 11 * u(0)) / density));
      stretch[l] = S(1 + 3 * u(1));
      ti[l] = S(1.2 * u(5));
      const double theta = 0.7 * u(2), phi = 6.283185307179586 * u(3);
      hx[l] = S(std::sin(theta) * std::cos(phi));
      hy[l] = S(std::sin(theta) * std::sin(phi));
      tau[l] = S(0.005 + 0.195 * u(4));
    }
    std::vector<double> v;
    for (const ParamSpec& s : Chermain::kParams) v.push_back(s.default_value);
    v[param_index<Chermain>("alpha_x")] = v[param_index<Chermain>("alpha_y")] = alpha;
    v[param_index<Chermain>("density")] = density;
    v[param_index<Chermain>("dh_dx_x")] = v[param_index<Chermain>("dh_dy_y")] = dh;
    const auto pw = Chermain::params<W>(v);
    const auto ps = Chermain::params<double>(v);
    const auto query = [](auto side_v, auto stretch_v, auto ti_v, auto hx_v, auto hy_v) {
      using T = decltype(side_v);
      ModelQuery<T> q{};
      const Vec3<T> h{hx_v, hy_v, sqrt(T(1) - hx_v * hx_v - hy_v * hy_v)};
      q.wi = {sin(ti_v), T(0), cos(ti_v)};
      q.wo = reflect(q.wi, h);
      q.footprint.duv_dx = {side_v * stretch_v, T(0)};
      q.footprint.duv_dy = {T(0), side_v / stretch_v};
      return q;
    };
    const ModelQuery<W> qw =
        query(LaneTraits<W>::load(side), LaneTraits<W>::load(stretch), LaneTraits<W>::load(ti),
              LaneTraits<W>::load(hx), LaneTraits<W>::load(hy));
    LaneTraits<W>::store(choose_chermain_model_level(pw, qw, LaneTraits<W>::load(tau)), out);
    for (std::size_t l = 0; l < kL; ++l) {
      const ModelQuery<double> qs =
          query(double(side[l]), double(stretch[l]), double(ti[l]), double(hx[l]), double(hy[l]));
      const double expected = choose_chermain_model_level(ps, qs, double(tau[l]));
      EXPECT_EQ(out[l], S(expected)) << side[l] << " " << stretch[l] << " " << ti[l] << " " << hx[l]
                                     << " " << hy[l] << " " << tau[l];
      smooth += expected == 0 ? 1 : 0;
      ++total;
    }
  }
  // The inputs reach the smooth level and the dictionaries both.
  EXPECT_GT(smooth, 0);
  EXPECT_LT(smooth, total);
}

TEST(ChermainChooserWide, BatchDoubleLanesMatchScalar) {
  expect_chermain_lanes_match_scalar<Wide<xsimd::batch<double>, ExactMath>>(0.0);
  expect_chermain_lanes_match_scalar<Wide<xsimd::batch<double>, ExactMath>>(0.02);
}

TEST(ChermainChooserWide, WideScalarMatchesScalar) {
  expect_chermain_lanes_match_scalar<Wide<double, ExactMath>>(0.0);
  expect_chermain_lanes_match_scalar<Wide<double, ExactMath>>(0.02);
}

}  // namespace
}  // namespace glintlab

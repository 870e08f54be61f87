// The adequacy chooser (core/glints/adequacy.h) on SIMD batches: every lane of an xsimd batch (the
// baseline ISA of this build) and of Wide<double> chooses the level the scalar double chooser
// chooses for that lane's inputs, through the model-level wrappers a shader would call.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/glints/adequacy.h"
#include "core/models/kemppinen_ggx.h"
#include "core/math/rng.h"
#include "core/simd/wide.h"
#include "core/simd/wide_lanes.h"

namespace glintlab {
namespace {

// Footprint size, probability and threshold of case i: N_P log-uniform in [1, 1e8], p
// log-uniform in [1e-6, 1], TAU in [0.005, 0.2].
struct Inputs {
  double n, p, tau;
};
Inputs inputs(std::uint64_t i) {
  const auto u = [&](int d) { return counter_uniform<double>(97, i, std::uint64_t(d)); };
  return {std::floor(std::pow(10.0, 8 * u(0))), std::pow(10.0, -6 * u(1)), 0.005 + 0.195 * u(2)};
}

template <class W>
void expect_lanes_match_scalar() {
  using S = typename W::ScalarType;
  constexpr std::size_t kL = LaneTraits<W>::kLanes;
  for (std::uint64_t g = 0; g < 2000; ++g) {
    alignas(64) S n[kL], p[kL], tau[kL], out[kL];
    for (std::size_t l = 0; l < kL; ++l) {
      const Inputs in = inputs(g * kL + l);
      n[l] = S(in.n), p[l] = S(in.p), tau[l] = S(in.tau);
    }
    const W level = choose_binomial_level(LaneTraits<W>::load(n), LaneTraits<W>::load(p),
                                          LaneTraits<W>::load(tau));
    LaneTraits<W>::store(level, out);
    for (std::size_t l = 0; l < kL; ++l)
      EXPECT_EQ(out[l], S(choose_binomial_level(double(n[l]), double(p[l]), double(tau[l]))))
          << n[l] << " " << p[l] << " " << tau[l];
  }
}

// The chooser by measured cost, lane by lane against the scalar one (costs of this CPU's order).
template <class W>
void expect_cost_lanes_match_scalar() {
  using S = typename W::ScalarType;
  constexpr std::size_t kL = LaneTraits<W>::kLanes;
  const std::array<double, kBinomialLevels> cost = {25, 85, 90, 50};
  for (std::uint64_t g = 0; g < 2000; ++g) {
    alignas(64) S n[kL], p[kL], tau[kL], out[kL];
    for (std::size_t l = 0; l < kL; ++l) {
      const Inputs in = inputs(g * kL + l);
      n[l] = S(in.n), p[l] = S(in.p), tau[l] = S(in.tau);
    }
    const W level =
        choose_binomial_level_by_cost(LaneTraits<W>::load(n), LaneTraits<W>::load(p),
                                      LaneTraits<W>::load(tau), cost);
    LaneTraits<W>::store(level, out);
    for (std::size_t l = 0; l < kL; ++l)
      EXPECT_EQ(out[l], S(choose_binomial_level_by_cost(double(n[l]), double(p[l]),
                                                        double(tau[l]), cost)))
          << n[l] << " " << p[l] << " " << tau[l];
  }
}

TEST(AdequacyChooserWide, ByCostBatchDoubleLanesMatchScalar) {
  expect_cost_lanes_match_scalar<Wide<xsimd::batch<double>, ExactMath>>();
}

TEST(AdequacyChooserWide, BatchDoubleLanesMatchScalar) {
  expect_lanes_match_scalar<Wide<xsimd::batch<double>, ExactMath>>();
}

TEST(AdequacyChooserWide, WideScalarMatchesScalar) {
  expect_lanes_match_scalar<Wide<double, ExactMath>>();
}

TEST(AdequacyChooserWide, ModelWrappersRunOnBatches) {
  using W = Wide<xsimd::batch<double>, ExactMath>;
  constexpr std::size_t kL = LaneTraits<W>::kLanes;
  const std::vector<double> v = {0.1, 0.1, 6.0, 0.26, 0.0, 0.0};  // kneiphof_klein kParams order
  const auto ps = KneiphofKlein::params<double>(v);
  const auto pw = KneiphofKlein::params<W>(v);
  alignas(64) double side[kL], out[kL];
  for (std::size_t l = 0; l < kL; ++l) side[l] = std::pow(10.0, -3.0 + 0.5 * double(l));
  ModelQuery<W> qw{};
  qw.wi = {W(0.0), W(0.0), W(1.0)};
  qw.wo = normalize(Vec3<W>{W(0.05), W(0.0), W(1.0)});
  qw.light = {W(1.0), W(1.0)};
  const W s = LaneTraits<W>::load(side);
  qw.footprint.duv_dx = {s, W(0.0)};
  qw.footprint.duv_dy = {W(0.0), s};
  LaneTraits<W>::store(choose_kneiphof_klein_level(pw, qw, W(0.02)), out);
  for (std::size_t l = 0; l < kL; ++l) {
    ModelQuery<double> q{};
    q.wi = {0, 0, 1};
    q.wo = normalize(Vec3<double>{0.05, 0, 1});
    q.light = {1, 1};
    q.footprint.duv_dx = {side[l], 0};
    q.footprint.duv_dy = {0, side[l]};
    EXPECT_EQ(out[l], choose_kneiphof_klein_level(ps, q, 0.02)) << l;
  }
}

// The Kemppinen chooser lane by lane against the scalar one: kemppinen_ggx at footprints of
// 10⁻¹ … 10⁷ expected points (side log-uniform, stretched up to 4×), α in [0.05, 0.5], ω_h up to
// 40° off the normal in any azimuth, TAU in [0.005, 0.2].
template <class W>
void expect_kemppinen_lanes_match_scalar() {
  using S = typename W::ScalarType;
  constexpr std::size_t kL = LaneTraits<W>::kLanes;
  for (std::uint64_t g = 0; g < 300; ++g) {
    alignas(64) S side[kL], stretch[kL], hx[kL], hy[kL], tau[kL], out[kL];
    const double alpha = 0.05 + 0.45 * counter_uniform<double>(41, g, 0);
    for (std::size_t l = 0; l < kL; ++l) {
      const auto u = [&](int d) { return counter_uniform<double>(43, g * kL + l, std::uint64_t(d)); };
      side[l] = S(std::pow(10.0, -2.5 + 4 * u(0)));
      stretch[l] = S(1 + 3 * u(1));
      const double theta = 0.7 * u(2), phi = 6.283185307179586 * u(3);
      hx[l] = S(std::sin(theta) * std::cos(phi));
      hy[l] = S(std::sin(theta) * std::sin(phi));
      tau[l] = S(0.005 + 0.195 * u(4));
    }
    std::vector<double> v;
    for (const ParamSpec& s : KemppinenGGX::kParams) v.push_back(s.default_value);
    v[param_index<KemppinenGGX>("alpha_x")] = v[param_index<KemppinenGGX>("alpha_y")] = alpha;
    const auto pw = KemppinenGGX::params<W>(v);
    const auto ps = KemppinenGGX::params<double>(v);
    const auto query = [](auto side_v, auto stretch_v, auto hx_v, auto hy_v) {
      using T = decltype(side_v);
      ModelQuery<T> q{};
      const Vec3<T> h{hx_v, hy_v, sqrt(T(1) - hx_v * hx_v - hy_v * hy_v)};
      q.wi = {T(0), T(0), T(1)};
      q.wo = reflect(q.wi, h);
      q.footprint.duv_dx = {side_v * stretch_v, T(0)};
      q.footprint.duv_dy = {T(0), side_v / stretch_v};
      return q;
    };
    const ModelQuery<W> qw =
        query(LaneTraits<W>::load(side), LaneTraits<W>::load(stretch), LaneTraits<W>::load(hx),
              LaneTraits<W>::load(hy));
    LaneTraits<W>::store(choose_kemppinen_model_level(pw, qw, LaneTraits<W>::load(tau)), out);
    for (std::size_t l = 0; l < kL; ++l) {
      const ModelQuery<double> qs =
          query(double(side[l]), double(stretch[l]), double(hx[l]), double(hy[l]));
      EXPECT_EQ(out[l], S(choose_kemppinen_model_level(ps, qs, double(tau[l]))))
          << side[l] << " " << stretch[l] << " " << hx[l] << " " << hy[l] << " " << tau[l];
    }
  }
}

TEST(AdequacyChooserWide, KemppinenBatchDoubleLanesMatchScalar) {
  expect_kemppinen_lanes_match_scalar<Wide<xsimd::batch<double>, ExactMath>>();
}

TEST(AdequacyChooserWide, KemppinenWideScalarMatchesScalar) {
  expect_kemppinen_lanes_match_scalar<Wide<double, ExactMath>>();
}

}  // namespace
}  // namespace glintlab

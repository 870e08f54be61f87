// The Kemppinen and Chermain choosers for given costs (core/glints/cost_chooser.h): in the GPU
// order they choose as the GPU-order choosers do, on every cell of both grids; under the order
// measured on this machine they are never refuted by the measured table (no cell where the chosen
// level's lower bound is above TAU), and the same check catches a cost chooser whose adequacy
// table is off by one level (each level taken where the next more complete one is adequate), which
// the measured order then drives to inadequate levels.
#include "core/glints/cost_chooser.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>

#include "core/models/kemppinen_beckmann.h"
#include "core/models/kemppinen_ggx.h"
#include "verify/adequacy/chermain_adequacy.h"
#include "verify/adequacy/kemppinen_adequacy.h"
#include "verify/adequacy/measured_tables.h"

namespace glintlab::verify::adequacy {
namespace {

constexpr double kTau = 0.02;

// ns per evaluation measured on this machine class (docs/adequacy.md "Cost from the benchmarks":
// glintlab_bench_glints' adequacy/<model>/level=<level>/avx512 rows, 2026-12-06), KemppinenLevel
// and ChermainLevel order. Not the GPU order: k16_exact below k16_rational (within noise),
// dict12 below dict4_ggaa, dict16 below dict8_ggaa.
constexpr std::array<double, kKemppinenLevels> kKemppinenGgxMeasured = {
    15, 1094, 1120, 3555, 3581, 15181, 15419, 51471, 50879};
constexpr std::array<double, kChermainLevels> kChermainMeasured = {34,  246,  534, 425, 991,
                                                                   530, 1357, 709, 1877};

// The adequacy table shifted by one level: each level taken where the next more complete one is
// adequate (a broken chooser's off-by-one).
template <std::size_t N>
std::array<bool, N> shifted(const std::array<bool, N>& a) {
  std::array<bool, N> s{};
  for (std::size_t l = 0; l + 1 < N; ++l) s[l] = a[l + 1];
  s[N - 1] = true;
  return s;
}

template <class Row>
bool refuted(const Row& r, int level) {
  const LevelStats& s = r.levels[std::size_t(level)];
  return s.mean_diff_lcb > kTau || s.cv_diff_lcb > kTau;
}

template <class M>
auto kemppinen_params(const KemppinenCell& c) {
  return M::template params<double>(kemppinen_level_param_values(c, KemppinenLevel::kK16Exact, 0));
}

TEST(CostChooser, KemppinenGpuOrderChoosesAsTheGpuOrderChooserOnBothGrids) {
  constexpr auto gpu = gpu_cost_order<kKemppinenLevels>();
  std::size_t n = 0, differ = 0, by_measured_differ = 0;
  const auto check = [&](auto model) {
    using M = decltype(model);
    for (Budget b : {Budget::kQuick, Budget::kFull})
      for (const KemppinenCell& c :
           make_kemppinen_grid({std::string(M::kName)}, kemppinen_grid_axes(b))) {
        const auto p = kemppinen_params<M>(c);
        for (int i = 0; i < 2; ++i)
          for (double tau : {kTau, 10 * kTau}) {
            const ModelQuery<double> q = kemppinen_cell_query(c, kemppinen_surface_position(c, i));
            const double want = choose_kemppinen_model_level(p, q, tau);
            const double got = choose_kemppinen_model_level_by_cost(p, q, tau, gpu);
            ++n;
            differ += got != want ? 1 : 0;
            by_measured_differ +=
                choose_kemppinen_model_level_by_cost(p, q, tau, kKemppinenGgxMeasured) != want;
          }
      }
  };
  check(KemppinenGGX{});
  check(KemppinenBeckmann{});
  EXPECT_EQ(differ, 0u) << n << " queries";
  // The measured order does choose otherwise (k16_exact for k16_rational).
  EXPECT_GT(by_measured_differ, 0u);
  std::printf(
      "kemppinen: %zu queries, GPU order as the chooser; the measured order differs in %zu\n", n,
      by_measured_differ);
}

TEST(CostChooser, ChermainGpuOrderChoosesAsTheGpuOrderChooserOnBothGrids) {
  constexpr auto gpu = gpu_cost_order<kChermainLevels>();
  std::size_t n = 0, differ = 0;
  for (Budget b : {Budget::kQuick, Budget::kFull})
    for (const ChermainCell& c : make_chermain_grid({"chermain"}, chermain_grid_axes(b))) {
      const auto p = chermain_level_params(c, kChermainMostComplete, 0);
      for (int i = 0; i < 2; ++i)
        for (double tau : {kTau, 10 * kTau}) {
          const ModelQuery<double> q = chermain_cell_query(c, chermain_surface_position(c, i));
          ++n;
          differ += choose_chermain_model_level_by_cost(p, q, tau, gpu) !=
                            choose_chermain_model_level(p, q, tau)
                        ? 1
                        : 0;
        }
    }
  EXPECT_EQ(differ, 0u) << n << " queries";
}

TEST(CostChooser, KemppinenMeasuredOrderNeverRefutedAndAnOffByOneTableIs) {
  // The Kemppinen chooser test's grid: 32 cells, 1500 positions.
  const auto rows = measured_kemppinen_small_grid(kTau);
  std::array<int, kKemppinenLevels> chosen{};
  int decided = 0, broken_refuted = 0, as_gpu_order = 0;
  for (const KemppinenCellResult& r : rows) {
    const auto p = kemppinen_params<KemppinenGGX>(r.cell);
    const ModelQuery<double> q =
        kemppinen_cell_query(r.cell, kemppinen_surface_position(r.cell, 0));
    const int level = int(choose_kemppinen_model_level_by_cost(p, q, kTau, kKemppinenGgxMeasured));
    ++chosen[std::size_t(level)];
    as_gpu_order += level == r.chooser ? 1 : 0;
    EXPECT_FALSE(refuted(r, level))
        << "points " << r.cell.points << " α " << r.cell.alpha << " θi " << r.cell.theta_i_deg
        << " θh " << r.cell.theta_h_deg << " chosen " << kKemppinenLevelNames[std::size_t(level)];
    decided += r.levels[std::size_t(level)].adequate ? 1 : 0;
    const auto adequate = kemppinen_level_adequacy(adequate_kemppinen_levels(
        kemppinen_level_moments(p.glint, p.ndf, q.footprint, half_vector(q.wi, q.wo)), kTau));
    const int broken = int(cheapest_adequate_level<double, kKemppinenLevels>(
        shifted(adequate), kKemppinenGgxMeasured));
    broken_refuted += refuted(r, broken) ? 1 : 0;
  }
  EXPECT_GT(decided, 0);
  EXPECT_GT(broken_refuted, 0);
  std::printf(
      "kemppinen by the measured order: %zu cells, adequate by the table in %d, the GPU order's "
      "level in %d; smooth %d, k1 %d, k4 %d, k9 %d, k16_rational %d, k16_exact %d; the off-by-one "
      "table refuted in %d\n",
      rows.size(), decided, as_gpu_order, chosen[0], chosen[1] + chosen[2], chosen[3] + chosen[4],
      chosen[5] + chosen[6], chosen[7], chosen[8], broken_refuted);
}

TEST(CostChooser, ChermainMeasuredOrderNeverRefutedAndAnOffByOneTableIs) {
  // The quick grid's 264 cells at 2000 positions, as the Chermain chooser test measures them.
  const auto rows = measured_chermain_quick_grid(kTau);
  std::array<int, kChermainLevels> chosen{};
  int decided = 0, broken_refuted = 0, as_gpu_order = 0;
  for (const ChermainCellResult& r : rows) {
    const auto p = chermain_level_params(r.cell, kChermainMostComplete, 0);
    const ModelQuery<double> q = chermain_cell_query(r.cell, chermain_surface_position(r.cell, 0));
    const int level = int(choose_chermain_model_level_by_cost(p, q, kTau, kChermainMeasured));
    ++chosen[std::size_t(level)];
    as_gpu_order += level == r.chooser ? 1 : 0;
    EXPECT_FALSE(refuted(r, level))
        << "facets " << r.cell.facets << " α " << r.cell.alpha << " θi " << r.cell.theta_i_deg
        << " θh " << r.cell.theta_h_deg << " dh " << r.cell.dh << " chosen "
        << kChermainLevelNames[std::size_t(level)];
    decided += r.levels[std::size_t(level)].adequate ? 1 : 0;
    const int broken = int(cheapest_adequate_level<double, kChermainLevels>(
        shifted(chermain_level_adequacy(p.sdf, p.d, q, kTau)), kChermainMeasured));
    broken_refuted += refuted(r, broken) ? 1 : 0;
  }
  EXPECT_GT(decided, 0);
  EXPECT_GT(broken_refuted, 0);
  std::printf(
      "chermain by the measured order: %zu cells, adequate by the table in %d, the GPU order's "
      "level in %d;",
      rows.size(), decided, as_gpu_order);
  for (std::size_t l = 0; l < kChermainLevels; ++l)
    std::printf(" %s %d", std::string(kChermainLevelNames[l]).c_str(), chosen[l]);
  std::printf("; the off-by-one table refuted in %d\n", broken_refuted);
}

}  // namespace
}  // namespace glintlab::verify::adequacy

// Table 1 analogue of Chermain et al. 2021 (cost of GGAA against no GGAA): Google Benchmark of
// the patch-SDF evaluation (textureLod vs textureGrad lookups, Eq. 3 vs Eq. 10/19) and of a 1-spp
// frame of the tube scene, single thread. Run:
//   build/release/experiments/bench/glintlab_bench_chermain --benchmark_out=out/bench/chermain.json
//   --benchmark_out_format=json
// Paper (RTX 2080, 1920×1080, OpenGL): +0.6 % to +4.2 % frame time with GGAA.
#include <benchmark/benchmark.h>

#include <vector>

#include "core/glints/chermain.h"
#include "core/math/rng.h"
#include "verify/claims/chermain_scenes.h"

namespace glintlab {
namespace {

struct Input {
  Vec2<double> m;
  FootprintQuery<double> fp;
  SlopeDerivatives d;
};

std::vector<Input> inputs() {
  std::vector<Input> v;
  for (std::uint64_t i = 0; i < 1024; ++i) {
    const auto u = [&](int dim) { return counter_uniform<double>(77, i, std::uint64_t(dim)); };
    const double foot = std::ldexp(1.0, -10 + int(6 * u(0)));
    v.push_back(
        {{u(1) - 0.5, u(2) - 0.5},
         {{u(3), u(4)}, {foot, 0}, {0, foot}},
         {0.05 * (u(5) - 0.5), 0.05 * (u(6) - 0.5), 0.05 * (u(7) - 0.5), 0.05 * (u(8) - 0.5)}});
  }
  return v;
}

void patch_sdf(benchmark::State& state, int kernel) {
  const std::vector<Input> in = inputs();
  const ChermainSdfParams p{&default_chermain_dictionary(), 0.25, 0.25, 0.3, 30, kernel, 0.5, 1};
  for (auto _ : state) {
    double s = 0;
    for (const Input& x : in) s += chermain_patch_sdf(p, x.m, x.fp, x.d);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(in.size()));
}

void tube_frame(benchmark::State& state, int kernel) {
  verify::TubeSceneOptions o;
  o.width = 128, o.height = 86, o.threads = 1;
  default_chermain_dictionary();
  for (auto _ : state) benchmark::DoNotOptimize(verify::render_tubes(o, kernel, 0.5));
  state.SetItemsProcessed(std::int64_t(state.iterations()) * o.width * o.height);
}

BENCHMARK_CAPTURE(patch_sdf, no_ggaa, kChermainNoGgaa);
BENCHMARK_CAPTURE(patch_sdf, ggaa, kChermainProjectedHalf);
BENCHMARK_CAPTURE(tube_frame, no_ggaa, kChermainNoGgaa)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(tube_frame, ggaa, kChermainProjectedHalf)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace glintlab

BENCHMARK_MAIN();

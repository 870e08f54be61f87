// Google Benchmark of Kemppinen et al. 2025 Algorithm 1 (core/glints/kemppinen.h), CPU scalar
// double: time per evaluation of D★^f against k, footprint size (the constant-time claim) and the
// erf of Eq. 10, and of the brute-force Eq. 5 (core/glints/kemppinen_reference.h) for contrast.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>

#include "core/glints/kemppinen.h"
#include "core/glints/kemppinen_reference.h"
#include "core/ndf/ggx.h"

namespace {

using namespace glintlab;

KemppinenParams<double> bench_params(int side, KemppinenErf erf) {
  KemppinenParams<double> p{};
  p.density = 1e4;
  p.microroughness = 0.02;
  p.anisotropy = 1;
  p.filter = 0.5;
  p.side = side;
  p.blend = KemppinenBlend::kRoulette;
  p.erf = erf;
  p.normalization = KemppinenNormalization::kCorrected;
  p.colors = KemppinenColors::kWhite;
  p.seed = 1;
  return p;
}

// Args: side (√k), footprint in level-0 cells, erf (0 exact, 1 rational).
void BM_KemppinenEval(benchmark::State& state) {
  const KemppinenParams<double> p =
      bench_params(int(state.range(0)), static_cast<KemppinenErf>(state.range(2)));
  const double d = double(state.range(1)) / std::sqrt(p.density) / p.filter;
  const GGX<double> ggx{0.3, 0.3};
  std::uint64_t i = 0;
  for (auto _ : state) {
    const FootprintQuery<double> fp{
        {counter_uniform<double>(9, i, 0) * 100, counter_uniform<double>(9, i, 1) * 100},
        {d, 0},
        {0, d}};
    const Vec3<double> h = normalize(Vec3<double>{0.1 * counter_uniform<double>(9, i, 2), 0.05, 1});
    benchmark::DoNotOptimize(kemppinen_eval(p, ggx, fp, h).d.x);
    ++i;
  }
  state.counters["points_visited"] = 2.0 * std::pow(double(state.range(0)), 4);
}
BENCHMARK(BM_KemppinenEval)
    ->ArgsProduct({{1, 2, 3, 4}, {1, 16, 256, 4096}, {0, 1}})
    ->ArgNames({"side", "footprint_cells", "erf"});

// The brute-force Eq. 5 over the same footprints: cost grows with the footprint's area.
void BM_KemppinenBruteForce(benchmark::State& state) {
  const KemppinenParams<double> p = bench_params(1, KemppinenErf::kExact);
  const double d = double(state.range(0)) / std::sqrt(p.density) / p.filter;
  const GGX<double> ggx{0.3, 0.3};
  std::uint64_t i = 0;
  for (auto _ : state) {
    const FootprintQuery<double> fp{
        {counter_uniform<double>(9, i, 0) * 100, counter_uniform<double>(9, i, 1) * 100},
        {d, 0},
        {0, d}};
    benchmark::DoNotOptimize(
        kemppinen_reference_filtered(p, ggx, fp, normalize(Vec3<double>{0.1, 0.05, 1})).x);
    ++i;
  }
}
BENCHMARK(BM_KemppinenBruteForce)->Arg(1)->Arg(4)->Arg(16)->ArgName("footprint_cells");

}  // namespace

BENCHMARK_MAIN();

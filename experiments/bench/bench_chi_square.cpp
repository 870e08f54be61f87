// Google Benchmark of verify's chi-square goodness-of-fit (verify/claims/gof_family.h) with 10^7
// samples for one configuration of smooth.sampler-matches-pdf: the plan (adaptive cubature of the
// expected counts) and the run (sampling + binning + statistic), samples drawn by the scalar
// sampler or by the batched one (core/simd sample_batch) that the claim uses. Goal: under 2 s on
// 2 cores with the batched samplers.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <string>

#include "verify/check.h"
#include "verify/claims/gof_family.h"

namespace glintlab::verify::bench {
namespace {

constexpr std::uint64_t kSamples = 10000000;

// The first configuration of the quick grid whose label starts with `prefix`.
const GofCase& config(const std::string& prefix) {
  static const GofSpec spec = smooth_sampler_spec(Budget::kQuick);
  for (const GofCase& c : spec.cases)
    if (c.label.starts_with(prefix)) return c;
  return spec.cases.front();
}

void bm_chi_square(benchmark::State& state, std::string prefix, bool batched, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  GofCase c = config(prefix);
  if (!batched) c.direction_batch = nullptr;
  std::string summary;
  for (auto _ : state) {
    const ChiSquarePlan plan = plan_gof_case(c, kSamples, 1e-3);
    const ChiSquareResult r = run_gof_case(plan, c, 1);
    summary = r.summary();
    benchmark::DoNotOptimize(summary.data());
  }
  state.SetLabel(c.label + ": " + summary);
}

}  // namespace
}  // namespace glintlab::verify::bench

int main(int argc, char** argv) {
  using glintlab::verify::bench::bm_chi_square;
  benchmark::Initialize(&argc, argv);
  for (const char* s : {"heitz_vndf/ggx", "beckmann_vndf/beckmann"})
    for (bool batched : {false, true})
      for (int threads : {1, 2})
        benchmark::RegisterBenchmark(
            ("verify_chi_square_1e7/" + std::string(s) + "/" + (batched ? "batched" : "scalar") +
             "/threads:" + std::to_string(threads))
                .c_str(),
            bm_chi_square, std::string(s), batched, threads)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->Iterations(1);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

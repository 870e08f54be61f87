// The Table 3 analogue of Kemppinen et al. 2025 as whole frames through the model batches
// (experiments/bench/kemppinen2025_table3_frame.h): per cell, precision and ISA, the wall time of
// one 1920×1080 frame with 3 point lights on every core (TBB's default), one iteration per
// repetition (a Kemppinen frame takes seconds): real_time is the ms per frame, cpu_time the CPU
// time of every thread of the process (on a shared machine: the frame's cost without the wait). Beside
// glintlab_bench_kemppinen's table3/ rows (ns per pixel, one core, scalar double), which give the
// frame time of the scalar path.
//   glintlab_bench_kemppinen_frame [--benchmark_filter=...] [--benchmark_repetitions=N]
//     [--isa=scalar|sse4.2|avx2|avx512 (default: the widest this CPU has)]
#include <benchmark/benchmark.h>
#include <tbb/info.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "core/simd/batch.h"
#include "experiments/bench/kemppinen2025_table3_frame.h"

namespace {

namespace kt3 = glintlab::kemppinen_table3;
namespace simd = glintlab::simd;

template <class T>
void BM_Table3Frame(benchmark::State& state, kt3::Cell cell, simd::Isa isa) {
  std::vector<T> frame(kt3::kPixels);
  for (auto _ : state) {
    kt3::render_pixels<T>(cell, 0, kt3::kPixels, isa, frame.data());
    benchmark::DoNotOptimize(frame.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(kt3::kPixels));
  state.SetLabel(std::string("1920x1080, 3 lights, batched ") +
                 (sizeof(T) == 4 ? "float" : "double") + " " + std::string(simd::isa_name(isa)) +
                 ", " + std::to_string(tbb::info::default_concurrency()) + " threads");
}

void register_frames(simd::Isa isa) {
  for (const kt3::Cell& c : kt3::cells()) {
    for (bool single : {true, false}) {
      const std::string name = "table3_frame" + kt3::cell_name(c).substr(std::strlen("table3")) +
                               "/precision:" + (single ? "float" : "double") +
                               "/isa:" + std::string(simd::isa_name(isa));
      auto* b = single ? benchmark::RegisterBenchmark(name.c_str(), BM_Table3Frame<float>, c, isa)
                       : benchmark::RegisterBenchmark(name.c_str(), BM_Table3Frame<double>, c, isa);
      b->Iterations(1)->UseRealTime()->MeasureProcessCPUTime()->Unit(benchmark::kMillisecond);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  simd::Isa isa = simd::best_isa();
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--isa=", 6) != 0) continue;
    const std::string name = argv[i] + 6;
    bool found = false;
    for (simd::Isa k :
         {simd::Isa::kScalar, simd::Isa::kSse42, simd::Isa::kAvx2, simd::Isa::kAvx512})
      if (simd::isa_name(k) == name && simd::isa_supported(k)) {
        isa = k;
        found = true;
      }
    if (!found) {
      std::fprintf(stderr,
                   "glintlab: error: --isa: '%s' is not an ISA this CPU has (valid: scalar, "
                   "sse4.2, avx2, avx512, as supported)\n",
                   name.c_str());
      return 2;
    }
    for (int j = i; j + 1 < argc; ++j) argv[j] = argv[j + 1];
    --argc;
    --i;
  }
  register_frames(isa);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

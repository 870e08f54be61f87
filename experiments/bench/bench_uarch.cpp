// Google Benchmark of this CPU's floating-point throughput per instruction width (scalar, 128-bit
// SSE, 256-bit AVX): division and multiplication, the ceilings behind the kernels' speed-ups.
#include <benchmark/benchmark.h>
#include <immintrin.h>

#include <cstdint>

// Eight independent chains x ← x op d, 16 rounds per benchmark iteration (so the benchmark loop's
// own cost, ~4.5 ns here, stays out of the multiply rows), kept in registers (the empty asm marks
// them live without a memory round trip): the unit's throughput, not its latency.
// d = 1 + 2^-23: ~7·10^8 rounds per chain before a value leaves the normal range (seconds).
namespace {

// (A macro rather than a template: the 256-bit bodies must be expanded inside the functions that
// carry the AVX target attribute.)
constexpr int kRounds = 16;

#define GLINTLAB_CHAINS(OP, D, INIT)                                                             \
  {                                                                                              \
    auto a0 = INIT, a1 = INIT, a2 = INIT, a3 = INIT, a4 = INIT, a5 = INIT, a6 = INIT, a7 = INIT; \
    const auto d = D;                                                                            \
    for (auto _ : state) {                                                                       \
      for (int r = 0; r < kRounds; ++r) {                                                        \
        a0 = OP(a0, d);                                                                          \
        a1 = OP(a1, d);                                                                          \
        a2 = OP(a2, d);                                                                          \
        a3 = OP(a3, d);                                                                          \
        a4 = OP(a4, d);                                                                          \
        a5 = OP(a5, d);                                                                          \
        a6 = OP(a6, d);                                                                          \
        a7 = OP(a7, d);                                                                          \
        asm volatile(""                                                                          \
                     : "+x"(a0), "+x"(a1), "+x"(a2), "+x"(a3), "+x"(a4), "+x"(a5), "+x"(a6),     \
                       "+x"(a7));                                                                \
      }                                                                                          \
    }                                                                                            \
    benchmark::DoNotOptimize(a0);                                                                \
  }

void finish(benchmark::State& state, int lanes) {
  const double instructions = 8.0 * kRounds * double(state.iterations());
  state.SetItemsProcessed(static_cast<std::int64_t>(instructions));
  state.counters["lanes"] = lanes;
  // Seconds per lane-operation as a rate counter inverted: lane operations per second.
  state.counters["lane_ops_per_second"] =
      benchmark::Counter(instructions * lanes, benchmark::Counter::kIsRate);
}

constexpr float kD = 1.00000012f;  // 1 + 2^-23

void bm_divss(benchmark::State& state) {
  GLINTLAB_CHAINS(_mm_div_ss, _mm_set_ss(kD), _mm_set_ss(1.5f));
  finish(state, 1);
}
void bm_divps128(benchmark::State& state) {
  GLINTLAB_CHAINS(_mm_div_ps, _mm_set1_ps(kD), _mm_set1_ps(1.5f));
  finish(state, 4);
}
void bm_mulss(benchmark::State& state) {
  GLINTLAB_CHAINS(_mm_mul_ss, _mm_set_ss(kD), _mm_set_ss(1.5f));
  finish(state, 1);
}
void bm_mulps128(benchmark::State& state) {
  GLINTLAB_CHAINS(_mm_mul_ps, _mm_set1_ps(kD), _mm_set1_ps(1.5f));
  finish(state, 4);
}
__attribute__((target("avx"))) void bm_divps256(benchmark::State& state) {
  GLINTLAB_CHAINS(_mm256_div_ps, _mm256_set1_ps(kD), _mm256_set1_ps(1.5f));
  finish(state, 8);
}
__attribute__((target("avx"))) void bm_mulps256(benchmark::State& state) {
  GLINTLAB_CHAINS(_mm256_mul_ps, _mm256_set1_ps(kD), _mm256_set1_ps(1.5f));
  finish(state, 8);
}
#undef GLINTLAB_CHAINS

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RegisterBenchmark("uarch/div/scalar", bm_divss);
  benchmark::RegisterBenchmark("uarch/div/sse128", bm_divps128);
  benchmark::RegisterBenchmark("uarch/mul/scalar", bm_mulss);
  benchmark::RegisterBenchmark("uarch/mul/sse128", bm_mulps128);
  if (__builtin_cpu_supports("avx")) {
    benchmark::RegisterBenchmark("uarch/div/avx256", bm_divps256);
    benchmark::RegisterBenchmark("uarch/mul/avx256", bm_mulps256);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// Google Benchmark of this CPU's floating-point throughput per instruction width (scalar, 128-bit
// SSE, 256-bit AVX): division and multiplication, the ceilings behind the kernels' speed-ups; and
// the FLOP peak of one core per ISA and precision (uarch/peak/...), which scripts/simd_tables.py
// divides the kernels' counted FLOP rates by (the roofline fraction of the same run).
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

// --- The FLOP peak per ISA --------------------------------------------------------------------
// What the arithmetic units sustain with no dependency stalls: 12 independent chains (more than
// latency × pipes: 4 cycles × 2 FMA pipes on current x86 cores), 32 rounds per benchmark iteration,
// in registers. Per ISA the instructions its kernels are built with: scalar (no -mfma) and SSE4.2
// have no FMA, so their peak is mulss/mulps on 6 chains interleaved with addss/addps on 6 (1 FLOP
// each, on the separate multiply and add pipes); AVX2 and AVX-512 run vfmadd (2 FLOPs). Counter
// flops_per_second = instructions × lanes × FLOPs per instruction.
constexpr int kPeakRounds = 32;

#define GLINTLAB_PEAK_CHAINS(OP_A, OP_B, D, E, INIT, CONSTRAINT)                                 \
  {                                                                                              \
    auto a0 = INIT, a1 = INIT, a2 = INIT, a3 = INIT, a4 = INIT, a5 = INIT, a6 = INIT, a7 = INIT; \
    auto a8 = INIT, a9 = INIT, a10 = INIT, a11 = INIT;                                           \
    const auto d = D;                                                                            \
    const auto e = E;                                                                            \
    for (auto _ : state) {                                                                       \
      for (int r = 0; r < kPeakRounds; ++r) {                                                    \
        a0 = OP_A(a0, d, e);                                                                     \
        a1 = OP_B(a1, d, e);                                                                     \
        a2 = OP_A(a2, d, e);                                                                     \
        a3 = OP_B(a3, d, e);                                                                     \
        a4 = OP_A(a4, d, e);                                                                     \
        a5 = OP_B(a5, d, e);                                                                     \
        a6 = OP_A(a6, d, e);                                                                     \
        a7 = OP_B(a7, d, e);                                                                     \
        a8 = OP_A(a8, d, e);                                                                     \
        a9 = OP_B(a9, d, e);                                                                     \
        a10 = OP_A(a10, d, e);                                                                   \
        a11 = OP_B(a11, d, e);                                                                   \
        asm volatile("" : CONSTRAINT(a0), CONSTRAINT(a1), CONSTRAINT(a2), CONSTRAINT(a3),        \
                     CONSTRAINT(a4), CONSTRAINT(a5), CONSTRAINT(a6), CONSTRAINT(a7),             \
                     CONSTRAINT(a8), CONSTRAINT(a9), CONSTRAINT(a10), CONSTRAINT(a11));          \
      }                                                                                          \
    }                                                                                            \
  }
#define GLINTLAB_XMM(a) "+x"(a)
#define GLINTLAB_ZMM(a) "+v"(a)

void finish_peak(benchmark::State& state, int lanes, double flops_per_instruction) {
  const double instructions = 12.0 * kPeakRounds * double(state.iterations());
  state.SetItemsProcessed(static_cast<std::int64_t>(instructions));
  state.counters["lanes"] = lanes;
  state.counters["flops_per_instruction"] = flops_per_instruction;
  state.counters["flops_per_second"] =
      benchmark::Counter(instructions * lanes * flops_per_instruction, benchmark::Counter::kIsRate);
}

// x·d and x + e with d = 1 + 2^-23 (2^-52) and e = 2^-20: values stay normal for ~10^9 rounds.
// The fma form x·d + e with d just below 1 converges to e / (1 − d), also normal.
constexpr double kGrowD = 1.0000000000000002;
constexpr float kGrowF = 1.00000012f;
constexpr float kShrinkF = 0.99999994f;
constexpr double kShrinkD = 0.99999999999999989;
constexpr double kStep = 9.5367431640625e-07;

inline __m128 mul_ss(__m128 x, __m128 d, __m128) { return _mm_mul_ss(x, d); }
inline __m128 add_ss(__m128 x, __m128, __m128 e) { return _mm_add_ss(x, e); }
inline __m128d mul_sd(__m128d x, __m128d d, __m128d) { return _mm_mul_sd(x, d); }
inline __m128d add_sd(__m128d x, __m128d, __m128d e) { return _mm_add_sd(x, e); }
inline __m128 mul_ps(__m128 x, __m128 d, __m128) { return _mm_mul_ps(x, d); }
inline __m128 add_ps(__m128 x, __m128, __m128 e) { return _mm_add_ps(x, e); }
inline __m128d mul_pd(__m128d x, __m128d d, __m128d) { return _mm_mul_pd(x, d); }
inline __m128d add_pd(__m128d x, __m128d, __m128d e) { return _mm_add_pd(x, e); }

void bm_peak_scalar_float(benchmark::State& state) {
  GLINTLAB_PEAK_CHAINS(mul_ss, add_ss, _mm_set_ss(kGrowF), _mm_set_ss(float(kStep)),
                       _mm_set_ss(1.5f), GLINTLAB_XMM);
  finish_peak(state, 1, 1.0);
}
void bm_peak_scalar_double(benchmark::State& state) {
  GLINTLAB_PEAK_CHAINS(mul_sd, add_sd, _mm_set_sd(kGrowD), _mm_set_sd(kStep), _mm_set_sd(1.5),
                       GLINTLAB_XMM);
  finish_peak(state, 1, 1.0);
}
void bm_peak_sse_float(benchmark::State& state) {
  GLINTLAB_PEAK_CHAINS(mul_ps, add_ps, _mm_set1_ps(kGrowF), _mm_set1_ps(float(kStep)),
                       _mm_set1_ps(1.5f), GLINTLAB_XMM);
  finish_peak(state, 4, 1.0);
}
void bm_peak_sse_double(benchmark::State& state) {
  GLINTLAB_PEAK_CHAINS(mul_pd, add_pd, _mm_set1_pd(kGrowD), _mm_set1_pd(kStep),
                       _mm_set1_pd(1.5), GLINTLAB_XMM);
  finish_peak(state, 2, 1.0);
}
// (Functions, not lambdas: a lambda does not inherit its enclosing function's target attribute.)
__attribute__((target("avx2,fma"))) inline __m256 fma_ps256(__m256 x, __m256 d, __m256 e) {
  return _mm256_fmadd_ps(x, d, e);
}
__attribute__((target("avx2,fma"))) inline __m256d fma_pd256(__m256d x, __m256d d, __m256d e) {
  return _mm256_fmadd_pd(x, d, e);
}
__attribute__((target("avx512f"))) inline __m512 fma_ps512(__m512 x, __m512 d, __m512 e) {
  return _mm512_fmadd_ps(x, d, e);
}
__attribute__((target("avx512f"))) inline __m512d fma_pd512(__m512d x, __m512d d, __m512d e) {
  return _mm512_fmadd_pd(x, d, e);
}
__attribute__((target("avx2,fma"))) void bm_peak_avx2_float(benchmark::State& state) {
  GLINTLAB_PEAK_CHAINS(fma_ps256, fma_ps256,
                       _mm256_set1_ps(kShrinkF), _mm256_set1_ps(float(kStep)),
                       _mm256_set1_ps(1.5f), GLINTLAB_XMM);
  finish_peak(state, 8, 2.0);
}
__attribute__((target("avx2,fma"))) void bm_peak_avx2_double(benchmark::State& state) {
  GLINTLAB_PEAK_CHAINS(fma_pd256, fma_pd256,
                       _mm256_set1_pd(kShrinkD), _mm256_set1_pd(kStep), _mm256_set1_pd(1.5),
                       GLINTLAB_XMM);
  finish_peak(state, 4, 2.0);
}
__attribute__((target("avx512f"))) void bm_peak_avx512_float(benchmark::State& state) {
  GLINTLAB_PEAK_CHAINS(fma_ps512, fma_ps512,
                       _mm512_set1_ps(kShrinkF), _mm512_set1_ps(float(kStep)),
                       _mm512_set1_ps(1.5f), GLINTLAB_ZMM);
  finish_peak(state, 16, 2.0);
}
__attribute__((target("avx512f"))) void bm_peak_avx512_double(benchmark::State& state) {
  GLINTLAB_PEAK_CHAINS(fma_pd512, fma_pd512,
                       _mm512_set1_pd(kShrinkD), _mm512_set1_pd(kStep), _mm512_set1_pd(1.5),
                       GLINTLAB_ZMM);
  finish_peak(state, 8, 2.0);
}
#undef GLINTLAB_PEAK_CHAINS
#undef GLINTLAB_XMM
#undef GLINTLAB_ZMM

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
  // uarch/peak/<isa>/<precision>: names as core/simd's isa_name, so a kernel row's ISA finds its
  // peak.
  benchmark::RegisterBenchmark("uarch/peak/scalar/float", bm_peak_scalar_float);
  benchmark::RegisterBenchmark("uarch/peak/scalar/double", bm_peak_scalar_double);
  benchmark::RegisterBenchmark("uarch/peak/sse4.2/float", bm_peak_sse_float);
  benchmark::RegisterBenchmark("uarch/peak/sse4.2/double", bm_peak_sse_double);
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    benchmark::RegisterBenchmark("uarch/peak/avx2/float", bm_peak_avx2_float);
    benchmark::RegisterBenchmark("uarch/peak/avx2/double", bm_peak_avx2_double);
  }
  if (__builtin_cpu_supports("avx512f")) {
    benchmark::RegisterBenchmark("uarch/peak/avx512/float", bm_peak_avx512_float);
    benchmark::RegisterBenchmark("uarch/peak/avx512/double", bm_peak_avx512_double);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

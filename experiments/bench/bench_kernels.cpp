// Google Benchmark suite of the batch API: items/s of every kernel × ISA × {exact, fast}, its
// counted FLOPs and FLOP rate, and the batched 10^7-sample chi-square workload. The roofline
// fraction (FLOP rate over this core's peak for the row's ISA, measured in the same run by
// bench_uarch.cpp's uarch/peak rows) is added by scripts/simd_tables.py annotate.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "core/math/rng.h"
#include "core/simd/batch.h"
#include "core/simd/inputs.h"
#include "core/simd/kernels.h"
#include "experiments/bench/flop_count.h"

namespace glintlab::simd::bench {
namespace {

using glintlab::bench::Counted;
using glintlab::bench::g_flops;

// --- The machine, for the JSON context --------------------------------------------------------
struct Cpu {
  std::string model = "unknown";
  double mhz = 0.0;
};
const Cpu& cpu() {
  static const Cpu c = [] {
    Cpu r;
    std::ifstream f("/proc/cpuinfo");
    std::string line;
    while (std::getline(f, line)) {
      const auto value = [&] { return line.substr(line.find(':') + 2); };
      if (r.model == "unknown" && line.rfind("model name", 0) == 0) r.model = value();
      if (r.mhz == 0.0 && line.rfind("cpu MHz", 0) == 0) r.mhz = std::stod(value());
    }
    return r;
  }();
  return c;
}

// --- FLOPs per evaluation, counted by instantiating each kernel on Counted -----------------
template <class K>
double count_flops() {
  std::vector<int> domains;
  for (auto d : K::kIn) domains.push_back(static_cast<int>(d));
  constexpr std::size_t kRows = 64;
  const auto cols = make_inputs(domains, kRows, 7);
  g_flops.flops = 0;
  for (std::size_t i = 0; i < kRows; ++i) {
    Counted x[K::kIn.size()];
    Counted y[K::kOut.size()];
    for (std::size_t j = 0; j < K::kIn.size(); ++j) x[j] = Counted(cols[j][i]);
    K::template eval<Counted>(x, y);
  }
  return double(g_flops.flops) / double(kRows);
}
const std::vector<double>& flops_per_eval() {
#define GLINTLAB_FLOPS(K) count_flops<K>(),
  static const std::vector<double> f = {GLINTLAB_SIMD_KERNELS(GLINTLAB_FLOPS)};
#undef GLINTLAB_FLOPS
  return f;
}

// --- Kernel throughput ----------------------------------------------------------------------
// Three working sets (docs/simd.md "Speed-ups" has what each measured on this machine):
//   kernel/isa/flavour       the CLI's chunk: 4096 rows per call on the same 4096 rows, which with
//                            every column (e.g. ggx.d: 5 + 1 floats = 96 KiB) sit in L2, not L1;
//   l1/kernel/isa/flavour    rows per call such that every column fits in half of a 32 KiB L1d
//                            (a power of two, 64 … 4096), reused: the cache-resident bound;
//   stream/kernel/isa/flavour  4096-row calls walking through 2^20 rows (ggx.d: 24 MiB, above
//                            the 8 MiB L3), so the columns come from memory: the streaming bound.
// Rows are make_inputs' 4096 rows (repeated for the streaming set), so the values are the same.
constexpr std::size_t kN = 4096;  // rows per call (the CLI's chunk)
constexpr std::size_t kStreamRows = std::size_t(1) << 20;
constexpr std::size_t kL1Bytes = 16 * 1024;

enum class WorkingSet { kChunk, kL1, kStream };

std::size_t l1_rows(int kernel, std::size_t scalar_bytes) {
  const KernelInfo info = kernel_info(kernel);
  const std::size_t row_bytes = scalar_bytes * (info.inputs.size() + info.outputs.size());
  std::size_t rows = 64;
  while (rows * 2 * row_bytes <= kL1Bytes && rows * 2 <= kN) rows *= 2;
  return rows;
}

template <class S>
struct Data {
  std::vector<std::vector<S>> in, out;
};
// One data set per (kernel, precision, rows), kept while consecutive benchmarks use it (the
// streaming sets are tens of MiB; rebuilding them for every run would dominate the suite).
template <class S>
Data<S>& data_for(int kernel, std::size_t rows) {
  static int cached_kernel = -1;
  static std::size_t cached_rows = 0;
  static Data<S> r;
  if (cached_kernel == kernel && cached_rows == rows) return r;
  const KernelInfo info = kernel_info(kernel);
  const auto d = make_inputs(info.inputs, kN, hash_string("experiments/bench"));
  r.in.assign(d.size(), std::vector<S>(rows));
  for (std::size_t j = 0; j < d.size(); ++j) {
    for (std::size_t i = 0; i < rows; ++i) r.in[j][i] = static_cast<S>(d[j][i % kN]);
  }
  r.out.assign(info.outputs.size(), std::vector<S>(rows));
  cached_kernel = kernel;
  cached_rows = rows;
  return r;
}

template <class S>
void bm_kernel(benchmark::State& state, int kernel, Isa isa, Math math, WorkingSet ws) {
  const std::size_t call = ws == WorkingSet::kL1 ? l1_rows(kernel, sizeof(S)) : kN;
  const std::size_t rows = ws == WorkingSet::kStream ? kStreamRows : call;
  Data<S>& d = data_for<S>(kernel, rows);
  std::vector<Column<S>> cols(d.in.size());
  std::vector<S*> outs(d.out.size());
  std::size_t at = 0;  // first row of this call (advances only in the streaming set)
  for (auto _ : state) {
    for (std::size_t j = 0; j < cols.size(); ++j) cols[j] = {d.in[j].data() + at, 1};
    for (std::size_t k = 0; k < outs.size(); ++k) outs[k] = d.out[k].data() + at;
    eval_batch(kernel, std::span<const Column<S>>(cols), std::span<S* const>(outs), call, isa,
               math);
    benchmark::DoNotOptimize(outs[0]);
    benchmark::ClobberMemory();
    at = at + call < rows ? at + call : 0;
  }
  const double items = double(state.iterations()) * double(call);
  const double flops = flops_per_eval()[kernel];
  state.SetItemsProcessed(static_cast<std::int64_t>(items));
  state.counters["flops_per_item"] = flops;
  state.counters["gflops"] = benchmark::Counter(items * flops * 1e-9, benchmark::Counter::kIsRate);
  state.counters["lanes"] = double(lanes(isa, sizeof(S) == 8));
  state.counters["rows_per_call"] = double(call);
  state.counters["working_set_bytes"] = double(rows * (d.in.size() + d.out.size()) * sizeof(S));
}

// --- The chi-square workload: 10^7 samples of one configuration, binned, on 2 threads -------
// Heitz VNDF on GGX αx = 0.3, αy = 0.15, θi = 60° (float). Per chunk of 2^16 samples: counter
// uniforms, sample_batch, bin wo into 32 (cosθ) × 64 (φ) cells; chunk histograms are summed in
// chunk order (deterministic for any thread count). Then the expected counts by a 4×4 midpoint
// rule per cell on the batched pdf, and Pearson's statistic over the cells with ≥ 5 expected.
constexpr std::size_t kSamples = 10000000;
constexpr int kThetaBins = 32, kPhiBins = 64, kCells = kThetaBins * kPhiBins;
constexpr std::size_t kChunk = std::size_t(1) << 16;

int cell_of(float x, float y, float z) {
  if (!(z > 0.0f)) return -1;
  const int t = std::min(kThetaBins - 1, static_cast<int>(z * kThetaBins));
  float phi = std::atan2(y, x);
  if (phi < 0.0f) phi += 6.2831853f;
  const int p = std::min(kPhiBins - 1, static_cast<int>(phi * (kPhiBins / 6.2831853f)));
  return t * kPhiBins + p;
}

void bm_chi_square(benchmark::State& state, Isa isa, int threads) {
  const int sampler = *find_kernel("sample.heitz_vndf/ggx");
  const int pdf = *find_kernel("pdf.heitz_vndf/ggx");
  const float wi[3] = {0.8660254f, 0.0f, 0.5f};
  const std::size_t chunks = (kSamples + kChunk - 1) / kChunk;
  double statistic = 0.0;
  for (auto _ : state) {
    std::vector<std::vector<std::uint32_t>> hist(chunks, std::vector<std::uint32_t>(kCells));
    const auto worker = [&](int t) {
      std::vector<float> u1(kChunk), u2(kChunk), o[8];
      for (auto& v : o) v.resize(kChunk);
      for (std::size_t c = std::size_t(t); c < chunks; c += std::size_t(threads)) {
        const std::size_t begin = c * kChunk, n = std::min(kChunk, kSamples - begin);
        for (std::size_t i = 0; i < n; ++i) {
          u1[i] = counter_uniform<float>(1, begin + i, 0);
          u2[i] = counter_uniform<float>(1, begin + i, 1);
        }
        sample_batch<float>(sampler, 0.3f, 0.15f, wi, u1.data(), u2.data(),
                            {o[0].data(), o[1].data(), o[2].data(), o[3].data(), o[4].data(),
                             o[5].data(), o[6].data(), o[7].data()},
                            n, isa);
        for (std::size_t i = 0; i < n; ++i) {
          if (o[7][i] != 0.0f) continue;
          const int cell = cell_of(o[0][i], o[1][i], o[2][i]);
          if (cell >= 0) ++hist[c][std::size_t(cell)];
        }
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker, t);
    worker(0);
    for (auto& th : pool) th.join();
    std::vector<double> observed(kCells, 0.0);
    for (const auto& h : hist) {
      for (int c = 0; c < kCells; ++c) observed[std::size_t(c)] += h[std::size_t(c)];
    }
    // Expected counts: 4×4 midpoints per cell in (cosθ, φ), dω = dcosθ dφ.
    constexpr int kSub = 4;
    const std::size_t m = std::size_t(kCells) * kSub * kSub;
    std::vector<float> x(m), y(m), z(m), p(m);
    for (int c = 0; c < kCells; ++c) {
      for (int s = 0; s < kSub * kSub; ++s) {
        const float ct = (float(c / kPhiBins) + (float(s / kSub) + 0.5f) / kSub) / kThetaBins;
        const float ph =
            (float(c % kPhiBins) + (float(s % kSub) + 0.5f) / kSub) * (6.2831853f / kPhiBins);
        const float st = std::sqrt(std::max(0.0f, 1.0f - ct * ct));
        const std::size_t i = std::size_t(c) * kSub * kSub + std::size_t(s);
        x[i] = st * std::cos(ph);
        y[i] = st * std::sin(ph);
        z[i] = ct;
      }
    }
    const float params[5] = {0.3f, 0.15f, wi[0], wi[1], wi[2]};
    const float* cols[3] = {x.data(), y.data(), z.data()};
    float* outs[1] = {p.data()};
    eval_batch<float>(pdf, params, cols, outs, m, isa);
    const double cell_area = (1.0 / kThetaBins) * (6.283185307179586 / kPhiBins) / (kSub * kSub);
    statistic = 0.0;
    for (int c = 0; c < kCells; ++c) {
      double e = 0.0;
      for (int s = 0; s < kSub * kSub; ++s) e += p[std::size_t(c) * kSub * kSub + std::size_t(s)];
      e *= cell_area * double(kSamples);
      if (e >= 5.0)
        statistic += (observed[std::size_t(c)] - e) * (observed[std::size_t(c)] - e) / e;
    }
    benchmark::DoNotOptimize(statistic);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kSamples));
  state.counters["samples"] = double(kSamples);
  state.counters["threads"] = threads;
  state.counters["chi2_statistic"] = statistic;
  state.counters["cells"] = kCells;
}

void register_all() {
  for (int k = 0; k < kernel_count(); ++k) {
    const std::string name(kernel_info(k).name);
    for (Isa isa : kAllIsas) {
      if (!isa_supported(isa)) continue;
      const std::string i(isa_name(isa));
      benchmark::RegisterBenchmark((name + "/" + i + "/float_exact").c_str(), bm_kernel<float>, k,
                                   isa, Math::kExact, WorkingSet::kChunk);
      benchmark::RegisterBenchmark((name + "/" + i + "/float_fast").c_str(), bm_kernel<float>, k,
                                   isa, Math::kFast, WorkingSet::kChunk);
      benchmark::RegisterBenchmark((name + "/" + i + "/double_exact").c_str(), bm_kernel<double>, k,
                                   isa, Math::kExact, WorkingSet::kChunk);
    }
    // The other working sets for the speed-up over scalar float exact only (scalar and the best
    // ISA, exact and fast): enough to tell compute from memory bounds, at a third of the time.
    for (const auto& [prefix, ws] :
         {std::pair{"l1/", WorkingSet::kL1}, std::pair{"stream/", WorkingSet::kStream}}) {
      const std::string b(isa_name(best_isa()));
      benchmark::RegisterBenchmark((prefix + name + "/scalar/float_exact").c_str(),
                                   bm_kernel<float>, k, Isa::kScalar, Math::kExact, ws);
      benchmark::RegisterBenchmark((prefix + name + "/" + b + "/float_exact").c_str(),
                                   bm_kernel<float>, k, best_isa(), Math::kExact, ws);
      benchmark::RegisterBenchmark((prefix + name + "/" + b + "/float_fast").c_str(),
                                   bm_kernel<float>, k, best_isa(), Math::kFast, ws);
    }
  }
  for (Isa isa : {Isa::kScalar, best_isa()}) {
    for (int threads : {1, 2}) {
      benchmark::RegisterBenchmark(("chi_square_1e7/heitz_vndf/" + std::string(isa_name(isa)) +
                                    "/threads:" + std::to_string(threads))
                                       .c_str(),
                                   bm_chi_square, isa, threads)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->Iterations(1);
    }
  }
}

}  // namespace
}  // namespace glintlab::simd::bench

int main(int argc, char** argv) {
  using namespace glintlab::simd::bench;
  benchmark::Initialize(&argc, argv);
  benchmark::AddCustomContext("cpu_model", cpu().model);
  benchmark::AddCustomContext("cpu_mhz_proc_cpuinfo", std::to_string(cpu().mhz));
  benchmark::AddCustomContext("roofline_peak",
                              "uarch/peak/<isa>/<precision> of bench_uarch.cpp, measured in the "
                              "same scripts/bench.sh run (scripts/simd_tables.py annotate)");
  benchmark::AddCustomContext("best_isa",
                              std::string(glintlab::simd::isa_name(glintlab::simd::best_isa())));
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

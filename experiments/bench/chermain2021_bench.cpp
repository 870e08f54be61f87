// Table 1 analogue of Chermain et al. 2021 (cost of GGAA against no GGAA): Google Benchmark of
// the patch-SDF evaluation (textureLod vs textureGrad lookups, Eq. 3 vs Eq. 10/19) and of a 1-spp
// frame of the tube scene, single thread. Run:
//   build/release/experiments/bench/glintlab_bench_chermain --benchmark_out=out/bench/chermain.json
//   --benchmark_out_format=json
// Paper (RTX 2080, 1920×1080, OpenGL): +0.6 % to +4.2 % frame time with GGAA.
// Method rows (experiments/bench/METHOD_BENCHMARKS.md): the filtered patch-SDF P22 against the
// dictionary's texel resolution and its number of levels L, each against a finer dictionary, and
// the tube frame with GGAA off / Eq. 20 / Eq. 21 (and plain supersampling) against the
// supersampled pixel integral of chermain.ggaa-error.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "core/glints/chermain.h"
#include "core/math/rng.h"
#include "experiments/bench/method_bench.h"
#include "verify/scenes/chermain_scenes.h"

namespace glintlab {
namespace {

struct Input {
  Vec2<double> m;
  FootprintQuery<double> fp;
  chermain2021::SlopeDerivatives d;
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
  const chermain2021::SdfParams p{
      &chermain2021::default_chermain_dictionary(), 0.25, 0.25, 0.3, 30, kernel, 0.5, 1};
  for (auto _ : state) {
    double s = 0;
    for (const Input& x : in) s += chermain2021::patch_sdf(p, x.m, x.fp, x.d);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(in.size()));
}

void tube_frame(benchmark::State& state, int kernel) {
  verify::TubeSceneOptions o;
  o.width = 128, o.height = 86, o.threads = 1;
  chermain2021::default_chermain_dictionary();
  for (auto _ : state) benchmark::DoNotOptimize(verify::render_tubes(o, kernel, 0.5));
  state.SetItemsProcessed(std::int64_t(state.iterations()) * o.width * o.height);
}

BENCHMARK_CAPTURE(patch_sdf, no_ggaa, chermain2021::kNoGgaa);
BENCHMARK_CAPTURE(patch_sdf, ggaa, chermain2021::kProjectedHalf);
BENCHMARK_CAPTURE(tube_frame, no_ggaa, chermain2021::kNoGgaa)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(tube_frame, ggaa, chermain2021::kProjectedHalf)->Unit(benchmark::kMillisecond);

// --- Method rows: P22 against the dictionary's resolution and levels -------------------------
// Queries: slopes m̃ drawn from the smooth SDF N(0, Σ) (α = 0.5, where P22 has its mass),
// isotropic footprints of side 2^l with l uniform so that the dictionary level k = ⌊l + ½ log2
// density⌋ covers [0, k_max), uv uniform over 16 × 16, and GGAA derivatives as patch_sdf's.
// Relative error |P − P_ref| / max(|P_ref|, 1e-3 · P22_smooth(0)).
struct SdfQuery {
  Vec2<double> m;
  FootprintQuery<double> fp;
  chermain2021::SlopeDerivatives d;
};

constexpr double kQueryAlpha = 0.5, kLog2Density = 10;

std::vector<SdfQuery> sdf_queries(const std::string& method, int count, int k_max) {
  const std::uint64_t seed = bench::method_seed(method);
  const double sigma = kQueryAlpha / std::sqrt(2.0);
  std::vector<SdfQuery> q;
  for (std::uint64_t i = 0; i < std::uint64_t(count); ++i) {
    const auto u = [&](int dim) { return counter_uniform<double>(seed, i, std::uint64_t(dim)); };
    const double r = sigma * std::sqrt(-2 * std::log(1 - u(0))), phi = 2 * kPi<double> * u(1);
    const double l = -0.5 * kLog2Density + k_max * u(2);
    const double foot = std::exp2(l);
    q.push_back(
        {{r * std::cos(phi), r * std::sin(phi)},
         {{16 * u(3), 16 * u(4)}, {foot, 0}, {0, foot}},
         {0.05 * (u(5) - 0.5), 0.05 * (u(6) - 0.5), 0.05 * (u(7) - 0.5), 0.05 * (u(8) - 0.5)}});
  }
  return q;
}

chermain2021::SdfParams sdf_params(const chermain2021::Dictionary* d, int kernel) {
  const double sigma = kQueryAlpha / std::sqrt(2.0);
  return {d, sigma, sigma, 0.0, kLog2Density, kernel, 0.5, 1};
}

std::vector<double> eval_sdf(const chermain2021::SdfParams& p, const std::vector<SdfQuery>& q) {
  std::vector<double> v;
  v.reserve(q.size());
  for (const SdfQuery& x : q) v.push_back(chermain2021::patch_sdf(p, x.m, x.fp, x.d));
  return v;
}

bench::ErrorStats sdf_errors(const std::vector<double>& v, const std::vector<double>& ref) {
  const double sigma = kQueryAlpha / std::sqrt(2.0);
  const double floor = 1e-3 / (2 * kPi<double> * sigma * sigma);
  std::vector<double> e;
  for (std::size_t i = 0; i < v.size(); ++i)
    e.push_back(bench::relative_error(v[i], ref[i], floor));
  return bench::error_stats(e);
}

// Dictionaries are generated on first use and kept for the run (a 4096-texel one is ~20 MB).
const chermain2021::Dictionary& dictionary(int n, int levels, int resolution) {
  static std::map<std::tuple<int, int, int>, std::unique_ptr<chermain2021::Dictionary>> cache;
  auto& d = cache[{n, levels, resolution}];
  if (!d) {
    chermain2021::DictionaryConfig c;
    c.distributions = n, c.levels = levels, c.resolution = resolution;
    d = std::make_unique<chermain2021::Dictionary>(c);
  }
  return *d;
}

void time_sdf(benchmark::State& s, const chermain2021::SdfParams& p,
              const std::vector<SdfQuery>& q) {
  std::size_t k = 0;
  for (auto _ : s) {
    const SdfQuery& x = q[k];
    benchmark::DoNotOptimize(chermain2021::patch_sdf(p, x.m, x.fp, x.d));
    k = k + 1 == q.size() ? 0 : k + 1;
  }
  s.SetItemsProcessed(std::int64_t(s.iterations()));
}

struct DictKey {
  int n, levels, resolution;
  bool operator==(const DictKey&) const = default;
};

// One P22 row: the setting's dictionary `dict` timed, measured against the reference's `ref`.
void register_sdf_row(const std::string& method, const std::string& setting,
                      const std::string& label, std::shared_ptr<const std::vector<SdfQuery>> q,
                      DictKey dict, DictKey ref, int kernel) {
  const auto params = [kernel](DictKey k) {
    return sdf_params(&dictionary(k.n, k.levels, k.resolution), kernel);
  };
  bench::register_method(
      method, setting, label + (dict == ref ? " (reference)" : ""),
      [=](benchmark::State& s) { time_sdf(s, params(dict), *q); },
      [=] { return sdf_errors(eval_sdf(params(dict), *q), eval_sdf(params(ref), *q)); });
}

void register_dictionary_methods() {
  const bool quick = bench::quick_mode();
  const int count = quick ? 256 : 4096;
  const int n = quick ? 12 : 48;
  // Resolution: L = 12 levels, the reference has 4096 texels (the largest the dictionary allows).
  const int levels = quick ? 8 : 12, ref_res = quick ? 512 : 4096;
  const std::vector<int> resolutions =
      quick ? std::vector<int>{16, 64} : std::vector<int>{16, 32, 64, 128, 256, 1024};
  for (int kernel : {int(chermain2021::kProjectedHalf), int(chermain2021::kNoGgaa)}) {
    const std::string method =
        std::string("chermain.p22_vs_dict_ref.") +
        (kernel == chermain2021::kNoGgaa ? "ggaa_off" : "ggaa_projected_half");
    const std::string label = fmt::format(
        "P22 ({}) from a {}-texel dictionary (N {}, L {}); rel. error, floor 1e-3 of the smooth "
        "peak",
        kernel == chermain2021::kNoGgaa ? "no GGAA" : "GGAA Eq. 21, s_K 0.5", ref_res, n, levels);
    auto queries =
        std::make_shared<const std::vector<SdfQuery>>(sdf_queries(method, count, levels));
    std::vector<int> all = resolutions;
    all.push_back(ref_res);
    for (int res : all)
      register_sdf_row(method, fmt::format("res={}", res), label, queries, {n, levels, res},
                       {n, levels, ref_res}, kernel);
  }
  // Levels: 64 texels (the default), footprints reaching k = 15; the reference has L = 16.
  {
    const std::string method = "chermain.p22_vs_levels_ref";
    const int ref_levels = quick ? 10 : 16;
    const std::vector<int> ls = quick ? std::vector<int>{4} : std::vector<int>{4, 8, 10, 12, 14};
    const std::string label = fmt::format(
        "P22 (GGAA Eq. 21, s_K 0.5) from an L = {} dictionary (N {}, 64 texels; k >= L: smooth "
        "SDF); rel. error, floor 1e-3 of the smooth peak",
        ref_levels, n);
    auto queries =
        std::make_shared<const std::vector<SdfQuery>>(sdf_queries(method, count, ref_levels));
    std::vector<int> all = ls;
    all.push_back(ref_levels);
    for (int L : all)
      register_sdf_row(method, fmt::format("L={}", L), label, queries, {n, L, 64},
                       {n, ref_levels, 64}, chermain2021::kProjectedHalf);
  }
}

// --- Method rows: the tube frame with GGAA on / off against the supersampled pixel integral ----
// The reference is chermain.ggaa-error's: `spp` stratified positions per pixel with the pixel's
// footprint, no GGAA. Error: |display(x) − display(ref)| per lit pixel on the claim's display
// scale (exposure mapping the reference's lit mean to 0.18, clamped to [0, 1]); err_rms is the
// claim's RMSE / 100. Time: one single-threaded frame / its pixel count.
void register_tube_methods() {
  const bool quick = bench::quick_mode();
  const std::string method = "chermain.tube_pixel_vs_supersampled";
  verify::TubeSceneOptions o;
  if (quick) o.width = 32, o.height = 22;
  const int ref_spp = quick ? 64 : 1024;
  const std::string label = fmt::format(
      "tubes {}x{}, {}-spp stratified pixel integral (no GGAA); display-scale abs. error per lit "
      "pixel, time per frame pixel",
      o.width, o.height, ref_spp);
  const std::uint64_t seed = bench::method_seed(method);
  const auto reference = [o, ref_spp, seed]() -> const Image& {
    static const Image ref = [&] {
      verify::TubeSceneOptions p = o;
      p.threads = 0;  // the same image whatever the thread count
      return verify::render_tubes_reference(p, ref_spp, seed);
    }();
    return ref;
  };
  struct Setting {
    std::string name;
    int kernel;
    double s_k;
    int spp;  // > 0: plain supersampling at that rate instead of the 1-spp GGAA frame
  };
  std::vector<Setting> settings = {
      {"ggaa=off", chermain2021::kNoGgaa, 0.5, 0},
      {"ggaa=half_slope,s_k=0.5", chermain2021::kHalfSlope, 0.5, 0},
      {"ggaa=half_slope,s_k=1", chermain2021::kHalfSlope, 1.0, 0},
      {"ggaa=projected_half,s_k=0.5", chermain2021::kProjectedHalf, 0.5, 0},
      {"ggaa=projected_half,s_k=1", chermain2021::kProjectedHalf, 1.0, 0}};
  for (int spp : quick ? std::vector<int>{4} : std::vector<int>{4, 16, 64})
    settings.push_back({fmt::format("ggaa=off,spp={}", spp), chermain2021::kNoGgaa, 0.5, spp});
  for (const Setting& st : settings) {
    const std::uint64_t ss_seed = bench::method_seed(method + "/" + st.name);
    const auto render = [o, st, ss_seed](int threads) {
      verify::TubeSceneOptions p = o;
      p.threads = threads;
      return st.spp > 0 ? verify::render_tubes_reference(p, st.spp, ss_seed)
                        : verify::render_tubes(p, st.kernel, st.s_k);
    };
    bench::register_method(
        method, st.name, label,
        [o, render](benchmark::State& s) {
          chermain2021::default_chermain_dictionary();
          for (auto _ : s) benchmark::DoNotOptimize(render(1));
          s.SetItemsProcessed(std::int64_t(s.iterations()) * o.width * o.height);
        },
        [render, reference] {
          return bench::error_stats(verify::display_abs_errors(render(0), reference()));
        });
  }
}

}  // namespace
}  // namespace glintlab

int main(int argc, char** argv) {
  glintlab::register_dictionary_methods();
  glintlab::register_tube_methods();
  return glintlab::bench::run_benchmarks(argc, argv);
}

// Google Benchmark: time per pixel of Podee et al.'s method (Sec. 3) and of the baselines it is
// compared with in Table 1 — centre sampling, LEAN mapping, the 64-spp supersampled reference —
// on the podee scene (core/scene/podee_scene.h) at the near, medium and far distances, single
// threaded; and the bare kernel podee_shade (float, double; exact and quad-as-circle weights).
// items/s = pixels per second. Run: glintlab_bench_podee --benchmark_out=out/bench/podee.json
// --benchmark_out_format=json.
#include <benchmark/benchmark.h>

#include <array>
#include <memory>
#include <vector>

#include "core/math/rng.h"
#include "core/scene/podee_scene.h"

namespace glintlab {
namespace {

constexpr int kSize = 64;

const PodeeScene& scene(double distance) {
  static const auto map = podee_normal_map();
  static const PodeeScene near(podee_config(kPodeeNear, kSize), map);
  static const PodeeScene medium(podee_config(kPodeeMedium, kSize), map);
  static const PodeeScene far(podee_config(kPodeeFar, kSize), map);
  return distance == kPodeeNear ? near : distance == kPodeeMedium ? medium : far;
}

// Pixels of the crop that hit the sphere: where every method does its work.
const std::vector<std::array<int, 2>>& sphere_pixels(double distance) {
  static std::vector<std::array<int, 2>> cache[3];
  const int k = distance == kPodeeNear ? 0 : distance == kPodeeMedium ? 1 : 2;
  if (cache[k].empty())
    for (int j = 0; j < kSize; ++j)
      for (int i = 0; i < kSize; ++i)
        if (scene(distance).corners(i, j).hit) cache[k].push_back({i, j});
  return cache[k];
}

void per_pixel(benchmark::State& state, PodeeMethod m, double distance) {
  const PodeeScene& s = scene(distance);
  const auto& px = sphere_pixels(distance);
  std::size_t k = 0;
  for (auto _ : state) {
    const auto& p = px[k];
    benchmark::DoNotOptimize(podee_pixel(s, m, p[0], p[1]));
    k = k + 1 == px.size() ? 0 : k + 1;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["distance"] = distance;
}

void reference_pixel(benchmark::State& state, double distance) {
  const PodeeScene& s = scene(distance);
  const auto& px = sphere_pixels(distance);
  std::size_t k = 0;
  std::uint64_t index = 0;
  for (auto _ : state) {
    const auto& p = px[k];
    double acc = 0;
    for (int n = 0; n < 64; ++n, ++index) {  // 8 × 8 stratified, as the paper's reference
      const double x = p[0] + (n % 8 + counter_uniform<double>(1, index, 0)) / 8;
      const double y = p[1] + (n / 8 + counter_uniform<double>(1, index, 1)) / 8;
      acc += s.radiance(x, y);
    }
    benchmark::DoNotOptimize(acc);
    k = k + 1 == px.size() ? 0 : k + 1;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["distance"] = distance;
}

template <class T>
void shade_kernel(benchmark::State& state, PodeeWeighting w) {
  std::vector<std::array<Vec3<T>, 4>> corners(1024);
  std::vector<Vec3<T>> lights(1024);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const auto u = [&](int d) { return counter_uniform<double>(7, i, std::uint64_t(d)); };
    const Vec3<double> l = normalize(Vec3<double>{0.2 * u(0), 0.2 * u(1), 1});
    const OrthonormalBasis<double> b = basis_from_z(l);
    for (int c = 0; c < 4; ++c) {
      const Vec3<double> r =
          normalize(l + (0.2 * u(2 + 2 * c) - 0.1) * b.x + (0.2 * u(3 + 2 * c) - 0.1) * b.y);
      corners[i][std::size_t(c)] = {T(r.x), T(r.y), T(r.z)};
    }
    lights[i] = {T(l.x), T(l.y), T(l.z)};
  }
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(podee_shade(corners[k], lights[k], T(0.05), w).value);
    k = (k + 1) & 1023;
  }
  state.SetItemsProcessed(state.iterations());
}

void register_all() {
  for (double d : {kPodeeNear, kPodeeMedium, kPodeeFar}) {
    for (PodeeMethod m : {PodeeMethod::kCentre, PodeeMethod::kLean, PodeeMethod::kPodee,
                          PodeeMethod::kPodeeQuadAsCircle}) {
      benchmark::RegisterBenchmark(
          (std::string("podee_pixel/") + to_string(m) + "/d" + std::to_string(int(d))).c_str(),
          [m, d](benchmark::State& s) { per_pixel(s, m, d); });
    }
    benchmark::RegisterBenchmark(("podee_pixel/reference64/d" + std::to_string(int(d))).c_str(),
                                 [d](benchmark::State& s) { reference_pixel(s, d); });
  }
  benchmark::RegisterBenchmark("podee_shade/double/exact", [](benchmark::State& s) {
    shade_kernel<double>(s, PodeeWeighting::kExact);
  });
  benchmark::RegisterBenchmark("podee_shade/double/quad_as_circle", [](benchmark::State& s) {
    shade_kernel<double>(s, PodeeWeighting::kQuadAsCircle);
  });
  benchmark::RegisterBenchmark("podee_shade/float/exact", [](benchmark::State& s) {
    shade_kernel<float>(s, PodeeWeighting::kExact);
  });
  benchmark::RegisterBenchmark("podee_shade/float/quad_as_circle", [](benchmark::State& s) {
    shade_kernel<float>(s, PodeeWeighting::kQuadAsCircle);
  });
}

}  // namespace
}  // namespace glintlab

int main(int argc, char** argv) {
  glintlab::register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

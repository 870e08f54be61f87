// Google Benchmark: time per pixel of Podee et al.'s method (Sec. 3) and of the baselines it is
// compared with in Table 1 — centre sampling, LEAN mapping, the 64-spp supersampled reference —
// on the podee scene (verify/scenes/podee_scene.h) at the near, medium and far distances, single
// threaded; and the bare kernel podee::shade (float, double; exact and quad-as-circle weights).
// items/s = pixels per second. Run: glintlab_bench_podee --benchmark_out=out/bench/podee.json
// --benchmark_out_format=json. Method rows (experiments/bench/METHOD_BENCHMARKS.md): the kernel's
// weightings (Sec. 3.2: exact circle ∩ quad, quad as circle, none) in double and float against
// the double exact one, and every method's pixel against a 1024-spp pixel integral per distance.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <array>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "core/math/rng.h"
#include "core/models/podee.h"
#include "experiments/bench/method_bench.h"
#include "verify/scenes/podee_scene.h"

namespace glintlab {
namespace {

constexpr int kSize = 64;

const podee::Scene& scene(double distance) {
  static const auto map = podee::normal_map();
  static const podee::Scene near(podee::config(podee::kNear, kSize), map);
  static const podee::Scene medium(podee::config(podee::kMedium, kSize), map);
  static const podee::Scene far(podee::config(podee::kFar, kSize), map);
  return distance == podee::kNear ? near : distance == podee::kMedium ? medium : far;
}

// Pixels of the crop that hit the sphere: where every method does its work.
const std::vector<std::array<int, 2>>& sphere_pixels(double distance) {
  static std::vector<std::array<int, 2>> cache[3];
  const int k = distance == podee::kNear ? 0 : distance == podee::kMedium ? 1 : 2;
  if (cache[k].empty())
    for (int j = 0; j < kSize; ++j)
      for (int i = 0; i < kSize; ++i)
        if (scene(distance).corners(i, j).hit) cache[k].push_back({i, j});
  return cache[k];
}

void per_pixel(benchmark::State& state, podee::Method m, double distance) {
  const podee::Scene& s = scene(distance);
  const auto& px = sphere_pixels(distance);
  std::size_t k = 0;
  for (auto _ : state) {
    const auto& p = px[k];
    benchmark::DoNotOptimize(podee::pixel(s, m, p[0], p[1]));
    k = k + 1 == px.size() ? 0 : k + 1;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["distance"] = distance;
}

void reference_pixel(benchmark::State& state, double distance) {
  const podee::Scene& s = scene(distance);
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
void shade_kernel(benchmark::State& state, podee::Weighting w) {
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
    benchmark::DoNotOptimize(podee::shade(corners[k], lights[k], T(0.05), w).value);
    k = (k + 1) & 1023;
  }
  state.SetItemsProcessed(state.iterations());
}

void register_all() {
  for (double d : {podee::kNear, podee::kMedium, podee::kFar}) {
    for (podee::Method m : {podee::Method::kCentre, podee::Method::kLean, podee::Method::kPodee,
                            podee::Method::kPodeeQuadAsCircle}) {
      benchmark::RegisterBenchmark(
          (std::string("podee_pixel/") + to_string(m) + "/d" + std::to_string(int(d))).c_str(),
          [m, d](benchmark::State& s) { per_pixel(s, m, d); });
    }
    benchmark::RegisterBenchmark(("podee_pixel/reference64/d" + std::to_string(int(d))).c_str(),
                                 [d](benchmark::State& s) { reference_pixel(s, d); });
  }
  benchmark::RegisterBenchmark("podee_shade/double/exact", [](benchmark::State& s) {
    shade_kernel<double>(s, podee::Weighting::kExact);
  });
  benchmark::RegisterBenchmark("podee_shade/double/quad_as_circle", [](benchmark::State& s) {
    shade_kernel<double>(s, podee::Weighting::kQuadAsCircle);
  });
  benchmark::RegisterBenchmark("podee_shade/float/exact", [](benchmark::State& s) {
    shade_kernel<float>(s, podee::Weighting::kExact);
  });
  benchmark::RegisterBenchmark("podee_shade/float/quad_as_circle", [](benchmark::State& s) {
    shade_kernel<float>(s, podee::Weighting::kQuadAsCircle);
  });
}

}  // namespace
}  // namespace glintlab

namespace glintlab {
namespace {

// --- Method rows: podee.value_vs_exact_area ---------------------------------------------------
// Reflection spaces as a pixel produces them: a parallelogram (random half-sizes 0.005–0.1 rad,
// rotation, shear) with each corner jittered by up to 15 % of its size, centred within 0.15 of
// the light's direction, corners in footprint order ((−,−), (+,−), (−,+), (+,+)); projected
// radii tan γ uniform in [0.01, 0.2], so that the circle and the quad overlap in every way.
// Error: |value − value_ref| (value = lit × weight ∈ [0, 1], absolute), reference podee::shade in
// double with the exact circle ∩ quad area.
struct ShadeQuery {
  std::array<Vec3<double>, 4> corners;
  Vec3<double> light;
  double tan_radius;
};

std::vector<ShadeQuery> shade_queries(const std::string& method, int count) {
  const std::uint64_t seed = bench::method_seed(method);
  std::vector<ShadeQuery> q(static_cast<std::size_t>(count));
  constexpr double kSign[4][2] = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
  for (std::size_t i = 0; i < q.size(); ++i) {
    const auto u = [&](int d) { return counter_uniform<double>(seed, i, std::uint64_t(d)); };
    const Vec3<double> l = normalize(Vec3<double>{0.2 * u(0) - 0.1, 0.2 * u(1) - 0.1, 1});
    const OrthonormalBasis<double> b = basis_from_z(l);
    const double ax = 0.005 + 0.095 * u(2), ay = 0.005 + 0.095 * u(3);
    const double th = 2 * kPi<double> * u(4), shear = 0.6 * u(5) - 0.3;
    const double cx = 0.3 * u(6) - 0.15, cy = 0.3 * u(7) - 0.15;
    for (int c = 0; c < 4; ++c) {
      const double jx = 0.3 * u(8 + 2 * c) - 0.15, jy = 0.3 * u(9 + 2 * c) - 0.15;
      const double x = ax * (kSign[c][0] + jx) + shear * ay * kSign[c][1];
      const double y = ay * (kSign[c][1] + jy);
      const double rx = std::cos(th) * x - std::sin(th) * y,
                   ry = std::sin(th) * x + std::cos(th) * y;
      q[i].corners[std::size_t(c)] = normalize(l + (cx + rx) * b.x + (cy + ry) * b.y);
    }
    q[i].light = l;
    q[i].tan_radius = 0.01 + 0.19 * u(16);
  }
  return q;
}

template <class T>
T shade_value(const ShadeQuery& x, podee::Weighting w) {
  std::array<Vec3<T>, 4> c;
  for (std::size_t k = 0; k < 4; ++k)
    c[k] = {T(x.corners[k].x), T(x.corners[k].y), T(x.corners[k].z)};
  return podee::shade(c, Vec3<T>{T(x.light.x), T(x.light.y), T(x.light.z)}, T(x.tan_radius), w)
      .value;
}

template <class T>
void register_weighting(const std::string& method, const std::string& label,
                        std::shared_ptr<const std::vector<ShadeQuery>> q, podee::Weighting w) {
  const bool is_ref = std::is_same_v<T, double> && w == podee::Weighting::kExact;
  const std::string setting =
      fmt::format("precision={},weighting={}", std::is_same_v<T, double> ? "double" : "float",
                  Podee::kWeightingNames[std::size_t(w)]);
  // The inputs converted once, so that the timed loop is the kernel alone.
  struct In {
    std::array<Vec3<T>, 4> c;
    Vec3<T> l;
    T r;
  };
  auto in = std::make_shared<std::vector<In>>();
  for (const ShadeQuery& x : *q) {
    In v;
    for (std::size_t k = 0; k < 4; ++k)
      v.c[k] = {T(x.corners[k].x), T(x.corners[k].y), T(x.corners[k].z)};
    v.l = {T(x.light.x), T(x.light.y), T(x.light.z)};
    v.r = T(x.tan_radius);
    in->push_back(v);
  }
  bench::register_method(
      method, setting, label + (is_ref ? " (reference)" : ""),
      [in, w](benchmark::State& s) {
        std::size_t k = 0;
        for (auto _ : s) {
          const In& v = (*in)[k];
          benchmark::DoNotOptimize(podee::shade(v.c, v.l, v.r, w).value);
          k = k + 1 == in->size() ? 0 : k + 1;
        }
        s.SetItemsProcessed(std::int64_t(s.iterations()));
      },
      [q, w] {
        std::vector<double> e;
        for (const ShadeQuery& x : *q)
          e.push_back(std::abs(double(shade_value<T>(x, w)) -
                               shade_value<double>(x, podee::Weighting::kExact)));
        return bench::error_stats(e);
      });
}

void register_weighting_methods() {
  const std::string method = "podee.value_vs_exact_area";
  const std::string label =
      "podee_shade double with the exact circle-quad area; abs. error of lit x weight";
  const auto q = std::make_shared<const std::vector<ShadeQuery>>(
      shade_queries(method, bench::quick_mode() ? 512 : 65536));
  for (podee::Weighting w :
       {podee::Weighting::kExact, podee::Weighting::kQuadAsCircle, podee::Weighting::kNone}) {
    register_weighting<double>(method, label, q, w);
    register_weighting<float>(method, label, q, w);
  }
}

// --- Method rows: podee.pixel_vs_supersampled.d<distance> -------------------------------------
// Reference: the stratified `ref_spp`-sample pixel average of podee::render_podee_reference. Error:
// |pixel − reference| over the pixels whose centre hits the sphere (radiance for unit light
// radiance, absolute); time per such pixel, single thread. Plain supersampling (another seed) is
// timed and measured the same way.
void register_pixel_methods() {
  const bool quick = bench::quick_mode();
  const int size = quick ? 24 : kSize, ref_spp = quick ? 64 : 1024;
  static const auto map = podee::normal_map();
  for (double d : {podee::kNear, podee::kMedium, podee::kFar}) {
    const std::string method = fmt::format("podee.pixel_vs_supersampled.d{}", int(d));
    const std::string label = fmt::format(
        "{}-spp stratified pixel integral ({}x{} crop); abs. pixel error on sphere pixels", ref_spp,
        size, size);
    const auto scene = std::make_shared<const podee::Scene>(podee::config(d, size), map);
    auto px = std::make_shared<std::vector<std::array<int, 2>>>();
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i)
        if (scene->corners(i, j).hit) px->push_back({i, j});
    const std::uint64_t seed = bench::method_seed(method);
    auto reference = std::make_shared<Image>();
    const auto ref = [scene, ref_spp, seed, reference]() -> const Image& {
      if (reference->data.empty())
        *reference = podee::render_podee_reference(*scene, ref_spp, seed, 0);
      return *reference;
    };
    const auto errors = [px, ref](const Image& im) {
      std::vector<double> e;
      for (const auto& p : *px)
        e.push_back(std::abs(im.at(p[0], p[1], 0) - ref().at(p[0], p[1], 0)));
      return bench::error_stats(e);
    };
    struct Row {
      std::string setting;
      podee::Method m;
    };
    for (const Row& r :
         {Row{"method=centre", podee::Method::kCentre}, Row{"method=lean", podee::Method::kLean},
          Row{"method=podee,weighting=exact", podee::Method::kPodee},
          Row{"method=podee,weighting=quad_as_circle", podee::Method::kPodeeQuadAsCircle},
          Row{"method=podee,weighting=none", podee::Method::kPodeeUnweighted}}) {
      const podee::Method m = r.m;
      bench::register_method(
          method, r.setting, label,
          [scene, px, m](benchmark::State& s) {
            std::size_t k = 0;
            for (auto _ : s) {
              const auto& p = (*px)[k];
              benchmark::DoNotOptimize(podee::pixel(*scene, m, p[0], p[1]));
              k = k + 1 == px->size() ? 0 : k + 1;
            }
            s.SetItemsProcessed(std::int64_t(s.iterations()));
          },
          [scene, m, errors] { return errors(podee::render_podee(*scene, m, 0)); });
    }
    for (int spp : quick ? std::vector<int>{4} : std::vector<int>{4, 16, 64}) {
      const std::string setting = fmt::format("method=supersampled,spp={}", spp);
      const std::uint64_t ss_seed = bench::method_seed(method + "/" + setting);
      bench::register_method(
          method, setting, label,
          [scene, px, spp, ss_seed](benchmark::State& s) {
            std::size_t k = 0;
            std::uint64_t index = 0;
            for (auto _ : s) {
              const auto& p = (*px)[k];
              double acc = 0;
              for (int n = 0; n < spp; ++n, ++index) {  // as podee::render_podee_reference samples
                const Vec2<double> o = stratified_offset(ss_seed, index, n, spp);
                acc += scene->radiance(p[0] + o.x, p[1] + o.y);
              }
              benchmark::DoNotOptimize(acc);
              k = k + 1 == px->size() ? 0 : k + 1;
            }
            s.SetItemsProcessed(std::int64_t(s.iterations()));
          },
          [scene, spp, ss_seed, errors] {
            return errors(podee::render_podee_reference(*scene, spp, ss_seed, 0));
          });
    }
  }
}

}  // namespace
}  // namespace glintlab

int main(int argc, char** argv) {
  glintlab::register_all();
  glintlab::register_weighting_methods();
  glintlab::register_pixel_methods();
  return glintlab::bench::run_benchmarks(argc, argv);
}

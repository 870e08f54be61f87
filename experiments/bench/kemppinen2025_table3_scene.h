// The Table 3 scene of Kemppinen et al. 2025 ("ms per frame ... at full HD resolution with 3
// lights", a plane orthogonal to the camera and one seen at 25°, low and high roughness, Beckmann
// and GGX), as timed per pixel by experiments/bench/kemppinen2025_bench.cpp and, without a
// benchmark JSON, by the kemppinen2025-table3 figure.
//
// Per pixel: the footprint from ray differentials (core/scene/footprint.h) and the cosine-weighted
// BRDF of kemppinen_ggx / kemppinen_beckmann toward 3 point lights (D★^f by Algorithm 1, Smith
// G2; k = 4 as in every result of the paper, the fast rational erf of Eq. 10, roulette, the
// model's defaults otherwise; no pdf, none is needed for point lights), or the smooth NDF's BRDF
// for scale. Where the paper is silent (it follows Deliot & Belcour 2023's setup without giving
// it): low roughness α = 0.1, high α = 0.5; the plane z = 0 with uv = world / 0.1 (a pixel at the
// centre of the 90° view spans 0.77 level-0 cells at density 10⁴), 45° vertical field of view;
// 90°: eye at height 1 looking straight down; 25°: eye at height 1, the view axis 25° above the
// plane (the top row's rays descend only 2.5°, so footprints grow to hundreds of cells across
// many MIP levels); 3 point lights of unit intensity at fixed positions.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/models/kemppinen_ggx.h"
#include "core/models/smooth_microfacet.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/scene/footprint.h"

namespace glintlab::kemppinen_table3 {

inline constexpr int kWidth = 1920, kHeight = 1080;
inline constexpr std::uint64_t kPixels = std::uint64_t(kWidth) * kHeight;
inline constexpr double kLowAlpha = 0.1, kHighAlpha = 0.5;

// The n-th pixel shaded by a run: (n · 1000003) mod (1920 · 1080), a stride coprime with the
// pixel count, so any run of consecutive n spreads over the whole frame.
inline std::uint64_t pixel_of(std::uint64_t n) { return (n * 1000003ULL) % kPixels; }

struct Scene {
  PinholeCamera<double> camera;
  Plane<double> plane;
  std::array<Vec3<double>, 3> lights;
};

inline Scene scene(int plane_deg) {
  const Frame<double> xy{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Plane<double> plane{{0, 0, 0}, xy, 0.1, 0};
  if (plane_deg == 90) {
    return {PinholeCamera<double>::look_at({0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 45, kWidth, kHeight),
            plane,
            {{{-0.3, 0.2, 1.2}, {0.4, -0.1, 1.0}, {0.0, 0.5, 1.5}}}};
  }
  const double back = 1 / std::tan(25 * std::numbers::pi / 180);
  return {PinholeCamera<double>::look_at({0, -back, 1}, {0, 0, 0}, {0, 0, 1}, 45, kWidth, kHeight),
          plane,
          {{{0, 3, 1.5}, {-2, 6, 2}, {2, 2, 1}}}};
}

// Radiance of one pixel: Σ over the 3 lights of value(ωi, ωl) / d², value = brdf(query).
template <class Brdf>
GLINTLAB_FN double shade_pixel(const Scene& s, std::uint64_t pixel, const Brdf& brdf) {
  const double x = double(pixel % kWidth) + 0.5, y = double(pixel / kWidth) + 0.5;
  const PixelFootprint<double> f =
      pixel_footprint(s.camera, s.plane, x, y, LightPoint<double>{s.lights[0], false});
  double radiance = 0;
  for (const Vec3<double>& light : s.lights) {
    const Vec3<double> d = light - f.surface.p;
    const ModelQuery<double> q{f.footprint, f.wi, f.frame.to_local(normalize(d)), {1.0, 1.0}};
    radiance += brdf(q) / dot(d, d);
  }
  return radiance;
}

// One Table 3 cell: NDF, plane angle, roughness; `smooth` shades with the base NDF instead.
struct Cell {
  bool ggx;
  int plane_deg;  // 90 or 25
  bool high;      // high roughness
  bool smooth;
};

// Benchmark name "table3/ndf:ggx/plane:90/roughness:low/model:kemppinen".
inline std::string cell_name(const Cell& c) {
  return std::string("table3/ndf:") + (c.ggx ? "ggx" : "beckmann") +
         "/plane:" + std::to_string(c.plane_deg) + "/roughness:" + (c.high ? "high" : "low") +
         "/model:" + (c.smooth ? "smooth" : "kemppinen");
}

// The model's parameter values (kParams order) with k = 4, erf = rational, roulette, α set.
inline std::vector<double> model_values(double alpha) {
  std::vector<double> v;
  for (const ParamSpec& s : KemppinenGGX::kParams) {
    double x = s.default_value;
    const std::string_view n = s.name;
    if (n == "alpha_x" || n == "alpha_y") x = alpha;
    if (n == "k") x = 1;         // "4"
    if (n == "erf") x = 1;       // "rational"
    if (n == "blending") x = 0;  // "roulette"
    v.push_back(x);
  }
  return v;
}

// Calls run(shade) with shade(pixel) → radiance for the cell, so the caller times the loop.
template <class Run>
void with_cell(const Cell& c, Run&& run) {
  const Scene s = scene(c.plane_deg);
  const std::vector<double> v = model_values(c.high ? kHighAlpha : kLowAlpha);
  const auto go = [&](const auto& p) {
    if (c.smooth) {
      run([&](std::uint64_t pixel) {
        return shade_pixel(s, pixel, [&](const ModelQuery<double>& q) {
          return detail::smooth_eval(p.ndf, q, 0.0).value;
        });
      });
    } else {
      run([&](std::uint64_t pixel) {
        return shade_pixel(s, pixel, [&](const ModelQuery<double>& q) {
          return detail::kemppinen_model_eval(p, q, 0.0).value;
        });
      });
    }
  };
  if (c.ggx)
    go(detail::kemppinen_model_params<GGX<double>, double>(v));
  else
    go(detail::kemppinen_model_params<Beckmann<double>, double>(v));
}

// Every cell: NDF (Beckmann first, the paper's column order) × plane × roughness × model.
inline std::vector<Cell> cells() {
  std::vector<Cell> out;
  for (bool smooth : {false, true})
    for (bool ggx : {false, true})
      for (int plane : {90, 25})
        for (bool high : {false, true}) out.push_back({ggx, plane, high, smooth});
  return out;
}

}  // namespace glintlab::kemppinen_table3

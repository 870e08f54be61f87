// The Table 3 analogue of Kemppinen et al. 2025 through the model batches: a whole 1920×1080 frame
// of one cell (experiments/bench/kemppinen2025_table3_scene.h), each pixel's query built as
// shade_pixel builds it (footprint from ray differentials, ω_i, one ω_o per light), every pixel's
// three light directions evaluated by the registered model's SIMD batch (core/simd/model_batch.h
// eval_batch, float or double, any ISA), blocks of pixels run in parallel, radiance = Σ value / d².
// The scalar path (shade_pixel on the model's double templates, one pixel at a time) is what
// experiments/bench/kemppinen2025_bench.cpp's table3/ rows time.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "core/model_layout.h"
#include "core/model_registry.h"
#include "core/simd/model_batch.h"
#include "experiments/bench/kemppinen2025_table3_scene.h"

namespace glintlab::kemppinen_table3 {

// The registered model a cell shades with and its parameter values: the Kemppinen model with k = 4,
// the rational erf and roulette (model_values), or the smooth model of the NDF, α set.
inline const ModelEntry& cell_model(const Cell& c) {
  if (c.smooth) return find_model(c.ggx ? "smooth_ggx" : "smooth_beckmann");
  return find_model(c.ggx ? "kemppinen_ggx" : "kemppinen_beckmann");
}

inline std::vector<double> cell_values(const Cell& c) {
  const double alpha = c.high ? kHighAlpha : kLowAlpha;
  if (!c.smooth) return model_values(alpha);
  const ModelEntry& m = cell_model(c);
  std::vector<double> v;
  for (const ParamSpec& p : m.params) {
    const std::string_view n = p.name;
    v.push_back(n == "alpha_x" || n == "alpha_y" ? alpha : p.default_value);
  }
  return v;
}

inline constexpr std::size_t kFrameBlock = 2048;  // pixels per parallel block

// radiance[i] for the pixels first .. first + count - 1 of the frame in scan order (pixel p at
// x = p mod 1920, y = p / 1920), with the model's batch of precision T on `isa`. Each pixel's sum
// runs over the lights in shade_pixel's order, in T.
template <class T>
void render_pixels(const Cell& c, std::uint64_t first, std::size_t count, simd::Isa isa,
                   T* radiance) {
  const Scene s = scene(c.plane_deg);
  const ModelEntry& model = cell_model(c);
  const std::vector<double> values = cell_values(c);
  constexpr std::size_t kCols = simd::kQueryColumns.size();
  constexpr std::size_t kLights = 3;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, kFrameBlock), [&](const tbb::
                                                                                    blocked_range<
                                                                                        std::
                                                                                            size_t>&
                                                                                        r) {
    const std::size_t rows = kLights * r.size();
    std::vector<T> query(kCols * rows), d2(rows);
    std::vector<T> out((2 + model.intermediates.size()) * rows);
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      const std::uint64_t pixel = first + i;
      const double x = double(pixel % kWidth) + 0.5, y = double(pixel / kWidth) + 0.5;
      const PixelFootprint<double> f =
          pixel_footprint(s.camera, s.plane, x, y, LightPoint<double>{s.lights[0], false});
      for (std::size_t l = 0; l < kLights; ++l) {
        const Vec3<double> d = s.lights[l] - f.surface.p;
        const ModelQuery<double> q{f.footprint, f.wi, f.frame.to_local(normalize(d)), {1.0, 1.0}};
        const QueryRow<double> row = to_row(q);
        const std::size_t k = kLights * (i - r.begin()) + l;
        for (std::size_t col = 0; col < kCols; ++col) query[col * rows + k] = T(row[col]);
        d2[k] = T(dot(d, d));
      }
    }
    std::array<simd::Column<T>, kCols> columns;
    for (std::size_t col = 0; col < kCols; ++col) columns[col] = {query.data() + col * rows, 1};
    std::vector<T*> outputs;
    for (std::size_t k = 0; k < 2 + model.intermediates.size(); ++k)
      outputs.push_back(out.data() + k * rows);
    simd::eval_batch(model, values, columns, outputs, rows, isa);
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      T sum = 0;
      for (std::size_t l = 0; l < kLights; ++l) {
        const std::size_t k = kLights * (i - r.begin()) + l;
        sum += out[k] / d2[k];
      }
      radiance[i] = sum;
    }
  });
}

// The whole frame.
template <class T>
std::vector<T> render_frame(const Cell& c, simd::Isa isa) {
  std::vector<T> frame(kPixels);
  render_pixels<T>(c, 0, kPixels, isa, frame.data());
  return frame;
}

}  // namespace glintlab::kemppinen_table3

// Stratified per-pixel supersampling — the generic per-pixel reference the papers compare
// against (64 spp in Podee, 1024 in Chermain, 8192 in Kemppinen Fig. 7) — and the deterministic
// multi-threaded image loop it runs in.
//
// Sample s of N in a pixel lies uniformly in cell (s mod nx, s div nx) of an nx × ny grid of
// equal cells, nx the largest divisor of N not above √N and ny = N / nx: every N has such a grid,
// so each sample is uniform over its cell and the pixel average is unbiased (stratified sampling,
// Mitchell 1996 / PBRT Sec. 7.3). Random numbers are counter-based (seed, pixel·N + s, dim), and
// rows are computed independently and written to their own pixels, so the image is identical for
// any thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/math/rng.h"
#include "core/math/vec.h"
#include "core/render/image.h"

namespace glintlab {

// Columns of the stratification grid for N samples.
inline int strata_columns(int n) {
  int nx = 1;
  for (int d = 1; d * d <= n; ++d) {
    if (n % d == 0) nx = d;
  }
  return nx;
}

// Position in [0, 1)² of sample s of n within the pixel (dimensions 0 and 1 of its counter).
inline Vec2<double> stratified_offset(std::uint64_t seed, std::uint64_t sample_index, int s,
                                      int n) {
  const int nx = strata_columns(n);
  const int ny = n / nx;
  const double jx = counter_uniform<double>(seed, sample_index, 0);
  const double jy = counter_uniform<double>(seed, sample_index, 1);
  return {(static_cast<double>(s % nx) + jx) / nx, (static_cast<double>(s / nx) + jy) / ny};
}

// Called for pixel (x, y) with `out` pointing at its num_channels values (zeroed).
using PixelFunction = std::function<void(int x, int y, double* out)>;
// Called after each finished row with (rows done, rows total); calls may come from any thread
// but never concurrently.
using RowProgress = std::function<void(long done, long total)>;

// Renders every pixel with `threads` worker threads (0 = all cores). Deterministic: the result
// does not depend on `threads`.
Image render_image(int width, int height, std::vector<std::string> channels, int threads,
                   const PixelFunction& pixel, const RowProgress& progress = {});

// The stratified N-sample pixel average: for sample s of pixel (x, y), with global sample index
// i = (y·width + x)·N + s, calls f(film position (x, y) + stratified_offset, i, acc), which adds
// that sample's channel values into acc; each pixel is acc / N. f draws its further random
// numbers as counter_uniform(seed, i, dim) with dim >= 2 (0 and 1 are the film position).
template <class SampleFn>
Image render_supersampled(int width, int height, std::vector<std::string> channels, int spp,
                          std::uint64_t seed, int threads, const SampleFn& f,
                          const RowProgress& progress = {}) {
  const std::size_t nc = channels.size();
  const auto pixel = [&](int x, int y, double* out) {
    const std::uint64_t first = (static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(width) +
                                 static_cast<std::uint64_t>(x)) *
                                static_cast<std::uint64_t>(spp);
    for (int s = 0; s < spp; ++s) {
      const Vec2<double> o = stratified_offset(seed, first + s, s, spp);
      f(Vec2<double>{x + o.x, y + o.y}, first + s, out);
    }
    for (std::size_t c = 0; c < nc; ++c) out[c] /= spp;
  };
  return render_image(width, height, std::move(channels), threads, pixel, progress);
}

}  // namespace glintlab

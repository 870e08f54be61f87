// Environment light from a lat-long float RGB image, importance-sampled by a piecewise-constant 2D
// distribution over its pixels (marginal over rows, conditional over columns: Pharr et al., PBRT
// 4th ed. Sec. A.5.3 and 12.5.2), with each pixel weighted by its luminance times its solid angle
// Ω_ij = (2π/W)(cos θ_j − cos θ_{j+1}) (the sin θ factor of the lat-long map, integrated over the
// pixel's row), then sampled uniformly in (cos θ, φ) inside the pixel. The density per unit solid
// angle is therefore exactly piecewise constant, pdf(ω) = Y_ij / Σ Y Ω, with no 1/sin θ pole.
//
// Convention: z up; row j covers θ ∈ [πj/H, π(j+1)/H] from +z (row 0 at the zenith, the top of
// the image), column i covers φ ∈ [2πi/W, 2π(i+1)/W) with φ = atan2(y, x);
// ω = (sin θ cos φ, sin θ sin φ, cos θ). A caller with another convention rotates its directions.
// The map owns its tables (host memory), so its lookups are host functions for scalar T; a GPU or
// batch backend would take a view of the same tables and gather.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "core/lights/light_sample.h"
#include "core/parameter_check.h"

namespace glintlab {

// A decoded lat-long image: width × height pixels, RGB floats, rows from the top (θ = 0) down.
struct LatLongImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  // 3 · width · height, row-major: rgb[3 (j width + i) + c]
};

class EnvironmentMap {
 public:
  // Validates the image: width, height >= 1, 3·width·height finite, non-negative values. An
  // all-black map is valid (no light): it is sampled uniformly over the sphere and radiates 0.
  explicit EnvironmentMap(LatLongImage image) : image_(std::move(image)) {
    const char* what = "environment map";
    detail::require(image_.width >= 1, what, "width", image_.width, "width >= 1 pixel");
    detail::require(image_.height >= 1, what, "height", image_.height, "height >= 1 pixel");
    const std::size_t n = std::size_t(image_.width) * std::size_t(image_.height);
    if (image_.rgb.size() != 3 * n)
      throw ParameterError(
          fmt::format("{}: {} pixel values for a {}x{} image (valid: 3 x width x height = {})",
                      what, image_.rgb.size(), image_.width, image_.height, 3 * n));
    for (std::size_t k = 0; k < image_.rgb.size(); ++k)
      if (!(std::isfinite(image_.rgb[k]) && image_.rgb[k] >= 0))
        throw ParameterError(
            fmt::format("{}: pixel ({}, {}) channel {} = {} is out of range (valid: finite, >= 0)",
                        what, (k / 3) % std::size_t(image_.width),
                        (k / 3) / std::size_t(image_.width), k % 3, image_.rgb[k]));
    build();
  }

  int width() const { return image_.width; }
  int height() const { return image_.height; }
  const LatLongImage& image() const { return image_; }

  // Rec. 709 luminance, the weight of a pixel's radiance in the distribution.
  static double luminance(double r, double g, double b) {
    return 0.2126 * r + 0.7152 * g + 0.0722 * b;
  }

  // The lat-long pixel grid: pixel (column i, row j) of a direction, clamped to the image.
  struct Grid {
    int width, height;
    template <class T>
    void pixel_of(Vec3<T> w, int* i, int* j) const {
      const T theta = safe_acos(w.z);
      T phi = atan2(w.y, w.x);
      phi = select(phi < T(0), phi + T(2 * kPi<T>), phi);
      *j = std::min(height - 1, std::max(0, int(theta * T(height) / T(kPi<T>))));
      *i = std::min(width - 1, std::max(0, int(phi * T(width) / T(2 * kPi<T>))));
    }
  };

  template <class T>
  void pixel_of(Vec3<T> w, int* i, int* j) const {
    Grid{image_.width, image_.height}.pixel_of(w, i, j);
  }

  template <class T>
  Vec3<T> radiance(Vec3<T>, Vec3<T> wi) const {
    int i, j;
    pixel_of(wi, &i, &j);
    const float* c = &image_.rgb[3 * (std::size_t(j) * image_.width + i)];
    return {T(c[0]), T(c[1]), T(c[2])};
  }

  template <class T>
  T pdf(Vec3<T>, Vec3<T> wi) const {
    int i, j;
    pixel_of(wi, &i, &j);
    return T(pixel_pdf_[std::size_t(j) * image_.width + i]);
  }

  // The map surrounds every point: its extent is the whole sphere (black pixels included).
  template <class T>
  T solid_angle(Vec3<T>) const {
    return T(4 * kPi<T>);
  }

  template <class T>
  LightSample<T> sample(Vec3<T> p, Vec2<T> u) const {
    T ur = u.x, uc = u.y;
    const int j = search(&row_cdf_[0], image_.height, &ur);
    const int i = search(&col_cdf_[std::size_t(j) * (image_.width + 1)], image_.width, &uc);
    const T c0 = T(cos_theta_[j]), c1 = T(cos_theta_[j + 1]);
    const T z = c0 - ur * (c0 - c1);
    const T phi = T(2 * kPi<T>) * (T(i) + uc) / T(image_.width);
    T sp, cp;
    sincos(phi, &sp, &cp);
    const T s = safe_sqrt((T(1) - z) * (T(1) + z));
    const Vec3<T> wi{s * cp, s * sp, z};
    const T pdf = T(pixel_pdf_[std::size_t(j) * image_.width + i]);
    return {wi, infinite_distance<T>(), radiance(p, wi), pdf, Mask<T>(pdf > T(0))};
  }

 private:
  // First k in [0, n) with cdf[k + 1] > u (cdf has n + 1 entries, cdf[0] = 0, cdf[n] = 1): a fixed
  // number of halvings, then u is rescaled to [0, 1) inside the chosen interval.
  template <class T>
  static int search(const double* cdf, int n, T* u) {
    int lo = 0, len = n;
    while (len > 0) {
      const int half = len / 2;
      const bool right = double(*u) >= cdf[lo + half + 1];
      lo = right ? lo + half + 1 : lo;
      len = right ? len - half - 1 : half;
    }
    lo = std::min(lo, n - 1);
    const double w = cdf[lo + 1] - cdf[lo];
    *u = std::min(T((double(*u) - cdf[lo]) / (w > 0 ? w : 1)), T(1) - T(1e-7));
    *u = std::max(*u, T(0));
    return lo;
  }

  void build() {
    const int w = image_.width, h = image_.height;
    cos_theta_.resize(h + 1);
    for (int j = 0; j <= h; ++j) cos_theta_[j] = std::cos(3.14159265358979323846 * j / h);
    cos_theta_[0] = 1;
    cos_theta_[h] = -1;
    std::vector<double> lum(std::size_t(w) * h);
    double total = 0;
    for (std::size_t k = 0; k < lum.size(); ++k) {
      lum[k] = luminance(image_.rgb[3 * k], image_.rgb[3 * k + 1], image_.rgb[3 * k + 2]);
      total += lum[k];
    }
    if (!(total > 0)) std::fill(lum.begin(), lum.end(), 1.0);  // black: uniform over the sphere
    row_cdf_.assign(h + 1, 0);
    col_cdf_.assign(std::size_t(h) * (w + 1), 0);
    double norm = 0;  // Σ Y Ω
    for (int j = 0; j < h; ++j) {
      const double omega = 2 * 3.14159265358979323846 / w * (cos_theta_[j] - cos_theta_[j + 1]);
      double row = 0;
      double* cc = &col_cdf_[std::size_t(j) * (w + 1)];
      for (int i = 0; i < w; ++i) {
        row += lum[std::size_t(j) * w + i];
        cc[i + 1] = row;
      }
      for (int i = 1; i <= w; ++i) cc[i] = row > 0 ? cc[i] / row : double(i) / w;
      cc[w] = 1;
      norm += row * omega;
      row_cdf_[j + 1] = norm;
    }
    for (int j = 1; j <= h; ++j) row_cdf_[j] /= norm;
    row_cdf_[h] = 1;
    pixel_pdf_.resize(lum.size());
    for (std::size_t k = 0; k < lum.size(); ++k) pixel_pdf_[k] = lum[k] / norm;
  }

  LatLongImage image_;
  std::vector<double> cos_theta_;  // H + 1 row boundaries, cos θ_j
  std::vector<double> row_cdf_;    // H + 1: marginal CDF of rows
  std::vector<double> col_cdf_;    // H × (W + 1): conditional CDF of columns per row
  std::vector<double> pixel_pdf_;  // W × H: density per unit solid angle
};

}  // namespace glintlab

// Procedural height field as a sum of sines, h(u, v) = Σ a_k sin(2π k_k·(u, v) + φ_k), with its
// analytic slopes ∂h/∂u, ∂h/∂v and normal (−∂h/∂u, −∂h/∂v, 1)/‖·‖, the slope form of normal
// mapping that LEAN mapping filters (Olano & Baker 2010 Sec. 3). Integer wave vectors make it tile
// the unit uv square. Two presets: isotropic bumps (wave vectors of equal length at angles whose
// tensor Σ k̂k̂ᵀ is isotropic) and brushed grooves (wave vectors along one direction plus a weak
// cross wave: strongly anisotropic, with a rotated covariance, ρ ≠ 0).
#pragma once

#include <cmath>
#include <vector>

#include "core/math/vec.h"
#include "core/parameter_check.h"

namespace glintlab {

inline constexpr int kMaxSineWaves = 16;

template <class T>
struct SineWave {
  T ku, kv;     // cycles per unit u and v (integers, so the field tiles [0, 1)²)
  T amplitude;  // in the units of u and v
  T phase;      // rad
};

// Height, slopes and unit normal at one uv (normal in the tangent frame: x along u, y along v).
template <class T>
struct SurfacePoint {
  T height;
  T slope_u, slope_v;  // ∂h/∂u, ∂h/∂v
  Vec3<T> normal;
};

template <class T>
struct SineHeightField {
  SineWave<T> wave[kMaxSineWaves];
  int count;

  GLINTLAB_FN SurfacePoint<T> eval(T u, T v) const {
    T h = T(0), hu = T(0), hv = T(0);
    for (int k = 0; k < count; ++k) {
      const SineWave<T>& w = wave[k];
      T s, c;
      sincos(T(2 * kPi<T>) * (w.ku * u + w.kv * v) + w.phase, &s, &c);
      h = fma(w.amplitude, s, h);
      const T g = T(2 * kPi<T>) * w.amplitude * c;
      hu = fma(g, w.ku, hu);
      hv = fma(g, w.kv, hv);
    }
    return {h, hu, hv, normalize(Vec3<T>{-hu, -hv, T(1)})};
  }

  // The slope covariance over one period, E[s sᵀ] = Σ a² (2π)² k kᵀ / 2, with E[s] = 0 (distinct,
  // non-opposite integer wave vectors are orthogonal over the unit square). {xx, yy, xy}.
  Vec3<double> slope_covariance() const {
    Vec3<double> c{0, 0, 0};
    for (int k = 0; k < count; ++k) {
      const double g = 2 * 3.14159265358979323846 * double(wave[k].amplitude);
      const double f = 0.5 * g * g;
      c = c + Vec3<double>{f * double(wave[k].ku) * double(wave[k].ku),
                           f * double(wave[k].kv) * double(wave[k].kv),
                           f * double(wave[k].ku) * double(wave[k].kv)};
    }
    return c;
  }
};

namespace detail {
// Phases from a fixed irrational rotation, so presets are deterministic and the waves uncorrelated.
inline double preset_phase(int k) {
  return 2 * 3.14159265358979323846 * std::fmod(0.6180339887498949 * (k + 1), 1.0);
}

template <class T>
SineHeightField<T> scaled_field(const std::vector<SineWave<double>>& waves, double slope_rms) {
  SineHeightField<double> d{};
  d.count = int(waves.size());
  for (int k = 0; k < d.count; ++k) d.wave[k] = waves[k];
  const Vec3<double> c = d.slope_covariance();
  const double scale = slope_rms / std::sqrt(0.5 * (c.x + c.y));
  SineHeightField<T> f{};
  f.count = d.count;
  for (int k = 0; k < d.count; ++k)
    f.wave[k] = {T(waves[k].ku), T(waves[k].kv), T(scale * waves[k].amplitude), T(waves[k].phase)};
  return f;
}
}  // namespace detail

// Isotropic bumps: two octaves of six wave vectors each, |k| = 5 ((5,0), (0,5), (3,4), (4,3),
// (−3,4), (−4,3)) and |k| = 13 ((13,0), (0,13), (5,12), (12,5), (−5,12), (−12,5)); in each octave
// Σ k̂k̂ᵀ = 3·I, so the slope covariance is isotropic. The second octave has (5/13)² the amplitude
// (so 5/13 the slope). Scaled to an rms slope per axis of `slope_rms`.
template <class T = double>
SineHeightField<T> isotropic_sine_bumps(double slope_rms) {
  detail::require(std::isfinite(slope_rms) && slope_rms > 0, "isotropic sine bumps", "slope_rms",
                  slope_rms, "a finite slope_rms > 0");
  const int k1[6][2] = {{5, 0}, {0, 5}, {3, 4}, {4, 3}, {-3, 4}, {-4, 3}};
  const int k2[6][2] = {{13, 0}, {0, 13}, {5, 12}, {12, 5}, {-5, 12}, {-12, 5}};
  std::vector<SineWave<double>> w;
  for (int k = 0; k < 6; ++k)
    w.push_back({double(k1[k][0]), double(k1[k][1]), 1.0, detail::preset_phase(k)});
  const double a2 = (5.0 / 13.0) * (5.0 / 13.0);
  for (int k = 0; k < 6; ++k)
    w.push_back({double(k2[k][0]), double(k2[k][1]), a2, detail::preset_phase(6 + k)});
  return detail::scaled_field<T>(w, slope_rms);
}

// Brushed grooves: the grooves run perpendicular to the integer direction (p, q); across them,
// four harmonics m·(p, q), m ∈ {7, 11, 17, 23}, with amplitudes ∝ 1/m (equal slope each); along
// them one weak wave 3·(−q, p). `anisotropy` = rms slope across / rms slope along (> 1). Scaled to
// an rms slope per axis (√(tr Σ / 2)) of `slope_rms`.
template <class T = double>
SineHeightField<T> brushed_grooves(double slope_rms, double anisotropy = 8, int p = 1, int q = 2) {
  const char* what = "brushed grooves";
  detail::require(std::isfinite(slope_rms) && slope_rms > 0, what, "slope_rms", slope_rms,
                  "a finite slope_rms > 0");
  detail::require(std::isfinite(anisotropy) && anisotropy >= 1, what, "anisotropy", anisotropy,
                  "a finite anisotropy >= 1");
  detail::require(p != 0 || q != 0, what, "direction (p, q)", 0, "integers, not both 0");
  std::vector<SineWave<double>> w;
  const int ms[4] = {7, 11, 17, 23};
  for (int k = 0; k < 4; ++k)
    w.push_back({double(ms[k] * p), double(ms[k] * q), 1.0 / ms[k], detail::preset_phase(k)});
  // Across: Σ_m (2π a_m m)²/2 |pq|² = 4 (2π)²/2 |pq|²; along: (2π a 3)²/2 |pq|².
  const double across = std::sqrt(4.0);
  const double a_along = across / anisotropy / 3.0;
  w.push_back({double(-3 * q), double(3 * p), a_along, detail::preset_phase(4)});
  return detail::scaled_field<T>(w, slope_rms);
}

}  // namespace glintlab

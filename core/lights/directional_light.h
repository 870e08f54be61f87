// Directional light with an opening angle: radiance arriving from the spherical cap of half-angle γ
// about a fixed direction, the same from every shading point (Kneiphof & Klein 2024 Sec. 5 and
// Fig. 6: γ ∈ {0.26°, 5°}, |Ω_i| = 2π(1 − cos γ) in Eq. 20). Sampled uniformly over the cap.
#pragma once

#include "core/lights/light_sample.h"
#include "core/lights/spherical_cap.h"
#include "core/parameter_check.h"

namespace glintlab {

template <class T>
struct DirectionalLight {
  SphericalCap<T> cap;  // axis: unit direction towards the light
  Vec3<T> emitted;      // RGB radiance inside the cap

  GLINTLAB_FN T solid_angle(Vec3<T>) const { return cap_solid_angle(cap); }
  GLINTLAB_FN T pdf(Vec3<T>, Vec3<T> wi) const { return cap_pdf(cap, wi); }
  GLINTLAB_FN Vec3<T> radiance(Vec3<T>, Vec3<T> wi) const {
    return select(cap_contains(cap, wi), emitted, Vec3<T>{T(0), T(0), T(0)});
  }
  GLINTLAB_FN LightSample<T> sample(Vec3<T>, Vec2<T> u) const {
    return {sample_cap(cap, u), infinite_distance<T>(), emitted, T(1) / cap_solid_angle(cap),
            Mask<T>(true)};
  }
};

// Radiance that gives normal irradiance E⊥ from a cap of half-angle γ: E⊥ = L ∫_cap cos θ dω =
// L π sin²γ, so L = E⊥ / (π sin²γ).
inline double directional_radiance_for_irradiance(double irradiance, double half_angle) {
  return irradiance / (3.14159265358979323846 * std::sin(half_angle) * std::sin(half_angle));
}

// A validated directional light (host side). `to_light`: any non-zero vector towards the light;
// half_angle γ in radians, 0 < γ < π/2; radiance >= 0.
template <class T = double>
DirectionalLight<T> make_directional_light(Vec3<double> to_light, double half_angle,
                                           Vec3<double> radiance) {
  const char* what = "directional light";
  const Vec3<double> a = detail::require_direction(what, "direction", to_light);
  detail::require(std::isfinite(half_angle) && half_angle > 0 && half_angle < 1.5707963267948966,
                  what, "half_angle", half_angle,
                  "0 < half_angle < pi/2 rad, i.e. (0, 90) degrees");
  detail::require_radiance(what, radiance);
  return {{cast<T>(a), T(one_minus_cos(half_angle))}, cast<T>(radiance)};
}

}  // namespace glintlab

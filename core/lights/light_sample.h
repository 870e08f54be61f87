// The record every light's sampler returns and the interface all lights share (no paper: the
// standard light-sampling contract of Monte Carlo rendering, Veach 1997 Sec. 9.2).
//
// Light interface (static polymorphism; each light in core/lights/ provides, for a shading point p
// and a unit direction wi leaving p):
//   LightSample<T> sample(Vec3<T> p, Vec2<T> u) const;  // u in [0, 1)²
//   T pdf(Vec3<T> p, Vec3<T> wi) const;                  // per unit solid angle; 0 off the light
//   Vec3<T> radiance(Vec3<T> p, Vec3<T> wi) const;       // RGB emitted towards p along −wi; 0 off
//   T solid_angle(Vec3<T> p) const;                      // of the light's support seen from p
// The support is the set of directions with pdf > 0; it is also where radiance may be non-zero, so
// light sampling alone is unbiased. For one-sided emitters (disk, rectangle, polygon) a point
// behind the emitting face sees an empty support: samples are invalid and pdf = 0 everywhere.
// pdf(p, s.wi) equals s.pdf for every valid sample s (up to rounding), and pdf integrates to 1
// over the sphere whenever the support is non-empty.
#pragma once

#include <limits>

#include "core/math/vec.h"

namespace glintlab {

template <class T>
struct LightSample {
  Vec3<T> wi;        // unit direction from the shading point towards the light
  T distance;        // to the emitting point along wi (+infinity for directional and environment)
  Vec3<T> radiance;  // RGB radiance arriving at p along −wi
  T pdf;             // per unit solid angle
  Mask<T> valid;     // false: no sample (empty support, or a rounding failure at its edge)
};

template <class T>
GLINTLAB_FN T infinite_distance() {
  return T(std::numeric_limits<Scalar<T>>::infinity());
}

}  // namespace glintlab

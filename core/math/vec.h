// Small vector types Vec2<T>, Vec3<T> for every float type (scalar, SIMD batch, CUDA).
#pragma once

#include "core/math/ops.h"

namespace glintlab {

template <class T>
struct Vec2 {
  T x, y;
};

template <class T>
struct Vec3 {
  T x, y, z;
};

template <class T>
GLINTLAB_FN Vec2<T> operator+(Vec2<T> a, Vec2<T> b) { return {a.x + b.x, a.y + b.y}; }
template <class T>
GLINTLAB_FN Vec2<T> operator-(Vec2<T> a, Vec2<T> b) { return {a.x - b.x, a.y - b.y}; }
template <class T>
GLINTLAB_FN Vec2<T> operator*(T s, Vec2<T> a) { return {s * a.x, s * a.y}; }
template <class T>
GLINTLAB_FN T dot(Vec2<T> a, Vec2<T> b) { return a.x * b.x + a.y * b.y; }

template <class T>
GLINTLAB_FN Vec3<T> operator+(Vec3<T> a, Vec3<T> b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class T>
GLINTLAB_FN Vec3<T> operator-(Vec3<T> a, Vec3<T> b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class T>
GLINTLAB_FN Vec3<T> operator-(Vec3<T> a) { return {-a.x, -a.y, -a.z}; }
template <class T>
GLINTLAB_FN Vec3<T> operator*(T s, Vec3<T> a) { return {s * a.x, s * a.y, s * a.z}; }
template <class T>
GLINTLAB_FN Vec3<T> operator*(Vec3<T> a, T s) { return {s * a.x, s * a.y, s * a.z}; }
template <class T>
GLINTLAB_FN T dot(Vec3<T> a, Vec3<T> b) { return fma(a.x, b.x, fma(a.y, b.y, a.z * b.z)); }
template <class T>
GLINTLAB_FN Vec3<T> cross(Vec3<T> a, Vec3<T> b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
GLINTLAB_FN T length_sqr(Vec3<T> a) { return dot(a, a); }
template <class T>
GLINTLAB_FN T length(Vec3<T> a) { return sqrt(dot(a, a)); }
template <class T>
GLINTLAB_FN Vec3<T> normalize(Vec3<T> a) { return rsqrt(dot(a, a)) * a; }
template <class T>
GLINTLAB_FN Vec3<T> select(Mask<T> m, Vec3<T> a, Vec3<T> b) {
  return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}
// Mirror reflection of w about the unit normal m: 2 (w.m) m - w.
template <class T>
GLINTLAB_FN Vec3<T> reflect(Vec3<T> w, Vec3<T> m) {
  return (T(2) * dot(w, m)) * m - w;
}

// Convert between float types (e.g. double queries to a float kernel).
template <class U, class T>
GLINTLAB_FN Vec3<U> cast(Vec3<T> a) {
  return {U(a.x), U(a.y), U(a.z)};
}

}  // namespace glintlab

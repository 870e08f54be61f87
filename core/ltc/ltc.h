// Linearly transformed cosines (LTC): lobe density, sampling and polygon integral with horizon
// clipping. Heitz, Dupuy, Hill, Neubelt 2016, "Real-time polygonal-light shading with linearly
// transformed cosines", Eq. 1 (density), Eq. 2 (Jacobian), Sec. 3.1 (sampling), Eq. 10–11 and
// Sec. 3.2 (polygon integral = the clamped cosine's form factor of the transformed polygon).
#pragma once

#include "core/lights/planar_emitter.h"
#include "core/math/ops.h"
#include "core/math/vec.h"

namespace glintlab {

// An LTC lobe in the local shading frame (z = normal). D_ltc(ω) is the clamped cosine
// D_o(ω_o) = max(0, ω_o.z)/π mapped by the 3×3 matrix M (ω = Mω_o/|Mω_o|); it integrates to 1
// over the sphere, and amplitude · D_ltc approximates the fitted target (the directional albedo
// for the BRDF·cos lobe, D_PR of Kneiphof & Klein 2024 Eq. 19 for the NDF lobe). Build it with
// make_ltc_lobe, which fills m and det_m_inv from m_inv.
template <class T>
struct LtcLobe {
  T m_inv[3][3];  // M⁻¹, row-major: ω_o ∝ M⁻¹ω. Any non-zero scale of M⁻¹ is the same lobe.
  T m[3][3];    // M = (M⁻¹)⁻¹, for sampling
  T det_m_inv;  // |det M⁻¹|, the numerator of the Jacobian (Heitz et al. 2016 Eq. 2)
  T amplitude;  // the scale of the normalized lobe (not used by ltc_density/polygon_integral)
};

template <class T>
GLINTLAB_FN Vec3<T> ltc_mul(const T (&a)[3][3], Vec3<T> v) {
  return {fma(a[0][0], v.x, fma(a[0][1], v.y, a[0][2] * v.z)),
          fma(a[1][0], v.x, fma(a[1][1], v.y, a[1][2] * v.z)),
          fma(a[2][0], v.x, fma(a[2][1], v.y, a[2][2] * v.z))};
}

// The lobe with inverse matrix m_inv (row-major) and the given amplitude; M by the adjugate. A
// singular m_inv gives det_m_inv = 0 and M = 0 (density 0 everywhere): kernels do not throw.
template <class T>
GLINTLAB_FN LtcLobe<T> make_ltc_lobe(const T (&m_inv)[3][3], T amplitude) {
  LtcLobe<T> l;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) l.m_inv[r][c] = m_inv[r][c];
  const T(&a)[3][3] = m_inv;
  const T c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  const T c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  const T c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  const T det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
  const Mask<T> ok = abs(det) > T(0);
  const T inv = select(ok, T(1) / select(ok, det, T(1)), T(0));
  l.m[0][0] = c00 * inv;
  l.m[1][0] = c01 * inv;
  l.m[2][0] = c02 * inv;
  l.m[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) * inv;
  l.m[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) * inv;
  l.m[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) * inv;
  l.m[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) * inv;
  l.m[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) * inv;
  l.m[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) * inv;
  l.det_m_inv = abs(det);
  l.amplitude = amplitude;
  return l;
}

// The isotropic-table form (Heitz et al. 2016 Sec. 4: M has zeros where it would couple y with x
// or z): M⁻¹ = [[a, 0, b], [0, 1, 0], [c, 0, d]] for a view direction in the xz-plane (φ_o = 0),
// the layout of core/ltc/ltc_table.h.
template <class T>
GLINTLAB_FN LtcLobe<T> make_ltc_lobe_isotropic(T a, T b, T c, T d, T amplitude) {
  const T m_inv[3][3] = {{a, T(0), b}, {T(0), T(1), T(0)}, {c, T(0), d}};
  return make_ltc_lobe(m_inv, amplitude);
}

// A lobe fitted for a view in the xz-plane, re-expressed for the shading-frame view direction wo
// (any azimuth): M⁻¹' = M⁻¹ R with R the rotation about z taking wo's azimuth to φ = 0. At
// normal incidence (no azimuth) R = identity.
template <class T>
GLINTLAB_FN LtcLobe<T> ltc_rotate_to_view(const LtcLobe<T>& lobe, Vec3<T> wo) {
  const T l2 = wo.x * wo.x + wo.y * wo.y;
  const Mask<T> tilted = l2 > T(0);
  const T inv = rsqrt(select(tilted, l2, T(1)));
  const T c = select(tilted, wo.x * inv, T(1)), s = select(tilted, wo.y * inv, T(0));
  T m_inv[3][3];
  for (int r = 0; r < 3; ++r) {
    // Row r of M⁻¹ times R = [[c, s, 0], [−s, c, 0], [0, 0, 1]].
    m_inv[r][0] = lobe.m_inv[r][0] * c - lobe.m_inv[r][1] * s;
    m_inv[r][1] = lobe.m_inv[r][0] * s + lobe.m_inv[r][1] * c;
    m_inv[r][2] = lobe.m_inv[r][2];
  }
  return make_ltc_lobe(m_inv, lobe.amplitude);
}

// Normalized density D_ltc(ω) for a unit direction ω (Heitz et al. 2016 Eq. 1 with the Jacobian
// |M⁻¹| / |M⁻¹ω|³ of Eq. 2): ∫_S² D_ltc = 1.
template <class T>
GLINTLAB_FN T ltc_density(const LtcLobe<T>& lobe, Vec3<T> w) {
  const Vec3<T> v = ltc_mul(lobe.m_inv, w);
  const T l2 = dot(v, v);
  const Mask<T> ok = (l2 > T(0)) && (v.z > T(0));
  // D_o(v/l) · |M⁻¹| / l³ with D_o = (v.z / l)/π and l = |v|: v.z |M⁻¹| / (π l⁴).
  const T l4 = sqr(select(ok, l2, T(1)));
  return select(ok, v.z * lobe.det_m_inv * kInvPi<T> / l4, T(0));
}

// amplitude · D_ltc(ω): the lobe's approximation of its target.
template <class T>
GLINTLAB_FN T ltc_eval(const LtcLobe<T>& lobe, Vec3<T> w) {
  return lobe.amplitude * ltc_density(lobe, w);
}

template <class T>
struct LtcSample {
  Vec3<T> dir;  // unit, local shading frame
  T pdf;        // ltc_density(lobe, dir), solid angle
};

// Sample D_ltc (Heitz et al. 2016 Sec. 3.1): a cosine-distributed ω_o (Malley's method: uniform
// disk lifted to the hemisphere), mapped to ω = Mω_o/|Mω_o|. u in [0, 1)².
template <class T>
GLINTLAB_FN LtcSample<T> ltc_sample(const LtcLobe<T>& lobe, Vec2<T> u) {
  T s, c;
  sincos(T(2 * kPi<T>) * u.y, &s, &c);
  const T r = sqrt(u.x);
  const Vec3<T> wo{r * c, r * s, safe_sqrt(T(1) - u.x)};
  const Vec3<T> v = ltc_mul(lobe.m, wo);
  const T l2 = dot(v, v);
  const Vec3<T> w = rsqrt(select(l2 > T(0), l2, T(1))) * v;
  return {w, ltc_density(lobe, w)};
}

namespace detail {

// Unit vector along v, or 0 for the zero vector.
template <class T>
GLINTLAB_FN Vec3<T> ltc_unit(Vec3<T> v) {
  const T l2 = dot(v, v);
  const Mask<T> ok = l2 > T(0);
  return select(ok, rsqrt(select(ok, l2, T(1))), T(0)) * v;
}

// One edge's term of Lambert's form factor (Heitz et al. 2016 Eq. 11): the arc angle θ between
// the unit vectors a and b times the z component of the unit normal of their great circle,
// written θ · (a × b).z / sin θ so it stays finite as the edge shrinks (θ/sin θ → 1).
template <class T>
GLINTLAB_FN T ltc_edge_term(Vec3<T> a, Vec3<T> b) {
  const Vec3<T> n = cross(a, b);
  const T sin_t = length(n);
  const T theta = atan2(sin_t, dot(a, b));
  const Mask<T> ok = sin_t > T(1e-7);
  return n.z * select(ok, theta / select(ok, sin_t, T(1)), T(1));
}

}  // namespace detail

namespace detail {

// Lambert's form factor of the polygon's part above the horizon, signed: positive when the
// vertices appear counter-clockwise seen from the origin (Heitz et al. 2016 Eq. 11, Sec. 3.2).
// Branch-free clipping: each edge is clipped to z ≥ 0, and the horizon arc from where the polygon
// leaves the upper hemisphere to where it re-enters closes it (a convex polygon crosses the
// horizon plane at most twice).
template <class T>
GLINTLAB_FN T ltc_signed_form_factor(const Vec3<T>* vertices, int n) {
  T sum = T(0);
  Vec3<T> exit{T(0), T(0), T(0)}, entry{T(0), T(0), T(0)};
  Mask<T> clipped = Mask<T>(false);
  for (int k = 0; k < n; ++k) {
    const Vec3<T> a = vertices[k], b = vertices[k + 1 < n ? k + 1 : 0];
    const Mask<T> a_up = a.z > T(0), b_up = b.z > T(0);
    const Mask<T> crosses = a_up != b_up;
    const T dz = a.z - b.z;
    const T t = select(crosses, a.z / select(crosses, dz, T(1)), T(0));
    Vec3<T> q = a + t * (b - a);
    q.z = T(0);  // exactly on the horizon
    const Vec3<T> s = select(a_up, a, q), e = select(b_up, b, q);
    const T term = ltc_edge_term(ltc_unit(s), ltc_unit(e));
    sum = sum + select(a_up || b_up, term, T(0));
    exit = select(a_up && !b_up, q, exit);
    entry = select(!a_up && b_up, q, entry);
    clipped = clipped || (a_up && !b_up);
  }
  sum = sum + select(clipped, ltc_edge_term(ltc_unit(exit), ltc_unit(entry)), T(0));
  // Counter-clockwise seen from the origin makes each (a × b).z negative: hence the minus sign.
  return -sum * T(0.5) * kInvPi<T>;
}

}  // namespace detail

// ∫ over a convex polygon of the clamped cosine max(0, ω.z)/π (Lambert's form factor with
// horizon clipping, Heitz et al. 2016 Eq. 10–11 and Sec. 3.2). `vertices` are positions relative
// to the shading point in the local frame (not necessarily unit), n of them (3 ≤ n ≤
// kMaxPolygonVertices; n is the same for every lane). Counted when the vertices appear
// counter-clockwise seen from the origin (the polygon lights' winding seen from their front side),
// else 0; with two_sided, either winding counts. A polygon whose plane contains the origin is
// degenerate (value unspecified): validate polygons on the host (core/ltc/ltc_polygon_check.h).
template <class T>
GLINTLAB_FN T clamped_cosine_polygon_integral(const Vec3<T>* vertices, int n,
                                              bool two_sided = false) {
  const T value = detail::ltc_signed_form_factor(vertices, n);
  return two_sided ? abs(value) : max(value, T(0));
}

// ∫ over a convex polygon of the normalized LTC lobe D_ltc (Heitz et al. 2016 Eq. 10: the
// polygon transformed by M⁻¹ and integrated against the clamped cosine). Same vertex convention
// and limits as clamped_cosine_polygon_integral; multiply by lobe.amplitude for the lobe's
// approximation of its target's integral (e.g. Kneiphof & Klein 2024 Eq. 13 with the D_PR scale
// of Sec. 5).
template <class T>
GLINTLAB_FN T ltc_polygon_integral(const LtcLobe<T>& lobe, const Vec3<T>* vertices, int n,
                                   bool two_sided = false) {
  const int count = n < kMaxPolygonVertices ? n : kMaxPolygonVertices;
  Vec3<T> p[kMaxPolygonVertices];
  for (int k = 0; k < count; ++k) p[k] = ltc_mul(lobe.m_inv, vertices[k]);
  // A map with det M⁻¹ < 0 reverses the winding: undo that so the front side stays the front.
  const T(&a)[3][3] = lobe.m_inv;
  const T det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) +
                a[0][1] * (a[1][2] * a[2][0] - a[1][0] * a[2][2]) +
                a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  const T value = select(det < T(0), T(-1), T(1)) * detail::ltc_signed_form_factor(p, count);
  return two_sided ? abs(value) : max(value, T(0));
}

// The same for a polygon light's unit vertex directions (core/lights/planar_emitter.h), already
// rotated into the shading frame by the caller.
template <class T>
GLINTLAB_FN T ltc_polygon_integral(const LtcLobe<T>& lobe, const PolygonVertices<T>& poly,
                                   bool two_sided = false) {
  return ltc_polygon_integral(lobe, poly.v, poly.count, two_sided);
}

}  // namespace glintlab

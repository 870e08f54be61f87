// The density eto.pdf-matches holds the bounded VNDF sampler's reflections to
// (verify/claims/eto/pdf_matches.cpp), in its own header for its test.
#pragma once

#include <cmath>
#include <span>

#include "core/math/vec.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/bounded_vndf.h"
#include "verify/stats/chi_square.h"

namespace glintlab::verify::eto_claims {

// What Eq. 8's density needs of ω_i, computed once per configuration: α, ω_i, k (Eq. 6 or the
// exact bound), t = ‖(αx i_x, αy i_y, i_z)‖ and î, the stretched ω_i.
struct Eq8Incidence {
  double ax, ay;
  Vec3<double> i;
  double k, t;
  Vec3<double> i_std;
};

// Eq. 8 × ‖dm/do‖ = 2 D(m) max(i·m, 0) χ⁺(k î_z + ô_z) / (k i_z + t) / (4|i·m|) for i_z > 0, ô the
// stretched reflection of î about m̂ ∝ (m_x/αx, m_y/αy, m_z). On any float type (double, or double
// lanes: the same IEEE operations in the same order, so the same bits lane by lane). Where i·m ≤ 0
// or χ⁺ = 0 the density is +0: k i_z + t ≥ (1 + k) i_z > 0 (k > −1, t ≥ i_z) and D(m) is finite,
// so the product with χ⁺ = 0 is +0 too.
template <class T>
GLINTLAB_INLINE T eq8_front_density(const GGX<T>& g, Vec3<T> i, T k, T t, Vec3<T> i_std,
                                    Vec3<T> o) {
  const Vec3<T> m = half_vector(i, o);
  const T im = dot(i, m);
  const Vec3<T> m_std = normalize(Vec3<T>{m.x / g.alpha_x, m.y / g.alpha_y, m.z});
  const Vec3<T> o_std = T(2) * dot(i_std, m_std) * m_std - i_std;
  const T p_m = T(2) * g.D(m) * im / (k * i.z + t);
  const T density = p_m / (T(4) * abs(im));
  return select(im > T(0), select(k * i_std.z + o_std.z > T(0), density, T(0)), T(0));
}

// Eq. 8's density of one configuration; for i_z ≤ 0, Eq. 7 (the full cap) as printed.
class Eq8ReflectionPdf {
 public:
  Eq8ReflectionPdf(const GGX<double>& g, const Vec3<double>& i, BoundedVndfBound bound)
      : a_{g.alpha_x,
           g.alpha_y,
           i,
           i.z <= 0 ? 0 : bounded_vndf_k(g, i, bound),
           std::sqrt(sqr(g.alpha_x * i.x) + sqr(g.alpha_y * i.y) + sqr(i.z)),
           normalize(Vec3<double>{g.alpha_x * i.x, g.alpha_y * i.y, i.z})} {}

  double operator()(const Vec3<double>& o) const {
    const GGX<double> g{a_.ax, a_.ay};
    if (a_.i.z <= 0) return pdf_vndf_backfacing_eq7(g, a_.i, o);
    return eq8_front_density(g, a_.i, a_.k, a_.t, a_.i_std, o);
  }

  // The same density at many directions per call, for the cubature of the expected counts
  // (ChiSquareOptions::direction_pdf_rows): in double lanes of simd::default_isa() (GLINTLAB_ISA
  // or the CPU's widest), one direction at a time on the scalar ISA; the same bits either way
  // (verify/claims/eto/eq8_density.cpp).
  DirectionPdfRows rows() const;

 private:
  Eq8Incidence a_;
};

}  // namespace glintlab::verify::eto_claims

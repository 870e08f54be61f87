// The density eto.pdf-matches holds the bounded VNDF sampler's reflections to
// (verify/claims/eto/pdf_matches.cpp), in its own header for its test.
#pragma once

#include <cmath>

#include "core/math/vec.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/bounded_vndf.h"

namespace glintlab::verify::eto_claims {

// Eq. 8 × ‖dm/do‖ = 2 D(m) max(i·m, 0) χ⁺(k î_z + ô_z) / (k i_z + t) / (4|i·m|), t = ‖(αx i_x,
// αy i_y, i_z)‖, ô the stretched reflection of î about m̂ ∝ (m_x/αx, m_y/αy, m_z); for i_z ≤ 0,
// Eq. 7 (the full cap) as printed. What depends on i alone (k, t, î) is computed once per
// configuration (the cubature evaluates the density some 10^7 times): the same operations on the
// same inputs, so the same bits. Where χ⁺ = 0 the density is +0 without D(m): k i_z + t ≥
// (1 + k) i_z > 0 (k > −1, t ≥ i_z) and D(m) is finite, so its product with χ⁺ = 0 was +0 too.
class Eq8ReflectionPdf {
 public:
  Eq8ReflectionPdf(const GGX<double>& g, const Vec3<double>& i, BoundedVndfBound bound)
      : g_(g),
        i_(i),
        k_(i.z <= 0 ? 0 : bounded_vndf_k(g, i, bound)),
        t_(std::sqrt(sqr(g.alpha_x * i.x) + sqr(g.alpha_y * i.y) + sqr(i.z))),
        i_std_(normalize(Vec3<double>{g.alpha_x * i.x, g.alpha_y * i.y, i.z})) {}

  double operator()(const Vec3<double>& o) const {
    if (i_.z <= 0) return pdf_vndf_backfacing_eq7(g_, i_, o);
    const Vec3<double> m = half_vector(i_, o);
    const double im = dot(i_, m);
    if (!(im > 0)) return 0;
    const Vec3<double> m_std = normalize(Vec3<double>{m.x / g_.alpha_x, m.y / g_.alpha_y, m.z});
    const Vec3<double> o_std = 2 * dot(i_std_, m_std) * m_std - i_std_;
    if (!(k_ * i_std_.z + o_std.z > 0)) return 0;  // χ⁺ = 0
    const double p_m = 2 * g_.D(m) * im / (k_ * i_.z + t_);
    return p_m / (4 * std::abs(im));
  }

 private:
  GGX<double> g_;
  Vec3<double> i_;
  double k_, t_;
  Vec3<double> i_std_;
};

}  // namespace glintlab::verify::eto_claims

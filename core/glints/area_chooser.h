// The engine chooser of the area family: which level of the binomial family
// (core/glints/adequacy.h: smooth, realtime, small_count, exact) a pixel of kneiphof_klein_area
// needs (Kneiphof & Klein 2024 Sec. 4, core/glints/kneiphof_ltc.h). The count is b ~ Binomial(N_P,
// p) (Eq. 11) with p = D_Ωh / D_H (Eq. 12), D_Ωh = D_PR · ∫_Ωi D_ltc over the light's polygon (Eq.
// 13 through the BRDF LTC lobe, Eq. 17–19), and the pixel value is L_o/L_i · b/(N_P p) (Eq. 16):
// every level shares the factor L_o/L_i, so the pixel's distribution over surface positions is the
// count's and the binomial chooser's closed forms hold with this p, whatever made it. What is new
// here is only the p: N_P from the footprint and p from the LTC terms exactly as the model computes
// them, then choose_binomial_level. docs/adequacy.md "The area chooser" has its counts against the
// measured table.
//
// Scalar only (templated on the scalar type, used and tested in double; the model itself is double
// only, kDoubleOnly, and not batched): the LTC table is indexed per lane (ltc_ggx_lookup). An engine
// on lanes computes p per lane with kneiphof_klein_area_count_inputs and runs choose_binomial_level,
// which is templated and branch-free, on the batch. No allocation, no exceptions, no virtual calls.
#pragma once

#include <type_traits>

#include "core/glints/adequacy.h"
#include "core/glints/kneiphof_ltc.h"

namespace glintlab {

// N_P and the unclamped p of a footprint under a convex polygon light (vertices relative to the
// shading point, counter-clockwise seen from it; kneiphof2024::area_light_terms_ltc), for isotropic
// GGX α with total area D_H (Eq. 29) and 10^density facets per unit uv area (density_scale,
// facet_density_scale): N_P = footprint_facet_count_scaled, p = D_Ωh / D_H where ω_i is above the
// horizon, else 0 (Eq. 12; the model clamps p to [0, 1], choose_binomial_level does too). `lobe`:
// D_Ωh's LTC lobe (kBrdfLobe, the paper's; kMonteCarlo is taken as kBrdfLobe, the model's Monte
// Carlo estimate of D_Ωh being a noisy estimate of the same integral).
template <class T>
struct AreaCountInputs {
  T facets, p;
};
template <class T>
AreaCountInputs<T> kneiphof_klein_area_count_inputs(const LtcTableView& table, T alpha,
                                                    T total_area, T density_scale,
                                                    const FootprintQuery<T>& footprint, Vec3<T> wi,
                                                    const Vec3<T>* vertices, int n,
                                                    kneiphof2024::AreaP lobe) {
  static_assert(std::is_floating_point_v<T>, "the area chooser indexes the LTC table per lane");
  const kneiphof2024::LtcAreaTerms<T> t =
      kneiphof2024::area_light_terms_ltc(table, alpha, wi, vertices, n, lobe);
  return {footprint_facet_count_scaled(footprint, density_scale),
          wi.z > T(0) ? t.d_omega_h / total_area : T(0)};
}

// The level (its BinomialLevel value as T) for that footprint and light at threshold tau.
template <class T>
T choose_kneiphof_klein_area_level(const LtcTableView& table, T alpha, T total_area,
                                   T density_scale, const FootprintQuery<T>& footprint, Vec3<T> wi,
                                   const Vec3<T>* vertices, int n, T tau,
                                   kneiphof2024::AreaP lobe = kneiphof2024::AreaP::kBrdfLobe) {
  const AreaCountInputs<T> in = kneiphof_klein_area_count_inputs(
      table, alpha, total_area, density_scale, footprint, wi, vertices, n, lobe);
  return choose_binomial_level(in.facets, in.p, tau);
}

// The same on what a shader of kneiphof_klein_area has: its parameters (the rectangle centred
// along the query's ω_o at light_distance, facing the shading point, turned and tilted as the
// parameters say; the LTC table; D_H; the density) and the query. N_P and p are the model's eval
// intermediates N_P and p_unclamped bit for bit where area_p is an LTC lobe (ltc, ltc_ndf); with
// area_p = mc the BRDF LTC lobe stands for the model's Monte Carlo D_Ωh.
inline AreaCountInputs<double> kneiphof_klein_area_model_count_inputs(
    const KneiphofKleinArea::Params<double>& p, const ModelQuery<double>& q) {
  const auto rect =
      kneiphof2024::facing_rectangle(q.wo, p.distance, p.width, p.height, p.rotation, p.tilt);
  return kneiphof_klein_area_count_inputs(*p.table, p.alpha, p.total_area,
                                          facet_density_scale<double>(p.log10_density), q.footprint,
                                          q.wi, rect.data(), 4, p.area_p);
}
inline double choose_kneiphof_klein_area_model_level(const KneiphofKleinArea::Params<double>& p,
                                                     const ModelQuery<double>& q, double tau) {
  const AreaCountInputs<double> in = kneiphof_klein_area_model_count_inputs(p, q);
  return choose_binomial_level(in.facets, in.p, tau);
}

}  // namespace glintlab

// Podee, Max, Iwasaki & Dobashi (micro-specular highlights, Sec. 3.1–3.2) as a model
// (core/model.h): a mirror pixel under a disk light, shaded with the most intense reflection
// vector of the reflection space and weighted by area(projected disk ∩ reflection space) /
// area(reflection space) (core/shading/podee_shade.h).
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string_view>

#include "core/model.h"
#include "core/ndf/ggx.h"
#include "core/samplers/heitz_vndf.h"
#include "core/shading/podee_shade.h"

namespace glintlab {

struct Podee {
  static constexpr std::string_view kName = "podee";
  // Conformance (verify/conformance/): what the model does not claim.
  static constexpr std::array<NotClaimed, 1> kNotClaimed = {{
      {"converges-to-smooth",
       "a mirror pixel's highlight under a disk light: the footprint enters only through its four "
       "corner reflection vectors and the model defines no smooth NDF it tends to; its GGX "
       "(alpha_x, alpha_y) only drives the sampler"},
  }};
  static constexpr std::string_view kDescription =
      "micro-specular highlight of a mirror pixel under a disk light: the reflection vector of the "
      "pixel's reflection space closest to the light's centre, times the covered fraction of the "
      "reflection space. value = reflected radiance per unit light radiance (wo = toward the "
      "disk's centre, light_cos_half_angle = its angular radius, the four corner reflection "
      "vectors r0..r3 in the local frame). The paper has no sampler: sample/pdf are Heitz 2018 "
      "GGX VNDF sampling with alpha_x, alpha_y, which do not enter value";
  static constexpr std::string_view kSource =
      "Podee, Max, Iwasaki & Dobashi, Micro-specular-highlight real-time rendering, Sec. 3.1 "
      "(selection), Sec. 3.2 (weighting), Fig. 2-3; sampler Heitz 2018";
  static constexpr unsigned kNeeds = kNeedsFootprint | kNeedsAreaLight | kNeedsPixelCorners;

  static constexpr std::array<std::string_view, 3> kWeightingNames = {"exact", "quad_as_circle",
                                                                      "none"};
  static constexpr std::array<std::string_view, 3> kSelectionNames = {"closest_point",
                                                                      "nearest_corner", "centroid"};
  static constexpr std::array<ParamSpec, 4> kParams = {{
      {"weighting", 0.0, 0.0, 2.0, false, false,
       "result weight (Sec. 3.2): exact circle-quad area, quad_as_circle (the reflection space as "
       "an equal-area circle: closed-form lens), none (weight 1, ablation)",
       kWeightingNames},
      {"selection", 0.0, 0.0, 2.0, false, false,
       "reflection vector selection (Sec. 3.1): closest_point (the paper's); nearest_corner and "
       "centroid are wrong rules kept as negative controls",
       kSelectionNames},
      {"alpha_x", 0.05, 1e-4, 1.0, false, false,
       "sampling only: GGX roughness along x of the VNDF sampler (the mirror has no lobe)"},
      {"alpha_y", 0.05, 1e-4, 1.0, false, false,
       "sampling only: GGX roughness along y of the VNDF sampler"},
  }};
  static constexpr std::array<std::string_view, 8> kIntermediates = {
      "r_x", "r_y", "r_z", "weight", "inside", "lit", "distance", "quad_area"};

  template <class T>
  struct Params {
    podee::Weighting weighting;  // uniform choices (not per lane)
    podee::Selection selection;
    GGX<T> sampling;
  };

  template <class T>
  static Params<T> params(std::span<const double> v) {
    return {static_cast<podee::Weighting>(static_cast<int>(v[param_index<Podee>("weighting")])),
            static_cast<podee::Selection>(static_cast<int>(v[param_index<Podee>("selection")])),
            GGX<T>{T(v[param_index<Podee>("alpha_x")]), T(v[param_index<Podee>("alpha_y")])}};
  }

  // The disk light needs a radius (its cone a half-angle > 0) and its centre above the surface.
  static std::optional<QueryViolation> validate(const ModelQuery<double>& q) {
    if (!(q.light.cos_half_angle < 1))
      return QueryViolation{"light_cos_half_angle", "< 1, a disk of radius > 0"};
    if (!(q.wo.z > 0)) return QueryViolation{"wo_z", "> 0, the disk's centre above the surface"};
    return std::nullopt;
  }

  // value = lit × weight where the light's centre is above the surface (wo.z > 0), else 0.
  template <class T>
  GLINTLAB_FN static ModelEval<T, kIntermediates.size()> eval(const Params<T>& p,
                                                              const ModelQuery<T>& q) {
    const podee::Result<T> r =
        podee::shade(q.footprint.corner_r, q.wo, podee::tan_radius(q.light.cos_half_angle),
                     p.weighting, p.selection);
    const Mask<T> above = q.wo.z > T(0);
    return {select(above, r.value, T(0)),
            pdf(p, q),
            {r.r.x, r.r.y, r.r.z, r.weight, select(r.inside, T(1), T(0)), r.lit, r.distance,
             r.quad_area}};
  }

  template <class T>
  GLINTLAB_FN static T pdf(const Params<T>& p, const ModelQuery<T>& q) {
    return pdf_heitz_vndf(p.sampling, q.wi, q.wo);
  }

  template <class T>
  GLINTLAB_FN static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    const MicrofacetSample<T> s = sample_heitz_vndf(p.sampling, q.wi, u);
    // The interface's identity weight = value / pdf, with value evaluated for a light centred on
    // the sampled direction (the same cone); 0 when rejected.
    ModelQuery<T> qs = q;
    qs.wo = s.wo;
    const T value = eval(p, qs).value;
    const Mask<T> ok = !s.rejected && s.pdf > T(0);
    return {s.wo, s.pdf, select(ok, value / select(ok, s.pdf, T(1)), T(0)), s.rejected};
  }
};

static_assert(Model<Podee>);
static_assert(ValidatesQuery<Podee>);  // a changed signature would silently drop the rules

}  // namespace glintlab

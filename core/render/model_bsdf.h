// Any registered-style model (core/model.h) as the BSDF of the Monte Carlo area-light reference
// (core/render/area_light_reference.h), so every model gets an MIS ground truth under area lights.
//
// The two interfaces name directions the other way round: the reference's f(ωo, ωi) has ωo toward
// the viewer and ωi toward the light; a model's query has ω_i toward the viewer and ω_o toward the
// light, and its value is f · max(cos θ_light, 0). The adapter swaps the names and divides the
// cosine back out (the reference multiplies it in again). Each evaluation is for one light
// direction (a delta light in the query's light cone), which is what a model that needs a point
// light is evaluated with; a model that integrates over an extended light itself (kNeedsAreaLight)
// is not a BSDF of this estimator and is refused at compile time.
#pragma once

#include "core/model.h"
#include "core/render/area_light_reference.h"

namespace glintlab {

template <Model M, class T = double>
struct ModelBsdf {
  static_assert((M::kNeeds & kNeedsAreaLight) == 0,
                "a model that integrates an area light itself is not a BSDF of the MIS reference");

  typename M::template Params<T> params;
  FootprintQuery<T> footprint{};  // the pixel footprint, for models that need one

  ModelQuery<T> query(Vec3<T> view, Vec3<T> light) const {
    return {footprint, view, light, LightQuery<T>{T(1), T(1)}};
  }
  // f(view, light) in 1/sr: the model's cosine-weighted value over cos θ_light (0 below the horizon).
  T f(Vec3<T> wo, Vec3<T> wi) const {
    const T value = M::template eval<T>(params, query(wo, wi)).value;
    return select(wi.z > T(0), value / select(wi.z > T(0), wi.z, T(1)), T(0));
  }
  BsdfSample<T> sample(Vec3<T> wo, Vec2<T> u) const {
    const ModelSample<T> s = M::template sample<T>(params, query(wo, Vec3<T>{T(0), T(0), T(1)}), u);
    return {s.wo, s.pdf, s.rejected};
  }
  T pdf(Vec3<T> wo, Vec3<T> wi) const { return M::template pdf<T>(params, query(wo, wi)); }
};

}  // namespace glintlab

// Smooth anisotropic Beckmann reflection as a model (core/model.h): Walter et al. 2007 Eq. 20,
// 25–27; samplers Walter 2007 Eq. 28–29 and the Beckmann VNDF sampler (Heitz & d'Eon 2014).
#pragma once

#include <array>
#include <span>
#include <string_view>

#include "core/model.h"
#include "core/models/smooth_microfacet.h"
#include "core/ndf/beckmann.h"
#include "core/samplers/sampler_list.h"

namespace glintlab {

struct SmoothBeckmann {
  static constexpr std::string_view kName = "smooth_beckmann";
  static constexpr std::string_view kDescription =
      "smooth anisotropic Beckmann reflection, F = 1, height-correlated Smith G2";
  static constexpr std::string_view kSource =
      "Walter et al. 2007 Eq. 20, 25-27; Heitz 2014 Eq. 99; samplers: Walter 2007, Heitz & "
      "d'Eon 2014";
  static constexpr unsigned kNeeds = kNeedsDirections;

  // The Beckmann rows of the sampler list (core/samplers/sampler_list.h) and their `sampler`
  // values.
  using Samplers = samplers::Of<Beckmann>;
  using Choices = samplers::Choices<Samplers>;
  static constexpr const auto& kSamplerNames = Choices::kNames;
  static constexpr std::array<ParamSpec, 3> kParams = {{
      // α ≥ 1e-4, the smallest roughness all.stability sweeps; at α = 1e-20 (float) or 1e-100
      // (double) D and the pdf are already NaN.
      {"alpha_x", 0.5, 1e-4, 100.0, false, false, "roughness along the tangent (x)"},
      {"alpha_y", 0.5, 1e-4, 100.0, false, false, "roughness along the bitangent (y)"},
      {"sampler", 1.0, 0.0, double(kSamplerNames.size() - 1), false, false,
       "sampler of wo: ndf (Walter 2007), vndf (Heitz & d'Eon 2014)", kSamplerNames},
  }};
  static constexpr auto kIntermediates = detail::kSmoothIntermediates;

  template <class T>
  struct Params {
    Beckmann<T> beckmann;
    int sampler;  // the row of Samplers; a uniform choice (not per lane)
  };

  template <class T>
  static Params<T> params(std::span<const double> v) {
    return {Beckmann<T>{T(v[param_index<SmoothBeckmann>("alpha_x")]),
                        T(v[param_index<SmoothBeckmann>("alpha_y")])},
            Choices::index(static_cast<int>(v[param_index<SmoothBeckmann>("sampler")]), 0)};
  }

  template <class T>
  GLINTLAB_FN static T pdf(const Params<T>& p, const ModelQuery<T>& q) {
    return samplers::with<Samplers>(p.sampler,
                                    [&]<class S>() { return S::pdf(p.beckmann, q.wi, q.wo); });
  }

  template <class T>
  GLINTLAB_FN static ModelEval<T, kIntermediates.size()> eval(const Params<T>& p,
                                                              const ModelQuery<T>& q) {
    return detail::smooth_eval(p.beckmann, q, pdf(p, q));
  }

  template <class T>
  GLINTLAB_FN static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    return samplers::with<Samplers>(p.sampler, [&]<class S>() {
      return detail::smooth_sample(p.beckmann, q.wi, S::sample(p.beckmann, q.wi, u));
    });
  }
};

static_assert(Model<SmoothBeckmann>);

}  // namespace glintlab

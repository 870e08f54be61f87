// Smooth anisotropic GGX reflection as a model (core/model.h): Walter et al. 2007 Eq. 20, 33–34;
// samplers Walter 2007 Eq. 35–36, Heitz 2018 VNDF, Dupuy & Benyoub 2023 spherical caps and Eto &
// Tokuyoshi 2023 bounded caps (Eq. 5–8, Listings 1–2), chosen by the `sampler` parameter.
#pragma once

#include <array>
#include <span>
#include <string_view>

#include "core/model.h"
#include "core/models/smooth_microfacet.h"
#include "core/ndf/ggx.h"
#include "core/samplers/sampler_list.h"

namespace glintlab {

struct SmoothGGX {
  static constexpr std::string_view kName = "smooth_ggx";
  static constexpr std::string_view kDescription =
      "smooth anisotropic GGX reflection, F = 1, height-correlated Smith G2";
  static constexpr std::string_view kSource =
      "Walter et al. 2007 Eq. 20, 33-34; Heitz 2014 Eq. 99; samplers: Walter 2007, Heitz 2018, "
      "Dupuy & Benyoub 2023, Eto & Tokuyoshi 2023";
  static constexpr unsigned kNeeds = kNeedsDirections;

  // The GGX rows of the sampler list (core/samplers/sampler_list.h) and their parameter values.
  using Samplers = samplers::Of<GGX>;
  using Choices = samplers::Choices<Samplers>;
  static constexpr const auto& kSamplerNames = Choices::kNames;
  static constexpr const auto& kBoundNames = Choices::kBounds;
  static constexpr std::array<ParamSpec, 4> kParams = {{
      // α ≥ 1e-4, the smallest roughness all.stability sweeps; at α = 1e-20 (float) or 1e-100
      // (double) D and the pdf are already NaN.
      {"alpha_x", 0.5, 1e-4, 100.0, false, false, "roughness along the tangent (x)"},
      {"alpha_y", 0.5, 1e-4, 100.0, false, false, "roughness along the bitangent (y)"},
      {"sampler", 1.0, 0.0, double(kSamplerNames.size() - 1), false, false,
       "sampler of wo: ndf (Walter 2007), vndf (Heitz 2018), spherical_caps (Dupuy & Benyoub "
       "2023), bounded_caps (Eto & Tokuyoshi 2023)",
       kSamplerNames},
      {"bound", 0.0, 0.0, double(kBoundNames.size() - 1), false, false,
       "bounded_caps only: k of Eq. 5 as in Listing 1, or exact for isotropic alpha", kBoundNames},
  }};
  static constexpr auto kIntermediates = detail::kSmoothIntermediates;

  template <class T>
  struct Params {
    GGX<T> ggx;
    int sampler;  // the row of Samplers; a uniform choice (not per lane): branching on it is
                  // allowed
  };

  template <class T>
  static Params<T> params(std::span<const double> v) {
    return {
        GGX<T>{T(v[param_index<SmoothGGX>("alpha_x")]), T(v[param_index<SmoothGGX>("alpha_y")])},
        Choices::index(static_cast<int>(v[param_index<SmoothGGX>("sampler")]),
                       static_cast<int>(v[param_index<SmoothGGX>("bound")]))};
  }

  template <class T>
  GLINTLAB_FN static T pdf(const Params<T>& p, const ModelQuery<T>& q) {
    return samplers::with<Samplers>(p.sampler,
                                    [&]<class S>() { return S::pdf(p.ggx, q.wi, q.wo); });
  }

  template <class T>
  GLINTLAB_FN static ModelEval<T, kIntermediates.size()> eval(const Params<T>& p,
                                                              const ModelQuery<T>& q) {
    return detail::smooth_eval(p.ggx, q, pdf(p, q));
  }

  template <class T>
  GLINTLAB_FN static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    return samplers::with<Samplers>(p.sampler, [&]<class S>() {
      return detail::smooth_sample(p.ggx, q.wi, S::sample(p.ggx, q.wi, u));
    });
  }
};

static_assert(Model<SmoothGGX>);

}  // namespace glintlab

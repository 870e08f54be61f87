// Kemppinen et al. 2025 glinty GGX reflection as a model (core/model.h): D★^f of Eq. 11 by
// Algorithm 1 on the GGX map T (core/maps/ggx_map.h), sampled by Algorithm 2.
#pragma once

#include "core/models/kemppinen_model.h"
#include "core/ndf/ggx.h"

namespace glintlab {

struct KemppinenGGX {
  static constexpr std::string_view kName = "kemppinen_ggx";
  static constexpr std::string_view kDescription =
      "glinty GGX NDF in constant time (Algorithm 1), Smith G2, F = 1; sampler: Algorithm 2 "
      "(pdf=marginal: its exact density; pdf=printed: lines 16-17)";
  static constexpr std::string_view kSource =
      "Kemppinen et al. 2025 Eq. 1, 4, 5, 8-11, Algorithms 1-2, Sec. 3.2.1";
  static constexpr unsigned kNeeds = kNeedsFootprint;
  static constexpr auto kParams = detail::kKemppinenParams;
  static constexpr auto kIntermediates = detail::kKemppinenIntermediates;

  template <class T>
  using Params = detail::KemppinenModelParams<GGX<T>, T>;

  template <class T>
  static Params<T> params(std::span<const double> v) {
    return detail::kemppinen_model_params<GGX<T>, T>(v);
  }
  template <class T>
  static T pdf(const Params<T>& p, const ModelQuery<T>& q) {
    return detail::kemppinen_model_pdf(p, q);
  }
  template <class T>
  static ModelEval<T, kIntermediates.size()> eval(const Params<T>& p, const ModelQuery<T>& q) {
    return detail::kemppinen_model_eval(p, q, pdf(p, q));
  }
  template <class T>
  static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    return detail::kemppinen_model_sample(p, q, u);
  }
};

static_assert(Model<KemppinenGGX>);

}  // namespace glintlab

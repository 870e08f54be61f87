// A plug-in model whose kernels take only scalar float types (declared for std::floating_point T,
// as a model built on scalar code would be) and that does not declare kBatched = false: its SIMD
// units must stop with one message naming the model and the two ways out
// (tests/plugin/unbatchable_plugin_test.cmake); it is compiled only by that test.
#include <glintlab/plugin.h>

#include <array>
#include <concepts>
#include <span>
#include <string_view>

#include "core/model.h"
#include "core/models/smooth_microfacet.h"
#include "core/ndf/ggx.h"
#include "core/samplers/heitz_vndf.h"

namespace glintlab::test {

struct ScalarOnlyGlints {
  static constexpr std::string_view kName = "scalar_only_glints";
  static constexpr std::string_view kDescription = "smooth GGX with kernels for scalar types only";
  static constexpr std::string_view kSource = "Walter et al. 2007 Eq. 20";
  static constexpr unsigned kNeeds = kNeedsDirections;
  static constexpr std::array<ParamSpec, 1> kParams = {{
      {"alpha_x", 0.3, 1e-4, 100.0, false, false, "roughness"},
  }};
  static constexpr std::array<std::string_view, 0> kIntermediates = {};

  template <class T>
  struct Params {
    GGX<T> ggx;
  };

  template <class T>
  static Params<T> params(std::span<const double> v) {
    const T a = T(v[param_index<ScalarOnlyGlints>("alpha_x")]);
    return {GGX<T>{a, a}};
  }

  template <std::floating_point T>
  static T pdf(const Params<T>& p, const ModelQuery<T>& q) {
    return pdf_heitz_vndf(p.ggx, q.wi, q.wo);
  }

  template <std::floating_point T>
  static ModelEval<T, 0> eval(const Params<T>& p, const ModelQuery<T>& q) {
    const auto smooth = detail::smooth_eval(p.ggx, q, pdf(p, q));
    return {smooth.value, smooth.pdf, {}};
  }

  template <std::floating_point T>
  static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    return detail::smooth_sample(p.ggx, q.wi, sample_heitz_vndf(p.ggx, q.wi, u));
  }
};

static_assert(Model<ScalarOnlyGlints>);

}  // namespace glintlab::test

GLINTLAB_PLUGIN(glintlab::test::ScalarOnlyGlints);

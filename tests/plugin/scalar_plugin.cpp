// A scalar plug-in model (kBatched = false, as docs/adding_a_model.md allows) whose roughness is
// called `roughness`, a name the stability sweep's named axes do not know, and whose only need is
// the directions: its model.scalar_glints.stability must still sweep its parameter and directions
// and reject the NaN control (tests/install/plugin_install_test.cmake).
#include <glintlab/plugin.h>

#include <array>
#include <span>
#include <string_view>

#include "core/model.h"
#include "core/models/smooth_microfacet.h"
#include "core/ndf/ggx.h"
#include "core/samplers/heitz_vndf.h"

namespace glintlab::test {

struct ScalarGlints {
  static constexpr std::string_view kName = "scalar_glints";
  static constexpr std::string_view kDescription =
      "smooth isotropic GGX as a scalar plug-in (kBatched = false)";
  static constexpr std::string_view kSource = "Walter et al. 2007 Eq. 20";
  static constexpr unsigned kNeeds = kNeedsDirections;
  static constexpr bool kBatched = false;
  static constexpr std::array<ParamSpec, 1> kParams = {{
      {"roughness", 0.3, 1e-3, 2.0, false, false, "isotropic GGX roughness"},
  }};
  static constexpr std::array<std::string_view, 0> kIntermediates = {};

  template <class T>
  struct Params {
    GGX<T> ggx;
  };

  template <class T>
  static Params<T> params(std::span<const double> v) {
    const T a = T(v[param_index<ScalarGlints>("roughness")]);
    return {GGX<T>{a, a}};
  }

  template <class T>
  static T pdf(const Params<T>& p, const ModelQuery<T>& q) {
    return pdf_heitz_vndf(p.ggx, q.wi, q.wo);
  }

  template <class T>
  static ModelEval<T, 0> eval(const Params<T>& p, const ModelQuery<T>& q) {
    const auto smooth = detail::smooth_eval(p.ggx, q, pdf(p, q));
    return {smooth.value, smooth.pdf, {}};
  }

  template <class T>
  static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    return detail::smooth_sample(p.ggx, q.wi, sample_heitz_vndf(p.ggx, q.wi, u));
  }
};

static_assert(Model<ScalarGlints>);

}  // namespace glintlab::test

GLINTLAB_PLUGIN(glintlab::test::ScalarGlints);

// Two scalar plug-in models (kBatched = false) whose eval is broken on purpose, for the verify
// suite's containment of a plug-in's faults (tests/cli/plugin_test.cpp): `throwing_eval` throws
// from every eval, `nan_eval` returns NaN for every value. Their conformance checks must report
// verdict "error" naming the model and the cause, while the other claims of the run still run and
// the run's files are written. Both are smooth isotropic GGX otherwise (pdf and sampler intact).
#include <glintlab/plugin.h>

#include <array>
#include <limits>
#include <span>
#include <stdexcept>
#include <string_view>

#include "core/model.h"
#include "core/models/smooth_microfacet.h"
#include "core/ndf/ggx.h"
#include "core/samplers/heitz_vndf.h"

namespace glintlab::test {

struct FaultyEvalBase {
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
    const T a = T(v[0]);
    return {GGX<T>{a, a}};
  }

  template <class T>
  static T pdf(const Params<T>& p, const ModelQuery<T>& q) {
    return pdf_heitz_vndf(p.ggx, q.wi, q.wo);
  }

  template <class T>
  static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    return detail::smooth_sample(p.ggx, q.wi, sample_heitz_vndf(p.ggx, q.wi, u));
  }
};

struct ThrowingEval : FaultyEvalBase {
  static constexpr std::string_view kName = "throwing_eval";
  static constexpr std::string_view kDescription = "smooth GGX whose eval throws (a test's fault)";
  static constexpr std::string_view kSource = "tests/plugin/faulty_eval_plugin.cpp";

  template <class T>
  static ModelEval<T, 0> eval(const Params<T>&, const ModelQuery<T>&) {
    throw std::runtime_error("throwing_eval: eval failed on purpose");
  }
};

struct NanEval : FaultyEvalBase {
  static constexpr std::string_view kName = "nan_eval";
  static constexpr std::string_view kDescription = "smooth GGX whose eval value is NaN (a test's fault)";
  static constexpr std::string_view kSource = "tests/plugin/faulty_eval_plugin.cpp";

  template <class T>
  static ModelEval<T, 0> eval(const Params<T>& p, const ModelQuery<T>& q) {
    return {T(std::numeric_limits<double>::quiet_NaN()), pdf(p, q), {}};
  }
};

static_assert(Model<ThrowingEval> && Model<NanEval>);

}  // namespace glintlab::test

GLINTLAB_PLUGIN(glintlab::test::ThrowingEval, glintlab::test::NanEval);

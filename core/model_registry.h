// Type-erased registry of the models of core/model.h, for the CLI (`glintlab models`, `eval
// --model`), the claims, the figures and the benchmarks. Kernels stay static; an entry holds
// double-precision thunks into them.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/model.h"

namespace glintlab {

// A bad model name or parameter; the message is one line naming the parameter and its range.
struct ModelParamError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

struct ErasedEval {
  double value, pdf;
  std::vector<double> intermediates;
};

struct ModelEntry {
  std::string_view name, description, source;
  unsigned needs;
  std::vector<ParamSpec> params;
  std::vector<std::string_view> intermediates;
  // `values` in params order, as returned by resolve_params.
  std::function<ErasedEval(const std::vector<double>& values, const ModelQuery<double>&)> eval;
  std::function<double(const std::vector<double>& values, const ModelQuery<double>&)> pdf;
  std::function<ModelSample<double>(const std::vector<double>& values, const ModelQuery<double>&,
                                    Vec2<double> u)>
      sample;
  // The static model the entry was made from (static_model_tag<M>(), set by make_model_entry),
  // so the batch API of core/simd/model_batch.h finds its SIMD instantiations; nullptr for an
  // entry built by hand (it is then batched as a scalar loop over the thunks above).
  const void* static_model = nullptr;
};

// One address per static model type (an inline variable: the same in every translation unit).
template <class M>
inline constexpr char kStaticModelTag = 0;
template <class M>
constexpr const void* static_model_tag() {
  return &kStaticModelTag<M>;
}

// Every registered model, in registration order.
const std::vector<ModelEntry>& registered_models();
// The entry named `name`; throws ModelParamError listing the valid names otherwise.
const ModelEntry& find_model(std::string_view name);

// The parameter values for `assignments` (name, text) over the defaults; throws ModelParamError
// for an unknown name, a repeated one, a value that does not parse, or one out of range.
std::vector<double> resolve_params(
    const ModelEntry& model, const std::vector<std::pair<std::string, std::string>>& assignments);
// "(0, 100]" or "one of: a, b, c" for a parameter.
std::string describe_range(const ParamSpec& p);
// The text of a value: the number, or the name of the choice.
std::string format_param_value(const ParamSpec& p, double value);
// "needs: footprint, point light" or "needs: directions only".
std::string describe_needs(unsigned needs);

// Builds the entry of a static model (used by the registration lines in model_registry.cpp).
template <Model M>
ModelEntry make_model_entry() {
  ModelEntry e;
  e.name = M::kName;
  e.description = M::kDescription;
  e.source = M::kSource;
  e.needs = M::kNeeds;
  e.static_model = static_model_tag<M>();
  e.params.assign(M::kParams.begin(), M::kParams.end());
  e.intermediates.assign(M::kIntermediates.begin(), M::kIntermediates.end());
  e.eval = [](const std::vector<double>& v, const ModelQuery<double>& q) {
    const auto r = M::template eval<double>(M::template params<double>(v), q);
    return ErasedEval{r.value, r.pdf, {r.intermediates.begin(), r.intermediates.end()}};
  };
  e.pdf = [](const std::vector<double>& v, const ModelQuery<double>& q) {
    return M::template pdf<double>(M::template params<double>(v), q);
  };
  e.sample = [](const std::vector<double>& v, const ModelQuery<double>& q, Vec2<double> u) {
    return M::template sample<double>(M::template params<double>(v), q, u);
  };
  return e;
}

}  // namespace glintlab

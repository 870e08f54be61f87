// Type-erased registry of the models of core/model.h, for the CLI (`glintlab models`, `eval
// --model`), the claims, the figures and the benchmarks. Kernels stay static; an entry holds
// double-precision thunks into them.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/model.h"
#include "core/model_layout.h"

namespace glintlab {

namespace simd::detail {
struct ModelBatchFns;  // core/simd/table.h
}  // namespace simd::detail

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
  // Optional: eval and pdf over many queries, and sample at one query for many uniform pairs, in
  // one call each, for a model whose every call costs far more than its arithmetic (a Python model
  // calls its numpy functions once per chunk). Row i of `out` is what the per-row thunk above gives
  // for row i, bit for bit. Set by make_model_entry for a model that shares work between the rows
  // of one call (detail::SharesRowWork: the Kemppinen models' mixture probability per footprint);
  // empty otherwise: eval_each / pdf_each / sample_each below loop over the thunks. A copy of an entry that replaces a thunk must replace or clear its rows
  // function too (clear_rows), or callers that use it would bypass the replacement.
  std::function<void(const std::vector<double>& values, std::span<const ModelQuery<double>> queries,
                     std::span<ErasedEval> out)>
      eval_rows;
  std::function<void(const std::vector<double>& values, std::span<const ModelQuery<double>> queries,
                     std::span<double> out)>
      pdf_rows;
  std::function<void(const std::vector<double>& values, const ModelQuery<double>& query,
                     std::span<const Vec2<double>> u, std::span<ModelSample<double>> out)>
      sample_rows;
  // The model's own rules on an evaluated query (M::validate; empty where it has none): the column
  // that breaks one and its valid range, or nothing.
  std::function<std::optional<QueryViolation>(const ModelQuery<double>&)> validate;
  // The same three through the model's float instantiation (inputs rounded to float, results
  // widened back), for the stability sweeps; empty where the model offers no float instantiation
  // (its eval/pdf/sample do not accept T = float, or it declares kDoubleOnly = true).
  std::function<ErasedEval(const std::vector<double>& values, const ModelQuery<double>&)>
      eval_float;
  std::function<double(const std::vector<double>& values, const ModelQuery<double>&)> pdf_float;
  std::function<ModelSample<double>(const std::vector<double>& values, const ModelQuery<double>&,
                                    Vec2<double> u)>
      sample_float;
  // The static model the entry was made from (static_model_tag<M>(), set by make_model_entry),
  // so the batch API of core/simd/model_batch.h finds its SIMD instantiations; nullptr for an
  // entry built by hand (it is then batched as a scalar loop over the thunks above).
  const void* static_model = nullptr;
  // A plug-in model's SIMD batches, compiled in the plug-in per ISA (glintlab/plugin.h sets it;
  // make_model_entry does not): the batch API runs them where static_model finds no built-in
  // instantiation. nullptr: none (a scalar loop over the thunks).
  const simd::detail::ModelBatchFns* plugin_batches = nullptr;
  // The registered model this one tends to as its footprint grows (M::kSmoothLimit), empty where
  // none is declared; and the conformance properties it does not claim (M::kNotClaimed).
  std::string_view smooth_limit;
  std::vector<NotClaimed> not_claimed;
};

// out[i] = eval / pdf of queries[i], sample of `query` at u[i], in one call of the entry's rows
// function where it has one, else a loop over its per-row thunk (same results either way).
inline void eval_each(const ModelEntry& m, const std::vector<double>& values,
                      std::span<const ModelQuery<double>> queries, std::span<ErasedEval> out) {
  if (m.eval_rows) return m.eval_rows(values, queries, out);
  for (std::size_t i = 0; i < queries.size(); ++i) out[i] = m.eval(values, queries[i]);
}
inline void pdf_each(const ModelEntry& m, const std::vector<double>& values,
                     std::span<const ModelQuery<double>> queries, std::span<double> out) {
  if (m.pdf_rows) return m.pdf_rows(values, queries, out);
  for (std::size_t i = 0; i < queries.size(); ++i) out[i] = m.pdf(values, queries[i]);
}
inline void sample_each(const ModelEntry& m, const std::vector<double>& values,
                        const ModelQuery<double>& query, std::span<const Vec2<double>> u,
                        std::span<ModelSample<double>> out) {
  if (m.sample_rows) return m.sample_rows(values, query, u, out);
  for (std::size_t i = 0; i < u.size(); ++i) out[i] = m.sample(values, query, u[i]);
}
// `m` without its rows functions (callers then loop over the per-row thunks).
inline ModelEntry clear_rows(ModelEntry m) {
  m.eval_rows = {};
  m.pdf_rows = {};
  m.sample_rows = {};
  return m;
}

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
// Adds a model at run time (a plug-in, a test's example model) after the built-in ones; every
// consumer of registered_models() (CLI, claims, figures, sweeps, benchmarks) then sees it. Call it
// before any concurrent use of the registry (start-up, a test's set-up): it is not thread-safe.
// The entry's string views must outlive the registry (static strings, as make_model_entry gives).
// Throws ModelParamError for an empty or already registered name, an entry without
// eval/pdf/sample, or a misspelled not-claimed property (check_not_claimed). References to
// registered entries stay valid (storage is reserved up front for kMaxModels entries; registering
// more throws).
inline constexpr std::size_t kMaxModels = 256;
void register_model(ModelEntry entry);
// Throws ModelParamError naming the property and the valid names when `entry` declares a
// not-claimed property that is not one of kConformanceProperties (register_model and the plug-in
// loader call it; the built-in models are checked when the registry is compiled).
void check_not_claimed(const ModelEntry& entry);

// The parameter values for `assignments` (name, text) over the defaults; throws ModelParamError
// for an unknown name, a repeated one, a value that does not parse, or one out of range.
std::vector<double> resolve_params(
    const ModelEntry& model, const std::vector<std::pair<std::string, std::string>>& assignments);
// "[0.0001, 100]" or "one of: a, b, c" for a parameter.
std::string describe_range(const ParamSpec& p);
// The text of a value: the number, or the name of the choice.
std::string format_param_value(const ParamSpec& p, double value);
// "needs: footprint, point light" or "needs: directions only".
std::string describe_needs(unsigned needs);

namespace detail {
// A float query from a double one (the sweeps' float path), every column of core/model_layout.h.
inline ModelQuery<float> to_float(const ModelQuery<double>& q) { return convert_query<float>(q); }

template <class M>
concept DeclaresSmoothLimit = requires {
  { M::kSmoothLimit } -> std::convertible_to<std::string_view>;
};
template <class M>
concept DeclaresNotClaimed = requires {
  M::kNotClaimed.size();
  { M::kNotClaimed[0].property } -> std::convertible_to<std::string_view>;
};

// Whether every property M declares not claimed is a conformance property, and every choice it
// limits one to is one of its parameters' choices (true where M declares none).
template <class M>
constexpr bool not_claimed_are_properties() {
  if constexpr (DeclaresNotClaimed<M>) {
    for (const NotClaimed& n : M::kNotClaimed)
      if (!is_conformance_property(n.property) ||
          (!n.choice.empty() && !is_declared_choice(M::kParams, n.choice)))
        return false;
  }
  return true;
}

template <class M>
concept DoubleOnly = requires {
  requires M::kDoubleOnly;
};

// Whether M's kernels are declared for T = float (and M does not opt out with kDoubleOnly).
template <class M>
concept HasFloatInstantiation = !DoubleOnly<M> && requires(std::span<const double> v) {
  {
    M::template eval<float>(M::template params<float>(v), ModelQuery<float>{})
    } -> std::same_as<ModelEval<float, M::kIntermediates.size()>>;
  {M::template pdf<float>(M::template params<float>(v), ModelQuery<float>{})};
  {
    M::template sample<float>(M::template params<float>(v), ModelQuery<float>{}, Vec2<float>{})
    } -> std::same_as<ModelSample<float>>;
};
// A model whose rows of one call share work: M::RowsShared holds it (host-side, per call), and
// M::pdf_row / eval_row / sample_row give each row's pdf / eval / sample in double with it, the
// bits of M::pdf / eval / sample.
template <class M>
concept SharesRowWork = requires(std::span<const double> v, const ModelQuery<double>& q,
                                 Vec2<double> u, typename M::RowsShared& shared) {
  { M::pdf_row(M::template params<double>(v), q, shared) } -> std::same_as<double>;
  {
    M::eval_row(M::template params<double>(v), q, shared)
    } -> std::same_as<ModelEval<double, M::kIntermediates.size()>>;
  { M::sample_row(M::template params<double>(v), q, u, shared) } -> std::same_as<ModelSample<double>>;
};
}  // namespace detail

// Builds the entry of a static model (model_registry.cpp makes one per type of BuiltinModels).
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
  if constexpr (detail::SharesRowWork<M>) {
    e.eval_rows = [](const std::vector<double>& v, std::span<const ModelQuery<double>> qs,
                     std::span<ErasedEval> out) {
      const auto p = M::template params<double>(v);
      typename M::RowsShared shared;
      for (std::size_t i = 0; i < qs.size(); ++i) {
        const auto r = M::eval_row(p, qs[i], shared);
        out[i] = ErasedEval{r.value, r.pdf, {r.intermediates.begin(), r.intermediates.end()}};
      }
    };
    e.pdf_rows = [](const std::vector<double>& v, std::span<const ModelQuery<double>> qs,
                    std::span<double> out) {
      const auto p = M::template params<double>(v);
      typename M::RowsShared shared;
      for (std::size_t i = 0; i < qs.size(); ++i) out[i] = M::pdf_row(p, qs[i], shared);
    };
    e.sample_rows = [](const std::vector<double>& v, const ModelQuery<double>& q,
                       std::span<const Vec2<double>> u, std::span<ModelSample<double>> out) {
      const auto p = M::template params<double>(v);
      typename M::RowsShared shared;
      for (std::size_t i = 0; i < u.size(); ++i) out[i] = M::sample_row(p, q, u[i], shared);
    };
  }
  if constexpr (ValidatesQuery<M>) e.validate = &M::validate;
  if constexpr (detail::DeclaresSmoothLimit<M>) e.smooth_limit = M::kSmoothLimit;
  if constexpr (detail::DeclaresNotClaimed<M>)
    e.not_claimed.assign(M::kNotClaimed.begin(), M::kNotClaimed.end());
  if constexpr (detail::HasFloatInstantiation<M>) {
    e.eval_float = [](const std::vector<double>& v, const ModelQuery<double>& q) {
      const auto r = M::template eval<float>(M::template params<float>(v), detail::to_float(q));
      ErasedEval out{r.value, r.pdf, {}};
      for (float x : r.intermediates) out.intermediates.push_back(x);
      return out;
    };
    e.pdf_float = [](const std::vector<double>& v, const ModelQuery<double>& q) {
      return double(M::template pdf<float>(M::template params<float>(v), detail::to_float(q)));
    };
    e.sample_float = [](const std::vector<double>& v, const ModelQuery<double>& q, Vec2<double> u) {
      const auto s = M::template sample<float>(M::template params<float>(v), detail::to_float(q),
                                               Vec2<float>{float(u.x), float(u.y)});
      return ModelSample<double>{
          {s.wo.x, s.wo.y, s.wo.z}, s.pdf, s.weight, static_cast<bool>(s.rejected)};
    };
  }
  return e;
}

}  // namespace glintlab

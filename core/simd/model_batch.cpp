// eval_batch / sample_batch over registered models: the per-ISA table's entries for the models of
// BatchedModels, a scalar loop over the entry's thunks for every other entry.
#include "core/simd/model_batch.h"

#include <fmt/format.h>

#include <array>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/model_layout.h"
#include "core/model_list.h"
#include "core/simd/table.h"

namespace glintlab::simd {
namespace {

template <class... Ms>
constexpr std::array<const void*, sizeof...(Ms)> tags_of(ModelList<Ms...>) {
  return {static_model_tag<Ms>()...};
}

std::string query_label(std::size_t j) {
  return fmt::format("query column {}", kQueryLayout[j].name);
}

// The index of the model in BatchedModels, or -1.
int batched_index(const ModelEntry& model) {
  static const auto kTags = tags_of(BatchedModels{});
  if (model.static_model == nullptr) return -1;
  for (std::size_t i = 0; i < kTags.size(); ++i)
    if (kTags[i] == model.static_model) return static_cast<int>(i);
  return -1;
}

template <class S>
void check_model(const char* what, const ModelEntry& model, std::size_t n_params,
                 std::span<const Column<S>> query, std::size_t n_out, std::size_t want_out, Isa isa,
                 Math math) {
  if (n_params != model.params.size()) {
    throw std::invalid_argument(fmt::format("{}: model {} takes {} parameter values, got {}", what,
                                            model.name, model.params.size(), n_params));
  }
  if ((query.size() != kQueryColumns.size() && query.size() != kQueryColumnsWithCorners) ||
      n_out != want_out) {
    throw std::invalid_argument(fmt::format(
        "{}: model {} takes {} (or {} with the corner vectors) query and {} output columns, got {} "
        "and {}",
        what, model.name, kQueryColumns.size(), kQueryColumnsWithCorners, want_out, query.size(),
        n_out));
  }
  detail::check_call(what, query, &query_label, isa, math);
}

// The query padded to kQueryColumnsWithCorners columns (zero corners where the caller gave none),
// then `extra` (sample's uniform columns).
template <class S, std::size_t N = 0>
std::array<Column<S>, kQueryColumnsWithCorners + N> full_query(
    std::span<const Column<S>> q, std::array<Column<S>, N> extra = {}) {
  static constexpr S kZero = 0;
  std::array<Column<S>, kQueryColumnsWithCorners + N> r;
  for (std::size_t j = 0; j < kQueryColumnsWithCorners; ++j)
    r[j] = j < q.size() ? q[j] : Column<S>{&kZero, 0};
  for (std::size_t j = 0; j < N; ++j) r[kQueryColumnsWithCorners + j] = extra[j];
  return r;
}

template <class S>
ModelQuery<double> query_row(std::span<const Column<S>> q, std::size_t i) {
  QueryRow<double> row;
  for (std::size_t j = 0; j < row.size(); ++j)
    row[j] = static_cast<double>(q[j].data[q[j].stride * i]);
  return from_row(row);
}

// A plug-in model's instantiation for isa (eval or sample), or nullptr.
const detail::BatchFns* plugin_fns(const ModelEntry& model, bool sample, Isa isa) {
  if (model.plugin_batches == nullptr) return nullptr;
  const auto& fns = sample ? model.plugin_batches->sample : model.plugin_batches->eval;
  return fns[static_cast<std::size_t>(isa)];
}

// Runs the model's entry (`entry`: its eval or its sample) of isa's table on the padded columns,
// or, for a plug-in model, the plug-in's instantiation for isa; false when there is neither.
template <class S>
bool run_batched(const ModelEntry& model, bool sample, std::span<const double> params,
                 std::span<const Column<S>> q, std::span<S* const> outputs, std::size_t n, Isa isa,
                 Math math) {
  const int m = batched_index(model);
  if (m >= 0) {
    const std::size_t index = static_cast<std::size_t>(m);
    detail::run<S>(sample ? detail::model_sample_entry(index) : detail::model_eval_entry(index),
                   params.data(), q.data(), outputs.data(), n, isa, math);
    return true;
  }
  const detail::BatchFns* f = plugin_fns(model, sample, isa);
  if (f == nullptr) return false;
  if constexpr (std::is_same_v<S, float>) {
    (math == Math::kFast ? f->fast_float : f->exact_float)(params.data(), q.data(), outputs.data(),
                                                           n);
  } else {
    f->exact_double(params.data(), q.data(), outputs.data(), n);
  }
  return true;
}

// Row i of a model that is not batched: the entry's double thunks.
template <class S>
void eval_row(const ModelEntry& model, const std::vector<double>& values,
              std::span<const Column<S>> q, std::span<S* const> outputs, std::size_t i) {
  const ErasedEval e = model.eval(values, query_row<S>(q, i));
  outputs[0][i] = static_cast<S>(e.value);
  outputs[1][i] = static_cast<S>(e.pdf);
  for (std::size_t k = 0; k < model.intermediates.size(); ++k)
    outputs[2 + k][i] = static_cast<S>(k < e.intermediates.size() ? e.intermediates[k] : 0.0);
}
// q: the padded query then the two uniform columns.
template <class S>
void sample_row(const ModelEntry& model, const std::vector<double>& values,
                std::span<const Column<S>> q, std::span<S* const> outputs, std::size_t i) {
  const Column<S> u1 = q[kQueryColumnsWithCorners], u2 = q[kQueryColumnsWithCorners + 1];
  const Vec2<double> u{static_cast<double>(u1.data[u1.stride * i]),
                       static_cast<double>(u2.data[u2.stride * i])};
  const ModelSample<double> s = model.sample(values, query_row<S>(q, i), u);
  const double row[6] = {s.wo.x, s.wo.y, s.wo.z, s.pdf, s.weight, s.rejected ? 1.0 : 0.0};
  for (std::size_t k = 0; k < 6; ++k) outputs[k][i] = static_cast<S>(row[k]);
}

template <class S>
void eval_any(const ModelEntry& model, std::span<const double> params,
              std::span<const Column<S>> query, std::span<S* const> outputs, std::size_t n, Isa isa,
              Math math) {
  check_model<S>("eval_batch", model, params.size(), query, outputs.size(),
                 2 + model.intermediates.size(), isa, math);
  const auto q = full_query(query);
  if (run_batched<S>(model, false, params, q, outputs, n, isa, math)) return;
  // Not batched: the entry's double thunks, row by row.
  const std::vector<double> values(params.begin(), params.end());
  for (std::size_t i = 0; i < n; ++i) eval_row<S>(model, values, q, outputs, i);
}

template <class S>
void check_uniform_columns(const char* what, Column<S> u1, Column<S> u2) {
  if (u1.stride > 1 || u2.stride > 1) {
    throw std::invalid_argument(fmt::format("{}: uniform columns have stride 0 or 1", what));
  }
}

template <class S>
void sample_any(const ModelEntry& model, std::span<const double> params,
                std::span<const Column<S>> query, Column<S> u1, Column<S> u2,
                std::span<S* const> outputs, std::size_t n, Isa isa, Math math) {
  check_model<S>("sample_batch", model, params.size(), query, outputs.size(), kSampleColumns.size(),
                 isa, math);
  check_uniform_columns<S>("sample_batch", u1, u2);
  const auto q = full_query(query, std::array{u1, u2});
  if (run_batched<S>(model, true, params, q, outputs, n, isa, math)) return;
  const std::vector<double> values(params.begin(), params.end());
  for (std::size_t i = 0; i < n; ++i) sample_row<S>(model, values, q, outputs, i);
}

// Parameter columns: one per parameter (the count is check_model's), each of stride 0 or 1.
void check_param_columns(const char* what, const ModelEntry& model,
                         std::span<const Column<double>> params) {
  for (std::size_t k = 0; k < params.size(); ++k) {
    if (params[k].stride > 1) {
      throw std::invalid_argument(
          fmt::format("{}: parameter column {} of model {} has stride {} (valid: 0 or 1)", what,
                      k < model.params.size() ? model.params[k].name : std::string_view("?"),
                      model.name, params[k].stride));
    }
  }
}

// Row i's parameter vector.
void row_values(std::span<const Column<double>> params, std::size_t i, std::vector<double>& values) {
  values.resize(params.size());
  for (std::size_t k = 0; k < params.size(); ++k) values[k] = params[k].data[params[k].stride * i];
}

// Whether every parameter column is one value for every row (then `values` holds them).
bool uniform_values(std::span<const Column<double>> params, std::vector<double>& values) {
  for (const Column<double>& c : params)
    if (c.stride != 0) return false;
  row_values(params, 0, values);
  return true;
}

// The model's lanes_ entry of isa's table (or its plug-in's) on the padded columns; false when
// the model has no SIMD instantiation. A plug-in entry without lanes_ functions runs each run of
// rows with equal parameters as one call of its uniform function.
template <class S>
bool run_batched_lanes(const ModelEntry& model, bool sample, std::span<const Column<double>> params,
                       std::span<const Column<S>> q, std::span<S* const> outputs, std::size_t n,
                       Isa isa, Math math) {
  const int m = batched_index(model);
  if (m >= 0) {
    const std::size_t index = static_cast<std::size_t>(m);
    detail::run_lanes<S>(
        sample ? detail::model_sample_entry(index) : detail::model_eval_entry(index),
        params.data(), q.data(), outputs.data(), n, isa, math);
    return true;
  }
  const detail::BatchFns* f = plugin_fns(model, sample, isa);
  if (f == nullptr) return false;
  detail::LaneBatchFn<S> lanes = nullptr;
  if constexpr (std::is_same_v<S, float>) {
    lanes = math == Math::kFast ? f->lanes_fast_float : f->lanes_exact_float;
  } else {
    lanes = f->lanes_exact_double;
  }
  if (lanes != nullptr) {
    lanes(params.data(), q.data(), outputs.data(), n);
    return true;
  }
  std::vector<double> values, next;
  std::vector<Column<S>> at(q.size());
  std::vector<S*> out(outputs.size());
  for (std::size_t begin = 0; begin < n;) {
    row_values(params, begin, values);
    std::size_t end = begin + 1;
    for (; end < n; ++end) {
      row_values(params, end, next);
      if (next != values) break;
    }
    for (std::size_t c = 0; c < q.size(); ++c)
      at[c] = {q[c].data + q[c].stride * begin, q[c].stride};
    for (std::size_t o = 0; o < outputs.size(); ++o) out[o] = outputs[o] + begin;
    run_batched<S>(model, sample, values, at, out, end - begin, isa, math);
    begin = end;
  }
  return true;
}

template <class S>
void eval_columns(const ModelEntry& model, std::span<const Column<double>> params,
                  std::span<const Column<S>> query, std::span<S* const> outputs, std::size_t n,
                  Isa isa, Math math) {
  check_param_columns("eval_batch", model, params);
  std::vector<double> values;
  if (uniform_values(params, values)) return eval_any<S>(model, values, query, outputs, n, isa, math);
  check_model<S>("eval_batch", model, params.size(), query, outputs.size(),
                 2 + model.intermediates.size(), isa, math);
  const auto q = full_query(query);
  if (run_batched_lanes<S>(model, false, params, q, outputs, n, isa, math)) return;
  for (std::size_t i = 0; i < n; ++i) {
    row_values(params, i, values);
    eval_row<S>(model, values, q, outputs, i);
  }
}

template <class S>
void sample_columns(const ModelEntry& model, std::span<const Column<double>> params,
                    std::span<const Column<S>> query, Column<S> u1, Column<S> u2,
                    std::span<S* const> outputs, std::size_t n, Isa isa, Math math) {
  check_param_columns("sample_batch", model, params);
  std::vector<double> values;
  if (uniform_values(params, values))
    return sample_any<S>(model, values, query, u1, u2, outputs, n, isa, math);
  check_model<S>("sample_batch", model, params.size(), query, outputs.size(), kSampleColumns.size(),
                 isa, math);
  check_uniform_columns<S>("sample_batch", u1, u2);
  const auto q = full_query(query, std::array{u1, u2});
  if (run_batched_lanes<S>(model, true, params, q, outputs, n, isa, math)) return;
  for (std::size_t i = 0; i < n; ++i) {
    row_values(params, i, values);
    sample_row<S>(model, values, q, outputs, i);
  }
}

}  // namespace

bool is_batched(const ModelEntry& model) {
  if (batched_index(model) >= 0) return true;
  for (Isa isa : kAllIsas)
    if (plugin_fns(model, false, isa) != nullptr) return true;
  return false;
}

void eval_batch(const ModelEntry& model, std::span<const double> params,
                std::span<const Column<float>> query, std::span<float* const> outputs,
                std::size_t n, Isa isa, Math math) {
  eval_any<float>(model, params, query, outputs, n, isa, math);
}
void eval_batch(const ModelEntry& model, std::span<const double> params,
                std::span<const Column<double>> query, std::span<double* const> outputs,
                std::size_t n, Isa isa, Math math) {
  eval_any<double>(model, params, query, outputs, n, isa, math);
}
void sample_batch(const ModelEntry& model, std::span<const double> params,
                  std::span<const Column<float>> query, Column<float> u1, Column<float> u2,
                  std::span<float* const> outputs, std::size_t n, Isa isa, Math math) {
  sample_any<float>(model, params, query, u1, u2, outputs, n, isa, math);
}
void sample_batch(const ModelEntry& model, std::span<const double> params,
                  std::span<const Column<double>> query, Column<double> u1, Column<double> u2,
                  std::span<double* const> outputs, std::size_t n, Isa isa, Math math) {
  sample_any<double>(model, params, query, u1, u2, outputs, n, isa, math);
}


void eval_batch_with_param_columns(const ModelEntry& model, std::span<const Column<double>> params,
                                   std::span<const Column<float>> query,
                                   std::span<float* const> outputs, std::size_t n, Isa isa,
                                   Math math) {
  eval_columns<float>(model, params, query, outputs, n, isa, math);
}
void eval_batch_with_param_columns(const ModelEntry& model, std::span<const Column<double>> params,
                                   std::span<const Column<double>> query,
                                   std::span<double* const> outputs, std::size_t n, Isa isa,
                                   Math math) {
  eval_columns<double>(model, params, query, outputs, n, isa, math);
}
void sample_batch_with_param_columns(const ModelEntry& model,
                                     std::span<const Column<double>> params,
                                     std::span<const Column<float>> query, Column<float> u1,
                                     Column<float> u2, std::span<float* const> outputs,
                                     std::size_t n, Isa isa, Math math) {
  sample_columns<float>(model, params, query, u1, u2, outputs, n, isa, math);
}
void sample_batch_with_param_columns(const ModelEntry& model,
                                     std::span<const Column<double>> params,
                                     std::span<const Column<double>> query, Column<double> u1,
                                     Column<double> u2, std::span<double* const> outputs,
                                     std::size_t n, Isa isa, Math math) {
  sample_columns<double>(model, params, query, u1, u2, outputs, n, isa, math);
}

}  // namespace glintlab::simd

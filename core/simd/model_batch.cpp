// eval_batch / sample_batch over registered models: the per-ISA table's entries for the models of
// BatchedModels, a scalar loop over the entry's thunks for every other entry.
#include "core/simd/model_batch.h"

#include <fmt/format.h>

#include <algorithm>
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
  // Query columns may have any stride (run_in_blocks gathers those above 1); the shared checks
  // see them as stride 1.
  std::array<Column<S>, kQueryColumnsWithCorners> checked{};
  for (std::size_t j = 0; j < query.size(); ++j)
    checked[j] = {query[j].data, std::min<std::size_t>(query[j].stride, 1)};
  detail::check_call(what, std::span<const Column<S>>(checked.data(), query.size()), &query_label,
                     isa, math);
}

// Rows per block of a call with query columns of stride above 1: a multiple of every ISA's lanes
// (16 floats for AVX-512), so that every block but the last runs full batches, and few enough
// that a block's gathered columns (at most 26 of them, 52 KiB in double) are still in the core's
// cache when the batch reads them.
constexpr std::size_t kStridedBlock = 256;

// Values src[stride * i] of rows i < count into dst (a C-ordered (N, 3) array's coordinate, stride
// 3, as its own loop: a constant stride the compiler vectorises).
template <class S>
void gather_strided(const S* src, std::size_t stride, S* dst, std::size_t count) {
  if (stride == 3) {
    for (std::size_t i = 0; i < count; ++i) dst[i] = src[3 * i];
    return;
  }
  for (std::size_t i = 0; i < count; ++i) dst[i] = src[stride * i];
}

// run(query, params, outputs, rows) over rows [0, n): in one call where every query column has
// stride 0 or 1, else block by block (kStridedBlock rows), each block's columns of stride above 1
// gathered into a buffer of stride-1 columns and every other column, parameter column and output
// advanced to the block's first row. Row i's result depends only on its own inputs (the batch
// contract), so the blocks give the rows of one call bit for bit.
template <class S, std::size_t N, class Run>
void run_in_blocks(const std::array<Column<S>, N>& q, std::span<const Column<double>> params,
                   std::span<S* const> outputs, std::size_t n, const Run& run) {
  const std::size_t strided = static_cast<std::size_t>(
      std::count_if(q.begin(), q.end(), [](const Column<S>& c) { return c.stride > 1; }));
  if (strided == 0) return run(std::span<const Column<S>>(q), params, outputs, n);
  std::vector<S> buffer(strided * std::min(n, kStridedBlock));
  std::array<Column<S>, N> block_q;
  std::vector<Column<double>> block_params(params.size());
  std::vector<S*> block_out(outputs.size());
  for (std::size_t begin = 0; begin < n; begin += kStridedBlock) {
    const std::size_t count = std::min(kStridedBlock, n - begin);
    S* next = buffer.data();
    for (std::size_t j = 0; j < N; ++j) {
      const Column<S>& c = q[j];
      block_q[j] = {c.data + c.stride * begin, c.stride};
      if (c.stride <= 1) continue;
      gather_strided(block_q[j].data, c.stride, next, count);
      block_q[j] = {next, 1};
      next += count;
    }
    for (std::size_t k = 0; k < params.size(); ++k)
      block_params[k] = {params[k].data + params[k].stride * begin, params[k].stride};
    for (std::size_t o = 0; o < outputs.size(); ++o) block_out[o] = outputs[o] + begin;
    run(std::span<const Column<S>>(block_q), std::span<const Column<double>>(block_params),
        std::span<S* const>(block_out), count);
  }
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
  const std::vector<double> values(params.begin(), params.end());
  run_in_blocks<S>(full_query(query), {}, outputs, n,
                   [&](std::span<const Column<S>> q, std::span<const Column<double>>,
                       std::span<S* const> out, std::size_t rows) {
                     if (run_batched<S>(model, false, params, q, out, rows, isa, math)) return;
                     // Not batched: the entry's double thunks, row by row.
                     for (std::size_t i = 0; i < rows; ++i) eval_row<S>(model, values, q, out, i);
                   });
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
  const std::vector<double> values(params.begin(), params.end());
  run_in_blocks<S>(full_query(query, std::array{u1, u2}), {}, outputs, n,
                   [&](std::span<const Column<S>> q, std::span<const Column<double>>,
                       std::span<S* const> out, std::size_t rows) {
                     if (run_batched<S>(model, true, params, q, out, rows, isa, math)) return;
                     for (std::size_t i = 0; i < rows; ++i) sample_row<S>(model, values, q, out, i);
                   });
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
  run_in_blocks<S>(full_query(query), params, outputs, n,
                   [&](std::span<const Column<S>> q, std::span<const Column<double>> p,
                       std::span<S* const> out, std::size_t rows) {
                     if (run_batched_lanes<S>(model, false, p, q, out, rows, isa, math)) return;
                     for (std::size_t i = 0; i < rows; ++i) {
                       row_values(p, i, values);
                       eval_row<S>(model, values, q, out, i);
                     }
                   });
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
  run_in_blocks<S>(full_query(query, std::array{u1, u2}), params, outputs, n,
                   [&](std::span<const Column<S>> q, std::span<const Column<double>> p,
                       std::span<S* const> out, std::size_t rows) {
                     if (run_batched_lanes<S>(model, true, p, q, out, rows, isa, math)) return;
                     for (std::size_t i = 0; i < rows; ++i) {
                       row_values(p, i, values);
                       sample_row<S>(model, values, q, out, i);
                     }
                   });
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

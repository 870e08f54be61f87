// Structure-of-arrays batch evaluation and sampling of a registered model (core/model_registry.h):
// the model's own eval/pdf/sample templates (core/model.h) instantiated on the SIMD batches of each
// ISA for the models of BatchedModels (core/model_list.h), a scalar loop over the entry's thunks
// for any other entry (including one built at run time). No xsimd in this header.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string_view>

#include "core/model_layout.h"
#include "core/model_registry.h"
#include "core/simd/batch.h"

namespace glintlab::simd {

// The query columns (core/model_layout.h), in layout order: footprint uv and its Jacobian, ω_i,
// ω_o, the light cone, then the footprint's four corner reflection vectors (FootprintQuery::
// corner_r, for the kNeedsPixelCorners models) as optional columns. A query of
// kQueryColumnsWithCorners columns carries them; one of kQueryColumns.size() leaves them zero.
inline constexpr std::size_t kQueryColumnsWithCorners = kQueryLayout.size();
inline constexpr std::size_t kCornerColumnCount = [] {
  std::size_t n = 0;
  for (const QueryColumn& c : kQueryLayout) n += c.part == QueryPart::kCorners ? 1 : 0;
  return n;
}();
template <std::size_t N>
constexpr std::array<std::string_view, N> query_column_names(std::size_t first) {
  std::array<std::string_view, N> names{};
  for (std::size_t k = 0; k < N; ++k) names[k] = kQueryLayout[first + k].name;
  return names;
}
// The columns without the corners (the columns of `glintlab eval --model`), and their defaults.
inline constexpr auto kQueryColumns =
    query_column_names<kQueryColumnsWithCorners - kCornerColumnCount>(0);
inline constexpr auto kQueryDefaults = [] {
  std::array<double, kQueryColumns.size()> defaults{};
  for (std::size_t k = 0; k < defaults.size(); ++k) defaults[k] = kQueryLayout[k].default_value;
  return defaults;
}();
// The corner columns, corner k at 3k..3k+2.
inline constexpr auto kCornerColumns = query_column_names<kCornerColumnCount>(kQueryColumns.size());
// eval_batch writes value, pdf, then the model's intermediates (ModelEntry::intermediates).
// sample_batch writes these (ModelSample: wo, its pdf, the weight value/pdf, rejected as 1 or 0).
inline constexpr std::array<std::string_view, 6> kSampleColumns = {"wo_x", "wo_y",   "wo_z",
                                                                   "pdf",  "weight", "rejected"};

// Whether `model` has SIMD instantiations (it is in BatchedModels, or a plug-in compiled its
// batches: ModelEntry::plugin_batches, for the ISAs it was built with); otherwise the batch calls
// below run the entry's double-precision thunks row by row (any ISA argument gives that result).
bool is_batched(const ModelEntry& model);

// outputs[k][i] for row i < n of the queries (query: kQueryColumns.size() columns, or
// kQueryColumnsWithCorners with the corner vectors; any stride, above 1 gathered block by block),
// with the parameter values `params` (ModelEntry::params order, as resolve_params returns them)
// for every row; outputs: 2 + model.intermediates.size() columns. Throws std::invalid_argument
// on wrong column counts or parameter count, Math::kFast with double, or an ISA this CPU lacks.
// Row i's result depends only on (its query, params, ISA, math): never on n or its position.
void eval_batch(const ModelEntry& model, std::span<const double> params,
                std::span<const Column<float>> query, std::span<float* const> outputs,
                std::size_t n, Isa isa, Math math = Math::kExact);
void eval_batch(const ModelEntry& model, std::span<const double> params,
                std::span<const Column<double>> query, std::span<double* const> outputs,
                std::size_t n, Isa isa, Math math = Math::kExact);

// One sample per row from the query's ω_i (and footprint, light) and the uniform pair (u1, u2);
// outputs: the kSampleColumns.size() columns. Same contract as eval_batch.
void sample_batch(const ModelEntry& model, std::span<const double> params,
                  std::span<const Column<float>> query, Column<float> u1, Column<float> u2,
                  std::span<float* const> outputs, std::size_t n, Isa isa,
                  Math math = Math::kExact);
void sample_batch(const ModelEntry& model, std::span<const double> params,
                  std::span<const Column<double>> query, Column<double> u1, Column<double> u2,
                  std::span<double* const> outputs, std::size_t n, Isa isa,
                  Math math = Math::kExact);

// eval_batch and sample_batch with a parameter column per parameter (ModelEntry::params order):
// stride 0 for one value for every row (as `params` above), stride 1 for row i's value at data[i].
// Row i's result is bit for bit that of eval_batch / sample_batch called with row i's values alone
// (same query, ISA and math). Rows with different values share a SIMD batch: each lane gets its
// own row's parameters, and the batch's kernel runs once unless uniform parameters (a choice, a
// seed, or every parameter of a model whose kernels take them as scalars, such as chermain) differ
// within it, then once per group of lanes that agree on them (core/simd/lane_params.h). With every
// column of stride 0 this is the call above. A model that is not batched runs its double thunks
// row by row with each row's values; a plug-in built before these entries existed is refused by the
// loader's ABI check. Throws as eval_batch, and for a parameter column of stride above 1.
void eval_batch_with_param_columns(const ModelEntry& model, std::span<const Column<double>> params,
                                   std::span<const Column<float>> query,
                                   std::span<float* const> outputs, std::size_t n, Isa isa,
                                   Math math = Math::kExact);
void eval_batch_with_param_columns(const ModelEntry& model, std::span<const Column<double>> params,
                                   std::span<const Column<double>> query,
                                   std::span<double* const> outputs, std::size_t n, Isa isa,
                                   Math math = Math::kExact);
void sample_batch_with_param_columns(const ModelEntry& model,
                                     std::span<const Column<double>> params,
                                     std::span<const Column<float>> query, Column<float> u1,
                                     Column<float> u2, std::span<float* const> outputs,
                                     std::size_t n, Isa isa, Math math = Math::kExact);
void sample_batch_with_param_columns(const ModelEntry& model,
                                     std::span<const Column<double>> params,
                                     std::span<const Column<double>> query, Column<double> u1,
                                     Column<double> u2, std::span<double* const> outputs,
                                     std::size_t n, Isa isa, Math math = Math::kExact);

}  // namespace glintlab::simd

// One eval or sample call of the Python module over the batch API (core/simd/model_batch.h):
// the parameters (scalars for every row or per-row arrays), the batch options, the row checks of
// `glintlab eval --model` (run over each chunk's columns), and the chunked parallel loop of the
// CLI, run without the GIL.
#pragma once

#include <pybind11/pybind11.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cli/batch_options.h"
#include "core/model_registry.h"
#include "core/simd/batch.h"
#include "python/query_columns.h"

namespace glintlab::python {

// The parameters of a call: the values of the constant ones (resolve_params order) and, for those
// given as (N,) arrays, their column sources (every value checked against the same ranges).
struct CallParams {
  std::vector<double> constant;
  std::vector<std::pair<std::size_t, ColumnSource>> per_row;  // (index in params, values)
  std::vector<ColumnSource> per_row_sources;                  // per_row's sources, in its order

  // Row `row`'s values into `values` (sized like constant).
  void at(std::size_t row, std::vector<double>& values) const {
    for (const auto& [k, s] : per_row) values[k] = s.at(row);
  }
};
CallParams call_params(const ModelEntry& model, const pybind11::object& params, std::size_t& rows,
                       std::vector<pybind11::object>& keep_alive);

// precision "double"/"float", isa (None: the CLI's default), math, threads (None: all cores), as
// the CLI's --precision, --isa, --math and --threads; ValueError naming the option otherwise.
cli::BatchOptions batch_options(const std::string& precision, const pybind11::object& isa,
                                const std::string& math, const pybind11::object& threads);

// The work on a set of rows: `inputs` the query columns (`width` of them, kQueryLayout order) then
// the extra columns (sample's uniforms), `count` rows each (stride 0 or 1); `outputs` count rows
// each; `params` a column per parameter (resolve_params order): stride 0 for a value of every row,
// stride 1 for a per-row array's values (only where run_chunks is told the work takes them).
// `storage`: the memory a chunk's gathered input columns lie in when the chunk gives it away (a
// numpy model's chunks, so that its functions can hold views of it), else empty.
struct ChunkStorage {
  std::shared_ptr<const void> owner;
  const void* begin = nullptr;
  const void* end = nullptr;
};
template <class S>
using BatchFn = std::function<void(std::span<const simd::Column<S>> inputs,
                                   std::span<S* const> outputs, std::size_t count,
                                   std::span<const simd::Column<double>> params,
                                   const ChunkStorage& storage)>;
// Writes the extra input columns of rows [begin, begin + count): extra[k][i] for row begin + i.
template <class S>
using ExtraFn =
    std::function<void(std::size_t begin, std::size_t count, std::span<S* const> extra)>;
// A check of row `row` besides eval --model's (sample's uniforms): the message, or nothing.
using RowCheck = std::function<std::optional<std::string>(std::size_t row)>;

// The rows of a chunk of a numpy model's call (four of the CLI's chunks): each call of its
// functions costs the interpreter and numpy's dispatch a fixed time, about as long as the
// numpy Lambertian's work on 4096 rows (its two functions on 10^6 rows: 1.6 ms in one call,
// 3.4 ms in chunks of 4096, 2.1 ms in chunks of 16384); at 16384 rows the six direction columns
// of a chunk (768 KiB) still fit a core's cache between the check and the functions.
inline constexpr std::size_t kNumpyModelChunk = 4 * cli::kBatchChunk;

// Rows [0, n) in the CLI's chunks (a numpy model's: kNumpyModelChunk) on opts.threads threads,
// the GIL released. Each chunk: its query columns read in place or gathered from the arrays'
// strides (chunk_columns; a numpy model's into storage given to f), its rows
// checked as eval --model checks them by a pass over those columns (the exact row checks, and
// their message, run only for a chunk where that pass finds a row that may be bad; the first bad
// row, lowest index, becomes a ValueError after the loop), then f. With `per_row_columns` (the
// batch API's eval_batch_with_param_columns, whose batches stay full whatever the values), f once
// per chunk, per-row parameters as stride-1 columns of the chunk's rows. Without it (a numpy
// model, whose functions take one value per parameter), f once per set of rows with equal
// parameters: the whole chunk without per-row parameters; with them, the chunk's rows grouped by
// their values in O(rows), each group gathered (in place where its rows are adjacent) and its
// results scattered back. `outputs`: n rows each.
// `unit_interval`: sources whose values extra_check requires in [0, 1) (sample's given
// uniforms), tested by a pass over each chunk's rows, so that extra_check runs row by row only in
// a chunk where that pass finds a value outside.
template <class S>
void run_chunks(const ModelEntry& model, const QuerySources& q, const CallParams& p,
                const cli::BatchOptions& opts, std::size_t width, std::span<S* const> outputs,
                const BatchFn<S>& f, bool per_row_columns, std::size_t extra_columns = 0,
                const ExtraFn<S>& extra = {}, const RowCheck& extra_check = {},
                std::span<const ColumnSource* const> unit_interval = {});

}  // namespace glintlab::python

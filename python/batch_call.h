// One eval or sample call of the Python module over the batch API (core/simd/model_batch.h):
// the parameters (scalars for every row or per-row arrays), the batch options, the row checks of
// `glintlab eval --model`, and the chunked parallel loop of the CLI, run without the GIL.
#pragma once

#include <pybind11/pybind11.h>

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cli/batch_options.h"
#include "core/model_registry.h"
#include "python/query_columns.h"

namespace glintlab::python {

// The parameters of a call: the values of the constant ones (resolve_params order) and, for those
// given as (N,) arrays, their column sources (checked row by row against the same ranges).
struct CallParams {
  std::vector<double> constant;
  std::vector<std::pair<std::size_t, ColumnSource>> per_row;  // (index in params, values)

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

// Rows [0, n) in the CLI's chunks on opts.threads threads, the GIL released: each chunk's rows
// checked as eval --model checks them (the first bad row, lowest index, becomes a ValueError
// after the loop), then f(begin, count, params) once per run of rows with equal parameters.
void run_chunks(const ModelEntry& model, const QuerySources& q, const CallParams& p,
                const cli::BatchOptions& opts,
                const std::function<void(std::size_t begin, std::size_t count,
                                         const std::vector<double>& params)>& f,
                const std::function<std::optional<std::string>(std::size_t row)>& extra_check = {});

}  // namespace glintlab::python

// Models prototyped in numpy (glintlab.register_model): three vectorised Python callables behind a
// registry entry (core/model_registry.h), so that every consumer of the registry (models(), eval,
// sample, the conformance suite) sees them like a built-in model without SIMD batches.
//
// The callables take a dict of (N,) float64 arrays keyed by the query layout's column names
// (core/model_layout.h; the parts the model's needs select) and a dict of parameter values; each
// call is checked (type, dtype, shape, NaN) and a failure becomes PythonModelError naming the model
// and the function. The entry's per-row thunks call them with N = 1; its rows functions
// (ModelEntry::eval_rows, pdf_rows, sample_rows, which the conformance suite calls where it has
// many queries) and the module's eval and sample call them once per chunk of rows
// (python_eval_rows, python_sample_rows). Every call takes the GIL itself, so callers run them
// without holding it.
#pragma once

#include <pybind11/pybind11.h>

#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/model_registry.h"
#include "core/simd/batch.h"

namespace glintlab::python {

// A Python model's callable raised, or returned something that is not what it must return.
struct PythonModelError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct PythonModel;

// Registers a Python model (chunked = false: without rows functions, so the suite calls the
// functions one query at a time, for comparing the two routes); ValueError for a bad name, needs, parameter list, smooth limit or
// not-claimed declaration (the messages name the argument and what is valid).
void register_python_model(const std::string& name, const pybind11::object& eval,
                           const pybind11::object& pdf, const pybind11::object& sample,
                           const pybind11::object& params, const pybind11::object& needs,
                           const pybind11::object& smooth_limit, const std::string& description,
                           const std::string& source, const pybind11::object& not_claimed,
                           bool chunked = true);

// Text that a registry entry's string views point into, kept for the life of the process (the
// registry is never emptied).
std::string_view keep_text(std::string text);

// The Python model behind a registry entry, or nullptr for any other entry.
const PythonModel* python_model(const ModelEntry& entry);

// Where the query columns of a call lie, so that the functions get read-only views of them rather
// than copies: a contiguous float64 column (stride 1) whose memory lies in one of these is passed
// as it lies, kept alive by the view; any other column is copied into a fresh array.
struct ColumnOwners {
  // Per query column (kQueryLayout order): the array the column's values lie in (borrowed; the
  // caller keeps it alive for the call), or null.
  std::span<PyObject* const> arrays;
  // Storage the gathered columns lie in, given away by the chunk (shared with the views), or null.
  std::shared_ptr<const void> storage;
  const void* storage_begin = nullptr;
  const void* storage_end = nullptr;
};

// value, pdf of rows [0, n) of the columns (kQueryLayout order, stride 0 or 1) into outputs[0],
// outputs[1]: one call of eval and one of pdf. Takes the GIL; throws PythonModelError. With
// `stream_results` (outputs that are parts of result arrays larger than the caches, read only
// after the call: the module's eval), double outputs are written by non-temporal stores.
template <class S>
void python_eval_rows(const PythonModel& model, const std::vector<double>& params,
                      std::span<const simd::Column<S>> query, std::span<S* const> outputs,
                      std::size_t n, const ColumnOwners& owners = {}, bool stream_results = false);
// One sample per row into the six columns of simd::kSampleColumns: one call of sample
// (`stream_results` as above, for the pdf and weight columns).
template <class S>
void python_sample_rows(const PythonModel& model, const std::vector<double>& params,
                        std::span<const simd::Column<S>> query, simd::Column<S> u1,
                        simd::Column<S> u2, std::span<S* const> outputs, std::size_t n,
                        const ColumnOwners& owners = {}, bool stream_results = false);

}  // namespace glintlab::python

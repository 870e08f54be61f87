// The models' kernels on a CUDA device, called from host code without CUDA headers: find the
// device, run a built-in model's eval, pdf or sample over a query set, time the launches. Built
// only with GLINTLAB_CUDA (gpu/CMakeLists.txt); the kernels are the models' own templates from
// their core headers (gpu/device_kernels.cuh).
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "gpu/device_timing.h"
#include "gpu/query_set.h"

namespace glintlab::gpu {

struct DeviceInfo {
  bool present = false;
  std::string name;  // e.g. "NVIDIA H200"
  int compute_major = 0, compute_minor = 0;
  std::string why_absent;  // when !present: the CUDA runtime's own words
};

// The first CUDA device, or why there is none (no driver, no device, a driver too old).
DeviceInfo find_device();

// The CUDA toolkit the kernels were compiled with, e.g. "13.0".
std::string cuda_compiler_version();

enum class Function { kEval, kPdf, kSample };
inline constexpr std::string_view function_name(Function f) {
  return f == Function::kEval ? "eval" : f == Function::kPdf ? "pdf" : "sample";
}

// A device-capable model's default parameter values (its kParams order), and the names of the
// output columns of `function` (as run_on_device returns them). Throw std::invalid_argument for
// a model without device kernels.
std::vector<double> default_params(std::string_view model);
std::vector<std::string> output_column_names(std::string_view model, Function function);

// A CUDA runtime failure, with the call and the runtime's message.
struct DeviceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `function` of the built-in model `model` (has_device_kernels) with the parameter values
// `params` (its kParams order), in precision T (float or double), over every row of `queries`
// (rounded to T as the CPU batches round them). Returns the output columns copied back: eval:
// value, pdf, then the intermediates; pdf: the pdf; sample: wo_x, wo_y, wo_z, pdf, weight,
// rejected (1 or 0) — the columns of the CPU batches (core/simd/model_batch.h). With `timing`,
// also launches the kernel `repetitions` more times and times them. Throws std::invalid_argument
// for a model without device kernels and DeviceError for a CUDA failure.
template <class T>
std::vector<std::vector<T>> run_on_device(std::string_view model, std::span<const double> params,
                                          Function function, const QuerySet& queries,
                                          int repetitions = 0, DeviceTiming* timing = nullptr);

}  // namespace glintlab::gpu

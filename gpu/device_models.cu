// Host side of the device kernels: device buffers, launches, CUDA-event timing, and the dispatch
// from a model's name to its kernels for the models of DeviceModels (gpu/device_support.h says
// why the other built-in models are not here).
#include <cuda_runtime.h>

#include <algorithm>
#include <array>
#include <string>
#include <type_traits>
#include <vector>

#include "core/glints/deliot_belcour.h"
#include "core/glints/kneiphof.h"
#include "core/models/kemppinen_beckmann.h"
#include "core/models/kemppinen_ggx.h"
#include "core/models/podee.h"
#include "core/models/smooth_beckmann.h"
#include "core/models/smooth_ggx.h"
#include "gpu/device_kernels.cuh"
#include "gpu/device_models.h"
#include "gpu/device_support.h"

namespace glintlab::gpu {
namespace {

template <class... Ms>
struct DeviceModelList {};
using DeviceModels =
    DeviceModelList<SmoothGGX, SmoothBeckmann, Podee, DeliotBelcour, KneiphofKlein, KemppinenGGX,
                    KemppinenBeckmann>;

void check(cudaError_t status, const char* call) {
  if (status != cudaSuccess)
    throw DeviceError(std::string(call) + ": " + cudaGetErrorName(status) + ": " +
                      cudaGetErrorString(status));
}
#define GLINTLAB_CUDA_CHECK(call) check((call), #call)

// One device array of n values of T, freed when it goes out of scope.
template <class T>
class DeviceArray {
 public:
  explicit DeviceArray(std::size_t n) : n_(n) {
    GLINTLAB_CUDA_CHECK(
        cudaMalloc(reinterpret_cast<void**>(&data_), std::max<std::size_t>(n, 1) * sizeof(T)));
  }
  DeviceArray(DeviceArray&& other) noexcept : n_(other.n_), data_(other.data_) {
    other.data_ = nullptr;
  }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  DeviceArray& operator=(DeviceArray&&) = delete;
  ~DeviceArray() { cudaFree(data_); }
  T* data() const { return data_; }
  void upload(const std::vector<T>& host) {
    GLINTLAB_CUDA_CHECK(cudaMemcpy(data_, host.data(), n_ * sizeof(T), cudaMemcpyHostToDevice));
  }
  std::vector<T> download() const {
    std::vector<T> host(n_);
    GLINTLAB_CUDA_CHECK(cudaMemcpy(host.data(), data_, n_ * sizeof(T), cudaMemcpyDeviceToHost));
    return host;
  }

 private:
  std::size_t n_;
  T* data_ = nullptr;
};

template <class T>
std::vector<T> rounded(const std::vector<double>& v) {
  std::vector<T> out(v.size());
  std::transform(v.begin(), v.end(), out.begin(), [](double x) { return static_cast<T>(x); });
  return out;
}

class DeviceEvent {
 public:
  DeviceEvent() { GLINTLAB_CUDA_CHECK(cudaEventCreate(&event_)); }
  DeviceEvent(const DeviceEvent&) = delete;
  DeviceEvent& operator=(const DeviceEvent&) = delete;
  ~DeviceEvent() { cudaEventDestroy(event_); }
  cudaEvent_t get() const { return event_; }

 private:
  cudaEvent_t event_{};
};

// Launches `launch` once untimed, then `repetitions` times between CUDA events.
template <class Launch>
void launch_and_time(const Launch& launch, std::size_t rows, int repetitions,
                     DeviceTiming* timing) {
  launch();
  GLINTLAB_CUDA_CHECK(cudaGetLastError());
  GLINTLAB_CUDA_CHECK(cudaDeviceSynchronize());
  if (timing == nullptr || repetitions <= 0) return;
  std::vector<float> ms(static_cast<std::size_t>(repetitions));
  DeviceEvent start, stop;
  for (float& t : ms) {
    GLINTLAB_CUDA_CHECK(cudaEventRecord(start.get()));
    launch();
    GLINTLAB_CUDA_CHECK(cudaEventRecord(stop.get()));
    GLINTLAB_CUDA_CHECK(cudaEventSynchronize(stop.get()));
    GLINTLAB_CUDA_CHECK(cudaGetLastError());
    GLINTLAB_CUDA_CHECK(cudaEventElapsedTime(&t, start.get(), stop.get()));
  }
  std::sort(ms.begin(), ms.end());
  timing->repetitions = repetitions;
  timing->median_ms = ms[ms.size() / 2];
  timing->min_ms = ms.front();
  timing->items_per_second = timing->median_ms > 0 ? double(rows) / (timing->median_ms * 1e-3) : 0;
}

template <class M, class T>
std::vector<std::vector<T>> run_model(std::span<const double> params, Function function,
                                      const QuerySet& queries, int repetitions,
                                      DeviceTiming* timing) {
  const std::size_t n = queries.rows;
  const auto p = M::template params<T>(params);
  std::vector<DeviceArray<T>> query;
  query.reserve(kQueryLayout.size());
  DeviceQueryColumns<T> query_columns{};
  query_offsets<T>(query_columns.offset);
  for (std::size_t k = 0; k < kQueryLayout.size(); ++k) {
    query.emplace_back(n);
    query.back().upload(rounded<T>(queries.columns[k]));
    query_columns.column[k] = query.back().data();
  }
  constexpr unsigned kThreads = 128;
  const unsigned blocks = static_cast<unsigned>((n + kThreads - 1) / kThreads);
  std::vector<DeviceArray<T>> out;
  const auto outputs = [&]<std::size_t N>(std::integral_constant<std::size_t, N>) {
    DeviceOutputColumns<T, N> columns{};
    for (std::size_t k = 0; k < N; ++k) {
      out.emplace_back(n);
      columns.column[k] = out.back().data();
    }
    return columns;
  };
  out.reserve(kEvalColumns<M, T> + 6);
  if (n > 0) {
    if (function == Function::kEval) {
      const auto columns = outputs(std::integral_constant<std::size_t, kEvalColumns<M, T>>{});
      launch_and_time(
          [&] { eval_kernel<M, T><<<blocks, kThreads>>>(p, query_columns, columns, n); }, n,
          repetitions, timing);
    } else if (function == Function::kPdf) {
      const auto columns = outputs(std::integral_constant<std::size_t, 1>{});
      launch_and_time([&] { pdf_kernel<M, T><<<blocks, kThreads>>>(p, query_columns, columns, n); },
                      n, repetitions, timing);
    } else {
      DeviceArray<T> u1(n), u2(n);
      u1.upload(rounded<T>(queries.u1));
      u2.upload(rounded<T>(queries.u2));
      const auto columns = outputs(std::integral_constant<std::size_t, 6>{});
      launch_and_time(
          [&] {
            sample_kernel<M, T>
                <<<blocks, kThreads>>>(p, query_columns, u1.data(), u2.data(), columns, n);
          },
          n, repetitions, timing);
    }
  }
  std::vector<std::vector<T>> result;
  for (const DeviceArray<T>& column : out) result.push_back(column.download());
  return result;
}

template <class... Ms, class Visit>
void with_model(DeviceModelList<Ms...>, std::string_view model, const Visit& visit) {
  const bool found =
      ((model == Ms::kName ? (visit(std::type_identity<Ms>{}), true) : false) || ...);
  if (!found)
    throw std::invalid_argument("model '" + std::string(model) + "' has no device kernels" +
                                (has_device_kernels(model) ? "" : " (docs/gpu.md says why)"));
}

}  // namespace

std::vector<double> default_params(std::string_view model) {
  std::vector<double> values;
  with_model(DeviceModels{}, model, [&]<class M>(std::type_identity<M>) {
    for (const ParamSpec& p : M::kParams) values.push_back(p.default_value);
  });
  return values;
}

std::vector<std::string> output_column_names(std::string_view model, Function function) {
  std::vector<std::string> names;
  with_model(DeviceModels{}, model, [&]<class M>(std::type_identity<M>) {
    if (function == Function::kEval) {
      names = {"value", "pdf"};
      for (std::string_view n : M::kIntermediates) names.emplace_back(n);
    } else if (function == Function::kPdf) {
      names = {"pdf"};
    } else {
      names = {"wo_x", "wo_y", "wo_z", "pdf", "weight", "rejected"};
    }
  });
  return names;
}

DeviceInfo find_device() {
  DeviceInfo info;
  int count = 0;
  const cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess) {
    info.why_absent = std::string(cudaGetErrorName(status)) + ": " + cudaGetErrorString(status);
    cudaGetLastError();  // clear the sticky error of a failed runtime start
    return info;
  }
  if (count == 0) {
    info.why_absent = "the CUDA runtime found no device";
    return info;
  }
  cudaDeviceProp prop{};
  check(cudaGetDeviceProperties(&prop, 0), "cudaGetDeviceProperties");
  info.present = true;
  info.name = prop.name;
  info.compute_major = prop.major;
  info.compute_minor = prop.minor;
  return info;
}

std::string cuda_compiler_version() {
  return std::to_string(__CUDACC_VER_MAJOR__) + "." + std::to_string(__CUDACC_VER_MINOR__);
}

template <class T>
std::vector<std::vector<T>> run_on_device(std::string_view model, std::span<const double> params,
                                          Function function, const QuerySet& queries,
                                          int repetitions, DeviceTiming* timing) {
  static_assert(std::is_same_v<T, float> || std::is_same_v<T, double>);
  std::vector<std::vector<T>> result;
  with_model(DeviceModels{}, model, [&]<class M>(std::type_identity<M>) {
    result = run_model<M, T>(params, function, queries, repetitions, timing);
  });
  return result;
}

template std::vector<std::vector<float>> run_on_device<float>(std::string_view,
                                                              std::span<const double>, Function,
                                                              const QuerySet&, int, DeviceTiming*);
template std::vector<std::vector<double>> run_on_device<double>(std::string_view,
                                                                std::span<const double>, Function,
                                                                const QuerySet&, int,
                                                                DeviceTiming*);

}  // namespace glintlab::gpu

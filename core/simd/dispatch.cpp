// Runtime ISA choice (CPU features, GLINTLAB_ISA), the one table switch and argument check behind
// every batch call, and the kernel eval_batch / sample_batch entry points.
#include <fmt/format.h>

#include <array>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/simd/batch.h"
#include "core/simd/kernels.h"
#include "core/simd/table.h"

namespace glintlab::simd {
namespace {

template <class K>
struct InputIds {
  static constexpr auto make() {
    std::array<int, K::kIn.size()> a{};
    for (std::size_t i = 0; i < K::kIn.size(); ++i) a[i] = static_cast<int>(K::kIn[i]);
    return a;
  }
  static constexpr auto kIds = make();
};

#define GLINTLAB_INFO(K) KernelInfo{K::kName, InputIds<K>::kIds, K::kOut},
const KernelInfo kInfos[] = {GLINTLAB_SIMD_KERNELS(GLINTLAB_INFO)};
#undef GLINTLAB_INFO
constexpr int kCount = static_cast<int>(sizeof(kInfos) / sizeof(kInfos[0]));

const detail::BatchFns* table(Isa isa) {
  switch (isa) {
    case Isa::kSse42:
      return detail::table_sse42();
    case Isa::kAvx2:
      return detail::table_avx2();
    case Isa::kAvx512:
      return detail::table_avx512();
    case Isa::kScalar:
      break;
  }
  return detail::table_scalar();
}

void check_kernel(int kernel, std::size_t n_in, std::size_t n_out) {
  if (kernel < 0 || kernel >= kCount) {
    throw std::invalid_argument("eval_batch: kernel id " + std::to_string(kernel) +
                                " out of range [0, " + std::to_string(kCount) + ")");
  }
  const KernelInfo& k = kInfos[kernel];
  if (n_in != k.inputs.size() || n_out != k.outputs.size()) {
    throw std::invalid_argument("eval_batch: " + std::string(k.name) + " takes " +
                                std::to_string(k.inputs.size()) + " input and " +
                                std::to_string(k.outputs.size()) + " output columns, got " +
                                std::to_string(n_in) + " and " + std::to_string(n_out));
  }
}

std::string input_label(std::size_t j) { return "input column " + std::to_string(j); }

template <class S>
void eval_kernel(int kernel, std::span<const Column<S>> inputs, std::span<S* const> outputs,
                 std::size_t n, Isa isa, Math math) {
  check_kernel(kernel, inputs.size(), outputs.size());
  detail::check_call("eval_batch", inputs, &input_label, isa, math);
  detail::run<S>(static_cast<std::size_t>(kernel), nullptr, inputs.data(), outputs.data(), n, isa,
                 math);
}

}  // namespace

namespace detail {

template <class S>
void check_call(const char* what, std::span<const Column<S>> in, std::string (*label)(std::size_t),
                Isa isa, Math math) {
  for (std::size_t j = 0; j < in.size(); ++j) {
    if (in[j].stride > 1) {
      throw std::invalid_argument(
          fmt::format("{}: {} has stride {} (valid: 0 or 1)", what, label(j), in[j].stride));
    }
  }
  if (!isa_supported(isa)) {
    throw std::invalid_argument(
        fmt::format("{}: ISA {} is not supported by this CPU", what, isa_name(isa)));
  }
  if (std::is_same_v<S, double> && math == Math::kFast) {
    throw std::invalid_argument(
        fmt::format("{}: fast math is single precision only (use float)", what));
  }
}
template void check_call<float>(const char*, std::span<const Column<float>>,
                                std::string (*)(std::size_t), Isa, Math);
template void check_call<double>(const char*, std::span<const Column<double>>,
                                 std::string (*)(std::size_t), Isa, Math);

template <class S>
void run(std::size_t entry, const double* params, const Column<S>* in, S* const* out, std::size_t n,
         Isa isa, Math math) {
  const BatchFns& f = table(isa)[entry];
  if constexpr (std::is_same_v<S, float>) {
    (math == Math::kFast ? f.fast_float : f.exact_float)(params, in, out, n);
  } else {
    f.exact_double(params, in, out, n);
  }
}
template void run<float>(std::size_t, const double*, const Column<float>*, float* const*,
                         std::size_t, Isa, Math);
template void run<double>(std::size_t, const double*, const Column<double>*, double* const*,
                          std::size_t, Isa, Math);

template <class S>
void run_lanes(std::size_t entry, const Column<double>* params, const Column<S>* in, S* const* out,
               std::size_t n, Isa isa, Math math) {
  const BatchFns& f = table(isa)[entry];
  if constexpr (std::is_same_v<S, float>) {
    (math == Math::kFast ? f.lanes_fast_float : f.lanes_exact_float)(params, in, out, n);
  } else {
    f.lanes_exact_double(params, in, out, n);
  }
}
template void run_lanes<float>(std::size_t, const Column<double>*, const Column<float>*,
                               float* const*, std::size_t, Isa, Math);
template void run_lanes<double>(std::size_t, const Column<double>*, const Column<double>*,
                                double* const*, std::size_t, Isa, Math);

}  // namespace detail

std::string_view isa_name(Isa isa) {
  switch (isa) {
    case Isa::kScalar:
      return "scalar";
    case Isa::kSse42:
      return "sse4.2";
    case Isa::kAvx2:
      return "avx2";
    case Isa::kAvx512:
      return "avx512";
  }
  return "scalar";
}

std::optional<Isa> parse_isa(std::string_view name) {
  for (Isa isa : kAllIsas) {
    if (isa_name(isa) == name) return isa;
  }
  return std::nullopt;
}

std::string_view math_name(Math math) { return math == Math::kFast ? "fast" : "exact"; }

std::optional<Math> parse_math(std::string_view name) {
  if (name == "exact") return Math::kExact;
  if (name == "fast") return Math::kFast;
  return std::nullopt;
}

std::optional<Isa> max_isa() {
  const char* env = std::getenv("GLINTLAB_MAX_ISA");
  if (env == nullptr || *env == '\0') return std::nullopt;
  const std::optional<Isa> isa = parse_isa(env);
  if (!isa) {
    throw std::invalid_argument("GLINTLAB_MAX_ISA: unknown ISA '" + std::string(env) +
                                "' (valid: scalar, sse4.2, avx2, avx512)");
  }
  return isa;
}

bool isa_supported(Isa isa) {
  // Isa's order is the order of width, so the cap is a comparison.
  if (const std::optional<Isa> cap = max_isa(); cap && isa > *cap) return false;
  // __builtin_cpu_supports reflects CPUID and, for AVX and AVX-512, the OS's XSAVE state.
  switch (isa) {
    case Isa::kScalar:
      return true;
    case Isa::kSse42:
      return __builtin_cpu_supports("sse4.2");
    case Isa::kAvx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    case Isa::kAvx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("fma");
  }
  return false;
}

Isa best_isa() {
  for (Isa isa : {Isa::kAvx512, Isa::kAvx2, Isa::kSse42}) {
    if (isa_supported(isa)) return isa;
  }
  return Isa::kScalar;
}

Isa default_isa() {
  const char* env = std::getenv("GLINTLAB_ISA");
  if (env == nullptr || *env == '\0') return best_isa();
  const std::optional<Isa> isa = parse_isa(env);
  if (!isa) {
    throw std::invalid_argument("GLINTLAB_ISA: unknown ISA '" + std::string(env) +
                                "' (valid: scalar, sse4.2, avx2, avx512)");
  }
  if (!isa_supported(*isa)) {
    throw std::invalid_argument(
        "GLINTLAB_ISA: '" + std::string(env) +
        "' is not supported by this CPU (best here: " + std::string(isa_name(best_isa())) +
        (max_isa() ? ", capped by GLINTLAB_MAX_ISA" : "") + ")");
  }
  return *isa;
}

std::size_t lanes(Isa isa, bool double_precision) {
  const std::size_t bytes = isa == Isa::kAvx512  ? 64
                            : isa == Isa::kAvx2  ? 32
                            : isa == Isa::kSse42 ? 16
                                                 : 0;
  if (bytes == 0) return 1;
  return bytes / (double_precision ? 8 : 4);
}

int kernel_count() { return kCount; }

std::optional<int> find_kernel(std::string_view name) {
  for (int i = 0; i < kCount; ++i) {
    if (kInfos[i].name == name) return i;
  }
  return std::nullopt;
}

KernelInfo kernel_info(int kernel) {
  if (kernel < 0 || kernel >= kCount) {
    throw std::invalid_argument("kernel_info: kernel id " + std::to_string(kernel) +
                                " out of range");
  }
  return kInfos[kernel];
}

void eval_batch(int kernel, std::span<const Column<float>> inputs, std::span<float* const> outputs,
                std::size_t n, Isa isa, Math math) {
  eval_kernel(kernel, inputs, outputs, n, isa, math);
}

void eval_batch(int kernel, std::span<const Column<double>> inputs,
                std::span<double* const> outputs, std::size_t n, Isa isa, Math math) {
  eval_kernel(kernel, inputs, outputs, n, isa, math);
}

template <class S>
void eval_batch(int kernel, std::span<const S> params, std::span<const S* const> columns,
                std::span<S* const> outputs, std::size_t n, Isa isa, Math math) {
  constexpr std::size_t kMaxInputs = 32;
  const std::size_t total = params.size() + columns.size();
  if (total > kMaxInputs) {
    throw std::invalid_argument("eval_batch: more than 32 input columns");
  }
  std::array<Column<S>, kMaxInputs> in{};
  for (std::size_t i = 0; i < params.size(); ++i) in[i] = {&params[i], 0};
  for (std::size_t i = 0; i < columns.size(); ++i) in[params.size() + i] = {columns[i], 1};
  eval_batch(kernel, std::span<const Column<S>>(in.data(), total), outputs, n, isa, math);
}
template void eval_batch<float>(int, std::span<const float>, std::span<const float* const>,
                                std::span<float* const>, std::size_t, Isa, Math);
template void eval_batch<double>(int, std::span<const double>, std::span<const double* const>,
                                 std::span<double* const>, std::size_t, Isa, Math);

template <class S>
void sample_batch(int sampler, S alpha_x, S alpha_y, const S wi[3], const S* u1, const S* u2,
                  SampleBatch<S> out, std::size_t n, Isa isa, Math math) {
  const std::array<S, 5> params{alpha_x, alpha_y, wi[0], wi[1], wi[2]};
  const std::array<const S*, 2> cols{u1, u2};
  const std::array<S*, 8> outs{out.wo_x, out.wo_y, out.wo_z, out.m_x,
                               out.m_y,  out.m_z,  out.pdf,  out.rejected};
  const KernelInfo k = kernel_info(sampler);
  if (k.outputs.size() != 8 || k.inputs.size() != 7) {
    throw std::invalid_argument("sample_batch: " + std::string(k.name) + " is not a sampler");
  }
  eval_batch<S>(sampler, params, cols, outs, n, isa, math);
}
template void sample_batch<float>(int, float, float, const float[3], const float*, const float*,
                                  SampleBatch<float>, std::size_t, Isa, Math);
template void sample_batch<double>(int, double, double, const double[3], const double*,
                                   const double*, SampleBatch<double>, std::size_t, Isa, Math);

}  // namespace glintlab::simd

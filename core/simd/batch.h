// Structure-of-arrays batch evaluation of every kernel of core/simd/kernels.h on the best SIMD
// instruction set of this CPU (or a forced one), exact or fast math. No xsimd in this header.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace glintlab::simd {

// Instruction sets, each compiled in its own translation unit with its own flags.
//   kScalar: the plain float/double kernels (any x86-64); kSse42: 4 floats / 2 doubles;
//   kAvx2: AVX2 + FMA, 8 / 4; kAvx512: AVX-512 F/CD/DQ/BW + FMA, 16 / 8. In order of width.
enum class Isa { kScalar, kSse42, kAvx2, kAvx512 };
inline constexpr Isa kAllIsas[] = {Isa::kScalar, Isa::kSse42, Isa::kAvx2, Isa::kAvx512};

// Exact: the ops layer as accurate as the scalar kernels. Fast: core/simd/fast_math.h's exp, erf,
// erfc, rsqrt (float only; errors documented there).
enum class Math { kExact, kFast };

std::string_view isa_name(Isa isa);  // "scalar", "sse4.2", "avx2", "avx512"
std::optional<Isa> parse_isa(std::string_view name);
std::string_view math_name(Math math);  // "exact", "fast"
std::optional<Math> parse_math(std::string_view name);
// This CPU (and OS) can run it, and it is not wider than GLINTLAB_MAX_ISA (scalar, sse4.2, avx2,
// avx512) if that is set: runs an AVX-512 machine as one without AVX-512 would (the tests use it
// to check the paths of CPUs they do not run on). Throws std::invalid_argument naming
// GLINTLAB_MAX_ISA and its valid values if it is set to an unknown name.
bool isa_supported(Isa isa);
std::optional<Isa> max_isa();  // GLINTLAB_MAX_ISA, if set
Isa best_isa();                // the widest supported
// The ISA eval_batch uses by default: GLINTLAB_ISA (scalar, sse4.2, avx2, avx512) if set, else
// best_isa(). Throws std::invalid_argument naming GLINTLAB_ISA and its valid values if it is
// unknown or names an ISA this CPU lacks.
Isa default_isa();
std::size_t lanes(Isa isa, bool double_precision);

// Kernels: ids in the order of GLINTLAB_SIMD_KERNELS.
int kernel_count();
std::optional<int> find_kernel(std::string_view name);
struct KernelInfo {
  std::string_view name;
  std::span<const int> inputs;  // core/simd/kernels.h Domain of each input column (as int)
  std::span<const std::string_view> outputs;
};
KernelInfo kernel_info(int kernel);

// One input column: n values (stride 1) or one value for every row (stride 0). The model batches'
// query columns may have any stride (core/simd/model_batch.h gathers those above 1).
template <class S>
struct Column {
  const S* data;
  std::size_t stride;
};

// out[k][i] = kernel(in[0][i], in[1][i], …) for i < n. inputs.size() and outputs.size() must match
// kernel_info; throws std::invalid_argument otherwise, for Math::kFast with double, or for an ISA
// this CPU lacks. Rows are evaluated in full SIMD batches (the tail padded), so row i's value
// does not depend on n or on where the row sits: it is a function of (inputs, ISA, math) only.
void eval_batch(int kernel, std::span<const Column<float>> inputs, std::span<float* const> outputs,
                std::size_t n, Isa isa, Math math = Math::kExact);
void eval_batch(int kernel, std::span<const Column<double>> inputs,
                std::span<double* const> outputs, std::size_t n, Isa isa, Math math = Math::kExact);

// The form with uniform parameters: params are the first params.size() inputs (e.g. alpha_x,
// alpha_y), the same for every row; columns the remaining inputs, n values each.
template <class S>
void eval_batch(int kernel, std::span<const S> params, std::span<const S* const> columns,
                std::span<S* const> outputs, std::size_t n, Isa isa, Math math = Math::kExact);

// Samplers: a kernel whose inputs are (alpha_x, alpha_y, wi_x, wi_y, wi_z, u1, u2) and outputs
// (wo, m, pdf, rejected). One configuration (alpha, wi) for n uniform pairs.
template <class S>
struct SampleBatch {
  S* wo_x;
  S* wo_y;
  S* wo_z;
  S* m_x;
  S* m_y;
  S* m_z;
  S* pdf;
  S* rejected;  // 1 or 0
};
template <class S>
void sample_batch(int sampler, S alpha_x, S alpha_y, const S wi[3], const S* u1, const S* u2,
                  SampleBatch<S> out, std::size_t n, Isa isa, Math math = Math::kExact);

}  // namespace glintlab::simd

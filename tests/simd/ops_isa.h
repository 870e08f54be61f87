// The ops layer one op at a time, on each ISA's batches and on the scalar types: the minimal
// per-op evidence behind the kernel equivalence budgets (avx512_ops_test.cpp). Each ISA's ops are
// compiled in their own translation unit with that ISA's flags (ops_isa_<isa>.cpp).
#pragma once

#include <cstddef>

#include "core/simd/batch.h"

namespace glintlab::simd::test {

enum class Op {
  // Correctly rounded IEEE 754 operations (and comparisons, selects): equal to scalar bit for bit.
  kAdd, kSub, kMul, kDiv, kSqrt, kFma, kNeg, kAbs, kMin, kMax, kFloor, kCopysign, kSignNotZero,
  kLess, kLessEqual, kGreater, kGreaterEqual, kEqual, kNotEqual, kIsfinite,
  // core/math/hash32.h in the batch's integer lanes: hash32_uniform(hash32_counter(index(a),
  // index(b), index(c))), bit for bit the scalar one.
  kHash32Uniform,
  // core/glints/binomial_kernel.h's exact draw, n = a, p = b, keyed by hash32_index(c), and the
  // loop it was before (simd/binomial_reference.h): bit for bit each other on every ISA.
  kBinomialExact, kBinomialExactReference,
  // xsimd's vectorised libm: within a few ulp of glibc, never bit-identical to it.
  kExp, kExpm1, kLog, kLog1p, kErf, kErfc, kAtan, kAcos, kAcosh, kAtan2, kSin, kCos, kTan,
  // core/simd/fast_math.h's rsqrt (hardware estimate + one Newton step), float only (0 in double).
  kFastRsqrt,
  // xsimd 8.1's own AVX-512 behaviour, bypassing core/simd/xsimd.h and wide.h's corrections: the
  // deliberately broken inputs that the comparisons above must catch.
  kUnfusedFma, kNegAsZeroMinus, kXsimdNotEqual,
};
inline constexpr int kOpCount = static_cast<int>(Op::kXsimdNotEqual) + 1;

// out[i] = op(a[i], b[i], c[i]) for i < n; n a multiple of 16.
struct IsaOps {
  void (*f)(Op, const float* a, const float* b, const float* c, float* out, std::size_t n);
  void (*d)(Op, const double* a, const double* b, const double* c, double* out, std::size_t n);
};
// The ops on the scalar types and on each ISA's batches; call an ISA's functions only when
// isa_supported(isa).
IsaOps isa_ops_scalar();
IsaOps isa_ops_sse42();
IsaOps isa_ops_avx2();
IsaOps isa_ops_avx512();

}  // namespace glintlab::simd::test

// xsimd, as glintlab uses it: <xsimd/xsimd.hpp> plus corrections of xsimd 8.1's (Debian 12's
// version) AVX-512 fused multiply-adds and negation, which disagree with IEEE 754 and with
// xsimd's own SSE/AVX kernels.
// Include this header, never <xsimd/xsimd.hpp> directly: an explicit specialization only takes
// effect if it is declared before the first use that instantiates the kernel.
#pragma once

#include <climits>
#include <xsimd/xsimd.hpp>

// What xsimd 8.1 does on AVX-512 (measured by tests/simd/avx512_ops_test.cpp):
// - fma, fms, fnma, fnms: there is no AVX-512 kernel, so the generic one runs, a*b + c with two
//   roundings. Every error-free product (x*x − fl(x*x) in exp_neg_sqr) becomes 0, and xsimd's own
//   exp, erf, sin... (which call fma) lose the accuracy of their AVX2 (FMA3) versions.
// - neg: computed as 0 − x, so −(+0) is +0, not −0. A sign lost on a zero flips copysign,
//   sign_not_zero and every frame built from them (the GGX VNDF's T1 for a normal-incidence view).
// Both are replaced below by the AVX-512F instructions, for the arch glintlab instantiates
// (xsimd::avx512bw). Equality-with-NaN semantics are handled in core/simd/wide.h instead, because
// xsimd's SSE/AVX kernels share the ordered != and glintlab needs the same fix on every ISA.
#if defined(__AVX512F__) && XSIMD_VERSION_MAJOR == 8
namespace xsimd::kernel {

#define GLINTLAB_XSIMD_FUSED(name, ps, pd)                                                        \
  template <>                                                                                    \
  inline batch<float, avx512bw> name<avx512bw, float>(                                           \
      batch<float, avx512bw> const& x, batch<float, avx512bw> const& y,                          \
      batch<float, avx512bw> const& z, requires_arch<generic>) noexcept {                        \
    return ps(x, y, z);                                                                          \
  }                                                                                              \
  template <>                                                                                    \
  inline batch<double, avx512bw> name<avx512bw, double>(                                         \
      batch<double, avx512bw> const& x, batch<double, avx512bw> const& y,                        \
      batch<double, avx512bw> const& z, requires_arch<generic>) noexcept {                       \
    return pd(x, y, z);                                                                          \
  }
GLINTLAB_XSIMD_FUSED(fma, _mm512_fmadd_ps, _mm512_fmadd_pd)     // x*y + z
GLINTLAB_XSIMD_FUSED(fms, _mm512_fmsub_ps, _mm512_fmsub_pd)     // x*y − z
GLINTLAB_XSIMD_FUSED(fnma, _mm512_fnmadd_ps, _mm512_fnmadd_pd)  // −x*y + z
GLINTLAB_XSIMD_FUSED(fnms, _mm512_fnmsub_ps, _mm512_fnmsub_pd)  // −x*y − z
#undef GLINTLAB_XSIMD_FUSED

// Negation flips the sign bit, as the scalar −x and xsimd's SSE/AVX kernels do.
template <>
inline batch<float, avx512bw> neg<avx512bw, float>(batch<float, avx512bw> const& x,
                                                   requires_arch<avx512f>) noexcept {
  return _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(x), _mm512_set1_epi32(INT_MIN)));
}
template <>
inline batch<double, avx512bw> neg<avx512bw, double>(batch<double, avx512bw> const& x,
                                                     requires_arch<avx512f>) noexcept {
  return _mm512_castsi512_pd(
      _mm512_xor_si512(_mm512_castpd_si512(x), _mm512_set1_epi64(LLONG_MIN)));
}

}  // namespace xsimd::kernel
#endif

// Lane operations of the Chermain kernels (core/glints/chermain.h, chermain_lookup.h) on the SIMD
// double batches: texel gathers, exact powers of two and the cells' counter draws (the SplitMix64
// mixer of core/math/rng.h) in vector registers, each lane the very bits of the scalar code.
#pragma once

// Why here and not in the ops layer: these are the only places the Chermain kernels leave the
// registers (a per-lane store, a libm or scalar integer step per lane, a load), and they are exact
// integer or power-of-two steps, so each has a vector form with the scalar bits. The vector forms
// take the batch's register (Wide<xsimd::batch<double, A>>::v converts to it) by its lane count and
// the instruction set this translation unit is built for: 8 lanes with AVX-512 (DQ), 4 with AVX2,
// 2 with SSE2; any other type (the scalar double instantiation, the host code) keeps the per-lane
// code. Forced inline: an out-of-line copy would be compiled for one unit's ISA and kept by the
// linker for every caller (core/math/rng.h).

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "core/math/config.h"
#include "core/math/lanes.h"
#include "core/math/rng.h"

namespace glintlab::chermain2021::lanes {

// The vector path a type takes: its double lanes when it is a SIMD batch of doubles this unit has
// the instructions for, else 0 (the per-lane code).
template <class T>
inline constexpr std::size_t kVectorDoubles = [] {
  if constexpr (std::is_floating_point_v<T> || !std::is_same_v<Scalar<T>, double>) {
    return std::size_t(0);
  } else {
    constexpr std::size_t n = kLaneCount<T>;
#if defined(__AVX512F__) && defined(__AVX512DQ__)
    if (n == 8) return n;
#endif
#if defined(__AVX2__)
    if (n == 4) return n;
#endif
#if defined(__SSE2__)
    if (n == 2) return n;
#endif
    return std::size_t(0);
  }
}();

// T from its register.
template <class T, class R>
GLINTLAB_INLINE T from_register(const R& r) {
  return T::wrap(decltype(T{}.v)(r));
}

// table[i] as a double in every lane, i the lane's integer-valued index in [0, 2^31) (the callers
// wrap or clamp it); a gather of floats, widened (exact).
template <class T>
GLINTLAB_INLINE T gather_texels(const float* table, const T& index) {
  constexpr std::size_t n = kVectorDoubles<T>;
  if constexpr (n == 8) {
#if defined(__AVX512F__) && defined(__AVX512DQ__)
    const __m256i at = _mm512_cvttpd_epi32(index.v);
    return from_register<T>(_mm512_cvtps_pd(_mm256_i32gather_ps(table, at, 4)));
#endif
  } else if constexpr (n == 4) {
#if defined(__AVX2__)
    const __m128i at = _mm256_cvttpd_epi32(index.v);
    return from_register<T>(_mm256_cvtps_pd(_mm_i32gather_ps(table, at, 4)));
#endif
  } else {
    const LanesOf<T> at(index);
    return float_lanes<T>(
        [&](std::size_t l) { return Scalar<T>(table[static_cast<std::size_t>(at[l])]); });
  }
}

// table[i0] and table[i1] per lane from one 64-bit gather of the pair at lo = min(i0, i1): the two
// taps of a linear lookup, whose wrapped indices are equal or adjacent (|i0 − i1| ≤ 1), so each
// is the pair's first or second float. table[lo + 1] must be readable (the dictionary keeps one
// float past its last table). Integer-valued indices in [0, 2^31); 8 or 4 lanes only (the SSE2
// batch has no gather: the caller reads the taps one by one).
template <class T>
GLINTLAB_INLINE void gather_texel_pair(const float* table, const T& i0, const T& i1, T* t0, T* t1) {
  constexpr std::size_t n = kVectorDoubles<T>;
  static_assert(n == 8 || n == 4, "gather_texel_pair: the AVX-512 and AVX2 batches only");
  if constexpr (n == 8) {
#if defined(__AVX512F__) && defined(__AVX512DQ__)
    const __m512d lo = _mm512_min_pd(i0.v, i1.v);
    const __m512i pair = _mm512_i32gather_epi64(_mm512_cvttpd_epi32(lo), table, 4);
    const __m512d first = _mm512_cvtps_pd(_mm256_castsi256_ps(_mm512_cvtepi64_epi32(pair)));
    const __m512d second =
        _mm512_cvtps_pd(_mm256_castsi256_ps(_mm512_cvtepi64_epi32(_mm512_srli_epi64(pair, 32))));
    *t0 = from_register<T>(
        _mm512_mask_blend_pd(_mm512_cmp_pd_mask(i0.v, lo, _CMP_EQ_OQ), second, first));
    *t1 = from_register<T>(
        _mm512_mask_blend_pd(_mm512_cmp_pd_mask(i1.v, lo, _CMP_EQ_OQ), second, first));
#endif
  } else {
#if defined(__AVX2__)
    const __m256d lo = _mm256_min_pd(i0.v, i1.v);
    const __m256i pair = _mm256_i32gather_epi64(reinterpret_cast<const long long*>(table),
                                                _mm256_cvttpd_epi32(lo), 4);
    // Floats 0, 2, 4, 6 (the pairs' first) to the low half, 1, 3, 5, 7 to the high half.
    const __m256i split =
        _mm256_permutevar8x32_epi32(pair, _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7));
    const __m256d first = _mm256_cvtps_pd(_mm_castsi128_ps(_mm256_castsi256_si128(split)));
    const __m256d second = _mm256_cvtps_pd(_mm_castsi128_ps(_mm256_extracti128_si256(split, 1)));
    *t0 = from_register<T>(_mm256_blendv_pd(second, first, _mm256_cmp_pd(i0.v, lo, _CMP_EQ_OQ)));
    *t1 = from_register<T>(_mm256_blendv_pd(second, first, _mm256_cmp_pd(i1.v, lo, _CMP_EQ_OQ)));
#endif
  }
}

// 2^e per lane for an integer-valued e in [−1022, 1023] (exact): e + 2^52 + 1023 holds e + 1023 in
// its low mantissa bits, which the shift moves into the exponent field.
template <class T>
GLINTLAB_INLINE T exp2_int(const T& e) {
  constexpr std::size_t n = kVectorDoubles<T>;
  constexpr double kBias = 0x1p52 + 1023.0;
  if constexpr (n == 8) {
#if defined(__AVX512F__) && defined(__AVX512DQ__)
    const __m512i b = _mm512_castpd_si512(_mm512_add_pd(e.v, _mm512_set1_pd(kBias)));
    return from_register<T>(_mm512_castsi512_pd(_mm512_slli_epi64(b, 52)));
#endif
  } else if constexpr (n == 4) {
#if defined(__AVX2__)
    const __m256i b = _mm256_castpd_si256(_mm256_add_pd(e.v, _mm256_set1_pd(kBias)));
    return from_register<T>(_mm256_castsi256_pd(_mm256_slli_epi64(b, 52)));
#endif
  } else if constexpr (n == 2) {
#if defined(__SSE2__)
    const __m128i b = _mm_castpd_si128(_mm_add_pd(e.v, _mm_set1_pd(kBias)));
    return from_register<T>(_mm_castsi128_pd(_mm_slli_epi64(b, 52)));
#endif
  } else {
    const LanesOf<T> el(e);
    return float_lanes<T>(
        [&](std::size_t l) { return std::ldexp(Scalar<T>(1), static_cast<int>(el[l])); });
  }
}

// 64-bit integer lanes of a vector path: the mixer's operations on them.
#if defined(__AVX512F__) && defined(__AVX512DQ__)
struct U64x8 {
  __m512i v;
  GLINTLAB_INLINE static U64x8 set1(std::uint64_t x) {
    return {_mm512_set1_epi64(std::int64_t(x))};
  }
  GLINTLAB_INLINE friend U64x8 operator^(U64x8 a, U64x8 b) { return {_mm512_xor_si512(a.v, b.v)}; }
  GLINTLAB_INLINE friend U64x8 operator+(U64x8 a, U64x8 b) { return {_mm512_add_epi64(a.v, b.v)}; }
  GLINTLAB_INLINE friend U64x8 operator*(U64x8 a, std::uint64_t c) {
    return {_mm512_mullo_epi64(a.v, _mm512_set1_epi64(std::int64_t(c)))};
  }
  template <int kShift>
  GLINTLAB_INLINE U64x8 shr() const {
    return {_mm512_srli_epi64(v, kShift)};
  }
};
#endif
#if defined(__AVX2__)
struct U64x4 {
  __m256i v;
  GLINTLAB_INLINE static U64x4 set1(std::uint64_t x) {
    return {_mm256_set1_epi64x(std::int64_t(x))};
  }
  GLINTLAB_INLINE friend U64x4 operator^(U64x4 a, U64x4 b) { return {_mm256_xor_si256(a.v, b.v)}; }
  GLINTLAB_INLINE friend U64x4 operator+(U64x4 a, U64x4 b) { return {_mm256_add_epi64(a.v, b.v)}; }
  // The low 64 bits of a · c from 32-bit halves (AVX2 has no 64-bit multiply): a_lo c_lo +
  // ((a_hi c_lo + a_lo c_hi) << 32), modulo 2^64.
  GLINTLAB_INLINE friend U64x4 operator*(U64x4 a, std::uint64_t c) {
    const __m256i c_lo = _mm256_set1_epi64x(std::int64_t(c & 0xffffffffULL));
    const __m256i c_hi = _mm256_set1_epi64x(std::int64_t(c >> 32));
    const __m256i lo = _mm256_mul_epu32(a.v, c_lo);
    const __m256i cross = _mm256_add_epi64(_mm256_mul_epu32(_mm256_srli_epi64(a.v, 32), c_lo),
                                           _mm256_mul_epu32(a.v, c_hi));
    return {_mm256_add_epi64(lo, _mm256_slli_epi64(cross, 32))};
  }
  template <int kShift>
  GLINTLAB_INLINE U64x4 shr() const {
    return {_mm256_srli_epi64(v, kShift)};
  }
};
#endif
#if defined(__SSE2__)
struct U64x2 {
  __m128i v;
  GLINTLAB_INLINE static U64x2 set1(std::uint64_t x) { return {_mm_set1_epi64x(std::int64_t(x))}; }
  GLINTLAB_INLINE friend U64x2 operator^(U64x2 a, U64x2 b) { return {_mm_xor_si128(a.v, b.v)}; }
  GLINTLAB_INLINE friend U64x2 operator+(U64x2 a, U64x2 b) { return {_mm_add_epi64(a.v, b.v)}; }
  GLINTLAB_INLINE friend U64x2 operator*(U64x2 a, std::uint64_t c) {
    const __m128i c_lo = _mm_set1_epi64x(std::int64_t(c & 0xffffffffULL));
    const __m128i c_hi = _mm_set1_epi64x(std::int64_t(c >> 32));
    const __m128i lo = _mm_mul_epu32(a.v, c_lo);
    const __m128i cross =
        _mm_add_epi64(_mm_mul_epu32(_mm_srli_epi64(a.v, 32), c_lo), _mm_mul_epu32(a.v, c_hi));
    return {_mm_add_epi64(lo, _mm_slli_epi64(cross, 32))};
  }
  template <int kShift>
  GLINTLAB_INLINE U64x2 shr() const {
    return {_mm_srli_epi64(v, kShift)};
  }
};
#endif

// mix64 (core/math/rng.h) on the lanes of U.
template <class U>
GLINTLAB_INLINE U mix64_lanes(U z) {
  z = (z ^ z.template shr<30>()) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ z.template shr<27>()) * 0x94d049bb133111ebULL;
  return z ^ z.template shr<31>();
}

// Per width: the double register, its integer lanes, and the conversions the draws need.
template <std::size_t N>
struct VectorOf;
#if defined(__AVX512F__) && defined(__AVX512DQ__)
template <>
struct VectorOf<8> {
  using D = __m512d;
  using U = U64x8;
  GLINTLAB_INLINE static D set1(double x) { return _mm512_set1_pd(x); }
  GLINTLAB_INLINE static D mul(D a, D b) { return _mm512_mul_pd(a, b); }
  // Truncation to int64, as the scalar cast of each lane; every lane converts.
  GLINTLAB_INLINE static bool to_int(D x, U* out) {
    out->v = _mm512_cvttpd_epi64(x);
    return true;
  }
  // b < 2^53 to double (exact).
  GLINTLAB_INLINE static D to_double(U b) { return _mm512_cvtepu64_pd(b.v); }
};
#endif
#if defined(__AVX2__)
template <>
struct VectorOf<4> {
  using D = __m256d;
  using U = U64x4;
  GLINTLAB_INLINE static D set1(double x) { return _mm256_set1_pd(x); }
  GLINTLAB_INLINE static D mul(D a, D b) { return _mm256_mul_pd(a, b); }
  // Integer-valued x with |x| < 2^51: x + 1.5·2^52 holds x + 2^51 in its mantissa. false (nothing
  // written) when a lane is out of that range or NaN.
  GLINTLAB_INLINE static bool to_int(D x, U* out) {
    const D magic = _mm256_set1_pd(0x1.8p52);  // 1.5·2^52
    const D abs_x = _mm256_andnot_pd(_mm256_set1_pd(-0.0), x);
    if (_mm256_movemask_pd(_mm256_cmp_pd(abs_x, _mm256_set1_pd(0x1p51), _CMP_NLT_UQ))) return false;
    out->v =
        _mm256_sub_epi64(_mm256_castpd_si256(_mm256_add_pd(x, magic)), _mm256_castpd_si256(magic));
    return true;
  }
  // b < 2^53 as 2^32 hi + lo: hi through 2^84 + hi 2^32, lo through 2^52 + lo; the sums exact.
  GLINTLAB_INLINE static D to_double(U b) {
    const __m256i lo = _mm256_blend_epi32(b.v, _mm256_castpd_si256(_mm256_set1_pd(0x1p52)), 0xaa);
    const __m256i hi =
        _mm256_or_si256(_mm256_srli_epi64(b.v, 32), _mm256_castpd_si256(_mm256_set1_pd(0x1p84)));
    const D high = _mm256_sub_pd(_mm256_castsi256_pd(hi),
                                 _mm256_set1_pd(0x1.00000001p84));  // 2^84 + 2^52
    return _mm256_add_pd(high, _mm256_castsi256_pd(lo));
  }
};
#endif
#if defined(__SSE2__)
template <>
struct VectorOf<2> {
  using D = __m128d;
  using U = U64x2;
  GLINTLAB_INLINE static D set1(double x) { return _mm_set1_pd(x); }
  GLINTLAB_INLINE static D mul(D a, D b) { return _mm_mul_pd(a, b); }
  GLINTLAB_INLINE static bool to_int(D x, U* out) {
    const D magic = _mm_set1_pd(0x1.8p52);
    const D abs_x = _mm_andnot_pd(_mm_set1_pd(-0.0), x);
    if (_mm_movemask_pd(_mm_cmpnlt_pd(abs_x, _mm_set1_pd(0x1p51)))) return false;
    out->v = _mm_sub_epi64(_mm_castpd_si128(_mm_add_pd(x, magic)), _mm_castpd_si128(magic));
    return true;
  }
  GLINTLAB_INLINE static D to_double(U b) {
    const __m128i lo = _mm_or_si128(_mm_and_si128(b.v, _mm_set1_epi64x(0xffffffffLL)),
                                    _mm_castpd_si128(_mm_set1_pd(0x1p52)));
    const __m128i hi = _mm_or_si128(_mm_srli_epi64(b.v, 32), _mm_castpd_si128(_mm_set1_pd(0x1p84)));
    const D high = _mm_sub_pd(_mm_castsi128_pd(hi), _mm_set1_pd(0x1.00000001p84));
    return _mm_add_pd(high, _mm_castsi128_pd(lo));
  }
};
#endif

// The three uniforms counter_uniform<double>(seed, key, d), d = 0, 1, 2, of each lane's cell key.
template <class T>
struct CellUniforms {
  T u0, u1, u2;
};

// On a vector path: the parts of the cell keys (cell_key, core/glints/chermain.h) of the four
// cells with lower-left corners (cu + di, cv + dj)·scale, di, dj ∈ {0, 1}, that two of them share:
// mix64(ci·φ) per column di and cj per row dj, and the step of counter_bits common to the batch.
template <class T>
struct CellBlockKeys {
  using U = typename VectorOf<kVectorDoubles<T>>::U;
  U column[2], row[2];
  U seed_step;
};

// The shared key parts of the 2 × 2 cells at (cu, cv) (see cell_uniforms); false (nothing written)
// where a lane's corner is beyond the exact integer conversion: the caller then takes the per-lane
// code.
template <class T>
GLINTLAB_INLINE bool cell_block_keys(std::uint64_t seed, const T& cu, const T& cv, const T& scale,
                                     CellBlockKeys<T>* out) {
  using V = VectorOf<kVectorDoubles<T>>;
  using U = typename V::U;
  U ci[2], cj[2];
  if (!V::to_int(V::mul(cu.v, scale.v), &ci[0]) ||
      !V::to_int(V::mul((cu + T(1)).v, scale.v), &ci[1]) ||
      !V::to_int(V::mul(cv.v, scale.v), &cj[0]) ||
      !V::to_int(V::mul((cv + T(1)).v, scale.v), &cj[1]))
    return false;
  for (int d = 0; d < 2; ++d) {
    out->column[d] = mix64_lanes(ci[d] * 0x9e3779b97f4a7c15ULL);
    out->row[d] = cj[d];
  }
  out->seed_step = U::set1(mix64(seed + 0x9e3779b97f4a7c15ULL));
  return true;
}

// The uniforms of cell (di, dj) of a block (cell_block_keys): as cell_uniforms.
template <class T>
GLINTLAB_INLINE CellUniforms<T> block_cell_uniforms(const CellBlockKeys<T>& keys, int di, int dj) {
  using V = VectorOf<kVectorDoubles<T>>;
  using U = typename V::U;
  const U key = keys.column[di] ^ keys.row[dj];
  const U h = mix64_lanes(keys.seed_step ^ (key + U::set1(0x632be59bd9b4e019ULL)));
  const auto uniform = [&](std::uint64_t dim) {
    const U bits = mix64_lanes(h ^ U::set1(dim * 0xd1b54a32d192ed03ULL + 0x8cb92ba72f3d8dd7ULL));
    return from_register<T>(V::mul(V::to_double(bits.template shr<11>()), V::set1(0x1p-53)));
  };
  return {uniform(0), uniform(1), uniform(2)};
}

// On a vector path (kVectorDoubles<T> > 0): the uniforms of the cells with lower-left corners
// (cu, cv)·scale in units of 2^-20 (integer-valued products), the key of each as cell_key
// (core/glints/chermain.h) computes it, then counter_bits (core/math/rng.h) split into its step
// common to the batch (mix64(seed + c)), one per key and one per dimension. false (nothing
// written) where a lane's corner is beyond the exact integer conversion (|·| ≥ 2^51 without
// AVX-512): the caller then takes the per-lane code.
template <class T>
GLINTLAB_INLINE bool cell_uniforms(std::uint64_t seed, const T& cu, const T& cv, const T& scale,
                                   CellUniforms<T>* out) {
  using V = VectorOf<kVectorDoubles<T>>;
  using U = typename V::U;
  U ci, cj;
  if (!V::to_int(V::mul(cu.v, scale.v), &ci) || !V::to_int(V::mul(cv.v, scale.v), &cj))
    return false;
  const U key = mix64_lanes(ci * 0x9e3779b97f4a7c15ULL) ^ cj;
  const U h = mix64_lanes(U::set1(mix64(seed + 0x9e3779b97f4a7c15ULL)) ^
                          (key + U::set1(0x632be59bd9b4e019ULL)));
  // counter_uniform<double>: the top 53 bits times 2^-53.
  const auto uniform = [&](std::uint64_t dim) {
    const U bits = mix64_lanes(h ^ U::set1(dim * 0xd1b54a32d192ed03ULL + 0x8cb92ba72f3d8dd7ULL));
    return from_register<T>(V::mul(V::to_double(bits.template shr<11>()), V::set1(0x1p-53)));
  };
  *out = {uniform(0), uniform(1), uniform(2)};
  return true;
}

}  // namespace glintlab::chermain2021::lanes

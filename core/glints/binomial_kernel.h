// The exact Binomial(n, p) draw of core/glints/binomial.h (binomial_exact: inverse CDF for n·p <
// 10, Hörmann 1993 BTRS otherwise) as a kernel on any float type: masked loops that run while any
// lane is still drawing, every lane on its own stream of uniforms, with binomial_exact's
// double-precision steps. Given binomial_exact's uniforms (CounterStream: core/math/rng.h's
// 64-bit counters, lane by lane) each lane gets exactly the count binomial_exact draws for it;
// the glint models draw from HashStream (core/math/hash32.h's 32-bit counter hash on the batch's
// own integer lanes), the same algorithm on other uniforms.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include "core/math/hash32_stream.h"
#include "core/math/lane_rng.h"
#include "core/math/ops.h"
#include "core/math/rng.h"

namespace glintlab {

// Uniforms in [0, 1) of dims 0, 1, … of each lane's hash32 stream (its key: hash32_key and
// hash32_nest), computed in the integer lanes of T (HashLaneTraits): 24 bits for float, 32 for
// double.
template <class T>
struct HashStream {
  HashLanes<T> key;
  GLINTLAB_INLINE T uniform(std::uint32_t dim) const;
};

// counter_uniform(seed, index of each lane, dim) (core/math/rng.h), lane by lane.
template <class T>
struct CounterStream {
  std::uint64_t seed;
  RngIndex<T> index;
  GLINTLAB_FN T uniform(std::uint32_t dim) const { return lane_uniform<T>(seed, index, dim); }
};

namespace detail {

// The same register as 32-bit lanes, for hash lanes of 64-bit integers (a double batch's:
// xsimd::batch<std::uint64_t, A> → xsimd::batch<std::uint32_t, A>); void for other lane types.
template <class U>
struct HalfWidthLanes {
  using type = void;
};
template <template <class, class> class Batch, class A>
struct HalfWidthLanes<Batch<std::uint64_t, A>> {
  using type = Batch<std::uint32_t, A>;
};
template <class T>
concept WideHashLanes = !std::is_void_v<typename HalfWidthLanes<HashLanes<T>>::type>;

// hash32_draw's counter term for dim (the wrap32 of dim · 0x85ebca6b + 0xc2b2ae35).
GLINTLAB_FN std::uint32_t hash32_dim_term(std::uint32_t dim) {
  return dim * 0x85ebca6bu + 0xc2b2ae35u;
}

// hash32 of 64-bit lanes holding 32-bit values, in the register's 32-bit lanes: the multiplies
// are the ISA's 32-bit ones (AVX2 has no 64-bit multiply; xsimd would multiply lane by lane)
// instead of 64-bit products wrapped to 32 bits, which have the same low 32 bits. A high half
// holding 0 stays 0 (hash32(0) = 0); a high half holding another 32-bit value is hashed on its
// own (two hashes per lane).
template <class U64>
GLINTLAB_INLINE U64 hash32_halves(const U64& x) {
  using U32 = typename HalfWidthLanes<U64>::type;
  return std::bit_cast<U64>(hash32(std::bit_cast<U32>(x)));
}

// HashLaneTraits<T>::to_uniform of 64-bit lanes below 2^32 (the double batches'): the value as
// the low mantissa bits of 2^52 (exact, no int64 conversion, which AVX2 lacks), times 2^-32.
template <class T>
GLINTLAB_INLINE T uniform_from_low_bits(const HashLanes<T>& bits) {
  using B = typename T::Raw;
  const B two52(4503599627370496.0);
  const B value = std::bit_cast<B>(bits | HashLanes<T>(0x4330000000000000ull)) - two52;
  return T::wrap(value * B(1.0 / 4294967296.0));
}

}  // namespace detail

// hash32_uniform(hash32_draw(key, dim)) in every lane: on double batches its 32-bit steps run in
// the register's 32-bit lanes (detail::hash32_halves), the same bits.
template <class T>
GLINTLAB_INLINE T HashStream<T>::uniform(std::uint32_t dim) const {
  if constexpr (detail::WideHashLanes<T>) {
    const HashLanes<T> h =
        detail::hash32_halves(key ^ HashLanes<T>(std::uint64_t(detail::hash32_dim_term(dim))));
    return detail::uniform_from_low_bits<T>(h);
  } else {
    return hash32_uniform<T>(hash32_draw(key, HashLanes<T>(dim)));
  }
}

namespace detail {

// The uniforms of dims dim and dim + 1 of a stream (BTRS's u and v of one attempt).
template <class T>
struct UniformPair {
  T first, second;
};
template <class T, class Stream>
GLINTLAB_INLINE UniformPair<T> uniform_pair(const Stream& stream,
                                                                std::uint32_t dim) {
  return {stream.uniform(dim), stream.uniform(dim + 1)};
}
// On a double batch both in one hash32 of the register's 32-bit lanes: each 64-bit lane holds
// its key ^ dim's term in the low half and key ^ (dim + 1)'s in the high half.
template <class T>
requires WideHashLanes<T>
GLINTLAB_INLINE UniformPair<T> uniform_pair(const HashStream<T>& stream,
                                                                std::uint32_t dim) {
  using U = HashLanes<T>;
  const std::uint64_t terms =
      std::uint64_t(hash32_dim_term(dim)) | (std::uint64_t(hash32_dim_term(dim + 1)) << 32);
  const U h = hash32_halves((stream.key | (stream.key << 32)) ^ U(terms));
  return {uniform_from_low_bits<T>(h & U(0xffffffffu)), uniform_from_low_bits<T>(h >> 32)};
}

}  // namespace detail

// Iteration bounds of the masked loops. Inversion: for n·p < 10 (p ≤ ½) the host loop stops by
// k ≈ n·p + 60 at the latest (the pmf falls below 1e-18 of the CDF there; for p near ½, n < 20),
// so 256 steps are never the binding limit. BTRS: an attempt is accepted with probability above
// ~0.8 (Hörmann 1993, Table 1), so 128 attempts are all rejected with probability < 1e-80; a lane
// that did reach the bound would keep its last in-range candidate.
inline constexpr int kBinomialInversionMaxSteps = 256;
inline constexpr int kBinomialBtrsMaxAttempts = 128;

namespace detail {

// log k! for k = 0..15 as the host's log_factorial computes it there (std::lgamma(k + 1)), so a
// gather gives the very values. Defined once in binomial_kernel.cpp (an inline variable with a
// dynamic initializer would give every ISA object a shared weak guard symbol).
extern const std::array<double, 16> kLogFactorialTable;

// Stirling's series of log_factorial (A&S 6.1.41), in its operation order, for x = k + 1 and
// its log.
template <class D>
GLINTLAB_FN D stirling_from_log(D x, D log_x) {
  const D ix = D(1) / x, ix2 = ix * ix;
  return (x - D(0.5)) * log_x - x + D(0.91893853320467274178) +
         ix * (D(1.0 / 12) - ix2 * (D(1.0 / 360) - ix2 * D(1.0 / 1260)));
}
template <class D>
GLINTLAB_FN D stirling_log_factorial(D k) {
  const D x = k + D(1);
  return stirling_from_log(x, log(x));
}

// log_factorial on lanes from Stirling's value where k ≥ 16: the table below 16.
template <class D>
GLINTLAB_FN D log_factorial_lanes_from(D k, D stirling) {
  const Mask<D> small = k < D(16);
  if (!any_lane<D>(small)) return stirling;
  const D table = lane_gather(kLogFactorialTable.data(), clamp(k, D(0), D(15)));
  if (!any_lane<D>(!small)) return table;
  return select(small, table, stirling);
}

// log_factorial on lanes: the table below 16, Stirling above; of the two, only what some lane
// selects is computed (a uniform branch; the same values).
template <class D>
GLINTLAB_FN D log_factorial_lanes(D k) {
  const Mask<D> small = k < D(16);
  if (!any_lane<D>(small)) return stirling_log_factorial(k);
  const D table = lane_gather(kLogFactorialTable.data(), clamp(k, D(0), D(15)));
  if (!any_lane<D>(!small)) return table;
  return select(small, table, stirling_log_factorial(k));
}

template <class D>
GLINTLAB_FN D stirling_correction(D x) {
  const D ix = D(1) / x, ix2 = ix * ix;
  return ix * (D(1.0 / 12) - ix2 * (D(1.0 / 360) - ix2 * D(1.0 / 1260)));
}

// log_factorial_ratio(a, ·) on lanes (the differenced Stirling form where both are ≥ 16) for a
// fixed a (BTRS's m and n − m, the same on every attempt): a's logs computed once, log(a + 1)
// shared by the differenced form and log a! (Stirling's). Of the two forms, only the one some
// lane selects is computed (a uniform branch; the same values).
template <class D>
struct LogFactorialRatioFrom {
  D a, xa, log_xa, correction_a, log_factorial_a;
  LogFactorialRatioFrom() = default;
  GLINTLAB_FN explicit LogFactorialRatioFrom(D a_)
      : a(a_),
        xa(a_ + D(1)),
        log_xa(log(xa)),
        correction_a(stirling_correction(xa)),
        log_factorial_a(log_factorial_lanes_from(a_, stirling_from_log(xa, log_xa))) {}
  GLINTLAB_FN D operator()(D b) const {
    const Mask<D> small = a < D(16) || b < D(16);
    if (!any_lane<D>(!small)) return log_factorial_a - log_factorial_lanes(b);
    const D xb = b + D(1), d = a - b;
    const D big = d * log_xa + (xb - D(0.5)) * log1p(d / xb) - d + correction_a -
                  stirling_correction(xb);
    if (!any_lane<D>(small)) return big;
    return select(small, log_factorial_a - log_factorial_lanes(b), big);
  }
};

// detail::binomial_inversion on the lanes of `active` (n·p < 10, p ≤ ½; others keep k = 0), u
// dim 0 of the stream (not drawn where no lane is active). A lane still running at step `it` has
// stepped at every step before, so its k is `it`: the pmf recurrence runs on every lane with that
// k (the same operations, so a running lane's f and cdf have the host loop's bits) and only the
// count is selected per lane. That keeps the masks and the division off the loop-carried chain
// (f·ratio, cdf + f), which otherwise waited on each step's compare and select.
template <class D, class Stream>
GLINTLAB_FN D binomial_inversion_lanes(D nd, D p, const Stream& stream, Mask<D> active) {
  if (!any_lane<D>(active)) return D(0);
  const D u = stream.uniform(0);
  const D q = D(1) - p, r = p / q;
  // Lanes not drawing start from 0 and stay 0 (no overflowing or denormal pmf on them).
  D f = select(active, exp(nd * log1p(-p)), D(0));
  D cdf = f;
  D k = D(0);
  const D stop_above = nd * p + D(1);
  Mask<D> running = active;
  for (int it = 0; it < kBinomialInversionMaxSteps; ++it) {
    const D k_running = D(Scalar<D>(it));
    const D k_next = D(Scalar<D>(it + 1));
    const Mask<D> step = running && (u > cdf) && (k_running < nd);
    if (!any_lane<D>(step)) break;  // uniform: no lane is still stepping
    f = f * ((nd - k_running) / k_next * r);
    cdf = cdf + f;
    k = select(step, k_next, k);
    const Mask<D> stop = (k_next > stop_above) && (f < D(1e-18) * cdf);
    running = step && !stop;
  }
  return k;
}

// detail::binomial_btrs on the lanes of `active` (n·p ≥ 10, p ≤ ½; others are left undefined):
// attempt j reads dims 2j and 2j + 1 of each lane's stream, as the host loop does; a lane stops
// at its first acceptance. The acceptance test's logs are computed only on attempts where some
// lane still drawing is in range and fails the squeeze (a uniform branch: the lanes the squeeze
// accepts do not read them), and its constants (alpha, log(p/q), the ratios' logs of m and
// n − m) on the first such attempt: where the squeeze decides every lane, never.
template <class D, class Stream>
GLINTLAB_FN D binomial_btrs_lanes(D nd, D p, const Stream& stream, Mask<D> active) {
  if (!any_lane<D>(active)) return D(0);
  const D q = D(1) - p;
  const D spq = sqrt(nd * p * q);
  const D b = D(1.15) + D(2.53) * spq;
  const D a = D(-0.0873) + D(0.0248) * b + D(0.01) * p;
  const D c = nd * p + D(0.5);
  const D vr = D(0.92) - D(4.2) / b;
  const D m = floor((nd + D(1)) * p);
  bool test_ready = false;
  D alpha, lpq;
  LogFactorialRatioFrom<D> ratio_from_m, ratio_from_n_minus_m;
  D result = m;
  Mask<D> left = active;
  for (int j = 0; j < kBinomialBtrsMaxAttempts && any_lane<D>(left); ++j) {
    const UniformPair<D> uv = uniform_pair<D>(stream, 2 * std::uint32_t(j));
    const D u = uv.first - D(0.5);
    const D v = uv.second;
    const D us = D(0.5) - abs(u);
    const D kd = floor((D(2) * a / us + b) * u + c);
    const Mask<D> in_range = !(kd < D(0) || kd > nd);
    const Mask<D> squeeze = us >= D(0.07) && v <= vr;
    Mask<D> accept = left && in_range && squeeze;
    const Mask<D> tested = left && in_range && !squeeze;
    if (any_lane<D>(tested)) {
      if (!test_ready) {
        alpha = (D(2.83) + D(5.1) / b) * spq;
        lpq = log(p / q);
        ratio_from_m = LogFactorialRatioFrom<D>(m);
        ratio_from_n_minus_m = LogFactorialRatioFrom<D>(nd - m);
        test_ready = true;
      }
      const D lv = log(v * alpha / (a / (us * us) + b));
      const D lr = ratio_from_m(kd) + ratio_from_n_minus_m(nd - kd) + (kd - m) * lpq;
      accept = accept || (tested && lv <= lr);
    }
    result = select(accept, kd, result);
    left = left && !accept;
  }
  return result;
}

// binomial_exact(n, p, seed, index) on a double type D with the uniforms of `stream` (dim 0 for
// the inversion, dims 2j, 2j + 1 for BTRS's attempt j): n integer-valued in [0, 2^53).
template <class D, class Stream>
GLINTLAB_FN D binomial_exact_double_lanes(D nd, D p, const Stream& stream) {
  const Mask<D> none = nd == D(0) || !(p > D(0));
  const Mask<D> all_n = p >= D(1);
  const Mask<D> live = !none && !all_n;
  const Mask<D> flip = p > D(0.5);
  const D pp = select(flip, D(1) - p, p);
  const Mask<D> small = nd * pp < D(10);
  const D k_inv = binomial_inversion_lanes(nd, pp, stream, live && small);
  const D k_btrs = binomial_btrs_lanes(nd, pp, stream, live && !small);
  D k = select(small, k_inv, k_btrs);
  k = select(flip, nd - k, k);
  return select(none, D(0), select(all_n, nd, k));
}

// The 32-bit values of a hash-lane type's lanes, stored to and loaded from plain arrays.
template <class U>
GLINTLAB_FN void store_hash_lanes(const U& h, std::uint32_t* out) {
  if constexpr (std::is_integral_v<U>) {
    out[0] = h;
  } else {
    alignas(64) typename U::value_type v[U::size];
    h.store_aligned(v);
    for (std::size_t l = 0; l < U::size; ++l) out[l] = static_cast<std::uint32_t>(v[l]);
  }
}
template <class U>
GLINTLAB_FN U load_hash_lanes(const std::uint32_t* in) {
  if constexpr (std::is_integral_v<U>) {
    return in[0];
  } else {
    alignas(64) typename U::value_type v[U::size];
    for (std::size_t l = 0; l < U::size; ++l) v[l] = in[l];
    return U::load_aligned(v);
  }
}

}  // namespace detail

namespace detail {

// Whether binomial_exact_lanes draws T's live lanes packed (binomial_exact_packed): float batches
// of 16 lanes where this unit has AVX-512 (vcompressps / vexpandps), of 8 where it has AVX2 (a
// permutation from a table). 0: the lanes in place, part by part.
template <class T>
inline constexpr std::size_t kPackedBinomialLanes = [] {
  if constexpr (std::is_floating_point_v<T> || !std::is_same_v<Scalar<T>, float>) {
    return std::size_t(0);
  } else {
    [[maybe_unused]] constexpr std::size_t n = LaneTraits<T>::kLanes;
#if defined(__AVX512F__)
    if (n == 16) return n;
#endif
#if defined(__AVX2__)
    if (n == 8) return n;
#endif
    return std::size_t(0);
  }
}();

// For each 8-bit mask of lanes: the permutation that puts its lanes first, in order, then the
// others (pack: the lane at each place), and its inverse (unpack: the place of each lane).
struct LanePermutations {
  std::array<std::array<std::uint8_t, 8>, 256> pack{}, unpack{};
};
// Defined once in binomial_kernel.cpp: an inline variable would be a weak symbol of every ISA
// object that reads it (tests/simd/isa_symbols_test.cmake).
extern const LanePermutations kLanePermutations;

// binomial_exact_double_lanes on the live lanes of a float batch (n ≠ 0, 0 < p < 1: those that
// draw), packed to the front so that they fill as few double parts as their number needs: with a
// few live lanes per batch (a footprint's N_P is often 0), one part where there were two (AVX-512:
// 16 float lanes, 8 double; AVX2: 8 and 4), and no exp/log set-up paid for a part of dead lanes.
// Each lane's draw depends on its own n, p and key alone (the loops mask per lane), so a lane
// gets the count it got in place; the others get binomial_exact_double_lanes's 0 (n = 0 or
// p ≤ 0 or NaN) or n (p ≥ 1). The float lanes convert to double exactly, so `live` is decided on
// them.
template <class T>
GLINTLAB_INLINE T binomial_exact_packed(const T& n, const T& p, const HashLanes<T>& key) {
  constexpr std::size_t kL = kPackedBinomialLanes<T>;
  if constexpr (kL == 16) {
#if defined(__AVX512F__)
    using D = typename LaneTraits<T>::Double;
    using DRaw = typename D::Raw;
    using U = HashLanes<D>;
    using Raw = typename T::Raw;
    const __m512 nv = n.v, pv = p.v, zero = _mm512_setzero_ps();
    const __m512i keys = key;
    const __mmask16 live = _mm512_cmp_ps_mask(nv, zero, _CMP_NEQ_UQ) &
                           _mm512_cmp_ps_mask(pv, zero, _CMP_GT_OQ) &
                           _mm512_cmp_ps_mask(pv, _mm512_set1_ps(1.0f), _CMP_LT_OQ);
    const __mmask16 none =
        _mm512_cmp_ps_mask(nv, zero, _CMP_EQ_OQ) | _mm512_cmp_ps_mask(pv, zero, _CMP_NGT_UQ);
    const __m512 dead = _mm512_mask_blend_ps(none, nv, zero);
    if (live == 0) return T::wrap(Raw(dead));
    const __m512 nc = _mm512_maskz_compress_ps(live, nv);
    const __m512 pc = _mm512_maskz_compress_ps(live, pv);
    const __m512i kc = _mm512_maskz_compress_epi32(live, keys);
    const auto draw = [](__m256 n8, __m256 p8, __m256i k8) {
      const D k = binomial_exact_double_lanes(D::wrap(DRaw(_mm512_cvtps_pd(n8))),
                                              D::wrap(DRaw(_mm512_cvtps_pd(p8))),
                                              HashStream<D>{U(_mm512_cvtepu32_epi64(k8))});
      return _mm256_castps_si256(_mm512_cvtpd_ps(k.v));
    };
    const __m256i low = draw(_mm512_castps512_ps256(nc), _mm512_castps512_ps256(pc),
                             _mm512_castsi512_si256(kc));
    __m256i high = _mm256_setzero_si256();
    if (std::popcount(unsigned(live)) > 8)
      high = draw(_mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(nc), 1)),
                  _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(pc), 1)),
                  _mm512_extracti64x4_epi64(kc, 1));
    const __m512 counts =
        _mm512_castsi512_ps(_mm512_inserti64x4(_mm512_castsi256_si512(low), high, 1));
    return T::wrap(Raw(_mm512_mask_expand_ps(dead, live, counts)));
#endif
  } else if constexpr (kL == 8) {
#if defined(__AVX2__)
    using D = typename LaneTraits<T>::Double;
    using DRaw = typename D::Raw;
    using U = HashLanes<D>;
    using Raw = typename T::Raw;
    const __m256 nv = n.v, pv = p.v, zero = _mm256_setzero_ps();
    const __m256i keys = key;
    const __m256 live_lanes = _mm256_and_ps(
        _mm256_and_ps(_mm256_cmp_ps(nv, zero, _CMP_NEQ_UQ), _mm256_cmp_ps(pv, zero, _CMP_GT_OQ)),
        _mm256_cmp_ps(pv, _mm256_set1_ps(1.0f), _CMP_LT_OQ));
    const __m256 none =
        _mm256_or_ps(_mm256_cmp_ps(nv, zero, _CMP_EQ_OQ), _mm256_cmp_ps(pv, zero, _CMP_NGT_UQ));
    const __m256 dead = _mm256_blendv_ps(nv, zero, none);
    const unsigned live = unsigned(_mm256_movemask_ps(live_lanes));
    if (live == 0) return T::wrap(Raw(dead));
    const __m256i pack = _mm256_cvtepu8_epi32(_mm_loadl_epi64(
        reinterpret_cast<const __m128i*>(kLanePermutations.pack[live].data())));
    const __m256 nc = _mm256_permutevar8x32_ps(nv, pack);
    const __m256 pc = _mm256_permutevar8x32_ps(pv, pack);
    const __m256i kc = _mm256_permutevar8x32_epi32(keys, pack);
    const auto draw = [](__m128 n4, __m128 p4, __m128i k4) {
      const D k = binomial_exact_double_lanes(D::wrap(DRaw(_mm256_cvtps_pd(n4))),
                                              D::wrap(DRaw(_mm256_cvtps_pd(p4))),
                                              HashStream<D>{U(_mm256_cvtepu32_epi64(k4))});
      return _mm256_cvtpd_ps(k.v);
    };
    // Lanes packed after the live ones are dead ones (the permutation's rest): drawn, they cost
    // nothing and their result is replaced by `dead`.
    const __m128 low = draw(_mm256_castps256_ps128(nc), _mm256_castps256_ps128(pc),
                            _mm256_castsi256_si128(kc));
    __m128 high = _mm_setzero_ps();
    if (std::popcount(live) > 4)
      high = draw(_mm256_extractf128_ps(nc, 1), _mm256_extractf128_ps(pc, 1),
                  _mm256_extracti128_si256(kc, 1));
    const __m256i unpack = _mm256_cvtepu8_epi32(_mm_loadl_epi64(
        reinterpret_cast<const __m128i*>(kLanePermutations.unpack[live].data())));
    const __m256 counts = _mm256_permutevar8x32_ps(_mm256_set_m128(high, low), unpack);
    return T::wrap(Raw(_mm256_blendv_ps(dead, counts, live_lanes)));
#endif
  }
  // Not reached: kPackedBinomialLanes is 0 where this unit lacks these ISAs.
  static_cast<void>(n), static_cast<void>(p), static_cast<void>(key);
  return T(0);
}

}  // namespace detail

// The exact Binomial(n, p) draw on every lane of T, n a count (integer-valued, ≥ 0), from each
// lane's hash32 stream (HashStream{key}): the lanes converted to double and drawn in the double
// batches of the same ISA (LaneTraits::Double), parts of as many lanes as those hold, each part's
// keys moved to that batch's hash lanes; on AVX2 and AVX-512 float batches the drawing lanes are
// packed into as few parts as they fill first (detail::binomial_exact_packed). On a scalar T: the
// same kernel in double.
template <class T>
GLINTLAB_FN T binomial_exact_lanes(T n, T p, const HashLanes<T>& key) {
  using D = typename LaneTraits<T>::Double;
  if constexpr (std::is_floating_point_v<T>) {
    return T(detail::binomial_exact_double_lanes(double(n), double(p), HashStream<double>{key}));
  } else if constexpr (detail::kPackedBinomialLanes<T> != 0) {
    return detail::binomial_exact_packed(n, p, key);
  } else {
    constexpr std::size_t kL = LaneTraits<T>::kLanes, kD = LaneTraits<D>::kLanes;
    static_assert(kL % kD == 0);
    alignas(64) Scalar<T> ns[kL], ps[kL], out[kL];
    alignas(64) std::uint32_t keys[kL];
    LaneTraits<T>::store(n, ns);
    LaneTraits<T>::store(p, ps);
    detail::store_hash_lanes(key, keys);
    for (std::size_t part = 0; part < kL; part += kD) {
      alignas(64) double nd[kD], pd[kD], kd[kD];
      for (std::size_t l = 0; l < kD; ++l) {
        nd[l] = double(ns[part + l]);
        pd[l] = double(ps[part + l]);
      }
      const D k = detail::binomial_exact_double_lanes(
          LaneTraits<D>::load(nd), LaneTraits<D>::load(pd),
          HashStream<D>{detail::load_hash_lanes<HashLanes<D>>(keys + part)});
      LaneTraits<D>::store(k, kd);
      for (std::size_t l = 0; l < kD; ++l) out[part + l] = Scalar<T>(kd[l]);
    }
    return LaneTraits<T>::load(out);
  }
}

}  // namespace glintlab

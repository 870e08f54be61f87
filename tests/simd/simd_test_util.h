// Shared helpers of the SIMD tests: the random input set, ULP distances, per-ISA skipping.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/simd/batch.h"
#include "core/simd/kernels.h"

namespace glintlab::simd::test {

// Number of distinct domains (kernels.h Domain) and the shared random rows, one column per
// domain: 10^6 rows, generated once per process (core/simd/inputs.h).
inline constexpr int kDomainCount = static_cast<int>(Domain::kKappa) + 1;
inline constexpr std::size_t kRows = 1000000;
const std::vector<std::vector<double>>& shared_inputs_double();
const std::vector<std::vector<float>>& shared_inputs_float();

// |a − b| in units in the last place of S: the distance of their ordered bit patterns (±0 equal,
// NaN = NaN, a NaN against a number is infinitely far).
template <class S>
double ulp_distance(S a, S b) {
  if (std::isnan(a) || std::isnan(b)) {
    return std::isnan(a) && std::isnan(b) ? 0.0 : std::numeric_limits<double>::infinity();
  }
  using U = std::conditional_t<sizeof(S) == 4, std::uint32_t, std::uint64_t>;
  // Ordered keys: 2^63 ± magnitude bits, so −0 and +0 coincide and neighbours differ by 1.
  const auto key = [](S x) -> std::uint64_t {
    const U u = std::bit_cast<U>(x);
    const U sign = U(1) << (8 * sizeof(S) - 1);
    const std::uint64_t mag = u & ~sign;
    constexpr std::uint64_t kMid = std::uint64_t(1) << 63;
    return (u & sign) ? kMid - mag : kMid + mag;
  };
  const std::uint64_t ka = key(a), kb = key(b);
  return static_cast<double>(ka > kb ? ka - kb : kb - ka);
}

}  // namespace glintlab::simd::test

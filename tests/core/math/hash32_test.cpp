// core/math/hash32.h: the 32-bit lane hash is uniform and avalanches, measured with tests that a
// weak hash fails (the negative controls: the identity; hash32 with 3 % of its outputs collapsed
// in the tested bits; a single multiply after one xor-shift, whose low output bits never see the
// high input bits). Its lanes on every ISA equal the scalar
// bits: tests/simd/avx512_ops_test.cpp (op "hash32 uniform").
#include "core/math/hash32.h"
#include "core/math/hash32_stream.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "core/math/rng.h"
#include "verify/stats/chi_square.h"
#include "verify/stats/mean_tests.h"

namespace glintlab {
namespace {

using Hash = std::function<std::uint32_t(std::uint32_t)>;

// Each test's level: the suite's family-wise rate 1e-3 (a correct hash fails one run in 1000).
constexpr double kLevel = 1e-3;

std::uint32_t identity(std::uint32_t x) { return x; }
std::uint32_t one_round(std::uint32_t x) {
  x ^= x >> 16;
  return x * 0x7feb352du;
}

// Pearson's chi-square of a 12-bit field of hash(i), i = 0 .. 2^20 − 1 (sequential counters,
// what a renderer feeds it), against the uniform: the top bits and the bottom bits.
double uniformity_p(const Hash& hash, int shift) {
  constexpr int kBits = 12;
  constexpr std::uint32_t kCount = 1u << 20;
  std::vector<std::int64_t> observed(1u << kBits, 0);
  for (std::uint32_t i = 0; i < kCount; ++i) ++observed[(hash(i) >> shift) & ((1u << kBits) - 1)];
  const std::vector<double> expected(observed.size(), double(kCount) / double(observed.size()));
  return verify::pearson_chi_square(observed, expected).p_value;
}

// The largest |P(output bit j flips | input bit i flips) − 1/2| over the 32 × 32 pairs, from n
// random inputs, and the bound a hash with no bias stays under with probability 1 − kLevel: the
// normal quantile of kLevel split over 1024 two-sided tests, times the binomial standard error.
struct Avalanche {
  double worst_bias = 0, bound = 0;
};
Avalanche avalanche(const Hash& hash) {
  constexpr int kInputs = 1 << 15;
  std::vector<int> flips(32 * 32, 0);
  for (int k = 0; k < kInputs; ++k) {
    const auto x = static_cast<std::uint32_t>(counter_bits(0x5eed, std::uint64_t(k), 0));
    const std::uint32_t h = hash(x);
    for (int i = 0; i < 32; ++i) {
      const std::uint32_t d = h ^ hash(x ^ (1u << i));
      for (int j = 0; j < 32; ++j) flips[i * 32 + j] += (d >> j) & 1u;
    }
  }
  Avalanche a;
  for (int f : flips) a.worst_bias = std::max(a.worst_bias, std::abs(double(f) / kInputs - 0.5));
  a.bound = verify::normal_quantile(1 - kLevel / (2 * 1024)) * 0.5 / std::sqrt(double(kInputs));
  return a;
}

TEST(Hash32, SequentialCountersAreUniformInTopAndBottomBits) {
  const Hash h = [](std::uint32_t x) { return hash32(x); };
  EXPECT_GT(uniformity_p(h, 20), kLevel);
  EXPECT_GT(uniformity_p(h, 0), kLevel);
  // The keyed form a kernel uses, over its index and over its dimension.
  const Hash by_index = [](std::uint32_t i) { return hash32_counter(7u, i, 3u); };
  const Hash by_dim = [](std::uint32_t d) { return hash32_counter(7u, 3u, d); };
  EXPECT_GT(uniformity_p(by_index, 20), kLevel);
  EXPECT_GT(uniformity_p(by_dim, 0), kLevel);
}

TEST(Hash32, WeakHashesFailUniformity) {
  EXPECT_LT(uniformity_p(identity, 20), kLevel);  // the counters' top bits are all 0
  // Near the truth: hash32 with one output in 32 (about 3 %) sent to 0 in the tested field.
  const Hash top_collapsed = [](std::uint32_t x) {
    const std::uint32_t h = hash32(x);
    return (h & 31u) == 0 ? h & 0x000fffffu : h;
  };
  const Hash bottom_collapsed = [](std::uint32_t x) {
    const std::uint32_t h = hash32(x);
    return (h >> 27) == 0 ? h & 0xfffff000u : h;
  };
  EXPECT_LT(uniformity_p(top_collapsed, 20), kLevel);
  EXPECT_LT(uniformity_p(bottom_collapsed, 0), kLevel);
}

TEST(Hash32, EveryOutputBitFlipsWithHalfProbability) {
  const Avalanche a = avalanche([](std::uint32_t x) { return hash32(x); });
  EXPECT_LT(a.worst_bias, a.bound) << "worst |P(flip) − 1/2| " << a.worst_bias;
}

TEST(Hash32, WeakHashesFailAvalanche) {
  const Avalanche id = avalanche(identity);
  EXPECT_GT(id.worst_bias, id.bound);
  // One round: flipping input bit 31 never reaches output bits 0–14.
  const Avalanche one = avalanche(one_round);
  EXPECT_GT(one.worst_bias, one.bound);
}

TEST(Hash32, IsABijectionOnASampleAndKeysSeparateStreams) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t i = 0; i < (1u << 16); ++i) out.push_back(hash32(i * 65537u + 12345u));
  std::sort(out.begin(), out.end());
  EXPECT_EQ(std::adjacent_find(out.begin(), out.end()), out.end());
  EXPECT_EQ(hash32(0u), 0u);  // the fixed point hash32_counter keys around
  EXPECT_NE(hash32_counter(0u, 0u, 0u), 0u);
  EXPECT_NE(hash32_counter(1u, 5u, 0u), hash32_counter(2u, 5u, 0u));
  EXPECT_NE(hash32_counter(1u, 5u, 0u), hash32_counter(1u, 5u, 1u));
}

TEST(Hash32, UniformsAndIndicesFollowTheirRules) {
  EXPECT_EQ(hash32_uniform<float>(0u), 0.0f);
  EXPECT_LT(hash32_uniform<float>(0xffffffffu), 1.0f);
  EXPECT_EQ(hash32_uniform<float>(0xffffffffu), 1.0f - 0x1p-24f);
  EXPECT_LT(hash32_uniform<double>(0xffffffffu), 1.0);
  EXPECT_EQ(hash32_uniform<double>(0x80000000u), 0.5);
  EXPECT_EQ(hash32_index(3.7f), 3u);
  EXPECT_EQ(hash32_index(-1.0), 0xffffffffu);
  EXPECT_EQ(hash32_index(-2147483520.0f), 0x80000080u);
  EXPECT_EQ(hash32_index(2147483648.0), 0u);  // out of range
  EXPECT_EQ(hash32_index(std::numeric_limits<float>::quiet_NaN()), 0u);
  EXPECT_EQ(hash32_index(-std::numeric_limits<double>::infinity()), 0u);
}

// core/math/hash32_stream.h spells out hash32_counter's steps so a kernel can keep the key: the
// same bits for every (seed, index, dim), counters at 0 and at the 32-bit edge included; a stream
// whose key misses its seed offset differs.
TEST(Hash32Stream, KeyThenDrawIsTheCounterHash) {
  const std::vector<std::uint32_t> edge = {0u, 1u, 2u, 0x7fffffffu, 0x80000000u, 0xfffffffeu,
                                           0xffffffffu, 0x9e3779b9u, 0x61c88647u};
  std::vector<std::uint32_t> values = edge;
  for (std::uint32_t i = 0; i < 40; ++i) values.push_back(hash32_counter(17u, i, 3u));
  std::size_t checked = 0, broken_equal = 0;
  for (std::uint32_t seed : values)
    for (std::uint32_t index : edge)
      for (std::uint32_t dim : {0u, 1u, 5u, 0xffffffffu}) {
        const std::uint32_t key = hash32_key(seed, index);
        EXPECT_EQ(hash32_draw(key, dim), hash32_counter(seed, index, dim));
        EXPECT_EQ(hash32_nest(key, dim), hash32(key ^ dim));
        const std::uint32_t no_offset = hash32(hash32(seed) ^ index);
        broken_equal += hash32_draw(no_offset, dim) == hash32_counter(seed, index, dim) ? 1 : 0;
        ++checked;
      }
  EXPECT_EQ(checked, std::size_t(49 * 9 * 4));
  EXPECT_EQ(broken_equal, 0u);
}

}  // namespace
}  // namespace glintlab

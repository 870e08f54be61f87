// Eto & Tokuyoshi's estimator claims draw their samples through the smooth_ggx model's SIMD batch
// (verify/claims/eto/common.h draw_batch): on the scalar ISA that is the scalar sampler's weight
// and rejection bit for bit, on the widest ISA within the batches' budget; the chunked sums do not
// depend on the thread count; the variance claims' measurement is kept per process.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "core/simd/batch.h"
#include "verify/claims/eto/common.h"
#include "verify/claims/eto/gain.h"

namespace glintlab::verify::eto_claims {
namespace {

constexpr std::size_t kCount = 3000;  // not a multiple of any batch width: a padded tail
const Config kConfigs[] = {{0.05, 0.05, 0}, {1, 0.1, 89}, {0.5, 0.5, 120}, {1.5, 1.5, 45}};

struct Drawn {
  std::vector<double> weight, rejected;
};

Drawn batched(Technique t, const Config& c, std::uint64_t seed) {
  Drawn d{std::vector<double>(kCount), std::vector<double>(kCount)};
  draw_batch(t, c, seed, 1000, kCount, d.weight.data(), d.rejected.data());
  return d;
}

// Runs f with GLINTLAB_ISA set to `isa` (draw_batch uses simd::default_isa()).
template <class F>
void with_isa(const char* isa, F&& f) {
  const char* old = std::getenv("GLINTLAB_ISA");
  const std::string saved = old ? old : "";
  setenv("GLINTLAB_ISA", isa, 1);
  f();
  if (old)
    setenv("GLINTLAB_ISA", saved.c_str(), 1);
  else
    unsetenv("GLINTLAB_ISA");
}

TEST(EtoBatches, ScalarIsaIsTheScalarSamplerBitForBit) {
  with_isa("scalar", [] {
    for (Technique t : {Technique::kSphericalCaps, Technique::kBounded})
      for (const Config& c : kConfigs) {
        const Drawn d = batched(t, c, 7);
        for (std::size_t j = 0; j < kCount; ++j) {
          ASSERT_EQ(d.weight[j], weight(t, c, 7, 1000 + j)) << to_string(t) << " row " << j;
          ASSERT_EQ(d.rejected[j], draw(t, c, 7, 1000 + j).rejected ? 1.0 : 0.0);
        }
      }
  });
}

// The widest ISA: weights within 2^10 ε of max(|scalar|, 1) for all but a few rows (a last-bit
// difference can move a sample across the cap's edge), the same rejections; a weight 2^-30 of its
// scale high is caught.
TEST(EtoBatches, WidestIsaIsTheScalarSamplerWithinTheBatchBudget) {
  const double budget = 1024 * std::numeric_limits<double>::epsilon();
  for (Technique t : {Technique::kSphericalCaps, Technique::kBounded})
    for (const Config& c : kConfigs) {
      const Drawn d = batched(t, c, 11);
      std::size_t outside = 0, outside_high = 0, flips = 0;
      for (std::size_t j = 0; j < kCount; ++j) {
        const double s = weight(t, c, 11, 1000 + j);
        const double scale = std::max(std::abs(s), 1.0);
        outside += std::abs(d.weight[j] - s) > budget * scale;
        outside_high += std::abs(d.weight[j] + std::ldexp(scale, -30) - s) > budget * scale;
        flips += d.rejected[j] != (draw(t, c, 11, 1000 + j).rejected ? 1.0 : 0.0);
      }
      EXPECT_LE(outside, kCount / 100) << to_string(t) << " α " << c.ax << " θ " << c.theta_deg;
      EXPECT_LE(flips, kCount / 100);
      EXPECT_GT(outside_high, kCount / 2) << "the control";
    }
}

TEST(EtoBatches, ChunkedSumsDoNotDependOnTheThreadCount) {
  const Config c{0.3, 0.1, 60};
  MeanAccumulator one, two;
  std::uint64_t rejected_one = 0, rejected_two = 0;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = accumulate_weights(Technique::kBounded, c, 5, 5 * kBatchChunk, 2);
    rejected_one = count_rejected(Technique::kSphericalCaps, c, 5, 5 * kBatchChunk);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = accumulate_weights(Technique::kBounded, c, 5, 5 * kBatchChunk, 2);
    rejected_two = count_rejected(Technique::kSphericalCaps, c, 5, 5 * kBatchChunk);
  }
  EXPECT_EQ(one.n, two.n);
  EXPECT_EQ(one.mean, two.mean);
  EXPECT_EQ(one.m2, two.m2);
  EXPECT_EQ(rejected_one, rejected_two);
  EXPECT_GT(rejected_one, 0u);
}

// accumulate_weights sums several chunks side by side: each chunk's accumulator is still the
// chunk's values added in order, merged in chunk order, bit for bit. 2·kChunksPerTask + 1 chunks
// and a short last one: a full group, a group cut short and a chunk cut short.
TEST(EtoBatches, ChunksSummedSideBySideAreTheChunksSummedOneByOne) {
  const Config c{0.7, 0.35, 30};
  const std::uint64_t n = (2 * kChunksPerTask + 1) * kBatchChunk - 100;
  for (int power : {1, 2}) {
    MeanAccumulator one_by_one;
    for (std::uint64_t first = 0; first < n; first += kBatchChunk) {
      const std::size_t count = std::size_t(std::min(n - first, kBatchChunk));
      std::vector<double> w(count), rejected(count);
      draw_batch(Technique::kBounded, c, 9, first, count, w.data(), rejected.data());
      MeanAccumulator chunk;
      for (double x : w) chunk.add(power == 2 ? x * x : x);
      one_by_one.merge(chunk);
    }
    const MeanAccumulator side_by_side = accumulate_weights(Technique::kBounded, c, 9, n, power);
    EXPECT_EQ(side_by_side.n, one_by_one.n);
    EXPECT_EQ(side_by_side.mean, one_by_one.mean) << "power " << power;
    EXPECT_EQ(side_by_side.m2, one_by_one.m2) << "power " << power;
  }
}

// observe_gain keeps its measurements per process (eto.variance-rough and eto.variance-smooth read
// one): a second call gives the first's numbers, and a grid of another sample count is measured
// anew, not read back.
TEST(EtoGain, KeptMeasurementsAreKeyedByConfigurationAndSampleCount) {
  const GainSizes small{{{0.8, 0.8, 0}, {0.2, 0.2, 45}}, 1u << 12};
  const GainSizes larger{small.grid, 1u << 13};
  const GainMeasured first = observe_gain(small, 1), again = observe_gain(small, 1);
  EXPECT_EQ(first.ratio, again.ratio);
  EXPECT_EQ(first.log_se, again.log_se);
  EXPECT_EQ(first.ratio_off, again.ratio_off);
  EXPECT_NE(observe_gain(larger, 1).log_se, first.log_se);
  EXPECT_NE(observe_gain(small, 0).ratio, first.ratio);
}

}  // namespace
}  // namespace glintlab::verify::eto_claims

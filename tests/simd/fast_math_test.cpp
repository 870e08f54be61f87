// Fast-math errors over dense inputs, against the documented bounds of core/simd/fast_math.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/simd/wide.h"

namespace glintlab {
namespace {

struct Errors {
  double abs = 0, rel = 0;
};

// 4·10^6 evenly spaced floats in [lo, hi]; relative error where |reference| > rel_floor.
template <class F, class R>
Errors sweep(const char* name, double lo, double hi, F f, R ref, double rel_floor = 0.0) {
  constexpr int kN = 4000000;
  Errors e;
  for (int i = 0; i <= kN; ++i) {
    const float x = static_cast<float>(lo + (hi - lo) * i / kN);
    const double r = ref(double(x));
    const double a = std::fabs(double(f(x)) - r);
    e.abs = std::max(e.abs, a);
    if (std::fabs(r) > rel_floor) e.rel = std::max(e.rel, a / std::fabs(r));
  }
  std::printf("fast %-6s [%g, %g]: max abs %.3g, max rel %.3g\n", name, lo, hi, e.abs, e.rel);
  return e;
}

TEST(SimdFastMath, ExpWithinDocumentedBound) {
  const Errors e = sweep(
      "exp", -87, 88, [](float x) { return fast::exp(x); }, [](double x) { return std::exp(x); });
  EXPECT_LE(e.rel, fast::kFastExpMaxRel);
  EXPECT_EQ(fast::exp(-100.0f), 0.0f);  // flushed below 2^-126, as documented
}

TEST(SimdFastMath, ErfWithinDocumentedBound) {
  const Errors e = sweep(
      "erf", -6, 6, [](float x) { return fast::erf(x); }, [](double x) { return std::erf(x); },
      1e-30);
  EXPECT_LE(e.abs, fast::kFastErfMaxAbs);
  EXPECT_LE(e.rel, fast::kFastErfMaxRel);
}

TEST(SimdFastMath, ErfcWithinDocumentedBound) {
  const auto f = [](float x) { return fast::erfc(x); };
  const auto r = [](double x) { return std::erfc(x); };
  const Errors all = sweep("erfc", -6, 9.2, f, r, 1e-30);
  const Errors to4 = sweep("erfc", -6, 4, f, r, 1e-30);
  EXPECT_LE(all.abs, fast::kFastErfcMaxAbs);
  EXPECT_LE(to4.rel, fast::kFastErfcMaxRelTo4);
  EXPECT_LE(all.rel, fast::kFastErfcMaxRelTo9);
}

TEST(SimdFastMath, RsqrtWithinDocumentedBound) {
  const Errors e = sweep(
      "rsqrt", 1e-3, 1e3, [](float x) { return fast::rsqrt(x); },
      [](double x) { return 1.0 / std::sqrt(x); });
  EXPECT_LE(e.rel, fast::kFastRsqrtMaxRel);
}

// The batch form (xsimd's default SSE2 arch in this TU) computes the same lanes as the scalar one.
TEST(SimdFastMath, BatchEqualsScalar) {
  using B = xsimd::batch<float>;
  alignas(64) float in[B::size], out[B::size];
  for (int i = 0; i < 100000; ++i) {
    for (std::size_t l = 0; l < B::size; ++l) in[l] = -9.0f + 1.8e-4f * float(i) + 0.01f * float(l);
    const B x = B::load_aligned(in);
    fast::erfc(x).store_aligned(out);
    for (std::size_t l = 0; l < B::size; ++l) ASSERT_EQ(out[l], fast::erfc(in[l])) << in[l];
    fast::exp(x).store_aligned(out);
    for (std::size_t l = 0; l < B::size; ++l) ASSERT_EQ(out[l], fast::exp(in[l])) << in[l];
    const B y = xsimd::abs(x) + B(1e-3f);
    fast::rsqrt(y).store_aligned(out);
    for (std::size_t l = 0; l < B::size; ++l) {
      ASSERT_EQ(out[l], fast::rsqrt(std::fabs(in[l]) + 1e-3f)) << in[l];
    }
  }
}

}  // namespace
}  // namespace glintlab

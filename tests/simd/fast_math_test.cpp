// Fast-math errors over dense inputs, against the documented bounds of core/simd/fast_math.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/math/rng.h"
#include "core/ndf/ggx.h"
#include "core/simd/batch.h"
#include "core/simd/inputs.h"
#include "core/simd/kernels.h"
#include "core/simd/wide.h"
#include "tests/simd/simd_test_util.h"

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

// GGX D with one division, over the kernel inputs (α in [1e-3, 2], anisotropy to 1:1000, m from
// the NDF, the hemisphere and the sphere) against GGX<double>::D at the same float inputs.
struct GgxDErrors {
  double rel = 0, ulp = 0;
  int zero_mismatches = 0;  // D = 0 (mz ≤ 0) in one and not the other
};
template <class F>
GgxDErrors ggx_d_errors(F f) {
  const int ids[] = {static_cast<int>(simd::Domain::kAlphaX),
                     static_cast<int>(simd::Domain::kAlphaY), static_cast<int>(simd::Domain::kMX),
                     static_cast<int>(simd::Domain::kMY), static_cast<int>(simd::Domain::kMZ)};
  static const auto c = simd::make_inputs(ids, 1000000, hash_string("simd.fast_math.ggx_d"));
  GgxDErrors e;
  for (std::size_t i = 0; i < c[0].size(); ++i) {
    const float ax = float(c[0][i]), ay = float(c[1][i]), mx = float(c[2][i]), my = float(c[3][i]),
                mz = float(c[4][i]);
    const double r = GGX<double>{ax, ay}.D(Vec3<double>{mx, my, mz});
    const float got = f(ax, ay, mx, my, mz);
    if ((r == 0.0) != (got == 0.0f)) ++e.zero_mismatches;
    if (r == 0.0) continue;
    e.rel = std::max(e.rel, std::fabs(double(got) - r) / r);
    e.ulp = std::max(e.ulp, simd::test::ulp_distance(got, float(r)));
  }
  std::printf("fast ggx_d: max rel %.3g, max %.0f ulp\n", e.rel, e.ulp);
  return e;
}

TEST(SimdFastMath, GgxDWithinDocumentedBound) {
  const GgxDErrors e = ggx_d_errors([](float ax, float ay, float mx, float my, float mz) {
    return fast::ggx_d(ax, ay, mx, my, mz);
  });
  EXPECT_LE(e.rel, fast::kFastGgxDMaxRel);
  EXPECT_LE(e.ulp, fast::kFastGgxDMaxUlp);
  EXPECT_EQ(e.zero_mismatches, 0);
  // The check can fail: the same form 2^-19 (16 to 32 ulp) off exceeds the bound.
  const GgxDErrors off = ggx_d_errors([](float ax, float ay, float mx, float my, float mz) {
    return fast::ggx_d(ax, ay, mx, my, mz) * (1.0f + 0x1p-19f);
  });
  EXPECT_GT(off.ulp, fast::kFastGgxDMaxUlp);
  EXPECT_GT(off.rel, fast::kFastGgxDMaxRel);
}

// The fast flavour of the ggx.d kernel is fast::ggx_d (every ISA, bit for bit, as the ISA TUs
// round × and + alike), and the exact flavour is GGX<float>::D: they differ in the last bits.
TEST(SimdFastMath, GgxDKernelTakesTheFastFormOnlyInFastMath) {
  const int k = *simd::find_kernel("ggx.d");
  constexpr std::size_t kN = 4099;
  const auto d = simd::make_inputs(simd::kernel_info(k).inputs, kN, 77);
  std::vector<std::vector<float>> in;
  for (const auto& col : d) in.emplace_back(col.begin(), col.end());
  std::vector<simd::Column<float>> cols;
  for (const auto& col : in) cols.push_back({col.data(), 1});
  for (simd::Isa isa : simd::kAllIsas) {
    if (!simd::isa_supported(isa)) continue;
    std::vector<float> fast_out(kN), exact_out(kN);
    float* fo[1] = {fast_out.data()};
    float* eo[1] = {exact_out.data()};
    simd::eval_batch(k, std::span<const simd::Column<float>>(cols), std::span<float* const>(fo), kN,
                     isa, simd::Math::kFast);
    simd::eval_batch(k, std::span<const simd::Column<float>>(cols), std::span<float* const>(eo), kN,
                     isa, simd::Math::kExact);
    int differ = 0;
    for (std::size_t i = 0; i < kN; ++i) {
      const float want = fast::ggx_d(in[0][i], in[1][i], in[2][i], in[3][i], in[4][i]);
      ASSERT_EQ(std::memcmp(&fast_out[i], &want, 4), 0) << simd::isa_name(isa) << " row " << i;
      const float exact =
          GGX<float>{in[0][i], in[1][i]}.D(Vec3<float>{in[2][i], in[3][i], in[4][i]});
      ASSERT_EQ(std::memcmp(&exact_out[i], &exact, 4), 0) << simd::isa_name(isa) << " row " << i;
      differ += fast_out[i] != exact_out[i];
    }
    EXPECT_GT(differ, 100) << simd::isa_name(isa);
  }
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

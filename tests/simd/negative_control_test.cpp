// Negative controls of the equivalence check: perturbed batch kernels must fail their budgets.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/simd/kernels.h"
#include "core/simd/wide.h"
#include "tests/simd/equivalence.h"
#include "tests/simd/simd_test_util.h"

namespace glintlab::simd::test {
namespace {

// A math policy whose exp is off by a factor 1 + 2^-12 (~2000 float ulp): an ops-layer bug of
// the kind a wrong batch overload would be.
struct PerturbedExpMath {
  template <class B>
  static B exp(const B& x) {
    return B(std::exp(x)) * B(1.0f + 0x1p-12f);
  }
};

// A GGX D whose batch result is 4 ulp high: the smallest error the bit-identical budget must see.
struct PerturbedGgxD : GgxD {
  template <class T>
  static void eval(const T* x, T* y) {
    GgxD::eval(x, y);
    y[0] = y[0] * T(1.0f + 4.0f * 0x1p-23f);
  }
};

template <class K, class W>
std::vector<std::vector<float>> run_local(int kernel, std::size_t n) {
  const auto& in = shared_inputs_float();
  const KernelInfo info = kernel_info(kernel);
  std::vector<std::vector<float>> out(K::kOut.size(), std::vector<float>(n));
  for (std::size_t i = 0; i < n; ++i) {
    W x[K::kIn.size()];
    W y[K::kOut.size()];
    for (std::size_t j = 0; j < K::kIn.size(); ++j) x[j] = W(in[info.inputs[j]][i]);
    K::template eval<W>(x, y);
    for (std::size_t o = 0; o < K::kOut.size(); ++o) {
      if constexpr (std::is_floating_point_v<W>) {
        out[o][i] = y[o];
      } else {
        out[o][i] = y[o].v;
      }
    }
  }
  return out;
}

TEST(SimdNegativeControl, PerturbedExpFailsBeckmannDBudget) {
  const int k = *find_kernel("beckmann.d");
  const std::size_t n = 200000;
  const auto ref = evaluate<float>(k, Isa::kScalar, Math::kExact, n);
  // Unperturbed, through the same local path (Wide<float>): passes.
  const Comparison good =
      compare_outputs<float>(k, ref, run_local<BeckmannD, Wide<float, ExactMath>>(k, n), "local");
  EXPECT_TRUE(good.pass) << good.summary;
  const Comparison bad = compare_outputs<float>(
      k, ref, run_local<BeckmannD, Wide<float, PerturbedExpMath>>(k, n), "perturbed-exp");
  EXPECT_FALSE(bad.pass) << bad.summary;
}

TEST(SimdNegativeControl, FourUlpOffGgxDFailsBitIdenticalBudget) {
  const int k = *find_kernel("ggx.d");
  const std::size_t n = 200000;
  const auto ref = evaluate<float>(k, Isa::kScalar, Math::kExact, n);
  const Comparison bad =
      compare_outputs<float>(k, ref, run_local<PerturbedGgxD, float>(k, n), "perturbed-4ulp");
  EXPECT_FALSE(bad.pass) << bad.summary;
}

// Fast math is a different function: where a kernel uses erfc (A&S 7.1.26, ~1e-3 relative in
// the tail) the exact budget must reject it, or the check could not tell the policies apart.
// (Beckmann D with fast exp, 3 ulp, and G1 above the horizon do stay within their budgets.)
TEST(SimdNegativeControl, FastErfcFailsExactBudget) {
  const int k = *find_kernel("beckmann.total_area_eq30");
  const std::size_t n = 200000;
  const auto ref = evaluate<float>(k, Isa::kScalar, Math::kExact, n);
  const Comparison bad =
      compare_outputs<float>(k, ref, evaluate<float>(k, best_isa(), Math::kFast, n), "fast");
  EXPECT_FALSE(bad.pass) << bad.summary;
}

}  // namespace
}  // namespace glintlab::simd::test

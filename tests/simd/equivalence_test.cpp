// Each batched kernel, on every ISA this CPU has, against its scalar instantiation (10^6 rows).
#include "tests/simd/equivalence.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "core/simd/batch.h"

namespace glintlab::simd::test {
namespace {

constexpr Isa kBatchIsas[] = {Isa::kSse42, Isa::kAvx2, Isa::kAvx512};

// Kernel outer, ISA inner: the scalar reference of one kernel is computed once and dropped.
template <class S>
void check_all_kernels() {
  int ran = 0;
  for (int k = 0; k < kernel_count(); ++k) {
    const std::size_t n = rows_for(kernel_info(k).name);
    const auto ref = evaluate<S>(k, Isa::kScalar, Math::kExact, n);
    for (Isa isa : kBatchIsas) {
      if (!isa_supported(isa)) continue;
      const Comparison c = compare_outputs<S>(k, ref, evaluate<S>(k, isa, Math::kExact, n),
                                              std::string(isa_name(isa)));
      std::printf("%s\n", c.summary.c_str());
      EXPECT_TRUE(c.pass) << c.summary;
      ++ran;
    }
  }
  EXPECT_GT(ran, 0) << "no SIMD ISA available: nothing compared";
}

TEST(SimdEquivalence, FloatEveryKernelEveryIsa) { check_all_kernels<float>(); }
TEST(SimdEquivalence, DoubleEveryKernelEveryIsa) { check_all_kernels<double>(); }

// The ISAs this CPU lacks are compiled and linked but never dispatched: say so, per ISA.
class SimdIsa : public ::testing::TestWithParam<Isa> {};
TEST_P(SimdIsa, ComparedWhenSupported) {
  const Isa isa = GetParam();
  if (!isa_supported(isa)) {
    GTEST_SKIP() << isa_name(isa) << ": this CPU lacks it; its translation unit is compiled and "
                 << "linked, dispatch never selects it, so its equivalence is not tested here";
  }
  EXPECT_NE(best_isa(), Isa::kScalar);
}
INSTANTIATE_TEST_SUITE_P(Isas, SimdIsa, ::testing::ValuesIn(kBatchIsas),
                         [](const ::testing::TestParamInfo<Isa>& p) {
                           std::string n(isa_name(p.param));
                           std::erase(n, '.');
                           return n;
                         });

}  // namespace
}  // namespace glintlab::simd::test

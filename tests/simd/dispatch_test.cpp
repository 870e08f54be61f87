// Runtime ISA choice: CPU features, the GLINTLAB_ISA override, and errors for bad requests.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/simd/batch.h"

namespace glintlab::simd {
namespace {

struct EnvGuard {
  explicit EnvGuard(const char* value) {
    if (value) {
      setenv("GLINTLAB_ISA", value, 1);
    } else {
      unsetenv("GLINTLAB_ISA");
    }
  }
  ~EnvGuard() { unsetenv("GLINTLAB_ISA"); }
};

TEST(SimdDispatch, BestIsaIsSupportedAndDefault) {
  const EnvGuard env(nullptr);
  EXPECT_TRUE(isa_supported(best_isa()));
  EXPECT_TRUE(isa_supported(Isa::kScalar));
  EXPECT_EQ(default_isa(), best_isa());
  if (!isa_supported(Isa::kAvx512)) {
    EXPECT_NE(best_isa(), Isa::kAvx512);
  }
}

TEST(SimdDispatch, EnvironmentForcesAnIsa) {
  for (Isa isa : kAllIsas) {
    if (!isa_supported(isa)) continue;
    const EnvGuard env(std::string(isa_name(isa)).c_str());
    EXPECT_EQ(default_isa(), isa);
  }
}

TEST(SimdDispatch, EnvironmentRejectsUnknownAndUnsupported) {
  {
    const EnvGuard env("avx9000");
    try {
      (void)default_isa();
      FAIL() << "no error for an unknown ISA";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("GLINTLAB_ISA"), std::string::npos);
      EXPECT_NE(std::string(e.what()).find("valid: scalar, sse4.2, avx2, avx512"),
                std::string::npos);
    }
  }
  for (Isa isa : kAllIsas) {
    if (isa_supported(isa)) continue;
    const EnvGuard env(std::string(isa_name(isa)).c_str());
    EXPECT_THROW((void)default_isa(), std::invalid_argument) << isa_name(isa);
  }
}

TEST(SimdDispatch, EvalBatchChecksItsArguments) {
  const int k = *find_kernel("ggx.d");
  const float v[5] = {0.1f, 0.1f, 0.0f, 0.0f, 1.0f};
  std::vector<Column<float>> in;
  for (float& x : const_cast<float(&)[5]>(v)) in.push_back({&x, 0});
  float out = 0;
  float* outs[1] = {&out};
  eval_batch(k, std::span<const Column<float>>(in), std::span<float* const>(outs), 1, Isa::kScalar);
  EXPECT_FLOAT_EQ(out, 1.0f / (3.14159265f * 0.01f));
  in[0].stride = 2;
  EXPECT_THROW(eval_batch(k, std::span<const Column<float>>(in), std::span<float* const>(outs), 1,
                          Isa::kScalar),
               std::invalid_argument);
  in[0].stride = 0;
  in.pop_back();
  EXPECT_THROW(eval_batch(k, std::span<const Column<float>>(in), std::span<float* const>(outs), 1,
                          Isa::kScalar),
               std::invalid_argument);
  std::vector<Column<double>> ind(5, Column<double>{nullptr, 0});
  double outd = 0;
  double* outsd[1] = {&outd};
  EXPECT_THROW(eval_batch(k, std::span<const Column<double>>(ind), std::span<double* const>(outsd),
                          1, Isa::kScalar, Math::kFast),
               std::invalid_argument);
  if (!isa_supported(Isa::kAvx512)) {
    in.push_back({&v[4], 0});
    EXPECT_THROW(eval_batch(k, std::span<const Column<float>>(in), std::span<float* const>(outs), 1,
                            Isa::kAvx512),
                 std::invalid_argument);
  }
}

// A row's value does not depend on n or on its position (the tail is padded, never scalar).
TEST(SimdDispatch, RowValueIndependentOfBatchLength) {
  const int k = *find_kernel("beckmann.lambda");
  constexpr std::size_t kN = 37;
  std::vector<float> ax(kN, 0.3f), ay(kN, 0.05f), x(kN), y(kN), z(kN);
  for (std::size_t i = 0; i < kN; ++i) {
    x[i] = 0.9f * float(i) / float(kN);
    y[i] = 0.1f;
    z[i] = std::sqrt(1.0f - x[i] * x[i] - 0.01f);
  }
  const auto run = [&](std::size_t offset, std::size_t n) {
    std::vector<float> out(n);
    std::vector<Column<float>> in = {{ax.data() + offset, 1},
                                     {ay.data() + offset, 1},
                                     {x.data() + offset, 1},
                                     {y.data() + offset, 1},
                                     {z.data() + offset, 1}};
    float* o[1] = {out.data()};
    eval_batch(k, std::span<const Column<float>>(in), std::span<float* const>(o), n, best_isa());
    return out;
  };
  const std::vector<float> all = run(0, kN);
  for (std::size_t off = 0; off < 10; ++off) {
    const std::vector<float> part = run(off, kN - off - 3);
    for (std::size_t i = 0; i < part.size(); ++i)
      ASSERT_EQ(part[i], all[off + i]) << off << " " << i;
  }
}

}  // namespace
}  // namespace glintlab::simd

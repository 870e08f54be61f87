// Runtime ISA choice: CPU features, the GLINTLAB_ISA override, and errors for bad requests.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/simd/batch.h"
#include "core/simd/inputs.h"

namespace glintlab::simd {
namespace {

// Sets (or, for nullptr, unsets) one environment variable for a scope, restoring its old value.
struct EnvGuard {
  explicit EnvGuard(const char* value, const char* name = "GLINTLAB_ISA") : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) {
      setenv(name, value, 1);
    } else {
      unsetenv(name);
    }
  }
  ~EnvGuard() {
    if (old_)
      setenv(name_, old_->c_str(), 1);
    else
      unsetenv(name_);
  }
  const char* name_;
  std::optional<std::string> old_;
};

// GLINTLAB_MAX_ISA caps what counts as supported: the machine seen as one without the wider ISAs.
TEST(SimdDispatch, MaxIsaCapsTheSupportedIsas) {
  const EnvGuard unforced(nullptr);
  for (Isa cap : kAllIsas) {
    const EnvGuard max(std::string(isa_name(cap)).c_str(), "GLINTLAB_MAX_ISA");
    EXPECT_EQ(max_isa(), cap);
    EXPECT_LE(best_isa(), cap);
    for (Isa isa : kAllIsas) {
      if (isa > cap) {
        EXPECT_FALSE(isa_supported(isa)) << isa_name(isa) << " above " << isa_name(cap);
      }
    }
    EXPECT_TRUE(isa_supported(Isa::kScalar));
  }
  {
    const EnvGuard max("scalar", "GLINTLAB_MAX_ISA");
    const EnvGuard forced("sse4.2");
    try {
      (void)default_isa();
      FAIL() << "GLINTLAB_ISA above GLINTLAB_MAX_ISA was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("GLINTLAB_MAX_ISA"), std::string::npos) << e.what();
    }
  }
  const EnvGuard bad("avx9000", "GLINTLAB_MAX_ISA");
  try {
    (void)isa_supported(Isa::kAvx2);
    FAIL() << "no error for an unknown GLINTLAB_MAX_ISA";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("GLINTLAB_MAX_ISA: unknown ISA 'avx9000' (valid: scalar, "
                                         "sse4.2, avx2, avx512)"),
              std::string::npos)
        << e.what();
  }
}

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

// The driver's full-batch loop (all columns unrolled, uniform columns by index mask) and its
// padded-tail path compute every row bit for bit alike: 67 rows at once (full batches and a
// tail) against each row alone (n = 1, a padded batch), for every kernel, ISA and flavour, with
// every column of n values and with the first two (α) as uniform stride-0 columns.
template <class S>
void expect_full_batches_equal_single_rows(int k, Isa isa, Math math) {
  constexpr std::size_t kN = 67;
  const KernelInfo info = kernel_info(k);
  const auto d = make_inputs(info.inputs, kN, 4242);
  std::vector<std::vector<S>> in;
  for (const auto& c : d) in.emplace_back(c.begin(), c.end());
  for (const bool uniform : {false, true}) {
    if (uniform) {
      for (std::size_t j = 0; j < 2 && j < in.size(); ++j) in[j].assign(kN, in[j][0]);
    }
    const auto run = [&](std::size_t first, std::size_t n) {
      std::vector<std::vector<S>> out(info.outputs.size(), std::vector<S>(n));
      std::vector<Column<S>> cols;
      std::vector<S*> outs;
      for (std::size_t j = 0; j < in.size(); ++j) {
        cols.push_back({in[j].data() + (uniform && j < 2 ? 0 : first), uniform && j < 2 ? 0u : 1u});
      }
      for (auto& o : out) outs.push_back(o.data());
      eval_batch(k, std::span<const Column<S>>(cols), std::span<S* const>(outs), n, isa, math);
      return out;
    };
    const auto all = run(0, kN);
    for (std::size_t i = 0; i < kN; ++i) {
      const auto one = run(i, 1);
      for (std::size_t o = 0; o < one.size(); ++o) {
        ASSERT_EQ(std::memcmp(&one[o][0], &all[o][i], sizeof(S)), 0)
            << info.name << " " << isa_name(isa) << " " << math_name(math) << " row " << i
            << " output " << o << (uniform ? " (uniform α)" : "") << ": " << one[o][0] << " vs "
            << all[o][i];
      }
    }
  }
}

TEST(SimdDispatch, FullBatchesEqualPaddedSingleRowsEveryKernel) {
  for (int k = 0; k < kernel_count(); ++k) {
    for (Isa isa : kAllIsas) {
      if (!isa_supported(isa)) continue;
      expect_full_batches_equal_single_rows<float>(k, isa, Math::kExact);
      expect_full_batches_equal_single_rows<float>(k, isa, Math::kFast);
      expect_full_batches_equal_single_rows<double>(k, isa, Math::kExact);
    }
  }
}

}  // namespace
}  // namespace glintlab::simd

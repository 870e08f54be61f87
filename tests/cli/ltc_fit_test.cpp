// `glintlab ltc-fit` (cli/ltc_fit.cpp): a tiny table is written with the documented columns and
// matches a second run with another thread count, and one on the baseline (non-FMA3) path;
// bad sizes, threads and sample counts get one line, exit 2 and no output.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>

#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

using LtcFitCliTest = CliTest;

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST_F(LtcFitCliTest, WritesBothTablesIdenticallyForAnyThreadCount) {
  ASSERT_EQ(
      run({"ltc-fit", "--size", "2", "--samples", "8", "--threads", "1", "--out", "a"}).exit_code,
      0);
  ASSERT_EQ(
      run({"ltc-fit", "--size", "2", "--samples", "8", "--threads", "2", "--out", "b"}).exit_code,
      0);
  for (const char* f : {"ggx_brdf.csv", "ggx_ndf.csv"}) {
    const std::string a = slurp(work() / "a" / f);
    EXPECT_NE(a.find("sqrt_alpha,theta_o,m00,m02,m20,m22,"), std::string::npos) << f;
    EXPECT_EQ(a, slurp(work() / "b" / f)) << f;
  }
}

// Sets GLINTLAB_MAX_ISA for a scope (the child processes inherit it), restoring its old value.
struct MaxIsaGuard {
  explicit MaxIsaGuard(const char* value) {
    if (const char* old = std::getenv("GLINTLAB_MAX_ISA")) old_ = old;
    setenv("GLINTLAB_MAX_ISA", value, 1);
  }
  ~MaxIsaGuard() {
    if (old_)
      setenv("GLINTLAB_MAX_ISA", old_->c_str(), 1);
    else
      unsetenv("GLINTLAB_MAX_ISA");
  }
  std::optional<std::string> old_;
};

// The objective and the albedo cubature also run compiled for FMA3 where the CPU has it; the
// baseline build of the same loops (GLINTLAB_MAX_ISA=scalar) writes the same bytes.
TEST_F(LtcFitCliTest, FmaPathWritesTheBaselinePathsBytes) {
  ASSERT_EQ(run({"ltc-fit", "--size", "3", "--samples", "8", "--out", "fast"}).exit_code, 0);
  {
    const MaxIsaGuard scalar("scalar");
    ASSERT_EQ(run({"ltc-fit", "--size", "3", "--samples", "8", "--out", "base"}).exit_code, 0);
  }
  for (const char* f : {"ggx_brdf.csv", "ggx_ndf.csv"})
    EXPECT_EQ(slurp(work() / "fast" / f), slurp(work() / "base" / f)) << f;
}

TEST_F(LtcFitCliTest, BadOptionsAreOneLineErrors) {
  expect_input_error(run({"ltc-fit", "--size", "1", "--out", "x"}), {"--size", "[2, 256]"}, {});
  expect_input_error(run({"ltc-fit", "--size", "257", "--out", "x"}), {"--size"}, {});
  expect_input_error(run({"ltc-fit", "--threads", "-1", "--out", "x"}), {"--threads"}, {});
  expect_input_error(run({"ltc-fit", "--samples", "2", "--out", "x"}), {"--samples"}, {});
}

}  // namespace
}  // namespace glintlab::cli_test

// `glintlab models` shows what the conformance suite takes from a model's declarations: its smooth
// limit (kSmoothLimit) and every property it does not claim (kNotClaimed, whole or for one
// parameter choice, and the suite's own reasons: no smooth limit, no float or SIMD instantiation),
// so a plug-in's author sees that the declarations were read before running verify.
#include <gtest/gtest.h>

#include <string>

#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

class ModelsDeclarationsTest : public CliTest {};

// The lines of one model's block of `glintlab models` (from "NAME: " to the next model's line).
std::string block_of(const std::string& out, const std::string& name) {
  std::string block;
  bool in = false;
  for (const std::string& line : lines_of(out)) {
    if (!line.empty() && line[0] != ' ') in = line.rfind(name + ": ", 0) == 0;
    if (in) block += line + "\n";
  }
  return block;
}

TEST_F(ModelsDeclarationsTest, PluginsSmoothLimitAndNotClaimedAreListed) {
  const RunResult r = run({"--plugin", kTestPluginZirrKaplanyan, "models"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string zk = block_of(r.out, "zirr_kaplanyan");
  ASSERT_FALSE(zk.empty()) << r.out;
  for (const char* line :
       {"  smooth limit (kSmoothLimit, for converges-to-smooth): smooth_ggx\n",
        "  not claimed: energy: the paper's clamped normal approximation",
        "  not claimed for binomial=small_count: float-vs-double: small_count draws"})
    EXPECT_NE(zk.find(line), std::string::npos) << line << "\nnot in:\n" << zk;
  EXPECT_EQ(zk.find("not claimed: converges-to-smooth"), std::string::npos) << zk;
}

TEST_F(ModelsDeclarationsTest, SuitesOwnReasonsAreListedAndSmoothModelsHaveNone) {
  const RunResult r = run({"--plugin", kTestPlugin, "models"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // A footprint model without kSmoothLimit: converges-to-smooth is not claimed, with the reason.
  const std::string ex = block_of(r.out, "example_glints");
  EXPECT_NE(ex.find("  not claimed: converges-to-smooth: the model declares no smooth limit "
                    "(kSmoothLimit)\n"),
            std::string::npos)
      << ex;
  EXPECT_EQ(ex.find("\n  smooth limit ("), std::string::npos) << ex;
  // Double only and unbatched: float-vs-double and simd-equivalence.
  const std::string area = block_of(r.out, "kneiphof_klein_area");
  EXPECT_NE(area.find("  not claimed: float-vs-double: "), std::string::npos) << area;
  EXPECT_NE(area.find("  not claimed: simd-equivalence: "), std::string::npos) << area;
  // A smooth model claims every property that applies to it (the footprint ones do not).
  const std::string smooth = block_of(r.out, "smooth_ggx");
  ASSERT_FALSE(smooth.empty()) << r.out;
  EXPECT_EQ(smooth.find("not claimed"), std::string::npos) << smooth;
  EXPECT_EQ(smooth.find("smooth limit"), std::string::npos) << smooth;
}

}  // namespace
}  // namespace glintlab::cli_test

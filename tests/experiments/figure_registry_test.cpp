// The figure registry: both Eto & Tokuyoshi experiments registered, unknown ids and unwritable
// output folders rejected with one line and no output left behind.
#include "experiments/figures/figure_registry.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace glintlab::experiments {
namespace {

namespace fs = std::filesystem;

TEST(FigureRegistry, ListsBothEtoExperiments) {
  const auto& figs = registered_figures();
  ASSERT_GE(figs.size(), 2u);
  EXPECT_EQ(find_figure("eto2023-fig4").target, "Fig. 4");
  EXPECT_EQ(find_figure("eto2023-fig4-rmse-spp").paper, "Eto & Tokuyoshi 2023");
  try {
    find_figure("fig99");
    FAIL() << "unknown id accepted";
  } catch (const FigureError& e) {
    EXPECT_NE(std::string(e.what()).find("eto2023-fig4"), std::string::npos);
  }
}

TEST(FigureRegistry, FailedRunLeavesNoOutput) {
  const fs::path dir = fs::temp_directory_path() / ("glintlab_fig_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const FigureEntry failing{"failing", "none", "none", "throws halfway",
                            [](const FigureContext& ctx) {
                              std::ofstream(ctx.dir / "half.csv") << "a\n1\n";
                              throw std::runtime_error("boom");
                            }};
  EXPECT_THROW(run_figure(failing, dir, {}), std::runtime_error);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 0);
  // A regular file where the output folder should be.
  std::ofstream(dir / "file") << "x";
  EXPECT_THROW(run_figure(failing, dir / "file", {}), FigureError);
  const FigureEntry ok{"ok", "none", "none", "writes one file", [](const FigureContext& ctx) {
                         std::ofstream(ctx.dir / "r.csv") << "a\n1\n";
                       }};
  const fs::path out = run_figure(ok, dir / "nested", {});
  EXPECT_TRUE(fs::exists(out / "r.csv"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "nested"), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace glintlab::experiments

// The adequacy table's files (experiments/adequacy/adequacy_outputs.h) with both families: one CSV
// with a `family` column, each family's level columns (`nan` in the other family's rows), the
// JSON's families and cells, one map per Kemppinen model × incidence, and z split over the
// decisions of both families.
#include "experiments/adequacy/adequacy_outputs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/io/csv.h"

namespace glintlab::experiments {
namespace {

namespace fs = std::filesystem;

TEST(AdequacyOutputs, BothFamiliesInOneTable) {
  const fs::path out = fs::temp_directory_path() / "glintlab_adequacy_outputs_test";
  fs::remove_all(out);
  AdequacyOptions o;
  o.models = {"deliot_belcour", "kemppinen_ggx"};
  verify::adequacy::KemppinenGridAxes k;
  k.points = {10, 1e5};
  k.alpha = {0.3};
  k.theta_i_deg = {0, 60};
  k.theta_h_count = 2;
  k.samples = 1000;
  o.kemppinen_axes = k;
  const std::size_t binomial_cells =
      verify::adequacy::make_grid({"deliot_belcour"},
                                  verify::adequacy::grid_axes(verify::Budget::kQuick))
          .size();
  EXPECT_EQ(table_decisions(o), binomial_cells * 3 + 8 * 8);
  const AdequacySummary s = run_adequacy(out, o);
  EXPECT_EQ(s.cells, binomial_cells);
  EXPECT_EQ(s.kemppinen.cells, 8u);
  EXPECT_EQ(s.decisions, binomial_cells * 3 + 8 * 8);
  EXPECT_EQ(s.z, verify::adequacy::decision_for_decisions(s.decisions, o.threshold).z);
  std::size_t chosen = 0;
  for (std::size_t c : s.kemppinen.chosen) chosen += c;
  EXPECT_EQ(chosen, 8u);

  const io::CsvTable csv = io::read_csv(out / "adequacy.csv");
  ASSERT_EQ(csv.num_rows(), binomial_cells + 8);
  const auto& header = csv.header();
  EXPECT_EQ(header[0], "family");
  const auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name;
    return std::size_t(it - header.begin());
  };
  const std::size_t family = column("family"), k16 = column("k16_exact_mean"),
                    realtime = column("realtime_mean"), smooth = column("smooth_mean"),
                    chosen_col = column("chosen");
  column("k1_rational_cv_diff_ucb");
  column("k9_exact_ns");
  std::size_t kemppinen_rows = 0;
  for (std::size_t r = 0; r < csv.num_rows(); ++r) {
    const bool is_k = csv.text(r, family) == "kemppinen";
    kemppinen_rows += is_k ? 1 : 0;
    // Each family's level columns filled, the other family's `nan`; smooth shared.
    EXPECT_EQ(csv.text(r, k16) == "nan", !is_k) << r;
    EXPECT_EQ(csv.text(r, realtime) == "nan", is_k) << r;
    EXPECT_NE(csv.text(r, smooth), "nan") << r;
    EXPECT_NE(csv.text(r, chosen_col), "nan") << r;
  }
  EXPECT_EQ(kemppinen_rows, 8u);

  std::ifstream in(out / "adequacy.json");
  const nlohmann::json doc = nlohmann::json::parse(in);
  EXPECT_EQ(doc["bound"]["decisions"], s.decisions);
  EXPECT_EQ(doc["families"]["kemppinen"]["most_complete"], "k16_exact");
  EXPECT_EQ(doc["families"]["kemppinen"]["levels"].size(), 9u);
  EXPECT_EQ(doc["families"]["kemppinen"]["summary"]["cells"], 8);
  // Per row (θ_i × θ_h: 4) the boundaries of smooth, k1, k4 and k9.
  EXPECT_EQ(doc["families"]["kemppinen"]["boundaries"].size(), 4u * 4u);
  EXPECT_EQ(doc["cells"].size(), binomial_cells + 8);
  const nlohmann::json& last = doc["cells"].back();
  EXPECT_EQ(last["family"], "kemppinen");
  EXPECT_EQ(last["levels"].size(), 9u);
  EXPECT_TRUE(last["levels"]["k16_exact"]["adequate"].get<bool>());
  std::size_t kemppinen_maps = 0;
  for (const auto& m : doc["maps"]) {
    // The PNG is drawn from its chart spec by reports/figure_charts.py (glintlab adequacy runs it).
    fs::path spec = out / m["png"].get<std::string>();
    EXPECT_TRUE(fs::exists(spec.replace_extension(".chart.json"))) << spec;
    EXPECT_TRUE(fs::exists(out / m["exr"].get<std::string>()));
    kemppinen_maps += m["family"] == "kemppinen" ? 1 : 0;
  }
  EXPECT_EQ(kemppinen_maps, 2u);  // one per incidence
  EXPECT_TRUE(fs::exists(out / "adequacy-levels.csv"));
  fs::remove_all(out);
}

}  // namespace
}  // namespace glintlab::experiments

// The adequacy table's files (experiments/adequacy/adequacy_outputs.h) with several families: one CSV
// with a `family` column, each family's level columns (`nan` in the other family's rows), the
// JSON's families and cells, one map per Kemppinen model × incidence, and z split over the
// decisions of both families.
#include "experiments/adequacy/adequacy_outputs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

// The area family (kneiphof_klein_area under the declared square lights) beside the Kemppinen
// family: its rows in the same CSV under `family` = area with the binomial level columns, its
// light declared in the JSON, one map per light × incidence, and z split over all decisions.
TEST(AdequacyOutputs, AreaFamilyInTheTable) {
  const fs::path out = fs::temp_directory_path() / "glintlab_adequacy_outputs_area_test";
  fs::remove_all(out);
  AdequacyOptions o;
  o.models = {"kemppinen_ggx", "kneiphof_klein_area"};
  verify::adequacy::KemppinenGridAxes k;
  k.points = {1e5};
  k.alpha = {0.3};
  k.theta_i_deg = {0};
  k.theta_h_count = 1;
  k.samples = 500;
  o.kemppinen_axes = k;
  verify::adequacy::GridAxes a;
  a.facets = {1, 1e4, 1e8};
  a.alpha = {0.3};
  a.light_half_angle_deg = {1, 10};
  a.theta_i_deg = {0, 60};
  a.theta_h_count = 2;
  a.samples = 1000;
  o.area_axes = a;
  const std::size_t area_cells = 3 * 2 * 2 * 2;
  EXPECT_EQ(table_decisions(o), area_cells * 3 + 1 * 8);
  const AdequacySummary s = run_adequacy(out, o);
  EXPECT_EQ(s.cells, 0u);
  EXPECT_EQ(s.kemppinen.cells, 1u);
  EXPECT_EQ(s.area.cells, area_cells);
  EXPECT_EQ(s.z, verify::adequacy::decision_for_decisions(area_cells * 3 + 8, o.threshold).z);
  std::size_t chosen = 0;
  for (std::size_t c : s.area.chosen) chosen += c;
  EXPECT_EQ(chosen, area_cells);
  EXPECT_EQ(s.area.chooser_refuted, 0u);

  const io::CsvTable csv = io::read_csv(out / "adequacy.csv");
  ASSERT_EQ(csv.num_rows(), area_cells + 1);
  const auto& header = csv.header();
  const auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name;
    return std::size_t(it - header.begin());
  };
  const std::size_t family = column("family"), exact = column("exact_mean"),
                    k16 = column("k16_exact_mean"), light = column("light_half_angle_deg"),
                    p = column("p");
  std::size_t area_rows = 0;
  for (std::size_t r = 0; r < csv.num_rows(); ++r) {
    const bool is_area = csv.text(r, family) == "area";
    area_rows += is_area ? 1 : 0;
    EXPECT_EQ(csv.text(r, exact) == "nan", !is_area) << r;
    EXPECT_EQ(csv.text(r, k16) == "nan", is_area) << r;
    EXPECT_EQ(csv.text(r, light) == "nan", !is_area) << r;
    EXPECT_EQ(csv.text(r, p) == "nan", !is_area) << r;
  }
  EXPECT_EQ(area_rows, area_cells);

  std::ifstream in(out / "adequacy.json");
  const nlohmann::json doc = nlohmann::json::parse(in);
  const nlohmann::json& fam = doc["families"]["area"];
  EXPECT_EQ(fam["models"], nlohmann::json::array({"kneiphof_klein_area"}));
  EXPECT_EQ(fam["most_complete"], "exact");
  EXPECT_EQ(fam["summary"]["cells"], area_cells);
  ASSERT_EQ(fam["light"]["side"].size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const double g = a.light_half_angle_deg[i] * std::acos(-1.0) / 180;
    EXPECT_NEAR(fam["light"]["solid_angle_sr"][i].get<double>(),
                2 * std::acos(-1.0) * (1 - std::cos(g)), 1e-12);
  }
  EXPECT_EQ(doc["cells"].back()["family"], "area");
  EXPECT_EQ(doc["cells"].back()["levels"].size(), 4u);
  std::size_t area_maps = 0;
  for (const auto& m : doc["maps"]) {
    EXPECT_TRUE(fs::exists(out / m["exr"].get<std::string>()));
    area_maps += m["family"] == "area" ? 1 : 0;
  }
  EXPECT_EQ(area_maps, 4u);  // per light × incidence
  EXPECT_TRUE(fs::exists(out / "adequacy_kneiphof_klein_area_light10_theta60.chart.json"));
  fs::remove_all(out);
}

// The area family priced by benchmark costs (--bench-from's LevelCosts): with the exact count
// cheaper than both approximations, the cheapest adequate level by the benchmark is smooth where
// smooth is adequate and exact elsewhere, and the family's sums are the costs summed; costs
// without the area model's rows leave its rows unpriced (`none`).
TEST(AdequacyOutputs, AreaFamilyPricedByTheBenchmark) {
  const fs::path out = fs::temp_directory_path() / "glintlab_adequacy_outputs_area_cost_test";
  fs::remove_all(out);
  AdequacyOptions o;
  o.models = {"kneiphof_klein_area"};
  verify::adequacy::GridAxes a;
  a.facets = {1, 1e4, 1e8};
  a.alpha = {0.3};
  a.light_half_angle_deg = {1, 10};
  a.theta_i_deg = {0};
  a.theta_h_count = 1;
  a.samples = 1000;
  o.area_axes = a;
  const std::size_t cells = 3 * 2;
  for (const bool priced : {true, false}) {
    LevelCosts c;
    c.source = "bench/glints.json";
    c.isa = "scalar";
    c.ns[priced ? "kneiphof_klein_area" : "deliot_belcour"] = {10, 200, 300, 100};
    o.costs = c;
    const AdequacySummary s = run_adequacy(out, o);
    ASSERT_EQ(s.area.cells, cells);
    EXPECT_EQ(s.area.benchmark_costs, priced);
    EXPECT_FALSE(s.benchmark_costs);  // the binomial family's sums: no binomial cells
    const io::CsvTable csv = io::read_csv(out / "adequacy.csv");
    ASSERT_EQ(csv.num_rows(), cells);
    const auto& header = csv.header();
    const std::size_t by_bench =
        std::size_t(std::find(header.begin(), header.end(), "cheapest_by_benchmark") -
                    header.begin());
    ASSERT_LT(by_bench, header.size());
    std::ifstream in(out / "adequacy.json");
    const nlohmann::json doc = nlohmann::json::parse(in);
    const nlohmann::json& fam = doc["families"]["area"];
    if (!priced) {
      EXPECT_FALSE(fam.contains("benchmark_costs"));
      for (std::size_t r = 0; r < csv.num_rows(); ++r) EXPECT_EQ(csv.text(r, by_bench), "none");
      continue;
    }
    std::size_t smooth = 0;
    double cheapest_total = 0;
    for (std::size_t r = 0; r < csv.num_rows(); ++r) {
      const nlohmann::json& cell = doc["cells"][r];
      const bool smooth_ok = cell["levels"]["smooth"]["adequate"].get<bool>();
      const std::string expected = smooth_ok ? "smooth" : "exact";
      EXPECT_EQ(csv.text(r, by_bench), expected) << r;
      EXPECT_EQ(cell["cheapest_by_benchmark"], expected) << r;
      smooth += smooth_ok ? 1 : 0;
      cheapest_total += smooth_ok ? 10 : 100;
    }
    EXPECT_GT(smooth, 0u);
    EXPECT_LT(smooth, cells);
    const nlohmann::json& b = fam["benchmark_costs"];
    EXPECT_EQ(b["isa"], "scalar");
    EXPECT_EQ(b["exact_ns_total"], 100.0 * double(cells));
    EXPECT_EQ(b["cheapest_ns_total"], cheapest_total);
    EXPECT_EQ(b["cheapest_by_benchmark"]["smooth"], smooth);
    EXPECT_EQ(b["cheapest_by_benchmark"]["exact"], cells - smooth);
  }
  fs::remove_all(out);
}

}  // namespace
}  // namespace glintlab::experiments

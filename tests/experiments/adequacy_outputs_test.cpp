// The adequacy table's files (experiments/adequacy/adequacy_outputs.h) with several families: one CSV
// with a `family` column, each family's level columns (`nan` in the other family's rows), the
// JSON's families and cells, one map per Kemppinen model × incidence, and z split over the
// decisions of both families.
#include "experiments/adequacy/adequacy_outputs.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/io/atomic_file.h"
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
    EXPECT_EQ(s.area.bench.priced, priced);
    EXPECT_FALSE(s.bench.priced);  // the binomial family's sums: no binomial cells
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
    EXPECT_EQ(b["most_complete"], "exact");
    EXPECT_EQ(b["most_complete_ns_total"], 100.0 * double(cells));
    EXPECT_EQ(b["cheapest_ns_total"], cheapest_total);
    EXPECT_EQ(b["cheapest_by_benchmark"]["smooth"], smooth);
    EXPECT_EQ(b["cheapest_by_benchmark"]["exact"], cells - smooth);
  }
  fs::remove_all(out);
}

// The least benchmark cost among the adequate levels: an inadequate level is never taken however
// cheap, the most complete level always may be, and a tie goes to the level earlier in the order.
TEST(AdequacyOutputs, CheapestAdequateLevel) {
  const std::array<bool, 4> adequate = {false, true, true, false};
  EXPECT_EQ(cheapest_adequate(adequate, std::array<double, 4>{1, 30, 20, 100}), 2);
  EXPECT_EQ(cheapest_adequate(adequate, std::array<double, 4>{1, 20, 20, 100}), 1);  // the tie
  EXPECT_EQ(cheapest_adequate(adequate, std::array<double, 4>{1, 30, 20, 10}), 3);
  EXPECT_EQ(cheapest_adequate(std::array<bool, 4>{}, std::array<double, 4>{1, 2, 3, 4}), 3);
}

// A file of benchmark rows: every model × level of `models` at ISA scalar, at `ns` per level in the
// family's order, but the row named `skip`.
std::string bench_rows_json(const std::vector<std::string>& models,
                            const std::vector<double>& ns, const std::string& skip = "") {
  nlohmann::json rows = nlohmann::json::array();
  for (const std::string& m : models) {
    const auto levels = adequacy_level_names(m);
    for (std::size_t l = 0; l < levels.size(); ++l) {
      const std::string name = fmt::format("adequacy/{}/level={}/scalar", m, levels[l]);
      if (name == skip) continue;
      rows.push_back({{"name", name}, {"run_name", name}, {"run_type", "iteration"},
                      {"real_time", 1e6}, {"time_unit", "ns"},
                      {"items_per_second", 1e9 / ns[l]}});
    }
  }
  return nlohmann::json{{"context", nlohmann::json::object()}, {"benchmarks", rows}}.dump(1);
}

// read_level_costs reads every family's levels in its order, and refuses a file without one of a
// selected model's rows, naming it.
TEST(AdequacyOutputs, LevelCostsOfEveryFamily) {
  const fs::path dir = fs::temp_directory_path() / "glintlab_adequacy_level_costs_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::vector<std::string> models = {"deliot_belcour", "kemppinen_beckmann",
                                           "kneiphof_klein_area", "chermain"};
  const std::vector<double> ns = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  io::write_file_atomic(dir / "glints.json", bench_rows_json(models, ns));
  const LevelCosts c = read_level_costs(dir, "bench", "scalar", models);
  EXPECT_EQ(c.source, (fs::path("bench") / "glints.json").string());
  EXPECT_EQ(c.ns.at("deliot_belcour"), std::vector<double>(ns.begin(), ns.begin() + 4));
  EXPECT_EQ(c.ns.at("kneiphof_klein_area"), std::vector<double>(ns.begin(), ns.begin() + 4));
  EXPECT_EQ(c.ns.at("kemppinen_beckmann"), ns);
  EXPECT_EQ(c.ns.at("chermain"), ns);
  io::write_file_atomic(dir / "glints.json",
                        bench_rows_json(models, ns, "adequacy/chermain/level=dict12/scalar"));
  try {
    read_level_costs(dir, "bench", "scalar", models);
    ADD_FAILURE() << "a file without adequacy/chermain/level=dict12/scalar was read";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("adequacy/chermain/level=dict12/scalar"),
              std::string::npos)
        << e.what();
  }
  // The other families' rows alone still price them.
  EXPECT_EQ(read_level_costs(dir, "bench", "scalar", {"kemppinen_beckmann"}).ns.size(), 1u);
  fs::remove_all(dir);
}

// The Kemppinen and Chermain families priced by benchmark costs (cells made by hand, so that every
// level's adequacy is known): per cell the adequate level of least cost, per family its sums
// against its most complete level, in adequacy.csv, adequacy.json and the printed line; a family
// whose models the costs lack is unpriced (`none`, no benchmark_costs, a line saying so).
TEST(AdequacyOutputs, KemppinenAndChermainPricedByTheBenchmark) {
  namespace adq = verify::adequacy;
  const fs::path out = fs::temp_directory_path() / "glintlab_adequacy_outputs_leveled_cost_test";
  fs::remove_all(out);
  AdequacyOptions o;
  o.models = {"kemppinen_ggx", "chermain"};
  adq::KemppinenGridAxes k;
  k.points = {10, 1e5};
  k.alpha = {0.3};
  k.theta_i_deg = {0};
  k.theta_h_count = 1;
  k.samples = 100;
  o.kemppinen_axes = k;
  adq::ChermainGridAxes ch;
  ch.facets = {1, 1e10};
  ch.alpha = {0.3};
  ch.theta_i_deg = {0};
  ch.dh = {0};
  ch.theta_h_count = 1;
  ch.samples = 100;
  o.chermain_axes = ch;
  // Per family two cells: the first with only the most complete level adequate; the second with
  // smooth (the GPU order's choice) and level 3 (k4_rational, dict8) adequate, level 1 (cheapest
  // of all) not.
  const auto set_levels = [](auto& r, int cell) {
    const int last = int(r.levels.size()) - 1;
    for (auto& l : r.levels) l.adequate = false;
    r.levels[std::size_t(last)].adequate = true;
    r.chosen = last;
    if (cell == 1) {
      r.levels[0].adequate = r.levels[3].adequate = true;
      r.chosen = 0;
    }
    r.cheapest_measured = r.chosen;
  };
  AdequacyCells cells;
  for (const adq::KemppinenCell& c : adq::make_kemppinen_grid({"kemppinen_ggx"}, k)) {
    cells.kemppinen.emplace_back();
    cells.kemppinen.back().cell = c;
    set_levels(cells.kemppinen.back(), int(cells.kemppinen.size()) - 1);
  }
  for (const adq::ChermainCell& c : adq::make_chermain_grid({"chermain"}, ch)) {
    cells.chermain.emplace_back();
    cells.chermain.back().cell = c;
    set_levels(cells.chermain.back(), int(cells.chermain.size()) - 1);
  }
  ASSERT_EQ(cells.kemppinen.size(), 2u);
  ASSERT_EQ(cells.chermain.size(), 2u);
  // Level 1 cheapest of all, then level 3, smooth, the most complete; the rest dearer.
  const std::vector<double> ns = {50, 5, 200, 20, 200, 200, 200, 200, 100};
  for (const bool chermain_priced : {true, false}) {
    LevelCosts costs;
    costs.source = "bench/glints.json";
    costs.isa = "scalar";
    costs.ns["kemppinen_ggx"] = ns;
    if (chermain_priced) costs.ns["chermain"] = ns;
    o.costs = costs;
    const AdequacySummary s = write_adequacy(out, o, cells);
    for (const BenchSums* b : {&s.kemppinen.bench, &s.chermain.bench}) {
      if (b == &s.chermain.bench && !chermain_priced) {
        EXPECT_FALSE(b->priced);
        EXPECT_NE(bench_sums_line("Chermain family", *b, kChermainLevelNames, costs.source,
                                  costs.isa)
                      .find("Chermain family: no benchmark costs"),
                  std::string::npos);
        continue;
      }
      ASSERT_TRUE(b->priced);
      EXPECT_EQ(b->most_complete_ns, 200.0);
      EXPECT_EQ(b->chosen_ns, 150.0);   // the most complete, smooth
      EXPECT_EQ(b->cheapest_ns, 120.0);  // the most complete, level 3
      ASSERT_EQ(b->cheapest_by_benchmark.size(), 9u);
      EXPECT_EQ(b->cheapest_by_benchmark[3], 1u);
      EXPECT_EQ(b->cheapest_by_benchmark[8], 1u);
      EXPECT_DOUBLE_EQ(b->cheapest_saved(), 0.4);
      // The engine chooser for these costs (core/glints/cost_chooser.h) at each cell: its levels'
      // costs summed, its levels counted, refuted where the table's bounds say so (the hand-made
      // levels' bounds are 0: nowhere).
      ASSERT_TRUE(b->engine);
      double engine_ns = 0;
      std::vector<std::size_t> engine(9);
      const auto add = [&](int level) {
        engine_ns += ns[std::size_t(level)];
        ++engine[std::size_t(level)];
      };
      if (b == &s.kemppinen.bench)
        for (const auto& r : cells.kemppinen)
          add(kemppinen_engine_level_by_cost(r.cell, o.threshold, ns));
      else
        for (const auto& r : cells.chermain)
          add(chermain_engine_level_by_cost(r.cell, o.threshold, ns));
      EXPECT_EQ(b->engine_ns, engine_ns);
      EXPECT_EQ(b->engine_by_cost, engine);
      EXPECT_EQ(b->engine_refuted, 0u);
    }
    const std::string line = bench_sums_line("Kemppinen family", s.kemppinen.bench,
                                             kKemppinenLevelNames, costs.source, costs.isa);
    EXPECT_NE(line.find("; engine chooser for these costs "), std::string::npos) << line;
    EXPECT_NE(line.find("refuted in 0 cells; smooth "), std::string::npos) << line;
    EXPECT_NE(line.find("k16_exact everywhere 200 ns"), std::string::npos) << line;
    EXPECT_NE(line.find("chosen level 150 ns (25.0 % saved)"), std::string::npos) << line;
    EXPECT_NE(line.find("120 ns (40.0 % saved; smooth 0, k1_rational 0, k1_exact 0, "
                        "k4_rational 1,"),
              std::string::npos)
        << line;
    const io::CsvTable csv = io::read_csv(out / "adequacy.csv");
    ASSERT_EQ(csv.num_rows(), 4u);
    const std::size_t by_bench = csv.column("cheapest_by_benchmark");
    EXPECT_EQ(csv.text(0, by_bench), "k16_exact");
    EXPECT_EQ(csv.text(1, by_bench), "k4_rational");
    EXPECT_EQ(csv.number(1, csv.column("bench_exact_ns")), 100.0);
    EXPECT_EQ(csv.number(1, csv.column("bench_chosen_ns")), 50.0);
    EXPECT_EQ(csv.number(1, csv.column("bench_cheapest_ns")), 20.0);
    EXPECT_EQ(csv.text(2, by_bench), chermain_priced ? "dict16_ggaa" : "none");
    EXPECT_EQ(csv.text(3, by_bench), chermain_priced ? "dict8" : "none");
    std::ifstream in(out / "adequacy.json");
    const nlohmann::json doc = nlohmann::json::parse(in);
    const nlohmann::json& kb = doc["families"]["kemppinen"]["benchmark_costs"];
    EXPECT_EQ(kb["most_complete"], "k16_exact");
    EXPECT_EQ(kb["cheapest_ns_total"], 120.0);
    EXPECT_EQ(kb["cheapest_by_benchmark"]["k4_rational"], 1);
    EXPECT_EQ(kb["engine_by_cost"]["ns_total"], s.kemppinen.bench.engine_ns);
    EXPECT_EQ(kb["engine_by_cost"]["refuted"], 0);
    EXPECT_EQ(doc["cells"][1]["cheapest_by_benchmark"], "k4_rational");
    EXPECT_EQ(doc["benchmark_costs"]["ns_per_eval"]["kemppinen_ggx"]["k4_rational"], 20.0);
    EXPECT_FALSE(doc["families"]["binomial"].contains("benchmark_costs"));  // no binomial cells
    const nlohmann::json& cf = doc["families"]["chermain"];
    EXPECT_EQ(cf.contains("benchmark_costs"), chermain_priced);
    if (chermain_priced) {
      EXPECT_EQ(cf["benchmark_costs"]["most_complete"], "dict16_ggaa");
      EXPECT_EQ(cf["benchmark_costs"]["chosen_ns_total"], 150.0);
      EXPECT_EQ(doc["cells"][3]["cheapest_by_benchmark"], "dict8");
    } else {
      EXPECT_FALSE(doc["cells"][3].contains("cheapest_by_benchmark"));
    }
  }
  fs::remove_all(out);
}

}  // namespace
}  // namespace glintlab::experiments

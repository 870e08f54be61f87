// The adequacy table in parts (experiments/adequacy/adequacy_shards.h) with both families: a
// part's cells are bit for bit the whole grid's cells at those positions, its file reads back
// exactly (every double's bits, NaN included), and the parts of a run joined are the whole grid;
// a cell missing or given twice is named.
#include "experiments/adequacy/adequacy_shards.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace glintlab::experiments {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The in-process timings (and the level measured cheapest from them) set to one value, so that two
// measurements of the same cells can be compared bit for bit.
AdequacyCells without_timing(AdequacyCells c) {
  for (auto& r : c.binomial) {
    for (auto& l : r.levels) l.ns_per_eval = 0;
    r.cheapest_measured = 0;
  }
  for (auto& r : c.kemppinen) {
    for (auto& l : r.levels) l.ns_per_eval = 0;
    r.cheapest_measured = 0;
  }
  for (auto& r : c.area) {
    for (auto& l : r.levels) l.ns_per_eval = 0;
    r.cheapest_measured = 0;
  }
  return c;
}

// The Kemppinen and the area family on small grids (the binomial family's parts:
// tests/cli/adequacy_shard_test.cpp).
AdequacyOptions small_run() {
  AdequacyOptions o;
  o.models = {"kemppinen_ggx", "kneiphof_klein_area"};
  verify::adequacy::KemppinenGridAxes k;
  k.points = {10, 1e4};
  k.alpha = {0.3};
  k.theta_i_deg = {0};
  k.theta_h_count = 2;
  k.samples = 500;
  o.kemppinen_axes = k;
  verify::adequacy::GridAxes a;
  a.facets = {1, 1e4, 1e7};
  a.alpha = {0.3};
  a.light_half_angle_deg = {1};
  a.theta_i_deg = {0};
  a.theta_h_count = 1;
  a.samples = 500;
  o.area_axes = a;
  return o;
}

TEST(AdequacyShards, PartsJoinedAreTheWholeGridBitForBit) {
  const fs::path dir = fs::temp_directory_path() / "glintlab_adequacy_shards_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const AdequacyOptions o = small_run();
  const AdequacyPart whole = adequacy_shard_part(o, 1, 1);
  ASSERT_EQ(whole.kemppinen.size(), 4u);
  ASSERT_EQ(whole.area.size(), 3u);
  const AdequacyCells all = measure_adequacy_part(o, whole);
  write_adequacy_part(dir / "whole.json", o, whole, without_timing(all));

  std::vector<AdequacyPartFile> parts;
  for (std::size_t k : {3, 1, 2}) {  // any order
    const AdequacyPart part = adequacy_shard_part(o, k, 3);
    const fs::path file = dir / ("part" + std::to_string(k) + ".json");
    write_adequacy_part(file, o, part, measure_adequacy_part(o, part));
    parts.push_back(read_adequacy_part(file));
    // Read back exactly: written again, the same bytes.
    write_adequacy_part(dir / "again.json", parts.back().options, parts.back().part,
                        parts.back().cells);
    EXPECT_EQ(read_text(dir / "again.json"), read_text(file)) << k;
    EXPECT_EQ(adequacy_run_text(parts.back().options), adequacy_run_text(o));
  }
  const AdequacyCells joined = join_adequacy_parts(o, parts);
  write_adequacy_part(dir / "joined.json", o, whole, without_timing(joined));
  EXPECT_EQ(read_text(dir / "joined.json"), read_text(dir / "whole.json"));
  // The grid's own cells, in its order.
  ASSERT_EQ(joined.kemppinen.size(), all.kemppinen.size());
  for (std::size_t i = 0; i < all.kemppinen.size(); ++i)
    EXPECT_EQ(joined.kemppinen[i].cell.points, all.kemppinen[i].cell.points);
  ASSERT_EQ(joined.area.size(), all.area.size());
  for (std::size_t i = 0; i < all.area.size(); ++i) {
    EXPECT_EQ(joined.area[i].cell.facets, all.area[i].cell.facets);
    EXPECT_EQ(joined.area[i].cell.model, "kneiphof_klein_area");
  }
  // Another area grid is another run.
  AdequacyOptions wider = o;
  wider.area_axes->light_half_angle_deg = {10};
  EXPECT_NE(adequacy_run_text(wider), adequacy_run_text(o));

  // Another TAU is another run.
  AdequacyOptions other = o;
  other.threshold = 0.05;
  EXPECT_NE(adequacy_run_text(other), adequacy_run_text(o));
  // A cell missing, or given twice.
  std::vector<AdequacyPartFile> missing(parts.begin(), parts.begin() + 2);
  EXPECT_THROW(
      try { join_adequacy_parts(o, missing); } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("no shard holds"), std::string::npos) << e.what();
        throw;
      },
      std::invalid_argument);
  std::vector<AdequacyPartFile> twice = parts;
  twice.push_back(parts.front());
  EXPECT_THROW(
      try { join_adequacy_parts(o, twice); } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("is in two shards"), std::string::npos) << e.what();
        throw;
      },
      std::invalid_argument);
  // A file that is not one.
  std::ofstream(dir / "bad.json") << "{\"format\": 3}";
  EXPECT_THROW(read_adequacy_part(dir / "bad.json"), std::invalid_argument);
  fs::remove_all(dir);
}

// NaN, infinities and signed zeros survive the file bit for bit.
TEST(AdequacyShards, NonFiniteNumbersReadBackExactly) {
  const fs::path file = fs::temp_directory_path() / "glintlab_adequacy_shards_nan.json";
  AdequacyOptions o = small_run();
  AdequacyPart part;
  part.kemppinen = {2};
  AdequacyCells cells;
  cells.kemppinen.resize(1);
  cells.kemppinen[0].levels[1].cv = std::nan("0x7");
  cells.kemppinen[0].levels[2].mean_diff_ucb = -INFINITY;
  cells.kemppinen[0].lambda = -0.0;
  write_adequacy_part(file, o, part, cells);
  const AdequacyPartFile f = read_adequacy_part(file);
  ASSERT_EQ(f.cells.kemppinen.size(), 1u);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(f.cells.kemppinen[0].levels[1].cv),
            std::bit_cast<std::uint64_t>(std::nan("0x7")));
  EXPECT_EQ(f.cells.kemppinen[0].levels[2].mean_diff_ucb, -INFINITY);
  EXPECT_TRUE(std::signbit(f.cells.kemppinen[0].lambda));
  EXPECT_EQ(f.part.kemppinen, part.kemppinen);
  // A position outside the run's grid is named.
  // The area family's cells likewise.
  AdequacyPart area_part;
  area_part.area = {1};
  AdequacyCells area_cells;
  area_cells.area.resize(1);
  area_cells.area[0].levels[0].cv_diff_ucb = INFINITY;
  area_cells.area[0].p = std::nan("0x9");
  write_adequacy_part(file, o, area_part, area_cells);
  const AdequacyPartFile g = read_adequacy_part(file);
  ASSERT_EQ(g.cells.area.size(), 1u);
  EXPECT_EQ(g.cells.area[0].levels[0].cv_diff_ucb, INFINITY);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(g.cells.area[0].p),
            std::bit_cast<std::uint64_t>(std::nan("0x9")));
  EXPECT_EQ(g.cells.area[0].cell.facets, 1e4);  // its cell placed from the run's area grid
  part.kemppinen = {4};
  write_adequacy_part(file, o, part, cells);
  EXPECT_THROW(read_adequacy_part(file), std::invalid_argument);
  fs::remove(file);
}

}  // namespace
}  // namespace glintlab::experiments

// The benchmark's per-ISA Chermain units (experiments/bench/chermain_level_isa.h: the adequacy
// rows' Chermain levels on each ISA's double batches) against Chermain::eval<double> on the quick
// Chermain grid's cells, every counting level, 64 positions each (the benchmark's queries): the
// same values within the batches' rounding. The comparison fails a unit handed another level's
// dictionary (the same code, the wrong table).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/simd/batch.h"
#include "experiments/bench/chermain_level_isa.h"
#include "verify/adequacy/chermain_adequacy.h"

namespace glintlab::bench {
namespace {

namespace adq = verify::adequacy;

struct LevelDiff {
  double largest_relative = 0;    // over the values either side is non-zero
  long compared = 0, differ = 0;  // differ: relative difference above 1e-9
};

// Every counting level of every quick cell through `eval`, handed the level's parameters or (the
// control) those of the next shorter dictionary, against the scalar eval of the level's.
LevelDiff compare(ChermainLevelEval eval, bool wrong_dictionary) {
  LevelDiff d;
  const auto cells =
      adq::make_chermain_grid({"chermain"}, adq::chermain_grid_axes(verify::Budget::kQuick));
  std::vector<double> got(64);
  for (int l = int(ChermainLevel::kDict8); l < kChermainLevels; ++l)
    for (const adq::ChermainCell& c : cells) {
      std::vector<ModelQuery<double>> q;
      for (int i = 0; i < 64; ++i)
        q.push_back(adq::chermain_cell_query(c, adq::chermain_surface_position(c, i)));
      const auto p = adq::chermain_level_params(c, ChermainLevel(l), 1);
      const auto handed =
          wrong_dictionary ? adq::chermain_level_params(c, ChermainLevel(l - 2), 1) : p;
      eval(handed, q.data(), got.data(), q.size());
      for (std::size_t i = 0; i < q.size(); ++i) {
        const double want = Chermain::eval<double>(p, q[i]).value;
        if (want == 0 && got[i] == 0) continue;
        const double rel = std::abs(got[i] - want) / std::max(std::abs(want), 1e-300);
        d.largest_relative = std::max(d.largest_relative, rel);
        ++d.compared;
        d.differ += rel > 1e-9 ? 1 : 0;
      }
    }
  return d;
}

TEST(ChermainLevelIsa, EveryIsaMatchesTheScalarEvalAndAWrongDictionaryIsCaught) {
  const ChermainLevelEval units[] = {chermain_level_isa_scalar(), chermain_level_isa_sse42(),
                                     chermain_level_isa_avx2(), chermain_level_isa_avx512()};
  int run = 0;
  for (std::size_t k = 0; k < std::size(simd::kAllIsas); ++k) {
    const simd::Isa isa = simd::kAllIsas[k];
    if (!simd::isa_supported(isa)) {
      std::printf("%s: this CPU lacks it; its unit is compiled, not compared\n",
                  std::string(simd::isa_name(isa)).c_str());
      continue;
    }
    ++run;
    const LevelDiff d = compare(units[k], false);
    EXPECT_GT(d.compared, 0);
    EXPECT_EQ(d.differ, 0) << simd::isa_name(isa) << ": largest relative difference "
                           << d.largest_relative;
    EXPECT_LE(d.largest_relative, 1e-9) << simd::isa_name(isa);
    const LevelDiff broken = compare(units[k], true);
    EXPECT_GT(broken.differ, 0) << simd::isa_name(isa);
    std::printf("%s: %ld values, largest relative difference %.3g; handed the next shorter "
                "dictionary: %ld of %ld differ\n",
                std::string(simd::isa_name(isa)).c_str(), d.compared, d.largest_relative,
                broken.differ, broken.compared);
  }
  EXPECT_GT(run, 0);
}

}  // namespace
}  // namespace glintlab::bench

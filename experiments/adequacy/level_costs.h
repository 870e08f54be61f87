// Each binomial level's cost per evaluation on this machine, from the Google Benchmark JSON of
// glintlab_bench_glints (its adequacy/<model>/level=<level>/<isa> rows: the quick adequacy grid's
// cells through the registry's batch API; for the area family, kneiphof_klein_area, the model's
// double thunk row by row and its smooth level's LTC call), for `glintlab adequacy --bench-from
// DIR` and the adequacy-scene figure: the level a cell needs priced by measurement rather than by the order of
// a GPU lane, and the time saved against the exact count everywhere.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/glints/adequacy.h"

namespace glintlab::experiments {

// The benchmark's file in a --bench-from folder.
inline constexpr std::string_view kLevelCostsFile = "glints.json";

struct LevelCosts {
  std::string source;  // the file, as the outputs name it
  std::string isa;     // the ISA whose rows price the levels
  // ns per evaluation per level (BinomialLevel order), per model of the family.
  std::map<std::string, std::array<double, kBinomialLevels>, std::less<>> ns;
};

// The rows of `isa` for every model in `models` from dir/glints.json (`shown_as`: the folder as
// the outputs name it). Throws std::invalid_argument naming the file and the first missing row
// (with the command that writes it) when the file is absent, not benchmark JSON or incomplete.
LevelCosts read_level_costs(const std::filesystem::path& dir, std::string_view shown_as,
                            std::string_view isa, const std::vector<std::string>& models);

// The adequate level of least cost (`adequate`: per level, BinomialLevel order; exact always).
int cheapest_adequate(const std::array<bool, kBinomialLevels>& adequate,
                      const std::array<double, kBinomialLevels>& ns);

}  // namespace glintlab::experiments

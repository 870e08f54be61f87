// Each adequacy level's cost per evaluation on this machine, from the Google Benchmark JSON of
// glintlab_bench_glints (its adequacy/<model>/level=<level>/<isa> rows: the quick adequacy grid's
// cells of every family — binomial, area (kneiphof_klein_area), Kemppinen, Chermain — each level
// as the bench file's header says it is timed), for `glintlab adequacy --bench-from DIR` and the
// adequacy-scene figure: the level a cell needs priced by measurement rather than by the order of
// a GPU lane, and the time saved against the family's most complete level everywhere.
#pragma once

#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace glintlab::verify::adequacy {
struct KemppinenCell;
struct ChermainCell;
}  // namespace glintlab::verify::adequacy

namespace glintlab::experiments {

// The benchmark's file in a --bench-from folder.
inline constexpr std::string_view kLevelCostsFile = "glints.json";

struct LevelCosts {
  std::string source;  // the file, as the outputs name it
  std::string isa;     // the ISA whose rows price the levels
  // ns per evaluation per level (the order of adequacy_level_names(model)), per model.
  std::map<std::string, std::vector<double>, std::less<>> ns;
};

// The level names of `model`'s adequacy family, cheapest first in the GPU order and the most
// complete last: the binomial levels (binomial and area families), the Kemppinen levels or the
// Chermain levels; empty for a model of no family.
std::span<const std::string_view> adequacy_level_names(std::string_view model);

// The rows of `isa` for every level of every model in `models` from dir/glints.json (`shown_as`:
// the folder as the outputs name it). Throws std::invalid_argument naming the file and the first
// missing row (with the command that writes it) when the file is absent, not benchmark JSON or
// incomplete.
LevelCosts read_level_costs(const std::filesystem::path& dir, std::string_view shown_as,
                            std::string_view isa, const std::vector<std::string>& models);

// The adequate level of least cost (`adequate` and `ns` per level in the family's order, the last
// level the most complete, taken whether adequate or not); a tie goes to the level earlier in the
// order (the cheaper one on a GPU lane).
int cheapest_adequate(std::span<const bool> adequate, std::span<const double> ns);

// The engine chooser for these costs at a cell of the Kemppinen or the Chermain table
// (choose_kemppinen_model_level_by_cost, choose_chermain_model_level_by_cost;
// core/glints/cost_chooser.h) where the table computes its GPU-order chooser: at the cell's first
// surface position, on the most complete level's parameters. `ns`: the cell's model's levels'
// costs in the family's order (LevelCosts::ns). The level's index in that order.
int kemppinen_engine_level_by_cost(const verify::adequacy::KemppinenCell& c, double tau,
                                   std::span<const double> ns);
int chermain_engine_level_by_cost(const verify::adequacy::ChermainCell& c, double tau,
                                  std::span<const double> ns);

}  // namespace glintlab::experiments

// `glintlab adequacy --shard K/N`: a part of the adequacy grid measured in one process, written as
// exact bits (adequacy-cells.json), and the parts of one run joined into the cells the unsharded
// run measures, from which write_adequacy writes the same files. A cell's seed is its position in
// the whole grid, so a cell measured in any shard is bit for bit the unsharded run's; only the
// in-process timings (ns per evaluation, and the cheapest level measured from them) differ.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "experiments/adequacy/adequacy_outputs.h"

namespace glintlab::experiments {

// The file a shard writes beside its manifest.
inline constexpr const char* kAdequacyCellsFile = "adequacy-cells.json";

// A part of a run's grid: positions of each family's cells in that family's whole grid.
struct AdequacyPart {
  std::vector<std::size_t> binomial, kemppinen, area, chermain;
};

// Shard k of n (1 <= k <= n): each family's cells dealt round-robin from the k-th, so every shard
// holds the same share of every family (a Kemppinen cell costs about ten binomial ones) and of
// every footprint size (the costlier cells).
AdequacyPart adequacy_shard_part(const AdequacyOptions& o, std::size_t k, std::size_t n);

// Every cell of the run's grid, in order: "binomial/<position>", then "kemppinen/<position>", then
// "area/<position>", then "chermain/<position>".
std::vector<std::string> adequacy_cell_ids(const AdequacyOptions& o);
// The ids of `part`'s cells, in the order of adequacy_cell_ids.
std::vector<std::string> adequacy_part_ids(const AdequacyPart& part);
// Everything a measured value depends on besides the seeds: budget, TAU, the benchmark costs,
// every family's grid cell by cell. Two shards belong to one run only when this text is the same.
std::string adequacy_run_text(const AdequacyOptions& o);

// The cells of `part` (TBB over the cells; `o.progress` once per cell).
AdequacyCells measure_adequacy_part(const AdequacyOptions& o, const AdequacyPart& part);

// adequacy-cells.json: the options the cells depend on (models, TAU, budget, the Kemppinen, the
// area and the Chermain axes, the benchmark costs), the part, and every field of every cell, each number as the hexadecimal
// bits of its double (exact, NaN and infinities included). Written atomically.
void write_adequacy_part(const std::filesystem::path& file, const AdequacyOptions& o,
                         const AdequacyPart& part, const AdequacyCells& cells);

struct AdequacyPartFile {
  AdequacyOptions options;  // models, threshold, budget, kemppinen_axes, area_axes, chermain_axes,
                            // costs
  AdequacyPart part;
  AdequacyCells cells;  // the part's cells, in its order
};
// Reads a file of write_adequacy_part; std::invalid_argument naming the file when it is not one.
AdequacyPartFile read_adequacy_part(const std::filesystem::path& file);

// The whole grid's cells of `o` from `parts` (of one run: checked by the caller): every cell
// exactly once. std::invalid_argument naming the cell that is missing or given twice.
AdequacyCells join_adequacy_parts(const AdequacyOptions& o,
                                  const std::vector<AdequacyPartFile>& parts);

}  // namespace glintlab::experiments

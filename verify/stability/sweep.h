// The stability sweep of one model × sampler (claim all.stability): every plane of sweep_plan.h
// measured cell by cell (cell_stats.h) into maps, with the failure region derived from them.
// Cells run in parallel (TBB), each with the seed check_seed("all.stability/<model>/<sampler>/
// <plane>", cell index) and a serial loop over its samples, so the maps are bit-identical for any
// thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "verify/check.h"
#include "verify/stability/cell_stats.h"
#include "verify/stability/sweep_plan.h"

namespace glintlab::verify::stability {

struct SweepMap {
  SweepPlane plane;
  std::vector<CellStats> cells;  // row-major: cells[row * plane.theta_deg.size() + column]
  const CellStats& at(std::size_t row, std::size_t col) const {
    return cells[row * plane.theta_deg.size() + col];
  }
};

struct ModelSweep {
  SweepTarget target;
  bool has_float = false;        // the float instantiation was swept too
  bool has_probability = false;  // the model exposes a probability intermediate
  bool has_variance = false;     // the fixed-position variance was measured in every cell
  std::vector<SweepMap> maps;
  double seconds = 0;  // wall time (progress and reports only; never asserted)
};

// Per-cell sample counts of a budget: quick = 64 uniform evaluations + 256 samples, full = 1024 +
// 1024 (and finer planes, sweep_planes(quick = false)).
CellBudget cell_budget(Budget b);

// Whether a sweep measures the fixed-position variance (cell_stats.h), about half of a sweep's
// time: the variance blow-up needs it (all.variance, a model's stability property, its maps and
// failure regions); the NaN, energy-gain and probability checks do not.
enum class FixedPositionVariance { kMeasure, kSkip };

// Sweeps one target. `progress(done, total)` is called after each finished plane (one thread).
ModelSweep sweep_model(const SweepTarget& target, Budget b,
                       const std::function<void(long, long)>& progress = {},
                       FixedPositionVariance variance = FixedPositionVariance::kMeasure);

// Measures the fixed-position variance of a sweep made without it, cell by cell as sweep_model
// would have (the same numbers, any thread count); nothing to do if it has it.
void add_fixed_position_variance(ModelSweep& s, Budget b);

// While a SweepReuse is alive, sweep_model returns the earlier sweep of the same registered model
// entry, sampler choice and budget instead of measuring it again: `glintlab compare` runs a
// model's conformance suite, whose stability property sweeps the model, and then reports that
// sweep's failure regions. Only entries of registered_models() are reused, never a copy of one
// (the controls' broken models). A sweep is deterministic, so a reused one is what a second sweep
// would measure (its `seconds` apart); a kept sweep without the fixed-position variance gets it
// added when a later call asks for it. One at a time per process; not nested.
class SweepReuse {
 public:
  SweepReuse();
  ~SweepReuse();
  SweepReuse(const SweepReuse&) = delete;
  SweepReuse& operator=(const SweepReuse&) = delete;
  std::size_t reused() const;  // sweeps returned from memory so far
};

}  // namespace glintlab::verify::stability

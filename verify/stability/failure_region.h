// The failure region of a stability sweep, in words, derived from its maps: for each defect (NaN,
// Inf, negative values; energy gain; p > 1; variance blow-up) the cells where it occurs, described
// by the ranges of the plane's parameter and of θi they span; and the verdict of all.stability
// for the model: holds (no NaN/Inf/negative anywhere), holds-in-regime (only outside the core
// domain of sweep_plan.h, or only in the float instantiation), fails (inside it).
#pragma once

#include <string>
#include <vector>

#include "verify/check.h"
#include "verify/stability/sweep.h"

namespace glintlab::verify::stability {

// The four kinds of breakage all.stability tells apart, each with its own verdict: NaN, Inf or
// negative numbers; a significant energy gain; a probability above one; a variance blow-up.
enum class DefectClass { kBreaks, kEnergyGain, kProbabilityAboveOne, kHugeVariance };

struct Finding {
  std::string defect;  // "NaN", "Inf", "negative", "energy gain > 1", "p > 1", ...
  DefectClass kind = DefectClass::kBreaks;
  std::string components;   // e.g. "value, pdf" or "sample weight" (where it applies)
  bool float_only = false;  // seen in the float instantiation only
  std::string plane;        // the plane's name
  std::string region;       // "α ≤ 0.0003 at θi ≥ 89.9°"
  std::size_t cells = 0, plane_cells = 0;
  double worst = 0;      // largest fraction (defects) or value (gain, p, relative variance)
  bool in_core = false;  // some flagged cell is in the core domain
  bool breaks = false;   // NaN, Inf or negative (the verdict's defects)
  std::string text() const;
};

std::vector<Finding> find_failures(const ModelSweep& s);

// "none: …" or the findings joined by "; ".
std::string describe_failure_region(const ModelSweep& s);

// holds / holds-in-regime / fails for one swept target and one kind of defect: holds where none
// is found, holds-in-regime where found only outside the core domain (or, for NaN/Inf/negative,
// only in the float instantiation), fails where found inside it; inconclusive for the variance
// blow-up of a sweep that did not measure the fixed-position variance.
Verdict stability_verdict(const ModelSweep& s, DefectClass kind = DefectClass::kBreaks);

}  // namespace glintlab::verify::stability

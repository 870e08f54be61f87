// Time per evaluation of a registered model through the batch dispatch (core/simd/model_batch.h),
// on the scalar path and on the widest ISA this CPU has (or GLINTLAB_ISA): a measurement of this
// run's machine, never a recorded number.
#pragma once

#include <string>

#include "core/model_registry.h"
#include "experiments/compare/compare_budget.h"

namespace glintlab::experiments::compare {

struct EvalTiming {
  double scalar_ns = 0;  // ns per eval, double precision, Isa::kScalar
  double best_ns = 0;    // the same on best_isa
  std::string best_isa;  // isa_name of the ISA timed as best
  bool batched = false;  // simd::is_batched: false means both paths are the thunk loop
};

// The best of 3 rounds of repeated eval_batch calls on b.timing_rows fixed queries (ωo spread over
// the hemisphere, ωi of the first scene) until a round lasts b.timing_seconds.
EvalTiming time_evaluations(const ModelEntry& model, const CompareBudget& b);

}  // namespace glintlab::experiments::compare

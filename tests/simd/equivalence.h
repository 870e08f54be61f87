// The equivalence criterion of batched against scalar kernels, and the per-kernel budgets.
#pragma once

#include <string>
#include <vector>

#include "core/simd/batch.h"

namespace glintlab::simd::test {

// A kernel's budget. Value outputs: |batch − scalar| ≤ ulp ulps, or both below √(smallest normal)
// in magnitude (there the kernels' own products underflow). Direction and map-point components
// (bounded by 1): |batch − scalar| ≤ abs_eps machine epsilons. Samplers: rows the scalar or the
// batch rejects compare only the flag, which may differ on at most flag_fraction of the rows
// (flags threshold values that differ by rounding); the reported pdf is compared with the scalar
// standalone pdf at the batch's own wo (the sampler's contract), with that pdf kernel's budget.
struct Budget {
  double ulp;
  double abs_eps;
  double flag_fraction;
  std::string why;
};
Budget budget(std::string_view kernel, bool double_precision);

// Rows compared for a kernel (10^6; 2^16 for the two-parameter total-area integrals, 32 nested
// evaluations each).
std::size_t rows_for(std::string_view kernel);

struct Comparison {
  bool pass;
  std::string summary;  // one line: kernel, ISA, measured maxima, budget
};

// Scalar and batched outputs of one kernel on the shared inputs.
template <class S>
std::vector<std::vector<S>> evaluate(int kernel, Isa isa, Math math, std::size_t n);

// Compares `got` (any evaluation of `kernel` on the first rows of the shared inputs) with the
// scalar reference `ref` of the same rows.
template <class S>
Comparison compare_outputs(int kernel, const std::vector<std::vector<S>>& ref,
                           const std::vector<std::vector<S>>& got, std::string label);

}  // namespace glintlab::simd::test

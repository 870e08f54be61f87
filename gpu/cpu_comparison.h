// CPU = GPU: a device check's results folder (gpu/gpu_check.cpp) compared with the CPU batches
// (core/simd/model_batch.h, scalar path, exact math) on the folder's own queries, column by
// column, within the budgets below (docs/gpu.md "Budgets").
//
// Why budgets and not bit equality: the device kernels are built without multiply-add
// contraction (--fmad=false) and with IEEE division and square root, so +, −, ×, ÷ and √ round as
// on the CPU; the difference is CUDA's math library (sin, cos, exp, log, erf, atan2 …: within
// 1–4 ulp in float, 1–2 in double, against glibc's), amplified where a formula cancels. The
// budgets are set for that, before any device run (provisional until the first one, docs/gpu.md);
// every row must be within them. A branch decided by a last-bit difference (a sample rejected on
// one side only) would show as a row beyond the budget, counted and named, not forgiven.
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace glintlab::gpu {

struct ComparisonBudget {
  double relative;      // |gpu − cpu| / max(|cpu|, floor) at most this
  double floor_of_max;  // floor = this × the column's largest |cpu| (values near zero)
};
inline constexpr ComparisonBudget kFloatBudget{1e-4, 1e-6};
inline constexpr ComparisonBudget kDoubleBudget{1e-10, 1e-13};

struct ColumnComparison {
  std::string column;
  std::size_t rows_over = 0;  // rows beyond the budget
  double max_relative = 0;    // the largest relative difference (as the budget measures it)
  std::size_t worst_row = 0;  // where it is
  double cpu = 0, gpu = 0;    // the values there
};

struct RunComparison {
  std::string model, precision, function;  // function: eval, pdf or sample
  std::vector<ColumnComparison> columns;
  bool within_budget = true;
};

struct FolderComparison {
  std::string device, cuda_version;
  std::size_t rows = 0;
  std::vector<RunComparison> runs;
  // The Table 3 frames' pixels against the CPU benchmark's shade_pixel (double): model is the
  // cell's name, function "frame", one column "radiance".
  std::vector<RunComparison> frames;
  bool within_budget = true;
};

// A results folder that cannot be read: a missing or malformed file, a row or column count that
// does not match, a model or function this build does not know. The message names the file.
struct ResultsError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

FolderComparison compare_with_cpu(const std::filesystem::path& folder);

// A table of every run and column: the largest relative difference, rows over the budget.
std::string describe(const FolderComparison& comparison);

}  // namespace glintlab::gpu

// The Table 3 analogue through the model batches (experiments/bench/kemppinen2025_table3_frame.h)
// renders the pixels the scalar path renders (shade_pixel, the model's double templates): in
// double, every cell, three runs of pixels across the frame: bit for bit with the batches' scalar
// instantiation, and on the widest ISA within the Kemppinen batches' value budget (docs/simd.md
// "Equivalence budgets": 64 ε per evaluation, at most 2 % of rows outside, where a last-bit
// difference in sin/cos moves a point into another cell); the frame does not depend on the thread
// count; a radiance 0.1 % high is caught.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "experiments/bench/kemppinen2025_table3_frame.h"

namespace glintlab::kemppinen_table3 {
namespace {

constexpr std::size_t kRun = 256;
// Rows 40, 540 and 1000, from x = 600: the far, middle and near field of the 25° plane.
constexpr std::uint64_t kRunStarts[] = {40 * 1920 + 600, 540 * 1920 + 600, 1000 * 1920 + 600};

// Pixels shaded by the scalar path and by the batches (double, on `isa`).
struct Pixels {
  std::vector<double> scalar, batched;
};

Pixels render_runs(const Cell& c, simd::Isa isa) {
  Pixels p;
  for (std::uint64_t first : kRunStarts) {
    with_cell(c, [&](const auto& shade) {
      for (std::size_t i = 0; i < kRun; ++i) p.scalar.push_back(shade(first + i));
    });
    std::vector<double> b(kRun);
    render_pixels<double>(c, first, kRun, isa, b.data());
    p.batched.insert(p.batched.end(), b.begin(), b.end());
  }
  return p;
}

// The fraction of pixels beyond 2 × 64 ε of the scalar radiance (a sum of three non-negative
// terms, each within 64 ε of its own magnitude), or NaN where one of them is not finite.
double fraction_outside(const Pixels& p, const std::function<double(double)>& perturb) {
  std::size_t outside = 0;
  for (std::size_t i = 0; i < p.scalar.size(); ++i) {
    const double b = perturb(p.batched[i]);
    if (!std::isfinite(b) || !std::isfinite(p.scalar[i]))
      return std::numeric_limits<double>::quiet_NaN();
    if (std::abs(b - p.scalar[i]) > 128 * std::numeric_limits<double>::epsilon() * p.scalar[i])
      ++outside;
  }
  return double(outside) / double(p.scalar.size());
}

// The batches' scalar instantiation is the scalar path's arithmetic: the same bits.
TEST(Table3Frame, ScalarBatchesAreTheScalarPathBitForBit) {
  for (const Cell& c : cells()) {
    const Pixels p = render_runs(c, simd::Isa::kScalar);
    EXPECT_EQ(p.batched, p.scalar) << cell_name(c);
  }
}

TEST(Table3Frame, WidestIsaPixelsAreTheScalarPathsWithinTheBatchBudget) {
  const auto same = [](double v) { return v; };
  const auto high = [](double v) { return v * 1.001 + 1e-300; };
  for (const Cell& c : cells()) {
    const Pixels p = render_runs(c, simd::best_isa());
    double lit = 0;
    for (double s : p.scalar) lit += s > 0 ? 1 : 0;
    EXPECT_GT(lit, 0.4 * double(p.scalar.size())) << cell_name(c) << ": the runs see the lights";
    // Each of a pixel's three evaluations may be among the 2 % of rows outside the budget.
    EXPECT_LE(fraction_outside(p, same), 3 * 0.02) << cell_name(c);
    // The control: every radiance 0.1 % high is outside the budget.
    EXPECT_GT(fraction_outside(p, high), 0.5) << cell_name(c);
  }
}

TEST(Table3Frame, PixelsDoNotDependOnTheThreadCount) {
  const Cell c{true, 25, false, false};
  std::vector<float> one(4096), two(4096);
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    render_pixels<float>(c, 500 * 1920, one.size(), simd::best_isa(), one.data());
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    render_pixels<float>(c, 500 * 1920, two.size(), simd::best_isa(), two.data());
  }
  EXPECT_EQ(one, two);
}

}  // namespace
}  // namespace glintlab::kemppinen_table3

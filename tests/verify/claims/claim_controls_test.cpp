// The statistical eto checks give bit-identical results on 1 and 2 threads (the claims' controls at
// their probe sizes: ClaimProbes.*; the full quick-budget runs are in registry_test.cpp).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstdint>
#include <stdexcept>
#include <string>

#include "verify/check.h"

namespace glintlab::verify {
namespace {

const Check& find(const std::string& id) {
  for (const Check& c : registered_checks())
    if (c.id == id) return c;
  throw std::runtime_error("not registered: " + id);
}

// The statistical checks' calibration runs (their per-seed p-values) do not depend on the number
// of threads: counter RNG, fixed chunks merged in order.
TEST(ClaimControls, StatisticalResultsIndependentOfThreadCount) {
  for (const char* id : {"eto.unbiased", "eto.fewer-rejections"}) {
    const Check& c = find(id);
    ASSERT_TRUE(is_statistical(c)) << id;
    double one = 0, two = 0;
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
      one = c.calibration(check_seed(id, 12345));
    }
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
      two = c.calibration(check_seed(id, 12345));
    }
    EXPECT_EQ(one, two) << id;  // bit-identical
    EXPECT_GT(one, 0) << id;
    EXPECT_LE(one, 1) << id;
  }
}

}  // namespace
}  // namespace glintlab::verify

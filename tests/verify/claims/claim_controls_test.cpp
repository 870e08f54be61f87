// smooth.eval-pdf-consistency on a small input: its statistic passes for the correct input and
// rejects its negative control (eto.*'s claims at their probe sizes: ClaimProbes.*); the
// statistical eto checks give bit-identical results on 1 and 2 threads. (The full quick-budget
// runs are in registry_test.cpp.)
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstdint>
#include <stdexcept>
#include <string>

#include "verify/check.h"
#include "verify/claims/control_probes.h"
#include "verify/claims/sampler_table.h"

namespace glintlab::verify {
namespace {

void expect_probe(const ControlProbe& p, const std::string& what) {
  EXPECT_TRUE(p.correct_passes()) << what << ": correct input " << p.correct << " vs "
                                  << p.threshold;
  EXPECT_TRUE(p.control_rejected()) << what << ": control " << p.control << " vs " << p.threshold;
}

TEST(ClaimControls, EvalPdfConsistencyEverySampler) {
  for (std::size_t s = 0; s < sampler_table().size(); ++s)
    for (int control : {0, 1})
      expect_probe(probe_eval_pdf_consistency(s, control),
                   sampler_table()[s].name + " control " + std::to_string(control));
}

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

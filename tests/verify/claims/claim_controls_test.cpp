// The non-chi-square claims (smooth.eval-pdf-consistency, eto.*): on a small
// input each check's statistic passes for the correct input and rejects its negative control; a
// statistical check gives bit-identical results on 1 and 2 threads. (The full quick-budget runs
// are in registry_test.cpp.)
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

TEST(ClaimControls, EtoUnbiased) { expect_probe(probe_eto_unbiased(), "eto.unbiased"); }

TEST(ClaimControls, EtoBoundIsInfimum) {
  expect_probe(probe_eto_bound_is_infimum(), "eto.bound-is-infimum");
}

TEST(ClaimControls, EtoFewerRejections) {
  expect_probe(probe_eto_fewer_rejections(), "eto.fewer-rejections");
}

TEST(ClaimControls, EtoVarianceRough) {
  expect_probe(probe_eto_variance_rough(), "eto.variance-rough");
}

TEST(ClaimControls, EtoBackfacingStablePdf) {
  expect_probe(probe_eto_backfacing_stable_pdf(), "eto.backfacing-stable-pdf");
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

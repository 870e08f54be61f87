// The chi-square claims over the smooth samplers compute their expected counts through the batched
// pdfs (ChiSquareOptions::direction_pdf_rows: core/simd/batch.h eval_batch of the pdf kernel on
// simd::default_isa()): the rows are the case's own pdf (bit for bit on the scalar ISA, within a
// few ULPs on the widest), and the plans they give are the scalar pdf's plans within a stated
// budget, which a batch 2 % off in one block of lanes exceeds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "verify/claims/gof_family.h"

namespace glintlab::verify {
namespace {

using V3 = Vec3<double>;

// Runs f with GLINTLAB_ISA set to `isa` (the batched pdfs use simd::default_isa()).
template <class F>
void with_isa(const char* isa, F&& f) {
  const char* old = std::getenv("GLINTLAB_ISA");
  const std::string saved = old ? old : "";
  setenv("GLINTLAB_ISA", isa, 1);
  f();
  if (old)
    setenv("GLINTLAB_ISA", saved.c_str(), 1);
  else
    unsetenv("GLINTLAB_ISA");
}

GofSpec spec_of(const std::string& id) {
  return id == "eto.pdf-matches" ? eto_pdf_spec(Budget::kQuick)
                                 : smooth_sampler_spec(Budget::kQuick);
}

// Directions where a case's pdf lives and where it does not: the case's own samples (its lobe,
// edges, tails) and a uniform spiral over the sphere. 3001: not a multiple of any batch width.
std::vector<V3> probe_directions(const GofCase& c) {
  constexpr std::size_t kHalf = 1500;
  std::vector<V3> w(2 * kHalf + 1);
  c.direction_batch(29, 0, kHalf, w.data());
  const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
  for (std::size_t j = 0; j <= kHalf; ++j) {
    const double z = 1 - 2 * (double(j) + 0.5) / double(kHalf + 1), r = std::sqrt(1 - z * z);
    w[kHalf + j] = {r * std::cos(golden * double(j)), r * std::sin(golden * double(j)), z};
  }
  return w;
}

// f(case) for every case (configurations and controls' wrong cases) whose pdf has rows.
template <class F>
std::size_t for_each_rows_case(const GofSpec& spec, F&& f) {
  std::vector<const GofCase*> cases;
  for (const GofCase& c : spec.cases) cases.push_back(&c);
  for (const GofControl& control : spec.controls)
    for (const GofControlCase& cc : control.cases)
      if (cc.plan_of < 0) cases.push_back(&cc.wrong);
  std::size_t with_rows = 0;
  for (const GofCase* c : cases) {
    if (!c->options.direction_pdf_rows) continue;
    f(*c);
    ++with_rows;
  }
  return with_rows;
}

class BatchedPdfs : public testing::TestWithParam<const char*> {};

TEST_P(BatchedPdfs, ScalarIsaIsThePdfBitForBit) {
  with_isa("scalar", [] {
    const std::size_t n = for_each_rows_case(spec_of(GetParam()), [](const GofCase& c) {
      const std::vector<V3> w = probe_directions(c);
      std::vector<double> rows(w.size());
      c.options.direction_pdf_rows(w, rows);
      for (std::size_t j = 0; j < w.size(); ++j) {
        const double p = c.direction_pdf(w[j]);
        ASSERT_TRUE(p == rows[j] || (std::isnan(p) && std::isnan(rows[j])))
            << c.label << " direction " << j << ": " << p << " vs " << rows[j];
      }
    });
    EXPECT_GT(n, 0u);
  });
}

// The widest ISA: each value within 2^10 ε (relative, or absolute below the smallest normal
// density 1e-300) of the scalar pdf; the same value 2^-30 off is caught wherever the pdf is above
// that.
TEST_P(BatchedPdfs, WidestIsaIsThePdfWithinTheBatchBudget) {
  const double budget = 1024 * std::numeric_limits<double>::epsilon();
  for_each_rows_case(spec_of(GetParam()), [&](const GofCase& c) {
    const std::vector<V3> w = probe_directions(c);
    std::vector<double> rows(w.size());
    c.options.direction_pdf_rows(w, rows);
    std::size_t outside = 0, outside_shifted = 0, positive = 0;
    for (std::size_t j = 0; j < w.size(); ++j) {
      const double p = c.direction_pdf(w[j]);
      const double scale = std::max(std::abs(p), 1e-300);
      outside += !(std::abs(rows[j] - p) <= budget * scale);
      positive += p > 1e-300;
      if (p > 1e-300) outside_shifted += !(std::abs(rows[j] * (1 + std::ldexp(1.0, -30)) - p) <= budget * scale);
    }
    EXPECT_EQ(outside, 0u) << c.label;
    EXPECT_EQ(outside_shifted, positive) << c.label << ": the control";
  });
}

INSTANTIATE_TEST_SUITE_P(Claims, BatchedPdfs,
                         testing::Values("eto.pdf-matches", "smooth.sampler-matches-pdf"));

// The largest difference between two plans' expected counts, relative to the larger of the two
// bins' own quadrature error estimates and 1e-12 of the count: ≤ 1 means the plans agree to within
// what either cubature claims (a pdf a few ULPs off can flip a bisection, moving a count within
// its error estimate, never beyond). Bins and edges must match exactly in number.
double plan_difference(const ChiSquarePlan& a, const ChiSquarePlan& b) {
  if (a.grids.size() != b.grids.size()) return std::numeric_limits<double>::infinity();
  double worst = 0;
  for (std::size_t g = 0; g < a.grids.size(); ++g) {
    const BinGrid &x = a.grids[g], &y = b.grids[g];
    if (x.bins() != y.bins()) return std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < x.bins(); ++k) {
      const double allowed = std::max({x.error[k], y.error[k],
                                       1e-12 * std::max(std::abs(x.expected[k]), std::abs(y.expected[k])),
                                       1e-300});
      worst = std::max(worst, std::abs(x.expected[k] - y.expected[k]) / allowed);
    }
  }
  return worst;
}

// A few configurations of smooth.sampler-matches-pdf (a narrow anisotropic lobe, grazing and
// back-facing incidences, Walter's singular density) planned at 2·10^4 samples (coarse bins only)
// with the scalar pdf and with its batch on the widest ISA: within plan_difference's budget, and
// nearly all bins within 1e-12 of each other. A batch that is 2 % off in one block of 8 lanes of
// every call is caught by the same comparison.
TEST(BatchedPdfCubature, PlansMatchTheScalarPdfsAndAWrongBatchIsCaught) {
  const GofSpec spec = smooth_sampler_spec(Budget::kQuick);
  std::size_t checked = 0;
  for (const GofCase& c : spec.cases) {
    const bool wanted = c.label.find("heitz_vndf/ggx α=(0.02,0.2) θi=80°") == 0 ||
                        c.label.find("walter/beckmann α=(1,0.1) θi=45°") == 0 ||
                        c.label.find("bounded_vndf_listing1/ggx α=(0.3,0.3) θi=120°") == 0;
    if (!wanted) continue;
    ++checked;
    GofCase scalar = c;
    scalar.options.direction_pdf_rows = {};
    const ChiSquarePlan one = plan_gof_case(scalar, 20'000, 1e-3);
    const ChiSquarePlan rows = plan_gof_case(c, 20'000, 1e-3);
    ASSERT_FALSE(one.inconclusive) << c.label << ": " << one.reason;
    ASSERT_FALSE(rows.inconclusive) << c.label << ": " << rows.reason;
    EXPECT_LE(plan_difference(one, rows), 1.0) << c.label;
    std::size_t bins = 0, close = 0;
    for (std::size_t g = 0; g < one.grids.size(); ++g)
      for (std::size_t k = 0; k < one.grids[g].bins(); ++k, ++bins)
        close += std::abs(one.grids[g].expected[k] - rows.grids[g].expected[k]) <=
                 1e-12 * one.grids[g].expected[k];
    EXPECT_GE(close * 10, bins * 9) << c.label << ": " << close << " of " << bins << " within 1e-12";

    GofCase wrong = c;
    wrong.options.direction_pdf_rows = [f = c.options.direction_pdf_rows](
                                           std::span<const V3> w, std::span<double> out) {
      f(w, out);
      for (std::size_t k = 8; k < std::min<std::size_t>(16, out.size()); ++k) out[k] *= 1.02;
    };
    EXPECT_GT(plan_difference(one, plan_gof_case(wrong, 20'000, 1e-3)), 1.0) << c.label;
  }
  EXPECT_EQ(checked, 3u);
}

}  // namespace
}  // namespace glintlab::verify

// The Chermain part of adequacy.prediction-matches-measurement
// (verify/claims/adequacy/chermain_prediction.h): one row's smooth boundary and one dictionary's
// boundary measured against the construction's, each holding, and the same measurements rejecting
// the predictions moved by 1.25 (the claim's control).
#include "verify/claims/adequacy/chermain_prediction.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glintlab::verify::adequacy_claims {
namespace {

TEST(ChermainPrediction, BoundariesHoldAndMovedOnesAreRejected) {
  const adequacy::ChermainCell row = chermain_boundary_rows()[2];  // θ_i 60°, peak, flat
  ASSERT_EQ(row.theta_i_deg, 60);
  ASSERT_EQ(row.dh, 0);
  const ChermainSmoothRow s = measure_chermain_smooth_row(row, 4000, 11);
  EXPECT_NEAR(s.predicted_fit / s.measured, 1, 0.03);
  EXPECT_GT(s.p_value, 1e-3);
  EXPECT_LT(s.moved_p_value, 1e-4);
  const ChermainDictionaryRow d =
      measure_chermain_dictionary_row(row, ChermainLevel::kDict12, 4000, 13);
  EXPECT_TRUE(d.identical);
  EXPECT_GT(d.predicted, d.identical_facets);
  EXPECT_LT(d.predicted, 4 * d.identical_facets);
  EXPECT_GT(d.p_mean, 1e-3);
  EXPECT_GT(d.p_cv, 1e-3);
  EXPECT_LT(std::min(d.moved_p_mean, d.moved_p_cv), 1e-4);
}

}  // namespace
}  // namespace glintlab::verify::adequacy_claims

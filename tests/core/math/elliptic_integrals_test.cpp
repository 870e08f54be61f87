// Tests of the kernel elliptic integrals (Carlson duplication, DLMF 19.36) against Boost.Math, in
// double and float, including moduli near 1 where the complete integral K diverges.
#include "core/math/elliptic_integrals.h"

#include <gtest/gtest.h>

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>
#include <boost/math/special_functions/ellint_rd.hpp>
#include <boost/math/special_functions/ellint_rf.hpp>

namespace glintlab {
namespace {

TEST(EllipticIntegrals, MatchBoostInDoubleAndFloat) {
  for (double k : {0.0, 0.1, 0.5, 0.9, 0.999, 1 - 1e-9}) {
    // 1 − k² rounded: a relative error ε/(1 − k²) in k'², which K inherits halved.
    const double tol = 1e-14 + 1e-16 / (1 - k * k);
    EXPECT_NEAR(elliptic_k(k) / boost::math::ellint_1(k), 1.0, tol) << k;
    EXPECT_NEAR(elliptic_e(k) / boost::math::ellint_2(k), 1.0, tol) << k;
    if (float(k) < 1) {
      EXPECT_NEAR(double(elliptic_k(float(k))) / boost::math::ellint_1(double(float(k))), 1.0, 1e-5)
          << k;
    }
    for (double phi : {0.01, 0.7, 1.5, 1.5707963267948966}) {
      EXPECT_NEAR(elliptic_f(phi, k) / boost::math::ellint_1(k, phi), 1.0, tol) << k << " " << phi;
      EXPECT_NEAR(elliptic_e(phi, k) / boost::math::ellint_2(k, phi), 1.0, tol) << k << " " << phi;
    }
  }
  for (double x : {0.0, 1e-8, 0.3, 2.0})
    for (double y : {1e-6, 0.5, 7.0}) {
      EXPECT_NEAR(carlson_rf(x, y, 1.3) / boost::math::ellint_rf(x, y, 1.3), 1.0, 1e-14);
      EXPECT_NEAR(carlson_rd(x, y, 1.3) / boost::math::ellint_rd(x, y, 1.3), 1.0, 1e-14);
    }
}

}  // namespace
}  // namespace glintlab

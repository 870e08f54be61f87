// core/math/ops.h: the scalar min/max, written inline, give libm's fmin/fmax bits (called through
// a function pointer, so the compiler can neither fold nor commute the call) on every edge case (a
// NaN on either side or both, infinities, subnormals, zeros) and on random pairs, float and double,
// except two zeros of opposite signs: C leaves that result unspecified (GCC treats fmin/fmax as
// commutative), and the ops layer fixes it to the first operand, as the SIMD batches' min/max
// (core/simd/wide.h). Negative controls: the other tie rule fails the tie check, and the plain
// comparison (a NaN first operand comes through) differs from libm.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/math/ops.h"
#include "core/math/rng.h"

namespace glintlab {
namespace {

template <class S>
std::vector<S> edge_values() {
  using L = std::numeric_limits<S>;
  return {S(0),           -S(0),        S(1),          -S(1),         S(0.5),
          L::infinity(),  -L::infinity(), L::quiet_NaN(), -L::quiet_NaN(), L::denorm_min(),
          -L::denorm_min(), L::min(),    L::max(),      -L::max(),     L::epsilon()};
}

template <class S>
auto bits(S x) {
  if constexpr (sizeof(S) == 4) {
    return std::bit_cast<std::uint32_t>(x);
  } else {
    return std::bit_cast<std::uint64_t>(x);
  }
}

// How many pairs (edge values × edge values, then random pairs; not two zeros of opposite signs)
// where f(a, b) and g(a, b) differ in their bits, any NaN counting as equal to any NaN (the NaN's
// payload is not part of the rule).
template <class S, class F, class G>
int mismatches(F f, G g) {
  std::vector<S> v = edge_values<S>();
  for (std::uint64_t i = 0; i < 2000; ++i)
    v.push_back(S(counter_uniform<double>(0x6d696e6d6178ULL, i, 0) * 8.0 - 4.0));
  int bad = 0;
  for (S a : v) {
    for (S b : v) {
      if (a == S(0) && b == S(0) && std::signbit(a) != std::signbit(b)) continue;
      const S x = f(a, b), y = g(a, b);
      if (!(std::isnan(x) && std::isnan(y)) && bits(x) != bits(y)) ++bad;
    }
  }
  return bad;
}

// libm's fmin/fmax for S through volatile pointers: real calls, operands in order.
template <class S>
S libm_min(S a, S b) {
  if constexpr (sizeof(S) == 4) {
    float (*volatile f)(float, float) = ::fminf;
    return f(a, b);
  } else {
    double (*volatile f)(double, double) = ::fmin;
    return f(a, b);
  }
}
template <class S>
S libm_max(S a, S b) {
  if constexpr (sizeof(S) == 4) {
    float (*volatile f)(float, float) = ::fmaxf;
    return f(a, b);
  } else {
    double (*volatile f)(double, double) = ::fmax;
    return f(a, b);
  }
}

// Two zeros of opposite signs give the first operand, in both orders.
template <class S, class F>
bool first_of_two_zeros(F f) {
  return std::signbit(f(S(0), -S(0))) == false && std::signbit(f(-S(0), S(0))) == true;
}

template <class S>
void check_min_max() {
  EXPECT_EQ((mismatches<S>([](S a, S b) { return min(a, b); }, libm_min<S>)), 0);
  EXPECT_EQ((mismatches<S>([](S a, S b) { return max(a, b); }, libm_max<S>)), 0);
  EXPECT_TRUE(first_of_two_zeros<S>([](S a, S b) { return min(a, b); }));
  EXPECT_TRUE(first_of_two_zeros<S>([](S a, S b) { return max(a, b); }));
  // Negative controls.
  EXPECT_FALSE(
      first_of_two_zeros<S>([](S a, S b) { return (b >= a || (a != a && b == b)) ? b : a; }));
  EXPECT_GT((mismatches<S>([](S a, S b) { return b > a ? b : a; }, libm_max<S>)), 0);
}

TEST(ScalarMinMax, EqualsFminFmaxBitForBitFloat) { check_min_max<float>(); }
TEST(ScalarMinMax, EqualsFminFmaxBitForBitDouble) { check_min_max<double>(); }

}  // namespace
}  // namespace glintlab

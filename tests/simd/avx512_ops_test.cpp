// The ops layer op by op on every ISA this CPU has, against the scalar ops: where a batch kernel
// may differ from its scalar instantiation, and why. This is where xsimd 8.1's AVX-512 defects
// were found (core/simd/xsimd.h): unfused fma, neg as 0 − x; and the ordered != of its AVX and
// AVX-512 kernels (core/simd/wide.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/simd/wide.h"  // fast::kFastRsqrtMaxRel
#include "simd/ops_isa.h"
#include "simd/simd_test_util.h"

namespace glintlab::simd::test {
namespace {

const char* op_label(Op op) {
  static const char* const kNames[] = {
      "add",  "sub",   "mul",      "div",      "sqrt",   "fma",    "neg",        "abs",
      "min",  "max",   "floor",    "copysign", "sign_not_zero",   "less",       "less_equal",
      "greater",       "greater_equal",        "equal",  "not_equal",           "isfinite",
      "hash32 uniform", "binomial exact", "binomial exact (reference loop)",
      "exp",  "expm1", "log",      "log1p",    "erf",    "erfc",   "atan",       "acos",
      "acosh", "atan2", "sin",     "cos",      "tan",    "fast rsqrt",
      "unfused_fma (xsimd 8.1 AVX-512)",
      "0 - x (xsimd 8.1 AVX-512 neg)",         "ordered != (xsimd 8.1 AVX/AVX-512)"};
  static_assert(sizeof(kNames) / sizeof(kNames[0]) == kOpCount);
  return kNames[static_cast<int>(op)];
}

constexpr Op kCorrectlyRounded[] = {
    Op::kAdd,   Op::kSub,      Op::kMul,          Op::kDiv,  Op::kSqrt,      Op::kFma,
    Op::kNeg,   Op::kAbs,      Op::kMin,          Op::kMax,  Op::kFloor,     Op::kCopysign,
    Op::kSignNotZero, Op::kLess, Op::kLessEqual,  Op::kGreater, Op::kGreaterEqual, Op::kEqual,
    Op::kNotEqual, Op::kIsfinite, Op::kHash32Uniform};
// xsimd's algorithms, the same on AVX2 and AVX-512 once both have a fused fma.
constexpr Op kSameAlgorithm[] = {Op::kExp,  Op::kExpm1, Op::kLog,   Op::kLog1p, Op::kErf,
                                 Op::kErfc, Op::kAtan,  Op::kAcos,  Op::kAcosh, Op::kAtan2};
// xsimd's sin/cos/tan choose their argument reduction from all lanes of a batch at once
// (`all(x <= bound)`), so a lane's result depends on its neighbours and thus on the batch width.
constexpr Op kBatchDependent[] = {Op::kSin, Op::kCos, Op::kTan};

// FNV-1a of the check's name: the seed (never picked to pass).
constexpr std::uint64_t seed_of(const char* s) {
  std::uint64_t h = 14695981039346656037ull;
  for (; *s; ++s) h = (h ^ static_cast<unsigned char>(*s)) * 1099511628211ull;
  return h;
}

// Rows: every pair of special values (signed zeros, NaN, infinities, subnormals, ±1, ±0.5, large),
// then random values on [−3, 3] and log-uniform magnitudes 1e−30…1e30 of either sign; c cycles.
template <class S>
struct Rows {
  std::vector<S> a, b, c;
  std::size_t moderate_begin = 0, moderate_end = 0;  // the [−3, 3] block
};
template <class S>
Rows<S> make_rows() {
  const S inf = std::numeric_limits<S>::infinity(), nan = std::numeric_limits<S>::quiet_NaN();
  const S sub = std::numeric_limits<S>::denorm_min() * S(3);
  const S special[] = {S(0), S(-0.0), S(1), S(-1),   S(0.5), S(-0.5), inf,  -inf, nan,
                       sub,  -sub,    S(2), S(100), S(-100), S(1e30), S(-1e30), S(0.7), S(-3)};
  Rows<S> r;
  for (S x : special)
    for (S y : special) {
      r.a.push_back(x);
      r.b.push_back(y);
      r.c.push_back(special[(r.c.size() * 7) % std::size(special)]);
    }
  std::mt19937_64 rng(seed_of("simd.ops"));
  std::uniform_real_distribution<double> u(-3.0, 3.0), e(-30.0, 30.0);
  r.moderate_begin = r.a.size();
  for (int i = 0; i < 20000; ++i) {
    r.a.push_back(static_cast<S>(u(rng)));
    r.b.push_back(static_cast<S>(u(rng)));
    r.c.push_back(static_cast<S>(u(rng)));
  }
  r.moderate_end = r.a.size();
  for (int i = 0; i < 20000; ++i) {
    const auto mag = [&] { return static_cast<S>(std::pow(10.0, e(rng)) * (u(rng) < 0 ? -1 : 1)); };
    r.a.push_back(mag());
    r.b.push_back(mag());
    r.c.push_back(mag());
  }
  while (r.a.size() % 16 != 0) {
    r.a.push_back(S(1));
    r.b.push_back(S(1));
    r.c.push_back(S(1));
  }
  return r;
}

template <class S>
std::vector<S> run(const IsaOps& ops, Op op, const Rows<S>& r) {
  std::vector<S> out(r.a.size());
  if constexpr (std::is_same_v<S, float>)
    ops.f(op, r.a.data(), r.b.data(), r.c.data(), out.data(), out.size());
  else
    ops.d(op, r.a.data(), r.b.data(), r.c.data(), out.data(), out.size());
  return out;
}

template <class S>
bool same(S x, S y) {
  return (std::isnan(x) && std::isnan(y)) || std::memcmp(&x, &y, sizeof(S)) == 0;
}

// Rows where two outputs differ (bits; any NaN equals any NaN), with the first one shown.
template <class S>
struct Diff {
  std::size_t count = 0;
  std::string first;
};
template <class S>
Diff<S> diff(const Rows<S>& r, const std::vector<S>& x, const std::vector<S>& y,
             std::size_t begin = 0, std::size_t end = SIZE_MAX) {
  Diff<S> d;
  for (std::size_t i = begin; i < std::min(end, x.size()); ++i) {
    if (same(x[i], y[i])) continue;
    if (d.count++ == 0) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "row %zu: a=%.9g b=%.9g c=%.9g gives %.17g vs %.17g", i,
                    double(r.a[i]), double(r.b[i]), double(r.c[i]), double(x[i]), double(y[i]));
      d.first = buf;
    }
  }
  return d;
}

struct IsaEntry {
  Isa isa;
  IsaOps (*ops)();
};
constexpr IsaEntry kIsas[] = {
    {Isa::kSse42, isa_ops_sse42}, {Isa::kAvx2, isa_ops_avx2}, {Isa::kAvx512, isa_ops_avx512}};

template <class S>
const char* type_name() {
  return std::is_same_v<S, float> ? "float" : "double";
}

// Correctly rounded ops, comparisons and selects: bit for bit the scalar result on every ISA.
// SSE4.2 has no fma instruction; its emulation (core/simd/wide.h) is held to 1 ulp on [−3, 3].
template <class S>
void check_correctly_rounded() {
  const Rows<S> r = make_rows<S>();
  const IsaOps scalar = isa_ops_scalar();
  int compared = 0;
  for (const IsaEntry& e : kIsas) {
    if (!isa_supported(e.isa)) {
      std::printf("%s: this CPU lacks it, not compared\n", std::string(isa_name(e.isa)).c_str());
      continue;
    }
    for (Op op : kCorrectlyRounded) {
      const auto ref = run<S>(scalar, op, r), got = run<S>(e.ops(), op, r);
      if (op == Op::kFma && e.isa == Isa::kSse42) {
        double worst = 0;
        for (std::size_t i = r.moderate_begin; i < r.moderate_end; ++i)
          worst = std::max(worst, ulp_distance(ref[i], got[i]));
        EXPECT_LE(worst, 1.0) << "sse4.2 emulated fma, " << type_name<S>();
        continue;
      }
      const Diff<S> d = diff(r, ref, got);
      EXPECT_EQ(d.count, 0u) << isa_name(e.isa) << " " << type_name<S>() << " " << op_label(op)
                             << " differs from scalar on " << d.count << " of " << ref.size()
                             << " rows; first " << d.first;
      ++compared;
    }
  }
  std::printf("%s: %d (ISA, op) pairs bit-identical to scalar on %zu rows\n", type_name<S>(),
              compared, r.a.size());
}
TEST(SimdOps, FloatCorrectlyRoundedOpsEqualScalarOnEveryIsa) { check_correctly_rounded<float>(); }
TEST(SimdOps, DoubleCorrectlyRoundedOpsEqualScalarOnEveryIsa) {
  check_correctly_rounded<double>();
}

template <class S>
void check_libm_avx512_against_avx2() {
  if (!isa_supported(Isa::kAvx512) || !isa_supported(Isa::kAvx2)) {
    GTEST_SKIP() << "avx512: this CPU lacks it; xsimd's AVX-512 libm is compiled, not compared";
  }
  const Rows<S> r = make_rows<S>();
  const IsaOps scalar = isa_ops_scalar(), avx2 = isa_ops_avx2(), avx512 = isa_ops_avx512();
  for (Op op : kSameAlgorithm) {
    const Diff<S> d = diff(r, run<S>(avx2, op, r), run<S>(avx512, op, r));
    EXPECT_EQ(d.count, 0u) << type_name<S>() << " " << op_label(op) << ": AVX-512 differs from "
                           << "AVX2 on " << d.count << " rows; first " << d.first;
  }
  // Batch-dependent trig: both widths within the same distance of glibc on finite arguments.
  for (Op op : kBatchDependent) {
    const auto ref = run<S>(scalar, op, r);
    double worst[2] = {0, 0};
    std::size_t differing = 0;
    const auto a2 = run<S>(avx2, op, r), a5 = run<S>(avx512, op, r);
    for (std::size_t i = 0; i < ref.size(); ++i) {
      if (!std::isfinite(r.a[i]) || std::abs(double(r.a[i])) > 1e5) continue;
      worst[0] = std::max(worst[0], ulp_distance(ref[i], a2[i]));
      worst[1] = std::max(worst[1], ulp_distance(ref[i], a5[i]));
      differing += !same(a2[i], a5[i]);
    }
    std::printf("%s %s (|x| <= 1e5): max ulp from glibc AVX2 %.0f, AVX-512 %.0f; %zu rows differ "
                "between the two\n",
                type_name<S>(), op_label(op), worst[0], worst[1], differing);
    EXPECT_LE(worst[1], std::max(worst[0], 2.0)) << type_name<S>() << " " << op_label(op);
  }
}
TEST(SimdOps, FloatXsimdLibmOnAvx512EqualsAvx2) { check_libm_avx512_against_avx2<float>(); }
TEST(SimdOps, DoubleXsimdLibmOnAvx512EqualsAvx2) { check_libm_avx512_against_avx2<double>(); }

// The fast rsqrt within its documented bound on every ISA: the hardware estimates differ (12 bits
// on SSE/AVX, CPU-specific; 14 bits on AVX-512), so each is measured, over fast_math_test.cpp's
// range [1e-3, 1e3] at 4·10^6 evenly spaced points.
TEST(SimdOps, FastRsqrtWithinDocumentedBoundOnEveryIsa) {
  Rows<float> r;
  constexpr int kN = 4000000;
  for (int i = 0; i < kN; ++i) r.a.push_back(static_cast<float>(1e-3 + (1e3 - 1e-3) * i / kN));
  r.b = r.a;
  r.c = r.a;
  const auto rel_error = [&](const IsaOps& ops) {
    const auto got = run<float>(ops, Op::kFastRsqrt, r);
    double worst = 0;
    for (std::size_t i = 0; i < got.size(); ++i) {
      const double ref = 1.0 / std::sqrt(double(r.a[i]));
      worst = std::max(worst, std::fabs(double(got[i]) - ref) / ref);
    }
    return worst;
  };
  const double scalar = rel_error(isa_ops_scalar());
  std::printf("fast rsqrt scalar: max rel %.3g (bound %.3g)\n", scalar, fast::kFastRsqrtMaxRel);
  EXPECT_LE(scalar, fast::kFastRsqrtMaxRel);
  for (const IsaEntry& e : kIsas) {
    if (!isa_supported(e.isa)) continue;
    const double w = rel_error(e.ops());
    std::printf("fast rsqrt %s: max rel %.3g\n", std::string(isa_name(e.isa)).c_str(), w);
    EXPECT_LE(w, fast::kFastRsqrtMaxRel) << isa_name(e.isa);
  }
}

// The comparisons above must catch what xsimd 8.1 computes without glintlab's corrections: this
// is the evidence for each correction, and proof that the checks can fail.
template <class S>
void check_uncorrected_ops_are_caught() {
  const Rows<S> r = make_rows<S>();
  const IsaOps scalar = isa_ops_scalar();
  const struct {
    Op broken, correct;
    Isa isa;
  } kCases[] = {{Op::kUnfusedFma, Op::kFma, Isa::kAvx512},
                {Op::kNegAsZeroMinus, Op::kNeg, Isa::kAvx512},
                {Op::kXsimdNotEqual, Op::kNotEqual, Isa::kAvx512},
                {Op::kXsimdNotEqual, Op::kNotEqual, Isa::kAvx2}};
  int ran = 0;
  for (const auto& k : kCases) {
    if (!isa_supported(k.isa)) continue;
    const IsaOps ops = kIsas[static_cast<int>(k.isa) - 1].ops();
    const Diff<S> d = diff(r, run<S>(scalar, k.correct, r), run<S>(ops, k.broken, r));
    std::printf("%s %s %s: %zu rows differ from scalar %s; first %s\n", std::string(isa_name(k.isa)).c_str(),
                type_name<S>(), op_label(k.broken), d.count, op_label(k.correct), d.first.c_str());
    EXPECT_GT(d.count, 0u) << op_label(k.broken) << " was not told apart from "
                           << op_label(k.correct);
    ++ran;
  }
  if (ran == 0) GTEST_SKIP() << "avx2, avx512: this CPU lacks both; nothing to show";
  if (!isa_supported(Isa::kAvx512))
    std::printf("avx512: this CPU lacks it; its uncorrected ops are not shown here\n");
}
TEST(SimdOps, FloatUncorrectedXsimdOpsAreCaught) { check_uncorrected_ops_are_caught<float>(); }
TEST(SimdOps, DoubleUncorrectedXsimdOpsAreCaught) { check_uncorrected_ops_are_caught<double>(); }

}  // namespace
}  // namespace glintlab::simd::test

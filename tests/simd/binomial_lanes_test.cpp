// The exact binomial kernel (core/glints/binomial_kernel.h) on every ISA this CPU has, float and
// double batches, against the loop it was before (simd/binomial_reference.h): the same count bit
// for bit on rows where, in one batch, some lanes take the inversion and some BTRS, and of the
// BTRS lanes some are accepted by the squeeze on their first attempt and some by the logs or on a
// later attempt (so attempts that skip the logs and attempts that compute them both occur); and on
// rows most of which draw nothing, so that the drawing lanes of a float batch are packed into
// fewer double parts (binomial_exact_packed).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "core/glints/binomial_kernel.h"
#include "core/simd/batch.h"
#include "simd/ops_isa.h"

namespace glintlab::simd::test {
namespace {

template <class S>
struct Rows {
  std::vector<S> n, p, key;
};

// n log-uniform in [1, n_max] (integers), p log-uniform in [1e-7, 1] with a quarter mirrored to
// p > ½, keys 0, 1, …; a few rows of each edge (n = 0, p = 0, p = 1). `sparse`: also, in blocks
// of 16 rows, a fraction 1/4, 3/4 or 31/32 of the rows (block by block), at random, one of those
// edges (rows that draw nothing).
template <class S>
Rows<S> make_rows(double n_max, bool sparse = false) {
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Rows<S> r;
  for (int i = 0; i < 16384; ++i) {
    double n = std::floor(std::pow(n_max, u(rng)));
    double p = std::pow(10.0, -7 * u(rng));
    if (u(rng) < 0.25) p = 1 - p;
    if (i % 509 == 0) n = 0;
    if (i % 511 == 0) p = 0;
    if (i % 513 == 0) p = 1;
    const double dead = sparse ? std::array{0.25, 0.75, 31.0 / 32}[(i / 16) % 3] : 0.0;
    if (u(rng) < dead) {
      const double edge = u(rng);
      if (edge < 1.0 / 3)
        n = 0;
      else
        p = edge < 2.0 / 3 ? 0.0 : 1.0;
    }
    r.n.push_back(S(n));
    r.p.push_back(S(p));
    r.key.push_back(S(i));
  }
  return r;
}

// How BTRS's first attempt decides a row (the host's arithmetic of detail::binomial_btrs): the
// squeeze accepts, or it does not (the logs or a later attempt decide), or its candidate is out
// of range (a later attempt decides: where no lane of a batch was tested on the first attempt,
// the kernel computes the test's constants on a later one); not BTRS at all.
enum class FirstAttempt { kNotBtrs, kSqueeze, kLogsOrLater, kOutOfRange };
FirstAttempt first_attempt(double n, double p, std::uint32_t key) {
  if (n == 0 || !(p > 0) || p >= 1) return FirstAttempt::kNotBtrs;
  const double pp = p > 0.5 ? 1 - p : p;
  if (n * pp < 10) return FirstAttempt::kNotBtrs;
  const HashStream<double> stream{key};
  const double spq = std::sqrt(n * pp * (1 - pp)), b = 1.15 + 2.53 * spq;
  const double a = -0.0873 + 0.0248 * b + 0.01 * pp, c = n * pp + 0.5, vr = 0.92 - 4.2 / b;
  const double u = stream.uniform(0) - 0.5, v = stream.uniform(1), us = 0.5 - std::abs(u);
  const double k = std::floor((2 * a / us + b) * u + c);
  if (k < 0 || k > n) return FirstAttempt::kOutOfRange;
  return us >= 0.07 && v <= vr ? FirstAttempt::kSqueeze : FirstAttempt::kLogsOrLater;
}

template <class S>
std::vector<S> run(const IsaOps& ops, Op op, const Rows<S>& r) {
  std::vector<S> out(r.n.size());
  if constexpr (std::is_same_v<S, float>)
    ops.f(op, r.n.data(), r.p.data(), r.key.data(), out.data(), out.size());
  else
    ops.d(op, r.n.data(), r.p.data(), r.key.data(), out.data(), out.size());
  return out;
}

struct IsaEntry {
  Isa isa;
  const char* name;
  IsaOps (*ops)();
};
constexpr IsaEntry kIsas[] = {{Isa::kScalar, "scalar", isa_ops_scalar},
                              {Isa::kSse42, "sse4.2", isa_ops_sse42},
                              {Isa::kAvx2, "avx2", isa_ops_avx2},
                              {Isa::kAvx512, "avx512", isa_ops_avx512}};

// Every ISA this CPU has: the kernel's counts bit for bit those of the reference loop.
template <class S>
void expect_equal_on_every_isa(const Rows<S>& r) {
  for (const IsaEntry& e : kIsas) {
    if (!isa_supported(e.isa)) {
      std::printf("%s: this CPU lacks it, not compared\n", e.name);
      continue;
    }
    const IsaOps ops = e.ops();
    const std::vector<S> got = run<S>(ops, Op::kBinomialExact, r);
    const std::vector<S> want = run<S>(ops, Op::kBinomialExactReference, r);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < got.size(); ++i) {
      if (std::memcmp(&got[i], &want[i], sizeof(S)) == 0) continue;
      if (differ++ == 0)
        ADD_FAILURE() << e.name << ": n=" << r.n[i] << " p=" << r.p[i] << " key=" << r.key[i]
                      << " gives " << got[i] << ", the reference loop " << want[i];
    }
    EXPECT_EQ(differ, 0u) << e.name << ": rows that differ from the reference loop";
  }
}

template <class S>
void expect_counts_equal_reference(double n_max) {
  const Rows<S> r = make_rows<S>(n_max);
  std::size_t squeeze = 0, logs = 0, out_of_range = 0, mixed_groups = 0, late_test_groups = 0;
  // Groups of 8 rows (a double batch of AVX-512, two of AVX2) holding both kinds of BTRS lane.
  for (std::size_t g = 0; g + 8 <= r.n.size(); g += 8) {
    bool has[4] = {false, false, false, false};
    for (std::size_t i = g; i < g + 8; ++i) {
      const FirstAttempt f =
          first_attempt(double(r.n[i]), double(r.p[i]), std::uint32_t(r.key[i]));
      has[int(f)] = true;
      squeeze += f == FirstAttempt::kSqueeze;
      logs += f == FirstAttempt::kLogsOrLater || f == FirstAttempt::kOutOfRange;
      out_of_range += f == FirstAttempt::kOutOfRange;
    }
    mixed_groups += has[int(FirstAttempt::kSqueeze)] &&
                    (has[int(FirstAttempt::kLogsOrLater)] || has[int(FirstAttempt::kOutOfRange)]);
    // No lane tested on the first attempt, one still drawing: an AVX-512 double part whose
    // test constants, if needed, come on a later attempt.
    late_test_groups +=
        has[int(FirstAttempt::kOutOfRange)] && !has[int(FirstAttempt::kLogsOrLater)];
  }
  std::printf("%s rows: %zu BTRS rows squeezed on the first attempt, %zu not (%zu out of range); "
              "%zu of %zu groups of 8 hold both, %zu none tested first\n",
              std::is_same_v<S, float> ? "float" : "double", squeeze, logs, out_of_range,
              mixed_groups, r.n.size() / 8, late_test_groups);
  EXPECT_GT(squeeze, r.n.size() / 10);
  EXPECT_GT(logs, r.n.size() / 50);
  EXPECT_GT(mixed_groups, r.n.size() / 8 / 4);
  EXPECT_GT(late_test_groups, 0u);
  expect_equal_on_every_isa(r);
}

// Rows most of which draw nothing, so that the float batches hold few drawing lanes (packed into
// fewer double parts: binomial_exact_packed), sometimes none and sometimes more than one part's.
template <class S>
void expect_sparse_counts_equal_reference(double n_max) {
  const Rows<S> r = make_rows<S>(n_max, /*sparse=*/true);
  // Groups of 16 (an AVX-512 float batch) and 8 (AVX2) by their drawing lanes: none, at most a
  // double part's (8; 4), more.
  std::size_t groups16[3] = {0, 0, 0}, groups8[3] = {0, 0, 0};
  for (std::size_t g = 0; g + 16 <= r.n.size(); g += 16) {
    std::size_t live[2] = {0, 0};
    for (std::size_t i = g; i < g + 16; ++i)
      live[(i - g) / 8] += r.n[i] != 0 && r.p[i] > 0 && r.p[i] < 1;
    const std::size_t all = live[0] + live[1];
    ++groups16[all == 0 ? 0 : all <= 8 ? 1 : 2];
    for (std::size_t h : live) ++groups8[h == 0 ? 0 : h <= 4 ? 1 : 2];
  }
  std::printf("groups of 16 with no / 1-8 / more drawing lanes: %zu %zu %zu; of 8 (0 / 1-4 / "
              "more): %zu %zu %zu\n",
              groups16[0], groups16[1], groups16[2], groups8[0], groups8[1], groups8[2]);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_GT(groups16[k], 0u);
    EXPECT_GT(groups8[k], 0u);
  }
  expect_equal_on_every_isa(r);
}

TEST(BinomialExactLanes, FloatCountsEqualTheReferenceLoopOnEveryIsa) {
  expect_counts_equal_reference<float>(1e7);  // below 2^24: integers exact in float
}
TEST(BinomialExactLanes, DoubleCountsEqualTheReferenceLoopOnEveryIsa) {
  expect_counts_equal_reference<double>(1e12);
}
TEST(BinomialExactLanes, FloatCountsWithFewDrawingLanesEqualTheReferenceLoopOnEveryIsa) {
  expect_sparse_counts_equal_reference<float>(1e7);
}

}  // namespace
}  // namespace glintlab::simd::test

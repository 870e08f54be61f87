// SIMD equivalence of the Kemppinen et al. 2025 models (kemppinen_ggx, kemppinen_beckmann): eval
// (D★^f of Eq. 11 by Algorithm 1, the marginal pdf of Algorithm 2) and sample (Algorithm 2)
// through the batch API on every ISA this CPU has, float and double, against the scalar
// instantiation, with stated budgets; perturbed batch kernels that must fail them.
#define GLINTLAB_SIMD_TU kemppinen_test
#include "core/simd/instantiate.h"
// (it gives this test the model driver on Wide<float>, for the perturbed controls)

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/math/rng.h"
#include "core/model_list.h"
#include "core/model_registry.h"
#include "core/simd/inputs.h"
#include "core/simd/model_batch.h"
#include "tests/simd/model_rows.h"
#include "tests/simd/simd_test_util.h"

namespace glintlab::simd::test {
namespace {

constexpr Isa kBatchIsas[] = {Isa::kSse42, Isa::kAvx2, Isa::kAvx512};
constexpr std::size_t kRowsPerSet = 512;  // query rows per parameter vector

// Rows per k. Full (the DISABLED_ test, run with --gtest_also_run_disabled_tests): 10^6 for
// k = 1 and 4, 16384 for k = 9, 8192 for k = 16 (those visit 2·81 and 2·256 points per eval and
// up to 2·9·81 and 2·16·256 candidates per pdf). ctest: 2^16, 2^15, 1024 and 512 rows, to stay
// within its time budget.
std::size_t rows_for_side(int side, bool full) {
  switch (side) {
    case 1:
      return full ? 1000000 : 1 << 16;
    case 2:
      return full ? 1000000 : 1 << 15;
    case 3:
      return full ? 16384 : 1024;
    default:
      return full ? 8192 : 512;
  }
}

// The budgets. Value outputs in machine epsilons of |batch − scalar| / (|scalar| + scale) (see
// compare); wo components (bounded by 1) in absolute machine epsilons; the rejection flag by the
// fraction of rows where it differs. Where batch and scalar take different discrete choices (a
// cell boundary of the block start floor(x·2^l − (n−1)/2), the reservoir's running-sum
// comparison, the level draw u < λ − ⌊λ⌋, the truncated Gaussian landing on U_Ω's rim), the
// output jumps: such rows may exceed the budgets on at most outlier_fraction of the rows.
// Sources of the errors: xsimd's exp (kemppinen2025::normal2), log (λ), erf (compensation, lobe
// masses), sin/cos (Alg. 2 line 2) and, for Beckmann, the map T's exp/erf, against glibc, a few
// ulps each; sums of up to 2k² lobes keep them relative, but the compensation max(∫_□N − ∫_B N, 0)
// cancels when B(k) holds the lobe (hence D★^f and the value are measured against a scale), and the
// lobe masses ∫_B N_j cancel for lobes far outside B (erf(b) − erf(a), both near ±1), so Σw★ and
// the pdf of a few rows are ill-conditioned in the scalar code itself. At high levels the angular
// cells are 2^−20 wide, 1–16 float ulps of x_a: a few-ulp difference of x_a (Alg. 2 line 2's
// sin/cos, Beckmann's T) changes the block, hence the sample and its flag. Measured on this
// machine (SSE4.2 and AVX2, 2^16 rows, k = 1…16, float / double): value, D★^f, λ ≤ 17 / 20 eps
// for GGX, Beckmann 99.9 % ≤ 1.2 / 5 eps (the rest: block flips through T); pdf 99 % ≤ 15 / 155
// eps; wo 99.99 % ≤ 85 / 250 eps; flags ≤ 0.30 % / 0.10 % of the rows.
struct KemppinenBudget {
  double value_eps;         // value, D★^f, λ: |Δ| / (|scalar| + scale), machine epsilons
  double pdf_eps;           // the eval's and the sample's pdf, relative, machine epsilons
  double wo_eps;            // sampled wo components, absolute, machine epsilons
  double outlier_fraction;  // rows beyond any of the above (discrete choice flips)
  double flag_fraction;     // rows whose rejection flag differs
};
KemppinenBudget kemppinen_budget(bool dbl) {
  if (dbl) return {64, 4096, 4096, 0.02, 0.005};
  return {64, 1024, 1024, 0.02, 0.01};
}

// One case: model, k, rows (sets of kRowsPerSet with one parameter vector each).
using Case = RowsCase;

// Parameter vector s: the choice parameters from the bits of s (every combination of blending,
// erf, normalization, colours and pdf appears every 32 sets), the real ones log-/uniform over
// their ranges, the roughness from the edge-case generator (α in [1e-3, 2], anisotropy to
// 1:1000). Footprints per row: 10 % zero, 5 % beyond the last level (λ clamped to 20), else a
// random Jacobian whose filter spans 2^−8 … 2^21 level-0 cells; uv in [−4, 4]².
Case make_case(const ModelEntry& m, int side, std::size_t n, std::uint64_t seed) {
  using D = Domain;
  const std::vector<int> domains = {int(D::kAlphaX), int(D::kAlphaY), int(D::kWiX), int(D::kWiY),
                                    int(D::kWiZ),    int(D::kWoX),    int(D::kWoY), int(D::kWoZ),
                                    int(D::kU1),     int(D::kU2)};
  const auto in = make_inputs(domains, n, seed);
  Case k;
  k.n = n;
  const std::size_t sets = (n + kRowsPerSet - 1) / kRowsPerSet;
  for (std::size_t s = 0; s < sets; ++s) {
    std::vector<double> v(m.params.size());
    for (std::size_t j = 0; j < m.params.size(); ++j) v[j] = m.params[j].default_value;
    const auto u = [&](std::uint64_t dim) { return row_uniform(seed, s, dim); };
    // Both Kemppinen models share one parameter list (detail::KemppinenModel).
    using P = KemppinenGGX;
    v[param_index<P>("alpha_x")] = in[0][s * kRowsPerSet];
    v[param_index<P>("alpha_y")] = in[1][s * kRowsPerSet];
    v[param_index<P>("density")] = log_uniform(1, 1e7, u(0));
    v[param_index<P>("microroughness")] = log_uniform(1e-4, 1, u(1));
    v[param_index<P>("anisotropy")] = log_uniform(0.05, 20, u(2));
    v[param_index<P>("filter")] = 0.05 + 3.95 * u(3);
    v[param_index<P>("k")] = double(side - 1);
    constexpr std::size_t kChoices[] = {param_index<P>("blending"), param_index<P>("erf"),
                                        param_index<P>("normalization"), param_index<P>("colors"),
                                        param_index<P>("pdf")};
    for (std::size_t b = 0; b < std::size(kChoices); ++b) v[kChoices[b]] = double((s >> b) & 1);
    v[param_index<P>("seed")] = double(s % 1000);
    k.params.push_back(v);
  }
  k.query.assign(kQueryColumns.size(), std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const std::vector<double>& v = k.params[i / kRowsPerSet];
    const auto u = [&](std::uint64_t dim) { return row_uniform(seed ^ 0x66707274ULL, i, dim); };
    const double sel = u(0);
    const double cells = sel < 0.1 ? 0 : sel < 0.15 ? 0x1p23 : std::exp2(-8 + 29 * u(1));
    const double d = cells / std::sqrt(v[param_index<KemppinenGGX>("density")]) /
                     v[param_index<KemppinenGGX>("filter")];
    fill_footprint_row(k.query, i, d, u, in);
  }
  k.u1 = in[8];
  k.u2 = in[9];
  return k;
}

// The row drivers of tests/simd/model_rows.h, one parameter vector per kRowsPerSet rows.
template <class S>
using Outputs = RowOutputs<S>;

template <class S>
Outputs<S> run_batch(const ModelEntry& m, const Case& k, Isa isa) {
  return run_rows_batch<S>(m, k, kRowsPerSet, isa);
}

// The model driver of core/simd/instantiate.h on W, called directly (perturbed models).
template <class M, class W, class S>
Outputs<S> run_driver(const ModelEntry& m, const Case& k) {
  return run_rows_driver<M, W, S>(m, k, kRowsPerSet);
}

// Maxima over the rows within the budget, and the rows outside it.
struct Measured {
  double value_eps = 0, pdf_eps = 0, wo_eps = 0;
  double outlier_fraction = 0, flag_fraction = 0;
  std::string summary(const std::string& what) const {
    char b[320];
    std::snprintf(b, sizeof b,
                  "%s: value/D/lambda %.3g eps, pdf %.3g eps, wo %.3g eps (rows within budget); "
                  "outliers %.3g, flags %.3g",
                  what.c_str(), value_eps, pdf_eps, wo_eps, outlier_fraction, flag_fraction);
    return b;
  }
  bool within(const KemppinenBudget& b) const {
    return value_eps <= b.value_eps && pdf_eps <= b.pdf_eps && wo_eps <= b.wo_eps &&
           outlier_fraction <= b.outlier_fraction && flag_fraction <= b.flag_fraction;
  }
};

// Compares batch outputs `got` with the scalar `ref` of case k, row by row: eval value (column
// 0, scale G2·2D/(4 ωi·n), the BRDF of the smooth lobe), D★^f (2, scale 2D: the compensation's
// erf differences cancel down to that absolute level), λ (6, scale 1), pdf (1) and the sample's
// pdf (relative); sample wo (0–2, absolute) and the flag (5). A row beyond any budget is an
// outlier.
template <class S>
Measured compare(const Case& k, const Outputs<S>& ref, const Outputs<S>& got,
                 const KemppinenBudget& b) {
  Measured r;
  const S eps = std::numeric_limits<S>::epsilon();
  const std::size_t n = ref.eval[0].size();
  std::size_t outliers = 0, flags = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d_smooth = 2 * std::abs(double(ref.eval[5][i]));
    const double wi_z = std::max(k.query[query_column_index("wi_z")][i], 1e-300);
    const double brdf_scale = std::abs(double(ref.eval[14][i])) * d_smooth / (4 * wi_z);
    double v = scaled_eps(got.eval[0][i], ref.eval[0][i], brdf_scale);
    v = std::max(v, scaled_eps(got.eval[2][i], ref.eval[2][i], d_smooth));
    v = std::max(v, scaled_eps(got.eval[6][i], ref.eval[6][i], 1.0));
    double p = scaled_eps(got.eval[1][i], ref.eval[1][i], 0.0);
    double w = 0;
    const bool rej_ref = ref.sample[5][i] != 0, rej = got.sample[5][i] != 0;
    if (rej != rej_ref) {
      ++flags;
    } else if (!rej) {
      for (std::size_t c = 0; c < 3; ++c)
        w = std::max(w, double(std::abs(got.sample[c][i] - ref.sample[c][i]) / eps));
      p = std::max(p, scaled_eps(got.sample[3][i], ref.sample[3][i], 0.0));
    }
    if (v > b.value_eps || p > b.pdf_eps || w > b.wo_eps) {
      ++outliers;
      continue;
    }
    r.value_eps = std::max(r.value_eps, v);
    r.pdf_eps = std::max(r.pdf_eps, p);
    r.wo_eps = std::max(r.wo_eps, w);
  }
  r.outlier_fraction = double(outliers) / double(n);
  r.flag_fraction = double(flags) / double(n);
  return r;
}

// The scalar ISA of the batch API is M's own scalar instantiation: spot-check bit equality.
template <class M, class S>
std::size_t scalar_mismatches(const Case& k, const Outputs<S>& ref) {
  std::size_t bad = 0;
  for (std::size_t i = 0; i < k.n; i += 997) {
    const auto p = M::template params<S>(k.params[i / kRowsPerSet]);
    const ModelQuery<S> q = row_query<S>(k, i);
    const auto e = M::template eval<S>(p, q);
    bad += ulp_distance(e.value, ref.eval[0][i]) != 0 || ulp_distance(e.pdf, ref.eval[1][i]) != 0;
    const ModelSample<S> s = M::template sample<S>(p, q, Vec2<S>{S(k.u1[i]), S(k.u2[i])});
    bad += ulp_distance(s.wo.x, ref.sample[0][i]) != 0 ||
           ulp_distance(s.pdf, ref.sample[3][i]) != 0 ||
           (static_cast<bool>(s.rejected) ? 1 : 0) != (ref.sample[5][i] != 0 ? 1 : 0);
  }
  return bad;
}

template <class M, class S>
void check_model(int side, bool full) {
  const ModelEntry& m = find_model(M::kName);
  ASSERT_TRUE(is_batched(m)) << m.name;
  const Case k = make_case(m, side, rows_for_side(side, full), hash_string(M::kName.data()) + side);
  const KemppinenBudget b = kemppinen_budget(sizeof(S) == 8);
  const Outputs<S> ref = run_batch<S>(m, k, Isa::kScalar);
  EXPECT_EQ((scalar_mismatches<M, S>(k, ref)), 0u) << m.name;
  int ran = 0;
  for (Isa isa : kBatchIsas) {
    if (!isa_supported(isa)) continue;
    const Measured r = compare(k, ref, run_batch<S>(m, k, isa), b);
    const std::string what = std::string(m.name) + " k=" + std::to_string(side * side) + " " +
                             std::string(isa_name(isa)) + (sizeof(S) == 8 ? " double" : " float") +
                             " (" + std::to_string(k.n) + " rows)";
    std::printf("%s\n", r.summary(what).c_str());
    EXPECT_TRUE(r.within(b)) << r.summary(what) << "; budget " << b.value_eps << " / " << b.pdf_eps
                             << " eps, " << b.wo_eps << " eps, outliers " << b.outlier_fraction
                             << ", flags " << b.flag_fraction;
    ++ran;
  }
  EXPECT_GT(ran, 0) << "no SIMD ISA available: nothing compared";
}

TEST(SimdKemppinenEquivalence, GgxFloat) {
  for (int side : {1, 2, 3, 4}) check_model<KemppinenGGX, float>(side, false);
}
TEST(SimdKemppinenEquivalence, GgxDouble) {
  for (int side : {1, 2, 3, 4}) check_model<KemppinenGGX, double>(side, false);
}
TEST(SimdKemppinenEquivalence, BeckmannFloat) {
  for (int side : {1, 2, 3, 4}) check_model<KemppinenBeckmann, float>(side, false);
}
TEST(SimdKemppinenEquivalence, BeckmannDouble) {
  for (int side : {1, 2, 3, 4}) check_model<KemppinenBeckmann, double>(side, false);
}
// The full counts (10^6 rows for k = 1 and 4): minutes, so outside ctest.
TEST(SimdKemppinenEquivalenceFull, DISABLED_Everything) {
  for (int side : {1, 2, 3, 4}) {
    check_model<KemppinenGGX, float>(side, true);
    check_model<KemppinenGGX, double>(side, true);
    check_model<KemppinenBeckmann, float>(side, true);
    check_model<KemppinenBeckmann, double>(side, true);
  }
}

// ---- Negative controls: perturbed batch kernels must fail the budgets -------------------------

// D★^f and the value one part in 2^12 high on every lane (2048 float eps; the value budget of
// 64 eps is relative to |D★^f| + 2D, so rows with D★^f ≳ D/16 see it), the kind of error a wrong
// constant in the roulette or the normalisation gives.
struct PerturbedEval : KemppinenGGX {
  template <class T>
  static ModelEval<T, kIntermediates.size()> eval(const Params<T>& p, const ModelQuery<T>& q) {
    auto r = KemppinenGGX::eval<T>(p, q);
    r.value = r.value * T(1.0 + 0x1p-12);
    r.intermediates[0] = r.intermediates[0] * T(1.0 + 0x1p-12);
    return r;
  }
};
// The sampled wo.x shifted by 2^−12 (2048 float eps: twice the wo budget), as a lobe centre or a
// truncation bound off by a fraction of a level-12 cell would move it.
struct PerturbedSample : KemppinenGGX {
  template <class T>
  static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    ModelSample<T> s = KemppinenGGX::sample<T>(p, q, u);
    s.wo.x = s.wo.x + T(0x1p-12);
    return s;
  }
};

const Case& control_case() {
  static const Case k = make_case(find_model("kemppinen_ggx"), 1, 1 << 15, 0x6e6567ULL);
  return k;
}
const Outputs<float>& control_ref() {
  static const Outputs<float> r =
      run_batch<float>(find_model("kemppinen_ggx"), control_case(), Isa::kScalar);
  return r;
}
using LocalWide = Wide<float, ExactMath>;

TEST(SimdKemppinenNegativeControl, UnperturbedLocalDriverPasses) {
  const ModelEntry& m = find_model("kemppinen_ggx");
  const Measured r = compare(control_case(), control_ref(),
                             run_driver<KemppinenGGX, LocalWide, float>(m, control_case()),
                             kemppinen_budget(false));
  EXPECT_TRUE(r.within(kemppinen_budget(false))) << r.summary("local");
  EXPECT_EQ(r.value_eps + r.pdf_eps + r.wo_eps + r.outlier_fraction + r.flag_fraction, 0.0)
      << r.summary("local");  // one lane of exact math: the scalar code
}

TEST(SimdKemppinenNegativeControl, PerturbedEvalFailsBudget) {
  const ModelEntry& m = find_model("kemppinen_ggx");
  const Measured r = compare(control_case(), control_ref(),
                             run_driver<PerturbedEval, LocalWide, float>(m, control_case()),
                             kemppinen_budget(false));
  std::printf("%s\n", r.summary("perturbed eval").c_str());
  EXPECT_GT(r.outlier_fraction, 0.1);
  EXPECT_FALSE(r.within(kemppinen_budget(false))) << r.summary("perturbed eval");
}

TEST(SimdKemppinenNegativeControl, PerturbedSampleFailsBudget) {
  const ModelEntry& m = find_model("kemppinen_ggx");
  const Measured r = compare(control_case(), control_ref(),
                             run_driver<PerturbedSample, LocalWide, float>(m, control_case()),
                             kemppinen_budget(false));
  std::printf("%s\n", r.summary("perturbed sample").c_str());
  EXPECT_GT(r.outlier_fraction, 0.1);
  EXPECT_FALSE(r.within(kemppinen_budget(false))) << r.summary("perturbed sample");
}

}  // namespace
}  // namespace glintlab::simd::test

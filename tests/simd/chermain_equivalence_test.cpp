// SIMD equivalence of the Chermain et al. 2020/2021 glinty patch-SDF model `chermain` (2021 Eq.
// 1–6, 9–21): eval (value, pdf and every intermediate) and sample through the batch API on every
// ISA this CPU has, on Wide<double> (the model is double-only), against the scalar double
// instantiation, with stated budgets, over footprints that span the LOD range; perturbed batch
// kernels that must fail them.
#define GLINTLAB_SIMD_TU chermain_test
#include "core/simd/instantiate.h"
// (it gives this test the model driver on this TU's baseline batch, for the controls)

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/glints/chermain.h"
#include "core/math/rng.h"
#include "core/model_registry.h"
#include "core/simd/inputs.h"
#include "core/simd/model_batch.h"
#include "tests/simd/model_rows.h"
#include "tests/simd/simd_test_util.h"

namespace glintlab::simd::test {
namespace {

constexpr Isa kBatchIsas[] = {Isa::kSse42, Isa::kAvx2, Isa::kAvx512};
constexpr std::size_t kRowsPerSet = 512;
constexpr std::size_t kCtestRows = std::size_t(1) << 18;
constexpr std::size_t kFullRows = 1000000;

// The budgets, in machine epsilons of |batch − scalar| / (|scalar| + scale) (see compare). Sources
// of the differences: xsimd's sin/cos (the cell rotation θ, the sampler's φ), exp (the smooth
// fallback, the pdf) and log (the sampler) against glibc, a few ulp each, and on SSE4.2 the
// emulated fma of dot(). log2 (the LOD, textureGrad's λ) is std::log2 per lane, and every texel
// index, the cell hash, the marginal indices, the dictionary level and the wrap are exact integers
// in both, so lod, dict_level, kernel_width and G2 are bit-identical. The rotated slope enters a
// piecewise-linear table, so its error stays relative to the SDF's scale; a discrete choice (the
// probe count ⌈P_max/P_min⌉ of textureGrad, which a one-ulp change of the rotated derivatives can
// move across an integer) may make a row jump: such rows are allowed on outlier_fraction of them.
// Measured maxima (2^18 rows, SSE4.2 and AVX2 alike; this CPU has no AVX-512): P22, D, brdf,
// value 29.8, pdf 2.75, mip_lambda 24, lod / dict_level / kernel_width / G2 0; sample wo 6, pdf 3,
// weight 49 eps; rows over budget 0, flags 0.
struct ChermainBudget {
  double sdf_eps;           // P22, D, brdf, value: against the smooth limit's peak (see compare)
  double pdf_eps;           // eval pdf and the sample's pdf (smooth Beckmann), relative
  double unit_eps;          // lod, mip_lambda (scale 1), G2 (in [0, 1]), kernel_width (relative)
  double wo_eps;            // sampled wo components, absolute
  double weight_eps;        // sample weight = value/pdf, against the value's scale / pdf
  double outlier_fraction;  // rows beyond any of the above (probe count flips)
  double flag_fraction;     // rows whose rejection flag differs
};
constexpr ChermainBudget kBudget{256, 16, 64, 32, 512, 1e-4, 1e-4};

// One case: one parameter vector per kRowsPerSet rows.
using Case = RowsCase;

// Parameter vector s: α from the edge-case generator (α in [1e-3, 2], anisotropy to 1:1000), ρ = 0
// on every fourth set, else uniform in (−0.99, 0.99); density log-uniform in [1, 1e12]; the GGAA
// kernel s mod 3 (off, half_slope, projected_half); s_K in [0.05, 4]; derivatives dh of length
// 10^U(−5, 1) in random directions (10 % zero, 10 % only d/dy: the P_min = 0 rule), so the probe
// count runs from 1 to 16 and λ over the pyramid; seed s mod 1000. Rows: 4 % zero footprint (LOD
// clamped to −20), 4 % a footprint of 2^45 (clamped to 39), else a footprint whose LOD puts the
// cell's dictionary level k = ⌊l + ½ log2 density⌋ uniformly in [−1.5, 17.5] (every level 0 … 15,
// the clamp at 0 and the smooth fallback k ≥ 16, and the blend between two LODs); Jacobian
// stretched 1:5 to 5:1 and sheared; uv in [−4, 4]²; ω_i, ω_o and the uniforms from the edge-case
// generator (grazing, back-facing, h_z ≤ 0, u at 0 and 1 − 2^−24).
Case make_case(std::size_t n, std::uint64_t seed) {
  using D = Domain;
  const std::vector<int> domains = {int(D::kAlphaX), int(D::kAlphaY), int(D::kWiX), int(D::kWiY),
                                    int(D::kWiZ),    int(D::kWoX),    int(D::kWoY), int(D::kWoZ),
                                    int(D::kU1),     int(D::kU2)};
  const auto in = make_inputs(domains, n, seed);
  Case k;
  k.n = n;
  const std::size_t sets = (n + kRowsPerSet - 1) / kRowsPerSet;
  for (std::size_t s = 0; s < sets; ++s) {
    const auto u = [&](std::uint64_t dim) { return row_uniform(seed, s, dim); };
    std::vector<double> v(Chermain::kParams.size());
    v[param_index<Chermain>("alpha_x")] = in[0][s * kRowsPerSet];
    v[param_index<Chermain>("alpha_y")] = in[1][s * kRowsPerSet];
    v[param_index<Chermain>("rho")] = s % 4 == 0 ? 0.0 : -0.99 + 1.98 * u(0);
    v[param_index<Chermain>("density")] = log_uniform(1, 1e12, u(1));
    v[param_index<Chermain>("ggaa")] = double(s % 3);
    v[param_index<Chermain>("s_k")] = 0.05 + 3.95 * u(2);
    const double g = std::pow(10.0, -5 + 6 * u(3)), a = 6.283185307179586 * u(4);
    const double sel = u(5), t = log_uniform(0.2, 5, u(6)), b = a + 0.3 + 2.5 * u(7);
    const bool zero = sel < 0.1, only_dy = sel >= 0.1 && sel < 0.2;
    v[param_index<Chermain>("dh_dx_x")] = zero || only_dy ? 0.0 : g * std::cos(a);
    v[param_index<Chermain>("dh_dx_y")] = zero || only_dy ? 0.0 : g * std::sin(a);
    v[param_index<Chermain>("dh_dy_x")] = zero ? 0.0 : g * t * std::cos(b);
    v[param_index<Chermain>("dh_dy_y")] = zero ? 0.0 : g * t * std::sin(b);
    v[param_index<Chermain>("seed")] = double(s % 1000);
    k.params.push_back(v);
  }
  k.query.assign(kQueryColumns.size(), std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const std::vector<double>& v = k.params[i / kRowsPerSet];
    const auto u = [&](std::uint64_t dim) { return row_uniform(seed ^ 0x63686572ULL, i, dim); };
    const double sel = u(0);
    const double level = -1.5 + 19 * u(1);
    const double foot =
        sel < 0.04 ? 0.0
        : sel < 0.08
            ? 0x1p45
            : std::exp2(level - 0.5 * std::log2(v[param_index<Chermain>("density")]) + 0.3 * u(7));
    fill_footprint_row(k.query, i, foot, u, in);
  }
  k.u1 = in[8];
  k.u2 = in[9];
  return k;
}

// The pdfs (the smooth Beckmann lobe's exp(−q/2)) are compared relative down to √(smallest
// normal), 1.5e-154, as tests/simd/model_equivalence_test.cpp does: below it xsimd's and glibc's
// exp differ in the last bits of (sub)normals far in the lobe's tail.
constexpr double kTinyPdf = 1.4916681462400413e-154;

// The eval output columns (value, pdf, then kIntermediates).
enum Col { kValue, kPdf, kP22, kLod, kDictLevel, kKernelWidth, kMipLambda, kD, kG2, kBrdf, kCols };
constexpr const char* kColNames[kCols] = {"value",        "pdf",        "P22", "lod", "dict_level",
                                          "kernel_width", "mip_lambda", "D",   "G2",  "brdf"};

struct Measured {
  double col[kCols] = {};  // maxima over the rows within budget, eps
  double wo_eps = 0, sample_pdf_eps = 0, weight_eps = 0;
  double outlier_fraction = 0, flag_fraction = 0;
  std::size_t smooth_rows = 0, blend_rows = 0, levels_hit = 0;  // coverage of the case
  std::size_t over[kCols + 1] = {};  // outlier rows per eval output, then per sample
  std::string summary(const std::string& what) const {
    std::string r = what + ":";
    char b[96];
    for (int c = 0; c < kCols; ++c) {
      std::snprintf(b, sizeof b, " %s %.3g", kColNames[c], col[c]);
      r += b;
    }
    std::snprintf(b, sizeof b, "; sample wo %.3g, pdf %.3g, weight %.3g eps", wo_eps,
                  sample_pdf_eps, weight_eps);
    r += b;
    std::snprintf(b, sizeof b, "; outliers %.3g (", outlier_fraction);
    r += b;
    for (int c = 0; c <= kCols; ++c)
      if (over[c] > 0) {
        std::snprintf(b, sizeof b, " %s %zu", c < kCols ? kColNames[c] : "sample", over[c]);
        r += b;
      }
    std::snprintf(b, sizeof b, " ), flags %.3g", flag_fraction);
    return r + b;
  }
  bool within(const ChermainBudget& b) const {
    return outlier_fraction <= b.outlier_fraction && flag_fraction <= b.flag_fraction;
  }
};

// The scale of the patch-SDF: the smooth limit's peak 1/(2π σ_x σ_y √(1 − ρ²)) (Eq. 16), carried
// to D (÷ h_z⁴), the BRDF (÷ 4 ω_i,z ω_o,z, G2 ≤ 1) and the value (× ω_o,z) at direction wo.
double sdf_scale(const std::vector<double>& v) {
  const double sx = v[param_index<Chermain>("alpha_x")] * 0.70710678118654752440,
               sy = v[param_index<Chermain>("alpha_y")] * 0.70710678118654752440,
               rho = v[param_index<Chermain>("rho")];
  return 1 / (2 * 3.141592653589793 * sx * sy * std::sqrt(1 - rho * rho));
}
struct Scales {
  double p22, d, brdf, value;
};
Scales scales(const std::vector<double>& v, Vec3<double> wi, Vec3<double> wo) {
  Scales s{sdf_scale(v), 0, 0, 0};
  const Vec3<double> h = half_vector(wi, wo);
  if (h.z > 0) s.d = s.p22 / std::pow(h.z, 4);
  if (wi.z > 0 && wo.z > 0) s.brdf = s.d / (4 * wi.z * wo.z), s.value = s.brdf * wo.z;
  return s;
}

// Eval outputs against the scalar run `ref`; the sample's wo against ref's, its pdf and weight
// against the scalar model M at the batch's own wo (the sampler's contract: a wo a few ε away has
// its own pdf, and the smooth pdf's exponent amplifies that shift in the tails).
template <class M = Chermain>
Measured compare(const Case& k, const RowOutputs<double>& ref, const RowOutputs<double>& got,
                 const ChermainBudget& b) {
  Measured r;
  const double eps = std::numeric_limits<double>::epsilon();
  std::size_t outliers = 0, flags = 0;
  bool level_seen[17] = {};
  for (std::size_t i = 0; i < k.n; ++i) {
    const std::vector<double>& v = k.params[i / kRowsPerSet];
    const ModelQuery<double> q = row_query<double>(k, i);
    const Vec3<double> wi = q.wi, wo = q.wo;
    const Scales sc = scales(v, wi, wo);
    const auto e = [&](int c, double scale) {
      return scaled_eps(got.eval[std::size_t(c)][i], ref.eval[std::size_t(c)][i], scale);
    };
    double d[kCols];
    d[kValue] = e(kValue, sc.value);
    d[kPdf] = e(kPdf, kTinyPdf);
    d[kP22] = e(kP22, sc.p22);
    d[kLod] = e(kLod, 1.0);
    d[kDictLevel] = got.eval[kDictLevel][i] == ref.eval[kDictLevel][i] ? 0.0 : 1e300;
    d[kKernelWidth] = e(kKernelWidth, 0.0);
    d[kMipLambda] = e(kMipLambda, 1.0);
    d[kD] = e(kD, sc.d);
    d[kG2] = e(kG2, 1.0);
    d[kBrdf] = e(kBrdf, sc.brdf);
    const double lim[kCols] = {b.sdf_eps,  b.pdf_eps,  b.sdf_eps, b.unit_eps, 0.0,
                               b.unit_eps, b.unit_eps, b.sdf_eps, b.unit_eps, b.sdf_eps};
    bool over = false;
    for (int c = 0; c < kCols; ++c) over = over || d[c] > lim[c];
    // Sample: wo, its pdf and the weight (value/pdf) against the scalar sample.
    double w = 0, p = 0, wt = 0;
    const bool rej_ref = ref.sample[5][i] != 0, rej = got.sample[5][i] != 0;
    if (rej != rej_ref) {
      ++flags;
    } else if (!rej) {
      for (std::size_t c = 0; c < 3; ++c)
        w = std::max(w, std::abs(got.sample[c][i] - ref.sample[c][i]) / eps);
      const auto mp = M::template params<double>(v);
      ModelQuery<double> qo = q;
      qo.wo = {got.sample[0][i], got.sample[1][i], got.sample[2][i]};
      qo.light = {1, 1};
      const double pdf = M::template pdf<double>(mp, qo);
      p = scaled_eps(got.sample[3][i], pdf, kTinyPdf);
      const double weight = pdf > 0 ? M::template eval<double>(mp, qo).value / pdf : 0.0;
      wt = scaled_eps(got.sample[4][i], weight, pdf > 0 ? scales(v, wi, qo.wo).value / pdf : 0.0);
    }
    over = over || w > b.wo_eps || p > b.pdf_eps || wt > b.weight_eps;
    // Coverage, from the reference.
    const double level = ref.eval[kDictLevel][i], lod = ref.eval[kLod][i];
    if (ref.eval[kP22][i] > 0 || level > 0) {
      if (level >= 0 && level <= 16) level_seen[int(level)] = true;
      r.smooth_rows += level >= 16 ? 1 : 0;
      r.blend_rows += lod != std::floor(lod) ? 1 : 0;
    }
    if (over) {
      ++outliers;
      for (int c = 0; c < kCols; ++c) r.over[c] += d[c] > lim[c] ? 1 : 0;
      r.over[kCols] += w > b.wo_eps || p > b.pdf_eps || wt > b.weight_eps ? 1 : 0;
      continue;
    }
    for (int c = 0; c < kCols; ++c) r.col[c] = std::max(r.col[c], d[c]);
    r.wo_eps = std::max(r.wo_eps, w);
    r.sample_pdf_eps = std::max(r.sample_pdf_eps, p);
    r.weight_eps = std::max(r.weight_eps, wt);
  }
  for (bool s : level_seen) r.levels_hit += s ? 1 : 0;
  r.outlier_fraction = double(outliers) / double(k.n);
  r.flag_fraction = double(flags) / double(k.n);
  return r;
}

// The scalar ISA of the batch API is Chermain's scalar double instantiation: bit-identical.
std::size_t scalar_mismatches(const Case& k, const RowOutputs<double>& ref) {
  std::size_t bad = 0;
  for (std::size_t i = 0; i < k.n; i += 61) {
    const auto p = Chermain::params<double>(k.params[i / kRowsPerSet]);
    ModelQuery<double> q;
    const auto c = [&](std::size_t j) { return k.query[j][i]; };
    q.footprint = {{c(0), c(1)}, {c(2), c(3)}, {c(4), c(5)}};
    q.wi = {c(6), c(7), c(8)};
    q.wo = {c(9), c(10), c(11)};
    q.light = {c(12), c(13)};
    const auto e = Chermain::eval<double>(p, q);
    bad += ulp_distance(e.value, ref.eval[0][i]) != 0 || ulp_distance(e.pdf, ref.eval[1][i]) != 0;
    for (std::size_t j = 0; j < e.intermediates.size(); ++j)
      bad += ulp_distance(e.intermediates[j], ref.eval[2 + j][i]) != 0;
    const ModelSample<double> s = Chermain::sample<double>(p, q, {k.u1[i], k.u2[i]});
    bad += ulp_distance(s.wo.x, ref.sample[0][i]) != 0 ||
           ulp_distance(s.pdf, ref.sample[3][i]) != 0 ||
           ulp_distance(s.weight, ref.sample[4][i]) != 0 ||
           (s.rejected ? 1 : 0) != (ref.sample[5][i] != 0 ? 1 : 0);
  }
  return bad;
}

void check_all_isas(std::size_t rows) {
  const ModelEntry& m = find_model("chermain");
  ASSERT_TRUE(is_batched(m));
  const Case k = make_case(rows, hash_string("chermain_equivalence"));
  const RowOutputs<double> ref = run_rows_batch<double>(m, k, kRowsPerSet, Isa::kScalar);
  EXPECT_EQ(scalar_mismatches(k, ref), 0u);
  int ran = 0;
  for (Isa isa : kBatchIsas) {
    if (!isa_supported(isa)) continue;
    const Measured r = compare(k, ref, run_rows_batch<double>(m, k, kRowsPerSet, isa), kBudget);
    const std::string what =
        "chermain " + std::string(isa_name(isa)) + " double (" + std::to_string(k.n) + " rows)";
    std::printf("%s\n  coverage: %zu dictionary levels + smooth, %zu smooth rows, %zu blended\n",
                r.summary(what).c_str(), r.levels_hit, r.smooth_rows, r.blend_rows);
    EXPECT_TRUE(r.within(kBudget)) << r.summary(what);
    EXPECT_EQ(r.levels_hit, 17u) << "levels 0..15 and the smooth fallback";
    EXPECT_GT(r.smooth_rows, k.n / 50);
    EXPECT_GT(r.blend_rows, k.n / 4);
    ++ran;
  }
  EXPECT_GT(ran, 0) << "no SIMD ISA available: nothing compared";
}

TEST(SimdChermainEquivalence, DoubleEveryIsa) { check_all_isas(kCtestRows); }

// The full count (10^6 rows): minutes, so outside ctest (--gtest_also_run_disabled_tests).
TEST(SimdChermainEquivalenceFull, DISABLED_Million) { check_all_isas(kFullRows); }

// Float columns: the double-only model runs on Wide<double> with the columns widened on load and
// the results rounded on store, so each ISA's float output is the scalar one's (computed from the
// same widened inputs) up to the double budgets above, then one rounding: within one float ulp
// except on the double outliers.
TEST(SimdChermainEquivalence, FloatColumnsRunOnDoubleBatches) {
  const ModelEntry& m = find_model("chermain");
  const Case k = make_case(1 << 15, hash_string("chermain_equivalence.float"));
  const RowOutputs<float> ref = run_rows_batch<float>(m, k, kRowsPerSet, Isa::kScalar);
  for (Isa isa : kBatchIsas) {
    if (!isa_supported(isa)) continue;
    const RowOutputs<float> got = run_rows_batch<float>(m, k, kRowsPerSet, isa);
    std::size_t over = 0;
    for (std::size_t c = 0; c < ref.eval.size(); ++c)
      for (std::size_t i = 0; i < k.n; ++i)
        over += ulp_distance(got.eval[c][i], ref.eval[c][i]) > 1 ? 1 : 0;
    EXPECT_LE(double(over), kBudget.outlier_fraction * double(k.n) * double(ref.eval.size()))
        << isa_name(isa);
  }
}

// ---- Controls on this TU's baseline double batch ------------------------------------------------

using BatchWide = Wide<xsimd::batch<double>, ExactMath>;

// Clamp-to-edge (the negative control of chermain.kernel-normalized) is not a model parameter:
// the model with it, on a real batch.
struct ChermainClamp : Chermain {
  template <class T>
  static Params<T> params(std::span<const double> v) {
    Params<T> p = Chermain::params<T>(v);
    p.sdf.wrap = chermain2021::TableWrap::kClampToEdge;
    return p;
  }
};
// P22, D, the BRDF and the value one part in 2^40 high (4096 double eps, 16 times the SDF budget:
// rows with P22 ≳ its scale / 15 see it), as a wrong normalization 1/det M would give.
struct PerturbedEval : Chermain {
  template <class T>
  static ModelEval<T, kIntermediates.size()> eval(const Params<T>& p, const ModelQuery<T>& q) {
    auto r = Chermain::eval<T>(p, q);
    const T f = T(1.0 + 0x1p-40);
    r.value = r.value * f;
    r.intermediates[0] = r.intermediates[0] * f;
    r.intermediates[5] = r.intermediates[5] * f;
    r.intermediates[7] = r.intermediates[7] * f;
    return r;
  }
};
// Every lane on the cell draws of seed + 1: the error of a batch that feeds its lanes the wrong
// counter stream.
struct PerturbedCells : Chermain {
  template <class T>
  static Params<T> params(std::span<const double> v) {
    Params<T> p = Chermain::params<T>(v);
    p.sdf.seed += 1;
    return p;
  }
};

const Case& control_case() {
  static const Case k = make_case(1 << 14, hash_string("chermain_equivalence.control"));
  return k;
}

TEST(SimdChermainEquivalence, ClampToEdgeOnABatch) {
  const ModelEntry& m = find_model("chermain");
  const Case& k = control_case();
  const RowOutputs<double> ref = run_rows_driver<ChermainClamp, double, double>(m, k, kRowsPerSet);
  const RowOutputs<double> mirror = run_rows_batch<double>(m, k, kRowsPerSet, Isa::kScalar);
  const Measured r = compare<ChermainClamp>(
      k, ref, run_rows_driver<ChermainClamp, BatchWide, double>(m, k, kRowsPerSet), kBudget);
  std::printf("%s\n", r.summary("chermain clamp-to-edge, baseline batch").c_str());
  EXPECT_TRUE(r.within(kBudget)) << r.summary("clamp");
  // The wrap matters on these rows (else the case would not test it).
  std::size_t differ = 0;
  for (std::size_t i = 0; i < k.n; ++i) differ += ref.eval[kP22][i] != mirror.eval[kP22][i];
  EXPECT_GT(differ, k.n / 100);
}

TEST(SimdChermainNegativeControl, UnperturbedBatchPassesPerturbedFail) {
  const ModelEntry& m = find_model("chermain");
  const Case& k = control_case();
  const RowOutputs<double> ref = run_rows_batch<double>(m, k, kRowsPerSet, Isa::kScalar);
  const Measured ok =
      compare(k, ref, run_rows_driver<Chermain, BatchWide, double>(m, k, kRowsPerSet), kBudget);
  std::printf("%s\n", ok.summary("unperturbed baseline batch").c_str());
  EXPECT_TRUE(ok.within(kBudget)) << ok.summary("unperturbed");
  const Measured bad_eval = compare(
      k, ref, run_rows_driver<PerturbedEval, BatchWide, double>(m, k, kRowsPerSet), kBudget);
  std::printf("%s\n", bad_eval.summary("perturbed eval").c_str());
  EXPECT_GT(bad_eval.outlier_fraction, 100 * kBudget.outlier_fraction);
  EXPECT_FALSE(bad_eval.within(kBudget));
  const Measured bad_cells = compare(
      k, ref, run_rows_driver<PerturbedCells, BatchWide, double>(m, k, kRowsPerSet), kBudget);
  std::printf("%s\n", bad_cells.summary("perturbed cell stream").c_str());
  EXPECT_GT(bad_cells.outlier_fraction, 100 * kBudget.outlier_fraction);
  EXPECT_FALSE(bad_cells.within(kBudget));
}

// The vector forms of core/glints/chermain_lanes.h on this TU's baseline batch against the scalar
// code they replace, bit for bit: each cell's three counter uniforms (keys over the whole exact
// range of the int64 conversion, and the refusal beyond it that sends the batch to the per-lane
// code), the same draws through a LOD's 2 × 2 block of shared key parts (cell_block_keys), and 2^e
// over the normal exponents.
TEST(SimdChermainLanes, CellUniformsAndPowersOfTwoAreTheScalarBits) {
  using chermain2021::lanes::kVectorDoubles;
  if constexpr (kVectorDoubles<BatchWide> == 0) {
    GTEST_SKIP() << "no vector path for this TU's baseline batch";
  } else {
    constexpr std::size_t kL = BatchWide::kLanes;
    const std::uint64_t seed = 2021;
    const double limit = 0x1p51;  // the exact conversion's range without AVX-512
    std::size_t checked = 0, refused = 0, bad = 0, block_checked = 0, block_refused = 0;
    for (std::uint64_t i = 0; i < 20000; ++i) {
      double cu[kL], cv[kL], scale[kL];
      for (std::size_t l = 0; l < kL; ++l) {
        const double u = counter_uniform<double>(seed, i, 10 + l);
        const int e = int(counter_uniform<double>(seed, i, 20 + l) * 60.0);  // scale 2^0 … 2^59
        scale[l] = std::ldexp(1.0, e);
        // Corners up to about 2^53 in units of 2^-20: most in range, some at or past 2^51.
        const double mag = std::ldexp(1.0, int(counter_uniform<double>(seed, i, 30 + l) * 54.0));
        cu[l] = std::floor((2 * u - 1) * mag / scale[l]);
        cv[l] = std::floor((counter_uniform<double>(seed, i, 40 + l) - 0.5) * mag / scale[l]);
        if (i % 97 == 0) cu[l] = (l % 2 ? -1.0 : 1.0) * std::floor((limit - 1) / scale[l]);
        if (i % 89 == 0) cv[l] = -0.0;
      }
      const BatchWide u = LaneAccess<BatchWide>::load(cu), v = LaneAccess<BatchWide>::load(cv);
      const BatchWide s = LaneAccess<BatchWide>::load(scale);
      bool in_range = true;
      for (std::size_t l = 0; l < kL; ++l)
        in_range =
            in_range && std::abs(cu[l] * scale[l]) < limit && std::abs(cv[l] * scale[l]) < limit;
      chermain2021::lanes::CellUniforms<BatchWide> got;
      if (!chermain2021::lanes::cell_uniforms(seed, u, v, s, &got)) {
        ++refused;
        bad += in_range;  // refused although every lane converts exactly
        continue;
      }
      bad += !in_range && kL != 8;  // accepted a lane past 2^51 (only AVX-512 converts those)
      const LanesOf<BatchWide> u0(got.u0), u1(got.u1), u2(got.u2);
      for (std::size_t l = 0; l < kL; ++l) {
        const std::uint64_t key =
            chermain2021::cell_key(std::int64_t(cu[l] * scale[l]), std::int64_t(cv[l] * scale[l]));
        bad += u0[l] != counter_uniform<double>(seed, key, 0) ||
               u1[l] != counter_uniform<double>(seed, key, 1) ||
               u2[l] != counter_uniform<double>(seed, key, 2);
        ++checked;
      }
      // The same draws through the 2 × 2 block's shared key parts (for_each_cell's path), for the
      // cells (cu + di, cv + dj); refused where any of the four corners is past the range.
      chermain2021::lanes::CellBlockKeys<BatchWide> keys;
      bool block_in_range = true;
      for (std::size_t l = 0; l < kL; ++l)
        block_in_range = block_in_range && std::abs((cu[l] + 1) * scale[l]) < limit &&
                         std::abs((cv[l] + 1) * scale[l]) < limit && in_range;
      if (!chermain2021::lanes::cell_block_keys(seed, u, v, s, &keys)) {
        ++block_refused;
        bad += block_in_range;
        continue;
      }
      bad += !block_in_range && kL != 8;
      for (int c = 0; c < 4; ++c) {
        const int di = c & 1, dj = c >> 1;
        const chermain2021::lanes::CellUniforms<BatchWide> b =
            chermain2021::lanes::block_cell_uniforms(keys, di, dj);
        const LanesOf<BatchWide> b0(b.u0), b1(b.u1), b2(b.u2);
        for (std::size_t l = 0; l < kL; ++l) {
          const std::uint64_t key = chermain2021::cell_key(std::int64_t((cu[l] + di) * scale[l]),
                                                           std::int64_t((cv[l] + dj) * scale[l]));
          bad += b0[l] != counter_uniform<double>(seed, key, 0) ||
                 b1[l] != counter_uniform<double>(seed, key, 1) ||
                 b2[l] != counter_uniform<double>(seed, key, 2);
          ++block_checked;
        }
      }
    }
    std::printf(
        "chermain lanes (%zu lanes): %zu lanes' draws checked, %zu batches refused, %zu bad; "
        "blocks: %zu cells' draws checked, %zu blocks refused\n",
        kL, checked, refused, bad, block_checked, block_refused);
    EXPECT_GT(block_checked, 4 * 20000u);
    EXPECT_GT(block_refused, 0u);
    EXPECT_EQ(bad, 0u);
    EXPECT_GT(checked, 20000u);
    EXPECT_GT(refused, 100u);
    for (int e = -1022; e <= 1023; ++e) {
      const LanesOf<BatchWide> p(chermain2021::lanes::exp2_int(BatchWide(double(e))));
      for (std::size_t l = 0; l < kL; ++l) EXPECT_EQ(p[l], std::ldexp(1.0, e)) << e;
    }
  }
}

}  // namespace
}  // namespace glintlab::simd::test

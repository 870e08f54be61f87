// Registry-level batching (core/simd/model_batch.h): every model of BatchedModels, on every ISA
// this CPU has, against the scalar float/double instantiation of its own eval/pdf/sample, with
// stated budgets; the scalar-loop fallback for entries that are not batched; perturbed controls.
#define GLINTLAB_SIMD_TU model_test
#include "core/simd/instantiate.h"
// (it gives this test the model driver on Wide<float>, for the perturbed controls)

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/math/orthonormal_basis.h"
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
constexpr std::size_t kParamSets = 256;   // parameter vectors per choice combination (smooth)
constexpr std::size_t kRowsPerSet = 512;  // query rows per parameter vector
// The glint models: at least 2^20 rows (float) and 2^18 rows (double, to keep the test's time
// within its CI share) over all choice combinations of the model together.
constexpr std::size_t kGlintRowsFloat = std::size_t(1) << 20;
constexpr std::size_t kGlintRowsDouble = std::size_t(1) << 18;

// One eval output's budget: `ulp` ulps, or, where floor > 0, |batch − scalar| ≤ ulp · ε ·
// max(|scalar|, floor) (a quantity on a known scale, e.g. a fraction in [0, 1]: its error in ε of
// that scale, not in ulps of a value that cancels to ~0).
struct OutputBudget {
  std::string_view name;
  double ulp;
  double floor = 0;
};

// One model's budgets. Eval outputs (value, pdf, intermediates) and the sample's pdf and weight:
// |batch − scalar| ≤ ulp ulps (`outputs` overrides it per named eval output), or both below
// √(smallest normal) in magnitude; the sample weight with floor value_floor / pdf where
// value_floor > 0 (the value's floor carried through the division). Rows where some of these exceed
// their budget are allowed on outlier_fraction of the rows: a discrete decision (a binomial gate,
// an inversion step, a rounding to a whole facet count, the inside test of a quad) that a one-ulp
// difference of a libm function moves across its threshold. Sampled wo: each component within
// wo_eps machine epsilons. Rejection flags may differ on flag_fraction of the rows (then only the
// flag is compared).
struct ModelBudget {
  double ulp;
  double pdf_ulp;
  double weight_ulp;
  double wo_eps;
  double flag_fraction;
  const char* why;
  std::vector<OutputBudget> outputs = {};
  double outlier_fraction = 0;
  double value_floor = 0;
  OutputBudget output(std::string_view name) const {
    for (const OutputBudget& o : outputs)
      if (o.name == name) return o;
    return {name, ulp, 0};
  }
};

// The glint models (measured maxima over the ISAs of this machine, float / double, in [ ]). Every
// output not named is bit-identical [0 / 0]: GGX D, G2, the VNDF pdf, the footprint's N_P (its
// 10^density is one host exp shared by the lanes), p, and the exact binomial count, which the
// masked inversion/BTRS kernel draws from each lane's own counter stream in the host's double
// steps [0 / 0 over 3.5e5 rows]. Rows over budget are allowed on 1e-5 of the rows [0 / 0]: a
// libm ulp (xsimd vs glibc exp, log1p, erfinv's steps) may move a threshold decision (an
// inversion step u ≤ F(k), BTRS's acceptance, the small-count search, the real-time gate,
// floor(np + σz + ½)) and change a count.
ModelBudget glint_budget(std::string_view model, std::string_view sampler, bool dbl,
                         double vndf_wo) {
  constexpr double kRows = 1e-5;
  if (model == "podee") {
    // value and weight are fractions of the light's radiance in [0, 1]: the exact circle ∩ quad
    // area sums signed segment areas (atan2, acos of xsimd vs glibc), the lens of quad_as_circle
    // acos and sqrt; errors in ε of 1 [value 2.5 / 2, weight 2.5 / 2 ε]; near-zero weights
    // cancel (ulp distances to 4e18 there). The sample weight, value/pdf at sampled directions,
    // meets the lens near tangency (acos near ±1) [exact 10.1 / 18.2, quad_as_circle 23.3 / 137
    // ε of value/pdf]. The selected vector, inside/lit, distance and quad area are IEEE
    // [0 / 0]. sample: the VNDF [pdf 0, wo 1.06e3 / 879 ε].
    ModelBudget b{0, 0, 1024, vndf_wo, 1e-4, "Podee: area fractions in eps of 1; selection IEEE"};
    b.outputs = {{"value", 64, 1.0}, {"weight", 64, 1.0}};
    b.value_floor = 1.0;
    b.outlier_fraction = kRows;
    return b;
  }
  // deliot_belcour, kneiphof_klein. gamma: Kneiphof's 2 atan2(√(omc/2), √(1 − omc/2)) [2 / 2].
  // The real-time binomial: expm1, log and erfinv's Newton steps, then m p + σ z cancels for
  // z ≈ −m p/σ [count 9 / 8.57e3, factor 7 / 1.02e4, value 10 / 1.4e4, eq22 7 / 8.24e3, sample
  // weight 6 / 6.23e3 ulp]; exact and small_count draw integer counts [0 / 0]. sample: the VNDF
  // [pdf 0, wo 2.17e3 / 5.21e3 ε]. (Double maxima from a 3.5e5-row run; the test runs 2.6e5.)
  const bool realtime = sampler == "realtime";
  const double rt = realtime ? (dbl ? 65536.0 : 32.0) : 0.0;
  ModelBudget b{0, 0, rt, vndf_wo, 1e-4, "binomial glints: IEEE GGX, exact counts; realtime libm"};
  b.outputs = {{"count", rt}, {"factor", rt}, {"value", rt}, {"eq22", rt}, {"gamma", 4.0}};
  b.outlier_fraction = kRows;
  return b;
}

// The budgets follow the kernels the model composes (tests/simd/equivalence.cpp, which gives
// each its reason); [measured maxima over every ISA of this machine, float / double].
ModelBudget model_budget(std::string_view model, std::string_view sampler, bool dbl) {
  constexpr double kFlags = 1e-4;
  // Heitz's VNDF sampler, which every glint model samples with: its wo budget below.
  const double vndf_wo = dbl ? 65536.0 : 16384.0;
  if (model == "smooth_ggx") {
    // GGX D, Λ, G1, G2 and every GGX pdf are IEEE +, −, ×, ÷, √ in the same order: bit-identical
    // [0]. wo inherits the sampler kernel's budget: Heitz's disk lift near the rim [1.06e3 /
    // 879 eps], the caps' unstretch at α = 1e-3 [36 / 21.5 eps], Walter's sin/cos [5 / 4 eps].
    const double wo = sampler == "vndf" ? vndf_wo : sampler == "ndf" ? 16.0 : 512.0;
    return {0, 0, 0, wo, kFlags, "GGX: IEEE ops only; wo as the sampler kernels"};
  }
  if (model == "smooth_beckmann") {
    // Beckmann: exp/erfc of xsimd vs glibc, a few ulp each [eval 7 / 66 ulp, sample pdf 7 / 35,
    // weight 6 / 61]; the VNDF pdf of a below-horizon wi cancels (½|ωz| erfc(a) against
    // σ e^{−a²}/(2√π), condition ~2a²) [eval pdf 1.38e3 / 4.84e10 ulp]; wo: Walter [4 eps], the
    // VNDF's Newton solve [15.5 / 1.42e3 eps].
    const double value = dbl ? 128.0 : 16.0;
    const double eval = sampler == "vndf" ? (dbl ? 68719476736.0 : 8192.0) : value;
    const double wo = sampler == "vndf" ? (dbl ? 4096.0 : 64.0) : 16.0;
    return {eval,   value,
            value,  wo,
            kFlags, "Beckmann: exp/erfc ulps, below-horizon VNDF pdf cancellation, Newton wo"};
  }
  return glint_budget(model, sampler, dbl, vndf_wo);
}

// The rows of one (model, choice combination) run: parameter vectors and query columns.
struct Case {
  std::vector<std::vector<double>> params;  // one vector per kRowsPerSet rows
  std::vector<std::vector<double>> query;   // kQueryColumnsWithCorners columns
  std::vector<double> u1, u2;               // uniforms
  std::string label;
  std::string sampler;  // the `sampler` (or `binomial`) choice, where the model has one
  std::size_t n = 0;    // params.size() × kRowsPerSet
  std::size_t rows() const { return n; }
};

bool is_glint(const ModelEntry& m) { return (m.needs & kNeedsFootprint) != 0; }

std::vector<Case> make_cases(const ModelEntry& m, bool dbl = false) {
  using D = Domain;
  const std::vector<int> domains = {int(D::kAlphaX), int(D::kAlphaY), int(D::kWiX), int(D::kWiY),
                                    int(D::kWiZ),    int(D::kWoX),    int(D::kWoY), int(D::kWoZ),
                                    int(D::kU1),     int(D::kU2)};
  // Every combination of the choice parameters (their indices), in mixed-radix order.
  std::size_t combos = 1;
  for (const ParamSpec& p : m.params)
    if (!p.choices.empty()) combos *= p.choices.size();
  const std::size_t sets =
      is_glint(m)
          ? std::max(dbl ? kParamSets / 4 : kParamSets,
                     ((dbl ? kGlintRowsDouble : kGlintRowsFloat) + combos * kRowsPerSet - 1) /
                         (combos * kRowsPerSet))
          : kParamSets;
  const std::size_t n = sets * kRowsPerSet;
  const auto in = make_inputs(domains, n, 0x6d6f64656cULL);
  std::vector<Case> cases;
  for (std::size_t c = 0; c < combos; ++c) {
    Case k;
    std::size_t rest = c;
    std::vector<double> choice(m.params.size(), 0);
    for (std::size_t j = 0; j < m.params.size(); ++j) {
      if (m.params[j].choices.empty()) continue;
      choice[j] = double(rest % m.params[j].choices.size());
      if (m.params[j].name == "sampler" || m.params[j].name == "binomial")
        k.sampler = m.params[j].choices[std::size_t(choice[j])];
      k.label += std::string(k.label.empty() ? "" : ",") + std::string(m.params[j].name) + "=" +
                 std::string(m.params[j].choices[std::size_t(choice[j])]);
      rest /= m.params[j].choices.size();
    }
    for (std::size_t s = 0; s < sets; ++s) {
      std::vector<double> v(m.params.size());
      const std::size_t row = s * kRowsPerSet;
      for (std::size_t j = 0; j < m.params.size(); ++j) {
        const ParamSpec& p = m.params[j];
        if (!p.choices.empty()) {
          v[j] = choice[j];
        } else if (p.name == "alpha_x" || p.name == "alpha_y") {
          v[j] = in[p.name == "alpha_x" ? 0 : 1][row];  // the edge-case roughness generator
        } else if (p.name == "seed") {
          v[j] = double(s);  // an integer, as the parameter's description asks
        } else {
          // Uniform over the range, kept inside open bounds.
          const double t = (double(s) + 0.5) / double(sets);
          v[j] = p.lo + t * (p.hi - p.lo);
        }
      }
      k.params.push_back(v);
    }
    k.query.assign(kQueryColumnsWithCorners, std::vector<double>(n, 0.0));
    for (std::size_t j = 0; j < kQueryColumns.size(); ++j) k.query[j].assign(n, kQueryDefaults[j]);
    for (std::size_t j = 0; j < kDirectionColumns.size(); ++j)
      k.query[kDirectionColumns[j]] = in[2 + j];
    k.u1 = in[8];
    k.u2 = in[9];
    add_scene_columns(m.needs, k.query, hash_string("model_equivalence.scene"));
    k.n = k.params.size() * kRowsPerSet;
    cases.push_back(std::move(k));
  }
  return cases;
}

// Outputs of eval (2 + M columns) and sample (6 columns) of one case through the batch API.
template <class S>
using Outputs = RowOutputs<S>;

// Error of batched values against a reference: ulps, with both-tiny values equal.
template <class S>
double value_ulps(S got, S ref) {
  const S tiny = std::sqrt(std::numeric_limits<S>::min());
  if (std::abs(got) < tiny && std::abs(ref) < tiny) return 0;
  return ulp_distance(got, ref);
}

struct Measured {
  double eval_ulp = 0, pdf_ulp = 0, weight_ulp = 0, wo_eps = 0, flag_fraction = 0;
  double outlier_fraction = 0;     // rows with an eval output, pdf or weight over its budget
  std::string worst_eval;          // which output
  std::vector<double> output_ulp;  // per eval output (value, pdf, intermediates)
  std::string summary(const std::string& what) const {
    char b[320];
    std::snprintf(b, sizeof b,
                  "%s: eval %.3g ulp (%s), sample pdf %.3g ulp, weight %.3g ulp, wo %.3g eps, "
                  "flags %.2g, rows over budget %.2g",
                  what.c_str(), eval_ulp, worst_eval.c_str(), pdf_ulp, weight_ulp, wo_eps,
                  flag_fraction, outlier_fraction);
    return b;
  }
  std::string per_output(const ModelEntry& m) const {
    std::string r;
    for (std::size_t c = 0; c < output_ulp.size(); ++c) {
      char b[64];
      std::snprintf(b, sizeof b, "%s%s %.3g", c == 0 ? "" : ", ",
                    c == 0   ? "value"
                    : c == 1 ? "pdf"
                             : std::string(m.intermediates[c - 2]).c_str(),
                    output_ulp[c]);
      r += b;
    }
    return r;
  }
  bool within(const ModelBudget& b) const {
    return outlier_fraction <= b.outlier_fraction && wo_eps <= b.wo_eps &&
           flag_fraction <= b.flag_fraction;
  }
};

// The scalar instantiation's eval outputs (value, pdf, intermediates: `columns` per row, row-major)
// and sample at every row of a case, each row's query, and the scalar pdf and value at the
// sampled wo (what a batch's sample is compared with where the batch samples the same wo, bit for
// bit). It does not depend on the ISA, so each case computes it once and compares every ISA's
// batch with it.
template <class S>
struct Reference {
  std::size_t columns = 0;
  std::vector<S> eval;
  std::vector<ModelSample<S>> sample;
  std::vector<ModelQuery<S>> query;
  std::vector<S> pdf_at_sampled_wo, value_at_sampled_wo;  // 0 where the sample is rejected
};

template <class S>
bool same_bits(const Vec3<S>& a, const Vec3<S>& b) {
  return std::bit_cast<std::array<S, 3>>(a) == std::bit_cast<std::array<S, 3>>(b);
}

template <class M, class S>
Reference<S> reference(const ModelEntry& m, const Case& k) {
  Reference<S> r;
  r.columns = 2 + m.intermediates.size();
  r.eval.reserve(k.rows() * r.columns);
  r.sample.reserve(k.rows());
  r.query.reserve(k.rows());
  r.pdf_at_sampled_wo.reserve(k.rows());
  r.value_at_sampled_wo.reserve(k.rows());
  for (std::size_t s = 0; s < k.params.size(); ++s) {
    const auto p = M::template params<S>(k.params[s]);
    for (std::size_t i = s * kRowsPerSet; i < (s + 1) * kRowsPerSet; ++i) {
      const ModelQuery<S> q = row_query<S>(k, i);
      const auto e = M::template eval<S>(p, q);
      r.eval.push_back(e.value);
      r.eval.push_back(e.pdf);
      r.eval.insert(r.eval.end(), e.intermediates.begin(), e.intermediates.end());
      const ModelSample<S> ss = M::template sample<S>(p, q, Vec2<S>{S(k.u1[i]), S(k.u2[i])});
      r.sample.push_back(ss);
      r.query.push_back(q);
      S pdf = 0, value = 0;
      if (!static_cast<bool>(ss.rejected)) {
        ModelQuery<S> qo = q;
        qo.wo = ss.wo;
        pdf = M::template pdf<S>(p, qo);
        value = pdf > S(0) ? M::template eval<S>(p, qo).value : S(0);
      }
      r.pdf_at_sampled_wo.push_back(pdf);
      r.value_at_sampled_wo.push_back(value);
    }
  }
  return r;
}

// Compares batch outputs with the scalar instantiation M::eval<S> / M::sample<S> (`ref`), and the
// sampled pdf with the scalar M::pdf<S> at the batch's own wo (the sampler's contract), under
// budget b.
template <class M, class S>
Measured compare(const ModelEntry& m, const Case& k, const Reference<S>& reference,
                 const Outputs<S>& got, const ModelBudget& b) {
  Measured r;
  std::size_t flags = 0, over = 0;
  const S eps = std::numeric_limits<S>::epsilon();
  std::vector<OutputBudget> out_budget;
  for (std::size_t c = 0; c < 2 + m.intermediates.size(); ++c)
    out_budget.push_back(b.output(c == 0 ? "value" : c == 1 ? "pdf" : m.intermediates[c - 2]));
  // The error of one output in its budget's unit (ulps, or ε of max(|ref|, floor)).
  const auto error = [&](S g, S ref, double floor) {
    if (floor > 0) {
      return std::abs(double(g) - double(ref)) /
             (double(eps) * std::max(std::abs(double(ref)), floor));
    }
    return value_ulps(g, ref);
  };
  r.output_ulp.assign(out_budget.size(), 0.0);
  for (std::size_t s = 0; s < k.params.size(); ++s) {
    const auto p = M::template params<S>(k.params[s]);
    for (std::size_t i = s * kRowsPerSet; i < (s + 1) * kRowsPerSet; ++i) {
      const ModelQuery<S>& q = reference.query[i];
      const S* ref = &reference.eval[i * reference.columns];
      bool row_over = false;
      for (std::size_t c = 0; c < reference.columns; ++c) {
        const double d = error(got.eval[c][i], ref[c], out_budget[c].floor);
        r.output_ulp[c] = std::max(r.output_ulp[c], d);
        row_over = row_over || d > out_budget[c].ulp;
        if (d > r.eval_ulp) {
          r.eval_ulp = d;
          r.worst_eval = c == 0 ? "value" : c == 1 ? "pdf" : std::string(m.intermediates[c - 2]);
        }
      }
      const ModelSample<S>& ss = reference.sample[i];
      const bool rej_ref = static_cast<bool>(ss.rejected), rej = got.sample[5][i] != 0;
      if (rej || rej_ref) {
        flags += rej != rej_ref ? 1 : 0;
        over += row_over ? 1 : 0;
        continue;
      }
      const S wo_ref[3] = {ss.wo.x, ss.wo.y, ss.wo.z};
      for (int c = 0; c < 3; ++c)
        r.wo_eps =
            std::max(r.wo_eps, double(std::abs(got.sample[std::size_t(c)][i] - wo_ref[c]) / eps));
      // The sample's pdf and weight against the scalar model at the batch's own wo: the pdf
      // is M::pdf there, the weight value/pdf (the estimator the sample stands for).
      // Where the batch sampled the reference's wo bit for bit, they are the reference's.
      ModelQuery<S> qo = q;
      qo.wo = {got.sample[0][i], got.sample[1][i], got.sample[2][i]};
      const bool same_wo = same_bits(qo.wo, ss.wo);
      const S pdf = same_wo ? reference.pdf_at_sampled_wo[i] : M::template pdf<S>(p, qo);
      const double dp = value_ulps(got.sample[3][i], pdf);
      r.pdf_ulp = std::max(r.pdf_ulp, dp);
      const S value = same_wo      ? reference.value_at_sampled_wo[i]
                      : pdf > S(0) ? M::template eval<S>(p, qo).value
                                   : S(0);
      const S weight = pdf > S(0) ? value / pdf : S(0);
      const double dw = error(got.sample[4][i], weight,
                              b.value_floor > 0 && pdf > S(0) ? b.value_floor / double(pdf) : 0.0);
      r.weight_ulp = std::max(r.weight_ulp, dw);
      over += row_over || dp > b.pdf_ulp || dw > b.weight_ulp ? 1 : 0;
    }
  }
  r.flag_fraction = double(flags) / double(k.rows());
  r.outlier_fraction = double(over) / double(k.rows());
  return r;
}

// One batch against the reference computed for it alone (each negative control compares one).
template <class M, class S>
Measured compare(const ModelEntry& m, const Case& k, const Outputs<S>& got, const ModelBudget& b) {
  return compare<M, S>(m, k, reference<M, S>(m, k), got, b);
}

template <class S, class... Ms>
void check_models(ModelList<Ms...>) {
  int ran = 0;
  const auto one = [&]<class M>() {
    const ModelEntry& m = find_model(M::kName);
    ASSERT_TRUE(is_batched(m)) << m.name;
    // The Kemppinen models' 128 choice combinations at these counts would take hours: they have
    // their own inputs, counts and budgets in tests/simd/kemppinen_equivalence_test.cpp.
    if (m.name.starts_with("kemppinen")) return;
    // Chermain (double-only, footprints across its LOD range):
    // tests/simd/chermain_equivalence_test.
    if (m.name == "chermain") return;
    for (const Case& k : make_cases(m, sizeof(S) == 8)) {
      const ModelBudget b = model_budget(m.name, k.sampler, sizeof(S) == 8);
      const Reference<S> ref = reference<M, S>(m, k);
      // The scalar ISA runs the very same instantiation: bit-identical.
      const Measured s =
          compare<M, S>(m, k, ref, run_rows_batch<S>(m, k, kRowsPerSet, Isa::kScalar), b);
      EXPECT_EQ(s.eval_ulp + s.pdf_ulp + s.weight_ulp + s.wo_eps + s.flag_fraction, 0.0)
          << s.summary(std::string(m.name) + " " + k.label + " scalar");
      for (Isa isa : kBatchIsas) {
        if (!isa_supported(isa)) continue;
        const Measured r = compare<M, S>(m, k, ref, run_rows_batch<S>(m, k, kRowsPerSet, isa), b);
        const std::string what =
            std::string(m.name) + " " + k.label + " " + std::string(isa_name(isa)) +
            (sizeof(S) == 8 ? " double" : " float") + " (" + std::to_string(k.rows()) + " rows)";
        std::printf("%s\n  per output: %s\n", r.summary(what).c_str(), r.per_output(m).c_str());
        EXPECT_TRUE(r.within(b)) << r.summary(what) << "; budget " << b.ulp << " ulp, " << b.pdf_ulp
                                 << " ulp, " << b.weight_ulp << " ulp, " << b.wo_eps << " eps, "
                                 << b.flag_fraction << ", rows over " << b.outlier_fraction << " ("
                                 << b.why << ")";
        ++ran;
      }
    }
  };
  (one.template operator()<Ms>(), ...);
  EXPECT_GT(ran, 0) << "no SIMD ISA available: nothing compared";
}

TEST(SimdModelEquivalence, FloatEveryBatchedModelEveryIsa) { check_models<float>(BatchedModels{}); }
TEST(SimdModelEquivalence, DoubleEveryBatchedModelEveryIsa) {
  check_models<double>(BatchedModels{});
}

// ---- Negative controls: perturbed batch models must fail the budgets --------------------------

// value 4 float ulps high: the smallest error GGX's bit-identical budget must see.
struct PerturbedEvalGgx : SmoothGGX {
  template <class T>
  static ModelEval<T, kIntermediates.size()> eval(const Params<T>& p, const ModelQuery<T>& q) {
    auto r = SmoothGGX::eval<T>(p, q);
    r.value = r.value * T(1.0f + 4.0f * 0x1p-23f);
    return r;
  }
};
// wo.x shifted by 64 float epsilons (pdf and weight left as the sampler computed them, so they
// no longer match the shifted wo either: both the wo and the pdf budgets see it).
struct PerturbedSampleGgx : SmoothGGX {
  template <class T>
  static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    ModelSample<T> s = SmoothGGX::sample<T>(p, q, u);
    s.wo.x = s.wo.x + T(64.0f * 0x1p-23f);
    return s;
  }
};

// The "ndf" case of smooth_ggx (Walter's sampler: wo budget 16 eps).
const Case& ggx_ndf_case() {
  static const Case k = [] {
    for (Case& c : make_cases(find_model("smooth_ggx")))
      if (c.sampler == "ndf") return c;
    return Case{};
  }();
  return k;
}

using LocalWide = Wide<float, ExactMath>;

TEST(SimdModelNegativeControl, UnperturbedLocalDriverPasses) {
  const ModelEntry& m = find_model("smooth_ggx");
  const Measured r = compare<SmoothGGX, float>(
      m, ggx_ndf_case(),
      run_rows_driver<SmoothGGX, LocalWide, float>(m, ggx_ndf_case(), kRowsPerSet),
      model_budget("smooth_ggx", "ndf", false));
  EXPECT_TRUE(r.within(model_budget("smooth_ggx", "ndf", false))) << r.summary("local");
}

TEST(SimdModelNegativeControl, PerturbedEvalFailsGgxBudget) {
  const ModelEntry& m = find_model("smooth_ggx");
  const Measured r = compare<SmoothGGX, float>(
      m, ggx_ndf_case(),
      run_rows_driver<PerturbedEvalGgx, LocalWide, float>(m, ggx_ndf_case(), kRowsPerSet),
      model_budget("smooth_ggx", "ndf", false));
  std::printf("%s\n", r.summary("perturbed eval").c_str());
  EXPECT_GE(r.eval_ulp, 3.0);
  EXPECT_FALSE(r.within(model_budget("smooth_ggx", "ndf", false))) << r.summary("perturbed eval");
}

TEST(SimdModelNegativeControl, PerturbedSampleFailsGgxBudget) {
  const ModelEntry& m = find_model("smooth_ggx");
  const Measured r = compare<SmoothGGX, float>(
      m, ggx_ndf_case(),
      run_rows_driver<PerturbedSampleGgx, LocalWide, float>(m, ggx_ndf_case(), kRowsPerSet),
      model_budget("smooth_ggx", "ndf", false));
  std::printf("%s\n", r.summary("perturbed sample").c_str());
  EXPECT_GT(r.wo_eps, 16.0);
  EXPECT_FALSE(r.within(model_budget("smooth_ggx", "ndf", false))) << r.summary("perturbed sample");
}

// ---- Negative controls of the glint models, on a real batch (this TU's baseline xsimd ISA) ------

using BatchWide = Wide<xsimd::batch<float>, ExactMath>;

// `sets` parameter vectors spread evenly over a model's case with this label (so the density
// and the other swept parameters cover their ranges), with their kRowsPerSet rows each.
Case glint_case(std::string_view model, std::string_view label, std::size_t sets) {
  for (Case& c : make_cases(find_model(model))) {
    if (c.label != label) continue;
    Case r;
    r.label = c.label;
    r.sampler = c.sampler;
    r.query.assign(c.query.size(), {});
    for (std::size_t j = 0; j < sets; ++j) {
      const std::size_t s = j * c.params.size() / sets, b = s * kRowsPerSet, e = b + kRowsPerSet;
      r.params.push_back(c.params[s]);
      for (std::size_t q = 0; q < c.query.size(); ++q)
        r.query[q].insert(r.query[q].end(), c.query[q].begin() + std::ptrdiff_t(b),
                          c.query[q].begin() + std::ptrdiff_t(e));
      r.u1.insert(r.u1.end(), c.u1.begin() + std::ptrdiff_t(b), c.u1.begin() + std::ptrdiff_t(e));
      r.u2.insert(r.u2.end(), c.u2.begin() + std::ptrdiff_t(b), c.u2.begin() + std::ptrdiff_t(e));
    }
    r.n = r.params.size() * kRowsPerSet;
    return r;
  }
  ADD_FAILURE() << "no case " << label << " for " << model;
  return Case{};
}

// Each lane on the hash32 stream of a footprint 2^-18 away in u (16 quanta of
// footprint_hash_coordinate): N_P and p unchanged, the binomial count drawn from other uniforms — the
// error a batch kernel makes that feeds its lanes the wrong (e.g. lane-shifted) stream.
struct PerturbedStreamDeliot : DeliotBelcour {
  template <class T>
  static ModelEval<T, kIntermediates.size()> eval(const Params<T>& p, const ModelQuery<T>& q) {
    ModelQuery<T> shifted = q;
    shifted.footprint.uv.x = q.footprint.uv.x + T(0x1p-18f);
    return DeliotBelcour::eval<T>(p, shifted);
  }
};

TEST(SimdModelNegativeControl, UnperturbedBatchDriverPassesDeliotBudget) {
  const ModelEntry& m = find_model("deliot_belcour");
  const Case k = glint_case("deliot_belcour", "binomial=exact", 64);
  const ModelBudget b = model_budget("deliot_belcour", "exact", false);
  const Measured r = compare<DeliotBelcour, float>(
      m, k, run_rows_driver<DeliotBelcour, BatchWide, float>(m, k, kRowsPerSet), b);
  std::printf("%s\n", r.summary("deliot exact, baseline batch").c_str());
  EXPECT_TRUE(r.within(b)) << r.summary("deliot exact, baseline batch");
}

TEST(SimdModelNegativeControl, PerturbedStreamFailsDeliotBudget) {
  const ModelEntry& m = find_model("deliot_belcour");
  const Case k = glint_case("deliot_belcour", "binomial=exact", 64);
  const ModelBudget b = model_budget("deliot_belcour", "exact", false);
  const Measured r = compare<DeliotBelcour, float>(
      m, k, run_rows_driver<PerturbedStreamDeliot, BatchWide, float>(m, k, kRowsPerSet), b);
  std::printf("%s\n", r.summary("deliot exact, perturbed stream").c_str());
  EXPECT_GT(r.outlier_fraction, 100 * b.outlier_fraction);
  EXPECT_FALSE(r.within(b)) << r.summary("deliot exact, perturbed stream");
}

// Podee's value 2^-12 high (2048 float ulps), every other output as computed: the budget of the
// value must see it on every lit row.
struct PerturbedValuePodee : Podee {
  template <class T>
  static ModelEval<T, kIntermediates.size()> eval(const Params<T>& p, const ModelQuery<T>& q) {
    auto r = Podee::eval<T>(p, q);
    r.value = r.value * T(1.0f + 0x1p-12f);
    return r;
  }
};

TEST(SimdModelNegativeControl, PodeeBatchDriverPassesAndPerturbedValueFails) {
  const ModelEntry& m = find_model("podee");
  const Case k = glint_case("podee", "weighting=exact,selection=closest_point", 64);
  const ModelBudget b = model_budget("podee", "", false);
  const Measured ok =
      compare<Podee, float>(m, k, run_rows_driver<Podee, BatchWide, float>(m, k, kRowsPerSet), b);
  std::printf("%s\n", ok.summary("podee, baseline batch").c_str());
  EXPECT_TRUE(ok.within(b)) << ok.summary("podee, baseline batch");
  const Measured bad = compare<Podee, float>(
      m, k, run_rows_driver<PerturbedValuePodee, BatchWide, float>(m, k, kRowsPerSet), b);
  std::printf("%s\n", bad.summary("podee, perturbed value").c_str());
  EXPECT_GT(bad.outlier_fraction, 100 * b.outlier_fraction);
  EXPECT_FALSE(bad.within(b)) << bad.summary("podee, perturbed value");
}

// ---- The scalar-loop fallback ---------------------------------------------------------------

// An entry registered at run time (built by hand, no static model): value = wo_z + wi_x, pdf =
// 1/(4π), one intermediate, samples wo = (u1, u2, wi_z) unnormalized (the thunks are arbitrary).
ModelEntry runtime_entry() {
  ModelEntry e;
  e.name = "runtime_test";
  e.needs = kNeedsDirections;
  e.params = {{"k", 2.0, 0.0, 10.0, false, false, "a factor"}};
  e.intermediates = {"twice"};
  e.eval = [](const std::vector<double>& v, const ModelQuery<double>& q) {
    return ErasedEval{q.wo.z + q.wi.x * v[0], 0.25 / 3.141592653589793, {2 * q.wo.z}};
  };
  e.pdf = [](const std::vector<double>&, const ModelQuery<double>&) { return 1.0; };
  e.sample = [](const std::vector<double>& v, const ModelQuery<double>& q, Vec2<double> u) {
    return ModelSample<double>{{u.x, u.y, q.wi.z}, v[0], u.x * u.y, u.x > 0.5};
  };
  return e;
}

template <class S>
void check_fallback(const ModelEntry& e) {
  EXPECT_FALSE(is_batched(e)) << e.name;
  const Case k = make_cases(e).front();
  const std::vector<double> params = k.params.front();
  for (Isa isa : kAllIsas) {
    if (!isa_supported(isa)) continue;
    const Outputs<S> o = run_rows_batch<S>(e, k, kRowsPerSet, isa);
    std::size_t bad = 0;
    for (std::size_t s = 0; s < kParamSets; ++s) {
      for (std::size_t i = s * kRowsPerSet; i < (s + 1) * kRowsPerSet; i += 97) {
        // The batch saw the directions in S: the reference gets the same rounded values (through
        // a volatile: GCC 12 at -O3 can fold (double)(float)x away).
        const auto r = [](double x) {
          volatile S rounded = S(x);
          return double(rounded);
        };
        QueryRow<double> row{};
        for (std::size_t j = 0; j < kQueryColumns.size(); ++j) row[j] = k.query[j][i];
        for (std::size_t j : kDirectionColumns) row[j] = r(row[j]);
        const ModelQuery<double> q = from_row(row);
        const ErasedEval ev = e.eval(k.params[s], q);
        bad += o.eval[0][i] != S(ev.value) || o.eval[1][i] != S(ev.pdf) ? 1 : 0;
        for (std::size_t c = 0; c < ev.intermediates.size(); ++c)
          bad += o.eval[2 + c][i] != S(ev.intermediates[c]) ? 1 : 0;
        const ModelSample<double> sm = e.sample(k.params[s], q, {r(k.u1[i]), r(k.u2[i])});
        bad += o.sample[0][i] != S(sm.wo.x) || o.sample[2][i] != S(sm.wo.z) ||
                       o.sample[3][i] != S(sm.pdf) || o.sample[4][i] != S(sm.weight) ||
                       o.sample[5][i] != S(sm.rejected ? 1 : 0)
                   ? 1
                   : 0;
      }
    }
    EXPECT_EQ(bad, 0u) << e.name << " " << isa_name(isa);
  }
}

TEST(SimdModelFallback, RuntimeEntryIsTheScalarLoopOnEveryIsa) {
  check_fallback<double>(runtime_entry());
  check_fallback<float>(runtime_entry());
}

// A static model that is not in BatchedModels: also the loop over its double thunks.
TEST(SimdModelFallback, UnlistedStaticModelIsTheScalarLoop) {
  check_fallback<double>(make_model_entry<PerturbedEvalGgx>());
}

TEST(SimdModelBatch, ListedModelsAreBatchedAndErrorsNameTheProblem) {
  for (const ModelEntry& m : registered_models())
    if (m.name == "smooth_ggx" || m.name == "smooth_beckmann") {
      EXPECT_TRUE(is_batched(m));
    }
  const ModelEntry& m = find_model("smooth_ggx");
  const std::vector<double> params = {0.5, 0.5, 1, 0};
  std::vector<Column<double>> q(kQueryColumns.size(), Column<double>{&kQueryDefaults[0], 0});
  std::vector<double> out(9);
  std::vector<double*> o(9, out.data());
  EXPECT_THROW(eval_batch(m, std::vector<double>{0.5}, q, o, 1, Isa::kScalar),
               std::invalid_argument);
  EXPECT_THROW(eval_batch(m, params, q, std::vector<double*>(3, out.data()), 1, Isa::kScalar),
               std::invalid_argument);
  EXPECT_NO_THROW(eval_batch(m, params, q, o, 0, Isa::kScalar));
}

}  // namespace
}  // namespace glintlab::simd::test

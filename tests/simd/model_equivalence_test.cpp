// Registry-level batching (core/simd/model_batch.h): every model of BatchedModels, on every ISA
// this CPU has, against the scalar float/double instantiation of its own eval/pdf/sample, with
// stated budgets; the scalar-loop fallback for entries that are not batched; perturbed controls.
#define GLINTLAB_SIMD_TU model_test
#include "core/simd/instantiate.h"
#include "core/simd/model_instantiate.h"
// (the two above give this test the model driver on Wide<float>, for the perturbed controls)

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/model_registry.h"
#include "core/simd/batched_models.h"
#include "core/simd/inputs.h"
#include "core/simd/model_batch.h"
#include "tests/simd/simd_test_util.h"

namespace glintlab::simd::test {
namespace {

constexpr Isa kBatchIsas[] = {Isa::kSse42, Isa::kAvx2, Isa::kAvx512};
constexpr std::size_t kParamSets = 256;   // parameter vectors per choice combination
constexpr std::size_t kRowsPerSet = 512;  // query rows per parameter vector

// One model's budgets. Eval outputs (value, pdf, intermediates) and the sample's pdf and weight:
// |batch − scalar| ≤ ulp ulps, or both below √(smallest normal) in magnitude. Sampled wo: each
// component within wo_eps machine epsilons. Rejection flags may differ on flag_fraction of the
// rows (then only the flag is compared).
struct ModelBudget {
  double ulp;
  double pdf_ulp;
  double weight_ulp;
  double wo_eps;
  double flag_fraction;
  const char* why;
};

// The budgets follow the kernels the model composes (tests/simd/equivalence.cpp, which gives
// each its reason); [measured maxima over every ISA of this machine, float / double].
ModelBudget model_budget(std::string_view model, std::string_view sampler, bool dbl) {
  constexpr double kFlags = 1e-4;
  if (model == "smooth_ggx") {
    // GGX D, Λ, G1, G2 and every GGX pdf are IEEE +, −, ×, ÷, √ in the same order: bit-identical
    // [0]. wo inherits the sampler kernel's budget: Heitz's disk lift near the rim [1.06e3 /
    // 879 eps], the caps' unstretch at α = 1e-3 [36 / 21.5 eps], Walter's sin/cos [5 / 4 eps].
    const double wo = sampler == "vndf"  ? (dbl ? 65536.0 : 16384.0)
                      : sampler == "ndf" ? 16.0
                                         : 512.0;
    return {0, 0, 0, wo, kFlags, "GGX: IEEE ops only; wo as the sampler kernels"};
  }
  // Beckmann: exp/erfc of xsimd vs glibc, a few ulp each [eval 7 / 66 ulp, sample pdf 7 / 35,
  // weight 6 / 61]; the VNDF pdf of a below-horizon wi cancels (½|ωz| erfc(a) against σ e^{−a²}
  // /(2√π), condition ~2a²) [eval pdf 1.38e3 / 4.84e10 ulp]; wo: Walter [4 eps], the VNDF's
  // Newton solve [15.5 / 1.42e3 eps].
  const double value = dbl ? 128.0 : 16.0;
  const double eval = sampler == "vndf" ? (dbl ? 68719476736.0 : 8192.0) : value;
  const double wo = sampler == "vndf" ? (dbl ? 4096.0 : 64.0) : 16.0;
  return {eval, value,  value,
          wo,   kFlags, "Beckmann: exp/erfc ulps, below-horizon VNDF pdf cancellation, Newton wo"};
}

// The rows of one (model, choice combination) run: parameter vectors and query columns.
struct Case {
  std::vector<std::vector<double>> params;  // kParamSets vectors
  std::vector<std::vector<double>> query;   // kQueryColumns.size() columns
  std::vector<double> u1, u2;               // uniforms
  std::string label;
  std::string sampler;  // the `sampler` choice, where the model has one
};

std::vector<Case> make_cases(const ModelEntry& m) {
  using D = Domain;
  const std::vector<int> domains = {int(D::kAlphaX), int(D::kAlphaY), int(D::kWiX), int(D::kWiY),
                                    int(D::kWiZ),    int(D::kWoX),    int(D::kWoY), int(D::kWoZ),
                                    int(D::kU1),     int(D::kU2)};
  const std::size_t n = kParamSets * kRowsPerSet;
  const auto in = make_inputs(domains, n, 0x6d6f64656cULL);
  // Every combination of the choice parameters (their indices), in mixed-radix order.
  std::size_t combos = 1;
  for (const ParamSpec& p : m.params)
    if (!p.choices.empty()) combos *= p.choices.size();
  std::vector<Case> cases;
  for (std::size_t c = 0; c < combos; ++c) {
    Case k;
    std::size_t rest = c;
    std::vector<double> choice(m.params.size(), 0);
    for (std::size_t j = 0; j < m.params.size(); ++j) {
      if (m.params[j].choices.empty()) continue;
      choice[j] = double(rest % m.params[j].choices.size());
      if (m.params[j].name == "sampler") k.sampler = m.params[j].choices[std::size_t(choice[j])];
      k.label += std::string(k.label.empty() ? "" : ",") + std::string(m.params[j].name) + "=" +
                 std::string(m.params[j].choices[std::size_t(choice[j])]);
      rest /= m.params[j].choices.size();
    }
    for (std::size_t s = 0; s < kParamSets; ++s) {
      std::vector<double> v(m.params.size());
      const std::size_t row = s * kRowsPerSet;
      for (std::size_t j = 0; j < m.params.size(); ++j) {
        const ParamSpec& p = m.params[j];
        if (!p.choices.empty()) {
          v[j] = choice[j];
        } else if (p.name == "alpha_x" || p.name == "alpha_y") {
          v[j] = in[p.name == "alpha_x" ? 0 : 1][row];  // the edge-case roughness generator
        } else {
          // Uniform over the range, kept inside open bounds.
          const double t = (double(s) + 0.5) / double(kParamSets);
          v[j] = p.lo + t * (p.hi - p.lo);
        }
      }
      k.params.push_back(v);
    }
    k.query.assign(kQueryColumns.size(), {});
    for (std::size_t j = 0; j < kQueryColumns.size(); ++j) k.query[j].assign(n, kQueryDefaults[j]);
    for (std::size_t j = 0; j < 6; ++j) k.query[6 + j] = in[2 + j];
    k.u1 = in[8];
    k.u2 = in[9];
    cases.push_back(std::move(k));
  }
  return cases;
}

template <class S>
std::vector<S> as(const std::vector<double>& v) {
  return std::vector<S>(v.begin(), v.end());
}

// Outputs of eval (2 + M columns) and sample (6 columns) of one case through the batch API.
template <class S>
struct Outputs {
  std::vector<std::vector<S>> eval, sample;
};

// Runs eval and sample of one case, kRowsPerSet rows per parameter vector, through `eval` and
// `sample` (callables taking params, query columns, u1, u2, output pointers, n).
template <class S, class Eval, class Sample>
Outputs<S> run_with(const ModelEntry& m, const Case& k, Eval eval, Sample sample) {
  const std::size_t n = kParamSets * kRowsPerSet;
  std::vector<std::vector<S>> q;
  for (const auto& c : k.query) q.push_back(as<S>(c));
  const std::vector<S> u1 = as<S>(k.u1), u2 = as<S>(k.u2);
  Outputs<S> o;
  o.eval.assign(2 + m.intermediates.size(), std::vector<S>(n));
  o.sample.assign(kSampleColumns.size(), std::vector<S>(n));
  for (std::size_t s = 0; s < kParamSets; ++s) {
    const std::size_t b = s * kRowsPerSet;
    std::vector<Column<S>> cols;
    for (const auto& c : q) cols.push_back({c.data() + b, 1});
    std::vector<S*> eo, so;
    for (auto& c : o.eval) eo.push_back(c.data() + b);
    for (auto& c : o.sample) so.push_back(c.data() + b);
    eval(k.params[s], cols, eo, kRowsPerSet);
    sample(k.params[s], cols, Column<S>{u1.data() + b, 1}, Column<S>{u2.data() + b, 1}, so,
           kRowsPerSet);
  }
  return o;
}

template <class S>
Outputs<S> run_batch(const ModelEntry& m, const Case& k, Isa isa) {
  return run_with<S>(
      m, k,
      [&](const std::vector<double>& p, const std::vector<Column<S>>& c, const std::vector<S*>& o,
          std::size_t n) { eval_batch(m, p, c, o, n, isa); },
      [&](const std::vector<double>& p, const std::vector<Column<S>>& c, Column<S> u1, Column<S> u2,
          const std::vector<S*>& o, std::size_t n) { sample_batch(m, p, c, u1, u2, o, n, isa); });
}

// The model driver of core/simd/model_instantiate.h on W, called directly (for models that are
// not in BatchedModels: the perturbed controls).
template <class M, class W, class S>
Outputs<S> run_driver(const ModelEntry& m, const Case& k) {
  return run_with<S>(
      m, k,
      [](const std::vector<double>& p, const std::vector<Column<S>>& c, const std::vector<S*>& o,
         std::size_t n) { detail::run_model_eval<M, W, S>(p.data(), c.data(), o.data(), n); },
      [](const std::vector<double>& p, const std::vector<Column<S>>& c, Column<S> u1, Column<S> u2,
         const std::vector<S*>& o, std::size_t n) {
        const Column<S> u[2] = {u1, u2};
        detail::run_model_sample<M, W, S>(p.data(), c.data(), u, o.data(), n);
      });
}

// Error of batched values against a reference: ulps, with both-tiny values equal.
template <class S>
double value_ulps(S got, S ref) {
  const S tiny = std::sqrt(std::numeric_limits<S>::min());
  if (std::abs(got) < tiny && std::abs(ref) < tiny) return 0;
  return ulp_distance(got, ref);
}

struct Measured {
  double eval_ulp = 0, pdf_ulp = 0, weight_ulp = 0, wo_eps = 0, flag_fraction = 0;
  std::string worst_eval;  // which output
  std::string summary(const std::string& what) const {
    char b[256];
    std::snprintf(b, sizeof b,
                  "%s: eval %.3g ulp (%s), sample pdf %.3g ulp, weight %.3g ulp, wo %.3g eps, "
                  "flags %.2g",
                  what.c_str(), eval_ulp, worst_eval.c_str(), pdf_ulp, weight_ulp, wo_eps,
                  flag_fraction);
    return b;
  }
  bool within(const ModelBudget& b) const {
    return eval_ulp <= b.ulp && pdf_ulp <= b.pdf_ulp && weight_ulp <= b.weight_ulp &&
           wo_eps <= b.wo_eps && flag_fraction <= b.flag_fraction;
  }
};

// Compares batch outputs with the scalar instantiation M::eval<S> / M::sample<S>, and the sampled
// pdf with the scalar M::pdf<S> at the batch's own wo (the sampler's contract).
template <class M, class S>
Measured compare(const ModelEntry& m, const Case& k, const Outputs<S>& got) {
  Measured r;
  std::size_t flags = 0;
  const S eps = std::numeric_limits<S>::epsilon();
  for (std::size_t s = 0; s < kParamSets; ++s) {
    const auto p = M::template params<S>(k.params[s]);
    for (std::size_t i = s * kRowsPerSet; i < (s + 1) * kRowsPerSet; ++i) {
      double v[kQueryColumns.size()];
      for (std::size_t j = 0; j < kQueryColumns.size(); ++j) v[j] = k.query[j][i];
      ModelQuery<S> q;
      q.footprint = {{S(v[0]), S(v[1])}, {S(v[2]), S(v[3])}, {S(v[4]), S(v[5])}};
      q.wi = {S(v[6]), S(v[7]), S(v[8])};
      q.wo = {S(v[9]), S(v[10]), S(v[11])};
      q.light = {S(v[12]), S(v[13])};
      const auto e = M::template eval<S>(p, q);
      std::vector<S> ref = {e.value, e.pdf};
      ref.insert(ref.end(), e.intermediates.begin(), e.intermediates.end());
      for (std::size_t c = 0; c < ref.size(); ++c) {
        const double d = value_ulps(got.eval[c][i], ref[c]);
        if (d > r.eval_ulp) {
          r.eval_ulp = d;
          r.worst_eval = c == 0 ? "value" : c == 1 ? "pdf" : std::string(m.intermediates[c - 2]);
        }
      }
      const ModelSample<S> ss = M::template sample<S>(p, q, Vec2<S>{S(k.u1[i]), S(k.u2[i])});
      const bool rej_ref = static_cast<bool>(ss.rejected), rej = got.sample[5][i] != 0;
      if (rej || rej_ref) {
        flags += rej != rej_ref ? 1 : 0;
        continue;
      }
      const S wo_ref[3] = {ss.wo.x, ss.wo.y, ss.wo.z};
      for (int c = 0; c < 3; ++c)
        r.wo_eps =
            std::max(r.wo_eps, double(std::abs(got.sample[std::size_t(c)][i] - wo_ref[c]) / eps));
      // The sample's pdf and weight against the scalar model at the batch's own wo: the pdf
      // is M::pdf there, the weight value/pdf (the estimator the sample stands for).
      ModelQuery<S> qo = q;
      qo.wo = {got.sample[0][i], got.sample[1][i], got.sample[2][i]};
      const S pdf = M::template pdf<S>(p, qo);
      r.pdf_ulp = std::max(r.pdf_ulp, value_ulps(got.sample[3][i], pdf));
      const S weight = M::template eval<S>(p, qo).value / pdf;
      r.weight_ulp = std::max(r.weight_ulp, value_ulps(got.sample[4][i], weight));
    }
  }
  r.flag_fraction = double(flags) / double(kParamSets * kRowsPerSet);
  return r;
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
    for (const Case& k : make_cases(m)) {
      const ModelBudget b = model_budget(m.name, k.sampler, sizeof(S) == 8);
      // The scalar ISA runs the very same instantiation: bit-identical.
      const Measured s = compare<M, S>(m, k, run_batch<S>(m, k, Isa::kScalar));
      EXPECT_EQ(s.eval_ulp + s.pdf_ulp + s.weight_ulp + s.wo_eps + s.flag_fraction, 0.0)
          << s.summary(std::string(m.name) + " " + k.label + " scalar");
      for (Isa isa : kBatchIsas) {
        if (!isa_supported(isa)) continue;
        const Measured r = compare<M, S>(m, k, run_batch<S>(m, k, isa));
        const std::string what = std::string(m.name) + " " + k.label + " " +
                                 std::string(isa_name(isa)) +
                                 (sizeof(S) == 8 ? " double" : " float");
        std::printf("%s\n", r.summary(what).c_str());
        EXPECT_TRUE(r.within(b)) << r.summary(what) << "; budget " << b.ulp << " ulp, " << b.pdf_ulp
                                 << " ulp, " << b.weight_ulp << " ulp, " << b.wo_eps << " eps, "
                                 << b.flag_fraction << " (" << b.why << ")";
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
      m, ggx_ndf_case(), run_driver<SmoothGGX, LocalWide, float>(m, ggx_ndf_case()));
  EXPECT_TRUE(r.within(model_budget("smooth_ggx", "ndf", false))) << r.summary("local");
}

TEST(SimdModelNegativeControl, PerturbedEvalFailsGgxBudget) {
  const ModelEntry& m = find_model("smooth_ggx");
  const Measured r = compare<SmoothGGX, float>(
      m, ggx_ndf_case(), run_driver<PerturbedEvalGgx, LocalWide, float>(m, ggx_ndf_case()));
  std::printf("%s\n", r.summary("perturbed eval").c_str());
  EXPECT_GE(r.eval_ulp, 3.0);
  EXPECT_FALSE(r.within(model_budget("smooth_ggx", "ndf", false))) << r.summary("perturbed eval");
}

TEST(SimdModelNegativeControl, PerturbedSampleFailsGgxBudget) {
  const ModelEntry& m = find_model("smooth_ggx");
  const Measured r = compare<SmoothGGX, float>(
      m, ggx_ndf_case(), run_driver<PerturbedSampleGgx, LocalWide, float>(m, ggx_ndf_case()));
  std::printf("%s\n", r.summary("perturbed sample").c_str());
  EXPECT_GT(r.wo_eps, 16.0);
  EXPECT_FALSE(r.within(model_budget("smooth_ggx", "ndf", false))) << r.summary("perturbed sample");
}

// ---- The scalar-loop fallback ---------------------------------------------------------------

// An entry registered at run time (built by hand, no static model): value = wo_z + wi_x, pdf =
// 1/(4π), one intermediate, samples wo = (u1, u2, wi_z) unnormalized (the thunks are arbitrary).
ModelEntry runtime_entry() {
  ModelEntry e;
  e.name = "runtime_test";
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
    const Outputs<S> o = run_batch<S>(e, k, isa);
    std::size_t bad = 0;
    for (std::size_t s = 0; s < kParamSets; ++s) {
      for (std::size_t i = s * kRowsPerSet; i < (s + 1) * kRowsPerSet; i += 97) {
        ModelQuery<double> q;
        q.footprint = {{k.query[0][i], k.query[1][i]},
                       {k.query[2][i], k.query[3][i]},
                       {k.query[4][i], k.query[5][i]}};
        // The batch saw the query in S: the reference gets the same rounded values (through a
        // volatile: GCC 12 at -O3 can fold (double)(float)x away).
        const auto r = [](double x) {
          volatile S rounded = S(x);
          return double(rounded);
        };
        q.wi = {r(k.query[6][i]), r(k.query[7][i]), r(k.query[8][i])};
        q.wo = {r(k.query[9][i]), r(k.query[10][i]), r(k.query[11][i])};
        q.light = {k.query[12][i], k.query[13][i]};
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

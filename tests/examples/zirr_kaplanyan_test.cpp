// The example plug-in model examples/zirr_kaplanyan (Zirr & Kaplanyan 2016), compiled here from its
// header and registered in-process as a plug-in would be: the paper's quantities (the reflection
// probability as the slope-disk mass of P22, the count's mean and variance against a directly
// simulated binomial, the normal approximation's energy gain at small counts, the smooth GGX
// limit), its sampler against its pdf, float against double and the SIMD instantiations. Each
// statistical comparison is also run on a deliberately wrong expectation, which it must reject.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string_view>
#include <vector>

#include "core/math/rng.h"
#include "core/model_registry.h"
#include "core/simd/wide.h"
#include "core/simd/wide_lanes.h"
#include "verify/check.h"
#include "verify/generic/model_sampler_gof.h"
#include "verify/stability/failure_region.h"
#include "verify/stability/sweep_plan.h"
#include "verify/stats/multiple_testing.h"
#include "zirr_kaplanyan.h"

namespace glintlab {
namespace {

using zk16::ZirrKaplanyan;
using P = ZirrKaplanyan::Params<double>;

const ModelEntry& model() {
  static const bool registered = [] {
    register_model(make_model_entry<ZirrKaplanyan>());
    return true;
  }();
  (void)registered;
  return find_model(ZirrKaplanyan::kName);
}

std::vector<double> values(const std::vector<std::pair<std::string, std::string>>& a = {}) {
  return resolve_params(model(), a);
}

Vec3<double> direction(double theta_deg, double phi_deg) {
  const double t = theta_deg * std::numbers::pi / 180, f = phi_deg * std::numbers::pi / 180;
  return {std::sin(t) * std::cos(f), std::sin(t) * std::sin(f), std::cos(t)};
}

// A square footprint of the given uv area centred at uv.
ModelQuery<double> query(Vec3<double> wi, Vec3<double> wo, double area, Vec2<double> uv = {0.3, 0.6}) {
  ModelQuery<double> q{};
  const double side = std::sqrt(area);
  q.wi = wi;
  q.wo = wo;
  q.footprint = {uv, {side, 0}, {0, side}};
  q.light = {1.0, 1.0};
  return q;
}

std::size_t at(std::string_view name) {
  const auto& n = model().intermediates;
  return std::size_t(std::find(n.begin(), n.end(), name) - n.begin());
}

// Sample mean and (unbiased) variance.
struct Moments {
  double mean = 0, var = 0;
  std::size_t n = 0;
};
Moments moments(const std::vector<double>& x) {
  Moments m;
  m.n = x.size();
  for (double v : x) m.mean += v;
  m.mean /= double(m.n);
  for (double v : x) m.var += (v - m.mean) * (v - m.mean);
  m.var /= double(m.n - 1);
  return m;
}

// Whether two samples' means agree (|z| < 4 for the two-sample standard error) and whether
// Var(x) = factor·Var(y) (|log ratio| < 4 standard errors; the standard error of a log-variance
// is √((κ − 1)/n) with κ the kurtosis, estimated from each sample).
struct Spread {
  Moments m;
  double log_var_se2;  // squared standard error of log Var
};
Spread spread(const std::vector<double>& x) {
  const Moments m = moments(x);
  double m4 = 0;
  for (double v : x) m4 += std::pow(v - m.mean, 4);
  m4 /= double(m.n);
  return {m, (m4 / (m.var * m.var) - 1) / double(m.n)};
}
bool mean_matches(const std::vector<double>& x, double expected) {
  const Moments m = moments(x);
  return std::abs(m.mean - expected) < 4 * std::sqrt(m.var / double(m.n));
}
bool means_agree(const std::vector<double>& x, const std::vector<double>& y, double y_scale = 1) {
  const Moments a = moments(x), b = moments(y);
  return std::abs(a.mean - y_scale * b.mean) <
         4 * std::sqrt(a.var / double(a.n) + y_scale * y_scale * b.var / double(b.n));
}
bool variances_agree(const std::vector<double>& x, const std::vector<double>& y, double factor) {
  const Spread a = spread(x), b = spread(y);
  return std::abs(std::log(a.m.var / (factor * b.m.var))) <
         4 * std::sqrt(a.log_var_se2 + b.log_var_se2);
}
bool variance_matches(const std::vector<double>& x, double expected_var) {
  const Spread a = spread(x);
  return std::abs(std::log(a.m.var / expected_var)) < 4 * std::sqrt(a.log_var_se2);
}

// Binomial(n, p) counts by direct simulation of n Bernoulli trials each.
std::vector<double> simulate_binomial(int n, double p, std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution trial(p);
  std::vector<double> out(count);
  for (auto& k : out) {
    int c = 0;
    for (int i = 0; i < n; ++i) c += trial(rng);
    k = c;
  }
  return out;
}

TEST(ZirrKaplanyan, RegistersWithItsParametersSmoothLimitAndFloatPath) {
  const ModelEntry& m = model();
  EXPECT_EQ(m.params.size(), 6u);
  EXPECT_TRUE(m.eval_float) << "the kernels instantiate for float";
  EXPECT_THROW(register_model(make_model_entry<ZirrKaplanyan>()), ModelParamError);
  EXPECT_THROW(values({{"microroughness", "0"}}), ModelParamError);
  EXPECT_THROW(values({{"binomial", "exact"}}), ModelParamError);
  EXPECT_THROW(values({{"seed", "1.5"}}), ModelParamError);
  // The declared smooth limit is registered and takes our roughness parameters by name.
  const ModelEntry& smooth = find_model(ZirrKaplanyan::kSmoothLimit);
  for (const char* name : {"alpha_x", "alpha_y"}) {
    const auto has = [&](const ModelEntry& e) {
      return std::any_of(e.params.begin(), e.params.end(),
                         [&](const ParamSpec& s) { return s.name == name; });
    };
    EXPECT_TRUE(has(m)) << name;
    EXPECT_TRUE(has(smooth)) << name;
  }
  constexpr std::array<std::string_view, 10> kProperties = {
      "eval-pdf-consistency", "sampler-matches-pdf", "sampler-covers-value", "pdf-normalized",
      "energy",               "float-vs-double",     "simd-equivalence",     "stability",
      "converges-to-smooth",  "constant-time"};
  for (const auto& nc : ZirrKaplanyan::kNotClaimed) {
    EXPECT_NE(std::find(kProperties.begin(), kProperties.end(), nc.property), kProperties.end())
        << nc.property;
    EXPECT_FALSE(nc.reason.empty());
  }
}

// p = π β² P22(s_h) is the first-order value of the slope-disk integral ∫_{|s − s_h| < β} P22 ds;
// P22 here is GGX's slope distribution in its own closed form, not through D(h) h_z⁴.
TEST(ZirrKaplanyan, ReflectionProbabilityIsTheSlopeDiskMassOfP22) {
  const double ax = 0.3, ay = 0.2;
  const auto p22 = [&](double sx, double sy) {
    const double e = 1 + sx * sx / (ax * ax) + sy * sy / (ay * ay);
    return 1 / (std::numbers::pi * ax * ay * e * e);
  };
  const auto disk_mass = [&](double cx, double cy, double beta) {
    // Midpoint rule in polar coordinates, 200 × 256 cells.
    double sum = 0;
    const int nr = 200, nt = 256;
    for (int i = 0; i < nr; ++i)
      for (int j = 0; j < nt; ++j) {
        const double r = beta * (i + 0.5) / nr, t = 2 * std::numbers::pi * (j + 0.5) / nt;
        sum += p22(cx + r * std::cos(t), cy + r * std::sin(t)) * r;
      }
    return sum * (beta / nr) * (2 * std::numbers::pi / nt);
  };
  const double beta = 0.01;
  const auto v = values({{"alpha_x", "0.3"}, {"alpha_y", "0.2"}, {"microroughness", "0.01"}});
  const Vec3<double> wi = direction(40, 10);
  int checked = 0;
  for (double theta : {0.0, 20.0, 45.0, 70.0})
    for (double phi : {0.0, 60.0, 200.0}) {
      const Vec3<double> wo = direction(theta, phi);
      const ErasedEval e = model().eval(v, query(wi, wo, 1e-4));
      const Vec3<double> h = normalize(wi + wo);
      const double sx = -h.x / h.z, sy = -h.y / h.z;
      const double mass = disk_mass(sx, sy, beta);
      const double p = e.intermediates[at("p")];
      EXPECT_NEAR(p / mass, 1.0, 2e-3) << theta << " " << phi;
      // A microdetail lobe 3 % wider is a p 6 % larger: the comparison tells them apart.
      EXPECT_GT(std::abs(disk_mass(sx, sy, beta * 1.03) / p - 1), 0.05) << theta << " " << phi;
      ++checked;
    }
  EXPECT_EQ(checked, 12);
}

// Counts over seeds at one query: each seed hashes other cells, so the counts are independent
// draws of the blended count Σ w_j X_j: mean N p (the binomial's) and variance N p (1 − p) Σ w_j²,
// against Binomial(N, p) simulated trial by trial. A variance of N p (a Poisson count, forgetting
// 1 − p: 11 % too large here), a variance 5 % too large and a mean 1 % too large are rejected.
TEST(ZirrKaplanyan, CountMeanAndVarianceMatchADirectlySimulatedBinomial) {
  const int n_trials = 400;
  // α = 0.25 and β = 0.079 give p = β²/α² ≈ 0.1 at h = n (P22(0) = 1/(π α²)).
  const Vec3<double> up{0, 0, 1};
  // Area 4^-(5.3): λ = 5.3, t = 0.3 between the two levels.
  const double area = std::pow(4.0, -5.3);
  const std::string density = fmt::format("{:.17g}", std::log10(n_trials / area));
  const std::size_t kSamples = 100000;
  for (const char* approx : {"normal", "small_count"}) {
    SCOPED_TRACE(approx);
    std::vector<double> count(kSamples);
    double p = 0, variance_factor = 0, n = 0;
    auto v = values({{"density", density}, {"microroughness", "0.079"}, {"binomial", approx}});
    for (std::size_t s = 0; s < kSamples; ++s) {
      v[param_index<ZirrKaplanyan>("seed")] = double(s);
      const ErasedEval e = model().eval(v, query(up, up, area));
      count[s] = e.intermediates[at("count")];
      p = e.intermediates[at("p")];
      n = e.intermediates[at("N_P")];
      variance_factor = e.intermediates[at("variance_factor")];
    }
    ASSERT_EQ(n, n_trials);
    EXPECT_NEAR(p, 0.079 * 0.079 / (0.25 * 0.25), 1e-12);
    // The blend weights: levels 0.7/0.3, and at h = n the slope grid puts s_h on a cell corner
    // (s/(2β) − ½ = −½): four cells of ¼ each.
    EXPECT_NEAR(variance_factor, (0.7 * 0.7 + 0.3 * 0.3) / 4, 1e-9);
    const std::vector<double> direct =
        simulate_binomial(n_trials, p, kSamples, hash_string("zk16.count-moments"));
    const Moments d = moments(direct);
    // The simulation itself against the binomial's moments.
    EXPECT_TRUE(mean_matches(direct, n_trials * p)) << d.mean;
    EXPECT_TRUE(variance_matches(direct, n_trials * p * (1 - p))) << d.var;
    const Moments c = moments(count);
    EXPECT_TRUE(means_agree(count, direct)) << c.mean << " vs " << d.mean;
    EXPECT_TRUE(variances_agree(count, direct, variance_factor))
        << c.var << " vs " << d.var * variance_factor;
    // Negative controls: the comparisons reject a wrong count variance or mean.
    EXPECT_FALSE(variance_matches(count, n_trials * p * variance_factor));
    EXPECT_FALSE(variances_agree(count, direct, 1.05 * variance_factor));
    EXPECT_FALSE(means_agree(count, direct, 1.01));
    fmt::print("{}: count mean {:.4f} (simulated binomial {:.4f}), variance {:.4f} (simulated x "
               "blend factor {:.4f})\n",
               approx, c.mean, d.mean, c.var, d.var * variance_factor);
  }
}

// The paper's normal approximation, clamped at 0, has a mean above N p where N p is small: the
// energy gain Kemppinen et al. 2025 (Fig. 15) report for this model. The mean factor b/(N p) over
// seeds equals the closed form E[clamp(X, 0, N)]/(N p) (1.197 at N p = 0.5), not 1; the
// small_count inversion is exact there and its mean factor is 1.
TEST(ZirrKaplanyan, NormalApproximationGainsEnergyAtSmallCounts) {
  const Vec3<double> up{0, 0, 1};
  const double area = std::pow(4.0, -6.0);
  const int n_trials = 50;  // p = 0.01: N p = 0.5
  const std::string density = fmt::format("{:.17g}", std::log10(n_trials / area));
  const std::string beta = fmt::format("{:.17g}", 0.25 * 0.1);
  const std::size_t kSamples = 40000;
  std::vector<double> normal(kSamples), small(kSamples);
  double p = 0;
  for (std::size_t s = 0; s < kSamples; ++s) {
    const std::string seed = std::to_string(s);
    auto v = values({{"density", density}, {"microroughness", beta}, {"seed", seed}});
    ErasedEval e = model().eval(v, query(up, up, area));
    normal[s] = e.intermediates[at("factor")];
    p = e.intermediates[at("p")];
    v = values({{"density", density},
                {"microroughness", beta},
                {"seed", seed},
                {"binomial", "small_count"}});
    small[s] = model().eval(v, query(up, up, area)).intermediates[at("factor")];
  }
  const double gain = zk16::count_normal_mean(n_trials, p) / (n_trials * p);
  EXPECT_NEAR(gain, 1.1974, 1e-3);  // the closed form, checked by Monte Carlo
  EXPECT_TRUE(mean_matches(normal, gain)) << moments(normal).mean << " vs " << gain;
  EXPECT_FALSE(mean_matches(normal, 1.0)) << "the gain is measurable";
  EXPECT_FALSE(mean_matches(normal, 0.97 * gain));
  EXPECT_TRUE(mean_matches(small, 1.0)) << moments(small).mean;
  EXPECT_FALSE(mean_matches(small, 1.03));
  fmt::print("energy factor at N p = 0.5: normal {:.4f} (closed form {:.4f}), small_count {:.4f}\n",
             moments(normal).mean, gain, moments(small).mean);
}

// As N_P grows the value tends to smooth_ggx's with the same α (the declared smooth limit): the
// relative deviation is within 5 predicted standard deviations √(Σw² (1 − p)/(N p)), and the
// RMS deviation over seeds falls as 1/√N. A smooth GGX with α 3 % off is outside the tolerance.
TEST(ZirrKaplanyan, TendsToSmoothGGXAsTheCountGrows) {
  const ModelEntry& smooth = find_model(ZirrKaplanyan::kSmoothLimit);
  const std::vector<double> sv = resolve_params(smooth, {{"alpha_x", "0.3"}, {"alpha_y", "0.2"}});
  const std::vector<double> off = resolve_params(smooth, {{"alpha_x", "0.309"}, {"alpha_y", "0.2"}});
  const double area = 1e-4;
  const auto v = values({{"alpha_x", "0.3"}, {"alpha_y", "0.2"}, {"density", "12"}});
  int rows = 0, off_rejected = 0;
  for (double ti : {0.0, 30.0, 60.0})
    for (double to : {10.0, 35.0, 55.0})
      for (double phi : {90.0, 180.0, 300.0}) {
        const ModelQuery<double> q = query(direction(ti, 0), direction(to, phi), area);
        const ErasedEval e = model().eval(v, q);
        const double expected = smooth.eval(sv, q).value;
        const double np = e.intermediates[at("expected_count")];
        const double sd = std::sqrt(e.intermediates[at("variance_factor")] *
                                    (1 - e.intermediates[at("p")]) / np);
        ASSERT_GT(np, 1e3);
        EXPECT_NEAR(e.value / expected, 1.0, 5 * sd + 1e-12) << ti << " " << to << " " << phi;
        EXPECT_NEAR(e.pdf, smooth.eval(sv, q).pdf, 1e-12 * e.pdf) << "the same VNDF pdf";
        off_rejected += std::abs(e.value / smooth.eval(off, q).value - 1) > 5 * sd + 1e-12;
        ++rows;
      }
  EXPECT_EQ(rows, 27);
  EXPECT_GE(off_rejected, 20) << "a 3 % wrong roughness is seen on most rows";

  // RMS relative deviation over seeds against the prediction, N_P from 1e2 to 1e8.
  const Vec3<double> wi = direction(30, 0), wo = direction(40, 150);
  const double expected = smooth.eval(sv, query(wi, wo, area)).value;
  double previous_rms = INFINITY;
  for (int decade = 6; decade <= 12; decade += 2) {
    double sum2 = 0, predicted = 0;
    const int kSeeds = 2000;
    for (int s = 0; s < kSeeds; ++s) {
      const auto vs = values({{"alpha_x", "0.3"},
                              {"alpha_y", "0.2"},
                              {"density", std::to_string(decade)},
                              {"binomial", "small_count"},
                              {"seed", std::to_string(s)}});
      const ErasedEval e = model().eval(vs, query(wi, wo, area));
      sum2 += std::pow(e.value / expected - 1, 2);
      predicted = e.intermediates[at("variance_factor")] * (1 - e.intermediates[at("p")]) /
                  e.intermediates[at("expected_count")];
    }
    const double rms = std::sqrt(sum2 / kSeeds);
    EXPECT_NEAR(rms / std::sqrt(predicted), 1.0, 0.1) << "N_P = 1e" << decade - 4;
    EXPECT_LT(rms, previous_rms);
    previous_rms = rms;
    fmt::print("N_P = 1e{}: RMS relative deviation from smooth_ggx {:.3e} (predicted {:.3e})\n",
               decade - 4, rms, std::sqrt(predicted));
  }
}

TEST(ZirrKaplanyan, SampleWeightIsValueOverPdfAndPdfMatches) {
  const auto v = values({{"density", "7"}});
  const ModelQuery<double> base = query(direction(50, 20), {0, 0, 1}, 2e-5);
  int accepted = 0;
  for (std::uint64_t i = 0; i < 4000; ++i) {
    const Vec2<double> u{counter_uniform<double>(7, i, 0), counter_uniform<double>(7, i, 1)};
    const ModelSample<double> s = model().sample(v, base, u);
    if (s.rejected) {
      EXPECT_EQ(s.weight, 0);
      continue;
    }
    ++accepted;
    ModelQuery<double> at_wo = base;
    at_wo.wo = s.wo;
    const ErasedEval e = model().eval(v, at_wo);
    EXPECT_NEAR(s.pdf, model().pdf(v, at_wo), 1e-12 * s.pdf);
    EXPECT_NEAR(e.pdf, s.pdf, 1e-12 * s.pdf);
    EXPECT_NEAR(s.weight, e.value / s.pdf, 1e-12 * (1 + s.weight));
  }
  EXPECT_GT(accepted, 3500);  // the VNDF puts ~7 % of its samples below the horizon here
  // The sampler against its own pdf (chi-square on the sphere), and the pdf 5 % too large rejected.
  verify::ModelGofOptions o;
  o.samples = 1u << 16;
  const std::string id = "zk16.sampler-matches-pdf";
  const auto good = verify::model_sampler_chi_square(model(), v, base, verify::check_seed(id, 0), o);
  EXPECT_FALSE(good.inconclusive) << good.reason;
  EXPECT_GT(good.p_value, verify::kFamilyWiseRate) << good.summary();
  o.pdf_scale = 1.05;
  const auto bad = verify::model_sampler_chi_square(model(), v, base, verify::check_seed(id, 1), o);
  EXPECT_TRUE(bad.rejects(verify::kFamilyWiseRate)) << bad.summary();
}

// Float against double on random queries: the same cells are hashed (keys in double from the
// float-rounded inputs), so all but rows on a cell boundary agree to float rounding. The control:
// a double evaluation with another seed disagrees on most rows.
TEST(ZirrKaplanyan, FloatAgreesWithDouble) {
  const ModelEntry& m = model();
  const auto v = values({{"density", "8"}, {"microroughness", "0.03"}});
  const auto other = values({{"density", "8"}, {"microroughness", "0.03"}, {"seed", "1"}});
  const int kRows = 4000;
  int off = 0, off_control = 0, nonzero = 0;
  const auto differ = [](double a, double b) {
    return std::abs(a - b) > 2e-3 * std::max(std::abs(a), std::abs(b)) + 1e-6;
  };
  for (int i = 0; i < kRows; ++i) {
    const auto u = [&](int d) { return counter_uniform<double>(11, std::uint64_t(i), std::uint64_t(d)); };
    const ModelQuery<double> q =
        query(direction(80 * u(0), 360 * u(1)), direction(80 * u(2), 360 * u(3)),
              std::pow(10.0, -7 + 3 * u(4)), {u(5), u(6)});
    const double d = m.eval(v, q).value;
    off += differ(d, m.eval_float(v, q).value);
    off_control += differ(d, m.eval(other, q).value);
    nonzero += d > 0;
  }
  EXPECT_GT(nonzero, kRows / 2);
  EXPECT_LE(off, kRows / 200) << off << " of " << kRows;
  EXPECT_GT(off_control, kRows / 2) << off_control << " of " << kRows;
  fmt::print("float vs double: {} of {} rows differ by more than 2e-3 relative\n", off, kRows);
}

// The kernels instantiate on the SIMD types: Wide<float, ExactMath> gives the scalar float result
// bit for bit, an xsimd double batch (this build's baseline ISA) every lane's scalar double result
// to rounding; sample() too.
TEST(ZirrKaplanyan, InstantiatesOnWideTypes) {
  const auto v = values({{"density", "8"}, {"microroughness", "0.03"}, {"binomial", "normal"}});
  using WF = Wide<float, ExactMath>;
  const auto pf = ZirrKaplanyan::params<float>(v);
  const auto pw = ZirrKaplanyan::params<WF>(v);
  const auto to_wide = [](const ModelQuery<float>& q) {
    ModelQuery<WF> w{};
    w.wi = {WF(q.wi.x), WF(q.wi.y), WF(q.wi.z)};
    w.wo = {WF(q.wo.x), WF(q.wo.y), WF(q.wo.z)};
    w.footprint.uv = {WF(q.footprint.uv.x), WF(q.footprint.uv.y)};
    w.footprint.duv_dx = {WF(q.footprint.duv_dx.x), WF(q.footprint.duv_dx.y)};
    w.footprint.duv_dy = {WF(q.footprint.duv_dy.x), WF(q.footprint.duv_dy.y)};
    w.light = {WF(1.0f), WF(1.0f)};
    return w;
  };
  using B = xsimd::batch<double>;
  using WB = Wide<B, ExactMath>;
  constexpr std::size_t kL = B::size;
  const auto pb = ZirrKaplanyan::params<WB>(v);
  int batch_off = 0;
  for (int g = 0; g < 200; ++g) {
    alignas(64) double lane[10][kL];
    std::array<ModelQuery<double>, kL> qs{};
    for (std::size_t j = 0; j < kL; ++j) {
      const std::uint64_t i = std::uint64_t(g) * kL + j;
      const auto u = [&](int d) { return counter_uniform<double>(13, i, std::uint64_t(d)); };
      qs[j] = query(direction(70 * u(0), 360 * u(1)), direction(70 * u(2), 360 * u(3)),
                    std::pow(10.0, -7 + 3 * u(4)), {u(5), u(6)});
      const ModelQuery<double>& q = qs[j];
      const double c[10] = {q.wi.x, q.wi.y, q.wi.z, q.wo.x, q.wo.y, q.wo.z,
                            q.footprint.uv.x, q.footprint.uv.y, q.footprint.duv_dx.x,
                            q.footprint.duv_dy.y};
      for (int k = 0; k < 10; ++k) lane[k][j] = c[k];
      // Wide<float>: bit for bit with the scalar float kernel.
      const ModelQuery<float> qf = detail::to_float(q);
      const auto sf = ZirrKaplanyan::eval(pf, qf);
      const auto sw = ZirrKaplanyan::eval(pw, to_wide(qf));
      EXPECT_EQ(std::bit_cast<std::uint32_t>(sf.value), std::bit_cast<std::uint32_t>(sw.value.v));
      const auto ssf = ZirrKaplanyan::sample(pf, qf, Vec2<float>{0.3f, 0.8f});
      const auto ssw = ZirrKaplanyan::sample(pw, to_wide(qf), Vec2<WF>{WF(0.3f), WF(0.8f)});
      EXPECT_EQ(std::bit_cast<std::uint32_t>(ssf.weight), std::bit_cast<std::uint32_t>(ssw.weight.v));
    }
    const auto load = [&](int k) { return WB::wrap(B::load_aligned(lane[k])); };
    ModelQuery<WB> qb{};
    qb.wi = {load(0), load(1), load(2)};
    qb.wo = {load(3), load(4), load(5)};
    qb.footprint.uv = {load(6), load(7)};
    qb.footprint.duv_dx = {load(8), WB(0.0)};
    qb.footprint.duv_dy = {WB(0.0), load(9)};
    qb.light = {WB(1.0), WB(1.0)};
    const auto eb = ZirrKaplanyan::eval(pb, qb);
    alignas(64) double out[kL];
    eb.value.v.store_aligned(out);
    for (std::size_t j = 0; j < kL; ++j) {
      const double s = model().eval(v, qs[j]).value;
      batch_off += std::abs(out[j] - s) > 1e-9 * std::max(1.0, std::abs(s));
    }
  }
  EXPECT_EQ(batch_off, 0);
}

// The stability sweep every registered model gets (glintlab sweep --models zirr_kaplanyan, the
// claim all.stability): α from 1e-4, θi to grazing and back-facing, anisotropy, density,
// microroughness and footprint over their ranges, double and float. Each defect class prints its
// verdict and region. NaN, Inf or negative values must not occur anywhere, nor p > 1 (p is
// saturated). The energy gain must be found: it is the paper's clamped normal approximation at
// N_P p ≪ 1 (mean factor ≈ 0.4/√(N_P p)), the reason the model declares "energy" not claimed.
TEST(ZirrKaplanyan, StabilitySweep) {
  model();
  const auto targets = verify::stability::sweep_targets("zirr_kaplanyan");
  ASSERT_EQ(targets.size(), 1u);
  const auto s = verify::stability::sweep_model(targets[0], verify::Budget::kQuick);
  std::vector<std::string> planes;
  for (const auto& m : s.maps) planes.push_back(m.plane.name);
  fmt::print("planes: {}\n", fmt::join(planes, ", "));
  fmt::print("{}\n", verify::stability::describe_failure_region(s));
  using verify::stability::DefectClass;
  for (auto kind : {DefectClass::kBreaks, DefectClass::kEnergyGain,
                    DefectClass::kProbabilityAboveOne, DefectClass::kHugeVariance})
    fmt::print("defect class {}: {}\n", int(kind),
               verify::to_string(verify::stability::stability_verdict(s, kind)));
  EXPECT_TRUE(s.has_float);
  EXPECT_TRUE(s.has_probability);
  EXPECT_EQ(verify::stability::stability_verdict(s, DefectClass::kBreaks), verify::Verdict::kHolds)
      << verify::stability::describe_failure_region(s);
  EXPECT_EQ(verify::stability::stability_verdict(s, DefectClass::kProbabilityAboveOne),
            verify::Verdict::kHolds);
  EXPECT_EQ(verify::stability::stability_verdict(s, DefectClass::kEnergyGain),
            verify::Verdict::kFails);
  EXPECT_TRUE(std::any_of(ZirrKaplanyan::kNotClaimed.begin(), ZirrKaplanyan::kNotClaimed.end(),
                          [](const auto& nc) { return nc.property == "energy"; }));
}

// What `glintlab eval --model zirr_kaplanyan --param …` prints, through the in-process registry:
// the parameters resolved by name, the row's value, pdf and named intermediates; the registry's
// thunk gives the template kernel's result exactly.
TEST(ZirrKaplanyan, EvalRowsThroughTheRegistry) {
  const ModelEntry& m = model();
  const auto v = resolve_params(m, {{"density", "7"}, {"binomial", "small_count"}, {"seed", "3"}});
  const ModelQuery<double> q = query(direction(45, 0), direction(45, 180), 1e-5);
  const ErasedEval e = m.eval(v, q);
  const auto direct = ZirrKaplanyan::eval(ZirrKaplanyan::params<double>(v), q);
  EXPECT_EQ(e.value, direct.value);
  ASSERT_EQ(e.intermediates.size(), m.intermediates.size());
  std::string row = fmt::format("model={} value={:.9g} pdf={:.9g}", m.name, e.value, e.pdf);
  for (std::size_t k = 0; k < e.intermediates.size(); ++k) {
    EXPECT_EQ(e.intermediates[k], direct.intermediates[k]) << m.intermediates[k];
    row += fmt::format(" {}={:.9g}", m.intermediates[k], e.intermediates[k]);
  }
  fmt::print("{}\n", row);
  EXPECT_EQ(e.intermediates[at("N_P")], 100.0);  // 1e-5 × 10^7
  EXPECT_GT(e.value, 0);
}

// Not a test: the cost per evaluation for the report (run with --gtest_also_run_disabled_tests),
// through the registry's double thunk like every consumer, next to deliot_belcour (one binomial
// draw per footprint) and smooth_ggx on the same queries.
TEST(ZirrKaplanyan, DISABLED_CostPerEvaluation) {
  const int n = 1 << 18;
  std::vector<ModelQuery<double>> qs(n);
  for (int i = 0; i < n; ++i) {
    const double t = double(i) / n;
    qs[std::size_t(i)] = query(direction(40, 0), direction(10 + 50 * t, 170), 1e-8 + 1e-6 * t,
                               {t, 1 - t});
  }
  const auto time = [&](const ModelEntry& m, const std::vector<double>& v) {
    double sink = 0;
    const auto start = std::chrono::steady_clock::now();
    for (const auto& q : qs) sink += m.eval(v, q).value;
    const double ns =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    return std::pair{ns / n, sink};
  };
  for (const char* approx : {"normal", "small_count"}) {
    const auto [ns, sink] = time(model(), values({{"binomial", approx}}));
    fmt::print("zirr_kaplanyan binomial={}: {:.0f} ns per eval (checksum {:.3g})\n", approx, ns,
               sink);
  }
  for (const char* other : {"deliot_belcour", "smooth_ggx"}) {
    const ModelEntry& m = find_model(other);
    const auto [ns, sink] = time(m, resolve_params(m, {}));
    fmt::print("{}: {:.0f} ns per eval (checksum {:.3g})\n", other, ns, sink);
  }
}

}  // namespace
}  // namespace glintlab

// The conformance suite's generator (every model gets every property, a model registered at run
// time too), its controls (each rejected by the property's own measure and decide steps), and
// deliberately broken toy models that fail the property they break.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <memory>
#include <span>
#include <cstdlib>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "core/model_registry.h"
#include "experiments/example_glint_model.h"
#include "verify/conformance/common.h"
#include "verify/conformance/conformance.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::conformance {
namespace {

using V3 = Vec3<double>;

std::set<std::string> ids_of(const std::vector<Check>& checks) {
  std::set<std::string> ids;
  for (const Check& c : checks) ids.insert(c.id);
  return ids;
}

TEST(ConformanceGenerator, EveryModelGetsEveryProperty) {
  const std::set<std::string> registered = ids_of(registered_checks());
  for (const ModelEntry& m : registered_models()) {
    const auto checks = conformance_checks(m);
    for (std::string_view p : kProperties) {
      const std::string id = "model." + std::string(m.name) + "." + std::string(p);
      const bool expected = applies(p, m);
      EXPECT_EQ(ids_of(checks).count(id), expected ? 1u : 0u) << id;
      EXPECT_EQ(registered.count(id), expected ? 1u : 0u) << id;
    }
    for (const Check& c : checks) {
      EXPECT_EQ(c.family, "model." + std::string(m.name)) << c.id;
      // Declared not-claimed properties are recorded as such, never as holding.
      const std::string property = c.id.substr(7 + m.name.size());
      if (not_claimed_reason(property, m)) {
        EXPECT_EQ(c.expected, Verdict::kNotClaimed) << c.id;
      }
      EXPECT_EQ(is_statistical(c), is_statistical_property(property) && !not_claimed_reason(property, m))
          << c.id;
    }
  }
  // Footprint properties only for footprint models.
  EXPECT_EQ(ids_of(conformance_checks(find_model("smooth_ggx"))).count("model.smooth_ggx.constant-time"), 0u);
}

// The papers' claims keep the level they had without the conformance suite, and a model's family
// level depends on that model alone.
TEST(ConformanceGenerator, FamiliesAreSeparate) {
  std::size_t paper_statistical = 0;
  for (const Check& c : registered_checks())
    if (c.family.empty() && is_statistical(c)) ++paper_statistical;
  EXPECT_DOUBLE_EQ(check_level(), sidak_level(kFamilyWiseRate, paper_statistical));
  const ModelEntry& ggx = find_model("smooth_ggx");
  // smooth_ggx claims all five statistical properties that apply to it (no footprint).
  EXPECT_DOUBLE_EQ(model_level(ggx), sidak_level(kFamilyWiseRate, 4));
}

// A model registered at run time (a plug-in) gets its checks from the registry, and its
// declarations reach them; in a child process, so the registry of the other tests is unchanged.
TEST(ConformanceGenerator, RuntimeModelGetsChecks) {
  EXPECT_EXIT(
      {
        register_model(make_model_entry<example::ExampleGlints>());
        const auto ids = ids_of(conformance_checks());
        bool ok = true;
        for (std::string_view p : kProperties)
          ok &= ids.count("model.example_glints." + std::string(p)) == 1;
        // No smooth limit declared: converges-to-smooth is not claimed, with the reason.
        for (const Check& c : conformance_checks())
          if (c.id == "model.example_glints.converges-to-smooth")
            ok &= c.expected == Verdict::kNotClaimed;
        std::exit(ok ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(ConformanceGenerator, DeclarationsReachTheEntry) {
  const ModelEntry& k = find_model("kemppinen_ggx");
  EXPECT_EQ(k.smooth_limit, "smooth_ggx");
  const ModelEntry& c = find_model("chermain");
  EXPECT_TRUE(not_claimed_reason("float-vs-double", c));
  EXPECT_TRUE(not_claimed_reason("converges-to-smooth", c));
  const CheckResult r = run_property("converges-to-smooth", c, Budget::kQuick);
  EXPECT_EQ(r.verdict, Verdict::kNotClaimed);
  EXPECT_NE(r.detail.find("V-cavity"), std::string::npos) << r.detail;
  EXPECT_FALSE(is_holding(r.verdict));
}

// Every control of a model that conforms is rejected: the genuine input holds, the control
// (about 3 % wrong) fails through the same measure and decide steps.
class ControlRejected : public ::testing::TestWithParam<std::pair<std::string, std::string>> {};

TEST_P(ControlRejected, ByTheSameDecision) {
  const auto& [model, property] = GetParam();
  const CheckResult r = run_property(property, find_model(model), Budget::kQuick);
  EXPECT_TRUE(is_holding(r.verdict)) << r.detail;
  ASSERT_TRUE(r.control_verdict.has_value());
  EXPECT_EQ(*r.control_verdict, Verdict::kFails) << r.control;
  EXPECT_TRUE(r.control_rejected);
}

INSTANTIATE_TEST_SUITE_P(
    Properties, ControlRejected,
    ::testing::Values(std::pair{"smooth_ggx", "eval-pdf-consistency"},
                      std::pair{"smooth_ggx", "sampler-matches-pdf"},
                      std::pair{"smooth_ggx", "sampler-covers-value"},
                      std::pair{"smooth_ggx", "pdf-normalized"},
                      std::pair{"smooth_ggx", "energy"},
                      std::pair{"smooth_ggx", "float-vs-double"},
                      std::pair{"smooth_ggx", "simd-equivalence"},
                      std::pair{"smooth_ggx", "stability"},
                      // The glint models whose Monte Carlo integrals once lacked the power
                      // (6 % relative standard error) to reject their 3 % controls.
                      std::pair{"podee", "sampler-covers-value"},
                      std::pair{"podee", "pdf-normalized"},
                      std::pair{"kneiphof_klein", "sampler-covers-value"},
                      std::pair{"deliot_belcour", "converges-to-smooth"},
                      std::pair{"deliot_belcour", "constant-time"}),
    [](const auto& param_info) {
      std::string n = param_info.param.first + "_" + param_info.param.second;
      for (char& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

// ---- Broken toy models ---------------------------------------------------------------------------

// A Lambertian toy: value = ρ cos θo / π, cosine sampling. `pdf_power` ≠ 1 claims a wrong pdf
// (cos^k θo (k + 1)/2π); `half` samples only the half-space wo_y ≥ 0 (reporting that sampler's
// true pdf, 2 cos θo/π there).
ModelEntry lambert_toy(double rho, double pdf_power = 1, bool half = false) {
  ModelEntry e;
  e.name = "toy_lambert";
  e.description = "test toy";
  e.source = "test";
  e.needs = kNeedsDirections;
  auto true_pdf = [half](const V3& wo) {
    if (!(wo.z > 0) || (half && wo.y < 0)) return 0.0;
    return (half ? 2.0 : 1.0) * wo.z / std::numbers::pi;
  };
  auto claimed_pdf = [true_pdf, pdf_power](const V3& wo) {
    if (pdf_power == 1) return true_pdf(wo);
    return wo.z > 0 ? std::pow(wo.z, pdf_power) * (pdf_power + 1) / (2 * std::numbers::pi) : 0.0;
  };
  e.eval = [rho, claimed_pdf](const std::vector<double>&, const ModelQuery<double>& q) {
    return ErasedEval{q.wo.z > 0 ? rho * q.wo.z / std::numbers::pi : 0.0, claimed_pdf(q.wo), {}};
  };
  e.pdf = [claimed_pdf](const std::vector<double>&, const ModelQuery<double>& q) {
    return claimed_pdf(q.wo);
  };
  e.sample = [rho, half, claimed_pdf](const std::vector<double>&, const ModelQuery<double>&,
                                      Vec2<double> u) {
    const double r = std::sqrt(u.x), phi = (half ? 1.0 : 2.0) * std::numbers::pi * u.y;
    const V3 wo{r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u.x))};
    const double pdf = claimed_pdf(wo);
    const double value = rho * wo.z / std::numbers::pi;
    return ModelSample<double>{wo, pdf, pdf > 0 ? value / pdf : 0.0, false};
  };
  return e;
}

Verdict verdict_of(const ModelEntry& m, std::string_view property) {
  return assess(property, m, Budget::kQuick, "test." + std::string(property), model_level(m)).verdict;
}

TEST(ConformanceToys, CorrectToyHolds) {
  const ModelEntry toy = lambert_toy(0.9);
  for (std::string_view p : {"eval-pdf-consistency", "sampler-matches-pdf", "sampler-covers-value",
                             "pdf-normalized", "energy"})
    EXPECT_EQ(verdict_of(toy, p), Verdict::kHolds) << p;
}

TEST(ConformanceToys, WrongPdfFailsSamplerMatchesPdf) {
  const ModelEntry toy = lambert_toy(0.9, 1.1);
  EXPECT_EQ(verdict_of(toy, "sampler-matches-pdf"), Verdict::kFails);
  // Still normalized (cos^1.1 · 2.1/2π integrates to 1): the defect is the shape.
  EXPECT_EQ(verdict_of(toy, "pdf-normalized"), Verdict::kHolds);
}

TEST(ConformanceToys, AlbedoAboveOneFailsEnergy) {
  EXPECT_EQ(verdict_of(lambert_toy(1.2), "energy"), Verdict::kFails);
  EXPECT_EQ(verdict_of(lambert_toy(1.0), "energy"), Verdict::kHolds);
}

// Energy is a property of eval, measured by the suite's hemisphere integral, not by the model's
// sampler: a sampler that reaches only half the lobe (its weights average to half the albedo, 0.6
// here, which a white furnace over the sampler's weights would pass) cannot hide the gain.
TEST(ConformanceToys, EnergyGainIsFoundWhereTheSamplerNeverGoes) {
  const ModelEntry toy = lambert_toy(1.2, 1, /*half=*/true);
  EXPECT_EQ(verdict_of(toy, "energy"), Verdict::kFails);
  const Assessment a = assess("energy", toy, Budget::kQuick, "test.energy", model_level(toy));
  EXPECT_NEAR(a.value, 1.2, 1e-3) << a.detail;
  EXPECT_EQ(verdict_of(lambert_toy(0.97, 1, /*half=*/true), "energy"), Verdict::kHolds);
}

// The sampler covers half the support and reports its own pdf truthfully: it matches its pdf,
// yet its estimates miss half the value.
// The chi-square of its directions holds; the weighted histogram sees the missing value too (in
// the cells it pools, where the reference has value and the sampler too few samples).
TEST(ConformanceToys, HalfSupportSamplerFailsCoversValue) {
  const ModelEntry toy = lambert_toy(0.9, 1, true);
  const Assessment a = assess("sampler-matches-pdf", toy, Budget::kQuick, "test.half",
                              model_level(toy));
  ASSERT_EQ(a.raw_p_values.size(), 2u);
  EXPECT_GT(a.raw_p_values[0], 1e-3) << a.detail;
  EXPECT_EQ(verdict_of(toy, "sampler-covers-value"), Verdict::kFails);
}

// The Lambertian toy whose sampler never draws the directions more than 8 × 0.3 rad from the
// mirror direction of ωi (the weighted histogram's outer ring at the toy's roughness scale, 0.3:
// a cap about the reverse of the mirror direction, by the horizon on the side of incidence,
// holding 1.8 % of ∫ value at θi = 70°): a draw landing there is rejected, and pdf() and eval's
// pdf are truthfully 0 there (cos θo / π elsewhere, integrating to the acceptance rate). With
// `excluded` false the same toy samples the whole hemisphere.
ModelEntry lambert_toy_missing_cap(double rho, bool excluded) {
  ModelEntry e = lambert_toy(rho);
  const double cap_cos = std::cos(8 * 0.3);
  auto missed = [excluded, cap_cos](const V3& wi, const V3& wo) {
    const V3 mirror{-wi.x, -wi.y, wi.z};
    return excluded && dot(wo, mirror) < cap_cos;
  };
  auto pdf = [missed](const ModelQuery<double>& q) {
    return q.wo.z > 0 && !missed(q.wi, q.wo) ? q.wo.z / std::numbers::pi : 0.0;
  };
  e.eval = [rho, pdf](const std::vector<double>&, const ModelQuery<double>& q) {
    return ErasedEval{q.wo.z > 0 ? rho * q.wo.z / std::numbers::pi : 0.0, pdf(q), {}};
  };
  e.pdf = [pdf](const std::vector<double>&, const ModelQuery<double>& q) { return pdf(q); };
  e.sample = [rho, missed](const std::vector<double>&, const ModelQuery<double>& q,
                           Vec2<double> u) {
    const double r = std::sqrt(u.x), phi = 2 * std::numbers::pi * u.y;
    const V3 wo{r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u.x))};
    if (missed(q.wi, wo)) return ModelSample<double>{V3{0, 0, 0}, 0.0, 0.0, true};
    const double density = wo.z / std::numbers::pi;
    return ModelSample<double>{wo, density,
                               density > 0 ? rho * wo.z / std::numbers::pi / density : 0.0, false};
  };
  return e;
}

// ---- Every declared choice is a configuration -----------------------------------------------------

// The Lambertian toy with a `sampler` parameter: cosine (the default) or a second sampler that,
// when `broken`, draws only the half-space wo_y ≥ 0 (reporting that sampler's pdf 2 cos θo/π there
// truthfully, as eval's and pdf() do: it misses half the value), and otherwise samples the
// hemisphere uniformly (pdf 1/2π: correct, the near-truth twin).
constexpr std::array<std::string_view, 2> kToySamplers = {"cosine", "second"};
ModelEntry lambert_toy_two_samplers(bool broken) {
  ModelEntry e = lambert_toy(0.9);
  e.params = {ParamSpec{"sampler", 0.0, 0.0, 1.0, false, false, "test sampler", kToySamplers}};
  auto pdf = [broken](const std::vector<double>& v, const V3& wo) {
    if (!(wo.z > 0)) return 0.0;
    if (v[0] == 0) return wo.z / std::numbers::pi;
    if (!broken) return 1 / (2 * std::numbers::pi);
    return wo.y >= 0 ? 2 * wo.z / std::numbers::pi : 0.0;
  };
  e.eval = [pdf](const std::vector<double>& v, const ModelQuery<double>& q) {
    return ErasedEval{q.wo.z > 0 ? 0.9 * q.wo.z / std::numbers::pi : 0.0, pdf(v, q.wo), {}};
  };
  e.pdf = [pdf](const std::vector<double>& v, const ModelQuery<double>& q) { return pdf(v, q.wo); };
  e.sample = [pdf, broken](const std::vector<double>& v, const ModelQuery<double>&,
                           Vec2<double> u) {
    V3 wo;
    if (v[0] == 0 || broken) {
      const double r = std::sqrt(u.x), phi = (v[0] == 0 ? 2.0 : 1.0) * std::numbers::pi * u.y;
      wo = {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u.x))};
    } else {
      const double z = u.x, r = std::sqrt(std::max(0.0, 1 - z * z)),
                   phi = 2 * std::numbers::pi * u.y;
      wo = {r * std::cos(phi), r * std::sin(phi), z};
    }
    const double density = pdf(v, wo);
    return ModelSample<double>{wo, density,
                               density > 0 ? 0.9 * wo.z / std::numbers::pi / density : 0.0, false};
  };
  return e;
}

// Only the defaults ran before: the broken second sampler was never drawn from, and the toy held.
// Now the choice is a configuration of sampler-covers-value and of sampler-matches-pdf (the
// weighted histogram), both fail on it, and the twin whose second sampler is correct holds.
TEST(ConformanceChoices, BrokenNonDefaultSamplerFails) {
  const ModelEntry broken = lambert_toy_two_samplers(true);
  ASSERT_EQ(variants(broken).size(), 1u);
  EXPECT_EQ(variants(broken)[0].label, "sampler=second");
  const Assessment c = assess("sampler-covers-value", broken, Budget::kQuick, "test.choices",
                              model_level(broken));
  EXPECT_EQ(c.verdict, Verdict::kFails) << c.detail;
  EXPECT_EQ(c.configurations, 3) << c.detail;  // θi 30° and 70° at the defaults, the choice at 70°
  EXPECT_NE(c.detail.find("sampler=second, θi=70°"), std::string::npos) << c.detail;
  // The defaults alone (what ran before) hold: the failure is the choice's.
  ASSERT_EQ(c.raw_p_values.size(), 3u);
  EXPECT_GT(c.raw_p_values[0], 1e-3) << c.detail;
  EXPECT_GT(c.raw_p_values[1], 1e-3) << c.detail;
  EXPECT_LT(c.raw_p_values[2], 1e-6) << c.detail;
  EXPECT_EQ(verdict_of(broken, "sampler-matches-pdf"), Verdict::kFails);

  const ModelEntry twin = lambert_toy_two_samplers(false);
  for (std::string_view p : {"eval-pdf-consistency", "sampler-matches-pdf", "sampler-covers-value",
                             "pdf-normalized"}) {
    const Assessment a = assess(p, twin, Budget::kQuick, "test.choices", model_level(twin));
    EXPECT_EQ(a.verdict, Verdict::kHolds) << p << ": " << a.detail;
  }
}

// The configurations: each non-default choice and the roughness grid (alpha_x and alpha_y
// together, the default 0.5 left out) for smooth_ggx; podee's grid inside its range without its
// default 0.05.
TEST(ConformanceChoices, EveryChoiceAndARoughnessGrid) {
  std::vector<std::string> labels;
  for (const Variant& v : variants(find_model("smooth_ggx"))) labels.push_back(v.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"sampler=ndf", "sampler=spherical_caps",
                                              "sampler=bounded_caps", "bound=exact_isotropic",
                                              "alpha_x=alpha_y=0.05", "alpha_x=alpha_y=0.3",
                                              "alpha_x=alpha_y=0.8"}));
  labels.clear();
  for (const Variant& v : variants(find_model("podee")))
    if (v.choice.empty()) labels.push_back(v.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"alpha_x=alpha_y=0.3", "alpha_x=alpha_y=0.8"}));
  // One θi per choice at quick, two at full, each at 1/7 of the samples (7 choices: together one
  // default setting's).
  const ModelEntry& ggx = find_model("smooth_ggx");
  EXPECT_EQ(variant_settings(ggx, Budget::kQuick, "pdf-normalized", nullptr).size(), 7u);
  const auto full = variant_settings(ggx, Budget::kFull, "pdf-normalized", nullptr);
  ASSERT_EQ(full.size(), 14u);
  for (const Setting& s : full) EXPECT_DOUBLE_EQ(s.share, 1.0 / 7);
  // At most a quarter each.
  EXPECT_DOUBLE_EQ(variant_share(lambert_toy_two_samplers(true)), kMaxVariantShare);
}

// Kemppinen's pdf=printed reports Algorithm 2's printed density by design: it is declared not
// claimed for the properties that compare the sample's pdf and weight with pdf() and value, left
// out of them with the reason in the row, and run by the others.
TEST(ConformanceChoices, PrintedPdfIsNotClaimedWhereItIsInconsistentByDesign) {
  const ModelEntry& k = find_model("kemppinen_ggx");
  for (std::string_view p : {"eval-pdf-consistency", "sampler-matches-pdf", "sampler-covers-value"}) {
    EXPECT_FALSE(not_claimed_reason(p, k)) << p;  // claimed at every other configuration
    std::string left_out;
    for (const Setting& s : variant_settings(k, Budget::kQuick, p, &left_out))
      EXPECT_EQ(s.label.find("pdf=printed"), std::string::npos) << p;
    EXPECT_EQ(left_out.rfind("pdf=printed (not claimed: ", 0), 0u) << left_out;
  }
  std::string left_out;
  bool printed = false;
  for (const Setting& s : variant_settings(k, Budget::kQuick, "pdf-normalized", &left_out))
    printed |= s.label.rfind("pdf=printed", 0) == 0;
  EXPECT_TRUE(printed);
  EXPECT_TRUE(left_out.empty()) << left_out;
}

// The cap's cells get no sample, so the pooled cells are never tested: only the value mass where
// the pdf is 0, counted from the reference's own draws, shows the weighted histogram (raw p
// second) the missing 1.8 %. The chi-square of the directions (raw p first) holds: the sampler
// matches its pdf. With the whole hemisphere sampled, the same toy holds.
TEST(ConformanceToys, SamplerMissingACapFailsTheWeightedHistogram) {
  const ModelEntry toy = lambert_toy_missing_cap(0.9, true);
  const Assessment a = assess("sampler-matches-pdf", toy, Budget::kQuick, "test.cap",
                              model_level(toy));
  ASSERT_EQ(a.raw_p_values.size(), 2u);
  EXPECT_GT(a.raw_p_values[0], 1e-3) << a.detail;
  EXPECT_LT(a.raw_p_values[1], model_level(toy)) << a.detail;
  EXPECT_EQ(a.verdict, Verdict::kFails) << a.detail;
  EXPECT_EQ(verdict_of(toy, "pdf-normalized"), Verdict::kHolds);
  const ModelEntry whole = lambert_toy_missing_cap(0.9, false);
  const Assessment g = assess("sampler-matches-pdf", whole, Budget::kQuick, "test.cap",
                              model_level(whole));
  EXPECT_EQ(g.verdict, Verdict::kHolds) << g.detail;
  EXPECT_NE(g.detail.find("value mass where eval's pdf is 0: none"), std::string::npos)
      << g.detail;
}

// The sampler and its pdf agree, but the weights over-estimate the value by 3 %: the chi-square of
// the directions (raw p first) cannot see it, the weighted histogram (raw p second) must.
TEST(ConformanceToys, WrongWeightsFailSamplerMatchesPdf) {
  const ModelEntry good = lambert_toy(0.9), toy = with_weight_scaled(good, 1.03);
  const Assessment a = assess("sampler-matches-pdf", toy, Budget::kQuick, "test.weighted",
                              model_level(toy));
  ASSERT_EQ(a.raw_p_values.size(), 2u);
  EXPECT_GT(a.raw_p_values[0], 1e-3);
  EXPECT_EQ(a.verdict, Verdict::kFails) << a.detail;
  const Assessment g = assess("sampler-matches-pdf", good, Budget::kQuick, "test.weighted",
                              model_level(good));
  EXPECT_EQ(g.verdict, Verdict::kHolds) << g.detail;
}

// verify prints "<value> = <statistic>": the label says what the value is. sampler-covers-value's
// value is a relative difference (here the weights' 3 %), pdf-normalized's a difference; their
// p-values are reported apart.
TEST(ConformanceToys, MeasuredValuesAreLabelledForWhatTheyAre) {
  const ModelEntry toy = with_weight_scaled(lambert_toy(0.9), 1.03);
  const Assessment a =
      assess("sampler-covers-value", toy, Budget::kQuick, "test.label", model_level(toy));
  EXPECT_NEAR(a.value, 0.03, 0.01);
  EXPECT_EQ(a.statistic.rfind("largest relative difference of the mean weight", 0), 0u)
      << a.statistic;
  ASSERT_TRUE(a.p_value.has_value());
  EXPECT_LT(*a.p_value, 1e-3);
  const Assessment n =
      assess("pdf-normalized", toy, Budget::kQuick, "test.label", model_level(toy));
  EXPECT_LT(std::abs(n.value), 0.01);
  EXPECT_EQ(n.statistic.rfind("largest difference of ∫ pdf", 0), 0u) << n.statistic;
}

// The Monte Carlo integral of a footprint model (a mixture about the mirror direction, never the
// model's sampler) is unbiased within its error: ∫ cos θo / π = 1 over the hemisphere, at a
// grazing and a near-normal incidence; the integrand 3 % too large is told apart.
TEST(ConformanceIntegral, MirrorMixtureIsUnbiased) {
  ModelEntry m = lambert_toy(1);
  m.needs = kNeedsFootprint;
  for (double theta : {10.0, 70.0}) {
    const V3 wi = make_query(m, theta, kFootprint).wi;
    for (double scale : {1.0, 1.03}) {
      const HemisphereIntegral i = integrate_hemisphere(
          m, [scale](const V3& w) { return scale * w.z / std::numbers::pi; }, wi, 0.1,
          Budget::kQuick, 20260 + std::uint64_t(theta));
      ASSERT_TRUE(i.monte_carlo);
      EXPECT_LT(i.error, 0.004) << theta;
      if (scale == 1.0) {
        EXPECT_LT(std::abs(i.value - 1), 4.5 * i.error) << theta << ": " << i.value;
      } else {
        EXPECT_GT(std::abs(i.value - 1), 4.5 * i.error) << theta << ": " << i.value;
      }
    }
  }
}

// smooth_ggx with NaN values at grazing incidence (θi > 80°, inside the sweep's core domain).
TEST(ConformanceToys, NanFailsStability) {
  ModelEntry toy = find_model("smooth_ggx");
  toy.eval = [f = toy.eval](const std::vector<double>& v, const ModelQuery<double>& q) {
    ErasedEval r = f(v, q);
    if (q.wi.z > 0 && q.wi.z < std::cos(80 * std::numbers::pi / 180)) r.value = std::nan("");
    return r;
  };
  EXPECT_EQ(verdict_of(toy, "stability"), Verdict::kFails);
  EXPECT_EQ(verdict_of(find_model("smooth_ggx"), "stability"), Verdict::kHolds);
}

// smooth_ggx declared as its own smooth limit, 5 % too bright at θi = 20° and 5 % too dark at
// θi = 50° (the two direction pairs): pooled over the pairs the biases cancel; decided pair by
// pair, converges-to-smooth fails. Unchanged, it holds.
TEST(ConformanceToys, OppositeBiasesAtTwoDirectionsFailConvergesToSmooth) {
  ModelEntry toy = find_model("smooth_ggx");
  toy.smooth_limit = "smooth_ggx";
  const ModelEntry exact = toy;
  toy.eval = [f = toy.eval](const std::vector<double>& v, const ModelQuery<double>& q) {
    ErasedEval r = f(v, q);
    r.value *= q.wi.z > std::cos(35 * std::numbers::pi / 180) ? 1.05 : 0.95;
    return r;
  };
  const Assessment a = assess("converges-to-smooth", toy, Budget::kQuick, "test.opposite",
                              model_level(toy));
  EXPECT_EQ(a.verdict, Verdict::kFails) << a.detail;
  EXPECT_NEAR(std::abs(a.value), 0.05, 1e-9) << a.detail;
  EXPECT_EQ(verdict_of(exact, "converges-to-smooth"), Verdict::kHolds);
}

// smooth_ggx declared as its own smooth limit, its value scaled by 1 ± σ with a sign that varies
// from footprint position to position (mean 1): a glinty model converging to the right limit. At
// σ = 0.2 the first 1024 positions leave the largest footprint undecided, and the second,
// larger estimate decides holds; at σ = 1 even the cap cannot, and the detail says underpowered
// and how many positions the tolerance needs.
ModelEntry noisy_smooth_ggx(double sigma) {
  ModelEntry toy = find_model("smooth_ggx");
  toy.smooth_limit = "smooth_ggx";
  toy.static_model = nullptr;
  toy.eval = [f = toy.eval, sigma](const std::vector<double>& v, const ModelQuery<double>& q) {
    ErasedEval r = f(v, q);
    const double phase = std::sin(q.footprint.uv.x * 7919.0 + q.footprint.uv.y * 104729.0);
    r.value *= 1 + (phase >= 0 ? sigma : -sigma);
    return r;
  };
  return toy;
}

TEST(ConformanceToys, ConvergesToSmoothDrawsWhatItsToleranceNeedsUpToACap) {
  const ModelEntry moderate = noisy_smooth_ggx(0.2);
  const Assessment a = assess("converges-to-smooth", moderate, Budget::kQuick, "test.noisy",
                              model_level(moderate));
  EXPECT_EQ(a.verdict, Verdict::kHolds) << a.detail;
  EXPECT_NE(a.detail.find("positions)"), std::string::npos) << a.detail;  // a second estimate
  EXPECT_EQ(a.detail.find("underpowered"), std::string::npos) << a.detail;

  const ModelEntry glinty = noisy_smooth_ggx(1.0);
  const Assessment g = assess("converges-to-smooth", glinty, Budget::kQuick, "test.noisy",
                              model_level(glinty));
  EXPECT_EQ(g.verdict, Verdict::kInconclusive) << g.detail;
  EXPECT_EQ(g.detail.rfind("underpowered at θi", 0), 0u) << g.detail;
  EXPECT_NE(g.detail.find("footprint positions for ±0.01 (cap 16384)"), std::string::npos)
      << g.detail;
}

// ---- Faults: a check that cannot compute its statistic -------------------------------------------

// An exception escaping a check's run (here from inside a parallel loop) is its error verdict,
// naming the model, the property and the exception's message; nothing else is reported.
TEST(ConformanceFaults, ThrowingEvalIsAnErrorNamingTheModel) {
  ModelEntry toy = lambert_toy(0.9);
  toy.eval = [](const std::vector<double>&, const ModelQuery<double>&) -> ErasedEval {
    throw std::runtime_error("toy eval broke");
  };
  bool ran = false;
  for (const Check& c : conformance_checks(toy)) {
    if (c.id != "model.toy_lambert.eval-pdf-consistency") continue;
    ran = true;
    const CheckResult r = c.run(Budget::kQuick);
    EXPECT_EQ(r.verdict, Verdict::kError);
    EXPECT_EQ(r.detail, "model toy_lambert: eval-pdf-consistency: exception: toy eval broke");
    EXPECT_FALSE(r.control_verdict.has_value());
    EXPECT_FALSE(control_ok(r));
    EXPECT_FALSE(is_holding(r.verdict));
  }
  EXPECT_TRUE(ran);
  EXPECT_STREQ(to_string(Verdict::kError), "error");
}

TEST(ConformanceFaults, ContainedCatchesAnyException) {
  const auto throws_int = contained("claim x", [](Budget) -> CheckResult { throw 7; });
  const CheckResult r = throws_int(Budget::kQuick);
  EXPECT_EQ(r.verdict, Verdict::kError);
  EXPECT_NE(r.detail.find("claim x: exception:"), std::string::npos) << r.detail;
  const auto fine = contained("claim y", [](Budget) {
    CheckResult ok;
    ok.verdict = Verdict::kHolds;
    return ok;
  });
  EXPECT_EQ(fine(Budget::kQuick).verdict, Verdict::kHolds);
}

// eval NaN everywhere: the properties whose statistic needs its value report error naming what
// was not finite (energy too: it integrates eval's value); stability, whose statistic counts NaN
// outputs, fails (its verdict, not an error).
TEST(ConformanceFaults, NanEvalIsAnErrorWhereANumberIsRequired) {
  ModelEntry toy = find_model("smooth_ggx");
  toy.eval = [f = toy.eval](const std::vector<double>& v, const ModelQuery<double>& q) {
    ErasedEval r = f(v, q);
    r.value = std::nan("");
    return r;
  };
  toy.static_model = nullptr;  // the batches loop over the NaN eval too
  const CheckResult covers = run_property("sampler-covers-value", toy, Budget::kQuick);
  EXPECT_EQ(covers.verdict, Verdict::kError);
  EXPECT_NE(covers.detail.find("model smooth_ggx: sampler-covers-value: ∫ value dωo at"),
            std::string::npos)
      << covers.detail;
  const CheckResult precision = run_property("float-vs-double", toy, Budget::kQuick);
  EXPECT_EQ(precision.verdict, Verdict::kError);
  EXPECT_NE(precision.detail.find("not finite on any"), std::string::npos) << precision.detail;
  EXPECT_EQ(run_property("sampler-matches-pdf", toy, Budget::kQuick).verdict, Verdict::kError);
  EXPECT_EQ(run_property("eval-pdf-consistency", toy, Budget::kQuick).verdict, Verdict::kError);
  EXPECT_EQ(run_property("stability", toy, Budget::kQuick).verdict, Verdict::kFails);
  const CheckResult energy = run_property("energy", toy, Budget::kQuick);
  EXPECT_EQ(energy.verdict, Verdict::kError);
  EXPECT_NE(energy.detail.find("∫ value dωo at"), std::string::npos) << energy.detail;
}

// ---- simd-equivalence's control perturbs the batch, the path under test ---------------------------

TEST(ConformanceControls, SimdControlScalesTheBatchNotTheScalarReference) {
  const ModelEntry& ggx = find_model("smooth_ggx");
  const Assessment genuine = assess("simd-equivalence", ggx, Budget::kQuick, "test.simd",
                                    model_level(ggx));
  ASSERT_EQ(genuine.verdict, Verdict::kHolds) << genuine.detail;
  const Control c = make_control("simd-equivalence", ggx, genuine, Input::kPerturbed);
  EXPECT_EQ(c.batch_value_scale, kControlOffset);
  // The scalar reference is the model's own eval, unchanged.
  ModelQuery<double> q = make_query(ggx, 30, kFootprint);
  q.wo = {-q.wi.x, -q.wi.y, q.wi.z};
  const auto values = resolve_params(ggx, {});
  EXPECT_EQ(c.model.eval(values, q).value, ggx.eval(values, q).value);
  const Assessment control = assess("simd-equivalence", c.model, Budget::kQuick, "test.simd",
                                    model_level(ggx), nullptr, c.batch_value_scale);
  EXPECT_EQ(control.verdict, Verdict::kFails) << control.detail;
  // The measured statistic is the same whichever side carries the 3 %: the share of non-zero rows.
  EXPECT_GT(control.value, 0.9) << control.detail;
}

// The scale reaches the batch output on every ISA: a batch 1e-6 off fails (beyond 1e-9 relative)
// where the unscaled batch holds; a scale of 1 changes nothing.
TEST(ConformanceControls, PerturbedBatchFailsSimdEquivalence) {
  const ModelEntry& ggx = find_model("smooth_ggx");
  const Assessment exact = assess("simd-equivalence", ggx, Budget::kQuick, "test.batch",
                                  model_level(ggx), nullptr, 1);
  const Assessment off = assess("simd-equivalence", ggx, Budget::kQuick, "test.batch",
                                model_level(ggx), nullptr, 1 + 1e-6);
  EXPECT_EQ(exact.verdict, Verdict::kHolds) << exact.detail;
  EXPECT_EQ(off.verdict, Verdict::kFails) << off.detail;
  EXPECT_EQ(off.configurations, exact.configurations);
  // Every ISA's batch was perturbed, not only one.
  EXPECT_EQ(off.detail.find(": 0 beyond"), std::string::npos) << off.detail;
}

// ---- Rows functions (ModelEntry::eval_rows, pdf_rows, sample_rows) ----------------------------

// The entry with rows functions over its own thunks, each call counted (a Python model's rows
// functions call its numpy functions once per chunk instead).
struct RowCalls {
  std::atomic<long> eval = 0, pdf = 0, sample = 0, rows = 0;
};
ModelEntry with_rows(ModelEntry e, std::shared_ptr<RowCalls> calls) {
  e.eval_rows = [f = e.eval, calls](const std::vector<double>& v,
                                    std::span<const ModelQuery<double>> qs,
                                    std::span<ErasedEval> out) {
    ++calls->eval;
    calls->rows += long(qs.size());
    for (std::size_t i = 0; i < qs.size(); ++i) out[i] = f(v, qs[i]);
  };
  e.pdf_rows = [f = e.pdf, calls](const std::vector<double>& v,
                                  std::span<const ModelQuery<double>> qs, std::span<double> out) {
    ++calls->pdf;
    calls->rows += long(qs.size());
    for (std::size_t i = 0; i < qs.size(); ++i) out[i] = f(v, qs[i]);
  };
  e.sample_rows = [f = e.sample, calls](const std::vector<double>& v, const ModelQuery<double>& q,
                                        std::span<const Vec2<double>> u,
                                        std::span<ModelSample<double>> out) {
    ++calls->sample;
    calls->rows += long(u.size());
    for (std::size_t i = 0; i < u.size(); ++i) out[i] = f(v, q, u[i]);
  };
  return e;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every altered copy of an entry (the controls) changes its rows functions as it changes its
// per-row thunks: eval_each / pdf_each / sample_each give what the thunks give, bit for bit (a copy
// that kept the original rows functions would let the suite's chunked callers bypass the change).
TEST(ConformanceRows, AlteredCopiesChangeTheRowsLikeTheThunks) {
  const ModelEntry base = with_rows(lambert_toy(0.9), std::make_shared<RowCalls>());
  const std::vector<std::pair<std::string, ModelEntry>> copies = {
      {"pdf scaled", with_pdf_scaled(base, 1.03)},
      {"value scaled", with_value_scaled(base, 1.03)},
      {"weight scaled", with_weight_scaled(base, 1.03)},
      {"sampler restricted", with_sampler_restricted(base, 0.3)},
      {"sparse NaN", with_sparse_nan(base, 0.3)},
      {"uniform sampler", with_uniform_sampler(base)},
      {"consistent sample", with_consistent_sample(with_pdf_scaled(base, 1.03))},
      {"outputs sanitized", with_outputs_sanitized(with_value_scaled(base, -1))},
      {"cost per area", with_cost_per_area(base, 0.01, 4)},
      {"footprint clamped", with_footprint_clamped(base, 0.01)}};
  const std::vector<double> values;
  ModelQuery<double> q = make_query(base, 40, 0.3);
  std::vector<ModelQuery<double>> qs;
  std::vector<Vec2<double>> u;
  for (std::uint64_t i = 0; i < 500; ++i) {
    u.push_back(pair_at(7, i));
    const double z = 2 * u.back().x - 1, r = std::sqrt(1 - z * z), phi = 2 * std::numbers::pi * u.back().y;
    qs.push_back(q);
    qs.back().wo = {r * std::cos(phi), r * std::sin(phi), z};
  }
  for (const auto& [what, m] : copies) {
    std::vector<ErasedEval> e(qs.size());
    std::vector<double> p(qs.size());
    std::vector<ModelSample<double>> x(u.size());
    eval_each(m, values, qs, e);
    pdf_each(m, values, qs, p);
    sample_each(m, values, q, u, x);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < qs.size(); ++i) {
      const ErasedEval one = m.eval(values, qs[i]);
      const ModelSample<double> s = m.sample(values, q, u[i]);
      differ += !same_bits(e[i].value, one.value) || !same_bits(e[i].pdf, one.pdf);
      differ += !same_bits(p[i], m.pdf(values, qs[i]));
      differ += !same_bits(x[i].wo.x, s.wo.x) || !same_bits(x[i].wo.z, s.wo.z) ||
                !same_bits(x[i].pdf, s.pdf) || !same_bits(x[i].weight, s.weight) ||
                x[i].rejected != s.rejected;
    }
    EXPECT_EQ(differ, 0u) << what;
  }
  // The test tells a stale rows function apart: the pdf thunk scaled, its rows left as they were.
  ModelEntry stale = base;
  stale.pdf = with_pdf_scaled(base, 1.03).pdf;
  std::vector<double> p(qs.size());
  pdf_each(stale, values, qs, p);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < qs.size(); ++i) differ += !same_bits(p[i], stale.pdf(values, qs[i]));
  EXPECT_GT(differ, 100u);
}

// The properties ask an entry with rows functions for whole chunks of queries: a few hundred calls
// for the quick budget's millions of queries, and the same check results as the entry without
// them.
TEST(ConformanceRows, PropertiesCallTheRowsPerChunk) {
  const ModelEntry one = lambert_toy(0.9);
  const auto calls = std::make_shared<RowCalls>();
  const ModelEntry rows = with_rows(one, calls);
  for (std::string_view p : {"eval-pdf-consistency", "sampler-matches-pdf", "energy"}) {
    const CheckResult a = run_property(std::string(p), one, Budget::kQuick);
    const CheckResult b = run_property(std::string(p), rows, Budget::kQuick);
    EXPECT_EQ(a.verdict, b.verdict) << p;
    EXPECT_EQ(a.detail, b.detail) << p;
    EXPECT_EQ(a.control, b.control) << p;
    EXPECT_TRUE(same_bits(a.value, b.value)) << p;
  }
  EXPECT_GT(calls->rows.load(), 1'000'000);
  EXPECT_LT(calls->eval + calls->pdf + calls->sample, calls->rows / 500) << calls->rows;
}

}  // namespace
}  // namespace glintlab::verify::conformance

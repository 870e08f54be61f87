// The model interface: registry entries evaluate exactly the kernels they wrap, samples agree
// with the standalone pdf and the value, the samplers all estimate the same albedo, and bad
// parameters get one-line errors naming the parameter and range.
#include "core/model_registry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/math/rng.h"
#include "core/models/smooth_beckmann.h"
#include "core/models/smooth_ggx.h"

namespace glintlab {
namespace {

ModelQuery<double> query(Vec3<double> wi, Vec3<double> wo) {
  ModelQuery<double> q{};
  q.wi = wi;
  q.wo = wo;
  q.light = {1, 1};
  return q;
}

TEST(ModelRegistry, ListsTheSmoothModels) {
  const auto& models = registered_models();
  ASSERT_GE(models.size(), 2u);
  EXPECT_EQ(models[0].name, "smooth_ggx");
  EXPECT_EQ(models[1].name, "smooth_beckmann");
  EXPECT_EQ(&find_model("smooth_beckmann"), &models[1]);
  EXPECT_THROW(find_model("phong"), ModelParamError);
}

TEST(ModelRegistry, EntryEvaluatesTheKernels) {
  const ModelEntry& m = find_model("smooth_ggx");
  const auto values =
      resolve_params(m, {{"alpha_x", "0.3"}, {"alpha_y", "0.6"}, {"sampler", "bounded_caps"}});
  const GGX<double> ggx{0.3, 0.6};
  const Vec3<double> wi = normalize(Vec3<double>{0.4, -0.2, 0.7});
  const Vec3<double> wo = normalize(Vec3<double>{-0.3, 0.5, 0.6});
  const ErasedEval e = m.eval(values, query(wi, wo));
  EXPECT_EQ(e.value, microfacet_brdf(ggx, wi, wo, 1.0) * wo.z);
  EXPECT_EQ(e.pdf, pdf_bounded_vndf(ggx, wi, wo, BoundedVndfBound::kListing1));
  ASSERT_EQ(e.intermediates.size(), m.intermediates.size());
  EXPECT_EQ(e.intermediates[3], ggx.D(half_vector(wi, wo)));  // "D"
  // A different sampler changes the pdf, not the value.
  const auto caps =
      resolve_params(m, {{"alpha_x", "0.3"}, {"alpha_y", "0.6"}, {"sampler", "spherical_caps"}});
  const ErasedEval c = m.eval(caps, query(wi, wo));
  EXPECT_EQ(c.value, e.value);
  EXPECT_NE(c.pdf, e.pdf);
}

TEST(ModelRegistry, SamplesCarryTheStandalonePdfAndWeight) {
  for (const ModelEntry& m : registered_models()) {
    const ParamSpec& sampler = m.params[2];
    for (std::size_t s = 0; s < sampler.choices.size(); ++s) {
      const auto values =
          resolve_params(m, {{"alpha_x", "0.4"}, {"sampler", std::string(sampler.choices[s])}});
      const Vec3<double> wi = normalize(Vec3<double>{0.6, 0.1, 0.5});
      int accepted = 0;
      for (int i = 0; i < 200; ++i) {
        const Vec2<double> u{counter_uniform<double>(7, i, 0), counter_uniform<double>(7, i, 1)};
        const ModelSample<double> smp = m.sample(values, query(wi, {0, 0, 1}), u);
        if (smp.rejected) {
          EXPECT_EQ(smp.weight, 0.0);
          continue;
        }
        ++accepted;
        const ModelQuery<double> q = query(wi, smp.wo);
        EXPECT_NEAR(smp.pdf, m.pdf(values, q), 1e-12 * smp.pdf)
            << m.name << " " << sampler.choices[s];
        const ErasedEval e = m.eval(values, q);
        EXPECT_NEAR(smp.weight, e.value / e.pdf, 1e-9 * smp.weight);
      }
      EXPECT_GT(accepted, 100);
    }
  }
}

// Every sampler of a model estimates the same directional albedo ∫ f cos dωo: the means of
// independent runs agree within 5 standard errors; the control (weights doubled) is rejected.
TEST(ModelRegistry, SamplersEstimateTheSameAlbedo) {
  const ModelEntry& m = find_model("smooth_ggx");
  const Vec3<double> wi = normalize(Vec3<double>{0.8, 0.0, 0.3});
  const int n = 100000;
  const std::uint64_t seed = hash_string("model_registry/albedo");
  std::vector<std::pair<double, double>> stats;  // mean, standard error
  for (std::string_view s : {"ndf", "vndf", "spherical_caps", "bounded_caps"}) {
    const auto values =
        resolve_params(m, {{"alpha_x", "0.8"}, {"alpha_y", "0.8"}, {"sampler", std::string(s)}});
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
      const Vec2<double> u{counter_uniform<double>(seed, i, 0),
                           counter_uniform<double>(seed, i, 1)};
      const double w = m.sample(values, query(wi, {0, 0, 1}), u).weight;
      sum += w;
      sum2 += w * w;
    }
    const double mean = sum / n;
    stats.emplace_back(mean, std::sqrt((sum2 / n - mean * mean) / n));
  }
  const auto agree = [](std::pair<double, double> a, std::pair<double, double> b) {
    return std::abs(a.first - b.first) <= 5 * std::hypot(a.second, b.second);
  };
  for (std::size_t i = 1; i < stats.size(); ++i) EXPECT_TRUE(agree(stats[0], stats[i])) << i;
  EXPECT_FALSE(agree(stats[0], {2 * stats[3].first, 2 * stats[3].second}));
  // Bounded caps rejects fewer samples, so its weights vary less (Eto & Tokuyoshi Sec. 3).
  EXPECT_LT(stats[3].second, stats[2].second);
}

std::string error_of(const ModelEntry& m, std::vector<std::pair<std::string, std::string>> kv) {
  try {
    resolve_params(m, kv);
  } catch (const ModelParamError& e) {
    return e.what();
  }
  return "";
}

TEST(ModelRegistry, BadParametersNameTheParameterAndRange) {
  const ModelEntry& m = find_model("smooth_ggx");
  const std::string range = error_of(m, {{"alpha_x", "0"}});
  EXPECT_NE(range.find("alpha_x"), std::string::npos);
  EXPECT_NE(range.find("[0.0001, 100]"), std::string::npos) << range;
  EXPECT_NE(error_of(m, {{"alpha_y", "abc"}}).find("is not a number"), std::string::npos);
  EXPECT_NE(error_of(m, {{"sampler", "heitz"}}).find("one of: ndf, vndf"), std::string::npos);
  EXPECT_NE(error_of(m, {{"eta", "1.5"}}).find("valid: alpha_x, alpha_y, sampler, bound"),
            std::string::npos);
  EXPECT_NE(error_of(m, {{"alpha_x", "1"}, {"alpha_x", "2"}}).find("given twice"),
            std::string::npos);
  EXPECT_EQ(error_of(m, {{"alpha_x", "100"}}), "");
  // A seed is a whole number: 1.9 is refused, not truncated to 1.
  const ModelEntry& kemppinen = find_model("kemppinen_ggx");
  const std::string fraction = error_of(kemppinen, {{"seed", "1.9"}});
  EXPECT_NE(fraction.find("not an integer"), std::string::npos) << fraction;
  EXPECT_NE(fraction.find("an integer in [0, 4294967295]"), std::string::npos) << fraction;
  EXPECT_EQ(error_of(kemppinen, {{"seed", "2"}}), "");
  for (const char* model : {"deliot_belcour", "kneiphof_klein", "chermain"})
    EXPECT_NE(error_of(find_model(model), {{"seed", "0.5"}}), "") << model;
  EXPECT_NE(error_of(find_model("kneiphof_klein_area"), {{"mc_samples", "10.5"}}), "");
  for (const ModelEntry& e : registered_models()) {
    for (const ParamSpec& p : e.params) {
      // Every default is valid.
      EXPECT_EQ(error_of(e, {{std::string(p.name), format_param_value(p, p.default_value)}}), "");
    }
  }
}

// A model's input rules come with its entry (the CLI knows no model): podee needs a disk of
// radius > 0 with its centre above the surface; a model without rules has no validate.
TEST(ModelRegistry, ModelsOwnTheirQueryRules) {
  const ModelEntry& podee = find_model("podee");
  ASSERT_TRUE(podee.validate);
  ModelQuery<double> q = query({0, 0, 1}, {0, 0, 1});
  q.light.cos_half_angle = 0.99;
  EXPECT_FALSE(podee.validate(q).has_value());
  q.light.cos_half_angle = 1;
  std::optional<QueryViolation> bad = podee.validate(q);
  ASSERT_TRUE(bad.has_value());
  EXPECT_EQ(bad->column, "light_cos_half_angle");
  EXPECT_NE(bad->valid.find("< 1"), std::string_view::npos);
  q.light.cos_half_angle = 0.99;
  q.wo = {0.6, 0, -0.8};
  bad = podee.validate(q);
  ASSERT_TRUE(bad.has_value());
  EXPECT_EQ(bad->column, "wo_z");
  EXPECT_NE(bad->valid.find("> 0"), std::string_view::npos);
  EXPECT_FALSE(find_model("smooth_ggx").validate);
}

// A not-claimed property must be one the conformance suite has: a misspelled one would silently
// leave the property claimed. The built-in models are checked at compile time (model_registry.cpp);
// an entry added at run time (a plug-in, a test's model) is refused naming the name and the valid
// ones, and nothing is registered.
TEST(ModelRegistry, MisspelledNotClaimedPropertyIsRefused) {
  static_assert(detail::not_claimed_are_properties<SmoothGGX>());
  for (const ModelEntry& e : registered_models()) EXPECT_NO_THROW(check_not_claimed(e)) << e.name;
  ModelEntry misspelled = make_model_entry<SmoothGGX>();
  misspelled.name = "smooth_ggx_misspelled_not_claimed";
  misspelled.not_claimed = {{"energy", "fine"}, {"constant_time", "misspelled"}};
  const std::size_t before = registered_models().size();
  try {
    register_model(misspelled);
    ADD_FAILURE() << "a misspelled not-claimed property was registered";
  } catch (const ModelParamError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'constant_time'"), std::string::npos) << what;
    EXPECT_NE(what.find("smooth_ggx_misspelled_not_claimed"), std::string::npos) << what;
    EXPECT_NE(what.find("valid: eval-pdf-consistency, "), std::string::npos) << what;
    EXPECT_NE(what.find("constant-time"), std::string::npos) << what;
  }
  EXPECT_EQ(registered_models().size(), before);
}

// A not-claimed declaration limited to a parameter choice must name one of the model's choices
// ("param=choice"); a choice it does not have is refused like a misspelled property.
TEST(ModelRegistry, NotClaimedChoiceMustBeDeclared) {
  static_assert(is_declared_choice(SmoothGGX::kParams, "sampler=ndf"));
  static_assert(!is_declared_choice(SmoothGGX::kParams, "sampler=nfd"));
  static_assert(!is_declared_choice(SmoothGGX::kParams, "alpha_x=0.5"));
  ModelEntry e = make_model_entry<SmoothGGX>();
  e.name = "smooth_ggx_not_claimed_choice";
  e.not_claimed = {{"energy", "fine", "sampler=ndf"}};
  EXPECT_NO_THROW(check_not_claimed(e));
  e.not_claimed = {{"energy", "misspelled", "sampler=nfd"}};
  try {
    check_not_claimed(e);
    ADD_FAILURE() << "an undeclared choice was accepted";
  } catch (const ModelParamError& x) {
    EXPECT_NE(std::string(x.what()).find("'sampler=nfd'"), std::string::npos) << x.what();
  }
}

}  // namespace
}  // namespace glintlab

// The validation scenes of adequacy.choice-is-safe (verify/scenes/adequacy_scenes.h): the
// decision's critical count, the engine chooser held and a broken chooser caught by the same
// decision on small renders, the chooser on (N_P, p) identical to the engine's, and the same
// pixels for any thread count.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "verify/scenes/adequacy_scenes.h"

namespace glintlab::verify::adequacy {
namespace {

SceneOptions small_options() {
  SceneOptions o;
  o.width = o.height = 32;
  o.realisations = 160;
  o.seed = 7;
  return o;
}

// Two scenes of both models: the plane under the spherical light (kneiphof_klein, the light's
// cone) and under the point light (deliot_belcour), at the high density.
SafetyTally tally_of(const SceneOptions& o) {
  SafetyTally t;
  for (const ChoiceScene& s : choice_scenes())
    if (s.name == "plane-point-high" || s.name == "plane-area-high")
      add(t, tally(render_choice_scene(s, o)));
  return t;
}

TEST(AdequacyChoiceDecision, AllowsTheCountABinomialAtTheFlagRateReaches) {
  SafetyTally t;
  t.lit = 10000;
  const double alpha = 1e-3;
  t.exceeds = 0;
  const SafetyDecision none = decide_choice_safety(t, alpha);
  EXPECT_EQ(none.verdict, Verdict::kHoldsInRegime);
  // 100 expected under H0, σ ≈ 9.95: the critical count lies some 3 σ above.
  EXPECT_GT(none.allowed, 125u);
  EXPECT_LT(none.allowed, 140u);
  t.exceeds = none.allowed;
  const SafetyDecision at = decide_choice_safety(t, alpha);
  EXPECT_EQ(at.verdict, Verdict::kHoldsInRegime);
  EXPECT_GE(at.p_value, alpha);
  t.exceeds = none.allowed + 1;
  const SafetyDecision over = decide_choice_safety(t, alpha);
  EXPECT_EQ(over.verdict, Verdict::kFails);
  EXPECT_LT(over.p_value, alpha);
  EXPECT_EQ(decide_choice_safety(SafetyTally{}, alpha).verdict, Verdict::kInconclusive);
}

TEST(AdequacyChoiceScenes, EngineChooserHoldsAndABrokenChooserFails) {
  const SceneOptions o = small_options();
  const SafetyTally genuine = tally_of(o);
  ASSERT_GT(genuine.lit, 1000u);
  ASSERT_GT(genuine.cheaper, genuine.lit / 2);
  EXPECT_EQ(decide_choice_safety(genuine, 1e-3).verdict, Verdict::kHoldsInRegime)
      << genuine.exceeds << " of " << genuine.lit;
  // A chooser that takes the footprint 100 times too large (a unit slip in the footprint's area):
  // it picks cheaper levels than the pixels need.
  SceneOptions broken = o;
  broken.chooser = [](double facets, double p, double tau) {
    return int(choose_binomial_level(100 * facets, p, tau));
  };
  const SafetyTally b = tally_of(broken);
  EXPECT_EQ(decide_choice_safety(b, 1e-3).verdict, Verdict::kFails) << b.exceeds << " of " << b.lit;
}

TEST(AdequacyChoiceScenes, ChooserOnFacetsAndProbabilityIsTheEngineChooser) {
  SceneOptions o = small_options();
  o.realisations = 2;
  SceneOptions by_np = o;
  by_np.chooser = [](double facets, double p, double tau) {
    return int(choose_binomial_level(facets, p, tau));
  };
  for (const ChoiceScene& s : choice_scenes()) {
    const SceneRender a = render_choice_scene(s, o), b = render_choice_scene(s, by_np);
    int on_surface = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
      EXPECT_EQ(a.pixels[i].level, b.pixels[i].level) << s.name << " pixel " << i;
      on_surface += a.pixels[i].surface ? 1 : 0;
    }
    EXPECT_GT(on_surface, 100) << s.name;
  }
}

// A scene rendered on one thread and on two.
std::pair<SceneRender, SceneRender> on_one_and_two_threads(const ChoiceScene& s,
                                                           const SceneOptions& o) {
  std::pair<SceneRender, SceneRender> r;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    r.first = render_choice_scene(s, o);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    r.second = render_choice_scene(s, o);
  }
  return r;
}

TEST(AdequacyChoiceScenes, SamePixelsForAnyThreadCount) {
  SceneOptions o = small_options();
  o.width = o.height = 16;
  const auto [one, two] = on_one_and_two_threads(choice_scenes().front(), o);
  for (std::size_t i = 0; i < one.pixels.size(); ++i) {
    EXPECT_EQ(one.pixels[i].chosen_value, two.pixels[i].chosen_value);
    EXPECT_EQ(one.pixels[i].exact_value, two.pixels[i].exact_value);
    EXPECT_EQ(one.pixels[i].cv_diff, two.pixels[i].cv_diff);
    EXPECT_EQ(one.pixels[i].exceeds, two.pixels[i].exceeds);
  }
}

TEST(AdequacyChoiceScenes, RejectsAnEmptyImageAndALevelOutsideTheFamily) {
  SceneOptions o = small_options();
  o.width = 0;
  EXPECT_THROW(render_choice_scene(choice_scenes().front(), o), std::invalid_argument);
  o = small_options();
  o.chooser = [](double, double, double) { return kBinomialLevels; };
  EXPECT_THROW(render_choice_scene(choice_scenes().front(), o), std::invalid_argument);
}

// The Kemppinen scenes: small renders of every scene, the engine chooser (choose_kemppinen_model_
// level) held by the decision, and a chooser told a footprint 100 times too large (it takes the
// smooth level or a smaller k where the pixels need more) caught by the same decision.
SceneOptions small_kemppinen_options() {
  SceneOptions o;
  o.width = o.height = 12;
  o.realisations = 128;
  o.seed = 11;
  return o;
}

SafetyTally kemppinen_tally_of(const SceneOptions& o) {
  SafetyTally t;
  for (const ChoiceScene& s : kemppinen_choice_scenes()) add(t, tally(render_choice_scene(s, o)));
  return t;
}

TEST(AdequacyChoiceScenes, KemppinenEngineChooserHoldsAndABrokenChooserFails) {
  const SceneOptions o = small_kemppinen_options();
  const SafetyTally genuine = kemppinen_tally_of(o);
  ASSERT_GT(genuine.lit, 300u);
  ASSERT_GT(genuine.cheaper, genuine.lit / 4);
  EXPECT_EQ(genuine.by_level[std::size_t(KemppinenLevel::kK16Exact)], 0u);
  EXPECT_EQ(decide_choice_safety(genuine, 1e-3).verdict, Verdict::kHoldsInRegime)
      << genuine.exceeds << " of " << genuine.lit;
  SceneOptions broken = o;
  broken.kemppinen_chooser = [](const KemppinenGGX::Params<double>& p, const ModelQuery<double>& q,
                                double tau) {
    ModelQuery<double> wide = q;
    wide.footprint.duv_dx = 10.0 * q.footprint.duv_dx;
    wide.footprint.duv_dy = 10.0 * q.footprint.duv_dy;
    return int(choose_kemppinen_model_level(p, wide, tau));
  };
  const SafetyTally b = kemppinen_tally_of(broken);
  EXPECT_EQ(decide_choice_safety(b, 1e-3).verdict, Verdict::kFails) << b.exceeds << " of " << b.lit;
}

TEST(AdequacyChoiceScenes, KemppinenPixelsAreTheSameForAnyThreadCount) {
  SceneOptions o = small_kemppinen_options();
  o.width = o.height = 6;
  const ChoiceScene s = kemppinen_choice_scenes().front();
  const auto [one, two] = on_one_and_two_threads(s, o);
  for (std::size_t i = 0; i < one.pixels.size(); ++i) {
    EXPECT_EQ(one.pixels[i].level, two.pixels[i].level);
    EXPECT_EQ(one.pixels[i].chosen_value, two.pixels[i].chosen_value);
    EXPECT_EQ(one.pixels[i].exact_value, two.pixels[i].exact_value);
    EXPECT_EQ(one.pixels[i].cv_diff, two.pixels[i].cv_diff);
  }
  o.kemppinen_chooser = [](const KemppinenGGX::Params<double>&, const ModelQuery<double>&,
                           double) { return kKemppinenLevels; };
  EXPECT_THROW(render_choice_scene(s, o), std::invalid_argument);
}

// The area family's scenes (kneiphof_klein_area, the plane under the square light): the binomial
// chooser with the model's N_P and LTC p holds on 16² renders of both, a chooser told a footprint
// 100 times too large fails, and the pixels are the same on one thread and on two.
TEST(AdequacyChoiceScenes, AreaChooserHoldsAndABrokenChooserFailsOnAnyThreadCount) {
  SceneOptions o = small_options();
  o.width = o.height = 16;
  o.realisations = 128;
  SafetyTally genuine, broken_tally;
  SceneOptions broken = o;
  broken.chooser = [](double facets, double p, double tau) {
    return int(choose_binomial_level(100 * facets, p, tau));
  };
  for (const ChoiceScene& s : area_choice_scenes()) {
    EXPECT_EQ(most_complete_level(s), int(BinomialLevel::kExact));
    add(genuine, tally(render_choice_scene(s, o)));
    add(broken_tally, tally(render_choice_scene(s, broken)));
  }
  ASSERT_GT(genuine.lit, 300u);
  ASSERT_GT(genuine.cheaper, genuine.lit / 2);
  EXPECT_EQ(decide_choice_safety(genuine, 1e-3).verdict, Verdict::kHoldsInRegime)
      << genuine.exceeds << " of " << genuine.lit;
  EXPECT_EQ(decide_choice_safety(broken_tally, 1e-3).verdict, Verdict::kFails)
      << broken_tally.exceeds << " of " << broken_tally.lit;
  o.width = o.height = 8;
  const auto [one, two] = on_one_and_two_threads(area_choice_scenes().back(), o);
  for (std::size_t i = 0; i < one.pixels.size(); ++i) {
    EXPECT_EQ(one.pixels[i].level, two.pixels[i].level);
    EXPECT_EQ(one.pixels[i].chosen_value, two.pixels[i].chosen_value);
    EXPECT_EQ(one.pixels[i].mean_diff, two.pixels[i].mean_diff);
  }
}

}  // namespace
}  // namespace glintlab::verify::adequacy

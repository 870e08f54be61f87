// The Chermain family's validation scenes of adequacy.choice-is-safe (chermain_choice_scenes,
// verify/scenes/adequacy_scenes.h): the engine chooser (choose_chermain_model_level) holds on small
// renders of both planes, a chooser that takes each dictionary some three levels early (told a
// footprint 10 times wider) fails by the same decision, and the pixels are the same on one thread
// and on two.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/glints/chermain_chooser.h"
#include "verify/scenes/adequacy_scenes.h"

namespace glintlab::verify::adequacy {
namespace {

SceneOptions chermain_options() {
  SceneOptions o;
  o.width = o.height = 12;
  o.realisations = 128;
  o.seed = 5;
  return o;
}

TEST(ChermainChoiceScenes, EngineChooserHoldsAndABrokenChooserFails) {
  const SceneOptions o = chermain_options();
  SceneOptions broken = o;
  broken.chermain_chooser = [](const Chermain::Params<double>& p, const ModelQuery<double>& q,
                               double tau) {
    ModelQuery<double> wide = q;
    wide.footprint.duv_dx = 10.0 * q.footprint.duv_dx;
    wide.footprint.duv_dy = 10.0 * q.footprint.duv_dy;
    return int(choose_chermain_model_level(p, wide, tau));
  };
  SafetyTally genuine, b;
  for (const ChoiceScene& s : chermain_choice_scenes()) {
    EXPECT_EQ(most_complete_level(s), int(kChermainMostComplete));
    add(genuine, tally(render_choice_scene(s, o)));
    add(b, tally(render_choice_scene(s, broken)));
  }
  ASSERT_GT(genuine.lit, 100u);
  ASSERT_GT(genuine.cheaper, genuine.lit / 4);
  EXPECT_EQ(decide_choice_safety(genuine, 1e-3).verdict, Verdict::kHoldsInRegime)
      << genuine.exceeds << " of " << genuine.lit;
  EXPECT_EQ(decide_choice_safety(b, 1e-3).verdict, Verdict::kFails) << b.exceeds << " of " << b.lit;
  std::printf("chermain scenes: %llu lit, %llu cheaper, %llu exceed; a footprint 10x wider: %llu\n",
              (unsigned long long)genuine.lit, (unsigned long long)genuine.cheaper,
              (unsigned long long)genuine.exceeds, (unsigned long long)b.exceeds);
}

TEST(ChermainChoiceScenes, PixelsAreTheSameForAnyThreadCount) {
  SceneOptions o = chermain_options();
  o.width = o.height = 6;
  const ChoiceScene s = chermain_choice_scenes().back();
  SceneRender one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = render_choice_scene(s, o);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = render_choice_scene(s, o);
  }
  for (std::size_t i = 0; i < one.pixels.size(); ++i) {
    EXPECT_EQ(one.pixels[i].level, two.pixels[i].level);
    EXPECT_EQ(one.pixels[i].chosen_value, two.pixels[i].chosen_value);
    EXPECT_EQ(one.pixels[i].exact_value, two.pixels[i].exact_value);
    EXPECT_EQ(one.pixels[i].cv_diff, two.pixels[i].cv_diff);
  }
  o.chermain_chooser = [](const Chermain::Params<double>&, const ModelQuery<double>&, double) {
    return kChermainLevels;
  };
  EXPECT_THROW(render_choice_scene(s, o), std::invalid_argument);
}

}  // namespace
}  // namespace glintlab::verify::adequacy

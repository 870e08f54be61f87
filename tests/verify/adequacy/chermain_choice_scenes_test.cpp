// The Chermain family's validation scenes of adequacy.choice-is-safe (chermain_choice_scenes,
// verify/scenes/adequacy_scenes.h): the engine chooser (choose_chermain_model_level) holds on small
// renders of both planes and of both spheres, a chooser that takes each dictionary some three
// levels early (told a footprint 10 times wider) fails by the same decision, the pixels are the
// same on one thread and on two, and each pixel's predicted adequate levels give the engine
// chooser's level and the chooser for given costs' (what the figure prices the scenes with).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <array>
#include <cstdio>

#include "core/glints/chermain_chooser.h"
#include "core/glints/cost_chooser.h"
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

// The scenes of one shape with the engine chooser and with a chooser told a footprint 10 times
// wider: the first holds, the second fails; returns the engine chooser's tally.
SafetyTally expect_holds_and_wider_fails(SceneShape shape, const SceneOptions& o) {
  SceneOptions broken = o;
  broken.chermain_chooser = [](const Chermain::Params<double>& p, const ModelQuery<double>& q,
                               double tau) {
    ModelQuery<double> wide = q;
    wide.footprint.duv_dx = 10.0 * q.footprint.duv_dx;
    wide.footprint.duv_dy = 10.0 * q.footprint.duv_dy;
    return int(choose_chermain_model_level(p, wide, tau));
  };
  SafetyTally genuine, b;
  int scenes = 0;
  for (const ChoiceScene& s : chermain_choice_scenes()) {
    if (s.shape != shape) continue;
    ++scenes;
    EXPECT_EQ(most_complete_level(s), int(kChermainMostComplete));
    EXPECT_EQ(s.round, shape == SceneShape::kSphere ? 1 : 0);
    add(genuine, tally(render_choice_scene(s, o)));
    add(b, tally(render_choice_scene(s, broken)));
  }
  EXPECT_EQ(scenes, 2);
  EXPECT_GT(genuine.lit, 100u);
  EXPECT_GT(genuine.cheaper, genuine.lit / 4);
  EXPECT_EQ(decide_choice_safety(genuine, 1e-3).verdict, Verdict::kHoldsInRegime)
      << genuine.exceeds << " of " << genuine.lit;
  EXPECT_EQ(decide_choice_safety(b, 1e-3).verdict, Verdict::kFails) << b.exceeds << " of " << b.lit;
  std::printf("chermain %s: %llu lit, %llu cheaper, %llu exceed; a footprint 10x wider: %llu\n",
              shape == SceneShape::kPlane ? "planes" : "spheres", (unsigned long long)genuine.lit,
              (unsigned long long)genuine.cheaper, (unsigned long long)genuine.exceeds,
              (unsigned long long)b.exceeds);
  return genuine;
}

TEST(ChermainChoiceScenes, EngineChooserHoldsAndABrokenChooserFails) {
  expect_holds_and_wider_fails(SceneShape::kPlane, chermain_options());
}

// The spheres (declared after the planes, at 10^8 and 10^11 microfacets per unit area): the same
// on 24² renders of both (fewer pixels hit the sphere).
TEST(ChermainChoiceScenes, SphereEngineChooserHoldsAndABrokenChooserFails) {
  SceneOptions o = chermain_options();
  o.width = o.height = 24;
  expect_holds_and_wider_fails(SceneShape::kSphere, o);
}

// ns per evaluation of the Chermain levels measured on this machine class (the AVX-512 rows of
// 2026-12-06, docs/adequacy.md "Choosers for given costs"): dict12 below dict4_ggaa, dict16 below
// dict8_ggaa.
constexpr std::array<double, kChermainLevels> kChermainMeasured = {34,  246,  534, 425, 991,
                                                                   530, 1357, 709, 1877};

std::array<bool, kChermainLevels> adequate_from(std::uint32_t bits) {
  std::array<bool, kChermainLevels> a{};
  for (std::size_t l = 0; l < kChermainLevels; ++l) a[l] = (bits >> l) & 1u;
  return a;
}

TEST(ChermainChoiceScenes, PredictedAdequateLevelsGiveTheEngineAndTheCostChoosersLevels) {
  // Both planes at 12², 8 realisations (the statistics are not looked at): every surface pixel's
  // ScenePixel::predicted_adequate, through cheapest_adequate_level, is the level the engine
  // chooser picked (GPU order) and, with the chooser replaced by
  // choose_chermain_model_level_by_cost for the measured order, that chooser's level. A table
  // shifted by a level (each level taken where the next is adequate) gives other levels.
  SceneOptions o = chermain_options();
  o.realisations = 8;
  SceneOptions by_cost = o;
  by_cost.chermain_chooser = [](const Chermain::Params<double>& p, const ModelQuery<double>& q,
                                double tau) {
    return int(choose_chermain_model_level_by_cost(p, q, tau, kChermainMeasured));
  };
  constexpr auto gpu = gpu_cost_order<kChermainLevels>();
  int surface = 0, differ_by_cost = 0, shifted_differ = 0;
  for (const ChoiceScene& s : chermain_choice_scenes()) {
    if (s.shape != SceneShape::kPlane) continue;
    const SceneRender engine = render_choice_scene(s, o), cost = render_choice_scene(s, by_cost);
    for (std::size_t i = 0; i < engine.pixels.size(); ++i) {
      const ScenePixel& e = engine.pixels[i];
      if (!e.surface) continue;
      ++surface;
      const auto adequate = adequate_from(e.predicted_adequate);
      EXPECT_EQ(int(cheapest_adequate_level<double, kChermainLevels>(adequate, gpu)), e.level);
      EXPECT_EQ(cost.pixels[i].predicted_adequate, e.predicted_adequate);
      EXPECT_EQ(int(cheapest_adequate_level<double, kChermainLevels>(adequate, kChermainMeasured)),
                cost.pixels[i].level);
      differ_by_cost += cost.pixels[i].level != e.level ? 1 : 0;
      std::array<bool, kChermainLevels> shifted{};
      for (std::size_t l = 0; l + 1 < kChermainLevels; ++l) shifted[l] = adequate[l + 1];
      shifted[kChermainLevels - 1] = true;
      shifted_differ +=
          int(cheapest_adequate_level<double, kChermainLevels>(shifted, gpu)) != e.level ? 1 : 0;
    }
  }
  EXPECT_GT(surface, 100);
  EXPECT_GT(shifted_differ, 0);
  std::printf(
      "chermain planes: %d surface pixels; the measured order's level differs from the GPU "
      "order's in %d; a shifted table's in %d\n",
      surface, differ_by_cost, shifted_differ);
}

TEST(ChermainChoiceScenes, PixelsAreTheSameForAnyThreadCount) {
  SceneOptions o = chermain_options();
  o.width = o.height = 6;
  const ChoiceScene s = chermain_choice_scenes()[1];
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

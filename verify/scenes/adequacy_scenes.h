// The validation scenes of claim adequacy.choice-is-safe (verify/claims/adequacy/choice_is_safe.cpp)
// and figure adequacy-scene (experiments/figures/adequacy_scene.cpp): scenes the adequacy grid was not
// measured on — a glinty plane seen from near to far under a point light and under a spherical
// (area) light, and a sphere, each at two facet densities — rendered per pixel with the level the
// engine chooser (core/glints/adequacy.h) picks for that pixel's footprint, and with the most
// complete level everywhere: for the binomial family (deliot_belcour, kneiphof_klein) exact
// counting, for the Kemppinen family (kemppinen_ggx) k = 16 with the exact erf; and the area family
// (kneiphof_klein_area: a plane under a rectangular light) against exact counting, chosen by its
// engine chooser (core/glints/area_chooser.h: the binomial chooser with the model's LTC p); and the
// Chermain family's (chermain_choice_scenes) against dict16_ggaa.
//
// Per pixel, the difference is measured the way the adequacy rule defines "no one could tell"
// (verify/adequacy/binomial_adequacy.h, compare_to_exact): over many realisations of the same
// material (the footprint moved over the surface, as the grid moves it), the relative difference
// of the means and the difference of the CVs of the chosen level against the exact one, each
// compared with TAU. A pixel "exceeds TAU" when either lower confidence bound is above TAU.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/glints/adequacy.h"
#include "core/glints/chermain.h"
#include "core/models/kemppinen_ggx.h"
#include "verify/adequacy/binomial_adequacy.h"

namespace glintlab::verify::adequacy {

enum class SceneShape { kPlane, kSphere };
enum class SceneLight { kPoint, kSphereLight, kRectLight };

struct ChoiceScene {
  std::string name;   // e.g. "plane-point-low"
  std::string model;  // deliot_belcour, kneiphof_klein or kemppinen_ggx
  SceneShape shape;
  SceneLight light;
  // log10 of the facets (binomial family: the models' density parameter) or of the points
  // (Kemppinen: K_P) per unit uv area
  double log10_density;
  std::string density_label;  // "low" or "high"
  // Declared with the claim (0) or later (1: the area and Chermain families' spheres): the
  // scenes' order over the families (declaration_order) puts every later scene after every
  // earlier one, so that a scene keeps its index and seed when another is declared.
  int round = 0;
};

// The scenes of families (the claim's order: binomial, Kemppinen, area, Chermain) in declaration
// order, as {family, scene} indices: the scenes of round 0 family by family, then those of round 1.
// A scene's position here is its seed index (claim adequacy.choice-is-safe's configuration index,
// figure adequacy-scene's seed).
std::vector<std::array<std::size_t, 2>> declaration_order(
    const std::vector<std::vector<ChoiceScene>>& families);

// The six scenes, declared before anything is measured: plane under a point light
// (deliot_belcour), plane under a spherical light (kneiphof_klein, the light's cone per pixel),
// sphere under a point light (kneiphof_klein, its default 0.26° cap), each at a low and a high
// density. GGX roughness kSceneAlpha, which is not a grid value.
std::vector<ChoiceScene> choice_scenes();
inline constexpr double kSceneAlpha = 0.15;

// The Kemppinen family's scenes, declared before anything is measured: the same plane and sphere
// under the same point lights (kemppinen_ggx evaluates a direction, not a cone: no area-light
// scene), roughness kSceneAlpha (the Kemppinen grid has 0.1, 0.3 at quick and 0.1, 0.2, 0.4 at
// full), the plane seen up to 88° (the grid's incidence stops at 60° / 80°), each at a low and a
// high K_P.
std::vector<ChoiceScene> kemppinen_choice_scenes();

// The area family's scenes, declared before anything is measured: the plane of choice_scenes()
// under a square light of side kRectLightSide at the point light's position (kneiphof_klein_area's
// rectangle, centred along ω_o at the light's distance and facing the shading point: the side
// gives it the area of the spherical light's disk, so the two area-light planes subtend the same
// solid angle to first order), GGX α = kSceneAlpha, at a low and a high facet density; and (round
// 1) the sphere of choice_scenes() under the same square light at its point light's position, at a
// low and a high density. The level per pixel: choose_kneiphof_klein_area_model_level
// (core/glints/area_chooser.h), i.e. choose_binomial_level(N_P, p, TAU) with the model's own N_P
// and (LTC) p.
std::vector<ChoiceScene> area_choice_scenes();
inline constexpr double kRectLightSide = 0.70898154036220639;  // 0.4 √π

// Whether a scene's model is of the Kemppinen family (its levels are KemppinenLevel values, its
// most complete level k16_exact) rather than the binomial one (BinomialLevel, exact).
// The Chermain family's scenes (model chermain, Chermain et al. 2021's defaults with isotropic
// roughness kSceneAlpha): the plane of choice_scenes() under its point light at 10^6 and 10^9
// microfacets per unit uv area and (round 1) the sphere under its point light at 10^8 and 10^11,
// their GGAA derivatives those of the pixel's half vector (the corner
// differences of core/scene/footprint.h, Eq. 21's h⊥): each pixel rendered with
// choose_chermain_model_level's level and with dict16_ggaa at the same realisations (the footprint
// moved along the R2 set over a square kChermainSpread cells of its coarser LOD wide, as the
// Chermain grid moves it: realisations never share a cell).
std::vector<ChoiceScene> chermain_choice_scenes();

bool is_kemppinen_scene(const ChoiceScene& s);
bool is_chermain_scene(const ChoiceScene& s);
bool is_area_scene(const ChoiceScene& s);
int most_complete_level(const ChoiceScene& s);

// A pixel's "exceeds TAU" decision: each of the two lower bounds at one-sided level
// kPixelFlagRate / 2, so that a pixel whose chosen level truly differs by at most TAU is flagged
// with probability at most kPixelFlagRate (asymptotically: the bounds are delta-method).
inline constexpr double kPixelFlagRate = 0.01;

// A chooser replacing the engine's (tests, controls): the level for N_P facets, reflection
// probability p and threshold tau.
using LevelChooser = std::function<int(double facets, double p, double tau)>;
// The same for the Kemppinen scenes: the level (a KemppinenLevel value) for the model's parameters
// and the pixel's query.
using ChermainLevelChooser =
    std::function<int(const Chermain::Params<double>&, const ModelQuery<double>&, double tau)>;
using KemppinenLevelChooser =
    std::function<int(const KemppinenGGX::Params<double>&, const ModelQuery<double>&, double tau)>;

struct SceneOptions {
  int width = 64, height = 64;
  int realisations = 256;                  // positions per pixel for the difference statistics
  double tau = kDefaultThreshold;          // what a pixel's difference is compared with
  double chooser_tau = kDefaultThreshold;  // the threshold the chooser is run with
  // empty: the engine chooser, choose_<model>_level (core/glints/adequacy.h, area_chooser.h)
  LevelChooser chooser;
  // empty: choose_kemppinen_model_level (core/glints/adequacy.h)
  KemppinenLevelChooser kemppinen_chooser;
  // empty: choose_chermain_model_level (core/glints/chermain_chooser.h), told the pixel's
  // parameters of dict16_ggaa (its derivatives included)
  ChermainLevelChooser chermain_chooser;
  std::uint64_t seed = 0;
};

struct ScenePixel {
  bool surface = false;      // the camera ray hits the shape and the light is above its horizon
  int level = -1;  // the chosen level (BinomialLevel or KemppinenLevel value), -1 off the surface
  // The footprint's N_P and the clamped probability (Kemppinen: the expected points per footprint,
  // K_P × its area, and p = 0).
  double facets = 0, p = 0;
  double chosen_value = 0, exact_value = 0;   // the rendered radiance (first realisation)
  double mean_diff = 0, cv_diff = 0;          // estimates over the realisations (0: level exact)
  double mean_diff_lcb = 0, cv_diff_lcb = 0;  // their lower confidence bounds
  // The exact level is non-zero at >= kMinLitPositions realisations: a difference is measurable.
  bool lit = false;
  bool exceeds = false;  // a lower bound above TAU: the chosen level differs by more, for sure
  // The Kemppinen and Chermain families: bit l set where the engine chooser at the options'
  // chooser_tau predicts level l adequate (kemppinen_level_adequacy, chermain_level_adequacy of
  // core/glints/cost_chooser.h and chermain_chooser.h), so that a chooser for given costs
  // (cheapest_adequate_level) can be priced on the pixel; 0 for the other families.
  std::uint32_t predicted_adequate = 0;
};

struct SceneRender {
  ChoiceScene scene;
  int width = 0, height = 0;
  std::vector<ScenePixel> pixels;  // row by row from the top left
};

// Renders one scene (in parallel over rows; the result does not depend on the thread count).
SceneRender render_choice_scene(const ChoiceScene& scene, const SceneOptions& options);

// Counts over scenes.
struct SafetyTally {
  std::uint64_t lit = 0;      // lit pixels (the claim's denominator)
  std::uint64_t cheaper = 0;  // of which the chooser picked a level cheaper than exact
  std::uint64_t exceeds = 0;  // of which the difference exceeds TAU
  // lit pixels per chosen level (the family's levels; the binomial family uses the first four)
  std::array<std::uint64_t, kKemppinenLevels> by_level{};
};
SafetyTally tally(const SceneRender& r);
void add(SafetyTally& into, const SafetyTally& t);

// The decision: the count of lit pixels exceeding TAU against H0 "the rate is at most
// kPixelFlagRate" (what safe choices give), one-sided exact binomial test at `alpha`. `allowed` is
// the largest count the test does not reject, so the verdict is holds-in-regime exactly when
// exceeds <= allowed.
struct SafetyDecision {
  double fraction = 0;          // exceeds / lit
  std::uint64_t allowed = 0;    // the largest count not rejected
  double allowed_fraction = 0;  // allowed / lit
  double p_value = 1;           // P(X >= exceeds) under Binomial(lit, kPixelFlagRate)
  Verdict verdict = Verdict::kInconclusive;
};
SafetyDecision decide_choice_safety(const SafetyTally& t, double alpha);

}  // namespace glintlab::verify::adequacy

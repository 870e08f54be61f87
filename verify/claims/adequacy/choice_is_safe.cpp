// adequacy.choice-is-safe — glintlab's rule, on the chooser of core/glints/adequacy.h (Kneiphof &
// Klein 2024 Eq. 16; Deliot & Belcour 2023).
//
// The rule (docs/verification.md, glintlab's own rules): "rendering each pixel with the chosen level differs from the most
// complete level by more than TAU in no more pixels than the confidence level allows, on scenes
// outside the fitting grid".
//
// Measured: on scenes the grids were not measured on (verify/scenes/adequacy_scenes.h), per pixel,
// the level an engine chooser picks against the family's most complete level, over realisations
// (surface positions): a lit pixel (the most complete level non-zero at ≥ kMinLitPositions
// realisations) exceeds when its chosen level's mean or CV differs by more than TAU (a lower bound
// at one-sided kPixelFlagRate / 2 each). For the binomial family (deliot_belcour, kneiphof_klein:
// six scenes), the Kemppinen family (kemppinen_ggx against k16_exact: four scenes), the area
// family (kneiphof_klein_area under a square light, the binomial chooser with its LTC p: the plane
// and the sphere, four scenes) and the Chermain family (against dict16_ggaa: the plane and the
// sphere, four scenes), each family decided on its own at the Šidák share of the per-check level
// by an exact binomial count against the rate kPixelFlagRate safe choices give; holds in regime
// when every family holds, fails when any fails.
// Control (perturbed): the choosers run with TAU × 10 (they then take levels up to 10 TAU off),
// rendered at the same positions; rejected only when every family fails.
// Regime: the engine choosers at TAU = 0.02 on these scenes, GGX α = 0.15, at the sizes stated.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "verify/claim_runner.h"
#include "core/glints/chermain_chooser.h"
#include "verify/claims/adequacy/list.h"
#include "verify/scenes/adequacy_scenes.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::adequacy_claims {

// The control runs the chooser at TAU × this: it then takes cheaper levels where they differ from
// the exact one by up to 10 TAU (the smooth level up to a CV of 0.1), which must be caught.
constexpr double kControlTauScale = 10;

// One family's scenes and options, and its name and level names for the detail.
struct ChoiceFamily {
  const char* name;
  std::vector<adequacy::ChoiceScene> scenes;
  adequacy::SceneOptions options;
  std::vector<std::string_view> level_names;
};

inline adequacy::SceneOptions scene_options(int side, int realisations) {
  adequacy::SceneOptions o;
  o.width = o.height = side;
  o.realisations = realisations;
  return o;
}

// The binomial scenes at `side`² pixels, `realisations` each; the Kemppinen scenes cost some
// 90 µs of CPU per realisation of a pixel (k = 16 is 512 points): fewer pixels and realisations
// (128 realisations still leave the lit condition, the exact level non-zero at >= 100 of them,
// reachable).
// The area scenes (an LTC integral per evaluation, some 2-3 µs) at `area_side`² pixels.
inline std::vector<ChoiceFamily> choice_families(int side, int realisations, int kemppinen_side,
                                                 int kemppinen_realisations, int area_side,
                                                 int area_realisations, int chermain_side,
                                                 int chermain_realisations) {
  return {{"binomial",
           adequacy::choice_scenes(),
           scene_options(side, realisations),
           {kBinomialLevelNames.begin(), kBinomialLevelNames.end()}},
          {"kemppinen",
           adequacy::kemppinen_choice_scenes(),
           scene_options(kemppinen_side, kemppinen_realisations),
           {kKemppinenLevelNames.begin(), kKemppinenLevelNames.end()}},
          {"area",
           adequacy::area_choice_scenes(),
           scene_options(area_side, area_realisations),
           {kBinomialLevelNames.begin(), kBinomialLevelNames.end()}},
          {"chermain",
           adequacy::chermain_choice_scenes(),
           scene_options(chermain_side, chermain_realisations),
           {kChermainLevelNames.begin(), kChermainLevelNames.end()}}};
}

struct FamilyMeasured {
  std::vector<adequacy::SafetyTally> scenes;
  adequacy::SafetyTally total;
  adequacy::SafetyDecision decision;
};

inline std::string describe_family(const ChoiceFamily& family, const FamilyMeasured& m) {
  std::string per_scene;
  for (std::size_t i = 0; i < m.scenes.size(); ++i) {
    const adequacy::SafetyTally& t = m.scenes[i];
    per_scene +=
        fmt::format("{}{} ({}): {} lit, {} cheaper, {} exceed", per_scene.empty() ? "" : "; ",
                    family.scenes[i].name, family.scenes[i].model, t.lit, t.cheaper, t.exceeds);
  }
  std::string levels;
  for (std::size_t l = 0; l < family.level_names.size(); ++l)
    levels += fmt::format("{}{} {}", l ? ", " : "", family.level_names[l], m.total.by_level[l]);
  return fmt::format(
      "{} family: {} of {} lit pixels exceed TAU (fraction {:.4g}; allowed ≤ {} = {:.4g}, "
      "one-sided exact binomial p = {:.3g} against rate ≤ {}); chosen levels of "
      "the lit pixels: {}; {}",
      family.name, m.total.exceeds, m.total.lit, m.decision.fraction, m.decision.allowed,
      m.decision.allowed_fraction, m.decision.p_value, adequacy::kPixelFlagRate, levels, per_scene);
}

struct ChoiceIsSafe {
  static constexpr std::string_view kId = "adequacy.choice-is-safe";
  static constexpr std::string_view kPaper = "glintlab (adequacy of the binomial family)";
  static constexpr std::string_view kSource =
      "core/glints/adequacy.h and chermain_chooser.h choosers; Kneiphof & Klein 2024 Eq. 16 (Sec. 4 "
      "for the area light); Deliot & Belcour 2023; Kemppinen et al. 2025; Chermain et al. 2021 "
      "Eq. 3, 19-21";
  // The paper's own sentence or equation the claim is judged against (glintlab's own rule).
  static constexpr std::string_view kQuote =
      "Not a paper's claim: glintlab's rule (docs/verification.md): \"rendering each pixel "
      "with the chosen level differs from the most complete level by more than TAU in "
      "no more pixels than the confidence level allows, on scenes outside the fitting "
      "grid\"";
  static constexpr bool kGlintlabRule = true;
  // The decision is a count against the exact binomial test's critical count, reported as a bound
  // (the test's p-value is in the detail): a p-valued check would take a share of check_level()
  // and move every recorded claim's level.
  static inline const std::string kStatistic = fmt::format(
      "per family, the fraction of lit pixels (most complete level non-zero at >= {} of the "
      "realisations) whose chosen level's mean or CV differs from the most complete level's by "
      "more than TAU (a lower bound at one-sided {} each above TAU); value and bound: the family "
      "nearest its allowed count",
      adequacy::kMinLitPositions, adequacy::kPixelFlagRate / 2);
  static constexpr Expected kExpected{.quick = Verdict::kHoldsInRegime};

  struct Sizes {
    std::vector<ChoiceFamily> families;
  };
  static Sizes sizes(Budget b) {
    return b == Budget::kQuick ? Sizes{choice_families(64, 256, 24, 128, 32, 256, 32, 128)}
                               : Sizes{choice_families(128, 1024, 48, 256, 64, 512, 64, 256)};
  }
  // The tests' probe: every scene, at fewer pixels (the realisations keep the lit condition
  // reachable).
  static Sizes probe_sizes() { return {choice_families(16, 128, 8, 128, 8, 128, 8, 128)}; }

  // Configurations: the scenes of every family in declaration order (adequacy::declaration_order:
  // the binomial, Kemppinen, area and Chermain planes and the binomial and Kemppinen spheres first,
  // then the area and Chermain spheres, declared later: every earlier scene keeps its seed).
  static std::vector<std::array<std::size_t, 2>> order(const Sizes& z) {
    std::vector<std::vector<adequacy::ChoiceScene>> scenes;
    for (const ChoiceFamily& f : z.families) scenes.push_back(f.scenes);
    return adequacy::declaration_order(scenes);
  }
  static int configurations(const Sizes& z) { return int(order(z).size()); }
  // One scene rendered with its family's engine chooser at TAU (genuine) and at TAU × 10 (the
  // control), at the same positions (seed: the claim id and the scene's index in declaration
  // order), differences compared with the rule's TAU.
  struct Evidence {
    adequacy::SafetyTally genuine, control;
  };
  static Evidence observe(const Sizes& z, int k, std::uint64_t seed) {
    const auto [f, i] = order(z)[std::size_t(k)];
    const ChoiceFamily& family = z.families[f];
    adequacy::SceneOptions o = family.options;
    o.seed = seed;
    Evidence e;
    o.chooser_tau = family.options.tau;
    e.genuine = adequacy::tally(adequacy::render_choice_scene(family.scenes[i], o));
    o.chooser_tau = family.options.tau * kControlTauScale;
    e.control = adequacy::tally(adequacy::render_choice_scene(family.scenes[i], o));
    return e;
  }

  // Every family decided on its own at the Šidák share of the per-check level (a family with many
  // pixels would otherwise hide another's unsafe choices).
  struct Measured {
    std::vector<FamilyMeasured> families;
    Verdict verdict = Verdict::kInconclusive;  // fails when any fails, holds when every holds
    std::size_t nearest = 0;                   // the family with the largest exceeds / allowed
    std::uint64_t lit = 0;
    Input input = Input::kGenuine;
  };
  static Measured measure(const Sizes& z, std::span<const Evidence> evidence, Input input) {
    Measured run;
    run.input = input;
    const double alpha = sidak_level(check_level(), z.families.size());
    // Each family's scenes in its own order: the evidence of scene i of family f.
    std::vector<std::vector<const Evidence*>> of(z.families.size());
    for (std::size_t f = 0; f < z.families.size(); ++f) of[f].resize(z.families[f].scenes.size());
    const auto configs = order(z);
    for (std::size_t k = 0; k < configs.size(); ++k) of[configs[k][0]][configs[k][1]] = &evidence[k];
    bool all_hold = true, any_fails = false;
    double nearest = -1;
    for (std::size_t f = 0; f < z.families.size(); ++f) {
      FamilyMeasured m;
      for (const Evidence* e : of[f]) {
        m.scenes.push_back(input == Input::kGenuine ? e->genuine : e->control);
        adequacy::add(m.total, m.scenes.back());
      }
      m.decision = adequacy::decide_choice_safety(m.total, alpha);
      all_hold = all_hold && m.decision.verdict == Verdict::kHoldsInRegime;
      any_fails = any_fails || m.decision.verdict == Verdict::kFails;
      const double ratio =
          double(m.total.exceeds) / double(std::max<std::uint64_t>(m.decision.allowed, 1));
      if (ratio > nearest) nearest = ratio, run.nearest = f;
      run.lit += m.total.lit;
      run.families.push_back(std::move(m));
    }
    run.verdict = any_fails  ? Verdict::kFails
                  : all_hold ? Verdict::kHoldsInRegime
                             : Verdict::kInconclusive;
    return run;
  }

  // The control is rejected only when every family's TAU × 10 chooser is caught: its verdict is
  // "fails" when every family fails, else the verdict of a family that was not caught.
  static Decision decide(const Sizes&, const Measured& m) {
    if (m.input != Input::kGenuine) {
      for (const FamilyMeasured& f : m.families)
        if (f.decision.verdict != Verdict::kFails) return {.verdict = f.decision.verdict};
      return {.verdict = Verdict::kFails};
    }
    return {.verdict = m.verdict,
            .value = m.families[m.nearest].decision.fraction,
            .bound = m.families[m.nearest].decision.allowed_fraction,
            .configurations = int(m.lit)};
  }

  static std::string regime(const Sizes& z) {
    const adequacy::SceneOptions& o = z.families[0].options;
    const adequacy::SceneOptions& k = z.families[1].options;
    const adequacy::SceneOptions& a = z.families[2].options;
    const adequacy::SceneOptions& c = z.families[3].options;
    // A family's scenes as "plane K_P 10^4, sphere ..." (`unit`: what the density counts).
    const auto densities = [&](std::size_t f, std::string_view unit) {
      std::string out;
      for (const adequacy::ChoiceScene& sc : z.families[f].scenes)
        out += fmt::format("{}{} {}10^{:g}", out.empty() ? "" : ", ",
                           sc.shape == adequacy::SceneShape::kPlane ? "plane" : "sphere", unit,
                           sc.log10_density);
      return out;
    };
    return fmt::format(
        "the engine choosers of core/glints/adequacy.h at TAU = {} on scenes outside the adequacy "
        "grids, GGX alpha = {}: the binomial family (deliot_belcour, kneiphof_klein; levels "
        "smooth, realtime, small_count, exact) on six scenes (a plane from 1.6 to 30 units under "
        "a point light and under a spherical light, a sphere under a point light, each at two "
        "facet densities), {}x{} pixels, {} realisations per pixel; the Kemppinen family "
        "(kemppinen_ggx; levels smooth, k = 1, 4, 9, 16 with the rational or the exact erf, "
        "against k16_exact) on {} scenes (the plane and the sphere under the point lights; {}), "
        "{}x{} pixels, {} realisations per pixel; the area family (kneiphof_klein_area; the "
        "binomial levels, chosen by choose_binomial_level with the model's N_P and LTC p) on {} "
        "scenes (the plane and the sphere under a square light of side {:.3g} facing the point, "
        "each at two facet densities: {} facets per unit area), {}x{} pixels, {} realisations per "
        "pixel; the Chermain family (chermain; levels smooth, dict4, 8, 12, 16 with GGAA off or "
        "on, against dict16_ggaa; chosen by choose_chermain_model_level of "
        "core/glints/chermain_chooser.h with the pixel's GGAA derivatives) on {} scenes (the plane "
        "and the sphere under the point lights: {} microfacets per unit area), {}x{} pixels, {} "
        "realisations per pixel; each family decided on its own at the Šidák share of the "
        "per-check level",
        o.tau, adequacy::kSceneAlpha, o.width, o.height, o.realisations,
        z.families[1].scenes.size(), densities(1, "K_P "), k.width, k.height, k.realisations,
        z.families[2].scenes.size(), adequacy::kRectLightSide, densities(2, ""), a.width, a.height,
        a.realisations, z.families[3].scenes.size(), densities(3, ""), c.width, c.height,
        c.realisations);
  }

  // The control's line as describe words it: it states its own rule for the verdict, so the
  // runner adds no "→ verdict (rejected)".
  static std::string control_text(const Sizes& z, const Measured& control, Input input, Verdict) {
    return describe(z, control, input);
  }
  static std::string describe(const Sizes& z, const Measured& m, Input input) {
    std::string out;
    for (std::size_t f = 0; f < z.families.size(); ++f)
      out += (f ? " | " : "") + describe_family(z.families[f], m.families[f]);
    if (input == Input::kGenuine) return out;
    return fmt::format(
        "the choosers run with TAU × {:g} (rejected only when every family "
        "fails): {}",
        kControlTauScale, out);
  }

  static std::string power(const Sizes& z, const Measured& m, const Measured& c) {
    std::string power;
    for (std::size_t f = 0; f < z.families.size(); ++f)
      power += fmt::format(
          "{}{}: rejects once more than {} of the {} lit pixels ({:.3g}) exceed TAU, where safe "
          "choices flag at most a fraction {}; the TAU × {:g} chooser makes {:.3g} exceed",
          f ? "; " : "", z.families[f].name, m.families[f].decision.allowed,
          m.families[f].total.lit, m.families[f].decision.allowed_fraction,
          adequacy::kPixelFlagRate, kControlTauScale, c.families[f].decision.fraction);
    return power;
  }
};

}  // namespace glintlab::verify::adequacy_claims

GLINTLAB_CLAIM(glintlab::verify::adequacy_claims::ChoiceIsSafe);

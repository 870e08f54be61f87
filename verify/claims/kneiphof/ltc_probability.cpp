// kneiphof.ltc-probability — Kneiphof & Klein 2024, Sec. 4, Sec. 7, Fig. 8, Eq. 12–19.
//
// The paper, Sec. 4: "we propose to approximate D_Ωi using the same LTC lobe as the outgoing
// radiance of the continuous microfacet BRDF …, despite the relatively large difference between
// the BRDF LTC approximation and the target NDF"; Sec. 7: "The difference due to an approximation
// of the continuous NDF with the same lobe is measurable but visually negligible."
//
// Measured: over square lights at distance 1 (centred on the mirror direction or overhead), √α and
// view angles (ltc_cells.h), the pixel L̂ = L_o·b/(N_P p) (Eq. 16) with p from the BRDF LTC lobe ×
// D_PR (the paper's choice) against the same pixel with a converged Monte Carlo p = D_Ωh/D_H: the
// largest change of its mean or standard deviation relative to its mean, at λ = N_P·p_MC 1..1000
// reflecting facets per pixel, held to the 2 % Weber fraction over the reference's ± 3 SE band.
// Beside it: the probability itself within 10 % (the stronger reading), an independent LTC fit
// at each regime cell's exact α and θv, and the table lobe's polygon integral by brute force.
// A "fails" stands only where the rule holds the near-truth input (an independent Monte Carlo
// p × 1.03); where it does not, the rule cannot tell a 3 % error from the truth (inconclusive).
// Control: the LTC pixel rendered 4 % brighter (perturbed: must fail); the pixel with the
// near-truth p (corrected: must hold).
// Regime, declared before measuring: the abstract assigns LTCs to "large light sources" (and
// spherical caps to small ones, Sec. 5), and the glints that matter sit in the highlight: lights
// of side ≥ 0.5 at distance 1 centred on the mirror direction, outside the lobe's tail.
#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "verify/claim_runner.h"
#include "verify/claims/kneiphof/common.h"
#include "verify/claims/kneiphof/ltc_cells.h"

namespace glintlab::verify::kneiphof_claims {

struct LtcProbability {
  static constexpr std::string_view kId = "kneiphof.ltc-probability";
  static constexpr std::string_view kPaper = kneiphof_claims::kPaper;
  static constexpr std::string_view kSource = "Sec. 4, Sec. 7, Fig. 8, Eq. 12–19";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Sec. 4: \"we propose to approximate D_Ωi using the same LTC lobe as the outgoing "
      "radiance of the continuous microfacet BRDF …, despite the relatively large "
      "difference between the BRDF LTC approximation and the target NDF\"; Sec. 7: "
      "\"The difference due to an approximation of the continuous NDF with the same "
      "lobe is measurable but visually negligible.\" Sec. 6 (Fig. 8): \"Our choice for "
      "reusing the existing LTC approximation is supported by an easier implementation "
      "and negligible change in appearance.\"";
  // What the check tests beyond the quote (so a verdict on it is never the paper failing).
  static constexpr std::string_view kStrongerReading =
      "The verdict is on the rendered difference (the pixel L̂ = L_o·b/(N_P p) of Eq. 16 with "
      "the LTC p against the Monte Carlo p, its mean and standard deviation held to the 2 % "
      "Weber fraction at 1–1000 reflecting facets per pixel). Measured beside it, a stronger "
      "reading than the paper's: p = D_PR · ∫ D_ltc within 10 % (kTolerance, borrowed from "
      "kneiphof.cap-probability) of a Monte Carlo D_Ωh in every cell of the declared regime "
      "(square lights of side ≥ 0.5 on the mirror direction, θv to 85°); it fails, and an "
      "independent LTC fit does not change that.";
  // The competing causes reviewed for a "fails" (verify/finding_rule.h): how each was ruled
  // out, or why it is still open.
  static std::vector<Alternative> alternatives() {
    return {{"implementation (our LTC fit)",
             "excluded: an independent fit at each regime cell's exact α and θv (L1 distance by a "
             "compass search over M⁻¹'s entries, where the table minimizes the L3 distance by "
             "Nelder–Mead over a factorized M and is interpolated; D_PR exact, not interpolated) "
             "leaves the BRDF lobe's probability error as it is (median share removed below 1 %; "
             "beyond 10 %: 7 → 7 of 18 cells quick, 46 → 44 of 108 full), so the error is the LTC "
             "family's, not our fit's (the NDF lobe's fit, the paper's alternative, is "
             "improvable: 17 → 6 cells beyond at full); the closed-form polygon integral agrees "
             "with brute force over the lobe's own samples (every cell within 4 SE)",
             true},
            {"tolerance (the rendered difference's resolution)",
             "not excluded: the rendered pixel L̂ = L_o·b/(N_P p) (Eq. 16) with the LTC p is "
             "beyond the 2 % Weber fraction of the Monte Carlo pixel's mean (in its standard "
             "deviation) in regime cells at every glint density, up to 5 % at 1000 reflecting "
             "facets per pixel (√α 0.9, θv 85°); but at 1 and 10 facets per pixel the same rule "
             "also rejects a near-truth input (an independent Monte Carlo p × 1.03), so it cannot "
             "tell the paper's approximation from a 3 % error there, and the paper states neither "
             "its figures' glint density nor a visual threshold",
             false},
            {"scene or regime mismatch",
             "not excluded: the pixels beyond 2 % at the densities the rule resolves (100 and 1000 "
             "facets per pixel) are grazing views (θv 75–85°, √α ≥ 0.3) and the roughest lobe (√α "
             "0.9); Figs. 7–8 show one plane under one rectangular light, whose view angles and "
             "roughness the paper does not give",
             false}};
  }
  static constexpr std::string_view kStatistic =
      "max rendered difference max(|Δ mean|, |Δ sd|)/mean of the pixel L̂ = L_o·b/(N_P p) (Eq. 16) "
      "with p from the BRDF LTC lobe × D_PR (the paper's choice) against p from Monte Carlo D_Ωh, "
      "over the regime's cells and λ = N_P p_MC 1..1000 reflecting facets per pixel";
  static constexpr std::string_view kRegime =
      "square light of side ≥ 0.5 at distance 1 (≥ 28° across: the abstract's 'large light "
      "sources'), centred on the mirror direction, every √α 0.1..0.9 and θv 0..85° of the grid, "
      "p_MC ≥ 1e-3 D_PR; λ = 1..1000 reflecting facets per pixel";
  // At the probe's four regime cells, decided from λ = 100 on (where the rule resolves the
  // near-truth input), the LTC pixel is within 2 %.
  static constexpr Expected kExpected{.quick = Verdict::kInconclusive,
                                      .probe = Verdict::kHoldsWithin};
  static constexpr bool kHasCorrectedControl = true;

  struct Sizes {
    std::vector<double> sides, roughness, views;  // light side at distance 1, √α, θv in degrees
    std::vector<int> positions;                   // 0: on the mirror direction, 1: overhead
    int samples;                                  // per Monte Carlo batch (16 batches)
    int refit_evaluations;                        // the independent fit's, per lobe
    std::size_t first_density;  // decided over kGlintsPerPixel from this density on
  };
  static Sizes sizes(Budget b) {
    if (b == Budget::kQuick)
      return {{0.05, 0.5, 2.0},
              {0.1, 0.5, 0.9},
              {0, 40, 85},
              {0, 1},
              2048,
              ltc::kRefitEvaluationsQuick,
              0};
    return {{0.05, 0.2, 0.5, 1.0, 2.0},
            {0.1, 0.2, 0.3, 0.5, 0.7, 0.9},
            {0, 20, 40, 60, 75, 85},
            {0, 1},
            65536,
            ltc::kRefitEvaluationsFull,
            0};
  }
  // Four regime cells (side 0.5 and 2, √α 0.5, θv 0° and 40°), from λ = 100 on: at λ 1 and 10 the
  // rule cannot hold a 3 % error near p = 1 (why the claim is inconclusive at the budgets).
  static Sizes probe_sizes() {
    return {{0.5, 2.0}, {0.5}, {0, 40}, {0}, 2048, ltc::kRefitEvaluationsQuick, 2};
  }

  // Configuration k: a column of the sweep, one √α, view and position, every light side (the
  // sides share its independent fit). Its cells' stream indices are their places in the sweep's
  // order: side, then √α, then view, then position.
  static int configurations(const Sizes& z) {
    return int(z.roughness.size() * z.views.size() * z.positions.size());
  }

  using Evidence = std::vector<ltc::Cell>;  // one per light side
  // One seed for the sweep; the independent fit on the mirror direction (where a light of side
  // ≥ 0.5 is in the regime).
  static Evidence observe(const Sizes& z, int k, std::uint64_t) {
    const int np = int(z.positions.size()), nv = int(z.views.size());
    const double sqrt_alpha = z.roughness[std::size_t(k / (np * nv))];
    const double view = z.views[std::size_t(k / np % nv)];
    const int position = z.positions[std::size_t(k % np)];
    const std::uint64_t seed = check_seed(std::string(kId), 0);
    std::optional<ltc::Refit> refit;
    Evidence column;
    for (std::size_t s = 0; s < z.sides.size(); ++s) {
      const ltc::Config c{z.sides[s], sqrt_alpha, view, position};
      const bool regime_light = position == 0 && c.side >= ltc::kRegimeMinSide;
      if (regime_light && !refit) refit = ltc::refit_at(sqrt_alpha, view, z.refit_evaluations);
      const std::uint64_t index = s * std::size_t(configurations(z)) + std::size_t(k);
      column.push_back(ltc::evaluate(c, z.samples, seed, index, regime_light ? &*refit : nullptr));
    }
    return column;
  }

  struct Measured {
    Input input;
    std::vector<ltc::Cell> cells;
  };
  // The cells in the sweep's order, and which input's pixel is judged.
  static Measured measure(const Sizes& z, std::span<const Evidence> all, Input input) {
    Measured m{input, {}};
    for (std::size_t s = 0; s < z.sides.size(); ++s)
      for (const Evidence& column : all) m.cells.push_back(column[s]);
    return m;
  }
  static ltc::CellPixel pixel_of(Input input) {
    return input == Input::kGenuine     ? ltc::brdf_pixel
           : input == Input::kPerturbed ? ltc::brighter_pixel
                                        : ltc::near_truth_pixel;
  }
  // Whether the rule holds the near-truth input: where it does not, a genuine "fails" is not a
  // finding. Added after the first run showed the near-truth input beyond 2 % at λ 1 and 10 near
  // p = 1, where the pixel's fluctuation √((1 − p)/(N_P p)) moves fast with p; the regime and the
  // tolerance are unchanged. The controls are decided by the declared rule alone.
  static bool resolves(const Sizes& z, const std::vector<ltc::Cell>& cells) {
    return is_holding(ltc::decide_rendered(cells, ltc::near_truth_pixel, z.first_density));
  }

  static Decision decide(const Sizes& z, const Measured& m) {
    const ltc::CellPixel get = pixel_of(m.input);
    const ltc::RenderedSummary regime =
        ltc::summarize_rendered(m.cells, get, true, z.first_density);
    Decision d{
        .value = regime.max, .bound = ltc::kVisualTolerance, .configurations = int(m.cells.size())};
    d.verdict =
        ltc::verdict_of(ltc::summarize_rendered(m.cells, get, false, z.first_density), regime);
    if (m.input == Input::kGenuine && d.verdict == Verdict::kFails && !resolves(z, m.cells))
      d.verdict = Verdict::kInconclusive;
    return d;
  }

  static std::string describe(const Sizes& z, const Measured& m, Input input);

  static std::string power(const Sizes&, const Measured& m, const Measured&) {
    double regime_se = 0;
    for (const ltc::Cell& c : m.cells)
      if (ltc::in_regime(c)) regime_se = std::max(regime_se, c.ref_se / c.ref);
    return fmt::format(
        "the rendered difference scales with the pixel's relative fluctuation √((1 − p)/λ), so at "
        "λ = 1 a probability error of about 4 % is beyond the 2 % tolerance and at λ = 1000 one of "
        "about 250 % is; the largest rel. SE of p_MC in the regime is {:.2g} (probability level: "
        "an excess of ≥ {:.2g} over 10 % is detected at 90 % power in every regime cell)",
        regime_se, (3 + 1.2816) * regime_se);
  }

  // Beside the control's verdict: the probability-level rule on the near-truth p and on the BRDF
  // lobe scaled by its albedo FGD (Sec. 4 'LTC Scale') in place of D_PR.
  static std::string beside_control(const Sizes&, const Measured& m) {
    const auto near_truth = [](const ltc::Cell& c) { return c.near_truth; };
    const auto scaled = [](const ltc::Cell& c) { return c.albedo_scaled; };
    return fmt::format(
        "Probability level beside it: an independent Monte Carlo D_Ωh × 1.03 in the LTC's place, "
        "everywhere {} ({}); the BRDF lobe scaled by its albedo FGD instead of D_PR (Sec. 4 'LTC "
        "Scale'), everywhere: {}, {} by the 10 % rule",
        ltc::describe_summary(ltc::summarize(m.cells, near_truth)),
        to_string(ltc::decide(m.cells, near_truth)),
        ltc::describe_summary(ltc::summarize(m.cells, scaled)),
        to_string(ltc::decide(m.cells, scaled)));
  }
};

std::string LtcProbability::describe(const Sizes& z, const Measured& m, Input input) {
  using namespace ltc;
  const std::vector<Cell>& cells = m.cells;
  const std::size_t d0 = z.first_density;
  if (input != Input::kGenuine)
    return fmt::format("{}: regime {}; everywhere {}",
                       input == Input::kPerturbed
                           ? "the LTC pixel rendered 4 % brighter"
                           : "the pixel with an independent Monte Carlo p × 1.03 (near truth)",
                       describe_rendered(summarize_rendered(cells, pixel_of(input), true, d0)),
                       describe_rendered(summarize_rendered(cells, pixel_of(input), false, d0)));
  const auto get_brdf = [](const Cell& c) { return c.brdf; };
  const LobeSummary brdf = summarize(cells, get_brdf);
  const LobeSummary brdf_regime = summarize(cells, get_brdf, true);
  const LobeSummary ndf = summarize(cells, [](const Cell& c) { return c.ndf; });
  const RenderedSummary rendered = summarize_rendered(cells, brdf_pixel, false, d0);
  const RenderedSummary rendered_regime = summarize_rendered(cells, brdf_pixel, true, d0);
  const RenderedSummary rendered_ndf = summarize_rendered(cells, ndf_pixel, true, d0);
  const RenderedSummary near_regime = summarize_rendered(cells, near_truth_pixel, true, d0);
  const FitComparison fits = compare_fits(cells);
  const Verdict declared = verdict_of(rendered, rendered_regime);
  const bool resolves = LtcProbability::resolves(z, cells);
  int tail = 0, regime_cells = 0;
  double tail_max = 0, worst_se = 0;
  for (const Cell& c : cells) {
    if (c.tail) {
      ++tail, tail_max = std::max(tail_max, rel_error(c.brdf, c));
      continue;
    }
    worst_se = std::max(worst_se, c.ref_se / c.ref);
    regime_cells += in_regime(c);
  }
  std::string by_lambda, resolved_beyond;
  for (std::size_t k = d0; k < kGlintsPerPixel.size(); ++k) {
    by_lambda += fmt::format("{}λ {:g}: {} / {}", k > d0 ? ", " : "", kGlintsPerPixel[k],
                             rendered_regime.not_in_by_lambda[k], near_regime.not_in_by_lambda[k]);
    // Where the rule holds the near-truth input in every regime cell: the LTC pixels beyond.
    if (near_regime.not_in_by_lambda[k] > 0) continue;
    for (const Cell& c : cells)
      if (in_regime(c)) {
        const RenderedDecision d = rendered_decision(brdf_pixel(c), c, kGlintsPerPixel[k]);
        if (d.low > kVisualTolerance)
          resolved_beyond += fmt::format("{}λ {:g} {} ({:.3g}, p error {:.3g})",
                                         resolved_beyond.empty() ? "" : "; ", kGlintsPerPixel[k],
                                         ltc::describe(c.c), d.at_estimate, rel_error(c.brdf, c));
      }
  }
  const Verdict stronger = verdict_of(brdf, brdf_regime);
  return fmt::format(
      "square light of side s at distance 1 (s {}..{}), √α {}..{}, θv {}..{}°, centred on the "
      "mirror direction or overhead; {} cells ({} in the tail, p_MC < {:.0e} D_PR, apart); MC {} "
      "batches, worst rel. SE {:.2g}. Rendered difference (tolerance {:.0f} %, the Weber "
      "fraction; each (cell, λ) pair decided over the reference's ± 3 SE band), regime "
      "(declared): {}, {} cells × λ {:g}..{:g}: BRDF lobe × D_PR (the paper's): {}; everywhere: "
      "{}; NDF lobe × D_PR ('+ NDF LTC', Fig. 8's middle column), regime: {}. The declared rule "
      "gives {}; regime pairs not within 2 %, BRDF lobe / near-truth input, by λ: {}{}; at the "
      "densities where the near-truth input is within 2 % in every regime cell, the LTC pixel is "
      "beyond at: {}. "
      "Stronger reading, "
      "the probability within {:.0f} % (± 3 SE): {}; regime: {}; everywhere: {}; median by axis: "
      "{}. NDF lobe × D_PR everywhere: {}; median by axis: {}. Tail cells: max rel. error {:.3g}. "
      "Independent fit (L1 compass search at the exact α, θv; exact D_PR), {} regime cells: BRDF "
      "lobe rel. error of p median {:.3g} → {:.3g}, max {:.3g} → {:.3g}, beyond 10 % {} → {}; "
      "NDF lobe median {:.3g} → {:.3g}, max {:.3g} → {:.3g}, beyond {} → {}; median share of the "
      "BRDF lobe's error an independent fit removes {:.2g}; the fit cause of the stronger "
      "reading's failure is {} (excluded when a regime cell stays beyond 10 % with the "
      "independent fit). The table's BRDF lobe integrated over the light by brute force (its own "
      "samples, over the same domain as the closed form): closed form within {:.2g} (max rel.), "
      "max |z| {:.2g} at {} ({:.5g} vs {:.5g}), {} cells beyond 4 SE; the part of the light below "
      "the horizon, which the LTC convention counts, holds up to {:.2g} of the lobe's integral "
      "({})",
      z.sides.front(), z.sides.back(), z.roughness.front(), z.roughness.back(), z.views.front(),
      z.views.back(), cells.size(), tail, kTailFraction, kBatches, worst_se, 100 * kVisualTolerance,
      kRegime.substr(0, kRegime.find("; λ")), regime_cells, kGlintsPerPixel.front(),
      kGlintsPerPixel.back(), describe_rendered(rendered_regime), describe_rendered(rendered),
      describe_rendered(rendered_ndf), to_string(declared), by_lambda,
      declared == Verdict::kFails && !resolves
          ? " (the near-truth input is not held by the rule: reported inconclusive)"
          : "",
      resolved_beyond.empty() ? "none" : resolved_beyond, 100 * kTolerance, to_string(stronger),
      describe_summary(brdf_regime), describe_summary(brdf), brdf.by_axis, describe_summary(ndf),
      ndf.by_axis, tail_max, fits.cells, fits.med_table, fits.med_indep, fits.max_table,
      fits.max_indep, fits.beyond_table, fits.beyond_indep, fits.ndf_med_table, fits.ndf_med_indep,
      fits.ndf_max_table, fits.ndf_max_indep, fits.ndf_beyond_table, fits.ndf_beyond_indep,
      fits.fit_share, fits.beyond_indep > 0 ? "excluded" : "NOT excluded", fits.polygon_max_rel,
      fits.polygon_max_z, ltc::describe(fits.polygon_worst), fits.polygon_worst_closed,
      fits.polygon_worst_mc, fits.polygon_beyond, fits.below_horizon_max,
      ltc::describe(fits.below_horizon_worst));
}

}  // namespace glintlab::verify::kneiphof_claims

GLINTLAB_CLAIM(glintlab::verify::kneiphof_claims::LtcProbability);

// podee.rmse — Podee, Max, Iwasaki & Dobashi, Table 1.
//
// The paper, Sec. 4: "Our method shows an improvement in both the quality and stability of a
// specular highlight over the conventional method and LEAN mapping." Table 1 (RMSE against
// "tiling 64x supersampling"): Conventional 0.0845, LEAN mapping 0.0977, Our Method 0.0826.
//
// Measured: at each camera distance, the MSE of the method minus that of centre sampling and of
// LEAN against the pixel integral, through two independent references R1, R2 (common.h: the
// estimate's only noise is the references'). Each ordering is a two-sided z test, Holm–Šidák over
// every (distance, baseline) at 1 %: the method wins or loses beyond the references' error, or
// ties within it. Holds: wins everywhere; holds-in-regime: wins at every distance of the regime;
// fails: loses inside it; inconclusive: a tie inside it.
// Control: an independent 64-spp reference × 1.03 (near truth) in place of both baselines
// (perturbed: the method must then lose), or in place of the method (corrected: it must win).
// Regime, declared before measuring: d ≤ 4, near and medium; the paper itself expects the method
// to fail far away (Sec. 4, podee.far-failure).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "verify/claim_runner.h"
#include "verify/claims/podee/common.h"
#include "verify/scenes/podee_scene.h"
#include "verify/stats/mean_tests.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::podee_claims {
namespace {

constexpr double kRmseRegimeMaxDistance = podee::kMedium;
constexpr double kRmseFamilyRate = 0.01;

struct RmseRow {
  double distance = 0;
  bool in_regime = false;
  double mse_centre = 0, mse_lean = 0, mse_method = 0, ref_rmse = 0, rmse_r1[3] = {0, 0, 0};
  Ordering vs_centre, vs_lean;
};

}  // namespace

struct Rmse {
  static constexpr std::string_view kId = "podee.rmse";
  static constexpr std::string_view kPaper = podee_claims::kPaper;
  static constexpr std::string_view kSource = "Table 1";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Sec. 4: \"Our method shows an improvement in both the quality and stability of a "
      "specular highlight over the conventional method and LEAN mapping.\" Table 1 "
      "(RMSE against \"tiling 64x supersampling\"): Conventional 0.0845, LEAN mapping "
      "0.0977, Our Method 0.0826";
  // What the check tests beyond the quote (so a verdict on it is never the paper failing).
  static constexpr std::string_view kStrongerReading =
      "Table 1 is one RMSE per method for Fig. 4's scene (distance not "
      "stated; the method 2 % below centre sampling); the check requires a "
      "lower MSE than both centre sampling and LEAN, beyond the references' "
      "noise, at every distance of a regime it declared (d ≤ 4) on the "
      "project's own normal-mapped sphere (core/scene/podee_scene.h), "
      "against the pixel integral through two 256-spp references. At d = 4 "
      "LEAN ties at the quick budget and is lower at the full one "
      "(docs/data/claims-full.json: LEAN 0.0058, method 0.0059).";
  // The competing causes reviewed for a "fails" (verify/finding_rule.h): how each was ruled
  // out, or why it is still open.
  static std::vector<Alternative> alternatives() {
    return {{"tolerance",
             "not excluded: at d = 4 LEAN's RMSE is 0.0058 against the method's 0.0059 (full "
             "budget, ΔMSE +8.2e-07 ± 3.1e-07, 2.4 % of the MSE, about 1.2 % in RMSE), where "
             "Table 1's medium-distance gap is 15 % (0.0826 against 0.0977); within a tolerance "
             "of a few per cent the two tie",
             false},
            {"scene or regime mismatch",
             "not excluded: the regime d ≤ 4 was declared by the project for the paper's "
             "\"medium\" distance of Table 1, whose scene and camera distances are not ours",
             false}};
  }
  static constexpr std::string_view kStatistic =
      "MSE(method) − min over baselines of MSE, against the pixel integral (two 64-spp "
      "references), at the medium distance";
  static constexpr std::string_view kRegime =
      "camera distance d ≤ 4 (near and medium; the paper expects failure far away, Sec. 4)";
  // At the probe's one near distance the method wins against both baselines.
  static constexpr Expected kExpected{.quick = Verdict::kInconclusive, .probe = Verdict::kHolds};
  static constexpr bool kHasCorrectedControl = true;

  struct Sizes {
    int size;                       // crop of the 96-pixel frame (same pixel footprint)
    int reference_spp;              // each of the two references
    std::vector<double> distances;  // camera distances
  };
  // The references: four times the paper's 64 spp at the quick budget, eight at the full one (the
  // estimate is unbiased for any count). The quick grid keeps the full grid's extremes (2 and 14)
  // and the regime's edge (4).
  static Sizes sizes(Budget b) {
    if (b == Budget::kQuick) return {64, 4 * kPaperSpp, {podee::kNear, podee::kMedium, 14}};
    return {128, 8 * kPaperSpp, {2, 3, podee::kMedium, 6, 8, podee::kFar, 14}};
  }
  static Sizes probe_sizes() { return {32, 4 * kPaperSpp, {podee::kNear}}; }

  using Evidence = RmsePixels;  // one per distance
  static int configurations(const Sizes& z) { return int(z.distances.size()); }
  static Evidence observe(const Sizes& z, int k, std::uint64_t) {
    return rmse_pixels(z.distances[std::size_t(k)], z.size, z.reference_spp);
  }

  struct Measured {
    std::vector<RmseRow> rows;
    double worst_detectable = 0;  // (z + 1.28) · SE, largest over the regime's comparisons
    double z = 0;                 // the per-comparison Šidák critical value
  };
  static Measured measure(const Sizes&, std::span<const Evidence> all, Input input) {
    Measured m;
    std::vector<double> p;
    for (const RmsePixels& px : all) {
      const auto& a = input == Input::kCorrected ? px.near_truth : px.method;
      const auto& c = input == Input::kPerturbed ? px.near_truth : px.centre;
      const auto& l = input == Input::kPerturbed ? px.near_truth : px.lean;
      RmseRow r;
      r.distance = px.distance;
      r.in_regime = px.distance <= kRmseRegimeMaxDistance;
      r.mse_centre = mse_vs_truth(c, px), r.mse_lean = mse_vs_truth(l, px);
      r.mse_method = mse_vs_truth(a, px);
      double rr = 0, e[3] = {0, 0, 0};
      for (std::size_t i = 0; i < px.r1.size(); ++i) {
        rr += (px.r1[i] - px.r2[i]) * (px.r1[i] - px.r2[i]);
        e[0] += (c[i] - px.r1[i]) * (c[i] - px.r1[i]);
        e[1] += (l[i] - px.r1[i]) * (l[i] - px.r1[i]);
        e[2] += (a[i] - px.r1[i]) * (a[i] - px.r1[i]);
      }
      const double n = double(px.r1.size());
      r.ref_rmse = std::sqrt(rr / n / 2);
      for (int k = 0; k < 3; ++k) r.rmse_r1[k] = std::sqrt(e[k] / n);
      r.vs_centre = order(a, c, px), r.vs_lean = order(a, l, px);
      p.push_back(r.vs_centre.p), p.push_back(r.vs_lean.p);
      m.rows.push_back(r);
    }
    const HolmSidakResult hs = holm_sidak(p, kRmseFamilyRate);
    m.z = normal_quantile(1 - 0.5 * sidak_level(kRmseFamilyRate, p.size()));
    for (std::size_t i = 0; i < m.rows.size(); ++i) {
      Ordering* o[2] = {&m.rows[i].vs_centre, &m.rows[i].vs_lean};
      for (int k = 0; k < 2; ++k) {
        if (hs.reject[2 * i + std::size_t(k)]) o[k]->sign = o[k]->d_mse < 0 ? -1 : 1;
        if (m.rows[i].in_regime)
          m.worst_detectable = std::max(m.worst_detectable, (m.z + 1.2816) * o[k]->se);
      }
    }
    return m;
  }

  static Decision decide(const Sizes&, const Measured& m) {
    Decision d{.configurations = int(m.rows.size()) * 2};
    for (const RmseRow& row : m.rows)
      if (row.distance == podee::kMedium)
        d.value = std::max(row.vs_centre.d_mse, row.vs_lean.d_mse);
    bool regime_wins = true, all_wins = true, loses = false;
    for (const RmseRow& r : m.rows) {
      const bool win = r.vs_centre.sign < 0 && r.vs_lean.sign < 0;
      all_wins = all_wins && win;
      if (!r.in_regime) continue;
      loses = loses || r.vs_centre.sign > 0 || r.vs_lean.sign > 0;
      regime_wins = regime_wins && win;
    }
    d.verdict = loses         ? Verdict::kFails
                : all_wins    ? Verdict::kHolds
                : regime_wins ? Verdict::kHoldsInRegime
                              : Verdict::kInconclusive;
    return d;
  }

  static std::string describe(const Sizes& z, const Measured& m, Input input) {
    if (input != Input::kGenuine)
      return fmt::format("an independent 64-spp reference × {} (near truth) in place of {}: {}",
                         1 + kNearTruthBias,
                         input == Input::kPerturbed ? "both baselines" : "the method", rows(m));
    std::string out = fmt::format(
        "{}² crop, unit light radiance (paper, medium: centre 0.0845, LEAN 0.0977, method 0.0826); "
        "two independent {}-spp references; regime declared: {}; orderings by Holm–Šidák at {} "
        "over {} comparisons: {}",
        z.size, z.reference_spp, kRegime, kRmseFamilyRate, 2 * m.rows.size(), rows(m));
    std::string ties;
    for (const RmseRow& row : m.rows)
      if (row.in_regime)
        for (auto [name, o] : {std::pair{"centre", row.vs_centre}, std::pair{"LEAN", row.vs_lean}})
          if (o.sign == 0)
            ties += fmt::format("{}d={} vs {} (ΔMSE {:+.2e}, SE {:.1e})", ties.empty() ? "" : ", ",
                                row.distance, name, o.d_mse, o.se);
    if (!ties.empty())
      out += fmt::format(
          ". Ties within the references' error inside the regime: {}; smaller than this budget "
          "resolves",
          ties);
    return out;
  }

  static std::string power(const Sizes&, const Measured& m, const Measured&) {
    return fmt::format(
        "MSE difference detected at 90 % power: ≥ {:.2e} ((z {:.2f} + 1.28) × SE, z at the Šidák "
        "per-comparison level; largest over the regime's comparisons)",
        m.worst_detectable, m.z);
  }

 private:
  static std::string rows(const Measured& m) {
    const auto word = [](const Ordering& o) {
      return o.sign < 0 ? "lower" : o.sign > 0 ? "higher" : "tie";
    };
    std::string out;
    for (const RmseRow& r : m.rows)
      out += fmt::format(
          "{}d={}{}: RMSE vs truth centre {:.4f}, LEAN {:.4f}, method {:.4f} (vs one "
          "reference {:.4f}, {:.4f}, {:.4f}; that reference's own RMSE {:.4f}); ΔMSE vs centre "
          "{:+.2e} ± {:.1e} ({}), vs LEAN {:+.2e} ± {:.1e} ({})",
          out.empty() ? "" : "; ", r.distance, r.in_regime ? " (regime)" : "",
          std::sqrt(std::max(0.0, r.mse_centre)), std::sqrt(std::max(0.0, r.mse_lean)),
          std::sqrt(std::max(0.0, r.mse_method)), r.rmse_r1[0], r.rmse_r1[1], r.rmse_r1[2],
          r.ref_rmse, r.vs_centre.d_mse, r.vs_centre.se, word(r.vs_centre), r.vs_lean.d_mse,
          r.vs_lean.se, word(r.vs_lean));
    return out;
  }
};

}  // namespace glintlab::verify::podee_claims

GLINTLAB_CLAIM(glintlab::verify::podee_claims::Rmse);

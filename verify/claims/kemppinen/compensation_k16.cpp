// kemppinen.compensation-k16 — Kemppinen et al. 2025, Fig. 14 left, Sec. 6.
//
// The paper, Fig. 14: "There are settings where this does not hold, causing the background to
// brighten before the points uniformly cover the surface (far left, using k=4 points), which can
// be mitigated by consider a larger neighborhood (middle left, with k=16 points)"; Sec. 6: "When
// the microroughness is too large, it considers areas outside of U_Ω and becomes visible before the
// glints converge to a uniform mass".
//
// Measured: per setting of the regime, on the same random positions, the relative bias against
// the brute-force Eq. 5 of Eq. 11 with k = 4 and with k = 16 (B(k) over the whole filter, as for
// kemppinen.compensation), and the paired gap |bias k=4| − |bias k=16| − 0.1·|bias k=4|.
// Candidates: T(ω_h) near the rim (GGX θ = 60°, 70°; Beckmann θ = 20°, 30°, 40°), α★ 0.05 and 0.1,
// footprints of 1–64 level-0 cells (2–64 at the quick budget); the geometry of the regime is
// checked per candidate before measuring. Candidates with σ_a of 1–2 cells are measured and
// reported apart, not judged: there B(16) holds only ±1 σ_a.
// Decided: k = 16 mitigates a setting when it removes at least a tenth of k = 4's bias (interval of
// the gap, Šidák over the judged settings): holds in the regime if it does in every setting, fails
// if the interval excludes it in one, else inconclusive.
// Control: k = 16 replaced by k = 4's result with 8 % of its error removed (perturbed: a claim that
// holds must fail) or 12 % (corrected: a claim that fails must hold), near the decision's edge.
// Regime, declared before measuring from those sentences: T(ω_h) near the rim of U_Ω (at most
// 3 lobe widths from it, so the lobe reaches into □ \ U_Ω, where Eq. 10 counts mass no point
// has); moderate α★; mid-field footprints, where the lobe's σ_a is at most one angular cell of
// level ⌊λ⌋ (the points are not yet a uniform mass, and B(16), two cells either side of x_a, holds
// the lobe's ±2 σ_a where B(4) holds ±1 σ_a); and where a pilot on other positions puts k = 4
// above Eq. 5 by more than 3 % (the brightening).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "verify/claim_runner.h"
#include "verify/claims/kemppinen/common.h"
#include "verify/claims/kemppinen/list.h"
#include "verify/scenes/kemppinen_presets.h"
#include "verify/stats/mean_tests.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::kemppinen_claims {
namespace {

constexpr double kMitigates = 0.1;  // a tenth of the k = 4 error removed
// The control's distance from kMitigates, in shares of k = 4's error.
constexpr double kK16ControlMargin = 0.02;
constexpr double kK16RimWidths = 3;
constexpr double kK16MidCells = 1;
constexpr double kK16WideCells = 2;  // candidates up to this σ_a, the wider ones reported apart
constexpr std::uint64_t kK16PilotSalt = 0x9e3779b97f4a7c15ULL;

std::vector<CompConfig> k16_candidates(Budget b) {
  std::vector<CompConfig> out;
  const std::vector<double> cells = b == Budget::kQuick
                                        ? std::vector<double>{2, 4, 16, 64}
                                        : std::vector<double>{1, 2, 4, 8, 16, 32, 64};
  for (bool ggx : {true, false})
    for (double s : {0.05, 0.1})
      for (double t : ggx ? std::vector<double>{60, 70} : std::vector<double>{20, 30, 40})
        for (double c : cells) out.push_back({{ggx, 0.3}, s, t, c});
  return out;
}

// The lobe's σ_a in angular cells of level ⌊λ⌋ where T(ω_h) is near the rim (geometry, without
// measuring); 0 where it is not.
double k16_lobe_cells(const CompConfig& c) {
  const P p = kemppinen2025::preset_params(kCompSide, c.alpha_star, 0);
  return with_ndf(c.ndf, [&](const auto& ndf) {
    const auto ang = kemppinen2025::angular(p, ndf, direction(c.theta));
    const double sigma = std::max(ang.sigma_a.x, ang.sigma_a.y);
    const double rim = 0.5 - std::hypot(ang.x_a.x - 0.5, ang.x_a.y - 0.5);
    const double res_a = std::exp2(std::floor(std::log2(2 * c.cells)));  // 2^⌊λ⌋
    return rim <= kK16RimWidths * sigma ? sigma * res_a : 0.0;
  });
}

struct K16Measured {
  CompConfig c;
  std::size_t n = 0;
  double lobe_cells = 0;        // σ_a in angular cells of level ⌊λ⌋
  double pilot = 0;             // k = 4's bias against Eq. 5 on the pilot's positions
  RelBias k4, k16;              // against Eq. 5, B(k) over the whole filter
  RelBias k4_block, k16_block;  // as implemented (Algorithm 1's spatial blocks)
  RelBias gap;                  // |k4| − |k16| − kMitigates·|k4|, paired over the positions
};

bool k16_brightens(const K16Measured& m) { return m.pilot > kCompTolerance && m.n > 0; }
bool k16_judged(const K16Measured& m) { return k16_brightens(m) && m.lobe_cells <= kK16MidCells; }

K16Measured measure_k16_setting(const CompConfig& c, const CompSize& sz, std::uint64_t seed) {
  K16Measured m;
  m.c = c;
  const CompSize pilot_size{sz.pairs / 4, sz.min, sz.max / 4};
  const std::uint64_t pilot_seed = seed ^ kK16PilotSalt;
  const CompSamples pilot =
      sample_comp(c, comp_positions(c, pilot_size, pilot_seed), pilot_seed, kCompSide);
  m.pilot = rel_bias(pilot.whole, pilot.ref).bias;
  if (m.pilot <= kCompTolerance) return m;  // no brightening: outside the regime
  const std::uint64_t n = comp_positions(c, sz, seed);
  const CompSamples s4 = sample_comp(c, n, seed, 2), s16 = sample_comp(c, n, seed, 4);
  m.n = n;
  m.k4 = rel_bias(s4.whole, s4.ref);
  m.k16 = rel_bias(s16.whole, s16.ref);
  m.k4_block = rel_bias(s4.block, s4.ref);
  m.k16_block = rel_bias(s16.block, s16.ref);
  // The gap as one ratio over the same positions: Eq. 5 + s4·0.9·(k4 − Eq. 5) − s16·(k16 − Eq. 5),
  // s the signs of the biases, so its standard error is the paired one.
  const double sign4 = m.k4.bias < 0 ? -1 : 1, sign16 = m.k16.bias < 0 ? -1 : 1;
  std::vector<double> combined(n);
  for (std::size_t i = 0; i < n; ++i)
    combined[i] = s4.ref[i] + sign4 * (1 - kMitigates) * (s4.whole[i] - s4.ref[i]) -
                  sign16 * (s16.whole[i] - s4.ref[i]);
  m.gap = rel_bias(combined, s4.ref);
  return m;
}

struct K16Gap {
  double gap, se;
};

// The error k = 16 removes, minus the required tenth of k = 4's, with its standard error (paired
// over the positions). With `removed` set, k = 16 is replaced by k = 4's result with that share of
// its error removed (the controls): the gap is (removed − kMitigates)·|k4|, its error alike.
K16Gap k16_gap(const K16Measured& m, std::optional<double> removed = std::nullopt) {
  if (!removed) return {m.gap.bias, m.gap.se};
  return {(*removed - kMitigates) * std::abs(m.k4.bias), std::abs(*removed - kMitigates) * m.k4.se};
}

Verdict decide_k16(const std::vector<K16Measured>& ms, std::optional<double> removed, double z) {
  bool all = true, any = false;
  for (const K16Measured& m : ms) {
    if (!k16_judged(m)) continue;
    any = true;
    const K16Gap g = k16_gap(m, removed);
    if (g.gap + z * g.se < 0) return Verdict::kFails;
    all = all && g.gap - z * g.se > 0;
  }
  return any && all ? Verdict::kHoldsInRegime : Verdict::kInconclusive;
}

constexpr std::string_view kK16Regime =
    "T(ω_h) within 3 σ_a of the rim of U_Ω, α★ 0.05–0.1, σ_a at most one angular cell of level "
    "⌊λ⌋ (mid-field), and k = 4 above Eq. 5 by more than 3 % in a pilot";

// The judged settings' least favourable gap and the detail's rows; what the power is computed from.
struct K16Summary {
  int judged = 0, brighten = 0;
  double z = 0, worst = 1e300, se = 0, e4_min = 1e300;
  std::string at, rows, wide;
};

K16Summary summarize_k16(const std::vector<K16Measured>& ms) {
  K16Summary s;
  s.judged = int(std::count_if(ms.begin(), ms.end(), k16_judged));
  s.z = normal_quantile(1 - sidak_level(check_level(), std::size_t(std::max(s.judged, 1))) / 2);
  for (const K16Measured& m : ms) {
    if (!k16_brightens(m)) continue;
    ++s.brighten;
    const std::string row = fmt::format(
        "{} (σ_a {:.2g} cells): k = 4 {:+.3g}, k = 16 {:+.3g} (as implemented {:+.3g}, {:+.3g})",
        comp_setting(m.c), m.lobe_cells, m.k4.bias, m.k16.bias, m.k4_block.bias, m.k16_block.bias);
    if (!k16_judged(m)) {
      s.wide += (s.wide.empty() ? "" : "; ") + row;
      continue;
    }
    const K16Gap g = k16_gap(m);
    s.se = std::max(s.se, g.se);
    s.e4_min = std::min(s.e4_min, std::abs(m.k4.bias));
    s.rows += (s.rows.empty() ? "" : "; ") + row;
    if (g.gap < s.worst) s.worst = g.gap, s.at = row;
  }
  return s;
}

}  // namespace

struct CompensationK16 {
  static constexpr std::string_view kId = "kemppinen.compensation-k16";
  static constexpr std::string_view kPaper = kemppinen_claims::kPaper;
  static constexpr std::string_view kSource = "Fig. 14 left, Sec. 6";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Fig. 14: \"There are settings where this does not hold, causing the background "
      "to brighten before the points uniformly cover the surface (far left, using k=4 "
      "points), which can be mitigated by consider a larger neighborhood (middle left, "
      "with k=16 points) …\" Sec. 5: \"When the microroughness is too large, it "
      "considers areas outside of U_Ω …\"";
  // What the check tests beyond the quote (so a verdict on it is never the paper failing).
  static constexpr std::string_view kStrongerReading =
      "The paper gives no α★ or footprint for Fig. 14 left; the check "
      "tests the regime its sentences describe (T(ω_h) within 3 σ_a of the "
      "rim of U_Ω, α★ 0.05–0.1, the lobe at most one angular cell wide at "
      "level ⌊λ⌋, and k = 4 above the brute-force Eq. 5 by more than 3 % in "
      "a pilot) and requires k = 16 to remove at least 10 % (the project's "
      "threshold) of k = 4's bias in every such setting, B(k)'s points "
      "summed over the whole filter. Settings with a lobe of 1–2 cells are "
      "reported, not judged.";
  // The competing causes reviewed for a "fails" (verify/finding_rule.h): how each was ruled
  // out, or why it is still open.
  static std::vector<Alternative> alternatives() {
    return {{"scene or regime mismatch",
             "excluded: tested where Fig. 14 left and Sec. 6 place the defect — T(ω_h) within 3 "
             "σ_a of the rim, α★ 0.05–0.1, the lobe at most one angular cell wide (mid-field) — "
             "and only in settings where k = 4 brightens against the brute-force Eq. 5 by more "
             "than 3 % in a pilot (+3.4 % to +54 %), the defect the figure shows",
             true},
            {"convention (the LOD: the spatial truncation)",
             "excluded: judged with B(k)'s points over the whole filter, so the 2×2 block's "
             "truncation under λ = log2(2σ·res) does not enter; as implemented it offsets k = 4's "
             "brightening in 4 of the 10 settings (full) and is reported beside it",
             true},
            {"tolerance",
             "excluded: k = 16 must remove only a tenth of k = 4's brightening, the least any "
             "reading of \"mitigated\" asks; it removes 62–100 % (full)",
             true}};
  }
  static constexpr std::string_view kStatistic =
      "smallest (|bias k=4| − |bias k=16| − 0.1·|bias k=4|) against Eq. 5 over the regime's "
      "settings";
  static constexpr Expected kExpected{.quick = Verdict::kHoldsInRegime};
  static constexpr bool kHasCorrectedControl = true;
  static constexpr std::string_view kRegime = kK16Regime;

  // The candidates whose geometry is in the regime (T(ω_h) near the rim, σ_a ≤ 2 cells), their σ_a
  // in cells, and the cost of one setting.
  struct Sizes {
    std::vector<CompConfig> configs;
    std::vector<double> lobe_cells;
    CompSize size;
  };
  static Sizes of(const std::vector<CompConfig>& candidates, const CompSize& size) {
    Sizes z{{}, {}, size};
    for (const CompConfig& c : candidates) {
      const double cells = k16_lobe_cells(c);
      if (cells > 0 && cells <= kK16WideCells) z.configs.push_back(c), z.lobe_cells.push_back(cells);
    }
    return z;
  }
  static Sizes sizes(Budget b) {
    return of(k16_candidates(b),
              b == Budget::kQuick ? CompSize{1.5e7, 24, 400} : CompSize{6e7, 48, 2000});
  }
  // Beckmann α★ = 0.1, θ = 40°, 64 cells: T(ω_h) at the rim, the lobe about one angular cell wide;
  // k = 4 brightens. 40 positions (the pilot's too).
  static Sizes probe_sizes() { return of({{{false, 0.3}, 0.1, 40.0, 64}}, {2e6, 40, 160}); }

  using Evidence = K16Measured;  // one setting: pilot, then k = 4 and k = 16 on the same positions
  static int configurations(const Sizes& z) { return int(z.configs.size()); }
  static Evidence observe(const Sizes& z, int k, std::uint64_t seed) {
    K16Measured m = measure_k16_setting(z.configs[std::size_t(k)], z.size, seed);
    m.lobe_cells = z.lobe_cells[std::size_t(k)];
    return m;
  }

  // Genuine: k = 16; perturbed: k = 4 with 8 % of its error removed; corrected: with 12 %.
  struct Measured {
    std::vector<K16Measured> ms;
    std::optional<double> removed;
    K16Summary s;
  };
  static Measured measure(const Sizes&, std::span<const Evidence> evidence, Input input) {
    Measured m{{evidence.begin(), evidence.end()}, {}, {}};
    if (input != Input::kGenuine)
      m.removed = kMitigates + (input == Input::kPerturbed ? -kK16ControlMargin : kK16ControlMargin);
    m.s = summarize_k16(m.ms);
    return m;
  }
  static Decision decide(const Sizes&, const Measured& m) {
    return {.verdict = decide_k16(m.ms, m.removed, m.s.z),
            .value = m.s.judged ? m.s.worst : 0,
            .bound = 0,
            .configurations = int(m.ms.size())};
  }
  static std::string describe(const Sizes&, const Measured& m, Input) {
    const K16Summary& s = m.s;
    return fmt::format(
        "regime: {}. Of {} candidates with T(ω_h) near the rim and σ_a ≤ {:g} cells, {} brighten "
        "by more than {:g} % in the pilot, {} of them with σ_a ≤ {:g} cell (judged). Relative bias "
        "against the brute-force Eq. 5 (same points, filter and LOD) on the same positions, B(k) "
        "over the whole filter: {}; k = 16 must remove at least {:.0f} % of k = 4's error in every "
        "setting (interval at z = {:.2f}); least favourable: {}. Not judged (σ_a of 1–2 cells, "
        "wider than B(16) holds): {}",
        kK16Regime, m.ms.size(), kK16WideCells, s.brighten, 100 * kCompTolerance, s.judged,
        kK16MidCells, s.rows.empty() ? "—" : s.rows, 100 * kMitigates, s.z,
        s.at.empty() ? "—" : s.at, s.wide.empty() ? "none" : s.wide);
  }
  static std::string control_text(const Sizes&, const Measured& m, Input input, Verdict v) {
    return fmt::format(
        "k = 4's result with {:.0f} % of its error removed ({} than the {:.0f} % required) in "
        "place of k = 16: {}",
        100 * m.removed.value_or(0), input == Input::kPerturbed ? "less" : "more", 100 * kMitigates,
        to_string(v));
  }
  static std::string power(const Sizes&, const Measured& m, const Measured&) {
    const K16Summary& s = m.s;
    return s.judged ? fmt::format(
                          "a removal of {:.2g} beyond the tenth of k = 4's error ({:.2g} % of the "
                          "smallest k = 4 error, {:.3g}) is detected with 90 % power (largest SE "
                          "{:.2g})",
                          (s.z + 1.2816) * s.se, 100 * (s.z + 1.2816) * s.se / s.e4_min, s.e4_min,
                          s.se)
                    : std::string("no setting in the regime");
  }
};

}  // namespace glintlab::verify::kemppinen_claims

GLINTLAB_CLAIM(glintlab::verify::kemppinen_claims::CompensationK16);

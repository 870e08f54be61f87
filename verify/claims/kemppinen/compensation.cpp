// kemppinen.compensation — Kemppinen et al. 2025, Eq. 9–11, Sec. 3.3.4.
//
// The paper, Sec. 3.3.4: "the exact point positions and orientations become however less
// significant, and using their expected contribution in place of their exact evaluation works
// well"; "The number k of angular neighbors considered is a performance-quality trade-off that is
// easy to change; we find that k = 4 is already good enough for most cases (see Figure 2)."
//
// Measured: per setting, over random positions, Eq. 11 with k = 4 (the points of B(k), the
// compensation C of Eq. 10 for the rest) against the brute-force Eq. 5: every point, the same
// points, the same Gaussian filter and LOD (core/glints/kemppinen_reference.h); the relative bias
// Σ(D★^f − Eq. 5) / Σ Eq. 5. The explicit sum over B(k) runs over the whole filter, as Sec. 3.3.4
// assumes ("the small spatial neighborhood is always large enough to cover the pixel filter"), so
// the error measured is that of the angular approximation the sentence is about; the spatial
// truncation (Algorithm 1's 2×2 block against the whole filter) is measured beside it, not judged.
// Grid: GGX and Beckmann (α = 0.3); α★ 0.005–0.1; θ taking T(ω_h) from the centre of U_Ω to near
// its rim; footprints from the near field (the lobe inside B(k)) to where C carries nearly all of
// D★^f (the brute force's cost grows as (α★ · footprint)², which bounds them).
// Decided: "most cases" is more than half of the settings where C carries at least 5 % of D★^f
// (elsewhere B(k) holds the lobe and Eq. 11 is Eq. 5), each classed by its interval (Šidák)
// against ±3 %: holds when more than half are within, fails when at most half can be.
// Control: Eq. 5 itself in place of Eq. 11, 4 % too bright (perturbed: a claim that holds must
// fail) or 1 % (corrected: a claim that fails must hold), through the same decision.
// Regime: none.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "verify/claim_runner.h"
#include "verify/claims/kemppinen/common.h"
#include "verify/claims/kemppinen/list.h"
#include "verify/stats/mean_tests.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::kemppinen_claims {
namespace {

constexpr double kCompMost = 0.5;          // "most": more than this share of the judged settings
constexpr double kCompActiveShare = 0.05;  // C's share of D★^f for a setting to be judged
constexpr double kCompControlFar = 0.04;   // the control's offset from Eq. 5 (claim holding)
constexpr double kCompControlNear = 0.01;  // the control's offset from Eq. 5 (claim failing)

std::vector<CompConfig> comp_configs(Budget b) {
  std::vector<CompConfig> out;
  const std::vector<double> cells = b == Budget::kQuick
                                        ? std::vector<double>{4, 16, 64}
                                        : std::vector<double>{2, 4, 8, 16, 32, 64, 128};
  for (bool ggx : {true, false})
    for (double s : {0.005, 0.02, 0.1})
      for (double t : ggx ? std::vector<double>{0, 30, 60} : std::vector<double>{0, 20, 40})
        for (double c : cells) out.push_back({{ggx, 0.3}, s, t, c});
  return out;
}

struct CompMeasured {
  CompConfig c;
  std::size_t n = 0;
  double c_share = 0;      // Σ C / Σ D★^f (whole filter)
  double block_share = 0;  // Σ explicit in the 2×2 block / Σ explicit over the whole filter
  double cross_check = 0;
  RelBias whole, block;  // against Eq. 5
};

CompMeasured measure_comp(const CompConfig& c, const CompSize& sz, std::uint64_t seed) {
  const CompSamples s = sample_comp(c, comp_positions(c, sz, seed), seed, kCompSide);
  CompMeasured m;
  m.c = c;
  m.n = s.ref.size();
  double whole = 0;
  for (double v : s.whole) whole += v;
  m.c_share = whole > 0 ? s.c_sum / whole : 0;
  m.block_share = s.explicit_whole > 0 ? s.explicit_block / s.explicit_whole : 1;
  m.cross_check = s.cross_check;
  m.whole = rel_bias(s.whole, s.ref);
  m.block = rel_bias(s.block, s.ref);
  return m;
}

bool comp_judged(const CompMeasured& m) { return m.c_share >= kCompActiveShare; }

// What is decided: Eq. 11 (genuine), or Eq. 5 offset by a share (the controls).
RelBias comp_input(const CompMeasured& m, Input in) {
  if (in == Input::kGenuine) return m.whole;
  return {in == Input::kPerturbed ? kCompControlFar : kCompControlNear, 0};
}

struct CompDecision {
  Verdict verdict = Verdict::kInconclusive;
  double z = 0;
  int judged = 0, within = 0, beyond = 0;
  RelBias worst;
  std::string worst_at;
};

CompDecision decide_compensation(const std::vector<CompMeasured>& ms, Input in) {
  CompDecision d;
  for (const CompMeasured& m : ms) d.judged += comp_judged(m);
  if (d.judged == 0) return d;
  d.z = normal_quantile(1 - sidak_level(check_level(), std::size_t(d.judged)) / 2);
  for (const CompMeasured& m : ms) {
    if (!comp_judged(m)) continue;
    const RelBias r = comp_input(m, in);
    const Band b = band(r.bias, d.z * r.se, kCompTolerance);
    d.within += b == Band::kWithin;
    d.beyond += b == Band::kBeyond;
    if (d.worst_at.empty() || std::abs(r.bias) > std::abs(d.worst.bias)) {
      d.worst = r;
      d.worst_at = comp_setting(m.c);
    }
  }
  const double need = kCompMost * d.judged;  // within must exceed it
  if (d.within > need)
    d.verdict = Verdict::kHolds;
  else if (d.judged - d.beyond <= need)
    d.verdict = Verdict::kFails;
  return d;
}

std::string describe_compensation(const std::vector<CompMeasured>& ms, const CompDecision& d) {
  const auto share_within = [&](double tol) {
    int w = 0;
    for (const CompMeasured& m : ms)
      if (comp_judged(m)) w += band(m.whole.bias, d.z * m.whole.se, tol) == Band::kWithin;
    return fmt::format("{} of {}", w, d.judged);
  };
  double idle_worst = 0, cross = 0, share_lo = 1, share_hi = 0, share_sum = 0, block_lo = 1e300,
         block_hi = -1e300;
  std::size_t n_lo = ~std::size_t(0), n_hi = 0;
  for (const CompMeasured& m : ms) {
    cross = std::max(cross, m.cross_check);
    n_lo = std::min(n_lo, m.n);
    n_hi = std::max(n_hi, m.n);
    if (!comp_judged(m)) idle_worst = std::max(idle_worst, std::abs(m.whole.bias));
    if (!comp_judged(m)) continue;
    share_lo = std::min(share_lo, m.block_share);
    share_hi = std::max(share_hi, m.block_share);
    share_sum += m.block_share;
    block_lo = std::min(block_lo, m.block.bias);
    block_hi = std::max(block_hi, m.block.bias);
  }
  std::string beyond_list;
  for (const CompMeasured& m : ms)
    if (comp_judged(m) && band(m.whole.bias, d.z * m.whole.se, kCompTolerance) == Band::kBeyond)
      beyond_list += fmt::format("{}{} {:+.3g}", beyond_list.empty() ? "" : "; ", comp_setting(m.c),
                                 m.whole.bias);
  return fmt::format(
      "Eq. 11 with k = 4 (B(k)'s points over the whole filter, plus C) against the brute-force "
      "Eq. 5 (every point within {:g} σ of filter and lobe, the same points, filter and LOD), {} "
      "settings, {}–{} positions each; C carries ≥ {:.0f} % of D★^f in {} (judged): {} within "
      "±{:g} %, {} beyond (interval at z = {:.2f}); most = more than half. Worst {:+.3g} ± {:.2g} "
      "at {}. Beyond: {}. Within ±1 %: {}; ±3 %: {}; ±10 %: {}. Where C carries less, B(k) holds "
      "the lobe and |bias| ≤ {:.2g}. Measured beside it, not judged — the spatial truncation, in "
      "the judged settings: Algorithm 1's 2×2 spatial block holds {:.1f} % ({:.1f}–{:.1f} % by "
      "setting) of B(k)'s explicit sum over the whole filter (LOD λ = log2(2σ·res): σ is ½ to 1 "
      "cell), and D★^f as implemented (block + C) is off Eq. 5 by {:+.3g} to {:+.3g}. The block's "
      "sum equals Algorithm 1's explicit part to {:.1g} of the largest Eq. 5 value",
      kCompReferenceSigmas, ms.size(), n_lo, n_hi, 100 * kCompActiveShare, d.judged, d.within,
      100 * kCompTolerance, d.beyond, d.z, d.worst.bias, d.worst.se, d.worst_at,
      beyond_list.empty() ? std::string("none") : beyond_list, share_within(0.01),
      share_within(kCompTolerance), share_within(0.1), idle_worst,
      100 * share_sum / std::max(d.judged, 1), 100 * share_lo, 100 * share_hi, block_lo, block_hi,
      cross);
}

}  // namespace

struct Compensation {
  static constexpr std::string_view kId = "kemppinen.compensation";
  static constexpr std::string_view kPaper = kemppinen_claims::kPaper;
  static constexpr std::string_view kSource = "Eq. 9–11, Sec. 3.3.4";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Sec. 3.3.4: \"using their expected contribution in place of their exact "
      "evaluation works well\"; \"The number k of angular neighbors considered is a "
      "performance-quality trade-off that is easy to change; we find that k = 4 is "
      "already good enough for most cases (see Figure 2).\"";
  // What the check tests beyond the quote (so a verdict on it is never the paper failing).
  static constexpr std::string_view kStrongerReading =
      "\"Most cases\" is read as more than half of the settings of a "
      "declared grid (GGX and Beckmann α = 0.3, α★ 0.005–0.1, θ from the "
      "centre of U_Ω to near its rim, footprints of 2–128 level-0 cells, "
      "4–64 at the quick budget) "
      "where C carries at least 5 % of D★^f, each within ±3 % (a tolerance "
      "the project chose) of the brute-force Eq. 5 with the same filter and "
      "LOD. B(k)'s points are summed over the whole filter, as Sec. 3.3.4 "
      "assumes; Algorithm 1's 2×2 spatial truncation, under the project's "
      "LOD λ = log2(2σ·res) 84 % of the filter, is measured apart.";
  // The competing causes reviewed for a "fails" (verify/finding_rule.h): how each was ruled
  // out, or why it is still open.
  static std::vector<Alternative> alternatives() {
    return {{"convention (the LOD of the footprint)",
             "excluded: the verdict is on Eq. 11 with B(k)'s points summed over the whole filter, "
             "as Sec. 3.3.4 assumes, so the spatial truncation that λ = log2(2σ·res) produces (σ "
             "= ½ to 1 cell) is not in it; measured apart, Algorithm 1's 2×2 block holds 84 % "
             "(83–86 % by setting) of B(k)'s explicit sum, and D★^f as implemented is off Eq. 5 "
             "by −15 % to +84 % (full)",
             true},
            {"scene or reference mismatch",
             "excluded: the reference is the brute-force Eq. 5 over the same points with the same "
             "Gaussian filter and LOD (core/glints/kemppinen_reference.h), every point within 5 σ "
             "of filter and lobe (less than 1.2e-6 of either left out); its part in B(k)'s 2×2 "
             "block equals Algorithm 1's explicit sum to 7e-16 of the largest value",
             true},
            {"tolerance (the reading of \"most cases\")",
             "not excluded: \"most\" is more than half of the settings where C carries at least 5 "
             "% of D★^f, each within ±3 %; the shares within ±1 %, ±3 % and ±10 % are 30, 44 and "
             "56 of 66 (full) and 0, 16 and 23 of 27 (quick), so a failure at ±3 % could be the "
             "tolerance's",
             false}};
  }
  static constexpr std::string_view kStatistic =
      "share of the settings where C carries ≥ 5 % of D★^f whose k = 4 bias against Eq. 5 is "
      "within ±3 % (more than 0.5 required)";
  static constexpr Expected kExpected{.quick = Verdict::kHolds};
  static constexpr bool kHasCorrectedControl = true;

  struct Sizes {
    std::vector<CompConfig> configs;
    CompSize size;
  };
  static Sizes sizes(Budget b) {
    return {comp_configs(b), b == Budget::kQuick ? CompSize{1.5e7, 24, 400} : CompSize{6e7, 48, 2000}};
  }
  // A reduced grid where C carries 70–98 % of D★^f: GGX and Beckmann, α★ 0.005 and 0.02, θ = 0,
  // 16 and 64 cells, 60 positions each.
  static Sizes probe_sizes() {
    Sizes z{{}, {2e6, 60, 60}};
    for (bool ggx : {true, false})
      for (double s : {0.005, 0.02})
        for (double c : {16.0, 64.0}) z.configs.push_back({{ggx, 0.3}, s, 0.0, c});
    return z;
  }

  using Evidence = CompMeasured;  // one setting's biases against Eq. 5
  static int configurations(const Sizes& z) { return int(z.configs.size()); }
  static Evidence observe(const Sizes& z, int k, std::uint64_t seed) {
    return measure_comp(z.configs[std::size_t(k)], z.size, seed);
  }

  // Genuine: Eq. 11; perturbed: Eq. 5 4 % too bright; corrected: Eq. 5 1 % too bright.
  struct Measured {
    std::vector<CompMeasured> ms;
    CompDecision d;
  };
  static Measured measure(const Sizes&, std::span<const Evidence> evidence, Input input) {
    Measured m{{evidence.begin(), evidence.end()}, {}};
    m.d = decide_compensation(m.ms, input);
    return m;
  }
  static Decision decide(const Sizes& z, const Measured& m) {
    return {.verdict = m.d.verdict,
            .value = m.d.judged ? double(m.d.within) / m.d.judged : 0,
            .bound = kCompMost,
            .configurations = int(z.configs.size())};
  }
  static std::string describe(const Sizes&, const Measured& m, Input) {
    return describe_compensation(m.ms, m.d);
  }
  static std::string control_text(const Sizes&, const Measured& m, Input input, Verdict) {
    return fmt::format(
        "Eq. 5 itself {:g} % too bright in place of Eq. 11, through the same decision: {} of {} "
        "within ±{:g} %",
        100 * (input == Input::kPerturbed ? kCompControlFar : kCompControlNear), m.d.within,
        m.d.judged, 100 * kCompTolerance);
  }
  static std::string power(const Sizes&, const Measured& m, const Measured&) {
    double se_max = 0;
    for (const CompMeasured& c : m.ms)
      if (comp_judged(c)) se_max = std::max(se_max, c.whole.se);
    return fmt::format(
        "a setting biased by {:.3g} (tolerance + (z + 1.28)·SE, largest SE {:.2g}) is classed "
        "beyond with 90 % power",
        kCompTolerance + (m.d.z + 1.2816) * se_max, se_max);
  }
};

}  // namespace glintlab::verify::kemppinen_claims

GLINTLAB_CLAIM(glintlab::verify::kemppinen_claims::Compensation);

// chermain.dictionary-converges — Chermain et al. 2021, Fig. 3 (Chermain et al. 2020).
//
// The paper, Fig. 3: "Pre-computed dictionary of 1D multi-scale distributions P_o [Chermain et
// al. 2020]. … As the LOD grows, they converge towards a Gaussian distribution with the same
// standard deviation σ_o." Sec. 3: "The highest LOD of all distributions P_o is the marginal
// distribution of a Beckmann SDF, with isotropic roughness σ_o."
//
// Measured: per level, the mean over the distributions (quick: every fourth) of the L1 distance of
// the level's 1D distribution to the Gaussian of std σ_o (midpoint rule, 4 points per texel), and
// the last level's standard deviation / σ_o; on the seed-2020 dictionary (full: also seeds 1 and
// 2). Holds when the mean L1 is non-increasing level to level, the last level is within L1 0.05
// of the Gaussian and its std within 1 % of σ_o, for every dictionary. Deterministic.
// Control (perturbed): the seed-2020 dictionary with its lobe means spread 2 % wider (a
// near-truth error of the one quantity the limit's standard deviation depends on).
// Regime: none.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/glints/chermain.h"
#include "verify/claim_runner.h"
#include "verify/claims/chermain/common.h"

namespace glintlab::verify::chermain_claims {
namespace {

// Tolerances fixed before measuring: the last level within 5 % L1 of the Gaussian and its
// standard deviation within 1 % of σ_o; the mean L1 distance non-increasing level to level.
constexpr double kL1Tolerance = 0.05;
constexpr double kStdTolerance = 0.01;
// The control's dictionary: lobe means × 1.02.
constexpr double kControlMeanScale = 1.02;

struct Convergence {
  std::vector<double> l1;  // mean over distributions, per level
  double std_ratio = 0;    // √(mean variance at the last level) / σ_o
};

Convergence convergence(const chermain2021::Dictionary& d, int stride) {
  Convergence c;
  const double so = d.sigma_o();
  const int per_texel = 4;
  const int steps = 2 * d.resolution() * per_texel;
  const double h = 2 * d.extent() / steps;
  double var_sum = 0;
  int count = 0;
  for (int k = 0; k < d.levels(); ++k) {
    double sum = 0;
    int n_used = 0;
    for (int n = 0; n < d.distributions(); n += stride, ++n_used) {
      double l1 = 0, var = 0;
      for (int i = 0; i < steps; ++i) {
        const double x = -d.extent() + (i + 0.5) * h;
        const double p = d.lookup_lod(n, k, x);
        const double g = std::exp(-0.5 * x * x / (so * so)) / (so * std::sqrt(2 * kPi<double>));
        l1 += std::abs(p - g);
        var += x * x * p;
      }
      sum += l1 * h;
      if (k == d.levels() - 1) var_sum += var * h, ++count;
    }
    c.l1.push_back(sum / n_used);
  }
  c.std_ratio = std::sqrt(var_sum / count) / so;
  return c;
}

bool converges(const Convergence& c) {
  for (std::size_t k = 1; k < c.l1.size(); ++k)
    if (c.l1[k] > c.l1[k - 1]) return false;
  return c.l1.back() <= kL1Tolerance && std::abs(c.std_ratio - 1) <= kStdTolerance;
}

std::string describe_convergence(const Convergence& c) {
  std::string levels;
  for (std::size_t k = 0; k < c.l1.size(); ++k)
    levels += fmt::format("{}{:.3g}", k ? ", " : "", c.l1[k]);
  return fmt::format("mean L1 per level [{}]; last-level std / sigma_o = {:.4f}", levels,
                     c.std_ratio);
}

}  // namespace

struct DictionaryConverges {
  static constexpr std::string_view kId = "chermain.dictionary-converges";
  static constexpr std::string_view kPaper = chermain_claims::kPaper;
  static constexpr std::string_view kSource = "Fig. 3 (Chermain et al. 2020)";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Fig. 3: \"Pre-computed dictionary of 1D multi-scale distributions P_o [Chermain "
      "et al. 2020]. … As the LOD grows, they converge towards a Gaussian distribution "
      "with the same standard deviation σ_o.\" Sec. 3: \"The highest LOD of all "
      "distributions P_o is the marginal distribution of a Beckmann SDF, with isotropic "
      "roughness σ_o.\"";
  // What the check tests beyond the quote (so a verdict on it is never the paper failing).
  static constexpr std::string_view kStrongerReading =
      "The check also requires the mean L1 distance to the Gaussian to be "
      "non-increasing at every level step (the paper states convergence, not "
      "monotonicity), with the last level within L1 0.05 and its standard "
      "deviation within 1 % of σ_o (tolerances the project chose), on the "
      "project's regenerated dictionary (seed 2020, N = 192, L = 16), not "
      "the authors' tables.";
  static constexpr std::string_view kStatistic =
      "mean L1 distance of the last level to the Gaussian of std σ_o";
  static constexpr Expected kExpected{.quick = Verdict::kHolds};

  struct Sizes {
    int stride;                              // every stride-th distribution
    std::vector<std::uint64_t> other_seeds;  // dictionaries measured beside seed 2020's
  };
  static Sizes sizes(Budget b) { return b == Budget::kQuick ? Sizes{4, {}} : Sizes{1, {1, 2}}; }
  static Sizes probe_sizes() { return {16, {}}; }

  // The genuine dictionaries (seed 2020, then the others), then the control's.
  static int configurations(const Sizes& z) { return 2 + int(z.other_seeds.size()); }
  using Evidence = Convergence;
  static Evidence observe(const Sizes& z, int k, std::uint64_t) {
    if (k == 0) return convergence(chermain2021::default_chermain_dictionary(), z.stride);
    chermain2021::DictionaryConfig c;
    if (k <= int(z.other_seeds.size()))
      c.seed = z.other_seeds[std::size_t(k - 1)];
    else
      c.mean_scale = kControlMeanScale;
    return convergence(chermain2021::Dictionary(c), z.stride);
  }

  using Measured = std::vector<Convergence>;  // the genuine dictionaries, or the control's
  static Measured measure(const Sizes&, std::span<const Evidence> all, Input input) {
    if (input == Input::kGenuine) return {all.begin(), all.end() - 1};
    return {all.back()};
  }

  // holds when every measured dictionary converges.
  static Decision decide(const Sizes&, const Measured& runs) {
    const bool all = std::all_of(runs.begin(), runs.end(), converges);
    return {.verdict = all ? Verdict::kHolds : Verdict::kFails,
            .value = runs.front().l1.back(),
            .bound = kL1Tolerance,
            .configurations = int(runs.size()) * int(runs.front().l1.size())};
  }

  static std::string describe(const Sizes&, const Measured& runs, Input input) {
    if (input != Input::kGenuine)
      return fmt::format("lobe means spread {:.0f} % wider (mean_scale {}): {}",
                         100 * (kControlMeanScale - 1), kControlMeanScale,
                         describe_convergence(runs.front()));
    double worst = 0;
    for (const Convergence& r : runs) worst = std::max(worst, std::abs(r.std_ratio - 1));
    return fmt::format(
        "{} dictionar{} (N=192, L=16, 64 texels, alpha_dict 0.5): {}; largest |std ratio - 1| "
        "over the dictionaries {:.2g} (held to L1 <= {}, |std ratio - 1| <= {}, L1 "
        "non-increasing)",
        runs.size(), runs.size() > 1 ? "ies (seeds 2020, 1, 2)" : "y (seed 2020)",
        describe_convergence(runs.front()), worst, kL1Tolerance, kStdTolerance);
  }

  static std::string power(const Sizes&, const Measured&, const Measured& control) {
    return fmt::format(
        "deterministic per dictionary (no sampling noise): a last level farther than L1 {} from "
        "the Gaussian, or a std off by more than {:.0f} %, is detected every time; lobe means "
        "spread {:.0f} % wider move the std by {:+.2f} %",
        kL1Tolerance, 100 * kStdTolerance, 100 * (kControlMeanScale - 1),
        100 * (control.front().std_ratio - 1));
  }
};

}  // namespace glintlab::verify::chermain_claims

GLINTLAB_CLAIM(glintlab::verify::chermain_claims::DictionaryConverges);

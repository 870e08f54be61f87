// Tests: Monte Carlo moment of each sampler against the cubature of its standalone pdf.
// The sampler draws from the density its pdf function claims (rejected draws included).
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/core/samplers/sampler_checks.h"

namespace glintlab {
namespace {

using namespace sampler_checks;

// 5 standard errors: 7 samplers × 4–5 configurations are ~32 z-scores; with fixed seeds the
// outcome is deterministic, and the chance that any |z| of a correct sampler exceeds 5 is ~2e-5.
constexpr double kMaxZ = 5;
constexpr int kDraws = 40000;

std::vector<Config> moment_configs(Kind k) {
  const bool ndf = singular_at_minus_wi(k);
  std::vector<Config> out = {{0.3, 0.3, dir(deg(50), 0.6)},
                             {0.8, 0.8, dir(deg(75), 2.0)},
                             {0.05, 0.05, V3{0, 0, 1}},
                             {0.02, 0.6, dir(deg(35), ndf ? kPiD / 2 : 1.1)}};
  if (handles_backfacing(k)) out.push_back({0.5, 0.5, dir(deg(115), 0.4)});
  return out;
}

MomentResult run(Kind k, const Config& c, std::uint64_t seed, double tilt = 0) {
  return moment_check(
      [&](const Config& cc, V2 u) {
        // tilt != 0: the mutant draws for an incidence rotated by `tilt` about the y axis.
        const double ct = std::cos(tilt), st = std::sin(tilt);
        const V3 wi{ct * cc.wi.x + st * cc.wi.z, cc.wi.y, -st * cc.wi.x + ct * cc.wi.z};
        return draw<double>(k, cc.ax, cc.ay, tilt == 0 ? cc.wi : wi, u);
      },
      [&](const Config& cc, const V3& wo) { return density<double>(k, cc.ax, cc.ay, cc.wi, wo); },
      k, c, seed, kDraws);
}

TEST(SamplerMoments, MonteCarloMeanMatchesCubature) {
  const std::uint64_t seed = test_seed();
  for (Kind k : kAllKinds)
    for (const Config& c : moment_configs(k)) {
      const MomentResult r = run(k, c, seed);
      std::printf("%-16s %-62s mc=%.6f exact=%.6f se=%.1e z=% .2f\n", name(k), describe(c).c_str(),
                  r.mc_mean, r.exact, r.mc_se, r.z);
      EXPECT_LT(std::abs(r.z), kMaxZ) << name(k) << " " << describe(c);
    }
}

// The same check rejects a sampler whose lobe is shifted by 0.06 rad (incidence tilted).
TEST(SamplerMoments, MutantShiftedLobeIsRejected) {
  const std::uint64_t seed = test_seed();
  for (Kind k : kAllKinds) {
    const Config c{0.3, 0.3, dir(deg(50), 0.6)};
    const MomentResult r = run(k, c, seed, 0.06);
    EXPECT_GT(std::abs(r.z), kMaxZ) << name(k);
  }
}

// The same check rejects the bounded sampler drawing with the wrong k (k/2, or the caps' k = 1)
// against pdf_bounded_vndf.
TEST(BoundedVndfMoments, MutantWrongKIsRejected) {
  const std::uint64_t seed = test_seed();
  for (const Config& c : {Config{0.6, 0.6, dir(deg(30), 0.2)}, Config{1, 1, V3{0, 0, 1}}})
    for (double scale : {0.5, -1.0}) {
      const GGX<double> g{c.ax, c.ay};
      const double k_right = bounded_vndf_k(g, c.wi, BoundedVndfBound::kListing1);
      const double k_wrong = scale < 0 ? 1.0 : scale * k_right;
      if (k_wrong == k_right) continue;  // α = 1, normal incidence: k = 0 scaled is still 0
      const MomentResult r = moment_check(
          [&](const Config& cc, V2 u) {
            return sample_bounded_vndf_with_k(GGX<double>{cc.ax, cc.ay}, cc.wi, u, k_wrong);
          },
          [&](const Config& cc, const V3& wo) {
            return pdf_bounded_vndf(GGX<double>{cc.ax, cc.ay}, cc.wi, wo);
          },
          Kind::kBoundedListing1, c, seed, kDraws);
      EXPECT_GT(std::abs(r.z), kMaxZ) << describe(c) << " k=" << k_wrong << " vs " << k_right;
    }
}

}  // namespace
}  // namespace glintlab

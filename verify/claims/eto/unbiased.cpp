// eto.unbiased — Eto & Tokuyoshi 2023, Sec. 3.3, Eq. 8, Listings 1–2.
//
// The paper, abstract: "This paper introduces an unbiased method to reduce the number of rejected
// samples for Smith–GGX VNDF sampling."
//
// Measured: per configuration (α 0.05–1 × αx/αy × θi), the mean of the bounded sampler's weights
// f cos / p_our (F = 1, Eq. 8's density, 0 for a rejected sample) against the spherical-cap
// sampler's (Welch's test) and against the albedo ∫ f cos dωo by cubature (one-sample t test); all
// tests corrected together by Holm–Šidák. Inconclusive where the cubature is not far more exact
// than the test.
// Control (perturbed): the same weights with the bounded pdf 2 % too large (each weight / 1.02):
// must fail.
// Regime: none.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "core/math/rng.h"
#include "verify/claim_runner.h"
#include "verify/claims/eto/common.h"
#include "verify/claims/eto/list.h"
#include "verify/claims/gof_family.h"
#include "verify/stats/mean_tests.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::eto_claims {
namespace {

constexpr double kControlPdfScale = 1.02;

MeanAccumulator weights(Technique t, const Config& c, std::uint64_t seed, std::uint64_t n) {
  return accumulate_weights(t, c, seed, n, 1);
}

// Weights of a pdf scaled by s are the correct weights divided by s, exactly up to rounding.
MeanAccumulator scaled(MeanAccumulator a, double s) {
  a.mean /= s;
  a.m2 /= s * s;
  return a;
}

// One configuration: the cubature albedo and both samplers' weights.
struct UnbiasedRow {
  Config c;
  double albedo = 0, albedo_error = 0;
  MeanAccumulator bounded, caps;
};

// The tests of the rows: per configuration Welch's (bounded vs caps) and the one-sample t (bounded
// vs cubature), corrected together.
struct UnbiasedTests {
  std::vector<double> p;
  std::vector<MeanTestResult> one;  // per configuration
  Family family;
  bool quadrature_ok = true;  // every cubature error far below the test's standard error
};
UnbiasedTests tests_of(const std::vector<UnbiasedRow>& rows) {
  UnbiasedTests t;
  for (const UnbiasedRow& r : rows) {
    t.p.push_back(welch_t_test(r.bounded, r.caps).p_value);
    t.one.push_back(t_test(r.bounded, r.albedo));
    t.p.push_back(t.one.back().p_value);
    if (r.albedo_error > 0.01 * t.one.back().std_error) t.quadrature_ok = false;
  }
  t.family = correct_family(t.p);
  return t;
}

}  // namespace

struct Unbiased {
  static constexpr std::string_view kId = "eto.unbiased";
  static constexpr std::string_view kPaper = kPaperVsCaps;
  static constexpr std::string_view kSource = "Sec. 3.3, Eq. 8, Listings 1–2";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Abstract: \"This paper introduces an unbiased method to reduce the number of "
      "rejected samples for Smith–GGX VNDF sampling.\" Sec. 3.3: \"If the reflection "
      "vector o is in the lower hemisphere, the integrand in the lighting integral must "
      "be zero. Therefore, omitting the Heaviside function does not affect Monte Carlo "
      "integration.\"";
  static constexpr std::string_view kStatistic =
      "Holm–Šidák adjusted p (Welch vs spherical caps; t vs cubature albedo)";
  static constexpr Expected kExpected{.quick = Verdict::kHolds};

  struct Sizes {
    std::vector<Config> grid;
    std::uint64_t n;  // samples per sampler and configuration
  };
  static Sizes sizes(Budget b) {
    return {estimator_grid(b), b == Budget::kQuick ? (1u << 15) : (1u << 20)};
  }
  static Sizes probe_sizes() { return {{{0.2, 0.2, 45}}, 1u << 15}; }

  using Evidence = UnbiasedRow;
  static int configurations(const Sizes& z) { return int(z.grid.size()); }
  static Evidence observe(const Sizes& z, int k, std::uint64_t) {
    const Config& c = z.grid[std::size_t(k)];
    const Moments mo = moments_by_cubature(c, false);
    const std::uint64_t i = std::uint64_t(k);
    return {c, mo.albedo, mo.albedo_error,
            weights(Technique::kBounded, c, check_seed(std::string(kId), 2 * i), z.n),
            weights(Technique::kSphericalCaps, c, check_seed(std::string(kId), 2 * i + 1), z.n)};
  }

  struct Measured {
    std::vector<UnbiasedRow> rows;
    double pdf_scale = 1;  // the factor on the bounded pdf (1: as implemented)
    UnbiasedTests tests;
  };
  static Measured measure(const Sizes&, std::span<const Evidence> e, Input input) {
    Measured m{{e.begin(), e.end()}, input == Input::kGenuine ? 1 : kControlPdfScale, {}};
    if (input != Input::kGenuine)
      for (UnbiasedRow& r : m.rows) r.bounded = scaled(r.bounded, m.pdf_scale);
    m.tests = tests_of(m.rows);
    return m;
  }

  // Inconclusive where the cubature is not far more exact than the test; fails where Holm–Šidák
  // rejects a test.
  static Decision decide(const Sizes&, const Measured& m) {
    const UnbiasedTests& t = m.tests;
    return {.verdict = !t.quadrature_ok              ? Verdict::kInconclusive
                       : t.family.hs.rejections == 0 ? Verdict::kHolds
                                                     : Verdict::kFails,
            .value = t.family.min_adjusted,
            .p_value = t.family.min_adjusted,
            .raw_p_values = t.family.hs.raw,
            .configurations = int(m.rows.size())};
  }

  // The grid's extent, the tests rejected and the largest relative bias.
  static std::string describe(const Sizes& z, const Measured& m, Input input) {
    const UnbiasedTests& t = m.tests;
    if (input != Input::kGenuine)
      return fmt::format(
          "bounded weights with pdf × {:g}: {} of {} tests rejected, adjusted p = {:.3g}",
          m.pdf_scale, t.family.hs.rejections, t.p.size(), t.family.min_adjusted);
    double a_lo = 1e300, a_hi = 0, ratio = 0, theta = 0, worst_bias = 0;
    std::size_t at = 0;
    for (std::size_t i = 0; i < m.rows.size(); ++i) {
      const UnbiasedRow& r = m.rows[i];
      a_lo = std::min(a_lo, r.c.ax), a_hi = std::max(a_hi, r.c.ax);
      ratio = std::max(ratio, r.c.ax / r.c.ay), theta = std::max(theta, r.c.theta_deg);
      const double bias = std::abs(r.bounded.mean / r.albedo - 1);
      if (bias > worst_bias) worst_bias = bias, at = i;
    }
    return fmt::format(
        "{} configurations (α {:g}–{:g}, αx/αy to {:g}, θi to {:g}°) × {} samples per sampler: {} "
        "of {} tests rejected at level {:.2g}; largest |E_bounded/E_cubature − 1| = {:.2g} ({}, "
        "albedo {:.4f})",
        m.rows.size(), a_lo, a_hi, ratio, theta, z.n, t.family.hs.rejections, t.p.size(),
        t.family.hs.alpha, worst_bias, describe_config(m.rows[at].c), m.rows[at].albedo);
  }

  static std::string power(const Sizes&, const Measured& m, const Measured&) {
    const double z_power = normal_quantile(1 - sidak_level(check_level(), m.tests.p.size()) / 2) +
                           normal_quantile(0.9);
    double power = 0;
    for (std::size_t i = 0; i < m.rows.size(); ++i)
      power = std::max(power, z_power * m.tests.one[i].std_error / m.rows[i].albedo);
    return fmt::format(
        "relative bias of the bounded estimator ≥ {:.2g} detected at 90 % power in every "
        "configuration (one-sample test)",
        power);
  }

  // One correct configuration: Welch's p of the bounded vs spherical-cap means.
  static double calibrate(std::uint64_t seed) {
    const Config c{0.6, 0.6, 45};
    const std::uint64_t n = 1u << 13;
    return welch_t_test(weights(Technique::kBounded, c, mix64(seed), n),
                        weights(Technique::kSphericalCaps, c, mix64(seed + 1), n))
        .p_value;
  }
};

}  // namespace glintlab::verify::eto_claims

GLINTLAB_CLAIM(glintlab::verify::eto_claims::Unbiased);

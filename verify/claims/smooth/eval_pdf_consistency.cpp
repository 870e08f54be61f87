// smooth.eval-pdf-consistency — Walter et al. 2007, Eq. 41; Heitz & d'Eon 2014 / Heitz 2018;
// Eto & Tokuyoshi 2023, Eq. 8 and Listing 2.
//
// The papers: Walter et al. 2007, Eq. 41: weight(o) = |i·m| G(i, o, m) / (|i·n| |m·n|); VNDF
// sampling (Heitz & d'Eon 2014, Heitz 2018): weight = G2(ω_i, ω_o) / G1(ω_i); Eto & Tokuyoshi 2023,
// Listing 2: "return ndf / (2.0f * (k * i.z + t)); // Eq. 8 * ||dm/do||" for Listing 1's samples.
//
// Measured: for every sampler of sampler_table(), per sample, the relative difference of the pdf
// sample() reports from the standalone pdf(ωo), and of the estimator's weight eval·cos/pdf from
// each paper's closed form (Walter Eq. 41; G2/G1; Eto Eq. 8: G2/G1 · (k i_z + t)/(i_z + t)),
// computed from Λ alone; per configuration: α ∈ {0.02, 0.3, 1} × anisotropy {1, 8} × θi ∈ {0°,
// 45°, 85°} (plus back-facing 120°, 175° where the sampler allows it), 2^16 samples (full: a denser
// grid, 2^20). Holds when the largest difference is within 10^-9 (rounding).
// Control (perturbed): one configuration per sampler (α = 0.3, θi = 75°, 4096 samples), each
// decided alone: the pdf recomputed with α × 1.02, and an eval whose G2 lost the G1(ωi) masking
// term. Every case must fail.
// Regime: none. Deterministic per sample (the samples are seeded per configuration).
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "core/math/rng.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/samplers/bounded_vndf.h"
#include "verify/claim_runner.h"
#include "verify/claims/gof_family.h"
#include "verify/claims/sampler_table.h"
#include "verify/claims/smooth/common.h"
#include "verify/claims/smooth/list.h"

namespace glintlab::verify {
namespace {

using V3 = Vec3<double>;

constexpr std::string_view kId = "smooth.eval-pdf-consistency";
// Relative tolerance: both quantities are the same algebra evaluated two ways, so they differ by
// rounding (a few ulp times the conditioning of G2 and D); any modelling error (α off by 2 %, G1
// dropped, a wrong Jacobian) is orders of magnitude larger.
constexpr double kTolerance = 1e-9;

struct Config {
  std::size_t sampler;
  double ax, ay, theta_deg;
};

V3 incidence(double theta_deg) {
  const double t = theta_deg * std::numbers::pi / 180, p = 0.7;  // a generic azimuth
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

enum class WeightForm { kWalter, kVndf, kBoundedListing1, kBoundedExact };

WeightForm weight_form(const std::string& name) {
  if (name.rfind("walter", 0) == 0) return WeightForm::kWalter;
  if (name == "bounded_vndf_listing1/ggx") return WeightForm::kBoundedListing1;
  if (name == "bounded_vndf_exact_isotropic/ggx") return WeightForm::kBoundedExact;
  return WeightForm::kVndf;
}

// The closed-form Monte Carlo weight of each technique (F = 1), from Λ alone: it shares no code
// path with eval/pdf, so an inconsistent pair (e.g. a pdf for one α, an eval for another) shows.
template <class Ndf>
double closed_form_weight(const Ndf& ndf, WeightForm form, V3 wi, V3 wo, V3 m) {
  if (!(wi.z > 0) || !(wo.z > 0)) return 0;
  const double li = ndf.lambda(wi), lo = ndf.lambda(wo);
  const double g2 = 1 / (1 + li + lo);  // height-correlated G2 (Heitz 2014 Eq. 99)
  switch (form) {
    case WeightForm::kWalter:  // Walter Eq. 41: |i·m| G / (|i·n| |m·n|)
      return std::abs(dot(wi, m)) * g2 / (wi.z * std::abs(m.z));
    case WeightForm::kVndf:  // G2 / G1(ωi)
      return g2 * (1 + li);
    case WeightForm::kBoundedListing1:
    case WeightForm::kBoundedExact: {
      // Eq. 8 over Eq. 7: the same density on the upper hemisphere times (i_z + t)/(k i_z + t).
      if constexpr (std::is_same_v<Ndf, GGX<double>>) {
        const double k =
            bounded_vndf_k(ndf, wi,
                           form == WeightForm::kBoundedExact ? BoundedVndfBound::kExactIsotropic
                                                             : BoundedVndfBound::kListing1);
        const double t = std::sqrt(ndf.sigma2(wi) + wi.z * wi.z);
        return g2 * (1 + li) * (k * wi.z + t) / (wi.z + t);
      }
      return std::numeric_limits<double>::quiet_NaN();
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// Relative difference, with exact zeros agreeing and NaN / one-sided zeros an infinite error.
double rel_error(double got, double want) {
  if (got == want) return 0;
  if (!std::isfinite(got) || !std::isfinite(want) || want == 0)
    return std::numeric_limits<double>::infinity();
  return std::abs(got - want) / std::abs(want);
}

// What the deliberately wrong variants change.
enum class Variant { kCorrect, kPdfAlphaOff, kEvalWithoutG1 };

struct Errors {
  double pdf = 0;     // max |pdf(sample()) − pdf(ωo)| / pdf(ωo), every sample
  double weight = 0;  // max relative error of eval·cos/pdf against the closed form, accepted ones
  std::uint64_t accepted = 0;
};

Errors measure(const Config& c, std::uint64_t n, Variant variant, std::uint64_t seed) {
  const SamplerEntry& e = sampler_table()[c.sampler];
  const V3 wi = incidence(c.theta_deg);
  const WeightForm form = weight_form(e.name);
  const double pa = variant == Variant::kPdfAlphaOff ? 1.02 : 1.0;
  constexpr std::uint64_t kChunk = 4096;
  const std::uint64_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<Errors> part(chunks);
  tbb::parallel_for(std::uint64_t(0), chunks, [&](std::uint64_t ch) {
    Errors r;
    for (std::uint64_t i = ch * kChunk; i < std::min(n, (ch + 1) * kChunk); ++i) {
      const Vec2<double> u{counter_uniform<double>(seed, i, 0),
                           counter_uniform<double>(seed, i, 1)};
      const MicrofacetSample<double> s = e.sample(c.ax, c.ay, wi, u);
      const double p = e.pdf(c.ax * pa, c.ay * pa, wi, s.wo);
      r.pdf = std::max(r.pdf, rel_error(s.pdf, p));
      if (s.rejected) continue;
      ++r.accepted;
      double f = e.brdf(c.ax, c.ay, wi, s.wo);
      auto closed = [&](const auto& ndf) {
        if (variant == Variant::kEvalWithoutG1 && wi.z > 0 && s.wo.z > 0)  // G2 → G1(ωo)
          f *= (1 + ndf.lambda(wi) + ndf.lambda(s.wo)) / (1 + ndf.lambda(s.wo));
        return closed_form_weight(ndf, form, wi, s.wo, s.m);
      };
      const double w_closed =
          e.ggx ? closed(GGX<double>{c.ax, c.ay}) : closed(Beckmann<double>{c.ax, c.ay});
      const double w = f * s.wo.z / s.pdf;  // the estimator's weight, eval·cos/pdf
      r.weight = std::max(r.weight, rel_error(w, w_closed));
    }
    part[ch] = r;
  });
  Errors all;  // max is exact, so the combination does not depend on the schedule
  for (const Errors& p : part) {
    all.pdf = std::max(all.pdf, p.pdf);
    all.weight = std::max(all.weight, p.weight);
    all.accepted += p.accepted;
  }
  return all;
}

std::vector<Config> grid(Budget b) {
  const bool quick = b == Budget::kQuick;
  const std::vector<double> alphas =
      quick ? std::vector<double>{0.02, 0.3, 1.0} : std::vector<double>{1e-3, 0.05, 0.5, 1.0, 2.0};
  const std::vector<double> ratios = quick ? std::vector<double>{1, 8} : std::vector<double>{1, 30};
  const std::vector<double> front =
      quick ? std::vector<double>{0, 45, 85} : std::vector<double>{0, 45, 80, 89.9};
  const std::vector<double> back =
      quick ? std::vector<double>{120, 175} : std::vector<double>{90.5, 135, 179};
  std::vector<Config> g;
  const auto& table = sampler_table();
  for (std::size_t s = 0; s < table.size(); ++s)
    for (double a : alphas)
      for (double r : ratios) {
        std::vector<double> thetas = front;
        if (table[s].allows_backfacing) thetas.insert(thetas.end(), back.begin(), back.end());
        for (double t : thetas) g.push_back({s, a, a / r, t});
      }
  return g;
}

// The errors of every configuration: the claim's own (seeds check_seed(kId, index), the runner's)
// or a control's, each run with its own seed.
struct ConsistencyMeasurement {
  std::vector<Config> configs;
  std::vector<Errors> errors;  // per configuration
  std::uint64_t n = 0;         // samples per configuration
};

ConsistencyMeasurement measure_consistency(const std::vector<Config>& configs, std::uint64_t n,
                                           Variant variant, std::uint64_t first_seed_index) {
  ConsistencyMeasurement m{configs, std::vector<Errors>(configs.size()), n};
  tbb::parallel_for(std::size_t(0), configs.size(), [&](std::size_t i) {
    m.errors[i] =
        measure(configs[i], n, variant, check_seed(std::string(kId), first_seed_index + i));
  });
  return m;
}

// The configurations with the largest pdf and weight errors.
std::pair<std::size_t, std::size_t> worst_of(const ConsistencyMeasurement& m) {
  std::size_t wp = 0, ww = 0;
  for (std::size_t i = 0; i < m.errors.size(); ++i) {
    if (m.errors[i].pdf > m.errors[wp].pdf) wp = i;
    if (m.errors[i].weight > m.errors[ww].weight) ww = i;
  }
  return {wp, ww};
}

double statistic_of(const ConsistencyMeasurement& m) {
  const auto [wp, ww] = worst_of(m);
  return m.errors.empty() ? 0 : std::max(m.errors[wp].pdf, m.errors[ww].weight);
}

// Holds when every sample's pdf and weight agree within the tolerance.
Verdict decide_consistency(const ConsistencyMeasurement& m) {
  return statistic_of(m) <= kTolerance ? Verdict::kHolds : Verdict::kFails;
}

std::string where(const Config& c) {
  return fmt::format("{} αx={:g} αy={:g} θi={:g}°", sampler_table()[c.sampler].name, c.ax, c.ay,
                     c.theta_deg);
}

// How much was sampled and where each error is largest.
std::string describe_consistency(const ConsistencyMeasurement& m) {
  const auto [wp, ww] = worst_of(m);
  std::uint64_t accepted = 0;
  for (const Errors& e : m.errors) accepted += e.accepted;
  return fmt::format(
      "{} samplers, {} configurations × {} samples ({} accepted): pdf max rel. error {:.2g} ({}), "
      "weight max rel. error {:.2g} ({}); tolerance {:.0e}",
      smooth_claims::sampler_count(std::span<const Config>(m.configs)), m.configs.size(), m.n,
      accepted, m.errors[wp].pdf, where(m.configs[wp]), m.errors[ww].weight, where(m.configs[ww]),
      kTolerance);
}

}  // namespace

namespace smooth_claims {

struct EvalPdfConsistency {
  static constexpr std::string_view kId = verify::kId;
  static constexpr std::string_view kPaper =
      "Walter et al. 2007; Heitz 2018; Dupuy & Benyoub 2023; Eto & Tokuyoshi 2023";
  static constexpr std::string_view kSource =
      "weight = f·cos/pdf (Walter Eq. 41, G2/G1, Eto Eq. 8); pdf(sample()) = pdf(ωo)";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Walter et al. 2007, Eq. 41: weight(o) = |i·m| G(i, o, m) / (|i·n| |m·n|); VNDF "
      "sampling (Heitz & d'Eon 2014, Heitz 2018): weight = G2(ω_i, ω_o) / G1(ω_i); Eto "
      "& Tokuyoshi 2023, Listing 2: \"return ndf / (2.0f * (k * i.z + t)); // Eq. 8 * "
      "||dm/do||\" for Listing 1's samples";
  static constexpr std::string_view kStatistic =
      "max relative error of pdf(sample()) vs pdf(ωo) and of eval·cos/pdf vs closed form";
  static constexpr Expected kExpected{.quick = Verdict::kHolds};

  struct Sizes {
    std::vector<Config> grid;
    std::uint64_t n = 0;  // samples per configuration
    Config control;       // the controls' configuration (its sampler: each in turn)
    std::uint64_t control_n = 0;
  };
  // Λ(ωi) is not negligible for Beckmann either at the controls' α = 0.3, θi = 75°.
  static Sizes sizes(Budget b) {
    return {grid(b), b == Budget::kQuick ? (1u << 16) : (1u << 20), {0, 0.3, 0.3, 75}, 4096};
  }
  // The tests' probe: every sampler at α = (0.3, 0.15), θi = 75°, 4096 samples, the controls there.
  static Sizes probe_sizes() {
    const Config c{0, 0.3, 0.15, 75};
    Sizes z{{}, 4096, c, 4096};
    for (std::size_t s = 0; s < sampler_table().size(); ++s) z.grid.push_back({s, c.ax, c.ay, 75});
    return z;
  }
  static int configurations(const Sizes& z) { return int(z.grid.size()); }

  using Evidence = Errors;
  static Evidence observe(const Sizes& z, int k, std::uint64_t seed) {
    return verify::measure(z.grid[std::size_t(k)], z.n, Variant::kCorrect, seed);
  }

  // The claim's configurations (genuine), or the controls (perturbed): one configuration per
  // sampler for each wrong variant, measured here with seeds of their own, each decided alone.
  struct Measured {
    ConsistencyMeasurement m;
    std::vector<Verdict> cases = {};
    std::string control_text = {};
  };
  static Measured measure(const Sizes& z, std::span<const Evidence> evidence, Input input) {
    if (input == Input::kGenuine)
      return {{z.grid, std::vector<Errors>(evidence.begin(), evidence.end()), z.n}};
    Measured out;
    const auto& table = sampler_table();
    for (auto [variant, seeds, what] :
         {std::tuple{Variant::kPdfAlphaOff, 1000, "α×1.02 in the recomputed pdf"},
          std::tuple{Variant::kEvalWithoutG1, 2000, "G1(ωi) dropped from eval"}}) {
      double smallest = 1e300;
      std::string at;
      for (std::size_t s = 0; s < table.size(); ++s) {
        const Config at_s{s, z.control.ax, z.control.ay, z.control.theta_deg};
        const ConsistencyMeasurement c =
            measure_consistency({at_s}, z.control_n, variant, std::uint64_t(seeds) + s);
        out.cases.push_back(decide_consistency(c));
        smallest = std::min(smallest, statistic_of(c));
        at = fmt::format("αx={:g} αy={:g} θi={:g}°, {} samples each", c.configs[0].ax,
                         c.configs[0].ay, c.configs[0].theta_deg, c.n);
      }
      out.control_text +=
          fmt::format("{}{}: smallest max error {:.3g} over {} samplers at {}",
                      out.control_text.empty() ? "" : "; ", what, smallest, table.size(), at);
    }
    return out;
  }

  static Decision decide(const Sizes&, const Measured& m) {
    if (!m.cases.empty()) return {.verdict = control_verdict_of_cases(m.cases)};
    return {.verdict = decide_consistency(m.m),
            .value = statistic_of(m.m),
            .bound = kTolerance,
            .configurations = int(m.m.configs.size())};
  }
  static std::string describe(const Sizes&, const Measured& m, Input input) {
    return input == Input::kGenuine ? describe_consistency(m.m) : m.control_text;
  }
  static std::string power(const Sizes& z, const Measured&, const Measured&) {
    return fmt::format(
        "deterministic per sample: a relative error above {:g} in any one of the {} samples per "
        "configuration is detected",
        kTolerance, z.n);
  }
};

}  // namespace smooth_claims
}  // namespace glintlab::verify

GLINTLAB_CLAIM(glintlab::verify::smooth_claims::EvalPdfConsistency);

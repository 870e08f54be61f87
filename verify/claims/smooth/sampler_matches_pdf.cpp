// smooth.sampler-matches-pdf — Walter et al. 2007, Eq. 14, 24; Heitz 2018, Eq. 1; Heitz & d'Eon
// 2014; Dupuy & Benyoub 2023; Eto & Tokuyoshi 2023, Eq. 8.
//
// The papers: Walter et al. 2007 (Eq. 14, 24): p_o(o) = p_m(m) / (4|o·m|); Heitz 2018: p_m(m) =
// D_ωi(m); Eto & Tokuyoshi 2023, Sec. 3.3: "By multiplying the above PDF p_our(m) by the Jacobian
// for the transformation between halfvectors and reflection vectors ‖dm/do‖ = 1/(4|i·m|), we
// obtain the PDF for our reflection vector sampling p_our(m)‖dm/do‖."
//
// Measured: every core sampler of sampler_table() (batched, core/simd/batch.h) draws ωo from the
// standalone pdf it reports, by chi-square on the whole sphere (rejected samples are directions
// too), per configuration: six (α, θi) pairs per sampler spanning α 0.02 … 1, anisotropy 1:10 both
// ways and θi 0° … 89°, plus back-facing 120° where that is defined (full: a denser grid, 10^7
// samples). The family's p-values are Holm–Šidák-corrected at the suite's level
// (verify/claims/gof_family.h).
// Control (perturbed): deliberately wrong densities and samplers (pdf × 1.02, the sampler's α ×
// 1.02, the reflection Jacobian dropped, G1(ωi) dropped from the VNDF, ωi and ωo swapped, the sign
// of ωi_z flipped in the back-facing pdf), each case decided in place of the configuration it is
// built on, as the family: every case must fail.
// Regime: none. To the runner the family is one configuration: it is planned and run as one, its
// controls reusing the configurations' plans and continuing their seeds (run_gof_family).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/simd/batch.h"
#include "verify/claim_runner.h"
#include "verify/claims/gof_family.h"
#include "verify/claims/gof_family_claim.h"
#include "verify/claims/kernel_direction_batch.h"
#include "verify/claims/sampler_table.h"
#include "verify/claims/smooth/common.h"
#include "verify/claims/smooth/list.h"

namespace glintlab::verify {
namespace {

using V3 = Vec3<double>;

struct Config {
  std::size_t sampler;  // index into sampler_table()
  double ax, ay, theta_deg;
};

// The distribution of ωo is defined for a back-facing ωi (ωi_z < 0) for the samplers that accept
// it and for Walter's NDF sampling, whose normals do not depend on ωi (its pdf covers every ωi);
// Heitz's and the Beckmann visible-normal samplers reject every sample there.
bool backfacing_defined(const SamplerEntry& e) {
  return e.allows_backfacing || e.name.starts_with("walter/");
}

// Quick: each sampler at six (α, θi) pairs that together span α 0.02 … 1, anisotropy 1:10 both
// ways and θi 0° … 89°, plus 120° where back-facing is defined. Full: α ∈ {0.02, 1, 0.02:0.2,
// 1:0.1} × θi ∈ {0°, 60°, 89°}, plus 120° and 150° back-facing; the Beckmann visible-normal sampler
// (≈ 6× slower per sample: two Newton inversions of erfc) keeps the quick grid at 10^7 samples.
std::vector<Config> grid(Budget b) {
  const std::vector<std::pair<double, double>> alphas = {
      {0.02, 0.02}, {0.3, 0.3}, {1, 1}, {0.02, 0.2}, {1, 0.1}};
  const auto& table = sampler_table();
  std::vector<Config> out;
  for (std::size_t s = 0; s < table.size(); ++s) {
    const bool quick_grid = b == Budget::kQuick || table[s].name == "beckmann_vndf/beckmann";
    if (!quick_grid) {
      for (std::size_t a : {0, 2, 3, 4})
        for (double t : {0.0, 60.0, 89.0}) out.push_back({s, alphas[a].first, alphas[a].second, t});
    } else {
      for (auto [a, t] : std::vector<std::pair<std::size_t, double>>{
               {0, 0}, {1, 45}, {2, 89}, {3, 80}, {4, 45}, {3, 0}})
        out.push_back({s, alphas[a].first, alphas[a].second, t});
    }
    if (backfacing_defined(table[s])) {
      out.push_back({s, 0.3, 0.3, 120});
      if (b == Budget::kFull) out.push_back({s, 1, 0.1, 150});
    }
  }
  return out;
}

std::string label(const Config& c) {
  return fmt::format("{} α=({:g},{:g}) θi={:g}°", sampler_table()[c.sampler].name, c.ax, c.ay,
                     c.theta_deg);
}

// A sampler of ωo for configuration c with roughness scaled by alpha_scale (1: the real one).
SeededDirections directions(const Config& c, double alpha_scale = 1) {
  const SamplerEntry& e = sampler_table()[c.sampler];
  const V3 wi = incidence(c.theta_deg);
  const double ax = alpha_scale * c.ax, ay = alpha_scale * c.ay;
  return [&e, wi, ax, ay](std::uint64_t seed, std::uint64_t i) {
    return e.sample(ax, ay, wi, uniform_pair(seed, i)).wo;
  };
}

// The batch kernel (core/simd/kernels.h) of a sampler of sampler_table(): the table names
// samplers as the kernels do, "sample.<function>/<ndf>".
int batch_kernel(const std::string& name) {
  if (const auto k = simd::find_kernel("sample." + name)) return *k;
  throw std::logic_error("sampler " + name + " has no batch kernel");
}

// The batch kernel of the sampler's standalone pdf, "pdf.<function>/<ndf>".
int pdf_kernel(const std::string& name) {
  if (const auto k = simd::find_kernel("pdf." + name)) return *k;
  throw std::logic_error("sampler " + name + " has no batch pdf kernel");
}

// The same sampler as directions(c, alpha_scale), batched (core/simd/batch.h sample_batch, double,
// on the ISA of GLINTLAB_ISA or the widest of this CPU): the same uniforms; wo within the
// equivalence budgets of tests/simd/ of the scalar one (bit-identical with GLINTLAB_ISA=scalar).
SeededDirectionBatch batched_directions(const Config& c, double alpha_scale = 1) {
  return kernel_direction_batch(batch_kernel(sampler_table()[c.sampler].name),
                                incidence(c.theta_deg), alpha_scale * c.ax, alpha_scale * c.ay,
                                /*upper_only=*/false);
}

GofCase make_case(const Config& c) {
  const SamplerEntry& e = sampler_table()[c.sampler];
  const V3 wi = incidence(c.theta_deg);
  GofCase g;
  g.label = label(c);
  g.options = reflection_options(wi);
  // NDF sampling's density has its 1/|ωi + ωo| singularity at −ωi, with a thin ray from there
  // towards the mirror direction (normals seen edge-on): binned about the mirror direction, bins
  // holding −ωi lost up to 8e-4 of the mass with error estimates of 4e-8 (measured, Beckmann
  // α = (1, 0.1), θi = 45°). With the pole at −ωi the singularity is integrable in the polar
  // coordinates and the ray lies on the meridian through the mirror direction, a cubature break.
  if (e.name.starts_with("walter/")) {
    g.options.lobe = -wi;
    g.options.point_features = {V3{-wi.x, -wi.y, wi.z}};
  }
  // The bounded cap's edge χ⁺(k î_z + ô_z) (Eto & Tokuyoshi Eq. 8) is, for anisotropic α, a curve
  // far from any parallel of the bin frame: near its extreme polar angle the support is a thin
  // sliver in azimuth that 15 Kronrod nodes over a whole ring step over (measured: ~1e-3 of the
  // mass placed in bins of zero expectation). Uniform azimuth breaks resolve it.
  if (e.name.starts_with("bounded_vndf_") && c.ax != c.ay)
    for (int k = 1; k < 64; ++k) g.options.phi_breaks.push_back(2 * std::numbers::pi * k / 64);
  g.direction_pdf = [&e, wi, ax = c.ax, ay = c.ay](const V3& wo) { return e.pdf(ax, ay, wi, wo); };
  // The expected counts' cubature asks for the same pdf at many directions at once, through its
  // batch kernel (within the batches' equivalence budgets of e.pdf).
  g.options.direction_pdf_rows =
      kernel_direction_pdf_rows(pdf_kernel(e.name), wi, c.ax, c.ay, /*upper_only=*/false);
  g.directions = directions(c);
  g.direction_batch = batched_directions(c);
  return g;
}

// Configurations of the grid with the given sampler name, roughness and incidence, if present.
int find(const std::vector<Config>& g, const std::string& name, double ax, double ay, double t) {
  for (std::size_t i = 0; i < g.size(); ++i)
    if (sampler_table()[g[i].sampler].name == name && g[i].ax == ax && g[i].ay == ay &&
        g[i].theta_deg == t)
      return int(i);
  return -1;
}

// The negative controls: each a wrong pdf or a wrong sampler on a few
// configurations of the grid, all present in both budgets' grids.
std::vector<GofControl> controls(const std::vector<Config>& g) {
  std::vector<GofControl> out;
  auto cfg = [&](const std::string& name, double ax, double ay, double t) {
    const int i = find(g, name, ax, ay, t);
    if (i < 0) throw std::logic_error("control built on a configuration missing from the grid");
    return i;
  };
  // Configuration i's plan with its expectations × pdf_scale, sampled with α × alpha_scale.
  auto sampled = [&](int i, const std::string& what, double alpha_scale, double pdf_scale) {
    const Config& c = g[std::size_t(i)];
    return GofControlCase{{label(c) + what,
                           {},
                           {},
                           {},
                           directions(c, alpha_scale),
                           {},
                           {},
                           batched_directions(c, alpha_scale)},
                          i,
                          pdf_scale};
  };
  // A claimed pdf 2 % too large everywhere: the plan's expectations × 1.02.
  GofControl scaled{"pdf × 1.02", {}};
  for (int i : {cfg("heitz_vndf/ggx", 1, 1, 89), cfg("walter/beckmann", 0.02, 0.2, 0),
                cfg("bounded_vndf_listing1/ggx", 1, 1, 89)})
    scaled.cases.push_back(sampled(i, " pdf×1.02", 1, 1.02));
  out.push_back(scaled);
  // The sampler run with α 2 % too large, against the true pdf.
  GofControl alpha{"sampler α × 1.02", {}};
  for (int i : {cfg("spherical_caps/ggx", 0.02, 0.2, 0), cfg("heitz_vndf/ggx", 0.02, 0.02, 0),
                cfg("walter/beckmann", 1, 1, 89)})
    alpha.cases.push_back(sampled(i, " α×1.02", 1.02, 1));
  out.push_back(alpha);
  // The reflection Jacobian 1/(4|ωo·h|) (Walter Eq. 14) dropped from the pdf: p(h) as if it were
  // the density of ωo. |ωo·h| = |ωi + ωo|/2 for the half vector.
  GofControl jacobian{"1/(4|ωo·h|) dropped from the pdf", {}};
  for (int i : {cfg("heitz_vndf/ggx", 1, 1, 89), cfg("spherical_caps/ggx", 0.02, 0.2, 0)}) {
    GofCase w = make_case(g[std::size_t(i)]);
    const V3 wi = incidence(g[std::size_t(i)].theta_deg);
    w.label += " without 1/(4|ωo·h|)";
    w.direction_pdf = [f = w.direction_pdf, wi](const V3& wo) {
      return f(wo) * 2 * length(wi + wo);
    };
    w.options.direction_pdf_rows = [f = w.options.direction_pdf_rows, wi](
                                       std::span<const V3> wo, std::span<double> pdf) {
      f(wo, pdf);
      for (std::size_t k = 0; k < wo.size(); ++k) pdf[k] = pdf[k] * 2 * length(wi + wo[k]);
    };
    jacobian.cases.push_back({w, -1, 1, i});
  }
  jacobian.gross = true;
  out.push_back(jacobian);
  // G1 dropped from the VNDF D_ωi = G1(ωi) max(0, ωi·m) D(m)/ωi_z (Heitz 2018 Eq. 1): the claimed
  // density is divided by the constant G1(ωi) = ωi_z/A(ωi).
  GofControl g1{"G1(ωi) dropped from the VNDF", {}};
  for (int i : {cfg("heitz_vndf/ggx", 1, 1, 89), cfg("beckmann_vndf/beckmann", 1, 1, 89)}) {
    const Config& c = g[std::size_t(i)];
    const V3 wi = incidence(c.theta_deg);
    const double a = sampler_table()[c.sampler].ggx
                         ? GGX<double>{c.ax, c.ay}.projected_area(wi)
                         : Beckmann<double>{c.ax, c.ay}.projected_area(wi);
    g1.cases.push_back(
        {{label(c) + " without G1", {}, {}, {}, directions(c), {}, {}, batched_directions(c)},
         i,
         a / wi.z});
  }
  g1.gross = true;  // G1(ωi) ≈ 0.5 at θi = 89°, α = 1
  out.push_back(g1);
  // ωi and ωo exchanged in the pdf (Walter's density is symmetric in them, so it is not used).
  GofControl swapped{"ωi and ωo swapped in the pdf", {}};
  for (int i :
       {cfg("heitz_vndf/ggx", 1, 1, 89), cfg("bounded_vndf_exact_isotropic/ggx", 0.02, 0.2, 0)}) {
    const Config& c = g[std::size_t(i)];
    GofCase w = make_case(c);
    const SamplerEntry& e = sampler_table()[c.sampler];
    w.label += " with ωi ↔ ωo";
    w.options.direction_pdf_rows =
        kernel_swapped_pdf_rows(pdf_kernel(e.name), incidence(c.theta_deg), c.ax, c.ay);
    w.direction_pdf = [&e, wi = incidence(c.theta_deg), ax = c.ax, ay = c.ay](const V3& wo) {
      return e.pdf(ax, ay, wo, wi);
    };
    swapped.cases.push_back({w, -1, 1, i});
  }
  swapped.gross = true;
  out.push_back(swapped);
  // Back-facing ωi: the stable form D(h)(t − i_z)/(2σ²) of Eto & Tokuyoshi Listing 2 with the sign
  // of i_z flipped, D(h)(t + i_z)/(2σ²).
  GofControl sign{"sign of ωi_z flipped in the back-facing pdf", {}};
  for (int i : {cfg("spherical_caps/ggx", 0.3, 0.3, 120),
                cfg("bounded_vndf_listing1/ggx", 0.3, 0.3, 120)}) {
    const Config& c = g[std::size_t(i)];
    GofCase w = make_case(c);
    w.label += " with (t + i_z)";
    w.options.direction_pdf_rows = {};  // the claimed pdf below, one direction at a time
    const GGX<double> ggx{c.ax, c.ay};
    w.direction_pdf = [ggx, wi = incidence(c.theta_deg)](const V3& wo) {
      const double s2 = ggx.sigma2(wi), t = std::sqrt(s2 + wi.z * wi.z);
      return ggx.D(half_vector(wi, wo)) * (t + wi.z) / (2 * s2);
    };
    sign.cases.push_back({w, -1, 1, i});
  }
  sign.gross = true;
  out.push_back(sign);
  return out;
}

// Quick: 10^5 samples per configuration, ≤ 600 fine bins; the subtle controls at 5·10^5 samples,
// where a 2 % error is far above the detectable δ. Full: 10^7 samples everywhere, ≤ 4096 fine bins.
constexpr GofSize kQuick{100'000, 500'000, 600};
constexpr GofSize kFull{10'000'000, 10'000'000, 4096};

// The tests' probe: the quick grid's configurations that its controls are built on, at 3·10^4
// samples (3·10^5 for the subtle controls: a 2 % error then gives a non-centrality ≈ 120 against
// ≈ 90 needed).
constexpr GofSize kProbe{30'000, 300'000, 500};
std::vector<Config> probe_grid() {
  const std::vector<Config> g = grid(Budget::kQuick);
  return configurations_under_controls(g, controls(g));
}

GofSpec spec_of(const std::vector<Config>& g) { return gof_spec(g, make_case, controls(g)); }

// The detail line, from the grid and the family's outcome alone.
std::string describe_family(const std::vector<Config>& g, const std::vector<GofCase>& cases,
                            const GofOutcome& o, const CheckResult& r, std::size_t worst) {
  return fmt::format(
      "{} configurations ({} samplers), {} samples each on the sphere: {} rejected at family rate "
      "{:.2g}, {} inconclusive, {} hard failures; smallest raw p {:.3g} at {} ({})",
      g.size(), smooth_claims::sampler_count(std::span<const Config>(g)),
      o.results.empty() ? 0 : o.results[0].n, o.family.rejections, o.family.alpha, o.inconclusive,
      o.hard_failures, r.raw_p_values[worst], cases[worst].label, o.results[worst].summary());
}

// One run of a known-correct configuration (spherical caps, α = 0.3, θi = 45°) at the quick size;
// the plan is computed once.
double calibration(std::uint64_t seed) {
  static const GofCase c = [] {
    std::size_t caps = 0;
    while (sampler_table()[caps].name != "spherical_caps/ggx") ++caps;
    return make_case({caps, 0.3, 0.3, 45});
  }();
  static const ChiSquarePlan plan = plan_gof_case(
      c, kQuick.n, sidak_level(check_level(), grid(Budget::kQuick).size()), kQuick.fine_max_bins);
  return run_gof_case(plan, c, seed).p_value;
}

}  // namespace

GofSpec smooth_sampler_spec(Budget b) { return spec_of(grid(b)); }

namespace smooth_claims {

struct SamplerMatchesPdf : GofFamilyClaim<SamplerMatchesPdf, Config> {
  static constexpr std::string_view kId = "smooth.sampler-matches-pdf";
  static constexpr std::string_view kPaper =
      "Walter et al. 2007; Heitz 2018; Heitz & d'Eon 2014; Dupuy & Benyoub 2023; Eto & Tokuyoshi "
      "2023";
  static constexpr std::string_view kSource =
      "sampled ωo ~ pdf(ωi, ωo) (Walter Eq. 14, 24; Heitz 2018 Eq. 1; Eto & Tokuyoshi Eq. 8)";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Eto & Tokuyoshi 2023, Sec. 3.3: \"By multiplying the above PDF p_our(m) by the "
      "Jacobian for the transformation between halfvectors and reflection vectors "
      "‖dm/do‖ = 1/(4|i·m|), we obtain the PDF for our reflection vector sampling "
      "p_our(m)‖dm/do‖.\" Walter et al. 2007 (Eq. 14, 24 as registered): p_o(o) = "
      "p_m(m) / (4|o·m|); Heitz 2018: p_m(m) = D_ωi(m)";
  static constexpr std::string_view kStatistic =
      "Holm–Šidák-corrected p of the chi-square of sampled ωo against the sampler's pdf";
  static constexpr Expected kExpected{.quick = Verdict::kHolds};

  static Sizes sizes(Budget b) { return {grid(b), b == Budget::kQuick ? kQuick : kFull}; }
  static Sizes probe_sizes() { return {probe_grid(), kProbe}; }
  static GofSpec spec(const Sizes& z) { return spec_of(z.grid); }
  static std::string genuine_text(const Sizes& z, const GofSpec& spec, const GofOutcome& o,
                                  const GofControlVerdicts&, const CheckResult& family,
                                  std::size_t worst) {
    return describe_family(z.grid, spec.cases, o, family, worst);
  }
  static double calibrate(std::uint64_t seed) { return calibration(seed); }
};

}  // namespace smooth_claims
}  // namespace glintlab::verify

GLINTLAB_CLAIM(glintlab::verify::smooth_claims::SamplerMatchesPdf);

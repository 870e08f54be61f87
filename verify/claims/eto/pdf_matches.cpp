// eto.pdf-matches — Eto & Tokuyoshi 2023, Eq. 8 (with χ⁺), Eq. 7 for i_z ≤ 0, Listing 2.
//
// The paper, Sec. 3.3: "Since our method limits the sampling range for ô_z into (−k î_z, 1], we
// represent this limited range using the Heaviside function χ⁺(k î_z + ô_z) [...] By multiplying
// the above PDF p_our(m) by the Jacobian for the transformation between halfvectors and reflection
// vectors ‖dm/do‖ = 1/(4|i·m|), we obtain the PDF for our reflection vector sampling
// p_our(m)‖dm/do‖." Listing 2 omits χ⁺, "assuming that our method is applied only to
// reflections".
//
// Measured: the bounded VNDF sampler's reflections ωo (drawn batched, core/simd/batch.h) against
// that density by chi-square, per configuration: Listing 1's k or the exact isotropic k of Eq. 5;
// Eq. 8 with χ⁺ over the whole sphere (Eq. 7 for i_z ≤ 0), or Listing 2 over ωo_z > 0 with
// rejected reflections counted as "no sample"; isotropic and anisotropic α, front- and back-facing
// incidence. The family's p-values are Holm–Šidák-corrected at the suite's level
// (verify/claims/gof_family.h).
// Control (perturbed): deliberately wrong densities and samplers (pdf × 1.02, the sampler's α ×
// 1.02, Listing 2 without χ⁺ over the whole sphere, the full-cap density k = 1, the sign of i_z
// flipped in Listing 2's back-facing form, ‖dm/do‖ dropped), each case decided in place of the
// configuration it is built on, as the family: every case must fail.
// Regime: none. To the runner the family is one configuration: it is planned and run as one, its
// controls reusing the configurations' plans and continuing their seeds (run_gof_family).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/bounded_vndf.h"
#include "core/samplers/spherical_caps.h"
#include "core/simd/batch.h"
#include "verify/claim_runner.h"
#include "verify/claims/eto/eq8_density.h"
#include "verify/claims/eto/list.h"
#include "verify/claims/gof_family.h"
#include "verify/claims/kernel_direction_batch.h"
#include "verify/claims/gof_family_claim.h"

namespace glintlab::verify {
namespace {

using V3 = Vec3<double>;
using eto_claims::Eq8ReflectionPdf;

// What a configuration compares the sampler with:
//  kEq8: Eq. 8 × 1/(4|i·m|) transcribed as printed, Heaviside χ⁺(k î_z + ô_z) included (Eq. 7 for
//    i_z ≤ 0), over the whole sphere, every sampled ωo kept;
//  kListing2: Listing 2 (no Heaviside, Listing 1's k) over the upper hemisphere, where the paper
//    uses it: sampled ωo with ωo_z ≤ 0 (rejected reflections) count as "no sample".
enum class Form { kEq8, kListing2 };

struct Config {
  BoundedVndfBound bound;
  double ax, ay, theta_deg;
  Form form;
};

const char* bound_name(BoundedVndfBound b) {
  return b == BoundedVndfBound::kListing1 ? "Listing-1 k" : "exact isotropic k";
}

std::vector<Config> grid(Budget b) {
  struct A {
    double ax, ay, theta;
  };
  // Quick: isotropic α = 0.3, 1, 1.5 (k < 0 for the exact bound) and anisotropic 3:1 and 1:10, at
  // incidences 0° … 89° and back-facing 120°, 150°. Full: every α × θi ∈ {0, 45, 80, 89, 150}.
  std::vector<A> pts;
  const std::vector<std::pair<double, double>> alphas = {{0.3, 0.3}, {1, 1},   {1.5, 1.5},
                                                         {0.6, 0.2}, {0.1, 1}, {0.05, 0.05}};
  if (b == Budget::kQuick) {
    pts = {{0.3, 0.3, 0}, {1, 1, 60},      {1.5, 1.5, 89}, {0.6, 0.2, 45},
           {0.1, 1, 80},  {0.3, 0.3, 120}, {0.6, 0.2, 150}};
  } else {
    for (auto [ax, ay] : alphas)
      for (double t : {0.0, 45.0, 80.0, 89.0, 150.0}) pts.push_back({ax, ay, t});
  }
  std::vector<Config> out;
  for (BoundedVndfBound bound : {BoundedVndfBound::kListing1, BoundedVndfBound::kExactIsotropic})
    for (const A& a : pts) out.push_back({bound, a.ax, a.ay, a.theta, Form::kEq8});
  for (const A& a : pts)
    out.push_back({BoundedVndfBound::kListing1, a.ax, a.ay, a.theta, Form::kListing2});
  return out;
}

std::string label(const Config& c) {
  return fmt::format("{}, {} α=({:g},{:g}) θi={:g}°",
                     c.form == Form::kEq8 ? "Eq. 8 on the sphere" : "Listing 2 on ωo_z > 0",
                     bound_name(c.bound), c.ax, c.ay, c.theta_deg);
}

SeededDirections directions(const Config& c, double alpha_scale = 1) {
  const GGX<double> g{alpha_scale * c.ax, alpha_scale * c.ay};
  const V3 wi = incidence(c.theta_deg);
  const bool hemisphere = c.form == Form::kListing2;
  return [g, wi, bound = c.bound, hemisphere](std::uint64_t seed, std::uint64_t i) {
    const V3 wo = sample_bounded_vndf(g, wi, uniform_pair(seed, i), bound).wo;
    return hemisphere && !(wo.z > 0) ? V3{0, 0, 0} : wo;
  };
}

// The same sampler, batched (core/simd/batch.h sample_batch, double, on simd::default_isa():
// GLINTLAB_ISA or the widest ISA of this CPU), with the same uniforms: directions(c, alpha_scale)
// bit for bit on the scalar ISA, within the batches' equivalence budgets on the others.
SeededDirectionBatch batched_directions(const Config& c, double alpha_scale = 1) {
  const char* name = c.bound == BoundedVndfBound::kListing1
                         ? "sample.bounded_vndf_listing1/ggx"
                         : "sample.bounded_vndf_exact_isotropic/ggx";
  const std::optional<int> kernel = simd::find_kernel(name);
  if (!kernel) throw std::logic_error(std::string("no batch kernel ") + name);
  return kernel_direction_batch(*kernel, incidence(c.theta_deg), alpha_scale * c.ax,
                                alpha_scale * c.ay, c.form == Form::kListing2);
}

GofCase make_case(const Config& c) {
  const GGX<double> g{c.ax, c.ay};
  const V3 wi = incidence(c.theta_deg);
  GofCase gc;
  gc.label = label(c);
  gc.options = reflection_options(wi);
  if (c.form == Form::kListing2) {
    // Pole at +z: the support's edge, the horizon, is then the parallel θ' = 90°.
    gc.options.lobe = {0, 0, 1};
    // pdf_bounded_vndf_listing2 with its k (Listing 1's, a function of ωi) computed once.
    gc.direction_pdf = [g, wi,
                        k = bounded_vndf_k(g, wi, BoundedVndfBound::kListing1)](const V3& wo) {
      return wo.z > 0 ? glintlab::detail::bounded_vndf_density(g, wi, g.D(half_vector(wi, wo)), k)
                      : 0.0;
    };
    // The same density through Listing 2's batch kernel for the expected counts' cubature (within
    // the batches' equivalence budgets).
    const std::optional<int> kernel = simd::find_kernel("pdf.bounded_vndf_listing2_printed/ggx");
    if (!kernel) throw std::logic_error("no batch kernel pdf.bounded_vndf_listing2_printed/ggx");
    gc.options.direction_pdf_rows =
        kernel_direction_pdf_rows(*kernel, wi, c.ax, c.ay, /*upper_only=*/true);
  } else {
    // Eq. 8 is this claim's own transcription; its rows run in double lanes, bit for bit.
    const Eq8ReflectionPdf pdf(g, wi, c.bound);
    gc.direction_pdf = pdf;
    gc.options.direction_pdf_rows = pdf.rows();
  }
  // For anisotropic α the cap edge χ⁺ = 0 is far from a parallel: azimuth breaks resolve the thin
  // slivers of support near its extreme polar angle (see smooth/sampler_matches_pdf.cpp).
  if (c.ax != c.ay)
    for (int k = 1; k < 64; ++k) gc.options.phi_breaks.push_back(2 * std::numbers::pi * k / 64);
  gc.directions = directions(c);
  gc.direction_batch = batched_directions(c);
  return gc;
}

int find(const std::vector<Config>& g, BoundedVndfBound bound, double ax, double ay, double t,
         Form form) {
  for (std::size_t i = 0; i < g.size(); ++i)
    if (g[i].bound == bound && g[i].ax == ax && g[i].ay == ay && g[i].theta_deg == t &&
        g[i].form == form)
      return int(i);
  return -1;
}

std::vector<GofControl> controls(const std::vector<Config>& g) {
  constexpr auto kL1 = BoundedVndfBound::kListing1;
  constexpr auto kEx = BoundedVndfBound::kExactIsotropic;
  const int iso = find(g, kL1, 0.3, 0.3, 0, Form::kEq8);
  const int aniso = find(g, kEx, 0.6, 0.2, 150, Form::kEq8);
  const int rough = find(g, kEx, 1.5, 1.5, 89, Form::kEq8);
  const int upper = find(g, kL1, 0.6, 0.2, 150, Form::kListing2);
  const int upper_rough = find(g, kL1, 1.5, 1.5, 89, Form::kListing2);
  const int aniso_front = find(g, kEx, 0.6, 0.2, 45, Form::kEq8);
  // α = 1: k = 0, the bounded cap is the upper half of the full one.
  const int unit = find(g, kL1, 1, 1, 60, Form::kEq8) >= 0 ? find(g, kL1, 1, 1, 60, Form::kEq8)
                                                           : find(g, kL1, 1, 1, 45, Form::kEq8);
  const int back = find(g, kL1, 0.3, 0.3, 150, Form::kEq8) >= 0
                       ? find(g, kL1, 0.3, 0.3, 150, Form::kEq8)
                       : find(g, kL1, 0.3, 0.3, 120, Form::kEq8);
  const int back2 = find(g, kEx, 0.6, 0.2, 150, Form::kEq8);
  auto at = [&](int i) -> const Config& {
    if (i < 0) throw std::logic_error("control built on a configuration missing from the grid");
    return g[std::size_t(i)];
  };
  // A control's case planned with its wrong pdf: one direction at a time, or through `rows` (the
  // same wrong pdf at many directions per call) where given.
  auto replanned = [&](int i, const std::string& what, DirectionPdf pdf,
                       DirectionPdfRows rows = {}) {
    GofCase w = make_case(at(i));
    w.label += " " + what;
    w.direction_pdf = std::move(pdf);
    w.options.direction_pdf_rows = std::move(rows);
    return GofControlCase{w, -1, 1, i};
  };
  std::vector<GofControl> out;

  GofControl scaled{"pdf × 1.02", {}};
  for (int i : {iso, rough, upper})
    scaled.cases.push_back({{label(at(i)) + " pdf×1.02",
                             {},
                             {},
                             {},
                             directions(at(i)),
                             {},
                             {},
                             batched_directions(at(i))},
                            i,
                            1.02});
  out.push_back(scaled);

  GofControl alpha{"sampler α × 1.02", {}};
  for (int i : {iso, aniso_front, upper_rough})
    alpha.cases.push_back({{label(at(i)) + " α×1.02",
                            {},
                            {},
                            {},
                            directions(at(i), 1.02),
                            {},
                            {},
                            batched_directions(at(i), 1.02)},
                           i,
                           1});
  out.push_back(alpha);

  // Listing 2 as printed, without χ⁺, taken as the density over the whole sphere: it integrates
  // to (1 + î_z)/(1 + k î_z) > 1.
  GofControl no_heaviside{"Listing 2 without χ⁺ over the whole sphere", {}, true};
  for (int i : {iso, unit}) {
    const GGX<double> ggx{at(i).ax, at(i).ay};
    const V3 wi = incidence(at(i).theta_deg);
    no_heaviside.cases.push_back(replanned(i, "Listing 2 without χ⁺", [ggx, wi](const V3& wo) {
      return pdf_bounded_vndf_listing2(ggx, wi, wo);
    }));
  }
  out.push_back(no_heaviside);

  // The previous (full-cap, k = 1) density of Dupuy & Benyoub for the bounded sampler's ωo.
  GofControl full_cap{"full-cap density (k = 1) for the bounded sampler", {}, true};
  for (int i : {iso, unit}) {
    const GGX<double> ggx{at(i).ax, at(i).ay};
    const V3 wi = incidence(at(i).theta_deg);
    full_cap.cases.push_back(replanned(
        i, "with k = 1", [ggx, wi](const V3& wo) { return pdf_spherical_caps(ggx, wi, wo); }));
  }
  out.push_back(full_cap);

  // i_z < 0: the stable form D(m)(t − i_z)/(2 len2) of Listing 2 with the sign of i_z flipped.
  GofControl sign{"sign of i_z flipped in Listing 2's back-facing form", {}, true};
  for (int i : {back, back2}) {
    const GGX<double> ggx{at(i).ax, at(i).ay};
    const V3 wi = incidence(at(i).theta_deg);
    sign.cases.push_back(replanned(i, "with (t + i_z)", [ggx, wi](const V3& wo) {
      const double s2 = ggx.sigma2(wi), t = std::sqrt(s2 + wi.z * wi.z);
      return ggx.D(half_vector(wi, wo)) * (t + wi.z) / (2 * s2);
    }));
  }
  out.push_back(sign);

  // ‖dm/do‖ = 1/(4|i·m|) dropped: p_our(m) taken as the density of ωo.
  GofControl jacobian{"‖dm/do‖ = 1/(4|i·m|) dropped", {}, true};
  for (int i : {iso, aniso}) {
    const GGX<double> ggx{at(i).ax, at(i).ay};
    const V3 wi = incidence(at(i).theta_deg);
    const Eq8ReflectionPdf pdf(ggx, wi, at(i).bound);
    jacobian.cases.push_back(replanned(
        i, "without ‖dm/do‖",
        [pdf, wi](const V3& wo) { return pdf(wo) * 2 * length(wi + wo); },
        [rows = pdf.rows(), wi](std::span<const V3> wo, std::span<double> density) {
          rows(wo, density);
          for (std::size_t r = 0; r < wo.size(); ++r)
            density[r] = density[r] * 2 * length(wi + wo[r]);
        }));
  }
  out.push_back(jacobian);
  return out;
}

// Quick: 10^5 samples per configuration (≤ 600 fine bins), subtle controls at 5·10^5 (λ ≈ 200 for a
// 2 % error). Full: 10^7.
constexpr GofSize kQuick{100'000, 500'000, 600};
constexpr GofSize kFull{10'000'000, 10'000'000, 4096};
// The tests' probe: the quick grid's configurations that its controls are built on, at 3·10^4
// samples; the subtle controls at the quick budget's 5·10^5 (at 3·10^5 the sampler's α × 1.02 at
// α = 1.5, θi = 89° (Listing 2) was seen kept, p = 3·10^-5 against a first Holm level of 1.1e-5).
constexpr GofSize kProbe{30'000, 500'000, 500};
std::vector<Config> probe_grid() {
  const std::vector<Config> g = grid(Budget::kQuick);
  return configurations_under_controls(g, controls(g));
}

GofSpec spec_of(const std::vector<Config>& g) { return gof_spec(g, make_case, controls(g)); }

// The detail line, from the grid, the family's outcome and the controls' verdicts alone.
std::string describe_family(const std::vector<Config>& g, const std::vector<GofCase>& cases,
                            const GofOutcome& o, const std::vector<GofControl>& ctl,
                            const GofControlVerdicts& cv, const CheckResult& r, std::size_t worst) {
  // How many configurations each form and bound has.
  std::string forms;
  for (Form f : {Form::kEq8, Form::kListing2})
    for (BoundedVndfBound bound :
         {BoundedVndfBound::kListing1, BoundedVndfBound::kExactIsotropic}) {
      const auto n = std::count_if(
          g.begin(), g.end(), [&](const Config& c) { return c.form == f && c.bound == bound; });
      if (n > 0)
        forms += fmt::format(
            "{}{} {} with {}", forms.empty() ? "" : ", ", n,
            f == Form::kEq8 ? "Eq. 8 with χ⁺ over the sphere" : "Listing 2 over ωo_z > 0",
            bound_name(bound));
    }
  // What the controls say of Listing 2 taken over the whole sphere.
  std::string listing2;
  for (std::size_t c = 0; c < ctl.size(); ++c)
    if (ctl[c].name.starts_with("Listing 2 without χ⁺"))
      listing2 = fmt::format(
          ". Listing 2 taken as a density over the whole sphere: {} of {} case(s) caught",
          std::count(cv.cases[c].begin(), cv.cases[c].end(), Verdict::kFails), cv.cases[c].size());
  return fmt::format(
      "{} configurations ({}), {} samples each: {} rejected at family rate {:.2g}, {} "
      "inconclusive, {} hard failures; smallest raw p {:.3g} at {} ({}){}",
      g.size(), forms, o.results.empty() ? 0 : o.results[0].n, o.family.rejections, o.family.alpha,
      o.inconclusive, o.hard_failures, r.raw_p_values[worst], cases[worst].label,
      o.results[worst].summary(), listing2);
}

// One run of a known-correct configuration (Eq. 8, Listing-1 k, α = 0.3, θi = 0°) at quick size.
double calibration(std::uint64_t seed) {
  static const GofCase c = make_case({BoundedVndfBound::kListing1, 0.3, 0.3, 0, Form::kEq8});
  static const ChiSquarePlan plan = plan_gof_case(
      c, kQuick.n, sidak_level(check_level(), grid(Budget::kQuick).size()), kQuick.fine_max_bins);
  return run_gof_case(plan, c, seed).p_value;
}

}  // namespace

GofSpec eto_pdf_spec(Budget b) { return spec_of(grid(b)); }

namespace eto_claims {

struct PdfMatches : GofFamilyClaim<PdfMatches, Config> {
  static constexpr std::string_view kId = "eto.pdf-matches";
  static constexpr std::string_view kPaper = "Eto & Tokuyoshi 2023";
  static constexpr std::string_view kSource = "Eq. 8 (with χ⁺), Eq. 7 for i_z ≤ 0, Listing 2";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Sec. 3.3, Eq. 8: p_our(m) = 2D(m) max(i·m, 0) / (k i_z + √(α_x² i_x² + α_y² i_y² "
      "+ i_z²)) · χ⁺(k î_z + ô_z); \"By multiplying the above PDF p_our(m) by the "
      "Jacobian … ‖dm/do‖ = 1/(4|i·m|), we obtain the PDF for our reflection vector "
      "sampling p_our(m)‖dm/do‖.\" Listing 2 for i_z ≥ 0; Eq. 7 (\"the previous PDF\") "
      "for i_z < 0";
  static constexpr std::string_view kStatistic =
      "Holm–Šidák-corrected p of the chi-square of sampled ωo against Eq. 8 / Listing 2";
  // An earlier full-budget rejection at α = (0.1, 1), θi = 45° was the cubature's: it missed
  // 1.1e-5 of the mass beside −ωi (fixed by the closing breaks around point features,
  // verify/stats).
  static constexpr Expected kExpected{
      .quick = Verdict::kHolds,
      .full = Verdict::kInconclusive,
      .why_full_differs =
          "the full budget's 10^7 samples per configuration put a sample, in one of its 90 "
          "configurations (Listing-1 k at α = (1.5, 1.5), θi = 45°, where k = 0), in a bin where "
          "the cubature finds no support: the cap's edge is a curve of which the cubature misses "
          "a sliver of about 5.5e-7 of the mass, and such a configuration is undecided rather than "
          "rejected; the quick budget's 10^5 samples and 21 configurations do not reach it"};

  static Sizes sizes(Budget b) { return {grid(b), b == Budget::kQuick ? kQuick : kFull}; }
  static Sizes probe_sizes() { return {probe_grid(), kProbe}; }
  static GofSpec spec(const Sizes& z) { return spec_of(z.grid); }
  static std::string genuine_text(const Sizes& z, const GofSpec& spec, const GofOutcome& o,
                                  const GofControlVerdicts& cv, const CheckResult& family,
                                  std::size_t worst) {
    return describe_family(z.grid, spec.cases, o, spec.controls, cv, family, worst);
  }
  static double calibrate(std::uint64_t seed) { return calibration(seed); }
};

}  // namespace eto_claims
}  // namespace glintlab::verify

GLINTLAB_CLAIM(glintlab::verify::eto_claims::PdfMatches);

// kneiphof.subdivision — Kneiphof & Klein 2024, App. C, Eq. 33–39, Fig. 9.
//
// The paper, App. C: "This appendix proves that the result of our model does not change upon
// subdivision of the light source if the integrand of D_Ωh can be assumed proportional to the
// continuous BRDF"; Eq. 34: Σ_k b(N_P, p_Ωh^(k)) = b(N_P, p_Ωh); Fig. 9: "With our assumption, the
// method becomes invariant to the size of the light source."
//
// Measured: a square light above the shading point split into 2^4 × 2^4 sub-lights, p_k by Monte
// Carlo D_Ωh of each (Eq. 33). Per draw, b ~ Binomial(N_P, p) split multinomially over the parts:
// Σ b_k and the three largest marginals b_k tested against their binomials (Holm–Šidák over every
// test at the suite's level), and the radiance with the shared lobe (L^(k) ∝ D_Ωh^(k), Eq. 32)
// summed over the parts against the single light's (Eq. 16/39), held to 1e-12 of L_o. Beside it:
// the Monte Carlo terms per part (Fig. 9 left, not claimed invariant).
// Control (perturbed), one for each half of the decision, failing only when both do: b drawn
// from Binomial(N_P, 1.05 p) (the counts); each sub-light's share of the lobe × (1 ± 2 %),
// alternating (the radiance).
// Regime: none.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "core/glints/binomial.h"
#include "core/glints/kneiphof.h"
#include "core/lights/polygon_light_check.h"
#include "core/ndf/ggx.h"
#include "core/ndf/total_area.h"
#include "verify/claim_runner.h"
#include "verify/claims/gof_family.h"
#include "verify/claims/kneiphof/common.h"
#include "verify/stats/chi_square.h"
#include "verify/stats/count_tests.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::kneiphof_claims {
namespace {

// A rectangle of half-width `w` centred at height 1 above the shading point, offset along x; the
// viewer at θ = 30° opposite. p_k by Monte Carlo D_Ωh of each of the 2^4 × 2^4 sub-lights (Eq. 33),
// p = Σ p_k (so the parts partition Ω_h exactly).
struct SubdivisionScene {
  double alpha, w;
  std::uint64_t n;                // N_P
  std::vector<double> p_k, lo_k;  // per sub-light p and L_o/L_i (Monte Carlo terms)
  double p = 0, lo = 0;           // whole light: Σ p_k, and its own L_o/L_i (Monte Carlo)
  double d_omega_h = 0;
};

SubdivisionScene subdivision_scene(double alpha, double w, std::uint64_t n, int samples,
                                   std::uint64_t seed) {
  SubdivisionScene s{alpha, w, n, {}, {}};
  const GGX<double> g{alpha, alpha};
  const double dh = total_area_ggx_eq29(alpha);
  const auto quad = quad_above(w);
  const auto parts = kneiphof2024::subdivide_quad(quad, 16, 16);
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const auto light = make_polygon_light(std::span<const Vec3<double>>(parts[k]), {1, 1, 1});
    const kneiphof2024::AreaLightTerms t = kneiphof2024::area_light_terms_mc(
        g, view_30(), light, Vec3<double>{0, 0, 0}, samples, seed, k);
    s.p_k.push_back(t.d_omega_h / dh);
    s.lo_k.push_back(t.lo_over_li);
    s.p += t.d_omega_h / dh;
    s.d_omega_h += t.d_omega_h;
  }
  const auto whole = make_polygon_light(std::span<const Vec3<double>>(quad), {1, 1, 1});
  s.lo = kneiphof2024::area_light_terms_mc(g, view_30(), whole, Vec3<double>{0, 0, 0}, samples * 64,
                                           seed, 1u << 20)
             .lo_over_li;
  return s;
}

struct SubdivisionRun {
  PearsonResult sum_test;          // Σ b_k against Binomial(N_P, p)
  std::vector<double> marginal_p;  // b_k against Binomial(N_P, p_k), a few k
  double shared_lobe_error = 0;  // max rel. |Σ_k L^(k) b_k/(N p_k) − L b/(N p)|, L^(k) ∝ D^(k)
  double mc_error = 0;           // RMS rel. difference with the Monte Carlo L_o^(k)
  double lobe_control_error = 0;  // control: the lobe shares L^(k) 2 % off, alternating in sign
};

// The control of the shared lobe: each sub-light's share of it × (1 ± kLobeShareBias), the sign
// alternating over the sub-lights (a lobe nearly, not exactly, shared).
constexpr double kLobeShareBias = 0.02;

// control: b drawn from Binomial(N_P, 1.05 p).
SubdivisionRun subdivision_run(const SubdivisionScene& s, std::uint64_t seed, int draws,
                               bool control) {
  SubdivisionRun r;
  std::vector<std::uint64_t> sums(static_cast<std::size_t>(draws));
  std::vector<std::vector<std::uint64_t>> marg(3, std::vector<std::uint64_t>(std::size_t(draws)));
  // The three largest parts, where the marginal tests have power.
  std::vector<std::size_t> order(s.p_k.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::partial_sort(order.begin(), order.begin() + 3, order.end(),
                    [&](std::size_t a, std::size_t b) { return s.p_k[a] > s.p_k[b]; });
  double mc2 = 0;
  const double nd = double(s.n);
  for (int d = 0; d < draws; ++d) {
    const std::uint64_t b =
        binomial_exact(s.n, std::min(1.0, control ? 1.05 * s.p : s.p), seed, std::uint64_t(d));
    const auto bk = kneiphof2024::multinomial_split(b, s.p_k, seed + 1, std::uint64_t(d));
    std::uint64_t sum = 0;
    double shared = 0, mc = 0, lobe_control = 0;
    for (std::size_t k = 0; k < bk.size(); ++k) {
      sum += bk[k];
      if (s.p_k[k] <= 0) continue;
      const double lk = s.lo * s.p_k[k] / s.p;  // Eq. 32: L^(k) ∝ ∫_Ωh^(k) D, the shared lobe
      shared += lk * double(bk[k]) / (nd * s.p_k[k]);
      mc += s.lo_k[k] * double(bk[k]) / (nd * s.p_k[k]);
      const double off = 1 + (k % 2 ? -kLobeShareBias : kLobeShareBias);
      lobe_control += off * lk * double(bk[k]) / (nd * s.p_k[k]);
    }
    sums[std::size_t(d)] = sum;
    for (int j = 0; j < 3; ++j) marg[std::size_t(j)][std::size_t(d)] = bk[order[std::size_t(j)]];
    const double single = s.lo * double(b) / (nd * s.p);  // Eq. 16 (Eq. 39)
    const double scale = s.lo;  // errors relative to L_o (single is 0 where b = 0)
    r.shared_lobe_error = std::max(r.shared_lobe_error, std::abs(shared - single) / scale);
    r.lobe_control_error = std::max(r.lobe_control_error, std::abs(lobe_control - single) / scale);
    mc2 += (mc - single) * (mc - single) / (scale * scale);
  }
  r.mc_error = std::sqrt(mc2 / draws);
  r.sum_test = binomial_counts_test(sums, s.n, s.p);
  for (int j = 0; j < 3; ++j)
    r.marginal_p.push_back(
        binomial_counts_test(marg[std::size_t(j)], s.n, s.p_k[order[std::size_t(j)]]).p_value);
  return r;
}

constexpr double kSharedLobeTolerance = 1e-12;  // exact up to rounding (Eq. 35–39)

struct SubdivisionConfig {
  double alpha, w;
  std::uint64_t n;
};

// Holds when no count test rejects at the Holm–Šidák level and the shared lobe's radiance is
// within the tolerance.
Verdict counts_and_radiance(const std::vector<double>& p, double shared_error) {
  return correct_family(p).hs.rejections == 0 && shared_error <= kSharedLobeTolerance
             ? Verdict::kHolds
             : Verdict::kFails;
}

}  // namespace

struct Subdivision {
  static constexpr std::string_view kId = "kneiphof.subdivision";
  static constexpr std::string_view kPaper = kneiphof_claims::kPaper;
  static constexpr std::string_view kSource = "App. C, Eq. 33–39, Fig. 9";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "App. C: \"This appendix proves that the result of our model does not change upon "
      "subdivision of the light source if the integrand of D_Ωh can be assumed "
      "proportional to the continuous BRDF\"; Eq. 34: Σ_k b(N_P, p_Ωh^(k)) = b(N_P, "
      "p_Ωh); Fig. 9: \"With our assumption, the method becomes invariant to the size "
      "of the light source.\"";
  static constexpr std::string_view kStatistic =
      "max relative radiance difference, 1 vs 256 sub-lights with the shared lobe (Eq. 32); the "
      "counts (Σ b_k and three marginals b_k vs Binomial) decided by their Holm–Šidák adjusted "
      "p-value";
  static constexpr Expected kExpected{.quick = Verdict::kHolds};

  struct Sizes {
    std::vector<SubdivisionConfig> lights;  // α, half-width, N_P
    int samples;                            // Monte Carlo samples per sub-light
    int draws;                              // of b per light
  };
  static Sizes sizes(Budget b) {
    Sizes z{{{0.25, 0.5, 2000}, {0.25, 0.05, 200000}, {0.81, 0.5, 2000}}, 16, 4000};
    if (b == Budget::kFull) {
      z.lights.insert(z.lights.end(), {{0.01, 0.05, 20000}, {0.81, 0.05, 200000}});
      z.samples = 64, z.draws = 40000;
    }
    return z;
  }
  static Sizes probe_sizes() { return {{{0.25, 0.5, 2000}}, 4, 2000}; }

  // One light: its parts, the genuine draws, and the biased counts' draws (independent streams).
  struct Evidence {
    SubdivisionScene scene;
    SubdivisionRun run, control;
  };
  static int configurations(const Sizes& z) { return int(z.lights.size()); }
  static Evidence observe(const Sizes& z, int k, std::uint64_t) {
    const SubdivisionConfig& c = z.lights[std::size_t(k)];
    const std::string id(kId);
    const std::uint64_t i = std::uint64_t(k);
    Evidence e;
    e.scene = subdivision_scene(c.alpha, c.w, c.n, z.samples, check_seed(id, 3 * i));
    e.run = subdivision_run(e.scene, check_seed(id, 3 * i + 1), z.draws, false);
    e.control = subdivision_run(e.scene, check_seed(id, 3 * i + 2), z.draws, true);
    return e;
  }

  struct Measured {
    Input input = Input::kGenuine;
    std::vector<double> p, p_control;  // p_control: each Σ b_k test replaced by the control's
    double shared = 0, lobe_min = 1e300, lobe_max = 0, control_min_p = 1, dof = 0;
    std::string mc;
    std::vector<double> light_p, light_n;  // each light's p and N_P
  };
  static Measured measure(const Sizes& z, std::span<const Evidence> all, Input input) {
    Measured m;
    m.input = input;
    for (std::size_t i = 0; i < all.size(); ++i) {
      const SubdivisionRun &run = all[i].run, &control = all[i].control;
      m.p.push_back(run.sum_test.p_value);
      m.p_control.push_back(control.sum_test.p_value);
      for (double q : run.marginal_p) m.p.push_back(q), m.p_control.push_back(q);
      m.lobe_max = std::max(m.lobe_max, run.lobe_control_error);
      m.shared = std::max(m.shared, run.shared_lobe_error);
      m.lobe_min = std::min(m.lobe_min, run.lobe_control_error);
      m.dof = std::max(m.dof, run.sum_test.dof);
      m.control_min_p = std::min(m.control_min_p, control.sum_test.p_value);
      m.mc += fmt::format("{}α={} half-width {}: p = {:.3g}, RMS {:.3g}", m.mc.empty() ? "" : "; ",
                          z.lights[i].alpha, z.lights[i].w, all[i].scene.p, run.mc_error);
      m.light_p.push_back(all[i].scene.p), m.light_n.push_back(double(all[i].scene.n));
    }
    return m;
  }

  // The perturbed input's verdict: its counts half (the biased counts with the genuine radiance)
  // where that does not fail, else its radiance half (the genuine counts with the biased shares).
  static Verdict counts_control(const Measured& m) {
    return counts_and_radiance(m.p_control, m.shared);
  }
  static Verdict lobe_control(const Measured& m) { return counts_and_radiance(m.p, m.lobe_max); }

  static Decision decide(const Sizes&, const Measured& m) {
    if (m.input != Input::kGenuine) {
      const Verdict counts = counts_control(m);
      return {.verdict = counts == Verdict::kFails ? lobe_control(m) : counts,
              .p_value = m.control_min_p};
    }
    const Family f = correct_family(m.p);
    return {.verdict = counts_and_radiance(m.p, m.shared),
            .value = m.shared,
            .bound = kSharedLobeTolerance,
            .p_value = f.min_adjusted,
            .raw_p_values = f.hs.raw,
            .configurations = int(m.light_p.size())};
  }

  static std::string describe(const Sizes& z, const Measured& m, Input input) {
    if (input != Input::kGenuine)
      return fmt::format(
          "b from Binomial(N_P, 1.05 p): smallest p = {:.3g} → {}; the shared lobe's share of "
          "each sub-light × (1 ± {}) (alternating): radiance difference {:.3g} .. {:.3g} of L_o",
          m.control_min_p, to_string(counts_control(m)), kLobeShareBias, m.lobe_min, m.lobe_max);
    return fmt::format(
        "2^4×2^4 sub-lights, {} draws per configuration, {} MC samples per sub-light; counts: {} "
        "of {} tests rejected at level {:.2g}; shared lobe (L^(k) ∝ D_Ωh^(k), Eq. 32): max |Σ_k "
        "− single|/L_o = {:.2g}; Monte Carlo terms (Fig. 9 left, not claimed invariant): {}",
        z.draws, z.samples, correct_family(m.p).hs.rejections, m.p.size(), check_level(), m.shared,
        m.mc);
  }

  // A shift of Σ b_k's mean by δ standard deviations gives the histogram test a non-centrality
  // ≈ draws·δ² (the binomial is near normal at these N_P p); that δ is a relative error of p of
  // δ √((1 − p)/(N_P p)).
  static std::string power(const Sizes& z, const Measured& m, const Measured&) {
    const double sd_shift =
        std::sqrt(min_detectable_noncentrality(m.dof, sidak_level(check_level(), m.p.size()), 0.9) /
                  double(z.draws));
    double p_rel = 0;
    for (std::size_t i = 0; i < m.light_p.size(); ++i)
      p_rel =
          std::max(p_rel, sd_shift * std::sqrt((1 - m.light_p[i]) / (m.light_n[i] * m.light_p[i])));
    return fmt::format(
        "counts: a shift of the mean of Σ b_k by {:.2g} standard deviations over {} draws (a "
        "relative error of p of at most {:.2g} % in these configurations) is detected with 90 % "
        "power at the first Holm–Šidák step (χ² with up to {} dof); radiance: any difference "
        "above 1e-12 of L_o (deterministic)",
        sd_shift, z.draws, 100 * p_rel, m.dof);
  }

  // One raw p of Σ b_k on the genuine counts (α = 0.25, half-width 0.5, N_P = 2000).
  static double calibrate(std::uint64_t seed) {
    const SubdivisionScene s = subdivision_scene(0.25, 0.5, 2000, 4, seed);
    return subdivision_run(s, seed + 7, 1000, false).sum_test.p_value;
  }
};

}  // namespace glintlab::verify::kneiphof_claims

GLINTLAB_CLAIM(glintlab::verify::kneiphof_claims::Subdivision);

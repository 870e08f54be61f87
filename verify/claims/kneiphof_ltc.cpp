// Claim kneiphof.ltc-probability of Kneiphof & Klein 2024 (Sec. 4, Sec. 7, Figs. 7–8, Eq. 12–19):
// the BRDF's LTC lobe scaled by D_PR in place of D_Ωh = ∫_Ωh D dh = ∫_Ωi D/(4⟨h, ω⟩) dω (Eq. 13)
// over a polygonal light makes a difference that is "measurable but visually negligible". The
// verdict is on the rendered pixel L̂ = L_o·b/(N_P p) (Eq. 16) with the LTC p against the same pixel
// with a converged Monte Carlo p, held to the Weber fraction; the probability itself held to 10 %
// is reported as the stronger reading, and the project's LTC fit is checked against an independent
// fit at the exact roughness and view angle, and its polygon integral against brute force.
#include "core/glints/kneiphof_ltc.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/glints/kneiphof.h"
#include "core/ltc/ltc_fit.h"
#include "core/ltc/ltc_table.h"
#include "core/ndf/total_area.h"
#include "verify/claims/claims.h"
#include "verify/claims/kneiphof_ltc_probe.h"

namespace glintlab::verify {
namespace {

const char* const kLtcProbability = "kneiphof.ltc-probability";

// Relative tolerance on p (as kneiphof.cap-probability holds Eq. 20 to): fixed before measuring.
constexpr double kTolerance = 0.1;
// A light catching less than this fraction of the potentially reflecting area D_PR is in the
// lobe's tail, where a relative error says little about glints: reported apart.
constexpr double kTailFraction = 1e-3;
constexpr int kBatches = 16;  // independent Monte Carlo batches: the reference's standard error
constexpr double kNearTruthBias = 0.03;

// The rendered difference (fixed before measuring). A pixel of N_P facets renders
// L̂ = L_o·b/(N_P p), b ~ Binomial(N_P, min(p, 1)) (Eq. 16); L_o is common to the images compared
// (Fig. 8 uses the LTC L_o throughout), so the pixel's mean and fluctuation relative to L_o depend
// on p and N_P alone. Two renderings are visually the same when neither the mean nor the standard
// deviation of the pixel moves by more than the Weber fraction of the mean: 2 %, the threshold the
// project uses for a seen change of mean or fluctuation (docs/adequacy.md, "Why 0.02").
constexpr double kVisualTolerance = 0.02;
// Glint densities: λ = N_P·p_MC, the expected number of reflecting facets per pixel, from sparse
// glints (one per pixel) to a nearly converged highlight (Fig. 10); every one is in the regime.
constexpr std::array<double, 4> kGlintsPerPixel = {1, 10, 100, 1000};
// The rendered control where the claim holds: the LTC pixel rendered 4 % brighter (near the truth,
// beyond the 2 % tolerance), through the same rule.
constexpr double kBrighterRender = 1.04;
// The independent fit (below): compass search on the L1 objective: its grid, and its objective
// evaluations per lobe (quick, full).
constexpr int kRefitSamples = 24;
constexpr int kRefitEvaluationsQuick = 80, kRefitEvaluationsFull = 240;
// The fit cause of the probability-level error is excluded when, with the independent fit in the
// table's place, a regime cell is still beyond the 10 % tolerance by 3 SE (the error is then the
// LTC family's, which no fit removes); fixed before measuring (compare_fits, run).

// The regime, declared before measuring: the abstract assigns LTCs to "large light sources"
// (and spherical caps to small ones, Sec. 5), and the glints that matter sit in the highlight:
// lights of side ≥ 0.5 at distance 1 (≥ 28° across) centred on the mirror direction, every √α and
// view angle of the grid, cells outside the lobe's tail.
constexpr double kRegimeMinSide = 0.5;
constexpr const char* kRegime =
    "square light of side ≥ 0.5 at distance 1 (≥ 28° across: the abstract's 'large light "
    "sources'), centred on the mirror direction, every √α 0.1..0.9 and θv 0..85° of the grid, "
    "p_MC ≥ 1e-3 D_PR";

struct Config {
  double side, sqrt_alpha, theta_v_deg;
  int position;  // 0: centred on the mirror direction of the view, 1: overhead (on the normal)
};

struct Cell {
  Config c;
  double ref = 0, ref_se = 0;  // Monte Carlo D_Ωh and its standard error
  double brdf = 0, ndf = 0;    // D_PR × ∫ D_ltc, BRDF lobe (the paper's) and NDF lobe
  double albedo_scaled = 0;    // control: the BRDF lobe scaled by its albedo FGD (no D_PR)
  double wrong_alpha = 0;      // control: the BRDF lobe looked up at 2α
  double near_truth = 0;       // control: an independent Monte Carlo D_Ωh × 1.03
  double d_pr = 0;
  double d_h = 0;  // D_H (Eq. 29): p = D_Ωh / D_H
  bool tail = false;
  // Regime cells only: the independent fits' D_Ωh (exact D_PR × the refitted lobe's polygon
  // integral) and the brute-force integral of the table's BRDF lobe over the light.
  bool refit = false;
  double brdf_indep = 0, ndf_indep = 0;
  double brdf_shape = 0, brdf_shape_mc = 0, brdf_shape_mc_se = 0, brdf_shape_above = 0;
};

Vec3<double> view_dir(double theta_v_deg) {
  const double t = theta_v_deg * std::numbers::pi / 180;
  return {-std::sin(t), 0, std::cos(t)};
}

// The square light of side `side` at distance 1, facing the shading point (origin).
std::array<Vec3<double>, 4> light_square(const Config& c) {
  const Vec3<double> wi = view_dir(c.theta_v_deg);
  const Vec3<double> dir =
      c.position == 0 ? Vec3<double>{-wi.x, -wi.y, wi.z} : Vec3<double>{0, 0, 1};
  return kneiphof2024::facing_rectangle(dir, 1.0, c.side, c.side, 0.0, 0.0);
}

// Monte Carlo D_Ωh and its standard error for one cell.
std::pair<double, double> mc_reference(const Config& c, int samples, std::uint64_t seed,
                                       std::uint64_t index) {
  double ref = 0, ref_se = 0;
  const double a = c.sqrt_alpha * c.sqrt_alpha;
  const GGX<double> g{a, a};
  const Vec3<double> wi = view_dir(c.theta_v_deg);
  const auto quad = light_square(c);
  const PolygonLight<double> light = kneiphof2024::rectangle_polygon_light(quad);
  // Two independent unbiased estimates of D_Ωh, combined by inverse variance: uniform solid-angle
  // samples of the light (efficient for a light small against the lobe) and half vectors drawn
  // from D cos θ_h (Walter et al. 2007 Eq. 35) counted where their reflection of ω_v hits the
  // light: ∫_Ωh D dh = E[1_Ωh(h)/cos θ_h] (efficient for a large light and a narrow lobe).
  double s = 0, s2 = 0, t = 0, t2 = 0;
  for (int k = 0; k < kBatches; ++k) {
    const std::uint64_t batch = index * kBatches + std::uint64_t(k);
    const double d =
        kneiphof2024::area_light_terms_mc(g, wi, light, Vec3<double>{0, 0, 0}, samples, seed, batch)
            .d_omega_h;
    s += d, s2 += d * d;
    double e = 0;
    for (int j = 0; j < samples; ++j) {
      const double u1 = (j + counter_uniform<double>(seed + 1, batch, 2 * std::uint64_t(j))) /
                        samples;  // stratified in cos θ_h
      const double u2 = counter_uniform<double>(seed + 1, batch, 2 * std::uint64_t(j) + 1);
      const double c2 = (1 - u1) / (1 + (a * a - 1) * u1);
      const double ch = std::sqrt(c2), sh = std::sqrt(std::max(0.0, 1 - c2));
      const double ph = 2 * std::numbers::pi * u2;
      const Vec3<double> h{sh * std::cos(ph), sh * std::sin(ph), ch};
      if (!(dot(wi, h) > 0) || !(ch > 0)) continue;
      const Vec3<double> w = reflect(wi, h);
      detail::PlaneHit<double> hit;
      if (w.z > 0 && light.hits(Vec3<double>{0, 0, 0}, w, &hit)) e += 1 / ch;
    }
    e /= samples;
    t += e, t2 += e * e;
  }
  const double ms = s / kBatches, mt = t / kBatches;
  const double vs = std::max(0.0, s2 / kBatches - ms * ms) / (kBatches - 1);
  const double vt = std::max(0.0, t2 / kBatches - mt * mt) / (kBatches - 1);
  if (vs > 0 && vt > 0) {
    ref = (ms / vs + mt / vt) / (1 / vs + 1 / vt);
    ref_se = std::sqrt(1 / (1 / vs + 1 / vt));
  } else {  // one estimator has no spread (e.g. no half vector hit): the light samples alone
    ref = ms;
    ref_se = std::sqrt(vs);
  }
  return {ref, ref_se};
}

// The table's unrotated coefficients of M⁻¹ bilinearly interpolated at √α and θ, as
// ltc_ggx_lookup reads them.
LtcCoefficients table_coefficients(LtcTarget target, double alpha, double theta) {
  const LtcTableView& t = ltc_ggx_table_view();
  const auto cell = detail::ltc_cell(t.size, std::sqrt(alpha), theta);
  const bool ndf = target == LtcTarget::kNdf;
  const auto k = [&](int i) {
    return detail::ltc_bilinear(ndf ? t.ndf : t.brdf, ndf ? 5 : 6, i, t.size, cell);
  };
  return {k(0), k(1), k(2), k(3)};
}

// The independent fit: at the exact α and θ (no table interpolation), the lobe minimizing the L1
// distance ∫ |f̂ − D_ltc| dω to the normalized target (the table minimizes the L3 distance) by a
// compass search over the four coefficients of M⁻¹ directly (the table's fit: Nelder–Mead over a
// factorized M). It starts from the table's interpolated entry, so it is never worse than the
// table in L1 at that point.
LtcCoefficients independent_fit(LtcTarget target, double alpha, double theta, int evaluations) {
  LtcCoefficients best = table_coefficients(target, alpha, theta);
  auto at = [&](const LtcCoefficients& c) {
    return ltc_fit_l1_error(target, alpha, theta, c, kRefitSamples);
  };
  double f = at(best);
  std::array<double, 4> step = {
      0.1 * (std::abs(best.m00) + 0.05), 0.1 * (std::abs(best.m02) + 0.05),
      0.1 * (std::abs(best.m20) + 0.05), 0.1 * (std::abs(best.m22) + 0.05)};
  int spent = 1;
  while (spent < evaluations && step[0] > 1e-5) {
    bool improved = false;
    for (int i = 0; i < 4 && spent < evaluations; ++i)
      for (double sign : {1.0, -1.0}) {
        LtcCoefficients trial = best;
        double* v[4] = {&trial.m00, &trial.m02, &trial.m20, &trial.m22};
        *v[i] += sign * step[std::size_t(i)];
        const double g = at(trial);
        ++spent;
        if (g < f) {
          best = trial, f = g, improved = true;
          break;
        }
      }
    if (!improved)
      for (double& s : step) s *= 0.5;
  }
  return best;
}

// The polygon integral of a lobe given by unrotated coefficients, turned to the view wi.
double lobe_integral(const LtcCoefficients& c, Vec3<double> wi,
                     const std::array<Vec3<double>, 4>& quad) {
  const LtcLobe<double> lobe =
      ltc_rotate_to_view(make_ltc_lobe_isotropic(c.m00, c.m02, c.m20, c.m22, 1.0), wi);
  return ltc_polygon_integral(lobe, quad.data(), 4);
}

// Brute force for the table's BRDF lobe over the light: the fraction of its samples (Heitz et al.
// 2016 Sec. 3.1) that hit the light, with its standard error, and the fraction that hit it above
// the horizon. The closed form clips the transformed polygon to the cosine's hemisphere (Heitz et
// al. 2016 Sec. 3.2), so it counts the lobe's part of a light that reaches below the surface's
// horizon: it is compared with the first, and the second gives that part's size.
struct LobeIntegralMc {
  double all, all_se, above;
};
LobeIntegralMc lobe_integral_mc(const LtcCoefficients& c, Vec3<double> wi,
                                const PolygonLight<double>& light, int samples, std::uint64_t seed,
                                std::uint64_t index) {
  const LtcLobe<double> lobe =
      ltc_rotate_to_view(make_ltc_lobe_isotropic(c.m00, c.m02, c.m20, c.m22, 1.0), wi);
  int hits = 0, above = 0;
  for (int j = 0; j < samples; ++j) {
    const Vec2<double> u{counter_uniform<double>(seed, index, 2 * std::uint64_t(j)),
                         counter_uniform<double>(seed, index, 2 * std::uint64_t(j) + 1)};
    const Vec3<double> w = ltc_sample(lobe, u).dir;
    detail::PlaneHit<double> hit;
    if (light.hits(Vec3<double>{0, 0, 0}, w, &hit)) ++hits, above += w.z > 0;
  }
  const double m = double(hits) / samples;
  return {m, std::sqrt(std::max(m * (1 - m), 0.0) / samples), double(above) / samples};
}

// The independent fits at one (√α, θv) of the regime, shared by its light sizes.
struct Refit {
  LtcCoefficients brdf, ndf;
  double d_pr;  // exact (ggx_d_pr), not interpolated
};
Refit refit_at(double sqrt_alpha, double theta_v_deg, int evaluations) {
  const double a = sqrt_alpha * sqrt_alpha, theta = theta_v_deg * std::numbers::pi / 180;
  return {independent_fit(LtcTarget::kBrdf, a, theta, evaluations),
          independent_fit(LtcTarget::kNdf, a, theta, evaluations),
          ggx_d_pr(a, std::max(std::cos(theta), kLtcMinCosTheta))};
}

Cell evaluate(const Config& c, int samples, std::uint64_t seed, std::uint64_t index,
              const Refit* refit = nullptr) {
  Cell r{c};
  const double a = c.sqrt_alpha * c.sqrt_alpha;
  const Vec3<double> wi = view_dir(c.theta_v_deg);
  const auto quad = light_square(c);
  std::tie(r.ref, r.ref_se) = mc_reference(c, samples, seed, index);
  const LtcTableView& table = ltc_ggx_table_view();
  const auto brdf = kneiphof2024::area_light_terms_ltc(table, a, wi, quad.data(), 4,
                                                       kneiphof2024::AreaP::kBrdfLobe);
  r.brdf = brdf.d_omega_h;
  r.d_pr = brdf.d_pr;
  r.ndf = kneiphof2024::area_light_terms_ltc(table, a, wi, quad.data(), 4,
                                             kneiphof2024::AreaP::kNdfLobe)
              .d_omega_h;
  r.albedo_scaled = kneiphof2024::area_light_terms_ltc(table, a, wi, quad.data(), 4,
                                                       kneiphof2024::AreaP::kBrdfLobe, brdf.albedo)
                        .d_omega_h;
  r.wrong_alpha = kneiphof2024::area_light_terms_ltc(table, std::min(1.0, 2 * a), wi, quad.data(),
                                                     4, kneiphof2024::AreaP::kBrdfLobe)
                      .d_omega_h;
  r.tail = r.ref < kTailFraction * r.d_pr;
  r.d_h = total_area_ggx_eq29(a);
  r.refit = refit != nullptr && !r.tail;
  if (r.refit) {
    const double theta = c.theta_v_deg * std::numbers::pi / 180;
    r.brdf_indep = refit->d_pr * lobe_integral(refit->brdf, wi, quad);
    r.ndf_indep = refit->d_pr * lobe_integral(refit->ndf, wi, quad);
    const LtcCoefficients table_brdf = table_coefficients(LtcTarget::kBrdf, a, theta);
    r.brdf_shape = lobe_integral(table_brdf, wi, quad);
    const LobeIntegralMc mc =
        lobe_integral_mc(table_brdf, wi, kneiphof2024::rectangle_polygon_light(quad),
                         kBatches * samples, seed + 3, index);
    r.brdf_shape_mc = mc.all, r.brdf_shape_mc_se = mc.all_se, r.brdf_shape_above = mc.above;
  }
  // The control's near-truth p: the same Monte Carlo estimator, independent seeds, × 1.03.
  // At most 8192 samples per batch: its own error stays far below the 7 % between 1.03 and the
  // tolerance, at an eighth of the full budget's cost.
  r.near_truth =
      (1 + kNearTruthBias) * mc_reference(c, std::min(samples, 8192), seed + 2, index).first;
  return r;
}

std::vector<Config> configs(Budget b) {
  const bool quick = b == Budget::kQuick;
  const std::vector<double> sides =
      quick ? std::vector<double>{0.05, 0.5, 2.0} : std::vector<double>{0.05, 0.2, 0.5, 1.0, 2.0};
  const std::vector<double> roughness = quick ? std::vector<double>{0.1, 0.5, 0.9}
                                              : std::vector<double>{0.1, 0.2, 0.3, 0.5, 0.7, 0.9};
  const std::vector<double> views =
      quick ? std::vector<double>{0, 40, 85} : std::vector<double>{0, 20, 40, 60, 75, 85};
  std::vector<Config> out;
  for (double s : sides)
    for (double sa : roughness)
      for (double v : views)
        for (int pos : {0, 1}) out.push_back({s, sa, v, pos});
  return out;
}

double rel_error(double got, const Cell& c) { return std::abs(got / c.ref - 1); }

// Where a relative error sits against the tolerance, given the reference's relative standard
// error: in (below tol by 3 σ), out (above by 3 σ) or undecided.
enum class Side { kIn, kOut, kUndecided };
Side side(double err, const Cell& c) {
  const double s = 3 * c.ref_se / c.ref;
  if (err + s <= kTolerance) return Side::kIn;
  if (err - s > kTolerance) return Side::kOut;
  return Side::kUndecided;
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// --- The rendered difference ---------------------------------------------------------------------

// The pixel's mean and standard deviation relative to L_o for N facets and probability p: the
// count uses min(p, 1) and so does the factor b/(N_P p) (core/glints/deliot_belcour.h), so the
// mean is L_o at any p; `brightness` scales the whole pixel (the control's brighter render).
struct Pixel {
  double mean, sd;
};
Pixel pixel(double p_raw, double n, double brightness) {
  const double p = std::clamp(p_raw, 1e-300, 1.0);
  return {brightness, brightness * std::sqrt((1 - p) / (n * p))};
}

// What one rendering of a cell puts in its pixel: the probability and the brightness scale.
struct Rendering {
  double p, brightness;
};

// The rendered difference against the Monte Carlo pixel with probability p_mc, at N facets:
// max(|Δ mean|, |Δ sd|) / mean.
double rendered_difference(Rendering x, double p_mc, double n) {
  const Pixel a = pixel(x.p, n, x.brightness), b = pixel(p_mc, n, 1.0);
  return std::max(std::abs(a.mean - b.mean), std::abs(a.sd - b.sd)) / b.mean;
}

// A cell's rendered difference at glint density λ, with the reference's ±3 SE band: N_P = λ/p_MC
// is the pixel's facet count (the same for every rendering), and p_MC runs over 9 points of the
// band; in when the largest difference is within the tolerance, out when the smallest is beyond.
struct RenderedDecision {
  double at_estimate, low, high;
};
RenderedDecision rendered_decision(Rendering x, const Cell& c, double lambda) {
  const double p_mc = c.ref / c.d_h, rse = c.ref_se / c.ref;
  const double n = std::max(1.0, lambda / p_mc);
  RenderedDecision d{rendered_difference(x, p_mc, n), INFINITY, 0};
  for (int k = -4; k <= 4; ++k) {
    const double e = rendered_difference(x, p_mc * (1 + 0.75 * k * rse), n);
    d.low = std::min(d.low, e), d.high = std::max(d.high, e);
  }
  return d;
}

struct RenderedSummary {
  int in = 0, out = 0, undecided = 0;
  double max = 0;
  Config worst{};
  double worst_lambda = 0;
  std::array<double, kGlintsPerPixel.size()> max_by_lambda{};
  std::array<int, kGlintsPerPixel.size()> not_in_by_lambda{};  // beyond or undecided, per λ
};

struct LobeSummary {
  int in = 0, out = 0, undecided = 0;
  double med = 0, max = 0;
  Config worst{};
  std::string by_axis;  // median error per light size, per √α, per view angle
  std::string out_list;
};

bool in_regime(const Cell& c) { return !c.tail && c.c.side >= kRegimeMinSide && c.c.position == 0; }

// Over the cells outside the tail (or the regime's only) and every density of kGlintsPerPixel.
template <class Get>
RenderedSummary summarize_rendered(const std::vector<Cell>& cells, Get get, bool regime_only,
                                   std::size_t first_density = 0) {
  RenderedSummary s;
  for (const Cell& c : cells) {
    if (c.tail || (regime_only && !in_regime(c))) continue;
    for (std::size_t k = first_density; k < kGlintsPerPixel.size(); ++k) {
      const RenderedDecision d = rendered_decision(get(c), c, kGlintsPerPixel[k]);
      s.max_by_lambda[k] = std::max(s.max_by_lambda[k], d.at_estimate);
      if (d.at_estimate > s.max)
        s.max = d.at_estimate, s.worst = c.c, s.worst_lambda = kGlintsPerPixel[k];
      if (d.high > kVisualTolerance) ++s.not_in_by_lambda[k];
      if (d.high <= kVisualTolerance)
        ++s.in;
      else if (d.low > kVisualTolerance)
        ++s.out;
      else
        ++s.undecided;
    }
  }
  return s;
}

template <class Get>
LobeSummary summarize(const std::vector<Cell>& cells, Get get, bool regime_only = false) {
  LobeSummary s;
  std::vector<double> all;
  std::vector<std::pair<std::string, std::vector<double>>> axes;
  auto add = [&](const std::string& key, double e) {
    for (auto& [k, v] : axes)
      if (k == key) return v.push_back(e);
    axes.push_back({key, {e}});
  };
  for (const Cell& c : cells) {
    if (c.tail || (regime_only && !in_regime(c))) continue;
    const double e = rel_error(get(c), c);
    all.push_back(e);
    if (e > s.max) s.max = e, s.worst = c.c;
    switch (side(e, c)) {
      case Side::kIn:
        ++s.in;
        break;
      case Side::kOut:
        ++s.out;
        break;
      case Side::kUndecided:
        ++s.undecided;
        break;
    }
    add(fmt::format("side {}", c.c.side), e);
    add(fmt::format("√α {}", c.c.sqrt_alpha), e);
    add(fmt::format("θv {}°", c.c.theta_v_deg), e);
    add(c.c.position == 0 ? "mirror" : "overhead", e);
  }
  s.med = median(all);
  for (const auto& [k, v] : axes)
    s.by_axis += fmt::format("{}{} {:.3g}", s.by_axis.empty() ? "" : ", ", k, median(v));
  return s;
}

std::string describe(const Config& c) {
  return fmt::format("side {} √α {} θv {}° {}", c.side, c.sqrt_alpha, c.theta_v_deg,
                     c.position == 0 ? "mirror" : "overhead");
}

// holds-within: every cell (outside the tail) within the tolerance by 3 SE; holds-in-regime:
// every cell of the regime within it, some outside not; fails: a cell of the regime beyond it by
// 3 SE; inconclusive: a regime cell undecided (its MC error straddles the tolerance).
template <class Summary>
Verdict verdict_of(const Summary& everywhere, const Summary& regime) {
  if (regime.in + regime.out + regime.undecided == 0) return Verdict::kInconclusive;
  if (regime.out > 0) return Verdict::kFails;
  if (regime.undecided > 0) return Verdict::kInconclusive;
  if (everywhere.out == 0 && everywhere.undecided == 0) return Verdict::kHoldsWithin;
  return Verdict::kHoldsInRegime;
}

template <class Get>
Verdict decide(const std::vector<Cell>& cells, Get get) {
  return verdict_of(summarize(cells, get), summarize(cells, get, true));
}

// The claim's decision: the rendered difference, by the same rule over (cell, density) pairs.
// first_density > 0 (tests only): the densities from kGlintsPerPixel[first_density] on.
template <class Get>
Verdict decide_rendered(const std::vector<Cell>& cells, Get get, std::size_t first_density = 0) {
  return verdict_of(summarize_rendered(cells, get, false, first_density),
                    summarize_rendered(cells, get, true, first_density));
}

std::string describe_rendered(const RenderedSummary& s) {
  std::string by;
  for (std::size_t k = 0; k < kGlintsPerPixel.size(); ++k)
    by += fmt::format("{}λ {:g}: {:.3g}", k ? ", " : "", kGlintsPerPixel[k], s.max_by_lambda[k]);
  return fmt::format(
      "max {:.3g} at {}, λ {:g}; within {} / beyond {} / undecided {} "
      "(cell, λ) pairs; max by λ: {}",
      s.max, s.in + s.out + s.undecided ? describe(s.worst) : "-", s.worst_lambda, s.in, s.out,
      s.undecided, by);
}

Rendering brdf_pixel(const Cell& c) { return {c.brdf / c.d_h, 1.0}; }
Rendering ndf_pixel(const Cell& c) { return {c.ndf / c.d_h, 1.0}; }
Rendering near_truth_pixel(const Cell& c) { return {c.near_truth / c.d_h, 1.0}; }
Rendering brighter_pixel(const Cell& c) { return {c.brdf / c.d_h, kBrighterRender}; }

// The independent fit beside the table's, over the regime cells: the probability-level error of
// D_PR × the lobe with each, and the polygon integral against brute force.
struct FitComparison {
  int cells = 0, beyond_table = 0, beyond_indep = 0, ndf_beyond_table = 0, ndf_beyond_indep = 0;
  double med_table = 0, med_indep = 0, max_table = 0, max_indep = 0;
  double ndf_med_table = 0, ndf_med_indep = 0, ndf_max_table = 0, ndf_max_indep = 0;
  double fit_share = 0;  // median over cells of (e_table − e_indep)/e_table for the BRDF lobe
  double polygon_max_z = 0, polygon_max_rel = 0;
  int polygon_beyond = 0;  // cells where closed form and brute force differ by more than 4 SE
  Config polygon_worst{};
  double polygon_worst_closed = 0, polygon_worst_mc = 0;
  double below_horizon_max = 0;  // the largest share of the lobe's light integral below the horizon
  Config below_horizon_worst{};
};

FitComparison compare_fits(const std::vector<Cell>& cells) {
  FitComparison f;
  std::vector<double> et, ei, nt, ni, share;
  for (const Cell& c : cells) {
    if (!c.refit || !in_regime(c)) continue;
    ++f.cells;
    const double a = rel_error(c.brdf, c), b = rel_error(c.brdf_indep, c);
    const double na = rel_error(c.ndf, c), nb = rel_error(c.ndf_indep, c);
    et.push_back(a), ei.push_back(b), nt.push_back(na), ni.push_back(nb);
    if (a > 0) share.push_back((a - b) / a);
    f.max_table = std::max(f.max_table, a), f.max_indep = std::max(f.max_indep, b);
    f.ndf_max_table = std::max(f.ndf_max_table, na),
    f.ndf_max_indep = std::max(f.ndf_max_indep, nb);
    f.beyond_table += side(a, c) == Side::kOut, f.beyond_indep += side(b, c) == Side::kOut;
    f.ndf_beyond_table += side(na, c) == Side::kOut,
        f.ndf_beyond_indep += side(nb, c) == Side::kOut;
    const double z =
        std::abs(c.brdf_shape - c.brdf_shape_mc) / std::max(c.brdf_shape_mc_se, 1e-300);
    if (z > f.polygon_max_z)
      f.polygon_max_z = z, f.polygon_worst = c.c, f.polygon_worst_closed = c.brdf_shape,
      f.polygon_worst_mc = c.brdf_shape_mc;
    if (c.brdf_shape_mc > 0)
      f.polygon_max_rel = std::max(f.polygon_max_rel, std::abs(c.brdf_shape / c.brdf_shape_mc - 1));
    f.polygon_beyond += z > 4;
    if (c.brdf_shape_mc > 0 && 1 - c.brdf_shape_above / c.brdf_shape_mc > f.below_horizon_max)
      f.below_horizon_max = 1 - c.brdf_shape_above / c.brdf_shape_mc, f.below_horizon_worst = c.c;
  }
  f.med_table = median(et), f.med_indep = median(ei);
  f.ndf_med_table = median(nt), f.ndf_med_indep = median(ni);
  f.fit_share = median(share);
  return f;
}

std::string describe_summary(const LobeSummary& s) {
  return fmt::format("median {:.3g}, max {:.3g} at {}; within {} / beyond {} / undecided {}", s.med,
                     s.max, s.in + s.out + s.undecided ? describe(s.worst) : "-", s.in, s.out,
                     s.undecided);
}

std::vector<Cell> run_cells(Budget b) {
  const auto cfg = configs(b);
  const int samples = b == Budget::kQuick ? 2048 : 65536;
  // The independent fits, once per (√α, θv) of the regime's cells (mirror, large lights).
  std::vector<std::pair<double, double>> keys;
  for (const Config& c : cfg)
    if (c.position == 0 && c.side >= kRegimeMinSide &&
        std::find(keys.begin(), keys.end(), std::pair{c.sqrt_alpha, c.theta_v_deg}) == keys.end())
      keys.push_back({c.sqrt_alpha, c.theta_v_deg});
  std::vector<Refit> refits(keys.size());
  const int evaluations = b == Budget::kQuick ? kRefitEvaluationsQuick : kRefitEvaluationsFull;
  tbb::parallel_for(std::size_t(0), keys.size(), [&](std::size_t i) {
    refits[i] = refit_at(keys[i].first, keys[i].second, evaluations);
  });
  std::vector<Cell> cells(cfg.size());
  const std::uint64_t seed = check_seed(kLtcProbability, 0);
  tbb::parallel_for(std::size_t(0), cfg.size(), [&](std::size_t i) {
    const Config& c = cfg[i];
    const Refit* refit = nullptr;
    if (c.position == 0 && c.side >= kRegimeMinSide)
      refit = &refits[std::size_t(
          std::find(keys.begin(), keys.end(), std::pair{c.sqrt_alpha, c.theta_v_deg}) -
          keys.begin())];
    cells[i] = evaluate(c, samples, seed, i, refit);
  });
  return cells;
}

CheckResult run(Budget b) {
  const std::vector<Cell> cells = run_cells(b);
  const auto get_brdf = [](const Cell& c) { return c.brdf; };
  const LobeSummary brdf = summarize(cells, get_brdf);
  const LobeSummary brdf_regime = summarize(cells, get_brdf, true);
  const LobeSummary ndf = summarize(cells, [](const Cell& c) { return c.ndf; });
  const LobeSummary scaled = summarize(cells, [](const Cell& c) { return c.albedo_scaled; });
  const RenderedSummary rendered = summarize_rendered(cells, brdf_pixel, false);
  const RenderedSummary rendered_regime = summarize_rendered(cells, brdf_pixel, true);
  const RenderedSummary rendered_ndf = summarize_rendered(cells, ndf_pixel, true);
  const FitComparison fits = compare_fits(cells);
  int tail = 0, regime_cells = 0;
  double tail_max = 0, worst_se = 0, regime_se = 0;
  for (const Cell& c : cells) {
    if (c.tail) {
      ++tail, tail_max = std::max(tail_max, rel_error(c.brdf, c));
      continue;
    }
    worst_se = std::max(worst_se, c.ref_se / c.ref);
    if (in_regime(c)) ++regime_cells, regime_se = std::max(regime_se, c.ref_se / c.ref);
  }
  CheckResult r;
  r.statistic =
      "max rendered difference max(|Δ mean|, |Δ sd|)/mean of the pixel L̂ = L_o·b/(N_P p) (Eq. 16) "
      "with p from the BRDF LTC lobe × D_PR (the paper's choice) against p from Monte Carlo D_Ωh, "
      "over the regime's cells and λ = N_P p_MC 1..1000 reflecting facets per pixel";
  r.configurations = int(cells.size());
  r.value = rendered_regime.max;
  r.bound = kVisualTolerance;
  // The declared rule's verdict stands only where the same rule holds a near-truth input (the
  // pixel with an independent Monte Carlo p × 1.03): where it does not, the rule cannot tell a
  // 3 % error from the truth, and its "fails" is not a finding (inconclusive). Added after the
  // first run showed the near-truth input beyond 2 % at λ 1 and 10 near p = 1, where the pixel's
  // fluctuation √((1 − p)/(N_P p)) moves fast with p; the regime and the tolerance are unchanged.
  const Verdict declared = verdict_of(rendered, rendered_regime);
  const RenderedSummary near_regime = summarize_rendered(cells, near_truth_pixel, true);
  const bool resolves = is_holding(decide_rendered(cells, near_truth_pixel));
  r.verdict = declared == Verdict::kFails && !resolves ? Verdict::kInconclusive : declared;
  std::string by_lambda, resolved_beyond;
  for (std::size_t k = 0; k < kGlintsPerPixel.size(); ++k) {
    by_lambda += fmt::format("{}λ {:g}: {} / {}", k ? ", " : "", kGlintsPerPixel[k],
                             rendered_regime.not_in_by_lambda[k], near_regime.not_in_by_lambda[k]);
    // Where the rule holds the near-truth input in every regime cell: the LTC pixels beyond.
    if (near_regime.not_in_by_lambda[k] > 0) continue;
    for (const Cell& c : cells)
      if (in_regime(c)) {
        const RenderedDecision d = rendered_decision(brdf_pixel(c), c, kGlintsPerPixel[k]);
        if (d.low > kVisualTolerance)
          resolved_beyond += fmt::format("{}λ {:g} {} ({:.3g}, p error {:.3g})",
                                         resolved_beyond.empty() ? "" : "; ", kGlintsPerPixel[k],
                                         describe(c.c), d.at_estimate, rel_error(c.brdf, c));
      }
  }
  if (r.verdict == Verdict::kHoldsInRegime)
    r.regime = fmt::format("{}; λ = {:g}..{:g} reflecting facets per pixel", kRegime,
                           kGlintsPerPixel.front(), kGlintsPerPixel.back());
  const Verdict stronger = verdict_of(brdf, brdf_regime);
  const auto& grid = configs(b);
  r.detail = fmt::format(
      "square light of side s at distance 1 (s {}..{}), √α {}..{}, θv {}..{}°, centred on the "
      "mirror direction or overhead; {} cells ({} in the tail, p_MC < {:.0e} D_PR, apart); MC {} "
      "batches, worst rel. SE {:.2g}. Rendered difference (tolerance {:.0f} %, the Weber "
      "fraction; each (cell, λ) pair decided over the reference's ± 3 SE band), regime "
      "(declared): {}, {} cells × λ {:g}..{:g}: BRDF lobe × D_PR (the paper's): {}; everywhere: "
      "{}; NDF lobe × D_PR ('+ NDF LTC', Fig. 8's middle column), regime: {}. The declared rule "
      "gives {}; regime pairs not within 2 %, BRDF lobe / near-truth input, by λ: {}{}; at the "
      "densities where the near-truth input is within 2 % in every regime cell, the LTC pixel is "
      "beyond at: {}. "
      "Stronger reading, "
      "the probability within {:.0f} % (± 3 SE): {}; regime: {}; everywhere: {}; median by axis: "
      "{}. NDF lobe × D_PR everywhere: {}; median by axis: {}. Tail cells: max rel. error {:.3g}. "
      "Independent fit (L1 compass search at the exact α, θv; exact D_PR), {} regime cells: BRDF "
      "lobe rel. error of p median {:.3g} → {:.3g}, max {:.3g} → {:.3g}, beyond 10 % {} → {}; "
      "NDF lobe median {:.3g} → {:.3g}, max {:.3g} → {:.3g}, beyond {} → {}; median share of the "
      "BRDF lobe's error an independent fit removes {:.2g}; the fit cause of the stronger "
      "reading's failure is {} (excluded when a regime cell stays beyond 10 % with the "
      "independent fit). The table's BRDF lobe integrated over the light by brute force (its own "
      "samples, over the same domain as the closed form): closed form within {:.2g} (max rel.), "
      "max |z| {:.2g} at {} ({:.5g} vs {:.5g}), {} cells beyond 4 SE; the part of the light below "
      "the horizon, which the LTC convention counts, holds up to {:.2g} of the lobe's integral "
      "({})",
      grid.front().side, grid.back().side, grid.front().sqrt_alpha, grid.back().sqrt_alpha,
      grid.front().theta_v_deg, grid.back().theta_v_deg, cells.size(), tail, kTailFraction,
      kBatches, worst_se, 100 * kVisualTolerance, kRegime, regime_cells, kGlintsPerPixel.front(),
      kGlintsPerPixel.back(), describe_rendered(rendered_regime), describe_rendered(rendered),
      describe_rendered(rendered_ndf), to_string(declared), by_lambda,
      declared == Verdict::kFails && !resolves
          ? " (the near-truth input is not held by the rule: reported inconclusive)"
          : "",
      resolved_beyond.empty() ? "none" : resolved_beyond, 100 * kTolerance, to_string(stronger),
      describe_summary(brdf_regime), describe_summary(brdf), brdf.by_axis, describe_summary(ndf),
      ndf.by_axis, tail_max, fits.cells, fits.med_table, fits.med_indep, fits.max_table,
      fits.max_indep, fits.beyond_table, fits.beyond_indep, fits.ndf_med_table, fits.ndf_med_indep,
      fits.ndf_max_table, fits.ndf_max_indep, fits.ndf_beyond_table, fits.ndf_beyond_indep,
      fits.fit_share, fits.beyond_indep > 0 ? "excluded" : "NOT excluded", fits.polygon_max_rel,
      fits.polygon_max_z, describe(fits.polygon_worst), fits.polygon_worst_closed,
      fits.polygon_worst_mc, fits.polygon_beyond, fits.below_horizon_max,
      describe(fits.below_horizon_worst));
  r.power = fmt::format(
      "the rendered difference scales with the pixel's relative fluctuation √((1 − p)/λ), so at "
      "λ = 1 a probability error of about 4 % is beyond the 2 % tolerance and at λ = 1000 one of "
      "about 250 % is; the largest rel. SE of p_MC in the regime is {:.2g} (probability level: an "
      "excess of ≥ {:.2g} over 10 % is detected at 90 % power in every regime cell)",
      regime_se, (3 + 1.2816) * regime_se);
  // The control, through the same rule. Where the claim holds: the LTC pixel rendered 4 %
  // brighter (must fail). Where it does not: an independent Monte Carlo p × 1.03 (must hold).
  const bool holding = is_holding(r.verdict);
  const auto get_ctl = [holding](const Cell& c) {
    return holding ? brighter_pixel(c) : near_truth_pixel(c);
  };
  const Verdict cv = decide_rendered(cells, get_ctl);
  record_control(r, cv);
  r.control = fmt::format(
      "{}: regime {}; everywhere {} → {} ({}). Probability level beside it: an independent Monte "
      "Carlo D_Ωh × 1.03 in the LTC's place, everywhere {} ({}); the BRDF lobe scaled by its "
      "albedo FGD instead of D_PR (Sec. 4 'LTC Scale'), everywhere: {}, {} by the 10 % rule",
      holding ? "the LTC pixel rendered 4 % brighter"
              : "the pixel with an independent Monte Carlo p × 1.03 (near truth)",
      describe_rendered(summarize_rendered(cells, get_ctl, true)),
      describe_rendered(summarize_rendered(cells, get_ctl, false)), to_string(cv),
      r.control_rejected ? "rejected" : "NOT rejected",
      describe_summary(summarize(cells, [](const Cell& c) { return c.near_truth; })),
      to_string(decide(cells, [](const Cell& c) { return c.near_truth; })),
      describe_summary(scaled),
      to_string(decide(cells, [](const Cell& c) { return c.albedo_scaled; })));
  return r;
}

}  // namespace

ControlProbe probe_kneiphof_ltc_probability() {
  // One cell of the sweep's regime (√α = 0.5, θv = 40°, side 0.5, mirror), MC at 16 × 1024.
  const Cell c = evaluate({0.5, 0.5, 40, 0}, 1024, check_seed(kLtcProbability, 1u << 20), 0);
  return {rel_error(c.brdf, c), rel_error(c.wrong_alpha, c), kTolerance, false};
}

LtcDecisionProbe probe_kneiphof_ltc_decision() {
  // Four cells of the regime (side 0.5 and 2, mirror, √α 0.5, θv 0° and 40°), MC at 16 × 2048;
  // the probability-level rule and the rendered one (the claim's).
  std::vector<Cell> cells;
  const std::uint64_t seed = check_seed(kLtcProbability, 1u << 21);
  for (double side : {0.5, 2.0})
    for (double v : {0.0, 40.0})
      cells.push_back(evaluate({side, 0.5, v, 0}, 2048, seed, cells.size()));
  const auto scaled = [](double f) { return [f](const Cell& c) { return f * c.ref; }; };
  const auto rendered_scaled = [](double f) {
    return [f](const Cell& c) { return Rendering{f * c.ref / c.d_h, 1.0}; };
  };
  return {decide(cells, [](const Cell& c) { return c.near_truth; }),
          decide(cells, scaled(1.2)),
          decide(cells, [](const Cell& c) { return c.wrong_alpha; }),
          decide_rendered(cells, near_truth_pixel),
          decide_rendered(cells, near_truth_pixel, 2),
          decide_rendered(cells, brighter_pixel),
          decide_rendered(cells, rendered_scaled(1.2)),
          decide_rendered(cells, [](const Cell& c) {
            return Rendering{c.ref / c.d_h, 1.04};
          })};
}

std::vector<Check> kneiphof_ltc_checks() {
  return {{kLtcProbability, "Kneiphof & Klein 2024", "Sec. 4, Sec. 7, Fig. 8, Eq. 12–19",
           Verdict::kInconclusive, run}};
}

}  // namespace glintlab::verify

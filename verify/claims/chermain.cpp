// chermain.*: Chermain et al. 2021 (with the 2020 glinty BRDF it extends). kernel-normalized
// (Eq. 15, Sec. 7), dictionary-converges (Fig. 3), correlation (Eq. 16–18, Fig. 10), the four
// GGAA claims of Figs. 8–9 as separate checks (ggaa-error and ggaa-shimmer on Fig. 8's tubes,
// ggaa-derivatives and ggaa-sk on the tubes with a bump map against a per-sample-footprint
// reference: replicated renders, paired t intervals) and lean-correlation (Fig. 7). Each check
// measures, decides, and runs its control through the same decision (record_control).
#include "core/glints/chermain.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "core/math/rng.h"
#include "verify/claims/chermain_probes.h"
#include "verify/claims/chermain_scenes.h"
#include "verify/claims/claims.h"
#include "verify/stats/mean_tests.h"

namespace glintlab::verify {
namespace {

constexpr const char* kPaper = "Chermain et al. 2021";

// --- chermain.kernel-normalized --------------------------------------------------------------
// Tables are float (like the paper's textures): unit integral to a few float ulps.
constexpr double kTableTolerance = 1e-5;
// 2D midpoint quadrature of the patch-SDF mass (and albedo) on the grids below.
constexpr double kPatchTolerance = 5e-3;

// Albedo ∫ f cos dω_o of the glinty BRDF for ω_i, on the slope grid of chermain2021::patch_moments:
// dω_o = 4 (ω_o·h) dω_h and dω_h = h_z³ dm̃, so the integrand is P22 G2 (ω_i·h)/(ω_i.z h_z).
double albedo(const chermain2021::SdfParams& p, const FootprintQuery<double>& fp,
              const chermain2021::SlopeDerivatives& d, Vec3<double> wi, int grid) {
  const double so = p.dictionary->sigma_o();
  const chermain2021::Matrix M = chermain2021::matrix(p.sigma_x, p.sigma_y, p.rho, so, p.with_rho);
  const double R =
      4 * std::sqrt(2.0) * so * std::sqrt(M.m00 * M.m00 + M.m01 * M.m01 + M.m11 * M.m11);
  const double h = 2 * R / grid;
  double sum = 0;
  for (int j = 0; j < grid; ++j)
    for (int i = 0; i < grid; ++i) {
      const Vec2<double> m{-R + (i + 0.5) * h, -R + (j + 0.5) * h};
      const Vec3<double> n = normalize(Vec3<double>{-m.x, -m.y, 1});
      const Vec3<double> wo = reflect(wi, n);
      if (!(wo.z > 0)) continue;
      const double P = chermain2021::patch_sdf(p, m, fp, d);
      if (P == 0) continue;
      sum += P * chermain2021::v_cavity_g2(wi, wo, n) * dot(wi, n) / (wi.z * n.z);
    }
  return sum * h * h;
}

struct NormalizationResult {
  double tables = 0, filtered = 0, patch = 0, albedo_max = 0;
  int configurations = 0;
};

// The control's dictionary: every texel × (1 + kTexelBias), tables normalized 2 % off.
constexpr double kTexelBias = 0.02;

// texel_scale: the measurement of a dictionary whose texels are all × texel_scale. The table
// integrals and the filtered marginals are linear in the texels, so they are the genuine
// dictionary's × texel_scale exactly. with_patch: also the patch-SDF mass and albedo (2D
// quadrature; the genuine dictionary only).
NormalizationResult normalization(bool quick, double texel_scale, bool with_patch) {
  const chermain2021::Dictionary& d = chermain2021::default_chermain_dictionary();
  const chermain2021::TableWrap wrap = chermain2021::TableWrap::kMirroredRepeat;
  NormalizationResult r;
  for (int n = 0; n < d.distributions(); ++n)
    for (int k = 0; k < d.levels(); ++k)
      for (int m = 0; m < d.mip_levels(); ++m)
        r.tables = std::max(r.tables, std::abs(texel_scale * d.table_integral(n, k, m) - 1)),
        ++r.configurations;
  const std::vector<std::pair<double, double>> grads = {
      {0.004, 0.001}, {0.02, 0.02}, {0.1, 0.01}, {0.5, 0.2}, {3.0, 0.5}};
  const int stride = quick ? 16 : 1;
  for (int n = 0; n < d.distributions(); n += stride)
    for (int k = 0; k < d.levels(); k += quick ? 3 : 1)
      for (auto [gx, gy] : grads) {
        r.filtered =
            std::max(r.filtered, std::abs(texel_scale * chermain2021::lookup_grad_integral(
                                                            d, n, k, gx, gy, wrap, quick ? 4 : 8) -
                                          1));
        ++r.configurations;
      }
  if (!with_patch) return r;
  const int grid = quick ? 200 : 600;
  const FootprintQuery<double> fp{{0.3, 0.7}, {0.004, 0.001}, {-0.001, 0.003}};
  const chermain2021::SlopeDerivatives der{0.06, -0.02, 0.01, 0.04};
  for (int kernel : {chermain2021::kNoGgaa, chermain2021::kProjectedHalf})
    for (double rho : quick ? std::vector<double>{0.6} : std::vector<double>{0.0, 0.6, -0.9})
      for (double log2_density :
           quick ? std::vector<double>{22} : std::vector<double>{14, 22, 30}) {
        chermain2021::SdfParams p{&d, 0.3, 0.2, rho, log2_density, kernel, 0.5, 17};
        p.wrap = wrap;
        r.patch =
            std::max(r.patch, std::abs(chermain2021::patch_moments(p, fp, der, grid).mass - 1));
        r.albedo_max =
            std::max(r.albedo_max, albedo(p, fp, der, normalize(Vec3<double>{0.4, 0.2, 1}), grid));
        ++r.configurations;
      }
  return r;
}

// holds when every table, filtered marginal and patch-SDF mass is within its tolerance of 1 and
// the white-furnace albedo does not exceed 1 by more than the patch tolerance.
Verdict decide_normalized(const NormalizationResult& r) {
  const bool ok = r.tables <= kTableTolerance && r.filtered <= kTableTolerance &&
                  r.patch <= kPatchTolerance && r.albedo_max <= 1 + kPatchTolerance;
  return ok ? Verdict::kHolds : Verdict::kFails;
}

std::string describe_normalized(const NormalizationResult& r) {
  return fmt::format(
      "every table at every MIP level: max |∫−1| = {:.2g}; textureGrad-filtered marginals (5 "
      "kernels, mirrored repeat): {:.2g} (held to {:.0e}); patch-SDF mass with/without GGAA by 2D "
      "quadrature: max |∫−1| = {:.2g}, white-furnace albedo max {:.4f} (held to {:.0e})",
      r.tables, r.filtered, kTableTolerance, r.patch, r.albedo_max, kPatchTolerance);
}

CheckResult kernel_normalized(Budget b) {
  const bool quick = b == Budget::kQuick;
  const NormalizationResult r = normalization(quick, 1.0, true);
  CheckResult res;
  res.configurations = r.configurations;
  res.statistic = "max |∫ filtered marginal − 1| over tables × MIP levels × kernels";
  res.value = std::max(r.tables, r.filtered);
  res.bound = kTableTolerance;
  res.verdict = decide_normalized(r);
  res.detail = describe_normalized(r);
  // Control: the same measurement of a dictionary normalized 2 % off (its patch-SDF terms kept
  // from the genuine measurement), through the same decision.
  NormalizationResult ctl = normalization(quick, 1 + kTexelBias, false);
  ctl.patch = r.patch, ctl.albedo_max = r.albedo_max;
  record_control(res, decide_normalized(ctl));
  res.power = fmt::format(
      "deterministic (sums over every texel of every table and level, no sampling noise): a table "
      "or filtered marginal whose integral is off 1 by more than {:.0e} anywhere is detected, "
      "every time (the genuine error is {:.2g}); the control's {:.0f} % is {:.0f}× the tolerance",
      kTableTolerance, res.value, 100 * kTexelBias, kTexelBias / kTableTolerance);
  res.control =
      fmt::format("every texel × {} (tables normalized {:.0f} % off): {} → {} ({})", 1 + kTexelBias,
                  100 * kTexelBias, describe_normalized(ctl), to_string(*res.control_verdict),
                  res.control_rejected ? "rejected" : "NOT rejected");
  return res;
}

// --- chermain.dictionary-converges -----------------------------------------------------------
// Tolerances fixed before measuring: the last level within 5 % L1 of the Gaussian and its
// standard deviation within 1 % of σ_o; the mean L1 distance non-increasing level to level.
constexpr double kL1Tolerance = 0.05;
constexpr double kStdTolerance = 0.01;

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

// holds when every measured dictionary converges.
Verdict decide_converges(const std::vector<Convergence>& runs) {
  for (const Convergence& c : runs)
    if (!converges(c)) return Verdict::kFails;
  return Verdict::kHolds;
}

std::string describe_convergence(const Convergence& c) {
  std::string levels;
  for (std::size_t k = 0; k < c.l1.size(); ++k)
    levels += fmt::format("{}{:.3g}", k ? ", " : "", c.l1[k]);
  return fmt::format("mean L1 per level [{}]; last-level std / sigma_o = {:.4f}", levels,
                     c.std_ratio);
}

// The control's dictionary: lobe means spread 2 % wider than the paper's (a near-truth error of
// the one quantity the limit's standard deviation depends on).
constexpr double kControlMeanScale = 1.02;

chermain2021::DictionaryConfig control_dictionary_config() {
  chermain2021::DictionaryConfig c;
  c.mean_scale = kControlMeanScale;
  return c;
}

CheckResult dictionary_converges(Budget b) {
  const bool quick = b == Budget::kQuick;
  const int stride = quick ? 4 : 1;
  std::vector<Convergence> runs = {
      convergence(chermain2021::default_chermain_dictionary(), stride)};
  if (!quick)
    for (std::uint64_t seed : {1, 2}) {
      chermain2021::DictionaryConfig c;
      c.seed = seed;
      runs.push_back(convergence(chermain2021::Dictionary(c), 1));
    }
  const Convergence& c = runs.front();
  CheckResult res;
  res.configurations = int(runs.size()) * int(c.l1.size());
  res.statistic = "mean L1 distance of the last level to the Gaussian of std σ_o";
  res.value = c.l1.back();
  res.bound = kL1Tolerance;
  res.verdict = decide_converges(runs);
  double worst = 0;
  for (const Convergence& r : runs) worst = std::max(worst, std::abs(r.std_ratio - 1));
  res.detail = fmt::format(
      "{} dictionar{} (N=192, L=16, 64 texels, alpha_dict 0.5): {}; largest |std ratio - 1| over "
      "the dictionaries {:.2g} (held to L1 <= {}, |std ratio - 1| <= {}, L1 non-increasing)",
      runs.size(), runs.size() > 1 ? "ies (seeds 2020, 1, 2)" : "y (seed 2020)",
      describe_convergence(c), worst, kL1Tolerance, kStdTolerance);
  // Control: the seed-2020 dictionary with its lobe means × 1.02, measured the same way.
  const Convergence ctl =
      convergence(chermain2021::Dictionary(control_dictionary_config()), stride);
  record_control(res, decide_converges({ctl}));
  res.power = fmt::format(
      "deterministic per dictionary (no sampling noise): a last level farther than L1 {} from the "
      "Gaussian, or a std off by more than {:.0f} %, is detected every time; lobe means spread "
      "{:.0f} % wider move the std by {:+.2f} %",
      kL1Tolerance, 100 * kStdTolerance, 100 * (kControlMeanScale - 1), 100 * (ctl.std_ratio - 1));
  res.control = fmt::format("lobe means spread {:.0f} % wider (mean_scale {}): {} → {} ({})",
                            100 * (kControlMeanScale - 1), kControlMeanScale,
                            describe_convergence(ctl), to_string(*res.control_verdict),
                            res.control_rejected ? "rejected" : "NOT rejected");
  return res;
}

// --- chermain.correlation --------------------------------------------------------------------
constexpr double kSigmaTolerance = 0.02;  // relative
constexpr double kRhoTolerance = 0.02;    // absolute

// Exact covariance of the patch-SDF by the change of variables m̃ = M R(θ) m̃_o per cell:
// Σ_cells w M R diag(v_x, v_y) Rᵀ Mᵀ, v the variance of each (symmetric) table.
struct Cov {
  double xx, yy, xy;
};

Cov patch_covariance(const chermain2021::SdfParams& p, const FootprintQuery<double>& fp) {
  const chermain2021::Dictionary& d = *p.dictionary;
  const chermain2021::Matrix M =
      chermain2021::matrix(p.sigma_x, p.sigma_y, p.rho, d.sigma_o(), p.with_rho);
  const auto variance = [&](int n, int k) {
    const int steps = 2 * d.resolution() * 8;
    const double h = 2 * d.extent() / steps;
    double v = 0;
    for (int i = 0; i < steps; ++i) {
      const double x = -d.extent() + (i + 0.5) * h;
      v += x * x * d.lookup_lod(n, k, x);
    }
    return v * h;
  };
  Cov c{0, 0, 0};
  chermain2021::for_each_cell(
      p, fp, [&](bool on, double w, double k, const chermain2021::Cell<double>& s) {
        if (!on) return;
        if (k >= d.levels()) {
          const double r = p.with_rho ? p.rho : 0.0;
          c.xx += w * p.sigma_x * p.sigma_x, c.yy += w * p.sigma_y * p.sigma_y;
          c.xy += w * r * p.sigma_x * p.sigma_y;
          return;
        }
        const double vx = variance(int(s.nx), int(k)), vy = variance(int(s.ny), int(k));
        // A = M R(θ): columns a = M (cos, sin), b = M (−sin, cos).
        const double a0 = M.m00 * s.cos_t + M.m01 * s.sin_t, a1 = M.m11 * s.sin_t;
        const double b0 = -M.m00 * s.sin_t + M.m01 * s.cos_t, b1 = M.m11 * s.cos_t;
        c.xx += w * (vx * a0 * a0 + vy * b0 * b0);
        c.yy += w * (vx * a1 * a1 + vy * b1 * b1);
        c.xy += w * (vx * a0 * a1 + vy * b0 * b1);
      });
  return c;
}

struct CorrelationResult {
  double sigma_err = 0, rho_err = 0, e2e_rho_err = 0;
  int configurations = 0;
  std::string worst;
};

// The control's patch-SDFs: built with ρ off by this much (towards the interior of (−1, 1)) and
// measured against the intended ρ.
constexpr double kControlRhoOffset = 0.03;

// rho_offset: each patch-SDF is built with ρ + rho_offset (ρ − rho_offset where that would leave
// (−1, 1)) and its covariance compared with the intended ρ: 0 for the genuine measurement.
CorrelationResult correlation(bool quick, double rho_offset) {
  CorrelationResult r;
  const auto built = [&](double rho) {
    return rho + rho_offset < 0.999 ? rho + rho_offset : rho - rho_offset;
  };
  // Footprint 2^-7.5 and density 2^45: LODs −8, −7 use dictionary levels 14 and 15 (the last).
  const double foot = std::ldexp(1.0, -8) * std::sqrt(2.0);
  const int n_uv = quick ? 4 : 32;
  const double so = chermain2021::default_chermain_dictionary().sigma_o();
  for (double rho : {0.0, 0.5, 0.99})
    for (auto [sx, sy] : {std::pair{so, so}, std::pair{0.3, 0.12}})
      for (int i = 0; i < n_uv; ++i) {
        const FootprintQuery<double> fp{{0.137 * i + 0.01, 0.291 * i + 0.02}, {foot, 0}, {0, foot}};
        chermain2021::SdfParams p{&chermain2021::default_chermain_dictionary(),
                                  sx,
                                  sy,
                                  built(rho),
                                  45,
                                  chermain2021::kNoGgaa,
                                  0.5,
                                  std::uint64_t(i)};
        const Cov c = patch_covariance(p, fp);
        const double es =
            std::max(std::abs(std::sqrt(c.xx) / sx - 1), std::abs(std::sqrt(c.yy) / sy - 1));
        const double er = std::abs(c.xy / std::sqrt(c.xx * c.yy) - rho);
        r.sigma_err = std::max(r.sigma_err, es);
        if (er > r.rho_err) {
          r.rho_err = er;
          r.worst = fmt::format("rho={} sigma=({:.3g},{:.3g}) uv #{}", rho, sx, sy, i);
        }
        ++r.configurations;
      }
  if (!quick) {  // end to end through the patch-SDF evaluation (2D quadrature), ρ = 0.5
    const FootprintQuery<double> fp{{0.41, 0.77}, {foot, 0}, {0, foot}};
    chermain2021::SdfParams p{&chermain2021::default_chermain_dictionary(),
                              so,
                              so,
                              built(0.5),
                              45,
                              chermain2021::kNoGgaa,
                              0.5,
                              3};
    const chermain2021::SlopeMoments2 m = chermain2021::patch_moments(p, fp, {0, 0, 0, 0}, 1000);
    r.e2e_rho_err = std::abs(m.xy / std::sqrt(m.xx * m.yy) - 0.5);
    ++r.configurations;
  }
  return r;
}

Verdict decide_correlation(const CorrelationResult& r) {
  return r.sigma_err <= kSigmaTolerance && r.rho_err <= kRhoTolerance &&
                 r.e2e_rho_err <= kRhoTolerance
             ? Verdict::kHolds
             : Verdict::kFails;
}

std::string describe_correlation(const CorrelationResult& r, bool quick) {
  return fmt::format(
      "max rel. sigma error {:.3g} (held to {}), max |rho_hat - rho| {:.3g} (held to {}; worst "
      "{}){}",
      r.sigma_err, kSigmaTolerance, r.rho_err, kRhoTolerance, r.worst,
      quick ? ""
            : fmt::format("; end-to-end 2D quadrature of P22 at rho 0.5: |rho_hat - rho| {:.3g}",
                          r.e2e_rho_err));
}

CheckResult correlation_check(Budget b) {
  const bool quick = b == Budget::kQuick;
  const CorrelationResult r = correlation(quick, 0);
  CheckResult res;
  res.configurations = r.configurations;
  res.statistic = "max |rho_hat − rho| of the patch-SDF covariance at the last dictionary levels";
  res.value = r.rho_err;
  res.bound = kRhoTolerance;
  res.verdict = decide_correlation(r);
  res.detail = fmt::format(
      "rho in {{0, 0.5, 0.99}}, sigma (sigma_o, sigma_o) and (0.3, 0.12), {} footprints each at "
      "dictionary levels 14-15: {}",
      quick ? 4 : 32, describe_correlation(r, quick));
  const CorrelationResult ctl = correlation(quick, kControlRhoOffset);
  record_control(res, decide_correlation(ctl));
  res.power = fmt::format(
      "quadrature of the dictionary's slope distribution (no sampling noise): a patch-SDF whose "
      "correlation is off by more than {} + {:.2g} (the genuine error) = {:.3f}, or sigma by more "
      "than {:.0f} % + {:.2g}, is detected every time",
      kRhoTolerance, r.rho_err, kRhoTolerance + r.rho_err, 100 * kSigmaTolerance, r.sigma_err);
  res.control = fmt::format(
      "patch-SDFs built with rho {:+} (rho 0.99: {}) and held to the intended rho: {} → {} ({})",
      kControlRhoOffset, 0.99 - kControlRhoOffset, describe_correlation(ctl, quick),
      to_string(*res.control_verdict), res.control_rejected ? "rejected" : "NOT rejected");
  return res;
}

}  // namespace

GgaaMeasurement measure_ggaa(const GgaaBudget& b, std::uint64_t seed) {
  TubeSceneOptions o;
  o.width = b.width, o.height = b.height, o.threads = b.threads;
  GgaaMeasurement m;
  m.reference = render_tubes_reference(o, b.reference_spp, seed);
  m.none = render_tubes(o, chermain2021::kNoGgaa, 0.5);
  m.half05 = render_tubes(o, chermain2021::kHalfSlope, 0.5);
  m.half1 = render_tubes(o, chermain2021::kHalfSlope, 1.0);
  m.proj05 = render_tubes(o, chermain2021::kProjectedHalf, 0.5);
  m.proj1 = render_tubes(o, chermain2021::kProjectedHalf, 1.0);
  for (int f = 0; f < b.frames; ++f) {
    TubeSceneOptions of = o;
    of.camera_shift = 0.37 * f;  // a slow pan: 0.37 pixel per frame
    m.frames_none.push_back(render_tubes(of, chermain2021::kNoGgaa, 0.5));
    m.frames05.push_back(render_tubes(of, chermain2021::kProjectedHalf, 0.5));
    m.frames1.push_back(render_tubes(of, chermain2021::kProjectedHalf, 1.0));
  }
  return m;
}

GgaaVerdict judge_ggaa(const GgaaMeasurement& m, const Image& reference) {
  GgaaVerdict v;
  v.rmse_none = display_rmse_percent(m.none, reference);
  v.rmse_half05 = display_rmse_percent(m.half05, reference);
  v.rmse_half1 = display_rmse_percent(m.half1, reference);
  v.rmse_proj05 = display_rmse_percent(m.proj05, reference);
  v.rmse_proj1 = display_rmse_percent(m.proj1, reference);
  v.flicker_none = frame_to_frame_variance(m.frames_none, reference);
  v.flicker05 = frame_to_frame_variance(m.frames05, reference);
  v.flicker1 = frame_to_frame_variance(m.frames1, reference);
  v.ggaa_lowers = v.rmse_proj05 < v.rmse_none && v.rmse_half05 < v.rmse_none;
  v.projected_beats_half = v.rmse_proj05 < v.rmse_half05 && v.rmse_proj1 < v.rmse_half1;
  v.small_kernel_lower_rmse = v.rmse_proj05 < v.rmse_proj1;
  v.small_kernel_shimmers_more = v.flicker05 > v.flicker1;
  return v;
}

// --- chermain.ggaa-error, ggaa-derivatives, ggaa-sk, ggaa-shimmer (Figs. 8–9) ----------------
// ggaa-error and ggaa-shimmer from one replicated measurement: K independent replicates of the
// tube scene (its own glint layout, sub-pixel camera offset and reference seed), the display RMSE
// without GGAA and with Eq. 21 at s_K 0.5 and the shimmer per replicate, orderings decided by a t
// confidence interval of the paired per-replicate differences (ggaa-derivatives and ggaa-sk:
// below, on the normal-mapped tubes).

GgaaReplicate measure_ggaa_replicate(const GgaaReplicateBudget& b, const std::string& id, int k) {
  TubeSceneOptions o;
  o.width = b.width, o.height = b.height, o.threads = b.threads;
  const std::uint64_t s = check_seed(id, std::uint64_t(k));
  o.sdf_seed = s;
  o.camera_shift = counter_uniform<double>(s, 0, 0);  // sub-pixel offset of the replicate
  const Image ref = render_tubes_reference(o, b.reference_spp, check_seed(id, 1000 + k));
  Image near_truth = render_tubes_reference(o, b.reference_spp, check_seed(id, 2000 + k));
  for (double& v : near_truth.data) v *= 1 + kGgaaNearTruthBias;
  GgaaReplicate r;
  r.none = display_rmse_percent(render_tubes(o, chermain2021::kNoGgaa, 0.5), ref);
  r.proj05 = display_rmse_percent(render_tubes(o, chermain2021::kProjectedHalf, 0.5), ref);
  r.near_truth = display_rmse_percent(near_truth, ref);
  std::vector<Image> f05, f1, slow1;
  for (int f = 0; f < b.frames; ++f) {
    TubeSceneOptions of = o;
    of.camera_shift = o.camera_shift + kGgaaPan * f;
    f05.push_back(render_tubes(of, chermain2021::kProjectedHalf, 0.5));
    f1.push_back(render_tubes(of, chermain2021::kProjectedHalf, 1.0));
    of.camera_shift = o.camera_shift + (1 - kGgaaSlowPan) * kGgaaPan * f;
    slow1.push_back(render_tubes(of, chermain2021::kProjectedHalf, 1.0));
  }
  r.flicker05 = frame_to_frame_variance(f05, ref);
  r.flicker1 = frame_to_frame_variance(f1, ref);
  r.flicker1_slow = frame_to_frame_variance(slow1, ref);
  return r;
}

PairedComparison compare_paired(const std::vector<double>& d, double confidence) {
  PairedComparison c;
  c.n = int(d.size());
  double m = 0;
  for (double x : d) m += x;
  m /= double(d.size());
  double v = 0;
  for (double x : d) v += (x - m) * (x - m);
  v /= double(d.size() - 1);
  c.mean = m;
  c.se = std::sqrt(v / double(d.size()));
  c.t = student_t_quantile(0.5 + 0.5 * confidence, double(d.size() - 1));
  c.lo = m - c.t * c.se, c.hi = m + c.t * c.se;
  // 90 % power against an effect δ: δ ≥ (t + z_0.9) · SE (normal approximation of the t power).
  c.detectable = (c.t + 1.2816) * c.se;
  return c;
}

Verdict decide_ggaa(const std::vector<std::vector<double>>& parts) {
  // Each part: per-replicate differences (claimed loser − claimed winner); Šidák over the parts.
  const double conf = std::pow(kGgaaConfidence, 1.0 / double(parts.size()));
  bool all_win = true;
  for (const auto& d : parts) {
    const PairedComparison c = compare_paired(d, conf);
    if (c.hi < 0) return Verdict::kFails;  // the claimed winner is worse beyond the noise
    if (!(c.lo > 0)) all_win = false;      // a tie within the noise
  }
  return all_win ? Verdict::kHolds : Verdict::kInconclusive;
}

namespace {

GgaaReplicateBudget ggaa_budget(Budget b) {
  return b == Budget::kQuick ? GgaaReplicateBudget{64, 44, 32, 3, 6, 0}
                             : GgaaReplicateBudget{128, 88, 64, 4, 10, 0};
}

// Memoized: the two checks share one measurement per budget.
const std::vector<GgaaReplicate>& ggaa_replicates(Budget b) {
  static std::mutex mutex;
  static std::map<int, std::vector<GgaaReplicate>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find(int(b));
  if (it != cache.end()) return it->second;
  const GgaaReplicateBudget g = ggaa_budget(b);
  std::vector<GgaaReplicate> reps;
  for (int k = 0; k < g.replicates; ++k)
    reps.push_back(measure_ggaa_replicate(g, "chermain.ggaa", k));
  return cache.emplace(int(b), std::move(reps)).first->second;
}

// A claim "a < b" in every part (RMSE: a is more accurate; shimmer: b shimmers more), decided on
// the per-replicate differences b − a. The control puts `control` in place of b when the genuine
// verdict holds (a near-truth image, or a pan 5 % slower: the claim must then fail) and in place
// of a when it does not (the corrected input: the claim must then hold).
struct GgaaPart {
  const char* a_name;
  double GgaaReplicate::*a;
  const char* b_name;
  double GgaaReplicate::*b;
};
struct GgaaClaim {
  const char* id;
  const char* claim;  // what is compared, for the statistic
  std::vector<GgaaPart> parts;
  double GgaaReplicate::*control;
  const char* control_name;
  const char* unit;
};

std::vector<std::vector<double>> ggaa_diffs(const std::vector<GgaaReplicate>& reps,
                                            const GgaaClaim& c, bool replace_a, bool replace_b) {
  std::vector<std::vector<double>> out;
  for (const GgaaPart& p : c.parts) {
    std::vector<double> d;
    for (const GgaaReplicate& r : reps)
      d.push_back((replace_b ? r.*(c.control) : r.*(p.b)) -
                  (replace_a ? r.*(c.control) : r.*(p.a)));
    out.push_back(d);
  }
  return out;
}

double mean_of(const std::vector<GgaaReplicate>& reps, double GgaaReplicate::*f) {
  double m = 0;
  for (const GgaaReplicate& r : reps) m += r.*f;
  return m / double(reps.size());
}

std::string describe_parts(const std::vector<GgaaReplicate>& reps, const GgaaClaim& c,
                           bool replace_a, bool replace_b) {
  const auto diffs = ggaa_diffs(reps, c, replace_a, replace_b);
  const double conf = std::pow(kGgaaConfidence, 1.0 / double(c.parts.size()));
  std::string out;
  for (std::size_t i = 0; i < c.parts.size(); ++i) {
    const PairedComparison pc = compare_paired(diffs[i], conf);
    const char* a = replace_a ? c.control_name : c.parts[i].a_name;
    const char* b = replace_b ? c.control_name : c.parts[i].b_name;
    out += fmt::format(
        "{}a = {} {:.3f} vs b = {} {:.3f} {} (means over replicates); b − a {:+.3f} ± {:.3f} SE, "
        "{:.2f} % CI [{:+.3f}, {:+.3f}] ({})",
        i ? "; " : "", a, mean_of(reps, replace_a ? c.control : c.parts[i].a), b,
        mean_of(reps, replace_b ? c.control : c.parts[i].b), c.unit, pc.mean, pc.se, 100 * conf,
        pc.lo, pc.hi,
        pc.lo > 0   ? "as claimed"
        : pc.hi < 0 ? "reversed"
                    : "tie within the noise");
  }
  return out;
}

CheckResult run_ggaa_claim(const GgaaClaim& c, Budget b) {
  const GgaaReplicateBudget g = ggaa_budget(b);
  const std::vector<GgaaReplicate>& reps = ggaa_replicates(b);
  const auto diffs = ggaa_diffs(reps, c, false, false);
  CheckResult r;
  r.configurations = g.replicates * int(c.parts.size());
  r.statistic = fmt::format("{}: mean paired difference over replicates", c.claim);
  const double conf = std::pow(kGgaaConfidence, 1.0 / double(c.parts.size()));
  PairedComparison first = compare_paired(diffs[0], conf);
  double detectable = 0;
  for (const auto& d : diffs) detectable = std::max(detectable, compare_paired(d, conf).detectable);
  r.value = first.mean;
  r.verdict = decide_ggaa(diffs);
  r.detail = fmt::format(
      "tubes {}x{}, {} replicates (own glint layout, sub-pixel camera offset, reference seed), "
      "reference {} spp (pixel footprint fixed, no GGAA), {} frames of a {}-pixel pan for "
      "shimmer (frame-to-frame variance x1e4); the claim: a < b in each part: {}. "
      "Paper: Fig. 8 4.815 -> 3.661 %; Fig. 9 13.48 | 7.53, 8.19 | 7.43, 7.79 %",
      g.width, g.height, g.replicates, g.reference_spp, g.frames, kGgaaPan,
      describe_parts(reps, c, false, false));
  r.power = fmt::format(
      "paired difference detected at 90 % power: ≥ {:.3f} {} ((t_{{{:.4f}, {}}} + 1.28) × SE of "
      "the mean over {} replicates, largest over {} part(s))",
      detectable, c.unit, 0.5 + 0.5 * conf, g.replicates - 1, g.replicates, c.parts.size());
  const bool holding = is_holding(r.verdict);
  const auto cd = ggaa_diffs(reps, c, !holding, holding);
  const Verdict cv = decide_ggaa(cd);
  record_control(r, cv);
  r.control = fmt::format("{} in place of {}: {} → {} ({})", c.control_name,
                          holding ? "b (the claimed higher)" : "a (the claimed lower)",
                          describe_parts(reps, c, !holding, holding), to_string(cv),
                          r.control_rejected ? "rejected" : "NOT rejected");
  return r;
}

const GgaaClaim kGgaaError{
    "chermain.ggaa-error",
    "display RMSE % of no GGAA − GGAA (Eq. 21, s_K 0.5)",
    {{"GGAA Eq. 21 s_K 0.5", &GgaaReplicate::proj05, "no GGAA", &GgaaReplicate::none}},
    &GgaaReplicate::near_truth,
    "an independent reference x 1.03 (near truth)",
    "% RMSE"};
const GgaaClaim kGgaaShimmer{
    "chermain.ggaa-shimmer",
    "frame-to-frame variance x1e4 of s_K 0.5 − s_K 1 (Eq. 21)",
    {{"s_K 1", &GgaaReplicate::flicker1, "s_K 0.5", &GgaaReplicate::flicker05}},
    &GgaaReplicate::flicker1_slow,
    "s_K 1 under a pan 5 % slower",
    "x1e-4"};

CheckResult ggaa_error(Budget b) { return run_ggaa_claim(kGgaaError, b); }
CheckResult ggaa_shimmer(Budget b) { return run_ggaa_claim(kGgaaShimmer, b); }

// --- chermain.ggaa-derivatives and chermain.ggaa-sk (Fig. 9) ----------------------------------
// One measurement for both: normal-mapped tubes (the shading normal varies within pixels, as on
// Fig. 9's lion head) against a reference whose every sample has its own footprint (the paper's
// 1,024-spp supersampled reference, not a fixed-footprint box average, which a wider kernel
// approximates by construction). Each claim is judged on its own sentence; the derivatives row
// also measures Eq. 21 at the kernel width Eq. 20 has, which tells whether the derivative choice
// matters beyond the width the s_K claim is about.

// The paper's regime (Fig. 9: normal map without LEAN, 1 spp, GGAA at s_K 0.5 and 1), declared
// before measuring: bumps 4 pixels wide, rms slope 0.1, on the tubes of Fig. 8 (α 0.35,
// 1.6e5 microfacets per unit uv).
constexpr double kBumpWavelengthPx = 4;
constexpr double kBumpSlopeRms = 0.1;

BumpyGgaaBudget bumpy_budget(Budget b) {
  return b == Budget::kQuick ? BumpyGgaaBudget{64, 44, 256, 6, 0}
                             : BumpyGgaaBudget{128, 88, 1024, 10, 0};
}

// Median over the pixels where both have a kernel of a's kernel width / b's (channel 3).
double median_width_ratio(const Image& a, const Image& b) {
  std::vector<double> r;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      if (a.at(x, y, 3) > 0 && b.at(x, y, 3) > 0) r.push_back(a.at(x, y, 3) / b.at(x, y, 3));
  if (r.empty()) return 1;
  std::nth_element(r.begin(), r.begin() + std::ptrdiff_t(r.size() / 2), r.end());
  return r[r.size() / 2];
}

}  // namespace

BumpyGgaaReplicate measure_bumpy_ggaa_replicate(const BumpyGgaaBudget& b, const std::string& id,
                                                int k) {
  BumpyTubeOptions o;
  o.tubes.width = b.width, o.tubes.height = b.height, o.tubes.threads = b.threads;
  o.bump_wavelength_px = kBumpWavelengthPx, o.bump_slope_rms = kBumpSlopeRms;
  const std::uint64_t s = check_seed(id, std::uint64_t(k));
  o.tubes.sdf_seed = s;
  o.tubes.camera_shift = counter_uniform<double>(s, 0, 0);
  const Image ref = render_bumpy_tubes_reference(o, b.reference_spp, check_seed(id, 1000 + k));
  const Image alt = render_bumpy_tubes_reference(o, b.reference_spp, check_seed(id, 2000 + k));
  const Image half05 = render_bumpy_tubes(o, chermain2021::kHalfSlope, 0.5);
  const Image half1 = render_bumpy_tubes(o, chermain2021::kHalfSlope, 1.0);
  const Image proj05 = render_bumpy_tubes(o, chermain2021::kProjectedHalf, 0.5);
  const Image proj1 = render_bumpy_tubes(o, chermain2021::kProjectedHalf, 1.0);
  BumpyGgaaReplicate r;
  r.none = display_rmse_percent(render_bumpy_tubes(o, chermain2021::kNoGgaa, 0.5), ref);
  r.half05 = display_rmse_percent(half05, ref), r.half1 = display_rmse_percent(half1, ref);
  r.proj05 = display_rmse_percent(proj05, ref), r.proj1 = display_rmse_percent(proj1, ref);
  r.half05_alt = display_rmse_percent(half05, alt), r.half1_alt = display_rmse_percent(half1, alt);
  r.proj05_alt = display_rmse_percent(proj05, alt), r.proj1_alt = display_rmse_percent(proj1, alt);
  r.width_ratio = median_width_ratio(half05, proj05);
  r.matched_s_k = 0.5 * r.width_ratio;
  r.proj_matched =
      display_rmse_percent(render_bumpy_tubes(o, chermain2021::kProjectedHalf, r.matched_s_k), ref);
  r.reference_error = display_rmse_percent(alt, ref) / std::sqrt(2.0);
  BumpyTubeOptions smooth_o = o;
  smooth_o.tubes.density = 1e40;  // every cell past the dictionary's last level: the smooth SDF
  const Image smooth = render_bumpy_tubes(smooth_o, chermain2021::kNoGgaa, 0.5);
  r.smooth = display_rmse_percent(smooth, ref);
  const Image px = render_bumpy_tubes_reference(o, b.reference_spp, check_seed(id, 3000 + k),
                                                BumpyReference::kPixelSized);
  r.none_px = display_rmse_percent(render_bumpy_tubes(o, chermain2021::kNoGgaa, 0.5), px);
  r.half05_px = display_rmse_percent(half05, px), r.half1_px = display_rmse_percent(half1, px);
  r.proj05_px = display_rmse_percent(proj05, px), r.proj1_px = display_rmse_percent(proj1, px);
  r.smooth_px = display_rmse_percent(smooth, px);
  Image near_truth = alt;
  for (double& v : near_truth.data) v *= 1 + kGgaaNearTruthBias;
  r.near_truth = display_rmse_percent(near_truth, ref);
  return r;
}

Verdict decide_ordering(const std::vector<std::vector<double>>& parts, double tolerance) {
  const double conf = std::pow(kGgaaConfidence, 1.0 / double(parts.size()));
  bool all_win = true;
  for (const auto& d : parts) {
    const PairedComparison c = compare_paired(d, conf);
    if (c.hi < -tolerance) return Verdict::kFails;  // reversed beyond the noise and the tolerance
    if (!(c.lo > 0)) all_win = false;
  }
  return all_win ? Verdict::kHolds : Verdict::kInconclusive;
}

namespace {

const std::vector<BumpyGgaaReplicate>& bumpy_replicates(Budget b) {
  static std::mutex mutex;
  static std::map<int, std::vector<BumpyGgaaReplicate>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find(int(b));
  if (it != cache.end()) return it->second;
  const BumpyGgaaBudget g = bumpy_budget(b);
  std::vector<BumpyGgaaReplicate> reps;
  for (int k = 0; k < g.replicates; ++k)
    reps.push_back(measure_bumpy_ggaa_replicate(g, "chermain.ggaa-fig9", k));
  return cache.emplace(int(b), std::move(reps)).first->second;
}

using BumpyField = double BumpyGgaaReplicate::*;
// "a has the lower RMSE" for one part: a and b against the reference, and against the second one.
struct OrderingPart {
  const char* a_name;
  BumpyField a, a_alt;
  const char* b_name;
  BumpyField b, b_alt;
};
struct Ordering {
  std::vector<OrderingPart> parts;
  // The control: the near-truth image in place of b (genuine verdict holding: the claim must then
  // fail) or of a (otherwise: it must then hold).
  std::vector<std::vector<double>> diffs(const std::vector<BumpyGgaaReplicate>& reps,
                                         bool replace_a = false, bool replace_b = false) const {
    std::vector<std::vector<double>> out;
    for (const OrderingPart& p : parts) {
      std::vector<double> d;
      for (const BumpyGgaaReplicate& r : reps)
        d.push_back((replace_b ? r.near_truth : r.*(p.b)) - (replace_a ? r.near_truth : r.*(p.a)));
      out.push_back(d);
    }
    return out;
  }
  // The reference's own error of the compared difference: the RMS over replicates of its change
  // between the two independent references, / √2 (one reference's share), largest over parts.
  double reference_error(const std::vector<BumpyGgaaReplicate>& reps) const {
    double worst = 0;
    for (const OrderingPart& p : parts) {
      double ss = 0;
      for (const BumpyGgaaReplicate& r : reps) {
        const double d = (r.*(p.b) - r.*(p.a)) - (r.*(p.b_alt) - r.*(p.a_alt));
        ss += d * d / 2;
      }
      worst = std::max(worst, std::sqrt(ss / double(reps.size())));
    }
    return worst;
  }
};

double mean_field(const std::vector<BumpyGgaaReplicate>& reps, BumpyField f) {
  double m = 0;
  for (const BumpyGgaaReplicate& r : reps) m += r.*f / double(reps.size());
  return m;
}

std::string describe_ordering(const std::vector<BumpyGgaaReplicate>& reps, const Ordering& o,
                              bool replace_a, bool replace_b) {
  const auto diffs = o.diffs(reps, replace_a, replace_b);
  const double conf = std::pow(kGgaaConfidence, 1.0 / double(o.parts.size()));
  const double nt = mean_field(reps, &BumpyGgaaReplicate::near_truth);
  std::string out;
  for (std::size_t i = 0; i < o.parts.size(); ++i) {
    const OrderingPart& p = o.parts[i];
    const PairedComparison c = compare_paired(diffs[i], conf);
    out += fmt::format(
        "{}{} {:.3f} vs {} {:.3f} % RMSE: difference {:+.3f} ± {:.3f} SE, {:.2f} % CI [{:+.3f}, "
        "{:+.3f}] ({})",
        i ? "; " : "", replace_a ? "near-truth image" : p.a_name,
        replace_a ? nt : mean_field(reps, p.a), replace_b ? "near-truth image" : p.b_name,
        replace_b ? nt : mean_field(reps, p.b), c.mean, c.se, 100 * conf, c.lo, c.hi,
        c.lo > 0   ? "as claimed"
        : c.hi < 0 ? "reversed"
                   : "tie within the noise");
  }
  return out;
}

std::string describe_bumpy_setup(const BumpyGgaaBudget& g,
                                 const std::vector<BumpyGgaaReplicate>& reps) {
  return fmt::format(
      "normal-mapped tubes {}x{} (bumps {} px, rms slope {}), {} replicates (own glint layout, "
      "sub-pixel camera offset, two independent references); reference {} spp, each sample with "
      "its own footprint (the pixel's / {} per axis, at least one microfacet), no GGAA; the "
      "reference's own error {:.3f} % RMSE (mean over replicates); no GGAA {:.3f} %, the smooth "
      "limit (no glints) {:.3f} %. Against the other reading of the reference (each sample's "
      "footprint the pixel's size, at its own uv): no GGAA {:.3f}, half slope {:.3f} | {:.3f}, "
      "projected half {:.3f} | {:.3f} (s_K 0.5 | 1), smooth limit {:.3f} %",
      g.width, g.height, kBumpWavelengthPx, kBumpSlopeRms, g.replicates, g.reference_spp,
      kBumpyReferenceStrata, mean_field(reps, &BumpyGgaaReplicate::reference_error),
      mean_field(reps, &BumpyGgaaReplicate::none), mean_field(reps, &BumpyGgaaReplicate::smooth),
      mean_field(reps, &BumpyGgaaReplicate::none_px),
      mean_field(reps, &BumpyGgaaReplicate::half05_px),
      mean_field(reps, &BumpyGgaaReplicate::half1_px),
      mean_field(reps, &BumpyGgaaReplicate::proj05_px),
      mean_field(reps, &BumpyGgaaReplicate::proj1_px),
      mean_field(reps, &BumpyGgaaReplicate::smooth_px));
}

// Judges one ordering claim on the shared measurement; the tolerance is kPairTolerance or the
// reference's own error of the compared difference, whichever is larger.
CheckResult run_ordering(const Ordering& o, const std::string& statistic, Budget b) {
  const BumpyGgaaBudget g = bumpy_budget(b);
  const std::vector<BumpyGgaaReplicate>& reps = bumpy_replicates(b);
  const double ref_err = o.reference_error(reps);
  const double tolerance = std::max(kPairTolerance, ref_err);
  const auto diffs = o.diffs(reps);
  const double conf = std::pow(kGgaaConfidence, 1.0 / double(o.parts.size()));
  CheckResult r;
  r.configurations = g.replicates * int(o.parts.size());
  r.statistic = statistic;
  r.value = compare_paired(diffs[0], conf).mean;
  r.bound = tolerance;
  r.verdict = decide_ordering(diffs, tolerance);
  double detectable = 0;
  for (const auto& d : diffs) detectable = std::max(detectable, compare_paired(d, conf).detectable);
  r.detail = fmt::format(
      "{}; {}. Held to: the claimed order with its interval above 0 (holds), reversed with its "
      "interval below −{:.3f} (fails: the larger of {} RMSE points, Fig. 9's smallest ordering, "
      "and the reference's own error of the difference, {:.3f}), else a tie. Paper (Fig. 9, "
      "1,024 spp): no GGAA 13.484, half slope 7.527 | 8.185, projected half 7.425 | 7.794 % "
      "(s_K 0.5 | 1)",
      describe_bumpy_setup(g, reps), describe_ordering(reps, o, false, false), tolerance,
      kPairTolerance, ref_err);
  r.power = fmt::format(
      "paired difference detected at 90 % power: ≥ {:.3f} % RMSE ((t_{{{:.4f}, {}}} + 1.28) × SE "
      "of the mean over {} replicates, largest over {} part(s))",
      detectable, 0.5 + 0.5 * conf, g.replicates - 1, g.replicates, o.parts.size());
  const bool holding = is_holding(r.verdict);
  const Verdict cv = decide_ordering(o.diffs(reps, !holding, holding), tolerance);
  record_control(r, cv);
  r.control =
      fmt::format("an independent reference × {} (near truth) in place of {}: {} → {} ({})",
                  1 + kGgaaNearTruthBias, holding ? "the claimed higher" : "the claimed lower",
                  describe_ordering(reps, o, !holding, holding), to_string(cv),
                  r.control_rejected ? "rejected" : "NOT rejected");
  return r;
}

const Ordering kDerivativeOrdering{
    {{"projected half s_K 0.5", &BumpyGgaaReplicate::proj05, &BumpyGgaaReplicate::proj05_alt,
      "half slope s_K 0.5", &BumpyGgaaReplicate::half05, &BumpyGgaaReplicate::half05_alt},
     {"projected half s_K 1", &BumpyGgaaReplicate::proj1, &BumpyGgaaReplicate::proj1_alt,
      "half slope s_K 1", &BumpyGgaaReplicate::half1, &BumpyGgaaReplicate::half1_alt}}};
const Ordering kSkOrdering{
    {{"projected half s_K 0.5", &BumpyGgaaReplicate::proj05, &BumpyGgaaReplicate::proj05_alt,
      "projected half s_K 1", &BumpyGgaaReplicate::proj1, &BumpyGgaaReplicate::proj1_alt},
     {"half slope s_K 0.5", &BumpyGgaaReplicate::half05, &BumpyGgaaReplicate::half05_alt,
      "half slope s_K 1", &BumpyGgaaReplicate::half1, &BumpyGgaaReplicate::half1_alt}}};

CheckResult ggaa_sk(Budget b) {
  return run_ordering(kSkOrdering,
                      "display RMSE % of s_K 1 − s_K 0.5 (Eq. 21, then Eq. 20), normal-mapped "
                      "tubes: mean paired difference over replicates",
                      b);
}

// The derivative claim, and whether it is a finding of its own: Eq. 20's kernel is wider than
// Eq. 21's at the same s_K, so its ordering may be the kernel width that chermain.ggaa-sk judges.
// Eq. 21 at the s_K matching Eq. 20's mean width separates the two: where that comparison ties
// and the s_K claim does not hold either, a reversal of this claim is the same cause as ggaa-sk's,
// reported there, not a second finding.
CheckResult ggaa_derivatives(Budget b) {
  CheckResult r = run_ordering(kDerivativeOrdering,
                               "display RMSE % of half slope (Eq. 20) − projected half vector "
                               "(Eq. 21), s_K 0.5 and 1, normal-mapped tubes: mean paired "
                               "difference over replicates",
                               b);
  const std::vector<BumpyGgaaReplicate>& reps = bumpy_replicates(b);
  std::vector<double> matched;
  for (const BumpyGgaaReplicate& x : reps) matched.push_back(x.half05 - x.proj_matched);
  const PairedComparison m = compare_paired(matched, kGgaaConfidence);
  const double tolerance = *r.bound;
  const Verdict matched_verdict = decide_ordering({matched}, tolerance);
  const Verdict sk = decide_ordering(kSkOrdering.diffs(reps),
                                     std::max(kPairTolerance, kSkOrdering.reference_error(reps)));
  r.detail += fmt::format(
      ". Kernel width: Eq. 20's is {:.2f}× Eq. 21's at s_K 0.5 (median over pixels, mean over "
      "replicates); Eq. 21 at the matching s_K {:.3f} {:.3f} % RMSE against half slope s_K 0.5 "
      "{:.3f} %: difference {:+.3f}, {:.0f} % CI [{:+.3f}, {:+.3f}] → {} at equal width",
      mean_field(reps, &BumpyGgaaReplicate::width_ratio),
      mean_field(reps, &BumpyGgaaReplicate::matched_s_k),
      mean_field(reps, &BumpyGgaaReplicate::proj_matched),
      mean_field(reps, &BumpyGgaaReplicate::half05), m.mean, 100 * kGgaaConfidence, m.lo, m.hi,
      to_string(matched_verdict));
  if (r.verdict == Verdict::kFails && matched_verdict != Verdict::kFails && !is_holding(sk)) {
    r.measured_verdict = r.verdict;
    r.verdict = Verdict::kInconclusive;
    r.detail = fmt::format(
        "inconclusive, not a separate finding: the check measured \"fails\", but at equal kernel "
        "width Eq. 20 and Eq. 21 do not differ beyond the tolerance, so the reversal is the "
        "kernel width, the cause chermain.ggaa-sk judges ({} there). Measured: {}",
        to_string(sk), r.detail);
  }
  return r;
}

}  // namespace

// --- chermain.lean-correlation ---------------------------------------------------------------
LeanMeasurement measure_lean(const LeanBudget& b, std::uint64_t seed) {
  NormalMapSceneOptions o;
  o.width = b.width, o.height = b.height, o.threads = b.threads;
  o.groove_p = b.groove_p, o.groove_q = b.groove_q;
  LeanMeasurement m;
  m.reference = render_normal_map_reference(o, b.reference_spp, seed);
  m.no_lean = render_normal_map(o, NormalMapMethod::kNoLean);
  m.lean_rho0 = render_normal_map(o, NormalMapMethod::kLeanRhoZero);
  m.lean = render_normal_map(o, NormalMapMethod::kLean);
  m.rmse_no_lean = display_rmse_percent(m.no_lean, m.reference);
  m.rmse_lean_rho0 = display_rmse_percent(m.lean_rho0, m.reference);
  m.rmse_lean = display_rmse_percent(m.lean, m.reference);
  return m;
}

bool lean_holds(const LeanMeasurement& m) {
  return m.rmse_lean < kLeanMargin * m.rmse_lean_rho0 && m.rmse_lean < kLeanMargin * m.rmse_no_lean;
}

namespace {

// One replicate of chermain.lean-correlation: an independent reference (the renders of the three
// methods are deterministic), the three methods' display RMSE % against it, and the control's
// near-truth image (a second independent reference × (1 + kLeanNearTruthBias)) against it.
struct LeanReplicate {
  double no_lean = 0, rho0 = 0, lean = 0, near_truth = 0;
};
constexpr double kLeanNearTruthBias = 0.03;
// The near-truth reference's samples per pixel: its own noise adds to its RMSE against the
// (independent, equally noisy) reference, so it has at least four times the paper's 64 (half a
// 64-spp reference's noise) and no fewer than the reference.
int lean_near_truth_spp(const LeanBudget& b) { return std::max(256, b.reference_spp); }

std::vector<LeanReplicate> measure_lean_replicates(const LeanBudget& budget, int replicates,
                                                   std::uint64_t first_seed_index,
                                                   int near_truth_spp) {
  std::vector<LeanReplicate> out;
  for (int k = 0; k < replicates; ++k) {
    const std::uint64_t index = first_seed_index + std::uint64_t(k);
    const LeanMeasurement m = measure_lean(budget, check_seed("chermain.lean-correlation", index));
    NormalMapSceneOptions o;
    o.width = budget.width, o.height = budget.height, o.threads = budget.threads;
    o.groove_p = budget.groove_p, o.groove_q = budget.groove_q;
    Image near_truth = render_normal_map_reference(
        o, near_truth_spp, check_seed("chermain.lean-correlation", 1000 + index));
    for (double& v : near_truth.data) v *= 1 + kLeanNearTruthBias;
    out.push_back({m.rmse_no_lean, m.rmse_lean_rho0, m.rmse_lean,
                   display_rmse_percent(near_truth, m.reference)});
  }
  return out;
}

// The two margins the claim needs, per replicate: margin × RMSE(other) − RMSE(LEAN with ρ), other
// = LEAN with ρ = 0 and no LEAN; control: the near-truth image in place of both others.
std::vector<std::vector<double>> lean_margins(const std::vector<LeanReplicate>& reps,
                                              bool control) {
  std::vector<std::vector<double>> parts(2);
  for (const LeanReplicate& r : reps) {
    parts[0].push_back(kLeanMargin * (control ? r.near_truth : r.rho0) - r.lean);
    parts[1].push_back(kLeanMargin * (control ? r.near_truth : r.no_lean) - r.lean);
  }
  return parts;
}

// holds when LEAN with ρ is below kLeanMargin × each other beyond the replicate noise (the paired
// intervals of chermain.ggaa-*, Šidák over the two parts).
Verdict decide_lean(const std::vector<LeanReplicate>& reps, bool control) {
  return decide_ggaa(lean_margins(reps, control));
}

double lean_confidence() { return std::pow(kGgaaConfidence, 0.5); }

std::string describe_lean(const std::vector<LeanReplicate>& reps, bool control) {
  const auto parts = lean_margins(reps, control);
  const double conf = lean_confidence();
  const PairedComparison c0 = compare_paired(parts[0], conf), c1 = compare_paired(parts[1], conf);
  double mean[4] = {0, 0, 0, 0};
  for (const LeanReplicate& r : reps) {
    mean[0] += r.no_lean / double(reps.size()), mean[1] += r.rho0 / double(reps.size());
    mean[2] += r.lean / double(reps.size()), mean[3] += r.near_truth / double(reps.size());
  }
  const std::string others =
      control ? fmt::format("near-truth image {:.3f} % in place of both", mean[3])
              : fmt::format("no LEAN {:.3f} %, LEAN rho = 0 {:.3f} %", mean[0], mean[1]);
  return fmt::format(
      "RMSE (mean over replicates) {}, LEAN with rho {:.3f} %; held to LEAN with rho below {} x "
      "each other: margin over {} {:.3f} [{:.3f}, {:.3f}], over {} {:.3f} [{:.3f}, {:.3f}] RMSE "
      "points (paired t, {:.1f} % each)",
      others, mean[2], kLeanMargin, control ? "the near-truth image" : "rho = 0", c0.mean, c0.lo,
      c0.hi, control ? "it" : "no LEAN", c1.mean, c1.lo, c1.hi, 100 * conf);
}

CheckResult lean_correlation(Budget b) {
  const bool quick = b == Budget::kQuick;
  const LeanBudget budget =
      quick ? LeanBudget{64, 44, 64, 1, 2, 0} : LeanBudget{192, 128, 1024, 1, 2, 0};
  constexpr int kReplicates = 4;
  const std::vector<LeanReplicate> reps =
      measure_lean_replicates(budget, kReplicates, 0, lean_near_truth_spp(budget));
  CheckResult res;
  res.configurations = 3;
  res.statistic = "display RMSE % of LEAN with rho (first replicate)";
  res.value = reps[0].lean;
  res.verdict = decide_lean(reps, false);
  res.detail = fmt::format(
      "grooves across (1, 2), plane {}x{}, {} independent references of {} spp (paper Fig. 7: no "
      "LEAN 8.009, LEAN rho = 0 10.378, LEAN with rho 4.764 %); first replicate: no LEAN {:.3f} %, "
      "LEAN rho = 0 {:.3f} %, LEAN with rho {:.3f} %; {}",
      budget.width, budget.height, kReplicates, budget.reference_spp, reps[0].no_lean, reps[0].rho0,
      reps[0].lean, describe_lean(reps, false));
  // Control: a near-truth image (an independent reference × 1.03) in place of both other
  // methods, through the same decision: LEAN with ρ cannot beat it.
  record_control(res, decide_lean(reps, true));
  const double conf = lean_confidence();
  const auto parts = lean_margins(reps, false);
  double near_truth = 0;
  for (const LeanReplicate& r : reps) near_truth += r.near_truth / double(reps.size());
  res.power = fmt::format(
      "a margin of {:.2g} RMSE points beyond LEAN's {}× line is detected with 90 % power "
      "(paired t over {} references); every RMSE includes the {}-spp reference's own noise: an "
      "image 3 % off the truth scores {:.2f} % against it",
      std::max(compare_paired(parts[0], conf).detectable,
               compare_paired(parts[1], conf).detectable),
      kLeanMargin, kReplicates, budget.reference_spp, near_truth);
  res.control = fmt::format(
      "an independent {}-spp reference × {} (near truth) in place of both no LEAN and LEAN rho = "
      "0: "
      "{} → {} ({})",
      lean_near_truth_spp(budget), 1 + kLeanNearTruthBias, describe_lean(reps, true),
      to_string(*res.control_verdict), res.control_rejected ? "rejected" : "NOT rejected");
  return res;
}

}  // namespace

ControlProbe probe_chermain_kernel_normalized() {
  const chermain2021::Dictionary& d = chermain2021::default_chermain_dictionary();
  const double f = chermain2021::lookup_grad_integral(d, 5, 6, 0.1, 0.01,
                                                      chermain2021::TableWrap::kMirroredRepeat, 4);
  return {std::abs(f - 1), std::abs((1 + kTexelBias) * f - 1), kTableTolerance, false};
}

ControlProbe probe_chermain_dictionary_converges() {
  const Convergence ok = convergence(chermain2021::default_chermain_dictionary(), 16);
  const Convergence bad = convergence(chermain2021::Dictionary(control_dictionary_config()), 16);
  // Statistic: the last level's L1 when the sequence converges, else +inf.
  const auto stat = [](const Convergence& c) { return converges(c) ? c.l1.back() : 1e300; };
  return {stat(ok), stat(bad), kL1Tolerance, false};
}

ControlProbe probe_chermain_correlation() {
  return {correlation(true, 0).rho_err, correlation(true, kControlRhoOffset).rho_err, kRhoTolerance,
          false};
}

LeanDecisionProbe probe_chermain_lean(const LeanBudget& b, int replicates) {
  const std::vector<LeanReplicate> reps =
      measure_lean_replicates(b, replicates, 1u << 20, lean_near_truth_spp(b));
  const auto margins = lean_margins(reps, true);
  double mean = 0;
  for (double m : margins[0]) mean += m / double(margins[0].size());
  return {decide_lean(reps, false), decide_lean(reps, true), mean, describe_lean(reps, true)};
}

std::vector<Check> chermain_checks() {
  return {
      {"chermain.kernel-normalized", kPaper, "Eq. 15, Sec. 6.1, 7", Verdict::kHolds,
       kernel_normalized},
      {"chermain.dictionary-converges", kPaper, "Fig. 3 (Chermain et al. 2020)", Verdict::kHolds,
       dictionary_converges},
      {"chermain.correlation", kPaper, "Eq. 16–18, Fig. 10", Verdict::kHolds, correlation_check},
      {"chermain.ggaa-error", kPaper, "Fig. 8, Sec. 6.2", Verdict::kHolds, ggaa_error},
      {"chermain.ggaa-derivatives", kPaper, "Fig. 9, Sec. 6.2", Verdict::kInconclusive,
       ggaa_derivatives},
      {"chermain.ggaa-sk", kPaper, "Fig. 9, Sec. 6.2", Verdict::kInconclusive, ggaa_sk},
      {"chermain.ggaa-shimmer", kPaper, "Fig. 9, Sec. 6.2", Verdict::kHolds, ggaa_shimmer},
      {"chermain.lean-correlation", kPaper, "Fig. 7, Sec. 5", Verdict::kHolds, lean_correlation},
  };
}

}  // namespace glintlab::verify

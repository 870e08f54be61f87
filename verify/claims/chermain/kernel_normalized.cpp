// chermain.kernel-normalized — Chermain et al. 2021, Eq. 15, Sec. 6.1, 7.
//
// The paper, Sec. 4 (Eq. 15): "Since the marginal distributions P_o are normalized, the filtered
// distribution P_M^22 is normalized and the BRDF is energy preserving if the kernels are
// normalized." Sec. 7: "We noticed no energy creation in our experiments though we have not
// experimentally proved it."
//
// Measured: the integral of every table of the dictionary at every MIP level (float tables, like
// the paper's textures: held to 1e-5 of 1), the textureGrad-filtered marginals (5 kernels,
// mirrored repeat) at every distribution and level (quick: a subset), and by 2D midpoint
// quadrature the patch-SDF's mass with and without GGAA and the white-furnace albedo of the
// glinty BRDF (held to 5e-3). Holds when every one is within its tolerance and the albedo does
// not exceed 1 by more than it. Deterministic: sums over every texel, no sampling noise.
// Control (perturbed): a dictionary with every texel × 1.02 (tables normalized 2 % off); the
// table integrals and filtered marginals are linear in the texels, so they are the genuine ones
// × 1.02 exactly; its patch-SDF terms are kept from the genuine measurement.
// Regime: none.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/glints/chermain.h"
#include "verify/claim_runner.h"
#include "verify/claims/chermain/common.h"

namespace glintlab::verify::chermain_claims {
namespace {

// Tables are float (like the paper's textures): unit integral to a few float ulps.
constexpr double kTableTolerance = 1e-5;
// 2D midpoint quadrature of the patch-SDF mass (and albedo) on the grids below.
constexpr double kPatchTolerance = 5e-3;
// The control's dictionary: every texel × (1 + kTexelBias), tables normalized 2 % off.
constexpr double kTexelBias = 0.02;

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

// One configuration: every table's integral (k = 0), one distribution's filtered marginals, or
// one patch-SDF's mass and albedo.
struct Integrals {
  enum Kind { kTables, kFiltered, kPatch } kind = kTables;
  std::vector<double> integrals;  // tables, filtered
  double mass = 0, albedo = 0;    // patch
};

struct Normalization {
  double tables = 0, filtered = 0, patch = 0, albedo_max = 0;
  int configurations = 0;
};

std::vector<std::pair<double, double>> gradients() {
  return {{0.004, 0.001}, {0.02, 0.02}, {0.1, 0.01}, {0.5, 0.2}, {3.0, 0.5}};
}

}  // namespace

struct KernelNormalized {
  static constexpr std::string_view kId = "chermain.kernel-normalized";
  static constexpr std::string_view kPaper = chermain_claims::kPaper;
  static constexpr std::string_view kSource = "Eq. 15, Sec. 6.1, 7";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Sec. 4 (Eq. 15): \"Since the marginal distributions P_o are normalized, the "
      "filtered distribution P_M^22 is normalized and the BRDF is energy preserving if "
      "the kernels are normalized.\" Sec. 7: \"We noticed no energy creation in our "
      "experiments though we have not experimentally proved it.\"";
  static constexpr std::string_view kStatistic =
      "max |∫ filtered marginal − 1| over tables × MIP levels × kernels";
  static constexpr Expected kExpected{.quick = Verdict::kHolds};

  struct Sizes {
    int distribution_stride, level_stride;  // of the filtered marginals
    int filter_quality;                     // lookup_grad_integral's samples per axis
    int grid;                               // of the patch-SDF quadrature
    std::vector<double> rhos, log2_densities;
  };
  static Sizes sizes(Budget b) {
    if (b == Budget::kQuick) return {16, 3, 4, 200, {0.6}, {22}};
    return {1, 1, 8, 600, {0.0, 0.6, -0.9}, {14, 22, 30}};
  }
  static Sizes probe_sizes() { return {64, 8, 4, 100, {0.6}, {22}}; }

  static const chermain2021::Dictionary& dictionary() {
    return chermain2021::default_chermain_dictionary();
  }
  static int filtered_distributions(const Sizes& z) {
    return (dictionary().distributions() + z.distribution_stride - 1) / z.distribution_stride;
  }
  // Both kernels (none, Eq. 21) at every ρ and density.
  static int patches(const Sizes& z) { return 2 * int(z.rhos.size() * z.log2_densities.size()); }
  static int configurations(const Sizes& z) { return 1 + filtered_distributions(z) + patches(z); }

  using Evidence = Integrals;
  static Evidence observe(const Sizes& z, int k, std::uint64_t) {
    const chermain2021::Dictionary& d = dictionary();
    const chermain2021::TableWrap wrap = chermain2021::TableWrap::kMirroredRepeat;
    Integrals e;
    if (k == 0) {
      for (int n = 0; n < d.distributions(); ++n)
        for (int l = 0; l < d.levels(); ++l)
          for (int m = 0; m < d.mip_levels(); ++m) e.integrals.push_back(d.table_integral(n, l, m));
      return e;
    }
    if (k <= filtered_distributions(z)) {
      e.kind = Integrals::kFiltered;
      const int n = (k - 1) * z.distribution_stride;
      for (int l = 0; l < d.levels(); l += z.level_stride)
        for (auto [gx, gy] : gradients())
          e.integrals.push_back(
              chermain2021::lookup_grad_integral(d, n, l, gx, gy, wrap, z.filter_quality));
      return e;
    }
    e.kind = Integrals::kPatch;
    const int i = k - 1 - filtered_distributions(z);
    const int per_kernel = int(z.rhos.size() * z.log2_densities.size());
    const int kernel = i < per_kernel ? chermain2021::kNoGgaa : chermain2021::kProjectedHalf;
    const double rho = z.rhos[std::size_t(i % per_kernel) / z.log2_densities.size()];
    const double log2_density =
        z.log2_densities[std::size_t(i % per_kernel) % z.log2_densities.size()];
    const FootprintQuery<double> fp{{0.3, 0.7}, {0.004, 0.001}, {-0.001, 0.003}};
    const chermain2021::SlopeDerivatives der{0.06, -0.02, 0.01, 0.04};
    chermain2021::SdfParams p{&d, 0.3, 0.2, rho, log2_density, kernel, 0.5, 17};
    p.wrap = wrap;
    e.mass = chermain2021::patch_moments(p, fp, der, z.grid).mass;
    e.albedo = albedo(p, fp, der, normalize(Vec3<double>{0.4, 0.2, 1}), z.grid);
    return e;
  }

  using Measured = Normalization;
  static Measured measure(const Sizes&, std::span<const Evidence> all, Input input) {
    const double scale = input == Input::kGenuine ? 1.0 : 1 + kTexelBias;
    Normalization r;
    for (const Integrals& e : all) {
      if (e.kind == Integrals::kPatch) {
        r.patch = std::max(r.patch, std::abs(e.mass - 1));
        r.albedo_max = std::max(r.albedo_max, e.albedo);
        ++r.configurations;
        continue;
      }
      double& worst = e.kind == Integrals::kTables ? r.tables : r.filtered;
      for (double integral : e.integrals) worst = std::max(worst, std::abs(scale * integral - 1));
      r.configurations += int(e.integrals.size());
    }
    return r;
  }

  // holds when every table, filtered marginal and patch-SDF mass is within its tolerance of 1
  // and the white-furnace albedo does not exceed 1 by more than the patch tolerance.
  static Decision decide(const Sizes&, const Measured& r) {
    const bool ok = r.tables <= kTableTolerance && r.filtered <= kTableTolerance &&
                    r.patch <= kPatchTolerance && r.albedo_max <= 1 + kPatchTolerance;
    return {.verdict = ok ? Verdict::kHolds : Verdict::kFails,
            .value = std::max(r.tables, r.filtered),
            .bound = kTableTolerance,
            .configurations = r.configurations};
  }

  static std::string describe(const Sizes&, const Measured& r, Input input) {
    const std::string measured = fmt::format(
        "every table at every MIP level: max |∫−1| = {:.2g}; textureGrad-filtered marginals (5 "
        "kernels, mirrored repeat): {:.2g} (held to {:.0e}); patch-SDF mass with/without GGAA by "
        "2D quadrature: max |∫−1| = {:.2g}, white-furnace albedo max {:.4f} (held to {:.0e})",
        r.tables, r.filtered, kTableTolerance, r.patch, r.albedo_max, kPatchTolerance);
    if (input == Input::kGenuine) return measured;
    return fmt::format("every texel × {} (tables normalized {:.0f} % off): {}", 1 + kTexelBias,
                       100 * kTexelBias, measured);
  }

  static std::string power(const Sizes&, const Measured& r, const Measured&) {
    return fmt::format(
        "deterministic (sums over every texel of every table and level, no sampling noise): a "
        "table or filtered marginal whose integral is off 1 by more than {:.0e} anywhere is "
        "detected, every time (the genuine error is {:.2g}); the control's {:.0f} % is {:.0f}× "
        "the tolerance",
        kTableTolerance, std::max(r.tables, r.filtered), 100 * kTexelBias,
        kTexelBias / kTableTolerance);
  }
};

}  // namespace glintlab::verify::chermain_claims

GLINTLAB_CLAIM(glintlab::verify::chermain_claims::KernelNormalized);

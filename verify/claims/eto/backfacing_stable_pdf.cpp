// eto.backfacing-stable-pdf — Eto & Tokuyoshi 2023, Eq. 7, Listing 2 (i_z < 0).
//
// The paper, Listing 2's caption: "For i_z < 0, we calculate the previous PDF p(m)‖dm/do‖ using a
// numerically stable form (please see the supplemental document for derivation)."; Eq. 7 is that
// previous PDF, p(m) = 2 D(m) max(i·m, 0) / (i_z + √(αx² i_x² + αy² i_y² + i_z²)).
//
// Measured: for back-facing incidence (θi from 90° + 1e-6 to 179.999°, i.e. i_z → 0⁻ and i_z → −1
// where i_z + t cancels) over α 1e-3–2 and anisotropy, and a spiral of ωo over the upper hemisphere
// plus reflection-like directions, the stable form D (t − i_z)/(2 len2) of Listing 2, and the
// samplers' back-facing densities that use it, against Eq. 7 × 1/(4|o·m|) evaluated in 50 digits:
// the largest relative error of the factor beside D (which both forms share), held to 1e-12
// (rounding is ~1e-15). Beside it: Eq. 7 as printed in double and float, and the whole density.
// Control (perturbed): the stable form 2 % too large, in Listing 2's function and the samplers'
// densities: must fail.
// Regime: none.
#include <fmt/format.h>

#include <algorithm>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "core/samplers/bounded_vndf.h"
#include "core/samplers/spherical_caps.h"
#include "verify/claim_runner.h"
#include "verify/claims/eto/common.h"
#include "verify/claims/eto/list.h"

namespace glintlab::verify::eto_claims {
namespace {

using V3 = Vec3<double>;
constexpr double kBackfacingTolerance = 1e-12;    // relative; rounding is ~1e-15
constexpr double kBackfacingControlScale = 1.02;  // the control: the stable form 2 % too large

using Big = boost::multiprecision::cpp_bin_float_50;

struct BigVec {
  Big x, y, z;
};
// The direction of a (nearly unit) double vector, exactly normalised in 50 digits: the inputs are
// directions, and Eq. 7's i·m / (4|o·m|) is only the density for unit i and o (for i ≈ −o a
// rounding-level |i| ≠ |o| would otherwise move the reference by ~ε/|i + o|²).
BigVec unit(V3 v) {
  const Big x = v.x, y = v.y, z = v.z;
  const Big l = sqrt(x * x + y * y + z * z);
  return {x / l, y / l, z / l};
}

// Eq. 7 × 1/(4|o·m|) as printed, in 50 digits, for the given directions; and the same divided by
// D(m): the factor 2 max(i·m, 0)/((i_z + t) 4|o·m|) that the stable form rewrites as
// (t − i_z)/(2 len2). D itself is common to both forms (and, for tiny α, ill-conditioned in the
// direction), so the forms are compared on the factor; the full density is reported as well.
struct Eq7Reference {
  Big density, factor;
};
Eq7Reference eq7_reference(double ax, double ay, V3 wi_d, V3 wo_d) {
  const BigVec wi = unit(wi_d), wo = unit(wo_d);
  const Big hx = wi.x + wo.x, hy = wi.y + wo.y, hz = wi.z + wo.z;
  const Big len = sqrt(hx * hx + hy * hy + hz * hz);
  const Big mx = hx / len, my = hy / len, mz = hz / len;
  if (!(mz > 0)) return {Big(0), Big(0)};
  const Big e = (mx / ax) * (mx / ax) + (my / ay) * (my / ay) + mz * mz;
  const Big d = 1 / (boost::math::constants::pi<Big>() * Big(ax) * Big(ay) * e * e);
  const Big im = wi.x * mx + wi.y * my + wi.z * mz;
  const Big om = wo.x * mx + wo.y * my + wo.z * mz;
  const Big len2 = (ax * wi.x) * (ax * wi.x) + (ay * wi.y) * (ay * wi.y);
  const Big t = sqrt(len2 + wi.z * wi.z);
  const Big factor = 2 * (im > 0 ? im : Big(0)) / (wi.z + t) / (4 * abs(om));
  return {d * factor, factor};
}

template <class T>
Vec3<T> cast3(V3 v) {
  return {T(v.x), T(v.y), T(v.z)};
}

// The largest error and where it was first reached (a NaN counts as infinite and takes the place).
struct Worst {
  double err = 0;
  std::string where = {};
  bool nan = false;  // the last update that took the place was a NaN
  void update(double e, const std::string& w) {
    if (!(e <= err))
      err = std::isnan(e) ? std::numeric_limits<double>::infinity() : e, where = w,
      nan = std::isnan(e);
  }
  // Another incidence's worst, taken as if its errors followed this one's.
  void merge(const Worst& o) {
    update(o.nan ? std::numeric_limits<double>::quiet_NaN() : o.err, o.where);
  }
};

// The worst relative errors of each form against the reference.
struct BackfacingErrors {
  Worst stable, printed, stable_f, printed_f, samplers, stable_density, printed_density;
  std::size_t evaluated = 0;

  void merge(const BackfacingErrors& o) {
    stable.merge(o.stable), printed.merge(o.printed), stable_f.merge(o.stable_f);
    printed_f.merge(o.printed_f), samplers.merge(o.samplers);
    stable_density.merge(o.stable_density), printed_density.merge(o.printed_density);
    evaluated += o.evaluated;
  }
};

// Both forms at one back-facing incidence θ (degrees) for (αx, αy), over n_o directions ωo; every
// value of the stable form (Listing 2's function and the samplers' back-facing densities) times
// `scale`.
BackfacingErrors backfacing_errors(double ax, double ay, double th, int n_o, double scale) {
  BackfacingErrors out;
  auto& [stable, printed, stable_f, printed_f, samplers, stable_density, printed_density,
         evaluated] = out;
  const V3 wi = incidence(th);
  for (int j = 0; j < n_o; ++j) {
    // A spiral over the upper hemisphere, plus the reflection-like directions near −wi's
    // mirror, where h stays near the normal.
    const double u = (j + 0.5) / n_o;
    const double to = std::acos(1 - u), po = 2.399963229728653 * j;
    V3 wo = direction(to, po);
    if (j % 3 == 0) wo = normalize(V3{-wi.x + 0.3 * u, -wi.y, std::abs(wi.z) + 0.1});
    const GGX<double> g{ax, ay};
    if (!(g.D(half_vector(wi, wo)) > 0)) continue;
    ++evaluated;
    const std::string where = fmt::format("αx={:g} αy={:g} θi={:g}°", ax, ay, th);
    const Eq7Reference ref = eq7_reference(ax, ay, wi, wo);
    auto rel = [&](double v, const Big& want) {
      return static_cast<double>(abs(Big(v) / want - 1));
    };
    const double d = g.D(half_vector(wi, wo));  // the value both forms compute
    const double p_stable = scale * pdf_vndf_backfacing_stable(g, wi, wo);
    const double p_printed = pdf_vndf_backfacing_eq7(g, wi, wo);
    stable.update(rel(p_stable / d, ref.factor), where);
    printed.update(rel(p_printed / d, ref.factor), where);
    stable_density.update(rel(p_stable, ref.density), where);
    printed_density.update(rel(p_printed, ref.density), where);
    // The samplers' own densities for i_z < 0 are the stable form.
    for (double v :
         {pdf_spherical_caps(g, wi, wo), pdf_bounded_vndf(g, wi, wo, BoundedVndfBound::kListing1),
          pdf_bounded_vndf(g, wi, wo, BoundedVndfBound::kExactIsotropic)})
      samplers.update(rel(scale * v / d, ref.factor), where);
    // Float: the inputs rounded to float, the reference recomputed for those inputs.
    const Vec3<float> wif = cast3<float>(wi), wof = cast3<float>(wo);
    const float axf = float(ax), ayf = float(ay);
    const GGX<float> gf{axf, ayf};
    const float df = gf.D(half_vector(wif, wof));
    if (!(df > 0) || !(wif.z < 0)) continue;
    const Eq7Reference ref_f =
        eq7_reference(axf, ayf, V3{wif.x, wif.y, wif.z}, V3{wof.x, wof.y, wof.z});
    stable_f.update(
        rel(scale * double(pdf_vndf_backfacing_stable(gf, wif, wof) / df), ref_f.factor), where);
    printed_f.update(rel(double(pdf_vndf_backfacing_eq7(gf, wif, wof) / df), ref_f.factor), where);
  }
  return out;
}

double statistic_of(const BackfacingErrors& e) { return std::max(e.stable.err, e.samplers.err); }

}  // namespace

struct BackfacingStablePdf {
  static constexpr std::string_view kId = "eto.backfacing-stable-pdf";
  static constexpr std::string_view kPaper = eto_claims::kPaper;
  static constexpr std::string_view kSource = "Eq. 7, Listing 2 (i_z < 0)";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Listing 2 caption: \"For i_z < 0, we calculate the previous PDF p(m)‖dm/do‖ "
      "using a numerically stable form\"; Listing 2: \"return ndf * (t - i.z) / (2.0f * "
      "len2); // = Eq. 7 * ||dm/do||\", with Eq. 7: p(m) = 2D(m) max(i·m, 0) / (i_z + "
      "√(α_x² i_x² + α_y² i_y² + i_z²))";
  static constexpr std::string_view kStatistic =
      "max relative error of the stable factor (t − i_z)/(2 len2) vs Eq. 7's (50-digit), double";
  static constexpr Expected kExpected{.quick = Verdict::kHolds};

  struct Sizes {
    std::vector<double> alphas, ratios, thetas;  // α, αx/αy, θi > 90° (degrees)
    int n_o;                                     // ωo directions per incidence
  };
  static Sizes sizes(Budget b) {
    // i_z → 0⁻ (just below the horizon) and i_z → −1 (where i_z + t cancels).
    Sizes z{{1e-3, 0.05, 0.5, 2.0},
            {1, 10},
            {90 + 1e-6, 90 + 1e-3, 90.5, 100, 120, 150, 170, 179, 179.9, 179.999},
            12};
    if (b == Budget::kQuick) return z;
    z.alphas = {1e-4, 1e-3, 0.01, 0.05, 0.2, 0.5, 1.0, 2.0};
    z.ratios = {1, 3, 30};
    z.thetas.insert(z.thetas.end(), {90 + 1e-9, 91, 135, 160, 175, 179.99, 179.9999});
    z.n_o = 48;
    return z;
  }
  static Sizes probe_sizes() { return {{1e-3, 0.5}, {1, 10}, {90.001, 120, 179.9}, 6}; }

  // Configuration k: α index k / (ratios × θi), then the ratio, then θi. The errors of the stable
  // form as written and with the control's bias, both against the one 50-digit reference.
  struct Evidence {
    BackfacingErrors as_written, biased;
  };
  static int configurations(const Sizes& z) {
    return int(z.alphas.size() * z.ratios.size() * z.thetas.size());
  }
  static Evidence observe(const Sizes& z, int k, std::uint64_t) {
    const std::size_t nt = z.thetas.size(), nr = z.ratios.size(), i = std::size_t(k);
    const double a = z.alphas[i / (nr * nt)], r = z.ratios[i / nt % nr], th = z.thetas[i % nt];
    return {backfacing_errors(a, a / r, th, z.n_o, 1),
            backfacing_errors(a, a / r, th, z.n_o, kBackfacingControlScale)};
  }

  struct Measured {
    BackfacingErrors e;
    double scale = 1;  // the factor on every evaluation of the stable form (1: as written)
  };
  static Measured measure(const Sizes&, std::span<const Evidence> ev, Input input) {
    Measured m{{}, input == Input::kGenuine ? 1 : kBackfacingControlScale};
    for (const Evidence& x : ev) m.e.merge(input == Input::kGenuine ? x.as_written : x.biased);
    return m;
  }

  // The stable form (and the samplers' densities, which use it) equals Eq. 7 to rounding.
  static Decision decide(const Sizes&, const Measured& m) {
    return {
        .verdict = statistic_of(m.e) <= kBackfacingTolerance ? Verdict::kHolds : Verdict::kFails,
        .value = statistic_of(m.e),
        .bound = kBackfacingTolerance,
        .configurations = int(m.e.evaluated)};
  }

  // Both forms' worst errors in double and float, and where.
  static std::string describe(const Sizes& z, const Measured& m, Input input) {
    const BackfacingErrors& e = m.e;
    if (input != Input::kGenuine)
      return fmt::format(
          "stable form × {:g} (a {:g} % bias, in Listing 2's function and the samplers' "
          "densities): max rel. error {:.3g}",
          m.scale, 100 * (m.scale - 1), statistic_of(e));
    const double min_iz =
        std::cos(*std::min_element(z.thetas.begin(), z.thetas.end()) * std::numbers::pi / 180);
    return fmt::format(
        "{} (ωi, ωo) pairs, i_z from {:.1e} to −1: stable form max rel. error {:.2g} in double "
        "({}), {:.2g} in float; samplers' back-facing pdfs {:.2g}; Eq. 7 as printed loses "
        "precision: {:.2g} in double ({}), {:.2g} in float ({}); whole density incl. D (whose "
        "conditioning in the direction is common to both forms): stable {:.2g}, printed {:.2g} in "
        "double",
        e.evaluated, min_iz, e.stable.err, e.stable.where, e.stable_f.err, e.samplers.err,
        e.printed.err, e.printed.where, e.printed_f.err, e.printed_f.where, e.stable_density.err,
        e.printed_density.err);
  }

  static std::string power(const Sizes&, const Measured&, const Measured&) {
    return fmt::format(
        "deterministic against a 50-digit reference: a relative error above {:g} anywhere on the "
        "grid is detected",
        kBackfacingTolerance);
  }
};

}  // namespace glintlab::verify::eto_claims

GLINTLAB_CLAIM(glintlab::verify::eto_claims::BackfacingStablePdf);

// Smooth microfacet baselines (Walter et al. 2007; Heitz 2014, 2018): normalisation of the NDF
// over projected area and of the distribution of visible normals, by adaptive cubature.
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "verify/claims/claims.h"
#include "verify/claims/gof_family.h"
#include "verify/stats/ndf_cubature.h"

namespace glintlab::verify {
namespace {

struct Config {
  bool ggx;
  double ax, ay;
  double theta_i_deg = 0;  // for the VNDF check
};

const char* ndf_name(bool ggx) { return ggx ? "GGX" : "Beckmann"; }

std::vector<Config> roughness_grid(Budget b) {
  std::vector<std::pair<double, double>> alphas;
  const int n = b == Budget::kQuick ? 6 : 16;
  for (int i = 0; i < n; ++i) {  // log-spaced 1e-3 .. 2
    const double a = 1e-3 * std::pow(2000.0, i / double(n - 1));
    alphas.push_back({a, a});
  }
  for (double ratio : b == Budget::kQuick ? std::vector<double>{5, 1000}
                                          : std::vector<double>{2, 5, 30, 100, 1000})
    for (double ay : {0.5, 1.0}) alphas.push_back({ay / ratio, ay});
  std::vector<Config> grid;
  for (bool ggx : {true, false})
    for (auto [ax, ay] : alphas) grid.push_back({ggx, ax, ay});
  return grid;
}

// A scale on D turns the true NDF into the negative control (2 % too much mass).
template <class Ndf>
struct ScaledNdf {
  Ndf ndf;
  double scale;
  double D(const Vec3<double>& m) const { return scale * ndf.D(m); }
  double projected_area(const Vec3<double>& w) const { return scale * ndf.projected_area(w); }
};

// Measure: per configuration, |integral − 1| and the cubature's error estimate.
struct NormalizationRow {
  Config c;
  double error = 0;       // |integral − 1|
  double quadrature = 0;  // cubature error estimate
};
struct NormalizationMeasurement {
  std::vector<NormalizationRow> rows;
  double scale = 1;  // the factor on D (1: the true NDF)
};

constexpr double kTolerance = 1e-6;  // far above cubature error (~1e-10), far below 2 %
constexpr double kControlScale = 1.02;

template <class F>
NormalizationRow normalization(const Config& c, double scale, F&& integrand_of_ndf) {
  auto run = [&](auto ndf) {
    const ScaledNdf<decltype(ndf)> scaled{ndf, scale};
    const Integral r = integrand_of_ndf(scaled, c);
    return NormalizationRow{c, std::abs(r.value - 1), r.error};
  };
  return c.ggx ? run(GGX<double>{c.ax, c.ay}) : run(Beckmann<double>{c.ax, c.ay});
}

// Runs `measure(config, scale)` over the configurations in parallel; rows land in grid order, so
// the outcome does not depend on the thread count.
template <class Measure>
NormalizationMeasurement measure_normalization(const std::vector<Config>& grid, double scale,
                                               Measure&& measure) {
  NormalizationMeasurement m{std::vector<NormalizationRow>(grid.size()), scale};
  tbb::parallel_for(std::size_t(0), grid.size(),
                    [&](std::size_t i) { m.rows[i] = measure(grid[i], scale); });
  return m;
}

std::size_t worst_row(const NormalizationMeasurement& m) {
  std::size_t worst = 0;
  for (std::size_t i = 0; i < m.rows.size(); ++i)
    if (m.rows[i].error > m.rows[worst].error) worst = i;
  return worst;
}

double largest_quadrature(const NormalizationMeasurement& m) {
  double quad = 0;
  for (const NormalizationRow& r : m.rows) quad = std::max(quad, r.quadrature);
  return quad;
}

// Decide: inconclusive where the cubature cannot resolve the tolerance; otherwise holds when the
// worst error is within it.
Verdict decide_normalization(const NormalizationMeasurement& m) {
  if (m.rows.empty() || largest_quadrature(m) > 0.1 * kTolerance) return Verdict::kInconclusive;
  return m.rows[worst_row(m)].error <= kTolerance ? Verdict::kHolds : Verdict::kFails;
}

// Describe: where the worst error is and how well the cubature resolved it.
std::string describe_normalization(const NormalizationMeasurement& m) {
  const NormalizationRow& w = m.rows[worst_row(m)];
  return fmt::format("worst {} at {} αx={:.3g} αy={:.3g}{}; cubature error estimate ≤ {:.1e}",
                     w.error, ndf_name(w.c.ggx), w.c.ax, w.c.ay,
                     w.c.theta_i_deg != 0 ? fmt::format(" θi={}°", w.c.theta_i_deg) : "",
                     largest_quadrature(m));
}

// The check: the grid through measure, decide and describe; the control, D × 1.02 on the first,
// the middle and the last configuration, each decided alone by the same decision.
template <class Measure>
CheckResult normalization_check(const std::vector<Config>& grid, Measure&& measure,
                                const std::string& statistic) {
  const NormalizationMeasurement m = measure_normalization(grid, 1.0, measure);
  CheckResult r;
  r.statistic = statistic;
  r.bound = kTolerance;
  r.configurations = int(m.rows.size());
  r.value = m.rows[worst_row(m)].error;
  r.verdict = decide_normalization(m);
  r.detail = describe_normalization(m);
  r.power = fmt::format(
      "deterministic (cubature, error estimate ≤ {:.1e}): any normalisation error above {:g} is "
      "detected, every time",
      largest_quadrature(m), kTolerance);
  std::vector<Verdict> cases;
  double control_min = 1e300;
  for (std::size_t i : {std::size_t(0), grid.size() / 2, grid.size() - 1}) {
    const NormalizationMeasurement c = measure_normalization({grid[i]}, kControlScale, measure);
    cases.push_back(decide_normalization(c));
    control_min = std::min(control_min, c.rows[0].error);
  }
  record_control(r, control_verdict_of_cases(cases));
  r.control = fmt::format(
      "D scaled by {:g}, each of {} configurations decided alone: smallest error {:.3g} → {} ({})",
      kControlScale, cases.size(), control_min, to_string(*r.control_verdict),
      r.control_rejected ? "rejected" : "NOT rejected");
  return r;
}

CheckResult projected_area(Budget b) {
  const auto grid = roughness_grid(b);
  auto measure = [](const Config& c, double scale) {
    return normalization(c, scale, [](const auto& ndf, const Config& cc) {
      return integrate_ndf_lobe([&](const Vec3<double>& m) { return ndf.D(m) * m.z; }, cc.ax, cc.ay,
                                true);
    });
  };
  return normalization_check(grid, measure, "max |∫ D(m) m·n dm − 1|");
}

CheckResult vndf_normalized(Budget b) {
  std::vector<Config> grid;
  const std::vector<double> thetas = b == Budget::kQuick
                                         ? std::vector<double>{0, 45, 80, 89.9}
                                         : std::vector<double>{0, 15, 30, 45, 60, 75, 85, 89, 89.9};
  for (Config c : roughness_grid(b))
    for (double t : thetas) {
      c.theta_i_deg = t;
      grid.push_back(c);
    }
  auto measure = [](const Config& c, double scale) {
    return normalization(c, scale, [](const auto& ndf, const Config& cc) {
      const double t = cc.theta_i_deg * std::numbers::pi / 180;
      const Vec3<double> wi{std::sin(t) * std::cos(0.3), std::sin(t) * std::sin(0.3), std::cos(t)};
      // The scaled NDF scales D and the projected area alike, so the control must break the
      // normalisation through D alone: integrate max(0, ωi·m) D(m) / A_true(ωi).
      const double a = ndf.ndf.projected_area(wi);
      return integrate_ndf_lobe(
          [&](const Vec3<double>& m) { return std::max(0.0, dot(wi, m)) * ndf.D(m) / a; }, cc.ax,
          cc.ay, true, 1e-10, &wi);
    });
  };
  return normalization_check(grid, measure, "max |∫ D_ωi(m) dm − 1|");
}

}  // namespace

std::vector<Check> smooth_checks() {
  return {
      {"smooth.projected-area", "Walter et al. 2007; Heitz 2014",
       "∫ D(ω)(ω·n) dω = 1 (Heitz 2014 Eq. 4)", Verdict::kHolds, projected_area},
      {"smooth.vndf-normalized", "Heitz 2018", "D_ωi(ω) integrates to 1 (Heitz 2018 Eq. 1)",
       Verdict::kHolds, vndf_normalized},
  };
}

}  // namespace glintlab::verify

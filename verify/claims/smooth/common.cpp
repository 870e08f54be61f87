#include "verify/claims/smooth/common.h"

namespace glintlab::verify::smooth_claims {
namespace {

const char* ndf_name(bool ggx) { return ggx ? "GGX" : "Beckmann"; }

}  // namespace

std::vector<NdfConfig> roughness_grid(Budget b) {
  std::vector<std::pair<double, double>> alphas;
  const int n = b == Budget::kQuick ? 6 : 16;
  for (int i = 0; i < n; ++i) {  // log-spaced 1e-3 .. 2
    const double a = 1e-3 * std::pow(2000.0, i / double(n - 1));
    alphas.push_back({a, a});
  }
  for (double ratio : b == Budget::kQuick ? std::vector<double>{5, 1000}
                                          : std::vector<double>{2, 5, 30, 100, 1000})
    for (double ay : {0.5, 1.0}) alphas.push_back({ay / ratio, ay});
  std::vector<NdfConfig> grid;
  for (bool ggx : {true, false})
    for (auto [ax, ay] : alphas) grid.push_back({ggx, ax, ay});
  return grid;
}

std::size_t worst_row(std::span<const NormalizationRow> rows) {
  std::size_t worst = 0;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i].error > rows[worst].error) worst = i;
  return worst;
}

double largest_quadrature(std::span<const NormalizationRow> rows) {
  double quad = 0;
  for (const NormalizationRow& r : rows) quad = std::max(quad, r.quadrature);
  return quad;
}

Verdict decide_normalization(std::span<const NormalizationRow> rows) {
  if (rows.empty() || largest_quadrature(rows) > 0.1 * kNormalizationTolerance)
    return Verdict::kInconclusive;
  return rows[worst_row(rows)].error <= kNormalizationTolerance ? Verdict::kHolds : Verdict::kFails;
}

std::string describe_normalization(std::span<const NormalizationRow> rows) {
  const NormalizationRow& w = rows[worst_row(rows)];
  return fmt::format("worst {} at {} αx={:.3g} αy={:.3g}{}; cubature error estimate ≤ {:.1e}",
                     w.error, ndf_name(w.c.ggx), w.c.ax, w.c.ay,
                     w.c.theta_i_deg != 0 ? fmt::format(" θi={}°", w.c.theta_i_deg) : "",
                     largest_quadrature(rows));
}

std::vector<std::size_t> control_configurations(std::size_t n) { return {0, n / 2, n - 1}; }

}  // namespace glintlab::verify::smooth_claims

// smooth.vndf-normalized — Heitz 2018, Eq. 1.
//
// The paper (Heitz 2018, Eq. 1): D_ωi(ω_m) = G1(ω_i) max(0, ω_i·ω_m) D(ω_m) / (ω_i·ω_g), with
// ∫_Ω D_ωi(ω_m) dω_m = 1; Eto & Tokuyoshi 2023, Sec. 3.3: "The VNDF is the PDF for visible
// microfacet normals", p(m) = 2D(m) max(i·m, 0) / (i_z + √(α_x² i_x² + α_y² i_y² + i_z²)) (Eq. 7).
//
// Measured: |∫ max(0, ωi·m) D(m) / A(ωi) dm − 1| by adaptive cubature, per configuration: GGX and
// Beckmann over the roughness grid of smooth.projected-area × θi ∈ {0°, 45°, 80°, 89.9°} (full:
// nine incidences 0° … 89.9°); holds when the worst error is within 10^-6, inconclusive where the
// cubature cannot resolve that tolerance.
// Control (perturbed): D scaled by 1.02 (the projected area A(ωi) kept true) on the first, the
// middle and the last configuration, each decided alone: every one must fail.
// Regime: none. Deterministic.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include "verify/claim_runner.h"
#include "verify/claims/smooth/common.h"
#include "verify/claims/smooth/list.h"

namespace glintlab::verify::smooth_claims {

struct VndfNormalized : NormalizationClaim<VndfNormalized> {
  static constexpr std::string_view kId = "smooth.vndf-normalized";
  static constexpr std::string_view kPaper = "Heitz 2018";
  static constexpr std::string_view kSource = "D_ωi(ω) integrates to 1 (Heitz 2018 Eq. 1)";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Eto & Tokuyoshi 2023, Sec. 3.3: \"The VNDF is the PDF for visible microfacet "
      "normals. For the Smith-GGX model, this PDF is given by\" p(m) = 2D(m) max(i·m, "
      "0) / (i_z + √(α_x² i_x² + α_y² i_y² + i_z²)) (Eq. 7); Heitz 2018 (Eq. 1 as "
      "registered): D_ωi(ω_m) = G1(ω_i) max(0, ω_i·ω_m) D(ω_m) / (ω_i·ω_g), ∫_Ω "
      "D_ωi(ω_m) dω_m = 1";
  static constexpr std::string_view kStatistic = "max |∫ D_ωi(m) dm − 1|";

  static std::vector<NdfConfig> grid(Budget b) {
    std::vector<NdfConfig> grid;
    const std::vector<double> thetas =
        b == Budget::kQuick ? std::vector<double>{0, 45, 80, 89.9}
                            : std::vector<double>{0, 15, 30, 45, 60, 75, 85, 89, 89.9};
    for (NdfConfig c : roughness_grid(b))
      for (double t : thetas) {
        c.theta_i_deg = t;
        grid.push_back(c);
      }
    return grid;
  }
  static NormalizationRow row(const NdfConfig& c, double scale) {
    return normalization(c, scale, [](const auto& ndf, const NdfConfig& cc) {
      const double t = cc.theta_i_deg * std::numbers::pi / 180;
      const Vec3<double> wi{std::sin(t) * std::cos(0.3), std::sin(t) * std::sin(0.3), std::cos(t)};
      // The scaled NDF scales D and the projected area alike, so the control must break the
      // normalisation through D alone: integrate max(0, ωi·m) D(m) / A_true(ωi).
      const double a = ndf.ndf.projected_area(wi);
      return integrate_ndf_lobe(
          [&](const Vec3<double>& m) { return std::max(0.0, dot(wi, m)) * ndf.D(m) / a; }, cc.ax,
          cc.ay, true, 1e-10, &wi);
    });
  }
};

}  // namespace glintlab::verify::smooth_claims

GLINTLAB_CLAIM(glintlab::verify::smooth_claims::VndfNormalized);

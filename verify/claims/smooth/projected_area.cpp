// smooth.projected-area — Walter et al. 2007; Heitz 2014, Eq. 4.
//
// The paper (Heitz 2014, Eq. 4): ∫_Ω D(ω_m) (ω_m·ω_g) dω_m = 1, the microsurface's projected area
// equals the macrosurface's, for GGX and Beckmann (Walter et al. 2007), isotropic and anisotropic.
//
// Measured: |∫ D(m) m·n dm − 1| by adaptive cubature over the upper hemisphere, per configuration:
// GGX and Beckmann at isotropic α log-spaced 10^-3 … 2 and anisotropic αx:αy up to 1:1000; holds
// when the worst error is within 10^-6 (far above the cubature's error estimate, ~10^-10),
// inconclusive where the cubature cannot resolve that tolerance.
// Control (perturbed): D scaled by 1.02 on the first, the middle and the last configuration, each
// decided alone: every one must fail.
// Regime: none. Deterministic.
#include <span>
#include <vector>

#include "verify/claim_runner.h"
#include "verify/claims/smooth/common.h"
#include "verify/claims/smooth/list.h"

namespace glintlab::verify::smooth_claims {

struct ProjectedArea : NormalizationClaim<ProjectedArea> {
  static constexpr std::string_view kId = "smooth.projected-area";
  static constexpr std::string_view kPaper = "Walter et al. 2007; Heitz 2014";
  static constexpr std::string_view kSource = "∫ D(ω)(ω·n) dω = 1 (Heitz 2014 Eq. 4)";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Heitz 2014, Eq. 4: ∫_Ω D(ω_m) (ω_m·ω_g) dω_m = 1 (GGX and Beckmann of Walter et "
      "al. 2007, isotropic and anisotropic)";
  static constexpr std::string_view kStatistic = "max |∫ D(m) m·n dm − 1|";

  static std::vector<NdfConfig> grid(Budget b) { return roughness_grid(b); }
  static NormalizationRow row(const NdfConfig& c, double scale) {
    return normalization(c, scale, [](const auto& ndf, const NdfConfig& cc) {
      return integrate_ndf_lobe([&](const Vec3<double>& m) { return ndf.D(m) * m.z; }, cc.ax, cc.ay,
                                true);
    });
  }
};

}  // namespace glintlab::verify::smooth_claims

GLINTLAB_CLAIM(glintlab::verify::smooth_claims::ProjectedArea);

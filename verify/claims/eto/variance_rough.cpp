// eto.variance-rough — Eto & Tokuyoshi 2023, Sec. 4, Figs. 4–6 (α = 0.8).
//
// The paper, Sec. 4: "Our method reduces errors, especially for high-roughness surfaces (α_x =
// α_y = 0.8 in Fig. 4)." and "Since our bounding spherical cap is tighter for lower anisotropy, our
// method is efficient, especially for low anisotropy."
//
// Measured: per configuration (α 0.05–1 × αx/αy × θi), the RMSE reduction 1 − √(M2_b/M2_c) of
// the bounded estimator against the spherical-cap one at equal sample count, from the second
// moments of both samplers' weights, with its interval (Šidák over the configurations); shared
// with eto.variance-smooth (gain.h says why this ratio is the one that holds under any lighting).
// Holds in the regime where every regime configuration's interval lies above a material 5 %
// reduction; fails where one lies below.
// Control (perturbed): an estimator with a 2 % reduction (the spherical-cap sampler against an
// independent run of itself, its RMSE × 0.98): must fail.
// Regime, declared before measuring: isotropic α ≥ 0.8 ("high-roughness", "low anisotropy"),
// θi ≤ 60° (towards grazing the two caps meet for every α).
#include "verify/claim_runner.h"
#include "verify/claims/eto/gain.h"
#include "verify/claims/eto/list.h"

namespace glintlab::verify::eto_claims {

struct VarianceRough : GainSteps<true> {
  static constexpr std::string_view kId = "eto.variance-rough";
  static constexpr std::string_view kSource = "Sec. 4, Figs. 4–6 (α = 0.8)";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Sec. 4: \"Our method reduces errors, especially for high-roughness surfaces (α_x "
      "= α_y = 0.8 in Fig. 4).\" \"Since our bounding spherical cap is tighter for "
      "lower anisotropy, our method is efficient, especially for low anisotropy.\"";
  // What the check tests beyond the quote (so a verdict on it is never the paper failing).
  static constexpr std::string_view kStrongerReading =
      "A reduction is held to at least 5 % of the RMSE (kMaterialGain, a "
      "threshold the project chose; the paper states no size), shown by the "
      "interval in every isotropic configuration with α ≥ 0.8 and θi ≤ 60°. "
      "It is measured on the second moment of the single-scattering weight "
      "(F = 1) per incident direction, not on the path-traced, "
      "energy-compensated orb renders of Figs. 4–6.";
  static constexpr std::string_view kStatistic =
      "smallest measured RMSE reduction inside the regime (lower end of interval)";
  static constexpr std::string_view kRegime = kRoughRegime;
  static constexpr Expected kExpected{.quick = Verdict::kHoldsInRegime};

  static Sizes probe_sizes() { return {{{1, 1, 0}, {0.8, 0.8, 45}}, 1u << 14}; }
};

}  // namespace glintlab::verify::eto_claims

GLINTLAB_CLAIM(glintlab::verify::eto_claims::VarianceRough);

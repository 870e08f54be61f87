// Fitting LTC lobes to GGX targets (Heitz, Dupuy, Hill, Neubelt 2016 Sec. 4: Nelder–Mead on an
// MIS-weighted L3 error from warm starts), the directional albedo / Fresnel cubature, and D_PR
// (Kneiphof & Klein 2024 Eq. 19). Deterministic: midpoint grids, no random numbers, and a fixed
// fit order whatever the thread count. `glintlab ltc-fit` (cli/ltc_fit.cpp) drives it.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "core/ltc/ltc_table.h"
#include "core/math/vec.h"

namespace glintlab {

// What a lobe is fitted to, as a function of ω_i for a view ω_o = (sin θ_o, 0, cos θ_o):
//   kBrdf: the GGX BRDF·cos ρ(ω_i, ω_o)⟨n, ω_i⟩ (F = 1, height-correlated G2), normalized by the
//          directional albedo; sampled through visible normals (Heitz 2018);
//   kNdf:  D(h)/(4⟨h, ω_i⟩) on ω_i ∈ H (Kneiphof & Klein 2024 Eq. 13), normalized by D_PR
//          (Eq. 19); sampled through h ∝ D(h)⟨n, h⟩ (Walter et al. 2007).
enum class LtcTarget { kBrdf, kNdf };

// The unnormalized target value at ω_i (0 below the horizon).
double ltc_target_value(LtcTarget target, double alpha, Vec3<double> wo, Vec3<double> wi);

// ∫_H ρ⟨n, ω_i⟩ dω_i (F = 1) and ∫_H ρ⟨n, ω_i⟩ (1 − ⟨ω_i, h⟩)⁵ dω_i by a grid × grid midpoint
// rule over the VNDF sampler's unit square (smooth integrand: G2/G1 ≤ 1).
struct LtcAlbedo {
  double albedo, fresnel;
};
LtcAlbedo ggx_ltc_albedo(double alpha, double cos_theta_o, int grid = 256);

// D_PR = ∫_H D(h)/(4⟨h, ω_i⟩) dω_i (Kneiphof & Klein 2024 Eq. 19) = ∫ D(h) dh over the half
// vectors whose reflection of ω_o stays above the horizon. In h's polar angle the azimuth range is
// closed form (ω_i.z ≥ 0 ⟺ cos φ_h ≥ −cos θ_o cos 2θ_h / (sin θ_o sin 2θ_h)), which leaves a 1-D
// integral over u = the GGX CDF of θ_h, done by adaptive Simpson to `tolerance`.
double ggx_d_pr(double alpha, double cos_theta_o, double tolerance = 1e-10);

// The fit's objective (Heitz et al. 2016 Sec. 4): ∫ |f̂ − D_ltc|³ dω, f̂ the normalized target,
// by MIS (balance heuristic) over `samples` × `samples` midpoint points of each of the two
// samplers (the lobe's and the target's).
double ltc_fit_objective(LtcTarget target, double alpha, double theta_o, const LtcCoefficients& c,
                         int samples = 24);
// The reported fit error: ∫ |f̂ − D_ltc| dω ∈ [0, 2] (twice the total-variation distance
// between the normalized target and the lobe), by the same MIS estimator.
double ltc_fit_l1_error(LtcTarget target, double alpha, double theta_o, const LtcCoefficients& c,
                        int samples = 64);

// ltc_fit_l1_error for many lobes at one (target, α, θ_o, samples): the target's normalization
// (a 256² cubature for kBrdf) and its sampler's points are computed once, not per lobe, as a
// search over lobes needs. Each call gives ltc_fit_l1_error's bits.
class LtcL1Error {
 public:
  LtcL1Error(LtcTarget target, double alpha, double theta_o, int samples = 64);
  double operator()(const LtcCoefficients& c) const;

 private:
  struct Grid;
  std::shared_ptr<const Grid> grid_;
};

struct LtcFitResult {
  LtcCoefficients coefficients;  // the table's M⁻¹
  LtcFitParameters parameters;   // what Nelder–Mead optimized
  double objective;              // ltc_fit_objective at the optimum
  int evaluations;               // objective evaluations Nelder–Mead spent
};

// One entry by Nelder–Mead from `warm_start` (Heitz et al. 2016 Sec. 4): M = [X Y Z] K, K =
// [[m11, 0, m13], [0, m22, 0], [m31, 0, 1]], with Z the target's mean direction (so a narrow lobe
// starts where its target is), over (log m11, log m22, m13/m11, m31). At θ_o = 0 the lobe is
// rotationally symmetric: m11 = m22, m13 = m31 = 0, one variable.
LtcFitResult fit_ltc_entry(LtcTarget target, double alpha, double theta_o,
                           const LtcFitParameters& warm_start, int samples = 24);

// The node values of the table layout (ltc_table.h): α_i (clamped to kLtcMinAlpha) and θ_j
// (clamped to cos θ ≥ kLtcMinCosTheta).
double ltc_node_alpha(int i, int size);
double ltc_node_theta(int j, int size);

struct LtcFitOptions {
  int size = kLtcTableSize;  // N, 2 ≤ N ≤ kLtcMaxTableSize
  int threads = 0;           // 0: all cores; results are identical for any value
  int samples = 24;          // per-axis sample count of the objective
  // Called after each finished table row (thread-safe calls, any order): done rows, total rows.
  std::function<void(int, int)> progress;
};

// Every table: per target, the θ_o = 0 column is fitted from the roughest entry (identity start)
// down to the smoothest, each from the previous one; then each roughness row from θ_o = 0 upwards,
// each entry from its neighbour at the previous θ_o (Heitz et al. 2016's warm starts). The two
// targets' columns run side by side, then the rows of both in one pool; every entry depends only
// on its fixed predecessor, so threads do not change it.
LtcTables fit_ltc_tables(const LtcFitOptions& options);

}  // namespace glintlab

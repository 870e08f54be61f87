// What the stability sweeps (claim all.stability, docs/verification.md) sweep for one registered
// model: the model × sampler targets and, per target, the 2-D planes (a parameter axis × the
// incidence angle) derived from the model's ParamSpec ranges and needs (core/model.h), never from
// its name.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/model_registry.h"

namespace glintlab::verify::stability {

// The parameter a plane sweeps along its rows; its columns are always the incidence θi.
enum class Axis {
  kAlpha,           // alpha_x = alpha_y = α (isotropic), log-spaced 1e-4 … 4
  kAnisotropy,      // alpha_x = α0 √r, alpha_y = α0 / √r, r = 1 … 1000
  kDensity,         // the `density` parameter over its range
  kMicroroughness,  // the `microroughness` parameter over its range
  kFootprint,       // footprint size s: duv_dx = (s, 0), duv_dy = (0, s) (footprint models)
  kLightSize,       // light cone half-angle (LightQuery::cos_half_angle; light models)
  kParameter,       // any other real parameter over its range, for a model no axis above applies to
  kDirections,      // one row at the defaults, for a model with no sweepable parameter at all
};

struct SweepPlane {
  Axis axis;
  std::string name;        // file-name stem: alpha, anisotropy, density, microroughness, ...
  std::string row_label;   // what a row's value is, with units, e.g. "alpha (isotropic)"
  std::string row_symbol;  // short form used in failure regions, e.g. "α", "αx/αy"
  std::vector<double> rows;
  std::vector<double> theta_deg;  // incidence polar angle, degrees; > 90 is back-facing
  std::size_t param = 0;  // index of the swept parameter (density, microroughness, kParameter)
};

// One model with one choice of its `sampler` parameter (or its only sampler).
struct SweepTarget {
  const ModelEntry* model = nullptr;
  std::optional<std::size_t> sampler_param;  // index of the `sampler` choice parameter
  std::size_t sampler_choice = 0;
  std::string sampler;     // the choice name, or "default" for a model without a sampler choice
  std::string id() const;  // "<model>/<sampler>"
};

inline constexpr double kDefaultAlpha = 0.1;  // α where a plane does not sweep it
inline constexpr double kDefaultFootprint = 1e-3;
inline constexpr double kDefaultLightHalfAngleDeg = 1.0;  // area-light models; delta otherwise

// The targets of every registered model whose name matches one of the comma-separated fnmatch
// globs (empty = all), in registration order and choice order.
std::vector<SweepTarget> sweep_targets(const std::string& globs = "");

// The planes of a model; `quick` uses coarser grids. Never empty: a model whose parameters none of
// the named axes covers (a plug-in is free to call its roughness anything) is swept along each of
// its real parameters with a finite range, or at its defaults when it has none.
std::vector<SweepPlane> sweep_planes(const ModelEntry& model, bool quick);

// Parameter values for one cell: the model's defaults, the target's sampler, α, and the plane's
// row value where it is a parameter. `row` is ignored by planes whose axis is not a parameter.
std::vector<double> cell_params(const SweepTarget& t, const SweepPlane& plane, double row);

// The value `v` moved into the parameter's range (open bounds by a relative 1e-9).
double clamp_to_range(const ParamSpec& p, double v);

// Whether an incidence angle is front-facing and not grazing past kCoreMaxThetaDeg, and a row is
// in the plane's core domain (α ≥ 1e-3, anisotropy ≤ 100:1): the domain in which a defect makes
// all.stability fail rather than hold in a regime.
inline constexpr double kCoreMaxThetaDeg = 89.0;
bool in_core_domain(const SweepPlane& plane, double row, double theta_deg);

}  // namespace glintlab::verify::stability

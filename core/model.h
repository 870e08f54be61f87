// The interface every NDF or glint model satisfies (docs/architecture.md, docs/adding_a_model.md):
// queries, results, parameter specifications and the Model concept the static kernels are written
// against.
//
// A model is a struct with static members (no state, no virtual calls):
//   kName, kDescription, kSource            identification (kSource cites the paper/equations)
//   kNeeds                                  bit set of ModelNeeds: what a scene must provide
//   kParams                                 std::array<ParamSpec, N>: name, default, range
//   kIntermediates                          std::array<std::string_view, M>: named quantities
//   template <class T> struct Params        plain parameter struct for the kernels
//   params<T>(span<const double> values)    values in kParams order (already validated)
//   eval<T>(Params, ModelQuery)   -> ModelEval<T, M>   value, pdf, intermediates
//   pdf<T>(Params, ModelQuery)    -> T                 density of wo given wi (per steradian)
//   sample<T>(Params, ModelQuery, Vec2 u) -> ModelSample<T>   wo from wi
// and optionally
//   validate(ModelQuery<double>) -> std::optional<QueryViolation>  the model's own input rules
//   kDoubleOnly = true            no float instantiation (SIMD batches run it on double)
//   kBatched = false              no SIMD instantiation (batches loop over its double thunks)
//   kSmoothLimit = "smooth_ggx"   the registered model a footprint model tends to as its footprint
//                                 grows (parameters of the same name are passed on; the
//                                 conformance suite's converges-to-smooth, verify/conformance/)
//   kNotClaimed = {{{"constant-time", "why"}}}  conformance properties the model does not claim,
//                                 each with its reason (reported as "not-claimed", never as holds);
//                                 a name outside kConformanceProperties is refused (a built-in
//                                 model does not compile, a plug-in does not load); a third
//                                 member "param=choice" limits it to that parameter choice
// params<T> reads the values by name (values[param_index<M>("seed")]), never by position.
// core/model_registry.h turns such a struct into a type-erased entry for the CLI, the claims, the
// figures and the benchmarks; adding a model = its file plus its type in core/model_list.h.
#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

#include "core/math/vec.h"

namespace glintlab {

// What a model needs from the scene. kDirections: only ω_i and ω_o (smooth NDFs).
// kFootprint: the pixel footprint (uv and its Jacobian; glint models). kPointLight: evaluated for
// a single light direction (delta or small cap, described by the query's light). kAreaLight: the
// model integrates over an extended light itself (the query's light cap).
enum ModelNeeds : unsigned {
  kNeedsDirections = 0u,
  kNeedsFootprint = 1u << 0,
  kNeedsPointLight = 1u << 1,
  kNeedsAreaLight = 1u << 2,
  kNeedsPixelCorners = 1u << 3,  // the footprint's four corner reflection vectors (Podee et al.)
};

// The pixel footprint in texture space: uv at the pixel centre and the Jacobian ∂uv/∂(pixel)
// (columns duv_dx = ∂(u,v)/∂x, duv_dy = ∂(u,v)/∂y), from ray differentials (core/scene/camera.h).
// corner_r (kNeedsPixelCorners models only; zero otherwise): the mirror reflections of the view
// direction at the pixel's four corners, unit, in the local frame of the pixel centre, in the
// corner order of core/scene/footprint.h.
template <class T>
struct FootprintQuery {
  Vec2<T> uv;
  Vec2<T> duv_dx, duv_dy;
  std::array<Vec3<T>, 4> corner_r{};
};

// The light seen from the shading point, in the local frame: a cone around the query's ω_o with
// cosine of the half-angle γ (1 = a delta direction, point or directional light) and the
// irradiance-normalized intensity carried along ω_o.
template <class T>
struct LightQuery {
  T cos_half_angle;
  T intensity;
};

// One query. Directions are unit vectors in the local shading frame (x tangent, y bitangent,
// z normal): ω_i is the given direction (toward the viewer), ω_o the other one (toward the light).
template <class T>
struct ModelQuery {
  FootprintQuery<T> footprint;
  Vec3<T> wi, wo;
  LightQuery<T> light;
};

// Result of eval: value = f(ω_i, ω_o) · max(ω_o.z, 0), the cosine-weighted BRDF (the integrand
// against incident radiance; per steradian); pdf = density of ω_o under the model's sampler;
// intermediates in kIntermediates order.
template <class T, std::size_t M>
struct ModelEval {
  T value;
  T pdf;
  std::array<T, M> intermediates;
};

// One sampled direction: wo, its density, the estimator weight value/pdf (0 when rejected) and
// whether the sampler rejected it (below the surface, back-facing microfacet).
template <class T>
struct ModelSample {
  Vec3<T> wo;
  T pdf;
  T weight;
  Mask<T> rejected;
};

// A model parameter: a real number in a range, or (choices non-empty) one of a list of names,
// stored as the index of the name.
struct ParamSpec {
  std::string_view name;
  double default_value;
  double lo, hi;          // valid range of a real parameter
  bool lo_open, hi_open;  // whether the bound itself is excluded
  std::string_view description;
  std::span<const std::string_view> choices = {};
  bool integral = false;  // a seed or a count: only whole numbers in [lo, hi] are valid
};

// The position of parameter `name` in `params` (a model's kParams); a compile error for a name that
// is not there.
void parameter_name_is_not_in_kParams();
template <std::size_t N>
consteval std::size_t param_index(const std::array<ParamSpec, N>& params, std::string_view name) {
  for (std::size_t i = 0; i < N; ++i)
    if (params[i].name == name) return i;
  parameter_name_is_not_in_kParams();
  return N;
}
template <class M>
consteval std::size_t param_index(std::string_view name) {
  return param_index(M::kParams, name);
}

// A conformance property (verify/conformance/) a model does not claim, and why: the suite reports
// it as "not-claimed" with the reason instead of running it. With `choice` ("param=name", one of
// the parameter's declared choices) only that configuration of the property is not claimed: the
// property runs over the model's other configurations, and its row names the one left out.
struct NotClaimed {
  std::string_view property, reason;
  std::string_view choice = {};
};

// Whether `choice` is "param=name" for a parameter of `params` with `name` among its choices.
template <class Params>
constexpr bool is_declared_choice(const Params& params, std::string_view choice) {
  const std::size_t eq = choice.find('=');
  if (eq == std::string_view::npos) return false;
  for (const auto& p : params)
    if (p.name == choice.substr(0, eq))
      for (std::string_view c : p.choices)
        if (c == choice.substr(eq + 1)) return true;
  return false;
}

// The conformance properties, in the suite's order: the valid NotClaimed::property names. Here
// rather than in verify/ so that the registry can refuse a misspelled declaration (a property it
// would otherwise silently claim).
// clang-format off
inline constexpr std::array<std::string_view, 10> kConformanceProperties = {
    "eval-pdf-consistency", "sampler-matches-pdf", "sampler-covers-value", "pdf-normalized",
    "energy",               "float-vs-double",     "simd-equivalence",     "stability",
    "converges-to-smooth",  "constant-time"};
// clang-format on

constexpr bool is_conformance_property(std::string_view name) {
  for (std::string_view p : kConformanceProperties)
    if (p == name) return true;
  return false;
}

// A query value a model does not take (from its optional static validate): the column that breaks
// the rule (a name of core/model_layout.h) and the valid range, in words.
struct QueryViolation {
  std::string_view column;
  std::string_view valid;
};

template <class M>
concept ValidatesQuery = requires(const ModelQuery<double>& q) {
  { M::validate(q) } -> std::same_as<std::optional<QueryViolation>>;
};

template <class M>
concept Model = requires(std::span<const double> values) {
  { M::kName } -> std::convertible_to<std::string_view>;
  { M::kDescription } -> std::convertible_to<std::string_view>;
  { M::kSource } -> std::convertible_to<std::string_view>;
  { M::kNeeds } -> std::convertible_to<unsigned>;
  M::kParams.size();
  M::kIntermediates.size();
  { M::template params<double>(values) } -> std::same_as<typename M::template Params<double>>;
  {
    M::template eval<double>(M::template params<double>(values), ModelQuery<double>{})
    } -> std::same_as<ModelEval<double, M::kIntermediates.size()>>;
  {
    M::template pdf<double>(M::template params<double>(values), ModelQuery<double>{})
    } -> std::same_as<double>;
  {
    M::template sample<double>(M::template params<double>(values), ModelQuery<double>{},
                               Vec2<double>{})
    } -> std::same_as<ModelSample<double>>;
};

}  // namespace glintlab

// A Kemppinen-family level (core/glints/adequacy.h, KemppinenLevel) as the model evaluates it: its
// parameter values, its value at a query without the sampler's pdf, and the smooth level's value.
// Shared by the adequacy grid (kemppinen_adequacy.cpp) and the validation scenes
// (verify/scenes/adequacy_scenes.cpp), so both measure the same levels.
#pragma once

#include <cstdint>
#include <vector>

#include "core/glints/adequacy.h"
#include "core/models/kemppinen_model.h"

namespace glintlab::verify::adequacy {

// The model's parameter values (its kParams order) for a counting level (not kSmooth): the
// model's defaults with isotropic roughness `alpha`, K_P = `density` points per unit uv area, the
// level's k and erf, and the seed.
template <class M>
std::vector<double> kemppinen_param_values(double alpha, double density, KemppinenLevel level,
                                           std::uint64_t seed) {
  std::vector<double> v;
  for (const ParamSpec& s : M::kParams) v.push_back(s.default_value);
  v[param_index<M>("alpha_x")] = alpha;
  v[param_index<M>("alpha_y")] = alpha;
  v[param_index<M>("density")] = density;
  v[param_index<M>("k")] = double(kemppinen_level_side(level) - 1);
  v[param_index<M>("erf")] = kemppinen_level_rational(level) ? 1.0 : 0.0;
  v[param_index<M>("seed")] = double(seed % 4294967296ULL);
  return v;
}

template <class M>
typename M::template Params<double> kemppinen_level_params(double alpha, double density,
                                                           KemppinenLevel level,
                                                           std::uint64_t seed) {
  return M::template params<double>(kemppinen_param_values<M>(alpha, density, level, seed));
}

// The model's value without its sampler's pdf (M::eval also computes the pdf, which the value
// does not use and which costs as much again).
template <class Params>
ModelEval<double, detail::kKemppinenIntermediates.size()> kemppinen_value(
    const Params& params, const ModelQuery<double>& q) {
  return detail::kemppinen_model_eval(params, q, 0.0);
}

// The smooth level, D★^f replaced by D of the base NDF: G2 D / (4 cos θ_i), from an evaluation of
// any counting level at the same directions (its intermediates D_smooth and G2).
inline double kemppinen_smooth_value(
    const ModelEval<double, detail::kKemppinenIntermediates.size()>& e,
    const ModelQuery<double>& q) {
  const double g2 = e.intermediates[12], d = e.intermediates[3];
  return q.wi.z > 0 && q.wo.z > 0 ? g2 * d / (4 * q.wi.z) : 0.0;
}

// The exact-erf twin of a counting level (itself for an exact one).
constexpr KemppinenLevel kemppinen_exact_twin(KemppinenLevel l) {
  return kemppinen_level_rational(l) ? KemppinenLevel(int(l) + 1) : l;
}

}  // namespace glintlab::verify::adequacy

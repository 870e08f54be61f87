// The engine choosers for given costs of the Kemppinen and Chermain families: the cheapest level
// that is adequate, under a cost order the engine passes in — the GPU order (gpu_cost_order: the
// choosers then choose as choose_kemppinen_level and choose_chermain_level do) or the ns per
// evaluation measured on the machine that renders (the benchmark rows
// adequacy/<model>/level=<level>/<isa> that `glintlab adequacy --bench-from` reads). The
// counterparts of the binomial family's choose_binomial_level_by_cost (core/glints/adequacy.h).
//
// A level is adequate where its family's chooser predicts it so, with the same margin:
// - Kemppinen (core/glints/adequacy.h, adequate_kemppinen_levels): the smooth level, and each
//   k = 1, 4, 9 where its predicted mean and CV differences from k = 16 are at most
//   kChooserMargin · TAU; the rational and the exact erf of one k alike (their difference is below
//   1e-5 of the mean); k = 16 always.
// - Chermain (core/glints/chermain_chooser.h): dictL with GGAA on where its dictionary is the whole
//   one bit for bit (every weighted LOD's level below L or past the last), dictL with GGAA off
//   there too where GGAA does not filter (no kernel or no derivative) or where the closed form
//   predicts GGAA off within kChooserMargin · TAU of GGAA on; the smooth level where both
//   LODs are past the last level or its closed-form CV and mean difference are at most
//   kChooserMargin · TAU; every level below the horizon (all are 0 there); dict16_ggaa always.
// docs/adequacy.md "Choosers for given costs" has their counts against the measured table.
//
// Header-only, templated on the float type, no allocation, `select` on lanes.
#pragma once

#include <array>
#include <cstddef>

#include "core/glints/adequacy.h"
#include "core/glints/chermain_chooser.h"

namespace glintlab {

// The adequate level of least cost (`adequate` and `cost` in the family's level order; the last
// level, the most complete, is taken where no cheaper adequate level costs less); a tie goes to
// the level earlier in the order (the cheaper one on a GPU lane). Returns the level's index as T.
template <class T, std::size_t N>
GLINTLAB_FN T cheapest_adequate_level(const std::array<Mask<T>, N>& adequate,
                                      const std::array<double, N>& cost) {
  T level = T(int(N - 1));
  T best = T(cost[N - 1]);
  for (int l = int(N) - 2; l >= 0; --l) {
    const Mask<T> take = adequate[std::size_t(l)] && T(cost[std::size_t(l)]) <= best;
    level = select(take, T(l), level);
    best = select(take, T(cost[std::size_t(l)]), best);
  }
  return level;
}

// The GPU order as costs: increasing along the level order.
template <std::size_t N>
constexpr std::array<double, N> gpu_cost_order() {
  std::array<double, N> c{};
  for (std::size_t l = 0; l < N; ++l) c[l] = double(l + 1);
  return c;
}

// ---- Kemppinen --------------------------------------------------------------------------------

// Each KemppinenLevel's predicted adequacy.
template <class T>
GLINTLAB_FN std::array<Mask<T>, kKemppinenLevels> kemppinen_level_adequacy(
    const AdequateKemppinenLevels<T>& a) {
  return {a.smooth,  a.side[0], a.side[0], a.side[1], a.side[1],
          a.side[2], a.side[2], a.side[3], a.side[3]};
}

// The cheapest adequate KemppinenLevel by `cost` (ns per evaluation or any order, KemppinenLevel
// order). Returns the level's KemppinenLevel value as T.
template <class Ndf, class T>
GLINTLAB_FN T choose_kemppinen_level_by_cost(const kemppinen2025::Params<T>& p, const Ndf& ndf,
                                             const FootprintQuery<T>& fp, Vec3<T> h, T tau,
                                             const std::array<double, kKemppinenLevels>& cost) {
  const AdequateKemppinenLevels<T> a =
      adequate_kemppinen_levels(kemppinen_level_moments(p, ndf, fp, h), tau);
  return cheapest_adequate_level<T, kKemppinenLevels>(kemppinen_level_adequacy(a), cost);
}

// The same on what a shader of kemppinen_ggx / kemppinen_beckmann has.
template <class Ndf, class T>
GLINTLAB_FN T choose_kemppinen_model_level_by_cost(
    const detail::KemppinenModelParams<Ndf, T>& params, const ModelQuery<T>& q, T tau,
    const std::array<double, kKemppinenLevels>& cost) {
  return choose_kemppinen_level_by_cost(params.glint, params.ndf, q.footprint,
                                        half_vector(q.wi, q.wo), tau, cost);
}

// ---- Chermain ---------------------------------------------------------------------------------

// The cheapest adequate ChermainLevel by `cost` (ChermainLevel order). Returns the level as T.
template <class T>
GLINTLAB_FN T choose_chermain_level_by_cost(const chermain2021::SdfParams& p,
                                            const chermain2021::SlopeDerivatives& d,
                                            const ModelQuery<T>& q, T tau,
                                            const std::array<double, kChermainLevels>& cost) {
  return cheapest_adequate_level<T, kChermainLevels>(chermain_level_adequacy(p, d, q, tau), cost);
}

// The same on what a shader of the model has.
template <class T>
GLINTLAB_FN T choose_chermain_model_level_by_cost(const Chermain::Params<T>& params,
                                                  const ModelQuery<T>& q, T tau,
                                                  const std::array<double, kChermainLevels>& cost) {
  return choose_chermain_level_by_cost(params.sdf, params.d, q, tau, cost);
}

}  // namespace glintlab

#include "verify/adequacy/area_adequacy.h"

#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/glints/area_chooser.h"
#include "core/glints/kneiphof_ltc.h"
#include "core/model_registry.h"

namespace glintlab::verify::adequacy {
namespace {

constexpr double kDeg = std::numbers::pi / 180;
// log10 facets per unit uv area, as the binomial grid's (N_P = footprint area · 10^6).
constexpr double kLog10Density = 6;

KneiphofKleinArea::Params<double> area_params(const Cell& c, BinomialLevel level,
                                              std::uint64_t seed) {
  return KneiphofKleinArea::params<double>(area_level_param_values(c, level, seed));
}

}  // namespace

double square_solid_angle(double side, double distance) {
  const double w2 = side * side;
  return 4 * std::asin(w2 / (w2 + 4 * distance * distance));
}

double square_light_side(double half_angle_deg, double distance) {
  // 4 asin(w²/(w² + 4d²)) = 2π(1 − cos γ)  ⇔  w²/(w² + 4d²) = s = sin(π(1 − cos γ)/2).
  const double gamma = half_angle_deg * kDeg;
  const double one_minus_cos = 2 * std::sin(0.5 * gamma) * std::sin(0.5 * gamma);
  const double s = std::sin(0.5 * std::numbers::pi * one_minus_cos);
  return 2 * distance * std::sqrt(s / (1 - s));
}

GridAxes area_grid_axes(Budget b) {
  GridAxes g = grid_axes(b);
  g.light_half_angle_deg =
      b == Budget::kQuick ? std::vector<double>{0.26, 1, 10} : std::vector<double>{0.26, 1, 3, 10};
  return g;
}

std::vector<double> area_level_param_values(const Cell& c, BinomialLevel level,
                                            std::uint64_t seed) {
  using M = KneiphofKleinArea;
  if (c.model != "kneiphof_klein_area")
    throw std::invalid_argument("adequacy: not a model of the area family: " + c.model);
  std::vector<double> v;
  for (const ParamSpec& s : M::kParams) v.push_back(s.default_value);
  const double side = square_light_side(c.light_half_angle_deg);
  v[param_index<M>("alpha")] = c.alpha;
  v[param_index<M>("density")] = kLog10Density;
  v[param_index<M>("light_distance")] = kAreaLightDistance;
  v[param_index<M>("light_width")] = side;
  v[param_index<M>("light_height")] = side;
  v[param_index<M>("light_rotation_deg")] = 0;
  v[param_index<M>("light_tilt_deg")] = 0;
  v[param_index<M>("area_p")] = double(int(kneiphof2024::AreaP::kBrdfLobe));  // the paper's
  v[param_index<M>("area_lo")] = 0;                                           // LTC
  v[param_index<M>("binomial")] = double(binomial_sampler_of(level));
  v[param_index<M>("seed")] = double(seed % 4294967296ULL);
  return v;
}

double area_level_values(const Cell& c, BinomialLevel level, int samples, std::uint64_t seed,
                         std::vector<double>& out) {
  out.resize(std::size_t(samples));
  const auto params = area_params(c, level, seed);
  // The query at position i is cell_query(c, uv.x, uv.y): set up once, its uv moved.
  ModelQuery<double> q = cell_query(c, 0, 0);
  const auto t0 = std::chrono::steady_clock::now();
  if (level == BinomialLevel::kSmooth) {
    // The family's smooth limit: L_o/L_i by the BRDF LTC lobe over the same rectangle (the model's
    // `smooth`, which its count scales by b/(N_P p)).
    for (int i = 0; i < samples; ++i) {
      const Vec2<double> uv = surface_position(i);
      q.footprint.uv = {uv.x, uv.y};
      const auto rect = kneiphof2024::facing_rectangle(q.wo, params.distance, params.width,
                                                       params.height, params.rotation, params.tilt);
      out[std::size_t(i)] =
          kneiphof2024::area_light_terms_ltc(*params.table, params.alpha, q.wi, rect.data(), 4,
                                             params.area_p)
              .lo_over_li;
    }
  } else {
    for (int i = 0; i < samples; ++i) {
      const Vec2<double> uv = surface_position(i);
      q.footprint.uv = {uv.x, uv.y};
      out[std::size_t(i)] = KneiphofKleinArea::eval<double>(params, q).value;
    }
  }
  const auto t1 = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::nano>(t1 - t0).count() / samples;
}

std::pair<double, double> area_cell_probability_and_smooth(const Cell& c) {
  const auto p = area_params(c, BinomialLevel::kExact, 0);
  const auto e = KneiphofKleinArea::eval<double>(p, cell_query(c, 0.5, 0.5));
  return {e.intermediates[2], e.intermediates[6]};  // p (clamped), smooth
}

int area_cell_chooser(const Cell& c, double tau) {
  return int(choose_kneiphof_klein_area_model_level(area_params(c, BinomialLevel::kExact, 0),
                                                    cell_query(c, 0.5, 0.5), tau));
}

std::vector<CellResult> measure_area_grid_at(const std::vector<Cell>& cells,
                                             const std::vector<std::size_t>& positions,
                                             int samples, const Decision& d,
                                             const std::function<void()>& progress) {
  return measure_grid_at(cells, positions, samples, d, progress, kAreaSeedName);
}

}  // namespace glintlab::verify::adequacy

#include "verify/adequacy/binomial_adequacy.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <tuple>

#include "core/model_registry.h"
#include "verify/adequacy/area_adequacy.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::adequacy {
namespace {

constexpr double kDeg = std::numbers::pi / 180;
// log10 facets per unit uv area of the grid's footprints: N_P = area · 10^6 (the models' default).
constexpr double kLog10Density = 6;

double theta_h_of(double alpha, int index) { return std::atan(alpha * index); }


// The model's parameter values in kParams order, with the level's sampler and the seed.
template <class M>
std::vector<double> model_param_values(const Cell& c, BinomialLevel level, std::uint64_t seed) {
  std::vector<double> v;
  for (const ParamSpec& s : M::kParams) v.push_back(s.default_value);
  v[param_index<M>("alpha_x")] = c.alpha;
  v[param_index<M>("alpha_y")] = c.alpha;
  v[param_index<M>("density")] = kLog10Density;
  v[param_index<M>("binomial")] = double(binomial_sampler_of(level));
  v[param_index<M>("seed")] = double(seed % 4294967296ULL);
  return v;
}
template <class M>
typename M::template Params<double> model_params(const Cell& c, BinomialLevel level,
                                                 std::uint64_t seed) {
  return M::template params<double>(model_param_values<M>(c, level, seed));
}


template <class M>
double values_of(const Cell& c, BinomialLevel level, int samples, std::uint64_t seed,
                 std::vector<double>& out) {
  out.resize(std::size_t(samples));
  const auto params = model_params<M>(c, level, seed);
  const auto t0 = std::chrono::steady_clock::now();
  // The query at position i is cell_query(c, uv.x, uv.y): set up once, its uv moved.
  ModelQuery<double> q = cell_query(c, 0, 0);
  if (level == BinomialLevel::kSmooth) {
    // The family's smooth limit: the smooth GGX value the models scale (F = 1).
    for (int i = 0; i < samples; ++i) {
      const Vec2<double> uv = surface_position(i);
      q.footprint.uv = {uv.x, uv.y};
      out[std::size_t(i)] = microfacet_brdf(params.ggx, q.wi, q.wo, 1.0) * std::max(q.wo.z, 0.0);
    }
  } else {
    for (int i = 0; i < samples; ++i) {
      const Vec2<double> uv = surface_position(i);
      q.footprint.uv = {uv.x, uv.y};
      out[std::size_t(i)] = M::template eval<double>(params, q).value;
    }
  }
  const auto t1 = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::nano>(t1 - t0).count() / samples;
}

double normal_quantile_upper(double alpha) {
  // Φ⁻¹(1 − α) by bisection on erfc (monotone; 200 halvings reach double precision).
  double lo = 0, hi = 40;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(mid / std::numbers::sqrt2) > alpha ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

BinomialSampler binomial_sampler_of(BinomialLevel level) {
  return level == BinomialLevel::kRealTime     ? BinomialSampler::kRealTime
         : level == BinomialLevel::kSmallCount ? BinomialSampler::kSmallCount
                                               : BinomialSampler::kExact;
}

// R2 low-discrepancy positions (Roberts 2018): distinct after the models' 2^-24 uv quantization.
Vec2<double> surface_position(int i) {
  const double a = 0.5 + 0.75487766624669276005 * i, b = 0.5 + 0.56984029099805326591 * i;
  return {a - std::floor(a), b - std::floor(b)};
}

ModelQuery<double> cell_query(const Cell& c, double u, double v) {
  ModelQuery<double> q{};
  const double ti = c.theta_i_deg * kDeg, th = c.theta_h_deg * kDeg;
  q.wi = {std::sin(ti), 0, std::cos(ti)};
  // h tilted sideways (azimuth 90°): ω_o.z = cos θ_i cos 2θ_h > 0 for θ_h < 45°.
  const Vec3<double> h{0, std::sin(th), std::cos(th)};
  const double wh = dot(q.wi, h);
  q.wo = normalize(Vec3<double>{2 * wh * h.x - q.wi.x, 2 * wh * h.y - q.wi.y, 2 * wh * h.z - q.wi.z});
  const double side = std::sqrt(c.facets / std::pow(10.0, kLog10Density));
  q.footprint.uv = {u, v};
  q.footprint.duv_dx = {side, 0};
  q.footprint.duv_dy = {0, side};
  q.light.cos_half_angle = std::cos(c.light_half_angle_deg * kDeg);
  q.light.intensity = 1;
  return q;
}

std::vector<double> level_param_values(const Cell& cell, BinomialLevel level, std::uint64_t seed) {
  if (level == BinomialLevel::kSmooth)
    throw std::invalid_argument("adequacy: the smooth level is smooth_ggx's value, not a count");
  if (cell.model == "deliot_belcour") return model_param_values<DeliotBelcour>(cell, level, seed);
  if (cell.model == "kneiphof_klein") return model_param_values<KneiphofKlein>(cell, level, seed);
  if (cell.model == "kneiphof_klein_area") return area_level_param_values(cell, level, seed);
  throw std::invalid_argument("adequacy: not a model of the binomial family: " + cell.model);
}

GridAxes grid_axes(Budget b) {
  GridAxes g;
  if (b == Budget::kQuick) {
    for (int e = 0; e <= 8; ++e) g.facets.push_back(std::pow(10.0, e));
    g.alpha = {0.05, 0.3};
    g.light_half_angle_deg = {0, 1, 10};
    g.theta_i_deg = {0, 60};
    g.samples = 8000;
  } else {
    for (int e = 0; e <= 16; ++e) g.facets.push_back(std::round(std::pow(10.0, 0.5 * e)));
    g.alpha = {0.02, 0.1, 0.25, 0.45};
    g.light_half_angle_deg = {0, 0.26, 1, 3, 10};
    g.theta_i_deg = {0, 30, 60, 80};
    g.samples = 32000;
  }
  return g;
}

std::vector<Cell> make_grid(const std::vector<std::string>& models, const GridAxes& axes) {
  std::vector<Cell> cells;
  for (const std::string& m : models)
    for (double light : axes.light_half_angle_deg)
      for (double ti : axes.theta_i_deg)
        for (double a : axes.alpha)
          for (int h = 0; h < axes.theta_h_count; ++h)
            for (double n : axes.facets)
              cells.push_back({m, n, a, light, ti, theta_h_of(a, h) / kDeg, h});
  return cells;
}

Decision decision_for(std::size_t cells, double threshold) {
  return decision_for_decisions(cells * std::size_t(kBinomialLevels - 1), threshold);
}

Decision decision_for_decisions(std::size_t decisions, double threshold) {
  return decision_at_level(sidak_level(kFamilyWiseRate, decisions), threshold);
}

Decision decision_at_level(double level, double threshold) {
  return {threshold, normal_quantile_upper(level)};
}

double level_values(const Cell& cell, BinomialLevel level, int samples, std::uint64_t seed,
                    std::vector<double>& out) {
  if (cell.model == "deliot_belcour") return values_of<DeliotBelcour>(cell, level, samples, seed, out);
  if (cell.model == "kneiphof_klein") return values_of<KneiphofKlein>(cell, level, samples, seed, out);
  if (cell.model == "kneiphof_klein_area") return area_level_values(cell, level, samples, seed, out);
  throw std::invalid_argument("adequacy: not a model of the binomial family: " + cell.model);
}

std::pair<double, double> cell_probability_and_smooth(const Cell& cell) {
  if (cell.model == "kneiphof_klein_area") return area_cell_probability_and_smooth(cell);
  const ModelQuery<double> q = cell_query(cell, 0.5, 0.5);
  if (cell.model == "deliot_belcour") {
    const auto p = model_params<DeliotBelcour>(cell, BinomialLevel::kExact, 0);
    const auto e = DeliotBelcour::eval<double>(p, q);
    return {e.intermediates[2], e.intermediates[6]};
  }
  const auto p = model_params<KneiphofKlein>(cell, BinomialLevel::kExact, 0);
  const auto e = KneiphofKlein::eval<double>(p, q);
  return {e.intermediates[2], e.intermediates[6]};
}

LevelStats compare_to_exact(const std::vector<double>& x, const std::vector<double>& ref,
                            const Decision& d) {
  const std::size_t n = x.size();
  LevelStats s;
  double mx = 0, my = 0, zeros = 0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += x[i], my += ref[i];
    zeros += x[i] == 0 ? 1 : 0;
  }
  mx /= double(n), my /= double(n);
  double vx = 0, vy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    vx += (x[i] - mx) * (x[i] - mx);
    vy += (ref[i] - my) * (ref[i] - my);
  }
  vx /= double(n), vy /= double(n);
  // A constant level (the smooth one) has no spread: not the rounding of its summed mean.
  bool x_constant = true;
  for (std::size_t i = 0; i < n; ++i) x_constant = x_constant && x[i] == x[0];
  if (x_constant) vx = 0, mx = n > 0 ? x[0] : 0;
  s.mean = mx;
  s.p_zero = zeros / double(n);
  s.cv = mx > 0 ? std::sqrt(vx) / mx : 0;
  const double cv_ref = my > 0 ? std::sqrt(vy) / my : 0;
  // The bounds below are asymptotic (the delta method): with few lit positions a sample of a
  // level that is mostly dark says too little (a level never lit would get a zero standard error).
  // There a level is not shown adequate (upper bounds infinite) nor shown different (lower bounds
  // 0), unless both are dark everywhere.
  double lit_x = 0, lit_ref = 0;
  for (std::size_t i = 0; i < n; ++i) {
    lit_x += x[i] != 0 ? 1 : 0;
    lit_ref += ref[i] != 0 ? 1 : 0;
  }
  if (lit_ref == 0 && lit_x == 0) {
    s.adequate = true;
    return s;
  }
  if (lit_ref < kMinLitPositions || (!x_constant && lit_x < kMinLitPositions)) {
    s.mean_diff = my > 0 ? std::abs(mx / my - 1) : INFINITY;
    s.cv_diff = std::abs(s.cv - cv_ref);
    s.mean_diff_ucb = s.cv_diff_ucb = INFINITY;
    s.mean_diff_lcb = s.cv_diff_lcb = 0;
    s.adequate = false;
    s.undecided = true;
    return s;
  }
  // Empirical influence functions of mean_x/mean_y − 1 and of CV_x − CV_y (the nonparametric delta
  // method): their spread over the paired positions is the estimates' standard error, whatever the
  // correlation between the levels' values.
  double sm = 0, smm = 0, sc = 0, scc = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = x[i] - mx, dy = ref[i] - my;
    const double im = (dx - (mx / my) * dy) / my;
    const double icx = vx > 0 ? s.cv * ((dx * dx - vx) / (2 * vx) - dx / mx) : 0;
    const double icy = vy > 0 ? cv_ref * ((dy * dy - vy) / (2 * vy) - dy / my) : 0;
    const double ic = icx - icy;
    sm += im, smm += im * im, sc += ic, scc += ic * ic;
  }
  const double nd = double(n);
  const double se_m = std::sqrt(std::max(smm / nd - (sm / nd) * (sm / nd), 0.0) / nd);
  const double se_c = std::sqrt(std::max(scc / nd - (sc / nd) * (sc / nd), 0.0) / nd);
  s.mean_diff = std::abs(mx / my - 1);
  s.cv_diff = std::abs(s.cv - cv_ref);
  s.mean_diff_ucb = s.mean_diff + d.z * se_m;
  s.mean_diff_lcb = std::max(s.mean_diff - d.z * se_m, 0.0);
  s.cv_diff_ucb = s.cv_diff + d.z * se_c;
  s.cv_diff_lcb = std::max(s.cv_diff - d.z * se_c, 0.0);
  s.adequate = s.mean_diff_ucb < d.threshold && s.cv_diff_ucb < d.threshold;
  return s;
}

CellResult measure_cell(const Cell& cell, int samples, std::uint64_t seed, const Decision& d) {
  CellResult r;
  r.cell = cell;
  const auto [p, smooth] = cell_probability_and_smooth(cell);
  r.p = p, r.smooth = smooth;
  r.levels = measure_levels<kBinomialLevels>(
      int(BinomialLevel::kExact), d,
      [&](int l, std::vector<double>& out) {
        return level_values(cell, BinomialLevel(l), samples, seed, out);
      },
      [](int, std::vector<double>&) {});
  std::tie(r.chosen, r.cheapest_measured) =
      chosen_and_cheapest_measured(r.levels, int(BinomialLevel::kExact));
  r.cv_predicted = binomial_count_cv(cell.facets, p);
  r.p_zero_predicted = binomial_zero_probability(cell.facets, p);
  // The engine chooser: the binomial one on the cell's N_P and p, the area family's on the model's
  // parameters and query (its own N_P and LTC p, the same numbers).
  r.chooser = cell.model == "kneiphof_klein_area"
                  ? area_cell_chooser(cell, d.threshold)
                  : int(choose_binomial_level(cell.facets, p, d.threshold));
  const LevelStats& c = r.levels[std::size_t(r.chooser)];
  r.chooser_refuted = c.mean_diff_lcb > d.threshold || c.cv_diff_lcb > d.threshold;
  return r;
}

std::vector<CellResult> measure_grid(const std::vector<Cell>& cells, int samples,
                                     const Decision& d, const std::function<void()>& progress) {
  std::vector<std::size_t> all(cells.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  return measure_grid_at(cells, all, samples, d, progress);
}

std::vector<CellResult> measure_grid_at(const std::vector<Cell>& cells,
                                        const std::vector<std::size_t>& positions, int samples,
                                        const Decision& d, const std::function<void()>& progress,
                                        const char* seed_name) {
  std::vector<CellResult> out(positions.size());
  tbb::parallel_for(std::size_t(0), positions.size(), [&](std::size_t j) {
    const std::size_t i = positions[j];
    out[j] = measure_cell(cells.at(i), samples, check_seed(seed_name, i), d);
    if (progress) progress();
  });
  return out;
}

}  // namespace glintlab::verify::adequacy

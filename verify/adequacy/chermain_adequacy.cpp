#include "verify/adequacy/chermain_adequacy.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <tuple>

namespace glintlab::verify::adequacy {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

// The footprint's half-axes in uv: a rectangle of area facets / density, stretched by 1/cos θ_i
// along the plane of incidence (x), as a pixel's footprint on a surface seen at θ_i.
Vec2<double> footprint_axes(const ChermainCell& c) {
  const double side = std::sqrt(c.facets / kChermainDensity);
  const double stretch = std::sqrt(1 / std::cos(c.theta_i_deg * kDeg));
  return {side * stretch, side / stretch};
}

// The model's defaults in its kParams order with the cell's roughness, the level's kernel, the
// cell's dh and the seed.
std::vector<double> param_values(const ChermainCell& c, bool ggaa, std::uint64_t seed) {
  using M = Chermain;
  std::vector<double> v;
  for (const ParamSpec& s : M::kParams) v.push_back(s.default_value);
  v[param_index<M>("alpha_x")] = c.alpha;
  v[param_index<M>("alpha_y")] = c.alpha;
  v[param_index<M>("density")] = kChermainDensity;
  v[param_index<M>("ggaa")] = ggaa ? double(chermain2021::kProjectedHalf) : 0.0;
  v[param_index<M>("dh_dx_x")] = c.dh;
  v[param_index<M>("dh_dx_y")] = 0;
  v[param_index<M>("dh_dy_x")] = 0;
  v[param_index<M>("dh_dy_y")] = c.dh;
  v[param_index<M>("seed")] = double(seed % 1000000000ULL);
  return v;
}

// The model's value (its eval; the pdf it also computes is the smooth one, one exp).
double value_at(const Chermain::Params<double>& p, const ModelQuery<double>& q) {
  return Chermain::eval<double>(p, q).value;
}

// The smooth level: the Gaussian slope density of covariance Σ (Eq. 16) in place of the
// patch-SDF, with the same V-cavity G2 (what the model falls back to past its last level).
double smooth_value(const Chermain::Params<double>& p, const ModelQuery<double>& q) {
  const Vec3<double> h = half_vector(q.wi, q.wo);
  if (!(q.wi.z > 0 && q.wo.z > 0 && h.z > 0)) return 0;
  const double D = Chermain::smooth_d(p.sdf, h);
  const double G2 = chermain2021::v_cavity_g2(q.wi, q.wo, h);
  return D * G2 / (4 * q.wi.z * q.wo.z) * q.wo.z;
}

double half_log2_density() { return 0.5 * std::log2(kChermainDensity); }

// k = ⌊l + ½ log2 density⌋, at least 0 (chermain2021::dictionary_level).
int dictionary_level(double l) {
  return int(std::max(0.0, std::floor(l + half_log2_density())));
}

}  // namespace

ChermainGridAxes chermain_grid_axes(Budget b) {
  ChermainGridAxes g;
  if (b == Budget::kQuick) {
    // 1 … 10¹⁰ microfacets: at 10¹⁰ (θ_i = 0) the coarser LOD is past the 16th level (the smooth
    // fallback, weight 0.8), so every level of the family meets the smooth limit there.
    for (int e = 0; e <= 10; ++e) g.facets.push_back(std::pow(10.0, e));
    g.alpha = {0.1, 0.3};
    g.theta_i_deg = {0, 60};
    g.dh = {0, 0.02};
    g.samples = 8000;
  } else {
    for (int e = 0; e <= 20; ++e) g.facets.push_back(std::round(std::pow(10.0, 0.5 * e)));
    g.alpha = {0.1, 0.2, 0.4};
    g.theta_i_deg = {0, 30, 60, 80};
    g.dh = {0, 0.005, 0.02, 0.05};
    g.samples = 32000;
  }
  return g;
}

std::vector<ChermainCell> make_chermain_grid(const std::vector<std::string>& models,
                                             const ChermainGridAxes& axes) {
  std::vector<ChermainCell> cells;
  for (const std::string& m : models)
    for (double dh : axes.dh)
      for (double ti : axes.theta_i_deg)
        for (double a : axes.alpha)
          for (int h = 0; h < axes.theta_h_count; ++h)
            for (double n : axes.facets)
              cells.push_back({m, n, a, ti, std::atan(a * h) / kDeg, h, dh});
  return cells;
}

ChermainConstruction chermain_construction(const ChermainCell& c) {
  // chermain2021::lod: log2 of the longer footprint side, clamped to [−20, 39].
  const Vec2<double> axes = footprint_axes(c);
  ChermainConstruction k;
  k.lod = std::clamp(std::log2(std::max(axes.x, axes.y)), -20.0, 39.0);
  const double l0 = std::floor(k.lod);
  k.level_fine = dictionary_level(l0);
  k.level_coarse = dictionary_level(l0 + 1);
  k.coarse_weighted = k.lod - l0 != 0;
  const double cell = std::ldexp(1.0, int(l0));
  k.cells_per_footprint = 4 * axes.x * axes.y / (cell * cell);
  k.lobes_per_cell = std::pow(4.0, std::min(k.level_fine, 16));
  return k;
}

ChermainLevel chermain_identical_level(const ChermainCell& c) {
  const ChermainConstruction k = chermain_construction(c);
  constexpr int kLast = 16;  // the default dictionary's levels
  // A weighted LOD's term is the same in dictL as in the whole dictionary when its level is below
  // L (the same tables), or when it is past the whole dictionary's last level (both smooth).
  const auto same = [&](int level, int L) { return level < L || level >= kLast; };
  const bool both_smooth =
      k.level_fine >= kLast && (!k.coarse_weighted || k.level_coarse >= kLast);
  if (both_smooth) return ChermainLevel::kSmooth;
  for (int L : {4, 8, 12, 16})
    if (same(k.level_fine, L) && (!k.coarse_weighted || same(k.level_coarse, L))) {
      const int dict_index = 2 * (L / 4) - 1;  // dictL
      return ChermainLevel(c.dh == 0 ? dict_index : dict_index + 1);
    }
  return kChermainMostComplete;
}

double chermain_identical_facets(int dictionary_levels, double theta_i_deg) {
  // The coarser LOD ⌊l_P⌋ + 1 uses level ⌊l_P⌋ + 1 + ⌊½ log2 density⌋ (⌊l_P⌋ integer), below L
  // while ⌊l_P⌋ ≤ L − 2 − ⌊½ log2 density⌋, i.e. the longer side below 2^(L − 1 − ⌊½ log2 d⌋);
  // the longer side is √(facets / density) / √cos θ_i.
  const double e = dictionary_levels - 1 - std::floor(half_log2_density());
  return kChermainDensity * std::pow(4.0, e) * std::cos(theta_i_deg * kDeg);
}

Vec2<double> chermain_surface_position(const ChermainCell& c, int i) {
  // The coarser LOD's cell side 2^(⌊l_P⌋ + 1) is at most twice the footprint's longer side.
  const double cell = std::ldexp(1.0, int(std::floor(chermain_construction(c).lod)) + 1);
  const Vec2<double> r = surface_position(i);
  return {r.x * kChermainSpread * cell, r.y * kChermainSpread * cell};
}

ModelQuery<double> chermain_cell_query(const ChermainCell& c, Vec2<double> uv) {
  ModelQuery<double> q{};
  const double ti = c.theta_i_deg * kDeg, th = c.theta_h_deg * kDeg;
  q.wi = {std::sin(ti), 0, std::cos(ti)};
  // h tilted sideways, as in the other grids: ω_o.z = cos θ_i cos 2θ_h > 0 for θ_h < 45°.
  const Vec3<double> h{0, std::sin(th), std::cos(th)};
  const double wh = dot(q.wi, h);
  q.wo =
      normalize(Vec3<double>{2 * wh * h.x - q.wi.x, 2 * wh * h.y - q.wi.y, 2 * wh * h.z - q.wi.z});
  const Vec2<double> axes = footprint_axes(c);
  q.footprint.uv = uv;
  q.footprint.duv_dx = {axes.x, 0};
  q.footprint.duv_dy = {0, axes.y};
  q.light.cos_half_angle = 1;
  q.light.intensity = 1;
  return q;
}

const chermain2021::Dictionary& chermain_level_dictionary(int levels) {
  if (levels == 16) return chermain2021::default_chermain_dictionary();
  if (levels != 4 && levels != 8 && levels != 12)
    throw std::invalid_argument("adequacy: a Chermain level keeps 4, 8, 12 or 16 levels");
  // Generated once each, in isolation: the generation is itself parallel (TBB), and a task stolen
  // while it runs must not wait on the same initialisation.
  const auto make = [](int l) {
    std::unique_ptr<chermain2021::Dictionary> d;
    tbb::this_task_arena::isolate([&] {
      chermain2021::DictionaryConfig c;
      c.levels = l;
      d = std::make_unique<chermain2021::Dictionary>(c);
    });
    return d;
  };
  static const std::unique_ptr<chermain2021::Dictionary> d4 = make(4), d8 = make(8),
                                                          d12 = make(12);
  return levels == 4 ? *d4 : levels == 8 ? *d8 : *d12;
}

Chermain::Params<double> chermain_level_params(const ChermainCell& c, ChermainLevel level,
                                               std::uint64_t seed) {
  if (level == ChermainLevel::kSmooth)
    throw std::invalid_argument("adequacy: the smooth level is the Gaussian slope density");
  auto p = Chermain::params<double>(param_values(c, chermain_level_ggaa(level), seed));
  p.sdf.dictionary = &chermain_level_dictionary(chermain_dictionary_levels(level));
  return p;
}

double chermain_level_values(const ChermainCell& cell, ChermainLevel level, int samples,
                             std::uint64_t seed, std::vector<double>& out) {
  out.resize(std::size_t(samples));
  using Clock = std::chrono::steady_clock;
  if (level == ChermainLevel::kSmooth) {
    // Independent of the position: one evaluation.
    const auto p = Chermain::params<double>(param_values(cell, false, seed));
    const auto t0 = Clock::now();
    const double v = smooth_value(p, chermain_cell_query(cell, chermain_surface_position(cell, 0)));
    for (int i = 0; i < samples; ++i) out[std::size_t(i)] = v;
    return std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / samples;
  }
  const auto p = chermain_level_params(cell, level, seed);
  const auto t0 = Clock::now();
  for (int i = 0; i < samples; ++i)
    out[std::size_t(i)] = value_at(p, chermain_cell_query(cell, chermain_surface_position(cell, i)));
  return std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / samples;
}

ChermainCellResult measure_chermain_cell(const ChermainCell& cell, int samples, std::uint64_t seed,
                                         const Decision& d, const ChermainLevelEdit& edit) {
  ChermainCellResult r;
  r.cell = cell;
  r.lod = chermain_construction(cell).lod;
  r.levels = measure_levels<kChermainLevels>(
      int(kChermainMostComplete), d,
      [&](int l, std::vector<double>& out) {
        return chermain_level_values(cell, ChermainLevel(l), samples, seed, out);
      },
      [&](int l, std::vector<double>& x) {
        if (edit) edit(ChermainLevel(l), x);
        if (l == int(ChermainLevel::kSmooth)) r.smooth = x.empty() ? 0 : x[0];
      });
  std::tie(r.chosen, r.cheapest_measured) =
      chosen_and_cheapest_measured(r.levels, int(kChermainMostComplete));
  r.construction = int(chermain_identical_level(cell));
  const LevelStats& c = r.levels[std::size_t(r.construction)];
  r.construction_refuted = c.mean_diff_lcb > d.threshold || c.cv_diff_lcb > d.threshold;
  return r;
}

std::vector<ChermainCellResult> measure_chermain_grid(const std::vector<ChermainCell>& cells,
                                                      int samples, const Decision& d,
                                                      const std::function<void()>& progress) {
  std::vector<std::size_t> all(cells.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  return measure_chermain_grid_at(cells, all, samples, d, progress);
}

std::vector<ChermainCellResult> measure_chermain_grid_at(
    const std::vector<ChermainCell>& cells, const std::vector<std::size_t>& positions, int samples,
    const Decision& d, const std::function<void()>& progress) {
  std::vector<ChermainCellResult> out(positions.size());
  if (positions.empty()) return out;
  for (int levels : {4, 8, 12, 16}) chermain_level_dictionary(levels);  // generated before the loop
  tbb::parallel_for(std::size_t(0), positions.size(), [&](std::size_t j) {
    const std::size_t i = positions[j];
    out[j] = measure_chermain_cell(cells.at(i), samples, check_seed("adequacy.chermain", i), d);
    if (progress) progress();
  });
  return out;
}

}  // namespace glintlab::verify::adequacy

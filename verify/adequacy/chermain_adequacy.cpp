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

}  // namespace

// The smooth level: the Gaussian slope density of covariance Σ (Eq. 16) in place of the
// patch-SDF, with the same V-cavity G2 (what the model falls back to past its last level).
double chermain_smooth_value(const Chermain::Params<double>& p, const ModelQuery<double>& q) {
  const Vec3<double> h = half_vector(q.wi, q.wo);
  if (!(q.wi.z > 0 && q.wo.z > 0 && h.z > 0)) return 0;
  const double D = Chermain::smooth_d(p.sdf, h);
  const double G2 = chermain2021::v_cavity_g2(q.wi, q.wo, h);
  return D * G2 / (4 * q.wi.z * q.wo.z) * q.wo.z;
}

namespace {

double half_log2_density() { return 0.5 * std::log2(kChermainDensity); }

// k = ⌊l + ½ log2 density⌋, at least 0 (chermain2021::dictionary_level).
int dictionary_level(double l) { return int(std::max(0.0, std::floor(l + half_log2_density()))); }

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
  const bool both_smooth = k.level_fine >= kLast && (!k.coarse_weighted || k.level_coarse >= kLast);
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

namespace {

// E[Σ W_0 W_1] per axis over the fine and coarse cells that share their draws (fine index 2I and
// coarse index I), the position uniform over a coarse cell (two fine ones), by the midpoint rule.
double shared_weight_per_axis() {
  constexpr int kNodes = 4096;
  double sum = 0;
  for (int q = 0; q < kNodes; ++q) {
    const double v = 2.0 * (q + 0.5) / kNodes;  // in fine cells
    const double s0 = v - 0.5, f0 = std::floor(s0), t0 = s0 - f0;
    const double s1 = v / 2 - 0.5, f1 = std::floor(s1), t1 = s1 - f1;
    for (int di = 0; di < 2; ++di)
      for (int dj = 0; dj < 2; ++dj)
        if (f0 + di == 2 * (f1 + dj)) sum += (di ? t0 : 1 - t0) * (dj ? t1 : 1 - t1);
  }
  return sum / kNodes;
}

// The moments of one cell's X at the LODs l0 and l0 + 1 (Eq. 4–6), over the rotation and the two
// marginals; `smooth[j]` where the LOD's level is past the dictionary's last (X the Gaussian).
struct LodMoments {
  double mu[2] = {0, 0}, m2[2] = {0, 0}, cross = 0, gauss = 0;
  bool smooth[2] = {false, false};
};

LodMoments lod_moments(const ChermainCell& c, int l0, int rotations,
                       ChermainLevel level = kChermainMostComplete) {
  const auto p = chermain_level_params(c, level, 0);
  const chermain2021::Dictionary& dict = *p.sdf.dictionary;
  const ModelQuery<double> q = chermain_cell_query(c, {0, 0});
  const Vec3<double> h = half_vector(q.wi, q.wo);
  const double mxs = -h.x / h.z, mys = -h.y / h.z;
  const chermain2021::Matrix M =
      chermain2021::matrix(p.sdf.sigma_x, p.sdf.sigma_y, p.sdf.rho, dict.sigma_o(), p.sdf.with_rho);
  const bool ggaa = p.sdf.kernel != chermain2021::kNoGgaa;
  const double sk = ggaa ? p.sdf.s_k : 0.0;
  const auto& d = p.d;
  const double ax = sk * (M.i00 * d.dx_x + M.i01 * d.dx_y), ay = sk * (M.i11 * d.dx_y);
  const double bx = sk * (M.i00 * d.dy_x + M.i01 * d.dy_y), by = sk * (M.i11 * d.dy_y);
  const double mx = M.i00 * mxs + M.i01 * mys, my = M.i11 * mys;
  LodMoments r;
  r.gauss = chermain2021::gaussian_sdf(mxs, mys, p.sdf.sigma_x, p.sdf.sigma_y,
                                       p.sdf.with_rho ? p.sdf.rho : 0.0);
  int k[2];
  for (int j = 0; j < 2; ++j) {
    k[j] = dictionary_level(double(l0 + j));
    r.smooth[j] = k[j] >= dict.levels();
  }
  const int N = dict.distributions();
  const auto lookup = [&](int n, int lv, double x, double dx, double dy) {
    return ggaa ? dict.lookup_grad(n, lv, x, dx, dy, p.sdf.wrap, 16)
                : dict.lookup_lod(n, lv, x, 0, p.sdf.wrap);
  };
  for (int t = 0; t < rotations; ++t) {
    const double theta = 2 * std::numbers::pi * (t + 0.5) / rotations;
    const double ct = std::cos(theta), st = std::sin(theta);
    const double xo = ct * mx + st * my, yo = -st * mx + ct * my;
    const double dxx = ct * ax + st * ay, dxy = ct * bx + st * by;
    const double dyx = -st * ax + ct * ay, dyy = -st * bx + ct * by;
    double g[2][2] = {}, q2[2][2] = {}, cr[2] = {};  // [level][axis]
    for (int n = 0; n < N; ++n) {
      double v[2][2];
      for (int j = 0; j < 2; ++j) {
        if (r.smooth[j]) continue;
        v[j][0] = lookup(n, k[j], xo, dxx, dxy);
        v[j][1] = lookup(n, k[j], yo, dyx, dyy);
        for (int a = 0; a < 2; ++a) g[j][a] += v[j][a], q2[j][a] += v[j][a] * v[j][a];
      }
      if (!r.smooth[0] && !r.smooth[1])
        for (int a = 0; a < 2; ++a) cr[a] += v[0][a] * v[1][a];
    }
    for (int j = 0; j < 2; ++j) {
      r.mu[j] += (g[j][0] / N) * (g[j][1] / N);
      r.m2[j] += (q2[j][0] / N) * (q2[j][1] / N);
    }
    r.cross += (cr[0] / N) * (cr[1] / N);
  }
  for (int j = 0; j < 2; ++j) {
    if (r.smooth[j]) {
      r.mu[j] = r.gauss, r.m2[j] = r.gauss * r.gauss;
      continue;
    }
    r.mu[j] /= rotations * M.det;
    r.m2[j] /= rotations * M.det * M.det;
  }
  r.cross = r.smooth[0] || r.smooth[1] ? r.mu[0] * r.mu[1] : r.cross / (rotations * M.det * M.det);
  return r;
}

// The patch-SDF's moments at LOD fraction w1 (the coarse LOD's weight) from its cells' moments.
ChermainExactMoments combine(const LodMoments& m, double w1, bool shared_draws) {
  static const double shared = [] {
    const double a = shared_weight_per_axis();
    return a * a;
  }();
  const double w0 = 1 - w1;
  ChermainExactMoments e;
  e.smooth = m.gauss;
  e.mean = w0 * m.mu[0] + w1 * m.mu[1];
  const double v0 = m.m2[0] - m.mu[0] * m.mu[0], v1 = m.m2[1] - m.mu[1] * m.mu[1];
  const double cov = m.cross - m.mu[0] * m.mu[1];
  const double var =
      4.0 / 9.0 * (w0 * w0 * v0 + w1 * w1 * v1) + (shared_draws ? 2 * w0 * w1 * cov * shared : 0.0);
  e.sd = std::sqrt(std::max(var, 0.0));
  return e;
}

}  // namespace

ChermainExactMoments chermain_exact_moments(const ChermainCell& c, int rotations, bool shared_draws,
                                            ChermainLevel level) {
  const double lod = chermain_construction(c).lod;
  const double l0 = std::floor(lod);
  return combine(lod_moments(c, int(l0), rotations, level), lod - l0, shared_draws);
}

namespace {
ChermainExactDifference difference(const ChermainExactMoments& a, const ChermainExactMoments& b) {
  return {a.mean / b.mean - 1, a.cv() - b.cv()};
}
}  // namespace

ChermainExactDifference chermain_exact_difference(const ChermainCell& c, ChermainLevel level,
                                                  int rotations) {
  return difference(chermain_exact_moments(c, rotations, true, level),
                    chermain_exact_moments(c, rotations, true, kChermainMostComplete));
}

double chermain_dictionary_boundary(const ChermainCell& c, ChermainLevel level, double tau,
                                    int rotations) {
  const int L = chermain_dictionary_levels(level);
  const int l0 = L - 1 - int(std::floor(half_log2_density()));
  const LodMoments ml = lod_moments(c, l0, rotations, level);
  const LodMoments m16 = lod_moments(c, l0, rotations, kChermainMostComplete);
  constexpr int kSteps = 1024;
  for (int s = 1; s < kSteps; ++s) {
    const double w1 = double(s) / kSteps;
    const ChermainExactDifference d = difference(combine(ml, w1, true), combine(m16, w1, true));
    if (std::max(std::abs(d.mean_diff), std::abs(d.cv_diff)) > tau)
      return chermain_identical_facets(L, c.theta_i_deg) * std::pow(4.0, w1);
  }
  return NAN;
}

double chermain_smooth_boundary(ChermainCell c, double tau, int rotations) {
  const double stretch_cos = std::cos(c.theta_i_deg * kDeg);
  // facets = density 4^l_P cos θ_i (the longer side 2^l_P, the shorter cos θ_i times it).
  const auto facets_at = [&](double l) {
    return kChermainDensity * std::pow(4.0, l) * stretch_cos;
  };
  int l0 = 39;
  while (l0 > -20 && dictionary_level(double(l0 - 1)) >= 16) --l0;  // from here both LODs smooth
  constexpr int kSteps = 256;
  for (--l0; l0 >= -20; --l0) {
    const LodMoments m = lod_moments(c, l0, rotations);
    for (int s = kSteps - 1; s >= 0; --s) {
      const ChermainExactMoments e = combine(m, double(s) / kSteps, true);
      if (std::max(std::abs(e.mean_diff()), e.cv()) > tau)
        return facets_at(l0 + double(s + 1) / kSteps);
    }
  }
  return facets_at(-20);
}

int chermain_chooser_level(const ChermainCell& c, double tau) {
  const auto p = chermain_level_params(c, kChermainMostComplete, 0);
  return int(
      choose_chermain_model_level(p, chermain_cell_query(c, chermain_surface_position(c, 0)), tau));
}

double chermain_chooser_cv(const ChermainCell& c) {
  const auto p = chermain_level_params(c, kChermainMostComplete, 0);
  const ModelQuery<double> q = chermain_cell_query(c, chermain_surface_position(c, 0));
  const Vec3<double> h = half_vector(q.wi, q.wo);
  return chermain_smooth_cv(p.sdf, p.d, Vec2<double>{-h.x / h.z, -h.y / h.z},
                            chermain_lods(p.sdf, q.footprint));
}

Vec2<double> chermain_surface_position(const ChermainCell& c, int i) {
  // The coarser LOD's cell side 2^(⌊l_P⌋ + 1) is at most twice the footprint's longer side.
  // (chermain_level_values computes the same inline, the cell hoisted out of its loop.)
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
  static const std::unique_ptr<chermain2021::Dictionary> d4 = make(4), d8 = make(8), d12 = make(12);
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
    const double v =
        chermain_smooth_value(p, chermain_cell_query(cell, chermain_surface_position(cell, 0)));
    for (int i = 0; i < samples; ++i) out[std::size_t(i)] = v;
    return std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / samples;
  }
  const auto p = chermain_level_params(cell, level, seed);
  // The query at position i is the cell's with uv = chermain_surface_position(cell, i): the
  // directions, the footprint and the coarser LOD's cell set up once, not at every position.
  ModelQuery<double> q = chermain_cell_query(cell, {0, 0});
  const double lod_cell = std::ldexp(1.0, int(std::floor(chermain_construction(cell).lod)) + 1);
  const auto t0 = Clock::now();
  for (int i = 0; i < samples; ++i) {
    const Vec2<double> r = surface_position(i);
    q.footprint.uv = {r.x * kChermainSpread * lod_cell, r.y * kChermainSpread * lod_cell};
    out[std::size_t(i)] = value_at(p, q);
  }
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
  r.chooser = chermain_chooser_level(cell, d.threshold);
  const LevelStats& e = r.levels[std::size_t(r.chooser)];
  r.chooser_refuted = e.mean_diff_lcb > d.threshold || e.cv_diff_lcb > d.threshold;
  r.cv_predicted = chermain_chooser_cv(cell);
  return r;
}

std::vector<ChermainCellResult> measure_chermain_grid(const std::vector<ChermainCell>& cells,
                                                      int samples, const Decision& d,
                                                      const std::function<void()>& progress) {
  std::vector<std::size_t> all(cells.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  return measure_chermain_grid_at(cells, all, samples, d, progress);
}

std::vector<ChermainCellResult> measure_chermain_grid_at(const std::vector<ChermainCell>& cells,
                                                         const std::vector<std::size_t>& positions,
                                                         int samples, const Decision& d,
                                                         const std::function<void()>& progress) {
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

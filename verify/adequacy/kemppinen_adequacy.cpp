#include "verify/adequacy/kemppinen_adequacy.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "core/models/kemppinen_beckmann.h"
#include "core/models/kemppinen_ggx.h"
#include "verify/adequacy/kemppinen_levels.h"

namespace glintlab::verify::adequacy {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

// The footprint's half-axes in uv: a rectangle of area points / K_P, stretched by 1/cos θ_i along
// the plane of incidence (x), as a pixel's footprint on a surface seen at θ_i.
Vec2<double> footprint_axes(const KemppinenCell& c) {
  const double side = std::sqrt(c.points / kKemppinenDensity);
  const double stretch = std::sqrt(1 / std::cos(c.theta_i_deg * kDeg));
  return {side * stretch, side / stretch};
}

// The spread's unit: the coarser level's spatial cell is 2^(⌊λ⌋+1)/√K_P ≤ 4 f σ = 2σ for the
// footprint's longer axis σ (f = 0.5), or 2/√K_P where λ is clamped at 0.
double coarser_cell(const KemppinenCell& c) {
  return 2 * std::max(footprint_axes(c).x, 1 / std::sqrt(kKemppinenDensity));
}

template <class M>
std::vector<double> model_param_values(const KemppinenCell& c, KemppinenLevel level,
                                       std::uint64_t seed) {
  return kemppinen_param_values<M>(c.alpha, kKemppinenDensity, level, seed);
}

// Positions at which a rational-erf level is also evaluated by the model itself, for its time.
constexpr int kRationalTimedPositions = 256;

template <class M>
typename M::template Params<double> level_params(const KemppinenCell& c, KemppinenLevel level,
                                                 std::uint64_t seed) {
  return kemppinen_level_params<M>(c.alpha, kKemppinenDensity, level, seed);
}

template <class M>
ModelEval<double, detail::kKemppinenIntermediates.size()> value_at(
    const typename M::template Params<double>& params, const KemppinenCell& c, int i) {
  return kemppinen_value(params, kemppinen_cell_query(c, kemppinen_surface_position(c, i)));
}

// An exact-erf level's values at the cell's first `samples` positions; returns the loop's ns per
// evaluation.
template <class M>
double exact_values_of(const KemppinenCell& c, KemppinenLevel exact, int samples,
                       std::uint64_t seed, std::vector<double>& out) {
  using Clock = std::chrono::steady_clock;
  out.resize(std::size_t(samples));
  const auto params = level_params<M>(c, exact, seed);
  // The query at position i is kemppinen_cell_query(c, kemppinen_surface_position(c, i)): the
  // directions, the footprint and the coarser cell set up once, its uv moved.
  ModelQuery<double> q = kemppinen_cell_query(c, {0, 0});
  const double cell = coarser_cell(c);
  const auto t0 = Clock::now();
  for (int i = 0; i < samples; ++i) {
    const Vec2<double> r = surface_position(i);
    q.footprint.uv = {r.x * kKemppinenSpread * cell, r.y * kKemppinenSpread * cell};
    out[std::size_t(i)] = kemppinen_value(params, q).value;
  }
  return std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / samples;
}

// A rational-erf level's values, `out` holding its exact twin's on entry. The rational erf enters
// only the compensation (Eq. 10), which depends on the half-vector and the LOD λ alone, not on
// the position (λ is the footprint's, the same at every position of a cell): the rational level's
// value is the exact level's plus a constant, taken here from one position
// (KemppinenAdequacy.RationalLevelIsTheExactOnePlusAConstant checks it against the model at every
// position). Its time is the model's own rational evaluation at the first
// kRationalTimedPositions positions.
template <class M>
double rational_values_from_exact(const KemppinenCell& c, KemppinenLevel level, int samples,
                                  std::uint64_t seed, std::vector<double>& out) {
  using Clock = std::chrono::steady_clock;
  const auto rational = level_params<M>(c, level, seed);
  const double shift = value_at<M>(rational, c, 0).value - out[0];
  for (double& v : out) v += shift;
  const int timed = std::min(samples, kRationalTimedPositions);
  double sink = 0;
  const auto t0 = Clock::now();
  for (int i = 0; i < timed; ++i) sink += value_at<M>(rational, c, i).value;
  const auto t1 = Clock::now();
  volatile double kept = sink;  // so the timed loop is not removed
  (void)kept;
  return std::chrono::duration<double, std::nano>(t1 - t0).count() / timed;
}

template <class M>
double values_of(const KemppinenCell& c, KemppinenLevel level, int samples, std::uint64_t seed,
                 std::vector<double>& out) {
  out.resize(std::size_t(samples));
  using Clock = std::chrono::steady_clock;
  if (level == KemppinenLevel::kSmooth) {
    // D★^f replaced by D: G2 and D of the model (independent of the position and the level).
    const auto t0 = Clock::now();
    const auto e = value_at<M>(level_params<M>(c, KemppinenLevel::kK1Exact, seed), c, 0);
    const double smooth =
        kemppinen_smooth_value(e, kemppinen_cell_query(c, kemppinen_surface_position(c, 0)));
    for (int i = 0; i < samples; ++i) out[std::size_t(i)] = smooth;
    return std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / samples;
  }
  const KemppinenLevel exact = kemppinen_exact_twin(level);
  const double t_exact = exact_values_of<M>(c, exact, samples, seed, out);
  if (exact == level) return t_exact;
  return rational_values_from_exact<M>(c, level, samples, seed, out);
}

template <class F>
decltype(auto) with_model(const std::string& model, F&& f) {
  if (model == "kemppinen_ggx") return f(KemppinenGGX{});
  if (model == "kemppinen_beckmann") return f(KemppinenBeckmann{});
  throw std::invalid_argument("adequacy: not a model of the Kemppinen family: " + model);
}

}  // namespace

KemppinenGridAxes kemppinen_grid_axes(Budget b) {
  KemppinenGridAxes g;
  if (b == Budget::kQuick) {
    // 1 … 10⁶: every row of the quick grid has reached the smooth level by 10⁵ (10⁷ was measured:
    // smooth in every row at 10⁶ and 10⁷).
    for (int e = 0; e <= 6; ++e) g.points.push_back(std::pow(10.0, e));
    g.alpha = {0.1, 0.3};
    g.theta_i_deg = {0, 60};
    g.samples = 8000;
  } else {
    for (int e = 0; e <= 14; ++e) g.points.push_back(std::round(std::pow(10.0, 0.5 * e)));
    g.alpha = {0.1, 0.2, 0.4};
    g.theta_i_deg = {0, 30, 60, 80};
    g.samples = 32000;
  }
  return g;
}

std::vector<KemppinenCell> make_kemppinen_grid(const std::vector<std::string>& models,
                                               const KemppinenGridAxes& axes) {
  std::vector<KemppinenCell> cells;
  for (const std::string& m : models)
    for (double ti : axes.theta_i_deg)
      for (double a : axes.alpha)
        for (int h = 0; h < axes.theta_h_count; ++h)
          for (double n : axes.points) cells.push_back({m, n, a, ti, std::atan(a * h) / kDeg, h});
  return cells;
}

Vec2<double> kemppinen_surface_position(const KemppinenCell& c, int i) {
  const double cell = coarser_cell(c);
  const Vec2<double> r = surface_position(i);
  return {r.x * kKemppinenSpread * cell, r.y * kKemppinenSpread * cell};
}

ModelQuery<double> kemppinen_cell_query(const KemppinenCell& c, Vec2<double> uv) {
  ModelQuery<double> q{};
  const double ti = c.theta_i_deg * kDeg, th = c.theta_h_deg * kDeg;
  q.wi = {std::sin(ti), 0, std::cos(ti)};
  // h tilted sideways, as in the binomial grid: ω_o.z = cos θ_i cos 2θ_h > 0 for θ_h < 45°.
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

std::vector<double> kemppinen_level_param_values(const KemppinenCell& c, KemppinenLevel level,
                                                 std::uint64_t seed) {
  if (level == KemppinenLevel::kSmooth)
    throw std::invalid_argument(
        "adequacy: the smooth level is the base NDF's value, not Algorithm 1");
  return with_model(c.model,
                    [&](auto m) { return model_param_values<decltype(m)>(c, level, seed); });
}

double kemppinen_level_values(const KemppinenCell& cell, KemppinenLevel level, int samples,
                              std::uint64_t seed, std::vector<double>& out) {
  return with_model(
      cell.model, [&](auto m) { return values_of<decltype(m)>(cell, level, samples, seed, out); });
}

KemppinenCellResult measure_kemppinen_cell(const KemppinenCell& cell, int samples,
                                           std::uint64_t seed, const Decision& d,
                                           const KemppinenLevelEdit& edit) {
  KemppinenCellResult r;
  r.cell = cell;
  // Each exact-erf level evaluated once: its rational twin's values are the same plus a constant
  // (rational_values_from_exact), the same values kemppinen_level_values gives, without
  // evaluating Algorithm 1 at every position again.
  std::array<std::vector<double>, kKemppinenLevels> exact_values;
  std::array<double, kKemppinenLevels> exact_ns{};
  r.levels = measure_levels<kKemppinenLevels>(
      int(KemppinenLevel::kK16Exact), d,
      [&](int l, std::vector<double>& out) {
        const auto level = KemppinenLevel(l);
        if (level == KemppinenLevel::kSmooth)
          return kemppinen_level_values(cell, level, samples, seed, out);
        const KemppinenLevel exact = kemppinen_exact_twin(level);
        std::vector<double>& e = exact_values[std::size_t(exact)];
        return with_model(cell.model, [&](auto m) {
          using M = decltype(m);
          if (e.empty())
            exact_ns[std::size_t(exact)] = exact_values_of<M>(cell, exact, samples, seed, e);
          out = e;
          if (exact == level) return exact_ns[std::size_t(exact)];
          return rational_values_from_exact<M>(cell, level, samples, seed, out);
        });
      },
      [&](int l, std::vector<double>& x) {
        if (edit) edit(KemppinenLevel(l), x);
        if (l == int(KemppinenLevel::kSmooth)) r.smooth = x.empty() ? 0 : x[0];
      });
  std::tie(r.chosen, r.cheapest_measured) =
      chosen_and_cheapest_measured(r.levels, int(KemppinenLevel::kK16Exact));
  with_model(cell.model, [&](auto m) {
    using M = decltype(m);
    const auto p =
        M::template params<double>(model_param_values<M>(cell, KemppinenLevel::kK16Exact, seed));
    const ModelQuery<double> q = kemppinen_cell_query(cell, kemppinen_surface_position(cell, 0));
    r.lambda = detail::kemppinen_model_eval(p, q, 0.0).intermediates[4];
    r.chooser = int(choose_kemppinen_model_level(p, q, d.threshold));
    const KemppinenMoments<double> mo =
        kemppinen_level_moments(p.glint, p.ndf, q.footprint, half_vector(q.wi, q.wo));
    r.cv_bound = mo.valid ? (std::sqrt(mo.var_points[3]) + mo.position_sd[3]) / mo.mean[3] : 0.0;
  });
  const LevelStats& c = r.levels[std::size_t(r.chooser)];
  r.chooser_refuted = c.mean_diff_lcb > d.threshold || c.cv_diff_lcb > d.threshold;
  return r;
}

std::vector<KemppinenCellResult> measure_kemppinen_grid(const std::vector<KemppinenCell>& cells,
                                                        int samples, const Decision& d,
                                                        const std::function<void()>& progress) {
  std::vector<std::size_t> all(cells.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  return measure_kemppinen_grid_at(cells, all, samples, d, progress);
}

std::vector<KemppinenCellResult> measure_kemppinen_grid_at(
    const std::vector<KemppinenCell>& cells, const std::vector<std::size_t>& positions, int samples,
    const Decision& d, const std::function<void()>& progress) {
  std::vector<KemppinenCellResult> out(positions.size());
  tbb::parallel_for(std::size_t(0), positions.size(), [&](std::size_t j) {
    const std::size_t i = positions[j];
    out[j] = measure_kemppinen_cell(cells.at(i), samples, check_seed("adequacy.kemppinen", i), d);
    if (progress) progress();
  });
  return out;
}

std::array<double, kKemppinenBoundaryLevels.size()> kemppinen_predicted_boundaries(KemppinenCell c,
                                                                                   double tau) {
  // Predicted adequacy at TAU itself: the chooser's rule with its margin divided out.
  const auto predicted_at = [&](double points) {
    c.points = points;
    return with_model(c.model, [&](auto m) {
      using M = decltype(m);
      const auto p =
          M::template params<double>(model_param_values<M>(c, KemppinenLevel::kK16Exact, 0));
      const ModelQuery<double> q = kemppinen_cell_query(c, kemppinen_surface_position(c, 0));
      return adequate_kemppinen_levels(
          kemppinen_level_moments(p.glint, p.ndf, q.footprint, half_vector(q.wi, q.wo)),
          tau / kChooserMargin);
    });
  };
  std::array<double, kKemppinenBoundaryLevels.size()> predicted;
  std::array<bool, kKemppinenBoundaryLevels.size()> open;
  predicted.fill(NAN);
  open.fill(true);
  const auto adequate = [](const AdequateKemppinenLevels<double>& a, KemppinenLevel l) {
    return l == KemppinenLevel::kSmooth ? bool(a.smooth)
                                        : bool(a.side[std::size_t(kemppinen_level_side(l) - 1)]);
  };
  double previous = NAN;
  for (int s = 0; s <= 1100; ++s) {
    const double points = std::pow(10.0, 9 - 0.01 * s);
    const AdequateKemppinenLevels<double> a = predicted_at(points);
    for (std::size_t i = 0; i < predicted.size(); ++i) {
      if (!open[i]) continue;
      if (adequate(a, kKemppinenBoundaryLevels[i])) continue;
      open[i] = false;  // not adequate here: the boundary is between here and the step above
      predicted[i] = s == 0 ? NAN : std::sqrt(points * previous);
    }
    previous = points;
  }
  for (std::size_t i = 0; i < predicted.size(); ++i)
    if (open[i]) predicted[i] = previous;  // adequate down to the scan's end
  return predicted;
}

std::vector<KemppinenBoundary> kemppinen_boundaries(const std::vector<KemppinenCellResult>& rows,
                                                    const KemppinenGridAxes& axes, double tau) {
  std::vector<KemppinenBoundary> out;
  const std::size_t n_cols = axes.points.size();
  for (std::size_t start = 0; start + n_cols <= rows.size(); start += n_cols) {
    const auto predicted = kemppinen_predicted_boundaries(rows[start].cell, tau);
    for (std::size_t i = 0; i < predicted.size(); ++i) {
      KemppinenBoundary b;
      b.row = rows[start].cell;
      b.level = kKemppinenBoundaryLevels[i];
      b.predicted = predicted[i];
      for (std::size_t k = n_cols; k-- > 0;) {
        const KemppinenCellResult& r = rows[start + k];
        if (!r.levels[std::size_t(b.level)].adequate) {
          b.measured_low = r.cell.points;
          b.measured_high = k + 1 < n_cols ? rows[start + k + 1].cell.points : NAN;
          break;
        }
        b.measured_high = r.cell.points;
      }
      out.push_back(b);
    }
  }
  return out;
}

}  // namespace glintlab::verify::adequacy

namespace glintlab::verify::adequacy {
namespace {

// E[R] and E[R²] of the roulette R(r, w) of Eq. 8 (kemppinen2025::roulette), r uniform on [0, 1),
// by the midpoint rule; R = w for linear blending.
std::pair<double, double> roulette_moments(kemppinen2025::Blend blend, double w) {
  if (blend != kemppinen2025::Blend::kRoulette) return {w, w * w};
  constexpr int kNodes = 2000;
  double m1 = 0, m2 = 0;
  for (int i = 0; i < kNodes; ++i) {
    const double r = kemppinen2025::roulette((i + 0.5) / kNodes, w);
    m1 += r, m2 += r * r;
  }
  return {m1 / kNodes, m2 / kNodes};
}

// Along one axis, at positions x uniform over [0, period): the block of n cells of side `cell`
// that Algorithm 1 visits around x (block_start), and per position the block's mass of the filter
// N(x − g; σ) over g, the sum of its cells' squared masses, and the √2-narrower filter's mass.
constexpr int kPositionNodes = 256;
struct AxisBlock {
  std::array<double, kPositionNodes> mass, mass_sq_cells, narrow;
};
AxisBlock axis_block(int n, double cell, double sigma, double period) {
  AxisBlock b{};
  for (int q = 0; q < kPositionNodes; ++q) {
    const double x = (q + 0.5) / kPositionNodes * period;
    const double start = std::floor(x / cell - 0.5 * (n - 1));
    double m = 0, sq = 0;
    for (int i = 0; i < n; ++i) {
      const double lo = (start + i) * cell - x, hi = lo + cell;
      const double mi =
          0.5 * (std::erf(hi / (std::sqrt(2.0) * sigma)) - std::erf(lo / (std::sqrt(2.0) * sigma)));
      m += mi, sq += mi * mi;
    }
    const double lo = start * cell - x, hi = lo + n * cell;
    b.mass[std::size_t(q)] = m;
    b.mass_sq_cells[std::size_t(q)] = sq;
    b.narrow[std::size_t(q)] = 0.5 * (std::erf(hi / sigma) - std::erf(lo / sigma));
  }
  return b;
}

double node_mean(const std::array<double, kPositionNodes>& a) {
  double s = 0;
  for (double v : a) s += v;
  return s / kPositionNodes;
}
double node_mean_product(const std::array<double, kPositionNodes>& a,
                         const std::array<double, kPositionNodes>& b) {
  double s = 0;
  for (std::size_t q = 0; q < a.size(); ++q) s += a[q] * b[q];
  return s / kPositionNodes;
}

// Along one angular axis at level resolution res_a: the masses of the lobe N(x_a; σ) over the
// block's cells inside the square [0, 1): their sum, the sum of their squares, the narrower
// lobe's mass over them.
struct AngularAxis {
  double mass = 0, mass_sq_cells = 0, narrow = 0;
};
AngularAxis angular_axis(int n, double res_a, double x_a, double sigma) {
  AngularAxis a;
  const double start = std::floor(x_a * res_a - 0.5 * (n - 1));
  const double first = std::max(start, 0.0), last = std::min(start + n, res_a);  // [first, last)
  for (double i = first; i < last; ++i) {
    const double lo = i / res_a - x_a, hi = (i + 1) / res_a - x_a;
    const double m =
        0.5 * (std::erf(hi / (std::sqrt(2.0) * sigma)) - std::erf(lo / (std::sqrt(2.0) * sigma)));
    a.mass += m, a.mass_sq_cells += m * m;
  }
  if (last > first)
    a.narrow =
        0.5 * (std::erf((last / res_a - x_a) / sigma) - std::erf((first / res_a - x_a) / sigma));
  return a;
}

template <class Ndf>
KemppinenExactMoments exact_moments(const kemppinen2025::Params<double>& p, const Ndf& ndf,
                                    const FootprintQuery<double>& fp, Vec3<double> h, int n) {
  using namespace kemppinen2025;
  KemppinenExactMoments out;
  const Angular<double> ang = angular(p, ndf, h);
  if (!ang.valid) return out;
  const double res = base_resolution(p);
  const Sym2<double> sigma_s = spatial_covariance(p, fp, res);
  const double lambda = lod(sigma_s, res);
  const double fl = std::min(std::floor(lambda), double(kMaxLevel - 1));
  const double w[2] = {1 - (lambda - fl), lambda - fl};
  const double sx = std::sqrt(sigma_s.xx), sy = std::sqrt(sigma_s.yy);
  const Vec2<double> sa = ang.sigma_a;
  // E[X²] per unit of m'_s m'_a: 1 / (K_P 16π² σ_sx σ_sy σ_ax σ_ay).
  const double points_scale =
      1 / (res * res * 16 * std::numbers::pi * std::numbers::pi * sx * sy * sa.x * sa.y);
  // Positions uniform over the coarser level's spatial cell (both blocks are periodic in it).
  const double period = std::ldexp(1.0, int(fl) + 1) / res;
  std::array<AxisBlock, 2> bx, by;
  std::array<double, 2> er{}, a{};
  double mean = 0, var_within = 0;
  for (int s = 0; s < 2; ++s) {
    const double res_a = std::ldexp(1.0, int(fl) + s), cell = res_a / res;
    bx[std::size_t(s)] = axis_block(n, cell, sx, period);
    by[std::size_t(s)] = axis_block(n, cell, sy, period);
    const AngularAxis ax = angular_axis(n, res_a, ang.x_a.x, sa.x);
    const AngularAxis ay = angular_axis(n, res_a, ang.x_a.y, sa.y);
    const auto [r1, r2] = roulette_moments(p.blend, w[s]);
    er[std::size_t(s)] = r1;
    a[std::size_t(s)] = ax.mass * ay.mass;
    // The compensation (Eq. 10), as the model computes it: w_l (∫_□ N − ∫_B N), the erf of p.
    const Vec2<double> lo{std::max(std::floor(ang.x_a.x * res_a - 0.5 * (n - 1)), 0.0) / res_a,
                          std::max(std::floor(ang.x_a.y * res_a - 0.5 * (n - 1)), 0.0) / res_a};
    const Vec2<double> hi{
        std::min(std::floor(ang.x_a.x * res_a - 0.5 * (n - 1)) + n, res_a) / res_a,
        std::min(std::floor(ang.x_a.y * res_a - 0.5 * (n - 1)) + n, res_a) / res_a};
    if (p.compensate) mean += w[s] * compensation(ang.x_a, sa, lo, hi, p.erf);
    const AxisBlock &x = bx[std::size_t(s)], &y = by[std::size_t(s)];
    mean += r1 * a[std::size_t(s)] * node_mean(x.mass) * node_mean(y.mass);
    var_within +=
        r2 * ax.narrow * ay.narrow * node_mean(x.narrow) * node_mean(y.narrow) * points_scale -
        r1 * r1 * ax.mass_sq_cells * ay.mass_sq_cells * node_mean(x.mass_sq_cells) *
            node_mean(y.mass_sq_cells);
  }
  // Var_x of the conditional mean Σ_l E[R_l] a_l s_l(x) s_l(y): x and y independent.
  double second = 0, first = 0;
  for (std::size_t s = 0; s < 2; ++s) {
    first += er[s] * a[s] * node_mean(bx[s].mass) * node_mean(by[s].mass);
    for (std::size_t t = 0; t < 2; ++t)
      second += er[s] * a[s] * er[t] * a[t] * node_mean_product(bx[s].mass, bx[t].mass) *
                node_mean_product(by[s].mass, by[t].mass);
  }
  out.mean = mean;
  out.sd = std::sqrt(std::max(var_within + second - first * first, 0.0));
  return out;
}

}  // namespace

KemppinenExactMoments kemppinen_exact_moments(const KemppinenCell& c, KemppinenLevel level) {
  if (level == KemppinenLevel::kSmooth) return {1, 0};
  return with_model(c.model, [&](auto m) {
    using M = decltype(m);
    const auto p = level_params<M>(c, level, 0);
    const ModelQuery<double> q = kemppinen_cell_query(c, kemppinen_surface_position(c, 0));
    return exact_moments(p.glint, p.ndf, q.footprint, half_vector(q.wi, q.wo),
                         kemppinen_level_side(level));
  });
}

namespace {

// The largest log10(points) of a scan down from 10⁹ in steps of 1/50 decade at which `above`
// holds, refined by bisection to 10⁻⁶ of a decade, as points (NaN: above at 10⁹; 0.01, the scan's
// end, where it never is).
template <class Above>
double scan_boundary(const Above& above) {
  for (int s = 0; s <= 550; ++s) {
    const double lp = 9 - 0.02 * s;
    if (!above(lp)) continue;
    if (s == 0) return NAN;
    double lo = lp, hi = lp + 0.02;  // above at lo, not at hi
    while (hi - lo > 1e-6) {
      const double mid = 0.5 * (lo + hi);
      (above(mid) ? lo : hi) = mid;
    }
    return std::pow(10.0, 0.5 * (lo + hi));
  }
  return 0.01;
}

}  // namespace

double kemppinen_exact_cv_boundary(KemppinenCell c, KemppinenLevel level, double tau) {
  return scan_boundary([&](double log_points) {
    c.points = std::pow(10.0, log_points);
    return kemppinen_exact_moments(c, level).cv() > tau;
  });
}

KemppinenExactDifference kemppinen_exact_difference(const KemppinenCell& c, KemppinenLevel level) {
  const KemppinenExactMoments m = kemppinen_exact_moments(c, level);
  const KemppinenExactMoments ref = kemppinen_exact_moments(c, KemppinenLevel::kK16Exact);
  if (!(ref.mean > 0)) return {0, 0};
  return {m.mean / ref.mean - 1, m.cv() - ref.cv()};
}

double kemppinen_exact_level_boundary(KemppinenCell c, KemppinenLevel level, double tau) {
  return scan_boundary([&](double log_points) {
    c.points = std::pow(10.0, log_points);
    const KemppinenExactDifference d = kemppinen_exact_difference(c, level);
    return std::max(std::abs(d.mean_diff), std::abs(d.cv_diff)) > tau;
  });
}

}  // namespace glintlab::verify::adequacy

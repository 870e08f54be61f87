// One stability-map cell: eval, pdf and sample of a registered model at one setting, counted.
#include "verify/stability/cell_stats.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>
#include <utility>

#include "core/math/rng.h"
#include "verify/claims/gof_family.h"

namespace glintlab::verify::stability {
namespace {

using V3 = Vec3<double>;

V3 uniform_sphere(double u1, double u2) {
  const double z = 1 - 2 * u1, r = std::sqrt(std::max(0.0, 1 - z * z));
  const double phi = 2 * std::numbers::pi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Mean and standard error of n values from their sum and sum of squares.
void mean_error(double sum, double sum2, std::uint64_t n, double& mean, double& error) {
  mean = n ? sum / double(n) : 0;
  const double var = n > 1 ? std::max(0.0, (sum2 - double(n) * mean * mean) / double(n - 1)) : 0;
  error = n ? std::sqrt(var / double(n)) : 0;
}

}  // namespace

std::array<Vec3<double>, 4> pixel_corner_reflections(const Vec3<double>& wi, double s) {
  // Corner order of core/scene/footprint.h: (x−½, y−½), (x+½, y−½), (x−½, y+½), (x+½, y+½).
  constexpr double kOffset[4][2] = {{-0.5, -0.5}, {0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}};
  std::array<V3, 4> r{};
  for (std::size_t c = 0; c < 4; ++c)
    r[c] = reflect(wi, normalize(V3{kOffset[c][0] * s, kOffset[c][1] * s, 1.0}));
  return r;
}

double furnace_light_solid_angle(const ModelEntry& m, const std::vector<double>& values,
                                 const ModelQuery<double>& q) {
  if (!(m.needs & kNeedsAreaLight)) return 0;
  for (std::size_t i = 0; i < m.intermediates.size(); ++i)
    if (m.intermediates[i] == "solid_angle") {
      ModelQuery<double> up = q;
      up.wo = {0, 0, 1};
      return m.eval(values, up).intermediates[i];
    }
  return 2 * std::numbers::pi * (1 - q.light.cos_half_angle);
}

bool is_probability_name(std::string_view name) {
  constexpr std::string_view kRaw = "_unclamped";  // the raw value before clamping, by design
  const bool raw = name.size() >= kRaw.size() && name.substr(name.size() - kRaw.size()) == kRaw;
  return (name == "p" || name.substr(0, 2) == "p_") && !raw;
}

void Defects::add_record(std::initializer_list<double> xs,
                         std::initializer_list<double> signed_free) {
  bool n = false, i = false, neg = false;
  for (double x : xs) {
    n |= x != x;
    i |= std::isinf(x);
    neg |= x < 0;
  }
  for (double x : signed_free) {  // components of a direction: only finiteness matters
    n |= x != x;
    i |= std::isinf(x);
  }
  nan += n;
  inf += i;
  negative += neg;
}

double CellStats::gain() const {
  double g = 0;
  auto consider = [&](double a, double e) {
    if (std::isfinite(a) && a - 1 > kGainSigmas * e + kGainRounding) g = std::max(g, a - 1);
  };
  consider(albedo, albedo_error);
  consider(albedo_uniform, albedo_uniform_error);
  return g;
}

V3 incidence_at(double theta_deg) { return incidence(theta_deg); }

namespace {

// The cell's parameters and query (its footprint and light follow the plane's axis and `row`),
// and the furnace's normalisation 1/Ω for area lights (1 otherwise).
struct CellSetup {
  std::vector<double> values;
  ModelQuery<double> q{};
  double light_solid_angle = 0, furnace = 1;
};

CellSetup setup_cell(const SweepTarget& target, const SweepPlane& plane, double row,
                     double theta_deg) {
  const ModelEntry& m = *target.model;
  CellSetup c;
  c.values = cell_params(target, plane, row);
  ModelQuery<double>& q = c.q;
  q.wi = incidence_at(theta_deg);
  const double s = plane.axis == Axis::kFootprint ? row : kDefaultFootprint;
  q.footprint = {{0.5, 0.5}, {s, 0}, {0, s}};
  const double half_deg = plane.axis == Axis::kLightSize ? row
                          : (m.needs & kNeedsAreaLight)  ? kDefaultLightHalfAngleDeg
                                                         : 0.0;
  q.light = {std::cos(half_deg * std::numbers::pi / 180), 1.0};
  if (m.needs & kNeedsPixelCorners) q.footprint.corner_r = pixel_corner_reflections(q.wi, s);
  // Area-light models return L_o/L_i, the BRDF integrated over the light: ∫ (L_o/L_i) dωo over
  // the light's centre is Ω ρ(ωi) exactly, so the furnace divides by Ω (a delta light: Ω = 0, no
  // normalisation; such a light reflects nothing almost everywhere).
  c.light_solid_angle = furnace_light_solid_angle(m, c.values, q);
  c.furnace = c.light_solid_angle > 0 ? 1 / c.light_solid_angle : 1.0;
  return c;
}

}  // namespace

CellStats measure_cell(const SweepTarget& target, const SweepPlane& plane, double row,
                       double theta_deg, const CellBudget& budget, std::uint64_t seed) {
  const ModelEntry& m = *target.model;
  std::vector<std::size_t> p_index;
  for (std::size_t i = 0; i < m.intermediates.size(); ++i)
    if (is_probability_name(m.intermediates[i])) p_index.push_back(i);
  const bool has_float = static_cast<bool>(m.eval_float);
  CellStats c;
  CellSetup setup = setup_cell(target, plane, row, theta_deg);
  const std::vector<double>& values = setup.values;
  ModelQuery<double>& q = setup.q;
  const double furnace = setup.furnace;
  c.light_solid_angle = setup.light_solid_angle;

  auto eval_at = [&](const V3& wo, double u1, double u2, bool uniform, double& sum, double& sum2) {
    q.wo = wo;
    q.footprint.uv = {u1, u2};  // glint models: a different position per evaluation
    const ErasedEval r = m.eval(values, q);
    ++c.evals;
    ++c.pdf_calls;
    c.value.add(r.value);
    c.pdf.add(r.pdf);
    for (std::size_t i : p_index) {
      const double p = r.intermediates[i];
      ++c.p_evals;
      if (p > 1) ++c.p_above_one;
      if (std::isfinite(p)) c.p_max = std::max(c.p_max, p);
    }
    if (uniform) {
      const double v = 4 * std::numbers::pi * furnace * (std::isfinite(r.value) ? r.value : 0.0);
      sum += v;
      sum2 += v * v;
    }
    if (has_float) {
      const ErasedEval f = m.eval_float(values, q);
      ++c.evals_f;
      ++c.pdf_calls_f;
      c.value_f.add(f.value);
      c.pdf_f.add(f.pdf);
    }
  };

  // Uniform directions (back-facing ωo included) and the directions where half vectors and
  // denominators degenerate: the mirror direction, ωo = −ωi (h = 0), ωo = ωi, the horizon.
  double us = 0, us2 = 0, unused = 0, unused2 = 0;
  for (std::uint64_t i = 0; i < budget.uniform_evals; ++i) {
    const V3 wo =
        uniform_sphere(counter_uniform<double>(seed, i, 0), counter_uniform<double>(seed, i, 1));
    eval_at(wo, counter_uniform<double>(seed, i, 2), counter_uniform<double>(seed, i, 3), true, us,
            us2);
  }
  mean_error(us, us2, budget.uniform_evals, c.albedo_uniform, c.albedo_uniform_error);
  const V3 wi = q.wi;
  const double hr = std::hypot(wi.x, wi.y);
  const V3 horizon = hr > 0 ? V3{-wi.x / hr, -wi.y / hr, 0} : V3{1, 0, 0};
  for (const V3& wo : {V3{-wi.x, -wi.y, wi.z}, V3{-wi.x, -wi.y, -wi.z}, wi, horizon})
    eval_at(wo, 0.5, 0.5, false, unused, unused2);

  // Sampled directions: the record, then eval and pdf() at each accepted ωo.
  double ws = 0, ws2 = 0;
  for (std::uint64_t i = 0; i < budget.samples; ++i) {
    const std::uint64_t k = budget.uniform_evals + i;
    const Vec2<double> u{counter_uniform<double>(seed, k, 4), counter_uniform<double>(seed, k, 5)};
    q.footprint.uv = {counter_uniform<double>(seed, k, 2), counter_uniform<double>(seed, k, 3)};
    const ModelSample<double> smp = m.sample(values, q, u);
    ++c.samples;
    c.sample.add_record({smp.pdf, smp.weight}, {smp.wo.x, smp.wo.y, smp.wo.z});
    if (has_float) {
      const ModelSample<double> f = m.sample_float(values, q, u);
      ++c.samples_f;
      c.sample_f.add_record({f.pdf, f.weight}, {f.wo.x, f.wo.y, f.wo.z});
    }
    const double w = smp.rejected || !std::isfinite(smp.weight) ? 0.0 : smp.weight;
    ws += furnace * w;
    ws2 += furnace * furnace * w * w;
    c.weight_max = std::max(c.weight_max, w);
    if (smp.rejected) continue;
    ++c.accepted;
    const V3 wo = smp.wo;
    const Vec2<double> uv = q.footprint.uv;
    eval_at(wo, uv.x, uv.y, false, unused, unused2);
    q.wo = wo;
    c.pdf.add(m.pdf(values, q));
    ++c.pdf_calls;
    if (has_float) {
      c.pdf_f.add(m.pdf_float(values, q));
      ++c.pdf_calls_f;
    }
  }
  mean_error(ws, ws2, budget.samples, c.albedo, c.albedo_error);
  return c;
}

void measure_fixed_position_variance(CellStats& c, const SweepTarget& target,
                                     const SweepPlane& plane, double row, double theta_deg,
                                     const CellBudget& budget, std::uint64_t seed) {
  const ModelEntry& m = *target.model;
  CellSetup setup = setup_cell(target, plane, row, theta_deg);
  const std::vector<double>& values = setup.values;
  ModelQuery<double>& q = setup.q;
  const double furnace = setup.furnace;
  c.relative_variance = 0;
  c.variance_samples = c.positions_reflecting = 0;

  // The position drawn once, then only the sampler's random numbers (index ranges and dimensions
  // measure_cell leaves unused, so its draws and these are independent of which runs first). A
  // position above the bound is measured again with fresh numbers, kVarianceConfirmFactor times
  // as many, and that estimate is the position's.
  const std::uint64_t first = budget.uniform_evals + budget.samples;
  auto relative_variance_at = [&](std::uint64_t j, std::uint64_t n, std::uint64_t dim) {
    double ps = 0, ps2 = 0;
    for (std::uint64_t i = 0; i < n; ++i) {
      const std::uint64_t k = first + j * n + i;
      const Vec2<double> u{counter_uniform<double>(seed, k, dim),
                           counter_uniform<double>(seed, k, dim + 1)};
      const ModelSample<double> smp = m.sample(values, q, u);
      ++c.variance_samples;
      const double w = furnace * (smp.rejected || !std::isfinite(smp.weight) ? 0.0 : smp.weight);
      ps += w;
      ps2 += w * w;
    }
    double mean = 0, error = 0;
    mean_error(ps, ps2, n, mean, error);
    const double scale = std::max(mean, kDarkAlbedo);
    return std::pair{mean, error * error * double(n) / (scale * scale)};
  };
  for (std::uint64_t j = 0; j < kVariancePositions; ++j) {
    q.footprint.uv = {counter_uniform<double>(seed, first + j, 6),
                      counter_uniform<double>(seed, first + j, 7)};
    auto [mean, rv] = relative_variance_at(j, budget.samples, 8);
    if (rv > kVarianceBlowup)
      std::tie(mean, rv) = relative_variance_at(j, kVarianceConfirmFactor * budget.samples, 10);
    c.positions_reflecting += mean >= kDarkAlbedo;
    c.relative_variance = std::max(c.relative_variance, rv);
  }
}

}  // namespace glintlab::verify::stability

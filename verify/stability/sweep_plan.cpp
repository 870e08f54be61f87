// Targets and planes of the stability sweeps, from each model's ParamSpec ranges and needs.
#include "verify/stability/sweep_plan.h"

#include <fmt/format.h>
#include <fnmatch.h>

#include <algorithm>
#include <cmath>

namespace glintlab::verify::stability {
namespace {

std::optional<std::size_t> find_param(const ModelEntry& m, std::string_view name) {
  for (std::size_t i = 0; i < m.params.size(); ++i)
    if (m.params[i].name == name && m.params[i].choices.empty()) return i;
  return std::nullopt;
}

bool matches(const std::string& globs, std::string_view name) {
  if (globs.empty()) return true;
  const std::string n(name);
  std::size_t start = 0;
  while (start <= globs.size()) {
    const std::size_t end = std::min(globs.find(',', start), globs.size());
    const std::string g = globs.substr(start, end - start);
    if (!g.empty() && ::fnmatch(g.c_str(), n.c_str(), 0) == 0) return true;
    start = end + 1;
  }
  return false;
}

// n values from lo to hi, log-spaced where the range spans more than two decades and lo > 0.
std::vector<double> span_range(const ParamSpec& p, int n) {
  std::vector<double> v;
  const double lo = p.lo, hi = p.hi;
  const bool log = lo > 0 && hi / lo > 100;
  for (int i = 0; i < n; ++i) {
    const double t = double(i) / double(n - 1);
    v.push_back(clamp_to_range(p, log ? lo * std::pow(hi / lo, t) : lo + (hi - lo) * t));
  }
  return v;
}

void dedupe(std::vector<double>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

}  // namespace

std::string SweepTarget::id() const { return fmt::format("{}/{}", model->name, sampler); }

double clamp_to_range(const ParamSpec& p, double v) {
  const double lo = p.lo_open ? p.lo + std::max(std::abs(p.lo), 1.0) * 1e-9 : p.lo;
  const double hi = p.hi_open ? p.hi - std::max(std::abs(p.hi), 1.0) * 1e-9 : p.hi;
  return std::clamp(v, lo, hi);
}

std::vector<SweepTarget> sweep_targets(const std::string& globs) {
  std::vector<SweepTarget> out;
  for (const ModelEntry& m : registered_models()) {
    if (!matches(globs, m.name)) continue;
    std::optional<std::size_t> sp;
    for (std::size_t i = 0; i < m.params.size(); ++i)
      if (m.params[i].name == "sampler" && !m.params[i].choices.empty()) sp = i;
    if (!sp) {
      out.push_back({&m, std::nullopt, 0, "default"});
      continue;
    }
    for (std::size_t c = 0; c < m.params[*sp].choices.size(); ++c)
      out.push_back({&m, sp, c, std::string(m.params[*sp].choices[c])});
  }
  return out;
}

std::vector<SweepPlane> sweep_planes(const ModelEntry& m, bool quick) {
  // Incidence: dense towards grazing (89.999° is the brief's limit) and a few back-facing angles.
  // The quick grid keeps the full grid's extremes and every grazing angle from 89.9° up.
  const std::vector<double> theta =
      quick ? std::vector<double>{0, 45, 75, 85, 89, 89.9, 89.95, 89.99, 89.999, 90.001, 120, 179.9}
            : std::vector<double>{0,      15,   30, 45,   60,   70,    75,    80,
                                  85,     88,   89, 89.5, 89.9, 89.95, 89.99, 89.999,
                                  90.001, 90.5, 95, 120,  150,  179.9};
  std::vector<SweepPlane> planes;
  const auto ax = find_param(m, "alpha_x"), ay = find_param(m, "alpha_y");
  const auto alpha = find_param(m, "alpha");
  if ((ax && ay) || alpha) {
    SweepPlane p{Axis::kAlpha, "alpha", "alpha (isotropic)", "α", {}, theta, 0};
    const int n = quick ? 11 : 25;
    const ParamSpec& spec = m.params[ax ? *ax : *alpha];
    for (int i = 0; i < n; ++i)  // 1e-4 … 4, clamped to the parameter's range
      p.rows.push_back(clamp_to_range(spec, 1e-4 * std::pow(4e4, double(i) / double(n - 1))));
    dedupe(p.rows);
    planes.push_back(std::move(p));
  }
  if (ax && ay) {
    SweepPlane p{Axis::kAnisotropy,
                 "anisotropy",
                 "anisotropy ratio alpha_x/alpha_y (alpha_x*alpha_y = 0.01)",
                 "αx/αy",
                 {},
                 theta,
                 0};
    const int n = quick ? 7 : 13;
    for (int i = 0; i < n; ++i) p.rows.push_back(std::pow(1000.0, double(i) / double(n - 1)));
    planes.push_back(std::move(p));
  }
  for (auto [axis, name] :
       {std::pair{Axis::kDensity, "density"}, std::pair{Axis::kMicroroughness, "microroughness"}}) {
    if (const auto i = find_param(m, name)) {
      SweepPlane p{axis, name, name, name, span_range(m.params[*i], quick ? 7 : 15), theta, *i};
      dedupe(p.rows);
      planes.push_back(std::move(p));
    }
  }
  if (m.needs & kNeedsFootprint) {
    SweepPlane p{Axis::kFootprint,
                 "footprint",
                 "footprint size s (uv per pixel)",
                 "footprint s",
                 {},
                 theta,
                 0};
    const int n = quick ? 7 : 13;
    for (int i = 0; i < n; ++i) p.rows.push_back(1e-6 * std::pow(1e6, double(i) / double(n - 1)));
    planes.push_back(std::move(p));
  }
  if (m.needs & (kNeedsPointLight | kNeedsAreaLight)) {
    SweepPlane p{Axis::kLightSize,
                 "light_size",
                 "light cone half-angle (degrees)",
                 "light half-angle",
                 {},
                 theta,
                 0};
    p.rows = quick ? std::vector<double>{0, 1e-3, 0.01, 0.1, 1, 10, 90}
                   : std::vector<double>{0,   1e-4, 1e-3, 3e-3, 0.01, 0.03, 0.1,
                                         0.3, 1,    3,    10,   30,   60,   90};
    planes.push_back(std::move(p));
  }
  // Footprint and light planes vary only the query: without a parameter plane the model's own
  // parameters would stay at their defaults, so the named axes count only when one applied.
  const bool parameter_plane = std::any_of(planes.begin(), planes.end(), [](const SweepPlane& p) {
    return p.axis != Axis::kFootprint && p.axis != Axis::kLightSize;
  });
  if (!parameter_plane) {
    for (std::size_t i = 0; i < m.params.size(); ++i) {
      const ParamSpec& spec = m.params[i];
      if (!spec.choices.empty() || !std::isfinite(spec.lo) || !std::isfinite(spec.hi)) continue;
      const std::string name(spec.name);
      SweepPlane p{Axis::kParameter, name, name, name, span_range(spec, quick ? 7 : 15), theta, i};
      if (spec.integral)
        for (double& r : p.rows)
          r = std::clamp(std::round(r), std::ceil(spec.lo), std::floor(spec.hi));
      dedupe(p.rows);
      planes.push_back(std::move(p));
    }
  }
  if (planes.empty())
    planes.push_back(
        {Axis::kDirections, "directions", "defaults (no parameter swept)", "-", {0}, theta, 0});
  return planes;
}

std::vector<double> cell_params(const SweepTarget& t, const SweepPlane& plane, double row) {
  const ModelEntry& m = *t.model;
  std::vector<double> v;
  for (const ParamSpec& p : m.params) v.push_back(p.default_value);
  if (t.sampler_param) v[*t.sampler_param] = double(t.sampler_choice);
  const auto ax = find_param(m, "alpha_x"), ay = find_param(m, "alpha_y");
  const auto alpha = find_param(m, "alpha");
  double a_x = kDefaultAlpha, a_y = kDefaultAlpha;
  if (plane.axis == Axis::kAlpha) a_x = a_y = row;
  if (plane.axis == Axis::kAnisotropy)
    a_x = kDefaultAlpha * std::sqrt(row), a_y = kDefaultAlpha / std::sqrt(row);
  if (ax) v[*ax] = clamp_to_range(m.params[*ax], a_x);
  if (ay) v[*ay] = clamp_to_range(m.params[*ay], a_y);
  if (alpha) v[*alpha] = clamp_to_range(m.params[*alpha], a_x);
  if (plane.axis == Axis::kDensity || plane.axis == Axis::kMicroroughness ||
      plane.axis == Axis::kParameter)
    v[plane.param] = row;
  return v;
}

bool in_core_domain(const SweepPlane& plane, double row, double theta_deg) {
  if (theta_deg > kCoreMaxThetaDeg) return false;
  if (plane.axis == Axis::kAlpha) return row >= 1e-3;
  if (plane.axis == Axis::kAnisotropy) return row <= 100;
  return true;
}

}  // namespace glintlab::verify::stability

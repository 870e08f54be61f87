// The rules kneiphof.ltc-probability judges its cells by (ltc_cells.h): the probability within
// 10 % of the Monte Carlo D_Ωh (± 3 SE), and the rendered pixel L̂ = L_o·b/(N_P p) (Eq. 16) within
// the 2 % Weber fraction of the Monte Carlo pixel; their summaries and the fit comparison.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "verify/claims/kneiphof/ltc_cells.h"

namespace glintlab::verify::kneiphof_claims::ltc {
namespace {

// --- The rendered difference ---------------------------------------------------------------------

// The pixel's mean and standard deviation relative to L_o for N facets and probability p: the
// count uses min(p, 1) and so does the factor b/(N_P p) (core/glints/deliot_belcour.h), so the
// mean is L_o at any p; `brightness` scales the whole pixel (the control's brighter render).
struct Pixel {
  double mean, sd;
};
Pixel pixel(double p_raw, double n, double brightness) {
  const double p = std::clamp(p_raw, 1e-300, 1.0);
  return {brightness, brightness * std::sqrt((1 - p) / (n * p))};
}

// The rendered difference against the Monte Carlo pixel with probability p_mc, at N facets:
// max(|Δ mean|, |Δ sd|) / mean.
double rendered_difference(Rendering x, double p_mc, double n) {
  const Pixel a = pixel(x.p, n, x.brightness), b = pixel(p_mc, n, 1.0);
  return std::max(std::abs(a.mean - b.mean), std::abs(a.sd - b.sd)) / b.mean;
}

}  // namespace

double rel_error(double got, const Cell& c) { return std::abs(got / c.ref - 1); }

Side side(double err, const Cell& c) {
  const double s = 3 * c.ref_se / c.ref;
  if (err + s <= kTolerance) return Side::kIn;
  if (err - s > kTolerance) return Side::kOut;
  return Side::kUndecided;
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

RenderedDecision rendered_decision(Rendering x, const Cell& c, double lambda) {
  const double p_mc = c.ref / c.d_h, rse = c.ref_se / c.ref;
  const double n = std::max(1.0, lambda / p_mc);
  RenderedDecision d{rendered_difference(x, p_mc, n), INFINITY, 0};
  for (int k = -4; k <= 4; ++k) {
    const double e = rendered_difference(x, p_mc * (1 + 0.75 * k * rse), n);
    d.low = std::min(d.low, e), d.high = std::max(d.high, e);
  }
  return d;
}

bool in_regime(const Cell& c) { return !c.tail && c.c.side >= kRegimeMinSide && c.c.position == 0; }

// Over the cells outside the tail (or the regime's only) and every density of kGlintsPerPixel.
RenderedSummary summarize_rendered(const std::vector<Cell>& cells, CellPixel get, bool regime_only,
                                   std::size_t first_density) {
  RenderedSummary s;
  for (const Cell& c : cells) {
    if (c.tail || (regime_only && !in_regime(c))) continue;
    for (std::size_t k = first_density; k < kGlintsPerPixel.size(); ++k) {
      const RenderedDecision d = rendered_decision(get(c), c, kGlintsPerPixel[k]);
      s.max_by_lambda[k] = std::max(s.max_by_lambda[k], d.at_estimate);
      if (d.at_estimate > s.max)
        s.max = d.at_estimate, s.worst = c.c, s.worst_lambda = kGlintsPerPixel[k];
      if (d.high > kVisualTolerance) ++s.not_in_by_lambda[k];
      if (d.high <= kVisualTolerance)
        ++s.in;
      else if (d.low > kVisualTolerance)
        ++s.out;
      else
        ++s.undecided;
    }
  }
  return s;
}

LobeSummary summarize(const std::vector<Cell>& cells, CellValue get, bool regime_only) {
  LobeSummary s;
  std::vector<double> all;
  std::vector<std::pair<std::string, std::vector<double>>> axes;
  auto add = [&](const std::string& key, double e) {
    for (auto& [k, v] : axes)
      if (k == key) return v.push_back(e);
    axes.push_back({key, {e}});
  };
  for (const Cell& c : cells) {
    if (c.tail || (regime_only && !in_regime(c))) continue;
    const double e = rel_error(get(c), c);
    all.push_back(e);
    if (e > s.max) s.max = e, s.worst = c.c;
    switch (side(e, c)) {
      case Side::kIn:
        ++s.in;
        break;
      case Side::kOut:
        ++s.out;
        break;
      case Side::kUndecided:
        ++s.undecided;
        break;
    }
    add(fmt::format("side {}", c.c.side), e);
    add(fmt::format("√α {}", c.c.sqrt_alpha), e);
    add(fmt::format("θv {}°", c.c.theta_v_deg), e);
    add(c.c.position == 0 ? "mirror" : "overhead", e);
  }
  s.med = median(all);
  for (const auto& [k, v] : axes)
    s.by_axis += fmt::format("{}{} {:.3g}", s.by_axis.empty() ? "" : ", ", k, median(v));
  return s;
}

std::string describe(const Config& c) {
  return fmt::format("side {} √α {} θv {}° {}", c.side, c.sqrt_alpha, c.theta_v_deg,
                     c.position == 0 ? "mirror" : "overhead");
}

Verdict decide(const std::vector<Cell>& cells, CellValue get) {
  return verdict_of(summarize(cells, get), summarize(cells, get, true));
}

// The claim's decision: the rendered difference, by the same rule over (cell, density) pairs.
// first_density > 0 (the probe size): the densities from kGlintsPerPixel[first_density] on.
Verdict decide_rendered(const std::vector<Cell>& cells, CellPixel get, std::size_t first_density) {
  return verdict_of(summarize_rendered(cells, get, false, first_density),
                    summarize_rendered(cells, get, true, first_density));
}

std::string describe_rendered(const RenderedSummary& s) {
  std::string by;
  for (std::size_t k = 0; k < kGlintsPerPixel.size(); ++k)
    by += fmt::format("{}λ {:g}: {:.3g}", k ? ", " : "", kGlintsPerPixel[k], s.max_by_lambda[k]);
  return fmt::format(
      "max {:.3g} at {}, λ {:g}; within {} / beyond {} / undecided {} "
      "(cell, λ) pairs; max by λ: {}",
      s.max, s.in + s.out + s.undecided ? describe(s.worst) : "-", s.worst_lambda, s.in, s.out,
      s.undecided, by);
}

Rendering brdf_pixel(const Cell& c) { return {c.brdf / c.d_h, 1.0}; }
Rendering ndf_pixel(const Cell& c) { return {c.ndf / c.d_h, 1.0}; }
Rendering near_truth_pixel(const Cell& c) { return {c.near_truth / c.d_h, 1.0}; }
Rendering brighter_pixel(const Cell& c) { return {c.brdf / c.d_h, kBrighterRender}; }

FitComparison compare_fits(const std::vector<Cell>& cells) {
  FitComparison f;
  std::vector<double> et, ei, nt, ni, share;
  for (const Cell& c : cells) {
    if (!c.refit || !in_regime(c)) continue;
    ++f.cells;
    const double a = rel_error(c.brdf, c), b = rel_error(c.brdf_indep, c);
    const double na = rel_error(c.ndf, c), nb = rel_error(c.ndf_indep, c);
    et.push_back(a), ei.push_back(b), nt.push_back(na), ni.push_back(nb);
    if (a > 0) share.push_back((a - b) / a);
    f.max_table = std::max(f.max_table, a), f.max_indep = std::max(f.max_indep, b);
    f.ndf_max_table = std::max(f.ndf_max_table, na),
    f.ndf_max_indep = std::max(f.ndf_max_indep, nb);
    f.beyond_table += side(a, c) == Side::kOut, f.beyond_indep += side(b, c) == Side::kOut;
    f.ndf_beyond_table += side(na, c) == Side::kOut,
        f.ndf_beyond_indep += side(nb, c) == Side::kOut;
    const double z =
        std::abs(c.brdf_shape - c.brdf_shape_mc) / std::max(c.brdf_shape_mc_se, 1e-300);
    if (z > f.polygon_max_z)
      f.polygon_max_z = z, f.polygon_worst = c.c, f.polygon_worst_closed = c.brdf_shape,
      f.polygon_worst_mc = c.brdf_shape_mc;
    if (c.brdf_shape_mc > 0)
      f.polygon_max_rel = std::max(f.polygon_max_rel, std::abs(c.brdf_shape / c.brdf_shape_mc - 1));
    f.polygon_beyond += z > 4;
    if (c.brdf_shape_mc > 0 && 1 - c.brdf_shape_above / c.brdf_shape_mc > f.below_horizon_max)
      f.below_horizon_max = 1 - c.brdf_shape_above / c.brdf_shape_mc, f.below_horizon_worst = c.c;
  }
  f.med_table = median(et), f.med_indep = median(ei);
  f.ndf_med_table = median(nt), f.ndf_med_indep = median(ni);
  f.fit_share = median(share);
  return f;
}

std::string describe_summary(const LobeSummary& s) {
  return fmt::format("median {:.3g}, max {:.3g} at {}; within {} / beyond {} / undecided {}", s.med,
                     s.max, s.in + s.out + s.undecided ? describe(s.worst) : "-", s.in, s.out,
                     s.undecided);
}

}  // namespace glintlab::verify::kneiphof_claims::ltc

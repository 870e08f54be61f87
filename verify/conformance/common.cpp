// Settings, queries, cubature and the altered copies of an entry shared by the conformance
// properties.
#include "verify/conformance/common.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>

#include "core/math/rng.h"
#include "core/model_layout.h"
#include "core/samplers/heitz_vndf.h"
#include "verify/check.h"
#include "verify/claims/gof_family.h"
#include "verify/stability/cell_stats.h"
#include "verify/stability/sweep_plan.h"
#include "verify/stats/mean_tests.h"
#include "verify/stats/multiple_testing.h"
#include "verify/stats/sphere_cubature.h"

namespace glintlab::verify::conformance {

using V3 = Vec3<double>;

ModelQuery<double> make_query(const ModelEntry& m, double theta_deg, double footprint) {
  ModelQuery<double> q{};
  q.wi = stability::incidence_at(theta_deg);
  q.wo = {-q.wi.x, -q.wi.y, q.wi.z};
  q.footprint = {{0.5, 0.5}, {footprint, 0}, {0, footprint}};
  const double half_deg = (m.needs & kNeedsAreaLight) ? stability::kDefaultLightHalfAngleDeg : 0.0;
  q.light = {std::cos(half_deg * std::numbers::pi / 180), 1.0};
  if (m.needs & kNeedsPixelCorners)
    q.footprint.corner_r = stability::pixel_corner_reflections(q.wi, footprint);
  return q;
}

std::vector<Setting> settings(const ModelEntry& m, Budget b) {
  const std::vector<double> values = resolve_params(m, {});
  const std::vector<double> thetas =
      b == Budget::kQuick ? std::vector<double>{30, 70} : std::vector<double>{0, 30, 60, 80};
  std::vector<Setting> out;
  for (double t : thetas)
    out.push_back({values, make_query(m, t, kFootprint), t,
                   fmt::format("defaults, θi={:g}°", t)});
  return out;
}

std::vector<Variant> variants(const ModelEntry& m) {
  const std::vector<double> defaults = resolve_params(m, {});
  std::vector<Variant> out;
  for (std::size_t i = 0; i < m.params.size(); ++i) {
    const ParamSpec& p = m.params[i];
    for (std::size_t c = 0; c < p.choices.size(); ++c) {
      if (double(c) == defaults[i]) continue;
      Variant v{defaults, fmt::format("{}={}", p.name, p.choices[c]), ""};
      v.values[i] = double(c);
      v.choice = v.label;
      out.push_back(std::move(v));
    }
  }
  // The roughness: alpha_x with alpha_y (kept isotropic), or alpha.
  std::vector<std::size_t> rough;
  for (std::string_view name : {"alpha_x", "alpha_y"})
    for (std::size_t i = 0; i < m.params.size(); ++i)
      if (m.params[i].name == name && m.params[i].choices.empty()) rough.push_back(i);
  if (rough.empty())
    for (std::size_t i = 0; i < m.params.size(); ++i)
      if (m.params[i].name == "alpha" && m.params[i].choices.empty()) rough.push_back(i);
  if (rough.empty()) return out;
  for (double a : kRoughnessGrid) {
    bool valid = true, all_default = true;
    for (std::size_t i : rough) {
      const ParamSpec& p = m.params[i];
      valid = valid && (p.lo_open ? a > p.lo : a >= p.lo) && (p.hi_open ? a < p.hi : a <= p.hi);
      all_default = all_default && a == defaults[i];
    }
    if (!valid || all_default) continue;
    Variant v{defaults, "", ""};
    for (std::size_t i : rough) {
      v.values[i] = a;
      v.label += fmt::format("{}=", m.params[i].name);
    }
    v.label += fmt::format("{:g}", a);
    out.push_back(std::move(v));
  }
  return out;
}

double variant_share(const ModelEntry& m) {
  const std::size_t n = variants(m).size() * ((m.needs & kNeedsFootprint) ? 2 : 1);
  return n == 0 ? kMaxVariantShare : std::min(kMaxVariantShare, 1.0 / double(n));
}

std::vector<Setting> variant_settings(const ModelEntry& m, Budget b, std::string_view property,
                                      std::string* left_out) {
  const std::vector<double> thetas =
      b == Budget::kQuick ? std::vector<double>{70} : std::vector<double>{30, 70};
  const double share = variant_share(m);
  std::vector<Setting> out;
  for (const Variant& v : variants(m)) {
    const NotClaimed* skip = nullptr;
    for (const NotClaimed& n : m.not_claimed)
      if (!n.choice.empty() && n.property == property && n.choice == v.choice) skip = &n;
    if (skip) {
      if (left_out)
        *left_out += fmt::format("{}{} (not claimed: {})", left_out->empty() ? "" : "; ", v.label,
                                 skip->reason);
      continue;
    }
    for (double t : thetas)
      out.push_back({v.values, make_query(m, t, kFootprint), t,
                     fmt::format("{}, θi={:g}°", v.label, t), share});
  }
  return out;
}

std::string describe_configurations(std::size_t defaults, const std::vector<Setting>& variants,
                                    const std::string& left_out) {
  std::string names;
  std::size_t distinct = 0;
  for (std::size_t k = 0; k < variants.size(); ++k) {
    const std::string name = variants[k].label.substr(0, variants[k].label.rfind(", θi="));
    if (k > 0 && variants[k - 1].label.substr(0, variants[k - 1].label.rfind(", θi=")) == name)
      continue;
    names += fmt::format("{}{}", names.empty() ? "" : ", ", name);
    ++distinct;
  }
  std::string out = fmt::format("{} at the defaults", defaults);
  if (!variants.empty())
    out += fmt::format(" + {} for {} parameter choice(s) ({}) at {:.3g} of the samples",
                       variants.size(), distinct, names, variants.front().share);
  if (!left_out.empty()) out += fmt::format("; not run: {}", left_out);
  return out;
}

std::vector<Setting> compensation_settings(const ModelEntry& m) {
  if (m.name != "kemppinen_ggx" && m.name != "kemppinen_beckmann") return {};
  // Where C dominates ∫ value (the explicit points' share of ∫ value dωo, measured with eval's
  // D_star_explicit / D_star_f on a 360 × 360 grid of ωo, GGX / Beckmann): a footprint of side 1
  // (λ ≈ 6.3: fine angular cells, the lobes spill out of B(k)) at θi = 30° (0.13 / 0.08) and
  // grazing 80° (0.28 / 0.10), and k = 1 (B(k) one angular cell) at side 0.4, θi = 80°
  // (0.17 / 0.07). Small footprints are not among them: at side 0.01 and below λ ≈ 0, the only
  // angular cell is B(k) and C = 0. At the defaults (side 0.1, GGX) C holds 3–5 % of ∫ value.
  // Algorithm 2 alone misses value only at the last (its mean weight 11 % short, GGX): with two
  // cells per axis its lobes' tails still reach where C lies.
  const std::vector<double> defaults = resolve_params(m, {});
  const std::vector<double> one_cell = resolve_params(m, {{"k", "1"}});
  const auto at = [&m](const std::vector<double>& values, double theta_deg, double footprint,
                       std::string_view what) {
    return Setting{values, make_query(m, theta_deg, footprint), theta_deg,
                   fmt::format("{}, θi={:g}°, footprint {:g}", what, theta_deg, footprint)};
  };
  return {at(defaults, 30, 1.0, "defaults"), at(defaults, 80, 1.0, "defaults"),
          at(one_cell, 80, 0.4, "k=1")};
}

double value_at(const ModelEntry& m, const std::vector<double>& values, ModelQuery<double> q,
                const V3& wo) {
  if (!(wo.z > 0)) return 0;
  q.wo = wo;
  if (m.validate && m.validate(q)) return 0;
  return m.eval(values, q).value;
}

void values_at(const ModelEntry& m, const std::vector<double>& values, const ModelQuery<double>& q,
               std::span<const V3> wo, std::span<double> out) {
  std::vector<double> pdf(wo.size());
  values_and_pdfs_at(m, values, q, wo, out, pdf);
}

void values_and_pdfs_at(const ModelEntry& m, const std::vector<double>& values,
                        const ModelQuery<double>& q, std::span<const V3> wo,
                        std::span<double> out, std::span<double> pdf) {
  std::vector<ModelQuery<double>> asked;
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < wo.size(); ++i) {
    out[i] = 0;
    pdf[i] = 0;
    if (!(wo[i].z > 0)) continue;
    ModelQuery<double> at = q;
    at.wo = wo[i];
    if (m.validate && m.validate(at)) continue;
    asked.push_back(at);
    rows.push_back(i);
  }
  std::vector<ErasedEval> e(asked.size());
  eval_each(m, values, asked, e);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    out[rows[k]] = e[k].value;
    pdf[rows[k]] = e[k].pdf;
  }
}

double roughness_hint(const ModelEntry& m, const std::vector<double>& values) {
  for (std::string_view name : {"alpha_x", "alpha"})
    for (std::size_t i = 0; i < m.params.size(); ++i)
      if (m.params[i].name == name && m.params[i].choices.empty()) return values[i];
  return 0.3;
}

namespace {

// The mirror direction of ωi and a frame (t, s, r) about it, where glossy lobes and glints sit.
struct MirrorFrame {
  V3 t, s, r;
  V3 to_world(const V3& w) const { return t * w.x + s * w.y + r * w.z; }
};
MirrorFrame mirror_frame(const V3& wi) {
  const V3 r = normalize(V3{-wi.x, -wi.y, std::max(wi.z, 1e-6)});
  const V3 helper = std::abs(r.z) < 0.9 ? V3{0, 0, 1} : V3{1, 0, 0};
  const V3 t = normalize(cross(helper, r));
  return {t, cross(r, t), r};
}

// The proposal of the Monte Carlo hemisphere integral: a fixed mixture, chosen without the
// model's sampler (the integral is the truth that sampler is tested against), of
//   - the uniform upper hemisphere (defensive: every direction with ωo_z > 0 has density, so the
//     estimate is unbiased for any integrand),
//   - Heitz 2018's GGX VNDF reflection of ωi (core/samplers/heitz_vndf.h, checked by the smooth
//     models' own conformance) at the roughness width, where a lobe's mass lies, and
//   - two caps about the mirror direction of half-angles 8 and 32 × the width (capped at π), for
//     values wider than that lobe or offset from it.
// Sample i takes component i mod 4, so each holds exactly a quarter of the samples (multi-sample
// MIS, balance heuristic: weight f / Σ_k ¼ p_k, unbiased; the iid variance bounds this
// estimator's). A uniform proposal alone put one direction in thousands into a narrow lobe: 6 %
// relative standard error at 10^5 samples for podee's highlight.
struct MirrorMixture {
  static constexpr std::size_t kComponents = 4;
  static constexpr std::array<double, 2> kCapFactors = {8, 32};
  MirrorFrame frame;
  V3 wi;
  GGX<double> lobe;
  std::array<double, 2> cap_cos{};

  MirrorMixture(const V3& incident, double width)
      : frame(mirror_frame(incident)),
        wi(incident),
        lobe{std::clamp(width, 1e-3, 1.0), std::clamp(width, 1e-3, 1.0)} {
    for (std::size_t k = 0; k < cap_cos.size(); ++k)
      cap_cos[k] = std::cos(std::min(kCapFactors[k] * lobe.alpha_x, std::numbers::pi));
  }
  V3 direction(std::uint64_t i, Vec2<double> u) const {
    const double phi = 2 * std::numbers::pi * u.y;
    const std::size_t k = std::size_t(i % kComponents);
    if (k == 0) {  // uniform upper hemisphere
      const double r = std::sqrt(std::max(0.0, 1 - u.x * u.x));
      return {r * std::cos(phi), r * std::sin(phi), u.x};
    }
    if (k == 1) return sample_heitz_vndf(lobe, wi, u).wo;
    const double z = 1 - u.x * (1 - cap_cos[k - 2]);
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    return normalize(frame.to_world(V3{r * std::cos(phi), r * std::sin(phi), z}));
  }
  double density(const V3& w) const {
    double q = w.z > 0 ? 1 / (2 * std::numbers::pi) : 0.0;
    q += pdf_heitz_vndf(lobe, wi, w);
    const double c = dot(w, frame.r);
    for (double cap : cap_cos)
      if (c >= cap) q += 1 / (2 * std::numbers::pi * (1 - cap));
    return q / double(kComponents);
  }
};

}  // namespace

Cubature integrate_about_mirror(const std::function<double(const V3&)>& f, const V3& wi,
                                double width, Budget b) {
  // Frame with its pole at the mirror direction r = (−wi_x, −wi_y, wi_z).
  const MirrorFrame frame = mirror_frame(wi);
  auto to_world = [&frame](const V3& w) { return frame.to_world(w); };
  const V3 up{0, 0, 1};
  const V3 up_local{dot(up, frame.t), dot(up, frame.s), dot(up, frame.r)};
  SphereCubatureOptions o;
  o.theta_breaks = lobe_theta_breaks(std::clamp(width, 1e-3, 1.0), 0, std::numbers::pi);
  o.theta_breaks_at_phi = [up_local](double phi, std::vector<double>& breaks) {
    breaks.push_back(plane_crossing_theta(up_local, phi));  // the horizon
  };
  o.rel_tol = cubature_rel_tol(b);
  o.max_depth = b == Budget::kQuick ? 10 : 16;
  const Integral i = integrate_sphere([&](const V3& w) { return f(to_world(w)); }, o);
  return {i.value, i.error};
}

Cubature integrate_about_mirror(const DirectionRows& f, const V3& wi, double width, Budget b) {
  // integrate_about_mirror's frame and options, with f asked for many directions at once.
  const MirrorFrame frame = mirror_frame(wi);
  const V3 up{0, 0, 1};
  const V3 up_local{dot(up, frame.t), dot(up, frame.s), dot(up, frame.r)};
  SphereCubatureOptions o;
  o.theta_breaks = lobe_theta_breaks(std::clamp(width, 1e-3, 1.0), 0, std::numbers::pi);
  o.theta_breaks_at_phi = [up_local](double phi, std::vector<double>& breaks) {
    breaks.push_back(plane_crossing_theta(up_local, phi));  // the horizon
  };
  o.rel_tol = cubature_rel_tol(b);
  o.max_depth = b == Budget::kQuick ? 10 : 16;
  std::vector<V3> world;
  const Integral i = integrate_sphere_rows(
      [&](std::span<const V3> w, std::span<double> out) {
        world.resize(w.size());
        for (std::size_t k = 0; k < w.size(); ++k) world[k] = frame.to_world(w[k]);
        f(world, out);
      },
      o);
  return {i.value, i.error};
}

Vec2<double> pair_at(std::uint64_t seed, std::uint64_t i) { return uniform_pair(seed, i); }

std::uint64_t reference_block(Budget b) { return b == Budget::kQuick ? 100'000 : 2'000'000; }

HemisphereIntegral integrate_hemisphere(const ModelEntry& m, const DirectionRows& f, const V3& wi,
                                        double width, Budget b, std::uint64_t seed, double share) {
  if (!(m.needs & kNeedsFootprint) && !m.eval_rows && !m.pdf_rows) {
    // One direction at a time (the lockstep below holds every inner integral of a step at once).
    const Cubature c = integrate_about_mirror(
        [&](const V3& w) {
          double y = 0;
          if (w.z > 0) f(std::span<const V3>(&w, 1), std::span<double>(&y, 1));
          return y;
        },
        wi, width, b);
    return {c.value, c.error, false};
  }
  if (!(m.needs & kNeedsFootprint)) {
    // An entry with rows functions: f above the horizon for a round's directions at once, 0 below.
    std::vector<V3> above;
    std::vector<double> f_above;
    const Cubature c = integrate_about_mirror(
        [&](std::span<const V3> w, std::span<double> out) {
          above.clear();
          for (const V3& d : w)
            if (d.z > 0) above.push_back(d);
          f_above.assign(above.size(), 0.0);
          f(above, f_above);
          std::size_t next = 0;
          for (std::size_t k = 0; k < w.size(); ++k) out[k] = w[k].z > 0 ? f_above[next++] : 0.0;
        },
        wi, width, b);
    return {c.value, c.error, false};
  }
  const MirrorMixture proposal(wi, width);
  const std::uint64_t block =
      std::max<std::uint64_t>(1, std::uint64_t(share * double(reference_block(b))));
  // accumulate_mean's fixed chunks, merged in chunk order, with f asked for each chunk's
  // directions above the horizon at once.
  auto estimate = [&](std::uint64_t first, std::uint64_t n) {
    std::vector<MeanAccumulator> parts(chunk_count(n));
    for_chunks(n, [&](std::uint64_t begin, std::uint64_t end, std::size_t c) {
      std::vector<V3> directions(end - begin), above;
      for (std::uint64_t i = begin; i < end; ++i) {
        const V3 w = proposal.direction(first + i, uniform_pair(seed, first + i));
        directions[i - begin] = w;
        if (w.z > 0) above.push_back(w);
      }
      std::vector<double> f_above(above.size());
      f(above, f_above);
      std::size_t next = 0;
      for (const V3& w : directions)  // density ≥ 1/8π above the horizon
        parts[c].add(w.z > 0 ? f_above[next++] / proposal.density(w) : 0.0);
    });
    MeanAccumulator total;
    for (const MeanAccumulator& a : parts) total.merge(a);
    return total;
  };
  // The pilot: one block of indices past the largest estimate's, discarded after it sets the
  // block count (so the count does not depend on the estimate's own draws, which would bias it).
  const MeanAccumulator pilot = estimate(kMaxReferenceBlocks * block, block);
  const double pilot_rel =
      pilot.mean != 0 ? std::sqrt(pilot.variance() / double(block)) / std::abs(pilot.mean) : 0.0;
  const double wanted = std::ceil(std::pow(pilot_rel / kReferenceRelativeError, 2));
  const std::uint64_t blocks =
      std::uint64_t(std::clamp(std::isfinite(wanted) ? wanted : 1e9, 1.0, double(kMaxReferenceBlocks)));
  const std::uint64_t n = blocks * block;
  const MeanAccumulator acc = estimate(0, n);
  return {acc.mean, std::sqrt(acc.variance() / double(n)), true};
}

bool is_registered(const ModelEntry& m) {
  const std::vector<ModelEntry>& all = registered_models();
  return !all.empty() && &m >= all.data() && &m < all.data() + all.size();
}

namespace {

// What identifies a setting's integral: the entry, the budget, the label, the parameter values and
// every query column (the label names the setting, the rest guards against two settings sharing
// one).
struct ValueIntegralKey {
  const ModelEntry* model;
  int budget;
  double share;
  std::string label;
  std::vector<double> values;
  std::vector<double> query;
  auto operator<=>(const ValueIntegralKey&) const = default;
};

std::vector<double> query_columns(const ModelQuery<double>& q) {
  std::vector<double> c;
  for_each_query_column(q, [&c](std::size_t, const QueryColumn&, const double& v) { c.push_back(v); });
  return c;
}

}  // namespace

HemisphereIntegral value_integral(const ModelEntry& m, const Setting& s, Budget b) {
  const auto integrate = [&] {
    return integrate_hemisphere(
        m,
        [&](std::span<const V3> wo, std::span<double> out) {
          values_at(m, s.values, s.query, wo, out);
        },
        s.query.wi, roughness_hint(m, s.values), b,
        check_seed(fmt::format("model.{}.value-integral.{}", m.name, s.label), 0), s.share);
  };
  if (!is_registered(m)) return integrate();
  static std::mutex mutex;
  static std::map<ValueIntegralKey, HemisphereIntegral> kept;
  const ValueIntegralKey key{&m, int(b), s.share, s.label, s.values, query_columns(s.query)};
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (auto it = kept.find(key); it != kept.end()) return it->second;
  }
  // Computed outside the lock (it runs its own parallel loop); two threads asking at once both
  // compute the same deterministic value.
  const HemisphereIntegral h = integrate();
  const std::lock_guard<std::mutex> lock(mutex);
  kept.emplace(key, h);
  return h;
}

HemisphereIntegral integrate_hemisphere(const ModelEntry& m, const std::function<double(const V3&)>& f,
                                        const V3& wi, double width, Budget b, std::uint64_t seed) {
  return integrate_hemisphere(
      m,
      [&f](std::span<const V3> w, std::span<double> out) {
        for (std::size_t i = 0; i < w.size(); ++i) out[i] = f(w[i]);
      },
      wi, width, b, seed);
}

MirrorCells::MirrorCells(const V3& wi, double width) {
  const MirrorFrame f = mirror_frame(wi);
  t = f.t;
  s = f.s;
  r = f.r;
  const double w = std::clamp(width, 1e-3, 1.0);
  const std::array<double, 3> factors = {2, 8, 32};
  for (std::size_t k = 0; k < ring_cos.size(); ++k)
    ring_cos[k] = std::cos(std::min(factors[k] * w, std::numbers::pi));
}

std::size_t MirrorCells::cell(const V3& w) const {
  const double c = dot(w, r);
  std::size_t ring = 0;
  while (ring < ring_cos.size() && c < ring_cos[ring]) ++ring;
  const double phi = std::atan2(dot(w, s), dot(w, t)) + std::numbers::pi;  // [0, 2π]
  const std::size_t sector = std::min<std::size_t>(3, std::size_t(phi / (std::numbers::pi / 2)));
  return ring * 4 + sector;
}

CellSums integrate_cells(const DirectionRows& f, const V3& wi, double width, std::uint64_t n,
                         std::uint64_t seed) {
  return integrate_cell_pair(
             [&f](std::span<const V3> w, std::span<double> first, std::span<double> second) {
               f(w, first);
               std::fill(second.begin(), second.end(), 0.0);
             },
             wi, width, n, seed)
      .first;
}

CellSumPair integrate_cell_pair(const DirectionRowPairs& fg, const V3& wi, double width,
                                std::uint64_t n, std::uint64_t seed) {
  const MirrorMixture proposal(wi, width);
  const MirrorCells cells(wi, width);
  std::vector<CellSumPair> parts(chunk_count(n));
  for_chunks(n, [&](std::uint64_t begin, std::uint64_t end, std::size_t c) {
    CellSumPair& p = parts[c];
    std::vector<V3> directions(end - begin), above;
    for (std::uint64_t i = begin; i < end; ++i) {
      const V3 w = proposal.direction(i, uniform_pair(seed, i));
      directions[i - begin] = w;
      if (w.z > 0) above.push_back(w);
    }
    std::vector<double> f_above(above.size()), g_above(above.size());
    fg(above, f_above, g_above);
    auto add = [&cells](CellSums& sums, const V3& w, double y) {
      if (y == 0) return;
      const std::size_t k = cells.cell(w);
      sums.sum[k] += y;
      sums.sum_sq[k] += y * y;
      ++sums.hits[k];
    };
    std::size_t next = 0;
    for (const V3& w : directions) {
      if (!(w.z > 0)) continue;
      const double density = proposal.density(w);  // ≥ 1/8π above the horizon
      add(p.first, w, f_above[next] / density);
      add(p.second, w, g_above[next] / density);
      ++next;
    }
  });
  CellSumPair all;
  all.first.n = all.second.n = n;
  for (const CellSumPair& p : parts)
    for (std::size_t k = 0; k < MirrorCells::kCount; ++k) {
      all.first.sum[k] += p.first.sum[k];
      all.first.sum_sq[k] += p.first.sum_sq[k];
      all.first.hits[k] += p.first.hits[k];
      all.second.sum[k] += p.second.sum[k];
      all.second.sum_sq[k] += p.second.sum_sq[k];
      all.second.hits[k] += p.second.hits[k];
    }
  return all;
}

FamilyOutcome family_at(const std::vector<double>& raw_p, double level) {
  FamilyOutcome f;
  if (raw_p.empty()) return f;
  const HolmSidakResult h = holm_sidak(raw_p, level);
  f.any_rejected = h.rejections > 0;
  f.rejections = h.rejections;
  f.reject = h.reject;
  f.min_adjusted = *std::min_element(h.adjusted.begin(), h.adjusted.end());
  return f;
}

namespace {
constexpr std::uint64_t kChunk = 4096;
}

std::size_t chunk_count(std::uint64_t n) { return std::size_t((n + kChunk - 1) / kChunk); }

void for_chunks(std::uint64_t n,
                const std::function<void(std::uint64_t, std::uint64_t, std::size_t)>& f) {
  tbb::parallel_for(std::size_t(0), chunk_count(n), [&](std::size_t c) {
    const std::uint64_t begin = c * kChunk, end = std::min<std::uint64_t>(n, begin + kChunk);
    f(begin, end, c);
  });
}

// ---- Altered copies ------------------------------------------------------------------------------

ModelEntry with_pdf_scaled(const ModelEntry& m, double scale) {
  ModelEntry e = m;
  e.pdf = ScaledPdf{m.pdf, scale, is_registered(m) ? &m : nullptr};
  if (m.pdf_float)
    e.pdf_float = [f = m.pdf_float, scale](const std::vector<double>& v,
                                           const ModelQuery<double>& q) { return scale * f(v, q); };
  if (m.pdf_rows)
    e.pdf_rows = [f = m.pdf_rows, scale](const std::vector<double>& v,
                                         std::span<const ModelQuery<double>> qs,
                                         std::span<double> out) {
      f(v, qs, out);
      for (double& x : out) x = scale * x;
    };
  return e;
}

ModelEntry with_value_scaled(const ModelEntry& m, double scale) {
  ModelEntry e = m;
  e.eval = [f = m.eval, scale](const std::vector<double>& v, const ModelQuery<double>& q) {
    ErasedEval r = f(v, q);
    r.value *= scale;
    return r;
  };
  if (m.eval_float)
    e.eval_float = [f = m.eval_float, scale](const std::vector<double>& v,
                                             const ModelQuery<double>& q) {
      ErasedEval r = f(v, q);
      r.value *= scale;
      return r;
    };
  if (m.eval_rows)
    e.eval_rows = [f = m.eval_rows, scale](const std::vector<double>& v,
                                           std::span<const ModelQuery<double>> qs,
                                           std::span<ErasedEval> out) {
      f(v, qs, out);
      for (ErasedEval& r : out) r.value *= scale;
    };
  return with_weight_scaled(e, scale);
}

ModelEntry with_weight_scaled(const ModelEntry& m, double scale) {
  ModelEntry e = m;
  e.sample = [f = m.sample, scale](const std::vector<double>& v, const ModelQuery<double>& q,
                                   Vec2<double> u) {
    ModelSample<double> s = f(v, q, u);
    s.weight *= scale;
    return s;
  };
  if (m.sample_rows)
    e.sample_rows = [f = m.sample_rows, scale](const std::vector<double>& v,
                                               const ModelQuery<double>& q,
                                               std::span<const Vec2<double>> u,
                                               std::span<ModelSample<double>> out) {
      f(v, q, u, out);
      for (ModelSample<double>& s : out) s.weight *= scale;
    };
  return e;
}

ModelEntry with_sampler_restricted(const ModelEntry& m, double share) {
  ModelEntry e = m;
  auto restrict = [share](Vec2<double> u, ModelSample<double>& s) {
    std::uint64_t bx, by;
    std::memcpy(&bx, &u.x, sizeof bx);
    std::memcpy(&by, &u.y, sizeof by);
    if (double(mix64(mix64(bx) ^ by) >> 11) * 0x1p-53 < share) {
      s.weight = 0;
      s.rejected = true;
    }
  };
  e.sample = [f = m.sample, restrict](const std::vector<double>& v, const ModelQuery<double>& q,
                                      Vec2<double> u) {
    ModelSample<double> s = f(v, q, u);
    restrict(u, s);
    return s;
  };
  if (m.sample_rows)
    e.sample_rows = [f = m.sample_rows, restrict](const std::vector<double>& v,
                                                  const ModelQuery<double>& q,
                                                  std::span<const Vec2<double>> u,
                                                  std::span<ModelSample<double>> out) {
      f(v, q, u, out);
      for (std::size_t i = 0; i < u.size(); ++i) restrict(u[i], out[i]);
    };
  return e;
}

ModelEntry with_sparse_nan(const ModelEntry& m, double rate) {
  ModelEntry e = m;
  auto broken = [rate](const ModelQuery<double>& q) {
    std::uint64_t h = 0;
    for (double x : {q.wi.x, q.wi.y, q.wi.z, q.wo.x, q.wo.y, q.wo.z, q.footprint.uv.x}) {
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      h = mix64(h ^ bits);
    }
    return double(h >> 11) * 0x1p-53 < rate;
  };
  e.eval = [f = m.eval, broken](const std::vector<double>& v, const ModelQuery<double>& q) {
    ErasedEval r = f(v, q);
    if (broken(q)) r.value = std::numeric_limits<double>::quiet_NaN();
    return r;
  };
  if (m.eval_float)
    e.eval_float = [f = m.eval_float, broken](const std::vector<double>& v,
                                              const ModelQuery<double>& q) {
      ErasedEval r = f(v, q);
      if (broken(q)) r.value = std::numeric_limits<double>::quiet_NaN();
      return r;
    };
  if (m.eval_rows)
    e.eval_rows = [f = m.eval_rows, broken](const std::vector<double>& v,
                                            std::span<const ModelQuery<double>> qs,
                                            std::span<ErasedEval> out) {
      f(v, qs, out);
      for (std::size_t i = 0; i < qs.size(); ++i)
        if (broken(qs[i])) out[i].value = std::numeric_limits<double>::quiet_NaN();
    };
  return e;
}

ModelEntry with_uniform_sampler(const ModelEntry& m) {
  ModelEntry e = m;
  constexpr double kPdf = 1 / (4 * std::numbers::pi);
  e.pdf = [](const std::vector<double>&, const ModelQuery<double>&) { return kPdf; };
  e.eval = [f = m.eval](const std::vector<double>& v, const ModelQuery<double>& q) {
    ErasedEval r = f(v, q);
    r.pdf = kPdf;
    return r;
  };
  auto uniform = [](Vec2<double> u) {
    const double z = 1 - 2 * u.x, r = std::sqrt(std::max(0.0, 1 - z * z));
    const double phi = 2 * std::numbers::pi * u.y;
    return V3{r * std::cos(phi), r * std::sin(phi), z};
  };
  e.sample = [m, uniform](const std::vector<double>& v, const ModelQuery<double>& q,
                          Vec2<double> u) {
    const V3 wo = uniform(u);
    const bool below = !(wo.z > 0);
    const double value = below ? 0.0 : value_at(m, v, q, wo);
    return ModelSample<double>{wo, kPdf, value / kPdf, below};
  };
  e.eval_rows = {};
  e.pdf_rows = {};
  e.sample_rows = {};
  if (m.eval_rows) {
    e.eval_rows = [f = m.eval_rows](const std::vector<double>& v,
                                    std::span<const ModelQuery<double>> qs,
                                    std::span<ErasedEval> out) {
      f(v, qs, out);
      for (ErasedEval& r : out) r.pdf = kPdf;
    };
    // value_at is 0 below the horizon, as the per-row sampler's value there.
    e.sample_rows = [m, uniform](const std::vector<double>& v, const ModelQuery<double>& q,
                                 std::span<const Vec2<double>> u,
                                 std::span<ModelSample<double>> out) {
      std::vector<V3> wo(u.size());
      for (std::size_t i = 0; i < u.size(); ++i) wo[i] = uniform(u[i]);
      std::vector<double> value(u.size());
      values_at(m, v, q, wo, value);
      for (std::size_t i = 0; i < u.size(); ++i)
        out[i] = ModelSample<double>{wo[i], kPdf, value[i] / kPdf, !(wo[i].z > 0)};
    };
  }
  e.eval_float = {};
  e.pdf_float = {};
  e.sample_float = {};
  e.static_model = nullptr;
  return e;
}

ModelEntry with_consistent_sample(const ModelEntry& m) {
  ModelEntry e = m;
  e.eval = [m](const std::vector<double>& v, const ModelQuery<double>& q) {
    ErasedEval r = m.eval(v, q);
    r.pdf = m.pdf(v, q);
    return r;
  };
  e.sample = [m](const std::vector<double>& v, const ModelQuery<double>& q, Vec2<double> u) {
    ModelSample<double> s = m.sample(v, q, u);
    ModelQuery<double> at = q;
    at.wo = s.wo;
    s.pdf = m.pdf(v, at);
    s.weight = s.rejected || !(s.pdf > 0) ? 0.0 : m.eval(v, at).value / s.pdf;
    return s;
  };
  e.eval_rows = {};
  e.sample_rows = {};
  if (m.eval_rows)
    e.eval_rows = [m](const std::vector<double>& v, std::span<const ModelQuery<double>> qs,
                      std::span<ErasedEval> out) {
      eval_each(m, v, qs, out);
      std::vector<double> pdf(qs.size());
      pdf_each(m, v, qs, pdf);
      for (std::size_t i = 0; i < qs.size(); ++i) out[i].pdf = pdf[i];
    };
  if (m.sample_rows)
    e.sample_rows = [m](const std::vector<double>& v, const ModelQuery<double>& q,
                        std::span<const Vec2<double>> u, std::span<ModelSample<double>> out) {
      sample_each(m, v, q, u, out);
      std::vector<ModelQuery<double>> at(u.size(), q);
      for (std::size_t i = 0; i < u.size(); ++i) at[i].wo = out[i].wo;
      std::vector<double> pdf(u.size());
      pdf_each(m, v, at, pdf);
      std::vector<ModelQuery<double>> weighed;
      for (std::size_t i = 0; i < u.size(); ++i) {
        out[i].pdf = pdf[i];
        if (!out[i].rejected && pdf[i] > 0) weighed.push_back(at[i]);
      }
      std::vector<ErasedEval> value(weighed.size());
      eval_each(m, v, weighed, value);
      std::size_t next = 0;
      for (ModelSample<double>& s : out)
        s.weight = s.rejected || !(s.pdf > 0) ? 0.0 : value[next++].value / s.pdf;
    };
  return e;
}

ModelEntry with_float_as_double(const ModelEntry& m) {
  ModelEntry e = m;
  e.eval_float = m.eval;
  e.pdf_float = m.pdf;
  e.sample_float = m.sample;
  return e;
}

ModelEntry with_outputs_sanitized(const ModelEntry& m) {
  auto clean = [](double x) { return std::isfinite(x) && x > 0 ? x : 0.0; };
  auto clean_eval = [clean](ErasedEval r) {
    r.value = clean(r.value);
    r.pdf = clean(r.pdf);
    for (double& x : r.intermediates) x = std::isfinite(x) ? x : 0.0;
    return r;
  };
  auto clean_sample = [clean](ModelSample<double> s) {
    s.pdf = clean(s.pdf);
    s.weight = clean(s.weight);
    if (!(std::isfinite(s.wo.x) && std::isfinite(s.wo.y) && std::isfinite(s.wo.z))) {
      s.wo = {0, 0, 0};
      s.rejected = true;
    }
    return s;
  };
  ModelEntry e = m;
  e.eval = [f = m.eval, clean_eval](const std::vector<double>& v, const ModelQuery<double>& q) {
    return clean_eval(f(v, q));
  };
  e.pdf = [f = m.pdf, clean](const std::vector<double>& v, const ModelQuery<double>& q) {
    return clean(f(v, q));
  };
  e.sample = [f = m.sample, clean_sample](const std::vector<double>& v,
                                          const ModelQuery<double>& q,
                                          Vec2<double> u) { return clean_sample(f(v, q, u)); };
  if (m.eval_float) {
    e.eval_float = [f = m.eval_float, clean_eval](const std::vector<double>& v,
                                                  const ModelQuery<double>& q) {
      return clean_eval(f(v, q));
    };
    e.pdf_float = [f = m.pdf_float, clean](const std::vector<double>& v,
                                           const ModelQuery<double>& q) { return clean(f(v, q)); };
    e.sample_float = [f = m.sample_float, clean_sample](const std::vector<double>& v,
                                                        const ModelQuery<double>& q,
                                                        Vec2<double> u) {
      return clean_sample(f(v, q, u));
    };
  }
  if (m.eval_rows)
    e.eval_rows = [f = m.eval_rows, clean_eval](const std::vector<double>& v,
                                                std::span<const ModelQuery<double>> qs,
                                                std::span<ErasedEval> out) {
      f(v, qs, out);
      for (ErasedEval& r : out) r = clean_eval(std::move(r));
    };
  if (m.pdf_rows)
    e.pdf_rows = [f = m.pdf_rows, clean](const std::vector<double>& v,
                                         std::span<const ModelQuery<double>> qs,
                                         std::span<double> out) {
      f(v, qs, out);
      for (double& x : out) x = clean(x);
    };
  if (m.sample_rows)
    e.sample_rows = [f = m.sample_rows, clean_sample](const std::vector<double>& v,
                                                      const ModelQuery<double>& q,
                                                      std::span<const Vec2<double>> u,
                                                      std::span<ModelSample<double>> out) {
      f(v, q, u, out);
      for (ModelSample<double>& s : out) s = clean_sample(s);
    };
  return e;
}

ModelEntry with_cost_per_area(const ModelEntry& m, double base_side, int max_parts) {
  ModelEntry e = m;
  e.eval = [f = m.eval, base_side, max_parts](const std::vector<double>& v,
                                              const ModelQuery<double>& q) {
    const double side = std::max(std::hypot(q.footprint.duv_dx.x, q.footprint.duv_dx.y),
                                 std::hypot(q.footprint.duv_dy.x, q.footprint.duv_dy.y));
    // One part up to 1.5 × the base side (the small footprint of the timing), max_parts per axis
    // beyond.
    const int k = side <= 1.5 * base_side ? 1 : max_parts;
    ErasedEval sum = f(v, q);
    for (int i = 1; i < k * k; ++i) {
      ModelQuery<double> sub = q;
      sub.footprint.uv =
          q.footprint.uv + side * Vec2<double>{double(i % k) / k - 0.5, double(i / k) / k - 0.5};
      const ErasedEval r = f(v, sub);
      sum.value += r.value;
    }
    sum.value /= double(k * k);
    return sum;
  };
  e.eval_rows = {};  // the cost is what this control is about: one query per call
  return e;
}

ModelEntry with_footprint_clamped(const ModelEntry& m, double side) {
  ModelEntry e = m;
  e.eval = [f = m.eval, side](const std::vector<double>& v, const ModelQuery<double>& q) {
    ModelQuery<double> c = q;
    c.footprint.duv_dx = {side, 0};
    c.footprint.duv_dy = {0, side};
    return f(v, c);
  };
  e.eval_rows = {};  // the cost is what this control is about: one query per call
  return e;
}

}  // namespace glintlab::verify::conformance

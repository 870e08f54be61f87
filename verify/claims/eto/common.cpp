// What Eto & Tokuyoshi's claims share (common.h).
#include "verify/claims/eto/common.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "core/math/rng.h"
#include "core/model_layout.h"
#include "core/model_registry.h"
#include "core/models/smooth_ggx.h"
#include "core/simd/model_batch.h"
#include "verify/stats/ndf_cubature.h"

namespace glintlab::verify::eto_claims {

using V3 = Vec3<double>;

namespace {
constexpr double kPhiI = 0.7;  // azimuth of ωi
}

V3 incidence(double theta_deg) {
  const double t = theta_deg * std::numbers::pi / 180;
  return {std::sin(t) * std::cos(kPhiI), std::sin(t) * std::sin(kPhiI), std::cos(t)};
}

V3 direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

std::string describe_config(const Config& c) {
  return fmt::format("αx={:g} αy={:g} θi={:g}°", c.ax, c.ay, c.theta_deg);
}

std::vector<Config> grid_of(const std::vector<double>& alphas, const std::vector<double>& ratios,
                            const std::vector<double>& thetas) {
  std::vector<Config> g;
  for (double a : alphas)
    for (double r : ratios)
      for (double t : thetas) g.push_back({a, a / r, t});
  return g;
}

std::vector<Config> estimator_grid(Budget b) {
  const bool quick = b == Budget::kQuick;
  const std::vector<double> alphas =
      quick ? std::vector<double>{0.05, 0.2, 0.5, 0.8, 1.0}
            : std::vector<double>{0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
  const std::vector<double> ratios =
      quick ? std::vector<double>{1, 4} : std::vector<double>{1, 2, 4, 10};  // αx / αy
  const std::vector<double> thetas =
      quick ? std::vector<double>{0, 45, 80} : std::vector<double>{0, 20, 40, 60, 75, 85, 89};
  return grid_of(alphas, ratios, thetas);
}

std::string_view to_string(Technique t) { return SmoothGGX::Choices::kRows[int(t)].choice; }

MicrofacetSample<double> draw(Technique t, const Config& c, std::uint64_t seed, std::uint64_t i) {
  const Vec2<double> u{counter_uniform<double>(seed, i, 0), counter_uniform<double>(seed, i, 1)};
  const V3 wi = incidence(c.theta_deg);
  return samplers::with<SmoothGGX::Samplers>(int(t),
                                             [&]<class S>() { return S::sample(c.ggx(), wi, u); });
}

double weight(Technique t, const Config& c, std::uint64_t seed, std::uint64_t i) {
  return sample_weight(c.ggx(), incidence(c.theta_deg), draw(t, c, seed, i));
}

void draw_batch(Technique t, const Config& c, std::uint64_t seed, std::uint64_t first,
                std::size_t count, double* weight, double* rejected) {
  static const ModelEntry& model = find_model("smooth_ggx");
  std::vector<double> values;
  for (const ParamSpec& p : model.params) {
    const std::string_view n = p.name;
    values.push_back(n == "alpha_x"   ? c.ax
                     : n == "alpha_y" ? c.ay
                     : n == "sampler" ? double(SmoothGGX::Choices::choice_of(int(t)))
                     : n == "bound"   ? double(SmoothGGX::Choices::bound_of(int(t)))
                                      : p.default_value);
  }
  // Every query column one value for every row (stride 0): the defaults, ω_i of the configuration.
  std::array<double, simd::kQueryColumns.size()> query = simd::kQueryDefaults;
  const V3 wi = incidence(c.theta_deg);
  query[query_column_index("wi_x")] = wi.x;
  query[query_column_index("wi_y")] = wi.y;
  query[query_column_index("wi_z")] = wi.z;
  std::array<simd::Column<double>, simd::kQueryColumns.size()> columns;
  for (std::size_t k = 0; k < columns.size(); ++k) columns[k] = {&query[k], 0};
  std::vector<double> u1(count), u2(count), out(simd::kSampleColumns.size() * count);
  for (std::size_t j = 0; j < count; ++j) {
    u1[j] = counter_uniform<double>(seed, first + j, 0);
    u2[j] = counter_uniform<double>(seed, first + j, 1);
  }
  std::array<double*, simd::kSampleColumns.size()> outputs;
  for (std::size_t k = 0; k < outputs.size(); ++k) outputs[k] = out.data() + k * count;
  simd::sample_batch(model, values, columns, {u1.data(), 1}, {u2.data(), 1}, outputs, count,
                     simd::default_isa());
  static_assert(simd::kSampleColumns[4] == "weight" && simd::kSampleColumns[5] == "rejected");
  std::copy_n(outputs[4], count, weight);
  std::copy_n(outputs[5], count, rejected);
}

namespace {

// f(chunk, weights, rejected, count) for every chunk of samples 0 … n − 1, in parallel.
template <class PerChunk>
void for_each_chunk(Technique t, const Config& c, std::uint64_t seed, std::uint64_t n,
                    PerChunk&& per_chunk) {
  const std::uint64_t chunks = (n + kBatchChunk - 1) / kBatchChunk;
  tbb::parallel_for(std::uint64_t(0), chunks, [&](std::uint64_t ch) {
    const std::size_t count = std::size_t(std::min(n, (ch + 1) * kBatchChunk) - ch * kBatchChunk);
    std::vector<double> w(count), rejected(count);
    draw_batch(t, c, seed, ch * kBatchChunk, count, w.data(), rejected.data());
    per_chunk(ch, w, rejected);
  });
}

}  // namespace

MeanAccumulator accumulate_weights(Technique t, const Config& c, std::uint64_t seed,
                                   std::uint64_t n, int power) {
  const std::uint64_t chunks = (n + kBatchChunk - 1) / kBatchChunk;
  std::vector<MeanAccumulator> parts(chunks);
  // Each chunk's sum is one serial chain of divisions (Welford); one task takes kChunksPerTask
  // chunks and feeds their accumulators in turn, so the chains overlap. Every accumulator still
  // gets its own chunk's values in order: the same sums, bit for bit, as one chunk per task.
  const std::uint64_t tasks = (chunks + kChunksPerTask - 1) / kChunksPerTask;
  tbb::parallel_for(std::uint64_t(0), tasks, [&](std::uint64_t task) {
    const std::uint64_t first = task * kChunksPerTask;
    const std::size_t group = std::size_t(std::min(chunks, first + kChunksPerTask) - first);
    std::array<std::vector<double>, kChunksPerTask> w;
    std::vector<double> rejected(kBatchChunk);
    for (std::size_t g = 0; g < group; ++g) {
      const std::uint64_t ch = first + g;
      w[g].resize(std::size_t(std::min(n, (ch + 1) * kBatchChunk) - ch * kBatchChunk));
      draw_batch(t, c, seed, ch * kBatchChunk, w[g].size(), w[g].data(), rejected.data());
      if (power == 2)
        for (double& x : w[g]) x = x * x;
    }
    for (std::size_t j = 0; j < w[0].size(); ++j)
      for (std::size_t g = 0; g < group; ++g)
        if (j < w[g].size()) parts[first + g].add(w[g][j]);
  });
  MeanAccumulator all;
  for (const MeanAccumulator& a : parts) all.merge(a);
  return all;
}

std::uint64_t count_rejected(Technique t, const Config& c, std::uint64_t seed, std::uint64_t n) {
  std::vector<std::uint64_t> parts((n + kBatchChunk - 1) / kBatchChunk);
  for_each_chunk(t, c, seed, n,
                 [&](std::uint64_t ch, const std::vector<double>&, const std::vector<double>& r) {
                   parts[ch] = std::uint64_t(std::count(r.begin(), r.end(), 1.0));
                 });
  std::uint64_t all = 0;
  for (std::uint64_t k : parts) all += k;
  return all;
}

Moments moments_by_cubature(const Config& c, bool second_moments) {
  const GGX<double> g = c.ggx();
  const V3 wi = incidence(c.theta_deg);
  // f·cos over the half vector, with the Jacobian 4 (ωi·h) of ωo = reflect(ωi, h) (Walter Eq. 14).
  // G2 → 0 as ωo reaches the horizon, so the integrand is continuous where ωo_z = 0.
  auto integrate = [&](int power, bool bounded) {
    return integrate_ndf_lobe(
        [&](const V3& h) {
          const double ih = dot(wi, h);
          if (!(ih > 0)) return 0.0;
          const V3 wo = reflect(wi, h);
          if (!(wo.z > 0)) return 0.0;
          const double fc = microfacet_brdf(g, wi, wo, 1.0) * wo.z;
          if (power == 1) return fc * 4 * ih;
          const double p = bounded ? pdf_bounded_vndf(g, wi, wo, BoundedVndfBound::kListing1)
                                   : pdf_spherical_caps(g, wi, wo);
          return fc * fc / p * 4 * ih;
        },
        c.ax, c.ay, true, 1e-10, &wi);
  };
  Moments m;
  const Integral e = integrate(1, false);
  m.albedo = e.value;
  m.albedo_error = e.error;
  if (second_moments) {
    const Integral mc = integrate(2, false), mb = integrate(2, true);
    m.m2_caps = mc.value;
    m.m2_caps_error = mc.error;
    m.m2_bounded = mb.value;
    m.m2_bounded_error = mb.error;
  }
  return m;
}

Rate caps_rejection_by_cubature(const Config& c) {
  const GGX<double> g = c.ggx();
  const V3 wi = incidence(c.theta_deg);
  const double pi = std::numbers::pi;
  SphereCubatureOptions o;
  // The density's support ends where the half vector reaches the horizon: ωo_z = −ωi_z, a θ line.
  o.theta_min = pi / 2;
  o.theta_max = pi - c.theta_deg * pi / 180;
  if (!(o.theta_max > o.theta_min)) return {};
  // The lobe's tail is steepest just below the horizon near the mirror azimuth at grazing
  // incidence, and near the end of the support: split geometrically there.
  const double a = std::min(c.ax, c.ay);
  for (int k = -6; k <= 6; ++k) {
    const double d = std::atan(a * std::ldexp(1.0, k));
    for (double t : {o.theta_min + d, o.theta_max - d})
      if (t > o.theta_min && t < o.theta_max) o.theta_breaks.push_back(t);
    for (double p : {kPhiI + pi + d, kPhiI + pi - d, kPhiI + d, kPhiI - d})
      o.phi_breaks.push_back(std::fmod(p + 4 * pi, 2 * pi));
  }
  o.phi_breaks.push_back(std::fmod(kPhiI + pi, 2 * pi));
  o.phi_breaks.push_back(kPhiI);
  if (c.ax != c.ay) {
    const auto more = anisotropy_phi_breaks(c.ax, c.ay);
    o.phi_breaks.insert(o.phi_breaks.end(), more.begin(), more.end());
  }
  o.rel_tol = 1e-10;
  const Integral r =
      integrate_sphere([&](const V3& wo) { return pdf_spherical_caps(g, wi, wo); }, o);
  return {r.value, r.error};
}

}  // namespace glintlab::verify::eto_claims

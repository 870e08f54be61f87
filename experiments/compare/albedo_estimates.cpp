#include "experiments/compare/albedo_estimates.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <span>

#include "core/math/rng.h"
#include "core/model_layout.h"
#include "core/simd/model_batch.h"
#include "verify/conformance/common.h"
#include "verify/stats/mean_tests.h"

namespace glintlab::experiments::compare {
namespace {

namespace cf = verify::conformance;
using V3 = Vec3<double>;

ModelQuery<double> scene_query(const ModelEntry& m, double theta_deg) {
  return cf::make_query(m, theta_deg, kSceneFootprint);
}

// The conformance suite's integral of the value over the upper hemisphere (integrate_hemisphere:
// cubature about the mirror direction, or for footprint models Monte Carlo over its fixed mirror
// mixture), the same truth sampler-covers-value tests the model's sampler against. The value is
// asked for many directions per call (values_at), so a model defined in Python is called once per
// chunk, not once per direction; the integral is the same.
AlbedoReference by_suite_integral(const ModelEntry& m, const std::vector<double>& values,
                                  const ModelQuery<double>& q, const CompareBudget& b,
                                  std::uint64_t seed) {
  const cf::DirectionRows value_rows = [&](std::span<const V3> w, std::span<double> out) {
    cf::values_at(m, values, q, w, out);
  };
  const verify::conformance::HemisphereIntegral h = cf::integrate_hemisphere(
      m, value_rows, q.wi, cf::roughness_hint(m, values), b.budget, seed);
  AlbedoReference ref;
  ref.method = h.monte_carlo ? "monte-carlo" : "cubature";
  ref.value = h.value;
  ref.error = h.error;
  const double bound = h.monte_carlo ? b.monte_carlo_converged_rel : b.cubature_converged_rel;
  ref.converged = std::isfinite(h.value) && std::isfinite(h.error) &&
                  h.error <= bound * std::max(std::abs(h.value), 1e-12) &&
                  (!h.monte_carlo || h.value != 0);
  return ref;
}

// N samples of the model's own sampler at query q; the estimate is the mean weight, a sample
// counting 0 where it is rejected, below the horizon or outside the model's domain (the reference
// integrates the same). Returns the estimate; adds the time to `seconds`. A batched model (every
// built-in one, a plug-in with its batches) samples through the batch dispatch on `isa`; any other
// (a model defined in Python) through sample_each, one call of its rows function per estimate,
// where the batch dispatch would call its per-row thunk once per sample (same samples, bit for
// bit: a Python model's every call costs far more than its arithmetic).
struct SampleBuffers {
  std::vector<double> u1, u2;
  std::vector<Vec2<double>> pairs;
  std::vector<ModelSample<double>> samples;
  std::vector<std::vector<double>> out;
};
double sampler_estimate(const ModelEntry& m, const std::vector<double>& values,
                        const ModelQuery<double>& q, std::uint64_t n, std::uint64_t seed,
                        simd::Isa isa, bool batched, SampleBuffers& buf, double& seconds) {
  buf.out.assign(simd::kSampleColumns.size(), std::vector<double>(n));
  if (batched) {
    buf.u1.resize(n);
    buf.u2.resize(n);
    for (std::uint64_t i = 0; i < n; ++i) {
      const Vec2<double> u = cf::pair_at(seed, i);
      buf.u1[i] = u.x;
      buf.u2[i] = u.y;
    }
    const QueryRow<double> row = to_row(q);
    std::vector<simd::Column<double>> query;
    for (const double& c : row) query.push_back({&c, 0});
    std::vector<double*> outputs;
    for (auto& o : buf.out) outputs.push_back(o.data());
    const auto start = std::chrono::steady_clock::now();
    simd::sample_batch(m, values, query, {buf.u1.data(), 1}, {buf.u2.data(), 1}, outputs, n, isa);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } else {
    buf.pairs.resize(n);
    for (std::uint64_t i = 0; i < n; ++i) buf.pairs[i] = cf::pair_at(seed, i);
    buf.samples.resize(n);
    const auto start = std::chrono::steady_clock::now();
    sample_each(m, values, q, buf.pairs, buf.samples);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // The columns sample_batch writes (kSampleColumns), rejected as 1 or 0.
    for (std::uint64_t i = 0; i < n; ++i) {
      const ModelSample<double>& s = buf.samples[i];
      const double row[6] = {s.wo.x, s.wo.y, s.wo.z, s.pdf, s.weight, s.rejected ? 1.0 : 0.0};
      for (std::size_t k = 0; k < 6; ++k) buf.out[k][i] = row[k];
    }
  }
  double sum = 0;
  for (std::uint64_t i = 0; i < n; ++i) {
    const V3 wo{buf.out[0][i], buf.out[1][i], buf.out[2][i]};
    ModelQuery<double> at = q;
    at.wo = wo;
    const bool counted = buf.out[5][i] == 0 && wo.z > 0 && !(m.validate && m.validate(at));
    sum += counted ? buf.out[4][i] : 0.0;
  }
  return sum / double(n);
}

}  // namespace

AlbedoReference reference_albedo(const ModelEntry& m, double theta_deg, const CompareBudget& b,
                                 std::uint64_t seed) {
  const std::vector<double> values = resolve_params(m, {});
  const ModelQuery<double> q = scene_query(m, theta_deg);
  AlbedoReference ref = by_suite_integral(m, values, q, b, seed);
  ref.theta_deg = theta_deg;
  return ref;
}

EqualTimeCurve equal_time_curve(const ModelEntry& m, const std::vector<AlbedoReference>& refs,
                                const CompareBudget& b, std::uint64_t seed) {
  EqualTimeCurve curve;
  const simd::Isa isa = simd::default_isa();
  curve.isa = std::string(simd::isa_name(isa));
  for (const AlbedoReference& r : refs) {
    if (!r.converged) {
      curve.reason = fmt::format("the reference at θi = {:g}° did not converge", r.theta_deg);
      return curve;
    }
    if (!(std::abs(r.value) > 0)) {
      curve.reason = fmt::format("the reference albedo at θi = {:g}° is 0", r.theta_deg);
      return curve;
    }
  }
  const std::vector<double> values = resolve_params(m, {});
  SampleBuffers buf;
  const std::vector<std::uint64_t> ladder = sample_ladder(b);
  const bool batched = simd::is_batched(m);
  // One untimed call first, so the first timed estimate does not pay for cold caches.
  double warm_up = 0;
  (void)sampler_estimate(m, values, scene_query(m, refs.front().theta_deg), ladder.back(), seed,
                         isa, batched, buf, warm_up);
  for (std::uint64_t n : ladder) {
    double seconds = 0, squares = 0;
    verify::MeanAccumulator bias;
    for (std::size_t s = 0; s < refs.size(); ++s) {
      const ModelQuery<double> q = scene_query(m, refs[s].theta_deg);
      double scene_squares = 0;
      for (int rep = 0; rep < b.repetitions; ++rep) {
        const std::uint64_t stream = counter_bits(seed, (n << 20) ^ (s << 10) ^ std::uint64_t(rep), 0);
        const double e = sampler_estimate(m, values, q, n, stream, isa, batched, buf, seconds);
        const double rel = (e - refs[s].value) / std::abs(refs[s].value);
        scene_squares += rel * rel;
        if (n == ladder.back()) bias.add(rel);
      }
      squares += scene_squares / b.repetitions;
    }
    const double estimates = double(refs.size()) * b.repetitions;
    curve.points.push_back({n, seconds / estimates, std::sqrt(squares / double(refs.size()))});
    if (n == ladder.back()) {
      // The references' own errors (one σ for Monte Carlo) enter the bias's standard error.
      double reference_squares = 0;
      for (const AlbedoReference& r : refs) reference_squares += std::pow(r.error / std::abs(r.value), 2);
      curve.reference_relative_error = std::sqrt(reference_squares / double(refs.size()));
      const double reference_variance = reference_squares / double(refs.size() * refs.size());
      curve.relative_bias = bias.mean;
      curve.relative_bias_se = std::sqrt(bias.variance() / double(bias.n) + reference_variance);
    }
  }
  return curve;
}

}  // namespace glintlab::experiments::compare

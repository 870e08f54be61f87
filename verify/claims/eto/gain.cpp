// The measurement and decision of eto.variance-rough and eto.variance-smooth (gain.h).
#include "verify/claims/eto/gain.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

#include "core/math/rng.h"
#include "core/samplers/bounded_vndf.h"
#include "verify/stats/mean_tests.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify::eto_claims {
namespace {

using V3 = Vec3<double>;
constexpr std::string_view kSeedId = "eto.variance-rough";  // both claims' measurement
constexpr double kRoughControlRmse = 0.98;   // the gain control: caps RMSE × 0.98 (2 % reduction)
constexpr double kSmoothControlRmse = 0.96;  // the no-gain control: bounded RMSE × 0.96

bool in_rough_regime(const Config& c) { return c.ax == c.ay && c.ax >= 0.8 && c.theta_deg <= 60; }
bool in_smooth_regime(const Config& c) {
  return c.ax == c.ay && std::abs(c.ax - 0.2) < 1e-12 && c.theta_deg <= 60;
}

// Second moment of the single-scattering weight f cos / p (F = 1) of technique t, n samples.
MeanAccumulator second_moment(Technique t, const Config& c, std::uint64_t seed, std::uint64_t n) {
  return accumulate_weights(t, c, seed, n, 2);
}

// The RMSE-reduction interval of a measured ratio: [gain(r·e^{z se}), gain(r·e^{−z se})].
GainInterval gain_interval(double ratio, double log_se, double z) {
  return {1 - std::sqrt(ratio * std::exp(z * log_se)), 1 - std::sqrt(ratio),
          1 - std::sqrt(ratio * std::exp(-z * log_se))};
}

// The input decided: the bounded sampler against the caps sampler; the gain's control (a 2 %
// reduction: the caps sampler against itself with its RMSE × 0.98); the no-gain control (the
// bounded sampler with its RMSE × 0.96).
GainInterval interval_of(const GainMeasured& m, Input input, bool rough, double z) {
  if (input == Input::kGenuine) return gain_interval(m.ratio, m.log_se, z);
  if (rough)
    return gain_interval(kRoughControlRmse * kRoughControlRmse * m.ratio_off, m.log_se_off, z);
  return gain_interval(kSmoothControlRmse * kSmoothControlRmse * m.ratio, m.log_se, z);
}

// Outside the regime, where the gain is shown: the measured reduction by α (isotropic, θi = 0),
// by anisotropy (α = 1, θi = 0) and by incidence (isotropic α = 1), and how the measured ratio
// compares with c.
std::string describe_gains(const std::vector<GainMeasured>& ms, double z) {
  std::string by_alpha, by_aniso, by_theta;
  int agree = 0;
  for (const GainMeasured& m : ms) {
    const GainInterval g = gain_interval(m.ratio, m.log_se, z);
    agree += std::abs(std::log(m.ratio / m.c_analytic)) <= z * m.log_se;
    const std::string v = fmt::format("{:.1f} %", 100 * g.mid);
    if (m.c.ax == m.c.ay && m.c.theta_deg == 0)
      by_alpha += fmt::format("{}{:g}: {}", by_alpha.empty() ? "" : ", ", m.c.ax, v);
    if (m.c.ax == 1.0 && m.c.theta_deg == 0)
      by_aniso += fmt::format("{}{:g}: {}", by_aniso.empty() ? "" : ", ", m.c.ax / m.c.ay, v);
    if (m.c.ax == 1.0 && m.c.ay == 1.0)
      by_theta += fmt::format("{}{:g}°: {}", by_theta.empty() ? "" : ", ", m.c.theta_deg, v);
  }
  return fmt::format(
      "measured RMSE reduction 1 − √(M2_b/M2_c) by α (isotropic, θi = 0) {}; by αx/αy (α = 1) {}; "
      "by θi (α = 1) {}; the measured ratio agrees with c = (k i_z + t)/(i_z + t) within its "
      "interval in {} of {} configurations",
      by_alpha, by_aniso, by_theta, agree, ms.size());
}

}  // namespace

GainSizes gain_sizes(Budget b) {
  const bool quick = b == Budget::kQuick;
  const std::vector<double> alphas =
      quick ? std::vector<double>{0.05, 0.2, 0.5, 0.8, 1.0}
            : std::vector<double>{0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
  const std::vector<double> ratios =
      quick ? std::vector<double>{1, 10} : std::vector<double>{1, 2, 4, 10};  // αx / αy
  const std::vector<double> thetas =
      quick ? std::vector<double>{0, 45, 80, 89} : std::vector<double>{0, 20, 40, 60, 75, 85, 89};
  return {grid_of(alphas, ratios, thetas), quick ? (1u << 15) : (1u << 20)};
}

namespace {

GainMeasured measure_configuration(const GainSizes& z, int configuration) {
  const Config& c = z.grid[std::size_t(configuration)];
  const std::uint64_t seed = check_seed(std::string(kSeedId), std::uint64_t(configuration));
  GainMeasured m{c};
  const auto log_ratio = [](const MeanAccumulator& b, const MeanAccumulator& a, double& se) {
    se = std::sqrt(b.variance() / (double(b.n) * b.mean * b.mean) +
                   a.variance() / (double(a.n) * a.mean * a.mean));
    return b.mean / a.mean;
  };
  const MeanAccumulator b = second_moment(Technique::kBounded, c, mix64(seed), z.n);
  const MeanAccumulator caps = second_moment(Technique::kSphericalCaps, c, mix64(seed + 1), z.n);
  const MeanAccumulator off = second_moment(Technique::kSphericalCaps, c, mix64(seed + 2), z.n);
  m.ratio = log_ratio(b, caps, m.log_se);
  m.ratio_off = log_ratio(off, caps, m.log_se_off);
  const V3 wi = incidence(c.theta_deg);
  const GGX<double> g = c.ggx();
  const double k = bounded_vndf_k(g, wi, BoundedVndfBound::kListing1);
  const double t = std::sqrt(g.sigma2(wi) + wi.z * wi.z);
  m.c_analytic = (k * wi.z + t) / (wi.z + t);
  return m;
}

}  // namespace

// Both claims read the same measurement: it is kept per process, by configuration, its index (the
// seed) and the sample count, so that of the two claims in one run the second reads what the
// first measured (deterministic, so which one measures does not matter).
GainMeasured observe_gain(const GainSizes& z, int configuration) {
  using Key = std::tuple<double, double, double, int, std::uint64_t>;
  static std::mutex mutex;
  static std::map<Key, GainMeasured> kept;
  const Config& c = z.grid[std::size_t(configuration)];
  const Key key{c.ax, c.ay, c.theta_deg, configuration, z.n};
  {
    const std::lock_guard lock(mutex);
    if (const auto it = kept.find(key); it != kept.end()) return it->second;
  }
  const GainMeasured m = measure_configuration(z, configuration);
  const std::lock_guard lock(mutex);
  kept.emplace(key, m);
  return m;
}

GainMeasurement measure_gain(std::span<const GainMeasured> ms, Input input, bool rough) {
  GainMeasurement d{{ms.begin(), ms.end()}};
  d.z = normal_quantile(1 - sidak_level(check_level(), ms.size()) / 2);
  const auto regime = rough ? in_rough_regime : in_smooth_regime;
  double least = rough ? 1e300 : -1e300;
  for (const GainMeasured& m : ms) {
    if (!regime(m.c)) continue;
    ++d.in;
    const GainInterval g = interval_of(m, input, rough, d.z);
    const bool shown = g.lo >= kMaterialGain, excluded = g.hi < kMaterialGain;
    d.yes += rough ? shown : excluded;
    d.no += rough ? excluded : shown;
    if (rough ? g.mid < least : g.mid > least) {
      least = g.mid;
      d.worst = g;
      d.worst_at = describe_config(m.c);
    }
  }
  if (d.in == 0) return d;
  if (d.no > 0)
    d.verdict = Verdict::kFails;
  else if (d.yes == d.in)
    d.verdict = Verdict::kHoldsInRegime;
  return d;
}

Decision decide_gain(const GainMeasurement& m, bool rough) {
  return {.verdict = m.verdict,
          .value = rough ? m.worst.lo : m.worst.hi,
          .bound = kMaterialGain,
          .configurations = int(m.ms.size())};
}

std::string describe_gain(const GainSizes& z, const GainMeasurement& d, Input input, bool rough) {
  if (input != Input::kGenuine)
    return fmt::format(
        "{}: {} of {} regime configurations {}, {} {}; nearest {:.1f} % [{:.1f}, {:.1f}] at {}",
        rough
            ? fmt::format("a {:g} % RMSE reduction (the spherical_caps sampler against an "
                          "independent run of itself, its RMSE × {:g})",
                          100 * (1 - kRoughControlRmse), kRoughControlRmse)
            : fmt::format("bounded weights with a {:g} % lower RMSE (second moment × {:.4g})",
                          100 * (1 - kSmoothControlRmse), kSmoothControlRmse * kSmoothControlRmse),
        d.yes, d.in, rough ? "show a material gain" : "exclude one", d.no,
        rough ? "exclude one" : "show one", 100 * d.worst.mid, 100 * d.worst.lo, 100 * d.worst.hi,
        d.worst_at);
  return fmt::format(
      "inside the regime ({}): {} of {} configurations {}, {} {}; least favourable {:.1f} % "
      "[{:.1f}, {:.1f}] at {} (interval at z = {:.2f}, {} samples per sampler); {}",
      rough ? kRoughRegime : kSmoothRegime, d.yes, d.in,
      rough ? "show a material (≥ 5 %) RMSE reduction" : "exclude a material RMSE reduction", d.no,
      rough ? "exclude one" : "show one", 100 * d.worst.mid, 100 * d.worst.lo, 100 * d.worst.hi,
      d.worst_at, d.z, z.n, describe_gains(d.ms, d.z));
}

std::string gain_power(const GainMeasurement& d, bool rough) {
  const auto regime = rough ? in_rough_regime : in_smooth_regime;
  double se = 0;
  for (const GainMeasured& m : d.ms)
    if (regime(m.c)) se = std::max(se, m.log_se);
  // A reduction g has interval half-width ≈ (1 − g)·z·se/2 in the gain: detected (90 %) once it is
  // (z + 1.28)·se/2 from the 5 % line. From the least favourable regime configuration, that is a
  // change of the bounded estimator's RMSE by the factor (1 − g_detected)/(1 − g_measured).
  const double detected =
      rough ? kMaterialGain - (d.z + 1.2816) * se / 2 : kMaterialGain + (d.z + 1.2816) * se / 2;
  const double rmse_change = (1 - detected) / (1 - d.worst.mid) - 1;
  return fmt::format(
      "an RMSE reduction {} {:.3g} is told apart from 5 % with 90 % power (largest log-ratio SE "
      "in the regime {:.2g}); from the least favourable regime configuration ({:.1f} %) that is "
      "the bounded estimator's RMSE {:.1f} % {}{}",
      rough ? "below" : "above", detected, se, 100 * d.worst.mid, 100 * std::abs(rmse_change),
      rmse_change > 0 ? "higher" : "lower",
      std::abs(rmse_change) > 0.05 ? ": a 1–5 % change of it cannot cross the 5 % line" : "");
}

}  // namespace glintlab::verify::eto_claims

// The paired intervals and the two shared replicated measurements of Chermain et al.'s claims
// (common.h).
#include "verify/claims/chermain/common.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <future>
#include <map>
#include <mutex>

#include "core/glints/chermain.h"
#include "core/math/rng.h"
#include "verify/scenes/chermain_scenes.h"
#include "verify/stats/mean_tests.h"

namespace glintlab::verify::chermain_claims {
namespace {

// The value of `key`, made by make() the first time it is asked for in this process and read from
// the cache after (the claims that share a measurement each observe it). Made outside the lock, so
// the replicates of one claim are still made in parallel.
template <typename Value, typename Key, typename Make>
Value made_once(const Key& key, Make make) {
  static std::mutex mutex;
  static std::map<Key, std::shared_future<Value>> cache;
  std::promise<Value> promise;
  std::shared_future<Value> future;
  bool mine = false;
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto [it, inserted] = cache.try_emplace(key);
    if (inserted) it->second = promise.get_future().share(), mine = true;
    future = it->second;
  }
  if (mine) {
    try {
      promise.set_value(make());
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
  }
  return future.get();
}

double mean_of(std::span<const GgaaReplicate> reps, double GgaaReplicate::*f) {
  double m = 0;
  for (const GgaaReplicate& r : reps) m += r.*f;
  return m / double(reps.size());
}

}  // namespace

PairedComparison compare_paired(const std::vector<double>& d, double confidence) {
  PairedComparison c;
  c.n = int(d.size());
  double m = 0;
  for (double x : d) m += x;
  m /= double(d.size());
  double v = 0;
  for (double x : d) v += (x - m) * (x - m);
  v /= double(d.size() - 1);
  c.mean = m;
  c.se = std::sqrt(v / double(d.size()));
  c.t = student_t_quantile(0.5 + 0.5 * confidence, double(d.size() - 1));
  c.lo = m - c.t * c.se, c.hi = m + c.t * c.se;
  // 90 % power against an effect δ: δ ≥ (t + z_0.9) · SE (normal approximation of the t power).
  c.detectable = (c.t + 1.2816) * c.se;
  return c;
}

Verdict decide_paired(const std::vector<std::vector<double>>& parts, double tolerance) {
  const double conf = sidak_confidence(parts.size());
  bool all_win = true;
  for (const auto& d : parts) {
    const PairedComparison c = compare_paired(d, conf);
    if (c.hi < -tolerance) return Verdict::kFails;  // reversed beyond the noise and the tolerance
    if (!(c.lo > 0)) all_win = false;               // a tie within the noise
  }
  return all_win ? Verdict::kHolds : Verdict::kInconclusive;
}

double largest_detectable(const std::vector<std::vector<double>>& parts) {
  const double conf = sidak_confidence(parts.size());
  double detectable = 0;
  for (const auto& d : parts) detectable = std::max(detectable, compare_paired(d, conf).detectable);
  return detectable;
}

std::string_view reading(const PairedComparison& c) {
  return c.lo > 0 ? "as claimed" : c.hi < 0 ? "reversed" : "tie within the noise";
}

std::string paired_power(const std::vector<std::vector<double>>& parts, std::string_view unit,
                         int replicates) {
  return fmt::format(
      "paired difference detected at 90 % power: ≥ {:.3f} {} ((t_{{{:.4f}, {}}} + 1.28) × SE of "
      "the mean over {} replicates, largest over {} part(s))",
      largest_detectable(parts), unit, 0.5 + 0.5 * sidak_confidence(parts.size()), replicates - 1,
      replicates, parts.size());
}

// --- The tube scene's replicates -------------------------------------------------------------

GgaaReplicate measure_ggaa_replicate(const GgaaReplicateBudget& b, const std::string& id, int k) {
  TubeSceneOptions o;
  o.width = b.width, o.height = b.height, o.threads = b.threads;
  const std::uint64_t s = check_seed(id, std::uint64_t(k));
  o.sdf_seed = s;
  o.camera_shift = counter_uniform<double>(s, 0, 0);  // sub-pixel offset of the replicate
  const Image ref = render_tubes_reference(o, b.reference_spp, check_seed(id, 1000 + k));
  Image near_truth = render_tubes_reference(o, b.reference_spp, check_seed(id, 2000 + k));
  for (double& v : near_truth.data) v *= 1 + kGgaaNearTruthBias;
  GgaaReplicate r;
  r.none = display_rmse_percent(render_tubes(o, chermain2021::kNoGgaa, 0.5), ref);
  r.proj05 = display_rmse_percent(render_tubes(o, chermain2021::kProjectedHalf, 0.5), ref);
  r.near_truth = display_rmse_percent(near_truth, ref);
  std::vector<Image> f05, f1, slow1;
  for (int f = 0; f < b.frames; ++f) {
    TubeSceneOptions of = o;
    of.camera_shift = o.camera_shift + kGgaaPan * f;
    f05.push_back(render_tubes(of, chermain2021::kProjectedHalf, 0.5));
    f1.push_back(render_tubes(of, chermain2021::kProjectedHalf, 1.0));
    of.camera_shift = o.camera_shift + (1 - kGgaaSlowPan) * kGgaaPan * f;
    slow1.push_back(render_tubes(of, chermain2021::kProjectedHalf, 1.0));
  }
  r.flicker05 = frame_to_frame_variance(f05, ref);
  r.flicker1 = frame_to_frame_variance(f1, ref);
  r.flicker1_slow = frame_to_frame_variance(slow1, ref);
  return r;
}

template <>
GgaaReplicateBudget replicate_budget<GgaaReplicateBudget>(Budget b) {
  return b == Budget::kQuick ? GgaaReplicateBudget{64, 44, 32, 3, 6, 0}
                             : GgaaReplicateBudget{128, 88, 64, 4, 10, 0};
}
template <>
GgaaReplicateBudget replicate_probe_budget<GgaaReplicateBudget>() {
  return {32, 22, 16, 3, 6, 0};
}

GgaaReplicate replicate(const GgaaReplicateBudget& b, int k) {
  const std::array<int, 5> key = {b.width, b.height, b.reference_spp, b.frames, k};
  return made_once<GgaaReplicate>(key,
                                  [&] { return measure_ggaa_replicate(b, "chermain.ggaa", k); });
}

GgaaMeasured measure_ordering(const GgaaOrdering& o, std::span<const GgaaReplicate> reps,
                              Input input) {
  GgaaMeasured m{.reps = {reps.begin(), reps.end()}, .input = input};
  const bool replace_a = input == Input::kCorrected, replace_b = input == Input::kPerturbed;
  for (const GgaaPart& p : o.parts) {
    std::vector<double> d;
    for (const GgaaReplicate& r : reps)
      d.push_back((replace_b ? r.*(o.control) : r.*(p.b)) -
                  (replace_a ? r.*(o.control) : r.*(p.a)));
    m.diffs.push_back(d);
  }
  return m;
}

Decision decide_ordering(const GgaaOrdering& o, const GgaaMeasured& m) {
  const double conf = sidak_confidence(o.parts.size());
  return {.verdict = decide_paired(m.diffs),
          .value = compare_paired(m.diffs[0], conf).mean,
          .configurations = int(m.reps.size()) * int(o.parts.size())};
}

namespace {

std::string ggaa_parts(const GgaaOrdering& o, const GgaaMeasured& m) {
  const bool replace_a = m.input == Input::kCorrected, replace_b = m.input == Input::kPerturbed;
  const double conf = sidak_confidence(o.parts.size());
  std::string out;
  for (std::size_t i = 0; i < o.parts.size(); ++i) {
    const PairedComparison pc = compare_paired(m.diffs[i], conf);
    const char* a = replace_a ? o.control_name : o.parts[i].a_name;
    const char* b = replace_b ? o.control_name : o.parts[i].b_name;
    out += fmt::format(
        "{}a = {} {:.3f} vs b = {} {:.3f} {} (means over replicates); b − a {:+.3f} ± {:.3f} SE, "
        "{:.2f} % CI [{:+.3f}, {:+.3f}] ({})",
        i ? "; " : "", a, mean_of(m.reps, replace_a ? o.control : o.parts[i].a), b,
        mean_of(m.reps, replace_b ? o.control : o.parts[i].b), o.unit, pc.mean, pc.se, 100 * conf,
        pc.lo, pc.hi, reading(pc));
  }
  return out;
}

}  // namespace

std::string describe_ordering(const GgaaOrdering& o, const GgaaReplicateBudget& g,
                              const GgaaMeasured& m) {
  if (m.input != Input::kGenuine)
    return fmt::format(
        "{} in place of {}: {}", o.control_name,
        m.input == Input::kPerturbed ? "b (the claimed higher)" : "a (the claimed lower)",
        ggaa_parts(o, m));
  return fmt::format(
      "tubes {}x{}, {} replicates (own glint layout, sub-pixel camera offset, reference seed), "
      "reference {} spp (pixel footprint fixed, no GGAA), {} frames of a {}-pixel pan for "
      "shimmer (frame-to-frame variance x1e4); the claim: a < b in each part: {}. "
      "Paper: Fig. 8 4.815 -> 3.661 %; Fig. 9 13.48 | 7.53, 8.19 | 7.43, 7.79 %",
      g.width, g.height, g.replicates, g.reference_spp, g.frames, kGgaaPan, ggaa_parts(o, m));
}

// --- The normal-mapped tubes' replicates -----------------------------------------------------
// The paper's regime (Fig. 9: normal map without LEAN, 1 spp, GGAA at s_K 0.5 and 1), declared
// before measuring: bumps 4 pixels wide, rms slope 0.1, on the tubes of Fig. 8 (α 0.35,
// 1.6e5 microfacets per unit uv).
namespace {

constexpr double kBumpWavelengthPx = 4;
constexpr double kBumpSlopeRms = 0.1;

// Median over the pixels where both have a kernel of a's kernel width / b's (channel 3).
double median_width_ratio(const Image& a, const Image& b) {
  std::vector<double> r;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      if (a.at(x, y, 3) > 0 && b.at(x, y, 3) > 0) r.push_back(a.at(x, y, 3) / b.at(x, y, 3));
  if (r.empty()) return 1;
  std::nth_element(r.begin(), r.begin() + std::ptrdiff_t(r.size() / 2), r.end());
  return r[r.size() / 2];
}

}  // namespace

BumpyGgaaReplicate measure_bumpy_ggaa_replicate(const BumpyGgaaBudget& b, const std::string& id,
                                                int k) {
  BumpyTubeOptions o;
  o.tubes.width = b.width, o.tubes.height = b.height, o.tubes.threads = b.threads;
  o.bump_wavelength_px = kBumpWavelengthPx, o.bump_slope_rms = kBumpSlopeRms;
  const std::uint64_t s = check_seed(id, std::uint64_t(k));
  o.tubes.sdf_seed = s;
  o.tubes.camera_shift = counter_uniform<double>(s, 0, 0);
  const Image ref = render_bumpy_tubes_reference(o, b.reference_spp, check_seed(id, 1000 + k));
  const Image alt = render_bumpy_tubes_reference(o, b.reference_spp, check_seed(id, 2000 + k));
  const Image half05 = render_bumpy_tubes(o, chermain2021::kHalfSlope, 0.5);
  const Image half1 = render_bumpy_tubes(o, chermain2021::kHalfSlope, 1.0);
  const Image proj05 = render_bumpy_tubes(o, chermain2021::kProjectedHalf, 0.5);
  const Image proj1 = render_bumpy_tubes(o, chermain2021::kProjectedHalf, 1.0);
  BumpyGgaaReplicate r;
  r.none = display_rmse_percent(render_bumpy_tubes(o, chermain2021::kNoGgaa, 0.5), ref);
  r.half05 = display_rmse_percent(half05, ref), r.half1 = display_rmse_percent(half1, ref);
  r.proj05 = display_rmse_percent(proj05, ref), r.proj1 = display_rmse_percent(proj1, ref);
  r.half05_alt = display_rmse_percent(half05, alt), r.half1_alt = display_rmse_percent(half1, alt);
  r.proj05_alt = display_rmse_percent(proj05, alt), r.proj1_alt = display_rmse_percent(proj1, alt);
  r.width_ratio = median_width_ratio(half05, proj05);
  r.matched_s_k = 0.5 * r.width_ratio;
  r.proj_matched =
      display_rmse_percent(render_bumpy_tubes(o, chermain2021::kProjectedHalf, r.matched_s_k), ref);
  r.reference_error = display_rmse_percent(alt, ref) / std::sqrt(2.0);
  BumpyTubeOptions smooth_o = o;
  smooth_o.tubes.density = 1e40;  // every cell past the dictionary's last level: the smooth SDF
  const Image smooth = render_bumpy_tubes(smooth_o, chermain2021::kNoGgaa, 0.5);
  r.smooth = display_rmse_percent(smooth, ref);
  const Image px = render_bumpy_tubes_reference(o, b.reference_spp, check_seed(id, 3000 + k),
                                                BumpyReference::kPixelSized);
  r.none_px = display_rmse_percent(render_bumpy_tubes(o, chermain2021::kNoGgaa, 0.5), px);
  r.half05_px = display_rmse_percent(half05, px), r.half1_px = display_rmse_percent(half1, px);
  r.proj05_px = display_rmse_percent(proj05, px), r.proj1_px = display_rmse_percent(proj1, px);
  r.smooth_px = display_rmse_percent(smooth, px);
  Image near_truth = alt;
  for (double& v : near_truth.data) v *= 1 + kGgaaNearTruthBias;
  r.near_truth = display_rmse_percent(near_truth, ref);
  return r;
}

template <>
BumpyGgaaBudget replicate_budget<BumpyGgaaBudget>(Budget b) {
  return b == Budget::kQuick ? BumpyGgaaBudget{64, 44, 256, 6, 0}
                             : BumpyGgaaBudget{128, 88, 1024, 10, 0};
}
template <>
BumpyGgaaBudget replicate_probe_budget<BumpyGgaaBudget>() {
  return {32, 22, 256, 4, 0};
}

BumpyGgaaReplicate replicate(const BumpyGgaaBudget& b, int k) {
  const std::array<int, 4> key = {b.width, b.height, b.reference_spp, k};
  return made_once<BumpyGgaaReplicate>(
      key, [&] { return measure_bumpy_ggaa_replicate(b, "chermain.ggaa-fig9", k); });
}

std::vector<std::vector<double>> Ordering::diffs(std::span<const BumpyGgaaReplicate> reps,
                                                 bool replace_a, bool replace_b) const {
  std::vector<std::vector<double>> out;
  for (const OrderingPart& p : parts) {
    std::vector<double> d;
    for (const BumpyGgaaReplicate& r : reps)
      d.push_back((replace_b ? r.near_truth : r.*(p.b)) - (replace_a ? r.near_truth : r.*(p.a)));
    out.push_back(d);
  }
  return out;
}

double Ordering::reference_error(std::span<const BumpyGgaaReplicate> reps) const {
  double worst = 0;
  for (const OrderingPart& p : parts) {
    double ss = 0;
    for (const BumpyGgaaReplicate& r : reps) {
      const double d = (r.*(p.b) - r.*(p.a)) - (r.*(p.b_alt) - r.*(p.a_alt));
      ss += d * d / 2;
    }
    worst = std::max(worst, std::sqrt(ss / double(reps.size())));
  }
  return worst;
}

double Ordering::tolerance(std::span<const BumpyGgaaReplicate> reps) const {
  return std::max(kPairTolerance, reference_error(reps));
}

double mean_field(std::span<const BumpyGgaaReplicate> reps, BumpyField f) {
  double m = 0;
  for (const BumpyGgaaReplicate& r : reps) m += r.*f / double(reps.size());
  return m;
}

OrderingMeasured measure_ordering(const Ordering& o, std::span<const BumpyGgaaReplicate> reps,
                                  Input input) {
  OrderingMeasured m{.reps = {reps.begin(), reps.end()}, .input = input};
  m.reference_error = o.reference_error(reps);
  m.tolerance = std::max(kPairTolerance, m.reference_error);
  m.diffs = o.diffs(reps, input == Input::kCorrected, input == Input::kPerturbed);
  return m;
}

Decision decide_ordering(const Ordering& o, const OrderingMeasured& m) {
  const double conf = sidak_confidence(o.parts.size());
  return {.verdict = decide_paired(m.diffs, m.tolerance),
          .value = compare_paired(m.diffs[0], conf).mean,
          .bound = m.tolerance,
          .configurations = int(m.reps.size()) * int(o.parts.size())};
}

namespace {

std::string ordering_parts(const Ordering& o, const OrderingMeasured& m) {
  const bool replace_a = m.input == Input::kCorrected, replace_b = m.input == Input::kPerturbed;
  const double conf = sidak_confidence(o.parts.size());
  const double nt = mean_field(m.reps, &BumpyGgaaReplicate::near_truth);
  std::string out;
  for (std::size_t i = 0; i < o.parts.size(); ++i) {
    const OrderingPart& p = o.parts[i];
    const PairedComparison c = compare_paired(m.diffs[i], conf);
    out += fmt::format(
        "{}{} {:.3f} vs {} {:.3f} % RMSE: difference {:+.3f} ± {:.3f} SE, {:.2f} % CI [{:+.3f}, "
        "{:+.3f}] ({})",
        i ? "; " : "", replace_a ? "near-truth image" : p.a_name,
        replace_a ? nt : mean_field(m.reps, p.a), replace_b ? "near-truth image" : p.b_name,
        replace_b ? nt : mean_field(m.reps, p.b), c.mean, c.se, 100 * conf, c.lo, c.hi, reading(c));
  }
  return out;
}

std::string bumpy_setup(const BumpyGgaaBudget& g, std::span<const BumpyGgaaReplicate> reps) {
  return fmt::format(
      "normal-mapped tubes {}x{} (bumps {} px, rms slope {}), {} replicates (own glint layout, "
      "sub-pixel camera offset, two independent references); reference {} spp, each sample with "
      "its own footprint (the pixel's / {} per axis, at least one microfacet), no GGAA; the "
      "reference's own error {:.3f} % RMSE (mean over replicates); no GGAA {:.3f} %, the smooth "
      "limit (no glints) {:.3f} %. Against the other reading of the reference (each sample's "
      "footprint the pixel's size, at its own uv): no GGAA {:.3f}, half slope {:.3f} | {:.3f}, "
      "projected half {:.3f} | {:.3f} (s_K 0.5 | 1), smooth limit {:.3f} %",
      g.width, g.height, kBumpWavelengthPx, kBumpSlopeRms, g.replicates, g.reference_spp,
      kBumpyReferenceStrata, mean_field(reps, &BumpyGgaaReplicate::reference_error),
      mean_field(reps, &BumpyGgaaReplicate::none), mean_field(reps, &BumpyGgaaReplicate::smooth),
      mean_field(reps, &BumpyGgaaReplicate::none_px),
      mean_field(reps, &BumpyGgaaReplicate::half05_px),
      mean_field(reps, &BumpyGgaaReplicate::half1_px),
      mean_field(reps, &BumpyGgaaReplicate::proj05_px),
      mean_field(reps, &BumpyGgaaReplicate::proj1_px),
      mean_field(reps, &BumpyGgaaReplicate::smooth_px));
}

}  // namespace

std::string describe_ordering(const Ordering& o, const BumpyGgaaBudget& g,
                              const OrderingMeasured& m) {
  if (m.input != Input::kGenuine)
    return fmt::format("an independent reference × {} (near truth) in place of {}: {}",
                       1 + kGgaaNearTruthBias,
                       m.input == Input::kPerturbed ? "the claimed higher" : "the claimed lower",
                       ordering_parts(o, m));
  return fmt::format(
      "{}; {}. Held to: the claimed order with its interval above 0 (holds), reversed with its "
      "interval below −{:.3f} (fails: the larger of {} RMSE points, Fig. 9's smallest ordering, "
      "and the reference's own error of the difference, {:.3f}), else a tie. Paper (Fig. 9, "
      "1,024 spp): no GGAA 13.484, half slope 7.527 | 8.185, projected half 7.425 | 7.794 % "
      "(s_K 0.5 | 1)",
      bumpy_setup(g, m.reps), ordering_parts(o, m), m.tolerance, kPairTolerance, m.reference_error);
}

const Ordering kSkOrdering{
    {{"projected half s_K 0.5", &BumpyGgaaReplicate::proj05, &BumpyGgaaReplicate::proj05_alt,
      "projected half s_K 1", &BumpyGgaaReplicate::proj1, &BumpyGgaaReplicate::proj1_alt},
     {"half slope s_K 0.5", &BumpyGgaaReplicate::half05, &BumpyGgaaReplicate::half05_alt,
      "half slope s_K 1", &BumpyGgaaReplicate::half1, &BumpyGgaaReplicate::half1_alt}}};

}  // namespace glintlab::verify::chermain_claims

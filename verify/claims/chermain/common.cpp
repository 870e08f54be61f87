// The paired intervals and the tube scene's replicated measurement of Chermain et al.'s claims
// (common.h); the normal-mapped tubes' replicates are in bumpy_tubes.cpp.
#include "verify/claims/chermain/common.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/glints/chermain.h"
#include "core/math/rng.h"
#include "verify/claims/chermain/made_once.h"
#include "verify/scenes/chermain_scenes.h"
#include "verify/stats/mean_tests.h"

namespace glintlab::verify::chermain_claims {
namespace {

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

}  // namespace glintlab::verify::chermain_claims

// The stability sweep engine (verify/stability/): targets and planes from the registry, the
// negative control found, defects of each kind detected and placed, and thread-independent maps.
#include "verify/stability/sweep.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "verify/stability/failure_region.h"
#include "verify/stability/nan_control.h"

namespace glintlab::verify::stability {
namespace {

// A copy of smooth_ggx whose results are altered by `f(values, query, eval)` (eval) and
// `g(values, query, sample)` (sample): the deliberately broken models of these tests.
template <class F, class G>
ModelEntry altered(std::string_view name, F f, G g, bool keep_float = false) {
  ModelEntry e = find_model("smooth_ggx");
  e.name = name;
  auto inner = e.eval;
  e.eval = [inner, f](const std::vector<double>& v, const ModelQuery<double>& q) {
    ErasedEval r = inner(v, q);
    f(v, q, r);
    return r;
  };
  auto inner_s = e.sample;
  e.sample = [inner_s, g](const std::vector<double>& v, const ModelQuery<double>& q,
                          Vec2<double> u) {
    ModelSample<double> s = inner_s(v, q, u);
    g(v, q, s);
    return s;
  };
  if (!keep_float) e.eval_float = {}, e.pdf_float = {}, e.sample_float = {};
  return e;
}

auto no_change = [](const std::vector<double>&, const ModelQuery<double>&, auto&) {};

SweepTarget target_of(const ModelEntry& m) { return {&m, std::nullopt, 0, "default"}; }

TEST(StabilitySweep, TargetsEveryRegisteredSamplerChoice) {
  const auto t = sweep_targets("smooth_*");
  // smooth_ggx: ndf, vndf, spherical_caps, bounded_caps; smooth_beckmann: ndf, vndf.
  ASSERT_EQ(t.size(), 6u);
  EXPECT_EQ(t[0].id(), "smooth_ggx/ndf");
  EXPECT_EQ(t[5].id(), "smooth_beckmann/vndf");
  EXPECT_TRUE(sweep_targets("nothing*").empty());
  EXPECT_EQ(sweep_targets("smooth_beckmann,smooth_ggx").size(), 6u);
}

TEST(StabilitySweep, PlanesFollowTheParameterSpecs) {
  const auto planes = sweep_planes(find_model("smooth_ggx"), true);
  ASSERT_EQ(planes.size(), 2u);  // alpha and anisotropy: no density, footprint or light
  EXPECT_EQ(planes[0].name, "alpha");
  EXPECT_DOUBLE_EQ(planes[0].rows.front(), 1e-4);
  EXPECT_DOUBLE_EQ(planes[0].rows.back(), 4.0);
  EXPECT_DOUBLE_EQ(planes[0].theta_deg[8], 89.999);
  EXPECT_GT(planes[0].theta_deg.back(), 90);  // back-facing incidence swept
  EXPECT_DOUBLE_EQ(planes[1].rows.back(), 1000.0);
  // A range narrower than 1e-4 … 4 clamps the α axis.
  ParamSpec p{"alpha_x", 0.5, 0.01, 1.0, false, true, ""};
  EXPECT_DOUBLE_EQ(clamp_to_range(p, 1e-4), 0.01);
  EXPECT_LT(clamp_to_range(p, 4.0), 1.0);
}

TEST(StabilitySweep, TheNanControlIsFoundWhereItIsBroken) {
  const ModelSweep s = sweep_model(target_of(nan_control_model()), Budget::kQuick);
  EXPECT_EQ(stability_verdict(s), Verdict::kFails);
  const std::string region = describe_failure_region(s);
  // NaN exactly on the α rows below 0.02 (0.0069 is the last quick row below it), every θi.
  EXPECT_NE(region.find("NaN in value for α ≤ 0.00693 at every θi"), std::string::npos) << region;
  EXPECT_EQ(region.find("anisotropy sweep"), std::string::npos) << region;  // αx ≥ 0.1 there
}

// A defect in 0.05 % of calls, the rarity all.stability's control has, is still found.
TEST(StabilitySweep, ASparseNanIsFound) {
  const ModelSweep s = sweep_model(target_of(sparse_nan_control_model()), Budget::kQuick);
  EXPECT_EQ(stability_verdict(s), Verdict::kFails) << describe_failure_region(s);
  EXPECT_EQ(stability_verdict(s, DefectClass::kEnergyGain), Verdict::kHolds);
}

// Each kind of breakage has its own verdict: a 3 % gain and weight spikes are found as such.
TEST(StabilitySweep, GainAndSpikeControlsFailTheirOwnKindOnly) {
  const ModelSweep g = sweep_model(target_of(gain_control_model()), Budget::kQuick);
  EXPECT_EQ(stability_verdict(g, DefectClass::kEnergyGain), Verdict::kFails);
  EXPECT_EQ(stability_verdict(g, DefectClass::kBreaks), Verdict::kHolds);
  const ModelSweep v = sweep_model(target_of(spike_control_model()), Budget::kQuick);
  EXPECT_EQ(stability_verdict(v, DefectClass::kHugeVariance), Verdict::kFails);
  EXPECT_EQ(stability_verdict(v, DefectClass::kBreaks), Verdict::kHolds);
}

// A glint-like copy of smooth_ggx: reflecting at one position in kSparseScale (uv.x in the first
// 1/kSparseScale of [0, 1)), there with value and weight × kSparseScale, and black elsewhere. Its
// sampler is exact at every position, so a renderer's pixel converges as fast as smooth_ggx's;
// only the spatial variance is large, which a new position per sample would count.
constexpr double kSparseScale = 128;
ModelEntry sparse_positions_model() {
  auto lit = [](const ModelQuery<double>& q) { return q.footprint.uv.x * kSparseScale < 1; };
  return altered(
      "sparse_positions_ggx",
      [lit](const std::vector<double>&, const ModelQuery<double>& q, ErasedEval& r) {
        r.value *= lit(q) ? kSparseScale : 0.0;
      },
      [lit](const std::vector<double>&, const ModelQuery<double>& q, ModelSample<double>& s) {
        s.weight *= lit(q) ? kSparseScale : 0.0;
      });
}

// smooth_ggx whose sampler draws the VNDF of a lobe `narrowing` times narrower than the BRDF's and
// weights by value/pdf of that lobe: unbiased, but where the narrow pdf is near zero the value is
// not (narrowing = 1: the model's own sampler, the near-truth input).
ModelEntry narrow_sampler_model(double narrowing) {
  ModelEntry e = find_model("smooth_ggx");
  e.name = "narrow_sampler_ggx";
  std::size_t ax = 0, ay = 0;
  for (std::size_t i = 0; i < e.params.size(); ++i) {
    if (e.params[i].name == "alpha_x") ax = i;
    if (e.params[i].name == "alpha_y") ay = i;
  }
  auto eval = e.eval;
  auto sample = e.sample;
  e.sample = [=](const std::vector<double>& v, const ModelQuery<double>& q, Vec2<double> u) {
    std::vector<double> narrow = v;
    narrow[ax] = clamp_to_range(e.params[ax], v[ax] / narrowing);
    narrow[ay] = clamp_to_range(e.params[ay], v[ay] / narrowing);
    ModelSample<double> s = sample(narrow, q, u);
    if (s.rejected || !(s.pdf > 0)) return s;
    ModelQuery<double> at = q;
    at.wo = s.wo;
    s.weight = eval(v, at).value / s.pdf;
    return s;
  };
  e.eval_float = {}, e.pdf_float = {}, e.sample_float = {};
  return e;
}

// The variance rule measures a renderer's pixel: at a fixed surface position. Spatial sparsity
// alone (an exact sampler, a glint at one position in 128) is no blow-up, though weights drawn at
// a new position per sample exceed the bound; a sampler whose pdf is near zero where the value is
// not fails by the same decision, and the same sampler with the BRDF's own lobe holds.
TEST(StabilitySweep, VarianceIsMeasuredAtAFixedPosition) {
  const ModelEntry sparse = sparse_positions_model();
  const ModelSweep s = sweep_model(target_of(sparse), Budget::kQuick);
  EXPECT_EQ(stability_verdict(s, DefectClass::kHugeVariance), Verdict::kHolds)
      << describe_failure_region(s);
  double spatial = 0;  // Var(w)/E(w)² of the furnace samples, one position per sample
  std::uint64_t bright = 0;
  for (const SweepMap& m : s.maps)
    for (const CellStats& c : m.cells) {
      if (c.albedo > 0)
        spatial = std::max(spatial, c.albedo_error * c.albedo_error * double(c.samples) /
                                        (c.albedo * c.albedo));
      bright += c.positions_reflecting;
    }
  EXPECT_GT(spatial, kVarianceBlowup);
  EXPECT_GT(bright, 0u);  // some fixed positions reflect, and their variance is measured

  const ModelEntry broken = narrow_sampler_model(32);
  const ModelSweep b = sweep_model(target_of(broken), Budget::kQuick);
  EXPECT_EQ(stability_verdict(b, DefectClass::kHugeVariance), Verdict::kFails)
      << describe_failure_region(b);
  EXPECT_EQ(stability_verdict(b, DefectClass::kBreaks), Verdict::kHolds);
  const ModelEntry near_truth = narrow_sampler_model(1);
  const ModelSweep t = sweep_model(target_of(near_truth), Budget::kQuick);
  EXPECT_EQ(stability_verdict(t, DefectClass::kHugeVariance), Verdict::kHolds)
      << describe_failure_region(t);
}

TEST(StabilitySweep, RawUnclampedValuesAreNotProbabilities) {
  EXPECT_TRUE(is_probability_name("p"));
  EXPECT_TRUE(is_probability_name("p_glint"));
  EXPECT_FALSE(is_probability_name("p_unclamped"));
  EXPECT_FALSE(is_probability_name("pdf"));
}

TEST(StabilitySweep, SmoothModelsAreClean) {
  for (const SweepTarget& t : sweep_targets("smooth_ggx")) {
    if (t.sampler != "vndf") continue;
    const ModelSweep s = sweep_model(t, Budget::kQuick);
    EXPECT_TRUE(s.has_float);
    EXPECT_FALSE(s.has_probability);
    EXPECT_EQ(stability_verdict(s), Verdict::kHolds) << describe_failure_region(s);
    EXPECT_EQ(describe_failure_region(s).rfind("none found", 0), 0u);
  }
}

TEST(StabilitySweep, BackFacingDefectsHoldInRegime) {
  const ModelEntry m = altered(
      "negative_backfacing",
      [](const std::vector<double>&, const ModelQuery<double>& q, ErasedEval& r) {
        if (q.wi.z < 0) r.value = -1;
      },
      no_change);
  const ModelSweep s = sweep_model(target_of(m), Budget::kQuick);
  EXPECT_EQ(stability_verdict(s), Verdict::kHoldsInRegime);
  const std::string region = describe_failure_region(s);
  EXPECT_NE(region.find("negative in value for every α at θi ≥ 90"), std::string::npos) << region;
}

TEST(StabilitySweep, InfNegativeSamplesAndGrazingInfAreDetected) {
  const ModelEntry m = altered(
      "inf_grazing",
      [](const std::vector<double>&, const ModelQuery<double>& q, ErasedEval& r) {
        if (q.wi.z > 0 && q.wi.z < 1e-3) r.pdf = std::numeric_limits<double>::infinity();
      },
      [](const std::vector<double>& v, const ModelQuery<double>&, ModelSample<double>& s) {
        if (v[0] > 1) s.weight = -s.weight - 1;  // a negative weight for α > 1
      });
  const ModelSweep s = sweep_model(target_of(m), Budget::kQuick);
  EXPECT_EQ(stability_verdict(s), Verdict::kFails);  // α > 1 at θi ≤ 89° is the core domain
  const std::string region = describe_failure_region(s);
  EXPECT_NE(region.find("Inf in pdf for every α at θi in [89.95°, 89.999°]"), std::string::npos)
      << region;
  EXPECT_NE(region.find("negative in sample for α ≥ 1.39"), std::string::npos) << region;
}

TEST(StabilitySweep, EnergyGainAndProbabilityAboveOneAreDetected) {
  ModelEntry m = altered(
      "gain_and_p",
      [](const std::vector<double>& v, const ModelQuery<double>&, ErasedEval& r) {
        r.value *= 3;
        r.intermediates[0] = v[0] < 0.01 ? 1.5 : 0.5;  // "p_h_x": a probability > 1 for α < 0.01
      },
      [](const std::vector<double>&, const ModelQuery<double>&, ModelSample<double>& s) {
        s.weight *= 3;
      });
  m.intermediates[0] = "p_h_x";
  EXPECT_TRUE(is_probability_name("p"));
  EXPECT_TRUE(is_probability_name("p_clamped"));
  EXPECT_FALSE(is_probability_name("pdf"));
  const ModelSweep s = sweep_model(target_of(m), Budget::kQuick);
  EXPECT_TRUE(s.has_probability);
  EXPECT_EQ(stability_verdict(s), Verdict::kHolds);  // neither is a NaN/Inf/negative defect
  const std::string region = describe_failure_region(s);
  EXPECT_NE(region.find("energy gain > 1 for"), std::string::npos) << region;
  EXPECT_NE(region.find("p > 1 for α ≤ 0.00693 at every θi"), std::string::npos) << region;
}

TEST(StabilitySweep, FloatOnlyDefectsHoldInRegime) {
  ModelEntry m = find_model("smooth_ggx");
  m.name = "float_nan";
  auto inner = m.eval_float;
  ASSERT_TRUE(inner);
  m.eval_float = [inner](const std::vector<double>& v, const ModelQuery<double>& q) {
    ErasedEval r = inner(v, q);
    r.value = std::numeric_limits<double>::quiet_NaN();
    return r;
  };
  const ModelSweep s = sweep_model({&m, 2, 1, "vndf"}, Budget::kQuick);
  EXPECT_EQ(stability_verdict(s), Verdict::kHoldsInRegime);
  EXPECT_NE(describe_failure_region(s).find("NaN in value (float only)"), std::string::npos);
}

TEST(StabilitySweep, MapsDoNotDependOnTheThreadCount) {
  const SweepTarget t = sweep_targets("smooth_ggx")[0];  // ndf: heavy-tailed weights
  auto sweep_with = [&](std::size_t threads) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, threads);
    return sweep_model(t, Budget::kQuick);
  };
  const ModelSweep a = sweep_with(1), b = sweep_with(2);
  ASSERT_EQ(a.maps.size(), b.maps.size());
  for (std::size_t k = 0; k < a.maps.size(); ++k)
    for (std::size_t i = 0; i < a.maps[k].cells.size(); ++i) {
      const CellStats &x = a.maps[k].cells[i], &y = b.maps[k].cells[i];
      EXPECT_EQ(x.albedo, y.albedo);
      EXPECT_EQ(x.relative_variance, y.relative_variance);
      EXPECT_EQ(x.albedo_uniform, y.albedo_uniform);
      EXPECT_EQ(x.accepted, y.accepted);
    }
  EXPECT_EQ(describe_failure_region(a), describe_failure_region(b));
}

}  // namespace
}  // namespace glintlab::verify::stability

namespace glintlab::verify::stability {
namespace {

bool same_maps(const ModelSweep& a, const ModelSweep& b) {
  if (a.maps.size() != b.maps.size()) return false;
  for (std::size_t k = 0; k < a.maps.size(); ++k)
    for (std::size_t i = 0; i < a.maps[k].cells.size(); ++i) {
      const CellStats &x = a.maps[k].cells[i], &y = b.maps[k].cells[i];
      if (x.evals != y.evals || x.samples != y.samples || x.albedo != y.albedo ||
          x.relative_variance != y.relative_variance || x.value.nan != y.value.nan)
        return false;
    }
  return true;
}

// Within a SweepReuse scope a registered model is swept once (the second call returns the first
// sweep); a copy of the entry (a control's broken model) and a sweep outside the scope are
// measured, and every one of them equals a fresh sweep.
TEST(StabilitySweep, ReuseReturnsTheSameSweepOfARegisteredModelOnly) {
  const ModelEntry& registered = find_model("smooth_beckmann");
  ModelEntry copy = registered;
  const ModelSweep fresh = sweep_model(target_of(registered), Budget::kQuick);
  {
    const SweepReuse reuse;
    const ModelSweep first = sweep_model(target_of(registered), Budget::kQuick);
    EXPECT_EQ(reuse.reused(), 0u);
    const ModelSweep second = sweep_model(target_of(registered), Budget::kQuick);
    EXPECT_EQ(reuse.reused(), 1u);
    (void)sweep_model(target_of(copy), Budget::kQuick);
    (void)sweep_model(target_of(copy), Budget::kQuick);
    EXPECT_EQ(reuse.reused(), 1u);  // copies are never reused
    EXPECT_TRUE(same_maps(fresh, first));
    EXPECT_TRUE(same_maps(fresh, second));
  }
  const SweepReuse later;
  (void)sweep_model(target_of(registered), Budget::kQuick);
  EXPECT_EQ(later.reused(), 0u);  // nothing kept past the scope that measured it
}

bool same_fixed_position_variance(const ModelSweep& a, const ModelSweep& b) {
  for (std::size_t k = 0; k < a.maps.size(); ++k)
    for (std::size_t i = 0; i < a.maps[k].cells.size(); ++i) {
      const CellStats &x = a.maps[k].cells[i], &y = b.maps[k].cells[i];
      if (x.relative_variance != y.relative_variance ||
          x.variance_samples != y.variance_samples ||
          x.positions_reflecting != y.positions_reflecting)
        return false;
    }
  return true;
}

// A sweep without the fixed-position variance measures everything else the same, cannot give the
// variance blow-up a verdict (the spike control is not silently passed), and gets exactly the
// variance a full sweep measures when it is added later, directly or through a SweepReuse.
TEST(StabilitySweep, FixedPositionVarianceAddedLaterIsTheSameAsMeasuredAtOnce) {
  const ModelEntry& registered = find_model("smooth_beckmann");
  const ModelSweep full = sweep_model(target_of(registered), Budget::kQuick);
  ModelSweep partial =
      sweep_model(target_of(registered), Budget::kQuick, {}, FixedPositionVariance::kSkip);
  EXPECT_TRUE(full.has_variance);
  EXPECT_FALSE(partial.has_variance);
  EXPECT_EQ(partial.maps[0].cells[0].variance_samples, 0u);
  EXPECT_EQ(stability_verdict(partial, DefectClass::kHugeVariance), Verdict::kInconclusive);
  EXPECT_NE(describe_failure_region(partial).find("variance not measured"), std::string::npos);
  add_fixed_position_variance(partial, Budget::kQuick);
  EXPECT_TRUE(partial.has_variance);
  EXPECT_TRUE(same_maps(full, partial));
  EXPECT_TRUE(same_fixed_position_variance(full, partial));
  EXPECT_EQ(describe_failure_region(full), describe_failure_region(partial));

  const ModelSweep spikes = sweep_model(target_of(spike_control_model()), Budget::kQuick, {},
                                        FixedPositionVariance::kSkip);
  EXPECT_EQ(stability_verdict(spikes, DefectClass::kHugeVariance), Verdict::kInconclusive);

  const SweepReuse reuse;
  const ModelSweep first =
      sweep_model(target_of(registered), Budget::kQuick, {}, FixedPositionVariance::kSkip);
  EXPECT_FALSE(first.has_variance);
  const ModelSweep second = sweep_model(target_of(registered), Budget::kQuick);
  EXPECT_TRUE(second.has_variance);
  EXPECT_TRUE(same_fixed_position_variance(full, second));
  const ModelSweep third =
      sweep_model(target_of(registered), Budget::kQuick, {}, FixedPositionVariance::kSkip);
  EXPECT_TRUE(third.has_variance);  // the kept sweep has it now
  EXPECT_EQ(reuse.reused(), 2u);
}

}  // namespace
}  // namespace glintlab::verify::stability

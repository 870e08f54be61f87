// The sampler properties of the conformance suite: eval-pdf-consistency, sampler-matches-pdf,
// sampler-covers-value, pdf-normalized and energy (verify/conformance/conformance.h).
#include <fmt/format.h>

#include <boost/math/distributions/chi_squared.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "core/model_layout.h"
#include "core/simd/model_batch.h"
#include "verify/conformance/common.h"
#include "verify/claims/gof_family.h"
#include "verify/stats/chi_square.h"
#include "verify/stability/cell_stats.h"
#include "verify/stability/sweep_plan.h"
#include "verify/stats/mean_tests.h"

namespace glintlab::verify::conformance {
namespace {

using V3 = Vec3<double>;

std::uint64_t samples(Budget b) { return b == Budget::kQuick ? 100'000 : 2'000'000; }

// Samples begin .. end − 1 of `seed` at the setting, one call of the entry's rows function (or a
// loop over its thunk).
std::vector<ModelSample<double>> samples_at(const ModelEntry& m, const Setting& s,
                                            std::uint64_t seed, std::uint64_t begin,
                                            std::uint64_t end) {
  std::vector<Vec2<double>> u(end - begin);
  for (std::uint64_t i = begin; i < end; ++i) u[i - begin] = pair_at(seed, i);
  std::vector<ModelSample<double>> x(u.size());
  sample_each(m, s.values, s.query, u, x);
  return x;
}

bool finite(const V3& w) { return std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z); }

// |a − b| relative to the larger magnitude; 0 when both are 0, infinite when either is not finite.
double relative_difference(double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b)) return std::numeric_limits<double>::infinity();
  const double scale = std::max(std::abs(a), std::abs(b));
  return scale > 0 ? std::abs(a - b) / scale : 0.0;
}

// Two-sided normal p-value of a difference beyond a known error bound: the bound is subtracted
// first (a cubature's estimated error), so the test is conservative against it.
double p_beyond_bound(double difference, double bound, double std_error) {
  const double excess = std::max(0.0, std::abs(difference) - bound);
  if (excess == 0) return 1;
  if (!(std_error > 0)) return 0;
  return std::erfc(excess / std_error / std::numbers::sqrt2);
}

// The smallest relative difference one configuration's z test detects with 90 % power: (z of the
// per-configuration Šidák share of `level`, two-sided, + z of 90 %) standard errors, relative to
// the truth. A property reports its most sensitive configuration's (a wrong input shifts every
// configuration; the property rejects when any does); one whose truth is 0 detects no relative
// difference (infinite).
double detectable_effect(double level, std::size_t configurations, double std_error, double truth) {
  const double per_config = 1 - std::pow(1 - level, 1.0 / double(std::max<std::size_t>(configurations, 1)));
  const double z = normal_quantile(1 - per_config / 2) + normal_quantile(0.9);
  return truth != 0 ? z * std_error / std::abs(truth) : std::numeric_limits<double>::infinity();
}

// A setting's share of n samples (Setting::share), at least 1.
std::uint64_t share_of(std::uint64_t n, const Setting& s) {
  return std::max<std::uint64_t>(1, std::uint64_t(s.share * double(n)));
}

// The smallest effect a property detects with 90 % power, at the defaults' most sensitive setting
// and over the parameter choices' settings (their fewer samples: the least and most sensitive).
struct PowerByConfiguration {
  double defaults = std::numeric_limits<double>::infinity();
  double choices_best = std::numeric_limits<double>::infinity(), choices_worst = 0;
  std::string defaults_where = "—", best_where = "—", worst_where = "—";
  void add(const Setting& s, double d) {
    if (s.share == 1) {
      if (d < defaults) {
        defaults = d;
        defaults_where = s.label;
      }
      return;
    }
    if (d < choices_best) {
      choices_best = d;
      best_where = s.label;
    }
    if (d >= choices_worst) {
      choices_worst = d;
      worst_where = s.label;
    }
  }
  // `effect` formats one detectable effect.
  template <class F>
  std::string describe(F effect) const {
    std::string out = fmt::format("{} ({})", effect(defaults), defaults_where);
    if (choices_worst > 0 || std::isfinite(choices_best))
      out += fmt::format("; per parameter-choice configuration: {} ({}) to {} ({})",
                         effect(choices_best), best_where, effect(choices_worst), worst_where);
    return out;
  }
};

// The sample mean of the weight (non-finite weights count as a hard failure) and the share of
// samples the sampler rejected or placed below the horizon.
struct WeightStats {
  MeanAccumulator weight;
  std::uint64_t accepted_above = 0, non_finite = 0;
};
WeightStats weight_stats(const ModelEntry& m, const Setting& s, std::uint64_t n,
                         std::uint64_t seed) {
  std::vector<WeightStats> parts(chunk_count(n));
  for_chunks(n, [&](std::uint64_t begin, std::uint64_t end, std::size_t c) {
    WeightStats& w = parts[c];
    for (const ModelSample<double>& x : samples_at(m, s, seed, begin, end)) {
      const double weight = x.rejected ? 0.0 : x.weight;
      if (!std::isfinite(weight)) {
        ++w.non_finite;
        w.weight.add(0);
        continue;
      }
      w.weight.add(weight);
      if (!x.rejected && finite(x.wo) && x.wo.z > 0) ++w.accepted_above;
    }
  });
  WeightStats all;
  for (const WeightStats& w : parts) {
    all.weight.merge(w.weight);
    all.accepted_above += w.accepted_above;
    all.non_finite += w.non_finite;
  }
  return all;
}

}  // namespace

// ---- eval-pdf-consistency ------------------------------------------------------------------------

// Every sample's pdf equals pdf() at its ωo, eval's pdf equals pdf(), and its weight equals
// value/pdf there; a rejected sample weighs 0. Deterministic: the largest relative difference over
// every sample of every setting, held to 1e-6 (the two paths compute the same expressions in a
// different order: double rounding is below 1e-12; a pdf 3 % off is 3e-2).
Assessment assess_eval_pdf(const ModelEntry& m, Budget b, const std::string& id, double) {
  constexpr double kTolerance = 1e-6;
  const std::uint64_t n_defaults = b == Budget::kQuick ? 4096 : 65536;
  Assessment a;
  a.statistic = "largest relative difference of sample pdf / eval pdf / weight from pdf() and "
                "value/pdf at the sampled ωo";
  a.bound = kTolerance;
  double worst = 0;
  std::string where = "—";
  auto set = settings(m, b);
  for (Setting& s : compensation_settings(m)) set.push_back(std::move(s));
  const std::size_t base = set.size();
  std::string left_out;
  const std::vector<Setting> choices = variant_settings(m, b, "eval-pdf-consistency", &left_out);
  set.insert(set.end(), choices.begin(), choices.end());
  std::uint64_t total = 0;
  for (std::size_t k = 0; k < set.size(); ++k) {
    const Setting& s = set[k];
    const std::uint64_t seed = check_seed(id, k);
    const std::uint64_t n = share_of(n_defaults, s);
    total += n;
    struct Part {
      double worst = 0;
      std::string what;
    };
    std::vector<Part> parts(chunk_count(n));
    for_chunks(n, [&](std::uint64_t begin, std::uint64_t end, std::size_t c) {
      Part& p = parts[c];
      auto note = [&](double d, const char* what) {
        if (d > p.worst) {
          p.worst = d;
          p.what = what;
        }
      };
      // The chunk's samples, then pdf() and eval at the sampled ωo of those that are samples.
      const std::vector<ModelSample<double>> xs = samples_at(m, s, seed, begin, end);
      std::vector<ModelQuery<double>> at;
      for (const ModelSample<double>& x : xs) {
        if (x.rejected || !finite(x.wo) || !(x.pdf > 0)) continue;  // "no sample"
        ModelQuery<double> q = s.query;
        q.wo = x.wo;
        at.push_back(q);
      }
      std::vector<double> pdfs(at.size());
      std::vector<ErasedEval> evals(at.size());
      pdf_each(m, s.values, at, pdfs);
      eval_each(m, s.values, at, evals);
      std::size_t next = 0;
      for (const ModelSample<double>& x : xs) {
        if (x.rejected) {
          note(x.weight == 0 ? 0.0 : 1.0, "a rejected sample with a nonzero weight");
          continue;
        }
        if (!finite(x.wo) || !(x.pdf > 0)) continue;
        const double pdf = pdfs[next];
        const ErasedEval& e = evals[next++];
        note(relative_difference(x.pdf, pdf), "sample pdf vs pdf()");
        note(relative_difference(e.pdf, pdf), "eval pdf vs pdf()");
        note(relative_difference(x.weight, pdf > 0 ? e.value / pdf : 0.0), "weight vs value/pdf");
      }
    });
    for (const Part& p : parts)
      if (p.worst > worst) {
        worst = p.worst;
        where = fmt::format("{} ({})", p.what, s.label);
      }
  }
  a.value = worst;
  a.configurations = int(set.size());
  a.verdict = worst <= kTolerance ? Verdict::kHolds : Verdict::kFails;
  a.power = fmt::format("deterministic at the sampled directions: any relative difference above "
                        "{:g} at one of the {} sampled ωo is detected ({} per setting at the "
                        "defaults, {} per parameter-choice setting)",
                        kTolerance, total, n_defaults, std::max<std::uint64_t>(1, std::uint64_t(variant_share(m) * double(n_defaults))));
  a.detail = fmt::format("{} settings ({}) × {} samples: largest relative difference {:.3g} (bound "
                         "{:g}){}",
                         set.size(), describe_configurations(base, choices, left_out), n_defaults,
                         worst, kTolerance, worst > 0 ? fmt::format(", at {}", where) : "");
  return a;
}

// ---- sampler-matches-pdf -------------------------------------------------------------------------

// Chi-square of the sampled ωo against pdf() on the sphere (verify/generic/model_sampler_gof.h),
// each setting a configuration, Holm–Šidák at the model's level.
namespace {
std::uint64_t gof_samples(Budget b) { return b == Budget::kQuick ? 100'000 : 2'000'000; }

// model_sampler_chi_square's test with the cubature held to what the sample count needs: 64
// coarse bins, the per-bin tolerance 0.1 counts (against ~1500 expected per bin the statistic
// moves by far less than one count; an unresolved bin is reported inconclusive, never decided)
// and, at the quick budget, no fine resolution. A glint model's pdf() can cost 10–100 µs (Kemppinen's
// marginal density, a total-area integral per call), and the default 1e-7 relative tolerance
// over 256 fine bins made one configuration take a minute.
// The model's pdf at many ωo through its SIMD batch (core/simd/model_batch.h eval_batch in double
// on simd::default_isa()): eval's pdf column, which every built-in model computes with its pdf
// template, so within the batches' equivalence budgets of m.pdf. The parameters are resolved once
// per call, where the thunk resolves them per direction (Kneiphof & Klein's total area: an
// azimuthal integral). Only for a registered entry (a control's copy replaces thunks that the
// batch would not see), or with_pdf_scaled's copy of one, as that entry's batch × the scale.
DirectionPdfRows batch_pdf_rows(const ModelEntry& m, const Setting& s) {
  static const std::size_t wo_column = [] {
    for (std::size_t k = 0; k < kQueryLayout.size(); ++k)
      if (kQueryLayout[k].name == "wo_x") return k;
    throw std::logic_error("the query layout has no wo_x column");
  }();
  return [&m, &s, row = to_row(s.query), isa = simd::default_isa()](std::span<const V3> w,
                                                                    std::span<double> out) {
    const std::size_t n = w.size();
    std::vector<double> wo(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
      wo[i] = w[i].x;
      wo[n + i] = w[i].y;
      wo[2 * n + i] = w[i].z;
    }
    std::vector<simd::Column<double>> query;
    for (const double& v : row) query.push_back({&v, 0});
    for (std::size_t d = 0; d < 3; ++d) query[wo_column + d] = {wo.data() + d * n, 1};
    std::vector<double> columns((2 + m.intermediates.size()) * n);
    std::vector<double*> outputs;
    for (std::size_t k = 0; k < 2 + m.intermediates.size(); ++k) outputs.push_back(columns.data() + k * n);
    simd::eval_batch(m, s.values, query, outputs, n, isa);
    std::copy(outputs[1], outputs[1] + n, out.begin());
  };
}

ChiSquareResult sampler_chi_square(const ModelEntry& m, const Setting& setting, std::uint64_t seed,
                                   Budget b) {
  // At the sweep's footprint 1e-3, not the settings' 0.1: there a glint model's pdf has thousands
  // of peaks of the microroughness' width, and the cubature of the bins' expectations took
  // minutes per setting (Kemppinen). The sampler and pdf are the same functions of the footprint.
  Setting s = setting;
  if (m.needs & kNeedsFootprint) {
    s.query.footprint.duv_dx = {stability::kDefaultFootprint, 0};
    s.query.footprint.duv_dy = {0, stability::kDefaultFootprint};
    if (m.needs & kNeedsPixelCorners)
      s.query.footprint.corner_r =
          stability::pixel_corner_reflections(s.query.wi, stability::kDefaultFootprint);
  }
  ChiSquareOptions o = reflection_options(s.query.wi);
  o.fine_max_bins = b == Budget::kQuick ? 0 : 1024;
  o.coarse_bins = 64;
  o.rel_tol = 1e-4;
  o.abs_tol_counts = 0.1;
  o.max_subdivisions = 60;
  const DirectionPdf pdf = [&m, &s](const V3& wo) {
    ModelQuery<double> q = s.query;
    q.wo = wo;
    return m.pdf(s.values, q);
  };
  if (m.pdf_rows)
    o.direction_pdf_rows = [&m, &s](std::span<const V3> w, std::span<double> out) {
      std::vector<ModelQuery<double>> at(w.size(), s.query);
      for (std::size_t i = 0; i < w.size(); ++i) at[i].wo = w[i];
      pdf_each(m, s.values, at, out);
    };
  else if (is_registered(m) && simd::is_batched(m))
    o.direction_pdf_rows = batch_pdf_rows(m, s);
  else if (const ScaledPdf* scaled = m.pdf.target<ScaledPdf>();
           scaled && scaled->registered && !scaled->registered->pdf_rows &&
           simd::is_batched(*scaled->registered))
    o.direction_pdf_rows = [f = batch_pdf_rows(*scaled->registered, s), c = scaled->scale](
                               std::span<const V3> w, std::span<double> out) {
      f(w, out);
      for (double& v : out) v = c * v;
    };
  const ChiSquarePlan plan =
      plan_direction_chi_square(SampleDomain::kSphere, pdf, share_of(gof_samples(b), s), o);
  return run_direction_chi_square(
      plan, DirectionBatchSampler([&](std::uint64_t begin, std::size_t count, V3* out) {
        const std::vector<ModelSample<double>> x = samples_at(m, s, seed, begin, begin + count);
        for (std::size_t k = 0; k < count; ++k) out[k] = x[k].wo;
      }));
}

// The weighted histogram (Mitsuba 3's chi2 test runs it with weighted sample counts): the sum of
// the weights value/pdf of the samples landing in a cell, over n, estimates ∫_cell value dωo, and
// is tested against that integral (the mirror mixture's Monte Carlo, independent draws), so the
// sampler is checked against what it estimates, not only against its own pdf. Per cell
// z = (weighted − reference) / (their standard errors in quadrature); cells with fewer than 20
// nonzero contributions on either side are pooled into one, tested when both sides have 20 there
// (a cell the sampler rarely reached has no standard error to test with: smooth_beckmann's
// far tail holds 3e-8 of the value, 0.003 expected samples in 10^5).
// Value where the sampler never goes is tested apart, whatever its cells: the model's own pdf
// says where that is. At the reference's draws, Z = the value mass where eval's pdf is 0 (value
// > 0, pdf == 0: the sampler, by its pdf, never draws there, so its estimate of that mass is 0 by
// construction) with its Monte Carlo standard error; one more term (0 − Z)² / SE_Z² with one
// more degree of freedom, and none when no reference draw lands there. A sampler whose pdf is > 0
// wherever the value is adds nothing: the term has no tolerance and cannot fire on a correct
// model. Where the pdf is > 0 but small (a region the sampler rarely reaches) the estimate is
// unbiased, only spread: that is the weights' variance, not a mass this test can miss.
// The statistic Σ z² is chi-square with one degree of freedom per cell tested (and one for Z).
// The reference takes two blocks of draws (its per-cell spread is 2–3 × the
// sampler's; more cost a glint model's eval time for little: the test's power against a global
// scale is covers-value's). At the settings' footprint (a glint model's value at
// the sweep's is ~0 almost everywhere, which tests nothing).
struct WeightedHistogram {
  double statistic = 0, p_value = 1;
  std::size_t cells = 0;
  std::uint64_t non_finite = 0;
  // ∫ value dωo where eval's pdf is 0 (Z), its standard error, and how many of the reference's
  // draws landed there (0: no term).
  double unreached = 0, unreached_se = 0;
  std::uint64_t unreached_draws = 0, reference_draws = 0;
  // Whether every cell's ∫_cell value is finite; false: nothing is tested (eval's value is NaN or
  // Inf where the reference draws it, and the property cannot be computed).
  bool reference_finite = true;
};
WeightedHistogram weighted_histogram(const ModelEntry& m, const Setting& s, Budget b,
                                     std::uint64_t sampler_seed, std::uint64_t reference_seed) {
  const std::uint64_t n = share_of(gof_samples(b), s);
  const double width = roughness_hint(m, s.values);
  const MirrorCells cells(s.query.wi, width);
  // The value, and the value where eval's pdf is 0, at the same draws.
  const CellSumPair integrals = integrate_cell_pair(
      [&](std::span<const V3> wo, std::span<double> value, std::span<double> unreached) {
        values_and_pdfs_at(m, s.values, s.query, wo, value, unreached);
        for (std::size_t i = 0; i < wo.size(); ++i)
          unreached[i] = value[i] > 0 && unreached[i] == 0 ? value[i] : 0.0;
      },
      s.query.wi, width, share_of(2 * reference_block(b), s), reference_seed);
  const CellSums& reference = integrals.first;
  WeightedHistogram h;
  for (std::size_t k = 0; k < MirrorCells::kCount; ++k)
    h.reference_finite = h.reference_finite && std::isfinite(reference.sum[k]);
  if (!h.reference_finite) return h;
  std::vector<CellSums> parts(chunk_count(n));
  std::vector<std::uint64_t> non_finite(parts.size(), 0);
  for_chunks(n, [&](std::uint64_t begin, std::uint64_t end, std::size_t c) {
    CellSums& p = parts[c];
    for (const ModelSample<double>& x : samples_at(m, s, sampler_seed, begin, end)) {
      if (x.rejected || x.weight == 0) continue;
      if (!std::isfinite(x.weight) || !finite(x.wo)) {
        ++non_finite[c];
        continue;
      }
      const std::size_t k = cells.cell(x.wo);
      p.sum[k] += x.weight;
      p.sum_sq[k] += x.weight * x.weight;
      ++p.hits[k];
    }
  });
  CellSums weighted;
  for (std::size_t c = 0; c < parts.size(); ++c) {
    h.non_finite += non_finite[c];
    for (std::size_t k = 0; k < MirrorCells::kCount; ++k) {
      weighted.sum[k] += parts[c].sum[k];
      weighted.sum_sq[k] += parts[c].sum_sq[k];
      weighted.hits[k] += parts[c].hits[k];
    }
  }
  // Mean and squared standard error of the per-draw contribution y over `draws` (zeros included).
  auto mean_se2 = [](double sum, double sum_sq, std::uint64_t draws) {
    const double d = double(draws), mean = sum / d;
    return std::pair{mean, std::max(0.0, sum_sq / d - mean * mean) / (d - 1)};
  };
  auto add_z2 = [&](double ws, double wss, double rs, double rss) {
    const auto [wm, wv] = mean_se2(ws, wss, n);
    const auto [rm, rv] = mean_se2(rs, rss, reference.n);
    h.statistic += wv + rv > 0 ? (wm - rm) * (wm - rm) / (wv + rv) : (wm == rm ? 0.0 : INFINITY);
    ++h.cells;
  };
  constexpr std::uint64_t kMinHits = 20;
  double pool[4] = {0, 0, 0, 0};
  std::uint64_t pool_hits[2] = {0, 0};
  for (std::size_t k = 0; k < MirrorCells::kCount; ++k) {
    if (weighted.hits[k] >= kMinHits && reference.hits[k] >= kMinHits) {
      add_z2(weighted.sum[k], weighted.sum_sq[k], reference.sum[k], reference.sum_sq[k]);
      continue;
    }
    pool[0] += weighted.sum[k];
    pool[1] += weighted.sum_sq[k];
    pool[2] += reference.sum[k];
    pool[3] += reference.sum_sq[k];
    pool_hits[0] += weighted.hits[k];
    pool_hits[1] += reference.hits[k];
  }
  if (pool_hits[0] >= kMinHits && pool_hits[1] >= kMinHits)
    add_z2(pool[0], pool[1], pool[2], pool[3]);
  // The unreached mass against the sampler's 0 there (a draw lands in one cell: the cells' sums
  // of y and y² add up to the whole region's).
  double unreached_sum = 0, unreached_sum_sq = 0;
  for (std::size_t k = 0; k < MirrorCells::kCount; ++k) {
    unreached_sum += integrals.second.sum[k];
    unreached_sum_sq += integrals.second.sum_sq[k];
    h.unreached_draws += integrals.second.hits[k];
  }
  h.reference_draws = reference.n;
  if (h.unreached_draws > 0) {
    const auto [z, z_se2] = mean_se2(unreached_sum, unreached_sum_sq, reference.n);
    h.unreached = z;
    h.unreached_se = std::sqrt(z_se2);
    h.statistic += z_se2 > 0 ? z * z / z_se2 : (z == 0 ? 0.0 : INFINITY);
    ++h.cells;
  }
  h.p_value = h.non_finite > 0 ? 0.0
              : h.cells == 0   ? 1.0
                               : boost::math::cdf(boost::math::complement(
                                     boost::math::chi_squared_distribution<double>(double(h.cells)),
                                     std::min(h.statistic, 1e300)));
  return h;
}
}  // namespace

Assessment assess_sampler_gof(const ModelEntry& m, Budget b, const std::string& id,
                              double level) {
  Assessment a;
  a.statistic = "Holm–Šidák-adjusted p of the chi-square of sampled ωo against pdf() and of the "
                "weighted histogram (value/pdf per cell against ∫_cell value)";
  // Quick: the θi = 70° setting only (the cubature of a glint model's pdf dominates the suite's
  // time); full: every setting, and the weighted histogram also at the compensation settings (the
  // chi-square moves every footprint to the sweep's, where they would repeat the others). Not at
  // quick: the three histograms took 2–6 × the property's time there (Kemppinen), and
  // sampler-covers-value checks the same settings. The parameter choices (common.h) get both
  // tests, after the defaults'.
  auto set = settings(m, b);
  if (b == Budget::kQuick) set.erase(set.begin());
  const std::size_t chi_defaults = set.size();
  if (b == Budget::kFull)
    for (Setting& s : compensation_settings(m)) set.push_back(std::move(s));
  const std::size_t base = set.size();
  std::string left_out;
  const std::vector<Setting> choices = variant_settings(m, b, "sampler-matches-pdf", &left_out);
  set.insert(set.end(), choices.begin(), choices.end());
  // Which settings get the chi-square: the defaults', and the parameter choices' of models without
  // a footprint. A footprint model's chi-square is the cubature of a glint pdf() (10–100 µs a
  // call) over 64 bins, 10–20 s a setting (Kemppinen), which for every choice would multiply the
  // suite's time; its choices get the weighted histogram, which tests the weights value/pdf per
  // cell against ∫_cell value and counts the value where the pdf is 0 (a sampler whose draws do
  // not follow its pdf gets weights that miss the value per cell).
  const bool chi_at_choices = !(m.needs & kNeedsFootprint);
  auto has_chi = [&](std::size_t k) { return k < chi_defaults || (chi_at_choices && k >= base); };
  std::size_t inconclusive = 0, hard = 0;
  std::vector<ChiSquareResult> results;
  std::vector<std::size_t> chi_setting;  // chi-square i ran at set[chi_setting[i]]
  std::vector<WeightedHistogram> weighted;
  std::vector<double> chi_p, weighted_p;
  std::size_t worst = 0, worst_weighted = 0;
  for (std::size_t k = 0; k < set.size(); ++k) {
    // The defaults' seeds: the chi-square's k, the weighted histogram's chi_defaults + 2k, + 1;
    // a parameter choice's 1000 + 3k, + 1, + 2.
    const bool choice = k >= base;
    if (has_chi(k)) {
      results.push_back(sampler_chi_square(m, set[k], check_seed(id, choice ? 1000 + 3 * k : k), b));
      const ChiSquareResult& r = results.back();
      chi_setting.push_back(k);
      chi_p.push_back(r.hard_fail ? 0.0 : r.p_value);
      inconclusive += r.inconclusive && !r.hard_fail ? 1 : 0;
      hard += r.hard_fail ? 1 : 0;
      if (chi_p.back() < chi_p[worst]) worst = chi_p.size() - 1;
    }
    weighted.push_back(weighted_histogram(
        m, set[k], b, check_seed(id, choice ? 1001 + 3 * k : chi_defaults + 2 * k),
        check_seed(id, choice ? 1002 + 3 * k : chi_defaults + 2 * k + 1)));
    weighted_p.push_back(weighted.back().p_value);
    if (!weighted.back().reference_finite && a.non_finite.empty())
      a.non_finite = fmt::format("∫_cell value dωo of the weighted histogram at {} is not finite "
                                 "(eval's value is not finite there)",
                                 set[k].label);
    if (weighted_p[k] < weighted_p[worst_weighted]) worst_weighted = k;
  }
  a.raw_p_values = chi_p;
  a.raw_p_values.insert(a.raw_p_values.end(), weighted_p.begin(), weighted_p.end());
  const FamilyOutcome f = family_at(a.raw_p_values, level);
  a.p_value = f.min_adjusted;
  a.value = f.min_adjusted;
  a.configurations = int(a.raw_p_values.size());
  a.verdict = hard > 0 || f.any_rejected ? Verdict::kFails
              : inconclusive > 0         ? Verdict::kInconclusive
                                         : Verdict::kHolds;
  // The chi-square's power: its coarse resolution's δ90 (a pdf off by a relative δ throughout,
  // detected with 90 % power; chi_square.h) and the same δ confined to one cell, at the most
  // sensitive setting of the defaults and over the parameter choices'.
  PowerByConfiguration global, one_cell;
  for (std::size_t i = 0; i < results.size(); ++i) {
    if (results[i].resolutions.empty()) continue;
    const ChiSquareResolution& coarse = results[i].resolutions.front();
    if (coarse.detectable_global > 0) {
      global.add(set[chi_setting[i]], coarse.detectable_global);
      one_cell.add(set[chi_setting[i]], coarse.detectable_one_cell);
    }
  }
  const auto relative = [](double d) {
    return std::isfinite(d) ? fmt::format("{:.2g}", d) : std::string("—");
  };
  a.power = std::isfinite(global.defaults)
                ? fmt::format("chi-square: a pdf off by a relative {}; or in one cell by {}",
                              global.describe(relative), one_cell.describe(relative))
                : std::string("not stated: no chi-square setting at the defaults was conclusive");
  const WeightedHistogram& w = weighted[worst_weighted];
  // Which of the two tests rejected (a control's detail says what caught it).
  std::size_t chi_rejected = 0, weighted_rejected = 0;
  for (std::size_t k = 0; k < f.reject.size(); ++k)
    (k < chi_p.size() ? chi_rejected : weighted_rejected) += f.reject[k] ? 1 : 0;
  a.detail = fmt::format(
      "{} settings ({}) × {} samples, chi-square and weighted histogram each{}{}: {} rejected at "
      "level {:.3g} (chi-square {}, weighted histogram {}), {} hard failures, {} inconclusive; "
      "chi-square: smallest raw p {:.3g} at {} ({}); "
      "weighted histogram: smallest raw p {:.3g} at {} (Σ z² {:.4g} over {} cells{}; value "
      "mass where eval's pdf is 0: {})",
      chi_setting.size(), describe_configurations(chi_defaults, choices, left_out),
      gof_samples(b),
      base > chi_defaults
          ? fmt::format(", and {} compensation settings weighted histogram only",
                        base - chi_defaults)
          : "",
      !chi_at_choices && !choices.empty()
          ? ", the parameter choices weighted histogram only (footprint model)"
          : "",
      f.rejections, level, chi_rejected, weighted_rejected, hard, inconclusive, chi_p[worst],
      set[chi_setting[worst]].label, results[worst].summary(), weighted_p[worst_weighted],
      set[worst_weighted].label, w.statistic, w.cells,
      w.non_finite ? fmt::format(", {} non-finite weights", w.non_finite) : "",
      w.unreached_draws > 0
          ? fmt::format("{:.4g} ± {:.2g} ({} of {} reference draws)", w.unreached,
                        w.unreached_se, w.unreached_draws, w.reference_draws)
          : fmt::format("none ({} reference draws)", w.reference_draws));
  return a;
}

// ---- sampler-covers-value ------------------------------------------------------------------------

// The sample mean of the weight estimates ∫ value dωo; the cubature of value (about the mirror
// direction, error estimate included) is the truth. A sampler whose pdf is 0 where the value is
// not misses that part, even when it matches its own pdf.
// The settings of sampler-covers-value (and energy): footprint models also at the wide footprint
// (common.h): quick moves its first setting there (kneiphof_klein's value is 0 everywhere at
// θi = 30° and footprint 0.1: it tested nothing), full adds every setting there; and where the
// compensation the paper's sampler leaves out carries the value (common.h).
std::vector<Setting> value_settings(const ModelEntry& m, Budget b) {
  auto set = settings(m, b);
  if (m.needs & kNeedsFootprint) {
    auto widened = [&m](const Setting& s) {
      return Setting{s.values, make_query(m, s.theta_deg, kWideFootprint), s.theta_deg,
                     fmt::format("{}, footprint {:g}", s.label, kWideFootprint)};
    };
    if (b == Budget::kQuick)
      set.front() = widened(set.front());
    else
      for (std::size_t k = 0, base = set.size(); k < base; ++k) set.push_back(widened(set[k]));
  }
  for (Setting& s : compensation_settings(m)) set.push_back(std::move(s));
  return set;
}

Assessment assess_covers_value(const ModelEntry& m, Budget b, const std::string& id,
                               double level, const std::vector<HemisphereIntegral>* reuse) {
  std::vector<Setting> set = value_settings(m, b);
  // And at the parameter choices (common.h), after these.
  std::string left_out;
  const std::size_t base = set.size();
  const std::vector<Setting> choices = variant_settings(m, b, "sampler-covers-value", &left_out);
  set.insert(set.end(), choices.begin(), choices.end());
  Assessment a = covers_value_at(m, set, b, id, level, reuse);
  a.detail += fmt::format("; configurations: {}", describe_configurations(base, choices, left_out));
  return a;
}

Assessment covers_value_at(const ModelEntry& m, const std::vector<Setting>& set, Budget b,
                           const std::string& id, double level,
                           const std::vector<HemisphereIntegral>* reuse) {
  Assessment a;
  a.statistic = "largest relative difference of the mean weight from ∫ value dωo (cubature; z "
                "test, p Holm–Šidák-adjusted)";
  PowerByConfiguration power;
  double worst_rel = 0;
  std::string where = "—";
  std::uint64_t non_finite = 0;
  // The settings at the full sample count (the defaults') come first; the parameter choices'
  // (Setting::share < 1) after them.
  std::size_t base = 0;
  while (base < set.size() && set[base].share == 1) ++base;
  for (std::size_t k = 0; k < set.size(); ++k) {
    const Setting& s = set[k];
    const std::uint64_t n = share_of(samples(b), s);
    // The suite's integral of the value at this setting (shared with energy; a parameter
    // choice's with its share of the draws).
    const HemisphereIntegral c = reuse && k < reuse->size() ? (*reuse)[k] : value_integral(m, s, b);
    a.references.push_back(c);
    if (!std::isfinite(c.value) && a.non_finite.empty())
      a.non_finite = fmt::format("∫ value dωo at {} is {} (eval's value is not finite there)",
                                 s.label, c.value);
    const WeightStats w = weight_stats(m, s, n, check_seed(id, k));
    non_finite += w.non_finite;
    const double weight_se = std::sqrt(w.weight.variance() / double(n));
    double se = weight_se, bound = c.error;
    if (c.monte_carlo) {  // two independent estimates: their errors add in quadrature
      se = std::hypot(se, c.error);
      bound = 0;
    }
    a.raw_p_values.push_back(w.non_finite ? 0.0 : p_beyond_bound(w.weight.mean - c.value, bound, se));
    power.add(s, detectable_effect(level, set.size(), se, c.value));
    const double rel = c.value > 0 ? (w.weight.mean - c.value) / c.value : w.weight.mean;
    if (std::abs(rel) >= std::abs(worst_rel)) {
      worst_rel = rel;
      where = fmt::format("{}: mean weight {:.5g} ± {:.2g}, ∫ value {:.5g} ± {:.2g}{}", s.label,
                          w.weight.mean, weight_se, c.value, c.error,
                          c.monte_carlo ? " (Monte Carlo estimate)" : " (cubature)");
    }
  }
  const FamilyOutcome f = family_at(a.raw_p_values, level);
  a.p_value = f.min_adjusted;
  a.value = worst_rel;
  a.configurations = int(set.size());
  a.verdict = f.any_rejected ? Verdict::kFails : Verdict::kHolds;
  a.power = fmt::format("a relative difference of ∫ value beyond the cubature's error of {}",
                        power.describe([](double d) { return fmt::format("{:.2g} %", 100 * d); }));
  a.detail = fmt::format("{} settings × {} samples: {} rejected at level {:.3g}{}; largest "
                         "relative difference {:+.3g} ({})",
                         set.size(), samples(b), f.rejections, level,
                         non_finite ? fmt::format(", {} non-finite weights", non_finite) : "",
                         worst_rel, where);
  return a;
}

// ---- pdf-normalized ------------------------------------------------------------------------------

// ∫ pdf dωo over the upper hemisphere (cubature) = the measured share of samples the sampler
// accepts above the horizon, 1 − (rejection rate).
Assessment assess_pdf_normalized(const ModelEntry& m, Budget b, const std::string& id,
                                 double level) {
  Assessment a;
  a.statistic = "largest difference of ∫ pdf dωo (ωo_z > 0) from the acceptance rate above the "
                "horizon (z test, p Holm–Šidák-adjusted)";
  auto set = settings(m, b);
  const std::size_t base = set.size();
  std::string left_out;
  const std::vector<Setting> choices = variant_settings(m, b, "pdf-normalized", &left_out);
  set.insert(set.end(), choices.begin(), choices.end());
  double worst = 0;
  PowerByConfiguration power;
  std::string where = "—";
  for (std::size_t k = 0; k < set.size(); ++k) {
    const Setting& s = set[k];
    const std::uint64_t n = share_of(samples(b), s);
    const HemisphereIntegral c = integrate_hemisphere(
        m,
        [&](std::span<const V3> wo, std::span<double> out) {
          std::vector<ModelQuery<double>> at(wo.size(), s.query);
          for (std::size_t i = 0; i < wo.size(); ++i) at[i].wo = wo[i];
          pdf_each(m, s.values, at, out);
        },
        s.query.wi, roughness_hint(m, s.values), b,
        check_seed(id, k < base ? base + k : 1000 + k), s.share);
    if (!std::isfinite(c.value) && a.non_finite.empty())
      a.non_finite = fmt::format("∫ pdf dωo at {} is {} (pdf() is not finite there)", s.label,
                                 c.value);
    const WeightStats w = weight_stats(m, s, n, check_seed(id, k));
    const double accept = double(w.accepted_above) / double(n);
    // The binomial standard error, at least that of one sample in n (no rejection seen).
    const double accept_se = std::max(std::sqrt(accept * (1 - accept) / double(n)), 1.0 / double(n));
    double se = accept_se, bound = c.error;
    if (c.monte_carlo) {
      se = std::hypot(se, c.error);
      bound = 0;
    }
    a.raw_p_values.push_back(p_beyond_bound(c.value - accept, bound, se));
    power.add(s, detectable_effect(level, set.size(), se, accept));
    if (std::abs(c.value - accept) >= std::abs(worst)) {
      worst = c.value - accept;
      where = fmt::format("{}: ∫ pdf {:.5g} ± {:.2g}, accepted {:.5g} ± {:.2g}", s.label, c.value,
                          c.error, accept, accept_se);
    }
  }
  const FamilyOutcome f = family_at(a.raw_p_values, level);
  a.p_value = f.min_adjusted;
  a.value = worst;
  a.configurations = int(set.size());
  a.verdict = f.any_rejected ? Verdict::kFails : Verdict::kHolds;
  a.power = fmt::format("a relative difference between ∫ pdf and the acceptance rate beyond the "
                        "cubature's error of {}",
                        power.describe([](double d) { return fmt::format("{:.2g} %", 100 * d); }));
  a.detail = fmt::format("{} settings ({}) × {} samples: {} rejected at level {:.3g}; largest "
                         "difference {:+.3g} ({})",
                         set.size(), describe_configurations(base, choices, left_out), samples(b),
                         f.rejections, level, worst, where);
  return a;
}

// ---- energy --------------------------------------------------------------------------------------

// White furnace: the albedo ∫ value dωo (over the light's solid angle for area-light models, as
// the stability sweep's furnace), tested one-sided against 1 at every setting (a grid over θi
// that reaches grazing at the full budget). The integral is the suite's own (integrate_hemisphere,
// the truth of sampler-covers-value and of compare's albedo curves), never the model's sampler:
// energy is a property of eval, and a sampler that misses part of the lobe would hide a gain
// there. Cubature (models without a footprint) is decided against its error estimate; the Monte
// Carlo integral (footprint models) by a one-sided z test on its standard error.
// (The integrals are seeded per setting by value_integral, not by the check's id.)
Assessment assess_energy(const ModelEntry& m, Budget b, const std::string& /*id*/,
                         double level) {
  Assessment a;
  a.statistic = "largest white-furnace albedo ∫ value dωo (/ light solid angle), by the suite's "
                "hemisphere integral";
  // sampler-covers-value's settings (their integrals are shared), and grazing incidence, where
  // energy gain of microfacet models shows first.
  auto set = value_settings(m, b);
  set.push_back({set.front().values, make_query(m, 85, kFootprint), 85,
                 "defaults, θi=85°"});
  double max_albedo = -1, power = std::numeric_limits<double>::infinity();
  std::string where = "—", power_where = "—";
  const double per_setting = 1 - std::pow(1 - level, 1.0 / double(set.size()));
  for (std::size_t k = 0; k < set.size(); ++k) {
    const Setting& s = set[k];
    const HemisphereIntegral c = value_integral(m, s, b);
    if (!std::isfinite(c.value) && a.non_finite.empty())
      a.non_finite = fmt::format("∫ value dωo at {} is {} (eval is not finite there)", s.label,
                                 c.value);
    const double omega = stability::furnace_light_solid_angle(m, s.values, s.query);
    const double scale = omega > 0 ? 1 / omega : 1.0;
    const double albedo = c.value * scale, error = c.error * scale;
    double p = 0, detectable = 0;
    if (c.monte_carlo) {
      // One-sided: only an albedo above 1 is a violation.
      const double z = error > 0 ? (albedo - 1) / error : (albedo > 1 ? INFINITY : -INFINITY);
      p = 0.5 * std::erfc(z / std::numbers::sqrt2);
      // The detectable excess over 1: (z of the per-setting level + z of 90 %) SE.
      detectable = (normal_quantile(1 - per_setting) + normal_quantile(0.9)) * error;
    } else {
      // Deterministic: above 1 by more than the cubature resolves (its error estimate, at least
      // the relative tolerance it was asked for) is a violation.
      detectable = std::max(error, cubature_rel_tol(b) * std::abs(albedo));
      p = albedo - 1 > detectable ? 0.0 : 1.0;
    }
    a.raw_p_values.push_back(std::isfinite(albedo) ? p : 0.0);
    // A setting where the value is exactly 0 everywhere drawn has nothing to gain: no power.
    if (!(c.value == 0 && c.error == 0) && detectable < power) {
      power = detectable;
      power_where = s.label;
    }
    if (albedo > max_albedo) {
      max_albedo = albedo;
      where = fmt::format("{} (± {:.2g}, {})", s.label, error,
                          c.monte_carlo ? "Monte Carlo SE" : "cubature error");
    }
  }
  const FamilyOutcome f = family_at(a.raw_p_values, level);
  a.p_value = f.min_adjusted;
  a.value = max_albedo;
  a.bound = 1;
  a.configurations = int(set.size());
  a.verdict = f.any_rejected ? Verdict::kFails : Verdict::kHolds;
  a.power = fmt::format("an albedo {:.2g} above 1 ({})", power, power_where);
  a.detail = fmt::format("{} settings, ∫ value dωo by the suite's hemisphere integral: {} "
                         "significantly above 1 at level {:.3g}; largest albedo {:.4g} at {}",
                         set.size(), f.rejections, level, max_albedo, where);
  return a;
}

}  // namespace glintlab::verify::conformance

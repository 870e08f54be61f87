// A family of chi-square configurations with Holm–Šidák correction and negative controls; see
// gof_family.h.
#include "verify/claims/gof_family.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>

#include "core/math/rng.h"

namespace glintlab::verify {

Family correct_family(const std::vector<double>& p) {
  Family f{holm_sidak(p, check_level())};
  for (double a : f.hs.adjusted) f.min_adjusted = std::min(f.min_adjusted, a);
  return f;
}

void record_p_values(CheckResult& r, const Family& f) {
  r.raw_p_values = f.hs.raw;
  r.p_value = f.min_adjusted;
}
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The plan of a pdf scaled by s: every expectation, its error and the mass scale with it.
ChiSquarePlan scaled_plan(const ChiSquarePlan& p, double s) {
  ChiSquarePlan q = p;
  for (BinGrid& g : q.grids) {
    for (double& e : g.expected) e *= s;
    for (double& e : g.error) e *= s;
    g.mass *= s;
    g.mass_error *= s;
  }
  if (p.direction_pdf)
    q.direction_pdf = [f = p.direction_pdf, s](const Vec3<double>& w) { return s * f(w); };
  if (p.options.direction_pdf_rows)
    q.options.direction_pdf_rows = [f = p.options.direction_pdf_rows, s](
                                       std::span<const Vec3<double>> w, std::span<double> out) {
      f(w, out);
      for (double& v : out) v *= s;
    };
  if (p.point_pdf) q.point_pdf = [f = p.point_pdf, s](const Vec2<double>& x) { return s * f(x); };
  return q;
}

// The p-value a result contributes to a family: 0 on a hard failure, NaN (never rejected) when the
// cubature could not decide.
double family_p(const ChiSquareResult& r) {
  if (r.hard_fail) return 0;
  return r.inconclusive ? kNaN : r.p_value;
}

}  // namespace

ChiSquarePlan plan_gof_case(const GofCase& c, std::uint64_t n, double level,
                            std::size_t fine_max_bins) {
  ChiSquareOptions o = c.options;
  o.level = level;
  o.fine_max_bins = fine_max_bins;
  return c.domain == SampleDomain::kDisk
             ? plan_disk_chi_square(c.point_pdf, n, o)
             : plan_direction_chi_square(SampleDomain::kSphere, c.direction_pdf, n, o);
}

ChiSquareResult run_gof_case(const ChiSquarePlan& plan, const GofCase& c, std::uint64_t seed) {
  if (c.domain == SampleDomain::kDisk)
    return run_disk_chi_square(plan, [&](std::uint64_t i) { return c.points(seed, i); });
  if (c.direction_batch) {
    return run_direction_chi_square(
        plan, DirectionBatchSampler([&](std::uint64_t begin, std::size_t count, Vec3<double>* out) {
          c.direction_batch(seed, begin, count, out);
        }));
  }
  return run_direction_chi_square(plan, [&](std::uint64_t i) { return c.directions(seed, i); });
}

GofOutcome run_gof_family(const std::string& id, const std::vector<GofCase>& cases,
                          const std::vector<GofControl>& controls, const GofSize& size) {
  GofOutcome out;
  const std::uint64_t n = size.n, control_n = size.control_n;
  const std::size_t fine = size.fine_max_bins;
  const std::size_t m = cases.size();
  out.configuration_level = sidak_level(check_level(), std::max<std::size_t>(m, 1));
  const double level = out.configuration_level;

  // The sample count of each control, and the configurations whose plan a control case reuses,
  // at that count: the configuration's own plan where it is n, a new one otherwise.
  auto count_of = [&](const GofControl& c) { return c.gross ? n : control_n; };
  std::map<std::pair<int, std::uint64_t>, ChiSquarePlan> shared;
  for (const GofControl& c : controls)
    for (const GofControlCase& cc : c.cases)
      if (cc.plan_of >= 0) shared[{cc.plan_of, count_of(c)}] = ChiSquarePlan{};
  std::vector<ChiSquarePlan*> keep(m, nullptr);
  for (auto& [key, plan] : shared)
    if (key.second == n) keep[std::size_t(key.first)] = &plan;

  out.results.resize(m);
  tbb::parallel_for(std::size_t(0), m, [&](std::size_t i) {
    ChiSquarePlan plan = plan_gof_case(cases[i], n, level, fine);
    out.results[i] = run_gof_case(plan, cases[i], check_seed(id, i));
    if (keep[i]) *keep[i] = std::move(plan);
  });
  std::vector<double> p(m);
  for (std::size_t i = 0; i < m; ++i) {
    p[i] = family_p(out.results[i]);
    out.inconclusive += out.results[i].inconclusive && !out.results[i].hard_fail ? 1 : 0;
    out.hard_failures += out.results[i].hard_fail ? 1 : 0;
  }
  out.family = holm_sidak(p, check_level());

  std::vector<std::pair<std::pair<int, std::uint64_t>, ChiSquarePlan*>> missing;
  for (auto& [key, plan] : shared)
    if (key.second != n) missing.push_back({key, &plan});
  tbb::parallel_for(std::size_t(0), missing.size(), [&](std::size_t b) {
    const auto [i, count] = missing[b].first;
    *missing[b].second = plan_gof_case(cases[std::size_t(i)], count, level, fine);
  });

  struct Job {
    std::size_t control, index;
  };
  std::vector<Job> jobs;
  out.control_results.resize(controls.size());
  for (std::size_t c = 0; c < controls.size(); ++c) {
    out.control_results[c].resize(controls[c].cases.size());
    for (std::size_t k = 0; k < controls[c].cases.size(); ++k) jobs.push_back({c, k});
  }
  tbb::parallel_for(std::size_t(0), jobs.size(), [&](std::size_t j) {
    const GofControlCase& cc = controls[jobs[j].control].cases[jobs[j].index];
    const std::uint64_t seed = check_seed(id, m + j);
    ChiSquareResult& r = out.control_results[jobs[j].control][jobs[j].index];
    const GofControl& control = controls[jobs[j].control];
    if (cc.plan_of >= 0) {
      const ChiSquarePlan& base = shared.at({cc.plan_of, count_of(control)});
      r = cc.pdf_scale == 1 ? run_gof_case(base, cc.wrong, seed)
                            : run_gof_case(scaled_plan(base, cc.pdf_scale), cc.wrong, seed);
    } else {
      r = run_gof_case(plan_gof_case(cc.wrong, count_of(control), level, fine), cc.wrong, seed);
    }
  });
  for (std::size_t c = 0; c < controls.size(); ++c) {
    double worst = 0;
    bool all = !out.control_results[c].empty();
    for (const ChiSquareResult& r : out.control_results[c]) {
      const double q = family_p(r);
      worst = std::isnan(q) ? 1.0 : std::max(worst, q);
      all = all && r.rejects(level) && !(r.inconclusive && !r.hard_fail);
    }
    out.control_p.push_back(worst);
    out.control_rejected.push_back(all);
  }
  return out;
}

namespace {

// The family's p-values and power into r; returns the configuration with the smallest raw p.
std::size_t record_family(const GofOutcome& o, CheckResult& r) {
  const std::size_t m = o.results.size();
  r.configurations = int(m);
  r.raw_p_values.clear();
  std::size_t worst = 0;
  double min_adjusted = 1;
  double coarse_global = 0, fine_cell = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const ChiSquareResult& x = o.results[i];
    r.raw_p_values.push_back(family_p(x));
    const double pi = std::isnan(r.raw_p_values[i]) ? 2.0 : r.raw_p_values[i];
    const double pw = std::isnan(r.raw_p_values[worst]) ? 2.0 : r.raw_p_values[worst];
    if (pi < pw) worst = i;
    if (!std::isnan(o.family.adjusted[i]))
      min_adjusted = std::min(min_adjusted, o.family.adjusted[i]);
    if (!x.resolutions.empty()) {
      coarse_global = std::max(coarse_global, x.resolutions.front().detectable_global);
      fine_cell = std::max(fine_cell, x.resolutions.back().detectable_one_cell);
    }
  }
  r.p_value = min_adjusted;
  const std::uint64_t n = m > 0 ? o.results[0].n : 0;
  r.power = fmt::format(
      "at 90 % power, per configuration (N = {}, level {:.2g}): a relative pdf error δ ≥ {:.3g} "
      "over the whole domain (coarse bins), or ≥ {:.3g} confined to one fine cell (worst "
      "configuration)",
      n, o.configuration_level, coarse_global, fine_cell);
  return worst;
}

// Each control's largest p over its cases and whether it was rejected, as one line; sets
// r.control_p_value to the largest p over all controls.
// caught(c, k): whether case k of control c was caught.
template <class Caught>
std::string control_text(const GofOutcome& o, const std::vector<GofControl>& controls,
                         const std::vector<bool>& rejected, Caught&& caught, CheckResult& r) {
  std::string text;
  double largest = 0;
  for (std::size_t c = 0; c < controls.size(); ++c) {
    largest = std::max(largest, o.control_p[c]);
    std::string where;
    if (!rejected[c])
      for (std::size_t k = 0; k < o.control_results[c].size(); ++k)
        if (!caught(c, k))
          where = fmt::format(" (kept: {}: {})", controls[c].cases[k].wrong.label,
                              o.control_results[c][k].summary());
    text += fmt::format("{}{}: largest p {:.3g} over {} case(s), {}{}", text.empty() ? "" : "; ",
                        controls[c].name, o.control_p[c], controls[c].cases.size(),
                        rejected[c] ? "rejected" : "NOT rejected", where);
  }
  r.control_p_value = largest;
  return text;
}

}  // namespace

Verdict decide_gof(const std::vector<ChiSquareResult>& results) {
  std::vector<double> p;
  bool hard = false, inconclusive = false;
  for (const ChiSquareResult& x : results) {
    p.push_back(family_p(x));
    hard = hard || x.hard_fail;
    inconclusive = inconclusive || (x.inconclusive && !x.hard_fail);
  }
  if (holm_sidak(p, check_level()).rejections > 0 || hard) return Verdict::kFails;
  return inconclusive ? Verdict::kInconclusive : Verdict::kHolds;
}

bool GofControlVerdicts::rejected(std::size_t control) const {
  return std::all_of(cases[control].begin(), cases[control].end(),
                     [](Verdict v) { return v == Verdict::kFails; });
}

GofControlVerdicts decide_gof_controls(const GofOutcome& o,
                                       const std::vector<GofControl>& controls) {
  GofControlVerdicts out;
  std::vector<Verdict> all;
  for (std::size_t c = 0; c < controls.size(); ++c) {
    out.cases.emplace_back();
    for (std::size_t k = 0; k < controls[c].cases.size(); ++k) {
      const int at = controls[c].cases[k].position();
      if (at < 0 || std::size_t(at) >= o.results.size())
        throw std::logic_error("control case " + controls[c].cases[k].wrong.label +
                               " replaces no configuration of the family");
      std::vector<ChiSquareResult> family = o.results;
      family[std::size_t(at)] = o.control_results[c][k];
      out.cases.back().push_back(decide_gof(family));
      all.push_back(out.cases.back().back());
    }
  }
  out.verdict = control_verdict_of_cases(all);
  return out;
}

std::size_t describe_gof(const GofOutcome& o, const std::vector<GofControl>& controls,
                         const GofControlVerdicts& cv, CheckResult& r) {
  const std::size_t worst = record_family(o, r);
  std::vector<bool> rejected;
  for (std::size_t c = 0; c < controls.size(); ++c) rejected.push_back(cv.rejected(c));
  const std::string text = control_text(
      o, controls, rejected,
      [&](std::size_t c, std::size_t k) { return cv.cases[c][k] == Verdict::kFails; }, r);
  r.control = fmt::format(
      "each wrong case in place of its configuration, decided as the family (a case alone is "
      "caught at the first Holm level {:.2g}): {}",
      o.configuration_level, text);
  return worst;
}

Verdict summarize_gof(const GofOutcome& o, const std::vector<GofControl>& controls, CheckResult& r,
                      std::size_t& worst) {
  worst = record_family(o, r);
  r.control_rejected = !controls.empty();
  for (std::size_t c = 0; c < controls.size(); ++c)
    r.control_rejected = r.control_rejected && o.control_rejected[c];
  r.control = fmt::format("rejected at the first Holm level {:.2g}: {}", o.configuration_level,
                          control_text(
                              o, controls, o.control_rejected,
                              [&](std::size_t c, std::size_t k) {
                                return o.control_results[c][k].rejects(o.configuration_level);
                              },
                              r));
  // The family's decision on the wrong inputs: a rejected control case is "fails" there; every
  // control family rejected makes the control's verdict fails.
  r.control_verdict = r.control_rejected ? Verdict::kFails : Verdict::kHolds;
  return decide_gof(o.results);
}

Verdict control_verdict_of_cases(const std::vector<Verdict>& cases) {
  for (Verdict v : cases)
    if (v != Verdict::kFails) return v;
  return cases.empty() ? Verdict::kInconclusive : Verdict::kFails;
}

Vec3<double> incidence(double theta_deg) {
  if (theta_deg == 0) return {0, 0, 1};
  const double t = theta_deg * std::numbers::pi / 180;
  return {std::sin(t) * std::cos(kIncidencePhi), std::sin(t) * std::sin(kIncidencePhi),
          std::cos(t)};
}

Vec2<double> uniform_pair(std::uint64_t seed, std::uint64_t index) {
  return {counter_uniform<double>(seed, index, 0), counter_uniform<double>(seed, index, 1)};
}

ChiSquareOptions reflection_options(const Vec3<double>& wi) {
  ChiSquareOptions o;
  o.lobe = wi.z > 0 ? Vec3<double>{-wi.x, -wi.y, wi.z} : Vec3<double>{0, 0, 1};
  o.point_features.push_back(-wi);
  return o;
}

}  // namespace glintlab::verify

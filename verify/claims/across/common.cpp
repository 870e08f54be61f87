#include "verify/claims/across/common.h"

#include <fmt/format.h>

#include <map>
#include <memory>
#include <mutex>
#include <tuple>
#include <utility>

namespace glintlab::verify::across_claims {

using namespace stability;

const std::vector<ModelSweep>& suite_sweeps(Budget b, FixedPositionVariance variance) {
  static std::mutex mutex;
  static std::map<std::pair<Budget, FixedPositionVariance>,
                  std::unique_ptr<std::vector<ModelSweep>>>
      cache;
  const std::lock_guard lock(mutex);
  auto& base = cache[{b, FixedPositionVariance::kSkip}];
  if (!base) {
    base = std::make_unique<std::vector<ModelSweep>>();
    for (const SweepTarget& t : sweep_targets())
      base->push_back(sweep_model(t, b, {}, FixedPositionVariance::kSkip));
  }
  if (variance == FixedPositionVariance::kSkip) return *base;
  auto& full = cache[{b, FixedPositionVariance::kMeasure}];
  if (!full) {
    full = std::make_unique<std::vector<ModelSweep>>(*base);
    for (ModelSweep& s : *full) add_fixed_position_variance(s, b);
  }
  return *full;
}

namespace {

std::vector<TargetVerdict> judge_targets(std::span<const ModelSweep> sweeps, DefectClass kind) {
  std::vector<TargetVerdict> out;
  for (const ModelSweep& s : sweeps) {
    TargetVerdict t{s.target.id(), stability_verdict(s, kind), ""};
    for (const Finding& f : find_failures(s))
      if (f.kind == kind) {
        t.first = f.text();
        break;
      }
    out.push_back(std::move(t));
  }
  return out;
}

// A control model's sweep at a budget, kept per process (deterministic: a second sweep would
// measure the same).
const ModelSweep& control_sweep(const ModelEntry* m, Budget b, FixedPositionVariance variance) {
  static std::mutex mutex;
  static std::map<std::tuple<const ModelEntry*, Budget, FixedPositionVariance>,
                  std::unique_ptr<ModelSweep>>
      cache;
  const std::lock_guard lock(mutex);
  auto& slot = cache[{m, b, variance}];
  if (!slot)
    slot =
        std::make_unique<ModelSweep>(sweep_model({m, std::nullopt, 0, "default"}, b, {}, variance));
  return *slot;
}

}  // namespace

Measured measure_kind(Budget b, const std::vector<ModelSweep>& suite, DefectClass kind,
                      std::span<const ModelEntry* const> control_models) {
  Measured m;
  m.suite = &suite;
  for (const ModelSweep& s : suite)
    for (const SweepMap& map : s.maps) m.cells += map.cells.size();
  if (control_models.empty()) {
    m.targets = judge_targets(suite, kind);
    return m;
  }
  const FixedPositionVariance variance = kind == DefectClass::kHugeVariance
                                             ? FixedPositionVariance::kMeasure
                                             : FixedPositionVariance::kSkip;
  std::vector<ModelSweep> sweeps;
  for (const ModelEntry* model : control_models)
    sweeps.push_back(control_sweep(model, b, variance));
  m.targets = judge_targets(sweeps, kind);
  return m;
}

Decision decide_kind(const Measured& m) {
  bool regime = false, fails = false;
  int breaking = 0;
  for (const TargetVerdict& t : m.targets) {
    fails |= t.verdict == Verdict::kFails;
    regime |= t.verdict == Verdict::kHoldsInRegime;
    breaking += t.verdict == Verdict::kFails;
  }
  return {.verdict = fails    ? Verdict::kFails
                     : regime ? Verdict::kHoldsInRegime
                              : Verdict::kHolds,
          .value = double(breaking),
          .bound = 0.0,
          .configurations = int(m.cells)};
}

std::string describe_targets(const std::vector<TargetVerdict>& targets) {
  std::vector<std::string> holds, regime, fails;
  for (const TargetVerdict& t : targets) {
    if (t.verdict == Verdict::kHolds)
      holds.push_back(t.id);
    else if (t.verdict == Verdict::kFails)
      fails.push_back(fmt::format("{} ({})", t.id, t.first));
    else
      regime.push_back(fmt::format("{} ({})", t.id, t.first));
  }
  auto list = [](const std::vector<std::string>& v) {
    return v.empty() ? std::string("none") : fmt::format("{}", fmt::join(v, "; "));
  };
  return fmt::format("fails: {}; holds outside the core domain only: {}; holds: {}", list(fails),
                     list(regime), list(holds));
}

std::string describe_suite(Budget b, const Measured& m) {
  return fmt::format("{} targets, {} cells ({} samples and {} uniform evaluations per cell): {}",
                     m.targets.size(), m.cells, cell_budget(b).samples,
                     cell_budget(b).uniform_evals, describe_targets(m.targets));
}

std::vector<const ModelEntry*> corrected_models() { return {&find_model("smooth_ggx")}; }

std::uint64_t fewest_calls(const std::vector<ModelSweep>& suite) {
  std::uint64_t fewest = ~std::uint64_t(0);
  for (const ModelSweep& s : suite) {
    std::uint64_t calls = 0;
    for (const SweepMap& m : s.maps)
      for (const CellStats& c : m.cells) calls += c.evals + c.samples;
    fewest = std::min(fewest, calls);
  }
  return fewest;
}

}  // namespace glintlab::verify::across_claims

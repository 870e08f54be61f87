// The stability sweep of one model × sampler over its planes, cell by cell.
#include "verify/stability/sweep.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <map>
#include <mutex>
#include <optional>
#include <tuple>

#include "core/model_registry.h"

namespace glintlab::verify::stability {

CellBudget cell_budget(Budget b) {
  // Quick takes 256 samples: Var(w)/E(w)² of n samples is at most n, so 64 could never show a
  // blow-up above kVarianceBlowup = 81.92.
  return b == Budget::kQuick ? CellBudget{64, 256} : CellBudget{1024, 1024};
}

namespace {

using SweepKey = std::tuple<const ModelEntry*, std::optional<std::size_t>, std::size_t, Budget>;
struct ReuseState {
  std::mutex mutex;
  bool active = false;
  std::map<SweepKey, ModelSweep> sweeps;
  std::size_t reused = 0;
};
ReuseState& reuse_state() {
  static ReuseState state;
  return state;
}
bool is_registered(const ModelEntry* m) {
  for (const ModelEntry& e : registered_models())
    if (&e == m) return true;
  return false;
}

std::uint64_t cell_seed(const SweepTarget& target, const SweepPlane& plane, std::size_t cell) {
  return check_seed("all.stability/" + target.id() + "/" + plane.name, cell);
}

ModelSweep measure_sweep(const SweepTarget& target, Budget b,
                         const std::function<void(long, long)>& progress,
                         FixedPositionVariance variance) {
  const auto start = std::chrono::steady_clock::now();
  ModelSweep s;
  s.target = target;
  s.has_float = static_cast<bool>(target.model->eval_float);
  for (std::string_view n : target.model->intermediates)
    s.has_probability |= is_probability_name(n);
  s.has_variance = variance == FixedPositionVariance::kMeasure;
  const CellBudget budget = cell_budget(b);
  const auto planes = sweep_planes(*target.model, b == Budget::kQuick);
  long done = 0;
  for (const SweepPlane& plane : planes) {
    SweepMap map{plane, std::vector<CellStats>(plane.rows.size() * plane.theta_deg.size())};
    const std::size_t cols = plane.theta_deg.size();
    tbb::parallel_for(std::size_t(0), map.cells.size(), [&](std::size_t i) {
      const double row = plane.rows[i / cols], theta = plane.theta_deg[i % cols];
      const std::uint64_t seed = cell_seed(target, plane, i);
      map.cells[i] = measure_cell(target, plane, row, theta, budget, seed);
      if (s.has_variance)
        measure_fixed_position_variance(map.cells[i], target, plane, row, theta, budget, seed);
    });
    s.maps.push_back(std::move(map));
    if (progress) progress(++done, long(planes.size()));
  }
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

}  // namespace

void add_fixed_position_variance(ModelSweep& s, Budget b) {
  if (s.has_variance) return;
  const auto start = std::chrono::steady_clock::now();
  const CellBudget budget = cell_budget(b);
  for (SweepMap& map : s.maps) {
    const SweepPlane& plane = map.plane;
    const std::size_t cols = plane.theta_deg.size();
    tbb::parallel_for(std::size_t(0), map.cells.size(), [&](std::size_t i) {
      measure_fixed_position_variance(map.cells[i], s.target, plane, plane.rows[i / cols],
                                      plane.theta_deg[i % cols], budget,
                                      cell_seed(s.target, plane, i));
    });
  }
  s.has_variance = true;
  s.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

ModelSweep sweep_model(const SweepTarget& target, Budget b,
                       const std::function<void(long, long)>& progress,
                       FixedPositionVariance variance) {
  ReuseState& r = reuse_state();
  const SweepKey key{target.model, target.sampler_param, target.sampler_choice, b};
  const bool needs_variance = variance == FixedPositionVariance::kMeasure;
  bool reusable = false;
  std::optional<ModelSweep> kept;
  {
    std::lock_guard lock(r.mutex);
    if (r.active && is_registered(target.model)) {
      reusable = true;
      if (auto it = r.sweeps.find(key); it != r.sweeps.end()) {
        ++r.reused;
        if (it->second.has_variance || !needs_variance) return it->second;
        kept = it->second;
      }
    }
  }
  ModelSweep s = kept ? std::move(*kept) : measure_sweep(target, b, progress, variance);
  if (kept) add_fixed_position_variance(s, b);
  if (reusable) {
    std::lock_guard lock(r.mutex);
    if (r.active) r.sweeps.insert_or_assign(key, s);
  }
  return s;
}

SweepReuse::SweepReuse() {
  ReuseState& r = reuse_state();
  std::lock_guard lock(r.mutex);
  r.active = true;
  r.sweeps.clear();
  r.reused = 0;
}
SweepReuse::~SweepReuse() {
  ReuseState& r = reuse_state();
  std::lock_guard lock(r.mutex);
  r.active = false;
  r.sweeps.clear();
}
std::size_t SweepReuse::reused() const {
  ReuseState& r = reuse_state();
  std::lock_guard lock(r.mutex);
  return r.reused;
}

}  // namespace glintlab::verify::stability

// The stability sweep of one model × sampler over its planes, cell by cell.
#include "verify/stability/sweep.h"

#include <tbb/parallel_for.h>

#include <chrono>

namespace glintlab::verify::stability {

CellBudget cell_budget(Budget b) {
  // Quick takes 256 samples: Var(w)/E(w)² of n samples is at most n − 1, so 64 could never show a
  // blow-up above kVarianceBlowup = 100.
  return b == Budget::kQuick ? CellBudget{64, 256} : CellBudget{1024, 1024};
}

ModelSweep sweep_model(const SweepTarget& target, Budget b,
                       const std::function<void(long, long)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  ModelSweep s;
  s.target = target;
  s.has_float = static_cast<bool>(target.model->eval_float);
  for (std::string_view n : target.model->intermediates)
    s.has_probability |= is_probability_name(n);
  const CellBudget budget = cell_budget(b);
  const auto planes = sweep_planes(*target.model, b == Budget::kQuick);
  long done = 0;
  for (const SweepPlane& plane : planes) {
    SweepMap map{plane, std::vector<CellStats>(plane.rows.size() * plane.theta_deg.size())};
    const std::string id = "all.stability/" + target.id() + "/" + plane.name;
    const std::size_t cols = plane.theta_deg.size();
    tbb::parallel_for(std::size_t(0), map.cells.size(), [&](std::size_t i) {
      map.cells[i] = measure_cell(target, plane, plane.rows[i / cols], plane.theta_deg[i % cols],
                                  budget, check_seed(id, i));
    });
    s.maps.push_back(std::move(map));
    if (progress) progress(++done, long(planes.size()));
  }
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

}  // namespace glintlab::verify::stability

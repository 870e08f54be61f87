// Google Benchmark of every registered model (core/model_registry.h) through the registry-level
// batch API (core/simd/model_batch.h): the entry's scalar double thunk loop against each ISA's
// batched eval and sample, items (queries) per second. Names: model/<name>/<isa>/<op>_<precision>,
// model/<name>/entry/<op> for the thunk loop (op eval, pdf or sample: the batch API has no pdf of
// its own, eval_batch writes the pdf column with the value, so the batched pdf is in the eval
// rows); every row carries counters batched (the model has SIMD instantiations, else the batch
// calls loop over the thunks) and double_only (its kernels take no float); a model with a choice parameter `k` (Kemppinen's
// neighbourhood) also gets model/<name>/k=<choice>/... for k = 1, 4, 16 (the default k is 1).
// Model plug-ins join like in `glintlab`: --plugin PATH (repeatable, anywhere) and
// GLINTLAB_PLUGINS.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/model_layout.h"
#include "core/model_registry.h"
#include "core/plugin_loader.h"
#include "core/simd/inputs.h"
#include "core/simd/kernels.h"
#include "core/simd/model_batch.h"

namespace glintlab::simd::bench {
namespace {

constexpr std::size_t kRows = 4096;

// kRows queries over the edge-case generator's wi, wo and uniforms, and the scene columns the
// model reads (footprint, light cone, corner vectors: add_scene_columns, core/simd/inputs.h).
struct Queries {
  std::vector<std::vector<double>> query;  // kQueryColumnsWithCorners columns
  std::vector<double> u1, u2;
};

Queries make_queries(unsigned needs) {
  using D = Domain;
  const std::vector<int> domains = {int(D::kWiX), int(D::kWiY), int(D::kWiZ), int(D::kWoX),
                                    int(D::kWoY), int(D::kWoZ), int(D::kU1),  int(D::kU2)};
  const auto in = make_inputs(domains, kRows, 0x62656e6368ULL);
  Queries r;
  for (const QueryColumn& c : kQueryLayout) r.query.emplace_back(kRows, c.default_value);
  // wi and wo from the generator, in its domain order wi_x .. wo_z.
  for (std::size_t j = 0; j < 6; ++j) r.query[query_column_index("wi_x") + j] = in[j];
  // uv over [0, 4)² by a low-discrepancy sequence, so glint models visit different cells
  // (models that need a footprint get theirs from add_scene_columns).
  for (std::size_t i = 0; i < kRows; ++i) {
    r.query[query_column_index("u")][i] = 4 * std::fmod(0.7548776662466927 * double(i), 1.0);
    r.query[query_column_index("v")][i] = 4 * std::fmod(0.5698402909980532 * double(i), 1.0);
  }
  r.u1 = in[6];
  r.u2 = in[7];
  add_scene_columns(needs, r.query, 0x7363656e65ULL);
  return r;
}

const Queries& queries(const ModelEntry& m) {
  static std::map<unsigned, Queries> cache;
  auto it = cache.find(m.needs);
  if (it == cache.end()) it = cache.emplace(m.needs, make_queries(m.needs)).first;
  return it->second;
}

std::vector<double> defaults(const ModelEntry& m) {
  std::vector<double> v;
  for (const ParamSpec& p : m.params) v.push_back(p.default_value);
  return v;
}

// The defaults with choice parameter `k` set to choice index `k_choice` (−1: unchanged).
std::vector<double> with_k(const ModelEntry& m, int k_choice) {
  std::vector<double> v = defaults(m);
  for (std::size_t j = 0; j < m.params.size(); ++j)
    if (k_choice >= 0 && m.params[j].name == "k") v[j] = double(k_choice);
  return v;
}

enum class Op { kEval, kPdf, kSample };

void model_counters(benchmark::State& state, const ModelEntry& m) {
  state.counters["batched"] = is_batched(m) ? 1.0 : 0.0;
  state.counters["double_only"] = m.eval_float ? 0.0 : 1.0;
}

void bm_entry(benchmark::State& state, const ModelEntry* m, Op op, int k_choice) {
  const Queries& q = queries(*m);
  const std::vector<double> params = with_k(*m, k_choice);
  double sink = 0;
  // One untimed row first: a model's first call may build its tables (Chermain's dictionary).
  sink += m->eval(params, ModelQuery<double>{}).value;
  for (auto _ : state) {
    for (std::size_t i = 0; i < kRows; ++i) {
      ModelQuery<double> mq{};
      const auto c = [&](std::size_t j) { return q.query[j][i]; };
      mq.footprint = {{c(0), c(1)}, {c(2), c(3)}, {c(4), c(5)}};
      for (std::size_t k = 0; k < 4; ++k)
        mq.footprint.corner_r[k] = {c(14 + 3 * k), c(15 + 3 * k), c(16 + 3 * k)};
      mq.wi = {c(6), c(7), c(8)};
      mq.wo = {c(9), c(10), c(11)};
      mq.light = {c(12), c(13)};
      switch (op) {
        case Op::kEval: sink += m->eval(params, mq).value; break;
        case Op::kPdf: sink += m->pdf(params, mq); break;
        case Op::kSample: sink += m->sample(params, mq, {q.u1[i], q.u2[i]}).weight; break;
      }
    }
    benchmark::DoNotOptimize(sink);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(kRows));
  model_counters(state, *m);
}

template <class S>
void bm_batch(benchmark::State& state, const ModelEntry* m, Isa isa, bool sample, int k_choice) {
  const Queries& q = queries(*m);
  const std::vector<double> params = with_k(*m, k_choice);
  std::vector<std::vector<S>> cols_data;
  for (const auto& c : q.query) cols_data.emplace_back(c.begin(), c.end());
  const std::vector<S> u1(q.u1.begin(), q.u1.end()), u2(q.u2.begin(), q.u2.end());
  std::vector<Column<S>> cols;
  for (const auto& c : cols_data) cols.push_back({c.data(), 1});
  const std::size_t n_out = sample ? kSampleColumns.size() : 2 + m->intermediates.size();
  std::vector<std::vector<S>> out(n_out, std::vector<S>(kRows));
  std::vector<S*> outs;
  for (auto& c : out) outs.push_back(c.data());
  // One untimed row first (a first call may build tables).
  if (sample) {
    sample_batch(*m, params, cols, {u1.data(), 1}, {u2.data(), 1}, outs, 1, isa);
  } else {
    eval_batch(*m, params, cols, outs, 1, isa);
  }
  for (auto _ : state) {
    if (sample) {
      sample_batch(*m, params, cols, {u1.data(), 1}, {u2.data(), 1}, outs, kRows, isa);
    } else {
      eval_batch(*m, params, cols, outs, kRows, isa);
    }
    benchmark::DoNotOptimize(out[0].data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(kRows));
  model_counters(state, *m);
}

void register_all() {
  for (const ModelEntry& m : registered_models()) {
    // (prefix, k choice index): the defaults, then k = 1, 4, 16 where the model has `k`.
    std::vector<std::pair<std::string, int>> variants = {{"", -1}};
    for (const ParamSpec& p : m.params)
      if (p.name == "k" && !p.choices.empty())
        for (std::size_t c = 0; c < p.choices.size(); ++c)
          if (p.choices[c] == "1" || p.choices[c] == "4" || p.choices[c] == "16")
            variants.emplace_back("k=" + std::string(p.choices[c]) + "/", int(c));
    for (const auto& [prefix, k_choice] : variants) {
      const std::string base = "model/" + std::string(m.name) + "/" + prefix;
      benchmark::RegisterBenchmark((base + "entry/pdf").c_str(), bm_entry, &m, Op::kPdf,
                                   k_choice);
      for (bool sample : {false, true}) {
        const std::string op = sample ? "sample" : "eval";
        benchmark::RegisterBenchmark((base + "entry/" + op).c_str(), bm_entry, &m,
                                     sample ? Op::kSample : Op::kEval, k_choice);
        for (Isa isa : kAllIsas) {
          if (!isa_supported(isa)) continue;
          const std::string name = base + std::string(isa_name(isa)) + "/" + op;
          benchmark::RegisterBenchmark((name + "_float").c_str(), bm_batch<float>, &m, isa, sample,
                                       k_choice);
          benchmark::RegisterBenchmark((name + "_double").c_str(), bm_batch<double>, &m, isa,
                                       sample, k_choice);
        }
      }
    }
  }
}

}  // namespace
}  // namespace glintlab::simd::bench

int main(int argc, char** argv) {
  // Before Initialize, which would reject --plugin as an unknown flag's value.
  try {
    glintlab::load_plugins(argc, argv, /*leading_only=*/false);
  } catch (const std::exception& e) {
    fmt::print(stderr, "glintlab_bench_models: error: {}\n", e.what());
    return 2;
  }
  benchmark::Initialize(&argc, argv);
  benchmark::AddCustomContext("best_isa",
                              std::string(glintlab::simd::isa_name(glintlab::simd::best_isa())));
  glintlab::simd::bench::register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

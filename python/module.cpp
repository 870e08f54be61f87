// The `glintlab._glintlab` extension: the model registry (core/model_registry.h) and its batch API
// (core/simd/model_batch.h) for numpy. glintlab/__init__.py re-exports it with the docstrings.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdint>
#include <optional>
#include <thread>
#include <string>
#include <type_traits>
#include <vector>

#include "cli/commands.h"
#include "cli/input.h"
#include "cli/suite_runs.h"
#include "core/math/rng.h"
#include "core/model_registry.h"
#include "core/plugin_loader.h"
#include "core/simd/model_batch.h"
#include "verify/check.h"
#include "verify/conformance/conformance.h"
#include "verify/results.h"
#include "python/batch_call.h"
#include "python/python_model.h"
#include "python/query_columns.h"
#include "python/result_pool.h"

namespace glintlab::python {
namespace {

const ModelEntry& model_named(const std::string& name) {
  try {
    return find_model(name);
  } catch (const ModelParamError& e) {
    throw py::value_error(e.what());
  }
}

std::vector<std::string> needs_names(unsigned needs) {
  std::vector<std::string> out;
  if (needs & kNeedsFootprint) out.emplace_back("footprint");
  if (needs & kNeedsPointLight) out.emplace_back("point light");
  if (needs & kNeedsAreaLight) out.emplace_back("area light");
  if (needs & kNeedsPixelCorners) out.emplace_back("pixel corners");
  return out;
}

py::dict param_dict(const ParamSpec& p) {
  py::dict d;
  d["name"] = std::string(p.name);
  d["description"] = std::string(p.description);
  d["range"] = describe_range(p);
  if (p.choices.empty()) {
    d["default"] = p.default_value;
    d["lo"] = p.lo;
    d["hi"] = p.hi;
    d["lo_open"] = p.lo_open;
    d["hi_open"] = p.hi_open;
    d["integral"] = p.integral;
  } else {
    d["default"] = format_param_value(p, p.default_value);
    std::vector<std::string> choices(p.choices.begin(), p.choices.end());
    d["choices"] = choices;
  }
  return d;
}

py::list models() {
  py::list out;
  for (const ModelEntry& m : registered_models()) {
    py::dict d;
    d["name"] = std::string(m.name);
    d["description"] = std::string(m.description);
    d["source"] = std::string(m.source);
    d["needs"] = needs_names(m.needs);
    py::list params;
    for (const ParamSpec& p : m.params) params.append(param_dict(p));
    d["params"] = params;
    d["intermediates"] = std::vector<std::string>(m.intermediates.begin(), m.intermediates.end());
    d["smooth_limit"] = m.smooth_limit.empty() ? py::object(py::none())
                                               : py::object(py::str(std::string(m.smooth_limit)));
    d["batched"] = simd::is_batched(m);
    out.append(d);
  }
  return out;
}

// The values of parameter columns of stride 0 (a numpy model's call: run_chunks groups its rows
// by their values).
std::vector<double> uniform_values(std::span<const simd::Column<double>> params) {
  std::vector<double> values;
  values.reserve(params.size());
  for (const simd::Column<double>& c : params) values.push_back(c.data[0]);
  return values;
}

// Where a numpy model's chunk columns lie (python_model.h, ColumnOwners): a column read in place
// lies in the caller's array (its source's owner), a gathered one in the chunk's storage.
template <class S>
ColumnOwners column_owners(const QuerySources& q, std::span<const simd::Column<S>> cols,
                           const ChunkStorage& storage, std::vector<PyObject*>& arrays) {
  arrays.assign(cols.size(), nullptr);
  for (std::size_t c = 0; c < cols.size() && c < q.columns.size(); ++c) {
    const ColumnSource& s = q.columns[c];
    if (!s.in_place<S>() || cols[c].stride != 1) continue;
    // Addresses compared as integers: a gathered column lies in another allocation.
    const auto at = reinterpret_cast<std::uintptr_t>(cols[c].data);
    const auto first = reinterpret_cast<std::uintptr_t>(s.data);
    if (at >= first && at < first + q.rows * sizeof(S)) arrays[c] = s.owner;
  }
  return ColumnOwners{arrays, storage.owner, storage.begin, storage.end};
}

// Whether p lies in the n values from `first` (compared as integers: p may lie elsewhere).
template <class S>
bool in_results(const S* p, const S* first, std::size_t n) {
  const auto at = reinterpret_cast<std::uintptr_t>(p), begin = reinterpret_cast<std::uintptr_t>(first);
  return at >= begin && at < begin + n * sizeof(S);
}

// The number of query columns the batch calls take for this model (with the corners or not).
std::size_t query_width(const ModelEntry& m) {
  return (m.needs & kNeedsPixelCorners) != 0 ? simd::kQueryColumnsWithCorners
                                             : simd::kQueryColumns.size();
}

template <class S>
py::dict eval_in(const ModelEntry& model, const QuerySources& q, const CallParams& p,
                 const cli::BatchOptions& opts) {
  const std::size_t n = q.rows, width = query_width(model);
  std::vector<py::array_t<S>> outs;
  {
    const PooledArrays pooled;  // memory kept mapped between calls (result_pool.h)
    for (std::size_t k = 0; k < 2 + model.intermediates.size(); ++k)
      outs.emplace_back(py::ssize_t(n));
  }
  std::vector<S*> out_data;
  for (auto& a : outs) out_data.push_back(a.mutable_data());
  const PythonModel* const numpy_model = python_model(model);  // looked up once, with the GIL
  run_chunks<S>(
      model, q, p, opts, width, out_data,
      [&](std::span<const simd::Column<S>> cols, std::span<S* const> o, std::size_t count,
          std::span<const simd::Column<double>> params, const ChunkStorage& storage) {
        if (numpy_model) {  // one call per chunk (per set of its rows with equal parameters)
          std::vector<PyObject*> arrays;
          // Streamed where o is a part of the result arrays (not a group's scratch, read next).
          python_eval_rows<S>(*numpy_model, uniform_values(params), cols, o, count,
                              column_owners<S>(q, cols, storage, arrays),
                              in_results(o[0], out_data[0], n));
        } else
          simd::eval_batch_with_param_columns(model, params, cols, o, count, opts.isa, opts.math);
      },
      numpy_model == nullptr);
  py::dict r;
  r["value"] = outs[0];
  r["pdf"] = outs[1];
  for (std::size_t k = 0; k < model.intermediates.size(); ++k)
    r[py::str(std::string(model.intermediates[k]))] = outs[2 + k];
  return r;
}

py::dict eval(const std::string& name, const py::object& wi, const py::object& wo,
              const py::object& params, const py::object& footprint, const py::object& light,
              const std::string& precision, const py::object& isa, const std::string& math,
              const py::object& threads) {
  const ModelEntry& model = model_named(name);
  const cli::BatchOptions opts = batch_options(precision, isa, math, threads);
  if (wi.is_none() || wo.is_none()) throw py::value_error("wi and wo are required (valid: (N, 3) or (3,) arrays)");
  QuerySources q = query_sources(model, wi, wo, footprint, light, 0);
  const CallParams p = call_params(model, params, q.rows, q.keep_alive);
  if (q.rows == 0) q.rows = 1;
  return opts.float_precision ? eval_in<float>(model, q, p, opts)
                              : eval_in<double>(model, q, p, opts);
}

template <class S>
py::dict sample_in(const ModelEntry& model, const QuerySources& q, const CallParams& p,
                   const cli::BatchOptions& opts, const ColumnSource* u1, const ColumnSource* u2,
                   std::uint64_t seed) {
  const std::size_t n = q.rows, width = query_width(model);
  std::optional<PooledArrays> pooled(std::in_place);  // result_pool.h
  py::array_t<S, py::array::f_style> wo({py::ssize_t(n), py::ssize_t(3)});
  auto pdf = py::array_t<S>(py::ssize_t(n));
  auto weight = py::array_t<S>(py::ssize_t(n));
  auto rejected = py::array_t<S>(py::ssize_t(n));  // scratch, as 0 or 1 (given back on return)
  auto rej = py::array_t<bool>(py::ssize_t(n));
  pooled.reset();
  S* wo_data = wo.mutable_data();
  S* const out_data[6] = {wo_data, wo_data + n, wo_data + 2 * n, pdf.mutable_data(),
                          weight.mutable_data(), rejected.mutable_data()};
  const ColumnSource* const given_u[2] = {u1, u2};
  const auto check_u = [&](std::size_t r) -> std::optional<std::string> {
    for (const ColumnSource* u : {u1, u2}) {
      const double v = u->at(r);
      if (!(v >= 0 && v < 1))
        return fmt::format("row {}, {}: {} is out of range (valid: [0, 1))", r, u->origin, v);
    }
    return std::nullopt;
  };
  const PythonModel* const numpy_model = python_model(model);  // looked up once, with the GIL
  run_chunks<S>(
      model, q, p, opts, width, std::span<S* const>(out_data),
      [&](std::span<const simd::Column<S>> in, std::span<S* const> o, std::size_t count,
          std::span<const simd::Column<double>> params, const ChunkStorage& storage) {
        const auto cols = in.first(width);
        if (numpy_model) {
          std::vector<PyObject*> arrays;
          python_sample_rows<S>(*numpy_model, uniform_values(params), cols, in[width],
                                in[width + 1], o, count,
                                column_owners<S>(q, cols, storage, arrays),
                                in_results(o[3], out_data[3], n));
        } else
          simd::sample_batch_with_param_columns(model, params, cols, in[width], in[width + 1], o,
                                                count, opts.isa, opts.math);
      },
      numpy_model == nullptr, 2,
      // The CLI's counter-based stream (sample --model), or the caller's uniforms.
      [&](std::size_t begin, std::size_t count, std::span<S* const> uniforms) {
        for (std::size_t i = 0; i < count; ++i) {
          uniforms[0][i] =
              u1 ? S(u1->at(begin + i)) : S(counter_uniform<double>(seed, begin + i, 0));
          uniforms[1][i] =
              u2 ? S(u2->at(begin + i)) : S(counter_uniform<double>(seed, begin + i, 1));
        }
      },
      u1 ? RowCheck(check_u) : RowCheck(),
      u1 ? std::span<const ColumnSource* const>(given_u) : std::span<const ColumnSource* const>());
  bool* rd = rej.mutable_data();
  const S* rejected_data = rejected.data();
  for (std::size_t i = 0; i < n; ++i) rd[i] = rejected_data[i] != 0;
  py::dict r;
  r["wo"] = wo;
  r["pdf"] = pdf;
  r["weight"] = weight;
  r["rejected"] = rej;
  return r;
}

py::dict sample(const std::string& name, const py::object& wi, const py::object& u,
                const py::object& params, const py::object& footprint, const py::object& light,
                const py::object& n, const py::object& seed, const std::string& precision,
                const py::object& isa, const std::string& math, const py::object& threads) {
  const ModelEntry& model = model_named(name);
  const cli::BatchOptions opts = batch_options(precision, isa, math, threads);
  if (wi.is_none()) throw py::value_error("wi is required (valid: an (N, 3) or (3,) array)");
  if (u.is_none() == n.is_none()) {
    throw py::value_error(
        "u, n: give exactly one (valid: u an (N, 2) array of uniforms in [0, 1), or n= and "
        "seed= for the CLI's counter-based stream)");
  }
  if (!u.is_none() && !seed.is_none())
    throw py::value_error("seed: only with n= (valid: u= or n= with seed=)");
  std::size_t rows = 0;
  std::uint64_t s = 0;
  if (!n.is_none()) {
    try {
      rows = cli::integer_option(std::string(py::str(n)), "n", 1, 1000000000);
      s = seed.is_none() ? 0 : cli::integer_option(std::string(py::str(seed)), "seed", 0, UINT64_MAX);
    } catch (const cli::InputError& e) {
      throw py::value_error(e.what());
    }
  }
  QuerySources q = query_sources(model, wi, py::none(), footprint, light, rows);
  ColumnSource u1, u2;
  if (!u.is_none()) {
    const py::array a = py::array::ensure(u);
    if (!a || a.ndim() != 2 || a.shape(1) != 2)
      throw py::value_error("u: not an (N, 2) array (valid: (N, 2) uniforms in [0, 1))");
    py::object col0 = a[py::make_tuple(py::slice(py::none(), py::none(), py::none()), 0)];
    py::object col1 = a[py::make_tuple(py::slice(py::none(), py::none(), py::none()), 1)];
    u1 = column_source(col0, "u[:, 0]", q.rows, q.keep_alive);
    u2 = column_source(col1, "u[:, 1]", q.rows, q.keep_alive);
  }
  const CallParams p = call_params(model, params, q.rows, q.keep_alive);
  if (q.rows == 0) q.rows = 1;
  const ColumnSource* p1 = u.is_none() ? nullptr : &u1;
  const ColumnSource* p2 = u.is_none() ? nullptr : &u2;
  return opts.float_precision ? sample_in<float>(model, q, p, opts, p1, p2, s)
                              : sample_in<double>(model, q, p, opts, p1, p2, s);
}

// Where each query column of an eval call would be read from in `precision` as a contiguous
// column: the array's own memory (its address), or None (strided, so gathered by the batches block
// by block or by a numpy model's chunk; converted; or a constant). For the tests of the no-copy
// path.
py::dict column_addresses(const std::string& name, const py::object& wi, const py::object& wo,
                          const py::object& footprint, const py::object& light,
                          const std::string& precision) {
  const ModelEntry& model = model_named(name);
  const QuerySources q = query_sources(model, wi, wo, footprint, light, 0);
  py::dict d;
  for (std::size_t c = 0; c < query_width(model); ++c) {
    const ColumnSource& s = q.columns[c];
    const bool in_place = precision == "float" ? s.in_place<float>() : s.in_place<double>();
    d[py::str(std::string(kQueryLayout[c].name))] =
        in_place ? py::object(py::int_(reinterpret_cast<std::uintptr_t>(s.data)))
                 : py::object(py::none());
  }
  return d;
}

// The reference time of eval(): seconds of simd::eval_batch alone, one thread, over the same rows
// as eval(model, wi, wo) with the model's defaults, the columns laid out beforehand (untimed) as
// contiguous SoA columns of `precision`, run in the CLI's chunks: {"isa": the ISA's name,
// "seconds": one entry per repeat, "cpu_seconds": the same repeats' CPU time of the thread}. For the
// benchmark experiments/bench/python_eval.py, which compares eval() against it.
// This thread's CPU seconds (user and system).
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

template <class S>
std::vector<double> eval_batch_seconds_in(const ModelEntry& model, const QuerySources& q,
                                          const cli::BatchOptions& opts, int repeats,
                                          std::vector<double>& cpu_seconds) {
  const std::size_t n = q.rows, width = query_width(model);
  const std::vector<double> params = resolve_params(model, {});
  std::vector<std::vector<S>> data(width);
  std::vector<simd::Column<S>> cols;
  for (std::size_t c = 0; c < width; ++c) {
    const ColumnSource& s = q.columns[c];
    if (s.data == nullptr || s.stride == 0) {
      data[c].assign(1, S(s.at(0)));
      cols.push_back({data[c].data(), 0});
    } else {
      data[c].resize(n);
      for (std::size_t i = 0; i < n; ++i) data[c][i] = S(s.at(i));
      cols.push_back({data[c].data(), 1});
    }
  }
  std::vector<std::vector<S>> out(2 + model.intermediates.size(), std::vector<S>(n));
  std::vector<double> seconds;
  const py::gil_scoped_release release;
  for (int r = 0; r < repeats; ++r) {
    const double c0 = thread_cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t begin = 0; begin < n; begin += cli::kBatchChunk) {
      const std::size_t count = std::min(cli::kBatchChunk, n - begin);
      std::vector<simd::Column<S>> chunk = cols;
      for (simd::Column<S>& c : chunk) c.data += c.stride * begin;
      std::vector<S*> o;
      for (auto& column : out) o.push_back(column.data() + begin);
      simd::eval_batch(model, params, chunk, o, count, opts.isa, opts.math);
    }
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    cpu_seconds.push_back(thread_cpu_seconds() - c0);
  }
  return seconds;
}

py::dict eval_batch_seconds(const std::string& name, const py::object& wi,
                                       const py::object& wo, const std::string& precision,
                                       const py::object& isa, const std::string& math,
                                       int repeats) {
  const ModelEntry& model = model_named(name);
  const cli::BatchOptions opts = batch_options(precision, isa, math, py::int_(1));
  QuerySources q = query_sources(model, wi, wo, py::none(), py::none(), 0);
  if (q.rows == 0) q.rows = 1;
  py::dict d;
  d["isa"] = std::string(simd::isa_name(opts.isa));
  std::vector<double> cpu;
  d["seconds"] = opts.float_precision ? eval_batch_seconds_in<float>(model, q, opts, repeats, cpu)
                                      : eval_batch_seconds_in<double>(model, q, opts, repeats, cpu);
  d["cpu_seconds"] = cpu;
  return d;
}

// The result pool's counters (result_pool.h), after setting its idle limit when one is given.
py::dict result_pool(const py::object& idle_limit) {
  if (!idle_limit.is_none()) {
    const long long bytes = py::cast<long long>(idle_limit);
    if (bytes < 0)
      throw py::value_error(fmt::format(
          "idle_limit: {} is out of range (valid: bytes >= 0, or None to leave it)", bytes));
    set_result_pool_limit(std::size_t(bytes));
  }
  const ResultPoolStats s = result_pool_stats();
  py::dict d;
  d["idle_bytes"] = s.idle_bytes;
  d["idle_blocks"] = s.idle_blocks;
  d["live_bytes"] = s.live_bytes;
  d["live_blocks"] = s.live_blocks;
  d["reused"] = s.reused;
  d["mapped"] = s.mapped;
  d["unmapped"] = s.unmapped;
  d["idle_limit"] = s.idle_limit;
  d["min_block_bytes"] = kPoolMinBytes;
  return d;
}

// For the tests: a copy of registered model `model`'s entry under `name`, without its static
// model, so that the module knows its batches and its own query rules only through the entry's
// functions, as it knows a plug-in's rules (python/batch_call.cpp: no column form of them).
void register_entry_copy(const std::string& model, const std::string& name) {
  ModelEntry e = model_named(model);
  e.name = keep_text(name);
  e.static_model = nullptr;
  e.plugin_batches = nullptr;
  try {
    register_model(std::move(e));
  } catch (const ModelParamError& error) {
    throw py::value_error(error.what());
  }
}

std::vector<std::string> load_plugin(const std::string& path) {
  try {
    const std::vector<std::string_view> names = glintlab::load_plugin(path, "load_plugin");
    return {names.begin(), names.end()};
  } catch (const PluginError& e) {
    throw py::value_error(e.what());
  }
}

// `glintlab verify --claims ... --budget ...` without the files: claims.json's text. The model checks
// are generated from the registry as it stands now, so a model registered from Python after start-up
// has its model.<name>.* checks. As in the CLI, model checks are selected only by a pattern naming
// "model.". The checks run without the GIL (a Python model's calls take it per call).
std::string verify(const std::string& claims, const std::string& budget, const py::object& threads) {
  if (budget != "quick" && budget != "full")
    throw py::value_error(fmt::format("budget: '{}' is not a budget (valid: quick, full)", budget));
  const int thread_count = cli::resolve_threads(threads.is_none() ? std::string("0") : std::string(py::str(threads)));
  const bool conformance = claims.find("model.") != std::string::npos;
  std::vector<const verify::Check*> all;
  for (const verify::Check& c : verify::registered_checks())
    if (c.family.empty()) all.push_back(&c);
  const std::vector<verify::Check> model_checks =
      conformance ? verify::conformance_checks() : std::vector<verify::Check>{};
  for (const verify::Check& c : model_checks) all.push_back(&c);
  std::vector<std::string> ids;
  for (const verify::Check* c : all) ids.push_back(c->id);
  const std::vector<std::string> chosen =
      cli::select_by_globs(claims, "claims", ids, "claim ids (see glintlab verify --list)");
  const verify::Budget b = budget == "full" ? verify::Budget::kFull : verify::Budget::kQuick;
  std::vector<verify::RunRecord> records;
  {
    const py::gil_scoped_release release;
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    std::size_t(thread_count));
    for (const verify::Check* c : all) {
      if (std::find(chosen.begin(), chosen.end(), c->id) == chosen.end()) continue;
      const auto t0 = std::chrono::steady_clock::now();
      verify::CheckResult r = c->run(b);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      records.push_back({c, std::move(r), s, b});
    }
  }
  verify::adjust_for_suite(records);
  const verify::RunInfo info{
      budget, thread_count,
      fmt::format("{} hardware thread(s), {} used", std::thread::hardware_concurrency(), thread_count)};
  return verify::to_json(records, info);
}

// `glintlab figure`, `sweep`, `compare` and `adequacy` in this process (cli/suite_runs.h): the
// command line's checks and runs on the command line's option text, so the models registered here
// (register_model, load_plugin) are the registry they see. They run without the GIL; a Python
// model's functions take it per call, as in verify().
std::optional<std::string> optional_text(const py::object& o) {
  if (o.is_none()) return std::nullopt;
  return std::string(py::str(o));
}

std::string figure(const std::string& id, const std::string& out, const std::string& budget,
                   const std::string& threads, const std::string& env,
                   const py::object& bench_from) {
  cli::FigureRequest r;
  r.id = id;
  r.out = out;
  r.budget = budget;
  r.threads = threads;
  r.env = env;
  r.bench_from = optional_text(bench_from);
  const py::gil_scoped_release release;
  return cli::run_figure_request(r).string();
}

py::dict sweep(const std::string& out, const std::string& budget, const std::string& models,
               const std::string& threads) {
  cli::SweepRequest r;
  r.out = out;
  r.budget = budget;
  r.models = models;
  r.threads = threads;
  experiments::SweepRunSummary s;
  {
    const py::gil_scoped_release release;
    s = cli::run_sweep_request(r);
  }
  py::dict d;
  d["json"] = s.json.string();
  d["targets"] = s.targets;
  return d;
}

py::dict compare(const std::string& out, const std::string& budget, const std::string& models,
                 const std::string& threads, const std::string& claims_from,
                 const std::string& sweeps_from) {
  cli::CompareRequest r;
  r.out = out;
  r.budget = budget;
  r.models = models;
  r.threads = threads;
  r.claims_from = claims_from;
  r.sweeps_from = sweeps_from;
  cli::CompareSummary s;
  {
    const py::gil_scoped_release release;
    s = cli::run_compare_request(r);
  }
  py::dict d;
  d["dir"] = s.dir.string();
  d["models"] = s.models;
  return d;
}

py::dict adequacy(const std::string& out, const std::string& budget, const std::string& models,
                  const std::string& threshold, const std::string& threads, bool calibrate,
                  const py::object& runs, const py::object& tables,
                  const py::object& bench_from, const py::object& positions) {
  cli::AdequacyRequest r;
  r.out = out;
  r.budget = budget;
  r.models = models;
  r.threshold = threshold;
  r.threads = threads;
  r.calibrate = calibrate;
  r.runs = optional_text(runs);
  r.tables = optional_text(tables);
  r.bench_from = optional_text(bench_from);
  r.positions = optional_text(positions);
  cli::AdequacyRunSummary s;
  {
    const py::gil_scoped_release release;
    s = cli::run_adequacy_request(r);
  }
  py::dict d;
  d["seconds"] = s.seconds;
  if (s.calibrate) {
    d["json"] = s.calibration.json.string();
    d["csv"] = s.calibration.csv.string();
    return d;
  }
  const experiments::AdequacySummary& t = s.table;
  d["json"] = t.json.string();
  d["csv"] = t.csv.string();
  d["maps"] = t.maps;
  d["cells"] = t.cells;
  const char* const levels[] = {"smooth", "realtime", "small_count", "exact"};
  py::dict chosen, cheapest;
  for (std::size_t k = 0; k < 4; ++k) {
    chosen[levels[k]] = t.chosen[k];
    cheapest[levels[k]] = t.cheapest_measured[k];
  }
  d["chosen"] = chosen;
  d["cheapest_measured"] = cheapest;
  d["chooser_matches"] = t.chooser_matches;
  d["chooser_refuted"] = t.chooser_refuted;
  d["undecided"] = t.undecided;
  d["exact_ns"] = t.exact_ns;
  d["chosen_ns"] = t.chosen_ns;
  d["cheapest_ns"] = t.cheapest_ns;
  return d;
}

}  // namespace
}  // namespace glintlab::python

PYBIND11_MODULE(_glintlab, m) {
  using namespace glintlab::python;
  namespace py = pybind11;
  using py::arg;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const glintlab::cli::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const glintlab::ModelParamError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  m.doc() = "glintlab's C++ layer (see the glintlab package for the documented functions)";
  init_result_pool();
  m.def("models", &models);
  m.def("eval", &eval, arg("model"), arg("wi"), arg("wo"), arg("params") = py::none(),
        arg("footprint") = py::none(), arg("light") = py::none(), arg("precision") = "double",
        arg("isa") = py::none(), arg("math") = "exact", arg("threads") = py::none());
  m.def("sample", &sample, arg("model"), arg("wi"), arg("u") = py::none(),
        arg("params") = py::none(), arg("footprint") = py::none(), arg("light") = py::none(),
        arg("n") = py::none(), arg("seed") = py::none(), arg("precision") = "double",
        arg("isa") = py::none(), arg("math") = "exact", arg("threads") = py::none());
  m.def("column_addresses", &column_addresses, arg("model"), arg("wi"), arg("wo"),
        arg("footprint") = py::none(), arg("light") = py::none(), arg("precision") = "double");
  m.def("eval_batch_seconds", &eval_batch_seconds, arg("model"), arg("wi"), arg("wo"),
        arg("precision") = "double", arg("isa") = py::none(), arg("math") = "exact",
        arg("repeats") = 5);
  m.def("load_plugin", &load_plugin, arg("path"));
  m.def("_register_entry_copy", &register_entry_copy, arg("model"), arg("name"));
  m.def("result_pool", &result_pool, arg("idle_limit") = py::none());
  m.def("register_model", &register_python_model, arg("name"), arg("eval"), arg("pdf"),
        arg("sample"), arg("params") = py::none(), arg("needs") = py::none(),
        arg("smooth_limit") = py::none(), arg("description") = "", arg("source") = "",
        arg("not_claimed") = py::none(), arg("chunked") = true);
  m.def("verify", &verify, arg("claims"), arg("budget") = "quick", arg("threads") = py::none());
  m.def("figure", &figure, arg("id"), arg("out"), arg("budget"), arg("threads"), arg("env"),
        arg("bench_from"));
  m.def("sweep", &sweep, arg("out"), arg("budget"), arg("models"), arg("threads"));
  m.def("compare", &compare, arg("out"), arg("budget"), arg("models"), arg("threads"),
        arg("claims_from"), arg("sweeps_from"));
  m.def("adequacy", &adequacy, arg("out"), arg("budget"), arg("models"), arg("threshold"),
        arg("threads"), arg("calibrate"), arg("runs"), arg("tables"), arg("bench_from"),
        arg("positions"));
}

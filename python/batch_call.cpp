// One eval or sample call over the batch API; see batch_call.h.
#include "python/batch_call.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <mutex>

#include "cli/commands.h"
#include "cli/eval_model.h"

namespace glintlab::python {
namespace {

std::string number_text(double v) { return fmt::format("{}", v); }

// resolve_params on one (name, text): the value, or the CLI's message prefixed with `where`.
double checked_value(const ModelEntry& model, const std::string& name, const std::string& text,
                     const std::string& where) {
  try {
    const std::vector<double> v = resolve_params(model, {{name, text}});
    std::size_t k = 0;
    while (model.params[k].name != name) ++k;
    return v[k];
  } catch (const ModelParamError& e) {
    throw py::value_error(where.empty() ? std::string(e.what()) : where + ": " + e.what());
  }
}

// A per-row array's values: each distinct one checked as --param would check it, an error naming
// the first row that holds it. O(N log N): the rows are sorted by (value, row) once.
void check_per_row(const ModelEntry& model, const ParamSpec& p, const ColumnSource& s,
                   std::size_t rows) {
  std::vector<std::pair<double, std::size_t>> seen;
  seen.reserve(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    const double v = s.at(r);
    if (!std::isfinite(v)) {
      checked_value(model, std::string(p.name), number_text(v),
                    fmt::format("params['{}'] row {}", p.name, r));
    }
    seen.emplace_back(v, r);
  }
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end(),
                         [](const auto& a, const auto& b) { return a.first == b.first; }),
             seen.end());
  for (const auto& [v, first_row] : seen) {
    // A choice is given per row by its index (the value models() lists as its default).
    const bool index = v >= 0 && std::floor(v) == v && v < double(p.choices.size());
    const std::string text =
        p.choices.empty() ? number_text(v)
                          : index ? std::string(p.choices[std::size_t(v)]) : number_text(v);
    checked_value(model, std::string(p.name), text,
                  fmt::format("params['{}'] row {}", p.name, first_row));
  }
}

}  // namespace

CallParams call_params(const ModelEntry& model, const py::object& params, std::size_t& rows,
                       std::vector<py::object>& keep_alive) {
  CallParams out;
  out.constant = resolve_params(model, {});
  if (params.is_none()) return out;
  if (!py::isinstance<py::dict>(params))
    throw py::value_error("params: not a dict (valid: a dict of parameter name -> value)");
  std::vector<std::pair<std::string, std::string>> texts;
  for (const auto& [key, item] : py::cast<py::dict>(params)) {
    const std::string name = py::str(key);
    if (py::isinstance<py::str>(item)) {
      texts.emplace_back(name, py::cast<std::string>(item));
    } else if (py::isinstance<py::float_>(item) || py::isinstance<py::int_>(item) ||
               (py::isinstance<py::array>(item) && py::cast<py::array>(item).ndim() == 0)) {
      texts.emplace_back(name, number_text(py::cast<double>(item)));
    } else {
      std::size_t k = 0;
      while (k < model.params.size() && model.params[k].name != name) ++k;
      if (k == model.params.size()) checked_value(model, name, "0", "");  // the unknown-name error
      ColumnSource s = column_source(item, fmt::format("params['{}']", name), rows, keep_alive);
      out.per_row.emplace_back(k, std::move(s));
    }
  }
  try {
    const std::vector<double> resolved = resolve_params(model, texts);
    for (const auto& [name, text] : texts) {
      std::size_t k = 0;
      while (model.params[k].name != name) ++k;
      out.constant[k] = resolved[k];
    }
  } catch (const ModelParamError& e) {
    throw py::value_error(e.what());
  }
  for (const auto& [k, s] : out.per_row) {
    for (const auto& [name, text] : texts)
      if (name == model.params[k].name)
        throw py::value_error(fmt::format("--param {}: given twice", name));
    check_per_row(model, model.params[k], s, std::max<std::size_t>(rows, 1));
  }
  return out;
}

cli::BatchOptions batch_options(const std::string& precision, const py::object& isa,
                                const std::string& math, const py::object& threads) {
  cli::BatchOptionTexts t;
  t.precision = precision;
  t.math = math;
  if (!isa.is_none()) t.isa = py::cast<std::string>(isa);
  if (!threads.is_none()) t.threads = std::string(py::str(threads));
  try {
    return cli::resolve_batch_options(t);
  } catch (const cli::InputError& e) {
    throw py::value_error(e.what());
  }
}

void run_chunks(const ModelEntry& model, const QuerySources& q, const CallParams& p,
                const cli::BatchOptions& opts,
                const std::function<void(std::size_t, std::size_t, const std::vector<double>&)>& f,
                const std::function<std::optional<std::string>(std::size_t)>& extra_check) {
  const std::size_t n = q.rows;
  std::mutex bad_mutex;
  std::optional<std::pair<std::size_t, std::string>> first_bad;
  {
    py::gil_scoped_release release;
    cli::for_each_chunk(n, opts, [&](std::size_t begin, std::size_t count) {
      for (std::size_t r = begin; r < begin + count; ++r) {
        std::optional<std::string> bad;
        try {
          cli::check_query_row(model, query_row(q.columns, r), [&](std::string_view column) {
            std::string origin = fmt::format("row {}", r);
            for (std::size_t c = 0; c < kQueryLayout.size(); ++c)
              if (kQueryLayout[c].name == column) origin += ", " + q.columns[c].origin;
            return origin;
          });
          if (extra_check) bad = extra_check(r);
        } catch (const cli::InputError& e) {
          bad = e.what();
        }
        if (bad) {
          const std::lock_guard<std::mutex> lock(bad_mutex);
          if (!first_bad || r < first_bad->first) first_bad.emplace(r, *bad);
          return;
        }
      }
      std::vector<double> values = p.constant, next = p.constant;
      std::size_t run = begin;
      while (run < begin + count) {
        p.at(run, values);
        std::size_t end = run + 1;
        for (; end < begin + count; ++end) {
          p.at(end, next);
          if (next != values) break;
        }
        f(run, end - run, values);
        run = end;
      }
    });
  }
  if (first_bad) throw py::value_error(first_bad->second);
}

}  // namespace glintlab::python

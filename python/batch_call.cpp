// One eval or sample call over the batch API; see batch_call.h.
#include "python/batch_call.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <type_traits>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/eval_model.h"
#include "core/model_list.h"
#include "core/simd/model_batch.h"
#include "python/result_pool.h"

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

// Whether `v` surely passes resolve_params as a per-row value of `p`: a choice by its index, or a
// finite number in range (and whole where integral). resolve_params reads the number's shortest
// text, which parses back to v, so this is its rule without the text.
bool surely_valid_value(const ParamSpec& p, double v) {
  if (!p.choices.empty()) return v >= 0 && std::floor(v) == v && v < double(p.choices.size());
  const bool in_range =
      (p.lo_open ? v > p.lo : v >= p.lo) && (p.hi_open ? v < p.hi : v <= p.hi);
  return std::isfinite(v) && in_range && (!p.integral || std::floor(v) == v);
}

// A per-row array's values: each distinct one checked as --param would check it, an error naming
// the first row that holds it. O(N) when every value passes (surely_valid_value, one pass);
// otherwise O(N log N) for the message: the rows sorted by (value, row), the smallest bad value
// reported.
void check_per_row(const ModelEntry& model, const ParamSpec& p, const ColumnSource& s,
                   std::size_t rows) {
  bool all_valid = true;
  for (std::size_t r = 0; r < rows; ++r) all_valid &= surely_valid_value(p, s.at(r));
  if (all_valid) return;
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

// eval --model's checks (cli::check_query_row) on rows [begin, begin + count), row by row, then
// `extra_check`: the first bad row and its message, or nothing.
std::optional<std::pair<std::size_t, std::string>> first_bad_row(
    const ModelEntry& model, const QuerySources& q, std::size_t begin, std::size_t count,
    const RowCheck& extra_check) {
  for (std::size_t r = begin; r < begin + count; ++r) {
    try {
      cli::check_query_row(model, query_row(q.columns, r), [&](std::string_view column) {
        std::string origin = fmt::format("row {}", r);
        for (std::size_t c = 0; c < kQueryLayout.size(); ++c)
          if (kQueryLayout[c].name == column) origin += ", " + q.columns[c].origin;
        return origin;
      });
      if (extra_check)
        if (std::optional<std::string> bad = extra_check(r)) return std::pair{r, std::move(*bad)};
    } catch (const cli::InputError& e) {
      return std::pair{r, std::string(e.what())};
    }
  }
  return std::nullopt;
}

// Bounds on a squared length a little inside eval --model's unit tolerance (|length - 1| <= 1e-6):
// a length whose square lies within them passes in any rounding.
constexpr double kUnitSquaredLo = (1 - cli::kUnitTolerance) * (1 - cli::kUnitTolerance) * (1 + 1e-9);
constexpr double kUnitSquaredHi = (1 + cli::kUnitTolerance) * (1 + cli::kUnitTolerance) * (1 - 1e-9);

constexpr std::uint64_t kSignBit = 0x8000000000000000ULL;
constexpr std::uint64_t kInfinityBits = 0x7ff0000000000000ULL;

// Whether |(x, y, z)|^2 of each row lies in [kUnitSquaredLo, kUnitSquaredHi] (NaN and infinity do
// not). On the bits, so that the loop vectorises (a reduction over bool does not): for the
// squared length's pattern u and the bounds' patterns lo <= hi (positive doubles order as their
// patterns), u - lo and hi - u both have their sign bit clear exactly when lo <= u <= hi, for
// every pattern (NaN of either sign, infinity and -0 included).
constexpr std::uint64_t kUnitLoBits = std::bit_cast<std::uint64_t>(kUnitSquaredLo);
constexpr std::uint64_t kUnitHiBits = std::bit_cast<std::uint64_t>(kUnitSquaredHi);
inline std::uint64_t outside_unit_bits(double a, double b, double c) {
  const std::uint64_t u = std::bit_cast<std::uint64_t>(a * a + b * b + c * c);
  return (u - kUnitLoBits) | (kUnitHiBits - u);
}
template <bool kContiguous>
bool squared_lengths_in_bounds(const simd::Column<double>& x, const simd::Column<double>& y,
                               const simd::Column<double>& z, std::size_t count) {
  const std::size_t sx = kContiguous ? 1 : x.stride, sy = kContiguous ? 1 : y.stride,
                    sz = kContiguous ? 1 : z.stride;
  std::uint64_t out = 0;
  for (std::size_t i = 0; i < count; ++i)
    out |= outside_unit_bits(x.data[sx * i], y.data[sy * i], z.data[sz * i]);
  return (out & kSignBit) == 0;
}
// The same for the rows of a C-ordered (N, 3) array read where it lies (row i at p[3i .. 3i+2]:
// constant strides, which the compiler vectorises), asking for the next chunk's rows on the way
// (for_row_blocks_prefetching, query_columns.h), so that they arrive while this chunk is evaluated.
GLINTLAB_PYTHON_CLONES
bool rows_in_bounds(const double* p, std::size_t count) {
  std::uint64_t out = 0;
  for_row_blocks_prefetching(p, count, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      out |= outside_unit_bits(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  });
  return (out & kSignBit) == 0;
}

// Whether every value of a column is finite (on the bits, as above: |v|'s pattern minus
// infinity's has its sign bit set exactly when v is finite).
bool all_finite(const simd::Column<double>& c, std::size_t count) {
  const auto not_finite = [](double v) {
    return ~((std::bit_cast<std::uint64_t>(v) & ~kSignBit) - kInfinityBits);
  };
  std::uint64_t out = 0;
  if (c.stride <= 1) {
    for (std::size_t i = 0; i < count; ++i) out |= not_finite(c.data[i]);
  } else {
    for (std::size_t i = 0; i < count; ++i) out |= not_finite(c.data[c.stride * i]);
  }
  return (out & kSignBit) == 0;
}

// The model's own rules (ModelEntry::validate) over rows [0, count) of query columns (kQueryLayout
// order, every column of the layout, any stride) in one pass: the first row they refuse, or
// count. Each row's query is read column by column into a ModelQuery; for the built-in models
// (found by their static_model tag) M::validate is inlined into the loop, so that only the columns
// its rules read are loaded (rows_validator); for any other entry with rules (a plug-in's, whose
// M::validate is compiled into the plug-in, or an entry built by hand) the entry's function is
// called on each loaded query (first_invalid_row_by_entry): through the plain function pointer it
// holds where it holds one (what make_model_entry stores for M::validate), else through the
// std::function. Either way the caller only learns whether a chunk may hold a refused row; the
// row and its message come from the exact checks.
template <class Validate>
std::size_t first_invalid_row_calling(std::span<const simd::Column<double>> cols,
                                      std::size_t count, Validate&& validate) {
  for (std::size_t i = 0; i < count; ++i) {
    ModelQuery<double> query{};
    for_each_query_column(query, [&](std::size_t k, const QueryColumn&, double& member) {
      member = cols[k].data[cols[k].stride * i];
    });
    if (validate(query)) return i;
  }
  return count;
}
template <class M>
std::size_t first_invalid_row_of(std::span<const simd::Column<double>> cols, std::size_t count) {
  return first_invalid_row_calling(cols, count, [](const ModelQuery<double>& q) {
    return M::validate(q);
  });
}
std::size_t first_invalid_row_by_entry(const ModelEntry& model,
                                       std::span<const simd::Column<double>> cols,
                                       std::size_t count) {
  using Rule = std::optional<QueryViolation> (*)(const ModelQuery<double>&);
  if (const Rule* rule = model.validate.target<Rule>(); rule != nullptr && *rule != nullptr)
    return first_invalid_row_calling(cols, count, *rule);
  return first_invalid_row_calling(cols, count, model.validate);
}
using RowsValidator = std::size_t (*)(std::span<const simd::Column<double>>, std::size_t);
template <class... Ms>
RowsValidator rows_validator_of(const ModelEntry& model, ModelList<Ms...>) {
  RowsValidator found = nullptr;
  const auto match = [&]<class M>() {
    if constexpr (ValidatesQuery<M>) {
      if (model.static_model == static_model_tag<M>() && model.validate)
        found = &first_invalid_row_of<M>;
    }
  };
  (match.template operator()<Ms>(), ...);
  return found;
}
RowsValidator rows_validator(const ModelEntry& model) {
  return rows_validator_of(model, BuiltinModels{});
}

// Whether every row of a chunk surely passes check_query_row's rules: every checked column
// finite, unit wi and wo (and the corner vectors where the model reads them), the light's range,
// and the model's own rules (validate) by their pass over the columns (rows_validator, or
// first_invalid_row_by_entry for a model whose rules have no column form here). `cols`:
// the chunk's columns in double (the values the rules read; any stride), `width` of them (the
// corners only where the model reads them, as check_query_row skips them otherwise). Branch-free
// passes over the columns; a squared length is tested against bounds a little inside the unit
// tolerance, so a row it passes passes |length - 1| <= 1e-6 in any rounding (and is finite), and
// a row near the bound goes to the exact checks (which then pass or name it).
bool rows_surely_valid(const ModelEntry& model, const QuerySources& q,
                       std::span<const simd::Column<double>> cols, std::size_t count,
                       const FusedUnitCheck* fused = nullptr) {
  const auto rows_of = [count](const simd::Column<double>& c) { return c.stride == 0 ? 1 : count; };
  bool bad = false;
  std::vector<bool> direction(cols.size(), false);
  const auto unit = [&](std::size_t first) {
    const simd::Column<double> &x = cols[first], &y = cols[first + 1], &z = cols[first + 2];
    direction[first] = direction[first + 1] = direction[first + 2] = true;
    // Tested by the gather already (chunk_columns with `fused`).
    if (fused != nullptr) {
      for (const auto& [column, outside] : fused->found) {
        if (column != first) continue;
        bad |= (outside & kSignBit) != 0;
        return;
      }
    }
    // The usual cases, three contiguous columns or the rows of a C-ordered (N, 3) array, as loops
    // of their own the compiler vectorises.
    if (x.stride == 1 && y.stride == 1 && z.stride == 1)
      bad |= !squared_lengths_in_bounds<true>(x, y, z, count);
    else if (x.stride == 3 && y.stride == 3 && z.stride == 3 && y.data == x.data + 1 &&
             z.data == x.data + 2)
      bad |= !rows_in_bounds(x.data, count);
    else
      bad |= !squared_lengths_in_bounds<false>(x, y, z, count);
  };
  unit(query_column_index("wi_x"));
  unit(query_column_index("wo_x"));
  for (std::size_t first = simd::kQueryColumns.size(); first + 2 < cols.size(); first += 3)
    unit(first);
  // Finite: the columns the unit tests did not already cover.
  for (std::size_t j = 0; j < cols.size(); ++j)
    if (!direction[j]) bad |= !all_finite(cols[j], rows_of(cols[j]));
  const simd::Column<double>& cos = cols[query_column_index("light_cos_half_angle")];
  for (std::size_t i = 0; i < rows_of(cos); ++i)
    bad |= !(cos.data[cos.stride * i] >= -1) | !(cos.data[cos.stride * i] <= 1);
  const simd::Column<double>& intensity = cols[query_column_index("light_intensity")];
  for (std::size_t i = 0; i < rows_of(intensity); ++i)
    bad |= !(intensity.data[intensity.stride * i] >= 0);
  if (!bad && model.validate) {
    // The model's own rules over every column of the layout: the columns the batch does not
    // take (the corners of a model that does not read them) are the layout's defaults unless the
    // caller gave them, which leaves them to the exact checks.
    std::array<simd::Column<double>, kQueryLayout.size()> all;
    for (std::size_t j = 0; j < all.size(); ++j) {
      all[j] = j < cols.size() ? cols[j] : simd::Column<double>{&q.columns[j].constant, 0};
      bad |= j >= cols.size() && q.columns[j].data != nullptr;
    }
    if (!bad) {
      const RowsValidator validate_rows = rows_validator(model);
      bad = (validate_rows != nullptr ? validate_rows(all, count)
                                      : first_invalid_row_by_entry(model, all, count)) != count;
    }
  }
  return !bad;
}

// The rows of a chunk grouped by their per-row parameter values, compared by bit pattern (each
// row evaluated with exactly its own values): group g is rows order[start[g]] .. order[start[g+1]
// - 1], increasing; groups in the order of their first rows. O(count): each row's values hashed
// into an open-addressing table of the groups' first rows, then a counting sort.
struct RowGroups {
  std::vector<std::uint64_t> bits;       // row i's values at [i * k, (i + 1) * k)
  std::vector<std::uint32_t> table;      // group + 1 per slot, 0 empty
  std::vector<std::uint32_t> first_row;  // per group
  std::vector<std::uint32_t> group_of;   // per row
  std::vector<std::uint32_t> order, start;

  void build(const CallParams& p, std::size_t begin, std::size_t count) {
    const std::size_t k = p.per_row.size();
    bits.resize(count * k);
    for (std::size_t j = 0; j < k; ++j) {
      const ColumnSource& s = p.per_row[j].second;
      for (std::size_t i = 0; i < count; ++i)
        bits[i * k + j] = std::bit_cast<std::uint64_t>(s.at(begin + i));
    }
    std::size_t slots = 16;
    while (slots < 2 * count) slots *= 2;
    table.assign(slots, 0);
    first_row.clear();
    group_of.resize(count);
    const auto same = [&](std::size_t a, std::size_t b) {
      return std::equal(bits.begin() + std::ptrdiff_t(a * k), bits.begin() + std::ptrdiff_t(a * k + k),
                        bits.begin() + std::ptrdiff_t(b * k));
    };
    for (std::size_t i = 0; i < count; ++i) {
      std::uint64_t h = 0x9e3779b97f4a7c15ULL;
      for (std::size_t j = 0; j < k; ++j) h = (h ^ bits[i * k + j]) * 0xff51afd7ed558ccdULL;
      std::size_t slot = std::size_t(h ^ (h >> 29)) & (slots - 1);
      while (table[slot] != 0 && !same(first_row[table[slot] - 1], i)) slot = (slot + 1) & (slots - 1);
      if (table[slot] == 0) {
        first_row.push_back(std::uint32_t(i));
        table[slot] = std::uint32_t(first_row.size());
      }
      group_of[i] = table[slot] - 1;
    }
    start.assign(first_row.size() + 1, 0);
    for (std::size_t i = 0; i < count; ++i) ++start[group_of[i] + 1];
    for (std::size_t g = 0; g < first_row.size(); ++g) start[g + 1] += start[g];
    order.resize(count);
    std::vector<std::uint32_t>& next = table;  // reused as each group's fill position
    next.assign(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < count; ++i) order[next[group_of[i]]++] = std::uint32_t(i);
  }
  std::size_t groups() const { return first_row.size(); }
};

// Per worker thread, kept across chunks and calls (a fresh chunk-sized buffer would be fresh pages
// for every chunk).
template <class S>
struct ChunkBuffers {
  std::vector<S> gathered, extra, group_in, group_out;
  FusedUnitCheck fused;
  std::vector<double> check, param_rows;
  RowGroups groups;
};

// Rows [0, n) in chunks of `rows` rows (a multiple of the CLI's kBatchChunk) on opts.threads
// threads, f(begin, count): the CLI's loop (cli::for_each_chunk) run over the chunks' numbers, each
// a range of kBatchChunk of its rows, so that the threads and their limit are the CLI's.
void for_each_chunk_of(std::size_t n, std::size_t rows, const cli::BatchOptions& opts,
                       const std::function<void(std::size_t begin, std::size_t count)>& f) {
  const std::size_t chunks = (n + rows - 1) / rows;
  cli::for_each_chunk(chunks * cli::kBatchChunk, opts, [&](std::size_t number, std::size_t) {
    const std::size_t begin = number / cli::kBatchChunk * rows;
    f(begin, std::min(rows, n - begin));
  });
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
      out.per_row_sources.push_back(s);
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

template <class S>
void run_chunks(const ModelEntry& model, const QuerySources& q, const CallParams& p,
                const cli::BatchOptions& opts, std::size_t width, std::span<S* const> outputs,
                const BatchFn<S>& f, bool per_row_columns, std::size_t extra_columns,
                const ExtraFn<S>& extra, const RowCheck& extra_check,
                std::span<const ColumnSource* const> unit_interval) {
  const std::size_t n = q.rows, n_out = outputs.size();
  std::mutex bad_mutex;
  std::optional<std::pair<std::size_t, std::string>> first_bad;
  {
    py::gil_scoped_release release;
    for_each_chunk_of(n, per_row_columns ? cli::kBatchChunk : kNumpyModelChunk, opts,
                      [&](std::size_t begin, std::size_t count) {
      thread_local ChunkBuffers<S> b;
      // A numpy model's chunk gathers into memory of its own, which its functions get views of
      // (python_model.h, ColumnOwners); the batches' into the thread's buffer.
      ChunkStorage storage;
      S* gather_into = nullptr;
      if (per_row_columns) {
        if (b.gathered.size() < width * count) b.gathered.resize(width * count);
        gather_into = b.gathered.data();
      } else {
        // From the pool (result_pool.h): the block the previous chunk gave back, its pages mapped
        // and its lines likely still cached, whatever malloc would do with a block of this size.
        const std::shared_ptr<void> block = pooled_block(width * count * sizeof(S));
        gather_into = static_cast<S*>(block.get());
        storage = {block, gather_into, gather_into + width * count};
      }
      // The batches read a coordinate of a C-ordered (N, 3) array where it lies (stride 3:
      // core/simd/model_batch.h gathers it block by block); a numpy model's functions get
      // contiguous columns.
      // A numpy model's gather of a C-ordered (N, 3) array in double tests the squared lengths
      // of its rows on the way (one pass over them instead of two).
      FusedUnitCheck& fused = b.fused;
      fused.found.clear();
      fused.lo = kUnitLoBits;
      fused.hi = kUnitHiBits;
      FusedUnitCheck* const fuse = per_row_columns ? nullptr : &fused;
      std::vector<simd::Column<S>> inputs =
          chunk_columns<S>(q.columns, width, begin, count, gather_into, per_row_columns, fuse);

      // The rules of check_query_row on the chunk's columns (the model's own by a pass over
      // them, rows_surely_valid); a caller's extra check other than the unit interval's is per
      // row, so it takes the exact route.
      bool surely_valid = !extra_check || !unit_interval.empty();
      for (const ColumnSource* u : unit_interval) {
        bool outside = false;
        for (std::size_t i = 0; i < count; ++i) {
          const double v = u->at(begin + i);
          outside |= !(v >= 0) | !(v < 1);
        }
        surely_valid &= !outside;
      }
      if (surely_valid) {
        if constexpr (std::is_same_v<S, double>) {
          surely_valid = rows_surely_valid(model, q, inputs, count, fuse);
        } else {
          const auto in_double =
              chunk_columns<double>(q.columns, width, begin, count, b.check, true);
          surely_valid = rows_surely_valid(model, q, in_double, count);
        }
      }
      if (!surely_valid) {
        if (auto bad = first_bad_row(model, q, begin, count, extra_check)) {
          const std::lock_guard<std::mutex> lock(bad_mutex);
          if (!first_bad || bad->first < first_bad->first) first_bad = std::move(bad);
          return;
        }
      }

      if (extra_columns > 0) {
        if (b.extra.size() < extra_columns * count) b.extra.resize(extra_columns * count);
        std::vector<S*> extra_data;
        for (std::size_t k = 0; k < extra_columns; ++k) {
          extra_data.push_back(b.extra.data() + k * count);
          inputs.push_back({extra_data.back(), 1});
        }
        extra(begin, count, extra_data);
      }
      std::vector<S*> out(n_out);
      // The columns f reads, rebuilt for each set of rows (allocated once, with the chunk's).
      std::vector<simd::Column<S>> at(inputs.size());
      // A column per parameter: stride 0 on `values` (the call's constants and, grouped, the
      // group's per-row values), or the chunk's rows of a per-row array.
      std::vector<double> values = p.constant;
      std::vector<simd::Column<double>> param_columns(values.size());
      for (std::size_t k = 0; k < values.size(); ++k) param_columns[k] = {&values[k], 0};
      const auto in_place = [&](std::size_t first, std::size_t rows) {
        for (std::size_t c = 0; c < inputs.size(); ++c)
          at[c] = {inputs[c].data + inputs[c].stride * first, inputs[c].stride};
        for (std::size_t o = 0; o < n_out; ++o) out[o] = outputs[o] + begin + first;
        f(at, out, rows, param_columns, storage);
      };
      if (p.per_row.empty()) {
        in_place(0, count);
        return;
      }
      if (per_row_columns) {
        const std::vector<simd::Column<double>> rows = chunk_columns<double>(
            p.per_row_sources, p.per_row_sources.size(), begin, count, b.param_rows);
        for (std::size_t j = 0; j < p.per_row.size(); ++j) param_columns[p.per_row[j].first] = rows[j];
        in_place(0, count);
        return;
      }
      RowGroups& g = b.groups;
      g.build(p, begin, count);
      for (std::size_t k = 0; k < g.groups(); ++k) {
        const std::uint32_t* rows = g.order.data() + g.start[k];
        const std::size_t size = g.start[k + 1] - g.start[k];
        p.at(begin + rows[0], values);
        if (rows[size - 1] - rows[0] + 1 == size) {
          in_place(rows[0], size);  // adjacent rows: the chunk's columns as they are
          continue;
        }
        // Scattered rows: gathered into full batches, the results scattered back.
        if (b.group_in.size() < inputs.size() * size) b.group_in.resize(inputs.size() * size);
        if (b.group_out.size() < n_out * size) b.group_out.resize(n_out * size);
        for (std::size_t c = 0; c < inputs.size(); ++c) {
          at[c] = inputs[c];
          if (inputs[c].stride == 0) continue;
          S* dst = b.group_in.data() + c * size;
          for (std::size_t i = 0; i < size; ++i) dst[i] = inputs[c].data[rows[i]];
          at[c] = {dst, 1};
        }
        for (std::size_t o = 0; o < n_out; ++o) out[o] = b.group_out.data() + o * size;
        f(at, out, size, param_columns, storage);
        for (std::size_t o = 0; o < n_out; ++o)
          for (std::size_t i = 0; i < size; ++i) outputs[o][begin + rows[i]] = out[o][i];
      }
    });
  }
  if (first_bad) throw py::value_error(first_bad->second);
}

template void run_chunks<float>(const ModelEntry&, const QuerySources&, const CallParams&,
                                const cli::BatchOptions&, std::size_t, std::span<float* const>,
                                const BatchFn<float>&, bool, std::size_t, const ExtraFn<float>&,
                                const RowCheck&, std::span<const ColumnSource* const>);
template void run_chunks<double>(const ModelEntry&, const QuerySources&, const CallParams&,
                                 const cli::BatchOptions&, std::size_t, std::span<double* const>,
                                 const BatchFn<double>&, bool, std::size_t, const ExtraFn<double>&,
                                 const RowCheck&, std::span<const ColumnSource* const>);

}  // namespace glintlab::python

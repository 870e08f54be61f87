// The query of a Python call as columns; see query_columns.h.
#include "python/query_columns.h"

#include <fmt/format.h>

#include <string_view>

#include "cli/eval_model.h"

namespace glintlab::python {
namespace {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d)
    s += fmt::format("{}{}", d ? ", " : "", a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// float32 and float64 arrays as they are, any other real dtype converted to float64 once.
py::array real_array(const py::handle& value, const std::string& name,
                     std::vector<py::object>& keep_alive) {
  py::array a = py::array::ensure(value);
  if (!a) throw py::value_error(fmt::format("{}: not an array of numbers (valid: real numbers)", name));
  const char kind = a.dtype().kind();
  const bool real = kind == 'f' || kind == 'i' || kind == 'u' || kind == 'b';
  if (!real) {
    throw py::value_error(fmt::format("{}: dtype {} is not real (valid: float32, float64 or an "
                                      "integer type)",
                                      name, std::string(py::str(a.dtype()))));
  }
  const bool usable = kind == 'f' && (a.itemsize() == 4 || a.itemsize() == 8);
  const bool aligned = a.ndim() == 0 || [&] {
    for (py::ssize_t d = 0; d < a.ndim(); ++d)
      if (a.strides(d) % a.itemsize() != 0) return false;
    return true;
  }();
  if (!usable || !aligned) a = py::array_t<double, py::array::forcecast>::ensure(a);
  keep_alive.push_back(a);
  return a;
}

ColumnSource source_of(const py::array& a, std::ptrdiff_t offset_elements, py::ssize_t axis,
                       std::string origin) {
  ColumnSource s;
  s.is_float = a.itemsize() == 4;
  s.data = static_cast<const char*>(a.data()) + offset_elements * a.itemsize();
  s.stride = axis < 0 ? 0 : a.strides(axis) / a.itemsize();
  s.origin = std::move(origin);
  s.owner = a.ptr();
  return s;
}

void match_rows(std::size_t& rows, std::size_t n, const std::string& name, const std::string& shape) {
  if (rows == 0) rows = n;
  if (rows != n) {
    throw py::value_error(
        fmt::format("{}: shape {} has {} rows, the other inputs {} (valid: the same row count N "
                    "everywhere, or one row broadcast)",
                    name, shape, n, rows));
  }
}

// wi or wo: (N, 3) or (3,) into three sources at `first`.
void direction_sources(const py::object& value, const std::string& name, std::size_t first,
                       QuerySources& q) {
  if (value.is_none()) return;
  const py::array a = real_array(value, name, q.keep_alive);
  const bool one = a.ndim() == 1 && a.shape(0) == 3;
  const bool many = a.ndim() == 2 && a.shape(1) == 3;
  if (!one && !many) {
    throw py::value_error(
        fmt::format("{}: shape {} is not a direction array (valid: (N, 3) or (3,))", name,
                    shape_text(a)));
  }
  if (many) match_rows(q.rows, std::size_t(a.shape(0)), name, shape_text(a));
  for (std::size_t k = 0; k < 3; ++k) {
    const std::ptrdiff_t offset = many ? a.strides(1) / a.itemsize() * std::ptrdiff_t(k)
                                       : a.strides(0) / a.itemsize() * std::ptrdiff_t(k);
    q.columns[first + k] =
        source_of(a, offset, many ? 0 : -1, fmt::format("{}[{}{}]", name, many ? ":, " : "", k));
  }
}

// footprint or light: a dict of the layout's column names of `parts`.
void dict_sources(const py::object& value, const std::string& name,
                  std::initializer_list<QueryPart> parts, QuerySources& q) {
  if (value.is_none()) return;
  if (!py::isinstance<py::dict>(value))
    throw py::value_error(fmt::format("{}: not a dict (valid: a dict of column name -> value)", name));
  std::string valid;
  for (const QueryColumn& c : kQueryLayout)
    for (QueryPart p : parts)
      if (c.part == p) valid += fmt::format("{}{}", valid.empty() ? "" : ", ", c.name);
  for (const auto& [key, item] : py::cast<py::dict>(value)) {
    const std::string k = py::str(key);
    std::size_t c = 0;
    bool known = false;
    for (; c < kQueryLayout.size(); ++c) {
      if (kQueryLayout[c].name != k) continue;
      for (QueryPart p : parts) known = known || kQueryLayout[c].part == p;
      break;
    }
    if (!known)
      throw py::value_error(fmt::format("{}: unknown column '{}' (valid: {})", name, k, valid));
    q.columns[c] = column_source(item, fmt::format("{}['{}']", name, k), q.rows, q.keep_alive);
  }
}

}  // namespace

ColumnSource column_source(const py::handle& value, const std::string& name, std::size_t& rows,
                           std::vector<py::object>& keep_alive) {
  const py::array a = real_array(value, name, keep_alive);
  if (a.ndim() == 0) return source_of(a, 0, -1, name);
  if (a.ndim() != 1) {
    throw py::value_error(
        fmt::format("{}: shape {} is not a column (valid: a scalar or an (N,) array)", name,
                    shape_text(a)));
  }
  match_rows(rows, std::size_t(a.shape(0)), name, shape_text(a));
  return source_of(a, 0, 0, name);
}

QuerySources query_sources(const ModelEntry& model, const py::object& wi, const py::object& wo,
                           const py::object& footprint, const py::object& light,
                           std::size_t rows) {
  QuerySources q;
  q.rows = rows;
  for (const QueryColumn& c : kQueryLayout) {
    ColumnSource s;
    s.constant = c.default_value;
    s.origin = std::string(c.name);
    q.columns.push_back(std::move(s));
  }
  direction_sources(wi, "wi", query_column_index("wi_x"), q);
  direction_sources(wo, "wo", query_column_index("wo_x"), q);
  dict_sources(footprint, "footprint", {QueryPart::kFootprint, QueryPart::kCorners}, q);
  dict_sources(light, "light", {QueryPart::kLight}, q);

  // Every column the model needs is given, as eval --model requires it of --in.
  const py::dict given = footprint.is_none() ? py::dict() : py::cast<py::dict>(footprint);
  const py::dict lit = light.is_none() ? py::dict() : py::cast<py::dict>(light);
  std::string missing;
  for (std::string_view c : cli::needed_query_columns(model)) {
    const py::str key(std::string(c).c_str());
    if (!given.contains(key) && !lit.contains(key))
      missing += fmt::format("{}{}", missing.empty() ? "" : ", ", c);
  }
  if (!missing.empty()) {
    throw py::value_error(fmt::format("missing query column(s) {} (model {}: {}; footprint and "
                                      "light columns go in the footprint= and light= dicts)",
                                      missing, model.name, describe_needs(model.needs)));
  }
  return q;
}

GLINTLAB_PYTHON_CLONES
std::uint64_t transpose_rows_checked(const double* src, std::size_t count, double* x, double* y,
                                     double* z, std::uint64_t lo, std::uint64_t hi) {
  std::uint64_t outside = 0;
  for_row_blocks_prefetching(src, count, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const double a = src[3 * i], bb = src[3 * i + 1], c = src[3 * i + 2];
      x[i] = a;
      y[i] = bb;
      z[i] = c;
      const std::uint64_t u = std::bit_cast<std::uint64_t>(a * a + bb * bb + c * c);
      outside |= (u - lo) | (hi - u);
    }
  });
  return outside;
}

}  // namespace glintlab::python

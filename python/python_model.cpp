// Models prototyped in numpy behind registry entries; see python_model.h.
#include "python/python_model.h"

#include <pybind11/numpy.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <map>
#include <type_traits>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/model_layout.h"
#include "core/simd/model_batch.h"
#include "python/result_pool.h"

namespace glintlab::python {

namespace py = pybind11;

struct PythonModel {
  std::string name;
  // Borrowed for the life of the process: the registry (and every copy of its entries) outlives
  // the interpreter, and dropping a reference after Python has finalised would crash at exit.
  PyObject* eval = nullptr;
  PyObject* pdf = nullptr;
  PyObject* sample = nullptr;
  std::vector<std::size_t> columns;  // the kQueryLayout columns passed to the callables
  std::vector<std::string> param_names;
  // The dict keys of columns and param_names as Python strings, made once (borrowed for the life
  // of the process, as the functions are).
  std::vector<PyObject*> column_keys, param_keys;
};

std::string_view keep_text(std::string text) {
  static std::deque<std::string> texts;
  return texts.emplace_back(std::move(text));
}

namespace {

std::map<std::string, const PythonModel*, std::less<>>& python_models() {
  static std::map<std::string, const PythonModel*, std::less<>> models;
  return models;
}

[[noreturn]] void fail(const PythonModel& m, std::string_view function, const std::string& why) {
  throw PythonModelError(fmt::format("glintlab model '{}': {} {}", m.name, function, why));
}

py::dict params_dict(const PythonModel& m, const std::vector<double>& values) {
  py::dict d;
  for (std::size_t k = 0; k < m.param_keys.size(); ++k) d[py::handle(m.param_keys[k])] = values[k];
  return d;
}

// A read-only array (q's arrays are the model's inputs, never its scratch space).
py::array read_only(py::array a) {
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// Whether p lies in [begin, end).
bool within(const void* p, const void* begin, const void* end) {
  const auto at = reinterpret_cast<std::uintptr_t>(p);
  return at >= reinterpret_cast<std::uintptr_t>(begin) && at < reinterpret_cast<std::uintptr_t>(end);
}

template <class S>
py::dict query_dict(const PythonModel& m, std::span<const simd::Column<S>> query, std::size_t n,
                    const ColumnOwners& owners) {
  static const S kZero = 0;  // a corner column the caller did not give
  py::dict d;
  py::object storage;  // the capsule keeping owners.storage alive, made for the first view into it
  for (std::size_t k = 0; k < m.columns.size(); ++k) {
    const std::size_t c = m.columns[k];
    const simd::Column<S> col = c < query.size() ? query[c] : simd::Column<S>{&kZero, 0};
    const py::handle key = m.column_keys[k];
    if (std::is_same_v<S, double> && col.stride == 1 && n > 0) {
      // A contiguous float64 column where it lies: a view of its owner's memory.
      py::handle base;
      if (c < owners.arrays.size() && owners.arrays[c] != nullptr) {
        base = owners.arrays[c];
      } else if (owners.storage && within(col.data, owners.storage_begin, owners.storage_end)) {
        if (!storage) {
          storage = py::capsule(new std::shared_ptr<const void>(owners.storage), [](void* p) {
            delete static_cast<std::shared_ptr<const void>*>(p);
          });
        }
        base = storage;
      }
      if (base) {
        d[key] = read_only(py::array(py::dtype::of<double>(), {py::ssize_t(n)}, {},
                                     static_cast<const void*>(col.data), base));
        continue;
      }
    }
    py::array_t<double> a(static_cast<py::ssize_t>(n));
    double* out = a.mutable_data();
    if (std::is_same_v<S, double> && col.stride == 1)
      std::memcpy(out, col.data, n * sizeof(double));
    else
      for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<double>(col.data[col.stride * i]);
    d[key] = read_only(std::move(a));
  }
  return d;
}

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t k = 0; k < a.ndim(); ++k) s += fmt::format("{}{}", k ? ", " : "", a.shape(k));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

constexpr std::uint64_t kSignBit = 0x8000000000000000ULL;
constexpr std::uint64_t kInfinityBits = 0x7ff0000000000000ULL;

// A result of float64 of shape (n,) or (n, width) (width 0: one dimension); its element (i, j)
// is at(i, j).
struct CheckedArray {
  CheckedArray(py::array a, std::size_t n, std::size_t width)
      : array(std::move(a)),
        base(static_cast<const char*>(array.data())),
        row_stride(array.strides(0)),
        column_stride(array.ndim() > 1 ? array.strides(1) : 0),
        columns(std::max<std::size_t>(width, 1)),
        flat(n <= 1 ? columns == 1 || column_stride == py::ssize_t(sizeof(double))
                    : row_stride == py::ssize_t(columns * sizeof(double)) &&
                          (columns == 1 || column_stride == py::ssize_t(sizeof(double)))) {}
  py::array array;
  // The layout read once: at() runs on every element, without calls into numpy.
  const char* base;
  py::ssize_t row_stride, column_stride;
  std::size_t columns;
  // The n × columns values lie as one C-ordered block (numpy's usual result): read by the loops
  // below at constant strides, which the compiler vectorises, rather than by at().
  bool flat;
  double at(std::size_t i, std::size_t j = 0) const {
    const char* p = base + py::ssize_t(i) * row_stride + py::ssize_t(j) * column_stride;
    double v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  bool any_nan(std::size_t n) const {
    bool nan = false;
    if (flat) {
      // On the bits, so that the loop vectorises (a reduction over bool does not): |v| above
      // infinity's pattern is a NaN, and 0x7ff0... - |v| then has its sign bit set.
      std::uint64_t above = 0;
      for (std::size_t k = 0; k < n * columns; ++k) {
        std::uint64_t b;
        std::memcpy(&b, base + k * sizeof(double), sizeof b);
        above |= kInfinityBits - (b & ~kSignBit);
      }
      nan = (above & kSignBit) != 0;
    } else {
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < columns; ++j) nan |= std::isnan(at(i, j));
    }
    return nan;
  }
  // Every column j of rows [0, n) into outs[j], as S; whether a value was NaN. One pass over the
  // values where they lie flat (the NaN test on the bits, as in any_nan).
  // With `stream`, a single column of double is stored around the caches (streamed).
  template <class S>
  bool copy_any_nan(std::span<S* const> outs, std::size_t n, bool stream = false) const {
    if constexpr (std::is_same_v<S, double>)
      if (stream && flat && columns == 1) return stream_copy_any_nan(outs[0], n);
    const auto pass = [&]<std::size_t kColumns>() {
      std::uint64_t above = 0;
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < kColumns; ++j) {
          double v;
          std::memcpy(&v, base + (i * kColumns + j) * sizeof(double), sizeof v);
          above |= kInfinityBits - (std::bit_cast<std::uint64_t>(v) & ~kSignBit);
          outs[j][i] = static_cast<S>(v);
        }
      return (above & kSignBit) != 0;
    };
    if (flat && columns == 1) return pass.template operator()<1>();
    if (flat && columns == 3) return pass.template operator()<3>();
    for (std::size_t j = 0; j < columns; ++j) copy_column(j, outs[j], n);
    return any_nan(n);
  }
  // The single column of rows [0, n) into out by non-temporal stores, which write whole lines to
  // memory without reading them first: for a part of a result array far larger than the caches,
  // which nothing reads before the call returns (a plain store first reads each line of it from
  // memory, doubling the traffic). Whether a value was NaN.
  bool stream_copy_any_nan(double* out, std::size_t n) const {
    const double* in = reinterpret_cast<const double*>(base);
    std::size_t i = 0;
    bool nan = false;
#if defined(__SSE2__)
    for (; i < n && reinterpret_cast<std::uintptr_t>(out + i) % 16 != 0; ++i) {
      nan |= std::isnan(in[i]);
      out[i] = in[i];
    }
    __m128d unordered = _mm_setzero_pd();
    for (; i + 2 <= n; i += 2) {
      const __m128d v = _mm_loadu_pd(in + i);
      unordered = _mm_or_pd(unordered, _mm_cmpunord_pd(v, v));
      _mm_stream_pd(out + i, v);
    }
    _mm_sfence();  // the streamed stores ordered before what follows (another thread's reads)
    nan |= _mm_movemask_pd(unordered) != 0;
#endif
    for (; i < n; ++i) {
      nan |= std::isnan(in[i]);
      out[i] = in[i];
    }
    return nan;
  }
  // Column j of rows [0, n) into out, as S.
  template <class S>
  void copy_column(std::size_t j, S* out, std::size_t n) const {
    if (flat) {
      const char* p = base + j * sizeof(double);
      for (std::size_t i = 0; i < n; ++i) {
        double v;
        std::memcpy(&v, p + i * columns * sizeof(double), sizeof v);
        out[i] = static_cast<S>(v);
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<S>(at(i, j));
    }
  }
};

// `result` checked as float64 of shape (n,) or (n, width) (width 0: one dimension).
CheckedArray checked_shape(const PythonModel& m, std::string_view function, const std::string& what,
                           const py::handle& result, std::size_t n, std::size_t width) {
  const auto want = [&] {
    return width == 0 ? fmt::format("float64 of shape ({},)", n)
                      : fmt::format("float64 of shape ({}, {})", n, width);
  };
  if (!py::isinstance<py::array>(result)) {
    fail(m, function, fmt::format("returned {} of type {} (valid: a numpy array, {})", what,
                                  std::string(py::str(py::type::handle_of(result).attr("__name__"))), want()));
  }
  const auto a = py::reinterpret_borrow<py::array>(result);
  const py::dtype dt = a.dtype();
  const char order = dt.byteorder();
  const bool native = order == '=' || order == '|' ||
                      order == (std::endian::native == std::endian::little ? '<' : '>');
  if (dt.kind() != 'f' || dt.itemsize() != 8 || !native) {
    fail(m, function, fmt::format("returned {} of dtype {} (valid: {})", what,
                                  std::string(py::str(py::handle(dt))), want()));
  }
  const bool shape_ok = width == 0 ? a.ndim() == 1 && std::size_t(a.shape(0)) == n
                                   : a.ndim() == 2 && std::size_t(a.shape(0)) == n &&
                                         std::size_t(a.shape(1)) == width;
  if (!shape_ok)
    fail(m, function, fmt::format("returned {} of shape {} (valid: {})", what, shape_text(a), want()));
  return CheckedArray{a, n, width};
}

// The row of the first NaN of `c` (which has one) as the function's error.
[[noreturn]] void fail_nan(const PythonModel& m, std::string_view function, const std::string& what,
                           const CheckedArray& c, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < c.columns; ++j)
      if (std::isnan(c.at(i, j))) {
        fail(m, function, fmt::format("returned NaN in {} at row {} of {} (valid: numbers, no NaN)",
                                      what, i, n));
      }
  fail(m, function, fmt::format("returned NaN in {} (valid: numbers, no NaN)", what));
}

// `result` checked by checked_shape and NaN-free (one branch-free pass; the row of the first NaN
// looked for only when there is one).
CheckedArray checked_array(const PythonModel& m, std::string_view function, const std::string& what,
                           const py::handle& result, std::size_t n, std::size_t width = 0) {
  CheckedArray c = checked_shape(m, function, what, result, n, width);
  if (c.any_nan(n)) fail_nan(m, function, what, c, n);
  return c;
}

// `result` checked as checked_array checks it, its columns copied into outs (one pass).
template <class S>
void copy_checked(const PythonModel& m, std::string_view function, const std::string& what,
                  const py::handle& result, std::size_t n, std::size_t width,
                  std::span<S* const> outs, bool stream = false) {
  const CheckedArray c = checked_shape(m, function, what, result, n, width);
  if (c.copy_any_nan(outs, n, stream)) fail_nan(m, function, what, c, n);
}

// Calls one of the model's functions; a Python exception becomes PythonModelError (built while the
// GIL is held, so the exception object is released with it).
template <class... Args>
py::object call(const PythonModel& m, std::string_view function, PyObject* f, Args&&... args) {
  try {
    return py::reinterpret_borrow<py::object>(f)(std::forward<Args>(args)...);
  } catch (py::error_already_set& e) {
    // One line (type: message), as a check's detail would carry it; not pybind11's traceback.
    std::string text = fmt::format("{}: {}", std::string(py::str(e.type().attr("__name__"))),
                                   std::string(py::str(e.value())));
    std::replace(text.begin(), text.end(), '\n', ' ');
    fail(m, function, "raised " + text);
  }
}

unsigned needs_bits(const py::object& needs) {
  static constexpr std::array<std::pair<std::string_view, unsigned>, 4> kNames = {
      {{"footprint", kNeedsFootprint},
       {"point light", kNeedsPointLight},
       {"area light", kNeedsAreaLight},
       {"pixel corners", kNeedsPixelCorners}}};
  unsigned bits = 0;
  if (needs.is_none()) return bits;
  if (py::isinstance<py::str>(needs))
    throw py::value_error("needs: a string (valid: a list of 'footprint', 'point light', 'area "
                          "light', 'pixel corners')");
  for (const py::handle item : needs) {
    const std::string name = py::str(item);
    bool found = false;
    for (const auto& [text, bit] : kNames)
      if (text == name) {
        bits |= bit;
        found = true;
      }
    if (!found) {
      throw py::value_error(fmt::format(
          "needs: '{}' is not a query part (valid: 'footprint', 'point light', 'area light', "
          "'pixel corners')",
          name));
    }
  }
  return bits;
}

bool column_needed(const QueryColumn& c, unsigned needs) {
  switch (c.part) {
    case QueryPart::kDirections: return true;
    case QueryPart::kFootprint: return (needs & (kNeedsFootprint | kNeedsPixelCorners)) != 0;
    case QueryPart::kLight: return (needs & (kNeedsPointLight | kNeedsAreaLight)) != 0;
    case QueryPart::kCorners: return (needs & kNeedsPixelCorners) != 0;
  }
  return false;
}

// One parameter from {"name", "default", "lo", "hi", optional "lo_open", "hi_open", "integral",
// "description"}.
ParamSpec param_spec(const py::handle& item) {
  if (!py::isinstance<py::dict>(item))
    throw py::value_error("params: an item is not a dict (valid: dicts with name, default, lo, hi "
                          "and optionally lo_open, hi_open, integral, description)");
  const auto d = py::reinterpret_borrow<py::dict>(item);
  for (const auto& [key, value] : d) {
    const std::string k = py::str(key);
    if (k != "name" && k != "default" && k != "lo" && k != "hi" && k != "lo_open" &&
        k != "hi_open" && k != "integral" && k != "description")
      throw py::value_error(fmt::format(
          "params: unknown key '{}' (valid: name, default, lo, hi, lo_open, hi_open, integral, "
          "description)",
          k));
  }
  for (const char* k : {"name", "default", "lo", "hi"})
    if (!d.contains(k))
      throw py::value_error(fmt::format("params: an item has no '{}' (valid: dicts with name, "
                                        "default, lo, hi)",
                                        k));
  ParamSpec p{};
  p.name = keep_text(py::str(d["name"]));
  p.default_value = py::cast<double>(d["default"]);
  p.lo = py::cast<double>(d["lo"]);
  p.hi = py::cast<double>(d["hi"]);
  p.lo_open = d.contains("lo_open") && py::cast<bool>(d["lo_open"]);
  p.hi_open = d.contains("hi_open") && py::cast<bool>(d["hi_open"]);
  p.integral = d.contains("integral") && py::cast<bool>(d["integral"]);
  p.description = keep_text(d.contains("description") ? std::string(py::str(d["description"])) : "");
  const bool lo_ok = p.lo_open ? p.default_value > p.lo : p.default_value >= p.lo;
  const bool hi_ok = p.hi_open ? p.default_value < p.hi : p.default_value <= p.hi;
  if (p.name.empty() || !(p.lo <= p.hi) || !lo_ok || !hi_ok)
    throw py::value_error(fmt::format(
        "params: '{}' needs a name and lo <= default <= hi (got default {}, range {})", p.name,
        p.default_value, describe_range(p)));
  return p;
}

bool valid_name(std::string_view name) {
  if (name.empty()) return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'))
      return false;
  return true;
}

}  // namespace

const PythonModel* python_model(const ModelEntry& entry) {
  const auto& models = python_models();
  const auto it = models.find(entry.name);
  return it == models.end() ? nullptr : it->second;
}

template <class S>
void python_eval_rows(const PythonModel& m, const std::vector<double>& params,
                      std::span<const simd::Column<S>> query, std::span<S* const> outputs,
                      std::size_t n, const ColumnOwners& owners, bool stream_results) {
  const py::gil_scoped_acquire gil;
  // The arrays made here and by the functions (numpy's temporaries of a chunk's size) take
  // blocks the pool keeps mapped, which the previous chunk's gave back (result_pool.h).
  const PooledArrays pooled;
  const py::dict q = query_dict<S>(m, query, n, owners);
  const py::dict p = params_dict(m, params);
  copy_checked<S>(m, "eval", "its value", call(m, "eval", m.eval, q, p), n, 0, outputs.first(1),
                  stream_results);
  copy_checked<S>(m, "pdf", "its pdf", call(m, "pdf", m.pdf, q, p), n, 0, outputs.subspan(1, 1),
                  stream_results);
}

template <class S>
void python_sample_rows(const PythonModel& m, const std::vector<double>& params,
                        std::span<const simd::Column<S>> query, simd::Column<S> u1,
                        simd::Column<S> u2, std::span<S* const> outputs, std::size_t n,
                        const ColumnOwners& owners, bool stream_results) {
  const py::gil_scoped_acquire gil;
  const PooledArrays pooled;  // as in python_eval_rows
  const py::dict q = query_dict<S>(m, query, n, owners);
  py::array_t<double> u({py::ssize_t(n), py::ssize_t(2)});
  double* ud = u.mutable_data();
  for (std::size_t i = 0; i < n; ++i) {
    ud[2 * i] = static_cast<double>(u1.data[u1.stride * i]);
    ud[2 * i + 1] = static_cast<double>(u2.data[u2.stride * i]);
  }
  const py::object r = call(m, "sample", m.sample, q, u, params_dict(m, params));
  if (!py::isinstance<py::dict>(r))
    fail(m, "sample", "did not return a dict (valid: a dict of wo (N, 3), pdf, weight and "
                      "optionally rejected (N,) bool)");
  const auto d = py::reinterpret_borrow<py::dict>(r);
  for (const char* k : {"wo", "pdf", "weight"})
    if (!d.contains(k))
      fail(m, "sample", fmt::format("returned no '{}' (valid: a dict of wo (N, 3), pdf, weight "
                                    "and optionally rejected (N,) bool)",
                                    k));
  copy_checked<S>(m, "sample", "its 'wo'", d["wo"], n, 3, outputs.first(3));
  copy_checked<S>(m, "sample", "its 'pdf'", d["pdf"], n, 0, outputs.subspan(3, 1),
                  stream_results);
  copy_checked<S>(m, "sample", "its 'weight'", d["weight"], n, 0, outputs.subspan(4, 1),
                  stream_results);
  std::vector<bool> rejected(n, false);
  if (d.contains("rejected")) {
    const py::object rej = d["rejected"];
    const auto a = py::isinstance<py::array>(rej) ? py::reinterpret_borrow<py::array>(rej)
                                                   : py::array();
    if (!a || a.dtype().kind() != 'b' || a.ndim() != 1 || std::size_t(a.shape(0)) != n)
      fail(m, "sample", fmt::format("returned a 'rejected' that is not a bool array of shape ({},)", n));
    const char* base = static_cast<const char*>(a.data());
    for (std::size_t i = 0; i < n; ++i)
      rejected[i] = *reinterpret_cast<const bool*>(base + py::ssize_t(i) * a.strides(0));
  }
  for (std::size_t i = 0; i < n; ++i) outputs[5][i] = rejected[i] ? S(1) : S(0);
}

template void python_eval_rows<float>(const PythonModel&, const std::vector<double>&,
                                      std::span<const simd::Column<float>>, std::span<float* const>,
                                      std::size_t, const ColumnOwners&, bool);
template void python_eval_rows<double>(const PythonModel&, const std::vector<double>&,
                                       std::span<const simd::Column<double>>,
                                       std::span<double* const>, std::size_t,
                                       const ColumnOwners&, bool);
template void python_sample_rows<float>(const PythonModel&, const std::vector<double>&,
                                        std::span<const simd::Column<float>>, simd::Column<float>,
                                        simd::Column<float>, std::span<float* const>, std::size_t,
                                        const ColumnOwners&, bool);
template void python_sample_rows<double>(const PythonModel&, const std::vector<double>&,
                                         std::span<const simd::Column<double>>,
                                         simd::Column<double>, simd::Column<double>,
                                         std::span<double* const>, std::size_t,
                                         const ColumnOwners&, bool);

void register_python_model(const std::string& name, const py::object& eval, const py::object& pdf,
                           const py::object& sample, const py::object& params,
                           const py::object& needs, const py::object& smooth_limit,
                           const std::string& description, const std::string& source,
                           const py::object& not_claimed, bool chunked) {
  if (!valid_name(name))
    throw py::value_error(fmt::format(
        "name: '{}' is not a model name (valid: letters, digits and '_', not empty)", name));
  for (const auto& [arg, f] : {std::pair{"eval", &eval}, {"pdf", &pdf}, {"sample", &sample}})
    if (!PyCallable_Check(f->ptr()))
      throw py::value_error(fmt::format("{}: not callable (valid: a function of (query, params))", arg));
  auto* m = new PythonModel;  // lives as long as the registry (the process)
  m->name = name;
  ModelEntry e;
  e.name = keep_text(name);
  e.description = keep_text(description);
  e.source = keep_text(source.empty() ? "Python (glintlab.register_model)" : source);
  e.needs = needs_bits(needs);
  if (!params.is_none())
    for (const py::handle item : params) {
      e.params.push_back(param_spec(item));
      m->param_names.emplace_back(e.params.back().name);
    }
  for (std::size_t c = 0; c < kQueryLayout.size(); ++c)
    if (column_needed(kQueryLayout[c], e.needs)) m->columns.push_back(c);
  if (!smooth_limit.is_none()) {
    const std::string limit = py::str(smooth_limit);
    try {
      find_model(limit);
    } catch (const ModelParamError& error) {
      throw py::value_error(fmt::format("smooth_limit: {}", error.what()));
    }
    e.smooth_limit = keep_text(limit);
  }
  if (!not_claimed.is_none()) {
    if (!py::isinstance<py::dict>(not_claimed))
      throw py::value_error("not_claimed: not a dict (valid: conformance property -> reason)");
    for (const auto& [property, reason] : py::reinterpret_borrow<py::dict>(not_claimed))
      e.not_claimed.push_back({keep_text(py::str(property)), keep_text(py::str(reason))});
  }
  e.eval = [m](const std::vector<double>& values, const ModelQuery<double>& q) {
    const QueryRow<double> row = to_row(q);
    std::array<simd::Column<double>, kQueryLayout.size()> cols;
    for (std::size_t c = 0; c < cols.size(); ++c) cols[c] = {&row[c], 0};
    double value = 0, pdf_value = 0;
    double* const out[2] = {&value, &pdf_value};
    python_eval_rows<double>(*m, values, cols, out, 1);
    return ErasedEval{value, pdf_value, {}};
  };
  e.pdf = [m](const std::vector<double>& values, const ModelQuery<double>& q) {
    const QueryRow<double> row = to_row(q);
    std::array<simd::Column<double>, kQueryLayout.size()> cols;
    for (std::size_t c = 0; c < cols.size(); ++c) cols[c] = {&row[c], 0};
    const py::gil_scoped_acquire gil;
    const py::object r = call(*m, "pdf", m->pdf, query_dict<double>(*m, cols, 1, {}),
                              params_dict(*m, values));
    return checked_array(*m, "pdf", "its pdf", r, 1).at(0);
  };
  e.sample = [m](const std::vector<double>& values, const ModelQuery<double>& q, Vec2<double> u) {
    const QueryRow<double> row = to_row(q);
    std::array<simd::Column<double>, kQueryLayout.size()> cols;
    for (std::size_t c = 0; c < cols.size(); ++c) cols[c] = {&row[c], 0};
    double out[6] = {};
    double* const outs[6] = {&out[0], &out[1], &out[2], &out[3], &out[4], &out[5]};
    python_sample_rows<double>(*m, values, cols, {&u.x, 0}, {&u.y, 0}, outs, 1);
    return ModelSample<double>{{out[0], out[1], out[2]}, out[3], out[4], out[5] != 0};
  };
  if (chunked) {
    // The same functions over whole chunks of rows (what the conformance suite calls where it has
    // many queries): one call of the Python function per chunk instead of one per row.
    e.eval_rows = [m](const std::vector<double>& values, std::span<const ModelQuery<double>> qs,
                      std::span<ErasedEval> out) {
      if (qs.empty()) return;
      std::vector<QueryRow<double>> rows(qs.size());
      for (std::size_t i = 0; i < qs.size(); ++i) rows[i] = to_row(qs[i]);
      std::array<simd::Column<double>, kQueryLayout.size()> cols;
      for (std::size_t c = 0; c < cols.size(); ++c) cols[c] = {&rows[0][c], kQueryLayout.size()};
      std::vector<double> value(qs.size()), pdf_value(qs.size());
      double* const outs[2] = {value.data(), pdf_value.data()};
      python_eval_rows<double>(*m, values, cols, outs, qs.size());
      for (std::size_t i = 0; i < qs.size(); ++i) out[i] = ErasedEval{value[i], pdf_value[i], {}};
    };
    e.pdf_rows = [m](const std::vector<double>& values, std::span<const ModelQuery<double>> qs,
                     std::span<double> out) {
      if (qs.empty()) return;
      std::vector<QueryRow<double>> rows(qs.size());
      for (std::size_t i = 0; i < qs.size(); ++i) rows[i] = to_row(qs[i]);
      std::array<simd::Column<double>, kQueryLayout.size()> cols;
      for (std::size_t c = 0; c < cols.size(); ++c) cols[c] = {&rows[0][c], kQueryLayout.size()};
      const py::gil_scoped_acquire gil;
      const py::object r = call(*m, "pdf", m->pdf, query_dict<double>(*m, cols, qs.size(), {}),
                                params_dict(*m, values));
      const CheckedArray a = checked_array(*m, "pdf", "its pdf", r, qs.size());
      for (std::size_t i = 0; i < qs.size(); ++i) out[i] = a.at(i);
    };
    e.sample_rows = [m](const std::vector<double>& values, const ModelQuery<double>& q,
                        std::span<const Vec2<double>> u, std::span<ModelSample<double>> out) {
      if (u.empty()) return;
      const QueryRow<double> row = to_row(q);
      std::array<simd::Column<double>, kQueryLayout.size()> cols;
      for (std::size_t c = 0; c < cols.size(); ++c) cols[c] = {&row[c], 0};
      const std::size_t n = u.size();
      std::vector<double> buffer(6 * n);
      double* const outs[6] = {&buffer[0],     &buffer[n],     &buffer[2 * n],
                               &buffer[3 * n], &buffer[4 * n], &buffer[5 * n]};
      python_sample_rows<double>(*m, values, cols, {&u[0].x, 2}, {&u[0].y, 2}, outs, n);
      for (std::size_t i = 0; i < n; ++i)
        out[i] = ModelSample<double>{
            {outs[0][i], outs[1][i], outs[2][i]}, outs[3][i], outs[4][i], outs[5][i] != 0};
    };
  }
  try {
    register_model(std::move(e));
  } catch (const ModelParamError& error) {
    delete m;
    throw py::value_error(error.what());
  }
  m->eval = eval.ptr();
  m->pdf = pdf.ptr();
  m->sample = sample.ptr();
  Py_INCREF(m->eval);
  Py_INCREF(m->pdf);
  Py_INCREF(m->sample);
  for (std::size_t c : m->columns)
    m->column_keys.push_back(py::str(std::string(kQueryLayout[c].name)).release().ptr());
  for (const std::string& param : m->param_names)
    m->param_keys.push_back(py::str(param).release().ptr());
  python_models().emplace(name, m);
}

}  // namespace glintlab::python

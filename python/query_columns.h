// The query of a Python call as columns of core/model_layout.h: each column read in place from a
// numpy array (any stride, float32 or float64), or one value for every row. A chunk of rows becomes
// the SoA columns of core/simd/model_batch.h without copying where the array already is one
// contiguous column of the precision evaluated in; otherwise the chunk is gathered into a buffer.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/model_layout.h"
#include "core/model_registry.h"
#include "core/simd/batch.h"

namespace glintlab::python {

namespace py = pybind11;

// Where one column's values come from: data[i * stride] (elements of float32 or float64), or
// `constant` for every row when data is null.
struct ColumnSource {
  const void* data = nullptr;
  std::ptrdiff_t stride = 0;
  bool is_float = false;
  double constant = 0;
  std::string origin;  // how an error names it: "wi[:, 0]", "footprint['u']"
  PyObject* owner = nullptr;  // the array data points into (borrowed: QuerySources::keep_alive)

  double at(std::size_t row) const {
    if (data == nullptr) return constant;
    const std::ptrdiff_t k = std::ptrdiff_t(row) * stride;
    return is_float ? double(static_cast<const float*>(data)[k])
                    : static_cast<const double*>(data)[k];
  }
  // Whether a chunk can be passed as it lies: one contiguous column of S.
  template <class S>
  bool in_place() const {
    return data != nullptr && stride == 1 && is_float == std::is_same_v<S, float>;
  }
};

// The columns of one call, kQueryLayout order (corners included), and the row count.
struct QuerySources {
  std::vector<ColumnSource> columns;
  std::size_t rows = 0;
  std::vector<py::object> keep_alive;  // converted arrays the sources point into
};

// Builds the sources of a call: `wi`, `wo` (N, 3) or (3,) arrays or None (the layout's defaults),
// `footprint` and `light` dicts of scalars or (N,) arrays keyed by the layout's column names.
// `rows` is the row count when no array fixes it (sample's n=), 0 otherwise; it stays 0 when
// every input is broadcast. Throws ValueError for
// a wrong shape, unknown key, a missing column the model needs, or mismatched row counts.
QuerySources query_sources(const ModelEntry& model, const py::object& wi, const py::object& wo,
                           const py::object& footprint, const py::object& light,
                           std::size_t rows);

// A 1-D (N,) or scalar input as a column source (float32/float64 read in place, any other real
// dtype converted once); `name` names it in errors. Row count checked against `rows` (0: any).
ColumnSource column_source(const py::handle& value, const std::string& name, std::size_t& rows,
                           std::vector<py::object>& keep_alive);

// A test of the squared lengths of a C-ordered (N, 3) float64 array's rows, fused into
// chunk_columns' transposing gather of it into double (one pass over the rows instead of a gather
// and then a pass over the gathered columns): `lo` <= `hi`, the bit patterns of positive bounds;
// for each array so gathered, its first column and the OR over its rows of (u - lo) | (hi - u), u
// the pattern of x^2 + y^2 + z^2 (its sign bit clear exactly when every u lies within the bounds:
// python/batch_call.cpp, squared_lengths_in_bounds).
struct FusedUnitCheck {
  std::uint64_t lo = 0, hi = 0;
  std::vector<std::pair<std::size_t, std::uint64_t>> found;  // (first column, OR of the bits)
};

// Rows [0, count) of a C-ordered (N, 3) array at `src` in blocks of 64 rows, f(b, e) for rows
// [b, e), each block after asking for the same rows of the next chunk (a software prefetch, a
// hint that never faults: past the array's end it does nothing), so that they arrive while this
// chunk is checked and evaluated rather than when the next is gathered (measured, CPU time per
// 10^6 rows: 1.5 ms less for a numpy model's call, 1.4 ms for smooth_ggx's).
template <class T, class F>
inline void for_row_blocks_prefetching(const T* src, std::size_t count, F&& f) {
  constexpr std::size_t kBlock = 64, kLine = 64;
  // The next chunk's address as an integer: it may lie past the array.
  const auto next_chunk = reinterpret_cast<std::uintptr_t>(src) + 3 * count * sizeof(T);
  for (std::size_t b = 0; b < count; b += kBlock) {
    for (std::size_t k = 0; k < 3 * kBlock * sizeof(T); k += kLine)
      __builtin_prefetch(reinterpret_cast<const void*>(next_chunk + 3 * b * sizeof(T) + k));
    f(b, std::min(count, b + kBlock));
  }
}

// A function compiled for AVX-512, AVX2 and the baseline, the widest the CPU has chosen when the
// module is loaded (function multiversioning): for the loops over whole arrays that the compiler
// vectorises, which the module's baseline (SSE2) would run two doubles at a time.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define GLINTLAB_PYTHON_CLONES __attribute__((target_clones("default", "avx2", "avx512f")))
#else
#define GLINTLAB_PYTHON_CLONES
#endif

// The fused loop of FusedUnitCheck: rows [0, count) of a C-ordered (N, 3) float64 array at `src`
// transposed into x, y, z, each row's squared length tested on the way; the OR over the rows of
// (u - lo) | (hi - u), u the pattern of x^2 + y^2 + z^2 (for_row_blocks_prefetching). Defined
// with GLINTLAB_PYTHON_CLONES (the attribute on the definition only: callers in other files call
// the chosen version through the symbol).
std::uint64_t transpose_rows_checked(const double* src, std::size_t count, double* x, double* y,
                                     double* z, std::uint64_t lo, std::uint64_t hi);

// The SoA columns of rows [begin, begin + count) in precision S, `ncols` first columns; columns
// not in place are gathered into `buffer` (ncols * count values; only those read are written), a
// strided column by a typed strided load per row. With `strided`, a column of S at a positive
// stride (a coordinate of a C-ordered (N, 3) array) is passed where it lies, with its stride, for
// the batch API (core/simd/model_batch.h reads such columns block by block). With `fused`, the
// gather of a C-ordered (N, 3) float64 array into double also tests its rows' squared lengths.
template <class S>
std::vector<simd::Column<S>> chunk_columns(const std::vector<ColumnSource>& sources,
                                           std::size_t ncols, std::size_t begin, std::size_t count,
                                           S* buffer, bool strided = false,
                                           FusedUnitCheck* fused = nullptr) {
  std::vector<simd::Column<S>> cols;
  cols.reserve(ncols);
  const auto gather = [count](auto* src, std::ptrdiff_t stride, S* dst) {
    for (std::size_t i = 0; i < count; ++i) dst[i] = S(src[std::ptrdiff_t(i) * stride]);
  };
  // Three columns that are the adjacent elements of each row of one array (a C-ordered (N, 3)
  // direction array): transposed in one pass over its rows rather than three strided passes.
  const auto gather3 = [count, fused](auto* src, std::ptrdiff_t stride, S* x, S* y, S* z,
                                     std::size_t first_column) {
    if (stride == 3) {  // a C-ordered (N, 3) array: constant strides, which the compiler vectorises
      if constexpr (std::is_same_v<S, double> &&
                    std::is_same_v<std::remove_cv_t<std::remove_pointer_t<decltype(src)>>, double>) {
        if (fused != nullptr) {  // the same loop, testing each row's squared length on the way
          fused->found.emplace_back(
              first_column, transpose_rows_checked(src, count, x, y, z, fused->lo, fused->hi));
          return;
        }
      }
      for_row_blocks_prefetching(src, count, [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) {
          x[i] = S(src[3 * i]);
          y[i] = S(src[3 * i + 1]);
          z[i] = S(src[3 * i + 2]);
        }
      });
      return;
    }
    for (std::size_t i = 0; i < count; ++i, src += stride) {
      x[i] = S(src[0]);
      y[i] = S(src[1]);
      z[i] = S(src[2]);
    }
  };
  const auto rows_of_one_array = [&](std::size_t c) {
    if (c + 2 >= ncols) return false;
    const ColumnSource &a = sources[c], &b = sources[c + 1], &d = sources[c + 2];
    const std::size_t size = a.is_float ? sizeof(float) : sizeof(double);
    const char* base = static_cast<const char*>(a.data);
    return a.data != nullptr && a.stride != 0 && !a.in_place<S>() && b.stride == a.stride &&
           d.stride == a.stride && b.is_float == a.is_float && d.is_float == a.is_float &&
           b.data == base + size && d.data == base + 2 * size;
  };
  for (std::size_t c = 0; c < ncols; ++c) {
    const ColumnSource& s = sources[c];
    S* gathered = buffer + c * count;
    if (strided && s.data != nullptr && s.stride > 0 && s.is_float == std::is_same_v<S, float>) {
      cols.push_back({static_cast<const S*>(s.data) + std::ptrdiff_t(begin) * s.stride,
                      std::size_t(s.stride)});
    } else if (rows_of_one_array(c)) {
      const std::ptrdiff_t first = std::ptrdiff_t(begin) * s.stride;
      if (s.is_float)
        gather3(static_cast<const float*>(s.data) + first, s.stride, gathered, gathered + count,
                gathered + 2 * count, c);
      else
        gather3(static_cast<const double*>(s.data) + first, s.stride, gathered, gathered + count,
                gathered + 2 * count, c);
      for (std::size_t k = 0; k < 3; ++k) cols.push_back({gathered + k * count, 1});
      c += 2;
    } else if (s.in_place<S>()) {
      cols.push_back({static_cast<const S*>(s.data) + begin, 1});
    } else if (s.data == nullptr || s.stride == 0) {
      gathered[0] = S(s.at(0));
      cols.push_back({gathered, 0});
    } else {
      const std::ptrdiff_t first = std::ptrdiff_t(begin) * s.stride;
      if (s.is_float)
        gather(static_cast<const float*>(s.data) + first, s.stride, gathered);
      else
        gather(static_cast<const double*>(s.data) + first, s.stride, gathered);
      cols.push_back({gathered, 1});
    }
  }
  return cols;
}

// The same into `buffer`, grown as needed (never cleared: every value read is written first).
template <class S>
std::vector<simd::Column<S>> chunk_columns(const std::vector<ColumnSource>& sources,
                                           std::size_t ncols, std::size_t begin, std::size_t count,
                                           std::vector<S>& buffer, bool strided = false) {
  if (buffer.size() < ncols * count) buffer.resize(ncols * count);
  return chunk_columns<S>(sources, ncols, begin, count, buffer.data(), strided);
}

// The query row `row` in double, every column of the layout.
inline QueryRow<double> query_row(const std::vector<ColumnSource>& sources, std::size_t row) {
  QueryRow<double> v{};
  for (std::size_t c = 0; c < v.size(); ++c) v[c] = sources[c].at(row);
  return v;
}

}  // namespace glintlab::python

// The device kernels: one thread per query row, each running a model's own eval, pdf or sample
// template (core/model.h) on T = float or double, reading the query columns of core/model_layout.h
// and writing the CPU batches' output columns. Nothing here re-states a model.
#pragma once

#include <cstddef>

#include "core/model.h"
#include "core/model_layout.h"

namespace glintlab::gpu {

// Column pointers are passed by value (a kernel argument), each n rows long, with where each
// column's member sits in ModelQuery<T> (query_offsets).
template <class T>
struct DeviceQueryColumns {
  const T* column[kQueryLayout.size()];
  std::size_t offset[kQueryLayout.size()];
};
template <class T, std::size_t N>
struct DeviceOutputColumns {
  T* column[N];
};

// The byte offset of each column's member in ModelQuery<T>, from the layout's own visitor, on the
// host: a device thread cannot run that visitor, which names each column with a std::string_view
// built from a literal (libstdc++'s strlen builtin, which nvcc compiles to nothing on the device
// — silently, the whole kernel with it).
template <class T>
void query_offsets(std::size_t (&offset)[kQueryLayout.size()]) {
  ModelQuery<T> q{};
  const auto* base = reinterpret_cast<const unsigned char*>(&q);
  for_each_query_column(q, [&](std::size_t k, const QueryColumn&, T& member) {
    offset[k] = static_cast<std::size_t>(reinterpret_cast<const unsigned char*>(&member) - base);
  });
}

template <class T>
__device__ ModelQuery<T> load_query(const DeviceQueryColumns<T>& columns, std::size_t row) {
  ModelQuery<T> q{};
  auto* base = reinterpret_cast<unsigned char*>(&q);
  for (std::size_t k = 0; k < kQueryLayout.size(); ++k)
    *reinterpret_cast<T*>(base + columns.offset[k]) = columns.column[k][row];
  return q;
}

__device__ inline std::size_t thread_row() {
  return std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
}

template <class M, class T>
inline constexpr std::size_t kEvalColumns = 2 + M::kIntermediates.size();

template <class M, class T>
__global__ void eval_kernel(typename M::template Params<T> params, DeviceQueryColumns<T> query,
                            DeviceOutputColumns<T, kEvalColumns<M, T>> out, std::size_t n) {
  const std::size_t i = thread_row();
  if (i >= n) return;
  const auto e = M::template eval<T>(params, load_query(query, i));
  out.column[0][i] = e.value;
  out.column[1][i] = e.pdf;
  for (std::size_t k = 0; k < M::kIntermediates.size(); ++k)
    out.column[2 + k][i] = e.intermediates[k];
}

template <class M, class T>
__global__ void pdf_kernel(typename M::template Params<T> params, DeviceQueryColumns<T> query,
                           DeviceOutputColumns<T, 1> out, std::size_t n) {
  const std::size_t i = thread_row();
  if (i >= n) return;
  out.column[0][i] = M::template pdf<T>(params, load_query(query, i));
}

template <class M, class T>
__global__ void sample_kernel(typename M::template Params<T> params, DeviceQueryColumns<T> query,
                              const T* u1, const T* u2, DeviceOutputColumns<T, 6> out,
                              std::size_t n) {
  const std::size_t i = thread_row();
  if (i >= n) return;
  const ModelSample<T> s =
      M::template sample<T>(params, load_query(query, i), Vec2<T>{u1[i], u2[i]});
  out.column[0][i] = s.wo.x;
  out.column[1][i] = s.wo.y;
  out.column[2][i] = s.wo.z;
  out.column[3][i] = s.pdf;
  out.column[4][i] = s.weight;
  out.column[5][i] = s.rejected ? T(1) : T(0);
}

}  // namespace glintlab::gpu

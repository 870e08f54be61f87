// The one host/device marker for every kernel, and the float-type traits kernels are written on.
#pragma once

#include <type_traits>

// Every kernel is marked GLINTLAB_FN so the same source builds for the CPU (scalar or SIMD batch)
// and, later, for CUDA. Kernels never throw, allocate, or branch on per-lane values.
#if defined(__CUDACC__)
#define GLINTLAB_FN __host__ __device__ inline
#else
#define GLINTLAB_FN inline
#endif

namespace glintlab {

// The mask type of a float type: bool for scalars; a batch backend specializes this.
template <class T>
struct MaskOf {
  using type = bool;
};
template <class T>
using Mask = typename MaskOf<T>::type;

// The scalar element type of a float type (itself for scalars).
template <class T>
struct ScalarOf {
  using type = T;
};
template <class T>
using Scalar = typename ScalarOf<T>::type;

}  // namespace glintlab

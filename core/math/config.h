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

// GLINTLAB_FN, forced inline: for kernels that take or return Vec3 and that GCC leaves out of line
// in the SIMD units (sample_heitz_vndf, pdf_vndf_reflection), where each call passed its
// Vec3<Wide> arguments through the stack (AVX2: the VNDF pdf about 3x faster inlined,
// docs/simd.md "Forced inline"). Inlining changes no result: the SIMD units are built with
// -ffp-contract=off, and the scalar code has no FMA instruction to contract to.
#if defined(__CUDACC__)
#define GLINTLAB_INLINE __host__ __device__ __forceinline__
#elif defined(__GNUC__)
#define GLINTLAB_INLINE [[gnu::always_inline]] inline
#else
#define GLINTLAB_INLINE inline
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

// Out-of-tree model plug-ins: a loadable module built with glintlab_add_model_plugin (the CMake
// function of find_package(glintlab)) whose one source file says, at namespace scope,
//
//   #include <glintlab/plugin.h>
//   GLINTLAB_PLUGIN(MyModel, MyOtherModel)
//
// for structs satisfying the Model concept (core/model.h). `glintlab --plugin PATH <command>` or
// GLINTLAB_PLUGINS=PATH[:PATH...] loads it (core/plugin_loader.h) and registers each model like a
// built-in one (docs/adding_a_model.md). The plug-in only uses core's headers: its kernels are
// compiled into it and called through the ModelEntry thunks that make_model_entry builds here;
// the registry itself stays in the host.
//
// SIMD batches: glintlab_add_model_plugin compiles the source holding GLINTLAB_PLUGIN once more
// per ISA (scalar, SSE4.2, AVX2, AVX-512, with core's flags for each), defining
// GLINTLAB_PLUGIN_ISA; there the macro instantiates each batched model's eval and sample on that
// ISA's batches (core/simd/instantiate.h, as core's own ISA units do) and the loader hands them to
// the batch API through ModelEntry::plugin_batches. That source should therefore hold only
// includes and the macro: a non-inline function defined in it would be defined once per ISA.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(GLINTLAB_PLUGIN_ISA)
#define GLINTLAB_SIMD_TU GLINTLAB_PLUGIN_ISA
#include "core/simd/instantiate.h"
#endif
#include "core/model.h"
#include "core/model_list.h"
#include "core/model_registry.h"
#include "core/simd/model_batch.h"
#include "core/simd/table.h"
#include "glintlab/version.h"

// Each ISA unit's table of the plug-in's models (weak: null where the plug-in was built without
// that unit, whose batches then fall back to the thunks). Entries: the eval of each model in
// GLINTLAB_PLUGIN's order, then the sample of each; all null for a model with kBatched = false.
__attribute__((weak)) const glintlab::simd::detail::BatchFns* glintlab_plugin_batches_scalar();
__attribute__((weak)) const glintlab::simd::detail::BatchFns* glintlab_plugin_batches_sse42();
__attribute__((weak)) const glintlab::simd::detail::BatchFns* glintlab_plugin_batches_avx2();
__attribute__((weak)) const glintlab::simd::detail::BatchFns* glintlab_plugin_batches_avx512();

namespace glintlab::plugin {

// What a plug-in and the host must agree on beyond the version: the C++ ABI (a ModelEntry holds
// std::function, std::vector and std::string_view built in the plug-in and used by the host) and
// the layout of the structs that cross the boundary. Compared field by field on load.
struct AbiTag {
  std::uint32_t gxx_abi;           // __GXX_ABI_VERSION
  std::uint32_t cxx11_string_abi;  // _GLIBCXX_USE_CXX11_ABI (std::string/std::function layout)
  std::uint32_t model_entry_size;  // sizeof(ModelEntry)
  std::uint32_t param_spec_size;   // sizeof(ParamSpec)
  std::uint32_t query_size;        // sizeof(ModelQuery<double>)
  std::uint32_t sample_size;       // sizeof(ModelSample<double>)
  std::uint32_t batch_columns;     // query columns of a batch call (kQueryColumnsWithCorners)
  std::uint32_t batch_fns_size;    // sizeof(simd::detail::BatchFns)
  friend constexpr bool operator==(const AbiTag&, const AbiTag&) = default;
};

#if defined(__GXX_ABI_VERSION)
inline constexpr std::uint32_t kGxxAbi = __GXX_ABI_VERSION;
#else
inline constexpr std::uint32_t kGxxAbi = 0;
#endif
#if defined(_GLIBCXX_USE_CXX11_ABI)
inline constexpr std::uint32_t kCxx11StringAbi = _GLIBCXX_USE_CXX11_ABI;
#else
inline constexpr std::uint32_t kCxx11StringAbi = 0;
#endif

constexpr AbiTag current_abi() {
  return AbiTag{kGxxAbi,
                kCxx11StringAbi,
                sizeof(ModelEntry),
                sizeof(ParamSpec),
                sizeof(ModelQuery<double>),
                sizeof(ModelSample<double>),
                static_cast<std::uint32_t>(simd::kQueryColumnsWithCorners),
                sizeof(simd::detail::BatchFns)};
}

// What the entry point returns. The first two members keep their place in every version of this
// struct, so a loader can always read what a plug-in was built against before anything else.
struct PluginInfo {
  const char* glintlab_version;  // GLINTLAB_VERSION of the headers the plug-in was compiled with
  AbiTag abi;
  // Appends one ModelEntry per model, in GLINTLAB_PLUGIN's order.
  void (*append_models)(std::vector<ModelEntry>& out);
};

namespace detail {

// The ISA tables of this plug-in, in Isa order.
inline std::array<const simd::detail::BatchFns*, 4> isa_tables() {
  const auto get = [](const simd::detail::BatchFns* (*f)()) { return f ? f() : nullptr; };
  return {get(&glintlab_plugin_batches_scalar), get(&glintlab_plugin_batches_sse42),
          get(&glintlab_plugin_batches_avx2), get(&glintlab_plugin_batches_avx512)};
}

template <Model... Ms>
void append_models(std::vector<ModelEntry>& out) {
  constexpr std::size_t kCount = sizeof...(Ms);
  // Built once; the entries point into it for the life of the plug-in.
  static const std::array<simd::detail::ModelBatchFns, kCount> kBatches = [] {
    const auto tables = isa_tables();
    std::array<simd::detail::ModelBatchFns, kCount> b{};
    for (std::size_t m = 0; m < kCount; ++m) {
      for (std::size_t isa = 0; isa < tables.size(); ++isa) {
        b[m].eval[isa] = tables[isa] ? &tables[isa][m] : nullptr;
        b[m].sample[isa] = tables[isa] ? &tables[isa][kCount + m] : nullptr;
      }
    }
    return b;
  }();
  std::size_t m = 0;
  const auto add = [&]<class M>() {
    ModelEntry e = make_model_entry<M>();
    if constexpr (Batched<M>) e.plugin_batches = &kBatches[m];
    out.push_back(std::move(e));
    ++m;
  };
  (add.template operator()<Ms>(), ...);
}

}  // namespace detail
}  // namespace glintlab::plugin

// The entry point's name; the number changes when PluginInfo's layout does, so a loader never
// reads a struct it does not know.
#define GLINTLAB_PLUGIN_ENTRY_POINT "glintlab_plugin_v1"

#if !defined(GLINTLAB_PLUGIN_ISA)

// Registers the listed model types (at least one); write it once, at namespace scope, in one
// source file of the plug-in. Type names may be qualified (my::Model).
#define GLINTLAB_PLUGIN(...)                                                                    \
  extern "C" __attribute__((visibility("default"), used)) const ::glintlab::plugin::PluginInfo* \
  glintlab_plugin_v1() {                                                                        \
    static const ::glintlab::plugin::PluginInfo kInfo{                                          \
        GLINTLAB_VERSION, ::glintlab::plugin::current_abi(),                                    \
        &::glintlab::plugin::detail::append_models<__VA_ARGS__>};                               \
    return &kInfo;                                                                              \
  }                                                                                             \
  static_assert(true, "GLINTLAB_PLUGIN(...) is followed by a semicolon")

#else  // one ISA unit of the plug-in (glintlab_add_model_plugin)

namespace glintlab::simd::detail {
namespace {  // internal linkage, as core's ISA units: nothing here is merged across ISAs

template <class M, class WF, class WFF, class WD>
constexpr BatchFns plugin_eval_fns() {
  if constexpr (Batched<M>) {
    return model_eval_fns<M, FloatBatchOf<M, WF, WD>, FloatBatchOf<M, WFF, WD>, WD>();
  } else {
    return BatchFns{};
  }
}
template <class M, class WF, class WFF, class WD>
constexpr BatchFns plugin_sample_fns() {
  if constexpr (Batched<M>) {
    return model_sample_fns<M, FloatBatchOf<M, WF, WD>, FloatBatchOf<M, WFF, WD>, WD>();
  } else {
    return BatchFns{};
  }
}

// The plug-in's table for this ISA (the order of the glintlab_plugin_batches_* declarations).
template <class WF, class WFF, class WD, class... Ms>
const BatchFns* plugin_table() {
  static constexpr BatchFns kTable[] = {plugin_eval_fns<Ms, WF, WFF, WD>()...,
                                        plugin_sample_fns<Ms, WF, WFF, WD>()...};
  return kTable;
}

// The batch types of this unit's ISA, as core/simd/isa_*.cpp use them.
#if defined(GLINTLAB_PLUGIN_ISA_SCALAR)
template <class... Ms>
const BatchFns* plugin_isa_table() {
  return plugin_table<float, Wide<float, FastMath>, double, Ms...>();
}
#else
#if defined(GLINTLAB_PLUGIN_ISA_SSE42) && defined(__SSE4_2__)
using PluginArch = xsimd::sse4_2;
#elif defined(GLINTLAB_PLUGIN_ISA_AVX2) && defined(__AVX2__) && defined(__FMA__)
using PluginArch = xsimd::fma3<xsimd::avx2>;
#elif defined(GLINTLAB_PLUGIN_ISA_AVX512) && defined(__AVX512F__) && defined(__AVX512BW__)
using PluginArch = xsimd::avx512bw;
#else
#error "GLINTLAB_PLUGIN_ISA: compile this unit through glintlab_add_model_plugin (ISA flags)"
#endif
template <class... Ms>
const BatchFns* plugin_isa_table() {
  return plugin_table<Wide<xsimd::batch<float, PluginArch> >,
                      Wide<xsimd::batch<float, PluginArch>, FastMath>,
                      Wide<xsimd::batch<double, PluginArch> >, Ms...>();
}
#endif

}  // namespace
}  // namespace glintlab::simd::detail

#define GLINTLAB_PLUGIN_CAT2(a, b) a##b
#define GLINTLAB_PLUGIN_CAT(a, b) GLINTLAB_PLUGIN_CAT2(a, b)
#define GLINTLAB_PLUGIN(...)                                                              \
  const ::glintlab::simd::detail::BatchFns* GLINTLAB_PLUGIN_CAT(glintlab_plugin_batches_, \
                                                                GLINTLAB_PLUGIN_ISA)() {  \
    return ::glintlab::simd::detail::plugin_isa_table<__VA_ARGS__>();                     \
  }                                                                                       \
  static_assert(true, "GLINTLAB_PLUGIN(...) is followed by a semicolon")

#endif

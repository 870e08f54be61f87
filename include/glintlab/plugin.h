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
#pragma once

#include <cstdint>
#include <vector>

#include "core/model.h"
#include "core/model_registry.h"
#include "glintlab/version.h"

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
                sizeof(ModelSample<double>)};
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
template <Model... Ms>
void append_models(std::vector<ModelEntry>& out) {
  (out.push_back(make_model_entry<Ms>()), ...);
}
}  // namespace detail

}  // namespace glintlab::plugin

// The entry point's name; the number changes when PluginInfo's layout does, so a loader never
// reads a struct it does not know.
#define GLINTLAB_PLUGIN_ENTRY_POINT "glintlab_plugin_v1"

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

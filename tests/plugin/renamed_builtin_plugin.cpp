// The built-in smooth_ggx model under another name, as a plug-in: its batches, compiled in the
// plug-in's ISA units, must equal the built-in model's bit for bit
// (tests/simd/plugin_batch_test.cpp).
#include <glintlab/plugin.h>

#include "core/models/smooth_ggx.h"

namespace glintlab::test {
struct PluginSmoothGGX : SmoothGGX {
  static constexpr std::string_view kName = "plugin_smooth_ggx";
};
}  // namespace glintlab::test

GLINTLAB_PLUGIN(glintlab::test::PluginSmoothGGX);

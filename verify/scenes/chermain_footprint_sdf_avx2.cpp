// glint_values in AVX2 (4 doubles) lanes (verify/scenes/chermain_footprint_sdf_lanes.h).
#if !defined(__AVX2__)
#error \
    "chermain_footprint_sdf_avx2.cpp must be compiled with its ISA's flags (verify/CMakeLists.txt)"
#endif
#include "verify/scenes/chermain_footprint_sdf_lanes.h"

namespace glintlab::verify::detail {

void glint_values_avx2(const FootprintSdf& sdf, const GlintSamples& samples,
                       std::span<double> out) {
  glint_values_lanes<Wide<xsimd::batch<double, xsimd::fma3<xsimd::avx2>>>>(sdf, samples, out);
}

void glint_values_avx2(const SampleFootprints& footprints, const GlintSamples& samples,
                       std::span<double> out) {
  glint_values_lanes<Wide<xsimd::batch<double, xsimd::fma3<xsimd::avx2>>>>(footprints, samples,
                                                                           out);
}

}  // namespace glintlab::verify::detail

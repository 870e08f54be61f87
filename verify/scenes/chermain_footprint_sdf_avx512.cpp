// glint_values in AVX-512 (8 doubles) lanes (verify/scenes/chermain_footprint_sdf_lanes.h).
#if !defined(__AVX512BW__)
#error \
    "chermain_footprint_sdf_avx512.cpp must be compiled with its ISA's flags (verify/CMakeLists.txt)"
#endif
#include "verify/scenes/chermain_footprint_sdf_lanes.h"

namespace glintlab::verify::detail {

void glint_values_avx512(const FootprintSdf& sdf, const GlintSamples& samples,
                         std::span<double> out) {
  glint_values_lanes<Wide<xsimd::batch<double, xsimd::avx512bw>>>(sdf, samples, out);
}

void glint_values_avx512(const SampleFootprints& footprints, const GlintSamples& samples,
                         std::span<double> out) {
  glint_values_lanes<Wide<xsimd::batch<double, xsimd::avx512bw>>>(footprints, samples, out);
}

}  // namespace glintlab::verify::detail

// Eq. 8's density over rows in AVX-512 (8 doubles) lanes (verify/claims/eto/eq8_density_lanes.h).
#if !defined(__AVX512BW__)
#error "eq8_density_avx512.cpp must be compiled with its ISA's flags (verify/CMakeLists.txt)"
#endif
#include "verify/claims/eto/eq8_density_lanes.h"

namespace glintlab::verify::eto_claims::detail {

void eq8_density_avx512(const Eq8Incidence& a, std::span<const Vec3<double>> wo,
                        std::span<double> out) {
  eq8_density_lanes<Wide<xsimd::batch<double, xsimd::avx512bw>>>(a, wo, out);
}

}  // namespace glintlab::verify::eto_claims::detail

// Eq. 8's density over rows in SSE4.2 (2 doubles) lanes (verify/claims/eto/eq8_density_lanes.h).
#if !defined(__SSE4_2__)
#error "eq8_density_sse42.cpp must be compiled with its ISA's flags (verify/CMakeLists.txt)"
#endif
#include "verify/claims/eto/eq8_density_lanes.h"

namespace glintlab::verify::eto_claims::detail {

void eq8_density_sse42(const Eq8Incidence& a, std::span<const Vec3<double>> wo,
                       std::span<double> out) {
  eq8_density_lanes<Wide<xsimd::batch<double, xsimd::sse4_2>>>(a, wo, out);
}

}  // namespace glintlab::verify::eto_claims::detail

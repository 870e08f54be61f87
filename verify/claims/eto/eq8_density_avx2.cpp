// Eq. 8's density over rows in AVX2 (4 doubles) lanes (verify/claims/eto/eq8_density_lanes.h).
#if !defined(__AVX2__)
#error "eq8_density_avx2.cpp must be compiled with its ISA's flags (verify/CMakeLists.txt)"
#endif
#include "verify/claims/eto/eq8_density_lanes.h"

namespace glintlab::verify::eto_claims::detail {

void eq8_density_avx2(const Eq8Incidence& a, std::span<const Vec3<double>> wo,
                      std::span<double> out) {
  eq8_density_lanes<Wide<xsimd::batch<double, xsimd::fma3<xsimd::avx2>>>>(a, wo, out);
}

}  // namespace glintlab::verify::eto_claims::detail

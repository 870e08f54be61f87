// Eq. 8's density at many directions per call: the lanes of simd::default_isa(), or one direction
// at a time on the scalar ISA; the same bits either way (tests/verify/claims/eto_pdf_matches_test.cpp).
#include "verify/claims/eto/eq8_density.h"

#include "core/simd/batch.h"

namespace glintlab::verify::eto_claims {

namespace detail {
void eq8_density_sse42(const Eq8Incidence&, std::span<const Vec3<double>>, std::span<double>);
void eq8_density_avx2(const Eq8Incidence&, std::span<const Vec3<double>>, std::span<double>);
void eq8_density_avx512(const Eq8Incidence&, std::span<const Vec3<double>>, std::span<double>);
}  // namespace detail

DirectionPdfRows Eq8ReflectionPdf::rows() const {
  return [pdf = *this](std::span<const Vec3<double>> wo, std::span<double> out) {
    switch (simd::default_isa()) {
      case simd::Isa::kAvx512: return detail::eq8_density_avx512(pdf.a_, wo, out);
      case simd::Isa::kAvx2: return detail::eq8_density_avx2(pdf.a_, wo, out);
      case simd::Isa::kSse42: return detail::eq8_density_sse42(pdf.a_, wo, out);
      case simd::Isa::kScalar: break;
    }
    for (std::size_t r = 0; r < wo.size(); ++r) out[r] = pdf(wo[r]);
  };
}

}  // namespace glintlab::verify::eto_claims

// glint_values: the lanes of AVX2 or AVX-512 where no footprint has a smooth term, else one
// sample at a time; the same bits either way (tests/verify/scenes/chermain_footprint_sdf_test.cpp).
#include "verify/scenes/chermain_footprint_sdf.h"

namespace glintlab::verify {

namespace detail {
void glint_values_avx2(const FootprintSdf&, const GlintSamples&, std::span<double>);
void glint_values_avx512(const FootprintSdf&, const GlintSamples&, std::span<double>);
void glint_values_avx2(const SampleFootprints&, const GlintSamples&, std::span<double>);
void glint_values_avx512(const SampleFootprints&, const GlintSamples&, std::span<double>);
}  // namespace detail

namespace {

void check(std::size_t samples, std::size_t out, simd::Isa isa) {
  if (out != samples) throw std::invalid_argument("glint_values: one output per sample");
  if (!simd::isa_supported(isa)) throw std::invalid_argument("glint_values: an ISA this CPU lacks");
}

// The SSE4.2 batches have no fused multiply-add (dot() would round otherwise): one at a time.
bool has_lanes(simd::Isa isa) { return isa == simd::Isa::kAvx512 || isa == simd::Isa::kAvx2; }

double glint_value_at(const FootprintSdf& sdf, const GlintSamples& s, std::size_t i) {
  return glint_value_of(sdf, {s.wi_x[i], s.wi_y[i], s.wi_z[i]}, {s.wl_x[i], s.wl_y[i], s.wl_z[i]},
                        {s.shift_x[i], s.shift_y[i]});
}

}  // namespace

void glint_values(const FootprintSdf& sdf, const GlintSamples& samples, std::span<double> out,
                  simd::Isa isa) {
  check(samples.size(), out.size(), isa);
  if (!sdf.has_smooth() && has_lanes(isa))
    return isa == simd::Isa::kAvx512 ? detail::glint_values_avx512(sdf, samples, out)
                                     : detail::glint_values_avx2(sdf, samples, out);
  for (std::size_t i = 0; i < samples.size(); ++i) out[i] = glint_value_at(sdf, samples, i);
}

void glint_values(const FootprintSdf& sdf, const GlintSamples& samples, std::span<double> out) {
  glint_values(sdf, samples, out, simd::default_isa());
}

void glint_values(const SampleFootprints& footprints, const GlintSamples& samples,
                  std::span<double> out, simd::Isa isa) {
  check(samples.size(), out.size(), isa);
  if (footprints.size() != samples.size())
    throw std::invalid_argument("glint_values: one footprint per sample");
  if (has_lanes(isa)) {
    if (isa == simd::Isa::kAvx512)
      detail::glint_values_avx512(footprints, samples, out);
    else
      detail::glint_values_avx2(footprints, samples, out);
  }
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (!has_lanes(isa) || footprints.smooth(i))
      out[i] = glint_value_at(footprints.sdf(i), samples, i);
}

void glint_values(const SampleFootprints& footprints, const GlintSamples& samples,
                  std::span<double> out) {
  glint_values(footprints, samples, out, simd::default_isa());
}

}  // namespace glintlab::verify

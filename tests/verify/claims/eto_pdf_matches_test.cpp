// eto.pdf-matches's density (verify/claims/eto/eq8_density.h) computes what depends on ωi alone
// once: the density as it was written before, per call, bit for bit; and its rows, in double lanes
// of every ISA this CPU has, the same bits again.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/math/rng.h"
#include "core/ndf/microfacet.h"
#include "core/simd/batch.h"
#include "verify/claims/eto/eq8_density.h"
#include "verify/claims/gof_family.h"  // incidence

namespace glintlab::verify::eto_claims {
namespace {

using V3 = Vec3<double>;

// Eq. 8 × ‖dm/do‖ as eto.pdf-matches evaluated it before (everything per call).
double eq8_reflection_pdf_per_call(const GGX<double>& g, const V3& i, const V3& o,
                                   BoundedVndfBound bound) {
  if (i.z <= 0) return pdf_vndf_backfacing_eq7(g, i, o);
  const V3 m = half_vector(i, o);
  const double im = dot(i, m);
  if (!(im > 0)) return 0;
  const double k = bounded_vndf_k(g, i, bound);
  const double t = std::sqrt(sqr(g.alpha_x * i.x) + sqr(g.alpha_y * i.y) + sqr(i.z));
  const V3 i_std = normalize(V3{g.alpha_x * i.x, g.alpha_y * i.y, i.z});
  const V3 m_std = normalize(V3{m.x / g.alpha_x, m.y / g.alpha_y, m.z});
  const V3 o_std = 2 * dot(i_std, m_std) * m_std - i_std;
  const double heaviside = k * i_std.z + o_std.z > 0 ? 1 : 0;
  const double p_m = 2 * g.D(m) * im / (k * i.z + t) * heaviside;
  return p_m / (4 * std::abs(im));
}

V3 uniform_direction(std::uint64_t seed, std::uint64_t n) {
  const double z = 2 * counter_uniform<double>(seed, n, 0) - 1;
  const double phi = 2 * 3.14159265358979323846 * counter_uniform<double>(seed, n, 1);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

TEST(EtoPdfMatchesDensity, IsThePerCallDensityBitForBit) {
  const GGX<double> ggxs[] = {{0.05, 0.05}, {0.3, 0.3}, {1, 1}, {1.5, 1.5}, {0.6, 0.2}, {0.1, 1}};
  std::size_t compared = 0, zero_by_heaviside = 0, positive = 0;
  for (const GGX<double>& g : ggxs)
    for (BoundedVndfBound bound : {BoundedVndfBound::kListing1, BoundedVndfBound::kExactIsotropic})
      for (double theta : {0.0, 45.0, 80.0, 89.0, 120.0, 150.0}) {
        const V3 wi = incidence(theta);
        const Eq8ReflectionPdf pdf(g, wi, bound);
        for (std::uint64_t n = 0; n < 2000; ++n) {
          const V3 wo = uniform_direction(7, n);
          const double before = eq8_reflection_pdf_per_call(g, wi, wo, bound);
          ASSERT_EQ(std::signbit(pdf(wo)), std::signbit(before));
          ASSERT_EQ(pdf(wo), before) << "α " << g.alpha_x << "," << g.alpha_y << " θ " << theta;
          ++compared;
          positive += before > 0;
          zero_by_heaviside += wi.z > 0 && before == 0 && dot(wi, half_vector(wi, wo)) > 0;
        }
      }
  EXPECT_EQ(compared, 144000u);
  EXPECT_GT(positive, 10000u);
  EXPECT_GT(zero_by_heaviside, 1000u) << "the χ⁺ = 0 branch is exercised";
}

// Runs f with GLINTLAB_ISA set to `isa` (the rows use simd::default_isa()).
template <class F>
void with_isa(simd::Isa isa, F&& f) {
  const char* old = std::getenv("GLINTLAB_ISA");
  const std::string saved = old ? old : "";
  setenv("GLINTLAB_ISA", std::string(simd::isa_name(isa)).c_str(), 1);
  f();
  if (old)
    setenv("GLINTLAB_ISA", saved.c_str(), 1);
  else
    unsetenv("GLINTLAB_ISA");
}

// The density's rows on every ISA of this CPU against the per-call density, bit for bit; row
// counts that leave a partial last batch of lanes, and directions where i·m ≤ 0, χ⁺ = 0 and
// ωo = −ωi (the half vector 0) among them. Returns the number of rows that differ.
std::size_t rows_differing(simd::Isa isa, bool one_row_one_ulp_up) {
  std::size_t differing = 0;
  const GGX<double> ggxs[] = {{0.05, 0.05}, {0.3, 0.3}, {1.5, 1.5}, {0.6, 0.2}};
  with_isa(isa, [&] {
    for (const GGX<double>& g : ggxs)
      for (BoundedVndfBound bound : {BoundedVndfBound::kListing1, BoundedVndfBound::kExactIsotropic})
        for (double theta : {0.0, 45.0, 89.0, 150.0}) {
          const V3 wi = incidence(theta);
          const Eq8ReflectionPdf pdf(g, wi, bound);
          std::vector<V3> wo;
          for (std::uint64_t n = 0; n < 1001; ++n) wo.push_back(uniform_direction(11, n));
          wo[500] = -wi;
          std::vector<double> out(wo.size());
          pdf.rows()(wo, out);
          if (one_row_one_ulp_up) out[777] = std::nextafter(out[777], HUGE_VAL);
          for (std::size_t r = 0; r < wo.size(); ++r) {
            const double before = eq8_reflection_pdf_per_call(g, wi, wo[r], bound);
            differing += std::signbit(out[r]) != std::signbit(before) ||
                         !(out[r] == before || (std::isnan(out[r]) && std::isnan(before)));
          }
        }
  });
  return differing;
}

TEST(EtoPdfMatchesDensity, RowsAreThePerCallDensityBitForBitOnEveryIsa) {
  int isas = 0;
  for (simd::Isa isa : simd::kAllIsas) {
    if (!simd::isa_supported(isa)) {
      std::printf("%s: not supported by this CPU, not compared\n",
                  std::string(simd::isa_name(isa)).c_str());
      continue;
    }
    EXPECT_EQ(rows_differing(isa, false), 0u) << simd::isa_name(isa);
    ++isas;
  }
  EXPECT_GE(isas, 2);
}

// The comparison above catches one row in each 1001 one ulp up (32 configurations).
TEST(EtoPdfMatchesDensity, ARowOneUlpOffIsCaught) {
  EXPECT_EQ(rows_differing(simd::best_isa(), true), 32u);
}

}  // namespace
}  // namespace glintlab::verify::eto_claims

// The sampler table; see sampler_table.h.
#include "verify/claims/sampler_table.h"

#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/beckmann_vndf.h"
#include "core/samplers/bounded_vndf.h"
#include "core/samplers/heitz_vndf.h"
#include "core/samplers/spherical_caps.h"
#include "core/samplers/walter.h"

namespace glintlab::verify {
namespace {

using V3 = Vec3<double>;
using V2 = Vec2<double>;

template <class Ndf>
double brdf_of(double ax, double ay, V3 wi, V3 wo) {
  return microfacet_brdf(Ndf{ax, ay}, wi, wo, 1.0);
}

}  // namespace

const std::vector<SamplerEntry>& sampler_table() {
  using G = GGX<double>;
  using B = Beckmann<double>;
  static const std::vector<SamplerEntry> table = {
      {"walter/ggx", true, false,
       [](double ax, double ay, V3 wi, V2 u) {
         return sample_walter(G{ax, ay}, wi, u);
       },
       [](double ax, double ay, V3 wi, V3 wo) {
         return pdf_walter(G{ax, ay}, wi, wo);
       },
       brdf_of<G>},
      {"walter/beckmann", false, false,
       [](double ax, double ay, V3 wi, V2 u) {
         return sample_walter(B{ax, ay}, wi, u);
       },
       [](double ax, double ay, V3 wi, V3 wo) {
         return pdf_walter(B{ax, ay}, wi, wo);
       },
       brdf_of<B>},
      {"heitz_vndf/ggx", true, false,
       [](double ax, double ay, V3 wi, V2 u) {
         return sample_heitz_vndf(G{ax, ay}, wi, u);
       },
       [](double ax, double ay, V3 wi, V3 wo) {
         return pdf_heitz_vndf(G{ax, ay}, wi, wo);
       },
       brdf_of<G>},
      {"beckmann_vndf/beckmann", false, false,
       [](double ax, double ay, V3 wi, V2 u) {
         return sample_beckmann_vndf(B{ax, ay}, wi, u);
       },
       [](double ax, double ay, V3 wi, V3 wo) {
         return pdf_beckmann_vndf(B{ax, ay}, wi, wo);
       },
       brdf_of<B>},
      {"spherical_caps/ggx", true, true,
       [](double ax, double ay, V3 wi, V2 u) {
         return sample_spherical_caps(G{ax, ay}, wi, u);
       },
       [](double ax, double ay, V3 wi, V3 wo) {
         return pdf_spherical_caps(G{ax, ay}, wi, wo);
       },
       brdf_of<G>},
      {"bounded_vndf_listing1/ggx", true, true,
       [](double ax, double ay, V3 wi, V2 u) {
         return sample_bounded_vndf(G{ax, ay}, wi, u, BoundedVndfBound::kListing1);
       },
       [](double ax, double ay, V3 wi, V3 wo) {
         return pdf_bounded_vndf(G{ax, ay}, wi, wo, BoundedVndfBound::kListing1);
       },
       brdf_of<G>},
      {"bounded_vndf_exact_isotropic/ggx", true, true,
       [](double ax, double ay, V3 wi, V2 u) {
         return sample_bounded_vndf(G{ax, ay}, wi, u, BoundedVndfBound::kExactIsotropic);
       },
       [](double ax, double ay, V3 wi, V3 wo) {
         return pdf_bounded_vndf(G{ax, ay}, wi, wo, BoundedVndfBound::kExactIsotropic);
       },
       brdf_of<G>},
  };
  return table;
}

}  // namespace glintlab::verify

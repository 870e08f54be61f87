// The sampler table; see sampler_table.h. One entry per row of the sampler list
// (core/samplers/sampler_list.h), in its order.
#include "verify/claims/sampler_table.h"

#include "core/ndf/microfacet.h"
#include "core/samplers/sampler_list.h"

namespace glintlab::verify {

const std::vector<SamplerEntry>& sampler_table() {
  using V3 = Vec3<double>;
  using V2 = Vec2<double>;
  static const std::vector<SamplerEntry> table = [] {
    std::vector<SamplerEntry> t;
    samplers::for_each<samplers::All>([&]<class S>() {
      using Ndf = typename S::template Ndf<double>;
      t.push_back({std::string(S::kInfo.name), S::kInfo.ndf == "ggx", S::kInfo.allows_backfacing,
                   [](double ax, double ay, V3 wi, V2 u) {
                     return S::sample(Ndf{ax, ay}, wi, u);
                   },
                   [](double ax, double ay, V3 wi, V3 wo) {
                     return S::pdf(Ndf{ax, ay}, wi, wo);
                   },
                   [](double ax, double ay, V3 wi, V3 wo) {
                     return microfacet_brdf(Ndf{ax, ay}, wi, wo, 1.0);
                   }});
    });
    return t;
  }();
  return table;
}

}  // namespace glintlab::verify

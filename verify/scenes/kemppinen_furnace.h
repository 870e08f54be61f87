// One sample of the area-averaged white furnace of Kemppinen et al. 2025 (Fig. 15), shared by the
// claim kemppinen.furnace and the figure kemppinen2025-fig15: ω_h ~ D cosθ_h (Walter et al. 2007
// Eq. 28–29, 35–36), ω_i its reflection about ω_h, at a position x of the surface. The weight of
// the smooth NDF is G2 |ω_o·ω_h| / (cosθ_o cosθ_h); the glinty one multiplies it by D★^f(x)/D
// (footprint 16 level-0 cells). Both are 0 for a reflection below the horizon.
#pragma once

#include "core/glints/kemppinen.h"
#include "core/math/vec.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/walter.h"
#include "verify/scenes/kemppinen_presets.h"

namespace glintlab::kemppinen2025 {

struct FurnaceSample {
  double glint = 0, smooth = 0;
};

template <class Ndf>
FurnaceSample furnace_sample(const Params<double>& p, const Ndf& ndf, const Vec3<double>& wo,
                             Vec2<double> x, Vec2<double> u) {
  const Vec3<double> m = sample_normal_walter(ndf, u);
  const Vec3<double> wi = reflect(wo, m);
  if (!(wi.z > 0 && dot(wo, m) > 0)) return {};
  const double s = smith_g2_height_correlated(ndf, wo, wi, m) * dot(wo, m) / (wo.z * m.z);
  const FootprintQuery<double> fp = footprint_cells(x, 16, p);
  return {s * eval(p, ndf, fp, m).d.x / ndf.D(m), s};
}

}  // namespace glintlab::kemppinen2025

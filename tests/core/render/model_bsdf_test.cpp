// The model-interface adapter of the MIS reference: smooth GGX through core/model.h gives the same
// area-light estimate as the hand-written GGX BSDF on the same uniforms, and a model with the
// wrong roughness (the control) does not.
#include "core/render/model_bsdf.h"

#include <gtest/gtest.h>

#include "core/lights/disk_light.h"
#include "core/models/smooth_ggx.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/heitz_vndf.h"

namespace glintlab {
namespace {

using V3 = Vec3<double>;

struct DirectGgx {  // the reference's BSDF written directly on the core kernels
  GGX<double> ggx;
  double f(V3 wo, V3 wi) const { return microfacet_brdf(ggx, wo, wi, 1.0); }
  BsdfSample<double> sample(V3 wo, Vec2<double> u) const {
    const MicrofacetSample<double> s = sample_heitz_vndf(ggx, wo, u);
    return {s.wo, s.pdf, s.rejected};
  }
  double pdf(V3 wo, V3 wi) const { return pdf_heitz_vndf(ggx, wo, wi); }
};

static_assert(ReferenceBsdf<ModelBsdf<SmoothGGX>, double>);

ReferenceEstimate estimate(const auto& bsdf) {
  const V3 wo = normalize(V3{0.5, 0.1, 0.866});
  const V3 c = 2.0 * V3{-wo.x, -wo.y, wo.z} + V3{0.3, 0.2, 0.0};
  const DiskLight<double> light = make_disk_light(c, -c, 0.5, V3{2.0, 1.0, 0.5});
  const ShadingPoint<double> sp{{0, 0, 0}, basis_from_z(V3{0, 0, 1})};
  ReferenceOptions o;
  o.samples = 1 << 14;
  o.seed = 7;
  return area_light_reference(light, bsdf, sp, wo, o);
}

TEST(ModelBsdf, SmoothGgxThroughTheModelInterfaceEqualsTheKernels) {
  const ModelBsdf<SmoothGGX> model{{GGX<double>{0.3, 0.3}, SmoothGGX::Choices::find("vndf")}};
  const ReferenceEstimate a = estimate(model), b = estimate(DirectGgx{{0.3, 0.3}});
  EXPECT_GT(a.mean.x, 0.0);
  EXPECT_NEAR(a.mean.x, b.mean.x, 1e-12 * b.mean.x);
  EXPECT_NEAR(a.mean.z, b.mean.z, 1e-12 * b.mean.z);
  // Control: the model at α = 0.36 (20 % off) must differ by many standard errors.
  const ModelBsdf<SmoothGGX> wrong{{GGX<double>{0.36, 0.36}, SmoothGGX::Choices::find("vndf")}};
  const ReferenceEstimate w = estimate(wrong);
  EXPECT_GT(std::abs(w.mean.x - b.mean.x), 5 * (w.std_error.x + b.std_error.x));
}

}  // namespace
}  // namespace glintlab

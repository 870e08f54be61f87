// Include order does not change which ops a kernel uses: kernels included before core/simd/wide.h.
#include <gtest/gtest.h>

#include <bit>

#include "core/ndf/beckmann.h"  // first, on purpose: before any Wide overload is declared
#include "core/samplers/heitz_vndf.h"
#include "core/simd/wide.h"

namespace glintlab {
namespace {

// Wide<float, ExactMath> must give the scalar float kernel bit for bit (its ops are the same
// std:: calls), and Wide<float, FastMath> must differ: both prove ADL found the Wide overloads
// although the kernel templates were defined before them.
TEST(SimdIncludeOrder, KernelsDefinedBeforeWideUseWideOps) {
  using WE = Wide<float, ExactMath>;
  using WF = Wide<float, FastMath>;
  int fast_differs = 0;
  for (int i = 1; i < 2000; ++i) {
    const float t = float(i) / 2000.0f;
    const Vec3<float> m = normalize(Vec3<float>{0.3f * t, -0.2f, 1.0f - 0.5f * t});
    const float ref = Beckmann<float>{0.2f, 0.35f}.D(m);
    const WE e = Beckmann<WE>{WE(0.2f), WE(0.35f)}.D(Vec3<WE>{WE(m.x), WE(m.y), WE(m.z)});
    const WF f = Beckmann<WF>{WF(0.2f), WF(0.35f)}.D(Vec3<WF>{WF(m.x), WF(m.y), WF(m.z)});
    EXPECT_EQ(std::bit_cast<std::uint32_t>(ref), std::bit_cast<std::uint32_t>(e.v)) << i;
    fast_differs += std::bit_cast<std::uint32_t>(ref) != std::bit_cast<std::uint32_t>(f.v);
  }
  EXPECT_GT(fast_differs, 100);
  // sincos has no scalar-signature match for Wide: it must resolve to the Wide overload too.
  const Vec3<float> s = sample_normal_heitz_vndf(
      GGX<float>{0.3f, 0.3f}, Vec3<float>{0.6f, 0.0f, 0.8f}, Vec2<float>{0.3f, 0.7f});
  const Vec3<WE> w =
      sample_normal_heitz_vndf(GGX<WE>{WE(0.3f), WE(0.3f)}, Vec3<WE>{WE(0.6f), WE(0.0f), WE(0.8f)},
                               Vec2<WE>{WE(0.3f), WE(0.7f)});
  EXPECT_EQ(s.x, w.x.v);
  EXPECT_EQ(s.y, w.y.v);
  EXPECT_EQ(s.z, w.z.v);
}

}  // namespace
}  // namespace glintlab

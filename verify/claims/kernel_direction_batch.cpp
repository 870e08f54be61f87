#include "verify/claims/kernel_direction_batch.h"

#include <vector>

#include "core/simd/batch.h"

namespace glintlab::verify {

SeededDirectionBatch kernel_direction_batch(int kernel, Vec3<double> wi, double ax, double ay,
                                            bool upper_only) {
  const simd::Isa isa = simd::default_isa();
  return [kernel, isa, wi, ax, ay, upper_only](std::uint64_t seed, std::uint64_t begin,
                                                std::size_t count, Vec3<double>* out) {
    std::vector<double> u1(count), u2(count), o(8 * count);
    for (std::size_t i = 0; i < count; ++i) {
      const Vec2<double> u = uniform_pair(seed, begin + i);
      u1[i] = u.x;
      u2[i] = u.y;
    }
    const double w[3] = {wi.x, wi.y, wi.z};
    double* p = o.data();
    simd::sample_batch<double>(kernel, ax, ay, w, u1.data(), u2.data(),
                               {p, p + count, p + 2 * count, p + 3 * count, p + 4 * count,
                                p + 5 * count, p + 6 * count, p + 7 * count},
                               count, isa);
    for (std::size_t i = 0; i < count; ++i) {
      const Vec3<double> wo{p[i], p[count + i], p[2 * count + i]};
      out[i] = upper_only && !(wo.z > 0) ? Vec3<double>{0, 0, 0} : wo;
    }
  };
}

}  // namespace glintlab::verify

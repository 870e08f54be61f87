// The scene Kneiphof & Klein's subdivision and convergence claims share (common.h).
#include "verify/claims/kneiphof/common.h"

#include <cmath>

namespace glintlab::verify::kneiphof_claims {

std::array<Vec3<double>, 4> quad_above(double w) {
  const Vec3<double> c{0.3, 0, 1};
  return {Vec3<double>{c.x - w, c.y + w, c.z}, Vec3<double>{c.x + w, c.y + w, c.z},
          Vec3<double>{c.x + w, c.y - w, c.z}, Vec3<double>{c.x - w, c.y - w, c.z}};
}

Vec3<double> view_30() { return {-0.5, 0, std::sqrt(0.75)}; }

}  // namespace glintlab::verify::kneiphof_claims

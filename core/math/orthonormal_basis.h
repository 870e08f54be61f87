// Orthonormal basis around one unit vector, without branches: Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited" (JCGT 6(1)), Listing 3 (the revised Frisvad construction).
#pragma once

#include "core/math/vec.h"

namespace glintlab {

// Right-handed frame (x, y, z): x × y = z.
template <class T>
struct OrthonormalBasis {
  Vec3<T> x, y, z;

  GLINTLAB_FN Vec3<T> to_local(Vec3<T> v) const { return {dot(v, x), dot(v, y), dot(v, z)}; }
  GLINTLAB_FN Vec3<T> to_world(Vec3<T> v) const { return v.x * x + v.y * y + v.z * z; }
};

// Frame with z = n (unit). Duff et al. Listing 3: the copysign keeps 1/(s + n_z) away from 0 for
// both hemispheres, so there is no singular direction.
template <class T>
GLINTLAB_FN OrthonormalBasis<T> basis_from_z(Vec3<T> n) {
  const T s = sign_not_zero(n.z);
  const T a = T(-1) / (s + n.z);
  const T b = n.x * n.y * a;
  return {Vec3<T>{T(1) + s * n.x * n.x * a, s * b, -s * n.x}, Vec3<T>{b, s + n.y * n.y * a, -n.y},
          n};
}

}  // namespace glintlab

// Fresnel reflectance for the microfacet BRDF: Schlick's approximation (Schlick 1994 Eq. 15) and
// the exact conductor reflectance for a complex index η + iκ (unpolarized average of Rs and Rp,
// in the real-arithmetic form of Lagarde, "Memo on Fresnel equations", 2013).
#pragma once

#include "core/math/vec.h"

namespace glintlab {

// F = F0 + (1 − F0)(1 − cosθ)^5, cosθ = ωi·h clamped to [0, 1].
template <class T>
GLINTLAB_FN T fresnel_schlick(T f0, T cos_theta) {
  const T c = T(1) - saturate(cos_theta);
  const T c2 = c * c;
  return fma(T(1) - f0, c2 * c2 * c, f0);
}

// Conductor with relative index η + iκ, one wavelength per call.
template <class T>
GLINTLAB_FN T fresnel_conductor(T eta, T kappa, T cos_theta) {
  const T c = saturate(cos_theta);
  const T cos2 = c * c;
  const T sin2 = T(1) - cos2;
  const T eta2 = eta * eta;
  const T k2 = kappa * kappa;
  const T t0 = eta2 - k2 - sin2;
  const T a2pb2 = sqrt(fma(t0, t0, T(4) * eta2 * k2));
  // a = Re √(t0 + 2iηκ). For t0 < 0 (every conductor with κ > η) a2pb2 + t0 cancels, so there
  // b = Im √(·) = √((a2pb2 − t0)/2) is taken first and a = ηκ/b (ab = ηκ).
  const T b = safe_sqrt(T(0.5) * (a2pb2 - t0));
  const T a =
      select(t0 >= T(0), safe_sqrt(T(0.5) * (a2pb2 + t0)), eta * kappa / select(b > T(0), b, T(1)));
  const T t1 = a2pb2 + cos2;
  const T t2 = T(2) * c * a;
  const T rs = (t1 - t2) / (t1 + t2);
  const T t3 = fma(cos2, a2pb2, sin2 * sin2);
  const T t4 = t2 * sin2;
  const T rp = rs * (t3 - t4) / (t3 + t4);
  return T(0.5) * (rs + rp);
}

}  // namespace glintlab

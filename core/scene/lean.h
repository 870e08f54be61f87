// LEAN mapping parameters from filtered slope moments: Olano & Baker 2010 ("LEAN Mapping", I3D),
// Sec. 3.2–4: the slope distribution within a footprint is a Gaussian with mean B = (E[s_x],
// E[s_y]) and covariance Σ = M − B Bᵀ, M the filtered second moments, plus the microsurface's own
// slope variance; σ_x, σ_y and ρ as Chermain et al. 2021 Eq. 16 write Σ.
#pragma once

#include "core/math/vec.h"
#include "core/scene/slope_moment_map.h"

namespace glintlab {

template <class T>
struct LeanParameters {
  T mean_x, mean_y;    // E[s_x], E[s_y]: the filtered normal's slopes
  T sigma_x, sigma_y;  // √Σ_xx, √Σ_yy
  T rho;               // Σ_xy / (σ_x σ_y), in [−1, 1]
};

// `base_alpha`: roughness of the underlying Beckmann microsurface, whose slopes have variance
// α²/2 per axis (Beckmann slope density exp(−|s|²/α²)/(πα²)); 0 for a mirror microsurface. Rounding
// can make M − B Bᵀ slightly negative for a constant map: clamped to 0, and ρ = 0 where σ = 0.
template <class T>
GLINTLAB_FN LeanParameters<T> lean_parameters(const SlopeMoments<T>& m, T base_alpha = T(0)) {
  const T base = T(0.5) * base_alpha * base_alpha;
  const T vx = max(m.xx - m.mean_x * m.mean_x, T(0)) + base;
  const T vy = max(m.yy - m.mean_y * m.mean_y, T(0)) + base;
  const T c = m.xy - m.mean_x * m.mean_y;
  const T sx = sqrt(vx), sy = sqrt(vy);
  const T rho = clamp(safe_div(c, sx * sy), T(-1), T(1));
  return {m.mean_x, m.mean_y, sx, sy, rho};
}

}  // namespace glintlab

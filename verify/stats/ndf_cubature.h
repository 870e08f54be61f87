// Cubature of functions of the microfacet normal with breakpoints suited to an NDF of roughness
// (αx, αy), so integrals resolve lobes down to α = 1e-3 and anisotropy 1:1000.
#pragma once

#include <algorithm>
#include <numbers>

#include "verify/stats/sphere_cubature.h"

namespace glintlab::verify {

// ∫ f(ω) dω over the sphere (or the upper hemisphere when upper_only), split where an NDF lobe of
// roughness (ax, ay) around +z varies.
// When `kink` is given, θ is also split where kink·m = 0 (the crease of a max(0, kink·m) factor).
template <class F>
Integral integrate_ndf_lobe(F&& f, double ax, double ay, bool upper_only = false,
                                    double rel_tol = 1e-10, const Vec3<double>* kink = nullptr) {
  SphereCubatureOptions o;
  o.theta_max = upper_only ? std::numbers::pi / 2 : std::numbers::pi;
  o.theta_breaks = lobe_theta_breaks(std::min(ax, ay), 0, o.theta_max);
  const auto more = lobe_theta_breaks(std::max(ax, ay), 0, o.theta_max);
  o.theta_breaks.insert(o.theta_breaks.end(), more.begin(), more.end());
  if (ax != ay) o.phi_breaks = anisotropy_phi_breaks(ax, ay);
  o.rel_tol = rel_tol;
  if (kink) {
    const Vec3<double> k = *kink;
    o.theta_breaks_at_phi = [k](double phi, std::vector<double>& b) {
      b.push_back(plane_crossing_theta(k, phi));
    };
  }
  return integrate_sphere(f, o);
}

}  // namespace glintlab::verify

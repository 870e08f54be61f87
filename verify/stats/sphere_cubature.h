// Adaptive cubature over regions of the sphere in (θ, φ), with an error estimate: nested adaptive
// Gauss–Kronrod (15-point, Boost.Math) in θ inside φ, with caller-given breakpoints so narrow lobes
// (α down to 1e-3, anisotropy to 1:1000) are resolved rather than stepped over.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "core/math/vec.h"

namespace glintlab::verify {

struct Integral {
  double value = 0;
  double error = 0;        // estimated absolute error (outer + accumulated inner estimates)
  long evaluations = 0;    // integrand calls
};

struct SphereCubatureOptions {
  double theta_min = 0;
  double theta_max = 3.14159265358979323846;  // whole sphere by default
  std::vector<double> theta_breaks;           // extra split points in (theta_min, theta_max)
  std::vector<double> phi_breaks;             // extra split points in (0, 2π)
  // Split points in θ that depend on φ, e.g. where a factor max(0, ω·m) has its kink; appended to
  // theta_breaks for each φ.
  std::function<void(double phi, std::vector<double>& breaks)> theta_breaks_at_phi;
  double rel_tol = 1e-9;
  unsigned max_depth = 18;
};

// ∫ f(ω) dω over θ ∈ [theta_min, theta_max], φ ∈ [0, 2π), ω = (sinθ cosφ, sinθ sinφ, cosθ).
Integral integrate_sphere(const std::function<double(const Vec3<double>&)>& f,
                          const SphereCubatureOptions& options);

// The same integral with f asked for many directions per call (out[i] = f(w[i]), bit for bit):
// each step of the outer rule over φ runs the inner integrals over θ at all of its azimuths in
// lockstep, and each round of their bisections asks for the points of all of their rules at
// once, for an integrand whose every call costs far more than its arithmetic (a Python model's).
// The same points, rules and bisections as integrate_sphere: the same result, bit for bit.
using SphereRows = std::function<void(std::span<const Vec3<double>> w, std::span<double> out)>;
Integral integrate_sphere_rows(const SphereRows& f, const SphereCubatureOptions& options);

// Breakpoints that resolve a lobe of angular width `width` around θ = 0 (geometric: width·2^k,
// k = −6..) and the horizon θ = π/2, clipped to (lo, hi). Used for NDF lobes of roughness α.
std::vector<double> lobe_theta_breaks(double width, double lo, double hi);

// Azimuth breakpoints for an anisotropic lobe αx:αy: the angles where tanφ = (αy/αx)·2^k, in all
// four quadrants, so a lobe squeezed to 1:1000 in φ is split where it varies.
std::vector<double> anisotropy_phi_breaks(double alpha_x, double alpha_y);

// The θ ∈ [0, π] at which the great circle ω·m = 0 crosses azimuth φ (the kink of max(0, ω·m)).
double plane_crossing_theta(const Vec3<double>& w, double phi);

}  // namespace glintlab::verify

// Nested adaptive Gauss–Kronrod cubature on the sphere; see sphere_cubature.h.
#include "verify/stats/sphere_cubature.h"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <numbers>

namespace glintlab::verify {
namespace {

using Rule = boost::math::quadrature::gauss_kronrod<double, 15>;

// Sorted, de-duplicated [lo, breaks..., hi] restricted to the open interval.
std::vector<double> partition(double lo, double hi, const std::vector<double>& breaks) {
  std::vector<double> p{lo};
  for (double b : breaks)
    if (b > lo && b < hi) p.push_back(b);
  p.push_back(hi);
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  return p;
}

struct Piece {
  double a, b, value, error;
  bool operator<(const Piece& o) const { return error < o.error; }
};

// One 15-point Kronrod estimate on [a, b] with the embedded 7-point Gauss rule as error estimate.
template <class F>
Piece kronrod(F& g, double a, double b) {
  static const auto& x = Rule::abscissa();
  static const auto& wk = Rule::weights();
  static const auto& wg = boost::math::quadrature::gauss<double, 7>::weights();
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  double k = 0, gs = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double fp = g(c + h * x[i]);
    const double fm = i == 0 ? fp : g(c - h * x[i]);
    const double sum = i == 0 ? fp : fp + fm;
    k += wk[i] * sum;
    if (i % 2 == 0) gs += wg[i / 2] * sum;  // Gauss nodes are the even Kronrod abscissae
  }
  return {a, b, k * h, std::abs((k - gs) * h)};
}

// Globally adaptive Gauss–Kronrod over the given partition: bisect the piece with the largest
// error until the total error is below max(rel_tol·|I|, abs_tol) or the piece budget is spent.
template <class F>
Integral integrate_1d(F&& g, const std::vector<double>& nodes, double rel_tol, unsigned depth) {
  std::vector<Piece> heap;
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) heap.push_back(kronrod(g, nodes[i], nodes[i + 1]));
  std::make_heap(heap.begin(), heap.end());
  const std::size_t budget = nodes.size() + (std::size_t(1) << std::min(depth, 14u));
  auto totals = [&] {
    Integral r;
    for (const Piece& p : heap) r.value += p.value, r.error += p.error;
    return r;
  };
  Integral r = totals();
  while (heap.size() < budget && r.error > std::max(rel_tol * std::abs(r.value), 1e-300)) {
    std::pop_heap(heap.begin(), heap.end());
    const Piece worst = heap.back();
    heap.pop_back();
    const double mid = 0.5 * (worst.a + worst.b);
    if (!(mid > worst.a && mid < worst.b)) {  // cannot split further: keep it and stop
      heap.push_back(worst);
      std::push_heap(heap.begin(), heap.end());
      break;
    }
    const Piece l = kronrod(g, worst.a, mid), rr = kronrod(g, mid, worst.b);
    r.value += l.value + rr.value - worst.value;
    r.error += l.error + rr.error - worst.error;
    heap.push_back(l);
    std::push_heap(heap.begin(), heap.end());
    heap.push_back(rr);
    std::push_heap(heap.begin(), heap.end());
  }
  return totals();  // re-sum to avoid drift from the running updates
}

}  // namespace

Integral integrate_sphere(const std::function<double(const Vec3<double>&)>& f,
                          const SphereCubatureOptions& o) {
  const std::vector<double> thetas = partition(o.theta_min, o.theta_max, o.theta_breaks);
  const std::vector<double> phis = partition(0.0, 2 * std::numbers::pi, o.phi_breaks);
  long evals = 0;
  double inner_error = 0;  // the largest inner error estimate seen by the outer rule
  auto outer = [&](double phi) {
    const double cp = std::cos(phi), sp = std::sin(phi);
    auto inner = [&](double theta) {
      ++evals;
      const double st = std::sin(theta);
      return f(Vec3<double>{st * cp, st * sp, std::cos(theta)}) * st;
    };
    Integral in;
    if (o.theta_breaks_at_phi) {
      std::vector<double> breaks = o.theta_breaks;
      o.theta_breaks_at_phi(phi, breaks);
      in = integrate_1d(inner, partition(o.theta_min, o.theta_max, breaks), 0.1 * o.rel_tol, o.max_depth);
    } else {
      in = integrate_1d(inner, thetas, 0.1 * o.rel_tol, o.max_depth);
    }
    inner_error = std::max(inner_error, in.error);
    return in.value;
  };
  Integral r = integrate_1d(outer, phis, o.rel_tol, o.max_depth);
  r.error += 2 * std::numbers::pi * inner_error;
  r.evaluations = evals;
  return r;
}

std::vector<double> lobe_theta_breaks(double width, double lo, double hi) {
  std::vector<double> b;
  for (int k = -6; k <= 40; ++k) {
    const double t = std::atan(width * std::ldexp(1.0, k));
    if (t > lo && t < hi) b.push_back(t);
  }
  const double half_pi = std::numbers::pi / 2;
  if (half_pi > lo && half_pi < hi) b.push_back(half_pi);
  return b;
}

double plane_crossing_theta(const Vec3<double>& w, double phi) {
  // sinθ (wx cosφ + wy sinφ) + cosθ wz = 0  ⇔  θ = atan2(−wz, wx cosφ + wy sinφ) taken in [0, π].
  const double c = w.x * std::cos(phi) + w.y * std::sin(phi);
  double t = std::atan2(-w.z, c);
  if (t < 0) t += std::numbers::pi;
  return t;
}

std::vector<double> anisotropy_phi_breaks(double alpha_x, double alpha_y) {
  std::vector<double> b;
  const double pi = std::numbers::pi;
  for (int k = -12; k <= 12; ++k) {
    const double p = std::atan(alpha_y / alpha_x * std::ldexp(1.0, k));
    for (double q : {p, pi - p, pi + p, 2 * pi - p}) b.push_back(q);
  }
  for (double q : {0.5 * pi, pi, 1.5 * pi}) b.push_back(q);
  return b;
}

}  // namespace glintlab::verify

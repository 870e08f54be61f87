// Nested adaptive Gauss–Kronrod cubature on the sphere; see sphere_cubature.h.
#include "verify/stats/sphere_cubature.h"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <numbers>
#include <span>
#include <utility>

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

// One 15-point Kronrod estimate on [a, b] with the embedded 7-point Gauss rule as error estimate:
// the integrand at the rule's 15 abscissae (0 and ± the 7 positive ones Boost lists;
// kronrod_abscissae, in the order the rule sums them), combined by kronrod_combine.
constexpr std::size_t kKronrodPoints = 15;

void kronrod_abscissae(double a, double b, double* out) {
  static const auto& x = Rule::abscissa();
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  std::size_t k = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    out[k++] = c + h * x[i];
    if (i != 0) out[k++] = c - h * x[i];
  }
}

Piece kronrod_combine(const double* f, double a, double b) {
  static const auto& x = Rule::abscissa();
  static const auto& wk = Rule::weights();
  static const auto& wg = boost::math::quadrature::gauss<double, 7>::weights();
  const double h = 0.5 * (b - a);
  double k = 0, gs = 0;
  std::size_t next = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double fp = f[next++];
    const double fm = i == 0 ? fp : f[next++];
    const double sum = i == 0 ? fp : fp + fm;
    k += wk[i] * sum;
    if (i % 2 == 0) gs += wg[i / 2] * sum;  // Gauss nodes are the even Kronrod abscissae
  }
  return {a, b, k * h, std::abs((k - gs) * h)};
}

template <class F>
Piece kronrod(F& g, double a, double b) {
  double x[kKronrodPoints], v[kKronrodPoints];
  kronrod_abscissae(a, b, x);
  for (std::size_t i = 0; i < kKronrodPoints; ++i) v[i] = g(x[i]);
  return kronrod_combine(v, a, b);
}

// Globally adaptive Gauss–Kronrod over the given partition: bisect the piece with the largest
// error until the total error is below max(rel_tol·|I|, abs_tol) or the piece budget is spent.
// A step machine, so that many integrations can run in lockstep with their integrand evaluated
// for all of them at once (integrate_sphere_rows): wanted() is the pieces whose rule the next
// step needs, feed() takes them, in that order.
class Adaptive1d {
 public:
  Adaptive1d(const std::vector<double>& nodes, double rel_tol, unsigned depth)
      : rel_tol_(rel_tol), budget_(nodes.size() + (std::size_t(1) << std::min(depth, 14u))) {
    for (std::size_t i = 0; i + 1 < nodes.size(); ++i) wanted_.push_back({nodes[i], nodes[i + 1]});
    if (wanted_.empty()) finish();
  }
  bool done() const { return done_; }
  const std::vector<std::pair<double, double>>& wanted() const { return wanted_; }
  Integral result() const { return result_; }

  void feed(std::span<const Piece> pieces) {
    if (initial_) {
      initial_ = false;
      heap_.assign(pieces.begin(), pieces.end());
      std::make_heap(heap_.begin(), heap_.end());
      running_ = totals();
    } else {
      const Piece &l = pieces[0], &rr = pieces[1];
      running_.value += l.value + rr.value - worst_.value;
      running_.error += l.error + rr.error - worst_.error;
      heap_.push_back(l);
      std::push_heap(heap_.begin(), heap_.end());
      heap_.push_back(rr);
      std::push_heap(heap_.begin(), heap_.end());
    }
    wanted_.clear();
    if (!(heap_.size() < budget_ &&
          running_.error > std::max(rel_tol_ * std::abs(running_.value), 1e-300)))
      return finish();
    std::pop_heap(heap_.begin(), heap_.end());
    worst_ = heap_.back();
    heap_.pop_back();
    const double mid = 0.5 * (worst_.a + worst_.b);
    if (!(mid > worst_.a && mid < worst_.b)) {  // cannot split further: keep it and stop
      heap_.push_back(worst_);
      std::push_heap(heap_.begin(), heap_.end());
      return finish();
    }
    wanted_ = {{worst_.a, mid}, {mid, worst_.b}};
  }

 private:
  Integral totals() const {
    Integral r;
    for (const Piece& p : heap_) r.value += p.value, r.error += p.error;
    return r;
  }
  void finish() {
    result_ = totals();  // re-sum to avoid drift from the running updates
    wanted_.clear();
    done_ = true;
  }

  double rel_tol_;
  std::size_t budget_;
  std::vector<Piece> heap_;
  std::vector<std::pair<double, double>> wanted_;
  Piece worst_{};
  Integral running_, result_;
  bool initial_ = true, done_ = false;
};

// One integration, its integrand called one point at a time.
template <class F>
Integral integrate_1d(F&& g, const std::vector<double>& nodes, double rel_tol, unsigned depth) {
  Adaptive1d a(nodes, rel_tol, depth);
  std::vector<Piece> pieces;
  while (!a.done()) {
    pieces.clear();
    for (const auto& [lo, hi] : a.wanted()) pieces.push_back(kronrod(g, lo, hi));
    a.feed(pieces);
  }
  return a.result();
}

// The θ nodes at azimuth φ.
std::vector<double> theta_nodes(const SphereCubatureOptions& o, const std::vector<double>& thetas,
                                double phi) {
  if (!o.theta_breaks_at_phi) return thetas;
  std::vector<double> breaks = o.theta_breaks;
  o.theta_breaks_at_phi(phi, breaks);
  return partition(o.theta_min, o.theta_max, breaks);
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
    const Integral in = integrate_1d(inner, theta_nodes(o, thetas, phi), 0.1 * o.rel_tol, o.max_depth);
    inner_error = std::max(inner_error, in.error);
    return in.value;
  };
  Integral r = integrate_1d(outer, phis, o.rel_tol, o.max_depth);
  r.error += 2 * std::numbers::pi * inner_error;
  r.evaluations = evals;
  return r;
}

Integral integrate_sphere_rows(const SphereRows& f, const SphereCubatureOptions& o) {
  const std::vector<double> thetas = partition(o.theta_min, o.theta_max, o.theta_breaks);
  const std::vector<double> phis = partition(0.0, 2 * std::numbers::pi, o.phi_breaks);
  long evals = 0;
  double inner_error = 0;
  struct Inner {
    double cp, sp;
    Adaptive1d a;
  };
  Adaptive1d outer(phis, o.rel_tol, o.max_depth);
  std::vector<Inner> inners;
  std::vector<Piece> pieces;
  std::vector<Vec3<double>> w;
  std::vector<double> sin_theta, value;
  while (!outer.done()) {
    // The inner integrals at every azimuth of this step's outer rules, run in lockstep: each round
    // asks f for the points of all of their rules at once.
    inners.clear();
    for (const auto& [lo, hi] : outer.wanted()) {
      double x[kKronrodPoints];
      kronrod_abscissae(lo, hi, x);
      for (double phi : x)
        inners.push_back({std::cos(phi), std::sin(phi),
                          Adaptive1d(theta_nodes(o, thetas, phi), 0.1 * o.rel_tol, o.max_depth)});
    }
    for (;;) {
      w.clear();
      sin_theta.clear();
      for (const Inner& in : inners) {
        if (in.a.done()) continue;
        for (const auto& [lo, hi] : in.a.wanted()) {
          double x[kKronrodPoints];
          kronrod_abscissae(lo, hi, x);
          for (double theta : x) {
            const double st = std::sin(theta);
            w.push_back({st * in.cp, st * in.sp, std::cos(theta)});
            sin_theta.push_back(st);
          }
        }
      }
      if (w.empty()) break;
      evals += long(w.size());
      value.assign(w.size(), 0.0);
      f(w, value);
      std::size_t next = 0;
      for (Inner& in : inners) {
        if (in.a.done()) continue;
        pieces.clear();
        for (const auto& [lo, hi] : in.a.wanted()) {
          double v[kKronrodPoints];
          for (double& y : v) {
            y = value[next] * sin_theta[next];
            ++next;
          }
          pieces.push_back(kronrod_combine(v, lo, hi));
        }
        in.a.feed(pieces);
      }
    }
    pieces.clear();
    std::size_t next = 0;
    for (const auto& [lo, hi] : outer.wanted()) {
      double v[kKronrodPoints];
      for (double& y : v) {
        const Integral in = inners[next++].a.result();
        inner_error = std::max(inner_error, in.error);  // in the one-at-a-time order
        y = in.value;
      }
      pieces.push_back(kronrod_combine(v, lo, hi));
    }
    outer.feed(pieces);
  }
  Integral r = outer.result();
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

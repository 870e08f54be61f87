// Shared sampler checks (pdf consistency, sphere cubature, moments, weights) for the tests.
// Written as functions of the sampler / pdf (callables) so the same check runs on the real
// kernels and on deliberately broken ones (mutants).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/math/rng.h"
#include "core/math/vec.h"
#include "core/samplers/beckmann_vndf.h"
#include "core/samplers/bounded_vndf.h"
#include "core/samplers/heitz_vndf.h"
#include "core/samplers/sample.h"
#include "core/samplers/spherical_caps.h"
#include "core/samplers/walter.h"
#include "verify/stats/sphere_cubature.h"

namespace glintlab::sampler_checks {

using V2 = Vec2<double>;
using V3 = Vec3<double>;
inline constexpr double kPiD = std::numbers::pi;

// ---- The samplers under test, by name, for both float types ---------------------------------

enum class Kind {
  kWalterGgx,
  kWalterBeckmann,
  kHeitz,
  kBeckmannVndf,
  kCaps,
  kBoundedListing1,
  kBoundedExact
};
inline const std::vector<Kind> kAllKinds = {
    Kind::kWalterGgx, Kind::kWalterBeckmann,  Kind::kHeitz,       Kind::kBeckmannVndf,
    Kind::kCaps,      Kind::kBoundedListing1, Kind::kBoundedExact};

inline const char* name(Kind k) {
  switch (k) {
    case Kind::kWalterGgx:
      return "walter_ggx";
    case Kind::kWalterBeckmann:
      return "walter_beckmann";
    case Kind::kHeitz:
      return "heitz_vndf";
    case Kind::kBeckmannVndf:
      return "beckmann_vndf";
    case Kind::kCaps:
      return "spherical_caps";
    case Kind::kBoundedListing1:
      return "bounded_listing1";
    case Kind::kBoundedExact:
      return "bounded_exact";
  }
  return "?";
}
// Samplers defined for a back-facing shading normal (wi_z <= 0).
inline bool handles_backfacing(Kind k) {
  return k == Kind::kCaps || k == Kind::kBoundedListing1 || k == Kind::kBoundedExact ||
         k == Kind::kWalterGgx || k == Kind::kWalterBeckmann;
}
inline bool is_beckmann(Kind k) { return k == Kind::kWalterBeckmann || k == Kind::kBeckmannVndf; }

template <class T>
MicrofacetSample<T> draw(Kind k, T ax, T ay, Vec3<T> wi, Vec2<T> u) {
  const GGX<T> g{ax, ay};
  const Beckmann<T> b{ax, ay};
  switch (k) {
    case Kind::kWalterGgx:
      return sample_walter(g, wi, u);
    case Kind::kWalterBeckmann:
      return sample_walter(b, wi, u);
    case Kind::kHeitz:
      return sample_heitz_vndf(g, wi, u);
    case Kind::kBeckmannVndf:
      return sample_beckmann_vndf(b, wi, u);
    case Kind::kCaps:
      return sample_spherical_caps(g, wi, u);
    case Kind::kBoundedListing1:
      return sample_bounded_vndf(g, wi, u, BoundedVndfBound::kListing1);
    case Kind::kBoundedExact:
      return sample_bounded_vndf(g, wi, u, BoundedVndfBound::kExactIsotropic);
  }
  return {};
}

template <class T>
T density(Kind k, T ax, T ay, Vec3<T> wi, Vec3<T> wo) {
  const GGX<T> g{ax, ay};
  const Beckmann<T> b{ax, ay};
  switch (k) {
    case Kind::kWalterGgx:
      return pdf_walter(g, wi, wo);
    case Kind::kWalterBeckmann:
      return pdf_walter(b, wi, wo);
    case Kind::kHeitz:
      return pdf_heitz_vndf(g, wi, wo);
    case Kind::kBeckmannVndf:
      return pdf_beckmann_vndf(b, wi, wo);
    case Kind::kCaps:
      return pdf_spherical_caps(g, wi, wo);
    case Kind::kBoundedListing1:
      return pdf_bounded_vndf(g, wi, wo, BoundedVndfBound::kListing1);
    case Kind::kBoundedExact:
      return pdf_bounded_vndf(g, wi, wo, BoundedVndfBound::kExactIsotropic);
  }
  return T(0);
}

template <class T>
T weight(Kind k, T ax, T ay, Vec3<T> wi, const MicrofacetSample<T>& s) {
  return is_beckmann(k) ? sample_weight(Beckmann<T>{ax, ay}, wi, s)
                        : sample_weight(GGX<T>{ax, ay}, wi, s);
}

// ---- Configurations ---------------------------------------------------------------------------

struct Config {
  double ax, ay;
  V3 wi;
};

// (double)(float)x, kept opaque to the optimizer: GCC 12.2 at -O2/-O3 folds the round trip of two
// adjacent lanes (e.g. x and y of a Vec3) into the identity (SLP vectorizer, wrong code; measured),
// which would silently hand the float and double kernels different inputs.
inline double through_float(double x) {
  volatile float f = static_cast<float>(x);
  return static_cast<double>(f);
}
inline V3 through_float(const V3& v) {
  return {through_float(v.x), through_float(v.y), through_float(v.z)};
}

inline V3 dir(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}
inline double deg(double d) { return d * kPiD / 180; }

inline std::string describe(const Config& c) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "ax=%g ay=%g wi=(%.6g, %.6g, %.6g) theta=%.4f deg", c.ax, c.ay,
                c.wi.x, c.wi.y, c.wi.z, std::acos(std::clamp(c.wi.z, -1.0, 1.0)) * 180 / kPiD);
  return buf;
}

// α from 1e-3 to 2 (anisotropic to 1:1000), θ up to 89.99°, several azimuths; back-facing
// incidences (θ > 90°) appended when `backfacing`.
inline std::vector<Config> grid(bool backfacing) {
  const std::vector<std::pair<double, double>> alphas = {
      {1e-3, 1e-3}, {0.02, 0.02}, {0.2, 0.2},  {0.6, 0.6}, {1, 1},  {2, 2},
      {1e-3, 1},    {1, 1e-3},    {0.05, 0.5}, {2, 0.5},   {1.5, 3}};
  std::vector<double> thetas = {0, 1e-4, 10, 45, 70, 85, 89, 89.99};
  if (backfacing) thetas.insert(thetas.end(), {90, 95, 120, 170, 180});
  const std::vector<double> phis = {0, 0.7, 2.1, 4.0};
  std::vector<Config> out;
  for (auto [ax, ay] : alphas)
    for (double t : thetas)
      for (double p : phis)
        out.push_back(
            {ax, ay, t == 0 || t == 180 ? V3{0, 0, t == 0 ? 1.0 : -1.0} : dir(deg(t), p)});
  return out;
}

// Stratified-ish u grid including the ends 0 and 1 − ε of the float type.
template <class T>
std::vector<Vec2<T>> u_grid(int n) {
  std::vector<T> v;
  for (int i = 0; i < n; ++i) v.push_back(T((i + 0.5) / n));
  v.push_back(T(0));
  v.push_back(T(1) - std::numeric_limits<T>::epsilon() / 2);  // largest T below 1
  v.push_back(T(1e-7));
  v.push_back(T(0.5));
  std::vector<Vec2<T>> out;
  for (T a : v)
    for (T b : v) out.push_back({a, b});
  return out;
}

// ---- Check 1: the sample's pdf is the standalone pdf of its wo ------------------------------

// Largest |s.pdf − pdf(wo)| / pdf(wo) over configs × u (0 when both are 0; inf for NaN).
template <class T, class Draw, class Pdf>
double max_pdf_mismatch(Draw&& draw_fn, Pdf&& pdf_fn, const std::vector<Config>& configs,
                        const std::vector<Vec2<T>>& us, std::string* worst = nullptr) {
  double err = 0;
  for (const Config& c : configs)
    for (const Vec2<T>& u : us) {
      const MicrofacetSample<T> s = draw_fn(c, u);
      const double p = double(pdf_fn(c, s.wo));
      const double sp = double(s.pdf);
      double e = (sp == 0 && p == 0) ? 0 : std::abs(sp - p) / std::max(std::abs(p), 1e-300);
      if (std::isnan(e)) e = std::numeric_limits<double>::infinity();
      if (e > err) {
        err = e;
        if (worst)
          *worst = describe(c) + " u=(" + std::to_string(double(u.x)) + "," +
                   std::to_string(double(u.y)) + ")";
      }
    }
  return err;
}

// ---- Check 2: ∫ pdf(wo) dwo over the sphere by cubature --------------------------------------

// Geometric breakpoints at distances w·4^j (j ≥ 0) on both sides of `centre`, inside (lo, hi).
inline void add_geometric(std::vector<double>& b, double centre, double w, double lo, double hi) {
  b.push_back(centre);
  for (double d = w; d < hi - lo; d *= 4) {
    b.push_back(centre - d);
    b.push_back(centre + d);
  }
  b.erase(std::remove_if(b.begin(), b.end(), [&](double x) { return !(x > lo && x < hi); }),
          b.end());
}

// ∫ f(wo) dwo over the sphere for a reflection pdf of incidence wi on roughness (ax, ay).
// The features of such a pdf: the lobe around the mirror direction c = (−wi_x, −wi_y, wi_z); the
// point −wi, where the half vector turns over; for the GGX VNDF the circle wo_z = −wi_z through −wi
// where the density jumps to 0 (h_z = 0); for NDF sampling a 1/|wo + wi| singularity at −wi with a
// thin ray from −wi towards c (the normals near z seen edge-on); for anisotropic roughness a thin
// band {wo : wo·n = −wi·n}, n ⊥ the wide axis and z (the reflections of normals in the plane of
// the wide axis). The frame is chosen so that these are coordinate lines:
//  - singular_at_minus_wi (NDF sampling): pole −wi, φ = 0 towards z; the singularity is then
//    integrable in polar coordinates, and the ray and c lie on the meridian φ = 0;
//  - otherwise pole z (isotropic; c and the circle are parallels) or n (anisotropic; the band is a
//    parallel).
// Geometric breakpoints in θ and φ are added around the images of c and −wi at the scale of the
// narrowest lobe width.
//
// split_at_support: instead of verify::integrate_sphere, a nested Gauss–Kronrod whose inner (θ)
// integral for each φ is also split where f's support begins or ends along that line (found by a
// scan and bisection). Needed for densities that jump to 0 along curves that are not coordinate
// lines (the bounded sampler's cap edge χ⁺(k î_z + ô_z) = 0, the GGX VNDF's h_z = 0 in an
// anisotropic frame): near the points where such a curve is tangent to a θ line, the jump encloses
// slivers thinner than the Kronrod node spacing, which a plain adaptive rule misses without
// noticing (measured: |∫ − 1| up to 9e-5 with an error estimate of 1e-9).
inline verify::Integral integrate_wo_nested(const std::function<double(const V3&)>& f,
                                            const verify::SphereCubatureOptions& o);

inline verify::Integral integrate_wo(const std::function<double(const V3&)>& f, const V3& wi,
                                     double ax, double ay, bool singular_at_minus_wi,
                                     double rel_tol = 1e-9, bool split_at_support = false) {
  const double amin = std::min({ax, ay, 1.0});
  const bool aniso = std::max(ax, ay) > 3 * std::min(ax, ay);
  V3 pole{0, 0, 1}, ref{1, 0, 0};
  if (singular_at_minus_wi) {
    pole = -wi;
    const V3 zt = V3{0, 0, 1} - pole.z * pole;  // z projected on the tangent plane at −wi
    ref = length(zt) > 1e-9 ? normalize(zt) : V3{1, 0, 0};
  } else if (aniso) {
    pole = ax > ay ? V3{0, 1, 0} : V3{1, 0, 0};
    ref = {0, 0, 1};
  }
  const V3 yaxis = cross(pole, ref);
  auto to_world = [&](const V3& w) { return w.x * ref + w.y * yaxis + w.z * pole; };
  auto polar = [&](const V3& w, double& t, double& p) {
    t = std::acos(std::clamp(dot(w, pole), -1.0, 1.0));
    p = std::atan2(dot(w, yaxis), dot(w, ref));
    if (p < 0) p += 2 * kPiD;
  };
  const double w0 = 0.5 * amin * std::max(std::abs(wi.z), 1e-2);
  verify::SphereCubatureOptions o;
  o.rel_tol = rel_tol;
  o.max_depth = 12;
  if (!singular_at_minus_wi) o.theta_breaks.push_back(kPiD / 2);
  auto add_phi = [&](double p, double wp) {
    std::vector<double> pb;
    for (double shift : {-2 * kPiD, 0.0, 2 * kPiD}) add_geometric(pb, p + shift, wp, 0, 2 * kPiD);
    o.phi_breaks.insert(o.phi_breaks.end(), pb.begin(), pb.end());
  };
  for (const V3& feature : {V3{-wi.x, -wi.y, wi.z}, V3{-wi.x, -wi.y, -wi.z}}) {
    double t, p;
    polar(feature, t, p);
    add_geometric(o.theta_breaks, t, w0, 0, kPiD);
    const double st = std::sin(t);
    if (st > 1e-9) add_phi(p, std::min(w0 / st, 1.0));
  }
  if (singular_at_minus_wi) {  // the ray from the pole along φ = 0, of angular width ~α
    add_phi(0, w0);
    add_phi(kPiD, w0);
  }
  const auto g = [&](const V3& w) { return f(to_world(w)); };
  return split_at_support ? integrate_wo_nested(g, o) : verify::integrate_sphere(g, o);
}

// Globally adaptive 15-point Gauss–Kronrod over the partition `nodes` (bisect the piece with the
// largest error until the summed error is below rel_tol·|I| or max_pieces is reached).
template <class G>
verify::Integral adaptive_gk(G&& g, const std::vector<double>& nodes, double rel_tol,
                             std::size_t max_pieces) {
  using Rule = boost::math::quadrature::gauss_kronrod<double, 15>;
  struct Piece {
    double a, b, value, error;
    bool operator<(const Piece& o) const { return error < o.error; }
  };
  const auto rule = [&](double a, double b) {
    const auto& x = Rule::abscissa();
    const auto& wk = Rule::weights();
    const auto& wg = boost::math::quadrature::gauss<double, 7>::weights();
    const double c = 0.5 * (a + b), h = 0.5 * (b - a);
    double k = 0, gs = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double sum = i == 0 ? g(c) : g(c + h * x[i]) + g(c - h * x[i]);
      k += wk[i] * sum;
      if (i % 2 == 0) gs += wg[i / 2] * sum;
    }
    return Piece{a, b, k * h, std::abs((k - gs) * h)};
  };
  std::vector<Piece> heap;
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) heap.push_back(rule(nodes[i], nodes[i + 1]));
  std::make_heap(heap.begin(), heap.end());
  const auto total = [&] {
    verify::Integral r;
    for (const Piece& p : heap) r.value += p.value, r.error += p.error;
    return r;
  };
  verify::Integral r = total();
  while (heap.size() < max_pieces && r.error > rel_tol * std::abs(r.value)) {
    std::pop_heap(heap.begin(), heap.end());
    const Piece w = heap.back();
    const double mid = 0.5 * (w.a + w.b);
    if (!(mid > w.a && mid < w.b)) break;
    heap.pop_back();
    const Piece l = rule(w.a, mid), rr = rule(mid, w.b);
    r.value += l.value + rr.value - w.value;
    r.error += l.error + rr.error - w.error;
    heap.push_back(l);
    std::push_heap(heap.begin(), heap.end());
    heap.push_back(rr);
    std::push_heap(heap.begin(), heap.end());
  }
  return total();
}

inline verify::Integral integrate_wo_nested(const std::function<double(const V3&)>& f,
                                            const verify::SphereCubatureOptions& o) {
  constexpr int kScan = 128;
  auto sorted = [](std::vector<double> b, double lo, double hi) {
    b.push_back(lo);
    b.push_back(hi);
    b.erase(std::remove_if(b.begin(), b.end(), [&](double x) { return !(x >= lo && x <= hi); }),
            b.end());
    std::sort(b.begin(), b.end());
    b.erase(std::unique(b.begin(), b.end()), b.end());
    return b;
  };
  long evaluations = 0;
  double inner_error = 0;
  const auto outer = [&](double phi) {
    const double cp = std::cos(phi), sp = std::sin(phi);
    const auto inner = [&](double t) {
      ++evaluations;
      const double st = std::sin(t);
      return f(V3{st * cp, st * sp, std::cos(t)}) * st;
    };
    std::vector<double> b = o.theta_breaks;
    // Support changes along the line: scan, then bisect each change to ~1e-14.
    const double lo = o.theta_min, hi = o.theta_max;
    double t_prev = lo + 1e-13;
    bool in_prev = inner(t_prev) > 0;
    for (int i = 1; i <= kScan; ++i) {
      const double t = i == kScan ? hi - 1e-13 : lo + (hi - lo) * i / kScan;
      const bool in = inner(t) > 0;
      if (in != in_prev) {
        double a = t_prev, c = t;
        for (int j = 0; j < 46; ++j) {
          const double m = 0.5 * (a + c);
          ((inner(m) > 0) == in_prev ? a : c) = m;
        }
        b.push_back(0.5 * (a + c));
      }
      t_prev = t;
      in_prev = in;
    }
    const verify::Integral line = adaptive_gk(inner, sorted(b, lo, hi), o.rel_tol, 4096);
    inner_error = std::max(inner_error, line.error);
    return line.value;
  };
  verify::Integral r = adaptive_gk(outer, sorted(o.phi_breaks, 0, 2 * kPiD), o.rel_tol, 4096);
  r.error += 2 * kPiD * inner_error;
  r.evaluations = evaluations;
  return r;
}

inline bool singular_at_minus_wi(Kind k) {
  return k == Kind::kWalterGgx || k == Kind::kWalterBeckmann;
}

// Whether k's density jumps to 0 along a curve that integrate_wo's frame does not align: the
// bounded cap edge always, the GGX VNDF's h_z = 0 circle in the anisotropic (band) frame.
inline bool needs_support_split(Kind k, double ax, double ay) {
  const bool aniso = std::max(ax, ay) > 3 * std::min(ax, ay);
  return k == Kind::kBoundedListing1 || k == Kind::kBoundedExact ||
         (aniso && (k == Kind::kHeitz || k == Kind::kCaps));
}

// ∫ pdf(wo) dwo over the sphere for sampler k at configuration c.
template <class Pdf>
verify::Integral integrate_pdf(Kind k, const Config& c, Pdf&& pdf, double rel_tol = 1e-9) {
  return integrate_wo([&](const V3& wo) { return pdf(wo); }, c.wi, c.ax, c.ay,
                      singular_at_minus_wi(k), rel_tol, needs_support_split(k, c.ax, c.ay));
}

// ---- Check 3: Monte Carlo moment against cubature ---------------------------------------------

// A smooth test function on the sphere, sensitive to the lobe's position and spread.
// Odd and even in every axis (the z term separates the upper and lower hemispheres), and positive
// (>= 0.5) so the cubature's relative tolerance is meaningful.
inline double moment_g(const V3& w) {
  return 4 + w.x + 0.7 * w.y + 0.8 * w.z + 1.3 * w.z * w.z + 0.4 * w.x * w.z - 0.6 * w.y * w.y;
}

struct MomentResult {
  double mc_mean, mc_se, exact, z;
};

// z-score of the Monte Carlo mean of g(wo) over n draws (counter RNG keyed by `seed`) against the
// cubature ∫ g(wo) pdf(wo) dwo. Rejected draws count: they are part of the sampled distribution.
template <class Draw, class Pdf>
MomentResult moment_check(Draw&& draw_fn, Pdf&& pdf_fn, Kind k, const Config& c, std::uint64_t seed,
                          int n) {
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const V2 u{counter_uniform<double>(seed, std::uint64_t(i), 0),
               counter_uniform<double>(seed, std::uint64_t(i), 1)};
    const double g = moment_g(draw_fn(c, u).wo);
    sum += g;
    sum2 += g * g;
  }
  const double mean = sum / n;
  const double var = std::max(sum2 / n - mean * mean, 0.0) * n / (n - 1.0);
  const double se = std::sqrt(var / n);
  const double exact = integrate_pdf(
                           k, c, [&](const V3& w) { return moment_g(w) * pdf_fn(c, w); }, 1e-8)
                           .value;
  return {mean, se, exact, (mean - exact) / std::max(se, 1e-300)};
}

// ---- Check 4: weights finite and non-negative -------------------------------------------------

// Number of (config, u) pairs whose sample has a non-finite or negative weight or pdf, a
// non-finite wo, or a non-zero weight on a rejected sample.
template <class T, class Draw, class Weight>
int count_bad_weights(Draw&& draw_fn, Weight&& weight_fn, const std::vector<Config>& configs,
                      const std::vector<Vec2<T>>& us, std::string* first = nullptr) {
  int bad = 0;
  for (const Config& c : configs)
    for (const Vec2<T>& u : us) {
      const MicrofacetSample<T> s = draw_fn(c, u);
      const T w = weight_fn(c, s);
      const bool ok = std::isfinite(w) && w >= 0 && std::isfinite(s.pdf) && s.pdf >= 0 &&
                      std::isfinite(s.wo.x) && std::isfinite(s.wo.y) && std::isfinite(s.wo.z) &&
                      (!s.rejected || w == 0);
      if (!ok) {
        if (bad == 0 && first)
          *first = describe(c) + " u=(" + std::to_string(double(u.x)) + "," +
                   std::to_string(double(u.y)) + ") w=" + std::to_string(double(w)) +
                   " pdf=" + std::to_string(double(s.pdf));
        ++bad;
      }
    }
  return bad;
}

// ---- Check 5: rejection rate ------------------------------------------------------------------

template <class Draw>
double rejection_rate(Draw&& draw_fn, const Config& c, std::uint64_t seed, int n) {
  int rej = 0;
  for (int i = 0; i < n; ++i) {
    const V2 u{counter_uniform<double>(seed, std::uint64_t(i), 0),
               counter_uniform<double>(seed, std::uint64_t(i), 1)};
    rej += draw_fn(c, u).rejected ? 1 : 0;
  }
  return double(rej) / n;
}

inline std::uint64_t test_seed() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return hash_string((std::string(info->test_suite_name()) + "." + info->name()).c_str());
}

}  // namespace glintlab::sampler_checks

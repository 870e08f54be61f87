// Tests of the Monte Carlo area-light reference: with a smooth GGX BRDF (Walter et al. 2007 Eq. 20,
// Heitz 2018 VNDF sampling) under a disk and a rectangle light, MIS (balance and power), light-only
// and BSDF-only estimates each agree with two cubature references (over the light's area, and over
// the sphere with the light's boundary as breakpoints) within their standard error; a wrong pdf in
// the MIS weights is detected (negative control); results depend only on (seed, sample count).
#include "core/render/area_light_reference.h"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <iostream>
#include <string>

#include "../lights/light_checks.h"
#include "core/lights/disk_light.h"
#include "core/lights/rectangle_light.h"
#include "core/ndf/ggx.h"
#include "core/samplers/heitz_vndf.h"
#include "verify/stats/mean_tests.h"

namespace glintlab {
namespace {

using namespace light_checks;

// The smooth GGX BRDF (F = 1) as a ReferenceBsdf: f by Walter et al. 2007 Eq. 20, sampling by
// Heitz 2018 (its "wi" is our viewing direction wo, its reflected "wo" our light direction wi).
template <class T>
struct SmoothGgxBsdf {
  GGX<T> ggx;
  GLINTLAB_FN T f(Vec3<T> wo, Vec3<T> wi) const { return microfacet_brdf(ggx, wo, wi, T(1)); }
  GLINTLAB_FN BsdfSample<T> sample(Vec3<T> wo, Vec2<T> u) const {
    const MicrofacetSample<T> s = sample_heitz_vndf(ggx, wo, u);
    return {s.wo, s.pdf, s.rejected};
  }
  GLINTLAB_FN T pdf(Vec3<T> wo, Vec3<T> wi) const { return pdf_heitz_vndf(ggx, wo, wi); }
};
static_assert(ReferenceBsdf<SmoothGgxBsdf<double>, double>);
static_assert(ReferenceLight<DiskLight<double>, double>);

// A light whose standalone pdf (the one the BSDF technique's MIS weight uses) is off by a factor:
// the negative control. Its sampler and radiance are the real ones.
template <class Light>
struct WrongPdfLight {
  Light light;
  double factor;
  LightSample<double> sample(V3 p, V2 u) const { return light.sample(p, u); }
  double pdf(V3 p, V3 w) const { return factor * light.pdf(p, w); }
  V3 radiance(V3 p, V3 w) const { return light.radiance(p, w); }
};

const ShadingPoint<double> kShading{{0, 0, 0}, basis_from_z(V3{0, 0, 1})};
const V3 kWo = normalize(V3{0.5, 0.1, 0.866});  // 30° from the normal
const V3 kL{2.0, 1.0, 0.5};
const V3 kMirror{-kWo.x, -kWo.y, kWo.z};

DiskLight<double> disk() {
  const V3 c = 2.0 * kMirror + V3{0.3, 0.2, 0.0};
  return make_disk_light(c, -c, 0.5, kL);
}
RectangleLight<double> rectangle() {
  const V3 c = 1.5 * kMirror + V3{-0.2, 0.3, 0.0};
  const OrthonormalBasis<double> b = basis_from_z(normalize(-c));
  return make_rectangle_light(c - 0.4 * b.x - 0.25 * b.y, 0.8 * b.x, 0.5 * b.y, kL);
}

// ∫ f L cos θi cos θl / d² over the light's area (channel y), nested Gauss–Kronrod.
template <class Bsdf>
double area_integrand(const Bsdf& bsdf, V3 q, V3 n) {
  const V3 v = q - kShading.position;
  const double d2 = dot(v, v);
  const V3 wi = (1 / std::sqrt(d2)) * v;
  const double cl = -dot(wi, n);
  if (cl <= 0 || wi.z <= 0) return 0;
  return bsdf.f(kWo, wi) * kL.y * wi.z * cl / d2;
}

using GK = boost::math::quadrature::gauss_kronrod<double, 15>;

template <class Bsdf>
double disk_area_cubature(const DiskLight<double>& d, const Bsdf& bsdf) {
  return GK::integrate(
      [&](double r) {
        return GK::integrate(
            [&](double phi) {
              const V3 q =
                  d.center + (r * std::cos(phi)) * d.frame.x + (r * std::sin(phi)) * d.frame.y;
              return r * area_integrand(bsdf, q, d.frame.z);
            },
            0, 2 * kPiD, 12, 1e-12);
      },
      0, d.radius, 12, 1e-12);
}

template <class Bsdf>
double rectangle_area_cubature(const RectangleLight<double>& r, const Bsdf& bsdf) {
  return r.area() *
         GK::integrate(
             [&](double s) {
               return GK::integrate(
                   [&](double t) {
                     return area_integrand(bsdf, r.corner + s * r.edge_u + t * r.edge_v, r.normal);
                   },
                   0, 1, 12, 1e-12);
             },
             0, 1, 12, 1e-12);
}

template <class Light, class Bsdf>
double sphere_cubature(const Light& light, const Bsdf& bsdf, const PlanarBoundary& b,
                       std::vector<double> phi_breaks = {}) {
  return integrate_about(
             b,
             [&](const V3& w) {
               return w.z > 0 ? bsdf.f(kWo, w) * light.radiance(kShading.position, w).y * w.z : 0.0;
             },
             std::move(phi_breaks), 1e-10)
      .value;
}

// z test of the estimate's channel y against the reference; returns the two-sided p-value.
double agreement(const ReferenceEstimate& e, double reference, const std::string& what) {
  verify::MeanAccumulator a;
  a.n = e.samples;
  a.mean = e.mean.y;
  a.m2 = e.variance.y * double(e.samples - 1);
  const auto t = verify::z_test(a, reference);
  std::cout << what << ": " << e.mean.y << " ± " << e.std_error.y << " (ref " << reference
            << ", z = " << t.statistic << ", p = " << t.p_value << ")\n";
  return t.p_value;
}

struct Scene {
  std::string name;
  double reference;
  std::function<ReferenceEstimate(const ReferenceOptions&)> run;
  std::function<ReferenceEstimate(const ReferenceOptions&, double)> run_wrong;
};

std::vector<Scene> scenes() {
  static const SmoothGgxBsdf<double> iso{{0.3, 0.3}};
  static const SmoothGgxBsdf<double> aniso{{0.15, 0.4}};
  static const DiskLight<double> dl = disk();
  static const RectangleLight<double> rl = rectangle();
  const double disk_ref = disk_area_cubature(dl, iso);
  const double rect_ref = rectangle_area_cubature(rl, aniso);
  // The second, independent reference: cubature over the sphere.
  const auto db =
      planar_boundary(kShading.position, dl.center, dl.frame.z, [](V3, V3) { return dl.radius; });
  EXPECT_NEAR(sphere_cubature(dl, iso, db) / disk_ref, 1.0, 1e-7);
  const std::vector<V3> rc{rl.corner, rl.corner + rl.edge_u, rl.corner + rl.edge_u + rl.edge_v,
                           rl.corner + rl.edge_v};
  const auto rb = planar_boundary(kShading.position, rl.corner + 0.5 * (rl.edge_u + rl.edge_v),
                                  rl.normal, polygon_exit(rc, rl.normal));
  EXPECT_NEAR(sphere_cubature(rl, aniso, rb, azimuths(rb, rc)) / rect_ref, 1.0, 1e-7);
  return {
      {"disk, GGX α = 0.3", disk_ref,
       [](const ReferenceOptions& o) { return area_light_reference(dl, iso, kShading, kWo, o); },
       [](const ReferenceOptions& o, double k) {
         return area_light_reference(WrongPdfLight<DiskLight<double>>{dl, k}, iso, kShading, kWo,
                                     o);
       }},
      {"rectangle, GGX α = (0.15, 0.4)", rect_ref,
       [](const ReferenceOptions& o) { return area_light_reference(rl, aniso, kShading, kWo, o); },
       [](const ReferenceOptions& o, double k) {
         return area_light_reference(WrongPdfLight<RectangleLight<double>>{rl, k}, aniso, kShading,
                                     kWo, o);
       }},
  };
}

constexpr std::uint64_t kSamples = 1 << 17;

TEST(AreaLightReference, EveryStrategyAgreesWithCubature) {
  struct S {
    const char* name;
    ReferenceStrategy strategy;
    MisHeuristic heuristic;
  };
  const S strategies[] = {{"MIS power", ReferenceStrategy::kMis, MisHeuristic::kPower},
                          {"MIS balance", ReferenceStrategy::kMis, MisHeuristic::kBalance},
                          {"light only", ReferenceStrategy::kLightOnly, MisHeuristic::kPower},
                          {"BSDF only", ReferenceStrategy::kBsdfOnly, MisHeuristic::kPower}};
  for (const Scene& s : scenes()) {
    ASSERT_GT(s.reference, 0.0);
    for (const S& st : strategies) {
      const std::string what = s.name + ", " + st.name;
      ReferenceOptions o;
      o.samples = kSamples;
      o.seed = verify::check_seed("render.area_light_reference." + what, 0);
      o.strategy = st.strategy;
      o.heuristic = st.heuristic;
      const ReferenceEstimate e = s.run(o);
      EXPECT_GT(agreement(e, s.reference, what), level()) << what;
      EXPECT_LT(e.std_error.y, 0.05 * s.reference) << what;  // the test has power
    }
  }
}

// Negative control: the BSDF technique's MIS weight uses a light pdf off by 2× (and by ½), so the
// weights no longer sum to 1 and the estimate is biased; the z test must reject it.
TEST(AreaLightReference, WrongPdfInTheMisWeightsIsDetected) {
  for (const Scene& s : scenes()) {
    for (double k : {2.0, 0.5}) {
      for (MisHeuristic h : {MisHeuristic::kPower, MisHeuristic::kBalance}) {
        const std::string what = s.name + (h == MisHeuristic::kPower ? ", power" : ", balance") +
                                 ", light pdf ×" + std::to_string(k) + " in the weights";
        ReferenceOptions o;
        o.samples = kSamples;
        o.seed = verify::check_seed("render.area_light_reference.control." + what, 0);
        o.heuristic = h;
        EXPECT_LT(agreement(s.run_wrong(o, k), s.reference, what), level()) << what;
      }
    }
  }
}

TEST(AreaLightReference, DependsOnlyOnSeedAndCount) {
  const auto s = scenes()[0];
  ReferenceOptions o;
  o.samples = 4096;
  o.seed = verify::check_seed("render.area_light_reference.determinism", 0);
  const ReferenceEstimate a = s.run(o), b = s.run(o);
  EXPECT_EQ(a.mean.x, b.mean.x);
  EXPECT_EQ(a.mean.y, b.mean.y);
  EXPECT_EQ(a.variance.z, b.variance.z);
  o.seed += 1;
  EXPECT_NE(s.run(o).mean.y, a.mean.y);
  // The per-sample kernel in float gives the double value to float precision.
  const DiskLight<double> dd = disk();
  const DiskLight<float> df{
      cast<float>(dd.center),
      {cast<float>(dd.frame.x), cast<float>(dd.frame.y), cast<float>(dd.frame.z)},
      float(dd.radius),
      cast<float>(dd.emitted)};
  const SmoothGgxBsdf<double> bd{{0.3, 0.3}};
  const SmoothGgxBsdf<float> bf{{0.3f, 0.3f}};
  const ShadingPoint<float> spf{{0, 0, 0}, basis_from_z(Vec3<float>{0, 0, 1})};
  for (std::uint64_t i = 0; i < 200; ++i) {
    const Vec2<float> ul{counter_uniform<float>(1, i, 0), counter_uniform<float>(1, i, 1)};
    const Vec2<float> ub{counter_uniform<float>(1, i, 2), counter_uniform<float>(1, i, 3)};
    const auto xd = reference_sample(dd, bd, kShading, kWo, V2{ul.x, ul.y}, V2{ub.x, ub.y},
                                     ReferenceStrategy::kMis, MisHeuristic::kPower);
    const auto xf = reference_sample(df, bf, spf, cast<float>(kWo), ul, ub, ReferenceStrategy::kMis,
                                     MisHeuristic::kPower);
    EXPECT_NEAR(double(xf.y), xd.y, 1e-4 * (1 + std::abs(xd.y))) << i;
  }
}

}  // namespace
}  // namespace glintlab

// Tests of the point (with radius), directional, disk, rectangle and polygon lights: parameter
// errors, solid angles against cubature and closed forms, pdf normalisation by cubature, sample
// records against the standalone pdf/radiance, and chi-square fits of every sampler with negative
// controls (a plausible wrong pdf of the same support, a distorted sampler) that must be rejected.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "core/lights/directional_light.h"
#include "core/lights/disk_light.h"
#include "core/lights/point_light.h"
#include "core/lights/polygon_light_check.h"
#include "core/lights/rectangle_light.h"
#include "light_checks.h"

namespace glintlab {
namespace {

using namespace light_checks;

const V3 kP{0, 0, 0};  // the shading point of every configuration
const V3 kL{1.0, 2.0, 3.0};

PointLight<double> point_light() { return make_point_light({0.3, -0.2, 2.0}, 0.25, kL); }
DirectionalLight<double> directional(double deg) {
  return make_directional_light({0.3, 0.1, 1.0}, deg * kPiD / 180, kL);
}
DiskLight<double> disk() { return make_disk_light({0.5, 0.2, 1.5}, {-0.3, 0.0, -1.0}, 0.6, kL); }
RectangleLight<double> rectangle(AreaSampling s) {
  return make_rectangle_light({-0.4, -0.3, 1.2}, {0, 0.7, 0}, {1.0, 0, 0.2}, kL, s);
}
std::vector<V3> pentagon() {
  const V3 c{0.2, 0.4, 1.3};
  const OrthonormalBasis<double> b = basis_from_z(normalize(V3{-0.2, -0.3, -1.0}));
  std::vector<V3> v;
  for (double a : {0.0, 70.0, 150.0, 220.0, 290.0}) {
    const double r = a * kPiD / 180;
    v.push_back(c + (0.5 * std::cos(r)) * b.x + (0.5 * std::sin(r)) * b.y);
  }
  return v;
}
PolygonLight<double> polygon(AreaSampling s) { return make_polygon_light(pentagon(), kL, s); }

std::vector<V3> rectangle_corners() {
  const auto r = rectangle(AreaSampling::kArea);
  return {r.corner, r.corner + r.edge_u, r.corner + r.edge_u + r.edge_v, r.corner + r.edge_v};
}

PlanarBoundary disk_boundary(const DiskLight<double>& d) {
  return planar_boundary(kP, d.center, d.frame.z,
                         [r = d.radius](V3, V3) { return r; });  // c is the centre
}
PlanarBoundary polygon_boundary(const std::vector<V3>& v, V3 n) {
  V3 c{0, 0, 0};
  for (const V3& q : v) c = c + q;
  c = (1.0 / double(v.size())) * c;
  return planar_boundary(kP, c, n, polygon_exit(v, n));
}

// ---- Parameter errors ---------------------------------------------------------------------------

template <class F>
void expect_error(F&& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one naming " << needle;
  } catch (const ParameterError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(needle), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    EXPECT_NE(m.find("valid"), std::string::npos) << m;
  }
}

TEST(Lights, ParameterErrorsNameTheParameterAndRange) {
  expect_error([] { make_point_light({0, 0, 1}, 0, kL); }, "radius");
  expect_error([] { make_point_light({0, 0, 1}, -1, kL); }, "radius");
  expect_error([] { make_point_light({0, 0, 1}, 1, {1, -1, 0}); }, "radiance");
  expect_error([] { make_directional_light({0, 0, 1}, 0, kL); }, "half_angle");
  expect_error([] { make_directional_light({0, 0, 1}, kPiD / 2, kL); }, "half_angle");
  expect_error([] { make_directional_light({0, 0, 1}, -0.1, kL); }, "half_angle");
  expect_error([] { make_directional_light({0, 0, 0}, 0.1, kL); }, "direction");
  expect_error([] { make_disk_light({0, 0, 1}, {0, 0, -1}, 0, kL); }, "radius");
  expect_error([] { make_disk_light({0, 0, 1}, {0, 0, 0}, 1, kL); }, "normal");
  expect_error([] { make_rectangle_light({0, 0, 1}, {1, 0, 0}, {0.1, 1, 0}, kL); }, "edge_u");
  expect_error([] { make_rectangle_light({0, 0, 1}, {0, 0, 0}, {0, 1, 0}, kL); }, "edge_u");
  const std::vector<V3> square{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  EXPECT_NO_THROW(make_polygon_light(square, kL));
  const std::vector<V3> dart{{0, 0, 1}, {1, 0, 1}, {0.3, 0.3, 1}, {0, 1, 1}};
  expect_error([&] { make_polygon_light(dart, kL); }, "not convex at vertex 2");
  const std::vector<V3> bent{{0, 0, 1}, {1, 0, 1}, {1, 1, 1.1}, {0, 1, 1}};
  expect_error([&] { make_polygon_light(bent, kL); }, "off the polygon's plane");
  const std::vector<V3> line{{0, 0, 1}, {1, 0, 1}, {2, 0, 1}};
  expect_error([&] { make_polygon_light(line, kL); }, "area");
  const std::vector<V3> repeated{{0, 0, 1}, {1, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  expect_error([&] { make_polygon_light(repeated, kL); }, "coincide");
  const std::vector<V3> collinear{{0, 0, 1}, {0.5, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  expect_error([&] { make_polygon_light(collinear, kL); }, "degenerate");
  const std::vector<V3> two{{0, 0, 1}, {1, 0, 1}};
  expect_error([&] { make_polygon_light(two, kL); }, "vertex count");
  std::vector<V3> star;  // a pentagram: every turn the same way, but it winds twice
  for (int k = 0; k < 5; ++k)
    star.push_back({std::cos(4 * kPiD * k / 5), std::sin(4 * kPiD * k / 5), 1.0});
  expect_error([&] { make_polygon_light(star, kL); }, "turning");
}

// ---- Solid angles -------------------------------------------------------------------------------

TEST(Lights, CapSolidAnglesMatchTheClosedForm) {
  // Point light: sin γ = r/d, Ω = 2π(1 − cos γ) (Kneiphof & Klein 2024 Sec. 5).
  const auto pl = point_light();
  const double d = length(pl.center - kP);
  EXPECT_NEAR(pl.solid_angle(kP), 2 * kPiD * (1 - std::sqrt(1 - 0.25 * 0.25 / (d * d))), 1e-15);
  EXPECT_EQ(pl.solid_angle(pl.center), 0.0);  // inside the ball: empty support
  // A sun-sized cap in float keeps its digits (1 − cos γ formed without cancellation).
  const auto sun = make_directional_light<float>({0, 0, 1}, 0.26 * kPiD / 180, kL);
  const double exact = 2 * kPiD * 2 * std::pow(std::sin(0.13 * kPiD / 180), 2);
  EXPECT_NEAR(sun.solid_angle({0, 0, 0}) / exact, 1.0, 1e-6);
  const auto far = make_point_light<float>({0, 0, 1000}, 1, kL);
  EXPECT_NEAR(far.solid_angle({0, 0, 0}) / (2 * kPiD * (1 - std::sqrt(1 - 1e-6))), 1.0, 1e-6);
}

TEST(Lights, PlanarSolidAnglesMatchCubature) {
  const auto dl = disk();
  const auto db = disk_boundary(dl);
  const double om_disk =
      integrate_about(db, [&](const V3& w) { return dl.pdf(kP, w) > 0 ? 1.0 : 0.0; }).value;
  EXPECT_NEAR(dl.solid_angle(kP) / om_disk, 1.0, 1e-8);
  // On the axis: 2π(1 − h/√(h² + R²)) exactly; off the axis, inside, on and outside the rim, down
  // to heights of 1e-3 R just above the rim (where k → 1 in Paxton's closed form).
  double worst = 0;
  for (double h : {1.0, 0.2, 0.05, 0.01, 0.001}) {
    const auto dz = make_disk_light({0, 0, h}, {0, 0, -1}, 1.0, kL);
    const double on = dz.solid_angle(kP);
    EXPECT_NEAR(on, 2 * kPiD * (1 - h / std::sqrt(h * h + 1)), 1e-12 * on) << h;
    for (double e : {0.5, 0.999, 1.0, 1.001, 1.5, 4.0}) {
      const auto off = make_disk_light({e, 0, h}, {0, 0, -1}, 1.0, kL);
      const auto ob = disk_boundary(off);
      const auto cub = integrate_about(
          ob, [&](const V3& w) { return off.pdf(kP, w) > 0 ? 1.0 : 0.0; }, {}, 1e-11);
      const double rel = off.solid_angle(kP) / cub.value - 1;
      worst = std::max(worst, std::abs(rel));
      EXPECT_NEAR(rel, 0.0, 1e-9 + 2 * cub.error / cub.value) << "h " << h << " e " << e;
    }
  }
  std::cout << "disk: max rel. error of the closed-form Ω against cubature " << worst << "\n";
  const auto df = make_disk_light<float>({0.999, 0, 0.001}, {0, 0, -1}, 1.0, kL);
  const auto dd = make_disk_light<double>({0.999, 0, 0.001}, {0, 0, -1}, 1.0, kL);
  EXPECT_NEAR(df.solid_angle({0, 0, 0}) / dd.solid_angle(kP), 1.0, 1e-5);
  const auto rl = rectangle(AreaSampling::kSolidAngle);
  const auto rc = rectangle_corners();
  const auto rb = polygon_boundary(rc, rl.normal);
  const double om_rect =
      integrate_about(
          rb, [&](const V3& w) { return rl.pdf(kP, w) > 0 ? 1.0 : 0.0; }, azimuths(rb, rc))
          .value;
  EXPECT_NEAR(rl.solid_angle(kP) / om_rect, 1.0, 1e-8);
  // Ureña's S equals the two-triangle Van Oosterom–Strackee sum.
  const auto rv = rl.vertices_from(kP);
  EXPECT_NEAR(rl.solid_angle(kP),
              spherical_triangle_solid_angle(rv.v[0], rv.v[1], rv.v[2]) +
                  spherical_triangle_solid_angle(rv.v[0], rv.v[2], rv.v[3]),
              1e-13);
  const auto pg = polygon(AreaSampling::kArea);
  const auto pv = pentagon();
  const auto pb = polygon_boundary(pv, pg.normal);
  const double om_poly =
      integrate_about(
          pb, [&](const V3& w) { return pg.pdf(kP, w) > 0 ? 1.0 : 0.0; }, azimuths(pb, pv))
          .value;
  EXPECT_NEAR(pg.solid_angle(kP) / om_poly, 1.0, 1e-8);
  // Behind a one-sided light: nothing.
  EXPECT_EQ(pg.solid_angle({0, 0, 5}), 0.0);
  EXPECT_EQ(rl.solid_angle({0, 0, 5}), 0.0);
  EXPECT_EQ(dl.solid_angle({0, 0, 5}), 0.0);
}

TEST(Lights, PolygonVerticesAsSeenFromAPoint) {
  const auto pg = polygon(AreaSampling::kArea);
  const auto v = pg.vertices_from(kP);
  ASSERT_EQ(v.count, 5);
  const auto pv = pentagon();
  for (int k = 0; k < 5; ++k) {
    EXPECT_NEAR(length(v.v[k]), 1.0, 1e-15);
    EXPECT_NEAR(length(cross(v.v[k], pv[k] - kP)), 0.0, 1e-12);
    // The light's winding, counter-clockwise about its normal: (v_k × v_{k+1})·n > 0.
    EXPECT_GT(dot(cross(v.v[k], v.v[(k + 1) % 5]), pg.normal), 0.0);
  }
}

// ---- pdfs: normalisation, sample records
// ---------------------------------------------------------

struct Case {
  std::string name;
  std::function<LightSample<double>(V2)> sample;
  std::function<double(const V3&)> pdf;
  std::function<V3(const V3&)> radiance;
  std::function<verify::Integral()> integral_of_pdf;
  V3 lobe;  // the chi-square frame's pole
  std::vector<double> phi_breaks;
};

verify::Integral integrate_cap(const V3& axis, double gamma,
                               const std::function<double(const V3&)>& f) {
  verify::SphereCubatureOptions o;
  o.theta_breaks = {gamma};
  o.rel_tol = 1e-10;
  const auto b = basis_from_z(axis);
  return verify::integrate_sphere([&](const V3& w) { return f(b.to_world(w)); }, o);
}

std::vector<Case> cases() {
  std::vector<Case> out;
  static const auto pl = point_light();
  static const auto d5 = directional(5.0);
  static const auto dsun = directional(0.26);
  static const auto dl = disk();
  static const auto ra = rectangle(AreaSampling::kArea);
  static const auto rs = rectangle(AreaSampling::kSolidAngle);
  static const auto pa = polygon(AreaSampling::kArea);
  static const auto ps = polygon(AreaSampling::kSolidAngle);
  const auto add = [&](std::string name, const auto& l, std::function<verify::Integral()> integ,
                       V3 lobe, std::vector<double> phi_breaks = {}) {
    out.push_back({name, [&l](V2 u) { return l.sample(kP, u); },
                   [&l](const V3& w) { return l.pdf(kP, w); },
                   [&l](const V3& w) { return l.radiance(kP, w); }, std::move(integ), lobe,
                   std::move(phi_breaks)});
  };
  const V3 pl_axis = normalize(pl.center - kP);
  const double pl_gamma = std::asin(pl.radius / length(pl.center - kP));
  add(
      "point", pl,
      [=] { return integrate_cap(pl_axis, pl_gamma, [](const V3& w) { return pl.pdf(kP, w); }); },
      pl_axis);
  add(
      "directional_5deg", d5,
      [=] {
        return integrate_cap(d5.cap.axis, 5 * kPiD / 180,
                             [](const V3& w) { return d5.pdf(kP, w); });
      },
      d5.cap.axis);
  add(
      "directional_sun", dsun,
      [=] {
        return integrate_cap(dsun.cap.axis, 0.26 * kPiD / 180,
                             [](const V3& w) { return dsun.pdf(kP, w); });
      },
      dsun.cap.axis);
  const auto db = disk_boundary(dl);
  add(
      "disk_area", dl,
      [=] { return integrate_about(db, [](const V3& w) { return dl.pdf(kP, w); }); }, db.frame.z);
  const auto rc = rectangle_corners();
  const auto rb = polygon_boundary(rc, ra.normal);
  const auto raz = azimuths(rb, rc);
  add(
      "rectangle_area", ra,
      [=] {
        return integrate_about(
            rb, [](const V3& w) { return ra.pdf(kP, w); }, raz);
      },
      rb.frame.z, raz);
  add(
      "rectangle_solid_angle", rs,
      [=] {
        return integrate_about(
            rb, [](const V3& w) { return rs.pdf(kP, w); }, raz);
      },
      rb.frame.z, raz);
  const auto pv = pentagon();
  const auto pb = polygon_boundary(pv, pa.normal);
  const auto paz = azimuths(pb, pv);
  add(
      "polygon_area", pa,
      [=] {
        return integrate_about(
            pb, [](const V3& w) { return pa.pdf(kP, w); }, paz);
      },
      pb.frame.z, paz);
  add(
      "polygon_solid_angle", ps,
      [=] {
        return integrate_about(
            pb, [](const V3& w) { return ps.pdf(kP, w); }, paz);
      },
      pb.frame.z, paz);
  return out;
}

TEST(Lights, PdfsIntegrateToOneByCubature) {
  for (const Case& c : cases()) {
    const verify::Integral i = c.integral_of_pdf();
    std::cout << c.name << ": ∫ pdf dω = " << i.value << " ± " << i.error << "\n";
    EXPECT_NEAR(i.value, 1.0, 1e-7) << c.name;
  }
}

TEST(Lights, SamplesAgreeWithPdfRadianceAndGeometry) {
  const std::uint64_t seed = verify::check_seed("lights.sample_records", 0);
  for (const Case& c : cases()) {
    for (std::uint64_t i = 0; i < 2000; ++i) {
      const LightSample<double> s = c.sample(u2(seed, i));
      ASSERT_TRUE(s.valid) << c.name << " " << i;
      EXPECT_NEAR(length(s.wi), 1.0, 1e-12);
      EXPECT_NEAR(s.pdf / c.pdf(s.wi), 1.0, 1e-9) << c.name << " " << i;
      const V3 L = c.radiance(s.wi);
      EXPECT_EQ(L.x, s.radiance.x) << c.name;
      EXPECT_EQ(L.z, s.radiance.z) << c.name;
      EXPECT_GT(s.distance, 0.0) << c.name;
    }
  }
  // The sampled distance lands on the emitter.
  const auto dl = disk();
  const auto pl = point_light();
  const auto ps = polygon(AreaSampling::kSolidAngle);
  for (std::uint64_t i = 0; i < 200; ++i) {
    const auto s = dl.sample(kP, u2(seed, i));
    EXPECT_NEAR(dot(kP + s.distance * s.wi - dl.center, dl.frame.z), 0.0, 1e-12);
    const auto t = pl.sample(kP, u2(seed, i));
    EXPECT_NEAR(length(kP + t.distance * t.wi - pl.center), pl.radius, 1e-12);
    const auto q = ps.sample(kP, u2(seed, i));
    EXPECT_NEAR(dot(kP + q.distance * q.wi - ps.vertex[0], ps.normal), 0.0, 1e-12);
  }
  // Behind a one-sided light every sample is invalid and the pdf is 0.
  const auto behind = dl.sample(V3{0.5, 0.2, 5.0}, V2{0.3, 0.6});
  EXPECT_FALSE(behind.valid);
  EXPECT_EQ(behind.pdf, 0.0);
  EXPECT_EQ(dl.pdf(V3{0.5, 0.2, 5.0}, V3{0, 0, -1}), 0.0);
}

// Float kernels agree with double ones on the same sample (what the SIMD/CUDA builds run).
TEST(Lights, FloatAgreesWithDouble) {
  const auto rd = make_rectangle_light<double>({-0.4, -0.3, 1.2}, {0, 0.7, 0}, {1.0, 0, 0.2}, kL);
  const auto rf = make_rectangle_light<float>({-0.4, -0.3, 1.2}, {0, 0.7, 0}, {1.0, 0, 0.2}, kL);
  const auto pd = make_polygon_light<double>(pentagon(), kL, AreaSampling::kArea);
  const auto pf = make_polygon_light<float>(pentagon(), kL, AreaSampling::kArea);
  const std::uint64_t seed = verify::check_seed("lights.float_double", 0);
  for (std::uint64_t i = 0; i < 500; ++i) {
    const V2 u = u2(seed, i);
    const Vec2<float> uf{float(u.x), float(u.y)};
    const auto a = rd.sample(kP, V2{double(uf.x), double(uf.y)});
    const auto b = rf.sample(Vec3<float>{0, 0, 0}, uf);
    EXPECT_NEAR(length(cast<double>(b.wi) - a.wi), 0.0, 1e-4) << i;
    EXPECT_NEAR(double(b.pdf) / a.pdf, 1.0, 1e-4) << i;
    const auto c = pd.sample(kP, V2{double(uf.x), double(uf.y)});
    const auto d = pf.sample(Vec3<float>{0, 0, 0}, uf);
    EXPECT_NEAR(length(cast<double>(d.wi) - c.wi), 0.0, 1e-4) << i;
    EXPECT_NEAR(double(d.pdf) / c.pdf, 1.0, 1e-4) << i;
  }
}

// ---- Chi-square fits and their negative controls
// -------------------------------------------------

constexpr std::uint64_t kN = 100'000;

// The chi-square plan (bins and cubature of expected counts) of one case's pdf, computed once and
// shared by the correct sampler and the negative controls held to that pdf.
const verify::ChiSquarePlan& plan_of(const Case& c) {
  static std::map<std::string, verify::ChiSquarePlan> plans;
  auto it = plans.find(c.name);
  if (it != plans.end()) return it->second;
  verify::ChiSquareOptions o;
  o.lobe = c.lobe;
  o.fine_max_bins = 512;
  o.phi_breaks = c.phi_breaks;
  return plans
      .emplace(c.name,
               verify::plan_direction_chi_square(verify::SampleDomain::kSphere, c.pdf, kN, o))
      .first->second;
}

// Samples of `c` (u optionally warped) against the pdf of `against`.
verify::ChiSquareResult fit(const Case& c, std::uint64_t seed, const Case& against,
                            std::function<V2(V2)> warp = nullptr) {
  const auto sample = [&c, seed, warp](std::uint64_t i) {
    V2 u = u2(seed, i);
    if (warp) u = warp(u);
    const LightSample<double> s = c.sample(u);
    return s.valid ? s.wi : V3{0, 0, 0};
  };
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = verify::run_direction_chi_square(plan_of(against), sample);
  std::cout << c.name << ": " << r.summary() << " ["
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()
            << " s]\n";
  return r;
}

const Case& case_named(const std::string& n) {
  static const std::vector<Case> all = cases();
  for (const Case& c : all)
    if (c.name == n) return c;
  throw std::runtime_error("no light case " + n);
}

void expect_fits(const std::string& name) {
  const Case& c = case_named(name);
  const auto r = fit(c, verify::check_seed("lights.chi_square." + name, 0), c);
  EXPECT_FALSE(r.rejects(level())) << name << ": " << r.summary();
  EXPECT_FALSE(r.inconclusive) << name << ": " << r.reason;
}

// Negative controls: a sampler held to a pdf it does not draw from (solid-angle sampling against
// the area pdf and back, the disk's area sampler against uniform solid angle), or a sampler with a
// distorted u (u1 → u1^0.9) against its own pdf. Every one must be rejected. One test per light
// family, so that each chi-square plan (the cubature of expected counts) is computed once and
// shared by the correct sampler and the controls held to the same pdf.
void expect_rejected(const std::string& sampler, const Case& against,
                     std::function<V2(V2)> warp = nullptr) {
  const auto r = fit(case_named(sampler), verify::check_seed("lights.control." + sampler, 0),
                     against, std::move(warp));
  EXPECT_TRUE(r.rejects(level())) << sampler << " vs pdf of " << against.name << ": "
                                  << r.summary();
}

const auto kWarp = [](V2 u) { return V2{std::pow(u.x, 0.9), u.y}; };

TEST(LightsChiSquare, CapsMatchTheirPdfsAndControlsAreRejected) {
  for (const char* n : {"point", "directional_5deg", "directional_sun"}) expect_fits(n);
  expect_rejected("point", case_named("point"), kWarp);
  expect_rejected("directional_5deg", case_named("directional_5deg"), kWarp);
}

TEST(LightsChiSquare, DiskMatchesItsPdfAndControlIsRejected) {
  expect_fits("disk_area");
  const auto dl = disk();
  const double om = dl.solid_angle(kP);
  Case uniform = case_named("disk_area");
  uniform.name = "disk_uniform_solid_angle";
  uniform.pdf = [dl, om](const V3& w) { return dl.pdf(kP, w) > 0 ? 1 / om : 0.0; };
  expect_rejected("disk_area", uniform);
}

TEST(LightsChiSquare, RectangleSamplersMatchTheirPdfsAndControlsAreRejected) {
  expect_fits("rectangle_area");
  expect_fits("rectangle_solid_angle");
  expect_rejected("rectangle_area", case_named("rectangle_solid_angle"));
  expect_rejected("rectangle_solid_angle", case_named("rectangle_area"));
}

TEST(LightsChiSquare, PolygonSamplersMatchTheirPdfsAndControlsAreRejected) {
  expect_fits("polygon_area");
  expect_fits("polygon_solid_angle");
  expect_rejected("polygon_area", case_named("polygon_solid_angle"));
  expect_rejected("polygon_solid_angle", case_named("polygon_area"));
}

}  // namespace
}  // namespace glintlab

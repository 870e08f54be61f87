// The micro-specular scene of Podee et al. (Sec. 4, Fig. 4, Table 1): a mirror-like, normal-mapped
// sphere under one small disk light, seen from near, medium and far, and the four ways of shading
// it the paper compares — the supersampled reference (Sec. 4: 64 samples per pixel, 8 × 8), the
// conventional pixel-centre sample, LEAN mapping (Olano & Baker 2010) and the paper's method
// (Sec. 3, core/shading/shade.h).
//
// Radiance at one surface point: the normal map perturbs the shading normal (slope form of Olano
// & Baker Sec. 3: n' ∝ −s_u t − s_v b + n), the view ray is mirrored about n', and the pixel sees
// the light's radiance (1) where that ray meets the disk, else 0 (F = 1, no masking: a normal map,
// not a microsurface). The background is black.
#pragma once

#include <cmath>
#include <memory>
#include <string>

#include "core/lights/disk_light.h"
#include "core/math/orthonormal_basis.h"
#include "core/parameter_check.h"
#include "core/render/image.h"
#include "core/render/supersample.h"
#include "core/scene/camera.h"
#include "core/scene/lean.h"
#include "core/scene/shapes.h"
#include "core/scene/sine_height_field.h"
#include "core/scene/slope_moment_map.h"
#include "core/shading/podee_light_check.h"
#include "core/shading/podee_shade.h"

namespace glintlab::podee {

// The normal map: isotropic sine bumps (core/scene/sine_height_field.h) tiled `tiles_u` × `tiles_v`
// times over the sphere's uv square, with its mip-mapped LEAN moments.
struct NormalMap {
  SineHeightField<double> field;
  int tiles_u, tiles_v;
  SlopeMomentMap moments;

  NormalMap(double slope_rms, int tu, int tv, int map_size)
      : field(isotropic_sine_bumps<double>(slope_rms)),
        tiles_u(tu),
        tiles_v(tv),
        moments(
            [f = isotropic_sine_bumps<double>(slope_rms)](double u, double v) {
              const SurfacePoint<double> s = f.eval(u, v);
              return Vec2<double>{s.slope_u, s.slope_v};
            },
            map_size, 2) {
    detail::require(tu >= 1 && tu <= 4096, "podee normal map", "tiles_u", tu, "1 to 4096");
    detail::require(tv >= 1 && tv <= 4096, "podee normal map", "tiles_v", tv, "1 to 4096");
  }

  // Slopes (∂h/∂u, ∂h/∂v) at the sphere's uv, in the units of a normal map (per tile).
  Vec2<double> slopes(Vec2<double> uv) const {
    const SurfacePoint<double> s = field.eval(uv.x * tiles_u, uv.y * tiles_v);
    return {s.slope_u, s.slope_v};
  }
};

struct SceneConfig {
  double distance = 5;        // camera distance from the sphere's centre (radius 1)
  int size = 96;              // image width = height, pixels
  double fov_degrees = 30;    // vertical field of view
  double light_radius = 0.1;  // disk radius
  double light_distance = 6;  // disk centre's distance from the sphere's centre
  Vec3<double> light_direction{0.97, 0.12, 0.1};  // from the sphere's centre toward the disk
  Vec2<double> film_shift{0, 0};  // sub-pixel camera motion: the film moved by this, in pixels
};

// The shading of one pixel by the paper's method, with what it selected.
struct Pixel {
  double value;
  Result<double> result;
  bool hit;
  double tan_radius;  // the projected disk's radius on the light plane
  Vec3<double> l;     // unit, from the centre hit toward the disk's centre
};

class Scene {
 public:
  Scene(const SceneConfig& c, std::shared_ptr<const NormalMap> map)
      : config_(c), map_(std::move(map)) {
    const char* what = "podee scene";
    detail::require(std::isfinite(c.distance) && c.distance > 1.05, what, "distance", c.distance,
                    "> 1.05 (outside the unit sphere)");
    detail::require(c.size >= 4 && c.size <= 8192, what, "size", c.size, "4 to 8192");
    // The light's centre must lie above the sphere's surface (height over the tangent plane of the
    // nearest surface point).
    require_light(what, c.light_radius, c.light_distance - 1);
    camera_ = PinholeCamera<double>::look_at({c.distance, 0, 0}, {0, 0, 0}, {0, 0, 1},
                                             c.fov_degrees, c.size, c.size);
    sphere_ = Sphere<double>{{0, 0, 0}, 1.0};
    // The disk faces the sphere's centre; beside the camera (+x), its mirror image lies near the
    // middle of the visible hemisphere.
    const Vec3<double> dir = detail::require_direction(what, "light_direction", c.light_direction);
    light_.center = c.light_distance * dir;
    light_.frame = basis_from_z(-1.0 * dir);
    light_.radius = c.light_radius;
    light_.emitted = {1, 1, 1};
  }

  const SceneConfig& config() const { return config_; }
  const PinholeCamera<double>& camera() const { return camera_; }
  const NormalMap& normal_map() const { return *map_; }
  const DiskLight<double>& light() const { return light_; }

  // Radiance along the primary ray through film position (x, y) (pixel (i, j) covers
  // [i, i+1] × [j, j+1]): the reference's integrand.
  double radiance(double x, double y) const {
    const Ray<double> ray = camera_.ray(x + config_.film_shift.x, y + config_.film_shift.y);
    const SurfaceHit<double> s = sphere_.intersect(ray);
    if (!s.hit) return 0;
    const Vec3<double> r = reflect(normalize(camera_.eye - s.p), mapped_normal(s.frame(), s.uv));
    detail::PlaneHit<double> h;
    return light_.hits(s.p, r, &h) ? 1.0 : 0.0;
  }

  // The conventional method: one sample at the pixel centre.
  double centre(int i, int j) const { return radiance(i + 0.5, j + 0.5); }

  // The paper's method (Sec. 3): corner reflection vectors → reflection space → selected vector
  // and weight.
  Pixel podee(int i, int j, Weighting w = Weighting::kExact,
              Selection sel = Selection::kClosestPoint) const {
    const Corners c = corners(i, j);
    if (!c.hit) return {0, {}, false, 0, {0, 0, 1}};
    const Vec3<double> to_light = light_.center - c.p;
    const double dist = length(to_light);
    const Vec3<double> l = (1 / dist) * to_light;
    const double cos_light = -dot(light_.frame.z, l);  // the disk's cosine toward p
    // The projected disk is an ellipse of semi-axes R/d and R cos θ_L / d on the light plane
    // (small-disk limit); the paper lights with a circle: the one of equal area.
    const double tan_radius = light_.radius / dist * std::sqrt(std::max(cos_light, 0.0));
    const Result<double> r = shade(c.r, l, tan_radius, w, sel);
    const bool facing = cos_light > 0 && dot(c.n, l) > 0;
    return {facing ? r.value : 0.0, r, true, tan_radius, l};
  }

  // LEAN mapping (Olano & Baker 2010 Sec. 3.2–4): the slope distribution in the pixel footprint a
  // Gaussian N(μ, Σ) from the trilinear moment lookup; the pixel value ∫_S N ds over the slope
  // region S of the half vectors toward the disk. S is replaced by a uniform disk of the same
  // area (Ω / (4 (o·h) cos³θ_h), the slope-space image of the solid angle Ω) and the uniform disk
  // by a Gaussian of its covariance (ρ²/4 per axis), so the value is π ρ² N(s_h; μ, Σ + ρ²/4 I):
  // LEAN's Gaussian lobe convolved with the light, as real-time LEAN renderers do for area
  // lights. Not clamped: where the lobe is much narrower than the light the Gaussian stand-in
  // overshoots (up to 2×), part of why LEAN "does not work at close distances" (Sec. 4).
  double lean(int i, int j) const {
    const double x = i + 0.5 + config_.film_shift.x, y = j + 0.5 + config_.film_shift.y;
    const Ray<double> ray = camera_.ray(x, y);
    const SurfaceHit<double> s = sphere_.intersect(ray);
    if (!s.hit) return 0;
    const Frame<double> f = s.frame();
    const Vec3<double> v = f.to_local(normalize(camera_.eye - s.p));
    const Vec3<double> to_light = light_.center - s.p;
    const double dist = length(to_light);
    const Vec3<double> l = f.to_local((1 / dist) * to_light);
    const double cos_light = -dot(light_.frame.z, (1 / dist) * to_light);
    if (l.z <= 0 || v.z <= 0 || cos_light <= 0) return 0;
    const Vec3<double> h = normalize(v + l);
    const double solid_angle =
        kPi<double> * light_.radius * light_.radius * cos_light / (dist * dist);
    const double rho2 = solid_angle / (4 * dot(l, h) * h.z * h.z * h.z) / kPi<double>;
    // The footprint from ray differentials (core/scene/camera.h corner rays on the tangent plane).
    const Vec2<double> uv_x =
        uv_on_tangent_plane(s, x + 0.5, y) - uv_on_tangent_plane(s, x - 0.5, y);
    const Vec2<double> uv_y =
        uv_on_tangent_plane(s, x, y + 0.5) - uv_on_tangent_plane(s, x, y - 0.5);
    const NormalMap& m = *map_;
    const Vec2<double> scale{double(m.tiles_u), double(m.tiles_v)};
    const auto tile = [&](Vec2<double> a) { return Vec2<double>{a.x * scale.x, a.y * scale.y}; };
    const Vec2<double> uvt = tile(s.uv);
    const LeanParameters<double> p = lean_parameters(m.moments.lookup(
        uvt.x - std::floor(uvt.x), uvt.y - std::floor(uvt.y), tile(uv_x), tile(uv_y)));
    const double sx = -h.x / h.z - p.mean_x, sy = -h.y / h.z - p.mean_y;
    const double vx = p.sigma_x * p.sigma_x + rho2 / 4, vy = p.sigma_y * p.sigma_y + rho2 / 4;
    const double cxy = p.rho * p.sigma_x * p.sigma_y;
    const double det = vx * vy - cxy * cxy;
    const double q = (vy * sx * sx - 2 * cxy * sx * sy + vx * sy * sy) / det;
    return kPi<double> * rho2 * std::exp(-0.5 * q) / (2 * kPi<double> * std::sqrt(det));
  }

  // The reflection vectors at the four corners of pixel (i, j) (corner order of
  // core/scene/footprint.h), the true ones on the normal-mapped surface: a corner ray that misses
  // the sphere is continued on the centre's tangent plane, with the uv the centre's footprint
  // extrapolates there.
  struct Corners {
    bool hit;
    Vec3<double> p, n;              // centre hit and its geometric normal
    std::array<Vec3<double>, 4> r;  // world space
  };
  Corners corners(int i, int j) const {
    Corners c{};
    const double x = i + 0.5 + config_.film_shift.x, y = j + 0.5 + config_.film_shift.y;
    const SurfaceHit<double> s = sphere_.intersect(camera_.ray(x, y));
    c.hit = s.hit;
    if (!s.hit) return c;
    c.p = s.p;
    c.n = s.n;
    constexpr double kOffset[4][2] = {{-0.5, -0.5}, {0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}};
    for (int k = 0; k < 4; ++k) c.r[k] = reflection_at(s, x + kOffset[k][0], y + kOffset[k][1]);
    return c;
  }

  // The true reflection vector (world) at the fraction (fx, fy) ∈ [0, 1]² of pixel (i, j), where
  // the pixel's centre hits the sphere (else (0, 0, 0)).
  Vec3<double> sub_pixel_reflection(int i, int j, double fx, double fy) const {
    const double x = i + config_.film_shift.x, y = j + config_.film_shift.y;
    const SurfaceHit<double> s = sphere_.intersect(camera_.ray(x + 0.5, y + 0.5));
    if (!s.hit) return {0, 0, 0};
    return reflection_at(s, x + fx, y + fy);
  }

  // The mirror reflection vector (world) of the ray through film position (x, y), on the sphere
  // where it hits, else on the tangent plane of `centre` (shifted film coordinates).
  Vec3<double> reflection_at(const SurfaceHit<double>& centre, double x, double y) const {
    const Ray<double> ray = camera_.ray(x, y);
    const SurfaceHit<double> h = sphere_.intersect(ray);
    if (h.hit) return reflect(normalize(camera_.eye - h.p), mapped_normal(h.frame(), h.uv));
    const Vec3<double> p = plane_point(centre, ray);
    const Vec2<double> uv = centre.uv + uv_offset(centre, p - centre.p);
    return reflect(normalize(camera_.eye - p), mapped_normal(centre.frame(), uv));
  }

 private:
  Vec3<double> mapped_normal(const Frame<double>& f, Vec2<double> uv) const {
    const Vec2<double> s = map_->slopes(uv);
    return normalize(f.n - s.x * f.t - s.y * f.b);
  }
  static Vec3<double> plane_point(const SurfaceHit<double>& s, const Ray<double>& r) {
    const double dn = dot(r.d, s.n);
    const double t = std::abs(dn) > 0 ? dot(s.p - r.o, s.n) / dn : 0.0;
    return r.o + t * r.d;
  }
  // (du, dv) with ∂p/∂u du + ∂p/∂v dv closest to dp (least squares).
  static Vec2<double> uv_offset(const SurfaceHit<double>& s, Vec3<double> dp) {
    const double a11 = dot(s.dpdu, s.dpdu), a12 = dot(s.dpdu, s.dpdv), a22 = dot(s.dpdv, s.dpdv);
    const double b1 = dot(s.dpdu, dp), b2 = dot(s.dpdv, dp);
    const double det = a11 * a22 - a12 * a12;
    if (!(std::abs(det) > 0)) return {0, 0};
    return {(a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det};
  }
  Vec2<double> uv_on_tangent_plane(const SurfaceHit<double>& s, double x, double y) const {
    return s.uv + uv_offset(s, plane_point(s, camera_.ray(x, y)) - s.p);
  }

  SceneConfig config_;
  std::shared_ptr<const NormalMap> map_;
  PinholeCamera<double> camera_;
  Sphere<double> sphere_;
  DiskLight<double> light_;
};

enum class Method {
  kCentre,
  kLean,
  kPodee,
  kPodeeQuadAsCircle,
  kPodeeUnweighted,
  kPodeeCentroidRule
};

inline const char* to_string(Method m) {
  switch (m) {
    case Method::kCentre:
      return "centre";
    case Method::kLean:
      return "lean";
    case Method::kPodee:
      return "podee";
    case Method::kPodeeQuadAsCircle:
      return "podee_quad_as_circle";
    case Method::kPodeeUnweighted:
      return "podee_unweighted";
    default:
      return "podee_centroid_rule";
  }
}

// One pixel of one method.
inline double pixel(const Scene& s, Method m, int i, int j) {
  switch (m) {
    case Method::kCentre:
      return s.centre(i, j);
    case Method::kLean:
      return s.lean(i, j);
    case Method::kPodee:
      return s.podee(i, j).value;
    case Method::kPodeeQuadAsCircle:
      return s.podee(i, j, Weighting::kQuadAsCircle).value;
    case Method::kPodeeUnweighted:
      return s.podee(i, j, Weighting::kNone).value;
    default:
      return s.podee(i, j, Weighting::kExact, Selection::kCentroid).value;
  }
}

// The image of one method (channel "Y": reflected radiance for unit light radiance).
inline Image render_podee(const Scene& s, Method m, int threads) {
  const int n = s.config().size;
  return render_image(n, n, {"Y"}, threads,
                      [&](int i, int j, double* out) { out[0] = pixel(s, m, i, j); });
}

// The supersampled reference: `spp` stratified samples per pixel (64 = the paper's 8 × 8).
inline Image render_podee_reference(const Scene& s, int spp, std::uint64_t seed, int threads,
                                    const RowProgress& progress = {}) {
  const int n = s.config().size;
  return render_supersampled(
      n, n, {"Y"}, spp, seed, threads,
      [&](Vec2<double> film, std::uint64_t, double* acc) { acc[0] += s.radiance(film.x, film.y); },
      progress);
}

// The experiments' settings. Pixel size is fixed by the 96-pixel frame of 30° (vertical field of
// view), so a smaller `size` crops the same view around its centre and keeps the pixel footprint
// (what the method's accuracy depends on) the same for every budget.
inline constexpr double kNear = 2, kMedium = 4, kFar = 10;

inline SceneConfig config(double distance, int size) {
  SceneConfig c;
  c.distance = distance;
  c.size = size;
  const double t = std::tan(15 * kPi<double> / 180) * size / 96.0;
  c.fov_degrees = 2 * std::atan(t) * 180 / kPi<double>;
  c.light_radius = 0.3;
  return c;
}

// The normal map: isotropic bumps of rms slope 0.15 per axis, 8 × 4 tiles over the sphere (about
// 100 bump wavelengths around the equator: several pixels per bump at the near distance, about one
// per pixel at the far one). `tiles_u` = 1 gives the low-frequency control map.
inline std::shared_ptr<const NormalMap> normal_map(int tiles_u = 8) {
  return std::make_shared<const NormalMap>(0.15, tiles_u, std::max(tiles_u / 2, 1), 256);
}

// Frame-to-frame variation under sub-pixel camera motion: `frames` frames with the film moved by
// (f, f/2) / frames pixels (a one-pixel diagonal pan), the mean over pixels and consecutive frame
// pairs of (I_{f+1} − I_f)². `spp` > 0: the supersampled reference at that many samples instead.
// `pan_start`: where the pan starts, in pixels (its phase against the normal map).
inline double flicker(SceneConfig c, std::shared_ptr<const NormalMap> map, Method m, int frames,
                      int threads, int spp = 0, std::uint64_t seed = 0,
                      Vec2<double> pan_start = {0, 0}) {
  Image previous;
  double sum = 0;
  long count = 0;
  for (int f = 0; f < frames; ++f) {
    c.film_shift = {pan_start.x + double(f) / frames, pan_start.y + 0.5 * f / frames};
    const Scene scene(c, map);
    Image im = spp > 0 ? render_podee_reference(scene, spp, seed, threads)
                       : render_podee(scene, m, threads);
    if (f > 0) {
      for (std::size_t k = 0; k < im.data.size(); ++k) sum += sqr(im.data[k] - previous.data[k]);
      count += long(im.data.size());
    }
    previous = std::move(im);
  }
  return count > 0 ? sum / double(count) : 0.0;
}

}  // namespace glintlab::podee

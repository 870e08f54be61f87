// Curved tubes and an anisotropic normal map rendered with the Chermain et al. 2020/2021 glinty
// BRDF (2021 Figs. 7–9): methods at 1 spp, references by stratified supersampling.
#include "verify/scenes/chermain_scenes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/render/supersample.h"
#include "core/scene/footprint.h"
#include "core/scene/lean.h"
#include "core/scene/sine_height_field.h"
#include "core/scene/slope_moment_map.h"
#include "verify/scenes/chermain_footprint_sdf.h"

namespace glintlab::verify {
namespace {

double glint_value(const chermain2021::SdfParams& p, Vec3<double> wi, Vec3<double> wl,
                   const FootprintQuery<double>& fp, const chermain2021::SlopeDerivatives& d,
                   Vec2<double> shift = {0, 0}) {
  return glint_value_of([&](Vec2<double> m) { return chermain2021::patch_sdf(p, m, fp, d); }, wi,
                        wl, shift);
}

// Three tubes (open cylinders) with distinct uv offsets, so that their cells differ.
struct TubeScene {
  std::array<Cylinder<double>, 3> tubes;
  SurfaceHit<double> intersect(const Ray<double>& r) const {
    SurfaceHit<double> best{};
    best.hit = false;
    for (std::size_t i = 0; i < tubes.size(); ++i) {
      SurfaceHit<double> h = tubes[i].intersect(r);
      if (h.hit && (!best.hit || h.t < best.t)) {
        h.uv.x += 3.0 * double(i);
        best = h;
      }
    }
    return best;
  }
};

TubeScene tube_scene() {
  const auto frame = [](Vec3<double> axis) {
    const Vec3<double> n = normalize(axis);
    return frame_from_normal_tangent(n, Vec3<double>{0, 0, 1});
  };
  return {{Cylinder<double>{{0, 0.75, 0}, frame({1, 0.1, 0}), 0.32, 2.5},
           Cylinder<double>{{0, -0.2, -0.3}, frame({1, -0.45, 0}), 0.28, 2.5},
           Cylinder<double>{{-0.9, -0.9, 0.2}, frame({0.2, 1, 0.3}), 0.22, 1.2}}};
}

PinholeCamera<double> tube_camera(const TubeSceneOptions& o) {
  const double fov = 40;
  const double pixel = 2 * 4.0 * std::tan(fov * kPi<double> / 360) / o.height;  // at the origin
  const Vec3<double> shift{o.camera_shift * pixel, 0, 0};
  return PinholeCamera<double>::look_at(Vec3<double>{0, 0, 4} + shift,
                                        Vec3<double>{0, 0, 0} + shift, {0, 1, 0}, fov, o.width,
                                        o.height);
}

constexpr Vec3<double> kTubeLight = {1.5, 2.5, 3.0};
constexpr double kTubeLightIntensity = 16;

chermain2021::SdfParams tube_params(const TubeSceneOptions& o, int kernel, double s_k) {
  const double s = o.alpha / std::sqrt(2.0);
  return {&chermain2021::default_chermain_dictionary(),
          s,
          s,
          0.0,
          std::log2(o.density),
          kernel,
          s_k,
          o.sdf_seed};
}

void check_size(int w, int h) {
  if (w < 2 || h < 2 || w > 4096 || h > 4096)
    throw std::invalid_argument("chermain scene: image size out of range (valid: 2..4096)");
}

void set_grey(double* out, double v) { out[0] = out[1] = out[2] = v; }

}  // namespace

Image render_tubes(const TubeSceneOptions& o, int kernel, double s_k) {
  check_size(o.width, o.height);
  const TubeScene scene = tube_scene();
  const PinholeCamera<double> cam = tube_camera(o);
  const LightPoint<double> light{kTubeLight, false};
  const chermain2021::SdfParams p = tube_params(o, kernel, s_k);
  return render_image(
      o.width, o.height, {"R", "G", "B"}, o.threads, [&](int x, int y, double* out) {
        const PixelFootprint<double> f = pixel_footprint(cam, scene, x + 0.5, y + 0.5, light);
        if (!f.surface.hit) return;
        const Vec3<double> h = half_vector(f.wi, f.wl);
        const chermain2021::SlopeDerivatives d =
            chermain2021::slope_derivatives(h, f.dh_dx, f.dh_dy, kernel);
        const Vec3<double> to_light = kTubeLight - f.surface.p;
        const double E = kTubeLightIntensity / dot(to_light, to_light);
        set_grey(out, E * glint_value(p, f.wi, f.wl, f.footprint, d));
      });
}

Image render_tubes_reference(const TubeSceneOptions& o, int spp, std::uint64_t seed) {
  check_size(o.width, o.height);
  const TubeScene scene = tube_scene();
  const PinholeCamera<double> cam = tube_camera(o);
  const LightPoint<double> light{kTubeLight, false};
  const chermain2021::SdfParams p = tube_params(o, chermain2021::kNoGgaa, 0.5);
  return render_image(
      o.width, o.height, {"R", "G", "B"}, o.threads, [&](int x, int y, double* out) {
        const PixelFootprint<double> f = pixel_footprint(cam, scene, x + 0.5, y + 0.5, light);
        if (!f.surface.hit) return;
        const std::uint64_t first =
            (std::uint64_t(y) * std::uint64_t(o.width) + std::uint64_t(x)) * std::uint64_t(spp);
        // Every sample shades with the pixel's footprint: its cells are drawn once, and the
        // samples' BRDF values are evaluated together.
        const FootprintSdf sdf(p, f.footprint);
        GlintSamples samples;
        samples.reserve(std::size_t(spp));
        std::vector<double> irradiance;
        irradiance.reserve(std::size_t(spp));
        for (int s = 0; s < spp; ++s) {
          const Vec2<double> off = stratified_offset(seed, first + std::uint64_t(s), s, spp);
          const SurfaceHit<double> hit = scene.intersect(cam.ray(x + off.x, y + off.y));
          if (!hit.hit) continue;
          const Frame<double> fr = hit.frame();
          const Vec3<double> wi = fr.to_local(normalize(cam.eye - hit.p));
          const Vec3<double> wl = fr.to_local(normalize(kTubeLight - hit.p));
          const Vec3<double> to_light = kTubeLight - hit.p;
          irradiance.push_back(kTubeLightIntensity / dot(to_light, to_light));
          samples.push(wi, wl, {0, 0});
        }
        std::vector<double> value(samples.size());
        glint_values(sdf, samples, value);
        double sum = 0;  // in sample order, as one loop over the samples would add them
        for (std::size_t i = 0; i < value.size(); ++i) sum += irradiance[i] * value[i];
        set_grey(out, sum / spp);
      });
}

namespace {

// The bump map's shading frame at a tube hit (BumpyTubeOptions): the solid texture's gradient
// projected on the geometric tangent frame gives the tangent-space slopes (s_t, s_b).
struct BumpMap {
  double k, amplitude;
  std::array<Vec3<double>, 6> dirs;
  std::array<double, 6> phase;

  Frame<double> frame(const SurfaceHit<double>& hit) const {
    const Frame<double> g = hit.frame();
    Vec3<double> grad{0, 0, 0};
    for (std::size_t j = 0; j < dirs.size(); ++j)
      grad = grad + (amplitude * k * std::cos(k * dot(dirs[j], hit.p) + phase[j])) * dirs[j];
    const Vec3<double> n_local = normalize(Vec3<double>{-dot(grad, g.t), -dot(grad, g.b), 1});
    return frame_from_normal_tangent(g.to_world(n_local), hit.dpdu);
  }
};

BumpMap bump_map(const BumpyTubeOptions& o) {
  check_size(o.tubes.width, o.tubes.height);
  if (!(o.bump_wavelength_px > 0 && o.bump_slope_rms >= 0))
    throw std::invalid_argument("bumpy tubes: wavelength must be > 0 and slope rms >= 0");
  const double pixel = 2 * 4.0 * std::tan(40 * kPi<double> / 360) / o.tubes.height;  // at origin
  const double k = 2 * kPi<double> / (o.bump_wavelength_px * pixel);
  const double r = 1 / std::sqrt(2.0);
  BumpMap m{k,
            o.bump_slope_rms / k,  // rms slope a·k (Σ (d_j·t)² = 2 over the six directions)
            {Vec3<double>{r, r, 0}, Vec3<double>{r, -r, 0}, Vec3<double>{r, 0, r},
             Vec3<double>{r, 0, -r}, Vec3<double>{0, r, r}, Vec3<double>{0, r, -r}},
            {}};
  for (std::size_t j = 0; j < m.phase.size(); ++j)  // phases from the golden-ratio rotation
    m.phase[j] = 2 * kPi<double> * std::fmod(0.6180339887498949 * double(j + 1), 1.0);
  return m;
}

}  // namespace

Image render_bumpy_tubes(const BumpyTubeOptions& o, int kernel, double s_k) {
  const BumpMap bumps = bump_map(o);
  const TubeScene scene = tube_scene();
  const PinholeCamera<double> cam = tube_camera(o.tubes);
  const LightPoint<double> light{kTubeLight, false};
  const chermain2021::SdfParams p = tube_params(o.tubes, kernel, s_k);
  constexpr double kCorner[4][2] = {{-0.5, -0.5}, {0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}};
  return render_image(
      o.tubes.width, o.tubes.height, {"R", "G", "B", "kernel_width"}, o.tubes.threads,
      [&](int x, int y, double* out) {
        const PixelFootprint<double> f = pixel_footprint(cam, scene, x + 0.5, y + 0.5, light);
        if (!f.surface.hit) return;
        const Frame<double> fr = bumps.frame(f.surface);
        const Vec3<double> wi = fr.to_local(normalize(cam.eye - f.surface.p));
        const Vec3<double> wl = fr.to_local(normalize(kTubeLight - f.surface.p));
        std::array<Vec3<double>, 4> corner_h{};
        for (int c = 0; c < 4; ++c) {
          const Ray<double> ray = cam.ray(x + 0.5 + kCorner[c][0], y + 0.5 + kCorner[c][1]);
          const SurfaceHit<double> hc = scene.intersect(ray);
          const Vec3<double> pc =
              hc.hit ? hc.p : detail::on_tangent_plane(ray, f.surface.p, f.surface.n);
          const Frame<double> fc = hc.hit ? bumps.frame(hc) : fr;
          corner_h[c] =
              fc.to_local(half_vector(normalize(cam.eye - pc), normalize(kTubeLight - pc)));
        }
        const Vec3<double> dh_dx =
            0.5 * ((corner_h[1] - corner_h[0]) + (corner_h[3] - corner_h[2]));
        const Vec3<double> dh_dy =
            0.5 * ((corner_h[2] - corner_h[0]) + (corner_h[3] - corner_h[1]));
        const Vec3<double> h = half_vector(wi, wl);
        const chermain2021::SlopeDerivatives d =
            chermain2021::slope_derivatives(h, dh_dx, dh_dy, kernel);
        const Vec3<double> to_light = kTubeLight - f.surface.p;
        const double E = kTubeLightIntensity / dot(to_light, to_light);
        set_grey(out, E * glint_value(p, wi, wl, f.footprint, d));
        const double sk = kernel == chermain2021::kNoGgaa ? 0.0 : s_k;
        out[3] = sk * std::sqrt(std::max(d.dx_x * d.dx_x + d.dx_y * d.dx_y,
                                         d.dy_x * d.dy_x + d.dy_y * d.dy_y));
      });
}

Image render_bumpy_tubes_reference(const BumpyTubeOptions& o, int spp, std::uint64_t seed,
                                   BumpyReference kind) {
  const BumpMap bumps = bump_map(o);
  const TubeScene scene = tube_scene();
  const PinholeCamera<double> cam = tube_camera(o.tubes);
  const LightPoint<double> light{kTubeLight, false};
  const chermain2021::SdfParams p = tube_params(o.tubes, chermain2021::kNoGgaa, 0.5);
  const double finest_lod = -0.5 * std::log2(o.tubes.density);  // one microfacet per cell
  return render_image(
      o.tubes.width, o.tubes.height, {"R", "G", "B"}, o.tubes.threads,
      [&](int x, int y, double* out) {
        const PixelFootprint<double> f = pixel_footprint(cam, scene, x + 0.5, y + 0.5, light);
        if (!f.surface.hit) return;
        FootprintQuery<double> sub = f.footprint;
        double scale = kind == BumpyReference::kFinest ? 1.0 / kBumpyReferenceStrata : 1.0;
        sub.duv_dx = scale * f.footprint.duv_dx, sub.duv_dy = scale * f.footprint.duv_dy;
        const double l = chermain2021::lod(sub);
        if (l < finest_lod) {
          scale *= std::exp2(finest_lod - l);
          sub.duv_dx = scale * f.footprint.duv_dx, sub.duv_dy = scale * f.footprint.duv_dy;
        }
        const std::uint64_t first =
            (std::uint64_t(y) * std::uint64_t(o.tubes.width) + std::uint64_t(x)) *
            std::uint64_t(spp);
        // The samples' cells drawn one sample at a time, their BRDF values evaluated together.
        SampleFootprints footprints(p);
        footprints.reserve(std::size_t(spp));
        GlintSamples samples;
        samples.reserve(std::size_t(spp));
        std::vector<double> irradiance;
        irradiance.reserve(std::size_t(spp));
        for (int s = 0; s < spp; ++s) {
          const Vec2<double> off = stratified_offset(seed, first + std::uint64_t(s), s, spp);
          const SurfaceHit<double> hit = scene.intersect(cam.ray(x + off.x, y + off.y));
          if (!hit.hit) continue;
          const Frame<double> fr = bumps.frame(hit);
          const Vec3<double> wi = fr.to_local(normalize(cam.eye - hit.p));
          const Vec3<double> wl = fr.to_local(normalize(kTubeLight - hit.p));
          const Vec3<double> to_light = kTubeLight - hit.p;
          irradiance.push_back(kTubeLightIntensity / dot(to_light, to_light));
          sub.uv = hit.uv;
          footprints.push(sub);
          samples.push(wi, wl, {0, 0});
        }
        std::vector<double> value(samples.size());
        glint_values(footprints, samples, value);
        double sum = 0;  // in sample order, as one loop over the samples would add them
        for (std::size_t i = 0; i < value.size(); ++i) sum += irradiance[i] * value[i];
        set_grey(out, sum / spp);
      });
}

namespace {

constexpr Vec3<double> kMapLightDir = {0.1, 0.85, 0.5};

struct MapScene {
  Plane<double> plane;
  PinholeCamera<double> camera;
  SineHeightField<double> field;
};

MapScene map_scene(const NormalMapSceneOptions& o) {
  check_size(o.width, o.height);
  MapScene s{
      Plane<double>{{0, 0, 0}, Frame<double>{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 1.0 / 6, 0},
      PinholeCamera<double>::look_at({0, -2.2, 1.2}, {0, 0.3, 0}, {0, 0, 1}, 40, o.width, o.height),
      brushed_grooves(o.slope_rms, o.anisotropy, o.groove_p, o.groove_q)};
  return s;
}

chermain2021::SdfParams map_params(const NormalMapSceneOptions& o, double sx, double sy,
                                   double rho) {
  return {&chermain2021::default_chermain_dictionary(),
          sx,
          sy,
          rho,
          std::log2(o.density),
          chermain2021::kNoGgaa,
          0.5,
          5};
}

}  // namespace

namespace {

// The normal map's slope moments (LEAN's MIP pyramid), the same for every method.
SlopeMomentMap normal_map_moments(const NormalMapSceneOptions& o, const MapScene& s) {
  return SlopeMomentMap(
      [&](double u, double v) {
        const SurfacePoint<double> q = s.field.eval(u, v);
        return Vec2<double>{q.slope_u, q.slope_v};
      },
      o.map_size, 4);
}

Image render_normal_map_with(const NormalMapSceneOptions& o, const MapScene& s,
                             const SlopeMomentMap& map, NormalMapMethod method) {
  const LightPoint<double> light{kMapLightDir, true};
  const chermain2021::SlopeDerivatives zero{0, 0, 0, 0};
  const double base = o.base_alpha / std::sqrt(2.0);
  return render_image(
      o.width, o.height, {"R", "G", "B"}, o.threads, [&](int x, int y, double* out) {
        const PixelFootprint<double> f =
            pixel_footprint(s.camera, s.plane, x + 0.5, y + 0.5, light);
        if (!f.surface.hit) return;
        const SlopeMoments<double> m =
            map.lookup(f.footprint.uv.x, f.footprint.uv.y, f.footprint.duv_dx, f.footprint.duv_dy);
        const LeanParameters<double> lp = lean_parameters(m, o.base_alpha);
        chermain2021::SdfParams p = map_params(o, base, base, 0);
        if (method != NormalMapMethod::kNoLean) {
          p.sigma_x = lp.sigma_x, p.sigma_y = lp.sigma_y;
          p.rho = method == NormalMapMethod::kLean ? std::clamp(lp.rho, -0.999, 0.999) : 0.0;
        }
        set_grey(out, glint_value(p, f.wi, f.wl, f.footprint, zero, {lp.mean_x, lp.mean_y}));
      });
}

}  // namespace

Image render_normal_map(const NormalMapSceneOptions& o, NormalMapMethod method) {
  const MapScene s = map_scene(o);
  return render_normal_map_with(o, s, normal_map_moments(o, s), method);
}

Image render_normal_map_reference(const NormalMapSceneOptions& o, int spp, std::uint64_t seed) {
  const MapScene s = map_scene(o);
  const LightPoint<double> light{kMapLightDir, true};
  const double base = o.base_alpha / std::sqrt(2.0);
  const chermain2021::SdfParams p = map_params(o, base, base, 0);
  const Vec3<double> wl_world = normalize(kMapLightDir);
  return render_image(
      o.width, o.height, {"R", "G", "B"}, o.threads, [&](int x, int y, double* out) {
        const PixelFootprint<double> f =
            pixel_footprint(s.camera, s.plane, x + 0.5, y + 0.5, light);
        if (!f.surface.hit) return;
        const std::uint64_t first =
            (std::uint64_t(y) * std::uint64_t(o.width) + std::uint64_t(x)) * std::uint64_t(spp);
        // Every sample shades with the pixel's footprint: its cells are drawn once, and the
        // samples' BRDF values are evaluated together.
        const FootprintSdf sdf(p, f.footprint);
        GlintSamples samples;
        samples.reserve(std::size_t(spp));
        for (int k = 0; k < spp; ++k) {
          const Vec2<double> off = stratified_offset(seed, first + std::uint64_t(k), k, spp);
          const SurfaceHit<double> hit = s.plane.intersect(s.camera.ray(x + off.x, y + off.y));
          if (!hit.hit) continue;
          const Frame<double> fr = hit.frame();
          const SurfacePoint<double> q = s.field.eval(hit.uv.x, hit.uv.y);
          samples.push(fr.to_local(normalize(s.camera.eye - hit.p)), fr.to_local(wl_world),
                       {q.slope_u, q.slope_v});
        }
        std::vector<double> value(samples.size());
        glint_values(sdf, samples, value);
        double sum = 0;  // in sample order, as one loop over the samples would add them
        for (const double v : value) sum += v;
        set_grey(out, sum / spp);
      });
}

namespace {

double exposure_of(const Image& ref) {
  double sum = 0;
  long n = 0;
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x)
      if (ref.at(x, y, 0) > 0) sum += ref.at(x, y, 0), ++n;
  if (n == 0 || !(sum > 0)) throw std::invalid_argument("display metric: reference is black");
  return 0.18 / (sum / double(n));
}

void check_same(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("display metric: image sizes differ");
}

}  // namespace

std::vector<double> display_abs_errors(const Image& x, const Image& reference) {
  check_same(x, reference);
  const double e = exposure_of(reference);
  std::vector<double> d;
  for (int j = 0; j < x.height; ++j)
    for (int i = 0; i < x.width; ++i) {
      if (!(reference.at(i, j, 0) > 0)) continue;
      const double a = std::clamp(e * x.at(i, j, 0), 0.0, 1.0);
      const double b = std::clamp(e * reference.at(i, j, 0), 0.0, 1.0);
      d.push_back(std::abs(a - b));
    }
  return d;
}

double display_rmse_percent(const Image& x, const Image& reference) {
  const std::vector<double> d = display_abs_errors(x, reference);
  double sum = 0;
  for (double v : d) sum += v * v;
  return 100 * std::sqrt(sum / double(d.size()));
}

double frame_to_frame_variance(const std::vector<Image>& frames, const Image& reference) {
  if (frames.size() < 2)
    throw std::invalid_argument("frame_to_frame_variance: fewer than 2 frames");
  const double e = exposure_of(reference);
  double sum = 0;
  long n = 0;
  for (std::size_t f = 1; f < frames.size(); ++f) {
    check_same(frames[f], frames[f - 1]);
    for (int j = 0; j < reference.height; ++j)
      for (int i = 0; i < reference.width; ++i) {
        const double a = std::clamp(e * frames[f].at(i, j, 0), 0.0, 1.0);
        const double b = std::clamp(e * frames[f - 1].at(i, j, 0), 0.0, 1.0);
        sum += (a - b) * (a - b), ++n;
      }
  }
  return 1e4 * sum / double(n);
}

GgaaVerdict judge_ggaa(const GgaaMeasurement& m, const Image& reference) {
  GgaaVerdict v;
  v.rmse_none = display_rmse_percent(m.none, reference);
  v.rmse_half05 = display_rmse_percent(m.half05, reference);
  v.rmse_half1 = display_rmse_percent(m.half1, reference);
  v.rmse_proj05 = display_rmse_percent(m.proj05, reference);
  v.rmse_proj1 = display_rmse_percent(m.proj1, reference);
  v.flicker_none = frame_to_frame_variance(m.frames_none, reference);
  v.flicker05 = frame_to_frame_variance(m.frames05, reference);
  v.flicker1 = frame_to_frame_variance(m.frames1, reference);
  v.ggaa_lowers = v.rmse_proj05 < v.rmse_none && v.rmse_half05 < v.rmse_none;
  v.projected_beats_half = v.rmse_proj05 < v.rmse_half05 && v.rmse_proj1 < v.rmse_half1;
  v.small_kernel_lower_rmse = v.rmse_proj05 < v.rmse_proj1;
  v.small_kernel_shimmers_more = v.flicker05 > v.flicker1;
  return v;
}

LeanMeasurement measure_lean(const LeanBudget& b, std::uint64_t seed) {
  NormalMapSceneOptions o;
  o.width = b.width, o.height = b.height, o.threads = b.threads;
  o.groove_p = b.groove_p, o.groove_q = b.groove_q;
  LeanMeasurement m;
  m.reference = render_normal_map_reference(o, b.reference_spp, seed);
  // The three methods read one slope moment map (render_normal_map would build it for each).
  const MapScene s = map_scene(o);
  const SlopeMomentMap map = normal_map_moments(o, s);
  m.no_lean = render_normal_map_with(o, s, map, NormalMapMethod::kNoLean);
  m.lean_rho0 = render_normal_map_with(o, s, map, NormalMapMethod::kLeanRhoZero);
  m.lean = render_normal_map_with(o, s, map, NormalMapMethod::kLean);
  m.rmse_no_lean = display_rmse_percent(m.no_lean, m.reference);
  m.rmse_lean_rho0 = display_rmse_percent(m.lean_rho0, m.reference);
  m.rmse_lean = display_rmse_percent(m.lean, m.reference);
  return m;
}

}  // namespace glintlab::verify

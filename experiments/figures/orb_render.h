// The rough-orb scene of Eto & Tokuyoshi 2023 Figs. 1 and 4: a sphere with a smooth microfacet
// model, seen by a pinhole camera, under an environment light, estimated per pixel by sampling
// the model (one bounce, no light sampling: the estimator whose variance the paper compares).
// Pixel value = (1/N) Σ_s [ray s hits ? w_s L_env(ω_o,s) : L_env(ray direction)], w_s = f cos/pdf
// of the model's sampler (0 for a rejected sample); ray positions stratified in the pixel
// (core/render/supersample.h).
#pragma once

#include <cstdint>

#include "core/model.h"
#include "core/render/supersample.h"
#include "core/scene/camera.h"
#include "core/scene/shapes.h"

namespace glintlab::experiments {

struct OrbScene {
  PinholeCamera<double> camera;
  Sphere<double> sphere;
};

// A unit sphere at the origin seen from 20° above the horizon, filling most of the frame.
inline OrbScene make_orb_scene(int width, int height) {
  const Vec3<double> eye{3.6 * 0.9397, 0.0, 3.6 * 0.3420};
  return {PinholeCamera<double>::look_at(eye, {0, 0, 0}, {0, 0, 1}, 36.0, width, height),
          Sphere<double>{{0, 0, 0}, 1.0}};
}

// Channels of an orb render: radiance, the fraction of the pixel's samples that hit the orb, and
// the fraction of them the sampler rejected.
inline std::vector<std::string> orb_channels() { return {"R", "G", "B", "coverage", "rejected"}; }

// Renders the scene with model M (parameters `params`) at `spp` stratified samples per pixel.
// Env is a distant light with radiance(p, ω) (EnvironmentMap of core/lights/, p unused).
template <Model M, class Env>
Image render_orb(const OrbScene& scene, const typename M::template Params<double>& params,
                 const Env& env, int spp, std::uint64_t seed, int threads,
                 const RowProgress& progress = {}) {
  const auto sample = [&](Vec2<double> film, std::uint64_t index, double* acc) {
    const Ray<double> ray = scene.camera.ray(film.x, film.y);
    const SurfaceHit<double> hit = scene.sphere.intersect(ray);
    Vec3<double> l{0, 0, 0};
    if (!hit.hit) {
      l = env.radiance(Vec3<double>{0, 0, 0}, normalize(ray.d));
    } else {
      acc[3] += 1;
      const Frame<double> frame = hit.frame();
      ModelQuery<double> q{};
      q.footprint.uv = hit.uv;
      q.wi = frame.to_local(normalize(-ray.d));
      q.light = {1.0, 1.0};
      const Vec2<double> u{counter_uniform<double>(seed, index, 2),
                           counter_uniform<double>(seed, index, 3)};
      const ModelSample<double> smp = M::template sample<double>(params, q, u);
      if (smp.rejected) {
        acc[4] += 1;
      } else {
        l = smp.weight * env.radiance(Vec3<double>{0, 0, 0}, frame.to_world(smp.wo));
      }
    }
    acc[0] += l.x;
    acc[1] += l.y;
    acc[2] += l.z;
  };
  return render_supersampled(scene.camera.width, scene.camera.height, orb_channels(), spp, seed,
                             threads, sample, progress);
}

}  // namespace glintlab::experiments

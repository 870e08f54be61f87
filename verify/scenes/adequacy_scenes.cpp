// The validation scenes of adequacy.choice-is-safe: per pixel, the chosen level and the exact
// level over realisations of the same material, compared by the adequacy rule's own statistics.
#include "verify/scenes/adequacy_scenes.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <boost/math/distributions/binomial.hpp>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <type_traits>

#include "core/glints/area_chooser.h"
#include "core/glints/chermain_chooser.h"
#include "core/glints/cost_chooser.h"
#include "core/glints/kneiphof_ltc.h"
#include "core/model_registry.h"
#include "core/scene/footprint.h"
#include "verify/adequacy/chermain_adequacy.h"
#include "verify/adequacy/kemppinen_adequacy.h"
#include "verify/adequacy/kemppinen_levels.h"

namespace glintlab::verify::adequacy {
namespace {

// The point light's position and intensity; the spherical light is a ball of kLightRadius there
// with the radiance that gives it the same power (so the two planes are exposed alike).
constexpr Vec3<double> kPlaneLight{0, 10, 1.5};
constexpr Vec3<double> kSphereSceneLight{2.5, 2.5, 3.0};
constexpr double kLightIntensity = 100;
constexpr double kLightRadius = 0.4;

// A family's predicted adequacy per level as ScenePixel::predicted_adequate's bits.
template <std::size_t N>
std::uint32_t adequacy_bits(const std::array<bool, N>& adequate) {
  std::uint32_t bits = 0;
  for (std::size_t l = 0; l < N; ++l) bits |= adequate[l] ? std::uint32_t(1) << l : 0;
  return bits;
}

struct SceneGeometry {
  PinholeCamera<double> camera;
  Plane<double> plane;
  Sphere<double> sphere;
  Vec3<double> light;
};

// The plane z = 0 (uv = world x, y) from a camera 1 unit above it whose rows run from 1.6 units
// ahead (incidence 58°) to 30 units (88°): the footprint grows some 4000-fold from the bottom row
// to the top. The sphere: the unit sphere from 3.6 units, 20° above its equator.
SceneGeometry geometry(const ChoiceScene& s, int width, int height) {
  SceneGeometry g{};
  if (s.shape == SceneShape::kPlane) {
    g.camera =
        PinholeCamera<double>::look_at({0, 0, 1}, {0, 3.3, 0}, {0, 0, 1}, 30.0, width, height);
    g.plane = Plane<double>{{0, 0, 0}, Frame<double>{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 1.0, 0.0};
    g.light = kPlaneLight;
  } else {
    g.camera = PinholeCamera<double>::look_at({3.6 * 0.9397, 0.0, 3.6 * 0.3420}, {0, 0, 0},
                                              {0, 0, 1}, 36.0, width, height);
    g.sphere = Sphere<double>{{0, 0, 0}, 1.0};
    g.light = kSphereSceneLight;
  }
  return g;
}


template <class M>
typename M::template Params<double> scene_params(const ChoiceScene& s, std::uint64_t seed) {
  std::vector<double> v;
  for (const ParamSpec& p : M::kParams) v.push_back(p.default_value);
  v[param_index<M>("alpha_x")] = kSceneAlpha;
  v[param_index<M>("alpha_y")] = kSceneAlpha;
  v[param_index<M>("density")] = s.log10_density;
  v[param_index<M>("seed")] = double(seed % 4294967296ULL);
  return M::template params<double>(v);
}

// A level's value at a query: the smooth level is the family's smooth factor (F = 1), as the
// grid measures it (verify/adequacy/binomial_adequacy.cpp); the others the model with that
// sampler.
template <class M>
double level_value(typename M::template Params<double> params, BinomialLevel level,
                   const ModelQuery<double>& q) {
  if (level == BinomialLevel::kSmooth)
    return microfacet_brdf(params.ggx, q.wi, q.wo, 1.0) * std::max(q.wo.z, 0.0);
  params.sampler = binomial_sampler_of(level);
  return M::template eval<double>(params, q).value;
}

// N_P and the clamped p exactly as the model (and its chooser) computes them.
std::pair<double, double> facets_and_p(const DeliotBelcour::Params<double>& params,
                                       const ModelQuery<double>& q) {
  const double d_n = kInvPi<double> / (params.ggx.alpha_x * params.ggx.alpha_y);
  return {footprint_facet_count_scaled(q.footprint, params.density_scale),
          saturate(params.r * params.ggx.D(half_vector(q.wi, q.wo)) / d_n)};
}
std::pair<double, double> facets_and_p(const KneiphofKlein::Params<double>& params,
                                       const ModelQuery<double>& q) {
  const double omc =
      q.light.cos_half_angle < 1 ? 1 - q.light.cos_half_angle : params.one_minus_cos_gamma;
  return {
      footprint_facet_count_scaled(q.footprint, params.density_scale),
      saturate(kneiphof2024::cap_probability_eq20(params.ggx, q.wi, q.wo, omc, params.total_area))};
}
double engine_level(const DeliotBelcour::Params<double>& params, const ModelQuery<double>& q,
                    double tau) {
  return choose_deliot_belcour_level(params, q, tau);
}
double engine_level(const KneiphofKlein::Params<double>& params, const ModelQuery<double>& q,
                    double tau) {
  return choose_kneiphof_klein_level(params, q, tau);
}

// Realisation j of a footprint centred at uv: j = 0 is the rendered pixel itself; the others
// move the centre along the R2 low-discrepancy sequence (Roberts 2018), as the grid moves it, so
// each keys the counter RNG afresh.
Vec2<double> realisation_uv(Vec2<double> uv, int j) {
  if (j == 0) return uv;
  const double a = uv.x + 0.75487766624669276005 * j, b = uv.y + 0.56984029099805326591 * j;
  return {a - std::floor(a), b - std::floor(b)};
}

// The query of pixel (col, row): its footprint, directions from ray differentials, a point light
// of unit intensity (the caller widens it to a cone), and the squared distance to the light.
// False where the ray misses the shape or the view or the light is below the horizon.
template <class Shape>
bool pixel_query(const SceneGeometry& g, const Shape& shape, int col, int row,
                 ModelQuery<double>& q, double& light_d2, PixelFootprint<double>& f) {
  f = pixel_footprint(g.camera, shape, col + 0.5, row + 0.5, LightPoint<double>{g.light, false});
  if (!f.surface.hit || !(f.wi.z > 0) || !(f.wl.z > 0)) return false;
  const Vec3<double> to_light = g.light - f.surface.p;
  light_d2 = dot(to_light, to_light);
  q = ModelQuery<double>{};
  q.footprint = f.footprint;
  q.wi = f.wi;
  q.wo = f.wl;
  q.light.intensity = 1;
  q.light.cos_half_angle = 1;
  return true;
}

// Every pixel whose camera ray hits the shape with the view and the light above its horizon (the
// others stay off the surface), in parallel over rows: fn(pixel, its query, the squared distance
// to the light, per-row scratch x and ref[, the pixel's footprint with its derivatives]).
template <class Shape, class F>
void for_each_surface_pixel(const SceneGeometry& g, const Shape& shape, const SceneOptions& o,
                            SceneRender& out, const F& fn) {
  tbb::parallel_for(0, o.height, [&](int row) {
    std::vector<double> x, ref;
    for (int col = 0; col < o.width; ++col) {
      ScenePixel& px = out.pixels[std::size_t(row) * std::size_t(o.width) + std::size_t(col)];
      ModelQuery<double> q;
      double d2 = 0;
      PixelFootprint<double> f;
      if (!pixel_query(g, shape, col, row, q, d2, f)) continue;
      px.surface = true;
      if constexpr (std::is_invocable_v<const F&, ScenePixel&, ModelQuery<double>&, double,
                                        std::vector<double>&, std::vector<double>&,
                                        const PixelFootprint<double>&>)
        fn(px, q, d2, x, ref, f);
      else
        fn(px, q, d2, x, ref);
    }
  });
}

// A pixel's renders (realisation 0) and, unless its level is the most complete one or it is not
// lit, the rule's differences of the chosen level's realisations `x` against the most complete
// level's `ref` and whether they exceed TAU.
void score_pixel(ScenePixel& px, const std::vector<double>& x, const std::vector<double>& ref,
                 std::size_t lit, double irradiance, bool most_complete, const Decision& d,
                 double tau) {
  px.exact_value = ref[0] * irradiance;
  px.chosen_value = x[0] * irradiance;
  px.lit = double(lit) >= kMinLitPositions;
  if (most_complete || !px.lit) return;
  const LevelStats st = compare_to_exact(x, ref, d);
  px.mean_diff = st.mean_diff, px.cv_diff = st.cv_diff;
  px.mean_diff_lcb = st.mean_diff_lcb, px.cv_diff_lcb = st.cv_diff_lcb;
  px.exceeds = !st.undecided && (st.mean_diff_lcb > tau || st.cv_diff_lcb > tau);
}

template <class M, class Shape>
void render_rows(const ChoiceScene& s, const SceneGeometry& g, const Shape& shape,
                 const SceneOptions& o, SceneRender& out) {
  const auto params = scene_params<M>(s, o.seed);
  const Decision pixel_decision = decision_at_level(kPixelFlagRate / 2, o.tau);
  for_each_surface_pixel(g, shape, o, out, [&](ScenePixel& px, ModelQuery<double>& q, double d2,
                                               std::vector<double>& x, std::vector<double>& ref) {
    // A point light (cos_half_angle 1): kneiphof_klein widens it to its 0.26° cap.
    if (s.light == SceneLight::kSphereLight)
      q.light.cos_half_angle = std::sqrt(std::max(1 - kLightRadius * kLightRadius / d2, 0.0));
    // Irradiance at the point from the light (the same for both lights, to first order).
    const double irradiance = kLightIntensity / d2;
    std::tie(px.facets, px.p) = facets_and_p(params, q);
    px.level = o.chooser ? o.chooser(px.facets, px.p, o.chooser_tau)
                         : int(engine_level(params, q, o.chooser_tau));
    if (px.level < 0 || px.level >= kBinomialLevels)
      throw std::invalid_argument("adequacy scenes: the chooser returned no level of the family");
    const auto chosen = BinomialLevel(px.level);
    const int n = o.realisations;
    x.resize(std::size_t(n));
    ref.resize(std::size_t(n));
    std::size_t lit = 0;
    for (int j = 0; j < n; ++j) {
      ModelQuery<double> at = q;
      at.footprint.uv = realisation_uv(q.footprint.uv, j);
      ref[std::size_t(j)] = level_value<M>(params, BinomialLevel::kExact, at);
      x[std::size_t(j)] = chosen == BinomialLevel::kExact ? ref[std::size_t(j)]
                                                          : level_value<M>(params, chosen, at);
      lit += ref[std::size_t(j)] != 0 ? 1 : 0;
    }
    score_pixel(px, x, ref, lit, irradiance, chosen == BinomialLevel::kExact, pixel_decision,
                o.tau);
  });
}

// Realisation j of a Kemppinen pixel: j = 0 is the rendered pixel itself; the others move the
// footprint's centre along the R2 sequence over a square kKemppinenSpread coarse cells wide, as the
// Kemppinen grid moves it (kemppinen_adequacy.h): the implicit grid is spatial, so realisations
// must not share its cells. Algorithm 1's coarser cell is 2^(⌊λ⌋+1)/√K_P ≤ 4 σ_max, and σ_max =
// f × the footprint's longer axis ≤ f (|duv_dx| + |duv_dy|) with f = 0.5 (or 2/√K_P where λ is
// clamped at 0); the spread uses that bound.
Vec2<double> kemppinen_realisation_uv(const ModelQuery<double>& q, double density, int j) {
  if (j == 0) return q.footprint.uv;
  const double cell = 2 * std::max(std::hypot(q.footprint.duv_dx.x, q.footprint.duv_dx.y) +
                                       std::hypot(q.footprint.duv_dy.x, q.footprint.duv_dy.y),
                                   1 / std::sqrt(density));
  const Vec2<double> r = surface_position(j);
  return {q.footprint.uv.x + r.x * kKemppinenSpread * cell,
          q.footprint.uv.y + r.y * kKemppinenSpread * cell};
}

// The Kemppinen family's pixels: the chosen level (choose_kemppinen_model_level, or the options'
// chooser) against k16_exact at the same realisations. A rational level's values are its exact
// twin's plus a constant (the compensation depends on ω_h and λ only, the same at every
// realisation of a pixel; KemppinenAdequacy.RationalLevelIsTheExactOnePlusAConstant), taken from
// realisation 0; the smooth level is G2 D / (4 cos θ_i), the same at every realisation.
template <class Shape>
void render_kemppinen_rows(const ChoiceScene& s, const SceneGeometry& g, const Shape& shape,
                           const SceneOptions& o, SceneRender& out) {
  using M = KemppinenGGX;
  const double density = std::pow(10.0, s.log10_density);
  std::array<M::Params<double>, kKemppinenLevels> params{};
  for (int l = 1; l < kKemppinenLevels; ++l)
    params[std::size_t(l)] =
        kemppinen_level_params<M>(kSceneAlpha, density, KemppinenLevel(l), o.seed);
  const M::Params<double>& reference = params[std::size_t(KemppinenLevel::kK16Exact)];
  const Decision pixel_decision = decision_at_level(kPixelFlagRate / 2, o.tau);
  for_each_surface_pixel(g, shape, o, out, [&](ScenePixel& px, ModelQuery<double>& q, double d2,
                                               std::vector<double>& x, std::vector<double>& ref) {
    const double irradiance = kLightIntensity / d2;
    px.facets = density * std::abs(q.footprint.duv_dx.x * q.footprint.duv_dy.y -
                                   q.footprint.duv_dx.y * q.footprint.duv_dy.x);
    px.p = 0;
    px.level = o.kemppinen_chooser ? o.kemppinen_chooser(reference, q, o.chooser_tau)
                                   : int(choose_kemppinen_model_level(reference, q, o.chooser_tau));
    px.predicted_adequate = adequacy_bits(kemppinen_level_adequacy(adequate_kemppinen_levels(
        kemppinen_level_moments(reference.glint, reference.ndf, q.footprint,
                                half_vector(q.wi, q.wo)),
        o.chooser_tau)));
    if (px.level < 0 || px.level >= kKemppinenLevels)
      throw std::invalid_argument("adequacy scenes: the chooser returned no Kemppinen level");
    const auto chosen = KemppinenLevel(px.level);
    const KemppinenLevel twin = kemppinen_exact_twin(chosen);
    const int n = o.realisations;
    x.resize(std::size_t(n));
    ref.resize(std::size_t(n));
    std::size_t lit = 0;
    double smooth = 0;
    for (int j = 0; j < n; ++j) {
      ModelQuery<double> at = q;
      at.footprint.uv = kemppinen_realisation_uv(q, density, j);
      const auto e = kemppinen_value(reference, at);
      ref[std::size_t(j)] = e.value;
      if (j == 0) smooth = kemppinen_smooth_value(e, at);
      x[std::size_t(j)] = chosen == KemppinenLevel::kSmooth ? smooth
                          : twin == KemppinenLevel::kK16Exact
                              ? e.value
                              : kemppinen_value(params[std::size_t(twin)], at).value;
      lit += e.value != 0 ? 1 : 0;
    }
    if (chosen != twin) {
      const double shift = kemppinen_value(params[std::size_t(chosen)], q).value -
                           (twin == KemppinenLevel::kK16Exact
                                ? ref[0]
                                : kemppinen_value(params[std::size_t(twin)], q).value);
      for (double& v : x) v += shift;
    }
    score_pixel(px, x, ref, lit, irradiance, chosen == KemppinenLevel::kK16Exact,
                pixel_decision, o.tau);
  });
}

// The area family's pixels: kneiphof_klein_area with the square light at the pixel's light
// distance, its level chosen by the engine chooser choose_kneiphof_klein_area_model_level
// (core/glints/area_chooser.h: the binomial chooser on the model's own N_P and LTC p, its eval's
// intermediates), against exact counting at the same realisations; the smooth level is the model's
// L_o/L_i (the same at every realisation). The rendered radiance takes the light's radiance that
// gives the point light's power.
template <class Shape>
void render_area_rows(const ChoiceScene& s, const SceneGeometry& g, const Shape& shape,
                      const SceneOptions& o, SceneRender& out) {
  using M = KneiphofKleinArea;
  std::vector<double> v;
  for (const ParamSpec& p : M::kParams) v.push_back(p.default_value);
  v[param_index<M>("alpha")] = kSceneAlpha;
  v[param_index<M>("density")] = s.log10_density;
  v[param_index<M>("light_width")] = kRectLightSide;
  v[param_index<M>("light_height")] = kRectLightSide;
  v[param_index<M>("seed")] = double(o.seed % 4294967296ULL);
  const M::Params<double> base = M::params<double>(v);
  const double radiance = kLightIntensity / (kRectLightSide * kRectLightSide);
  const Decision pixel_decision = decision_at_level(kPixelFlagRate / 2, o.tau);
  for_each_surface_pixel(g, shape, o, out, [&](ScenePixel& px, ModelQuery<double>& q, double d2,
                                               std::vector<double>& x, std::vector<double>& ref) {
    M::Params<double> params = base;
    params.distance = std::sqrt(d2);
    params.sampler = BinomialSampler::kExact;
    const auto e = M::eval<double>(params, q);
    px.facets = e.intermediates[0];
    px.p = e.intermediates[2];
    const double smooth = e.intermediates[6];
    px.level = o.chooser ? o.chooser(px.facets, px.p, o.chooser_tau)
                         : int(choose_kneiphof_klein_area_model_level(params, q, o.chooser_tau));
    if (px.level < 0 || px.level >= kBinomialLevels)
      throw std::invalid_argument("adequacy scenes: the chooser returned no level of the family");
    const auto chosen = BinomialLevel(px.level);
    M::Params<double> chosen_params = params;
    chosen_params.sampler = binomial_sampler_of(chosen);
    const int n = o.realisations;
    x.resize(std::size_t(n));
    ref.resize(std::size_t(n));
    std::size_t lit = 0;
    for (int j = 0; j < n; ++j) {
      ModelQuery<double> at = q;
      at.footprint.uv = realisation_uv(q.footprint.uv, j);
      ref[std::size_t(j)] = M::eval<double>(params, at).value;
      x[std::size_t(j)] = chosen == BinomialLevel::kExact    ? ref[std::size_t(j)]
                          : chosen == BinomialLevel::kSmooth ? smooth
                                                             : M::eval<double>(chosen_params, at).value;
      lit += ref[std::size_t(j)] != 0 ? 1 : 0;
    }
    score_pixel(px, x, ref, lit, radiance, chosen == BinomialLevel::kExact, pixel_decision,
                o.tau);
  });
}

// Realisation j of a Chermain pixel: j = 0 is the rendered pixel itself; the others move the
// footprint's centre along the R2 sequence over a square kChermainSpread cells of its coarser LOD
// wide (2^(⌊l_P⌋ + 1), chermain2021::lod), as the Chermain grid moves it: the model visits the
// 2 × 2 cells nearest the position at each LOD, so realisations must not share them.
Vec2<double> chermain_realisation_uv(const ModelQuery<double>& q, int j) {
  if (j == 0) return q.footprint.uv;
  const double cell = std::ldexp(1.0, int(std::floor(chermain2021::lod(q.footprint))) + 1);
  const Vec2<double> r = surface_position(j);
  return {q.footprint.uv.x + r.x * kChermainSpread * cell,
          q.footprint.uv.y + r.y * kChermainSpread * cell};
}

// The Chermain family's pixels: the chosen level (choose_chermain_model_level on the pixel's
// dict16_ggaa parameters, its GGAA derivatives those of the half vector, Eq. 21) against
// dict16_ggaa at the same realisations; a dictL level is the model with the first L dictionary
// levels (verify's chermain_level_dictionary), GGAA off or on; the smooth level the Gaussian of Σ
// (chermain_smooth_value, the same at every realisation).
template <class Shape>
void render_chermain_rows(const ChoiceScene& s, const SceneGeometry& g, const Shape& shape,
                          const SceneOptions& o, SceneRender& out) {
  using M = Chermain;
  const double density = std::pow(10.0, s.log10_density);
  std::vector<double> v;
  for (const ParamSpec& p : M::kParams) v.push_back(p.default_value);
  v[param_index<M>("alpha_x")] = kSceneAlpha;
  v[param_index<M>("alpha_y")] = kSceneAlpha;
  v[param_index<M>("density")] = density;
  v[param_index<M>("ggaa")] = double(chermain2021::kProjectedHalf);
  v[param_index<M>("seed")] = double(o.seed % 1000000000ULL);
  const M::Params<double> base = M::params<double>(v);
  for (int levels : {4, 8, 12, 16}) chermain_level_dictionary(levels);  // before the loop
  const Decision pixel_decision = decision_at_level(kPixelFlagRate / 2, o.tau);
  for_each_surface_pixel(g, shape, o, out,
                         [&](ScenePixel& px, ModelQuery<double>& q, double d2,
                             std::vector<double>& x, std::vector<double>& ref,
                             const PixelFootprint<double>& f) {
    const double irradiance = kLightIntensity / d2;
    M::Params<double> reference = base;
    reference.d = {f.dh_dx.x, f.dh_dx.y, f.dh_dy.x, f.dh_dy.y};
    px.facets = density * std::abs(q.footprint.duv_dx.x * q.footprint.duv_dy.y -
                                   q.footprint.duv_dx.y * q.footprint.duv_dy.x);
    px.p = 0;
    px.level = o.chermain_chooser ? o.chermain_chooser(reference, q, o.chooser_tau)
                                  : int(choose_chermain_model_level(reference, q, o.chooser_tau));
    px.predicted_adequate =
        adequacy_bits(chermain_level_adequacy(reference.sdf, reference.d, q, o.chooser_tau));
    if (px.level < 0 || px.level >= kChermainLevels)
      throw std::invalid_argument("adequacy scenes: the chooser returned no Chermain level");
    const auto chosen = ChermainLevel(px.level);
    M::Params<double> level = reference;
    if (chosen != ChermainLevel::kSmooth) {
      level.sdf.dictionary = &chermain_level_dictionary(chermain_dictionary_levels(chosen));
      level.sdf.kernel = chermain_level_ggaa(chosen) ? chermain2021::kProjectedHalf
                                                     : chermain2021::kNoGgaa;
    }
    const double smooth = chermain_smooth_value(reference, q);
    const int n = o.realisations;
    x.resize(std::size_t(n));
    ref.resize(std::size_t(n));
    std::size_t lit = 0;
    for (int j = 0; j < n; ++j) {
      ModelQuery<double> at = q;
      at.footprint.uv = chermain_realisation_uv(q, j);
      ref[std::size_t(j)] = M::eval<double>(reference, at).value;
      x[std::size_t(j)] = chosen == kChermainMostComplete ? ref[std::size_t(j)]
                          : chosen == ChermainLevel::kSmooth ? smooth
                                                             : M::eval<double>(level, at).value;
      lit += ref[std::size_t(j)] != 0 ? 1 : 0;
    }
    score_pixel(px, x, ref, lit, irradiance, chosen == kChermainMostComplete, pixel_decision,
                o.tau);
  });
}

template <class M>
void render_model(const ChoiceScene& s, const SceneGeometry& g, const SceneOptions& o,
                  SceneRender& out) {
  if (s.shape == SceneShape::kPlane)
    render_rows<M>(s, g, g.plane, o, out);
  else
    render_rows<M>(s, g, g.sphere, o, out);
}

void render_kemppinen(const ChoiceScene& s, const SceneGeometry& g, const SceneOptions& o,
                      SceneRender& out) {
  if (s.shape == SceneShape::kPlane)
    render_kemppinen_rows(s, g, g.plane, o, out);
  else
    render_kemppinen_rows(s, g, g.sphere, o, out);
}

}  // namespace

std::vector<ChoiceScene> choice_scenes() {
  // Densities put each scene's footprints on both sides of the smooth boundary
  // N_P p ≈ 1/(margin·TAU)² = 10^4: the planes' footprints span 4.7e-4 to 1.9 uv units² at 64
  // pixels (the spherical light's cone 1.1° to 3.7°); the sphere's about 3.5e-5/sin θ uv units²,
  // where kneiphof_klein's 0.26° cap gives p ≤ 2.2e-4 (its value at normal incidence).
  return {
      {"plane-point-low", "deliot_belcour", SceneShape::kPlane, SceneLight::kPoint, 6, "low"},
      {"plane-point-high", "deliot_belcour", SceneShape::kPlane, SceneLight::kPoint, 8, "high"},
      {"plane-area-low", "kneiphof_klein", SceneShape::kPlane, SceneLight::kSphereLight, 6, "low"},
      {"plane-area-high", "kneiphof_klein", SceneShape::kPlane, SceneLight::kSphereLight, 8,
       "high"},
      {"sphere-point-low", "kneiphof_klein", SceneShape::kSphere, SceneLight::kPoint, 10, "low"},
      {"sphere-point-high", "kneiphof_klein", SceneShape::kSphere, SceneLight::kPoint, 12, "high"},
  };
}

std::vector<ChoiceScene> kemppinen_choice_scenes() {
  // K_P spreads the footprints over the Kemppinen grid's range (k = 16 needed below about 100
  // points per footprint, the smooth level adequate from 10³ to 10⁵ on the grid, later off the
  // peak): at 24 pixels the plane's footprints span about 10⁻³ to 10 uv units², so 10 to 10⁵
  // points at K_P = 10⁴ and 10⁴ to 10⁸ at 10⁷; the sphere's some 10⁻⁴ uv units² and more, so
  // 10³ to 10⁶ points at 10⁷ and 10⁴ to 10⁷ at 10⁸ (the model's largest K_P).
  return {
      {"kemppinen-plane-low", "kemppinen_ggx", SceneShape::kPlane, SceneLight::kPoint, 4, "low"},
      {"kemppinen-plane-high", "kemppinen_ggx", SceneShape::kPlane, SceneLight::kPoint, 7, "high"},
      {"kemppinen-sphere-low", "kemppinen_ggx", SceneShape::kSphere, SceneLight::kPoint, 7, "low"},
      {"kemppinen-sphere-high", "kemppinen_ggx", SceneShape::kSphere, SceneLight::kPoint, 8,
       "high"},
  };
}

std::vector<ChoiceScene> area_choice_scenes() {
  // The plane's footprints (4.7e-4 to 1.9 uv units² at 64 pixels) at 10^6 and 10^8 facets per unit
  // area, as plane-area-low and -high: on both sides of the smooth boundary.
  // The sphere's footprints (about 3.5e-5/sin θ uv units² at 64 pixels, 1.4e-4/sin θ at 32, the
  // limb's larger) under the square light at kSphereSceneLight (some 3.6 units from the lit side:
  // a half-angle near 6°, so p reaches about 0.1 at the highlight, some 500 times kneiphof_klein's
  // 0.26° cap) at 10^8 and 10^10 facets per unit area: N_P p from a few to about 10^3 at 10^8 and
  // to about 10^5 at the highlight at 10^10, on both sides of the smooth boundary (10^4; measured
  // after declaring: the smooth level only at 10^10, realtime to exact at both).
  return {
      {"area-plane-rect-low", "kneiphof_klein_area", SceneShape::kPlane, SceneLight::kRectLight, 6,
       "low"},
      {"area-plane-rect-high", "kneiphof_klein_area", SceneShape::kPlane, SceneLight::kRectLight,
       8, "high"},
      {"area-sphere-rect-low", "kneiphof_klein_area", SceneShape::kSphere, SceneLight::kRectLight,
       8, "low", 1},
      {"area-sphere-rect-high", "kneiphof_klein_area", SceneShape::kSphere,
       SceneLight::kRectLight, 10, "high", 1},
  };
}

std::vector<ChoiceScene> chermain_choice_scenes() {
  // The plane's footprints (4.7e-4 to 1.9 uv units² at 64 pixels) at 10^6 microfacets per unit
  // area: about 500 to 2·10^6 per footprint (dict8 and dict12 by the construction); at 10^9: 5·10^5
  // to 2·10^9 (dict12, dict16 and the smooth level near its boundary, about 10^9).
  // The sphere under its point light at 100 times the planes' densities (its footprints, about
  // 3.5e-5/sin θ uv units² at 64 pixels and 1.4e-4/sin θ at 32, are smaller than the plane's
  // smallest): 10^8 and 10^11 microfacets per unit area. (Measured after declaring: the chooser
  // takes dict12_ggaa at 10^8 at 32 pixels, dict8_ggaa at 64; dict16_ggaa and the smooth level at
  // 10^11.)
  return {
      {"chermain-plane-low", "chermain", SceneShape::kPlane, SceneLight::kPoint, 6, "low"},
      {"chermain-plane-high", "chermain", SceneShape::kPlane, SceneLight::kPoint, 9, "high"},
      {"chermain-sphere-low", "chermain", SceneShape::kSphere, SceneLight::kPoint, 8, "low", 1},
      {"chermain-sphere-high", "chermain", SceneShape::kSphere, SceneLight::kPoint, 11, "high", 1},
  };
}

std::vector<std::array<std::size_t, 2>> declaration_order(
    const std::vector<std::vector<ChoiceScene>>& families) {
  std::vector<std::array<std::size_t, 2>> order;
  int last_round = 0;
  for (const auto& f : families)
    for (const ChoiceScene& s : f) last_round = std::max(last_round, s.round);
  for (int round = 0; round <= last_round; ++round)
    for (std::size_t f = 0; f < families.size(); ++f)
      for (std::size_t i = 0; i < families[f].size(); ++i)
        if (families[f][i].round == round) order.push_back({f, i});
  return order;
}

bool is_kemppinen_scene(const ChoiceScene& s) { return s.model == "kemppinen_ggx"; }
bool is_chermain_scene(const ChoiceScene& s) { return s.model == "chermain"; }
bool is_area_scene(const ChoiceScene& s) { return s.model == "kneiphof_klein_area"; }

int most_complete_level(const ChoiceScene& s) {
  return is_kemppinen_scene(s)  ? int(KemppinenLevel::kK16Exact)
         : is_chermain_scene(s) ? int(kChermainMostComplete)
                                : int(BinomialLevel::kExact);
}

SceneRender render_choice_scene(const ChoiceScene& scene, const SceneOptions& options) {
  if (options.width < 1 || options.height < 1 || options.realisations < 2)
    throw std::invalid_argument("adequacy scenes: the image needs a pixel and two realisations");
  SceneRender out;
  out.scene = scene;
  out.width = options.width;
  out.height = options.height;
  out.pixels.resize(std::size_t(options.width) * std::size_t(options.height));
  const SceneGeometry g = geometry(scene, options.width, options.height);
  if (scene.model == "deliot_belcour")
    render_model<DeliotBelcour>(scene, g, options, out);
  else if (scene.model == "kneiphof_klein")
    render_model<KneiphofKlein>(scene, g, options, out);
  else if (is_kemppinen_scene(scene))
    render_kemppinen(scene, g, options, out);
  else if (is_chermain_scene(scene) && scene.shape == SceneShape::kPlane)
    render_chermain_rows(scene, g, g.plane, options, out);
  else if (is_chermain_scene(scene))
    render_chermain_rows(scene, g, g.sphere, options, out);
  else if (is_area_scene(scene) && scene.shape == SceneShape::kPlane)
    render_area_rows(scene, g, g.plane, options, out);
  else if (is_area_scene(scene))
    render_area_rows(scene, g, g.sphere, options, out);
  else
    throw std::invalid_argument(
        "adequacy scenes: not a model of the binomial, Kemppinen, area or Chermain family: " +
        scene.model);
  return out;
}

SafetyTally tally(const SceneRender& r) {
  SafetyTally t;
  const int complete = most_complete_level(r.scene);
  for (const ScenePixel& p : r.pixels) {
    if (!p.lit) continue;
    ++t.lit;
    ++t.by_level[std::size_t(p.level)];
    t.cheaper += p.level != complete ? 1 : 0;
    t.exceeds += p.exceeds ? 1 : 0;
  }
  return t;
}

void add(SafetyTally& into, const SafetyTally& t) {
  into.lit += t.lit;
  into.cheaper += t.cheaper;
  into.exceeds += t.exceeds;
  for (std::size_t l = 0; l < into.by_level.size(); ++l) into.by_level[l] += t.by_level[l];
}

SafetyDecision decide_choice_safety(const SafetyTally& t, double alpha) {
  SafetyDecision d;
  if (t.lit == 0) return d;  // nothing measured: inconclusive
  const boost::math::binomial_distribution<double> h0(double(t.lit), kPixelFlagRate);
  const auto upper_tail = [&](std::uint64_t k) {  // P(X >= k)
    return k == 0 ? 1.0 : boost::math::cdf(boost::math::complement(h0, double(k - 1)));
  };
  d.fraction = double(t.exceeds) / double(t.lit);
  d.p_value = upper_tail(t.exceeds);
  std::uint64_t k = std::uint64_t(std::floor(double(t.lit) * kPixelFlagRate));
  while (k < t.lit && upper_tail(k + 1) >= alpha) ++k;
  d.allowed = k;
  d.allowed_fraction = double(k) / double(t.lit);
  d.verdict = t.exceeds <= d.allowed ? Verdict::kHoldsInRegime : Verdict::kFails;
  return d;
}

}  // namespace glintlab::verify::adequacy

// Kneiphof & Klein 2024 Sec. 4 with Heitz et al. 2016 LTCs: p_Ωh = D_Ωh/D_H over a polygonal area
// light with D_Ωh ≈ D_PR · ∫_Ωi D_ltc dω (Eq. 12–13, 17–19, "LTC Scale"), L_o by the BRDF LTC lobe,
// the radiance L̂ = L_o·b/(N_P p) (Eq. 16); and the model kneiphof_klein_area (a rectangular light).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <string_view>
#include <type_traits>

#include "core/glints/kneiphof.h"
#include "core/lights/polygon_light_check.h"
#include "core/ltc/ltc.h"
#include "core/ltc/ltc_table.h"

namespace glintlab::kneiphof2024 {

// How D_Ωh (Eq. 13) is obtained over a polygon. kBrdfLobe: the BRDF·cos LTC lobe, the same one
// that gives L_o, scaled by D_PR (the paper's choice, Sec. 4 and Eq. 17: it makes the model
// invariant under subdivision, App. C). kNdfLobe: the separately fitted NDF lobe scaled by D_PR
// ("+ NDF LTC" of Table 1, Fig. 8). kMonteCarlo: area_light_terms_mc, the reference.
enum class AreaP : int { kBrdfLobe = 0, kNdfLobe = 1, kMonteCarlo = 2 };
inline constexpr std::array<std::string_view, 3> kAreaPNames = {"ltc", "ltc_ndf", "mc"};
// How L_o/L_i = ∫_Ωi ρ̃ dω (Eq. 3, 15) is obtained: the BRDF LTC lobe × albedo, or Monte Carlo.
inline constexpr std::array<std::string_view, 2> kAreaLoNames = {"ltc", "mc"};

template <class T>
struct LtcAreaTerms {
  T d_omega_h = T(0);   // D_PR · ∫_Ωi D_ltc (Eq. 13 through Sec. 4's LTC scale)
  T lo_over_li = T(0);  // albedo · ∫_Ωi D_ltc,brdf (Heitz et al. 2016 Eq. 10, F = 1)
  T d_pr = T(0);        // Eq. 19, from the table
  T albedo = T(0);      // Eq. 18 (FGD with F = 1), from the table
};

// The LTC terms for isotropic GGX α, viewer wi (unit, shading frame) and a convex polygon given by
// its vertices relative to the shading point (counter-clockwise seen from it: the emitting side),
// clipped at the horizon. `lobe` picks the shape of D_Ωh's lobe (kMonteCarlo is not an LTC: it is
// treated as kBrdfLobe here). `amplitude_override` > 0 replaces D_PR as the scale (the claim's
// negative control: the unscaled or albedo-scaled lobe). Scalar T: the table lookup is per lane.
template <class T>
LtcAreaTerms<T> area_light_terms_ltc(const LtcTableView& table, T alpha, Vec3<T> wi,
                                     const Vec3<T>* vertices, int n, AreaP lobe,
                                     T amplitude_override = T(0)) {
  LtcAreaTerms<T> t;
  if (!(wi.z > T(0))) return t;
  const LtcGgxLookup<T> l = ltc_ggx_lookup(table, alpha, wi);
  const T brdf = ltc_polygon_integral(l.brdf, vertices, n);
  const T shape = lobe == AreaP::kNdfLobe ? ltc_polygon_integral(l.ndf, vertices, n) : brdf;
  t.d_pr = l.ndf.amplitude;
  t.albedo = l.brdf.amplitude;
  t.d_omega_h = (amplitude_override > T(0) ? amplitude_override : t.d_pr) * shape;
  t.lo_over_li = t.albedo * brdf;
  return t;
}

// A w × h rectangle centred at distance d along the unit direction `dir` from the shading point,
// facing it, turned by `rotation` about dir and tilted by `tilt` (|tilt| < π/2) about its width
// axis; vertices counter-clockwise seen from the shading point. Always planar, convex and
// non-degenerate for w, h, d > 0, and the shading point is in front (distance d cos tilt).
inline std::array<Vec3<double>, 4> facing_rectangle(Vec3<double> dir, double d, double w, double h,
                                                    double rotation, double tilt) {
  // t1 × t2 = −dir, so (−,−), (+,−), (+,+), (−,+) along (e_w, e_h) winds about −dir.
  const Vec3<double> up = std::abs(dir.z) < 0.999 ? Vec3<double>{0, 0, 1} : Vec3<double>{1, 0, 0};
  const Vec3<double> t1 = normalize(cross(up, dir)), t2 = cross(t1, dir);
  const double cr = std::cos(rotation), sr = std::sin(rotation);
  const Vec3<double> ew = cr * t1 + sr * t2, eh0 = cr * t2 - sr * t1;
  const Vec3<double> eh = std::cos(tilt) * eh0 + std::sin(tilt) * dir;
  const Vec3<double> c = d * dir, a = 0.5 * w * ew, b = 0.5 * h * eh;
  return {c - a - b, c + a - b, c + a + b, c - a + b};
}

// The polygon light of a rectangle from facing_rectangle without make_polygon_light's checks
// (which throw): fields as make_polygon_light fills them, for a rectangle known to be valid.
inline PolygonLight<double> rectangle_polygon_light(const std::array<Vec3<double>, 4>& v) {
  PolygonLight<double> l{};
  l.count = 4;
  for (int k = 0; k < 4; ++k) l.vertex[k] = v[std::size_t(k)];
  const Vec3<double> n = cross(v[1] - v[0], v[2] - v[1]);
  l.normal = normalize(n);
  l.area = length(n);
  l.fan_cdf[0] = 0.5;  // the two fan triangles of a parallelogram have equal areas
  l.fan_cdf[1] = 1.0;
  l.emitted = {1, 1, 1};
  l.sampling = AreaSampling::kSolidAngle;
  return l;
}

// --- The model: polygonal (rectangular) area lights (Sec. 4) -------------------------------------

struct KneiphofKleinArea {
  static constexpr std::string_view kName = "kneiphof_klein_area";
  // Conformance (verify/conformance/): what the model does not claim.
  static constexpr std::array<NotClaimed, 3> kNotClaimed = {{
      {"float-vs-double", "double only (kDoubleOnly): the LTC table lookup is scalar double"},
      {"simd-equivalence",
       "not batched (kBatched = false): its batches are a loop over the double thunks, so there is "
       "no SIMD instantiation to compare"},
      {"converges-to-smooth",
       "its smooth limit is GGX integrated over the rectangle light (the LTC polygon integral), "
       "which no registered model evaluates; smooth_ggx is a point-light model"},
  }};
  static constexpr std::string_view kDescription =
      "Kneiphof & Klein 2024 binomial glints under a rectangular area light (Sec. 4): the "
      "rectangle is centred along the query's wo at light_distance, facing the shading point "
      "(turned by light_rotation_deg, tilted by light_tilt_deg); p = D_Omega_h/D_H (Eq. 12) with "
      "D_Omega_h = D_PR x the LTC lobe's polygon integral (area_p=ltc: the BRDF lobe, the paper's "
      "choice; ltc_ndf: the separately fitted NDF lobe, '+ NDF LTC') or Monte Carlo (mc, "
      "mc_samples solid-angle samples); clamped to [0, 1], b ~ Binomial(N_P, p); value = L_o/L_i "
      "x b/(N_P p) (Eq. 16), L_o/L_i the BRDF (F = 1) integrated over the light (area_lo: LTC or "
      "Monte Carlo), NOT per steradian; isotropic GGX only (the LTC tables, as the paper); no "
      "glint sampler in the paper: samples the smooth VNDF (Heitz 2018) and returns its pdf";
  static constexpr std::string_view kSource =
      "Kneiphof & Klein 2024 Eq. 12-19 (Sec. 4), Eq. 16; Heitz, Dupuy, Hill, Neubelt 2016 LTC "
      "(core/ltc); D_H by Eq. 29";
  static constexpr unsigned kNeeds = kNeedsFootprint | kNeedsAreaLight;
  static constexpr bool kDoubleOnly = true;  // the LTC table lookup is scalar double
  static constexpr bool kBatched = false;    // (so the batch API loops over its thunks)
  static constexpr std::array<ParamSpec, 12> kParams = {{
      {"alpha", 0.25, kLtcMinAlpha, 1.0, false, false,
       "isotropic GGX roughness (the LTC tables cover sqrt(alpha) in [0, 1])"},
      kBinomialGlintDensity,
      {"light_distance", 1.0, 0.01, 100.0, false, false,
       "distance from the shading point to the rectangle's centre (along wo)"},
      {"light_width", 0.5, 1e-4, 100.0, false, false, "the rectangle's width (same units)"},
      {"light_height", 0.5, 1e-4, 100.0, false, false, "the rectangle's height (same units)"},
      {"light_rotation_deg", 0.0, -180.0, 180.0, false, false,
       "rotation of the rectangle about wo, degrees"},
      {"light_tilt_deg", 0.0, -90.0, 90.0, true, true,
       "tilt of the rectangle about its width axis away from facing the point, degrees"},
      {"area_p", 0.0, 0.0, 2.0, false, false,
       "D_Omega_h: ltc (BRDF LTC lobe x D_PR, the paper's), ltc_ndf (NDF LTC lobe x D_PR), mc",
       kAreaPNames},
      {"area_lo", 0.0, 0.0, 1.0, false, false,
       "L_o/L_i: ltc (BRDF LTC lobe x albedo) or mc (Monte Carlo)", kAreaLoNames},
      {"mc_samples",
       256.0,
       1.0,
       1048576.0,
       false,
       false,
       "solid-angle samples of the Monte Carlo terms (integer)",
       {},
       true},
      kBinomialGlintSampler,
      kBinomialGlintSeed,
  }};
  static constexpr std::array<std::string_view, 11> kIntermediates = {
      "N_P",    "p_unclamped", "p",    "p_clamped", "count",      "factor",
      "smooth", "D_Omega_h",   "D_PR", "D_H",       "solid_angle"};

  template <class T>
  struct Params {
    double alpha, log10_density, distance, width, height, rotation, tilt, total_area;
    AreaP area_p;
    bool lo_mc;
    int mc_samples;
    BinomialSampler sampler;
    std::uint64_t seed;
    const LtcTableView* table;
  };

  template <class T>
  static Params<T> params(std::span<const double> v) {
    const double deg = std::numbers::pi / 180;
    using M = KneiphofKleinArea;
    return {v[param_index<M>("alpha")],
            v[param_index<M>("density")],
            v[param_index<M>("light_distance")],
            v[param_index<M>("light_width")],
            v[param_index<M>("light_height")],
            v[param_index<M>("light_rotation_deg")] * deg,
            v[param_index<M>("light_tilt_deg")] * deg,
            total_area_ggx_eq29(v[param_index<M>("alpha")]),
            static_cast<AreaP>(int(v[param_index<M>("area_p")])),
            int(v[param_index<M>("area_lo")]) == 1,
            int(v[param_index<M>("mc_samples")]),
            static_cast<BinomialSampler>(int(v[param_index<M>("binomial")])),
            static_cast<std::uint64_t>(v[param_index<M>("seed")]),
            &ltc_ggx_table_view()};
  }

  template <class T>
  static T pdf(const Params<T>& p, const ModelQuery<T>& q) {
    return pdf_heitz_vndf(GGX<T>{T(p.alpha), T(p.alpha)}, q.wi, q.wo);
  }

  template <class T>
  static ModelEval<T, kIntermediates.size()> eval(const Params<T>& p, const ModelQuery<T>& q) {
    static_assert(std::is_same_v<T, double>, "kneiphof_klein_area is double only");
    const GGX<double> ggx{p.alpha, p.alpha};
    const auto rect = facing_rectangle(q.wo, p.distance, p.width, p.height, p.rotation, p.tilt);
    const PolygonLight<double> light = rectangle_polygon_light(rect);
    const Vec3<double> origin{0, 0, 0};
    const std::uint64_t index = footprint_rng_index(q.footprint);
    const bool need_mc = p.area_p == AreaP::kMonteCarlo || p.lo_mc;
    const AreaLightTerms mc =
        need_mc ? area_light_terms_mc(ggx, q.wi, light, origin, p.mc_samples, p.seed + 1, index)
                : AreaLightTerms{};
    const LtcAreaTerms<double> ltc =
        area_light_terms_ltc(*p.table, p.alpha, q.wi, rect.data(), 4, p.area_p);
    const double d_omega_h = p.area_p == AreaP::kMonteCarlo ? mc.d_omega_h : ltc.d_omega_h;
    const double smooth = p.lo_mc ? mc.lo_over_li : ltc.lo_over_li;
    const double p_raw = q.wi.z > 0 ? d_omega_h / p.total_area : 0.0;
    const BinomialGlintCount<double> b = binomial_glint_count(
        q.footprint, facet_density_scale<double>(p.log10_density), p_raw, p.sampler, p.seed);
    return {smooth * b.factor,
            pdf(p, q),
            {b.n, p_raw, b.p, p_raw > 1 ? 1.0 : 0.0, b.count, b.factor, smooth, d_omega_h, ltc.d_pr,
             p.total_area, light.solid_angle(origin)}};
  }

  template <class T>
  static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    const MicrofacetSample<T> s = sample_heitz_vndf(GGX<T>{T(p.alpha), T(p.alpha)}, q.wi, u);
    ModelQuery<T> at = q;
    at.wo = s.wo;
    const T value = s.rejected ? T(0) : eval(p, at).value;
    return {s.wo, s.pdf, s.rejected ? T(0) : safe_div(value, s.pdf), s.rejected};
  }
};

static_assert(Model<KneiphofKleinArea>);

}  // namespace glintlab::kneiphof2024

namespace glintlab {
// Registered models are named in namespace glintlab, like every other model (core/model_list.h).
using kneiphof2024::KneiphofKleinArea;
}  // namespace glintlab

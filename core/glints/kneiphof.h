// Kneiphof & Klein 2024, "Real-Time Rendering of Glints in the Presence of Area Lights": the
// discrete NDF D̂_P (Eq. 6, 10), the reflection probability p_Ωh = D_Ωh/D_H (Eq. 12–13), its
// spherical-cap form for point/directional lights (Eq. 20) with the radiance of Eq. 16 / Eq. 22,
// the Monte Carlo D_Ωh and L_o over a polygonal light, and the multinomial split of a count over a
// subdivided light (App. C, Eq. 33–39). The LTC form of D_Ωh (Eq. 12–19) is in
// core/glints/kneiphof_ltc.h.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <string_view>
#include <vector>

#include "core/glints/binomial.h"
#include "core/glints/deliot_belcour.h"
#include "core/lights/polygon_light.h"
#include "core/lights/spherical_cap.h"
#include "core/model.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/ndf/total_area.h"
#include "core/samplers/heitz_vndf.h"

namespace glintlab::kneiphof2024 {

// --- Discrete NDF (Eq. 6): N_P facets drawn from D/D_H
// --------------------------------------------

namespace detail {
// I(c) = ∫_0^c dt/(1 + k t²)², k = α² − 1: the isotropic GGX mass 2α² I(c) of the directions with
// cos θ ≤ c (D dω = α² 2π dc/(π(1 + k c²)²)); 2α² I(1) = D_H, Eq. 29.
inline double ggx_cos_mass(double alpha, double c) {
  const double k = alpha * alpha - 1;
  double a;
  if (std::abs(k) < 1e-12)
    a = c;
  else if (k > 0)
    a = std::atan(std::sqrt(k) * c) / std::sqrt(k);
  else
    a = std::atanh(std::sqrt(-k) * c) / std::sqrt(-k);
  return 0.5 * (c / (1 + k * c * c) + a);
}
}  // namespace detail

// One facet normal h ~ D(h)/D_H dω of isotropic GGX (Eq. 6: h^(k) ∝ D(h^(k))/D_H, the NDF itself,
// not the projected D cos θ), by inverting the mass in cos θ (bisection to double precision) and
// a uniform azimuth. u in [0, 1)². Host-side.
inline Vec3<double> sample_discrete_ndf_facet(double alpha, Vec2<double> u) {
  const double total = detail::ggx_cos_mass(alpha, 1);
  const double target = u.x * total;  // the mass below cos θ = c is I(c)
  double lo = 0, hi = 1;
  for (int i = 0; i < 64; ++i) {
    const double mid = 0.5 * (lo + hi);
    (detail::ggx_cos_mass(alpha, mid) < target ? lo : hi) = mid;
  }
  const double c = 0.5 * (lo + hi), s = std::sqrt(std::max(0.0, 1 - c * c));
  const double phi = 2 * std::numbers::pi * u.y;
  return {s * std::cos(phi), s * std::sin(phi), c};
}

// ∫_A D̂_P dh = (D_H/N_P)·#{k : h^(k) ∈ A} (Eq. 10) for a count of facets in A.
inline double discrete_ndf_integral(double total_area, std::uint64_t n, std::uint64_t in_a) {
  return n == 0 ? 0.0 : total_area * double(in_a) / double(n);
}

// --- Spherical cap lights (Sec. 5) -------------------------------------------------------------

// Eq. 20: p_Ωh ≈ |Ω_i|·D(h)/(D_H·4⟨h, ω_l⟩), |Ω_i| = 2π(1 − cos γ), the NDF taken constant over the
// cap around the light direction ω_l (our query's wo). Unclamped: p > 1 where the assumption fails.
template <class Ndf, class T>
GLINTLAB_FN T cap_probability_eq20(const Ndf& ndf, Vec3<T> wi, Vec3<T> wl, T one_minus_cos_gamma,
                                   T total_area) {
  const Vec3<T> h = half_vector(wi, wl);
  const T solid = T(2 * kPi<T>) * one_minus_cos_gamma;
  return safe_div(solid * ndf.D(h), total_area * T(4) * max(dot(h, wl), T(0)));
}

// Eq. 22 over the light's irradiance E: G2/⟨n, ω_v⟩ · D_H ⟨h, ω_l⟩/|Ω_i| · b/N_P (F = 1), ω_v the
// viewer (our wi). Equal to smooth·b/(N_P p) with Eq. 20's p (Eq. 21), unclamped.
template <class Ndf, class T>
GLINTLAB_FN T cap_radiance_eq22(const Ndf& ndf, Vec3<T> wi, Vec3<T> wl, T one_minus_cos_gamma,
                                T total_area, T count, T n) {
  const Vec3<T> h = half_vector(wi, wl);
  const T g2 = smith_g2_height_correlated(ndf, wi, wl, h);
  const T solid = T(2 * kPi<T>) * one_minus_cos_gamma;
  const T lit = select(wi.z > T(0) && wl.z > T(0), T(1), T(0));
  return lit * safe_div(g2 * total_area * max(dot(h, wl), T(0)) * safe_div(count, n), wi.z * solid);
}

// --- Polygonal area lights: Monte Carlo terms (Eq. 3, 13) ----------------------------------------

// For a light seen from the shading point p (world axes = the local shading frame, z the normal):
// D_Ωh = ∫_Ωi D(h)/(4⟨h, ω⟩) dω (Eq. 13) and L_o/L_i = ∫_Ωi ρ(ω, ω_v)⟨n, ω⟩ dω (Eq. 3, F = 1), both
// by the same uniform solid-angle samples of the polygon (Arvo 1995 per fan triangle), keyed by
// (seed, index dims).
struct AreaLightTerms {
  double d_omega_h = 0;   // D_Ωh
  double lo_over_li = 0;  // ∫ ρ̃ dω
  double solid_angle = 0;
};

inline AreaLightTerms area_light_terms_mc(const GGX<double>& ggx, Vec3<double> wi,
                                          const PolygonLight<double>& light, Vec3<double> origin,
                                          int samples, std::uint64_t seed, std::uint64_t index) {
  AreaLightTerms t;
  t.solid_angle = light.solid_angle(origin);
  if (samples <= 0 || !(t.solid_angle > 0) || wi.z <= 0) return t;
  double sd = 0, sl = 0;
  for (int s = 0; s < samples; ++s) {
    // Stratified in u.x (s/samples + jitter): a lower-variance estimate at the same cost.
    const double ux = (s + counter_uniform<double>(seed, index, 2 * std::uint64_t(s))) / samples;
    const double uy = counter_uniform<double>(seed, index, 2 * std::uint64_t(s) + 1);
    const LightSample<double> ls = light.sample(origin, Vec2<double>{ux, uy});
    if (!ls.valid || ls.wi.z <= 0) continue;
    const Vec3<double> h = half_vector(wi, ls.wi);
    sd += ggx.D(h) / (4 * dot(h, ls.wi)) / ls.pdf;
    sl += microfacet_brdf(ggx, wi, ls.wi, 1.0) * ls.wi.z / ls.pdf;
  }
  t.d_omega_h = sd / samples;
  t.lo_over_li = sl / samples;
  return t;
}

// A convex planar quad split into nu × nv bilinear sub-quads (App. C's 2^4 × 2^4): each is planar
// (in the quad's plane) and convex, and together they partition the quad. Vertices v0..v3 in order.
inline std::vector<std::array<Vec3<double>, 4>> subdivide_quad(const std::array<Vec3<double>, 4>& v,
                                                               int nu, int nv) {
  auto at = [&](double a, double b) {
    return (1 - a) * (1 - b) * v[0] + a * (1 - b) * v[1] + a * b * v[2] + (1 - a) * b * v[3];
  };
  std::vector<std::array<Vec3<double>, 4>> out;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double a0 = double(i) / nu, a1 = double(i + 1) / nu;
      const double b0 = double(j) / nv, b1 = double(j + 1) / nv;
      out.push_back({at(a0, b0), at(a1, b0), at(a1, b1), at(a0, b1)});
    }
  return out;
}

// App. C: b facets reflecting from the whole light split over its K parts, a facet of the light
// falling in part k with probability p_k/p (Eq. 33; the parts partition Ω_h, Σ p_k = p), as a
// chain of conditional binomials: b_k ~ Binomial(b − Σ_{j<k} b_j, p_k/(p − Σ_{j<k} p_j)). Then
// (b_1..b_K) is multinomial and each b_k is marginally Binomial(N_P, p_k) (Eq. 34). Exact sampler;
// part k uses index·K + k of the counter RNG.
inline std::vector<std::uint64_t> multinomial_split(std::uint64_t b, std::span<const double> parts,
                                                    std::uint64_t seed, std::uint64_t index) {
  double rest = 0;
  for (double p : parts) rest += p;
  std::vector<std::uint64_t> out(parts.size(), 0);
  std::size_t last = 0;  // the last part with p_k > 0 takes what rounding left over
  for (std::size_t k = 0; k < parts.size(); ++k)
    if (parts[k] > 0) last = k;
  std::uint64_t left = b;
  for (std::size_t k = 0; k <= last && left > 0; ++k) {
    const double q = k == last ? 1.0 : std::min(1.0, parts[k] / rest);
    out[k] = binomial_exact(left, q, seed, index * parts.size() + k);
    left -= out[k];
    rest -= parts[k];
    if (!(rest > 0)) rest = 0;
  }
  return out;
}

// --- The model: point and directional lights through a cap (Sec. 5) -----------------------------

struct KneiphofKlein {
  static constexpr std::string_view kName = "kneiphof_klein";
  // The smooth model its footprint average tends to (conformance: converges-to-smooth).
  static constexpr std::string_view kSmoothLimit = "smooth_ggx";
  static constexpr std::string_view kDescription =
      "Kneiphof & Klein 2024 binomial glints for point/directional lights as spherical caps: "
      "p = |Omega| D(h)/(D_H 4 <h, wl>) (Eq. 20), clamped to [0, 1], b ~ Binomial(N_P, p), value = "
      "smooth GGX (F = 1) x b/(N_P p) (Eq. 16; = Eq. 22 where unclamped); the cap's half-angle is "
      "the query light's when it has one, else gamma_deg; no glint sampler in the paper: samples "
      "the smooth VNDF (Heitz 2018) and returns its pdf";
  static constexpr std::string_view kSource =
      "Kneiphof & Klein 2024 Eq. 6, 11-12, 16, 20-22; D_H by Eq. 29 (anisotropic: its azimuthal "
      "average)";
  static constexpr unsigned kNeeds = kNeedsFootprint | kNeedsPointLight;
  static constexpr std::array<ParamSpec, 6> kParams = binomial_glint_params(
      {"gamma_deg", 0.26, 0.0, 90.0, true, true,
       "half-angle of the cap a delta light is widened to, degrees (Sec. 5)"});
  static constexpr std::array<std::string_view, 10> kIntermediates = {
      "N_P", "p_unclamped", "p", "p_clamped", "count", "factor", "smooth", "D_H", "gamma", "eq22"};

  template <class T>
  struct Params {
    GGX<T> ggx;
    T log10_density, one_minus_cos_gamma, total_area;
    BinomialSampler sampler;
    std::uint64_t seed;
    T density_scale;  // 10^log10_density (facet_density_scale)
  };

  template <class T>
  static Params<T> params(std::span<const double> v) {
    const GGX<double> g{v[param_index<KneiphofKlein>("alpha_x")],
                        v[param_index<KneiphofKlein>("alpha_y")]};
    const double density = v[param_index<KneiphofKlein>("density")];
    return {GGX<T>{T(g.alpha_x), T(g.alpha_y)},
            T(density),
            T(one_minus_cos(v[param_index<KneiphofKlein>("gamma_deg")] * std::numbers::pi / 180)),
            T(total_area(g)),
            static_cast<BinomialSampler>(int(v[param_index<KneiphofKlein>("binomial")])),
            static_cast<std::uint64_t>(v[param_index<KneiphofKlein>("seed")]),
            facet_density_scale<T>(density)};
  }

  template <class T>
  GLINTLAB_FN static T pdf(const Params<T>& p, const ModelQuery<T>& q) {
    return pdf_heitz_vndf(p.ggx, q.wi, q.wo);
  }

  template <class T>
  GLINTLAB_FN static ModelEval<T, kIntermediates.size()> eval(const Params<T>& p,
                                                              const ModelQuery<T>& q) {
    // The query's cone when it has one (cos γ < 1), else the parameter's cap.
    const T omc =
        select(q.light.cos_half_angle < T(1), T(1) - q.light.cos_half_angle, p.one_minus_cos_gamma);
    const T smooth = microfacet_brdf(p.ggx, q.wi, q.wo, T(1)) * max(q.wo.z, T(0));
    const T p_raw = cap_probability_eq20(p.ggx, q.wi, q.wo, omc, p.total_area);
    const BinomialGlintCount<T> b =
        binomial_glint_count(q.footprint, p.density_scale, p_raw, p.sampler, p.seed);
    const T gamma = T(2) * atan2(sqrt(T(0.5) * omc), safe_sqrt(T(1) - T(0.5) * omc));
    return {
        smooth * b.factor,
        pdf(p, q),
        {b.n, p_raw, b.p, select(p_raw > T(1), T(1), T(0)), b.count, b.factor, smooth, p.total_area,
         gamma, cap_radiance_eq22(p.ggx, q.wi, q.wo, omc, p.total_area, b.count, b.n)}};
  }

  template <class T>
  GLINTLAB_FN static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    return sample_binomial_glints_vndf<KneiphofKlein>(p, q, u);
  }
};

static_assert(Model<KneiphofKlein>);

}  // namespace glintlab::kneiphof2024

namespace glintlab {
// Registered models are named in namespace glintlab, like every other model (core/model_list.h).
using kneiphof2024::KneiphofKlein;
}  // namespace glintlab

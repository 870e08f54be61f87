// Fitting LTC lobes to GGX targets (Heitz, Dupuy, Hill, Neubelt 2016 Sec. 4), the albedo/Fresnel
// cubature and D_PR (Kneiphof & Klein 2024 Eq. 19): see ltc_fit.h.
#include "core/ltc/ltc_fit.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/parameter_check.h"
#include "core/samplers/heitz_vndf.h"
#include "core/samplers/walter.h"
#include "core/simd/batch.h"

namespace glintlab {
namespace {

using V = Vec3<double>;
constexpr double kPiD = std::numbers::pi;

V view_dir(double theta_o) { return {std::sin(theta_o), 0.0, std::cos(theta_o)}; }

LtcLobe<double> lobe_of(const LtcCoefficients& c) {
  return make_ltc_lobe_isotropic(c.m00, c.m02, c.m20, c.m22, 1.0);
}

// The target's sampler: a direction and its density over the whole sphere (the pdf functions
// are defined everywhere, so a sample below the horizon still counts in the MIS sums, with
// target value 0).
struct TargetSample {
  V dir;
  double pdf;
};

TargetSample sample_target(LtcTarget target, const GGX<double>& ggx, V wo, Vec2<double> u) {
  if (target == LtcTarget::kBrdf) {
    const V m = sample_normal_heitz_vndf(ggx, wo, u);
    const V wi = reflect(wo, m);
    return {wi, pdf_heitz_vndf(ggx, wo, wi)};
  }
  const V m = sample_normal_walter(ggx, u);
  const V wi = reflect(wo, m);
  return {wi, pdf_walter(ggx, wo, wi)};
}

double target_norm(LtcTarget target, double alpha, double theta_o) {
  const double c = std::cos(theta_o);
  return target == LtcTarget::kBrdf ? ggx_ltc_albedo(alpha, c).albedo : ggx_d_pr(alpha, c);
}

// The parts of the MIS estimator that do not depend on the lobe, computed once per fitted entry
// (Nelder–Mead evaluates the objective hundreds of times for one entry): the target sampler's
// points with their densities and target values, and the cosine directions the lobe's sampler
// maps. Every value comes from the same expressions as when everything is evaluated per call, so
// the sums, and the fitted tables, are the same bits.
struct MisGrid {
  LtcTarget target;
  double alpha;
  GGX<double> ggx;
  V wo;
  double inv_norm;
  int samples;
  // The view's terms of the BRDF and of its VNDF density: Λ(ω_o) and A(ω_o).
  double lambda_wo, view_area;
  // Per midpoint (a, b), a-major: the clamped-cosine direction before M (ltc_sample's first half).
  std::vector<V> cosine_dir;
  // The target sampler's direction, density, value · inv_norm, and whether it counts (pdf > 0
  // and finite).
  std::vector<V> target_dir;
  std::vector<double> target_pdf_at, target_value_at, target_raw_value;
  std::vector<unsigned char> target_counts;
};

MisGrid make_mis_grid(LtcTarget target, double alpha, double theta_o, double norm, int samples) {
  MisGrid g{target, alpha, GGX<double>{alpha, alpha}, view_dir(theta_o),
            norm > 0 ? 1.0 / norm : 0.0, samples, 0.0, 0.0, {}, {}, {}, {}, {}, {}};
  g.lambda_wo = g.ggx.lambda(g.wo);
  g.view_area = g.ggx.projected_area(g.wo);
  const std::size_t count = std::size_t(samples) * samples;
  g.cosine_dir.resize(count), g.target_dir.resize(count), g.target_pdf_at.resize(count);
  g.target_value_at.resize(count), g.target_raw_value.resize(count), g.target_counts.resize(count);
  for (int a = 0; a < samples; ++a)
    for (int b = 0; b < samples; ++b) {
      const std::size_t k = std::size_t(a) * samples + b;
      const Vec2<double> u{(a + 0.5) / samples, (b + 0.5) / samples};
      // ltc_sample's cosine-distributed direction (Malley's method), as core/ltc/ltc.h forms it.
      double s, c;
      sincos(2 * kPiD * u.y, &s, &c);
      const double r = sqrt(u.x);
      g.cosine_dir[k] = V{r * c, r * s, safe_sqrt(1.0 - u.x)};
      const TargetSample t = sample_target(target, g.ggx, g.wo, u);
      g.target_dir[k] = t.dir;
      g.target_pdf_at[k] = t.pdf;
      g.target_counts[k] = t.pdf > 0 && std::isfinite(t.pdf);
      g.target_raw_value[k] = ltc_target_value(target, alpha, g.wo, t.dir);
      g.target_value_at[k] = g.target_raw_value[k] * g.inv_norm;
    }
  return g;
}

// ltc_sample (core/ltc/ltc.h) from its precomputed cosine direction: ω = Mω_o/|Mω_o| and its
// density, the same operations in the same order.
GLINTLAB_INLINE LtcSample<double> ltc_sample_from_cosine(const LtcLobe<double>& lobe, V cosine_dir) {
  const V v = ltc_mul(lobe.m, cosine_dir);
  const double l2 = dot(v, v);
  const V w = rsqrt(select(l2 > 0.0, l2, 1.0)) * v;
  return {w, ltc_density(lobe, w)};
}

// The target's value and its sampler's density at ω_i, as ltc_target_value and pdf_heitz_vndf /
// pdf_walter give them, with what the two share computed once: the half vector (ω_i + ω_o or ω_o + ω_i, the same
// sums) normalized by 1/√l2 in both, and D of it; the view's Λ and A from the grid.
struct TargetAt {
  double value, pdf;
};

GLINTLAB_INLINE TargetAt target_at(const MisGrid& g, V wi) {
  const V sum = wi + g.wo;
  const double l2 = dot(sum, sum);
  const bool above = wi.z > 0 && g.wo.z > 0;
  if (g.target == LtcTarget::kBrdf) {
    // microfacet_brdf's half_vector and pdf_vndf_reflection's D(h)/(4 A(ω_o)) (core/samplers).
    const V h = (l2 > 0 ? rsqrt(l2) : 0.0) * sum;
    const double d = g.ggx.D(h);
    const double pdf = g.view_area > 0 ? d / (4.0 * g.view_area) : 0.0;
    if (!above) return {0.0, pdf};
    // Height-correlated G2 (Heitz 2014 Eq. 99) and F G2 D/(4 ω_i.z ω_o.z) · ω_i.z with F = 1.
    const bool visible = dot(wi, h) > 0 && dot(g.wo, h) > 0;
    const double g2 = visible ? 1.0 / (1.0 + g.ggx.lambda(wi) + g.lambda_wo) : 0.0;
    const double denom = 4.0 * (wi.z * g.wo.z);
    return {1.0 * g2 * d / denom * wi.z, pdf};
  }
  // pdf_walter's D(h⁺) h⁺.z/(2|ω_o + ω_i|); above the horizon h⁺ is the half vector itself.
  const bool nonzero = l2 > 0;
  const double len = sqrt(nonzero ? l2 : 1.0);
  const V h = (1.0 / len) * sum;
  const V hp = h.z < 0 ? -h : h;
  const double d = g.ggx.D(hp);
  const double pdf = nonzero ? d * hp.z / (2.0 * len) : 0.0;
  if (!above) return {0.0, pdf};
  const double c = dot(h, wi);
  return {c > 0 ? d / (4 * c) : 0.0, pdf};
}

// ∫ |f̂ − D_ltc|^power dω by the balance heuristic over both samplers' midpoint grids.
template <int kPower>
GLINTLAB_INLINE double mis_distance_body(const MisGrid& g, const LtcCoefficients& c) {
  const LtcLobe<double> lobe = lobe_of(c);
  const auto term = [](double f, double density, double pf) {
    const double p = pf + density;
    const double d = std::abs(f - density);
    return p > 0 ? (kPower == 3 ? d * d * d : d) / p : 0.0;
  };
  const int n = g.samples;
  double sum = 0;
  // The order of the additions is the (a, b) order, lobe sample then target sample.
  for (std::size_t k = 0; k < std::size_t(n) * n; ++k) {
    const LtcSample<double> s = ltc_sample_from_cosine(lobe, g.cosine_dir[k]);
    if (s.pdf > 0) {
      const TargetAt t = target_at(g, s.dir);
      sum += term(t.value * g.inv_norm, s.pdf, t.pdf);
    }
    if (g.target_counts[k])
      sum += term(g.target_value_at[k], ltc_density(lobe, g.target_dir[k]), g.target_pdf_at[k]);
  }
  return sum / (double(n) * n);
}

// The same loop compiled for FMA3: the LTC matrix products' std::fma is a libm call on baseline
// x86-64 and one instruction here, correctly rounded either way, so the sums are the same bits
// (nothing else is fused: core/CMakeLists.txt builds this file with -ffp-contract=off).
template <int kPower>
[[gnu::target("avx2,fma")]] double mis_distance_fma3(const MisGrid& g, const LtcCoefficients& c) {
  return mis_distance_body<kPower>(g, c);
}

template <int kPower>
double mis_distance(const MisGrid& g, const LtcCoefficients& c) {
  static const bool fma3 = simd::isa_supported(simd::Isa::kAvx2);
  return fma3 ? mis_distance_fma3<kPower>(g, c) : mis_distance_body<kPower>(g, c);
}

double mis_distance(LtcTarget target, double alpha, double theta_o, double norm,
                    const LtcCoefficients& c, int samples, int power) {
  const MisGrid g = make_mis_grid(target, alpha, theta_o, norm, samples);
  return power == 3 ? mis_distance<3>(g, c) : mis_distance<1>(g, c);
}

// Nelder–Mead (Nelder & Mead 1965; reflection 1, expansion 2, contraction 1/2, shrink 1/2) over
// `dim` ≤ 4 variables; deterministic. Returns the best point; *evaluations counts calls.
template <class F>
std::array<double, 4> nelder_mead(F&& f, std::array<double, 4> x0, int dim,
                                  const std::array<double, 4>& step, int max_evaluations,
                                  double* best_value, int* evaluations) {
  std::array<std::array<double, 4>, 5> x;
  x.fill(x0);
  std::array<double, 5> fx{};
  for (int k = 0; k < dim; ++k) x[k + 1][k] += step[k];
  int evals = 0;
  const auto eval = [&](const std::array<double, 4>& p) {
    ++evals;
    return f(p);
  };
  for (int k = 0; k <= dim; ++k) fx[k] = eval(x[k]);
  while (evals < max_evaluations) {
    std::array<int, 5> order{0, 1, 2, 3, 4};
    std::stable_sort(order.begin(), order.begin() + dim + 1,
                     [&](int a, int b) { return fx[a] < fx[b]; });
    const int best = order[0], worst = order[dim], second = order[dim - 1];
    // Converged: the values agree to 1e-7 relative and the simplex is small.
    double size = 0;
    for (int k = 0; k <= dim; ++k)
      for (int d = 0; d < dim; ++d) size = std::max(size, std::abs(x[k][d] - x[best][d]));
    if (std::abs(fx[worst] - fx[best]) <= 1e-7 * std::abs(fx[best]) && size < 1e-5) break;
    if (size < 1e-10) break;
    std::array<double, 4> centroid{0, 0, 0, 0};
    for (int k = 0; k <= dim; ++k)
      if (k != worst)
        for (int d = 0; d < dim; ++d) centroid[d] += x[k][d] / dim;
    const auto along = [&](double t) {
      std::array<double, 4> p = x0;
      for (int d = 0; d < dim; ++d) p[d] = centroid[d] + t * (x[worst][d] - centroid[d]);
      return p;
    };
    const std::array<double, 4> r = along(-1.0);
    const double fr = eval(r);
    if (fr < fx[best]) {
      const std::array<double, 4> e = along(-2.0);
      const double fe = eval(e);
      if (fe < fr) {
        x[worst] = e, fx[worst] = fe;
      } else {
        x[worst] = r, fx[worst] = fr;
      }
    } else if (fr < fx[second]) {
      x[worst] = r, fx[worst] = fr;
    } else {
      const bool outside = fr < fx[worst];
      const std::array<double, 4> c = along(outside ? -0.5 : 0.5);
      const double fc = eval(c);
      if (fc < (outside ? fr : fx[worst])) {
        x[worst] = c, fx[worst] = fc;
      } else {
        for (int k = 0; k <= dim; ++k) {
          if (k == best) continue;
          for (int d = 0; d < dim; ++d) x[k][d] = x[best][d] + 0.5 * (x[k][d] - x[best][d]);
          fx[k] = eval(x[k]);
        }
      }
    }
  }
  int best = 0;
  for (int k = 1; k <= dim; ++k)
    if (fx[k] < fx[best]) best = k;
  *best_value = fx[best];
  *evaluations = evals;
  return x[best];
}

// Adaptive Simpson on [a, b] (Kuncir 1962 / Lyness 1969 with the Richardson correction).
template <class F>
double simpson_rec(F& f, double a, double b, double fa, double fm, double fb, double whole,
                   double tol, int depth) {
  const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
  const double delta = left + right - whole;
  if (depth <= 0 || std::abs(delta) <= 15 * tol) return left + right + delta / 15;
  return simpson_rec(f, a, m, fa, flm, fm, left, tol / 2, depth - 1) +
         simpson_rec(f, m, b, fm, frm, fb, right, tol / 2, depth - 1);
}

template <class F>
double adaptive_simpson(F f, double a, double b, double tol) {
  // Eight starting panels so that a narrow feature cannot hide between the first nodes.
  double sum = 0;
  for (int k = 0; k < 8; ++k) {
    const double lo = a + (b - a) * k / 8, hi = a + (b - a) * (k + 1) / 8;
    const double fa = f(lo), fb = f(hi), fm = f(0.5 * (lo + hi));
    sum += simpson_rec(f, lo, hi, fa, fm, fb, (hi - lo) / 6 * (fa + 4 * fm + fb), tol / 8, 50);
  }
  return sum;
}

}  // namespace

double ltc_target_value(LtcTarget target, double alpha, V wo, V wi) {
  const GGX<double> ggx{alpha, alpha};
  if (!(wi.z > 0) || !(wo.z > 0)) return 0.0;
  if (target == LtcTarget::kBrdf) return microfacet_brdf(ggx, wi, wo, 1.0) * wi.z;
  const V h = half_vector(wi, wo);
  const double c = dot(h, wi);
  return c > 0 ? ggx.D(h) / (4 * c) : 0.0;
}

namespace {

GLINTLAB_INLINE LtcAlbedo ggx_ltc_albedo_body(double alpha, double cos_theta_o, int grid) {
  const GGX<double> ggx{alpha, alpha};
  const double c = std::clamp(cos_theta_o, 0.0, 1.0);
  const V wo{std::sqrt(1 - c * c), 0.0, c};
  double albedo = 0, fresnel = 0;
  for (int a = 0; a < grid; ++a)
    for (int b = 0; b < grid; ++b) {
      const MicrofacetSample<double> s =
          sample_heitz_vndf(ggx, wo, Vec2<double>{(a + 0.5) / grid, (b + 0.5) / grid});
      const double w = sample_weight(ggx, wo, s);
      albedo += w;
      fresnel += w * std::pow(1 - std::clamp(dot(s.wo, s.m), 0.0, 1.0), 5);
    }
  const double n = double(grid) * grid;
  return {albedo / n, fresnel / n};
}

// FMA3 build of the same loop (the sampler's and the dot products' std::fma in one instruction;
// see mis_distance_fma3).
[[gnu::target("avx2,fma")]] LtcAlbedo ggx_ltc_albedo_fma3(double alpha, double cos_theta_o,
                                                         int grid) {
  return ggx_ltc_albedo_body(alpha, cos_theta_o, grid);
}

}  // namespace

LtcAlbedo ggx_ltc_albedo(double alpha, double cos_theta_o, int grid) {
  static const bool fma3 = simd::isa_supported(simd::Isa::kAvx2);
  return fma3 ? ggx_ltc_albedo_fma3(alpha, cos_theta_o, grid)
              : ggx_ltc_albedo_body(alpha, cos_theta_o, grid);
}

double ggx_d_pr(double alpha, double cos_theta_o, double tolerance) {
  const double co = std::clamp(cos_theta_o, 0.0, 1.0), so = std::sqrt(1 - co * co);
  const double a2 = alpha * alpha;
  // u = 1 − s² (u: the GGX CDF variable, tan²θ_h = α² u/(1 − u)) removes the 1/cos θ_h
  // endpoint singularity: D(h) dh = du dφ/(2π cos θ_h) and du = 2s ds.
  const auto integrand = [&](double s) {
    if (!(s > 0)) return 0.0;
    const double u = 1 - s * s;
    const double t2 = a2 * u / (s * s);  // tan²θ_h
    const double inv_cos = std::sqrt(1 + t2);
    const double cos2 = (1 - t2) / (1 + t2), sin2 = 2 * std::sqrt(t2) / (1 + t2);
    double fraction;  // share of the azimuths φ_h whose reflection stays above the horizon
    if (so * sin2 <= 0) {
      fraction = co * cos2 >= 0 ? 1.0 : 0.0;
    } else {
      const double kappa = -co * cos2 / (so * sin2);
      fraction = std::acos(std::clamp(kappa, -1.0, 1.0)) / kPiD;
    }
    return fraction * inv_cos * 2 * s;
  };
  return adaptive_simpson(integrand, 0.0, 1.0, tolerance);
}

double ltc_fit_objective(LtcTarget target, double alpha, double theta_o, const LtcCoefficients& c,
                         int samples) {
  return mis_distance(target, alpha, theta_o, target_norm(target, alpha, theta_o), c, samples, 3);
}

double ltc_fit_l1_error(LtcTarget target, double alpha, double theta_o, const LtcCoefficients& c,
                        int samples) {
  return mis_distance(target, alpha, theta_o, target_norm(target, alpha, theta_o), c, samples, 1);
}

struct LtcL1Error::Grid {
  MisGrid mis;
};

LtcL1Error::LtcL1Error(LtcTarget target, double alpha, double theta_o, int samples)
    : grid_(std::make_shared<const Grid>(Grid{make_mis_grid(
          target, alpha, theta_o, target_norm(target, alpha, theta_o), samples)})) {}

double LtcL1Error::operator()(const LtcCoefficients& c) const { return mis_distance<1>(grid_->mis, c); }

namespace {

// The target's mean direction E_f̂[ω] by its own sampler (Heitz et al. 2016 Sec. 4: the lobe's
// frame), kept in the xz-plane by symmetry; the normal at normal incidence.
V target_mean_direction(const MisGrid& g, double theta_o) {
  if (theta_o <= 0) return {0, 0, 1};
  V sum{0, 0, 0};
  for (std::size_t k = 0; k < g.target_dir.size(); ++k) {
    if (!g.target_counts[k]) continue;
    sum = sum + (g.target_raw_value[k] / g.target_pdf_at[k]) * g.target_dir[k];
  }
  sum.y = 0;
  return length(sum) > 0 ? normalize(sum) : V{0, 0, 1};
}

// M = [X Y Z] K with K = [[m11, 0, m13], [0, m22, 0], [m31, 0, 1]] (Heitz et al. 2016 Sec. 4's
// matrix form, in the frame of the mean direction Z, Y = (0, 1, 0)); returned as the table's
// M⁻¹ = K⁻¹ [X Y Z]ᵀ scaled to M⁻¹₁₁ = 1.
LtcCoefficients coefficients_of(const LtcFitParameters& p, V z) {
  const V x{z.z, 0, -z.x};
  // The xz block [[m11, m13], [m31, 1]] inverted; row 1 of K⁻¹ is Y/m22, so scale by m22.
  const double s = p.m22 / (p.m11 - p.m13 * p.m31);
  const V row0 = s * (x - p.m13 * z), row2 = s * (p.m11 * z - p.m31 * x);
  return {row0.x, row0.z, row2.x, row2.z};
}

LtcFitResult fit_with_norm(LtcTarget target, double alpha, double theta_o, double norm,
                           const LtcFitParameters& warm, int samples) {
  const bool normal_incidence = theta_o <= 0;
  const MisGrid grid = make_mis_grid(target, alpha, theta_o, norm, samples);
  const V z = target_mean_direction(grid, theta_o);
  // Logarithms of the scales, so one simplex step fits every α.
  const auto params = [&](const std::array<double, 4>& x) {
    if (normal_incidence) return LtcFitParameters{std::exp(x[0]), std::exp(x[0]), 0.0, 0.0};
    return LtcFitParameters{std::exp(x[0]), std::exp(x[1]), x[2] * std::exp(x[0]), x[3]};
  };
  const auto objective = [&](const std::array<double, 4>& x) {
    const LtcFitParameters p = params(x);
    // det K > 0: the other sign is the same family mirrored.
    if (!(p.m11 - p.m13 * p.m31 > 0)) return 1e300;
    const LtcCoefficients c = coefficients_of(p, z);
    const double value = mis_distance<3>(grid, c);
    return std::isfinite(value) ? value : 1e300;
  };
  const std::array<double, 4> x0{std::log(warm.m11), std::log(warm.m22), warm.m13 / warm.m11,
                                 warm.m31};
  const std::array<double, 4> step{0.1, 0.1, 0.05, 0.05};
  double best = 0;
  int evals = 0;
  const std::array<double, 4> x =
      nelder_mead(objective, x0, normal_incidence ? 1 : 4, step, 500, &best, &evals);
  const LtcFitParameters p = params(x);
  return {coefficients_of(p, z), p, best, evals};
}

// The parameters as the CSV stores them (9 significant digits): each entry starts from exactly
// what a reader of the committed tables sees, so any entry can be refitted bit for bit.
LtcFitParameters as_written(const LtcFitParameters& p) {
  const auto r = [](double x) { return std::stod(fmt::format("{:.9g}", x)); };
  return {r(p.m11), r(p.m22), r(p.m13), r(p.m31)};
}

}  // namespace

LtcFitResult fit_ltc_entry(LtcTarget target, double alpha, double theta_o,
                           const LtcFitParameters& warm_start, int samples) {
  return fit_with_norm(target, alpha, theta_o, target_norm(target, alpha, theta_o), warm_start,
                       samples);
}

double ltc_node_alpha(int i, int size) {
  const double s = size > 1 ? double(i) / (size - 1) : 0.0;
  return std::max(s * s, kLtcMinAlpha);
}

double ltc_node_theta(int j, int size) {
  const double t = size > 1 ? double(j) / (size - 1) * 0.5 * kPiD : 0.0;
  return std::min(t, std::acos(kLtcMinCosTheta));
}

LtcTables fit_ltc_tables(const LtcFitOptions& o) {
  const int n = o.size;
  if (n < 2 || n > kLtcMaxTableSize)
    throw ParameterError(
        fmt::format("ltc fit: size = {} is out of range (valid: 2 to {})", n, kLtcMaxTableSize));
  LtcTables t;
  t.size = n;
  const std::size_t count = std::size_t(n) * n;
  t.brdf.resize(count), t.albedo.resize(count), t.fresnel.resize(count);
  t.brdf_error.resize(count), t.ndf.resize(count), t.brdf_params.resize(count),
      t.ndf_params.resize(count), t.d_pr.resize(count), t.ndf_error.resize(count);
  tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
  std::atomic<int> done{0};
  const int total = 3 * n;
  const auto report = [&] {
    const int d = ++done;
    if (o.progress) o.progress(d, total);
  };
  arena.execute([&] {
    // Norms first: every fit of an entry uses its own.
    tbb::parallel_for(0, n, [&](int i) {
      for (int j = 0; j < n; ++j) {
        const std::size_t k = std::size_t(i) * n + j;
        const double a = ltc_node_alpha(i, n), c = std::cos(ltc_node_theta(j, n));
        const LtcAlbedo alb = ggx_ltc_albedo(a, c);
        t.albedo[k] = alb.albedo, t.fresnel[k] = alb.fresnel;
        t.d_pr[k] = ggx_d_pr(a, c);
      }
      report();
    });
    struct TargetTables {
      LtcTarget target;
      std::vector<LtcCoefficients>& lobes;
      std::vector<LtcFitParameters>& params;
      std::vector<double>& error;
      const std::vector<double>& norm;
    };
    const std::array<TargetTables, 2> targets{
        TargetTables{LtcTarget::kBrdf, t.brdf, t.brdf_params, t.brdf_error, t.albedo},
        TargetTables{LtcTarget::kNdf, t.ndf, t.ndf_params, t.ndf_error, t.d_pr}};
    // θ_o = 0 column of each target, roughest first, from the clamped cosine (α = 1 at normal
    // incidence): a chain, so the two targets' columns run side by side.
    const auto fit_column = [&](const TargetTables& f) {
      LtcFitParameters warm{1, 1, 0, 0};
      for (int i = n - 1; i >= 0; --i) {
        const std::size_t k = std::size_t(i) * n;
        const LtcFitResult r = fit_with_norm(f.target, ltc_node_alpha(i, n), 0.0, f.norm[k],
                                             as_written(warm), o.samples);
        f.lobes[k] = r.coefficients, f.params[k] = warm = r.parameters;
      }
    };
    tbb::parallel_invoke([&] { fit_column(targets[0]); }, [&] { fit_column(targets[1]); });
    // Then every row of both targets, one task each (2N tasks of unequal cost: one pool, so a
    // thread that finishes a cheap row takes the next one of either target).
    tbb::parallel_for(
        0, 2 * n,
        [&](int task) {
          const TargetTables& f = targets[task / n];
          const int i = task % n;
          const double a = ltc_node_alpha(i, n);
          for (int j = 1; j < n; ++j) {
            const std::size_t k = std::size_t(i) * n + j;
            const LtcFitResult r = fit_with_norm(f.target, a, ltc_node_theta(j, n), f.norm[k],
                                                 as_written(f.params[k - 1]), o.samples);
            f.lobes[k] = r.coefficients, f.params[k] = r.parameters;
          }
          for (int j = 0; j < n; ++j) {
            const std::size_t k = std::size_t(i) * n + j;
            f.error[k] =
                mis_distance(f.target, a, ltc_node_theta(j, n), f.norm[k], f.lobes[k], 64, 1);
          }
          report();
        },
        tbb::simple_partitioner{});
  });
  return t;
}

}  // namespace glintlab

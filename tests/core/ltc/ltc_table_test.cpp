// Tests of the LTC tables (core/ltc/ltc_table.h, ltc_fit.h; Heitz et al. 2016 Sec. 4, Kneiphof &
// Klein 2024 Eq. 13, 19): D_PR and albedo against independent cubature, the fit error over the
// committed table, that committed entries are reproduced by a refit from their committed warm
// starts (and that a perturbed entry is not), CSV round trip and errors, and the tables' LTC
// integral over polygons against Monte Carlo of the GGX BRDF·cos and of D(h)/(4⟨h, ω_i⟩).
#include "core/ltc/ltc_table.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <vector>

#include "core/lights/polygon_light_check.h"
#include "core/ltc/ltc.h"
#include "core/ltc/ltc_fit.h"
#include "core/math/rng.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/ndf/total_area.h"
#include "core/samplers/heitz_vndf.h"
#include "core/samplers/walter.h"

namespace glintlab {
namespace {

using V = Vec3<double>;
constexpr double kPiD = std::numbers::pi;

// D_PR by a brute-force 2-D midpoint rule over h in (cos θ_h, φ_h): an independent route to Eq. 19.
double d_pr_brute(double alpha, double theta_o, int n) {
  const GGX<double> ggx{alpha, alpha};
  const V wo{std::sin(theta_o), 0, std::cos(theta_o)};
  double sum = 0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      // u ∈ (0,1) → θ_h by the GGX CDF, so D cos θ_h dh = du dφ/(2π).
      const double u = (a + 0.5) / n, phi = 2 * kPiD * (b + 0.5) / n;
      const double t = alpha * std::sqrt(u / (1 - u));
      const double c = 1 / std::sqrt(1 + t * t), s = t * c;
      const V h{s * std::cos(phi), s * std::sin(phi), c};
      const V wi = reflect(wo, h);
      if (wi.z > 0) sum += 1 / c;
    }
  (void)ggx;
  return sum / (double(n) * n);
}

TEST(LtcTable, DprMatchesBruteForceCubatureAndBounds) {
  for (double alpha : {0.05, 0.3, 0.7, 1.0})
    for (double theta : {0.0, 0.6, 1.2, 1.5}) {
      const double d = ggx_d_pr(alpha, std::cos(theta));
      EXPECT_NEAR(d, d_pr_brute(alpha, theta, 1200), 2e-3) << alpha << " " << theta;
      // Eq. 19 integrates D over part of H: at most D_H (Eq. 29).
      EXPECT_LE(d, total_area_ggx_eq29(alpha) + 1e-9);
    }
  // At normal incidence the reflection stays up exactly for θ_h ≤ π/4: D_PR = CDF share / ...
  // For α = 1, D = 1/π and D_PR = ∫_{θ_h ≤ π/4} dh / π = 2(1 − cos π/4) = 2 − √2.
  EXPECT_NEAR(ggx_d_pr(1.0, 1.0), 2 - std::sqrt(2.0), 1e-9);
}

TEST(LtcTable, AlbedoMatchesUniformHemisphereCubature) {
  for (double alpha : {0.3, 0.8})
    for (double theta : {0.2, 1.0}) {
      const V wo{std::sin(theta), 0, std::cos(theta)};
      const int n = 1000;
      double sum = 0, fres = 0;
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          const double z = (a + 0.5) / n, phi = 2 * kPiD * (b + 0.5) / n;
          const double r = std::sqrt(1 - z * z);
          const V wi{r * std::cos(phi), r * std::sin(phi), z};
          const double f = ltc_target_value(LtcTarget::kBrdf, alpha, wo, wi);
          sum += f;
          fres += f * std::pow(1 - dot(wi, half_vector(wi, wo)), 5);
        }
      const double w = 2 * kPiD / (double(n) * n);
      const LtcAlbedo alb = ggx_ltc_albedo(alpha, std::cos(theta));
      EXPECT_NEAR(alb.albedo, sum * w, 1e-3) << alpha << " " << theta;
      EXPECT_NEAR(alb.fresnel, fres * w, 1e-4) << alpha << " " << theta;
    }
}

// Bounds on the fit's L1 error ∫|f̂ − D_ltc| (of 2), set before the 64 × 64 fit was run.
constexpr double kBrdfMedianBound = 0.05;
constexpr double kBrdfMax60Bound = 0.2;
constexpr double kNdfMedianBound = 0.2;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

TEST(LtcTable, CommittedTablesAreTheFullSizeFit) {
  const LtcTables& t = ltc_ggx_tables();
  EXPECT_EQ(t.size, kLtcTableSize);
  ASSERT_EQ(t.brdf.size(), std::size_t(t.size) * t.size);
}

TEST(LtcTable, FitErrorOverTheTable) {
  // ∫|f̂ − D_ltc| dω ∈ [0, 2] of each committed entry; reported and bounded where the fit is
  // expected to work (θ_o ≤ 60°: see docs/ltc.md for the measured values at grazing).
  const LtcTables& t = ltc_ggx_tables();
  const int n = t.size;
  std::vector<double> brdf_all, ndf_all, brdf_60, ndf_60;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::size_t k = std::size_t(i) * n + j;
      brdf_all.push_back(t.brdf_error[k]);
      ndf_all.push_back(t.ndf_error[k]);
      if (ltc_node_theta(j, n) <= kPiD / 3 + 1e-9) {
        brdf_60.push_back(t.brdf_error[k]);
        ndf_60.push_back(t.ndf_error[k]);
      }
    }
  const auto mx = [](const std::vector<double>& v) {
    return *std::max_element(v.begin(), v.end());
  };
  RecordProperty("brdf_l1_median", std::to_string(median(brdf_all)));
  RecordProperty("brdf_l1_max", std::to_string(mx(brdf_all)));
  RecordProperty("ndf_l1_median", std::to_string(median(ndf_all)));
  RecordProperty("ndf_l1_max", std::to_string(mx(ndf_all)));
  std::printf(
      "LTC fit L1 error: BRDF median %.4f max %.4f (theta<=60: median %.4f max %.4f); "
      "NDF median %.4f max %.4f (theta<=60: median %.4f max %.4f)\n",
      median(brdf_all), mx(brdf_all), median(brdf_60), mx(brdf_60), median(ndf_all), mx(ndf_all),
      median(ndf_60), mx(ndf_60));
  EXPECT_LT(median(brdf_all), kBrdfMedianBound);
  EXPECT_LT(mx(brdf_60), kBrdfMax60Bound);
  EXPECT_LT(median(ndf_all), kNdfMedianBound);
}

// Refit entry (i, j) from the committed fit parameters of (i, j − 1), exactly as fit_ltc_tables
// does (it starts each entry from its neighbour's parameters as written to the CSV), and return
// the relative difference from `committed`: rounding to the CSV's 9 digits only, if the
// committed tables are what the code fits.
double refit_difference(LtcTarget target, const LtcTables& t, int i, int j,
                        const LtcCoefficients& committed) {
  const int n = t.size;
  const std::size_t k = std::size_t(i) * n + j;
  const std::vector<LtcFitParameters>& p =
      target == LtcTarget::kBrdf ? t.brdf_params : t.ndf_params;
  const LtcFitResult r =
      fit_ltc_entry(target, ltc_node_alpha(i, n), ltc_node_theta(j, n), p[k - 1]);
  const LtcCoefficients& c = r.coefficients;
  const double scale = std::abs(committed.m00) + std::abs(committed.m02) + std::abs(committed.m20) +
                       std::abs(committed.m22);
  return (std::abs(c.m00 - committed.m00) + std::abs(c.m02 - committed.m02) +
          std::abs(c.m20 - committed.m20) + std::abs(c.m22 - committed.m22)) /
         scale;
}

// 9 significant digits in the CSV: a few 1e-9 relative.
constexpr double kRefitTolerance = 1e-8;

struct Entry {
  int i, j;
};
// A smooth, a medium and a rough entry, away from the grazing column.
std::vector<Entry> refit_entries(int n) { return {{n / 8, n / 4}, {n / 2, n / 2}, {n - 1, n / 3}}; }

TEST(LtcTable, CommittedEntriesMatchARefit) {
  const LtcTables& t = ltc_ggx_tables();
  const int n = t.size;
  for (const Entry e : refit_entries(n)) {
    const std::size_t k = std::size_t(e.i) * n + e.j;
    EXPECT_LT(refit_difference(LtcTarget::kBrdf, t, e.i, e.j, t.brdf[k]), 1e-4)
        << e.i << "," << e.j;
    EXPECT_LT(refit_difference(LtcTarget::kNdf, t, e.i, e.j, t.ndf[k]), 1e-4) << e.i << "," << e.j;
    const double a = ltc_node_alpha(e.i, n), c = std::cos(ltc_node_theta(e.j, n));
    const LtcAlbedo alb = ggx_ltc_albedo(a, c);
    EXPECT_NEAR(alb.albedo, t.albedo[k], 1e-8);
    EXPECT_NEAR(alb.fresnel, t.fresnel[k], 1e-8);
    EXPECT_NEAR(ggx_d_pr(a, c), t.d_pr[k], 1e-8);
    EXPECT_NEAR(ltc_fit_l1_error(LtcTarget::kBrdf, a, ltc_node_theta(e.j, n), t.brdf[k]),
                t.brdf_error[k], 1e-6 + 1e-4 * t.brdf_error[k]);
  }
}

// The error kept for a search over lobes is the one-call error, bit for bit, for both targets
// and for lobes away from the table's (as a search visits).
TEST(LtcTable, KeptL1ErrorIsTheOneCallErrorBitForBit) {
  const LtcTables& t = ltc_ggx_tables();
  const int n = t.size;
  for (const LtcTarget target : {LtcTarget::kBrdf, LtcTarget::kNdf})
    for (const Entry e : refit_entries(n)) {
      const double a = ltc_node_alpha(e.i, n), theta = ltc_node_theta(e.j, n);
      const LtcL1Error kept(target, a, theta, 16);
      LtcCoefficients c = t.brdf[std::size_t(e.i) * n + e.j];
      for (int step = 0; step < 3; ++step, c.m02 += 0.05, c.m20 -= 0.03)
        EXPECT_EQ(kept(c), ltc_fit_l1_error(target, a, theta, c, 16)) << e.i << "," << e.j;
    }
}

TEST(LtcTable, NegativeControlPerturbedEntryFailsTheRefitCheck) {
  const LtcTables& t = ltc_ggx_tables();
  const int n = t.size;
  const Entry e = refit_entries(n)[1];
  LtcCoefficients wrong = t.brdf[std::size_t(e.i) * n + e.j];
  // A change in the 6th digit, as a fit with other settings or a stale table would leave.
  wrong.m02 += 1e-6 * (std::abs(wrong.m00) + std::abs(wrong.m02));
  EXPECT_GT(refit_difference(LtcTarget::kBrdf, t, e.i, e.j, wrong), kRefitTolerance);
}

TEST(LtcTable, CsvRoundTripAndErrors) {
  const LtcTables& t = ltc_ggx_tables();
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("glintlab_ltc_" + std::to_string(::getpid()));
  write_ltc_tables(dir.string(), t, "test");
  const auto slurp = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string b = slurp(dir / "ggx_brdf.csv"), d = slurp(dir / "ggx_ndf.csv");
  std::filesystem::remove_all(dir);
  const LtcTables r = parse_ltc_tables(b, d);
  ASSERT_EQ(r.size, t.size);
  for (std::size_t k = 0; k < t.brdf.size(); ++k) {
    EXPECT_EQ(r.brdf[k].m02, t.brdf[k].m02);
    EXPECT_EQ(r.d_pr[k], t.d_pr[k]);
  }
  // Truncated file: not N x N rows.
  const std::string cut = b.substr(0, b.rfind('\n', b.size() - 2) + 1);
  try {
    parse_ltc_tables(cut, d);
    ADD_FAILURE() << "no error";
  } catch (const ParameterError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_ltc_tables(b, "m00\n1\n"), ParameterError);
  LtcFitOptions bad;
  bad.size = 1;
  EXPECT_THROW(fit_ltc_tables(bad), ParameterError);
}

TEST(LtcTable, LookupAtNodesAndRotation) {
  const LtcTables& t = ltc_ggx_tables();
  const LtcTableView& view = ltc_ggx_table_view();
  const int n = t.size, i = n / 2, j = n / 3;
  const double sa = double(i) / (n - 1), th = double(j) / (n - 1) * kPiD / 2;
  const LtcGgxLookup<double> l = ltc_ggx_lookup(view, sa * sa, V{std::sin(th), 0, std::cos(th)});
  const std::size_t k = std::size_t(i) * n + j;
  EXPECT_NEAR(l.brdf.m_inv[0][2], t.brdf[k].m02, 1e-9);
  EXPECT_NEAR(l.brdf.amplitude, t.albedo[k], 1e-9);
  EXPECT_NEAR(l.ndf.amplitude, t.d_pr[k], 1e-9);
  // A view at azimuth φ and a polygon rotated by φ about z: the same integral.
  const double phi = 1.1;
  const auto rot = [&](V v) {
    return V{std::cos(phi) * v.x - std::sin(phi) * v.y, std::sin(phi) * v.x + std::cos(phi) * v.y,
             v.z};
  };
  const LtcGgxLookup<double> lr =
      ltc_ggx_lookup(view, sa * sa, rot(V{std::sin(th), 0, std::cos(th)}));
  const std::vector<V> poly{{-1.5, -0.5, 1}, {-0.5, -0.5, 1}, {-0.5, 0.5, 1}, {-1.5, 0.5, 1}};
  std::vector<V> poly_r;
  for (const V& v : poly) poly_r.push_back(rot(v));
  EXPECT_NEAR(ltc_polygon_integral(l.brdf, poly.data(), 4, true),
              ltc_polygon_integral(lr.brdf, poly_r.data(), 4, true), 1e-12);
}

// ∫_P target dω_i by Monte Carlo with the target's own sampler (VNDF for the BRDF, D cos θ_h for
// the NDF): mean and standard error over n samples.
struct Mc {
  double mean, sigma;
};
Mc mc_target_over_polygon(LtcTarget target, double alpha, V wo, const PolygonLight<double>& light,
                          const char* id, int n) {
  const GGX<double> ggx{alpha, alpha};
  const std::uint64_t seed = hash_string(id);
  double s = 0, s2 = 0;
  for (int k = 0; k < n; ++k) {
    const Vec2<double> u{counter_uniform<double>(seed, std::uint64_t(k), 0),
                         counter_uniform<double>(seed, std::uint64_t(k), 1)};
    const MicrofacetSample<double> m =
        target == LtcTarget::kBrdf ? sample_heitz_vndf(ggx, wo, u) : sample_walter(ggx, wo, u);
    double w = 0;
    detail::PlaneHit<double> h;
    if (m.pdf > 0 && light.hits(V{0, 0, 0}, m.wo, &h))
      w = ltc_target_value(target, alpha, wo, m.wo) / m.pdf;
    s += w, s2 += w * w;
  }
  const double mean = s / n;
  return {mean, std::sqrt(std::max(s2 / n - mean * mean, 0.0) / n)};
}

// Counter-clockwise seen from the origin: the winding whose right-hand normal faces the origin.
std::vector<V> facing_origin(std::vector<V> v) {
  V newell{0, 0, 0};
  for (std::size_t k = 0; k < v.size(); ++k) newell = newell + cross(v[k], v[(k + 1) % v.size()]);
  if (dot(newell, v[0]) > 0) std::reverse(v.begin(), v.end());
  return v;
}

std::vector<std::vector<V>> lit_polygons() {
  // A rectangle overhead, one towards the reflection direction of a 45° view, a small one, and a
  // large wall crossing the horizon.
  std::vector<std::vector<V>> p{
      {{-0.5, -0.5, 1}, {-0.5, 0.5, 1}, {0.5, 0.5, 1}, {0.5, -0.5, 1}},
      {{-1.5, -0.4, 1}, {-1.5, 0.4, 1}, {-0.6, 0.4, 1}, {-0.6, -0.4, 1}},
      {{-1.05, -0.05, 1}, {-1.05, 0.05, 1}, {-0.95, 0.05, 1}, {-0.95, -0.05, 1}},
      {{-2, -3, -1}, {-2, 3, -1}, {-2, 3, 3}, {-2, -3, 3}}};
  for (std::vector<V>& v : p) v = facing_origin(v);
  return p;
}

struct Config {
  double sqrt_alpha, theta;
};
std::vector<Config> lit_configs() { return {{0.3, 0.3}, {0.5, 0.785}, {0.8, 0.6}, {0.45, 1.0}}; }

// The LTC estimate of ∫_P target for a config (amplitude · ∫_P D_ltc) by table lookup, off-node.
double ltc_estimate(LtcTarget target, const LtcGgxLookup<double>& l, const std::vector<V>& poly) {
  const LtcLobe<double>& lobe = target == LtcTarget::kBrdf ? l.brdf : l.ndf;
  return lobe.amplitude * ltc_polygon_integral(lobe, poly.data(), int(poly.size()));
}

// Stated error: |LTC − MC| ≤ kTol · (target's total over H) + 5σ.
constexpr double kTol = 0.03;

TEST(LtcTable, PolygonIntegralMatchesMonteCarloOfGgx) {
  const LtcTableView& view = ltc_ggx_table_view();
  double worst_brdf = 0, worst_ndf = 0;
  for (const LtcTarget target : {LtcTarget::kBrdf, LtcTarget::kNdf})
    for (const Config c : lit_configs()) {
      const double alpha = c.sqrt_alpha * c.sqrt_alpha;
      const V wo{std::sin(c.theta), 0, std::cos(c.theta)};
      const LtcGgxLookup<double> l = ltc_ggx_lookup(view, alpha, wo);
      const double total = target == LtcTarget::kBrdf ? l.brdf.amplitude : l.ndf.amplitude;
      for (const std::vector<V>& poly : lit_polygons()) {
        const Mc mc =
            mc_target_over_polygon(target, alpha, wo, make_polygon_light<double>(poly, {1, 1, 1}),
                                   "ltc.table-polygon-vs-mc", 100000);
        const double est = ltc_estimate(target, l, poly);
        const double rel = (std::abs(est - mc.mean) - 5 * mc.sigma) / total;
        (target == LtcTarget::kBrdf ? worst_brdf : worst_ndf) =
            std::max(target == LtcTarget::kBrdf ? worst_brdf : worst_ndf, rel);
        EXPECT_LE(std::abs(est - mc.mean), kTol * total + 5 * mc.sigma)
            << (target == LtcTarget::kBrdf ? "brdf" : "ndf") << " sqrt_alpha " << c.sqrt_alpha
            << " theta " << c.theta << " LTC " << est << " MC " << mc.mean << " ± " << mc.sigma;
      }
    }
  std::printf("LTC polygon vs MC: worst |LTC - MC| - 5 sigma, over the total: BRDF %.4f NDF %.4f\n",
              worst_brdf, worst_ndf);
}

TEST(LtcTable, NegativeControlWrongRoughnessLobeFailsPolygonCheck) {
  // The lobe looked up for twice the roughness must fall outside the stated error somewhere.
  const LtcTableView& view = ltc_ggx_table_view();
  int rejected = 0;
  for (const Config c : lit_configs()) {
    const double alpha = c.sqrt_alpha * c.sqrt_alpha;
    const V wo{std::sin(c.theta), 0, std::cos(c.theta)};
    const LtcGgxLookup<double> good = ltc_ggx_lookup(view, alpha, wo);
    LtcGgxLookup<double> wrong = ltc_ggx_lookup(view, std::min(2 * alpha, 1.0), wo);
    wrong.brdf.amplitude = good.brdf.amplitude;  // the shape alone is wrong
    for (const std::vector<V>& poly : lit_polygons()) {
      const Mc mc = mc_target_over_polygon(LtcTarget::kBrdf, alpha, wo,
                                           make_polygon_light<double>(poly, {1, 1, 1}),
                                           "ltc.table-polygon-vs-mc", 100000);
      const double est = ltc_estimate(LtcTarget::kBrdf, wrong, poly);
      if (std::abs(est - mc.mean) > kTol * good.brdf.amplitude + 5 * mc.sigma) ++rejected;
    }
  }
  EXPECT_GE(rejected, 1);
}

}  // namespace
}  // namespace glintlab

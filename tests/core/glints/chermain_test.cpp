// Chermain et al. 2020/2021: the dictionary (determinism, symmetry, prefixes, normalization of
// every MIP level and of textureGrad lookups, Eq. 15), the matrix M (Eq. 18), the patch-SDF's
// normalization with and without GGAA, the smooth fallback, and the registered model.
#include "core/glints/chermain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/model_registry.h"
#include "core/parameter_check.h"

namespace glintlab {
namespace {

chermain2021::DictionaryConfig small_config() {
  chermain2021::DictionaryConfig c;
  c.distributions = 12;
  c.levels = 8;
  c.seed = 7;
  return c;
}

const chermain2021::Dictionary& small_dictionary() {
  static const chermain2021::Dictionary d(small_config());
  return d;
}

TEST(ChermainDictionary, RejectsBadConfiguration) {
  const auto message = [](chermain2021::DictionaryConfig c) -> std::string {
    try {
      validate(c);
    } catch (const ParameterError& e) {
      return e.what();
    }
    return "";
  };
  chermain2021::DictionaryConfig c = small_config();
  c.distributions = 10;
  EXPECT_NE(message(c).find("distributions (N) = 10"), std::string::npos) << message(c);
  c = small_config(), c.levels = 0;
  EXPECT_NE(message(c).find("levels"), std::string::npos);
  c = small_config(), c.levels = 21;
  EXPECT_NE(message(c).find("levels"), std::string::npos);
  c = small_config(), c.resolution = 48;
  EXPECT_NE(message(c).find("resolution"), std::string::npos);
  c = small_config(), c.lobe_std = 0.4;  // ≥ σ_o = 0.354
  EXPECT_NE(message(c).find("lobe_std"), std::string::npos);
  c = small_config(), c.alpha_dict = 0;
  EXPECT_NE(message(c).find("alpha_dict"), std::string::npos);
  EXPECT_EQ(message(small_config()), "");
}

TEST(ChermainDictionary, DeterministicFromSeed) {
  const chermain2021::Dictionary a(small_config()), b(small_config());
  chermain2021::DictionaryConfig other = small_config();
  other.seed = 8;
  const chermain2021::Dictionary c(other);
  int differ = 0;
  for (int n = 0; n < a.distributions(); ++n)
    for (int k = 0; k < a.levels(); ++k)
      for (int t = 0; t < a.resolution(); ++t) {
        ASSERT_EQ(a.texel(n, k, 0, t), b.texel(n, k, 0, t));
        differ += a.texel(n, k, 0, t) != c.texel(n, k, 0, t);
      }
  EXPECT_GT(differ, a.distributions() * a.levels() * a.resolution() / 2);
}

TEST(ChermainDictionary, LevelsArePrefixesSymmetricAndNormalized) {
  const chermain2021::Dictionary& d = small_dictionary();
  const int L = d.levels();
  // Prefix: level k is level 0's lobe plus 2^k − 1 further lobes of the same fixed sequence, so a
  // dictionary with fewer levels has bit-identical tables at the levels it has.
  chermain2021::DictionaryConfig fewer = small_config();
  fewer.levels = 4;
  const chermain2021::Dictionary f(fewer);
  for (int n = 0; n < d.distributions(); ++n)
    for (int k = 0; k < 4; ++k)
      for (int t = 0; t < d.resolution(); ++t) ASSERT_EQ(d.texel(n, k, 0, t), f.texel(n, k, 0, t));
  for (int n = 0; n < d.distributions(); ++n)
    for (int k = 0; k < L; ++k) {
      for (int m = 0; m < d.mip_levels(); ++m) EXPECT_NEAR(d.table_integral(n, k, m), 1.0, 2e-6);
      for (double x : {0.0, 0.013, 0.2, 0.7, 1.3})
        EXPECT_NEAR(d.lookup_lod(n, k, x), d.lookup_lod(n, k, -x), 1e-12 * d.lookup_lod(n, k, x));
      EXPECT_EQ(d.lookup_lod(n, k, d.extent()), 0.0);
    }
  // Level 0 is one symmetric lobe pair: almost all mass within 5 lobe std of ±μ_0.
  const double mu = std::abs(d.lobe_mean(0, 0));
  EXPECT_GT(d.lookup_lod(0, 0, mu), 5 * d.lookup_lod(0, 0, mu + 0.1));
}

TEST(ChermainDictionary, TextureGradKeepsUnitIntegralOnlyWithMirroredRepeat) {
  const chermain2021::Dictionary& d = small_dictionary();
  for (int k : {0, 3, 7})
    for (double dx : {0.0, 0.01, 0.05, 0.3, 2.0}) {
      EXPECT_NEAR(chermain2021::lookup_grad_integral(d, 1, k, dx, 0.3 * dx,
                                                     chermain2021::TableWrap::kMirroredRepeat),
                  1.0, 1e-5)
          << "k=" << k << " dx=" << dx;
    }
  // Zero derivatives: the level-0 lookup exactly.
  for (double x : {0.0, 0.1, -0.33, 0.9})
    EXPECT_EQ(d.lookup_grad(2, 5, x, 0, 0), d.lookup_lod(2, 5, x));
  // Clamp-to-edge breaks the symmetry of the mirrored table: far from normalized.
  EXPECT_GT(std::abs(chermain2021::lookup_grad_integral(d, 1, 3, 0.05, 0.01,
                                                        chermain2021::TableWrap::kClampToEdge) -
                     1),
            0.05);
  chermain2021::TableFilter f;
  d.lookup_grad(0, 0, 0.1, 0.2, 0.05, chermain2021::TableWrap::kMirroredRepeat, 16, &f);
  EXPECT_EQ(f.probes, 4);
  EXPECT_NEAR(f.lambda, std::log2(0.2 * d.resolution() / d.extent() / 4), 1e-12);
}

TEST(ChermainMatrix, CovarianceIsSigma) {
  for (double rho : {0.0, 0.5, 0.99, -0.7}) {
    const double sx = 0.3, sy = 0.12, so = 0.35;
    const chermain2021::Matrix M = chermain2021::matrix(sx, sy, rho, so);
    // M Σ_o Mᵀ with Σ_o = σ_o² I (Eq. 17).
    const double c00 = so * so * (M.m00 * M.m00 + M.m01 * M.m01);
    const double c01 = so * so * (M.m00 * M.m10 + M.m01 * M.m11);
    const double c11 = so * so * (M.m10 * M.m10 + M.m11 * M.m11);
    EXPECT_NEAR(c00, sx * sx, 1e-14);
    EXPECT_NEAR(c11, sy * sy, 1e-14);
    EXPECT_NEAR(c01, rho * sx * sy, 1e-14);
    EXPECT_NEAR(M.m00 * M.i00 + M.m01 * M.i10, 1, 1e-14);
    EXPECT_NEAR(M.m00 * M.i01 + M.m01 * M.i11, 0, 1e-14);
  }
}

chermain2021::SdfParams sdf_params(double log2_density, int kernel, double rho = 0.5) {
  return {&small_dictionary(), 0.25, 0.18, rho, log2_density, kernel, 0.5, 3};
}

TEST(ChermainPatchSdf, NormalizedWithAndWithoutGgaa) {
  const FootprintQuery<double> fp{{0.3, 0.7}, {0.01, 0.002}, {-0.003, 0.008}};
  const chermain2021::SlopeDerivatives d{0.08, -0.02, 0.01, 0.05};
  for (int kernel : {chermain2021::kNoGgaa, chermain2021::kProjectedHalf}) {
    const chermain2021::SlopeMoments2 m =
        chermain2021::patch_moments(sdf_params(14, kernel), fp, d, 500);
    EXPECT_NEAR(m.mass, 1.0, 2e-3) << "kernel " << kernel;
  }
  // The smooth fallback (dictionary level ≥ L) is the Gaussian of covariance Σ exactly.
  const chermain2021::SlopeMoments2 s =
      chermain2021::patch_moments(sdf_params(60, chermain2021::kNoGgaa), fp, d, 400);
  EXPECT_NEAR(s.mass, 1.0, 1e-6);
  EXPECT_NEAR(std::sqrt(s.xx), 0.25, 1e-4);
  EXPECT_NEAR(std::sqrt(s.yy), 0.18, 1e-4);
  EXPECT_NEAR(s.xy / std::sqrt(s.xx * s.yy), 0.5, 1e-4);
}

TEST(ChermainPatchSdf, LodAndLevelFromFootprint) {
  const FootprintQuery<double> fp{{0.3, 0.7}, {1.0 / 256, 0}, {0, 1.0 / 512}};
  chermain2021::SdfInfo info;
  const chermain2021::SlopeDerivatives d{0, 0, 0, 0};
  chermain2021::patch_sdf(sdf_params(20, chermain2021::kNoGgaa), {0.1, 0.0}, fp, d, &info);
  EXPECT_DOUBLE_EQ(info.lod, -8);
  EXPECT_DOUBLE_EQ(info.dict_level, 2);  // ⌊−8 + 10⌋
  chermain2021::patch_sdf(sdf_params(40, chermain2021::kNoGgaa), {0.1, 0.0}, fp, d, &info);
  EXPECT_DOUBLE_EQ(info.dict_level, small_dictionary().levels());  // smooth fallback
}

TEST(ChermainModel, RegisteredAndEvaluates) {
  const ModelEntry& e = find_model("chermain");
  std::vector<double> v = resolve_params(e, {{"ggaa", "off"}});
  ModelQuery<double> q{};
  q.footprint = {{0.4, 0.6}, {1e-3, 0}, {0, 1e-3}};
  q.wi = normalize(Vec3<double>{0.3, 0.1, 1});
  q.wo = normalize(Vec3<double>{-0.2, -0.15, 1});
  const ErasedEval r = e.eval(v, q);
  EXPECT_GT(r.value, 0);
  EXPECT_GT(r.pdf, 0);
  ASSERT_EQ(r.intermediates.size(), 8u);
  EXPECT_NEAR(r.intermediates[1], std::log2(1e-3), 1e-12);  // lod
  // GGAA with zero derivatives equals no GGAA.
  const ErasedEval g = e.eval(resolve_params(e, {{"ggaa", "projected_half"}}), q);
  EXPECT_EQ(g.value, r.value);
  EXPECT_THROW(resolve_params(e, {{"rho", "1"}}), ModelParamError);
  EXPECT_THROW(resolve_params(e, {{"alpha_x", "0"}}), ModelParamError);
  const ModelSample<double> s = e.sample(v, q, {0.3, 0.6});
  ASSERT_FALSE(s.rejected);
  ModelQuery<double> qs = q;
  qs.wo = s.wo;
  EXPECT_NEAR(s.pdf, e.pdf(v, qs), 1e-12 * s.pdf);
}

}  // namespace
}  // namespace glintlab

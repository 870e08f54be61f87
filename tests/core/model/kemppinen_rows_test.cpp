// The Kemppinen models' rows functions (ModelEntry::pdf_rows, eval_rows, sample_rows), which
// compute the mixture probability once per run of rows at one footprint, give each row the bits of
// the per-row thunk: on random queries in runs of equal footprints, footprints alternating between
// two whose mixture probabilities differ (a probability kept from the wrong footprint would show),
// and every row its own footprint; both NDFs, every k, both mappings, both pdf choices.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/math/rng.h"
#include "core/model_registry.h"
#include "core/models/kemppinen_ggx.h"

namespace glintlab {
namespace {

bool same(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

Vec3<double> direction(std::uint64_t seed, std::uint64_t i, bool upper) {
  const double z = upper ? 0.02 + 0.98 * counter_uniform<double>(seed, i, 0)
                         : 2 * counter_uniform<double>(seed, i, 0) - 1;  // some below the horizon
  const double phi = 2 * 3.141592653589793 * counter_uniform<double>(seed, i, 1);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

FootprintQuery<double> footprint(double uv_x, double uv_y, double dx, double dy) {
  FootprintQuery<double> f;
  f.uv = {uv_x, uv_y};
  f.duv_dx = {dx, 0.3 * dy};
  f.duv_dy = {-0.2 * dx, dy};
  return f;
}

// The queries: `pattern` 0 runs of 7 equal footprints (a, b, a, b), 1 footprints alternating
// between a and b, 2 a new footprint per row.
std::vector<ModelQuery<double>> queries(int pattern, const FootprintQuery<double>& a,
                                        const FootprintQuery<double>& b, std::uint64_t seed) {
  std::vector<ModelQuery<double>> qs(28);
  for (std::size_t i = 0; i < qs.size(); ++i) {
    ModelQuery<double> q{};
    q.wi = direction(seed, 2 * i, i % 11 != 5);
    q.wo = direction(seed, 2 * i + 1, i % 13 != 4);
    q.footprint = pattern == 0   ? ((i / 7) % 2 ? b : a)
                  : pattern == 1 ? (i % 2 ? b : a)
                                 : footprint(counter_uniform<double>(seed, i, 5),
                                             counter_uniform<double>(seed, i, 6),
                                             0.0005 + 0.3 * counter_uniform<double>(seed, i, 7),
                                             0.0005 + 0.3 * counter_uniform<double>(seed, i, 8));
    qs[i] = q;
  }
  return qs;
}

// (model, k): one test each, so that each stays under a second.
class KemppinenRows : public ::testing::TestWithParam<std::tuple<const char*, const char*>> {};

TEST_P(KemppinenRows, EachRowIsThePerRowThunksBits) {
  // Two footprints whose mixture probabilities differ at every setting below (checked).
  const FootprintQuery<double> a = footprint(0.31, 0.67, 0.1, 0.12);
  const FootprintQuery<double> b = footprint(0.52, 0.18, 0.3, 0.28);
  std::uint64_t seed = 1;
  const auto [name, k] = GetParam();
  {
    const ModelEntry& m = find_model(name);
    ASSERT_TRUE(m.pdf_rows && m.eval_rows && m.sample_rows) << name;
    for (const char* mapping : {"uv", "triplanar"})
      for (const char* pdf : {"marginal", "printed"}) {
        const std::vector<std::pair<std::string, std::string>> assigned = {{"k", k},
                                                                           {"mapping", mapping},
                                                                           {"pdf", pdf},
                                                                           {"normal_theta", "35"},
                                                                           {"normal_phi", "60"},
                                                                           {"alpha_x", "0.25"},
                                                                           {"alpha_y", "0.4"}};
        const std::vector<double> values = resolve_params(m, assigned);
        const std::string where = fmt::format("{} k={} mapping={} pdf={}", name, k, mapping, pdf);
        {
          const auto p = KemppinenGGX::params<double>(values);
          ModelQuery<double> qa{}, qb{};
          qa.footprint = a;
          qb.footprint = b;
          ASSERT_NE(detail::kemppinen_model_mixture_probability(p, qa),
                    detail::kemppinen_model_mixture_probability(p, qb))
              << where;
        }
        for (int pattern = 0; pattern < 3; ++pattern) {
          const std::vector<ModelQuery<double>> qs = queries(pattern, a, b, seed++);
          // pdf() and eval do not depend on the pdf choice (sample's alone): once.
          const bool printed = std::string(pdf) == "printed";
          std::vector<double> pdfs(printed ? 0 : qs.size());
          std::vector<ErasedEval> evals(pdfs.size());
          m.pdf_rows(values, std::span(qs).first(pdfs.size()), pdfs);
          m.eval_rows(values, std::span(qs).first(pdfs.size()), evals);
          int nonzero = 0;
          for (std::size_t i = 0; i < pdfs.size(); ++i) {
            EXPECT_TRUE(same(pdfs[i], m.pdf(values, qs[i]))) << where << " pdf row " << i;
            const ErasedEval e = m.eval(values, qs[i]);
            EXPECT_TRUE(same(evals[i].value, e.value)) << where << " eval row " << i;
            EXPECT_TRUE(same(evals[i].pdf, e.pdf)) << where << " eval pdf row " << i;
            ASSERT_EQ(evals[i].intermediates.size(), e.intermediates.size());
            for (std::size_t j = 0; j < e.intermediates.size(); ++j)
              EXPECT_TRUE(same(evals[i].intermediates[j], e.intermediates[j]))
                  << where << " row " << i << " intermediate " << m.intermediates[j];
            nonzero += pdfs[i] > 0;
          }
          if (!printed) {
            EXPECT_GT(nonzero, 8) << where;
          }
          // The samples at one query (sample_rows' form), at a query of each footprint.
          for (const ModelQuery<double>& q : {qs[0], qs[1], qs[5]}) {
            std::vector<Vec2<double>> u(24);
            for (std::size_t i = 0; i < u.size(); ++i)
              u[i] = {counter_uniform<double>(seed, i, 3), counter_uniform<double>(seed, i, 4)};
            std::vector<ModelSample<double>> s(u.size());
            m.sample_rows(values, q, u, s);
            for (std::size_t i = 0; i < u.size(); ++i) {
              const ModelSample<double> t = m.sample(values, q, u[i]);
              EXPECT_TRUE(same(s[i].wo.x, t.wo.x) && same(s[i].wo.y, t.wo.y) &&
                          same(s[i].wo.z, t.wo.z) && same(s[i].pdf, t.pdf) &&
                          same(s[i].weight, t.weight) && s[i].rejected == t.rejected)
                  << where << " sample " << i;
            }
          }
        }
      }
  }
}

INSTANTIATE_TEST_SUITE_P(ModelAndK, KemppinenRows,
                         ::testing::Combine(::testing::Values("kemppinen_ggx",
                                                              "kemppinen_beckmann"),
                                            ::testing::Values("1", "4", "9", "16")),
                         [](const ::testing::TestParamInfo<KemppinenRows::ParamType>& param) {
                           return fmt::format("{}_k{}", std::get<0>(param.param),
                                              std::get<1>(param.param));
                         });

// An altered copy that replaces a thunk clears the rows functions with clear_rows; the Kemppinen
// entries' rows then route through the thunks again.
TEST(KemppinenRowsCleared, LoopOverTheThunks) {
  const ModelEntry e = clear_rows(find_model("kemppinen_ggx"));
  EXPECT_FALSE(e.pdf_rows || e.eval_rows || e.sample_rows);
}

}  // namespace
}  // namespace glintlab

// `glintlab eval`: every output column equals the library kernel evaluated on the same query.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "cli/cli_test_util.h"
#include "core/io/csv.h"
#include "core/maps/beckmann_map.h"
#include "core/maps/ggx_map.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/ndf/total_area.h"
#include "core/samplers/beckmann_vndf.h"
#include "core/samplers/bounded_vndf.h"
#include "core/samplers/heitz_vndf.h"
#include "core/samplers/spherical_caps.h"
#include "core/samplers/walter.h"

namespace glintlab::cli_test {
namespace {

using V3 = Vec3<double>;

const std::vector<std::string> kQueryColumns = {"ndf",  "alpha_x", "alpha_y", "wi_x", "wi_y",
                                                "wi_z", "wo_x",    "wo_y",    "wo_z"};
const std::vector<std::string> kResultColumns = {"h_x",
                                                 "h_y",
                                                 "h_z",
                                                 "D",
                                                 "lambda_wi",
                                                 "G1_wi",
                                                 "G1_wo",
                                                 "G2",
                                                 "vndf_h",
                                                 "pdf_ndf",
                                                 "pdf_vndf",
                                                 "pdf_spherical_caps",
                                                 "pdf_bounded_caps_listing1",
                                                 "pdf_bounded_caps_exact_isotropic",
                                                 "brdf",
                                                 "DH",
                                                 "T_x",
                                                 "T_y",
                                                 "JT_paper",
                                                 "JT_true"};
// The samplers Beckmann does not have: their pdf columns are 'nan' for a beckmann query.
const std::vector<std::string> kGgxOnlyPdfs = {"pdf_spherical_caps", "pdf_bounded_caps_listing1",
                                               "pdf_bounded_caps_exact_isotropic"};

struct Query {
  std::string ndf;
  double ax, ay;
  V3 wi, wo;
};

V3 unit(double x, double y, double z) { return normalize(V3{x, y, z}); }

// Queries over both NDFs, isotropic and anisotropic, with grazing, back-facing and opposite
// directions, so every branch of the kernels is represented.
std::vector<Query> queries() {
  return {
      {"ggx", 0.3, 0.3, unit(0.3, 0.1, 0.9), unit(-0.4, 0.2, 0.8)},
      {"ggx", 0.05, 0.6, unit(0.7, -0.2, 0.3), unit(-0.1, 0.5, 0.6)},
      {"ggx", 1.0, 1.0, unit(0, 0, 1), unit(0, 0, 1)},
      {"ggx", 0.2, 0.4, unit(0.9, 0.0, 0.02), unit(-0.9, 0.1, 0.05)},
      {"ggx", 0.5, 0.3, unit(0.2, 0.3, -0.4), unit(0.1, -0.2, 0.9)},  // wi below the surface
      {"ggx", 0.3, 0.3, unit(0.3, 0.1, 0.9), unit(0.5, 0.2, -0.3)},   // wo below the surface
      {"beckmann", 0.3, 0.3, unit(0.3, 0.1, 0.9), unit(-0.4, 0.2, 0.8)},
      {"beckmann", 0.08, 0.7, unit(-0.6, 0.3, 0.4), unit(0.2, -0.5, 0.7)},
      {"beckmann", 0.9, 0.9, unit(0.1, 0.1, 0.05), unit(0.0, -0.3, 0.2)},
      {"beckmann", 0.4, 0.2, unit(0.2, 0.3, -0.4), unit(0.1, -0.2, 0.9)},
  };
}

// The expected result columns for a query, straight from the kernels.
std::map<std::string, double> expected(const Query& q) {
  const auto common = [&](const auto& ndf, double pdf_vndf, std::array<double, 3> ggx_only) {
    const V3 h = half_vector(q.wi, q.wo);
    const Vec2<double> t = map_to_square(ndf, h);
    return std::map<std::string, double>{
        {"h_x", h.x},
        {"h_y", h.y},
        {"h_z", h.z},
        {"D", ndf.D(h)},
        {"lambda_wi", ndf.lambda(q.wi)},
        {"G1_wi", smith_g1(ndf, q.wi, h)},
        {"G1_wo", smith_g1(ndf, q.wo, h)},
        {"G2", smith_g2_height_correlated(ndf, q.wi, q.wo, h)},
        {"vndf_h", vndf(ndf, q.wi, h)},
        {"pdf_ndf", pdf_walter(ndf, q.wi, q.wo)},
        {"pdf_vndf", pdf_vndf},
        {"pdf_spherical_caps", ggx_only[0]},
        {"pdf_bounded_caps_listing1", ggx_only[1]},
        {"pdf_bounded_caps_exact_isotropic", ggx_only[2]},
        {"brdf", microfacet_brdf(ndf, q.wi, q.wo, 1.0)},
        {"DH", total_area(ndf)},
        {"T_x", t.x},
        {"T_y", t.y},
        {"JT_paper", map_jacobian_paper(ndf, h)},
        {"JT_true", map_jacobian_true(ndf, h)},
    };
  };
  if (q.ndf == "ggx") {
    const GGX<double> g{q.ax, q.ay};
    return common(g, pdf_heitz_vndf(g, q.wi, q.wo),
                  {pdf_spherical_caps(g, q.wi, q.wo),
                   pdf_bounded_vndf(g, q.wi, q.wo, BoundedVndfBound::kListing1),
                   pdf_bounded_vndf(g, q.wi, q.wo, BoundedVndfBound::kExactIsotropic)});
  }
  const Beckmann<double> b{q.ax, q.ay};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return common(b, pdf_beckmann_vndf(b, q.wi, q.wo), {nan, nan, nan});
}

// Equal to 1e-15 relative (NaN matches NaN only).
bool close(double got, double want) {
  if (std::isnan(want) || std::isnan(got)) return std::isnan(want) && std::isnan(got);
  if (got == want) return true;
  return std::abs(got - want) <= 1e-15 * std::max(std::abs(got), std::abs(want));
}

std::string query_csv(const std::vector<Query>& qs, const std::vector<std::string>& order) {
  std::string text;
  for (std::size_t i = 0; i < order.size(); ++i) text += (i ? "," : "") + order[i];
  text += "\n";
  for (const Query& q : qs) {
    const std::map<std::string, std::string> f = {{"ndf", q.ndf},
                                                  {"alpha_x", io::format_double(q.ax)},
                                                  {"alpha_y", io::format_double(q.ay)},
                                                  {"wi_x", io::format_double(q.wi.x)},
                                                  {"wi_y", io::format_double(q.wi.y)},
                                                  {"wi_z", io::format_double(q.wi.z)},
                                                  {"wo_x", io::format_double(q.wo.x)},
                                                  {"wo_y", io::format_double(q.wo.y)},
                                                  {"wo_z", io::format_double(q.wo.z)}};
    for (std::size_t i = 0; i < order.size(); ++i) text += (i ? "," : "") + f.at(order[i]);
    text += "\n";
  }
  return text;
}

using EvalTest = CliTest;

TEST_F(EvalTest, EveryColumnEqualsTheLibraryKernels) {
  const std::vector<Query> qs = queries();
  // Columns in a shuffled order: the input order of columns must not matter.
  const std::vector<std::string> order = {"wo_z", "ndf",  "wi_x",    "alpha_y", "wo_x",
                                          "wi_z", "wi_y", "alpha_x", "wo_y"};
  write_text(path("q.csv"), query_csv(qs, order));

  const RunResult r = run({"eval", "--in", "q.csv", "--out", "r.csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(unexpected_files(work(), {"q.csv", "r.csv"}), std::vector<std::string>{});

  const io::CsvTable t = io::read_csv(path("r.csv"));
  std::vector<std::string> want_header = kQueryColumns;
  want_header.insert(want_header.end(), kResultColumns.begin(), kResultColumns.end());
  ASSERT_EQ(t.header(), want_header);
  ASSERT_EQ(t.num_rows(), qs.size());

  int compared = 0;
  for (std::size_t i = 0; i < qs.size(); ++i) {
    const Query& q = qs[i];
    SCOPED_TRACE("row " + std::to_string(i + 1) + " (" + q.ndf + ")");
    // The query columns come back with the same values.
    EXPECT_EQ(t.text(i, t.column("ndf")), q.ndf);
    EXPECT_EQ(t.number(i, t.column("alpha_x")), q.ax);
    EXPECT_EQ(t.number(i, t.column("alpha_y")), q.ay);
    EXPECT_EQ(t.number(i, t.column("wi_x")), q.wi.x);
    EXPECT_EQ(t.number(i, t.column("wi_y")), q.wi.y);
    EXPECT_EQ(t.number(i, t.column("wi_z")), q.wi.z);
    EXPECT_EQ(t.number(i, t.column("wo_x")), q.wo.x);
    EXPECT_EQ(t.number(i, t.column("wo_y")), q.wo.y);
    EXPECT_EQ(t.number(i, t.column("wo_z")), q.wo.z);
    for (const auto& [name, want] : expected(q)) {
      const std::string_view text = t.text(i, t.column(name));
      const double got = cell_value(t, i, t.column(name));
      EXPECT_TRUE(close(got, want))
          << name << ": got " << text << ", want " << io::format_double(want);
      ++compared;
    }
    if (q.ndf == "beckmann") {
      for (const std::string& name : kGgxOnlyPdfs) EXPECT_EQ(t.text(i, t.column(name)), "nan");
    }
  }
  EXPECT_EQ(compared, static_cast<int>(qs.size() * kResultColumns.size()));
}

TEST_F(EvalTest, PrintsSeventeenSignificantDigits) {
  write_text(path("q.csv"),
             "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\nggx,0.1,0.3,0,0,1,0,0.6,0.8\n");
  const RunResult r = run({"eval", "--in", "q.csv", "--out", "r.csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = lines_of(read_text(path("r.csv")));
  ASSERT_EQ(lines.size(), 2u);
  // 0.1 and 0.3 are not exact in binary: 17 digits show the double actually used.
  EXPECT_EQ(
      lines[1].rfind("ggx,0.10000000000000001,0.29999999999999999,0,0,1,0,0.59999999999999998,"
                     "0.80000000000000004,",
                     0),
      0u)
      << lines[1];
}

TEST_F(EvalTest, EmptyQueryFileGivesHeaderOnly) {
  write_text(path("q.csv"), "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n");
  const RunResult r = run({"eval", "--in", "q.csv", "--out", "r.csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(lines_of(read_text(path("r.csv"))).size(), 1u);
}

TEST_F(EvalTest, AcceptsCrlfSpacesAndTrailingBlankLines) {
  write_text(path("q.csv"),
             "ndf, alpha_x ,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\r\n"
             "beckmann, 0.25 ,+0.5,0,0,1,0.6,0,0.8\r\n\r\n\n");
  const RunResult r = run({"eval", "--in", "q.csv", "--out", "r.csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::CsvTable t = io::read_csv(path("r.csv"));
  ASSERT_EQ(t.num_rows(), 1u);
  EXPECT_EQ(t.number(0, t.column("alpha_x")), 0.25);
  EXPECT_EQ(t.number(0, t.column("alpha_y")), 0.5);
}

}  // namespace
}  // namespace glintlab::cli_test

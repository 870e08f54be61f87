// `glintlab sample`: deterministic output, the library's samples row by row, and pdf and weight
// columns that equal the standalone kernels.
#include "core/samplers/sample.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cli/cli_test_util.h"
#include "core/io/csv.h"
#include "core/math/rng.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/samplers/beckmann_vndf.h"
#include "core/samplers/bounded_vndf.h"
#include "core/samplers/heitz_vndf.h"
#include "core/samplers/spherical_caps.h"
#include "core/samplers/walter.h"

namespace glintlab::cli_test {
namespace {

using V3 = Vec3<double>;
using Sample = MicrofacetSample<double>;

const std::vector<std::string> kColumns = {"wo_x", "wo_y", "wo_z",   "h_x",     "h_y",
                                           "h_z",  "pdf",  "weight", "rejected"};

bool close(double got, double want, double rel) {
  if (got == want) return true;
  return std::abs(got - want) <= rel * std::max(std::abs(got), std::abs(want));
}

struct Case {
  std::string ndf, alpha, wi, sampler, bound;  // bound empty: not passed
  double ax, ay;
  V3 wi_v;
};

V3 unit(double x, double y, double z) { return normalize(V3{x, y, z}); }

std::string vec_arg(V3 v) {
  return io::format_double(v.x) + "," + io::format_double(v.y) + "," + io::format_double(v.z);
}

std::vector<Case> cases() {
  const V3 up = unit(0.4, -0.3, 0.7);
  const V3 grazing = unit(0.95, 0.1, 0.05);
  const V3 below = unit(0.5, 0.2, -0.3);
  return {
      {"ggx", "0.3", vec_arg(up), "ndf", "", 0.3, 0.3, up},
      {"ggx", "0.2,0.5", vec_arg(up), "vndf", "", 0.2, 0.5, up},
      {"ggx", "0.6,0.1", vec_arg(grazing), "spherical_caps", "", 0.6, 0.1, grazing},
      {"ggx", "0.4", vec_arg(below), "spherical_caps", "", 0.4, 0.4, below},
      {"ggx", "0.3,0.6", vec_arg(up), "bounded_caps", "", 0.3, 0.6, up},
      {"ggx", "0.5", vec_arg(grazing), "bounded_caps", "exact_isotropic", 0.5, 0.5, grazing},
      {"ggx", "0.5", vec_arg(below), "bounded_caps", "listing1", 0.5, 0.5, below},
      {"beckmann", "0.3", vec_arg(up), "ndf", "", 0.3, 0.3, up},
      {"beckmann", "0.7,0.2", vec_arg(grazing), "vndf", "", 0.7, 0.2, grazing},
  };
}

std::vector<std::string> args_for(const Case& c, int n, const std::string& seed,
                                  const std::string& out) {
  std::vector<std::string> a = {
      "sample",       "--ndf",     c.ndf,     "--alpha", c.alpha,
      "--wi=" + c.wi, "--sampler", c.sampler, "--n",     std::to_string(n),
      "--seed",       seed,        "--out",   out};
  if (!c.bound.empty()) {
    a.push_back("--bound");
    a.push_back(c.bound);
  }
  return a;
}

// The library's sample i and its standalone pdf for a case.
Sample library_sample(const Case& c, std::uint64_t seed, std::uint64_t i) {
  const Vec2<double> u{counter_uniform<double>(seed, i, 0), counter_uniform<double>(seed, i, 1)};
  const BoundedVndfBound bound = c.bound == "exact_isotropic" ? BoundedVndfBound::kExactIsotropic
                                                              : BoundedVndfBound::kListing1;
  if (c.ndf == "ggx") {
    const GGX<double> g{c.ax, c.ay};
    if (c.sampler == "ndf") return sample_walter(g, c.wi_v, u);
    if (c.sampler == "vndf") return sample_heitz_vndf(g, c.wi_v, u);
    if (c.sampler == "spherical_caps") return sample_spherical_caps(g, c.wi_v, u);
    return sample_bounded_vndf(g, c.wi_v, u, bound);
  }
  const Beckmann<double> b{c.ax, c.ay};
  if (c.sampler == "ndf") return sample_walter(b, c.wi_v, u);
  return sample_beckmann_vndf(b, c.wi_v, u);
}

double standalone_pdf(const Case& c, V3 wo) {
  const BoundedVndfBound bound = c.bound == "exact_isotropic" ? BoundedVndfBound::kExactIsotropic
                                                              : BoundedVndfBound::kListing1;
  if (c.ndf == "ggx") {
    const GGX<double> g{c.ax, c.ay};
    if (c.sampler == "ndf") return pdf_walter(g, c.wi_v, wo);
    if (c.sampler == "vndf") return pdf_heitz_vndf(g, c.wi_v, wo);
    if (c.sampler == "spherical_caps") return pdf_spherical_caps(g, c.wi_v, wo);
    return pdf_bounded_vndf(g, c.wi_v, wo, bound);
  }
  const Beckmann<double> b{c.ax, c.ay};
  if (c.sampler == "ndf") return pdf_walter(b, c.wi_v, wo);
  return pdf_beckmann_vndf(b, c.wi_v, wo);
}

double library_weight(const Case& c, const Sample& s) {
  if (c.ndf == "ggx") return sample_weight(GGX<double>{c.ax, c.ay}, c.wi_v, s);
  return sample_weight(Beckmann<double>{c.ax, c.ay}, c.wi_v, s);
}

using SampleTest = CliTest;

TEST_F(SampleTest, SameSeedIsByteIdenticalAndOtherSeedDiffers) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.ndf + " " + c.sampler);
    ASSERT_EQ(run(args_for(c, 200, "7", "a.csv")).exit_code, 0);
    ASSERT_EQ(run(args_for(c, 200, "7", "b.csv")).exit_code, 0);
    ASSERT_EQ(run(args_for(c, 200, "8", "c.csv")).exit_code, 0);
    const std::string a = read_text(path("a.csv")), b = read_text(path("b.csv")),
                      other = read_text(path("c.csv"));
    EXPECT_EQ(lines_of(a).size(), 201u);
    EXPECT_EQ(a, b);
    EXPECT_NE(a, other);
    EXPECT_EQ(unexpected_files(work(), {"a.csv", "b.csv", "c.csv"}), std::vector<std::string>{});
  }
}

TEST_F(SampleTest, RowsAreTheLibrarySamplesWithStandalonePdfAndWeight) {
  constexpr int kN = 2000;
  constexpr std::uint64_t kSeed = 12345;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.ndf + " " + c.sampler + " " + c.bound + " wi=" + c.wi);
    const RunResult r = run(args_for(c, kN, std::to_string(kSeed), "s.csv"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const io::CsvTable t = io::read_csv(path("s.csv"));
    ASSERT_EQ(t.header(), kColumns);
    ASSERT_EQ(t.num_rows(), static_cast<std::size_t>(kN));
    int accepted = 0;
    for (std::size_t i = 0; i < t.num_rows(); ++i) {
      const auto num = [&](std::size_t col) { return cell_value(t, i, col); };
      const V3 wo{num(0), num(1), num(2)};
      const V3 m{num(3), num(4), num(5)};
      const double pdf = num(6), weight = num(7);
      const std::string_view rej = t.text(i, 8);
      ASSERT_TRUE(rej == "0" || rej == "1") << rej;

      // The row is the library's sample i, exactly (17 digits read back to the same double).
      const Sample s = library_sample(c, kSeed, i);
      ASSERT_EQ(static_cast<bool>(s.rejected), rej == "1") << "row " << i + 1;
      EXPECT_TRUE(same_value(wo.x, s.wo.x)) << "row " << i + 1 << " wo.x";
      EXPECT_TRUE(same_value(wo.y, s.wo.y)) << "row " << i + 1 << " wo.y";
      EXPECT_TRUE(same_value(wo.z, s.wo.z)) << "row " << i + 1 << " wo.z";
      EXPECT_TRUE(same_value(m.x, s.m.x)) << "row " << i + 1 << " m.x";
      EXPECT_TRUE(same_value(m.y, s.m.y)) << "row " << i + 1 << " m.y";
      EXPECT_TRUE(same_value(m.z, s.m.z)) << "row " << i + 1 << " m.z";
      EXPECT_TRUE(same_value(pdf, s.pdf)) << "row " << i + 1 << " pdf";
      // The pdf column equals the sampler's standalone pdf at the written wo (rejected samples
      // included: the pdf is the density of every produced wo).
      EXPECT_TRUE(close(pdf, standalone_pdf(c, wo), 1e-15))
          << "row " << i + 1 << ": pdf " << io::format_double(pdf) << " vs standalone "
          << io::format_double(standalone_pdf(c, wo));
      if (rej == "1") {
        EXPECT_EQ(weight, 0.0) << "row " << i + 1;
        continue;
      }
      ++accepted;
      EXPECT_TRUE(same_value(weight, library_weight(c, s))) << "row " << i + 1;
    }
    EXPECT_GT(accepted, 0);
  }
}

TEST_F(SampleTest, OutputDoesNotDependOnN) {
  // Sample i depends only on (seed, i): the first rows of a longer run are the shorter run.
  const Case c = cases()[1];
  ASSERT_EQ(run(args_for(c, 10, "3", "short.csv")).exit_code, 0);
  ASSERT_EQ(run(args_for(c, 50, "3", "long.csv")).exit_code, 0);
  const std::vector<std::string> a = lines_of(read_text(path("short.csv")));
  const std::vector<std::string> b = lines_of(read_text(path("long.csv")));
  ASSERT_EQ(a.size(), 11u);
  ASSERT_EQ(b.size(), 51u);
  EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin()));
}

TEST_F(SampleTest, DefaultSeedIsZeroAndDefaultBoundIsListing1) {
  const Case c = cases()[4];  // bounded_caps, no --bound
  std::vector<std::string> a = args_for(c, 20, "0", "explicit.csv");
  a.push_back("--bound");
  a.push_back("listing1");
  ASSERT_EQ(run(a).exit_code, 0);
  std::vector<std::string> d = {"sample",    "--ndf",   c.ndf, "--alpha", c.alpha, "--wi=" + c.wi,
                                "--sampler", c.sampler, "--n", "20",      "--out", "default.csv"};
  const RunResult r = run(d);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(path("explicit.csv")), read_text(path("default.csv")));
}

// Each canonical name runs without a note; each old spelling prints one line naming the canonical
// spelling and writes the same file as it.
TEST_F(SampleTest, OldSpellingsNoteTheCanonicalNameAndSampleTheSame) {
  struct Alias {
    std::string option, old_name, canonical;
    std::vector<std::string> extra;  // the rest of the arguments
  };
  const std::vector<Alias> aliases = {
      {"--sampler", "caps", "spherical_caps", {}},
      {"--sampler", "bounded", "bounded_caps", {}},
      {"--bound", "exact-isotropic", "exact_isotropic", {"--sampler", "bounded_caps"}},
  };
  for (const Alias& a : aliases) {
    SCOPED_TRACE(a.option + " " + a.old_name);
    const auto args = [&](const std::string& name, const std::string& out) {
      std::vector<std::string> v = {"sample",         "--ndf", "ggx", "--alpha", "0.4,0.6",
                                    "--wi=0.6,0,0.8", "--n",   "50",  "--out",   out,
                                    a.option,         name};
      v.insert(v.end(), a.extra.begin(), a.extra.end());
      return v;
    };
    const RunResult canonical = run(args(a.canonical, "canonical.csv"));
    ASSERT_EQ(canonical.exit_code, 0) << canonical.err;
    EXPECT_EQ(canonical.err, "");
    const RunResult old = run(args(a.old_name, "old.csv"));
    ASSERT_EQ(old.exit_code, 0) << old.err;
    EXPECT_EQ(old.err, "glintlab: note: " + a.option + " " + a.old_name + " is spelled " +
                           a.canonical + "\n");
    EXPECT_EQ(read_text(path("old.csv")), read_text(path("canonical.csv")));
  }
  for (const std::string name : {"ndf", "vndf", "spherical_caps", "bounded_caps"}) {
    SCOPED_TRACE(name);
    const RunResult r = run({"sample", "--ndf", "ggx", "--alpha", "0.4", "--wi=0.6,0,0.8",
                             "--sampler", name, "--n", "5", "--out", "s.csv"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
  }
  const RunResult listing1 =
      run({"sample", "--ndf", "ggx", "--alpha", "0.4", "--wi=0.6,0,0.8", "--sampler",
           "bounded_caps", "--bound", "listing1", "--n", "5", "--out", "s.csv"});
  EXPECT_EQ(listing1.exit_code, 0) << listing1.err;
  EXPECT_EQ(listing1.err, "");
}

}  // namespace
}  // namespace glintlab::cli_test

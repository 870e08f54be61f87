// Kemppinen et al. 2025 Fig. 7 analogue: convergence under an environment light, RMSE vs spp on
// log-log axes, glinty importance sampling (Sec. 3.3.5, Algorithm 2, here in the mixture of
// core/glints/kemppinen_full_sampling.h that also samples the compensation term) against
// sampling the smooth NDF (D cosθ), for GGX and Beckmann, over a small image of a glinty plane.
//
// Setting (the paper gives no parameters for Fig. 7): α = 0.2, α★ = 0.02, k = 4 (the paper's k,
// Sec. 3.3.4), density 10⁴, filter 0.5, a pixel of one level-0 cell (λ = 1), θ_v = 30° looking at
// the mirror direction of the default environment's sun (kemppinen2025::env_sky), or `--env FILE`.
// Reference: smooth-NDF sampling at `reference_spp` with seeds independent of the series (the
// paper: "references computed with 8192 samples per pixel"); RMSE over the luminance of every
// pixel. The printed-pdf variant of the mixture is plotted as well: its error stops falling where
// its bias takes over.
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/io/exr.h"
#include "core/io/png.h"
#include "core/math/rng.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/ndf/ndf_kind.h"
#include "core/render/convergence.h"
#include "experiments/figures/kemppinen2025.h"
#include "experiments/figures/chart_spec.h"
#include "experiments/figures/panel_layout.h"
#include "verify/scenes/kemppinen_env_radiance.h"
#include "verify/scenes/kemppinen_presets.h"

namespace glintlab::experiments {
namespace {

using V3 = Vec3<double>;
constexpr std::string_view kFig7Id = "kemppinen2025-fig7";
constexpr double kAlpha = 0.2, kAlphaStar = 0.02, kThetaV = 30.0;
constexpr int kSide = 2;

struct Fig7Budget {
  int size;           // image side in pixels
  int max_spp;        // longest series point (one stream of max_spp samples per pixel)
  int reference_spp;  // smooth-NDF sampling, independent seeds
  int preview_spp;    // the low-spp images
};

// Images a person can see (128² quick, 512² full) with fewer samples per pixel rather than fewer
// pixels: a mixture sample costs ~10 reference samples (Algorithm 2), so the series is short; the
// many pixels keep the RMSE precise, and the reference's own noise, which flattens the raw slope
// at these reference counts, is subtracted in the second slope.
Fig7Budget fig7_budget(bool quick) {
  return quick ? Fig7Budget{128, 16, 128, 4} : Fig7Budget{512, 32, 256, 4};
}

struct Strategy {
  std::string_view name;
  V3 color;
};
constexpr std::array<Strategy, 3> kStrategies = {{{"glinty_is", {0.85, 0.15, 0.1}},
                                                  {"glinty_is_printed_pdf", {0.95, 0.6, 0.1}},
                                                  {"smooth_ndf_is", {0.1, 0.3, 0.85}}}};

struct NdfRun {
  std::string_view name;
  bool ggx = false;
  double q = 0;
  Image reference, preview[3];
  std::vector<RmseAtSpp> rmse[3];
  double slope[3] = {0, 0, 0};
  double slope_minus_reference_noise[3] = {0, 0, 0};  // of √(RMSE² − reference_noise)
  double reference_noise = 0;  // mean over pixels of the reference's variance (luminance)
  std::uint64_t seed = 0;      // the series seed
};

std::uint64_t fig7_seed(std::string_view what) {
  return hash_string(fmt::format("{}/{}", kFig7Id, what).c_str()) & 0xffffffffu;
}

void run_ndf(const FigureContext& ctx, const EnvironmentMap& env, const Fig7Budget& b,
             NdfRun& out) {
  const kemppinen2025::Params<double> p =
      kemppinen2025::preset_params(kSide, kAlphaStar, fig7_seed("points"));
  const double pixel_uv = 1 / std::sqrt(p.density) / p.filter;  // one level-0 cell per pixel
  const kemppinen2025::PlaneView view{kThetaV * std::numbers::pi / 180, {0.25, 0.5}, pixel_uv};
  const V3 v = view.view();
  const int n = b.size * b.size;
  const std::uint64_t series_seed = fig7_seed(fmt::format("{}/series", out.name));
  out.seed = series_seed;
  const std::uint64_t ref_seed = fig7_seed(fmt::format("{}/reference", out.name));
  std::vector<int> spps;
  for (int s = 1; s <= b.max_spp; s *= 2) spps.push_back(s);
  const std::size_t levels = spps.size();
  // Per row: [strategy][spp level] error sums, and the sum of the reference's variances.
  std::vector<std::vector<BatchErrorSums>> row_errors(std::size_t(b.size),
                                                      std::vector<BatchErrorSums>(3 * levels));
  std::vector<double> row_ref_var(std::size_t(b.size), 0.0);
  out.reference = Image(b.size, b.size, {"R", "G", "B"});
  for (Image& im : out.preview) im = Image(b.size, b.size, {"R", "G", "B"});
  std::vector<double> qs(std::size_t(b.size));
  tbb::parallel_for(0, b.size, [&](int y) {
    std::vector<BatchErrorSums>& errors = row_errors[std::size_t(y)];
    std::vector<double> lum(std::size_t(b.max_spp));
    for (int x = 0; x < b.size; ++x) {
      const int k = y * b.size + x;
      const FootprintQuery<double> fp = view.pixel(x, y);
      with_ndf(ndf_kind(out.ggx), kAlpha, kAlpha, [&](const auto& ndf) {
        const std::uint64_t ks = std::uint64_t(k);
        // The reference: D cosθ sampling with its own seeds, mean and variance of the mean.
        V3 sum{0, 0, 0};
        double sy = 0, syy = 0;
        const std::uint64_t rs = mix64(ref_seed ^ mix64(ks));
        for (int i = 0; i < b.reference_spp; ++i) {
          const std::uint64_t is = std::uint64_t(i);
          const V3 e = kemppinen2025::env_estimate_smooth(
              p, ndf, fp, env, v,
              Vec2<double>{counter_uniform<double>(rs, is, 0),
                           counter_uniform<double>(rs, is, 1)});
          sum = sum + e;
          const double yv = kemppinen2025::luminance(e);
          sy += yv;
          syy += yv * yv;
        }
        const double nr = b.reference_spp, ref = sy / nr;
        row_ref_var[std::size_t(y)] += std::max(0.0, (syy - nr * ref * ref) / (nr - 1)) / nr;
        const V3 m = (1.0 / nr) * sum;
        out.reference.at(x, y, 0) = m.x, out.reference.at(x, y, 1) = m.y;
        out.reference.at(x, y, 2) = m.z;
        const kemppinen2025::EnvSamples s = kemppinen2025::env_samples(
            p, ndf, fp, env, v, std::uint64_t(b.max_spp), mix64(series_seed ^ mix64(ks)));
        if (x == 0) qs[std::size_t(y)] = s.q;
        const std::vector<V3>* src[3] = {&s.exact, &s.printed, &s.smooth};
        for (int t = 0; t < 3; ++t) {
          V3 psum{0, 0, 0};
          for (int i = 0; i < b.max_spp; ++i) {
            const V3& e = (*src[t])[std::size_t(i)];
            lum[std::size_t(i)] = kemppinen2025::luminance(e);
            if (i < b.preview_spp) psum = psum + e;
          }
          const V3 pm = (1.0 / b.preview_spp) * psum;
          out.preview[t].at(x, y, 0) = pm.x, out.preview[t].at(x, y, 1) = pm.y;
          out.preview[t].at(x, y, 2) = pm.z;
          // Disjoint batches of spp consecutive samples, each an independent spp-sample estimate.
          for (std::size_t j = 0; j < levels; ++j) {
            const int sp = spps[j];
            for (int b0 = 0; b0 + sp <= b.max_spp; b0 += sp) {
              double bm = 0;
              for (int i = b0; i < b0 + sp; ++i) bm += lum[std::size_t(i)];
              errors[std::size_t(t) * levels + j].add((bm / sp - ref) * (bm / sp - ref));
            }
          }
        }
        return 0;
      });
    }
  });
  if (ctx.progress) ctx.progress(fmt::format("{} {}", kFig7Id, out.name), n, n);
  out.q = qs[0];
  // Rows summed in order: the same bytes for any thread count.
  for (int t = 0; t < 3; ++t) {
    out.rmse[t].clear();
    for (std::size_t j = 0; j < levels; ++j) {
      BatchErrorSums total;
      for (const auto& row : row_errors) total.add(row[std::size_t(t) * levels + j]);
      out.rmse[t].push_back(rmse_from_batch_errors(spps[j], total));
    }
    out.slope[t] = loglog_slope(out.rmse[t]);
  }
  double rv = 0;
  for (double r : row_ref_var) rv += r;
  out.reference_noise = rv / n;
  for (int t = 0; t < 3; ++t) {
    std::vector<RmseAtSpp> less_noise = out.rmse[t];
    for (RmseAtSpp& a : less_noise)
      a.rmse = std::sqrt(std::max(0.0, a.rmse * a.rmse - out.reference_noise));
    out.slope_minus_reference_noise[t] = loglog_slope(less_noise);
  }
}

// Nearest-neighbour enlargement and side-by-side tiles (reference, then each strategy).
Image preview_montage(const std::vector<NdfRun>& runs, int scale) {
  const int s = runs[0].reference.width * scale;
  Image out(4 * s, s * int(runs.size()), {"R", "G", "B"});
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const Image* tiles[4] = {&runs[r].reference, &runs[r].preview[0], &runs[r].preview[1],
                             &runs[r].preview[2]};
    for (int t = 0; t < 4; ++t)
      for (int y = 0; y < s; ++y)
        for (int x = 0; x < s; ++x)
          for (std::size_t c = 0; c < 3; ++c)
            out.at(t * s + x, int(r) * s + y, c) = tiles[t]->at(x / scale, y / scale, c);
  }
  return out;
}

void run_fig7(const FigureContext& ctx) {
  const Fig7Budget b = fig7_budget(ctx.quick), full = fig7_budget(false);
  const EnvironmentMap default_env(kemppinen2025::env_sky());
  const EnvironmentMap& env = ctx.environment ? *ctx.environment : default_env;
  const std::string env_name =
      ctx.environment ? ctx.environment_name
                      : "procedural sky 64x32, soft sun (half angle 0.2 rad, radiance 10) at the "
                        "mirror direction";
  std::vector<NdfRun> runs(2);  // the paper's order: left Beckmann, right GGX
  runs[0].name = "beckmann";
  runs[0].ggx = false;
  runs[1].name = "ggx";
  runs[1].ggx = true;
  for (NdfRun& r : runs) run_ndf(ctx, env, b, r);
  for (const NdfRun& r : runs) {
    const std::string params = fmt::format(
        "ndf={} alpha={} microroughness={} k={} density=1e4 filter=0.5 theta_v={} "
        "pixel=1 level-0 cell q={:.4g} environment={}",
        r.name, kAlpha, kAlphaStar, kSide * kSide, kThetaV, r.q, env_name);
    auto attrs = [&](std::string_view what, int spp) {
      return io::ExrAttributes{{"glintlab_figure", std::string(kFig7Id)},
                               {"glintlab_model", r.ggx ? "kemppinen_ggx" : "kemppinen_beckmann"},
                               {"glintlab_parameters", params},
                               {"glintlab_estimator", std::string(what)},
                               {"glintlab_seed", fmt::format("{}", r.seed)},
                               {"glintlab_spp", fmt::format("{}", spp)},
                               {"glintlab_version", std::string(glintlab_version())}};
    };
    io::write_exr(ctx.dir / fmt::format("{}_reference.exr", r.name), r.reference,
                  attrs("smooth_ndf_is (reference)", b.reference_spp));
    for (int t = 0; t < 3; ++t)
      io::write_exr(
          ctx.dir / fmt::format("{}_{}_{}spp.exr", r.name, kStrategies[t].name, b.preview_spp),
          r.preview[t], attrs(kStrategies[t].name, b.preview_spp));
  }
  io::write_csv_atomic(
      ctx.dir / "rmse_spp.csv",
      {"ndf", "strategy", "spp", "rmse", "stderr", "rmse_minus_reference_noise", "batches",
       "reference_spp"},
      [&](io::CsvWriter& w) {
        for (const NdfRun& r : runs)
          for (int t = 0; t < 3; ++t)
            for (const RmseAtSpp& a : r.rmse[t]) {
              w.cell(r.name).cell(kStrategies[t].name).cell_int(a.spp).cell(a.rmse);
              w.cell(a.std_error)
                  .cell(std::sqrt(std::max(0.0, a.rmse * a.rmse - r.reference_noise)));
              w.cell_int((long long)a.batches).cell_int(b.reference_spp).end_row();
            }
      });
  io::write_csv_atomic(ctx.dir / "loglog_slopes.csv",
                       {"ndf", "strategy", "slope", "slope_minus_reference_noise", "rmse_at_1spp",
                        "mixture_probability_q"},
                       [&](io::CsvWriter& w) {
                         for (const NdfRun& r : runs)
                           for (int t = 0; t < 3; ++t)
                             w.cell(r.name)
                                 .cell(kStrategies[t].name)
                                 .cell(r.slope[t])
                                 .cell(r.slope_minus_reference_noise[t])
                                 .cell(r.rmse[t][0].rmse)
                                 .cell(r.q)
                                 .end_row();
                       });
  // The log-log chart of rmse_spp.csv (drawn by reports/figure_charts.py): one panel per NDF,
  // each strategy's points joined (power laws are straight here), +-2 standard errors.
  ChartSpec chart{
      .title = fmt::format("{}: RMSE vs spp under the environment light (log-log)", kFig7Id),
      .csv = "rmse_spp.csv"};
  for (const NdfRun& r : runs) {
    ChartPanel panel{
        .title = fmt::format("{}: RMSE against a {} spp reference, +-2 s.e.", r.name,
                             b.reference_spp),
        .where = {{"ndf", std::string(r.name)}},
        .x = {.column = "spp", .label = "samples per pixel [spp]", .log = true},
        .y = {.label = "RMSE of the luminance against the reference [linear radiance]",
              .log = true},
        .guide_slope = -0.5,
        .guide_label = "slope -1/2 (unbiased Monte Carlo)"};
    for (const Strategy& st : kStrategies)
      panel.series.push_back({.label = std::string(st.name),
                              .where = {{"strategy", std::string(st.name)}},
                              .y = "rmse",
                              .y_error = "stderr",
                              .y_error_scale = 2,
                              .color = {st.color.x, st.color.y, st.color.z}});
    chart.panels.push_back(std::move(panel));
  }
  write_chart_spec(ctx.dir / "fig7_rmse_spp.png", chart);
  const int enlargement = std::max(1, 192 / b.size);
  io::write_png_preview(ctx.dir / "fig7_images.png", preview_montage(runs, enlargement), 0.1);
  std::vector<std::string> labels;
  for (const NdfRun& r : runs) {
    labels.push_back(fmt::format("{}: reference ({} spp)", r.name, b.reference_spp));
    for (const Strategy& st : kStrategies)
      labels.push_back(fmt::format("{}: {}, {} spp", r.name, st.name, b.preview_spp));
  }
  write_panel_layout(ctx.dir / "fig7_images.png",
                     {fmt::format("kemppinen2025-fig7: the glinty plane under the environment, per "
                                  "NDF and sampling strategy (exposure 0.1; {0} x {0} pixels, one "
                                  "level-0 cell each, enlarged {1} x)",
                                  b.size, enlargement),
                      4,
                      0,
                      labels});
  std::string md = fmt::format(
      "# {} — environment-light convergence (Kemppinen et al. 2025, Fig. 7)\n\n"
      "Glinty plane ({}×{} pixels, one level-0 cell per pixel, θ_v = {}°), α = {}, α★ = {}, "
      "k = {}, density 1e4, filter 0.5, environment: {}.\n\n"
      "Reference: smooth-NDF importance sampling (ω_h ~ D cosθ) at **{} spp** per pixel with "
      "seeds independent of the series (the paper used 8192 spp). RMSE over the luminance of "
      "all pixels, from {} spp per pixel cut into batches; `rmse_minus_reference_noise` "
      "subtracts the reference's own variance (its mean over pixels), and the second slope is "
      "that series' (the raw slope flattens where the reference's noise is a visible part of "
      "the error). Glinty IS = the mixture of Algorithm 2 "
      "(probability q) and D cosθ with the exact mixture density "
      "(core/glints/kemppinen_full_sampling.h); the printed-pdf variant uses Algorithm 2's "
      "printed pdf (lines 16–17) in the same mixture.\n\n"
      "{}"
      "| ndf | strategy | log-log slope | slope less reference noise | RMSE at 1 spp | RMSE at "
      "{} spp |\n|---|---|---|---|---|---|\n",
      kFig7Id, b.size, b.size, kThetaV, kAlpha, kAlphaStar, kSide * kSide, env_name,
      b.reference_spp, b.max_spp,
      ctx.quick ? fmt::format("`--budget quick`: {}² pixels, fewer samples per pixel (full: {}² "
                              "pixels, series to {} spp, reference {} spp).\n\n",
                              b.size, full.size, full.max_spp, full.reference_spp)
                : std::string(),
      b.max_spp);
  for (const NdfRun& r : runs)
    for (int t = 0; t < 3; ++t)
      md += fmt::format("| {} | {} | {:.3f} | {:.3f} | {:.4g} | {:.4g} |\n", r.name,
                        kStrategies[t].name, r.slope[t], r.slope_minus_reference_noise[t],
                        r.rmse[t].front().rmse, r.rmse[t].back().rmse);
  md +=
      "\nSlope −½ is unbiased Monte Carlo; a slope flattening toward 0 is a bias against the "
      "reference.";
  for (const NdfRun& r : runs)
    md += fmt::format(
        " {}: q = {:.3g}, RMSE ratio smooth/glinty at 1 spp {:.3g} (variance ratio {:.3g}), "
        "reference noise (mean variance of a pixel's reference) {:.3g}.",
        r.name, r.q, r.rmse[2].front().rmse / r.rmse[0].front().rmse,
        std::pow(r.rmse[2].front().rmse / r.rmse[0].front().rmse, 2), r.reference_noise);
  md +=
      "\n\nPNG: `fig7_rmse_spp.png` (left Beckmann, right GGX; red glinty IS, orange printed "
      "pdf, blue smooth-NDF IS; decade grid), `fig7_images.png` (rows Beckmann, GGX: reference, "
      "then each strategy at the preview spp).\n";
  io::write_file_atomic(ctx.dir / "summary.md", md);
}

}  // namespace

FigureEntry kemppinen2025_fig7_entry() {
  return {kFig7Id, "Kemppinen et al. 2025", "Fig. 7",
          "environment-light convergence: RMSE vs spp (log-log) of glinty IS (Algorithm 2 + D cos "
          "mixture, exact and printed pdf) vs smooth-NDF IS, GGX and Beckmann, on a glinty plane",
          run_fig7};
}

}  // namespace glintlab::experiments

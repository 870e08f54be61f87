// Kemppinen et al. 2025 figures: Fig. 2–3 (D★^f of Eq. 11 on the prior disk U_Ω and on the
// hemisphere, smooth vs glinty, GGX and Beckmann), Fig. 6 (roulette Eq. 8 vs linear MIP blending
// across a LOD transition), Fig. 10 (one sweep per Table 1 parameter), Fig. 14 (k = 4 vs 16
// neighbours; microroughness too high) and Fig. 15 (white furnace averaged over surface area,
// Sec. 5). Every D★^f is Algorithm 1 as the models kemppinen_ggx / kemppinen_beckmann evaluate it
// (core/glints/kemppinen.h), with no filtering beyond the model's.
#include "experiments/figures/kemppinen2025.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/glints/kemppinen.h"
#include "core/io/csv.h"
#include "core/io/exr.h"
#include "core/io/png.h"
#include "core/maps/beckmann_map.h"
#include "core/maps/ggx_map.h"
#include "core/math/rng.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/ndf/ndf_kind.h"
#include "core/samplers/walter.h"
#include "experiments/figures/chart_spec.h"
#include "experiments/figures/panel_layout.h"
#include "verify/scenes/kemppinen_furnace.h"
#include "verify/scenes/kemppinen_presets.h"

namespace glintlab::experiments {
namespace {

using V2 = Vec2<double>;
using V3 = Vec3<double>;
using P = kemppinen2025::Params<double>;
constexpr double kPiD = std::numbers::pi;

constexpr std::string_view kFig23Id = "kemppinen2025-fig2-3";
constexpr std::string_view kFig6Id = "kemppinen2025-fig6";
constexpr std::string_view kFig14Id = "kemppinen2025-fig14";
constexpr std::string_view kFig15Id = "kemppinen2025-fig15";
constexpr std::string_view kFig10Id = "kemppinen2025-fig10";

struct NdfChoice {
  std::string_view name;  // "ggx" or "beckmann"
  bool ggx;
};
constexpr std::array<NdfChoice, 2> kNdfs = {{{"ggx", true}, {"beckmann", false}}};

std::string model_name(bool ggx) { return ggx ? "kemppinen_ggx" : "kemppinen_beckmann"; }

std::string params_text(const P& p, double alpha, double cells) {
  return fmt::format(
      "alpha_x={0} alpha_y={0} density={1} microroughness={2} anisotropy={3} filter={4} k={5} "
      "blending={6} erf=exact normalization=corrected colors=white seed={7} footprint_cells={8}",
      alpha, p.density, p.microroughness, p.anisotropy, p.filter, p.side * p.side,
      p.blend == kemppinen2025::Blend::kRoulette ? "roulette" : "linear", p.seed, cells);
}

io::ExrAttributes attributes(std::string_view figure, bool ggx, const std::string& params,
                             std::uint64_t seed) {
  return {{"glintlab_figure", std::string(figure)},
          {"glintlab_model", model_name(ggx)},
          {"glintlab_parameters", params},
          {"glintlab_seed", fmt::format("{}", seed)},
          {"glintlab_version", std::string(glintlab_version())}};
}

std::uint64_t seed_for(std::string_view figure, std::string_view what) {
  return hash_string(fmt::format("{}/{}", figure, what).c_str()) & 0xffffffffu;
}

// One channel of `src` scaled into R, G, B of a preview tile (false colour: grey).
Image grey_tile(const Image& src, const std::string& channel, double scale) {
  Image out(src.width, src.height, {"R", "G", "B"});
  const std::size_t c = src.channel(channel);
  for (int y = 0; y < src.height; ++y)
    for (int x = 0; x < src.width; ++x)
      for (std::size_t k = 0; k < 3; ++k) out.at(x, y, k) = scale * src.at(x, y, c);
  return out;
}

// Tiles of equal size side by side in a grid (RGB), for the PNG previews.
Image montage(const std::vector<Image>& tiles, int columns) {
  const int w = tiles[0].width, h = tiles[0].height;
  const int rows = (static_cast<int>(tiles.size()) + columns - 1) / columns;
  Image out(w * columns, h * rows, {"R", "G", "B"});
  for (std::size_t k = 0; k < tiles.size(); ++k) {
    const int ox = static_cast<int>(k) % columns * w, oy = static_cast<int>(k) / columns * h;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (std::size_t c = 0; c < 3; ++c) out.at(ox + x, oy + y, c) = tiles[k].at(x, y, c);
  }
  return out;
}

// ---- Fig. 2–3: D★^f on U_Ω and on Ω ----------------------------------------------------------

// Fig. 3 setting: α = 0.5 (a wide highlight), α★ = 0.02, footprint 8 level-0 cells (λ = 4, a
// 16 × 16 angular grid at level 4: a few hundred points in U_Ω), k = 4.
constexpr double kFig23Alpha = 0.5, kFig23AlphaStar = 0.02, kFig23Cells = 8;
constexpr int kFig23Positions = 16;

void run_fig2_3(const FigureContext& ctx) {
  const int n = ctx.quick ? 128 : 512;
  const std::uint64_t seed = seed_for(kFig23Id, "points");
  const P p = kemppinen2025::preset_params(2, kFig23AlphaStar, seed);
  const FootprintQuery<double> fp = kemppinen2025::footprint_cells({0.5, 0.5}, kFig23Cells, p);
  const std::string ptext = params_text(p, kFig23Alpha, kFig23Cells);
  struct Row {
    std::string_view ndf, domain;
    double smooth_integral, glinty_integral, explicit_integral, compensation_integral;
    double glinty_max, lambda, area_mean, area_mean_se;
  };
  std::vector<Row> rows;
  std::vector<Image> maps;  // per NDF and domain: smooth, glinty and inside, as mapped
  std::vector<ImageMapPanel> panels;
  maps.reserve(std::size(kNdfs) * 2);
  for (const NdfChoice& nd : kNdfs) {
    with_ndf(ndf_kind(nd.ggx), kFig23Alpha, kFig23Alpha, [&](const auto& ndf) {
      // Prior space: pixel centre p of [0,1]², ratio D★^f/D at ω_h = T⁻¹(p) (uniform 1 for the
      // smooth NDF); its mean over U_Ω equals ∫ D★^f cosθ_h dω_h only where T pushes D cosθ to
      // the uniform density: Beckmann, not the GGX map L∘M̃ as printed (it pushes D cosθ to a
      // non-uniform density: E|q|² = 1/3 instead of ½ on the unit disk; kemppinen.jacobian).
      // Hemisphere: pixel centre (x, y) of the projected disk, ω_h = (x, y, √(1−x²−y²)); the
      // pixel sum of D × pixel area is the same integral (dx dy = cosθ_h dω_h).
      for (std::string_view domain : {"disk", "hemisphere"}) {
        const bool disk = domain == "disk";
        Image img(n, n,
                  {"R", "G", "B", "D_smooth", "D_star_f", "D_star_explicit", "D_star_compensation",
                   "ratio", "inside"});
        double s_int = 0, g_int = 0, e_int = 0, c_int = 0, g_max = 0, lambda = 0;
        for (int y = 0; y < n; ++y) {
          for (int x = 0; x < n; ++x) {
            const double u = (x + 0.5) / n, v = (y + 0.5) / n;
            V3 h;
            bool inside;
            if (disk) {
              inside = (u - 0.5) * (u - 0.5) + (v - 0.5) * (v - 0.5) < 0.25;
              h = map_from_square(ndf, V2{u, v});
            } else {
              const double qx = 2 * u - 1, qy = 1 - 2 * v, r2 = qx * qx + qy * qy;
              inside = r2 < 1;
              h = {qx, qy, std::sqrt(std::max(0.0, 1 - r2))};
            }
            if (!inside || !(h.z > 0)) continue;
            const kemppinen2025::Result<double> r = kemppinen2025::eval(p, ndf, fp, h);
            const double ratio = r.smooth_d > 0 ? r.d.x / r.smooth_d : 0.0;
            const double shown = disk ? ratio : r.d.x;
            img.at(x, y, 0) = img.at(x, y, 1) = img.at(x, y, 2) = shown;
            img.at(x, y, 3) = r.smooth_d;
            img.at(x, y, 4) = r.d.x;
            img.at(x, y, 5) = r.explicit_part.x;
            img.at(x, y, 6) = r.compensation_part.x;
            img.at(x, y, 7) = ratio;
            img.at(x, y, 8) = 1;
            lambda = r.lambda;
            g_max = std::max(g_max, shown);
            // Disk: mean over U_Ω (pixel area 1/n² over |U_Ω| = π/4); hemisphere: area (2/n)².
            const double wgt = disk ? 1.0 / (double(n) * n * (kPiD / 4)) : 4.0 / (double(n) * n);
            s_int += wgt * (disk ? 1.0 : r.smooth_d);
            g_int += wgt * (disk ? ratio : r.d.x);
            e_int += wgt * (disk ? r.explicit_part.x / r.smooth_d : r.explicit_part.x);
            c_int += wgt * (disk ? r.compensation_part.x / r.smooth_d : r.compensation_part.x);
          }
        }
        // The area mean over positions of ∫ D★^f cosθ_h dω_h (hemisphere quadrature at n/2):
        // Eq. 2 asks for 1 (the smooth integral) up to the lobe mass outside U_Ω.
        double a_sum = 0, a_sum2 = 0;
        const int m = n / 2;
        for (int k = 0; k < kFig23Positions; ++k) {
          const V2 uv{1000 * counter_uniform<double>(seed, std::uint64_t(k), 0),
                      1000 * counter_uniform<double>(seed, std::uint64_t(k), 1)};
          const FootprintQuery<double> fk = kemppinen2025::footprint_cells(uv, kFig23Cells, p);
          double integral = 0;
          for (int y = 0; y < m; ++y)
            for (int x = 0; x < m; ++x) {
              const double qx = 2 * (x + 0.5) / m - 1, qy = 2 * (y + 0.5) / m - 1;
              const double r2 = qx * qx + qy * qy;
              if (r2 >= 1) continue;
              const V3 h{qx, qy, std::sqrt(1 - r2)};
              integral += kemppinen2025::eval(p, ndf, fk, h).d.x * 4 / (double(m) * m);
            }
          a_sum += integral, a_sum2 += integral * integral;
        }
        const double a_mean = a_sum / kFig23Positions;
        const double a_se = std::sqrt(std::max(0.0, a_sum2 / kFig23Positions - a_mean * a_mean) /
                                      (kFig23Positions - 1));
        io::write_exr(ctx.dir / fmt::format("{}_{}.exr", nd.name, domain), img,
                      attributes(kFig23Id, nd.ggx, ptext, seed));
        rows.push_back({nd.name, domain, s_int, g_int, e_int, c_int, g_max, lambda, a_mean, a_se});
        // Heat maps: smooth (left) and glinty (right) on one colour bar from 0 to twice the
        // smooth maximum, so that the glints saturate where they concentrate energy.
        double s_max = 0;
        Image& map = maps.emplace_back(n, n, std::vector<std::string>{"smooth", "glinty",
                                                                      "inside"});
        for (int y = 0; y < n; ++y)
          for (int x = 0; x < n; ++x) {
            const double smooth = disk ? img.at(x, y, 8) : img.at(x, y, 3);
            s_max = std::max(s_max, smooth);
            map.at(x, y, 0) = smooth;
            map.at(x, y, 1) = img.at(x, y, 0);
            map.at(x, y, 2) = img.at(x, y, 8);
          }
        const double top = s_max > 0 ? 2 * s_max : 1.0;
        for (const bool glinty : {false, true}) {
          ImageMapPanel mp = image_map_panel(
              fmt::format("{}_{}_{}", nd.name, domain, glinty ? "glinty" : "smooth"),
              fmt::format("{} {}: {} {}", nd.name, domain, glinty ? "glinty" : "smooth",
                          disk ? (glinty ? "D*f / D" : "1") : (glinty ? "D*f" : "D")),
              &map, glinty ? "glinty" : "smooth");
          if (disk) {  // prior-space pixel centres (u, v) = ((x + 0.5) / n, (y + 0.5) / n)
            mp.x0 = mp.y0 = 0.5 / n, mp.dx = mp.dy = 1.0 / n;
            mp.x_label = "prior-space u [1]", mp.y_label = "prior-space v [1]";
            mp.value_label = "D*f / D [1] (smooth: 1)";
          } else {  // projected hemisphere (h.x, h.y) = (2u - 1, 1 - 2v)
            mp.x0 = 1.0 / n - 1, mp.dx = 2.0 / n, mp.y0 = 1 - 1.0 / n, mp.dy = -2.0 / n;
            mp.x_label = "h.x [1] (orthographic)", mp.y_label = "h.y [1] (orthographic)";
            mp.value_label = glinty ? "D*f [1/sr]" : "D [1/sr]";
          }
          mp.value_label += fmt::format(" (above {:.3g} saturates)", top);
          mp.range = {0, top};
          mp.inside = "inside";
          panels.push_back(std::move(mp));
        }
      }
      return 0;
    });
  }
  io::write_csv_atomic(
      ctx.dir / "integrals.csv",
      {"ndf", "domain", "quantity", "alpha", "microroughness", "footprint_cells", "lambda",
       "resolution", "smooth_integral", "glinty_integral", "glinty_explicit_integral",
       "glinty_compensation_integral", "glinty_over_smooth", "glinty_max",
       "area_mean_glinty_hemisphere_integral", "area_mean_se", "area_positions"},
      [&](io::CsvWriter& w) {
        for (const Row& r : rows) {
          w.cell(r.ndf).cell(r.domain);
          w.cell(r.domain == "disk" ? "mean over U_Omega of 1 (smooth) and D_star_f/D (glinty)"
                                    : "integral of D cos and D_star_f cos over the hemisphere");
          w.cell(kFig23Alpha).cell(kFig23AlphaStar);
          w.cell(kFig23Cells).cell(r.lambda).cell_int(n).cell(r.smooth_integral);
          w.cell(r.glinty_integral).cell(r.explicit_integral).cell(r.compensation_integral);
          w.cell(r.glinty_integral / r.smooth_integral).cell(r.glinty_max);
          w.cell(r.area_mean).cell(r.area_mean_se).cell_int(kFig23Positions).end_row();
        }
      });
  write_image_maps(ctx.dir / "fig2_3.png",
                   fmt::format("kemppinen2025-fig2_3: smooth vs glinty NDF over the prior "
                               "square's disk and the projected hemisphere\nfootprint {} cells, "
                               "{} x {} pixels",
                               kFig23Cells, n, n),
                   panels, 4, "value");
}

// ---- Fig. 15: area-averaged white furnace -----------------------------------------------------

// E(θo) = E_x ∫ f★ cosθ_i dω_i, glinty and smooth on the same samples
// (verify/scenes/kemppinen_furnace.h, as kemppinen.furnace; k = 4).
struct FurnaceRow {
  std::string_view ndf;
  double alpha, alpha_star, theta;
  double glint, glint_se, smooth, smooth_se;
};

FurnaceRow furnace(const NdfChoice& nd, double alpha, double alpha_star, double theta_deg,
                   std::uint64_t n, std::uint64_t seed) {
  const P p = kemppinen2025::preset_params(2, alpha_star, seed);
  const double t = theta_deg * kPiD / 180;
  const V3 wo{std::sin(t) * std::cos(0.3), std::sin(t) * std::sin(0.3), std::cos(t)};
  double sg = 0, sg2 = 0, ss = 0, ss2 = 0;
  with_ndf(ndf_kind(nd.ggx), alpha, alpha, [&](const auto& ndf) {
    for (std::uint64_t i = 0; i < n; ++i) {
      const V2 u{counter_uniform<double>(seed, i, 2), counter_uniform<double>(seed, i, 3)};
      const V2 uv{1000 * counter_uniform<double>(seed, i, 0),
                  1000 * counter_uniform<double>(seed, i, 1)};
      const kemppinen2025::FurnaceSample f = kemppinen2025::furnace_sample(p, ndf, wo, uv, u);
      sg += f.glint, sg2 += f.glint * f.glint, ss += f.smooth, ss2 += f.smooth * f.smooth;
    }
    return 0;
  });
  const double nn = double(n);
  auto se = [&](double s1, double s2) {
    return std::sqrt(std::max(0.0, (s2 - s1 * s1 / nn) / (nn - 1)) / nn);
  };
  return {nd.name, alpha, alpha_star, theta_deg, sg / nn, se(sg, sg2), ss / nn, se(ss, ss2)};
}

void run_fig15(const FigureContext& ctx) {
  const std::uint64_t n = ctx.quick ? 1500 : 40000;
  const double step = ctx.quick ? 10 : 5;
  const std::array<double, 2> alphas = {0.1, 0.5};
  constexpr double kAlphaStar = 0.02;
  std::vector<FurnaceRow> rows;
  long done = 0;
  const long total = 2 * 2 * static_cast<long>(85 / step + 1);
  for (const NdfChoice& nd : kNdfs)
    for (double a : alphas)
      for (double th = 0; th <= 85 + 1e-9; th += step) {
        rows.push_back(furnace(nd, a, kAlphaStar, th, n,
                               seed_for(kFig15Id, fmt::format("{}/{}/{}", nd.name, a, th))));
        if (ctx.progress) ctx.progress("kemppinen2025-fig15 furnace", ++done, total);
      }
  io::write_csv_atomic(
      ctx.dir / "furnace.csv",
      {"ndf", "alpha", "microroughness", "theta_o_deg", "samples", "energy_glinty",
       "energy_glinty_se", "energy_smooth", "energy_smooth_se", "glinty_minus_smooth"},
      [&](io::CsvWriter& w) {
        for (const FurnaceRow& r : rows) {
          w.cell(r.ndf).cell(r.alpha).cell(r.alpha_star).cell(r.theta);
          w.cell_int(static_cast<long long>(n)).cell(r.glint).cell(r.glint_se);
          w.cell(r.smooth).cell(r.smooth_se).cell(r.glint - r.smooth).end_row();
        }
      });
  // Chart (drawn by reports/figure_charts.py): energy over θo, one panel per NDF; GGX blue,
  // Beckmann red, glinty solid and dark, smooth dashed and light, α = 0.5 the darker; ±2 s.e.
  ChartSpec chart{
      .title = fmt::format("{}: area-averaged white furnace over theta_o, glinty vs smooth",
                           kFig15Id),
      .csv = "furnace.csv"};
  for (const NdfChoice& nd : kNdfs) {
    ChartPanel panel{
        .title = fmt::format("{}: glinty (solid) vs smooth (dashed), +-2 s.e., {} samples",
                             nd.ggx ? "GGX" : "Beckmann", n),
        .where = {{"ndf", std::string(nd.name)}},
        .x = {.column = "theta_o_deg",
              .label = "outgoing angle theta_o [deg]",
              .range = std::array{0.0, 85.0}},
        .y = {.label = "white-furnace energy (reflected / incident) [1]"},
        .hlines = {{1.0, "energy 1 (no loss, no gain)"}}};
    for (double a : alphas) {
      const double shade = a < 0.3 ? 1.0 : 0.6;
      const ChartWhere where{{"alpha", fmt::format("{}", a)}};
      panel.series.push_back({.label = fmt::format("alpha {}, glinty", a),
                              .where = where,
                              .y = "energy_glinty",
                              .y_error = "energy_glinty_se",
                              .y_error_scale = 2,
                              .color = nd.ggx ? std::array{0.0, 0.0, shade}
                                              : std::array{shade, 0.0, 0.0}});
      panel.series.push_back({.label = fmt::format("alpha {}, smooth", a),
                              .where = where,
                              .y = "energy_smooth",
                              .y_error = "energy_smooth_se",
                              .y_error_scale = 2,
                              .color = nd.ggx ? std::array{0.5, 0.7, 1.0}
                                              : std::array{1.0, 0.6, 0.5},
                              .line = "dashed",
                              .marker = "s"});
    }
    chart.panels.push_back(std::move(panel));
  }
  write_chart_spec(ctx.dir / "furnace.png", chart);
}

// ---- Fig. 14: limitations ----------------------------------------------------------------

// Left: background brightening with a large microroughness: ratio D★^f/D at an off-peak ω_h
// (θ_h = 2.5 α) over positions (columns) and footprints growing from 1 to 2^9 cells (rows), k = 4
// vs 16. Right: a smooth surface (α = 0.05) with α★ = 0.02 vs 0.5: the area-mean D★^f over θ_h.
void run_fig14(const FigureContext& ctx) {
  const int w = ctx.quick ? 48 : 192, hgt = ctx.quick ? 32 : 128;
  const int per_row = ctx.quick ? 64 : 512;
  constexpr double kAlpha = 0.3, kAlphaStarHigh = 0.3;
  const std::uint64_t seed = seed_for(kFig14Id, "points");
  struct Row {
    int k;
    double cells, mean_ratio, mean_abs_error;
  };
  std::vector<Row> rows;
  std::vector<Image> maps;
  maps.reserve(2);
  const GGX<double> ggx{kAlpha, kAlpha};
  const double th = std::atan(2.5 * kAlpha);
  const V3 h{std::sin(th), 0, std::cos(th)};
  for (int side : {2, 4}) {
    const P p = kemppinen2025::preset_params(side, kAlphaStarHigh, seed);
    Image img(w, hgt, {"R", "G", "B", "ratio", "error_vs_D"});
    for (int y = 0; y < hgt; ++y) {
      const double cells = std::exp2(9.0 * y / (hgt - 1));
      double sum = 0, sum_abs = 0;
      for (int i = 0; i < std::max(per_row, w); ++i) {
        const V2 uv{1000 * counter_uniform<double>(seed, std::uint64_t(y) * 100000 + i, 0),
                    1000 * counter_uniform<double>(seed, std::uint64_t(y) * 100000 + i, 1)};
        const kemppinen2025::Result<double> r =
            kemppinen2025::eval(p, ggx, kemppinen2025::footprint_cells(uv, cells, p), h);
        const double ratio = r.d.x / r.smooth_d;
        if (i < w) {
          img.at(i, y, 0) = img.at(i, y, 1) = img.at(i, y, 2) = img.at(i, y, 3) = ratio;
          img.at(i, y, 4) = ratio - 1;
        }
        if (i < per_row) sum += ratio, sum_abs += std::abs(ratio - 1);
      }
      rows.push_back({side * side, cells, sum / per_row, sum_abs / per_row});
    }
    io::write_exr(ctx.dir / fmt::format("background_k{}.exr", side * side), img,
                  attributes(kFig14Id, true, params_text(p, kAlpha, -1), seed));
    maps.push_back(std::move(img));
  }
  io::write_csv_atomic(ctx.dir / "background.csv",
                       {"k", "footprint_cells", "lambda", "alpha", "microroughness", "theta_h_deg",
                        "positions", "mean_ratio_to_D", "mean_abs_error_vs_D"},
                       [&](io::CsvWriter& wr) {
                         for (const Row& r : rows) {
                           wr.cell_int(r.k).cell(r.cells).cell(std::log2(2 * r.cells)).cell(kAlpha);
                           wr.cell(kAlphaStarHigh).cell(th * 180 / kPiD).cell_int(per_row);
                           wr.cell(r.mean_ratio).cell(r.mean_abs_error).end_row();
                         }
                       });
  // Row y of an image: footprint 2^(9 y / (hgt - 1)) cells; column: a position.
  std::vector<ImageMapPanel> panels;
  for (std::size_t k = 0; k < maps.size(); ++k) {
    ImageMapPanel mp = image_map_panel(fmt::format("k{}", k == 0 ? 4 : 16),
                           fmt::format("k = {}", k == 0 ? 4 : 16), &maps[k], "ratio");
    mp.dy = 9.0 / (hgt - 1);
    mp.x_label = "position index [1]", mp.y_label = "log2 footprint cells [1]";
    mp.value_label = "D*f / D [1] (1: the smooth D; above 2 saturates)";
    mp.range = {0, 2};
    mp.top_down = false;
    panels.push_back(std::move(mp));
  }
  write_image_maps(ctx.dir / "background.png",
                   fmt::format("kemppinen2025-fig14: D*f / D at theta_h {:.3g} deg over "
                               "positions and footprint size\nGGX alpha {}, microroughness {}",
                               th * 180 / kPiD, kAlpha, kAlphaStarHigh),
                   panels, 2, "ratio");

  // Right pair: the highlight's shape, area mean of D★^f over θ_h (φ_h = 0), footprint 64 cells.
  constexpr double kSmoothAlpha = 0.05;
  const GGX<double> smooth{kSmoothAlpha, kSmoothAlpha};
  const int n_theta = ctx.quick ? 16 : 48, positions = ctx.quick ? 48 : 400;
  io::write_csv_atomic(
      ctx.dir / "highlight_shape.csv",
      {"theta_h_deg", "alpha", "D_smooth", "mean_D_star_f_microroughness_0.02",
       "mean_D_star_f_microroughness_0.5", "positions"},
      [&](io::CsvWriter& wr) {
        for (int t = 0; t < n_theta; ++t) {
          const double deg = 12.0 * t / (n_theta - 1);
          const double a = deg * kPiD / 180;
          const V3 hh{std::sin(a), 0, std::cos(a)};
          double m_lo = 0, m_hi = 0;
          for (double as : {0.02, 0.5}) {
            const P p = kemppinen2025::preset_params(2, as, seed);
            double s = 0;
            for (int i = 0; i < positions; ++i) {
              const V2 uv{1000 * counter_uniform<double>(seed, std::uint64_t(i), 4),
                          1000 * counter_uniform<double>(seed, std::uint64_t(i), 5)};
              s +=
                  kemppinen2025::eval(p, smooth, kemppinen2025::footprint_cells(uv, 64, p), hh).d.x;
            }
            (as < 0.1 ? m_lo : m_hi) = s / positions;
          }
          wr.cell(deg).cell(kSmoothAlpha).cell(smooth.D(hh)).cell(m_lo).cell(m_hi);
          wr.cell_int(positions).end_row();
        }
      });
}

// ---- Fig. 6: roulette vs linear blending across a LOD transition ----------------------------

// Columns: footprints from λ = 3 to λ = 5 (cells = 2^λ / 2); rows: positions. ω_h = the normal
// (the highlight's centre). Per column and blend: mean, coefficient of variation, the fraction
// of "lit" pixels (D★^f above 2 D) with their mean intensity, and the 99th percentile: linear
// blending at λ = n + ½ averages two point sets, twice the glints at half the intensity (lower
// variation than either level), which the roulette avoids (Sec. 3.3.3).
void run_fig6(const FigureContext& ctx) {
  const int cols = ctx.quick ? 17 : 65, rows_n = ctx.quick ? 1000 : 10000, img_rows = 64;
  constexpr double kAlpha = 0.3, kAlphaStar = 0.005;
  const std::uint64_t seed = seed_for(kFig6Id, "points");
  const GGX<double> ggx{kAlpha, kAlpha};
  const V3 h{0, 0, 1};
  struct Row {
    std::string_view blend;
    double lambda, w1, mean, cv, lit_fraction, lit_mean, p99, max;
  };
  std::vector<Row> out;
  std::vector<Image> maps;
  maps.reserve(2);
  for (kemppinen2025::Blend blend :
       {kemppinen2025::Blend::kRoulette, kemppinen2025::Blend::kLinear}) {
    P p = kemppinen2025::preset_params(2, kAlphaStar, seed);
    p.blend = blend;
    const std::string_view name = blend == kemppinen2025::Blend::kRoulette ? "roulette" : "linear";
    Image img(cols, img_rows, {"R", "G", "B", "D_star_f", "D_star_explicit"});
    for (int c = 0; c < cols; ++c) {
      const double lambda = 3.0 + 2.0 * c / (cols - 1);
      const double cells = std::exp2(lambda) / 2;
      std::vector<double> d(static_cast<std::size_t>(rows_n));
      double w1 = 0;
      for (int i = 0; i < rows_n; ++i) {
        // The same positions in every column and for both blends (paired comparison).
        const V2 uv{1000 * counter_uniform<double>(seed, std::uint64_t(i), 0),
                    1000 * counter_uniform<double>(seed, std::uint64_t(i), 1)};
        const kemppinen2025::Result<double> r =
            kemppinen2025::eval(p, ggx, kemppinen2025::footprint_cells(uv, cells, p), h);
        d[std::size_t(i)] = r.d.x, w1 = r.w1;
        if (i < img_rows) {
          img.at(c, i, 0) = img.at(c, i, 1) = img.at(c, i, 2) = img.at(c, i, 3) = r.d.x;
          img.at(c, i, 4) = r.explicit_part.x;
        }
      }
      double s = 0, s2 = 0, mx = 0;
      for (double v : d) s += v, s2 += v * v, mx = std::max(mx, v);
      const double mean = s / rows_n;
      const double var = std::max(0.0, s2 / rows_n - mean * mean);
      double lit = 0, lit_sum = 0;
      for (double v : d) {
        if (v > 2 * ggx.D(h)) lit += 1, lit_sum += v;
      }
      std::vector<double> sorted = d;
      std::sort(sorted.begin(), sorted.end());
      const double p99 = sorted[static_cast<std::size_t>(0.99 * (rows_n - 1))];
      out.push_back({name, lambda, w1, mean, mean > 0 ? std::sqrt(var) / mean : 0, lit / rows_n,
                     lit > 0 ? lit_sum / lit : 0, p99, mx});
    }
    io::write_exr(ctx.dir / fmt::format("strip_{}.exr", name), img,
                  attributes(kFig6Id, true, params_text(p, kAlpha, -1), seed));
    maps.push_back(std::move(img));
  }
  io::write_csv_atomic(ctx.dir / "blending.csv",
                       {"blending", "lambda", "w_level1", "footprint_cells", "positions",
                        "mean_D_star_f", "cv_D_star_f", "lit_fraction", "lit_mean_D_star_f",
                        "p99_D_star_f", "max_D_star_f", "D_smooth"},
                       [&](io::CsvWriter& w) {
                         for (const Row& r : out) {
                           w.cell(r.blend).cell(r.lambda).cell(r.w1).cell(std::exp2(r.lambda) / 2);
                           w.cell_int(rows_n).cell(r.mean).cell(r.cv).cell(r.lit_fraction);
                           w.cell(r.lit_mean).cell(r.p99).cell(r.max).cell(ggx.D(h)).end_row();
                         }
                       });
  // Column c of an image: LOD lambda = 3 + 2 c / (cols - 1); row: a position. The maps show
  // D*f / D(h), as the preview did.
  std::vector<ImageMapPanel> panels;
  for (std::size_t k = 0; k < maps.size(); ++k) {
    Image& img = maps[k];
    const std::size_t c = img.channel("D_star_f");
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) img.at(x, y, c) /= ggx.D(h);
    const std::string blend = k == 0 ? "roulette" : "linear";
    ImageMapPanel mp = image_map_panel(blend, blend + " blending", &img, "D_star_f");
    mp.x0 = 3, mp.dx = 2.0 / (cols - 1);
    mp.x_label = "LOD lambda [1]", mp.y_label = "position index [1]";
    mp.value_label = "D*f / D(h) [1] (above 2 saturates)";
    mp.range = {0, 2};
    mp.top_down = false;
    panels.push_back(std::move(mp));
  }
  write_image_maps(ctx.dir / "strip.png",
                   fmt::format("kemppinen2025-fig6: D*f at normal incidence over the LOD, per "
                               "blending\nGGX alpha {}, microroughness {}, {} positions shown",
                               kAlpha, kAlphaStar, img_rows),
                   panels, 1, "D_star_f_over_D");
}

// ---- Fig. 10: one sweep per parameter ----------------------------------------------------

// A glinty GGX plane z = 0, x, y ∈ [−1, 1] (uv = 4 xy), seen by a pinhole camera at (0, 0, 1.5)
// and lit by a unit point light at (0.6, 0, 1.5): radiance G2 D★^f / (4 cosθ_o) / r², the pixel
// footprint from the pixel spacing (no Fresnel). Rows: roughness α, microroughness α★, density
// K_P, anisotropy a; each varied over five values, the others at α = 0.2, α★ = 0.02, K_P = 10⁴,
// a = 1, k = 4 (Table 1 parameters).
struct SweepParam {
  std::string_view name;
  std::array<double, 5> values;
};
constexpr std::array<SweepParam, 4> kSweeps = {{
    {"alpha", {0.05, 0.1, 0.2, 0.4, 0.8}},
    {"microroughness", {0.005, 0.01, 0.02, 0.05, 0.1}},
    {"density", {1e2, 1e3, 1e4, 1e5, 1e6}},
    {"anisotropy", {0.25, 0.5, 1, 2, 4}},
}};

void run_fig10(const FigureContext& ctx) {
  // One footprint-filtered evaluation per pixel (no sampling): cheap enough for 512 at full.
  const int n = ctx.quick ? 128 : 512;
  constexpr double kUvScale = 4;
  const std::uint64_t seed = seed_for(kFig10Id, "points");
  const V3 cam{0, 0, 1.5}, light{0.6, 0, 1.5};
  struct Row {
    std::string_view param;
    double value, mean, smooth_mean, cv, lit_fraction, max;
  };
  std::vector<Row> rows;
  std::vector<Image> tiles;
  double exposure = 0;
  for (const SweepParam& sw : kSweeps) {
    Image strip(5 * n, n, {"R", "G", "B", "radiance_smooth"});
    for (std::size_t k = 0; k < sw.values.size(); ++k) {
      const double v = sw.values[k];
      double alpha = 0.2;
      P p = kemppinen2025::preset_params(2, 0.02, seed);
      if (sw.name == "alpha") alpha = v;
      if (sw.name == "microroughness") p.microroughness = v;
      if (sw.name == "density") p.density = v;
      if (sw.name == "anisotropy") p.anisotropy = v;
      const GGX<double> ggx{alpha, alpha};
      double s = 0, s2 = 0, sm = 0, mx = 0, lit = 0;
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const V3 pos{2 * (x + 0.5) / n - 1, 1 - 2 * (y + 0.5) / n, 0};
          const V3 wo = normalize(cam - pos), to_light = light - pos;
          const double r2 = dot(to_light, to_light);
          const V3 wi = (1 / std::sqrt(r2)) * to_light;
          const V3 h = normalize(wi + wo);
          const double d = 2.0 / n * kUvScale;
          const FootprintQuery<double> fp{{pos.x * kUvScale, pos.y * kUvScale}, {d, 0}, {0, d}};
          const kemppinen2025::Result<double> r = kemppinen2025::eval(p, ggx, fp, h);
          const double g = smith_g2_height_correlated(ggx, wi, wo, h) / (4 * wo.z * r2);
          const double rad = g * r.d.x, smooth = g * r.smooth_d;
          const int ox = static_cast<int>(k) * n;
          strip.at(ox + x, y, 0) = strip.at(ox + x, y, 1) = strip.at(ox + x, y, 2) = rad;
          strip.at(ox + x, y, 3) = smooth;
          s += rad, s2 += rad * rad, sm += smooth, mx = std::max(mx, rad);
          if (rad > 2 * smooth && rad > 0) lit += 1;
        }
      const double np = double(n) * n, mean = s / np;
      rows.push_back({sw.name, v, mean, sm / np,
                      mean > 0 ? std::sqrt(std::max(0.0, s2 / np - mean * mean)) / mean : 0,
                      lit / np, mx});
      if (sw.name == "alpha" && v == 0.2) {
        for (int y = 0; y < n; ++y)
          for (int x = 0; x < n; ++x)
            exposure = std::max(exposure, strip.at(static_cast<int>(k) * n + x, y, 3));
      }
    }
    io::write_exr(ctx.dir / fmt::format("sweep_{}.exr", sw.name), strip,
                  attributes(kFig10Id, true,
                             fmt::format("sweep of {} over {} {} {} {} {}; others: alpha=0.2 "
                                         "microroughness=0.02 density=1e4 anisotropy=1 k=4 "
                                         "filter=0.5 seed={}",
                                         sw.name, sw.values[0], sw.values[1], sw.values[2],
                                         sw.values[3], sw.values[4], seed),
                             seed));
    tiles.push_back(std::move(strip));
  }
  io::write_csv_atomic(
      ctx.dir / "sweeps.csv",
      {"parameter", "value", "mean_radiance", "mean_radiance_smooth", "glinty_over_smooth",
       "cv_radiance", "lit_fraction", "max_radiance", "resolution"},
      [&](io::CsvWriter& w) {
        for (const Row& r : rows) {
          w.cell(r.param).cell(r.value).cell(r.mean).cell(r.smooth_mean);
          w.cell(r.mean / r.smooth_mean).cell(r.cv).cell(r.lit_fraction).cell(r.max);
          w.cell_int(n).end_row();
        }
      });
  std::vector<Image> rgb;
  for (const Image& t : tiles) rgb.push_back(grey_tile(t, "R", exposure > 0 ? 0.7 / exposure : 1));
  io::write_png_preview(ctx.dir / "sweeps.png", montage(rgb, 1));
  std::vector<std::string> labels;
  for (const SweepParam& sw : kSweeps)
    for (double v : sw.values) labels.push_back(fmt::format("{} {}", sw.name, v));
  write_panel_layout(ctx.dir / "sweeps.png",
                     {"kemppinen2025-fig10: a glinty GGX plane under a point light, one "
                      "parameter swept per row (others alpha 0.2, microroughness 0.02, density "
                      "1e4, anisotropy 1)",
                      5,
                      0,
                      labels});
}

}  // namespace

FigureEntry kemppinen2025_fig2_3_entry() {
  return {kFig23Id, "Kemppinen et al. 2025", "Fig. 2-3",
          "D_star_f (Algorithm 1) on the prior disk U_Omega (as D_star_f/D) and on the "
          "hemisphere, smooth vs glinty, GGX and Beckmann alpha 0.5; integrals in a CSV",
          run_fig2_3};
}

FigureEntry kemppinen2025_fig6_entry() {
  return {kFig6Id, "Kemppinen et al. 2025", "Fig. 6",
          "roulette (Eq. 8) vs linear MIP blending across lambda 3..5: strip of footprints, "
          "per-glint intensity statistics",
          run_fig6};
}

FigureEntry kemppinen2025_fig14_entry() {
  return {kFig14Id, "Kemppinen et al. 2025", "Fig. 14",
          "limitations: background brightening with k = 4 vs 16 at microroughness 0.3 over "
          "footprint size; highlight shape of alpha 0.05 with microroughness 0.02 vs 0.5",
          run_fig14};
}

FigureEntry kemppinen2025_fig15_entry() {
  return {kFig15Id, "Kemppinen et al. 2025", "Fig. 15",
          "white furnace over theta_o averaged over surface area, glinty vs smooth GGX and "
          "Beckmann, alpha 0.1 and 0.5 (CSV + chart)",
          run_fig15};
}

FigureEntry kemppinen2025_fig10_entry() {
  return {kFig10Id, "Kemppinen et al. 2025", "Fig. 10",
          "one sweep per parameter (roughness, microroughness, density, anisotropy; five values "
          "each) on a glinty GGX plane under a point light: images and radiance statistics",
          run_fig10};
}

}  // namespace glintlab::experiments

// Figure experiments of Kneiphof & Klein 2024 on a glinty GGX plane seen from above: Fig. 6 (the
// cap probability of Eq. 20 against Deliot & Belcour's R fitted at normal incidence, and the
// p > 1 region), Fig. 9 (a 2^4 × 2^4 subdivided light: Monte Carlo terms vs the single LTC lobe),
// Fig. 10 (convergence to the smooth BRDF as N_P quadruples) and a Table 1 analogue (time per
// evaluation, read from the Google Benchmark JSON of experiments/bench/bench_glints.cpp in the
// --bench-from folder; without one it says so and prints only the paper's row).
//
// The scene: the plane z = 0, uv = (x, y) ∈ [−1, 1]², the viewer at C = (0, −1, 1.2); a pixel's
// footprint is its square in uv (the plane is rendered top-down, the viewer direction varies as
// seen from C). Lights: directional along the mirror direction of the plane's centre, (0, 1, 1.2)
// normalised, or a horizontal square of half-width w centred at (0, 1, 1.2) emitting downward.
// Radiance: L_i = 1 (area) or irradiance E = 1 (directional); F = 1.
#include "experiments/figures/kneiphof2024.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "core/glints/binomial.h"
#include "core/glints/deliot_belcour.h"
#include "core/glints/kneiphof.h"
#include "core/glints/kneiphof_ltc.h"
#include "core/lights/polygon_light_check.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/io/exr.h"
#include "core/io/png.h"
#include "core/ltc/ltc_table.h"
#include "core/ndf/total_area.h"
#include "core/render/image.h"
#include "experiments/figures/bench_json.h"
#include "experiments/figures/chart_spec.h"
#include "experiments/figures/panel_layout.h"

namespace glintlab::experiments {
namespace {

constexpr Vec3<double> kEye{0, -1, 1.2};

// Seeds derived from the figure id (never hand-picked).
std::uint64_t figure_seed(std::string_view id, std::uint64_t k) {
  return mix64(hash_string(std::string(id).c_str()) + k);
}
const Vec3<double> kSunDir = normalize(Vec3<double>{0, 1, 1.2});

io::ExrAttributes attributes(std::string_view id, const std::string& what) {
  return {{"glintlab_figure", std::string(id)},
          {"glintlab_version", std::string(glintlab_version())},
          {"content", what}};
}

// Grey RGB tile from a scalar field.
Image tile(int size, const std::vector<double>& v, double scale) {
  Image im(size, size, {"R", "G", "B"});
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (std::size_t c = 0; c < 3; ++c)
        im.at(x, y, c) = scale * v[std::size_t(y) * std::size_t(size) + std::size_t(x)];
  return im;
}

Image montage(const std::vector<Image>& images, int columns) {
  const int w = images[0].width, h = images[0].height, gap = 2;
  const int rows = (int(images.size()) + columns - 1) / columns;
  Image out(columns * (w + gap) - gap, rows * (h + gap) - gap, {"R", "G", "B"});
  for (std::size_t k = 0; k < images.size(); ++k) {
    const int ox = int(k) % columns * (w + gap), oy = int(k) / columns * (h + gap);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (std::size_t c = 0; c < 3; ++c) out.at(ox + x, oy + y, c) = images[k].at(x, y, c);
  }
  return out;
}

struct Pixel {
  Vec3<double> p, wi;
  FootprintQuery<double> footprint;
  std::uint64_t index;
};

Pixel pixel(int size, int x, int y) {
  Pixel px;
  const double side = 2.0 / size;
  px.p = {-1 + side * (x + 0.5), 1 - side * (y + 0.5), 0};
  px.wi = normalize(kEye - px.p);
  px.footprint = {{px.p.x, px.p.y}, {side, 0}, {0, side}};
  px.index = std::uint64_t(y) * std::uint64_t(size) + std::uint64_t(x);
  return px;
}

// A horizontal square of half-width w at (cx, cy, h), emitting downward.
std::array<Vec3<double>, 4> square_light(double w) {
  const double cx = 0, cy = 1, h = 1.2;
  return {Vec3<double>{cx - w, cy + w, h}, Vec3<double>{cx + w, cy + w, h},
          Vec3<double>{cx + w, cy - w, h}, Vec3<double>{cx - w, cy - w, h}};
}

PolygonLight<double> polygon(const std::array<Vec3<double>, 4>& v) {
  return make_polygon_light(std::span<const Vec3<double>>(v), {1, 1, 1});
}

double scale_to_peak(const std::vector<double>& smooth) {
  double m = 0;
  for (double v : smooth) m = std::max(m, v);
  return m > 0 ? 0.8 / m : 1.0;
}

// ---- Fig. 6 --------------------------------------------------------------------------------
constexpr std::string_view kFig6 = "kneiphof2024-fig6";

double p_normal(double alpha, double gamma_deg) {
  const GGX<double> g{alpha, alpha};
  const Vec3<double> n{0, 0, 1};
  return kneiphof2024::cap_probability_eq20(
      g, n, n, one_minus_cos(gamma_deg * std::numbers::pi / 180), total_area_ggx_eq29(alpha));
}

// The chart spec of p_map.png: p of Eq. 20 at normal incidence over (γ, √α), the γ grid
// logarithmic (its columns evenly spaced in log γ), p on a log colour scale, the cells with p > 1
// outlined in red.
void write_p_map_spec(const std::filesystem::path& png, const std::string& csv, int na, int ng) {
  const nlohmann::json panel = {
      {"title", fmt::format("p of Eq. 20 at normal incidence, {} x {} cells", ng, na)},
      {"x",
       {{"column", "gamma_deg"},
        {"label", "cap half-angle gamma [deg] (log spacing)"},
        {"ticks", 4}}},
      {"y",
       {{"columns", {"sqrt_alpha"}}, {"format", "{sqrt_alpha:.3g}"}, {"label", "sqrt(alpha) [1]"}}},
      {"value",
       {{"column", "p_eq20"},
        {"label", "cap probability p (Eq. 20) [1] (log scale)"},
        {"log", true}}},
      {"flags",
       {{{"column", "p_gt_1"},
         {"value", 1},
         {"label", "p > 1 (not a probability)"},
         {"color", {1.0, 0.0, 0.0}},
         {"style", "outline"}}}}};
  write_chart_json(png, {
      {"kind", "heatmap"},
      {"title",
       "kneiphof2024-fig6: p of Eq. 20 over gamma and sqrt(alpha)\nGGX, normal incidence "
       "(R of Deliot & Belcour = p)"},
      {"csv", csv},
      {"panels", {panel}}});
}

void run_fig6(const FigureContext& ctx) {
  // One closed-form evaluation per pixel centre: cheap enough for 512 pixels at full.
  const int size = ctx.quick ? 128 : 512;
  const double density = 7.0;  // log10 facets per unit uv area
  std::vector<Image> tiles;
  struct RRow {
    double sa, gamma, r;
    double clamped_fraction;
  };
  std::vector<RRow> rrows;
  for (double sa : {0.1, 0.5, 0.9}) {
    for (double gd : {0.26, 5.0}) {
      const double a = sa * sa, r = p_normal(a, gd);
      const auto kk = KneiphofKlein::params<double>(std::vector<double>{a, a, density, gd, 0, 6});
      const auto db = DeliotBelcour::params<double>(std::vector<double>{a, a, density, r, 0, 6});
      const std::size_t n = std::size_t(size) * std::size_t(size);
      std::vector<double> vk(n), vd(n), vs(n);
      std::vector<int> clamped(n, 0);
      tbb::parallel_for(0, size, [&](int y) {
        for (int x = 0; x < size; ++x) {
          const Pixel px = pixel(size, x, y);
          ModelQuery<double> q{px.footprint, px.wi, kSunDir, {1.0, 1.0}};
          const auto ek = KneiphofKlein::eval(kk, q);
          const auto ed = DeliotBelcour::eval(db, q);
          const std::size_t i = std::size_t(px.index);
          vk[i] = ek.value;
          vd[i] = ed.value;
          vs[i] = ek.intermediates[6];
          clamped[i] = ek.intermediates[3] > 0;
        }
      });
      const double sc = scale_to_peak(vs);
      Image both(size, size, {"kneiphof_klein", "deliot_belcour", "smooth", "p_clamped"});
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const std::size_t i = std::size_t(y) * std::size_t(size) + std::size_t(x);
          both.at(x, y, 0) = vk[i], both.at(x, y, 1) = vd[i], both.at(x, y, 2) = vs[i];
          both.at(x, y, 3) = clamped[i];
        }
      io::write_exr(ctx.dir / fmt::format("sa{}_gamma{}.exr", sa, gd), both,
                    attributes(kFig6, fmt::format("sqrt_alpha={} gamma_deg={} R={}", sa, gd, r)));
      tiles.push_back(tile(size, vk, sc));
      tiles.push_back(tile(size, vd, sc));
      double frac = 0;
      for (int c : clamped) frac += c;
      rrows.push_back({sa, gd, r, frac / double(n)});
    }
  }
  // Columns: γ = 0.26° (K&K, D&B), γ = 5° (K&K, D&B); rows √α = 0.1, 0.5, 0.9 — as Fig. 6.
  io::write_png_preview(ctx.dir / "fig6.png", montage(tiles, 4));
  std::vector<std::string> labels;
  for (const RRow& r : rrows)
    for (std::string_view model : {"Kneiphof & Klein", "Deliot & Belcour"})
      labels.push_back(fmt::format("sqrt(alpha) {}, gamma {} deg: {}", r.sa, r.gamma, model));
  write_panel_layout(ctx.dir / "fig6.png",
                     {"kneiphof2024-fig6: glints of the two models under a cap light (grey = "
                      "0.8 x radiance / smooth peak)",
                      4,
                      2,
                      labels});
  io::write_csv_atomic(
      ctx.dir / "fig6.csv",
      {"sqrt_alpha", "gamma_deg", "R_fitted", "p_normal_incidence", "p_gt_1",
       "clamped_pixel_fraction"},
      [&](io::CsvWriter& w) {
        for (const RRow& r : rrows) {
          w.cell(r.sa).cell(r.gamma).cell(r.r).cell(r.r).cell_int(r.r > 1).cell(r.clamped_fraction);
          w.end_row();
        }
      });
  // The p > 1 map at normal incidence over (√α, γ): its numbers in p_map.csv, drawn by matplotlib
  // into p_map.png (write_p_map_spec).
  const int na = ctx.quick ? 17 : 81, ng = ctx.quick ? 13 : 61;
  io::write_csv_atomic(ctx.dir / "p_map.csv", {"sqrt_alpha", "gamma_deg", "p_eq20", "p_gt_1"},
                       [&](io::CsvWriter& w) {
                         for (int i = 0; i < na; ++i)
                           for (int j = 0; j < ng; ++j) {
                             const double sa = 0.1 + 0.8 * i / (na - 1);
                             const double gd = 0.1 * std::pow(200.0, double(j) / (ng - 1));
                             const double p = p_normal(sa * sa, gd);
                             w.cell(sa).cell(gd).cell(p).cell_int(p > 1);
                             w.end_row();
                           }
                       });
  write_p_map_spec(ctx.dir / "p_map.png", "p_map.csv", na, ng);
  std::string md =
      "# kneiphof2024-fig6\n\nR making Deliot & Belcour equal to Eq. 20 at normal incidence "
      "(R = p, since D(h)/D(n) = 1 there). The paper gives no numbers; it states p > 1 (and R > 1) "
      "for √α = 0.1, γ = 5°.\n\n| √α | γ | R = p | p > 1 |\n|---|---|---|---|\n";
  for (const RRow& r : rrows)
    md += fmt::format("| {} | {}° | {:.4g} | {} |\n", r.sa, r.gamma, r.r, r.r > 1 ? "yes" : "no");
  md +=
      "\nfig6.png: rows √α = 0.1, 0.5, 0.9; columns (γ = 0.26°: K&K, D&B), (γ = 5°: K&K, D&B); "
      "p_map.png: p at normal incidence over γ (x, 0.1°..20° log) and √α (y, 0.1 bottom..0.9 "
      "top), red where p > 1.\n";
  io::write_file_atomic(ctx.dir / "summary.md", md);
}

// ---- Fig. 9 --------------------------------------------------------------------------------
constexpr std::string_view kFig9 = "kneiphof2024-fig9";

void run_fig9(const FigureContext& ctx) {
  // Pixels a person can see (128² quick, 512² full) with fewer samples per sub-light: every pixel
  // integrates 256 sub-lights, so 512² at 2 samples costs about what 256² at 8 did.
  const int size = ctx.quick ? 128 : 512;
  const int samples = ctx.quick ? 1 : 2;  // MC samples per sub-light (and ×256 for the whole)
  const double alpha = 0.25, density = 6.0;
  const GGX<double> g{alpha, alpha};
  const double dh = total_area_ggx_eq29(alpha);
  const LtcTableView& table = ltc_ggx_table_view();
  std::vector<Image> tiles;
  struct Row {
    double w, mc_rel_rms, ltc_max, ltc_vs_mc_rel_rms;
  };
  std::vector<Row> rows;
  for (double w : {0.4, 0.1}) {
    const auto quad = square_light(w);
    const PolygonLight<double> whole = polygon(quad);
    const auto sub_quads = kneiphof2024::subdivide_quad(quad, 16, 16);
    std::vector<PolygonLight<double>> parts;
    for (const auto& q : sub_quads) parts.push_back(polygon(q));
    const std::size_t n = std::size_t(size) * std::size_t(size);
    std::vector<double> single(n), sub_mc(n), single_ltc(n), sub_ltc(n), smooth(n);
    tbb::parallel_for(0, size, [&](int y) {
      std::vector<double> pk(parts.size()), lk(parts.size()), qk(parts.size()), lq(parts.size());
      for (int x = 0; x < size; ++x) {
        const Pixel px = pixel(size, x, y);
        const std::size_t i = std::size_t(px.index);
        const std::uint64_t seed = figure_seed(kFig9, 0);
        // Vertices relative to the shading point (the plane's frame is the shading frame).
        const auto rel = [&](const std::array<Vec3<double>, 4>& q) {
          return std::array<Vec3<double>, 4>{q[0] - px.p, q[1] - px.p, q[2] - px.p, q[3] - px.p};
        };
        double p = 0, p_ltc = 0;
        for (std::size_t k = 0; k < parts.size(); ++k) {
          const kneiphof2024::AreaLightTerms t = kneiphof2024::area_light_terms_mc(
              g, px.wi, parts[k], px.p, samples, seed, px.index * parts.size() + k);
          pk[k] = t.d_omega_h / dh;
          lk[k] = t.lo_over_li;
          p += pk[k];
          // The single LTC lobe (Sec. 4): the BRDF lobe for L_o and, × D_PR, for D_Ωh.
          const auto v = rel(sub_quads[k]);
          const kneiphof2024::LtcAreaTerms<double> l = kneiphof2024::area_light_terms_ltc(
              table, alpha, px.wi, v.data(), 4, kneiphof2024::AreaP::kBrdfLobe);
          qk[k] = l.d_omega_h / dh;
          lq[k] = l.lo_over_li;
          p_ltc += qk[k];
        }
        const kneiphof2024::AreaLightTerms t = kneiphof2024::area_light_terms_mc(
            g, px.wi, whole, px.p, samples * 256, seed + 1, px.index);
        const auto v = rel(quad);
        const kneiphof2024::LtcAreaTerms<double> l = kneiphof2024::area_light_terms_ltc(
            table, alpha, px.wi, v.data(), 4, kneiphof2024::AreaP::kBrdfLobe);
        const double nf = footprint_facet_count(px.footprint, density);
        const double pc = std::min(1.0, p);
        const std::uint64_t b = binomial_exact(std::uint64_t(nf), pc, seed + 2, px.index);
        const auto bk = kneiphof2024::multinomial_split(b, pk, seed + 3, px.index);
        // The LTC light's own p (its polygon integral), its count, and the split over the parts.
        const double pl = std::min(1.0, l.d_omega_h / dh);
        const std::uint64_t bl = binomial_exact(std::uint64_t(nf), pl, seed + 4, px.index);
        const auto blk = kneiphof2024::multinomial_split(bl, qk, seed + 5, px.index);
        double mc = 0, ltc = 0;
        for (std::size_t k = 0; k < parts.size(); ++k) {
          if (pk[k] > 0) mc += lk[k] * double(bk[k]) / (nf * pk[k]);
          if (qk[k] > 0) ltc += lq[k] * double(blk[k]) / (nf * qk[k]);
        }
        single[i] = t.lo_over_li * binomial_radiance_factor(double(b), nf, pc);
        sub_mc[i] = mc;
        single_ltc[i] = l.lo_over_li * binomial_radiance_factor(double(bl), nf, pl);
        sub_ltc[i] = ltc;
        smooth[i] = t.lo_over_li;
      }
    });
    double num = 0, den = 0, ltc_max = 0, lnum = 0, lden = 0;
    for (std::size_t i = 0; i < n; ++i) {
      num += (sub_mc[i] - single[i]) * (sub_mc[i] - single[i]);
      den += single[i] * single[i];
      ltc_max = std::max(ltc_max, std::abs(sub_ltc[i] - single_ltc[i]) / (smooth[i] + 1e-300));
      lnum += (single_ltc[i] - single[i]) * (single_ltc[i] - single[i]);
      lden += single[i] * single[i];
    }
    rows.push_back({w, std::sqrt(num / std::max(den, 1e-300)), ltc_max,
                    std::sqrt(lnum / std::max(lden, 1e-300))});
    Image exr(size, size,
              {"single_mc", "subdivided_mc", "single_ltc", "subdivided_ltc", "smooth_mc"});
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const std::size_t i = std::size_t(y) * std::size_t(size) + std::size_t(x);
        exr.at(x, y, 0) = single[i], exr.at(x, y, 1) = sub_mc[i];
        exr.at(x, y, 2) = single_ltc[i], exr.at(x, y, 3) = sub_ltc[i];
        exr.at(x, y, 4) = smooth[i];
      }
    io::write_exr(ctx.dir / fmt::format("halfwidth{}.exr", w), exr,
                  attributes(kFig9, fmt::format("light half-width {}, alpha {}", w, alpha)));
    const double sc = scale_to_peak(smooth);
    tiles.push_back(tile(size, single, sc));
    tiles.push_back(tile(size, sub_mc, sc));
    tiles.push_back(tile(size, single_ltc, sc));
    tiles.push_back(tile(size, sub_ltc, sc));
  }
  io::write_png_preview(ctx.dir / "fig9.png", montage(tiles, 4));
  std::vector<std::string> labels;
  for (const Row& r : rows)
    for (std::string_view what : {"single light (MC terms)", "256 sub-lights (MC terms)",
                                  "single light (LTC)", "256 sub-lights (LTC)"})
      labels.push_back(fmt::format("half-width {}: {}", r.w, what));
  write_panel_layout(ctx.dir / "fig9.png",
                     {fmt::format("kneiphof2024-fig9: one area light vs 256 sub-lights, {} MC "
                                  "samples per sub-light (grey = 0.8 x radiance / smooth peak)",
                                  samples),
                      4,
                      2,
                      labels});
  io::write_csv_atomic(
      ctx.dir / "fig9.csv",
      {"light_half_width", "alpha", "rel_rms_subdivided_mc_vs_single_mc",
       "max_rel_subdivided_ltc_vs_single_ltc", "rel_rms_single_ltc_vs_single_mc"},
      [&](io::CsvWriter& w) {
        for (const Row& r : rows) {
          w.cell(r.w).cell(alpha).cell(r.mc_rel_rms).cell(r.ltc_max).cell(r.ltc_vs_mc_rel_rms);
          w.end_row();
        }
      });
  std::string md =
      "# kneiphof2024-fig9\n\nOne light vs 2^4×2^4 sub-lights, counts split multinomially (App. "
      "C). Monte Carlo terms (left pair) differ (the paper: the error grows with the light's "
      "size); with the single LTC lobe (right pair: the BRDF LTC lobe gives L_o and, × D_PR, "
      "D_Ωh of every part, Sec. 4 / Eq. 32) the result is invariant up to rounding. The last "
      "column is the LTC image against the Monte Carlo one (different counts: p differs).\n\n| "
      "half-width | rel. RMS (MC terms) | max rel. (LTC, / smooth) | rel. RMS LTC vs MC "
      "|\n|---|---|---|---|\n";
  for (const Row& r : rows)
    md += fmt::format("| {} | {:.4g} | {:.2g} | {:.3g} |\n", r.w, r.mc_rel_rms, r.ltc_max,
                      r.ltc_vs_mc_rel_rms);
  md +=
      "\nfig9.png: rows half-width 0.4, 0.1; columns single light (MC terms), 256 sub-lights (MC "
      "terms), single light (LTC), 256 sub-lights (LTC).\n";
  io::write_file_atomic(ctx.dir / "summary.md", md);
}

// ---- Fig. 10 ----------------------------------------------------------------------------------
constexpr std::string_view kFig10 = "kneiphof2024-fig10";

void run_fig10(const FigureContext& ctx) {
  const int size = ctx.quick ? 128 : 512;
  const int strips = 8;                      // N_P quadruples from strip to strip
  const int samples = ctx.quick ? 16 : 128;  // MC samples per pixel for an area light
  // log10 facet density of the first strip, raised with the pixel count so that each strip's N_P
  // (facets per pixel footprint, what the figure is about) is the same at every image size.
  const double d0 = 5.0 + 2 * std::log10(size / 32.0);
  std::vector<Image> tiles;
  struct Row {
    std::string light;
    double sa;
    int strip;
    double n_p, rel_rms, rel_mean;
  };
  std::vector<Row> rows;
  for (double sa : {0.1, 0.5, 0.9}) {
    const double a = sa * sa;
    const GGX<double> g{a, a};
    const double dh = total_area_ggx_eq29(a);
    for (std::string_view light : {"large area", "small area", "directional"}) {
      const bool dir = light == "directional";
      const PolygonLight<double> pl = polygon(square_light(light == "large area" ? 0.4 : 0.05));
      const std::size_t n = std::size_t(size) * std::size_t(size);
      std::vector<double> glint(n), smooth(n), np(n);
      tbb::parallel_for(0, size, [&](int y) {
        for (int x = 0; x < size; ++x) {
          const Pixel px = pixel(size, x, y);
          const std::size_t i = std::size_t(px.index);
          const int strip = x * strips / size;
          const double dens = d0 + strip * std::log10(4.0);
          double p, lo;
          if (dir) {
            p = kneiphof2024::cap_probability_eq20(
                g, px.wi, kSunDir, one_minus_cos(0.26 * std::numbers::pi / 180), dh);
            lo = microfacet_brdf(g, px.wi, kSunDir, 1.0) * kSunDir.z;
          } else {
            const kneiphof2024::AreaLightTerms t = kneiphof2024::area_light_terms_mc(
                g, px.wi, pl, px.p, samples, figure_seed(kFig10, 0), px.index);
            p = t.d_omega_h / dh;
            lo = t.lo_over_li;
          }
          const double pc = std::min(1.0, p);
          const double nf = footprint_facet_count(px.footprint, dens);
          const std::uint64_t b =
              binomial_exact(std::uint64_t(nf), pc, figure_seed(kFig10, 1), px.index);
          glint[i] = lo * binomial_radiance_factor(double(b), nf, pc);
          smooth[i] = lo;
          np[i] = nf;
        }
      });
      // Per strip: relative RMS and relative mean difference to the smooth BRDF.
      for (int s = 0; s < strips; ++s) {
        double e2 = 0, l2 = 0, sg = 0, ss = 0, nps = 0;
        int cnt = 0;
        for (int y = 0; y < size; ++y)
          for (int x = 0; x < size; ++x) {
            if (x * strips / size != s) continue;
            const std::size_t i = std::size_t(y) * std::size_t(size) + std::size_t(x);
            e2 += (glint[i] - smooth[i]) * (glint[i] - smooth[i]);
            l2 += smooth[i] * smooth[i];
            sg += glint[i], ss += smooth[i], nps += np[i], ++cnt;
          }
        rows.push_back({std::string(light), sa, s, nps / cnt, std::sqrt(e2 / std::max(l2, 1e-300)),
                        ss > 0 ? sg / ss - 1 : 0});
      }
      Image exr(size, size, {"glint", "smooth", "N_P"});
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const std::size_t i = std::size_t(y) * std::size_t(size) + std::size_t(x);
          exr.at(x, y, 0) = glint[i], exr.at(x, y, 1) = smooth[i], exr.at(x, y, 2) = np[i];
        }
      std::string tag(light);
      std::replace(tag.begin(), tag.end(), ' ', '_');
      io::write_exr(ctx.dir / fmt::format("sa{}_{}.exr", sa, tag), exr,
                    attributes(kFig10, fmt::format("sqrt_alpha={} light={}", sa, light)));
      const double sc = scale_to_peak(smooth);
      tiles.push_back(tile(size, glint, sc));
      tiles.push_back(tile(size, smooth, sc));
    }
  }
  io::write_png_preview(ctx.dir / "fig10.png", montage(tiles, 6));
  std::vector<std::string> labels;
  for (double sa : {0.1, 0.5, 0.9})
    for (std::string_view light : {"large area", "small area", "directional"})
      for (std::string_view what : {"glints", "smooth"})
        labels.push_back(fmt::format("sqrt(alpha) {}, {} light: {}", sa, light, what));
  write_panel_layout(ctx.dir / "fig10.png",
                     {fmt::format("kneiphof2024-fig10: glints vs the smooth BRDF, N_P x4 per "
                                  "vertical strip of {}, area lights {} MC samples per pixel "
                                  "(grey = 0.8 x radiance / smooth peak)",
                                  strips, samples),
                      6,
                      2,
                      labels});
  io::write_csv_atomic(
      ctx.dir / "fig10.csv",
      {"light", "sqrt_alpha", "strip", "mean_N_P", "rel_rms_vs_smooth", "rel_mean_vs_smooth"},
      [&](io::CsvWriter& w) {
        for (const Row& r : rows) {
          w.cell(r.light).cell(r.sa).cell_int(r.strip).cell(r.n_p).cell(r.rel_rms).cell(r.rel_mean);
          w.end_row();
        }
      });
  std::string md =
      "# kneiphof2024-fig10\n\nN_P quadruples from strip to strip (left to right, log10 density "
      "5 + 0.602 j); each row √α = 0.1, 0.5, 0.9; pairs (glint, smooth) for a large area light "
      "(half-width 0.4), a small one (0.05) and a directional light (γ = 0.26°). Relative RMS to "
      "the smooth BRDF per strip (last strip = converged):\n\n| light | √α | first strip | last "
      "strip |\n|---|---|---|---|\n";
  for (std::size_t k = 0; k + strips - 1 < rows.size(); k += strips)
    md += fmt::format("| {} | {} | {:.3g} | {:.3g} |\n", rows[k].light, rows[k].sa, rows[k].rel_rms,
                      rows[k + strips - 1].rel_rms);
  io::write_file_atomic(ctx.dir / "summary.md", md);
}

// ---- Table 1 analogue
// ----------------------------------------------------------------------------
constexpr std::string_view kTable1 = "kneiphof2024-table1";

// The paper's RTX 4090 row (ms per frame at 3840 × 2160) for comparison.
struct PaperRow {
  std::string_view light;
  double smooth, db, ours, ndf_ltc;
};
constexpr PaperRow kPaper[] = {{"none", 1.4, 1.4, 1.4, 1.4},
                               {"directional", 1.4, 2.2, 2.1, 2.1},
                               {"area", 1.7, 2.7, 2.8, 2.9}};

// "table1/method:M/light:L ... real_time" rows of the benchmark JSON, without a JSON library:
// the fields of one benchmark object are "name" then, later, "real_time" and "time_unit".
std::vector<std::array<double, 4>> read_bench(const std::filesystem::path& path, bool* found) {
  std::vector<std::array<double, 4>> t(3, {NAN, NAN, NAN, NAN});  // [light][method], ns
  std::ifstream in(path);
  *found = bool(in);
  std::string line;
  int method = -1, light = -1;
  bool aggregate_other = false;
  while (std::getline(in, line)) {
    const auto name = line.find("\"name\": \"table1/method:");
    if (name != std::string::npos) {
      method = line[name + 23] - '0';
      const auto l = line.find("light:");
      light = l == std::string::npos ? -1 : line[l + 6] - '0';
      aggregate_other = line.find("_mean") != std::string::npos ||
                        line.find("_stddev") != std::string::npos ||
                        line.find("_cv") != std::string::npos;
      continue;
    }
    const auto rt = line.find("\"real_time\": ");
    if (rt != std::string::npos && method >= 0 && light >= 0 && method < 4 && light < 3 &&
        !aggregate_other) {
      t[std::size_t(light)][std::size_t(method)] = std::stod(line.substr(rt + 13));
      method = light = -1;
    }
  }
  return t;
}

// A time of the table in the summary: "—" for a row the JSON lacks.
std::string ns_cell(double ns) { return std::isnan(ns) ? "—" : fmt::format("{:.1f}", ns); }

void run_table1(const FigureContext& ctx) {
  constexpr std::string_view kFile = "glints.json";
  constexpr std::string_view kTool = "glintlab_bench_glints --benchmark_filter=table1";
  const BenchSource src = bench_source(ctx, kFile);
  bool found = false;
  const auto t =
      src.path.empty() ? std::vector<std::array<double, 4>>{} : read_bench(src.path, &found);
  std::string md = fmt::format(
      "# kneiphof2024-table1\n\nTime per evaluation (ns, scalar double, one core) from the Google "
      "Benchmark JSON of `glintlab_bench_glints`. Area light (a unit square at height 2): L_o by "
      "the BRDF LTC lobe (Heitz et al. 2016, our fitted 64 × 64 table) for every column; Kneiphof "
      "& Klein reuse that lobe × D_PR for p (Sec. 4), + NDF LTC integrates the separately fitted "
      "NDF lobe × D_PR as well (one more polygon integral); Deliot & Belcour take glints for the "
      "light's mean direction. Directional: + NDF LTC is Kneiphof & Klein (no lobe). The paper's "
      "numbers are ms per 4K frame on an RTX 4090: compare ratios, not values.\n\n");
  if (!found) {
    // Nothing measured: the sentence and the paper's row, no column of ours (no table of nan).
    md += no_bench_data(src, kFile, kTool) + "\n\n";
    md += "| light | paper ms (smooth / D&B / ours / + NDF LTC) |\n|---|---|\n";
    for (const PaperRow& p : kPaper)
      md += fmt::format("| {} | {} / {} / {} / {} |\n", p.light, p.smooth, p.db, p.ours, p.ndf_ltc);
    io::write_file_atomic(ctx.dir / "summary.md", md);
    return;
  }
  io::write_csv_atomic(
      ctx.dir / "table1.csv",
      {"light", "smooth_ns", "deliot_belcour_ns", "kneiphof_klein_ns", "ndf_ltc_ns",
       "paper_rtx4090_smooth_ms", "paper_db_ms", "paper_ours_ms", "paper_ndf_ltc_ms"},
      [&](io::CsvWriter& w) {
        for (int l = 0; l < 3; ++l) {
          w.cell(kPaper[l].light);
          for (int m = 0; m < 4; ++m) w.cell(t[std::size_t(l)][std::size_t(m)]);
          w.cell(kPaper[l].smooth).cell(kPaper[l].db).cell(kPaper[l].ours).cell(kPaper[l].ndf_ltc);
          w.end_row();
        }
      });
  md += fmt::format("Our times are read from `{}`; a row it lacks shows —.\n", src.shown_as);
  md +=
      "\n| light | smooth ns | D&B ns | K&K ns | + NDF LTC ns | paper ms (smooth / D&B / ours / + "
      "NDF LTC) |\n|---|---|---|---|---|---|\n";
  for (int l = 0; l < 3; ++l) {
    const auto& m = t[std::size_t(l)];
    md += fmt::format("| {} | {} | {} | {} | {} | {} / {} / {} / {} |\n", kPaper[l].light,
                      ns_cell(m[0]), ns_cell(m[1]), ns_cell(m[2]), ns_cell(m[3]), kPaper[l].smooth,
                      kPaper[l].db, kPaper[l].ours, kPaper[l].ndf_ltc);
  }
  io::write_file_atomic(ctx.dir / "summary.md", md);
}

}  // namespace

FigureEntry kneiphof2024_fig6_entry() {
  return {kFig6, "Kneiphof & Klein 2024", "Fig. 6",
          "cap probability (Eq. 20) vs Deliot & Belcour with R fitted at normal incidence; p > 1 "
          "region",
          run_fig6};
}
FigureEntry kneiphof2024_fig9_entry() {
  return {
      kFig9, "Kneiphof & Klein 2024", "Fig. 9",
      "2^4 x 2^4 subdivided light: Monte Carlo terms vs the single LTC lobe, multinomial counts",
      run_fig9};
}
FigureEntry kneiphof2024_fig10_entry() {
  return {kFig10, "Kneiphof & Klein 2024", "Fig. 10",
          "convergence to the smooth BRDF as N_P quadruples (large/small area, directional)",
          run_fig10};
}
FigureEntry kneiphof2024_table1_entry() {
  return {
      kTable1, "Kneiphof & Klein 2024", "Table 1",
      "time per evaluation: smooth, Deliot & Belcour, Kneiphof & Klein, + NDF LTC (benchmark JSON)",
      run_table1};
}

}  // namespace glintlab::experiments

// Podee et al. (micro-specular highlights) Table 1, the Fig. 4 comparison over camera distance and
// the stability (flicker) comparison: centre sampling, LEAN mapping and the paper's method
// (Sec. 3) against the paper's 64-spp supersampled reference and a converged one, on the scene of
// verify/scenes/podee_scene.h (normal-mapped mirror sphere, one disk light). Paper: an OpenGL scene
// (not published) of unknown distance and normal map, 8-bit images; here an analytic sphere,
// procedural sine-bump normal map, linear radiance for unit light radiance on a black background.
#include "experiments/figures/podee.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/io/exr.h"
#include "core/io/png.h"
#include "core/math/rng.h"
#include "core/render/metrics.h"
#include "core/scene/sine_height_field.h"
#include "core/scene/slope_moment_map.h"
#include "experiments/figures/chart_spec.h"
#include "experiments/figures/panel_layout.h"
#include "verify/scenes/podee_scene.h"

namespace glintlab::experiments {
namespace {

constexpr int kPaperSpp = 64;
constexpr std::array<podee::Method, 4> kMethods = {podee::Method::kCentre, podee::Method::kLean,
                                                   podee::Method::kPodee,
                                                   podee::Method::kPodeeQuadAsCircle};
// Table 1 of the paper, in the order centre, LEAN, method.
constexpr std::array<double, 3> kPaperRmse = {0.0845, 0.0977, 0.0826};

// A panel is `views` × `views` views of `size` pixels across, side by side, each at the pixel
// footprint of the 96-pixel, 30° frame (podee::config), which the experiment fixes because the
// method's accuracy depends on it. One wider view would only widen the black background around a
// sphere that spans about 190, 90 and 37 pixels at distances 2, 4 and 10; more views show more of
// the glinting surface instead (podee_view_normal_map).
struct Budget {
  int size;   // pixels across one view
  int views;  // views per panel side
  int converged_spp;
  int frames;
  std::vector<double> distances;
  int panel() const { return size * views; }
};
// Quick: one 128-pixel view, which a reader needs to see the highlights, and fewer samples in the
// converged reference. Full: 4 × 4 views, 512² panels.
Budget budget(const FigureContext& ctx) {
  if (ctx.quick) return {128, 1, 128, 6, {podee::kNear, podee::kMedium, podee::kFar}};
  return {128, 4, 1024, 32, {2, 2.5, 3, 4, 5, 6, 8, 10, 12, 14}};
}

// View 0 keeps the seeds of the single view, so it is the quick budget's image.
std::uint64_t seed_for(std::string_view figure, std::string_view what, double distance, int spp,
                       int view = 0) {
  std::string key = fmt::format("{}/{}/d={}/spp={}", figure, what, distance, spp);
  if (view > 0) key += fmt::format("/view={}", view);
  return hash_string(key.c_str());
}

std::vector<std::shared_ptr<const podee::NormalMap>> view_normal_maps(const Budget& b) {
  std::vector<std::shared_ptr<const podee::NormalMap>> maps;
  for (int k = 0; k < b.views * b.views; ++k) maps.push_back(podee_view_normal_map(k, b.views));
  return maps;
}

// The panel of one distance: render(k, scene of view k) for each view, placed row by row.
template <class RenderView>
Image render_panel(const Budget& b, double distance,
                   const std::vector<std::shared_ptr<const podee::NormalMap>>& maps,
                   const RenderView& render) {
  Image out(b.panel(), b.panel(), {"Y"});
  for (int k = 0; k < b.views * b.views; ++k) {
    const Image view = render(k, podee::Scene(podee::config(distance, b.size), maps[k]));
    const int ox = k % b.views * b.size, oy = k / b.views * b.size;
    for (int y = 0; y < b.size; ++y)
      for (int x = 0; x < b.size; ++x) out.at(ox + x, oy + y, 0) = view.at(x, y, 0);
  }
  return out;
}

io::ExrAttributes attributes(std::string_view figure, std::string_view method, double distance,
                             int spp, std::uint64_t seed, int views) {
  return {{"glintlab_figure", std::string(figure)},
          {"glintlab_views",
           fmt::format("{0} x {0} views side by side; view k (row by row from the top left) has "
                       "the normal map translated by (k mod {0}, k div {0}) / {0} of a tile and "
                       "the seed of view 0 (glintlab_seed) with /view=k appended to its key",
                       views)},
          {"glintlab_method", std::string(method)},
          {"glintlab_distance", fmt::format("{}", distance)},
          {"glintlab_spp", fmt::format("{}", spp)},
          {"glintlab_seed", fmt::format("{}", seed)},
          {"glintlab_version", std::string(glintlab_version())},
          {"glintlab_scene",
           "unit mirror sphere, sine-bump normal map (rms slope 0.15, 8x4 tiles), disk light "
           "radius 0.3 at distance 6, pinhole 30 deg per 96 px, channel Y = radiance for unit "
           "light radiance"}};
}

// Grayscale images side by side in a grid, as RGB, for the PNG preview.
Image montage(const std::vector<Image>& images, int columns) {
  const int w = images[0].width, h = images[0].height;
  const int rows = (static_cast<int>(images.size()) + columns - 1) / columns;
  Image out(w * columns, h * rows, {"R", "G", "B"});
  for (std::size_t k = 0; k < images.size(); ++k) {
    const int ox = static_cast<int>(k) % columns * w, oy = static_cast<int>(k) / columns * h;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (std::size_t c = 0; c < 3; ++c)
          out.at(ox + x, oy + y, c) = images[k].at(x, y, 0);
  }
  return out;
}

void progress(const FigureContext& ctx, const std::string& stage, long done, long total) {
  if (ctx.progress) ctx.progress(stage, done, total);
}

// Everything one distance gives: both references and every method, with RMSEs.
struct DistanceRun {
  double distance;
  Image paper, converged;
  std::uint64_t paper_seed, converged_seed;
  std::vector<Image> method;  // kMethods order
  std::vector<double> vs_paper, vs_converged;
  double paper_vs_converged;
};

DistanceRun run_distance(const FigureContext& ctx, std::string_view figure, double distance,
                         const Budget& b,
                         const std::vector<std::shared_ptr<const podee::NormalMap>>& maps) {
  DistanceRun r{distance,
                {},
                {},
                seed_for(figure, "reference", distance, kPaperSpp),
                seed_for(figure, "converged", distance, b.converged_spp),
                {},
                {},
                {},
                0};
  const int n = b.views * b.views;
  const auto reference = [&](int spp, std::string_view what) {
    return render_panel(b, distance, maps, [&](int k, const podee::Scene& scene) {
      const std::string stage =
          fmt::format("{} d={} {} spp, view {}/{}", figure, distance, spp, k + 1, n);
      return podee::render_podee_reference(scene, spp, seed_for(figure, what, distance, spp, k),
                                           ctx.threads,
                                           [&](long d, long t) { progress(ctx, stage, d, t); });
    });
  };
  r.paper = reference(kPaperSpp, "reference");
  r.converged = reference(b.converged_spp, "converged");
  MetricOptions o;
  o.channels = {"Y"};
  for (podee::Method m : kMethods) {
    r.method.push_back(render_panel(b, distance, maps, [&](int, const podee::Scene& scene) {
      return podee::render_podee(scene, m, ctx.threads);
    }));
    r.vs_paper.push_back(rmse(r.method.back(), r.paper, o));
    r.vs_converged.push_back(rmse(r.method.back(), r.converged, o));
  }
  r.paper_vs_converged = rmse(r.paper, r.converged, o);
  return r;
}

// What a panel is, for the summaries.
std::string describe_panel(const Budget& b) {
  const std::string view =
      fmt::format("{}² pixels at the pixel footprint of a 96-pixel, 30° frame", b.size);
  if (b.views == 1) return "one view of the sphere, " + view;
  return fmt::format(
      "{}² pixels: {} × {} views of the sphere, each {}, each with its normal map translated by "
      "another fraction of a tile (another part of the bumps under the highlight)",
      b.panel(), b.views, b.views, view);
}

std::string tag(double distance) { return fmt::format("d{}", distance); }

void write_distance_images(const FigureContext& ctx, std::string_view figure, const DistanceRun& r,
                           const Budget& b) {
  io::write_exr(ctx.dir / fmt::format("{}_reference64.exr", tag(r.distance)), r.paper,
                attributes(figure, "reference", r.distance, kPaperSpp, r.paper_seed, b.views));
  io::write_exr(
      ctx.dir / fmt::format("{}_converged.exr", tag(r.distance)), r.converged,
      attributes(figure, "converged", r.distance, b.converged_spp, r.converged_seed, b.views));
  for (std::size_t m = 0; m < kMethods.size(); ++m)
    io::write_exr(ctx.dir / fmt::format("{}_{}.exr", tag(r.distance), to_string(kMethods[m])),
                  r.method[m],
                  attributes(figure, to_string(kMethods[m]), r.distance, 1, 0, b.views));
}

// Montage row: converged | 64 spp | centre | LEAN | method, and the labels of its panels.
void append_row(std::vector<Image>& cells, std::vector<std::string>& labels, const DistanceRun& r,
                const Budget& b) {
  cells.push_back(r.converged);
  cells.push_back(r.paper);
  labels.push_back(fmt::format("d {}: converged ({} spp)", r.distance, b.converged_spp));
  labels.push_back(fmt::format("d {}: reference ({} spp)", r.distance, kPaperSpp));
  for (std::size_t m = 0; m < 3; ++m) {
    cells.push_back(r.method[m]);
    labels.push_back(fmt::format("d {}: {}, 1 spp", r.distance, to_string(kMethods[m])));
  }
}

// The montages' title: what one panel shows.
std::string sphere_title(const Budget& b) {
  const std::string what =
      b.views == 1 ? std::string("the bump-mapped sphere")
                   : fmt::format(
                         "{0} x {0} views of the bump-mapped sphere, each with its normal "
                         "map translated by another fraction of a tile,",
                         b.views);
  return what + " under a disk light, per camera distance d (linear radiance, grey)";
}

void run_table1(const FigureContext& ctx) {
  const Budget b = budget(ctx);
  const char* id = "podee-table1";
  const auto maps = view_normal_maps(b);
  std::vector<DistanceRun> runs;
  for (double d : {podee::kNear, podee::kMedium, podee::kFar})
    runs.push_back(run_distance(ctx, id, d, b, maps));
  for (const DistanceRun& r : runs) write_distance_images(ctx, id, r, b);
  io::write_csv_atomic(
      ctx.dir / "table1.csv",
      {"distance", "method", "rmse_vs_64spp", "rmse_vs_converged", "converged_spp", "paper_rmse",
       "size_px"},
      [&](io::CsvWriter& w) {
        for (const DistanceRun& r : runs) {
          for (std::size_t m = 0; m < kMethods.size(); ++m) {
            w.cell(r.distance).cell(to_string(kMethods[m])).cell(r.vs_paper[m]);
            w.cell(r.vs_converged[m]).cell(double(b.converged_spp));
            w.cell(m < 3 ? kPaperRmse[m] : std::nan("")).cell(double(b.panel()));
            w.end_row();
          }
          w.cell(r.distance).cell("reference64").cell(0.0).cell(r.paper_vs_converged);
          w.cell(double(b.converged_spp)).cell(std::nan("")).cell(double(b.panel()));
          w.end_row();
        }
      });
  std::string md = fmt::format(
      "# Podee et al. Table 1 — RMSE against the 64-spp reference\n\n"
      "{}; linear radiance for unit light radiance; converged reference {} spp{}. The RMSE is "
      "over every pixel of the panel.\n\n"
      "| distance | centre | LEAN | method | method (quad-as-circle weight) | 64 spp vs converged "
      "|\n| --- | --- | --- | --- | --- | --- |\n"
      "| paper (Table 1) | 0.0845 | 0.0977 | 0.0826 | — | — |\n",
      describe_panel(b), b.converged_spp, ctx.quick ? " (quick budget)" : "");
  for (const DistanceRun& r : runs)
    md += fmt::format("| {} | {:.4f} | {:.4f} | {:.4f} | {:.4f} | {:.4f} |\n", r.distance,
                      r.vs_paper[0], r.vs_paper[1], r.vs_paper[2], r.vs_paper[3],
                      r.paper_vs_converged);
  md +=
      "\nSetup differences: the paper's scene, normal map, camera distance and light are not "
      "published (an OpenGL scene, 8-bit tone-mapped images, RMSE presumably in [0, 1] display "
      "units); ours is an analytic unit sphere with a procedural sine-bump normal map (rms slope "
      "0.15), one disk light (radius 0.3 at distance 6), black background, linear radiance. "
      "Absolute RMSEs are therefore not comparable, only the ordering of the three methods. Our "
      "LEAN lights with the disk as a Gaussian convolved with LEAN's lobe (verify/scenes/"
      "podee_scene.h), the paper does not say how its LEAN lit the disk.\n";
  io::write_file_atomic(ctx.dir / "summary.md", md);
  std::vector<Image> cells;
  std::vector<std::string> labels;
  for (const DistanceRun& r : runs) append_row(cells, labels, r, b);
  io::write_png_preview(ctx.dir / "table1.png", montage(cells, 5));
  write_panel_layout(ctx.dir / "table1.png",
                     {fmt::format("podee-table1: {}", sphere_title(b)), 5, 0, labels});
}

void run_distance_figure(const FigureContext& ctx) {
  const Budget b = budget(ctx);
  const char* id = "podee-fig4-distance";
  std::vector<DistanceRun> runs;
  const auto maps = view_normal_maps(b);
  for (double d : b.distances) runs.push_back(run_distance(ctx, id, d, b, maps));
  io::write_csv_atomic(
      ctx.dir / "error_vs_distance.csv",
      {"distance", "pixel_size_at_sphere", "method", "rmse_vs_64spp", "rmse_vs_converged",
       "ratio_to_best_baseline"},
      [&](io::CsvWriter& w) {
        for (const DistanceRun& r : runs) {
          const double best = std::min(r.vs_paper[0], r.vs_paper[1]);
          // Pixel footprint on the sphere's nearest point: (d − 1) · 2 tan(15°) / 96.
          const double px = (r.distance - 1) * 2 * std::tan(15 * kPi<double> / 180) / 96;
          for (std::size_t m = 0; m < kMethods.size(); ++m) {
            w.cell(r.distance).cell(px).cell(to_string(kMethods[m])).cell(r.vs_paper[m]);
            w.cell(r.vs_converged[m]).cell(r.vs_paper[m] / best);
            w.end_row();
          }
        }
      });
  std::vector<Image> cells;
  std::vector<std::string> labels;
  for (const DistanceRun& r : runs) {
    append_row(cells, labels, r, b);
    io::write_exr(ctx.dir / fmt::format("{}_podee.exr", tag(r.distance)), r.method[2],
                  attributes(id, "podee", r.distance, 1, 0, b.views));
    io::write_exr(
        ctx.dir / fmt::format("{}_converged.exr", tag(r.distance)), r.converged,
        attributes(id, "converged", r.distance, b.converged_spp, r.converged_seed, b.views));
  }
  io::write_png_preview(ctx.dir / "error_vs_distance.png", montage(cells, 5));
  write_panel_layout(ctx.dir / "error_vs_distance.png",
                     {fmt::format("podee-fig4-distance: {}", sphere_title(b)), 5, 0, labels});
}

void run_flicker(const FigureContext& ctx) {
  const Budget b = budget(ctx);
  const char* id = "podee-fig4-flicker";
  const auto maps = view_normal_maps(b);
  const int n = b.views * b.views;
  struct Row {
    std::string method;
    double distance, flicker;
  };
  std::vector<Row> rows;
  std::vector<Image> cells;
  std::vector<std::string> labels;
  constexpr std::array<podee::Method, 3> kCompared = {podee::Method::kCentre, podee::Method::kLean,
                                                      podee::Method::kPodee};
  for (double d : {podee::kNear, podee::kMedium, podee::kFar}) {
    const podee::SceneConfig c = podee::config(d, b.size);
    // Every view has as many pixels, so the mean over views is the mean over the panel's pixels.
    const auto panel_flicker = [&](podee::Method m, int spp) {
      double sum = 0;
      for (int k = 0; k < n; ++k) {
        progress(ctx,
                 fmt::format("{} d={} {}, view {}/{}", id, d,
                             spp > 0 ? "reference64" : to_string(m), k + 1, n),
                 0, 1);
        sum += podee::flicker(c, maps[std::size_t(k)], m, b.frames, ctx.threads, spp,
                              spp > 0 ? seed_for(id, "reference", d, spp, k) : 0);
      }
      return sum / n;
    };
    for (podee::Method m : kCompared) rows.push_back({to_string(m), d, panel_flicker(m, 0)});
    rows.push_back({"reference64", d, panel_flicker(podee::Method::kCentre, kPaperSpp)});
    // Per-pixel temporal standard deviation images of the three methods at this distance.
    for (podee::Method m : kCompared) {
      Image sd = render_panel(b, d, maps, [&](int k, const podee::Scene& view) {
        Image sum(b.size, b.size, {"Y"}), sum2(b.size, b.size, {"Y"});
        for (int f = 0; f < b.frames; ++f) {
          podee::SceneConfig cf = view.config();
          cf.film_shift = {double(f) / b.frames, 0.5 * f / b.frames};
          const Image im =
              podee::render_podee(podee::Scene(cf, maps[std::size_t(k)]), m, ctx.threads);
          for (std::size_t i = 0; i < im.data.size(); ++i) {
            sum.data[i] += im.data[i];
            sum2.data[i] += im.data[i] * im.data[i];
          }
        }
        Image out(b.size, b.size, {"Y"});
        for (std::size_t i = 0; i < out.data.size(); ++i) {
          const double mean = sum.data[i] / b.frames;
          out.data[i] = std::sqrt(std::max(sum2.data[i] / b.frames - mean * mean, 0.0));
        }
        return out;
      });
      io::write_exr(ctx.dir / fmt::format("{}_{}_temporal_sd.exr", tag(d), to_string(m)), sd,
                    attributes(id, to_string(m), d, 1, 0, b.views));
      cells.push_back(std::move(sd));
      labels.push_back(fmt::format("d {}: {}", d, to_string(m)));
    }
  }
  io::write_csv_atomic(
      ctx.dir / "flicker.csv",
      {"distance", "method", "mean_sq_frame_difference", "ratio_to_centre", "frames"},
      [&](io::CsvWriter& w) {
        for (const Row& r : rows) {
          double centre = 0;
          for (const Row& q : rows)
            if (q.distance == r.distance && q.method == "centre") centre = q.flicker;
          w.cell(r.distance).cell(r.method).cell(r.flicker).cell(r.flicker / centre);
          w.cell(double(b.frames));
          w.end_row();
        }
      });
  // The per-pixel temporal standard deviations as heat maps on one colour bar (a grey preview
  // showed 2 x sd, saturating at sd 0.5; the bar does too).
  std::vector<ImageMapPanel> panels;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    ImageMapPanel mp = image_map_panel(fmt::format("{}_{}", k / 3, k % 3), labels[k], &cells[k],
                                       "Y");
    mp.x_label = "x [pixel]", mp.y_label = "y [pixel]";
    mp.value_label = "temporal standard deviation of Y [radiance] (above 0.5 saturates)";
    mp.range = {0, 0.5};
    panels.push_back(std::move(mp));
  }
  write_image_maps(
      ctx.dir / "flicker.png",
      fmt::format("podee-fig4-flicker: per-pixel temporal standard deviation over {} sub-pixel "
                  "camera shifts{}",
                  b.frames,
                  b.views == 1 ? std::string()
                               : fmt::format("\n{0} x {0} views of the sphere per panel, normal "
                                             "map translated per view",
                                             b.views)),
      panels, 3, "temporal_sd");
}

}  // namespace

std::shared_ptr<const podee::NormalMap> podee_view_normal_map(int view, int views) {
  std::shared_ptr<const podee::NormalMap> base = podee::normal_map();
  if (view == 0) return base;
  const double du = double(view % views) / views, dv = double(view / views) / views;
  auto m = std::make_shared<podee::NormalMap>(*base);
  for (int k = 0; k < m->field.count; ++k) {
    SineWave<double>& w = m->field.wave[k];
    w.phase += 2 * kPi<double> * (w.ku * du + w.kv * dv);
  }
  // The supersampling podee::NormalMap builds its moments with.
  constexpr int kMomentSupersample = 2;
  m->moments = SlopeMomentMap(
      [f = m->field](double u, double v) {
        const SurfacePoint<double> s = f.eval(u, v);
        return Vec2<double>{s.slope_u, s.slope_v};
      },
      base->moments.size(), kMomentSupersample);
  return m;
}

FigureEntry podee_table1_entry() {
  return {"podee-table1", "Podee et al.", "Table 1",
          "RMSE of centre sampling, LEAN mapping and the method against the 64-spp reference "
          "(and a converged one) at near/medium/far distances, paper's numbers beside ours",
          run_table1};
}

FigureEntry podee_fig4_distance_entry() {
  return {"podee-fig4-distance", "Podee et al.", "Fig. 4 / Sec. 4",
          "error against camera distance: the method's far-distance failure", run_distance_figure};
}

FigureEntry podee_fig4_flicker_entry() {
  return {"podee-fig4-flicker", "Podee et al.", "Sec. 4 (stability)",
          "flicker (mean squared frame-to-frame difference) under a one-pixel sub-pixel pan, "
          "centre / LEAN / method / 64-spp reference, and per-pixel temporal deviation images",
          run_flicker};
}

}  // namespace glintlab::experiments

// `models-hemisphere`: for every registered model at its default parameters (and the sweeps'
// default footprint and light), eval's value f·cos and pdf over the upper hemisphere of ωo at
// θi = 45°, in orthographic projection (pixel (x, y) ↦ ωo = (x, y, √(1 − x² − y²))), with Riemann
// estimates of ∫ f cos dωo (the albedo) and ∫ pdf dωo over the hemisphere.
#include "experiments/figures/models_hemisphere.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/io/exr.h"
#include "core/model_registry.h"
#include "experiments/figures/chart_spec.h"
#include "verify/stability/cell_stats.h"

namespace glintlab::experiments {
namespace {

constexpr double kThetaDeg = 45;
constexpr int kMapCells = 128;  // the charts' cells per axis at most

// STEM.png, drawn by matplotlib from STEM_map.csv: value f·cos and pdf over the hemisphere (the
// EXR's channels 0 and 1) as two heat maps, on at most kMapCells² cells, each the mean of the
// finite pixels of its block inside the disk (the pixels themselves at quick); a block with a
// non-finite pixel is flagged. Cells outside the disk have no row.
void write_map(const std::filesystem::path& dir, const std::string& stem, const Image& img,
               double vmax, double pmax) {
  const int n = img.width, cells = std::min(n, kMapCells), block = n / cells;
  const std::string csv = stem + "_map.csv";
  io::write_csv_atomic(
      dir / csv, {"wo_x", "wo_y", "value", "pdf", "nonfinite"}, [&](io::CsvWriter& w) {
        for (int cy = 0; cy < cells; ++cy)
          for (int cx = 0; cx < cells; ++cx) {
            double v = 0, p = 0;
            int inside = 0, finite = 0;
            for (int y = cy * block; y < (cy + 1) * block; ++y)
              for (int x = cx * block; x < (cx + 1) * block; ++x) {
                const double px = (x + 0.5) / n * 2 - 1, py = 1 - (y + 0.5) / n * 2;
                if (px * px + py * py >= 1) continue;
                ++inside;
                const double a = img.at(x, y, 0), b = img.at(x, y, 1);
                if (!std::isfinite(a) || !std::isfinite(b)) continue;
                v += a, p += b, ++finite;
              }
            if (inside == 0) continue;
            const double nan = std::numeric_limits<double>::quiet_NaN();
            w.cell((cx + 0.5) / cells * 2 - 1).cell(1 - (cy + 0.5) / cells * 2);
            w.cell(finite ? v / finite : nan).cell(finite ? p / finite : nan);
            w.cell_int(finite < inside ? 1 : 0).end_row();
          }
      });
  const nlohmann::json x = {{"column", "wo_x"}, {"label", "wo.x [1] (orthographic)"}};
  const nlohmann::json y = {{"columns", {"wo_y"}},
                            {"format", "{wo_y:.2f}"},
                            {"label", "wo.y [1] (orthographic)"},
                            {"invert", true}};
  const nlohmann::json flags = {{{"column", "nonfinite"},
                                 {"value", 1},
                                 {"label", "a NaN or Inf pixel"},
                                 {"color", {1.0, 0.0, 0.0}},
                                 {"style", "fill"}}};
  nlohmann::json panels = nlohmann::json::array();
  for (const auto& [column, what, label, peak] :
       {std::tuple{"value", "value f cos(theta_o)", "f cos(theta_o) [1/sr]", vmax},
        std::tuple{"pdf", "pdf of sample", "pdf [1/sr]", pmax}})
    panels.push_back({{"title", fmt::format("{} (largest pixel {:.4g})", what, peak)},
                      {"x", x},
                      {"y", y},
                      {"value", {{"column", column}, {"label", label}}},
                      {"flags", flags},
                      {"empty_label", "below the horizon (outside the disk)"}});
  write_chart_json(dir / (stem + ".png"), {
      {"kind", "heatmap"},
      {"title", fmt::format("models-hemisphere: {} at its default parameters, theta_i = {:g} deg\n"
                            "upper hemisphere of wo, {} x {} cells{}",
                            stem, kThetaDeg, cells, cells,
                            block > 1 ? fmt::format(" (each the mean of {0} x {0} pixels)", block)
                                      : std::string())},
      {"csv", csv},
      {"columns", 2},
      {"panels", panels}});
}

void run(const FigureContext& ctx) {
  const int n = ctx.quick ? 128 : 512;
  const Vec3<double> wi = verify::stability::incidence_at(kThetaDeg);
  io::AtomicFile csv(ctx.dir / "models_hemisphere.csv");
  io::CsvWriter w(csv.stream(),
                  {"model", "theta_i_deg", "pixels", "albedo_estimate", "pdf_mass_upper_hemisphere",
                   "value_max", "pdf_max", "nonfinite_pixels"});
  const auto& models = registered_models();
  for (std::size_t mi = 0; mi < models.size(); ++mi) {
    const ModelEntry& m = models[mi];
    std::vector<double> values;
    for (const ParamSpec& p : m.params) values.push_back(p.default_value);
    ModelQuery<double> q{};
    q.wi = wi;
    const double s = verify::stability::kDefaultFootprint;
    q.footprint = {{0.5, 0.5}, {s, 0}, {0, s}};
    const double half =
        (m.needs & kNeedsAreaLight) ? verify::stability::kDefaultLightHalfAngleDeg : 0.0;
    q.light = {std::cos(half * std::numbers::pi / 180), 1.0};
    Image img(n, n, {"value", "pdf", "R", "G", "B"});
    tbb::parallel_for(0, n, [&](int y) {
      ModelQuery<double> qq = q;
      for (int x = 0; x < n; ++x) {
        const double px = (x + 0.5) / n * 2 - 1, py = 1 - (y + 0.5) / n * 2;  // +y at the top
        const double r2 = px * px + py * py;
        if (r2 >= 1) continue;
        qq.wo = {px, py, std::sqrt(1 - r2)};
        const ErasedEval e = m.eval(values, qq);
        img.at(x, y, 0) = e.value;
        img.at(x, y, 1) = e.pdf;
      }
    });
    double albedo = 0, mass = 0, vmax = 0, pmax = 0;
    long bad = 0;
    const double pixel = (2.0 / n) * (2.0 / n);
    for (int y = 0; y < n; ++y)  // serial, in pixel order: the sums do not depend on threads
      for (int x = 0; x < n; ++x) {
        const double px = (x + 0.5) / n * 2 - 1, py = 1 - (y + 0.5) / n * 2;
        const double r2 = px * px + py * py;
        if (r2 >= 1) continue;
        const double z = std::sqrt(1 - r2), v = img.at(x, y, 0), p = img.at(x, y, 1);
        if (!std::isfinite(v) || !std::isfinite(p)) {
          ++bad;
          continue;
        }
        albedo += v / z * pixel;  // dω = dx dy / z
        mass += p / z * pixel;
        vmax = std::max(vmax, v);
        pmax = std::max(pmax, p);
      }
    // The EXR's R, G: value and pdf, each scaled to its maximum.
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double v = img.at(x, y, 0), p = img.at(x, y, 1);
        img.at(x, y, 2) = vmax > 0 && std::isfinite(v) ? v / vmax : 0;
        img.at(x, y, 3) = pmax > 0 && std::isfinite(p) ? p / pmax : 0;
      }
    const std::string stem(m.name);
    io::write_exr(ctx.dir / (stem + ".exr"), img,
                  {{"glintlab_model", stem},
                   {"glintlab_parameters", "defaults"},
                   {"glintlab_theta_i_deg", fmt::format("{:g}", kThetaDeg)},
                   {"glintlab_projection", "orthographic upper hemisphere, +x right, +y up"},
                   {"glintlab_version", std::string(glintlab_version())}});
    write_map(ctx.dir, stem, img, vmax, pmax);
    w.cell(stem).cell(kThetaDeg).cell_int(n * n).cell(albedo).cell(mass).cell(vmax).cell(pmax);
    w.cell_int(bad).end_row();
    if (ctx.progress) ctx.progress("models", long(mi + 1), long(models.size()));
  }
  w.flush();
  csv.commit();
}

}  // namespace

FigureEntry models_hemisphere_entry() {
  return {"models-hemisphere", "every registered model", "no paper figure",
          "value f*cos (red) and pdf (green) of each model on the hemisphere at theta_i = 45 deg",
          run};
}

}  // namespace glintlab::experiments

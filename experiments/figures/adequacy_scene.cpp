// Figure adequacy-scene: per validation scene (verify/scenes/adequacy_scenes.h; the binomial
// family's six, the Kemppinen family's four, the area family's four and the Chermain family's four
// (each a plane and a sphere at two densities),
// rendered by the claim's own
// render_choice_scene) the render with each pixel's chosen level, the render with the family's most
// complete level everywhere (exact counting; k16_exact; exact counting), the difference map (the
// larger of the mean's relative difference and the CV difference over the pixel's realisations,
// in units of TAU) and the map of the chosen level: the difference and level maps as one labelled
// sheet drawn by matplotlib (adequacy-scene.png from adequacy-scene-pixels.csv and its chart spec:
// titles, axes, colour scales, legends), the two renders as the plain montage panels.png with its
// panels.json, one EXR per scene (every per-pixel quantity), a CSV of per-scene counts per family
// (adequacy-scene.csv, adequacy-scene-kemppinen.csv, adequacy-scene-area.csv,
// adequacy-scene-chermain.csv) and summary.md with each family decided as claim
// adequacy.choice-is-safe decides it (the Šidák share over its four families); given benchmark
// data (--bench-from), each scene's time per evaluation with the chosen levels against its
// family's most complete level everywhere (adequacy-scene-cost.csv, summary.md; every family's
// scenes, each priced by its models' adequacy/ rows).
#include "experiments/figures/adequacy_scene.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/glints/chermain_chooser.h"
#include "core/glints/cost_chooser.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/io/exr.h"
#include "core/io/png.h"
#include "core/render/image.h"
#include "core/simd/batch.h"
#include "experiments/adequacy/adequacy_outputs.h"
#include "experiments/adequacy/level_costs.h"
#include "experiments/figures/bench_json.h"
#include "experiments/figures/chart_spec.h"
#include "experiments/figures/panel_layout.h"
#include "verify/scenes/adequacy_scenes.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::experiments {
namespace {

namespace adq = verify::adequacy;

constexpr std::string_view kId = "adequacy-scene";
// The difference map's scale runs from 0 to this many TAU.
constexpr double kScaleMaxTau = 2;
const Vec3<double> kOffSurface{0.8, 0.8, 0.8};  // no surface, or the light below its horizon
const Vec3<double> kDark{0.45, 0.45, 0.45};     // exact level lit too rarely to measure
const Vec3<double> kExceeds{0.9, 0.0, 0.9};     // a lower bound above TAU

// The families of claim adequacy.choice-is-safe, in its order (its Šidák split is over all four).
enum class Family { kBinomial, kKemppinen, kArea, kChermain };
constexpr int kFamilies = 4;

// A family's level names and colours (the binomial levels for the binomial and area families).
std::span<const std::string_view> family_level_names(Family f) {
  if (f == Family::kKemppinen) return kKemppinenLevelNames;
  if (f == Family::kChermain) return kChermainLevelNames;
  return kBinomialLevelNames;
}
Vec3<double> family_level_color(Family f, std::size_t l) {
  if (f == Family::kKemppinen) return kKemppinenLevelColors[l];
  if (f == Family::kChermain) return kChermainLevelColors[l];
  return kAdequacyLevelColors[l];
}
const char* family_title(Family f) {
  return f == Family::kKemppinen ? "Kemppinen"
         : f == Family::kArea    ? "Area"
         : f == Family::kChermain ? "Chermain"
                                  : "Binomial";
}

struct SceneResult {
  adq::SceneRender render;
  // kKemppinen: KemppinenLevel values, k16_exact complete; kChermain: ChermainLevel values,
  // dict16_ggaa complete; else BinomialLevel values, exact.
  Family family = Family::kBinomial;
  int realisations = 0;
  int zoom = 1;  // the sheet's pixels per render pixel (the Kemppinen and area scenes are smaller)
  adq::SafetyTally tally;
  double exposure = 1;
  double max_diff = 0;  // the largest difference estimate over the measured pixels, in TAU
};

// 0.8 / the 99th percentile of the exact render over the surface: the highlight not all clipped.
double exposure_of(const adq::SceneRender& r) {
  std::vector<double> v;
  for (const adq::ScenePixel& p : r.pixels)
    if (p.surface && p.exact_value > 0) v.push_back(p.exact_value);
  if (v.empty()) return 1;
  const std::size_t k = std::min(v.size() - 1, std::size_t(0.99 * double(v.size())));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k] > 0 ? 0.8 / v[k] : 1;
}

double difference_in_tau(const adq::ScenePixel& p, double tau) {
  return std::max(p.mean_diff, p.cv_diff) / tau;
}

void put(Image& im, int x, int y, Vec3<double> c) {
  im.at(x, y, 0) = c.x, im.at(x, y, 1) = c.y, im.at(x, y, 2) = c.z;
}

// The renders of a scene (the montage panels.png): each pixel with its chosen level, or with the
// family's most complete level everywhere, at the scene's exposure; black off the surface. Its
// difference and level maps are the labelled sheet's heat maps (write_sheet_spec).
enum class Render { kChosen, kExact };

Image render_panel(const SceneResult& s, Render which) {
  const adq::SceneRender& r = s.render;
  Image im(r.width, r.height, {"R", "G", "B"});
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x) {
      const adq::ScenePixel& p = r.pixels[std::size_t(y) * std::size_t(r.width) + std::size_t(x)];
      const double v = which == Render::kChosen ? p.chosen_value : p.exact_value;
      put(im, x, y,
          p.surface ? Vec3<double>{1, 1, 1} * std::min(v * s.exposure, 1.0)
                    : Vec3<double>{0, 0, 0});
    }
  return im;
}

void blit(Image& to, const Image& from, int ox, int oy) {
  for (int y = 0; y < from.height; ++y)
    for (int x = 0; x < from.width; ++x)
      for (std::size_t c = 0; c < 3; ++c) to.at(ox + x, oy + y, c) = from.at(x, y, c);
}

// Each pixel as a zoom × zoom block (the Kemppinen and area scenes' renders at the binomial
// panels' size).
Image enlarge(const Image& from, int zoom) {
  if (zoom == 1) return from;
  Image out(from.width * zoom, from.height * zoom, {"R", "G", "B"});
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (std::size_t c = 0; c < 3; ++c) out.at(x, y, c) = from.at(x / zoom, y / zoom, c);
  return out;
}

Image display_panel(const SceneResult& s, Render which) {
  return enlarge(render_panel(s, which), s.zoom);
}

std::string_view most_complete_name(const SceneResult& r) {
  return family_level_names(r.family)[std::size_t(adq::most_complete_level(r.render.scene))];
}

// What log10_density counts: the binomial models' facets, Kemppinen's points (K_P).
const char* density_unit(const adq::ChoiceScene& s) {
  return adq::is_kemppinen_scene(s) ? "points (K_P)"
         : adq::is_chermain_scene(s) ? "microfacets"
                                     : "facets";
}

const char* light_name(adq::SceneLight l) {
  return l == adq::SceneLight::kPoint         ? "point"
         : l == adq::SceneLight::kSphereLight ? "spherical"
                                              : "square";
}

std::string scene_label(const adq::ChoiceScene& s) {
  return fmt::format("{} ({}, {} light, {} density, 1e{:g} {} per unit uv area)",
                     s.shape == adq::SceneShape::kPlane ? "plane" : "sphere", s.model,
                     light_name(s.light), s.density_label, s.log10_density, density_unit(s));
}

const char* kColumnNames[4] = {"chosen level", "most complete level", "difference / TAU",
                               "chosen level map"};

// How the sheet's title describes a family's renders.
struct FamilyLine {
  std::string_view family, complete;
  int width = 0, height = 0, realisations = 0;
};

// Every scene's pixels as data (the sheet's maps): the difference in TAU where it is measured
// (nan off the surface, where the most complete level is dark, and where a bound exceeds TAU),
// whether a bound exceeds TAU, whether the pixel is too dark to measure, and the chosen level
// (-1 off the surface); pixels in image order, row 0 at the top.
void write_pixels_csv(const std::filesystem::path& file, const std::vector<SceneResult>& results,
                      double tau) {
  io::write_csv_atomic(
      file, {"scene", "x", "y", "difference", "exceeds", "dark", "level"}, [&](io::CsvWriter& w) {
        for (const SceneResult& s : results) {
          const adq::SceneRender& r = s.render;
          for (int y = 0; y < r.height; ++y)
            for (int x = 0; x < r.width; ++x) {
              const adq::ScenePixel& p =
                  r.pixels[std::size_t(y) * std::size_t(r.width) + std::size_t(x)];
              const bool measured = p.surface && p.lit && !p.exceeds;
              w.cell(r.scene.name).cell_int(x).cell_int(y);
              w.cell(measured ? difference_in_tau(p, tau) : NAN);
              w.cell_int(p.exceeds ? 1 : 0).cell_int(p.surface && !p.lit && !p.exceeds ? 1 : 0);
              w.cell_int(p.surface ? p.level : -1).end_row();
            }
        }
      });
}

nlohmann::json rgb(Vec3<double> c) { return {c.x, c.y, c.z}; }

// The labelled sheet's spec (drawn by reports/figure_charts.py from the pixels' CSV): per scene
// its difference map (a heat map on a 0 .. kScaleMaxTau TAU colour bar, the pixels over TAU and
// the dark ones filled and counted) beside its chosen-level map (the family's levels as the
// colour bar). The renders are the montage panels.png.
void write_sheet_spec(const std::filesystem::path& png, const std::string& csv,
                      const std::vector<SceneResult>& scenes, const adq::SceneOptions& o,
                      const std::vector<FamilyLine>& families) {
  std::string title = fmt::format(
      "adequacy-scene: each pixel with its chosen level against the most complete level "
      "everywhere (TAU = {}, GGX alpha {})",
      o.tau, adq::kSceneAlpha);
  for (const FamilyLine& l : families)
    title += fmt::format("\n{} family: most complete {}, {}x{} pixels, {} realisations per pixel",
                         l.family, l.complete, l.width, l.height, l.realisations);
  const nlohmann::json x = {{"column", "x"}, {"label", "x [pixel]"}};
  const nlohmann::json y = {
      {"columns", {"y"}}, {"format", "{y}"}, {"label", "y [pixel]"}, {"invert", true}};
  nlohmann::json panels = nlohmann::json::array();
  for (const SceneResult& r : scenes) {
    const std::string name = fmt::format("{} ({})", r.render.scene.name, r.render.scene.model);
    const std::string counts = fmt::format(
        "1e{:g} {}/uv area: {} lit, {} cheaper, {} over TAU", r.render.scene.log10_density,
        adq::is_kemppinen_scene(r.render.scene) ? "points" : "facets", r.tally.lit, r.tally.cheaper,
        r.tally.exceeds);
    const nlohmann::json where = {{"scene", r.render.scene.name}};
    panels.push_back({{"kind", "heatmap"},
                      {"title", fmt::format("{}: {}\n{}", name, kColumnNames[2], counts)},
                      {"where", where},
                      {"x", x},
                      {"y", y},
                      {"value",
                       {{"column", "difference"},
                        {"label", "difference / TAU [1] (max of mean and CV differences)"},
                        {"range", {0.0, kScaleMaxTau}},
                        {"cmap", "coolwarm"}}},
                      {"flags",
                       {{{"column", "exceeds"},
                         {"value", 1},
                         {"label", "exceeds TAU (bound)"},
                         {"color", rgb(kExceeds)},
                         {"style", "fill"}},
                        {{"column", "dark"},
                         {"value", 1},
                         {"label", "dark: not measurable"},
                         {"color", rgb(kDark)},
                         {"style", "fill"}}}},
                      {"empty_label", "off the surface"}});
    nlohmann::json categories = nlohmann::json::array();
    categories.push_back(
        {{"value", -1}, {"label", "off the surface"}, {"color", rgb(kOffSurface)}});
    for (std::size_t l = 0; l < family_level_names(r.family).size(); ++l)
      categories.push_back({{"value", l},
                            {"label", family_level_names(r.family)[l]},
                            {"color", rgb(family_level_color(r.family, l))}});
    panels.push_back({{"kind", "categories"},
                      {"title", fmt::format("{}: {}\n{}", name, kColumnNames[3], counts)},
                      {"where", where},
                      {"x", x},
                      {"y", y},
                      {"value", {{"column", "level"}, {"label", "chosen level"}}},
                      {"categories", categories}});
  }
  write_chart_json(png, {{"kind", "heatmap"},
                         {"title", title},
                         {"csv", csv},
                         {"columns", 2},
                         {"panels", panels}});
}

Image montage(const std::vector<Image>& tiles, int columns, int gap) {
  const int w = tiles[0].width, h = tiles[0].height;
  const int rows = (int(tiles.size()) + columns - 1) / columns;
  Image out(columns * (w + gap) - gap, rows * (h + gap) - gap, {"R", "G", "B"});
  std::fill(out.data.begin(), out.data.end(), 1.0);
  for (std::size_t k = 0; k < tiles.size(); ++k)
    blit(out, tiles[k], int(k) % columns * (w + gap), int(k) / columns * (h + gap));
  return out;
}

void write_scene_exr(const FigureContext& ctx, const SceneResult& s) {
  const adq::SceneRender& r = s.render;
  Image im(r.width, r.height,
           {"chosen", "exact", "level", "facets", "p", "mean_diff", "cv_diff", "mean_diff_lcb",
            "cv_diff_lcb", "lit", "exceeds", "surface"});
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x) {
      const adq::ScenePixel& p = r.pixels[std::size_t(y) * std::size_t(r.width) + std::size_t(x)];
      const double v[] = {
          p.chosen_value,    p.exact_value,    double(p.level), p.facets,      p.p,
          p.mean_diff,       p.cv_diff,        p.mean_diff_lcb, p.cv_diff_lcb, double(p.lit),
          double(p.exceeds), double(p.surface)};
      for (std::size_t c = 0; c < std::size(v); ++c) im.at(x, y, c) = v[c];
    }
  std::string levels;
  for (std::size_t l = 0; l < family_level_names(s.family).size(); ++l)
    levels += fmt::format("{} {}, ", l, family_level_names(s.family)[l]);
  io::write_exr(ctx.dir / (r.scene.name + ".exr"), im,
                {{"glintlab_figure", std::string(kId)},
                 {"glintlab_version", std::string(glintlab_version())},
                 {"content", fmt::format("{}; level: {}-1 off the surface; chosen/exact: "
                                         "radiance of the first realisation with the chosen "
                                         "level / the most complete level ({})",
                                         scene_label(r.scene), levels, most_complete_name(s))}});
}

// A scene's time per evaluation summed over its surface pixels (where a shader runs), each level
// priced by the benchmark (`ns`: its family's levels, the most complete last): the most complete
// level everywhere (exact counting, k16_exact, dict16_ggaa), the engine chooser's levels (the GPU
// order) and the levels the family's chooser for these costs picks: choose_binomial_level_by_cost
// (core/glints/adequacy.h) on the pixel's N_P and p; for the Kemppinen and Chermain families
// cheapest_adequate_level (core/glints/cost_chooser.h) on the levels the engine chooser predicts
// adequate at the pixel (ScenePixel::predicted_adequate), which is what
// choose_kemppinen_model_level_by_cost and choose_chermain_model_level_by_cost compute.
struct SceneCost {
  double exact_ns = 0, chosen_ns = 0, by_cost_ns = 0;
};
template <std::size_t N>
std::array<bool, N> adequacy_from_bits(std::uint32_t bits) {
  std::array<bool, N> a{};
  for (std::size_t l = 0; l < N; ++l) a[l] = (bits >> l) & 1u;
  return a;
}
SceneCost scene_cost(const adq::SceneRender& r, Family family, std::span<const double> ns,
                     double tau) {
  static_assert(kKemppinenLevels == kChermainLevels);
  SceneCost c;
  const bool binomial = family == Family::kBinomial || family == Family::kArea;
  std::array<double, kBinomialLevels> cost{};
  std::array<double, kChermainLevels> cost9{};
  if (binomial)
    std::copy_n(ns.begin(), kBinomialLevels, cost.begin());
  else
    std::copy_n(ns.begin(), kChermainLevels, cost9.begin());
  for (const adq::ScenePixel& p : r.pixels) {
    if (!p.surface || p.level < 0) continue;
    c.exact_ns += ns.back();
    c.chosen_ns += ns[std::size_t(p.level)];
    const std::size_t by_cost =
        binomial ? std::size_t(choose_binomial_level_by_cost(p.facets, p.p, tau, cost))
                 : std::size_t(cheapest_adequate_level<double, kChermainLevels>(
                       adequacy_from_bits<kChermainLevels>(p.predicted_adequate), cost9));
    c.by_cost_ns += ns[by_cost];
  }
  return c;
}

// The cost section of summary.md and adequacy-scene-cost.csv, or the one sentence saying why there
// is none. Each family's scenes are priced by its models' rows; a family whose rows the file lacks
// (an older file) is left unpriced, and the summary says why.
std::string write_scene_costs(const FigureContext& ctx, const std::vector<SceneResult>& results,
                              double tau) {
  const BenchSource src = bench_source(ctx, kLevelCostsFile);
  if (src.path.empty() || !std::filesystem::exists(src.path))
    return "\n## Time per evaluation\n\n" +
           no_bench_data(src, kLevelCostsFile,
                         "glintlab_bench_glints --benchmark_filter=^adequacy/") +
           "\n";
  LevelCosts costs;
  costs.isa = simd::isa_name(simd::default_isa());
  std::vector<std::string> unpriced, reasons;  // families without costs, and why
  for (const Family f : {Family::kBinomial, Family::kKemppinen, Family::kArea, Family::kChermain}) {
    std::vector<std::string> models;
    for (const SceneResult& r : results)
      if (r.family == f &&
          std::find(models.begin(), models.end(), r.render.scene.model) == models.end())
        models.push_back(r.render.scene.model);
    if (models.empty()) continue;
    try {
      LevelCosts c = read_level_costs(src.path.parent_path(),
                                      std::filesystem::path(src.shown_as).parent_path().string(),
                                      costs.isa, models);
      costs.source = c.source;
      for (auto& [model, ns] : c.ns) costs.ns.emplace(model, std::move(ns));
    } catch (const std::invalid_argument& e) {
      const std::string_view title = family_title(f);
      unpriced.push_back(f == Family::kArea ? "area" : std::string(title));
      reasons.emplace_back(
          std::string_view(e.what()).substr(std::string_view("--bench-from: ").size()));
    }
  }
  if (costs.ns.empty())
    return fmt::format("\n## Time per evaluation\n\nNo benchmark data: {}.\n",
                       fmt::join(reasons, "; "));
  const auto priced = [&](const SceneResult& r) {
    return costs.ns.count(r.render.scene.model) > 0;
  };
  std::string md = fmt::format(
      "\n## Time per evaluation\n\nEach level priced by {} (rows adequacy/<model>/level=<level>/"
      "{}), summed over each scene's surface pixels: the family's most complete level everywhere "
      "(exact counting, k16_exact, dict16_ggaa), the engine chooser's levels (the GPU-lane order) "
      "and the levels the family's chooser for these costs picks (choose_binomial_level_by_cost; "
      "choose_kemppinen_model_level_by_cost and choose_chermain_model_level_by_cost, "
      "core/glints/cost_chooser.h); saved = 1 − time / most complete time.\n\n",
      costs.source, costs.isa);
  if (!unpriced.empty())
    md += fmt::format("The {} scenes are not priced here: {}.\n\n", fmt::join(unpriced, " and "),
                      fmt::join(reasons, "; "));
  md +=
      "| scene | most complete everywhere (ns) | chosen levels (ns) | saved | by these costs (ns) "
      "| saved |\n|---|---|---|---|---|---|\n";
  const auto saved = [](double t, double exact) { return exact > 0 ? 1 - t / exact : 0.0; };
  io::write_csv_atomic(
      ctx.dir / "adequacy-scene-cost.csv",
      {"scene", "model", "isa", "surface_pixels_exact_ns", "chosen_ns", "chosen_saved_fraction",
       "by_cost_ns", "by_cost_saved_fraction"},
      [&](io::CsvWriter& w) {
        for (const SceneResult& r : results) {
          if (!priced(r)) continue;
          const SceneCost c =
              scene_cost(r.render, r.family, costs.ns.at(r.render.scene.model), tau);
          w.cell(r.render.scene.name).cell(r.render.scene.model).cell(costs.isa);
          w.cell(c.exact_ns).cell(c.chosen_ns).cell(saved(c.chosen_ns, c.exact_ns));
          w.cell(c.by_cost_ns).cell(std::isnan(c.by_cost_ns) ? NAN : saved(c.by_cost_ns, c.exact_ns));
          w.end_row();
          md += fmt::format("| {} | {:.4g} | {:.4g} | {:.1f} % | {} | {} |\n",
                            r.render.scene.name, c.exact_ns, c.chosen_ns,
                            100 * saved(c.chosen_ns, c.exact_ns),
                            std::isnan(c.by_cost_ns) ? "—" : fmt::format("{:.4g}", c.by_cost_ns),
                            std::isnan(c.by_cost_ns)
                                ? "—"
                                : fmt::format("{:.1f} %", 100 * saved(c.by_cost_ns, c.exact_ns)));
        }
      });
  return md;
}

// The per-scene counts of one family as CSV: the scenes' settings, the tally and the lit pixels per
// chosen level (the family's level names as columns).
void write_family_csv(const std::filesystem::path& file, const std::vector<SceneResult>& results,
                      Family family) {
  const std::span<const std::string_view> names = family_level_names(family);
  std::vector<std::string_view> header = {"scene",         "model",   "shape",  "light",
                                          "log10_density", "width",   "height", "realisations",
                                          "lit",           "cheaper", "exceeds"};
  const std::size_t levels = names.size();
  for (std::size_t l = 0; l < levels; ++l) header.emplace_back(names[l]);
  header.emplace_back("max_diff_over_tau");
  header.emplace_back("exposure");
  io::write_csv_atomic(file, header, [&](io::CsvWriter& w) {
    for (const SceneResult& r : results) {
      if (r.family != family) continue;
      const adq::ChoiceScene& s = r.render.scene;
      w.cell(s.name)
          .cell(s.model)
          .cell(s.shape == adq::SceneShape::kPlane ? "plane" : "sphere")
          .cell(light_name(s.light))
          .cell(s.log10_density)
          .cell_int(r.render.width)
          .cell_int(r.render.height)
          .cell_int(r.realisations)
          .cell_int((long long)r.tally.lit)
          .cell_int((long long)r.tally.cheaper)
          .cell_int((long long)r.tally.exceeds);
      for (std::size_t l = 0; l < levels; ++l) w.cell_int((long long)r.tally.by_level[l]);
      w.cell(r.max_diff).cell(r.exposure);
      w.end_row();
    }
  });
}

// One family's section of summary.md: its scenes' table and the decision claim
// adequacy.choice-is-safe takes on such counts (each family on its own at the Šidák share of the
// per-check level, as the claim decides them).
std::string family_summary(const std::vector<SceneResult>& results, Family family, double alpha) {
  const std::span<const std::string_view> names = family_level_names(family);
  adq::SafetyTally total;
  std::string md = fmt::format("| scene | model | lit pixels | cheaper than {} | exceed TAU |",
                               family == Family::kKemppinen  ? "k16_exact"
                               : family == Family::kChermain ? "dict16_ggaa"
                                                             : "exact");
  const std::size_t levels = names.size();
  for (std::size_t l = 0; l < levels; ++l) md += fmt::format(" {} |", names[l]);
  md += " max difference / TAU |\n|";
  for (std::size_t c = 0; c < levels + 6; ++c) md += "---|";
  md += "\n";
  for (const SceneResult& r : results) {
    if (r.family != family) continue;
    adq::add(total, r.tally);
    md += fmt::format("| {} | {} | {} | {} | {} |", r.render.scene.name, r.render.scene.model,
                      r.tally.lit, r.tally.cheaper, r.tally.exceeds);
    for (std::size_t l = 0; l < levels; ++l) md += fmt::format(" {} |", r.tally.by_level[l]);
    md += fmt::format(" {:.3g} |\n", r.max_diff);
  }
  const adq::SafetyDecision d = adq::decide_choice_safety(total, alpha);
  md += fmt::format(
      "\n{} family: {} of {} lit pixels exceed TAU (fraction {:.4g}); the decision of claim "
      "adequacy.choice-is-safe on these pixels allows at most {} ({:.4g}; one-sided exact "
      "binomial test of rate ≤ {} at {:.3g}, the Šidák share of {:.3g} over the {} families, "
      "p = {:.3g}): {}.\n",
      family_title(family), total.exceeds, total.lit, d.fraction, d.allowed,
      d.allowed_fraction, adq::kPixelFlagRate, alpha, verify::check_level(), kFamilies, d.p_value,
      to_string(d.verdict));
  return md;
}

void run_adequacy_scene(const FigureContext& ctx) {
  std::unique_ptr<tbb::global_control> limit;
  if (ctx.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  std::size_t(ctx.threads));
  adq::SceneOptions o;
  // Renders a person can see: 128² at quick, 512² at full, both with 256 realisations per pixel
  // (fewer realisations rather than fewer pixels; claim adequacy.choice-is-safe measures its own
  // scenes at its own sizes, verify/claims/adequacy/choice_is_safe.cpp).
  o.width = o.height = ctx.quick ? 128 : 512;
  o.realisations = 256;
  // The Kemppinen scenes: k = 16 costs some 90 µs of CPU per evaluation, so 32² with 128
  // realisations at quick and 64² with 256 at full (the claim: 24² and 48²), each pixel shown as
  // a block at the binomial panels' size.
  adq::SceneOptions ko;
  ko.width = ko.height = ctx.quick ? 32 : 64;
  ko.realisations = ctx.quick ? 128 : 256;
  // The area scenes: kneiphof_klein_area's LTC polygon integral costs some 2-3 µs per evaluation,
  // so 64² at quick and 128² at full (the claim: 32² and 64²), 256 and 512 realisations.
  adq::SceneOptions ao;
  ao.width = ao.height = ctx.quick ? 64 : 128;
  ao.realisations = ctx.quick ? 256 : 512;
  // The Chermain scenes: dict16_ggaa's 16-probe textureGrad costs some 2-4 µs per evaluation, so
  // 32² with 128 realisations at quick and 64² with 256 at full (the claim's sizes).
  adq::SceneOptions co;
  co.width = co.height = ctx.quick ? 32 : 64;
  co.realisations = ctx.quick ? 128 : 256;
  const adq::SceneOptions* options[kFamilies] = {&o, &ko, &ao, &co};
  // The scenes of every family in the claim's order (binomial, Kemppinen, area, Chermain), each
  // family's in its own order; a scene's seed index is its place in declaration order
  // (adq::declaration_order: the scenes declared later, the area and Chermain spheres, after all
  // the others, so that the others keep their seeds), as the claim's.
  const std::vector<std::vector<adq::ChoiceScene>> lists = {
      adq::choice_scenes(), adq::kemppinen_choice_scenes(), adq::area_choice_scenes(),
      adq::chermain_choice_scenes()};
  std::vector<std::vector<std::size_t>> seed_index(lists.size());
  for (std::size_t f = 0; f < lists.size(); ++f) seed_index[f].resize(lists[f].size());
  const auto declared = adq::declaration_order(lists);
  for (std::size_t k = 0; k < declared.size(); ++k) seed_index[declared[k][0]][declared[k][1]] = k;
  std::vector<adq::ChoiceScene> scenes;
  std::vector<Family> families;
  std::vector<std::size_t> seeds;
  for (std::size_t f = 0; f < lists.size(); ++f)
    for (std::size_t i = 0; i < lists[f].size(); ++i) {
      scenes.push_back(lists[f][i]);
      families.push_back(Family(f));
      seeds.push_back(seed_index[f][i]);
    }
  // The scenes side by side as well as each over its rows: a scene's rows alone leave a thread
  // idle over its last rows (a sphere's lit rows cost the most), 18 times in a row. Each scene's
  // seed and render do not depend on the order or the threads; the files are written in order.
  std::vector<SceneResult> results(scenes.size());
  std::mutex progress_mutex;
  std::size_t rendered = 0;
  if (ctx.progress) ctx.progress("adequacy-scene: scenes", 0, long(scenes.size()));
  tbb::parallel_for(std::size_t(0), scenes.size(), [&](std::size_t i) {
    SceneResult& r = results[i];
    r.family = families[i];
    // Seeds from the figure id and the scene's index in declaration order (as the claim's).
    adq::SceneOptions so = *options[int(r.family)];
    so.seed = verify::check_seed(std::string(kId), seeds[i]);
    r.realisations = so.realisations;
    r.zoom = o.width / so.width;
    r.render = adq::render_choice_scene(scenes[i], so);
    r.tally = adq::tally(r.render);
    r.exposure = exposure_of(r.render);
    for (const adq::ScenePixel& p : r.render.pixels)
      if (p.lit) r.max_diff = std::max(r.max_diff, difference_in_tau(p, o.tau));
    const std::lock_guard<std::mutex> lock(progress_mutex);
    ++rendered;
    if (ctx.progress) ctx.progress("adequacy-scene: scenes", long(rendered), long(scenes.size()));
  });
  for (const SceneResult& r : results) write_scene_exr(ctx, r);

  write_pixels_csv(ctx.dir / "adequacy-scene-pixels.csv", results, o.tau);
  write_sheet_spec(ctx.dir / "adequacy-scene.png", "adequacy-scene-pixels.csv", results, o,
                   {{"binomial", kBinomialLevelNames[std::size_t(BinomialLevel::kExact)], o.width,
                     o.height, o.realisations},
                    {"kemppinen", kKemppinenLevelNames[std::size_t(KemppinenLevel::kK16Exact)],
                     ko.width, ko.height, ko.realisations},
                    {"area", kBinomialLevelNames[std::size_t(BinomialLevel::kExact)], ao.width,
                     ao.height, ao.realisations},
                    {"chermain", kChermainLevelNames[std::size_t(kChermainMostComplete)],
                     co.width, co.height, co.realisations}});
  std::vector<Image> tiles;
  std::vector<std::string> labels;
  for (const SceneResult& r : results)
    for (const Render c : {Render::kChosen, Render::kExact}) {
      tiles.push_back(display_panel(r, c));
      labels.push_back(fmt::format("{}: {}", r.render.scene.name, kColumnNames[int(c)]));
    }
  io::write_png_preview(ctx.dir / "panels.png", montage(tiles, 4, 2));
  write_panel_layout(ctx.dir / "panels.png",
                     {"adequacy-scene: per scene the render with the chosen level and with the "
                      "most complete level (same exposure; their difference and the chosen level "
                      "are the maps of adequacy-scene.png)",
                      4,
                      2,
                      labels});

  write_family_csv(ctx.dir / "adequacy-scene.csv", results, Family::kBinomial);
  write_family_csv(ctx.dir / "adequacy-scene-kemppinen.csv", results, Family::kKemppinen);
  write_family_csv(ctx.dir / "adequacy-scene-area.csv", results, Family::kArea);
  write_family_csv(ctx.dir / "adequacy-scene-chermain.csv", results, Family::kChermain);

  // Each family at the Šidák share of the per-check level over the claim's families.
  const double alpha = verify::sidak_level(verify::check_level(), kFamilies);
  std::string md = fmt::format(
      "# adequacy-scene\n\nScenes the adequacy grid was not measured on (verify/scenes/"
      "adequacy_scenes.h), rendered by the claim's own code (render_choice_scene): each pixel "
      "with the level the engine chooser (core/glints/adequacy.h) picks for its footprint and "
      "with the family's most complete level everywhere. The difference of a pixel is measured "
      "over its realisations of the same material (the footprint moved over the surface), by the "
      "adequacy rule's statistics: |mean/mean_complete − 1| and |CV − CV_complete|; it exceeds "
      "TAU = {} when either lower bound (one-sided {} each) is above TAU.\n\n"
      "## Binomial family (deliot_belcour, kneiphof_klein; most complete: exact counting)\n\n"
      "{}×{} pixels, {} realisations per pixel.\n\n",
      o.tau, adq::kPixelFlagRate / 2, o.width, o.height, o.realisations);
  md += family_summary(results, Family::kBinomial, alpha);
  md += fmt::format(
      "\n## Kemppinen family (kemppinen_ggx; most complete: k16_exact)\n\n"
      "{}×{} pixels (each shown {}×{} on the sheet), {} realisations per pixel; levels by "
      "choose_kemppinen_model_level; K_P is the points per unit uv area.\n\n",
      ko.width, ko.height, o.width / ko.width, o.width / ko.width, ko.realisations);
  md += family_summary(results, Family::kKemppinen, alpha);
  md += fmt::format(
      "\n## Area family (kneiphof_klein_area under a square light of side {:.3g}; most complete: "
      "exact counting)\n\n"
      "{}×{} pixels (each shown {}×{} on the sheet), {} realisations per pixel; levels by "
      "choose_kneiphof_klein_area_model_level (core/glints/area_chooser.h: choose_binomial_level "
      "with the model's N_P and LTC p).\n\n",
      adq::kRectLightSide, ao.width, ao.height, o.width / ao.width, o.width / ao.width,
      ao.realisations);
  md += family_summary(results, Family::kArea, alpha);
  md += fmt::format(
      "\n## Chermain family (chermain; most complete: dict16_ggaa)\n\n"
      "{}×{} pixels (each shown {}×{} on the sheet), {} realisations per pixel; levels by "
      "choose_chermain_model_level (core/glints/chermain_chooser.h) with the pixel's GGAA "
      "derivatives; the density is microfacets per unit uv area.\n\n",
      co.width, co.height, o.width / co.width, o.width / co.width, co.realisations);
  md += family_summary(results, Family::kChermain, alpha);
  md += fmt::format(
      "\nadequacy-scene.png (drawn by matplotlib from adequacy-scene-pixels.csv): one row per "
      "scene; columns: the difference map (max of the two differences over TAU on its colour "
      "scale, 0 to 2 TAU; magenta where it exceeds TAU for sure; dark grey where the most "
      "complete level is lit at fewer than {:g} realisations; light grey off the surface) and the "
      "chosen level (binomial and area: green smooth, blue realtime, orange small_count, red "
      "exact; "
      "Kemppinen: green smooth, then k = 1, 4, 9, 16 in blue, yellow, purple, red, the exact erf "
      "the darker shade; Chermain: the same colours for smooth, dict4, 8, 12, 16, GGAA on the "
      "darker shade). panels.png: per scene the chosen-level render and the most complete "
      "level's render (same exposure), two scenes a row, unlabelled (labels in "
      "panels.panels.json); <scene>.exr every per-pixel "
      "quantity at the render's size; adequacy-scene.csv, adequacy-scene-kemppinen.csv, "
      "adequacy-scene-area.csv and adequacy-scene-chermain.csv the per-scene counts.\n",
      adq::kMinLitPositions);
  md += write_scene_costs(ctx, results, o.tau);
  io::write_file_atomic(ctx.dir / "summary.md", md);
}

}  // namespace

FigureEntry adequacy_scene_entry() {
  return {
      kId, "glintlab (adequacy of the binomial family)", "claim adequacy.choice-is-safe",
      "validation scenes of the binomial, Kemppinen, area and Chermain families: each pixel's "
      "chosen level "
      "against the family's most complete level, with the difference map and the "
      "chosen-level map",
      run_adequacy_scene};
}

}  // namespace glintlab::experiments

// `glintlab adequacy [--models GLOBS] [--threshold TAU] [--budget quick|full] [--positions N]
// [--threads N] [--out DIR] [--bench-from DIR] [--calibrate [--runs N] [--tables N]]`: where each
// cheaper level
// of the binomial
// glint family is indistinguishable from the exact count, and each cheaper level of the Kemppinen
// family from k = 16 with the exact erf, of the area and Chermain families likewise, each family's
// levels priced by the benchmark with --bench-from (verify/adequacy/, experiments/adequacy/;
// docs/adequacy.md); with --calibrate, the decision rule's false-adequate rate on synthetic cells
// whose truth is known instead.
#include <fmt/format.h>
#include <tbb/global_control.h>

#include <array>
#include <chrono>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "cli/child_process.h"
#include "cli/commands.h"
#include "cli/input.h"
#include "cli/progress.h"
#include "cli/shard.h"
#include "cli/shard_merge.h"
#include "cli/suite_runs.h"
#include "core/io/atomic_file.h"
#include "core/simd/batch.h"
#include "experiments/adequacy/adequacy_outputs.h"
#include "experiments/adequacy/adequacy_shards.h"

namespace glintlab::cli {
namespace {

namespace fs = std::filesystem;

// --positions: below 100 every cell is undecided (a cell's exact level must be lit at 100
// positions); a million keeps a cell's level values (nine levels of doubles) within 100 MB.
constexpr std::uint64_t kMinPositions = 100, kMaxPositions = 1000000;

struct AdequacyCliOptions {
  std::string out = "out/adequacy";
  BudgetOption budget;
  std::string models = "*";
  std::string threshold = "0.02";
  std::string threads;
  bool calibrate = false;
  std::string runs = "2000";
  std::string tables = "20";
  std::string bench_from;
  std::string shard;
  std::string positions;
};

// A family of the binomial levels (the binomial and the area family): cells per level, the
// chooser against the table, undecided cells and the summed in-process times.
void print_counting_family(std::string_view family, std::string_view chooser, std::size_t cells,
                           const std::array<std::size_t, kBinomialLevels>& chosen,
                           std::size_t matches, std::size_t refuted, std::size_t undecided,
                           double exact_ns, double chosen_ns, double cheapest_ns,
                           const std::array<std::size_t, kBinomialLevels>& cheapest) {
  fmt::print(
      "{}: {} cells; cheapest adequate level: smooth {}, realtime {}, small_count {}, exact {}\n",
      family, cells, chosen[0], chosen[1], chosen[2], chosen[3]);
  fmt::print("{}: same level as measured in {} cells, refuted in {}\n", chooser, matches, refuted);
  fmt::print("{} cells undecided (too few lit positions at the exact level: exact kept)\n",
             undecided);
  const auto saved = [&](double ns) { return exact_ns > 0 ? 100 * (1 - ns / exact_ns) : 0.0; };
  fmt::print(
      "time per evaluation summed over cells (this CPU, scalar double): exact everywhere "
      "{:.0f} ns; chosen level {:.0f} ns ({:.1f} % saved); measured-cheapest adequate level "
      "{:.0f} ns ({:.1f} % saved; smooth {}, realtime {}, small_count {}, exact {} cells)\n",
      exact_ns, chosen_ns, saved(chosen_ns), cheapest_ns, saved(cheapest_ns), cheapest[0],
      cheapest[1], cheapest[2], cheapest[3]);
}

// A family of many levels (Kemppinen, Chermain): cells per level, its chooser's line, undecided
// cells and the summed in-process times against its most complete level.
template <std::size_t N>
void print_leveled_family(std::string_view family, const std::array<std::string_view, N>& names,
                          std::size_t cells, const std::array<std::size_t, N>& chosen,
                          const std::string& chooser_line, std::size_t undecided,
                          std::string_view most_complete, double most_complete_ns,
                          double chosen_ns, double cheapest_ns) {
  std::vector<std::string> counts;
  for (std::size_t l = 0; l < N; ++l) counts.push_back(fmt::format("{} {}", names[l], chosen[l]));
  fmt::print("{}: {} cells; cheapest adequate level: {}\n", family, cells, fmt::join(counts, ", "));
  fmt::print("{}\n", chooser_line);
  fmt::print("{} cells undecided (too few lit positions at {}: {} kept)\n", undecided,
             most_complete, most_complete);
  const auto saved = [&](double ns) {
    return most_complete_ns > 0 ? 100 * (1 - ns / most_complete_ns) : 0.0;
  };
  fmt::print(
      "time per evaluation summed over cells (this CPU, scalar double): {} everywhere "
      "{:.0f} ns; chosen level {:.0f} ns ({:.1f} % saved); measured-cheapest adequate level "
      "{:.0f} ns ({:.1f} % saved)\n",
      most_complete, most_complete_ns, chosen_ns, saved(chosen_ns), cheapest_ns,
      saved(cheapest_ns));
}

void print_calibration(const AdequacyRunSummary& run) {
  const auto& s = run.calibration;
  const auto& cal = s.calibration;
  fmt::print(
      "adequacy calibration: TAU {:g}, {} positions per cell, the table's {} decisions (z {:.3f}); "
      "{} synthetic cells per case and delta, {} tables per family-wise delta\n",
      cal.options.threshold, cal.options.samples, cal.options.table_decisions,
      cal.table_decision.z, cal.options.runs, cal.options.tables);
  for (const auto& r : cal.rows)
    if (r.delta == 0)
      fmt::print("  {:6} cv_exact {:<5g} nominal {:<9.3g} false adequate {:>5}/{} = {:.3g} "
                 "[{:.3g}, {:.3g}] {}\n",
                 verify::adequacy::kTruthKindNames[std::size_t(r.truth.kind)], r.truth.cv_exact,
                 r.nominal, r.declared_adequate, r.decisions, r.rate, r.rate_low, r.rate_high,
                 verify::adequacy::kRateVerdictNames[std::size_t(r.verdict)]);
  for (const auto& r : cal.pooled)
    fmt::print("  pooled delta {:<5g} nominal {:<9.3g} {} {:>5}/{} = {:.3g} [{:.3g}, {:.3g}] {}\n",
               r.delta, r.nominal, r.truly_adequate ? "adequate (power)" : "false adequate  ",
               r.declared_adequate, r.decisions, r.rate, r.rate_low, r.rate_high,
               verify::adequacy::kRateVerdictNames[std::size_t(r.verdict)]);
  for (const auto& fw : cal.family_wise)
    fmt::print(
        "family-wise at delta {:g} (tables of {} decisions at TAU (1 + delta), the table's z): "
        "{}/{} tables with a false adequate ({} in all) = {:.3g} [{:.3g}, {:.3g}] against {:g}: "
        "{}\n",
        fw.delta, fw.table_decisions, fw.tables_with_false_adequate, fw.tables, fw.false_adequate,
        fw.rate, fw.rate_low, fw.rate_high, fw.nominal,
        verify::adequacy::kRateVerdictNames[std::size_t(fw.verdict)]);
  fmt::print("wrote {} and {} in {:.1f} s\n", s.csv.string(), s.json.string(), run.seconds);
}

void run(const CLI::App* cmd, const AdequacyCliOptions& o) {
  AdequacyRequest r;
  r.out = o.out;
  r.budget = resolve_budget(cmd, o.budget);
  r.models = o.models;
  r.threshold = o.threshold;
  r.threads = o.threads;
  r.calibrate = o.calibrate;
  if (option_count(cmd, "--runs") > 0) r.runs = o.runs;
  if (option_count(cmd, "--tables") > 0) r.tables = o.tables;
  if (option_count(cmd, "--bench-from") > 0) r.bench_from = o.bench_from;
  if (option_count(cmd, "--shard") > 0) r.shard = o.shard;
  if (option_count(cmd, "--positions") > 0) r.positions = o.positions;
  const AdequacyRunSummary run = run_adequacy_request(r);
  if (run.shard) {
    fmt::print(
        "adequacy: shard {}/{} measured {} of the table's {} cells; wrote {} and shard.json "
        "in {:.1f} s (glintlab merge joins the shards)\n",
        run.shard->first, run.shard->second, run.shard_cells, run.table_cells,
        (fs::path(r.out) / experiments::kAdequacyCellsFile).string(), run.seconds);
    return;
  }
  if (run.calibrate) {
    print_calibration(run);
    return;
  }
  const auto& s = run.table;
  const double seconds = run.seconds;
  fmt::print("adequacy: TAU {:g}, z {:.3f} (Sidak over the table's {} decisions)\n", run.threshold,
             s.z, s.decisions);
  if (s.cells > 0)
    print_counting_family("binomial family", "chooser (core/glints/adequacy.h)", s.cells, s.chosen,
                          s.chooser_matches, s.chooser_refuted, s.undecided, s.exact_ns,
                          s.chosen_ns, s.cheapest_ns, s.cheapest_measured);
  if (s.kemppinen.cells > 0) {
    const auto& k = s.kemppinen;
    print_leveled_family(
        "Kemppinen family", kKemppinenLevelNames, k.cells, k.chosen,
        fmt::format("chooser (core/glints/adequacy.h): same level as measured in {} cells, "
                    "refuted in {}",
                    k.chooser_matches, k.chooser_refuted),
        k.undecided, "k16_exact", k.most_complete_ns, k.chosen_ns, k.cheapest_ns);
  }
  if (s.area.cells > 0) {
    const auto& a = s.area;
    print_counting_family("area family (kneiphof_klein_area, square lights)",
                          "chooser (core/glints/area_chooser.h)", a.cells, a.chosen,
                          a.chooser_matches, a.chooser_refuted, a.undecided, a.exact_ns,
                          a.chosen_ns, a.cheapest_ns, a.cheapest_measured);
  }
  if (s.chermain.cells > 0) {
    const auto& c = s.chermain;
    print_leveled_family(
        "Chermain family", verify::adequacy::kChermainLevelNames, c.cells, c.chosen,
        fmt::format("chooser (core/glints/chermain_chooser.h): same level as measured in {} "
                    "cells, refuted in {}; construction alone (the level equal to dict16_ggaa bit "
                    "for bit): {} and {}",
                    c.chooser_matches, c.chooser_refuted, c.construction_matches,
                    c.construction_refuted),
        c.undecided, "dict16_ggaa", c.most_complete_ns, c.chosen_ns, c.cheapest_ns);
  }
  if (!run.costs_source.empty()) {
    // Each family's benchmark sums, in the order of the lines above.
    const auto line = [&](std::size_t cells, std::string_view family,
                          const experiments::BenchSums& b,
                          std::span<const std::string_view> levels) {
      if (cells > 0)
        fmt::print("{}\n", experiments::bench_sums_line(family, b, levels, run.costs_source,
                                                         run.costs_isa));
    };
    line(s.cells, "binomial family", s.bench, kBinomialLevelNames);
    line(s.kemppinen.cells, "Kemppinen family", s.kemppinen.bench, kKemppinenLevelNames);
    line(s.area.cells, "area family", s.area.bench, kBinomialLevelNames);
    line(s.chermain.cells, "Chermain family", s.chermain.bench,
         verify::adequacy::kChermainLevelNames);
  } else {
    fmt::print("no benchmark costs (--bench-from DIR, DIR/glints.json from "
               "glintlab_bench_glints --benchmark_filter=^adequacy/): levels priced by the GPU "
               "order and the in-process timing only\n");
  }
  fmt::print("wrote {}, {} and {} maps in {:.1f} s\n", s.csv.string(), s.json.string(),
             s.maps.size(), seconds);
}

constexpr const char* kFooter =
    R"(Four families are measured. The binomial glint family (deliot_belcour, kneiphof_klein) has four levels, cheapest first:
smooth (the smooth GGX value), realtime, small_count and exact counting (the `binomial` parameter).
Per cell of a grid (footprint size N_P = 1 .. 1e8 expected facets, roughness, light half-angle
0 (delta) .. 10 deg, incidence, half-vector angle on and off the specular peak) each level is
evaluated at the same surface positions (quick: 8000, full: 32000); a level is adequate when
|mean/mean_exact - 1| and |CV - CV_exact| both have upper confidence bounds below TAU (default
0.02: luminance differences under about 1-2 % are not seen). The bounds' level splits the
suite's family-wise rate over every decision; a cell whose exact level is lit at fewer than 100
positions is undecided and keeps exact. `chosen` takes the levels in the order above (the GPU-lane
cost order); `cheapest_measured` is the adequate level timed fastest in this run (scalar double,
in-process). --bench-from DIR prices the levels of every family by Google Benchmark JSON instead:
DIR/glints.json's adequacy/<model>/level=<level>/<isa> rows of glintlab_bench_glints at the ISA
glintlab runs (GLINTLAB_ISA, else the widest), adding `cheapest_by_benchmark` and per family the
time saved against its most complete level everywhere (a file without a row of a selected model's
level is refused, naming the row). Writes DIR/adequacy.csv and adequacy.json (the
table, with each level's measured ns per evaluation: the only numbers that vary run to run) and
per model x light x incidence an EXR and a labelled PNG map of the cheapest adequate level, with
the predicted boundary CV = sqrt((1 - p)/(N_P p)) = TAU drawn over it (drawn by matplotlib,
reports/figure_charts.py, from its MAP.chart.json and the maps' cells in adequacy-levels.csv).
The Kemppinen family (kemppinen_ggx, kemppinen_beckmann) has nine levels, cheapest first: smooth
(the base NDF in place of the glinty one), then Algorithm 1 with k = 1, 4, 9, 16 neighbours, each
with the rational erf before the exact one in the compensation; the most complete is k16_exact.
Its grid: 1 .. 1e6 expected points per footprint, roughness, incidence (the footprint stretched by
1/cos theta_i) and half-vector angle; the same decision, against k16_exact, with z split over the
decisions of both families. Its rows share adequacy.csv (column `family`; its own level columns,
nan in the other family's rows) and adequacy.json (with each row's predicted and
measured boundary per level), with one map per model and incidence and the predicted smooth
boundary drawn over it.
The area family (kneiphof_klein_area: binomial counting under a rectangular light, p from the LTC
polygon integral) has the binomial levels, its smooth level L_o/L_i. Its grid is the binomial one
with the cone light replaced by a square facing the shading point at distance 1 along omega_o,
its side chosen so that its solid angle is a cone's of half-angle 0.26, 1, 10 deg (full adds 3);
the same decision against its exact level. Its rows share adequacy.csv (family `area`, the binomial
level columns; light_half_angle_deg the cone-equivalent half-angle), with one map per light and
incidence.
The Chermain family (chermain: the procedural patch-SDF of Chermain et al. 2020 with 2021's GGAA)
has nine levels, cheapest first: smooth (the Gaussian slope density of covariance Sigma, the
model's smooth / LEAN fallback), then the model with a dictionary of its first 4, 8, 12, 16 levels
(the smooth fallback past them), each with GGAA off (textureLod) before on (textureGrad, Eq. 21);
the most complete is dict16_ggaa. Its grid: 1 .. 1e10 expected microfacets per footprint,
roughness, incidence, half-vector angle and the GGAA derivative |d h_perp/dx| per pixel (column
ggaa_dh); the same decision against dict16_ggaa. Its `chooser` is the construction's: the cheapest
level equal to dict16_ggaa bit for bit (every weighted LOD's dictionary level below L). One map per
dh and incidence.
--calibrate measures the decision instead: on synthetic cells whose cheaper level differs from
exact by exactly TAU (1 + delta) (in the mean, in the CV, or the smooth level at the boundary),
delta = -0.5, -0.25, -0.1 (truly adequate: the power), 0 (the boundary), 0.05, 0.1, 0.25 (just
beyond it), --runs cells each (default 2000) with the budget's positions, how often the same rule
declares it adequate, at nominal levels 0.05, 0.01, 1e-3, 1e-4 and the table's own, with
Clopper-Pearson intervals (also pooled over the cases); and the family-wise rate: --tables whole
tables (default 20) of the grid's number of decisions, every one at TAU (1 + delta) for delta = 0,
0.05, 0.1, 0.25, decided at the table's z. Writes DIR/adequacy-calibration.csv and
adequacy-calibration.json.)";

}  // namespace

AdequacyRunSummary run_adequacy_request(const AdequacyRequest& o) {
  const bool quick = quick_budget(o.budget);
  std::vector<std::string> names(verify::adequacy::kBinomialFamilyModels.begin(),
                                 verify::adequacy::kBinomialFamilyModels.end());
  names.insert(names.end(), verify::adequacy::kKemppinenFamilyModels.begin(),
               verify::adequacy::kKemppinenFamilyModels.end());
  names.insert(names.end(), verify::adequacy::kAreaFamilyModels.begin(),
               verify::adequacy::kAreaFamilyModels.end());
  names.insert(names.end(), verify::adequacy::kChermainFamilyModels.begin(),
               verify::adequacy::kChermainFamilyModels.end());
  experiments::AdequacyOptions a;
  a.models = select_by_globs(
      o.models, "--models", names,
      fmt::format("models of the binomial, Kemppinen, area and Chermain families: {}",
                  fmt::join(names, ", ")));
  a.threshold = number_option(o.threshold, "--threshold", 0, 1, true, false);
  a.budget = quick ? verify::Budget::kQuick : verify::Budget::kFull;
  const std::uint64_t runs = integer_option(o.runs.value_or("2000"), "--runs", 1, 1000000);
  if (!o.calibrate && o.runs)
    throw InputError("--runs: only with --calibrate (synthetic cells per case and delta)");
  const std::uint64_t tables = integer_option(o.tables.value_or("20"), "--tables", 0, 100000);
  if (!o.calibrate && o.tables)
    throw InputError("--tables: only with --calibrate (whole tables per family-wise delta)");
  if (o.positions)
    experiments::set_positions_per_cell(
        a, int(integer_option(*o.positions, "--positions", kMinPositions, kMaxPositions)));
  const int threads = resolve_threads(o.threads);
  if (o.calibrate && o.bench_from)
    throw InputError("--bench-from: only without --calibrate (it prices the table's levels)");
  if (o.calibrate && o.shard)
    throw InputError("--shard: only without --calibrate (it splits the table's cells)");
  const std::optional<Shard> shard =
      o.shard ? std::optional<Shard>(parse_shard(*o.shard, "--shard")) : std::nullopt;
  if (o.bench_from) {
    std::error_code ec;
    if (!std::filesystem::is_directory(*o.bench_from, ec))
      throw InputError(fmt::format("--bench-from: '{}' is not a folder (valid: a folder holding "
                                   "{} of glintlab_bench_glints)",
                                   *o.bench_from, experiments::kLevelCostsFile));
    try {
      a.costs = experiments::read_level_costs(*o.bench_from, *o.bench_from,
                                              simd::isa_name(simd::default_isa()),
                                              experiments::priced_models(a.models));
    } catch (const std::invalid_argument& e) {
      throw InputError(e.what());
    }
  }
  check_output_dir(o.out, "--out");
  register_staging_parent(o.out);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  AdequacyRunSummary run;
  run.calibrate = o.calibrate;
  run.threshold = a.threshold;
  std::mutex m;
  const auto t0 = std::chrono::steady_clock::now();
  if (shard) {
    const experiments::AdequacyPart part =
        experiments::adequacy_shard_part(a, std::size_t(shard->k), std::size_t(shard->n));
    ShardManifest manifest;
    manifest.command = "adequacy";
    manifest.version = glintlab_version_text();
    manifest.budget = quick ? "quick" : "full";
    manifest.selection = experiments::adequacy_cell_ids(a);
    manifest.selection_digest =
        selection_digest(experiments::adequacy_run_text(a), manifest.selection);
    manifest.covered = experiments::adequacy_part_ids(part);
    manifest.shard = *shard;
    manifest.threads = threads;
    manifest.machine =
        fmt::format("{} hardware thread(s), {} used", std::thread::hardware_concurrency(), threads);
    Progress bar(fmt::format("adequacy shard {}/{}", shard->k, shard->n),
                 long(manifest.covered.size()));
    a.progress = [&] {
      const std::lock_guard<std::mutex> lock(m);
      bar.step("cells");
    };
    const experiments::AdequacyCells cells = experiments::measure_adequacy_part(a, part);
    fs::create_directories(o.out);
    experiments::write_adequacy_part(fs::path(o.out) / experiments::kAdequacyCellsFile, a, part,
                                     cells);
    io::write_file_atomic(fs::path(o.out) / "shard.json", to_json(manifest));
    run.shard = std::pair{shard->k, shard->n};
    run.shard_cells = manifest.covered.size();
    run.table_cells = manifest.selection.size();
  } else if (o.calibrate) {
    experiments::AdequacyCalibrationOptions c;
    c.models = a.models;
    c.threshold = a.threshold;
    c.budget = a.budget;
    c.runs = std::size_t(runs);
    c.tables = std::size_t(tables);
    if (o.positions) c.positions = a.binomial_axes->samples;
    Progress bar("adequacy calibration",
                 long(verify::adequacy::calibration_cells(
                     experiments::decision_calibration_options(c))));
    c.progress = [&] {
      const std::lock_guard<std::mutex> lock(m);
      bar.step("cells");
    };
    run.calibration = experiments::run_adequacy_calibration(o.out, c);
  } else {
    const long total =
        long(verify::adequacy::make_grid(experiments::binomial_models(a.models),
                                         verify::adequacy::grid_axes(a.budget))
                 .size() +
             verify::adequacy::make_kemppinen_grid(experiments::kemppinen_models(a.models),
                                                   verify::adequacy::kemppinen_grid_axes(a.budget))
                 .size() +
             verify::adequacy::make_grid(experiments::area_models(a.models),
                                         verify::adequacy::area_grid_axes(a.budget))
                 .size() +
             verify::adequacy::make_chermain_grid(experiments::chermain_models(a.models),
                                                  verify::adequacy::chermain_grid_axes(a.budget))
                 .size());
    Progress bar("adequacy", total);
    a.progress = [&] {
      const std::lock_guard<std::mutex> lock(m);
      bar.step("cells");
    };
    run.table = experiments::run_adequacy(o.out, a);
    draw_figure_charts(o.out);  // the maps, drawn by matplotlib from their chart specs
    if (a.costs) {
      run.costs_source = a.costs->source;
      run.costs_isa = a.costs->isa;
    }
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

void merge_adequacy_shards(const std::vector<std::string>& dirs,
                           const std::vector<ShardManifest>& manifests, const std::string& out) {
  std::vector<experiments::AdequacyPartFile> parts;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    const fs::path file = fs::path(dirs[i]) / experiments::kAdequacyCellsFile;
    try {
      parts.push_back(experiments::read_adequacy_part(file));
    } catch (const std::invalid_argument& e) {
      throw InputError(fmt::format("merge: {}", e.what()));
    }
    if (experiments::adequacy_part_ids(parts.back().part) != manifests[i].covered)
      throw InputError(
          fmt::format("merge: {} does not hold the cells its shard.json lists", file.string()));
    if (selection_digest(experiments::adequacy_run_text(parts.back().options),
                         manifests[i].selection) != manifests[i].selection_digest)
      throw InputError(fmt::format(
          "merge: {} was measured with other settings than its shard.json names", file.string()));
  }
  // Every shard has the run's digest (cli/merge.cpp), so the first one's settings are the run's.
  const experiments::AdequacyOptions& o = parts.front().options;
  experiments::AdequacyCells cells;
  try {
    cells = experiments::join_adequacy_parts(o, parts);
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("merge: {}", e.what()));
  }
  register_staging_parent(out);
  const experiments::AdequacySummary s = experiments::write_adequacy(out, o, cells);
  draw_figure_charts(out);  // the maps, drawn by matplotlib from their chart specs
  fmt::print("adequacy: {} cells from {} shards; wrote {}, {} and {} maps\n",
             cells.binomial.size() + cells.kemppinen.size() + cells.area.size() +
                 cells.chermain.size(),
             dirs.size(), s.csv.string(),
             s.json.string(), s.maps.size());
}

void add_adequacy_command(CLI::App& app) {
  auto o = std::make_shared<AdequacyCliOptions>();
  CLI::App* cmd =
      add_command(app, "adequacy",
                  "Where a cheaper glint model level is indistinguishable from the most complete");
  add_text_option(cmd, "--out", o->out, "output folder", "DIR");
  add_budget_option(cmd, o->budget,
                    "quick = 9 footprint sizes x 12 settings (seconds), full = finer");
  add_text_option(cmd, "--models", o->models,
                  "comma-separated globs over the models (deliot_belcour, kneiphof_klein, "
                  "kemppinen_ggx, kemppinen_beckmann, kneiphof_klein_area, chermain)",
                  "LIST");
  add_text_option(cmd, "--threshold", o->threshold,
                  "TAU, the largest relative difference no one sees: a number in (0, 1]", "NUMBER");
  add_threads_option(cmd, o->threads);
  add_bool_flag(cmd, "--calibrate", o->calibrate,
                "measure the decision rule's false-adequate rate on synthetic cells of known truth");
  add_text_option(cmd, "--runs", o->runs,
                  "with --calibrate: synthetic cells per case and delta, an integer in [1, 1000000]",
                  "INT");
  add_text_option(cmd, "--tables", o->tables,
                  "with --calibrate: whole tables per family-wise delta, an integer in [0, 100000]",
                  "INT");
  add_text_option(cmd, "--bench-from", o->bench_from,
                  "a folder holding glints.json of glintlab_bench_glints (its adequacy/ rows): "
                  "each level's cost per evaluation on this machine",
                  "DIR");
  add_text_option(cmd, "--shard", o->shard,
                  "K/N: measure only the K-th of N parts of the table's cells (each family's cells "
                  "dealt round-robin) into DIR/adequacy-cells.json and shard.json; glintlab merge "
                  "joins the N folders into the files of one run",
                  "K/N");
  add_text_option(cmd, "--positions", o->positions,
                  fmt::format("surface positions per cell, an integer in [{}, {}]; default: the "
                              "budget's (quick 8000, full 32000)",
                              kMinPositions, kMaxPositions),
                  "INT");
  set_footer(cmd, kFooter);
  set_callback(cmd, [cmd, o] { run(cmd, *o); });
}

}  // namespace glintlab::cli

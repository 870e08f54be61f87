// Kemppinen et al. 2025 timing figures: kemppinen2025-table3 (Table 3 analogue: time per pixel on
// a 90° and a 25° plane, low and high roughness, 3 lights, Beckmann and GGX; the scene of
// experiments/bench/kemppinen2025_table3_scene.h) and kemppinen2025-speed-accuracy (error of the
// constant-time D★^f of Eq. 11 against the brute-force Eq. 5 and against the smooth D, per k and
// erf of Eq. 10, against ns per evaluation; and the cost against footprint size, the constant-time
// claim). Both read the Google Benchmark JSON kemppinen.json of
// experiments/bench/kemppinen2025_bench.cpp from the --bench-from folder; rows it lacks (all of
// them without one) are measured in process (the CPU time of one thread over a small query set)
// and marked so in their time_source column.
#include "experiments/figures/kemppinen2025_table3.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <ctime>
#include <optional>
#include <string>
#include <vector>

#include "core/glints/kemppinen.h"
#include "core/glints/kemppinen_reference.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/ndf/ndf_kind.h"
#include "experiments/bench/kemppinen2025_speed_accuracy.h"
#include "experiments/bench/kemppinen2025_table3_scene.h"
#include "experiments/figures/bench_json.h"
#include "experiments/figures/chart_spec.h"

namespace glintlab::experiments {
namespace {

namespace sa = glintlab::kemppinen_sa;
namespace kt3 = glintlab::kemppinen_table3;

constexpr std::string_view kTable3Id = "kemppinen2025-table3";
constexpr std::string_view kSpeedId = "kemppinen2025-speed-accuracy";
constexpr std::string_view kJsonFile = "kemppinen.json";
constexpr std::string_view kTool = "glintlab_bench_kemppinen";
constexpr std::string_view kFromJson = "google_benchmark_json";
constexpr std::string_view kInProcess = "in_process_thread_cputime";

// The bench JSON's rows, or nothing (no folder given, or no file in it). A malformed file is a
// figure error.
std::optional<std::vector<BenchRow>> bench_rows(const BenchSource& src) {
  if (src.path.empty()) return std::nullopt;
  try {
    return read_bench_json(src.path);
  } catch (const std::exception& e) {
    throw FigureError(e.what());
  }
}

// This thread's CPU time in ms (CLOCK_THREAD_CPUTIME_ID): unlike the wall clock it does not count
// the time other processes of a loaded machine take, like Google Benchmark's items_per_second.
double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

// CPU ns per call of f over `calls` calls, repeated until at least `min_ms` of CPU time, after
// one untimed pass (first-touch and cache warm-up).
template <class F>
double time_ns(F&& f, long calls, double min_ms) {
  volatile double sink = 0;
  for (long i = 0; i < calls; ++i) sink = sink + f(i);
  long done = 0;
  const double t0 = thread_cpu_ms();
  double elapsed_ms = 0;
  do {
    double acc = 0;
    for (long i = 0; i < calls; ++i) acc += f(done + i);
    sink = sink + acc;
    done += calls;
    elapsed_ms = thread_cpu_ms() - t0;
  } while (elapsed_ms < min_ms);
  return elapsed_ms * 1e6 / double(done);
}

// Where the times came from: the JSON's rows, rows measured here (all of them without a JSON,
// which says so in one sentence).
std::string time_source_note(const BenchSource& src, bool have_json, bool any_json,
                             bool any_in_process, double min_ms) {
  std::string s;
  if (!have_json) s += no_bench_data(src, kJsonFile, kTool) + " ";
  if (any_json) s += fmt::format("Times marked `{}` are from `{}`. ", kFromJson, src.shown_as);
  if (any_in_process)
    s += fmt::format(
        "Times marked `{}` were measured in this run (CPU time of one thread, {} ms per row "
        "or more, on whatever machine ran it): indicative only.",
        kInProcess, min_ms);
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s + "\n";
}

// ---- Table 3 -----------------------------------------------------------------------------

// The paper's "Ours" row: ms per full-HD frame on an RTX 3090, [beckmann, ggx] per column
// (90° low, 90° high, 25° low, 25° high), and the other methods' rows for context.
struct PaperRow {
  std::string_view method;
  std::array<std::array<double, 2>, 4> ms;  // NAN = "NA"
};
constexpr PaperRow kPaper[] = {
    {"Kemppinen et al. (ours)", {{{3.26, 1.70}, {3.27, 3.33}, {3.31, 1.59}, {3.36, 3.07}}}},
    {"Zirr & Kaplanyan*", {{{1.42, NAN}, {1.48, NAN}, {2.72, NAN}, {2.80, NAN}}}},
    {"Deliot & Belcour", {{{2.07, 1.99}, {2.06, 2.06}, {2.09, 2.00}, {2.06, 2.07}}}},
    {"Chermain et al.", {{{3.70, NAN}, {3.44, NAN}, {18.02, NAN}, {19.44, NAN}}}},
};
int paper_column(const kt3::Cell& c) { return (c.plane_deg == 90 ? 0 : 2) + (c.high ? 1 : 0); }

struct Table3Time {
  double ns = NAN;
  std::string_view source;
};

void run_table3(const FigureContext& ctx) {
  const BenchSource src = bench_source(ctx, kJsonFile);
  const auto json = bench_rows(src);
  const double min_ms = ctx.quick ? 15 : 300;
  const long pixels = ctx.quick ? 400 : 20000;
  std::vector<kt3::Cell> cells = kt3::cells();
  std::vector<Table3Time> t(cells.size());
  bool any_json = false, any_in_process = false;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (ctx.progress) ctx.progress("time per pixel", long(i), long(cells.size()));
    const BenchRow* r = json ? find_bench_row(*json, kt3::cell_name(cells[i])) : nullptr;
    if (r) {
      t[i] = {r->ns_per_item(), kFromJson};
      any_json = true;
      continue;
    }
    kt3::with_cell(cells[i], [&](const auto& shade) {
      t[i] = {
          time_ns([&](long n) { return shade(kt3::pixel_of(std::uint64_t(n))); }, pixels, min_ms),
          kInProcess};
    });
    any_in_process = true;
  }
  const auto smooth_of = [&](std::size_t i) {
    for (std::size_t j = 0; j < cells.size(); ++j)
      if (cells[j].smooth && cells[j].ggx == cells[i].ggx &&
          cells[j].plane_deg == cells[i].plane_deg && cells[j].high == cells[i].high)
        return t[j].ns;
    return std::nan("");
  };
  const double frame = double(kt3::kPixels);
  constexpr std::string_view kHeader[] = {"ndf",
                                          "plane_deg",
                                          "roughness",
                                          "alpha",
                                          "ns_per_pixel",
                                          "smooth_ns_per_pixel",
                                          "ratio_to_smooth",
                                          "ms_per_frame_1core",
                                          "paper_rtx3090_ms_per_frame",
                                          "paper_ns_per_pixel",
                                          "time_source"};
  io::write_csv_atomic(ctx.dir / "table3.csv", kHeader, [&](io::CsvWriter& w) {
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const kt3::Cell& c = cells[i];
      if (c.smooth) continue;
      const double paper = kPaper[0].ms[std::size_t(paper_column(c))][c.ggx ? 1 : 0];
      w.cell(c.ggx ? "ggx" : "beckmann").cell_int(c.plane_deg).cell(c.high ? "high" : "low");
      w.cell(c.high ? kt3::kHighAlpha : kt3::kLowAlpha).cell(t[i].ns).cell(smooth_of(i));
      w.cell(t[i].ns / smooth_of(i)).cell(t[i].ns * frame * 1e-6).cell(paper);
      w.cell(paper * 1e6 / frame).cell(t[i].source).end_row();
    }
  });
  // summary.md: the paper's layout (Beckmann/GGX per cell), ours in ms per frame on one core.
  const auto ours = [&](bool smooth, int col) {
    std::string s;
    for (bool ggx : {false, true})
      for (std::size_t i = 0; i < cells.size(); ++i)
        if (cells[i].smooth == smooth && cells[i].ggx == ggx && paper_column(cells[i]) == col)
          s += fmt::format("{}{:.0f}", ggx ? "/" : "", t[i].ns * frame * 1e-6);
    return s;
  };
  std::string md = fmt::format(
      "# {}\n\nKemppinen et al. 2025 Table 3 analogue. Paper: ms per full-HD (1920x1080) frame on "
      "an RTX 3090 (GPU, averaged over 1000 frames), 3 lights, Beckmann/GGX. Ours: **CPU scalar "
      "double, one core, no SIMD**, ns per pixel (footprint by ray differentials + the BRDF of "
      "kemppinen_beckmann/kemppinen_ggx toward 3 point lights; k = 4, fast rational erf, "
      "roulette) times 1920x1080 = ms per frame on one core. Compare ratios between cells, not "
      "values. Low roughness alpha = {}, high alpha = {}, plane, camera and lights: see "
      "experiments/bench/kemppinen2025_table3_scene.h (the paper does not give them).\n\n"
      "| method | 90° low | 90° high | 25° low | 25° high |\n|---|---|---|---|---|\n",
      kTable3Id, kt3::kLowAlpha, kt3::kHighAlpha);
  for (const PaperRow& p : kPaper) {
    md += fmt::format("| paper: {} (GPU ms) ", p.method);
    for (const auto& c : p.ms)
      md += fmt::format("| {}/{} ", std::isnan(c[0]) ? "NA" : fmt::format("{:.2f}", c[0]),
                        std::isnan(c[1]) ? "NA" : fmt::format("{:.2f}", c[1]));
    md += "|\n";
  }
  md += "| glintlab kemppinen (CPU 1-core ms) ";
  for (int col = 0; col < 4; ++col) md += fmt::format("| {} ", ours(false, col));
  md += "|\n| glintlab smooth NDF, same pixels (CPU 1-core ms) ";
  for (int col = 0; col < 4; ++col) md += fmt::format("| {} ", ours(true, col));
  md += "|\n\n";
  md +=
      "The paper's GGX cells at low roughness are about half its others, which it attributes to "
      "\"early exits for points outside the hemisphere\" in sparse cases. glintlab's kernel is "
      "branch-free (every query visits 2k² cell pairs, see kemppinen.constant-time), so our "
      "cells differ only by the cost of the footprint and of the exp/erf calls.\n\n";
  md += time_source_note(src, bool(json), any_json, any_in_process, min_ms);
  io::write_file_atomic(ctx.dir / "summary.md", md);
}

// ---- Speed vs accuracy -------------------------------------------------------------------

struct SaRow {
  bool ggx;
  sa::Reference ref;
  std::string setting;  // "k=4,erf=fast", or "method=bruteforce" for the reference itself
  int k;                // 0 for the reference
  std::string erf, blend;
  double ns;
  sa::Errors err;
  std::string_view source;
  bool front = false;
};

// Errors and time of one setting measured here (the JSON lacks the row).
void measure_in_process(SaRow& row, const sa::Setting* s, bool quick, double min_ms) {
  const int n = row.ref == sa::Reference::kBruteForce
                    ? (quick ? sa::kQuickQueries : sa::kBruteForceQueries)
                    : sa::kSmoothQueries;
  const std::vector<sa::Query> q = sa::queries(row.ggx, row.ref, n);
  std::vector<double> scale;
  const kemppinen2025::Blend blend = s ? s->blend : kemppinen2025::Blend::kRoulette;
  const std::vector<double> ref = sa::reference_all(row.ggx, row.ref, blend, q, &scale);
  const kemppinen2025::Params<double> p = sa::params(
      s ? *s : sa::Setting{1, kemppinen2025::Erf::kExact, kemppinen2025::Blend::kRoulette}, 1);
  with_ndf(ndf_kind(row.ggx), sa::kAlpha, sa::kAlpha, [&](const auto& ndf) {
    const auto at = [&](long i) -> const sa::Query& { return q[std::size_t(i) % q.size()]; };
    if (s) {
      row.err = sa::errors(sa::eval_all(row.ggx, *s, q), ref, scale);
      row.ns = time_ns([&](long i) { return kemppinen2025::eval(p, ndf, at(i).fp, at(i).h).d.x; },
                       long(q.size()), min_ms);
    } else {
      row.err = {0, 0, 0, int(q.size())};
      row.ns = time_ns(
          [&](long i) { return kemppinen2025::reference_filtered(p, ndf, at(i).fp, at(i).h).x; },
          std::min<long>(long(q.size()), quick ? 4 : 64), min_ms);
    }
    return 0;
  });
  row.source = kInProcess;
}

struct CostRow {
  std::string method;  // "constant_time" or "bruteforce"
  int k;               // 0 for the brute force
  int cells;
  double ns, points;
  std::string_view source;
};

void run_speed_accuracy(const FigureContext& ctx) {
  const BenchSource src = bench_source(ctx, kJsonFile);
  const auto json = bench_rows(src);
  const double min_ms = ctx.quick ? 8 : 200;
  bool any_json = false, any_in_process = false;
  std::vector<SaRow> rows;
  for (bool ggx : {true, false}) {
    for (sa::Reference ref : {sa::Reference::kBruteForce, sa::Reference::kSmooth}) {
      std::vector<sa::Setting> settings = sa::settings(ref);
      const std::size_t n = settings.size() + (ref == sa::Reference::kBruteForce ? 1 : 0);
      for (std::size_t i = 0; i < n; ++i) {
        const sa::Setting* s = i < settings.size() ? &settings[i] : nullptr;
        SaRow row{
            ggx,
            ref,
            s ? sa::setting_name(*s) : "method=bruteforce",
            s ? s->side * s->side : 0,
            s ? (s->erf == kemppinen2025::Erf::kExact ? "exact" : "fast") : "none",
            s ? (s->blend == kemppinen2025::Blend::kRoulette ? "roulette" : "linear") : "roulette",
            NAN,
            {},
            {}};
        if (ctx.progress) ctx.progress("speed vs accuracy", long(rows.size()), 50);
        const std::string name = "method/" + sa::method_id(ggx, ref) + "/" + row.setting;
        const BenchRow* b = json ? find_bench_row(*json, name) : nullptr;
        if (b && b->counters.count("err_max") && b->counters.count("err_n")) {
          row.ns = b->ns_per_item();
          row.err = {b->counters.at("err_max"), b->counters.at("err_rms"),
                     b->counters.at("err_p99"), int(b->counters.at("err_n"))};
          row.source = kFromJson;
          any_json = true;
        } else {
          measure_in_process(row, s, ctx.quick, min_ms);
          any_in_process = true;
        }
        rows.push_back(row);
      }
    }
  }
  // Pareto front (ns against RMS error) per method and blending: the reference (error 0) is on
  // its method's front by definition.
  for (std::size_t a = 0; a < rows.size(); ++a) {
    bool dominated = false;
    for (std::size_t b = 0; b < rows.size() && !dominated; ++b) {
      if (rows[b].ggx != rows[a].ggx || rows[b].ref != rows[a].ref) continue;
      if (rows[a].k != 0 && rows[b].k != 0 && rows[b].blend != rows[a].blend) continue;
      dominated = rows[b].ns <= rows[a].ns && rows[b].err.rms <= rows[a].err.rms &&
                  (rows[b].ns < rows[a].ns || rows[b].err.rms < rows[a].err.rms);
    }
    rows[a].front = !dominated;
  }
  constexpr std::string_view kHeader[] = {
      "method",          "setting",   "k",          "erf",     "blend",
      "ns_per_eval",     "err_max",   "err_rms",    "err_p99", "err_n",
      "on_pareto_front", "reference", "time_source"};
  io::write_csv_atomic(ctx.dir / "speed_accuracy.csv", kHeader, [&](io::CsvWriter& w) {
    for (const SaRow& r : rows) {
      std::string setting = r.setting;  // the CSV has no quoting: ',' → ';'
      std::replace(setting.begin(), setting.end(), ',', ';');
      w.cell(sa::method_id(r.ggx, r.ref)).cell(setting).cell_int(r.k).cell(r.erf).cell(r.blend);
      w.cell(r.ns).cell(r.err.max).cell(r.err.rms).cell(r.err.p99).cell_int(r.err.n);
      w.cell_int(r.front ? 1 : 0)
          .cell(r.ref == sa::Reference::kBruteForce ? "eq5_bruteforce" : "smooth_D")
          .cell(r.source)
          .end_row();
    }
  });
  // The chart of speed_accuracy.csv (drawn by reports/figure_charts.py): one panel per NDF;
  // series: vs brute force (roulette), vs brute force (linear), vs smooth D; points labelled
  // k + e/f (exact/fast erf), each series' Pareto front ringed and joined.
  ChartSpec chart{
      .title = fmt::format("{}: RMS error vs time per evaluation (log-log)", kSpeedId),
      .csv = "speed_accuracy.csv"};
  for (bool ggx : {true, false}) {
    ChartPanel panel{
        .title = fmt::format("{}: label k, e/f = exact/fast erf", sa::ndf_name(ggx)),
        .x = {.column = "ns_per_eval", .label = "time per evaluation [ns] (one core)", .log = true},
        .y = {.label = "RMS error |D*f - reference| / D(omega_h) [1]", .log = true}};
    const struct {
      sa::Reference ref;
      std::string_view blend, name;
      std::array<double, 3> color;
    } kSeries[] = {{sa::Reference::kBruteForce, "roulette", "vs Eq. 5 (roulette)", {0.1, 0.3, 0.9}},
                   {sa::Reference::kBruteForce, "linear", "vs Eq. 5 (linear)", {0.1, 0.7, 0.3}},
                   {sa::Reference::kSmooth, "roulette", "vs smooth D (far)", {0.85, 0.2, 0.1}}};
    for (const auto& ser : kSeries)
      panel.series.push_back(
          {.label = std::string(ser.name),
           .where = {{"method", sa::method_id(ggx, ser.ref)}, {"blend", std::string(ser.blend)}},
           .y = "err_rms",
           .color = ser.color,
           .line = "none",
           .point_label = "{k}{erf:.1}",
           .mark = "on_pareto_front",
           .mark_label = "Pareto front (time against RMS error)"});
    chart.panels.push_back(std::move(panel));
  }
  write_chart_spec(ctx.dir / "speed_accuracy.png", chart);

  // Cost against footprint: Algorithm 1 for each k (exact erf) and the brute-force Eq. 5.
  std::vector<CostRow> cost;
  for (int side = 1; side <= kemppinen2025::kMaxSide; ++side)
    for (int cells : sa::kCostCells)
      cost.push_back({"constant_time", side * side, cells, NAN, 2.0 * std::pow(side, 4), {}});
  for (int cells = 1; cells <= sa::kBruteForceMaxCells; cells *= 2)
    cost.push_back({"bruteforce", 0, cells, NAN, NAN, {}});
  const GGX<double> ggx{sa::kAlpha, sa::kAlpha};
  for (CostRow& c : cost) {
    const std::string name =
        c.k ? fmt::format("BM_KemppinenEval/side:{}/footprint_cells:{}/erf:0",
                          int(std::lround(std::sqrt(c.k))), c.cells)
            : fmt::format("BM_KemppinenBruteForce/footprint_cells:{}", c.cells);
    const BenchRow* b = json ? find_bench_row(*json, name) : nullptr;
    if (b) {
      c.ns = b->ns_per_item();
      if (b->counters.count("points_visited")) c.points = b->counters.at("points_visited");
      c.source = kFromJson;
      any_json = true;
      continue;
    }
    const int side = c.k ? int(std::lround(std::sqrt(c.k))) : 1;
    const kemppinen2025::Params<double> p =
        sa::params({side, kemppinen2025::Erf::kExact, kemppinen2025::Blend::kRoulette}, 1);
    if (c.k) {
      c.ns = time_ns(
          [&](long i) {
            const sa::Query q = sa::cost_query(std::uint64_t(i), c.cells);
            return kemppinen2025::eval(p, ggx, q.fp, q.h).d.x;
          },
          64, min_ms);
    } else {
      if (ctx.quick && c.cells > 16) continue;  // its cost grows with the area: full run only
      const int n = ctx.quick ? 2 : 16;
      std::int64_t visited = 0;
      for (int i = 0; i < 64; ++i) {
        const sa::Query q = sa::cost_query(std::uint64_t(i), c.cells);
        kemppinen2025::reference_filtered(p, ggx, q.fp, q.h, false, &visited);
      }
      c.points = double(visited) / 64.0;
      c.ns = time_ns(
          [&](long i) {
            const sa::Query q = sa::cost_query(std::uint64_t(i), c.cells);
            return kemppinen2025::reference_filtered(p, ggx, q.fp, q.h).x;
          },
          n, min_ms);
    }
    c.source = kInProcess;
    any_in_process = true;
  }
  constexpr std::string_view kCostHeader[] = {
      "method", "k", "footprint_cells", "ns_per_eval", "points_visited", "time_source"};
  io::write_csv_atomic(ctx.dir / "cost_vs_footprint.csv", kCostHeader, [&](io::CsvWriter& w) {
    for (const CostRow& c : cost) {
      w.cell(c.method).cell_int(c.k).cell_int(c.cells).cell(c.ns).cell(c.points);
      w.cell(c.source.empty() ? std::string_view("not_measured") : c.source).end_row();
    }
  });
  // The chart of cost_vs_footprint.csv (drawn by reports/figure_charts.py): time and points
  // visited against the footprint, Algorithm 1 per k against the brute force.
  constexpr std::array<double, 3> kColors[] = {
      {0.1, 0.3, 0.9}, {0.1, 0.7, 0.3}, {0.9, 0.6, 0.1}, {0.6, 0.2, 0.8}, {0.85, 0.1, 0.1}};
  ChartSpec cost_chart{
      .title = fmt::format("{}: cost against the footprint (constant time vs Eq. 5)", kSpeedId),
      .csv = "cost_vs_footprint.csv"};
  for (bool points : {false, true}) {
    ChartPanel panel{
        .title = points ? "points visited vs footprint" : "time per evaluation vs footprint",
        .x = {.column = "footprint_cells", .label = "footprint [level-0 cells]", .log = true},
        .y = {.label = points ? "points visited [1]" : "time per evaluation [ns] (one core)",
              .log = true}};
    for (int s = 0; s <= kemppinen2025::kMaxSide; ++s) {
      const int k = s == kemppinen2025::kMaxSide ? 0 : (s + 1) * (s + 1);
      panel.series.push_back(
          {.label = k ? fmt::format("constant time k={}", k) : "brute force Eq. 5",
           .where = {{"method", k ? "constant_time" : "bruteforce"}, {"k", fmt::format("{}", k)}},
           .y = points ? "points_visited" : "ns_per_eval",
           .color = kColors[s]});
    }
    cost_chart.panels.push_back(std::move(panel));
  }
  write_chart_spec(ctx.dir / "cost_vs_footprint.png", cost_chart);

  std::string md = fmt::format(
      "# {}\n\nSpeed vs accuracy of the constant-time D★^f (Eq. 11, Algorithm 1) for k in "
      "{{1, 4, 9, 16}} x erf in {{exact, fast (A&S 7.1.28 rational)}} (and linear vs roulette "
      "blending against Eq. 5), CPU scalar double, one core. GGX and Beckmann, alpha = {}, "
      "microroughness = {}, density 1e4, filter 0.5; omega_h ~ D cos. References:\n"
      "- {}: {}\n- {}: {}\n\n`speed_accuracy.csv` (Pareto front: ns_per_eval against err_rms per "
      "method and blending), `speed_accuracy.png` (RMS error vs ns, log-log, front dashed and "
      "ringed), `cost_vs_footprint.csv/.png` (ns and points visited against the footprint: "
      "constant for Algorithm 1, growing with the area for the brute force).\n\n"
      "| method | setting | ns/eval | err_rms | err_p99 | err_max | n | front |\n"
      "|---|---|---|---|---|---|---|---|\n",
      kSpeedId, sa::kAlpha, sa::kMicroroughness, "dstar_f_vs_bruteforce",
      sa::reference_label(sa::Reference::kBruteForce), "dstar_f_vs_smooth",
      sa::reference_label(sa::Reference::kSmooth));
  for (const SaRow& r : rows)
    md += fmt::format("| {} | {} | {:.4g} | {:.3g} | {:.3g} | {:.3g} | {} | {} |\n",
                      sa::method_id(r.ggx, r.ref), r.setting, r.ns, r.err.rms, r.err.p99, r.err.max,
                      r.err.n, r.front ? "yes" : "");
  md += "\n" + time_source_note(src, bool(json), any_json, any_in_process, min_ms);
  io::write_file_atomic(ctx.dir / "summary.md", md);
}

}  // namespace

FigureEntry kemppinen2025_table3_entry() {
  return {kTable3Id, "Kemppinen et al. 2025", "Table 3",
          "time per pixel, 90/25 degree plane, low/high roughness, 3 lights, Beckmann/GGX, CPU "
          "scalar (benchmark JSON; measured in process where it lacks rows)",
          run_table3};
}

FigureEntry kemppinen2025_speed_accuracy_entry() {
  return {kSpeedId, "Kemppinen et al. 2025", "Sec. 3.3.4 (speed vs accuracy)",
          "error of D*f (Eq. 11) vs brute-force Eq. 5 and vs smooth D per k and erf against ns "
          "per evaluation; cost vs footprint (benchmark JSON; in process where it lacks rows)",
          run_speed_accuracy};
}

}  // namespace glintlab::experiments

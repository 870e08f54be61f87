// Google Benchmark suite of the binomial-counting glints: the cost of one Binomial(n, p) draw per
// sampler over an (n, p) grid (pairs with experiments/data/binomial_error.csv, speed against
// accuracy), and Kneiphof & Klein 2024 Table 1's analogue: time per shading evaluation for smooth
// GGX, Deliot & Belcour, Kneiphof & Klein and Kneiphof & Klein + NDF LTC, under no light, a
// directional light and a rectangular area light (area: L_o by the BRDF LTC lobe of core/ltc for
// every method, p by the same lobe × D_PR for Kneiphof & Klein and by the NDF lobe × D_PR for
// "+ NDF LTC", core/glints/kneiphof_ltc.h). Scalar double on one core; run scripts/bench.sh or
// this binary with --benchmark_out=FILE --benchmark_out_format=json. Method rows
// (METHOD_BENCHMARKS.md): method/binomial.count_vs_exact.<regime>/sampler=..., the distribution
// error of each sampler (core/glints/binomial_distribution.h, no sampling) beside its time per
// draw. Adequacy rows (adequacy/<model>/level=<level>/<isa>): each level of every adequacy family
// (binomial, Kemppinen, area, Chermain) on every ISA this CPU has, over the family's quick
// adequacy grid's cells, the cost per evaluation `glintlab adequacy --bench-from` and the
// adequacy-scene figure read (how each family's levels run: the section's comment).
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/glints/binomial.h"
#include "core/glints/binomial_distribution.h"
#include "core/glints/deliot_belcour.h"
#include "core/glints/kneiphof.h"
#include "core/glints/kneiphof_ltc.h"
#include "core/ltc/ltc_table.h"
#include "core/model_registry.h"
#include "core/models/smooth_ggx.h"
#include "core/simd/model_batch.h"
#include "experiments/bench/chermain_level_isa.h"
#include "experiments/bench/method_bench.h"
#include "verify/adequacy/area_adequacy.h"
#include "verify/adequacy/binomial_adequacy.h"
#include "verify/adequacy/chermain_adequacy.h"
#include "verify/adequacy/kemppinen_adequacy.h"

namespace glintlab {
namespace {

// --- Binomial draws: args {log2 n, −log10 p ×10} -------------------------------------------------
double grid_p(std::int64_t code) { return std::pow(10.0, -double(code) / 10.0); }

void binomial_exact_bm(benchmark::State& s) {
  const std::uint64_t n = std::uint64_t(1) << s.range(0);
  const double p = grid_p(s.range(1));
  std::uint64_t i = 0;
  for (auto _ : s) benchmark::DoNotOptimize(binomial_exact(n, p, 1, i++));
  s.SetItemsProcessed(std::int64_t(i));
}
void binomial_realtime_bm(benchmark::State& s) {
  const double n = std::ldexp(1.0, int(s.range(0))), p = grid_p(s.range(1));
  std::uint64_t i = 0;
  for (auto _ : s) {
    benchmark::DoNotOptimize(binomial_realtime(n, p, counter_uniform<double>(1, i, 0),
                                               counter_uniform<double>(1, i, 1)));
    ++i;
  }
  s.SetItemsProcessed(std::int64_t(i));
}
void binomial_small_count_bm(benchmark::State& s) {
  const double n = std::ldexp(1.0, int(s.range(0))), p = grid_p(s.range(1));
  std::uint64_t i = 0;
  for (auto _ : s) {
    benchmark::DoNotOptimize(binomial_small_count(n, p, counter_uniform<double>(1, i, 0)));
    ++i;
  }
  s.SetItemsProcessed(std::int64_t(i));
}
void binomial_args(benchmark::internal::Benchmark* b) {
  for (int e : {4, 10, 20})
    for (int pc : {40, 20, 5}) b->Args({e, pc});  // p = 1e-4, 1e-2, 0.316
}
BENCHMARK(binomial_exact_bm)->Name("binomial/exact")->Apply(binomial_args);
BENCHMARK(binomial_realtime_bm)->Name("binomial/realtime")->Apply(binomial_args);
BENCHMARK(binomial_small_count_bm)->Name("binomial/small_count")->Apply(binomial_args);

// --- Method rows: binomial.count_vs_exact.<regime>, one per (n, p) regime ---------------------
// The error is the Kolmogorov–Smirnov distance sup|F − A| between the sampler's exact
// distribution and Binomial(n, p) (binomial_distribution.h: computed, not sampled), so err_max =
// err_rms = err_p99 = that distance and err_n = 1; `tv` (discrete samplers) and `mean_rel_error`
// are extra counters. The exact sampler is the reference (error 0 by definition).
struct BinomialRegime {
  int log2_n;
  double p;
  const char* id;  // n and p in the method id (no '/' or spaces)
};
constexpr BinomialRegime kRegimes[] = {
    {4, 1e-1, "n16_p1e-1"},        // np = 1.6: few trials, a handful of facets
    {10, 1e-3, "n1024_p1e-3"},     // np ≈ 1: the gate dominates
    {10, 3e-1, "n1024_p3e-1"},     // np ≈ 307: the Gaussian regime
    {20, 1e-6, "n1048576_p1e-6"},  // np ≈ 1 with many trials
    {20, 1e-4, "n1048576_p1e-4"},  // np ≈ 105
};

void register_binomial_methods() {
  for (const BinomialRegime& r : kRegimes) {
    const std::string method = std::string("binomial.count_vs_exact.") + r.id;
    const std::uint64_t n = std::uint64_t(1) << r.log2_n;
    const double nd = double(n), p = r.p;
    const std::uint64_t seed = bench::method_seed(method);
    const std::string label = "exact Binomial(n, p) pmf; KS distance of the sampler's exact CDF";
    bench::register_method(
        method, "sampler=exact", label + " (reference)",
        [n, p, seed](benchmark::State& s) {
          std::uint64_t i = 0;
          for (auto _ : s) benchmark::DoNotOptimize(binomial_exact(n, p, seed, i++));
          s.SetItemsProcessed(std::int64_t(i));
        },
        [] {
          return bench::ErrorStats{0, 0, 0, 1, {{"tv", 0.0}, {"mean_rel_error", 0.0}}};
        });
    bench::register_method(
        method, "sampler=realtime", label,
        [nd, p, seed](benchmark::State& s) {
          std::uint64_t i = 0;
          for (auto _ : s) {
            benchmark::DoNotOptimize(binomial_realtime(nd, p, counter_uniform<double>(seed, i, 0),
                                                       counter_uniform<double>(seed, i, 1)));
            ++i;
          }
          s.SetItemsProcessed(std::int64_t(i));
        },
        [n, p] {
          const BinomialError e = realtime_error(n, p);
          return bench::ErrorStats{e.ks, e.ks, e.ks, 1, {{"mean_rel_error", e.mean_rel}}};
        });
    bench::register_method(
        method, "sampler=small_count", label,
        [nd, p, seed](benchmark::State& s) {
          std::uint64_t i = 0;
          for (auto _ : s) {
            benchmark::DoNotOptimize(
                binomial_small_count(nd, p, counter_uniform<double>(seed, i, 0)));
            ++i;
          }
          s.SetItemsProcessed(std::int64_t(i));
        },
        [n, p] {
          const BinomialError e = small_count_error(n, p);
          return bench::ErrorStats{
              e.ks, e.ks, e.ks, 1, {{"tv", e.tv}, {"mean_rel_error", e.mean_rel}}};
        });
  }
}

// --- Table 1 analogue
// ------------------------------------------------------------------------------
constexpr int kQueries = 1024;
enum Light { kNone = 0, kDirectional = 1, kArea = 2 };
enum Method { kSmooth = 0, kDeliotBelcour = 1, kKneiphofKlein = 2, kNdfLtc = 3 };

std::vector<ModelQuery<double>> queries() {
  std::vector<ModelQuery<double>> q(kQueries);
  for (int i = 0; i < kQueries; ++i) {
    const double t = 0.6 * counter_uniform<double>(3, std::uint64_t(i), 0);
    const double ph = 6.283185307179586 * counter_uniform<double>(3, std::uint64_t(i), 1);
    auto& x = q[std::size_t(i)];
    x.wi = {std::sin(t) * std::cos(ph), std::sin(t) * std::sin(ph), std::cos(t)};
    x.wo = {-0.3 * std::cos(ph), -0.3 * std::sin(ph), std::sqrt(1 - 0.09)};
    x.footprint.uv = {counter_uniform<double>(3, std::uint64_t(i), 2), 0.5};
    x.footprint.duv_dx = {1e-3, 0};
    x.footprint.duv_dy = {0, 1e-3};
    x.light = {1.0, 1.0};
  }
  return q;
}

// A unit square at height 2 above the shading point, emitting downward (counter-clockwise seen
// from below).
const std::array<Vec3<double>, 4>& area_vertices() {
  static const std::array<Vec3<double>, 4> v = {
      Vec3<double>{-0.5, 0.5, 2}, {0.5, 0.5, 2}, {0.5, -0.5, 2}, {-0.5, -0.5, 2}};
  return v;
}

void table1(benchmark::State& s) {
  const auto method = Method(s.range(0));
  const auto light = Light(s.range(1));
  const auto qs = queries();
  const auto smooth = SmoothGGX::params<double>(std::vector<double>{0.25, 0.25, 1, 0});
  const auto db = DeliotBelcour::params<double>(std::vector<double>{0.25, 0.25, 8, 0.05, 1, 0});
  const auto kk = KneiphofKlein::params<double>(std::vector<double>{0.25, 0.25, 8, 0.26, 1, 0});
  const GGX<double> ggx{0.25, 0.25};
  const double dh = total_area(ggx);
  const LtcTableView& table = ltc_ggx_table_view();
  std::size_t i = 0;
  for (auto _ : s) {
    const ModelQuery<double>& q = qs[i++ % qs.size()];
    double v = 0;
    if (light == kNone) {
      v = q.wi.z;  // the query itself: the baseline without shading
    } else if (light == kDirectional) {
      if (method == kSmooth) v = SmoothGGX::eval(smooth, q).value;
      if (method == kDeliotBelcour) v = DeliotBelcour::eval(db, q).value;
      // + NDF LTC changes nothing for a directional light (Eq. 20's cap, no lobe).
      if (method == kKneiphofKlein || method == kNdfLtc) v = KneiphofKlein::eval(kk, q).value;
    } else {
      // Heitz et al. 2016 LTC for L_o; Kneiphof & Klein reuse the BRDF lobe × D_PR for p (Sec. 4),
      // "+ NDF LTC" integrates the separately fitted NDF lobe as well.
      const kneiphof2024::LtcAreaTerms<double> t = kneiphof2024::area_light_terms_ltc(
          table, 0.25, q.wi, area_vertices().data(), 4,
          method == kNdfLtc ? kneiphof2024::AreaP::kNdfLobe : kneiphof2024::AreaP::kBrdfLobe);
      if (method == kSmooth) {
        v = t.lo_over_li;
      } else {
        const double n = footprint_facet_count(q.footprint, 8.0);
        // D&B (as Kneiphof & Klein's Table 1 runs it): glints for the light's mean direction.
        const double p =
            method == kDeliotBelcour
                ? std::min(1.0, 0.05 * ggx.D(half_vector(q.wi, Vec3<double>{0, 0, 1})) /
                                    ggx.D(Vec3<double>{0, 0, 1}))
                : std::min(1.0, t.d_omega_h / dh);
        const double b =
            draw_binomial(BinomialSampler::kRealTime, n, p, footprint_hash_key(q.footprint, 5));
        v = t.lo_over_li * binomial_radiance_factor(b, n, p);
      }
    }
    benchmark::DoNotOptimize(v);
  }
  s.SetItemsProcessed(std::int64_t(i));
}
BENCHMARK(table1)
    ->Name("table1")
    ->ArgNames({"method", "light"})
    ->ArgsProduct({{kSmooth, kDeliotBelcour, kKneiphofKlein, kNdfLtc},
                   {kNone, kDirectional, kArea}});

// --- Adequacy levels: adequacy/<model>/level=<level>/<isa> ---------------------------------------
// A level's cost per evaluation where the adequacy table decides it: every cell of the family's
// quick grid (verify/adequacy: binomial and area, footprints of 1 to 10^8 facets on and near the
// specular peak; Kemppinen, 1 to 10^6 expected points; Chermain, 1 to 10^10 expected microfacets,
// both GGAA derivatives) at kAdequacyPositions surface positions of the family's own spread, one
// batch per cell (a cell's parameters are uniform, as a shader's material is over a pixel batch),
// in double. Each row is one shape (adequacy_bm): a list of cells, each evaluating its positions.
// - Through the registry's batch API on the row's ISA: the binomial family's levels (the smooth
//   level smooth_ggx's value at the cell's roughness, the family's smooth limit), the area family's
//   counting levels (its model has no SIMD batches: the double thunk row by row), the Kemppinen
//   family's counting levels (k and erf are the model's parameters) and its smooth level (the base
//   NDF's smooth model, smooth_ggx or smooth_beckmann, at the cell's roughness).
// - On the row's ISA through the model's own eval template: every Chermain counting level. A
//   dictionary of L < 16 levels is a table the registered model cannot be given (its dictionary is
//   the default one, not a parameter), so the registry's batch API cannot run it; each level runs
//   Chermain::eval on the ISA's double batches (chermain_level_isa.h: one unit per ISA, with
//   core's flags for it, the batch core's batched Chermain uses) with the level's dictionary and
//   GGAA kernel (chermain_level_params, as the table measures it).
// - Scalar double on every ISA (the same code; the rows are per ISA so that every ISA's costs are
//   complete): the area family's smooth level (the LTC call a shader without glints makes) and
//   the Chermain smooth level, the Gaussian slope density it falls back to
//   (chermain_smooth_value, one exp: scalar in the table too).
constexpr int kAdequacyPositions = 64;

// One cell of a row: its kAdequacyPositions values into `out`.
using AdequacyCellRun = std::function<void(double* out)>;

// A row: the cells `prepare` returns (built when the row runs, not when it is registered), each
// evaluated once per iteration.
void adequacy_bm(benchmark::State& s, const std::function<std::vector<AdequacyCellRun>()>& prepare) {
  const std::vector<AdequacyCellRun> cells = prepare();
  std::vector<double> out(kAdequacyPositions);
  std::int64_t evals = 0;
  for (auto _ : s) {
    for (const AdequacyCellRun& cell : cells) {
      cell(out.data());
      benchmark::DoNotOptimize(out.data());
      benchmark::ClobberMemory();
    }
    evals += std::int64_t(cells.size()) * kAdequacyPositions;
  }
  s.SetItemsProcessed(evals);
}

// A cell through the registry's batch API: `m` with `params` at `queries` on `isa`.
AdequacyCellRun batch_cell(const ModelEntry& m, std::vector<double> params,
                           const std::vector<ModelQuery<double>>& queries, simd::Isa isa) {
  // Every column of the layout (the corner columns stay 0: no adequacy model reads them).
  auto cols = std::make_shared<std::vector<std::vector<double>>>(
      simd::kQueryColumnsWithCorners, std::vector<double>(queries.size()));
  for (std::size_t i = 0; i < queries.size(); ++i)
    for_each_query_column(queries[i], [&](std::size_t k, const QueryColumn&, const double& v) {
      (*cols)[k][i] = v;
    });
  std::vector<simd::Column<double>> spans;
  for (const auto& c : *cols) spans.push_back({c.data(), 1});
  auto scratch = std::make_shared<std::vector<std::vector<double>>>(
      1 + m.intermediates.size(), std::vector<double>(queries.size()));
  std::vector<double*> outs(2 + m.intermediates.size());
  for (std::size_t k = 1; k < outs.size(); ++k) outs[k] = (*scratch)[k - 1].data();
  return [&m, params = std::move(params), cols, spans, scratch, outs, isa,
          n = queries.size()](double* out) mutable {
    outs[0] = out;
    simd::eval_batch(m, params, spans, outs, n, isa);
  };
}

// A cell evaluated in scalar double: value(i) for each position.
template <class Value>
AdequacyCellRun scalar_cell(Value value) {
  return [value = std::move(value)](double* out) {
    for (int i = 0; i < kAdequacyPositions; ++i) out[i] = value(i);
  };
}

// The smooth model of a family's smooth limit at isotropic roughness `alpha`.
std::vector<double> smooth_params(const ModelEntry& smooth, double alpha) {
  return resolve_params(smooth, {{"alpha_x", fmt::format("{}", alpha)},
                                 {"alpha_y", fmt::format("{}", alpha)}});
}

// The binomial family's and the area family's rows (the binomial levels).
std::vector<AdequacyCellRun> binomial_level_cells(const std::string& model, BinomialLevel level,
                                                  simd::Isa isa) {
  namespace adq = verify::adequacy;
  const bool area = model == adq::kAreaFamilyModels[0];
  const ModelEntry& m = find_model(model);
  const ModelEntry& smooth = find_model("smooth_ggx");
  std::vector<AdequacyCellRun> cells;
  for (const adq::Cell& c : adq::make_grid({model}, area ? adq::area_grid_axes(verify::Budget::kQuick)
                                                          : adq::grid_axes(verify::Budget::kQuick))) {
    std::vector<ModelQuery<double>> queries;
    for (int i = 0; i < kAdequacyPositions; ++i) {
      const Vec2<double> uv = adq::surface_position(i);
      queries.push_back(adq::cell_query(c, uv.x, uv.y));
    }
    if (area && level == BinomialLevel::kSmooth) {
      // L_o/L_i by the BRDF LTC lobe over the cell's square light (kneiphof2024::
      // area_light_terms_ltc, one table lookup and one polygon integral: what a shader without
      // glints pays, and what verify/adequacy/area_adequacy.cpp measures as the smooth level).
      using M = KneiphofKleinArea;
      const M::Params<double> p =
          M::params<double>(adq::area_level_param_values(c, BinomialLevel::kSmooth, 1));
      cells.push_back(scalar_cell([p, queries](int i) {
        const ModelQuery<double>& q = queries[std::size_t(i)];
        const auto rect =
            kneiphof2024::facing_rectangle(q.wo, p.distance, p.width, p.height, p.rotation, p.tilt);
        return kneiphof2024::area_light_terms_ltc(*p.table, p.alpha, q.wi, rect.data(), 4,
                                                  p.area_p)
            .lo_over_li;
      }));
    } else if (area) {
      cells.push_back(batch_cell(m, adq::area_level_param_values(c, level, 1), queries, isa));
    } else if (level == BinomialLevel::kSmooth) {
      cells.push_back(batch_cell(smooth, smooth_params(smooth, c.alpha), queries, isa));
    } else {
      cells.push_back(batch_cell(m, adq::level_param_values(c, level, 1), queries, isa));
    }
  }
  return cells;
}

// The Kemppinen family's rows.
std::vector<AdequacyCellRun> kemppinen_level_cells(const std::string& model, KemppinenLevel level,
                                                   simd::Isa isa) {
  namespace adq = verify::adequacy;
  const ModelEntry& m = find_model(model);
  const ModelEntry& smooth =
      find_model(model == "kemppinen_beckmann" ? "smooth_beckmann" : "smooth_ggx");
  std::vector<AdequacyCellRun> cells;
  for (const adq::KemppinenCell& c : adq::make_kemppinen_grid(
           {model}, adq::kemppinen_grid_axes(verify::Budget::kQuick))) {
    std::vector<ModelQuery<double>> queries;
    for (int i = 0; i < kAdequacyPositions; ++i)
      queries.push_back(adq::kemppinen_cell_query(c, adq::kemppinen_surface_position(c, i)));
    cells.push_back(level == KemppinenLevel::kSmooth
                        ? batch_cell(smooth, smooth_params(smooth, c.alpha), queries, isa)
                        : batch_cell(m, adq::kemppinen_level_param_values(c, level, 1), queries,
                                     isa));
  }
  return cells;
}

// Chermain::eval on `isa`'s double batches (chermain_level_isa.h).
bench::ChermainLevelEval chermain_level_eval(simd::Isa isa) {
  switch (isa) {
    case simd::Isa::kSse42: return bench::chermain_level_isa_sse42();
    case simd::Isa::kAvx2: return bench::chermain_level_isa_avx2();
    case simd::Isa::kAvx512: return bench::chermain_level_isa_avx512();
    default: return bench::chermain_level_isa_scalar();
  }
}

// The Chermain family's rows (see above).
std::vector<AdequacyCellRun> chermain_level_cells(ChermainLevel level, simd::Isa isa) {
  namespace adq = verify::adequacy;
  std::vector<AdequacyCellRun> cells;
  for (const adq::ChermainCell& c :
       adq::make_chermain_grid({"chermain"}, adq::chermain_grid_axes(verify::Budget::kQuick))) {
    std::vector<ModelQuery<double>> queries;
    for (int i = 0; i < kAdequacyPositions; ++i)
      queries.push_back(adq::chermain_cell_query(c, adq::chermain_surface_position(c, i)));
    // The smooth level reads Σ and G2 only: any counting level's parameters give them.
    const Chermain::Params<double> p = adq::chermain_level_params(
        c, level == ChermainLevel::kSmooth ? kChermainMostComplete : level, 1);
    if (level == ChermainLevel::kSmooth)
      cells.push_back(scalar_cell([p, queries](int i) {
        return adq::chermain_smooth_value(p, queries[std::size_t(i)]);
      }));
    else
      cells.push_back([p, queries, eval = chermain_level_eval(isa)](double* out) {
        eval(p, queries.data(), out, queries.size());
      });
  }
  return cells;
}

void register_adequacy_levels() {
  namespace adq = verify::adequacy;
  // One row per model × level × ISA this CPU has.
  const auto add = [](std::string_view model, std::string_view level,
                      std::function<std::vector<AdequacyCellRun>(simd::Isa)> cells) {
    for (simd::Isa isa : simd::kAllIsas) {
      if (!simd::isa_supported(isa)) continue;
      const std::string name =
          fmt::format("adequacy/{}/level={}/{}", model, level, simd::isa_name(isa));
      benchmark::RegisterBenchmark(name.c_str(), adequacy_bm,
                                   std::function<std::vector<AdequacyCellRun>()>(
                                       [cells, isa] { return cells(isa); }));
    }
  };
  // The families in the table's order: binomial, Kemppinen, area, Chermain.
  for (std::string_view model : adq::kBinomialFamilyModels)
    for (int l = 0; l < kBinomialLevels; ++l)
      add(model, kBinomialLevelNames[std::size_t(l)], [m = std::string(model), l](simd::Isa isa) {
        return binomial_level_cells(m, BinomialLevel(l), isa);
      });
  for (std::string_view model : adq::kKemppinenFamilyModels)
    for (int l = 0; l < kKemppinenLevels; ++l)
      add(model, kKemppinenLevelNames[std::size_t(l)], [m = std::string(model), l](simd::Isa isa) {
        return kemppinen_level_cells(m, KemppinenLevel(l), isa);
      });
  for (std::string_view model : adq::kAreaFamilyModels)
    for (int l = 0; l < kBinomialLevels; ++l)
      add(model, kBinomialLevelNames[std::size_t(l)], [m = std::string(model), l](simd::Isa isa) {
        return binomial_level_cells(m, BinomialLevel(l), isa);
      });
  for (int l = 0; l < kChermainLevels; ++l)
    add(adq::kChermainFamilyModels[0], kChermainLevelNames[std::size_t(l)],
        [l](simd::Isa isa) { return chermain_level_cells(ChermainLevel(l), isa); });
}

}  // namespace
}  // namespace glintlab

int main(int argc, char** argv) {
  glintlab::register_binomial_methods();
  glintlab::register_adequacy_levels();
  return glintlab::bench::run_benchmarks(argc, argv);
}

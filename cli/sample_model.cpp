// `glintlab sample --model`: samples of a registered model's own sampler (core/model.h
// ModelSample) for one ωi, in SIMD batches of fixed chunks (core/simd/model_batch.h).
#include "cli/sample_model.h"

#include <fmt/format.h>

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/eval_model.h"
#include "cli/input.h"
#include "cli/model_options.h"
#include "cli/out_csv.h"
#include "core/io/csv.h"
#include "core/math/rng.h"
#include "core/model_layout.h"
#include "core/model_registry.h"
#include "core/simd/model_batch.h"

namespace glintlab::cli {
namespace {

constexpr std::uint64_t kMaxSamples = 1000000000;

}  // namespace

const char* const kModelSampleFooter = R"(
WITH --model NAME (any model of 'glintlab models'; --param name=value sets its parameters, the
sampler among them): --wi, --n, --seed and --out as above; --ndf, --alpha, --sampler and --bound
do not apply. --out has one row per sample i = 0 .. N-1 with the columns
  wo_x, wo_y, wo_z  the sampled direction (toward the light)
  pdf               its density per steradian under the model's sampler
  weight            value / pdf, the Monte Carlo weight of the cosine-weighted BRDF (0 if rejected)
  rejected          1 if the sampler rejected the sample, else 0
with the same uniforms u = (counter_uniform(S, i, 0), counter_uniform(S, i, 1)). The query
columns the model needs besides the directions (the footprint, the light, the corner vectors: see
eval's WITH --model) are required, as eval --model requires them, in --query
'name=value,...' (e.g. --query u=0.5,v=0.5,dudx=1e-3,dvdx=0,dudy=0,dvdy=1e-3), and checked as
eval checks them; a model that needs only the directions takes no --query.)";

void run_model_sample(const ModelSampleArgs& a) {
  const ResolvedModel resolved = resolve_model(a.model, a.params);
  const ModelEntry* model = resolved.model;
  const std::vector<double>& params = resolved.params;
  const BatchOptions opts = resolve_batch_options(a.batch);
  const Vec3<double> wi = parse_unit_direction(a.wi, "--wi");
  const std::uint64_t n = parse_integer(a.n, "--n", 1, kMaxSamples);
  const std::uint64_t seed = parse_integer(a.seed, "--seed", 0, UINT64_MAX);
  QueryRow<double> row = parse_query_option(*model, a.query, a.query_given);
  row[query_column_index("wi_x")] = wi.x;
  row[query_column_index("wi_y")] = wi.y;
  row[query_column_index("wi_z")] = wi.z;
  check_query_row(*model, row, [](std::string_view column) {
    return column.empty() ? std::string("--wi/--query") : "--query " + std::string(column);
  });
  check_output_file(a.out, "--out");
  // About 20 bytes per number written (17 significant digits, sign, exponent, comma), and the
  // samples are held in memory (8 bytes per number) before they are written.
  check_free_space(a.out, n * (simd::kSampleColumns.size() * 20), "--out");

  std::vector<std::vector<double>> out(simd::kSampleColumns.size(), std::vector<double>(n));
  const auto run = [&]<class S>(S) {
    // The query columns, and the corner vectors as the optional trailing columns for the models
    // that read them (as eval --model passes them).
    const bool corners = (model->needs & kNeedsPixelCorners) != 0;
    std::vector<S> q(corners ? row.size() : simd::kQueryColumns.size());
    for (std::size_t j = 0; j < q.size(); ++j) q[j] = S(row[j]);
    std::vector<S> res;
    if constexpr (std::is_same_v<S, float>) res.resize(out.size() * n);
    for_each_chunk(n, opts, [&](std::size_t begin, std::size_t count) {
      std::vector<S> u1(count), u2(count);
      for (std::size_t i = 0; i < count; ++i) {
        u1[i] = S(counter_uniform<double>(seed, begin + i, 0));
        u2[i] = S(counter_uniform<double>(seed, begin + i, 1));
      }
      std::vector<simd::Column<S>> cols;
      for (const S& x : q) cols.push_back({&x, 0});
      std::vector<S*> outs;
      for (std::size_t k = 0; k < out.size(); ++k) {
        if constexpr (std::is_same_v<S, float>) {
          outs.push_back(res.data() + k * n + begin);
        } else {
          outs.push_back(out[k].data() + begin);
        }
      }
      simd::sample_batch(*model, params, cols, {u1.data(), 1}, {u2.data(), 1}, outs, count,
                         opts.isa, opts.math);
    });
    if constexpr (std::is_same_v<S, float>)
      for (std::size_t k = 0; k < out.size(); ++k)
        for (std::size_t i = 0; i < n; ++i) out[k][i] = res[k * n + i];
  };
  if (opts.float_precision) {
    run(0.0f);
  } else {
    run(0.0);
  }

  write_out_csv(a.out, simd::kSampleColumns, [&](io::CsvWriter& w) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k + 1 < out.size(); ++k) w.cell(out[k][i]);
      w.cell_int(out.back()[i] != 0 ? 1 : 0);
      w.end_row();
    }
  });
}

}  // namespace glintlab::cli

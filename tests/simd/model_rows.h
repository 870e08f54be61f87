// The row drivers of the per-model SIMD equivalence tests: eval and sample of a case's rows through
// the batch API (core/simd/model_batch.h) on one ISA, or through the model driver of
// core/simd/instantiate.h on a test's own W (perturbed models), one parameter vector per
// `rows_per_set` rows. Include after core/simd/instantiate.h (the test TU's driver).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/math/rng.h"
#include "core/model_layout.h"
#include "core/model_registry.h"
#include "core/simd/model_batch.h"

namespace glintlab::simd::test {

// What the drivers read of a case: params (one vector per rows_per_set rows), query columns
// (kQueryColumns.size() or kQueryColumnsWithCorners), uniforms u1, u2 and the row count n.
template <class C>
concept RowCase = requires(const C& c) {
  c.params[0][0];
  c.query[0][0];
  c.u1[0];
  c.u2[0];
  std::size_t(c.n);
};

// A case of the per-model equivalence tests: one parameter vector per rows_per_set rows, the query
// columns (kQueryColumns.size()), the sampler's uniforms and the row count (a RowCase).
struct RowsCase {
  std::vector<std::vector<double>> params;
  std::vector<std::vector<double>> query;
  std::vector<double> u1, u2;
  std::size_t n = 0;
};

// ωi then ωo, the order of core/simd/inputs.h's direction domains (kWiX … kWoZ).
inline constexpr std::array<std::size_t, 6> kDirectionColumns = {
    query_column_index("wi_x"), query_column_index("wi_y"), query_column_index("wi_z"),
    query_column_index("wo_x"), query_column_index("wo_y"), query_column_index("wo_z")};

inline double row_uniform(std::uint64_t seed, std::uint64_t i, std::uint64_t dim) {
  return counter_uniform<double>(seed, i, dim);
}
inline double log_uniform(double lo, double hi, double u) {
  return std::exp(std::log(lo) + u * (std::log(hi) - std::log(lo)));
}

// Query row i of a footprint model: uv uniform in [−4, 4]², a footprint Jacobian of size `scale`
// in a random direction u(2) with shear u(3) and stretch u(4) in [0.2, 5], uv from u(5), u(6);
// ωi, ωo from columns 2…7 of the edge-case inputs `in` (core/simd/inputs.h); a unit light.
template <class U>
void fill_footprint_row(std::vector<std::vector<double>>& query, std::size_t i, double scale,
                        const U& u, const std::vector<std::vector<double>>& in) {
  const double a = 6.283185307179586 * u(2), shear = u(3) - 0.5,
               stretch = log_uniform(0.2, 5, u(4));
  query[query_column_index("u")][i] = -4 + 8 * u(5);
  query[query_column_index("v")][i] = -4 + 8 * u(6);
  query[query_column_index("dudx")][i] = scale * stretch * std::cos(a);
  query[query_column_index("dvdx")][i] = scale * stretch * std::sin(a);
  query[query_column_index("dudy")][i] = scale * (-std::sin(a) + shear * std::cos(a)) / stretch;
  query[query_column_index("dvdy")][i] = scale * (std::cos(a) + shear * std::sin(a)) / stretch;
  for (std::size_t j = 0; j < kDirectionColumns.size(); ++j)
    query[kDirectionColumns[j]][i] = in[2 + j][i];
  query[query_column_index("light_cos_half_angle")][i] = 1;
  query[query_column_index("light_intensity")][i] = 1;
}

// Row i of a case's query columns (with or without the corner columns) as a query in S.
template <class S, class C>
ModelQuery<S> row_query(const C& k, std::size_t i) {
  QueryRow<double> row{};
  for (std::size_t j = 0; j < k.query.size(); ++j) row[j] = k.query[j][i];
  return convert_query<S>(from_row(row));
}

// |got − ref| / (|ref| + scale) in machine epsilons of S (0 where both are NaN or equal; ∞ for a
// NaN against a number).
template <class S>
double scaled_eps(S got, S ref, double scale) {
  if (std::isnan(got) || std::isnan(ref))
    return std::isnan(got) && std::isnan(ref) ? 0 : std::numeric_limits<double>::infinity();
  if (got == ref) return 0;
  const double d = std::abs(double(got) - double(ref)) / (std::abs(double(ref)) + scale);
  return d / double(std::numeric_limits<S>::epsilon());
}

// Outputs of eval (2 + intermediates columns) and sample (kSampleColumns) of every row.
template <class S>
struct RowOutputs {
  std::vector<std::vector<S>> eval, sample;
};

// Eval and sample of every row of `k` through the callables (params, query columns, u1, u2,
// outputs, n); the last set may be partial.
template <class S, RowCase C, class Eval, class Sample>
RowOutputs<S> run_rows_with(const ModelEntry& m, const C& k, std::size_t rows_per_set, Eval eval,
                            Sample sample) {
  std::vector<std::vector<S>> q;
  for (const auto& c : k.query) q.emplace_back(c.begin(), c.end());
  const std::vector<S> u1(k.u1.begin(), k.u1.end()), u2(k.u2.begin(), k.u2.end());
  RowOutputs<S> o;
  o.eval.assign(2 + m.intermediates.size(), std::vector<S>(k.n));
  o.sample.assign(kSampleColumns.size(), std::vector<S>(k.n));
  for (std::size_t s = 0; s * rows_per_set < k.n; ++s) {
    const std::size_t b = s * rows_per_set, rows = std::min(rows_per_set, k.n - b);
    std::vector<Column<S>> cols;
    for (const auto& c : q) cols.push_back({c.data() + b, 1});
    std::vector<S*> eo, so;
    for (auto& c : o.eval) eo.push_back(c.data() + b);
    for (auto& c : o.sample) so.push_back(c.data() + b);
    eval(k.params[s], cols, eo, rows);
    sample(k.params[s], cols, Column<S>{u1.data() + b, 1}, Column<S>{u2.data() + b, 1}, so, rows);
  }
  return o;
}

// Through the batch API on `isa`.
template <class S, RowCase C>
RowOutputs<S> run_rows_batch(const ModelEntry& m, const C& k, std::size_t rows_per_set, Isa isa) {
  return run_rows_with<S>(
      m, k, rows_per_set,
      [&](const std::vector<double>& p, const std::vector<Column<S>>& c, const std::vector<S*>& o,
          std::size_t n) { eval_batch(m, p, c, o, n, isa); },
      [&](const std::vector<double>& p, const std::vector<Column<S>>& c, Column<S> u1, Column<S> u2,
          const std::vector<S*>& o, std::size_t n) { sample_batch(m, p, c, u1, u2, o, n, isa); });
}

// Through the model driver of core/simd/instantiate.h on W (any model M, listed or not).
template <class M, class W, class S, RowCase C>
RowOutputs<S> run_rows_driver(const ModelEntry& m, const C& k, std::size_t rows_per_set) {
  return run_rows_with<S>(
      m, k, rows_per_set,
      [](const std::vector<double>& p, const std::vector<Column<S>>& c, const std::vector<S*>& o,
         std::size_t n) { detail::run_model_eval<M, W, S>(p.data(), c.data(), o.data(), n); },
      [](const std::vector<double>& p, const std::vector<Column<S>>& c, Column<S> u1, Column<S> u2,
         const std::vector<S*>& o, std::size_t n) {
        // The driver reads u after all kQueryColumnsWithCorners query columns.
        static constexpr S kZero = 0;
        std::vector<Column<S>> in = c;
        in.resize(kQueryColumnsWithCorners, Column<S>{&kZero, 0});
        in.insert(in.end(), {u1, u2});
        detail::run_model_sample<M, W, S>(p.data(), in.data(), o.data(), n);
      });
}

}  // namespace glintlab::simd::test

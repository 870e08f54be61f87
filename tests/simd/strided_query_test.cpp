// Query columns of stride above 1 in the model batch API (core/simd/model_batch.h): a coordinate of
// a C-ordered (N, 3) direction array (stride 3) or a column of a C-ordered (N, columns) matrix of
// every query column, read where it lies and gathered block by block by model_batch.cpp. Every
// registered model, the scalar ISA and the widest this CPU has (one lane and the most lanes per
// batch: the blocks are the same for every ISA), float and double, eval and sample, uniform parameters
// and per-row parameter columns: each row bit for bit what the same rows give as stride-1 columns,
// over several blocks and a partial one. A control: one changed value of the strided matrix is
// caught by the same comparison.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/math/rng.h"
#include "core/model_layout.h"
#include "core/model_registry.h"
#include "core/simd/inputs.h"
#include "core/simd/kernels.h"
#include "core/simd/model_batch.h"

namespace glintlab::simd::test {
namespace {

// Two full blocks of model_batch.cpp's 256 rows and a partial one (not a multiple of any ISA's
// lanes, so its last batch is partial too).
constexpr std::size_t kRows = 600;

struct Queries {
  std::vector<std::vector<double>> columns;  // kQueryColumnsWithCorners, kRows each
  std::vector<double> u1, u2;
  std::vector<std::vector<double>> params;  // a column per parameter (per-row values)
};

Queries make_queries(const ModelEntry& m, std::uint64_t seed) {
  using D = Domain;
  const std::vector<int> domains = {int(D::kWiX), int(D::kWiY), int(D::kWiZ), int(D::kWoX),
                                    int(D::kWoY), int(D::kWoZ), int(D::kU1),  int(D::kU2)};
  const auto in = make_inputs(domains, kRows, seed);
  Queries q;
  q.columns.assign(kQueryColumnsWithCorners, std::vector<double>(kRows, 0.0));
  for (std::size_t j = 0; j < kQueryColumns.size(); ++j)
    q.columns[j].assign(kRows, kQueryDefaults[j]);
  const std::size_t wi = query_column_index("wi_x"), wo = query_column_index("wo_x");
  for (std::size_t j = 0; j < 3; ++j) {
    q.columns[wi + j] = in[j];
    q.columns[wo + j] = in[3 + j];
  }
  q.u1 = in[6];
  q.u2 = in[7];
  add_scene_columns(m.needs, q.columns, seed + 1);
  // Per-row values of every parameter that is not a choice (the choices one value for all rows),
  // each inside its range.
  for (std::size_t p = 0; p < m.params.size(); ++p) {
    const ParamSpec& spec = m.params[p];
    std::vector<double> column(kRows, spec.default_value);
    if (spec.choices.empty() && spec.name != "seed") {
      for (std::size_t i = 0; i < kRows; ++i) {
        const double hi = spec.integral ? std::min(spec.hi, spec.lo + 31) : spec.hi;
        const double t = 0.02 + 0.96 * counter_uniform<double>(seed + 3, i, p);
        const double v = spec.lo + t * (hi - spec.lo);
        column[i] = spec.integral ? std::floor(v) : v;
      }
    }
    q.params.push_back(std::move(column));
  }
  return q;
}

// The columns in S in one of three layouts: stride-1 columns; wi and wo as C-ordered (N, 3)
// arrays (stride 3), the rest stride 1; every column of a C-ordered (N, columns) matrix.
enum class Layout { kColumns, kDirectionRows, kMatrix };

template <class S>
struct LaidOut {
  std::vector<S> storage;
  std::vector<Column<S>> query;
  std::vector<S> u1, u2;

  LaidOut(const Queries& q, Layout layout)
      : u1(q.u1.begin(), q.u1.end()), u2(q.u2.begin(), q.u2.end()) {
    const std::size_t w = q.columns.size();
    storage.resize(w * kRows);
    query.resize(w);
    const std::size_t wi = query_column_index("wi_x"), wo = query_column_index("wo_x");
    for (std::size_t j = 0; j < w; ++j) {
      std::size_t offset = j * kRows, stride = 1;
      if (layout == Layout::kMatrix) {
        offset = j;
        stride = w;
      } else if (layout == Layout::kDirectionRows &&
                 ((j >= wi && j < wi + 3) || (j >= wo && j < wo + 3))) {
        const std::size_t first = j < wi + 3 ? wi : wo;  // the array's place: its x column's
        offset = first * kRows + (j - first);
        stride = 3;
      }
      for (std::size_t i = 0; i < kRows; ++i) storage[offset + stride * i] = S(q.columns[j][i]);
      query[j] = {storage.data() + offset, stride};
    }
  }
};

template <class S>
bool same_bits(S a, S b) {
  using U = std::conditional_t<sizeof(S) == 4, std::uint32_t, std::uint64_t>;
  return std::bit_cast<U>(a) == std::bit_cast<U>(b);
}

// Eval and sample of every row, uniform parameters (the defaults) and per-row parameter columns:
// every output column, concatenated.
template <class S>
std::vector<std::vector<S>> run(const ModelEntry& m, const Queries& q, const LaidOut<S>& c,
                                Isa isa, Math math) {
  const std::size_t n_eval = 2 + m.intermediates.size(), n_sample = kSampleColumns.size();
  std::vector<std::vector<S>> out(2 * (n_eval + n_sample), std::vector<S>(kRows));
  std::vector<S*> o;
  for (auto& col : out) o.push_back(col.data());
  const std::span<S* const> all(o);
  const std::vector<double> defaults = resolve_params(m, {});
  const Column<S> u1{c.u1.data(), 1}, u2{c.u2.data(), 1};
  eval_batch(m, defaults, c.query, all.subspan(0, n_eval), kRows, isa, math);
  sample_batch(m, defaults, c.query, u1, u2, all.subspan(n_eval, n_sample), kRows, isa, math);
  std::vector<Column<double>> params;
  for (const auto& p : q.params) params.push_back({p.data(), 1});
  const std::size_t second = n_eval + n_sample;
  eval_batch_with_param_columns(m, params, c.query, all.subspan(second, n_eval), kRows, isa, math);
  sample_batch_with_param_columns(m, params, c.query, u1, u2,
                                  all.subspan(second + n_eval, n_sample), kRows, isa, math);
  return out;
}

template <class S>
std::size_t differences(const std::vector<std::vector<S>>& a,
                        const std::vector<std::vector<S>>& b) {
  std::size_t n = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    for (std::size_t i = 0; i < kRows; ++i) n += !same_bits(a[k][i], b[k][i]);
  return n;
}

template <class S>
void check_every_model(Math math) {
  for (const ModelEntry& m : registered_models()) {
    const Queries q = make_queries(m, hash_string(std::string(m.name).c_str()));
    const LaidOut<S> columns(q, Layout::kColumns), rows(q, Layout::kDirectionRows),
        matrix(q, Layout::kMatrix);
    ASSERT_EQ(rows.query[query_column_index("wo_y")].stride, 3u);
    ASSERT_EQ(matrix.query[0].stride, kQueryColumnsWithCorners);
    for (Isa isa : {Isa::kScalar, best_isa()}) {
      const auto ref = run<S>(m, q, columns, isa, math);
      EXPECT_EQ(differences(ref, run<S>(m, q, rows, isa, math)), 0u)
          << m.name << " on " << isa_name(isa) << ", (N, 3) direction arrays";
      EXPECT_EQ(differences(ref, run<S>(m, q, matrix, isa, math)), 0u)
          << m.name << " on " << isa_name(isa) << ", one (N, columns) matrix";
    }
  }
}

TEST(SimdStridedQuery, DoubleEveryModelScalarAndWidestIsaIsTheColumnsBitForBit) {
  check_every_model<double>(Math::kExact);
}
TEST(SimdStridedQuery, FloatEveryModelScalarAndWidestIsaIsTheColumnsBitForBit) {
  check_every_model<float>(Math::kExact);
  check_every_model<float>(Math::kFast);
}

// The comparison above catches a changed row: wo_z of row 300 (in the second block) nudged in the
// strided matrix changes that row's outputs, and only that row's.
TEST(SimdStridedQuery, AChangedStridedValueIsCaught) {
  const ModelEntry& m = find_model("smooth_ggx");
  const Queries q = make_queries(m, 11);
  const LaidOut<double> columns(q, Layout::kColumns);
  LaidOut<double> matrix(q, Layout::kMatrix);
  const std::size_t wo_z = query_column_index("wo_z");
  double& v = matrix.storage[wo_z + kQueryColumnsWithCorners * 300];
  v = std::nextafter(v, 0.0) * (1 - 1e-9);
  const Isa isa = best_isa();
  const auto ref = run<double>(m, q, columns, isa, Math::kExact);
  const auto got = run<double>(m, q, matrix, isa, Math::kExact);
  EXPECT_GT(differences(ref, got), 0u);
  for (std::size_t k = 0; k < ref.size(); ++k)
    for (std::size_t i = 0; i < kRows; ++i)
      if (i != 300) {
        EXPECT_TRUE(same_bits(ref[k][i], got[k][i])) << "row " << i;
      }
}

// The uniform columns of sample stay stride 0 or 1.
TEST(SimdStridedQuery, UniformColumnsOfStrideAboveOneAreRefused) {
  const ModelEntry& m = find_model("smooth_ggx");
  const Queries q = make_queries(m, 12);
  const LaidOut<double> c(q, Layout::kDirectionRows);
  std::vector<std::vector<double>> out(kSampleColumns.size(), std::vector<double>(kRows));
  std::vector<double*> o;
  for (auto& col : out) o.push_back(col.data());
  EXPECT_THROW(sample_batch(m, resolve_params(m, {}), c.query, Column<double>{c.u1.data(), 2},
                            Column<double>{c.u2.data(), 1}, o, kRows / 2, Isa::kScalar),
               std::invalid_argument);
}

}  // namespace
}  // namespace glintlab::simd::test

// eval_batch_with_param_columns / sample_batch_with_param_columns (core/simd/model_batch.h): a
// parameter column per parameter, rows with different values sharing a batch. Every registered
// model (batched, and the scalar loop of the others), every ISA this CPU has, float (exact and
// fast) and double: each row bit for bit what eval_batch / sample_batch give for that row alone
// with its own values; and the groups of lanes that core/simd/lane_params.h forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/math/rng.h"
#include "core/model_list.h"
#include "core/model_registry.h"
#include "core/simd/inputs.h"
#include "core/simd/kernels.h"
#include "core/simd/model_batch.h"
#include "core/simd/wide.h"
// (after wide.h: the merge's lane access of Wide)
#include "core/simd/lane_params.h"

namespace glintlab::simd::test {
namespace {

constexpr std::size_t kRows = 37;  // two batches of the widest (16 floats) and a partial one

// How a case's parameter columns vary over the rows.
enum class Variation {
  kEveryRow,            // every parameter its own value on every row (choices too)
  kContinuousEveryRow,  // the non-choice parameters per row, the choices one value for all rows
  kBlocks,              // every parameter per row, in runs of 1 to 9 equal rows
  kOneColumn,           // one parameter per row (the first non-choice one), the others stride 0
};

// A value of p drawn from u in [0, 1): a choice's index, an integer, or a number inside the range
// (log-uniform over a wide positive range). An integer other than a seed is a count of samples
// (kneiphof_klein_area's mc_samples), the cost of a row: kept within [lo, lo + 31].
double draw_value(const ParamSpec& p, double u) {
  if (!p.choices.empty())
    return std::min(std::floor(u * double(p.choices.size())), double(p.choices.size() - 1));
  const double hi = p.integral && p.name != "seed" ? std::min(p.hi, p.lo + 31) : p.hi;
  const double t = 0.02 + 0.96 * u;
  double v = p.lo > 0 && hi / p.lo > 100 ? std::exp(std::log(p.lo) + t * std::log(hi / p.lo))
                                         : p.lo + t * (hi - p.lo);
  if (p.integral) v = std::floor(v);
  return v;
}

struct Case {
  std::vector<std::vector<double>> params;  // one column per parameter, kRows rows
  std::vector<bool> per_row;                // whether column k varies (else row 0's value)
  std::vector<std::vector<double>> query;   // kQueryColumnsWithCorners columns
  std::vector<double> u1, u2;
};

Case make_case(const ModelEntry& m, Variation variation, std::uint64_t seed) {
  using D = Domain;
  const std::vector<int> domains = {int(D::kWiX), int(D::kWiY), int(D::kWiZ), int(D::kWoX),
                                    int(D::kWoY), int(D::kWoZ), int(D::kU1),  int(D::kU2)};
  const auto in = make_inputs(domains, kRows, seed);
  Case k;
  k.query.assign(kQueryColumnsWithCorners, std::vector<double>(kRows, 0.0));
  for (std::size_t j = 0; j < kQueryColumns.size(); ++j) k.query[j].assign(kRows, kQueryDefaults[j]);
  const std::size_t directions[6] = {query_column_index("wi_x"), query_column_index("wi_y"),
                                     query_column_index("wi_z"), query_column_index("wo_x"),
                                     query_column_index("wo_y"), query_column_index("wo_z")};
  for (std::size_t j = 0; j < 6; ++j) k.query[directions[j]] = in[j];
  k.u1 = in[6];
  k.u2 = in[7];
  add_scene_columns(m.needs, k.query, seed + 1);

  const std::size_t first_number = static_cast<std::size_t>(
      std::find_if(m.params.begin(), m.params.end(),
                   [](const ParamSpec& p) { return p.choices.empty(); }) -
      m.params.begin());
  for (std::size_t p = 0; p < m.params.size(); ++p) {
    const ParamSpec& spec = m.params[p];
    bool varies = true;
    if (variation == Variation::kContinuousEveryRow) varies = spec.choices.empty();
    if (variation == Variation::kOneColumn) varies = p == first_number;
    std::vector<double> column(kRows);
    std::size_t run_end = 0;
    double value = 0;
    for (std::size_t i = 0; i < kRows; ++i) {
      const auto u = [&](std::uint64_t d) { return counter_uniform<double>(seed + 7, i, 4 * p + d); };
      if (i == 0 || (varies && i >= run_end)) {
        value = draw_value(spec, u(0));
        run_end = i + (variation == Variation::kBlocks ? 1 + std::size_t(9 * u(1)) : 1);
      }
      column[i] = value;
    }
    k.params.push_back(std::move(column));
    k.per_row.push_back(varies);
  }
  return k;
}

template <class S>
bool same_bits(S a, S b) {
  if (std::isnan(a) && std::isnan(b)) return true;
  using U = std::conditional_t<sizeof(S) == 4, std::uint32_t, std::uint64_t>;
  return std::bit_cast<U>(a) == std::bit_cast<U>(b);
}

template <class S>
struct Outputs {
  std::vector<std::vector<S>> eval, sample;
};

template <class S>
struct CaseColumns {
  std::vector<std::vector<S>> query;
  std::vector<S> u1, u2;
  explicit CaseColumns(const Case& k) : u1(k.u1.begin(), k.u1.end()), u2(k.u2.begin(), k.u2.end()) {
    for (const auto& c : k.query) query.emplace_back(c.begin(), c.end());
  }
  // Rows [first, first + ...) as stride-1 columns.
  std::vector<Column<S>> at(std::size_t first) const {
    std::vector<Column<S>> cols;
    for (const auto& c : query) cols.push_back({c.data() + first, 1});
    return cols;
  }
};

// Every row through the parameter columns, in one call.
template <class S>
Outputs<S> run_columns(const ModelEntry& m, const Case& k, Isa isa, Math math) {
  const CaseColumns<S> c(k);
  std::vector<Column<double>> params;
  for (std::size_t p = 0; p < k.params.size(); ++p)
    params.push_back({k.params[p].data(), k.per_row[p] ? std::size_t(1) : std::size_t(0)});
  Outputs<S> o;
  o.eval.assign(2 + m.intermediates.size(), std::vector<S>(kRows));
  o.sample.assign(kSampleColumns.size(), std::vector<S>(kRows));
  std::vector<S*> eo, so;
  for (auto& col : o.eval) eo.push_back(col.data());
  for (auto& col : o.sample) so.push_back(col.data());
  const auto q = c.at(0);
  eval_batch_with_param_columns(m, params, q, eo, kRows, isa, math);
  sample_batch_with_param_columns(m, params, q, Column<S>{c.u1.data(), 1},
                                  Column<S>{c.u2.data(), 1}, so, kRows, isa, math);
  return o;
}

// Row i alone through eval_batch / sample_batch with the values of row `values_row`.
template <class S>
void run_alone(const ModelEntry& m, const Case& k, const CaseColumns<S>& c, std::size_t i,
               std::size_t values_row, Isa isa, Math math, std::vector<S>& eval,
               std::vector<S>& sample) {
  std::vector<double> values;
  for (const auto& column : k.params) values.push_back(column[values_row]);
  eval.assign(2 + m.intermediates.size(), S(0));
  sample.assign(kSampleColumns.size(), S(0));
  std::vector<S*> eo, so;
  for (S& v : eval) eo.push_back(&v);
  for (S& v : sample) so.push_back(&v);
  const auto q = c.at(i);
  eval_batch(m, values, q, eo, 1, isa, math);
  sample_batch(m, values, q, Column<S>{c.u1.data() + i, 1}, Column<S>{c.u2.data() + i, 1}, so, 1,
               isa, math);
}

// The rows of `got` that differ from the rows alone (with each row's own values, or, with
// `shift`, with the next row's values: a control the comparison must catch), as "row: column".
template <class S>
std::vector<std::string> differing_rows(const ModelEntry& m, const Case& k, const Outputs<S>& got,
                                        Isa isa, Math math, bool shift) {
  const CaseColumns<S> c(k);
  std::vector<std::string> bad;
  std::vector<S> eval, sample;
  for (std::size_t i = 0; i < kRows; ++i) {
    run_alone<S>(m, k, c, i, shift ? (i + 1) % kRows : i, isa, math, eval, sample);
    for (std::size_t o = 0; o < eval.size(); ++o)
      if (!same_bits(got.eval[o][i], eval[o]))
        bad.push_back(std::to_string(i) + ": eval output " + std::to_string(o));
    for (std::size_t o = 0; o < sample.size(); ++o)
      if (!same_bits(got.sample[o][i], sample[o]))
        bad.push_back(std::to_string(i) + ": sample " + std::string(kSampleColumns[o]));
  }
  return bad;
}

template <class S>
void check_every_model(Math math) {
  const Variation variations[] = {Variation::kEveryRow, Variation::kContinuousEveryRow,
                                  Variation::kBlocks, Variation::kOneColumn};
  const char* names[] = {"every row", "continuous every row", "blocks", "one column"};
  for (const ModelEntry& m : registered_models()) {
    if (m.params.empty()) continue;
    for (std::size_t v = 0; v < std::size(variations); ++v) {
      const Case k = make_case(m, variations[v], hash_string(std::string(m.name).c_str()) + v);
      for (Isa isa : kAllIsas) {
        if (!isa_supported(isa)) continue;
        const Outputs<S> got = run_columns<S>(m, k, isa, math);
        const std::vector<std::string> bad = differing_rows<S>(m, k, got, isa, math, false);
        EXPECT_TRUE(bad.empty()) << m.name << " on " << isa_name(isa) << " (" << names[v]
                                 << "): " << bad.size() << " differences, first " << bad.front();
      }
    }
  }
}

TEST(SimdParamColumns, FloatEveryModelEveryIsaIsEachRowAlone) { check_every_model<float>(Math::kExact); }
TEST(SimdParamColumns, FastFloatEveryModelEveryIsaIsEachRowAlone) {
  check_every_model<float>(Math::kFast);
}
TEST(SimdParamColumns, DoubleEveryModelEveryIsaIsEachRowAlone) {
  check_every_model<double>(Math::kExact);
}

// The comparison above can fail: rows evaluated with their neighbours' values differ from the
// columns' rows (each model, its widest ISA, double).
TEST(SimdParamColumns, RowsWithTheirNeighboursValuesDiffer) {
  Isa widest = Isa::kScalar;
  for (Isa isa : kAllIsas)
    if (isa_supported(isa)) widest = isa;
  for (const ModelEntry& m : registered_models()) {
    if (m.params.empty()) continue;
    const Case k = make_case(m, Variation::kContinuousEveryRow, hash_string(std::string(m.name).c_str()));
    const Outputs<double> got = run_columns<double>(m, k, widest, Math::kExact);
    EXPECT_FALSE(differing_rows<double>(m, k, got, widest, Math::kExact, true).empty()) << m.name;
  }
}

// All stride 0 is eval_batch itself; a column of stride 2 and a wrong column count are refused.
TEST(SimdParamColumns, BroadcastColumnsAreEvalBatchAndBadColumnsAreRefused) {
  const ModelEntry& m = find_model("smooth_ggx");
  const Case k = make_case(m, Variation::kEveryRow, 5);
  Case uniform = k;
  for (std::size_t p = 0; p < uniform.per_row.size(); ++p) uniform.per_row[p] = false;
  const Outputs<double> got = run_columns<double>(m, uniform, Isa::kScalar, Math::kExact);
  const CaseColumns<double> c(k);
  std::vector<double> values;
  for (const auto& column : k.params) values.push_back(column[0]);
  std::vector<std::vector<double>> ref(2 + m.intermediates.size(), std::vector<double>(kRows));
  std::vector<double*> ro;
  for (auto& col : ref) ro.push_back(col.data());
  eval_batch(m, values, c.at(0), ro, kRows, Isa::kScalar);
  for (std::size_t o = 0; o < ref.size(); ++o)
    for (std::size_t i = 0; i < kRows; ++i) ASSERT_TRUE(same_bits(got.eval[o][i], ref[o][i]));

  std::vector<Column<double>> params;
  for (const auto& column : k.params) params.push_back({column.data(), 1});
  const auto q = c.at(0);
  params[0].stride = 2;
  EXPECT_THROW(eval_batch_with_param_columns(m, params, q, ro, kRows, Isa::kScalar),
               std::invalid_argument);
  params[0].stride = 1;
  params.pop_back();
  EXPECT_THROW(eval_batch_with_param_columns(m, params, q, ro, kRows, Isa::kScalar),
               std::invalid_argument);
}

// The groups of core/simd/lane_params.h on this build's baseline batch (xsimd's default
// architecture): lanes that differ in per-lane parameters share one Params (the batch runs once);
// lanes that differ in a uniform one (a choice, a seed) are split by it.
using BaselineDouble = Wide<xsimd::batch<double>>;
constexpr std::size_t kBaselineLanes = BaselineDouble::kLanes;

template <class M>
std::size_t groups_of(const std::vector<std::vector<double>>& lanes_values) {
  std::vector<std::vector<double>> columns(M::kParams.size(), std::vector<double>(kBaselineLanes));
  for (std::size_t l = 0; l < kBaselineLanes; ++l)
    for (std::size_t p = 0; p < M::kParams.size(); ++p) columns[p][l] = lanes_values[l][p];
  std::vector<Column<double>> params;
  for (const auto& c : columns) params.push_back({c.data(), 1});
  detail::lanes::LaneParams<M, BaselineDouble> lp;
  lp.load(params.data(), 0, kBaselineLanes);
  return lp.groups();
}

template <class M>
std::vector<std::vector<double>> default_lanes() {
  std::vector<double> d;
  for (const ParamSpec& p : M::kParams) d.push_back(p.default_value);
  return std::vector<std::vector<double>>(kBaselineLanes, d);
}

TEST(SimdParamColumns, LanesShareOneParamsUnlessAUniformParameterDiffers) {
  ASSERT_GE(kBaselineLanes, 2u);
  // Every batched model's Params can be taken apart (else every distinct vector is its own group).
  const auto mergeable = []<class M>(M) {
    EXPECT_TRUE((detail::lanes::mergeable<BaselineDouble,
                                          typename M::template Params<BaselineDouble>>()))
        << M::kName;
  };
  []<class... Ms>(auto check, ModelList<Ms...>) { (check(Ms{}), ...); }(mergeable, BatchedModels{});

  auto ggx = default_lanes<SmoothGGX>();
  for (std::size_t l = 0; l < kBaselineLanes; ++l) {
    ggx[l][param_index<SmoothGGX>("alpha_x")] = 0.1 + 0.1 * double(l);
    ggx[l][param_index<SmoothGGX>("alpha_y")] = 0.5 / (1 + double(l));
  }
  EXPECT_EQ(groups_of<SmoothGGX>(ggx), 1u);
  ggx[1][param_index<SmoothGGX>("sampler")] = 0;  // ndf in lane 1, vndf elsewhere
  EXPECT_EQ(groups_of<SmoothGGX>(ggx), 2u);

  auto db = default_lanes<DeliotBelcour>();
  for (std::size_t l = 0; l < kBaselineLanes; ++l) {
    db[l][param_index<DeliotBelcour>("density")] = 2 + double(l);
    db[l][param_index<DeliotBelcour>("r")] = 1 + double(l);
  }
  EXPECT_EQ(groups_of<DeliotBelcour>(db), 1u);
  for (std::size_t l = 0; l < kBaselineLanes; ++l)
    db[l][param_index<DeliotBelcour>("seed")] = double(l);
  EXPECT_EQ(groups_of<DeliotBelcour>(db), kBaselineLanes);

  // Chermain's parameters are all uniform (double SdfParams): one group per distinct vector.
  auto ch = default_lanes<Chermain>();
  ch[0][param_index<Chermain>("alpha_x")] = 0.25;
  EXPECT_EQ(groups_of<Chermain>(ch), 2u);
}

}  // namespace
}  // namespace glintlab::simd::test

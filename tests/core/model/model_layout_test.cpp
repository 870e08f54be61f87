// The query layout (core/model_layout.h): every member of ModelQuery has exactly one column, and
// every conversion between a query and its columns (flat rows, the float conversion of the
// registry's float thunks, the registry's thunks, the SoA batch API) carries every column to its
// own member. Each column gets a distinct non-zero value, so a dropped column (left 0) or a
// misplaced one (another column's value) fails, naming the column.
#include "core/model_layout.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "core/model_registry.h"
#include "core/simd/model_batch.h"

namespace glintlab {
namespace {

constexpr std::size_t kColumns = kQueryLayout.size();

// Column k holds 0.5 + 0.25 k: distinct, non-zero and exact in float.
template <class T>
QueryRow<T> distinct_row() {
  QueryRow<T> row{};
  for (std::size_t k = 0; k < kColumns; ++k) row[k] = T(0.5 + 0.25 * double(k));
  return row;
}

template <class T, class U>
void expect_row(const QueryRow<T>& got, const QueryRow<U>& want, const std::string& where) {
  for (std::size_t k = 0; k < kColumns; ++k)
    EXPECT_EQ(double(got[k]), double(want[k])) << where << ": column " << kQueryLayout[k].name;
}

// A model that returns its query: eval's intermediates are the query's columns, sample's wo is
// columns u.x .. u.x + 2. No parameters.
struct EchoQuery {
  static constexpr std::string_view kName = "echo_query";
  static constexpr std::string_view kDescription = "test model: returns its query";
  static constexpr std::string_view kSource = "tests/core/model/model_layout_test.cpp";
  static constexpr unsigned kNeeds = kNeedsFootprint | kNeedsAreaLight | kNeedsPixelCorners;
  static constexpr std::array<ParamSpec, 0> kParams{};
  static constexpr auto kIntermediates = [] {
    std::array<std::string_view, kColumns> names{};
    for (std::size_t k = 0; k < kColumns; ++k) names[k] = kQueryLayout[k].name;
    return names;
  }();
  template <class T>
  struct Params {};
  template <class T>
  static Params<T> params(std::span<const double>) {
    return {};
  }
  template <class T>
  static ModelEval<T, kColumns> eval(const Params<T>&, const ModelQuery<T>& q) {
    return {T(0), T(0), to_row(q)};
  }
  template <class T>
  static T pdf(const Params<T>&, const ModelQuery<T>&) {
    return T(0);
  }
  template <class T>
  static ModelSample<T> sample(const Params<T>&, const ModelQuery<T>& q, Vec2<T> u) {
    const QueryRow<T> row = to_row(q);
    const auto k = static_cast<std::size_t>(u.x);
    return {{row[k], row[k + 1], row[k + 2]}, T(0), T(0), Mask<T>(false)};
  }
};
static_assert(Model<EchoQuery>);

TEST(ModelLayout, EveryMemberHasOneColumn) {
  // A member added to ModelQuery without a column changes its size.
  EXPECT_EQ(sizeof(ModelQuery<double>), kColumns * sizeof(double));
  std::set<std::string_view> names;
  for (const QueryColumn& c : kQueryLayout) EXPECT_TRUE(names.insert(c.name).second) << c.name;
  // The names against the members, spelled out independently of the layout.
  const QueryRow<double> row = distinct_row<double>();
  const ModelQuery<double> q = from_row(row);
  const auto at = [&](std::string_view name) {
    for (std::size_t k = 0; k < kColumns; ++k)
      if (kQueryLayout[k].name == name) return row[k];
    ADD_FAILURE() << "no column " << name;
    return 0.0;
  };
  const FootprintQuery<double>& f = q.footprint;
  EXPECT_EQ(f.uv.x, at("u"));
  EXPECT_EQ(f.uv.y, at("v"));
  EXPECT_EQ(f.duv_dx.x, at("dudx"));
  EXPECT_EQ(f.duv_dx.y, at("dvdx"));
  EXPECT_EQ(f.duv_dy.x, at("dudy"));
  EXPECT_EQ(f.duv_dy.y, at("dvdy"));
  EXPECT_EQ(q.wi.x, at("wi_x"));
  EXPECT_EQ(q.wi.y, at("wi_y"));
  EXPECT_EQ(q.wi.z, at("wi_z"));
  EXPECT_EQ(q.wo.x, at("wo_x"));
  EXPECT_EQ(q.wo.y, at("wo_y"));
  EXPECT_EQ(q.wo.z, at("wo_z"));
  EXPECT_EQ(q.light.cos_half_angle, at("light_cos_half_angle"));
  EXPECT_EQ(q.light.intensity, at("light_intensity"));
  for (std::size_t c = 0; c < 4; ++c) {
    const std::string r = "r" + std::to_string(c);
    EXPECT_EQ(f.corner_r[c].x, at(r + "_x"));
    EXPECT_EQ(f.corner_r[c].y, at(r + "_y"));
    EXPECT_EQ(f.corner_r[c].z, at(r + "_z"));
  }
  // The corner columns last: a query without them is a prefix.
  for (std::size_t k = 0; k < kColumns; ++k)
    EXPECT_EQ(kQueryLayout[k].part == QueryPart::kCorners, k >= kColumns - 12)
        << kQueryLayout[k].name;
}

TEST(ModelLayout, RowsRoundTrip) {
  expect_row(to_row(from_row(distinct_row<double>())), distinct_row<double>(), "double");
  expect_row(to_row(from_row(distinct_row<float>())), distinct_row<float>(), "float");
  expect_row(to_row(convert_query<double>(from_row(distinct_row<float>()))), distinct_row<double>(),
             "float -> double");
}

// The float thunks' conversion (the stability sweeps' float path) keeps every column, the corner
// reflection vectors among them.
TEST(ModelLayout, FloatConversionCarriesEveryColumn) {
  const ModelQuery<float> f = detail::to_float(from_row(distinct_row<double>()));
  expect_row(to_row(f), distinct_row<float>(), "detail::to_float");
}

TEST(ModelLayout, RegistryThunksCarryEveryColumn) {
  const ModelEntry entry = make_model_entry<EchoQuery>();
  ASSERT_TRUE(entry.eval_float && entry.sample_float);
  const ModelQuery<double> q = from_row(distinct_row<double>());
  const auto as_row = [](const std::vector<double>& v) {
    QueryRow<double> row{};
    for (std::size_t k = 0; k < kColumns && k < v.size(); ++k) row[k] = v[k];
    return row;
  };
  expect_row(as_row(entry.eval({}, q).intermediates), distinct_row<double>(), "eval");
  expect_row(as_row(entry.eval_float({}, q).intermediates), distinct_row<double>(), "eval_float");
  for (std::size_t k = 0; k + 2 < kColumns; ++k) {
    for (const bool in_float : {false, true}) {
      const ModelSample<double> s =
          (in_float ? entry.sample_float : entry.sample)({}, q, Vec2<double>{double(k), 0});
      const std::string where = std::string(in_float ? "sample_float" : "sample") + ", column " +
                                std::string(kQueryLayout[k].name);
      EXPECT_EQ(s.wo.x, distinct_row<double>()[k]) << where;
      EXPECT_EQ(s.wo.y, distinct_row<double>()[k + 1]) << where;
      EXPECT_EQ(s.wo.z, distinct_row<double>()[k + 2]) << where;
    }
  }
}

// The SoA batch API: columns in layout order, one row per call; without the corner columns the
// corners are zero.
template <class S>
void expect_batch_round_trip(bool with_corners) {
  const ModelEntry entry = make_model_entry<EchoQuery>();
  const QueryRow<S> row = distinct_row<S>();
  const std::size_t n_columns = with_corners ? kColumns : kColumns - 12;
  std::vector<simd::Column<S>> query;
  for (std::size_t k = 0; k < n_columns; ++k) query.push_back({&row[k], 0});
  std::vector<S> out(2 + kColumns);
  std::vector<S*> outputs;
  for (S& x : out) outputs.push_back(&x);
  simd::eval_batch(entry, {}, query, outputs, 1, simd::Isa::kScalar);
  QueryRow<S> got{}, want = row;
  for (std::size_t k = 0; k < kColumns; ++k) got[k] = out[2 + k];
  if (!with_corners)
    for (std::size_t k = n_columns; k < kColumns; ++k) want[k] = S(0);
  expect_row(got, want, with_corners ? "eval_batch" : "eval_batch without corners");
}

TEST(ModelLayout, BatchColumnsCarryEveryColumn) {
  expect_batch_round_trip<double>(true);
  expect_batch_round_trip<float>(true);
  expect_batch_round_trip<double>(false);
  expect_batch_round_trip<float>(false);
}

}  // namespace
}  // namespace glintlab

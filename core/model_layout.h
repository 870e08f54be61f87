// The flat column layout of ModelQuery (core/model.h): the one list of its columns, each with its
// name, the member it maps to and its default. Everything that turns a query into columns or back
// derives from it: the CLI's CSV columns, the SoA batches of core/simd/model_batch.h, the float
// conversion of the registry's float thunks, the benchmarks and the tests.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

#include "core/model.h"

namespace glintlab {

// The part of the query a column belongs to; a model's kNeeds decides which parts it reads.
enum class QueryPart { kFootprint, kDirections, kLight, kCorners };

struct QueryColumn {
  std::string_view name;
  QueryPart part;
  double default_value;  // where the model does not need the part or the input leaves it out
};

// visit(column index, QueryColumn, member) for every column of q (a ModelQuery<T>, const or not;
// member is a T& or const T&), in column order. The corner columns come last, so a query without
// them is a prefix of the layout.
template <class Query, class Visit>
GLINTLAB_FN constexpr void for_each_query_column(Query& q, Visit&& visit) {
  std::size_t index = 0;
  const auto column = [&](std::string_view name, QueryPart part, double default_value,
                          auto& member) {
    visit(index++, QueryColumn{name, part, default_value}, member);
  };
  using enum QueryPart;
  column("u", kFootprint, 0, q.footprint.uv.x);
  column("v", kFootprint, 0, q.footprint.uv.y);
  column("dudx", kFootprint, 0, q.footprint.duv_dx.x);
  column("dvdx", kFootprint, 0, q.footprint.duv_dx.y);
  column("dudy", kFootprint, 0, q.footprint.duv_dy.x);
  column("dvdy", kFootprint, 0, q.footprint.duv_dy.y);
  column("wi_x", kDirections, 0, q.wi.x);
  column("wi_y", kDirections, 0, q.wi.y);
  column("wi_z", kDirections, 1, q.wi.z);
  column("wo_x", kDirections, 0, q.wo.x);
  column("wo_y", kDirections, 0, q.wo.y);
  column("wo_z", kDirections, 1, q.wo.z);
  column("light_cos_half_angle", kLight, 1, q.light.cos_half_angle);
  column("light_intensity", kLight, 1, q.light.intensity);
  // Corner k's reflection vector as rk_x, rk_y, rk_z.
  constexpr std::string_view kCornerNames[4][3] = {
      {"r0_x", "r0_y", "r0_z"}, {"r1_x", "r1_y", "r1_z"},
      {"r2_x", "r2_y", "r2_z"}, {"r3_x", "r3_y", "r3_z"}};
  for (std::size_t k = 0; k < 4; ++k) {
    column(kCornerNames[k][0], kCorners, 0, q.footprint.corner_r[k].x);
    column(kCornerNames[k][1], kCorners, 0, q.footprint.corner_r[k].y);
    column(kCornerNames[k][2], kCorners, 0, q.footprint.corner_r[k].z);
  }
}

namespace detail {
consteval std::size_t count_query_columns() {
  ModelQuery<double> q{};
  std::size_t n = 0;
  for_each_query_column(q, [&](std::size_t, const QueryColumn&, double&) { ++n; });
  return n;
}
}  // namespace detail

// Every column, in column order.
inline constexpr std::array<QueryColumn, detail::count_query_columns()> kQueryLayout = [] {
  std::array<QueryColumn, detail::count_query_columns()> layout{};
  ModelQuery<double> q{};
  for_each_query_column(q, [&](std::size_t k, const QueryColumn& c, double&) { layout[k] = c; });
  return layout;
}();

// The index of the column `name`; a compile error for a name that is not a column.
void query_column_name_is_not_in_the_layout();
consteval std::size_t query_column_index(std::string_view name) {
  for (std::size_t k = 0; k < kQueryLayout.size(); ++k)
    if (kQueryLayout[k].name == name) return k;
  query_column_name_is_not_in_the_layout();
  return kQueryLayout.size();
}

// The query as a flat row of column values, and back.
template <class T>
using QueryRow = std::array<T, kQueryLayout.size()>;

template <class T>
constexpr QueryRow<T> to_row(const ModelQuery<T>& q) {
  QueryRow<T> row{};
  for_each_query_column(
      q, [&](std::size_t k, const QueryColumn&, const T& member) { row[k] = member; });
  return row;
}

template <class T>
constexpr ModelQuery<T> from_row(const QueryRow<T>& row) {
  ModelQuery<T> q{};
  for_each_query_column(q, [&](std::size_t k, const QueryColumn&, T& member) { member = row[k]; });
  return q;
}

// The query in another float type, column by column (To(value): rounded to float or widened).
template <class To, class From>
constexpr ModelQuery<To> convert_query(const ModelQuery<From>& q) {
  const QueryRow<From> from = to_row(q);
  QueryRow<To> to{};
  for (std::size_t k = 0; k < to.size(); ++k) to[k] = static_cast<To>(from[k]);
  return from_row(to);
}

}  // namespace glintlab

// Per-lane parameters of a model's batch (model_batch.h's eval_batch_with_param_columns): the
// Params<W> of a batch whose lanes hold rows with different parameter values, built from each
// row's own M::params<W>, so that every lane sees exactly the values its row evaluated alone sees.
// Included by core/simd/instantiate.h only (the ISA units), before core/simd/wide.h is fine: the
// Wide specialisations it uses are looked up where its templates are instantiated.
#pragma once

// Why this shape: a model's Params<W> (core/model.h) mixes per-lane members (a W, e.g. GGX<W>'s
// alpha_x) with uniform ones its kernels may branch on (a sampler choice, a seed, Chermain's double
// SdfParams). Lanes whose uniform members agree share one Params<W>, each W member taking lane l
// from lane l's own Params; lanes whose uniform members differ go to another group (another kernel
// run over the batch, only its lanes' results kept). The members are visited by aggregate
// reflection (brace-initialisation counts them, structured bindings name them), so no model
// declares anything for it. A member this cannot take apart (a class that is neither a W nor an
// aggregate, e.g. a mask or a batch of another width) makes lanes merge only with lanes of the same
// parameter vector: one group per distinct vector, still correct. An aggregate it miscounts (one
// holding a C array) fails to compile at the structured binding, never silently.

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <tuple>
#include <type_traits>
#include <utility>

#include "core/math/lanes.h"
#include "core/simd/batch.h"

namespace glintlab::simd::detail {
namespace {  // internal linkage, as core/simd/instantiate.h: each ISA unit keeps its own copy
namespace lanes {

// Converts to anything; only named in unevaluated operands (member counting).
struct AnyInit {
  template <class U>
  operator U() const;  // NOLINT(google-explicit-constructor): implicit by design
};

template <class T, std::size_t... I>
constexpr bool brace_initializable(std::index_sequence<I...>) {
  return requires { T{(static_cast<void>(I), AnyInit{})...}; };
}

inline constexpr std::size_t kMaxMembers = 16;

// The number of members of aggregate T, or 0 when it has more than kMaxMembers.
template <class T, std::size_t N = kMaxMembers>
constexpr std::size_t member_count() {
  if constexpr (N == 0) {
    return 0;
  } else if constexpr (brace_initializable<T>(std::make_index_sequence<N>{})) {
    return brace_initializable<T>(std::make_index_sequence<N + 1>{}) ? 0 : N;
  } else {
    return member_count<T, N - 1>();
  }
}

// The members of aggregate T as a tuple of references, in declaration order.
template <class T>
constexpr auto tie_members(T& t) {
  constexpr std::size_t n = member_count<std::remove_const_t<T>>();
  // clang-format off
  if constexpr (n == 1) { auto& [a] = t; return std::tie(a); }
  else if constexpr (n == 2) { auto& [a, b] = t; return std::tie(a, b); }
  else if constexpr (n == 3) { auto& [a, b, c] = t; return std::tie(a, b, c); }
  else if constexpr (n == 4) { auto& [a, b, c, d] = t; return std::tie(a, b, c, d); }
  else if constexpr (n == 5) { auto& [a, b, c, d, e] = t; return std::tie(a, b, c, d, e); }
  else if constexpr (n == 6) { auto& [a, b, c, d, e, f] = t; return std::tie(a, b, c, d, e, f); }
  else if constexpr (n == 7) { auto& [a, b, c, d, e, f, g] = t; return std::tie(a, b, c, d, e, f, g); }
  else if constexpr (n == 8) { auto& [a, b, c, d, e, f, g, h] = t; return std::tie(a, b, c, d, e, f, g, h); }
  else if constexpr (n == 9) { auto& [a, b, c, d, e, f, g, h, i] = t; return std::tie(a, b, c, d, e, f, g, h, i); }
  else if constexpr (n == 10) { auto& [a, b, c, d, e, f, g, h, i, j] = t; return std::tie(a, b, c, d, e, f, g, h, i, j); }
  else if constexpr (n == 11) { auto& [a, b, c, d, e, f, g, h, i, j, k] = t; return std::tie(a, b, c, d, e, f, g, h, i, j, k); }
  else if constexpr (n == 12) { auto& [a, b, c, d, e, f, g, h, i, j, k, l] = t; return std::tie(a, b, c, d, e, f, g, h, i, j, k, l); }
  else if constexpr (n == 13) { auto& [a, b, c, d, e, f, g, h, i, j, k, l, m] = t; return std::tie(a, b, c, d, e, f, g, h, i, j, k, l, m); }
  else if constexpr (n == 14) { auto& [a, b, c, d, e, f, g, h, i, j, k, l, m, o] = t; return std::tie(a, b, c, d, e, f, g, h, i, j, k, l, m, o); }
  else if constexpr (n == 15) { auto& [a, b, c, d, e, f, g, h, i, j, k, l, m, o, p] = t; return std::tie(a, b, c, d, e, f, g, h, i, j, k, l, m, o, p); }
  else { static_assert(n == 16); auto& [a, b, c, d, e, f, g, h, i, j, k, l, m, o, p, q] = t; return std::tie(a, b, c, d, e, f, g, h, i, j, k, l, m, o, p, q); }
  // clang-format on
}

template <class T>
struct IsStdArray : std::false_type {};
template <class E, std::size_t N>
struct IsStdArray<std::array<E, N>> : std::true_type {};

// What a member of Params<W> is to the merge.
enum class Kind {
  kLane,       // a W: lane l comes from lane l's own Params
  kUniform,    // a number, enum or pointer: must be equal for the lanes to share a Params
  kArray,      // a std::array of members
  kAggregate,  // a struct of members
  kOpaque,     // anything else: not merged
};

template <class W, class T>
constexpr Kind kind_of() {
  if constexpr (std::is_same_v<T, W>) {
    return Kind::kLane;
  } else if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T> || std::is_pointer_v<T>) {
    return Kind::kUniform;
  } else if constexpr (IsStdArray<T>::value) {
    return Kind::kArray;
  } else if constexpr (std::is_aggregate_v<T> && !std::is_array_v<T> && !std::is_union_v<T>) {
    return member_count<T>() > 0 ? Kind::kAggregate : Kind::kOpaque;
  } else {
    return Kind::kOpaque;
  }
}

// Whether lanes of Params type T can be merged: every member, recursively, a lane, a uniform or
// an array or aggregate of them.
template <class W, class T>
constexpr bool mergeable() {
  constexpr Kind k = kind_of<W, T>();
  if constexpr (k == Kind::kLane || k == Kind::kUniform) {
    return true;
  } else if constexpr (k == Kind::kArray) {
    return mergeable<W, typename T::value_type>();
  } else if constexpr (k == Kind::kAggregate) {
    using Tie = decltype(tie_members(std::declval<T&>()));
    return []<std::size_t... I>(std::index_sequence<I...>) {
      return (mergeable<W, std::remove_cvref_t<std::tuple_element_t<I, Tie>>>() && ...);
    }(std::make_index_sequence<std::tuple_size_v<Tie>>{});
  } else {
    return false;
  }
}

// Whether the uniform members of a and b are equal, bit for bit (only for mergeable T).
template <class W, class T>
bool same_uniforms(const T& a, const T& b) {
  constexpr Kind k = kind_of<W, T>();
  if constexpr (k == Kind::kLane) {
    return true;
  } else if constexpr (k == Kind::kUniform) {
    if constexpr (std::is_floating_point_v<T>) {
      using Bits = std::conditional_t<sizeof(T) == 8, std::uint64_t, std::uint32_t>;
      static_assert(sizeof(T) == sizeof(Bits));
      return std::bit_cast<Bits>(a) == std::bit_cast<Bits>(b);
    } else {
      return a == b;
    }
  } else if constexpr (k == Kind::kArray) {
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!same_uniforms<W>(a[i], b[i])) return false;
    return true;
  } else {
    static_assert(k == Kind::kAggregate);
    const auto ta = tie_members(a);
    const auto tb = tie_members(b);
    return [&]<std::size_t... I>(std::index_sequence<I...>) {
      return (same_uniforms<W>(std::get<I>(ta), std::get<I>(tb)) && ...);
    }(std::make_index_sequence<std::tuple_size_v<decltype(ta)>>{});
  }
}

// Lane `lane` of every lane member of dst set to that lane of src's (only for mergeable T).
template <class W, class T>
void set_lane(T& dst, const T& src, std::size_t lane) {
  constexpr Kind k = kind_of<W, T>();
  if constexpr (k == Kind::kLane) {
    // A W is its lanes' scalars in lane order (a SIMD register's memory image): the lane is
    // copied as bytes, without storing and reloading the whole register.
    using S = Scalar<W>;
    static_assert(std::is_trivially_copyable_v<W> && sizeof(W) == LaneAccess<W>::kLanes * sizeof(S));
    std::memcpy(reinterpret_cast<char*>(&dst) + lane * sizeof(S),
                reinterpret_cast<const char*>(&src) + lane * sizeof(S), sizeof(S));
  } else if constexpr (k == Kind::kArray) {
    for (std::size_t i = 0; i < dst.size(); ++i) set_lane<W>(dst[i], src[i], lane);
  } else if constexpr (k == Kind::kAggregate) {
    const auto td = tie_members(dst);
    const auto ts = tie_members(src);
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      (set_lane<W>(std::get<I>(td), std::get<I>(ts), lane), ...);
    }(std::make_index_sequence<std::tuple_size_v<decltype(td)>>{});
  }
}

// The parameters of one batch of model M on W: each lane's parameter vector (rows [i, i + count)
// of the parameter columns, the lanes past count padded with row i, as the query's are), grouped
// so that the lanes of a group share one Params<W>. The batch's kernel runs once per group; lane l
// keeps the results of group_of(l). Reused across batches: a batch with the lanes' vectors of the
// previous one keeps its groups (blocks of equal values cost one comparison per batch).
template <class M, class W>
class LaneParams {
 public:
  static constexpr std::size_t kLanes = LaneAccess<W>::kLanes;
  static constexpr std::size_t kParamCount = M::kParams.size();
  using P = typename M::template Params<W>;
  static_assert(kLanes <= 256, "group_of_ holds a lane's group in one byte");

  void load(const Column<double>* params, std::size_t i, std::size_t count) {
    Values v;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const std::size_t row = i + (l < count ? l : 0);
      for (std::size_t k = 0; k < kParamCount; ++k)
        v[l][k] = params[k].data[params[k].stride * row];
    }
    if (loaded_ && std::memcmp(&v, &values_, sizeof(Values)) == 0) return;
    values_ = v;
    loaded_ = true;
    groups_ = 0;
    for (std::size_t l = 0; l < kLanes; ++l) {
      // A lane with the vector of the lane before it joins that lane's group.
      if (l > 0 && std::memcmp(&v[l], &v[l - 1], sizeof(v[l])) == 0) {
        group_of_[l] = group_of_[l - 1];
        if constexpr (kMerge) set_lane<W>(group_[group_of_[l]], current_, l);
        continue;
      }
      current_ = M::template params<W>(std::span<const double>(v[l].data(), kParamCount));
      std::size_t g = 0;
      if constexpr (kMerge) {
        while (g < groups_ && !same_uniforms<W>(group_[g], current_)) ++g;
        if (g < groups_) set_lane<W>(group_[g], current_, l);
      } else {
        // Not mergeable: only lanes of the same vector share a group.
        std::size_t same = 0;
        while (same < l && std::memcmp(&v[same], &v[l], sizeof(v[l])) != 0) ++same;
        g = same < l ? group_of_[same] : groups_;
      }
      if (g == groups_) group_[groups_++] = current_;
      group_of_[l] = static_cast<unsigned char>(g);
    }
  }

  std::size_t groups() const { return groups_; }
  const P& group(std::size_t g) const { return group_[g]; }
  std::size_t group_of(std::size_t lane) const { return group_of_[lane]; }

 private:
  using Values = std::array<std::array<double, kParamCount>, kLanes>;
  static constexpr bool kMerge = kLanes > 1 && mergeable<W, P>();

  Values values_{};
  bool loaded_ = false;
  std::size_t groups_ = 0;
  std::array<P, kLanes> group_{};
  std::array<unsigned char, kLanes> group_of_{};
  P current_{};
};

}  // namespace lanes
}  // namespace
}  // namespace glintlab::simd::detail

// The samplers of the core, one row each. Every place that names a sampler is generated from this
// list: the batch kernels sample.<name> and pdf.<name> (core/simd/kernels.h), the sampler claims'
// table (verify/claims/sampler_table.cpp), the smooth models' `sampler` and `bound` choices
// (SmoothGGX, SmoothBeckmann), `glintlab sample --sampler/--bound` and `glintlab eval`'s pdf
// columns. Adding a sampler is its function in core/samplers/ and one row here.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>
#include <tuple>
#include <type_traits>

#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/samplers/beckmann_vndf.h"
#include "core/samplers/bounded_vndf.h"
#include "core/samplers/heitz_vndf.h"
#include "core/samplers/spherical_caps.h"
#include "core/samplers/walter.h"

namespace glintlab {

// What the list says of one sampler.
struct SamplerInfo {
  std::string_view name;    // `<core function>/<ndf>`, e.g. "heitz_vndf/ggx" (kernels, claims)
  std::string_view ndf;     // "ggx" or "beckmann"
  std::string_view choice;  // the smooth model's `sampler` value; one choice may span NDFs
  std::string_view bound;   // the `bound` value, where one choice has several samplers; else ""
  bool allows_backfacing;   // accepts wi.z <= 0 (a back-facing shading normal)
  std::string_view source;  // the paper and equations
};

// X(A, Type, Ndf, name, ndf, choice, bound, allows_backfacing, source, sample, pdf): `sample` and
// `pdf` are expressions in `ndf` (an Ndf<T>), `wi`, and `u` (sample) or `wo` (pdf). A is passed
// through to X unchanged (core/simd/kernels.h's kernel list forwards its own X in it).
// clang-format off
#define GLINTLAB_SAMPLERS(X, A)                                                                   \
  X(A, WalterGgx, GGX, "walter/ggx", "ggx", "ndf", "", false, "Walter et al. 2007 Eq. 35-36",     \
    sample_walter(ndf, wi, u), pdf_walter(ndf, wi, wo))                                          \
  X(A, WalterBeckmann, Beckmann, "walter/beckmann", "beckmann", "ndf", "", false,                \
    "Walter et al. 2007 Eq. 28-29", sample_walter(ndf, wi, u), pdf_walter(ndf, wi, wo))           \
  X(A, HeitzVndf, GGX, "heitz_vndf/ggx", "ggx", "vndf", "", false, "Heitz 2018 Sec. 3, Eq. 1",    \
    sample_heitz_vndf(ndf, wi, u), pdf_heitz_vndf(ndf, wi, wo))                                   \
  X(A, BeckmannVndf, Beckmann, "beckmann_vndf/beckmann", "beckmann", "vndf", "", false,           \
    "Heitz & d'Eon 2014", sample_beckmann_vndf(ndf, wi, u), pdf_beckmann_vndf(ndf, wi, wo))       \
  X(A, SphericalCaps, GGX, "spherical_caps/ggx", "ggx", "spherical_caps", "", true,               \
    "Dupuy & Benyoub 2023", sample_spherical_caps(ndf, wi, u), pdf_spherical_caps(ndf, wi, wo))   \
  X(A, BoundedListing1, GGX, "bounded_vndf_listing1/ggx", "ggx", "bounded_caps", "listing1",      \
    true, "Eto & Tokuyoshi 2023 Eq. 5-8, Listing 1",                                              \
    sample_bounded_vndf(ndf, wi, u, BoundedVndfBound::kListing1),                                 \
    pdf_bounded_vndf(ndf, wi, wo, BoundedVndfBound::kListing1))                                   \
  X(A, BoundedExactIso, GGX, "bounded_vndf_exact_isotropic/ggx", "ggx", "bounded_caps",           \
    "exact_isotropic", true, "Eto & Tokuyoshi 2023 Eq. 5-8, k exact for isotropic alpha",         \
    sample_bounded_vndf(ndf, wi, u, BoundedVndfBound::kExactIsotropic),                           \
    pdf_bounded_vndf(ndf, wi, wo, BoundedVndfBound::kExactIsotropic))
// clang-format on

// One type per row: samplers::HeitzVndf::sample(ggx, wi, u), ::pdf(ggx, wi, wo), ::kInfo.
namespace samplers {
#define GLINTLAB_SAMPLER_TYPE(A, Type, NdfType, name_, ndf_, choice_, bound_, backfacing, source_, \
                              sample_expr, pdf_expr)                                               \
  struct Type {                                                                                    \
    static constexpr SamplerInfo kInfo{name_, ndf_, choice_, bound_, backfacing, source_};         \
    template <class T>                                                                             \
    using Ndf = NdfType<T>;                                                                        \
    template <class T>                                                                             \
    GLINTLAB_INLINE static MicrofacetSample<T> sample(const NdfType<T>& ndf, Vec3<T> wi,           \
                                                      Vec2<T> u) {                                 \
      return sample_expr;                                                                          \
    }                                                                                              \
    template <class T>                                                                             \
    GLINTLAB_INLINE static T pdf(const NdfType<T>& ndf, Vec3<T> wi, Vec3<T> wo) {                  \
      return pdf_expr;                                                                             \
    }                                                                                              \
  };
GLINTLAB_SAMPLERS(GLINTLAB_SAMPLER_TYPE, )
#undef GLINTLAB_SAMPLER_TYPE

#define GLINTLAB_SAMPLER_TUPLE(A, Type, ...) std::tuple<Type>{},
// Every row, in list order, as a std::tuple of the types.
using All = decltype(std::tuple_cat(GLINTLAB_SAMPLERS(GLINTLAB_SAMPLER_TUPLE, ) std::tuple<>{}));
#undef GLINTLAB_SAMPLER_TUPLE

namespace detail {
template <template <class> class Ndf, class... S>
auto of_ndf(std::tuple<S...>*) -> decltype(std::tuple_cat(
    std::conditional_t<std::is_same_v<typename S::template Ndf<double>, Ndf<double>>, std::tuple<S>,
                       std::tuple<>>{}...));
}  // namespace detail

// The rows that sample NDF Ndf (GGX or Beckmann), in list order.
template <template <class> class Ndf>
using Of = decltype(detail::of_ndf<Ndf>(static_cast<All*>(nullptr)));

// The `sampler` and `bound` choices of a model over the samplers List: the distinct `choice`
// values, then the distinct `bound` values, each in list order.
template <class List>
struct Choices;
template <class... S>
struct Choices<std::tuple<S...>> {
  static constexpr std::array<SamplerInfo, sizeof...(S)> kRows{S::kInfo...};

 private:
  template <bool Bounds>
  static constexpr std::string_view key(const SamplerInfo& s) {
    return Bounds ? s.bound : s.choice;
  }
  template <bool Bounds>
  static constexpr std::size_t distinct() {
    std::size_t n = 0;
    for (std::size_t i = 0; i < kRows.size(); ++i) {
      bool seen = key<Bounds>(kRows[i]).empty();
      for (std::size_t j = 0; j < i; ++j)
        seen = seen || key<Bounds>(kRows[j]) == key<Bounds>(kRows[i]);
      n += seen ? 0 : 1;
    }
    return n;
  }
  template <bool Bounds>
  static constexpr auto names() {
    std::array<std::string_view, distinct<Bounds>()> out{};
    std::size_t n = 0;
    for (const SamplerInfo& s : kRows) {
      bool seen = key<Bounds>(s).empty();
      for (std::size_t j = 0; j < n; ++j) seen = seen || out[j] == key<Bounds>(s);
      if (!seen) out[n++] = key<Bounds>(s);
    }
    return out;
  }

 public:
  static constexpr auto kNames = names<false>();  // the `sampler` parameter's values
  static constexpr auto kBounds = names<true>();  // the `bound` parameter's values

  // The position in List of the row that choice (a `sampler` value) and bound choose; the bound
  // applies only to a choice that has several rows (the first row of a choice otherwise). -1: none.
  static constexpr int find(std::string_view choice, std::string_view bound = {}) {
    for (std::size_t i = 0; i < kRows.size(); ++i)
      if (kRows[i].choice == choice &&
          (kRows[i].bound.empty() || bound.empty() || kRows[i].bound == bound))
        return int(i);
    return -1;
  }
  // The same by the parameters' indices (a model's params(): the values are checked already).
  static constexpr int index(int choice, int bound) {
    // A local copy of the table, so that the ISA units share no symbol (tests/simd/isa_symbols).
    constexpr auto rows = index_table();
    return rows[std::size_t(choice) * kBoundsPerChoice + std::size_t(bound)];
  }
  // The `sampler` and `bound` parameter values that choose row `row` (the inverse of index; the
  // bound is 0 for a choice with one row).
  static constexpr int choice_of(int row) {
    return position(kNames, kRows[std::size_t(row)].choice);
  }
  static constexpr int bound_of(int row) {
    return kRows[std::size_t(row)].bound.empty() ? 0
                                                 : position(kBounds, kRows[std::size_t(row)].bound);
  }

 private:
  static constexpr std::size_t kBoundsPerChoice = kBounds.empty() ? 1 : kBounds.size();
  static constexpr auto index_table() {
    std::array<int, kNames.size() * kBoundsPerChoice> rows{};
    for (std::size_t c = 0; c < kNames.size(); ++c)
      for (std::size_t b = 0; b < kBoundsPerChoice; ++b)
        rows[c * kBoundsPerChoice + b] =
            find(kNames[c], kBounds.empty() ? std::string_view{} : kBounds[b]);
    return rows;
  }
  template <std::size_t N>
  static constexpr int position(const std::array<std::string_view, N>& names, std::string_view v) {
    for (std::size_t i = 0; i < N; ++i)
      if (names[i] == v) return int(i);
    return -1;
  }
};

// f.template operator()<S>() for the row S at `index` of List. The index is a uniform choice (one
// per batch, never per lane), so this branches.
template <class List, std::size_t I = 0, class F>
GLINTLAB_INLINE decltype(auto) with(int index, const F& f) {
  using S = std::tuple_element_t<I, List>;
  if constexpr (I + 1 == std::tuple_size_v<List>) {
    return f.template operator()<S>();
  } else {
    if (index == int(I)) return f.template operator()<S>();
    return with<List, I + 1>(index, f);
  }
}

// f.template operator()<S>() for every row S of List, in order (host code: tables, the CLI).
template <class List, class F>
constexpr void for_each(const F& f) {
  [&]<class... S>(std::tuple<S...>*) {
    (f.template operator()<S>(), ...);
  }(static_cast<List*>(nullptr));
}

}  // namespace samplers
}  // namespace glintlab

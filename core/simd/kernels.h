// The kernel list of the batch API: every core kernel (core/ndf, core/samplers, core/maps,
// core/ndf/total_area.h) as a structure-of-arrays functor, one template for scalar and SIMD.
#pragma once

// A functor K has kName, kIn (the domain of each input column, which also names it), kOut (the
// output column names) and `template <class T> static void eval(const T* in, T* out)`, which
// calls the kernel template on T = float, double or any Wide<B, M>. Adding a kernel (a new model)
// = one functor here plus one line in GLINTLAB_SIMD_KERNELS: scalar and every ISA instantiate it,
// the equivalence tests (tests/simd/) and the benchmarks (experiments/bench/) iterate over it.
// Masks come out as 1 (true) or 0. The papers and equations are cited at the kernels themselves.

#include <array>
#include <string_view>
#include <type_traits>

#include "core/maps/beckmann_map.h"
#include "core/maps/ggx_map.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/fresnel.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "core/ndf/total_area.h"
#include "core/samplers/bounded_vndf.h"
#include "core/samplers/sampler_list.h"

namespace glintlab::simd {

// What an input column holds; the test and benchmark input generator (core/simd/inputs.h) draws
// each domain over its edge cases.
enum class Domain {
  kAlphaX,
  kAlphaY,  // anisotropic roughness pair
  kAlpha,   // one isotropic roughness
  kWiX,
  kWiY,
  kWiZ,  // incident direction (any hemisphere, grazing, normal)
  kWoX,
  kWoY,
  kWoZ,  // outgoing direction (half near the reflection lobe)
  kMX,
  kMY,
  kMZ,  // microfacet normal (half near the NDF peak)
  kU1,
  kU2,  // uniforms in [0, 1)
  kPX,
  kPY,  // point of the map's disk in the unit square
  kF0,
  kEta,
  kKappa,  // Fresnel parameters
};

namespace detail {
template <class T>
GLINTLAB_FN Vec3<T> v3(const T* x, int i) {
  return {x[i], x[i + 1], x[i + 2]};
}
template <class T>
GLINTLAB_FN void put3(T* y, int i, Vec3<T> v) {
  y[i] = v.x;
  y[i + 1] = v.y;
  y[i + 2] = v.z;
}
// The D kernels: Ndf<T>::D, except where T's math policy has a one-division GGX D (FastMath:
// core/simd/fast_math.h fast::ggx_d, float only, error documented there). Only the ggx.d kernel
// takes it; GGX<T>::D itself, and every kernel built on it, stays exact in both policies.
template <class Ndf, class T>
GLINTLAB_FN T ndf_d(const Ndf& ndf, Vec3<T> m) {
  if constexpr (std::is_same_v<Ndf, GGX<T>> &&
                requires { T::Policy::ggx_d(m.x.v, m.x.v, m.x.v, m.x.v, m.x.v); }) {
    return T::wrap(T::Policy::ggx_d(ndf.alpha_x.v, ndf.alpha_y.v, m.x.v, m.y.v, m.z.v));
  } else {
    return ndf.D(m);
  }
}
template <class T>
GLINTLAB_FN T from_mask(Mask<T> m) {
  return select(m, T(1), T(0));
}
template <class T>
GLINTLAB_FN void put_sample(T* y, const MicrofacetSample<T>& s) {
  put3(y, 0, s.wo);
  put3(y, 3, s.m);
  y[6] = s.pdf;
  y[7] = from_mask<T>(s.rejected);
}
}  // namespace detail

using D = Domain;
inline constexpr std::array kInW = {D::kAlphaX, D::kAlphaY, D::kWiX, D::kWiY, D::kWiZ};
inline constexpr std::array kInM = {D::kAlphaX, D::kAlphaY, D::kMX, D::kMY, D::kMZ};
inline constexpr std::array kInWiM = {D::kAlphaX, D::kAlphaY, D::kWiX, D::kWiY,
                                      D::kWiZ,    D::kMX,     D::kMY,  D::kMZ};
inline constexpr std::array kInWiWo = {D::kAlphaX, D::kAlphaY, D::kWiX, D::kWiY,
                                       D::kWiZ,    D::kWoX,    D::kWoY, D::kWoZ};
inline constexpr std::array kInSample = {D::kAlphaX, D::kAlphaY, D::kWiX, D::kWiY,
                                         D::kWiZ,    D::kU1,     D::kU2};
inline constexpr std::array<std::string_view, 1> kOutValue = {"value"};
inline constexpr std::array<std::string_view, 8> kOutSample = {"wo_x", "wo_y", "wo_z", "m_x",
                                                               "m_y",  "m_z",  "pdf",  "rejected"};

// --- NDF terms, for both NDFs ---------------------------------------------------------------
#define GLINTLAB_NDF_KERNELS(Prefix, Ndf, name)                                              \
  struct Prefix##D {                                                                         \
    static constexpr std::string_view kName = name ".d";                                     \
    static constexpr auto kIn = kInM;                                                        \
    static constexpr auto kOut = kOutValue;                                                  \
    template <class T>                                                                       \
    GLINTLAB_FN static void eval(const T* x, T* y) {                                         \
      y[0] = detail::ndf_d(Ndf<T>{x[0], x[1]}, detail::v3(x, 2));                            \
    }                                                                                        \
  };                                                                                         \
  struct Prefix##Lambda {                                                                    \
    static constexpr std::string_view kName = name ".lambda";                                \
    static constexpr auto kIn = kInW;                                                        \
    static constexpr auto kOut = kOutValue;                                                  \
    template <class T>                                                                       \
    GLINTLAB_FN static void eval(const T* x, T* y) {                                         \
      y[0] = Ndf<T>{x[0], x[1]}.lambda(detail::v3(x, 2));                                    \
    }                                                                                        \
  };                                                                                         \
  struct Prefix##ProjectedArea {                                                             \
    static constexpr std::string_view kName = name ".projected_area";                        \
    static constexpr auto kIn = kInW;                                                        \
    static constexpr auto kOut = kOutValue;                                                  \
    template <class T>                                                                       \
    GLINTLAB_FN static void eval(const T* x, T* y) {                                         \
      y[0] = Ndf<T>{x[0], x[1]}.projected_area(detail::v3(x, 2));                            \
    }                                                                                        \
  };                                                                                         \
  struct Prefix##G1 {                                                                        \
    static constexpr std::string_view kName = name ".g1";                                    \
    static constexpr auto kIn = kInWiM;                                                      \
    static constexpr auto kOut = kOutValue;                                                  \
    template <class T>                                                                       \
    GLINTLAB_FN static void eval(const T* x, T* y) {                                         \
      y[0] = smith_g1(Ndf<T>{x[0], x[1]}, detail::v3(x, 2), detail::v3(x, 5));               \
    }                                                                                        \
  };                                                                                         \
  struct Prefix##G2HeightCorrelated {                                                        \
    static constexpr std::string_view kName = name ".g2_height_correlated";                  \
    static constexpr auto kIn = kInWiWo;                                                     \
    static constexpr auto kOut = kOutValue;                                                  \
    template <class T>                                                                       \
    GLINTLAB_FN static void eval(const T* x, T* y) {                                         \
      const Vec3<T> wi = detail::v3(x, 2), wo = detail::v3(x, 5);                            \
      y[0] = smith_g2_height_correlated(Ndf<T>{x[0], x[1]}, wi, wo, half_vector(wi, wo));    \
    }                                                                                        \
  };                                                                                         \
  struct Prefix##G2Separable {                                                               \
    static constexpr std::string_view kName = name ".g2_separable";                          \
    static constexpr auto kIn = kInWiWo;                                                     \
    static constexpr auto kOut = kOutValue;                                                  \
    template <class T>                                                                       \
    GLINTLAB_FN static void eval(const T* x, T* y) {                                         \
      const Vec3<T> wi = detail::v3(x, 2), wo = detail::v3(x, 5);                            \
      y[0] = smith_g2_separable(Ndf<T>{x[0], x[1]}, wi, wo, half_vector(wi, wo));            \
    }                                                                                        \
  };                                                                                         \
  struct Prefix##Vndf {                                                                      \
    static constexpr std::string_view kName = name ".vndf";                                  \
    static constexpr auto kIn = kInWiM;                                                      \
    static constexpr auto kOut = kOutValue;                                                  \
    template <class T>                                                                       \
    GLINTLAB_FN static void eval(const T* x, T* y) {                                         \
      y[0] = vndf(Ndf<T>{x[0], x[1]}, detail::v3(x, 2), detail::v3(x, 5));                   \
    }                                                                                        \
  };                                                                                         \
  struct Prefix##BrdfSchlick {                                                               \
    static constexpr std::string_view kName = name ".brdf_schlick";                          \
    static constexpr std::array kIn = {D::kAlphaX, D::kAlphaY, D::kF0,  D::kWiX, D::kWiY,    \
                                       D::kWiZ,    D::kWoX,    D::kWoY, D::kWoZ};            \
    static constexpr auto kOut = kOutValue;                                                  \
    template <class T>                                                                       \
    GLINTLAB_FN static void eval(const T* x, T* y) {                                         \
      const Vec3<T> wi = detail::v3(x, 3), wo = detail::v3(x, 6);                            \
      const T f = fresnel_schlick(x[2], dot(wi, half_vector(wi, wo)));                       \
      y[0] = microfacet_brdf(Ndf<T>{x[0], x[1]}, wi, wo, f);                                 \
    }                                                                                        \
  };                                                                                         \
  struct Prefix##BrdfConductor {                                                             \
    static constexpr std::string_view kName = name ".brdf_conductor";                        \
    static constexpr std::array kIn = {D::kAlphaX, D::kAlphaY, D::kEta, D::kKappa, D::kWiX,  \
                                       D::kWiY,    D::kWiZ,    D::kWoX, D::kWoY,   D::kWoZ}; \
    static constexpr auto kOut = kOutValue;                                                  \
    template <class T>                                                                       \
    GLINTLAB_FN static void eval(const T* x, T* y) {                                         \
      const Vec3<T> wi = detail::v3(x, 4), wo = detail::v3(x, 7);                            \
      const T f = fresnel_conductor(x[2], x[3], dot(wi, half_vector(wi, wo)));               \
      y[0] = microfacet_brdf(Ndf<T>{x[0], x[1]}, wi, wo, f);                                 \
    }                                                                                        \
  };

GLINTLAB_NDF_KERNELS(Ggx, GGX, "ggx")
GLINTLAB_NDF_KERNELS(Beckmann, Beckmann, "beckmann")
#undef GLINTLAB_NDF_KERNELS

// --- Samplers and their standalone pdfs -----------------------------------------------------
#define GLINTLAB_SAMPLER_KERNEL(Type, Ndf, name, call) \
  struct Type {                                        \
    static constexpr std::string_view kName = name;    \
    static constexpr auto kIn = kInSample;             \
    static constexpr auto kOut = kOutSample;           \
    template <class T>                                 \
    GLINTLAB_FN static void eval(const T* x, T* y) {   \
      const Ndf<T> ndf{x[0], x[1]};                    \
      const Vec3<T> wi = detail::v3(x, 2);             \
      const Vec2<T> u{x[5], x[6]};                     \
      detail::put_sample(y, call);                     \
    }                                                  \
  };
#define GLINTLAB_PDF_KERNEL(Type, Ndf, name, call)                \
  struct Type {                                                   \
    static constexpr std::string_view kName = name;               \
    static constexpr auto kIn = kInWiWo;                          \
    static constexpr auto kOut = kOutValue;                       \
    template <class T>                                            \
    GLINTLAB_FN static void eval(const T* x, T* y) {              \
      const Ndf<T> ndf{x[0], x[1]};                               \
      const Vec3<T> wi = detail::v3(x, 2), wo = detail::v3(x, 5); \
      y[0] = call;                                                \
    }                                                             \
  };

// sample.<name> and pdf.<name> for every row of the sampler list (core/samplers/sampler_list.h).
#define GLINTLAB_SAMPLER_KERNEL_PAIR(A, Type, Ndf, name, ...)                                \
  GLINTLAB_SAMPLER_KERNEL(Sample##Type, Ndf, "sample." name,                                 \
                          samplers::Type::sample(ndf, wi, u))                                \
  GLINTLAB_PDF_KERNEL(Pdf##Type, Ndf, "pdf." name, samplers::Type::pdf(ndf, wi, wo))
GLINTLAB_SAMPLERS(GLINTLAB_SAMPLER_KERNEL_PAIR, )
#undef GLINTLAB_SAMPLER_KERNEL_PAIR

// The densities that are not a sampler's: Eto & Tokuyoshi's Listing 2 as printed and Eq. 7.
GLINTLAB_PDF_KERNEL(PdfBoundedListing2, GGX, "pdf.bounded_vndf_listing2_printed/ggx",
                    pdf_bounded_vndf_listing2(ndf, wi, wo))
GLINTLAB_PDF_KERNEL(PdfBackfacingEq7, GGX, "pdf.vndf_backfacing_eq7/ggx",
                    pdf_vndf_backfacing_eq7(ndf, wi, wo))
GLINTLAB_PDF_KERNEL(PdfBackfacingStable, GGX, "pdf.vndf_backfacing_stable/ggx",
                    pdf_vndf_backfacing_stable(ndf, wi, wo))
#undef GLINTLAB_SAMPLER_KERNEL
#undef GLINTLAB_PDF_KERNEL

// --- Kemppinen 2025 maps T, for both NDFs ----------------------------------------------------
#define GLINTLAB_MAP_KERNELS(Prefix, Ndf, name)                                         \
  struct Prefix##MapToSquare {                                                          \
    static constexpr std::string_view kName = name ".map_to_square";                    \
    static constexpr std::array kIn = {D::kAlphaX, D::kAlphaY, D::kMX, D::kMY, D::kMZ}; \
    static constexpr std::array<std::string_view, 2> kOut = {"p_x", "p_y"};             \
    template <class T>                                                                  \
    GLINTLAB_FN static void eval(const T* x, T* y) {                                    \
      const Vec2<T> p = map_to_square(Ndf<T>{x[0], x[1]}, detail::v3(x, 2));            \
      y[0] = p.x;                                                                       \
      y[1] = p.y;                                                                       \
    }                                                                                   \
  };                                                                                    \
  struct Prefix##MapFromSquare {                                                        \
    static constexpr std::string_view kName = name ".map_from_square";                  \
    static constexpr std::array kIn = {D::kAlphaX, D::kAlphaY, D::kPX, D::kPY};         \
    static constexpr std::array<std::string_view, 3> kOut = {"w_x", "w_y", "w_z"};      \
    template <class T>                                                                  \
    GLINTLAB_FN static void eval(const T* x, T* y) {                                    \
      detail::put3(y, 0, map_from_square(Ndf<T>{x[0], x[1]}, Vec2<T>{x[2], x[3]}));     \
    }                                                                                   \
  };                                                                                    \
  struct Prefix##MapJacobianPaper {                                                     \
    static constexpr std::string_view kName = name ".map_jacobian_paper";               \
    static constexpr auto kIn = kInM;                                                   \
    static constexpr auto kOut = kOutValue;                                             \
    template <class T>                                                                  \
    GLINTLAB_FN static void eval(const T* x, T* y) {                                    \
      y[0] = map_jacobian_paper(Ndf<T>{x[0], x[1]}, detail::v3(x, 2));                  \
    }                                                                                   \
  };                                                                                    \
  struct Prefix##MapJacobianTrue {                                                      \
    static constexpr std::string_view kName = name ".map_jacobian_true";                \
    static constexpr auto kIn = kInM;                                                   \
    static constexpr auto kOut = kOutValue;                                             \
    template <class T>                                                                  \
    GLINTLAB_FN static void eval(const T* x, T* y) {                                    \
      y[0] = map_jacobian_true(Ndf<T>{x[0], x[1]}, detail::v3(x, 2));                   \
    }                                                                                   \
  };

GLINTLAB_MAP_KERNELS(Ggx, GGX, "ggx")
GLINTLAB_MAP_KERNELS(Beckmann, Beckmann, "beckmann")
#undef GLINTLAB_MAP_KERNELS

// --- Kneiphof & Klein 2024 total microfacet area ---------------------------------------------
struct TotalAreaGgx {
  static constexpr std::string_view kName = "ggx.total_area";
  static constexpr std::array kIn = {D::kAlphaX, D::kAlphaY};
  static constexpr auto kOut = kOutValue;
  template <class T>
  GLINTLAB_FN static void eval(const T* x, T* y) {
    y[0] = total_area(GGX<T>{x[0], x[1]});
  }
};
struct TotalAreaBeckmann {
  static constexpr std::string_view kName = "beckmann.total_area";
  static constexpr std::array kIn = {D::kAlphaX, D::kAlphaY};
  static constexpr auto kOut = kOutValue;
  template <class T>
  GLINTLAB_FN static void eval(const T* x, T* y) {
    y[0] = total_area(Beckmann<T>{x[0], x[1]});
  }
};
#define GLINTLAB_ISO_AREA_KERNEL(Type, name, fn)     \
  struct Type {                                      \
    static constexpr std::string_view kName = name;  \
    static constexpr std::array kIn = {D::kAlpha};   \
    static constexpr auto kOut = kOutValue;          \
    template <class T>                               \
    GLINTLAB_FN static void eval(const T* x, T* y) { \
      y[0] = fn(x[0]);                               \
    }                                                \
  };
GLINTLAB_ISO_AREA_KERNEL(TotalAreaGgxEq29, "ggx.total_area_eq29", total_area_ggx_eq29)
GLINTLAB_ISO_AREA_KERNEL(TotalAreaBeckmannEq30, "beckmann.total_area_eq30",
                         total_area_beckmann_eq30)
GLINTLAB_ISO_AREA_KERNEL(TotalAreaBeckmannEq31, "beckmann.total_area_eq31_printed",
                         total_area_beckmann_eq31)
#undef GLINTLAB_ISO_AREA_KERNEL

// The list. X(Type) once per kernel; the batch table, tests and benchmarks expand it. The
// samplers' kernels come from the sampler list: every sample.* kernel, then every pdf.* kernel.
#define GLINTLAB_SAMPLE_KERNEL_OF(X, Type, ...) X(Sample##Type)
#define GLINTLAB_PDF_KERNEL_OF(X, Type, ...) X(Pdf##Type)
// clang-format off
#define GLINTLAB_SIMD_KERNELS(X)                                                                   \
  X(GgxD) X(GgxLambda) X(GgxProjectedArea) X(GgxG1)                                                \
  X(GgxG2HeightCorrelated) X(GgxG2Separable) X(GgxVndf) X(GgxBrdfSchlick) X(GgxBrdfConductor)      \
  X(BeckmannD) X(BeckmannLambda) X(BeckmannProjectedArea) X(BeckmannG1)                            \
  X(BeckmannG2HeightCorrelated) X(BeckmannG2Separable) X(BeckmannVndf)                             \
  X(BeckmannBrdfSchlick) X(BeckmannBrdfConductor)                                                  \
  GLINTLAB_SAMPLERS(GLINTLAB_SAMPLE_KERNEL_OF, X) GLINTLAB_SAMPLERS(GLINTLAB_PDF_KERNEL_OF, X)     \
  X(PdfBoundedListing2)                                                                            \
  X(PdfBackfacingEq7) X(PdfBackfacingStable)                                                       \
  X(GgxMapToSquare) X(GgxMapFromSquare) X(GgxMapJacobianPaper) X(GgxMapJacobianTrue)               \
  X(BeckmannMapToSquare) X(BeckmannMapFromSquare) X(BeckmannMapJacobianPaper)                      \
  X(BeckmannMapJacobianTrue)                                                                       \
  X(TotalAreaGgx) X(TotalAreaBeckmann) X(TotalAreaGgxEq29) X(TotalAreaBeckmannEq30)                \
  X(TotalAreaBeckmannEq31)
// clang-format on

}  // namespace glintlab::simd

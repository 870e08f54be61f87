// The engine choosers of every adequacy family (core/glints/adequacy.h: binomial, Kemppinen;
// core/glints/chermain_chooser.h) compiled once per ISA, each in its own translation unit with that
// ISA's flags (chooser_isa_<isa>.cpp, flags in tests/CMakeLists.txt as core/'s isa_*.cpp units get
// them), on that ISA's double and float batches: chooser_isa_test.cpp runs each one the CPU has on
// the measured tables' cells and compares every lane with the scalar double chooser. The area
// family's chooser (core/glints/area_chooser.h) is scalar only: its binomial step runs here on the
// area table's (N_P, p).
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include "core/glints/chermain.h"
#include "core/model.h"

namespace glintlab::verify::adequacy::isa_test {

// How the lanes are computed: as the library does, or (the test's broken control) with every
// select's arms swapped in the batch's last lane, a lane path that disagrees with the scalar one.
enum class LanePath { kLibrary, kLastLaneSwapped };

// Each function fills out[i], i < n, with the chooser's level for row i (n any count: the last
// batch is padded with the last row). Rows of one call share the model's parameters.
struct ChooserIsaFns {
  // choose_binomial_level(facets, p, tau)
  void (*binomial)(const double* facets, const double* p, const double* tau, double* out,
                   std::size_t n, LanePath path);
  // choose_binomial_level_by_cost with the costs `cost` (ns per evaluation, BinomialLevel order)
  void (*binomial_by_cost)(const double* facets, const double* p, const double* tau,
                           const std::array<double, 4>& cost, double* out, std::size_t n,
                           LanePath path);
  // The model wrappers on the model's parameter values (its kParams order) and the queries:
  // choose_deliot_belcour_level, choose_kneiphof_klein_level, choose_kemppinen_model_level
  // (kemppinen_ggx, kemppinen_beckmann). The Kemppinen chooser has no broken path: its lanes turn
  // MIP levels into integer shifts, which a swapped select would feed out-of-range values (UB).
  void (*deliot_belcour)(std::span<const double> params, const ModelQuery<double>* q,
                         const double* tau, double* out, std::size_t n, LanePath path);
  void (*kneiphof_klein)(std::span<const double> params, const ModelQuery<double>* q,
                         const double* tau, double* out, std::size_t n, LanePath path);
  void (*kemppinen_ggx)(std::span<const double> params, const ModelQuery<double>* q,
                        const double* tau, double* out, std::size_t n);
  void (*kemppinen_beckmann)(std::span<const double> params, const ModelQuery<double>* q,
                             const double* tau, double* out, std::size_t n);
  // choose_chermain_model_level on Chermain::Params (its dictionary and derivatives as built by
  // the caller; they are uniform over a batch).
  void (*chermain)(const chermain2021::SdfParams& sdf, const chermain2021::SlopeDerivatives& d,
                   const ModelQuery<double>* q, const double* tau, double* out, std::size_t n,
                   LanePath path);
  // The choosers for given costs (core/glints/cost_chooser.h) with the costs `cost` (the family's
  // level order): choose_kemppinen_model_level_by_cost (kemppinen_ggx, kemppinen_beckmann),
  // choose_chermain_model_level_by_cost. The Kemppinen ones' broken path swaps the last lane's
  // selects only where the level is composed from the levels' adequacy by cost (their adequacy
  // on the library's lanes, for the reason above).
  void (*kemppinen_ggx_by_cost)(std::span<const double> params, const ModelQuery<double>* q,
                                const double* tau, const std::array<double, 9>& cost,
                                double* out, std::size_t n, LanePath path);
  void (*kemppinen_beckmann_by_cost)(std::span<const double> params, const ModelQuery<double>* q,
                                     const double* tau, const std::array<double, 9>& cost,
                                     double* out, std::size_t n, LanePath path);
  void (*chermain_by_cost)(const chermain2021::SdfParams& sdf,
                           const chermain2021::SlopeDerivatives& d, const ModelQuery<double>* q,
                           const double* tau, const std::array<double, 9>& cost, double* out,
                           std::size_t n, LanePath path);
  std::size_t lanes;  // values per batch (the scalar unit: 1)
};

// An ISA unit's choosers on its double batches (the scalar unit: Wide<double>) and on its float
// batches (the inputs rounded to float and every step of the chooser in float, as a float shader
// runs it; the scalar unit: Wide<float>, on the C library's float functions, the batches on
// xsimd's). The outputs are doubles either way. One getter per unit: its name carries the ISA
// (verify.chooser_isa_objects_share_no_weak_symbols).
struct ChooserIsaUnit {
  ChooserIsaFns f64, f32;
};

// Call an ISA's functions only where isa_supported(isa) (core/simd/batch.h).
ChooserIsaUnit chooser_isa_scalar();
ChooserIsaUnit chooser_isa_sse42();
ChooserIsaUnit chooser_isa_avx2();
ChooserIsaUnit chooser_isa_avx512();

}  // namespace glintlab::verify::adequacy::isa_test

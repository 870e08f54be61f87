// The models of core/model_registry.cpp that get SIMD batch instantiations
// (core/simd/model_batch.h): one type list. Their eval/pdf/sample templates (core/model.h) must
// instantiate on Wide<>.
#pragma once

#include "core/glints/chermain.h"
#include "core/glints/deliot_belcour.h"
#include "core/glints/kneiphof.h"
#include "core/models/kemppinen_beckmann.h"
#include "core/models/kemppinen_ggx.h"
#include "core/models/podee.h"
#include "core/models/smooth_beckmann.h"
#include "core/models/smooth_ggx.h"

namespace glintlab::simd {

template <class... Ms>
struct ModelList {
  static constexpr std::size_t kSize = sizeof...(Ms);
};

// Adding a model = its type here (after its registration line in core/model_registry.cpp): every
// ISA translation unit then instantiates its eval, pdf and sample on that ISA's batches, and the
// model equivalence tests (tests/simd/model_equivalence_test.cpp) and bench_models cover it. A
// registered model that is not listed still works through the batch API, as a scalar loop. A
// model with kDoubleOnly (Chermain) is instantiated on the double batches only, for float columns
// too (core/simd/model_instantiate.h).
using BatchedModels = ModelList<SmoothGGX, SmoothBeckmann, Podee, DeliotBelcour, KneiphofKlein,
                                KemppinenGGX, KemppinenBeckmann, Chermain>;

}  // namespace glintlab::simd

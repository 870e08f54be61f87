// Chermain::eval (core/glints/chermain.h) on one ISA's double batches with parameters the caller
// builds: a Chermain level of the adequacy table (a dictionary of its first L levels, GGAA off or
// on: verify's chermain_level_params) is a dictionary the registered model cannot be handed (its
// dictionary is the default one, not a parameter), so the registry's batch API cannot run it. Each
// ISA's unit (chermain_level_isa_<isa>.cpp, compiled with that ISA's flags as core's isa_*.cpp
// units are: experiments/bench/CMakeLists.txt) runs the model's own eval template on that ISA's
// double batch, as core's batched Chermain does (the scalar unit: plain double). bench_glints.cpp
// times the adequacy/chermain/level=<level>/<isa> rows through them.
#pragma once

#include <cstddef>

#include "core/glints/chermain.h"
#include "core/model.h"

namespace glintlab::bench {

// out[i] = Chermain::eval(p, q[i]).value for i < n (the last batch padded with the last query).
using ChermainLevelEval = void (*)(const Chermain::Params<double>& p, const ModelQuery<double>* q,
                                   double* out, std::size_t n);

// Call an ISA's function only where simd::isa_supported(isa) (core/simd/batch.h).
ChermainLevelEval chermain_level_isa_scalar();
ChermainLevelEval chermain_level_isa_sse42();
ChermainLevelEval chermain_level_isa_avx2();
ChermainLevelEval chermain_level_isa_avx512();

}  // namespace glintlab::bench

// The batch options and the chunked parallel loop; see batch_options.h.
#include "cli/batch_options.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <stdexcept>

#include "cli/commands.h"
#include "cli/input.h"

namespace glintlab::cli {

const char* const kBatchOptionsFooter = R"(
BATCHED EVALUATION (with --model): rows run in structure-of-arrays batches on SIMD instructions
(core/simd/model_batch.h) for the models built for it (every built-in model but
kneiphof_klein_area, and the models of a plug-in built with glintlab_add_model_plugin; any other
model runs row by row in double precision). --isa picks the instruction set (unset: GLINTLAB_ISA
if set, else the widest this CPU has), --precision the float type the model is evaluated in,
--math exact or fast (core/simd/fast_math.h exp/erf/erfc/rsqrt; float only). --threads sets the
worker threads with or without --model; the output is the same for any thread count.
The results of one ISA and precision do not depend on the row's position, the number of rows or
the thread count; between ISAs they agree within the budgets of tests/simd/.)";

void add_batch_options(CLI::App* cmd, BatchOptionTexts& t) {
  add_text_option(cmd, "--isa", t.isa,
                  "with --model: scalar, sse4.2, avx2 or avx512 (unset: GLINTLAB_ISA, else the "
                  "best of this CPU)",
                  "NAME");
  add_text_option(cmd, "--precision", t.precision, "with --model: double or float", "NAME");
  add_text_option(cmd, "--math", t.math, "with --model: exact, or fast (needs --precision float)",
                  "NAME");
  add_threads_option(cmd, t.threads);
}

bool batch_options_given(const CLI::App* cmd) {
  for (const char* name : {"--isa", "--precision", "--math"})
    if (option_count(cmd, name) > 0) return true;
  return false;
}

BatchOptions resolve_batch_options(const BatchOptionTexts& t) {
  BatchOptions o{};
  if (t.isa.empty()) {
    try {
      o.isa = simd::default_isa();
    } catch (const std::invalid_argument& e) {
      throw InputError(e.what());
    }
  } else {
    const auto isa = simd::parse_isa(t.isa);
    if (!isa) {
      throw InputError(
          fmt::format("--isa: unknown ISA '{}' (valid: scalar, sse4.2, avx2, avx512)", t.isa));
    }
    if (!simd::isa_supported(*isa)) {
      throw InputError(
          fmt::format("--isa: '{}' is not supported by this CPU (valid here: up to {})", t.isa,
                      simd::isa_name(simd::best_isa())));
    }
    o.isa = *isa;
  }
  if (t.precision != "double" && t.precision != "float") {
    throw InputError(
        fmt::format("--precision: unknown precision '{}' (valid: double, float)", t.precision));
  }
  o.float_precision = t.precision == "float";
  const auto math = simd::parse_math(t.math);
  if (!math)
    throw InputError(fmt::format("--math: unknown math '{}' (valid: exact, fast)", t.math));
  if (*math == simd::Math::kFast && !o.float_precision) {
    throw InputError("--math: fast needs --precision float (valid with double: exact)");
  }
  o.math = *math;
  o.threads = resolve_threads(t.threads);
  return o;
}

void for_each_chunk(std::size_t n, const BatchOptions& o,
                    const std::function<void(std::size_t begin, std::size_t count)>& f) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(o.threads));
  const std::size_t chunks = (n + kBatchChunk - 1) / kBatchChunk;
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    const std::size_t begin = c * kBatchChunk;
    f(begin, std::min(kBatchChunk, n - begin));
  });
}

}  // namespace glintlab::cli

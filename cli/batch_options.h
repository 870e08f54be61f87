// The batch options of `glintlab eval --model` and `glintlab sample --model` (--isa, --precision,
// --math, --threads) and the chunked parallel loop they run: core/simd/model_batch.h underneath.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "cli/cli11_fwd.h"
#include "core/simd/batch.h"

namespace glintlab::cli {

struct BatchOptionTexts {
  std::string isa, precision = "double", math = "exact";
  std::string threads = "0";
};

struct BatchOptions {
  simd::Isa isa;
  bool float_precision;
  simd::Math math;
  int threads;  // > 0
};

// Adds --isa, --precision, --math (they need --model) and --threads (parallel rows, with or
// without --model) to `cmd`, stored in `t`.
void add_batch_options(CLI::App* cmd, BatchOptionTexts& t);
// Validates them (InputError naming the option and its valid values). --isa defaults to
// GLINTLAB_ISA, else the widest ISA of this CPU.
BatchOptions resolve_batch_options(const BatchOptionTexts& t);
// Whether --isa, --precision or --math was given on the command line (they need --model).
bool batch_options_given(const CLI::App* cmd);

// Rows [0, n) in fixed chunks of kBatchChunk rows, on o.threads worker threads; f(begin, count).
// Chunks are independent and every row's result depends only on its inputs, so the output does
// not depend on the thread count.
inline constexpr std::size_t kBatchChunk = 4096;
void for_each_chunk(std::size_t n, const BatchOptions& o,
                    const std::function<void(std::size_t begin, std::size_t count)>& f);

// The help text of the options (appended to the subcommand footers).
extern const char* const kBatchOptionsFooter;

}  // namespace glintlab::cli

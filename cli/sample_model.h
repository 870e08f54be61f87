// `glintlab sample --model NAME [--param k=v ...] --wi x,y,z --n N`: N samples of a registered
// model's sampler for one ωi, batched (core/simd/model_batch.h).
#pragma once

#include <string>
#include <vector>

#include "cli/batch_options.h"

namespace glintlab::cli {

struct ModelSampleArgs {
  std::string model;
  std::vector<std::string> params;
  std::string wi, n, seed = "0", out;
  std::string query;  // --query: name=value,... of the query columns the model needs
  bool query_given = false;
  BatchOptionTexts batch;
};

void run_model_sample(const ModelSampleArgs& args);

extern const char* const kModelSampleFooter;

}  // namespace glintlab::cli

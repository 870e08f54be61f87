// `glintlab eval --model NAME [--param k=v ...]`: any registered model on CSV query rows or a grid
// of directions, batched (core/simd/model_batch.h).
#pragma once

#include <string>
#include <vector>

#include "cli/batch_options.h"

namespace glintlab::cli {

struct ModelEvalArgs {
  std::string model;
  std::vector<std::string> params;  // the raw "k=v" texts of --param
  std::string in_path;              // --in, or empty with --grid
  std::string grid;                 // --grid, or empty
  std::string out_path;
  BatchOptionTexts batch;
};

void run_model_eval(const ModelEvalArgs& args);

// The help text of the --model form (appended to eval's footer).
extern const char* const kModelEvalFooter;

}  // namespace glintlab::cli

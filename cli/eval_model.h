// `glintlab eval --model NAME [--param k=v ...]`: any registered model on CSV query rows.
#pragma once

#include <string>
#include <vector>

namespace glintlab::cli {

// `params` are the raw "k=v" texts of --param.
void run_model_eval(const std::string& model, const std::vector<std::string>& params,
                    const std::string& in_path, const std::string& out_path);

// The help text of the --model form (appended to eval's footer).
extern const char* const kModelEvalFooter;

}  // namespace glintlab::cli

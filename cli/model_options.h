// The --model and --param options `glintlab eval --model` and `glintlab sample --model` share:
// added to a subcommand, then resolved against the model registry (core/model_registry.h).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "cli/cli11_fwd.h"
#include "core/model_registry.h"

namespace glintlab::cli {

// Adds --model (described by `model_help`) and --param (name=value, repeatable) to `cmd`.
void add_model_options(CLI::App* cmd, std::string& model, std::vector<std::string>& params,
                       const std::string& model_help);

// The (name, value) pairs of --param texts "name=value"; InputError for any other form.
std::vector<std::pair<std::string, std::string>> split_params(
    const std::vector<std::string>& texts);

// The registered model `name` and its parameter values (its defaults, then the --param texts);
// InputError naming --model or --param and the valid values otherwise.
struct ResolvedModel {
  const ModelEntry* model;
  std::vector<double> params;
};
ResolvedModel resolve_model(const std::string& name, const std::vector<std::string>& param_texts);

}  // namespace glintlab::cli

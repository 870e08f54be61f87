// --model and --param of `glintlab eval` and `glintlab sample`; see model_options.h.
#include "cli/model_options.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli/commands.h"

namespace glintlab::cli {

void add_model_options(CLI::App* cmd, std::string& model, std::vector<std::string>& params,
                       const std::string& model_help) {
  cmd->add_option("--model", model, model_help);
  cmd->add_option("--param", params, "With --model: name=value, repeatable")
      ->allow_extra_args(false);
}

std::vector<std::pair<std::string, std::string>> split_params(
    const std::vector<std::string>& texts) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& t : texts) {
    const std::size_t eq = t.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw InputError(
          fmt::format("--param: '{}' is not of the form name=value (see glintlab models)", t));
    }
    out.emplace_back(t.substr(0, eq), t.substr(eq + 1));
  }
  return out;
}

ResolvedModel resolve_model(const std::string& name, const std::vector<std::string>& param_texts) {
  ResolvedModel r{nullptr, {}};
  try {
    r.model = &find_model(name);
    r.params = resolve_params(*r.model, split_params(param_texts));
  } catch (const ModelParamError& e) {
    throw InputError(e.what());
  }
  return r;
}

}  // namespace glintlab::cli

// `glintlab models`: the registered models (core/model_registry.h) with their parameters,
// defaults, valid ranges and the intermediate quantities `eval --model` writes.
#include <fmt/format.h>

#include "cli/commands.h"
#include "cli/input.h"
#include "core/model_registry.h"

namespace glintlab::cli {

void add_models_command(CLI::App& app) {
  CLI::App* cmd = add_command(
      app, "models", "List the registered models, their parameters, defaults and valid ranges");
  set_callback(cmd, [] {
    for (const ModelEntry& m : registered_models()) {
      fmt::print("{}: {}\n  source: {}\n  {}\n", m.name, m.description, m.source,
                 describe_needs(m.needs));
      for (const ParamSpec& p : m.params) {
        fmt::print("  --param {}={}  (valid: {})  {}\n", p.name,
                   format_param_value(p, p.default_value), describe_range(p), p.description);
      }
      fmt::print("  intermediates: {}\n", fmt::join(m.intermediates, ", "));
    }
  });
}

}  // namespace glintlab::cli

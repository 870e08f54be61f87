// `glintlab models`: the registered models (core/model_registry.h) with their parameters,
// defaults, valid ranges, the intermediate quantities `eval --model` writes, and what the
// conformance suite takes from the model's declarations: its smooth limit and each property it
// does not claim, with the reason (the suite's own rule, verify/conformance/conformance.h), so a
// plug-in's author sees that kSmoothLimit and kNotClaimed were read.
#include <fmt/format.h>

#include "cli/commands.h"
#include "cli/input.h"
#include "core/model_registry.h"
#include "verify/conformance/conformance.h"

namespace glintlab::cli {

void add_models_command(CLI::App& app) {
  CLI::App* cmd = add_command(
      app, "models",
      "List the registered models, their parameters, defaults and valid ranges, and what each "
      "declares to the conformance suite (smooth limit, properties not claimed)");
  set_callback(cmd, [] {
    for (const ModelEntry& m : registered_models()) {
      fmt::print("{}: {}\n  source: {}\n  {}\n", m.name, m.description, m.source,
                 describe_needs(m.needs));
      for (const ParamSpec& p : m.params) {
        fmt::print("  --param {}={}  (valid: {})  {}\n", p.name,
                   format_param_value(p, p.default_value), describe_range(p), p.description);
      }
      fmt::print("  intermediates: {}\n", fmt::join(m.intermediates, ", "));
      if (!m.smooth_limit.empty())
        fmt::print("  smooth limit (kSmoothLimit, for converges-to-smooth): {}\n", m.smooth_limit);
      for (std::string_view p : verify::conformance::kProperties) {
        if (!verify::conformance::applies(p, m)) continue;
        if (const auto why = verify::conformance::not_claimed_reason(p, m))
          fmt::print("  not claimed: {}: {}\n", p, *why);
        for (const NotClaimed& n : m.not_claimed)
          if (n.property == p && !n.choice.empty())
            fmt::print("  not claimed for {}: {}: {}\n", n.choice, p, n.reason);
      }
    }
  });
}

}  // namespace glintlab::cli

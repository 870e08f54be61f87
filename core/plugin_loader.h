// Loading model plug-ins (glintlab/plugin.h) into the registry (core/model_registry.h): by path
// (`glintlab --plugin PATH`, repeatable) and from GLINTLAB_PLUGINS (colon-separated paths), before
// any command or benchmark runs. A plug-in stays loaded for the life of the process (its entries'
// code and strings live in it).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace glintlab {

// A plug-in that cannot be used; the message is one line, "<source> <path>: <why>".
struct PluginError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// Loads the plug-in at `path` (dlopen RTLD_NOW | RTLD_LOCAL) and registers each of its models;
// returns their names. `source` names where the path came from in the message ("--plugin",
// "GLINTLAB_PLUGINS:"). Throws PluginError for a path that does not exist or cannot be loaded, a
// file without the entry point, a plug-in built against another glintlab version or ABI, a model
// name already registered, or a not-claimed property that is not a conformance property (no model
// of that plug-in is then registered). Not thread-safe: call it at start-up, as register_model.
std::vector<std::string_view> load_plugin(const std::string& path,
                                          std::string_view source = "--plugin");

// The paths of GLINTLAB_PLUGINS (empty entries skipped; none when unset).
std::vector<std::string> plugin_paths_from_environment();

// Removes the global `--plugin PATH` / `--plugin=PATH` options from argv (argv[1..], up to the
// first other argument when `leading_only`, else anywhere) and returns their paths in order; a
// --plugin without a path throws PluginError.
std::vector<std::string> take_plugin_options(int& argc, char** argv, bool leading_only);

// GLINTLAB_PLUGINS' plug-ins, then the --plugin ones taken from argv (take_plugin_options).
void load_plugins(int& argc, char** argv, bool leading_only);

// The --plugin paths load_plugins loaded, in order: a command that runs glintlab as a child
// process passes them on, so the child knows the same models (GLINTLAB_PLUGINS is inherited).
const std::vector<std::string>& plugin_option_paths();

}  // namespace glintlab

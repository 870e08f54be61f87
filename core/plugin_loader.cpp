// Plug-in loading: dlopen, the entry point of glintlab/plugin.h, version and ABI checks, then
// register_model for each entry.
#include "core/plugin_loader.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/model_registry.h"
#include "glintlab/plugin.h"

namespace glintlab {
namespace {

std::string describe_abi(const plugin::AbiTag& t) {
  return fmt::format(
      "C++ ABI {}, cxx11 strings {}, sizeof ModelEntry {}, ParamSpec {}, ModelQuery {}, "
      "ModelSample {}",
      t.gxx_abi, t.cxx11_string_abi, t.model_entry_size, t.param_spec_size, t.query_size,
      t.sample_size);
}

}  // namespace

std::vector<std::string_view> load_plugin(const std::string& path, std::string_view source) {
  const auto fail = [&](std::string_view why) {
    return PluginError(fmt::format("{} {}: {}", source, path, why));
  };
  std::error_code ec;
  if (path.empty()) throw fail("an empty path (valid: the path of a plug-in module)");
  if (!std::filesystem::exists(path, ec)) {
    throw fail("no such file (valid: the path of a module built with glintlab_add_model_plugin)");
  }
  if (std::filesystem::is_directory(path, ec)) {
    throw fail("is a directory (valid: the path of a module built with glintlab_add_model_plugin)");
  }
  // An absolute path, so dlopen never searches the library path for it.
  const std::string absolute = std::filesystem::absolute(path, ec).string();
  void* handle = dlopen(absolute.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = dlerror();
    throw fail(fmt::format("cannot be loaded ({})", why ? why : "dlopen failed"));
  }
  // From here on the module stays loaded even when refused: an earlier plug-in at the same path
  // shares the handle, and unloading code that may have run static initialisers gains nothing.
  void* symbol = dlsym(handle, GLINTLAB_PLUGIN_ENTRY_POINT);
  if (symbol == nullptr) {
    throw fail("not a glintlab plug-in (no " GLINTLAB_PLUGIN_ENTRY_POINT
               " entry point; build it with glintlab_add_model_plugin and GLINTLAB_PLUGIN)");
  }
  using EntryPoint = const plugin::PluginInfo* (*)();
  const plugin::PluginInfo* info = reinterpret_cast<EntryPoint>(symbol)();
  if (info == nullptr || info->glintlab_version == nullptr) {
    throw fail("its " GLINTLAB_PLUGIN_ENTRY_POINT " returned no plug-in description");
  }
  if (std::strcmp(info->glintlab_version, GLINTLAB_VERSION) != 0) {
    throw fail(fmt::format(
        "built against glintlab {}, this is glintlab {} (rebuild the plug-in against this "
        "installation)",
        info->glintlab_version, GLINTLAB_VERSION));
  }
  if (!(info->abi == plugin::current_abi())) {
    throw fail(fmt::format(
        "built against glintlab {} with another ABI ({}), this glintlab {} has {} (rebuild the "
        "plug-in against this installation with the same compiler)",
        info->glintlab_version, describe_abi(info->abi), GLINTLAB_VERSION,
        describe_abi(plugin::current_abi())));
  }
  std::vector<ModelEntry> entries;
  info->append_models(entries);
  if (entries.empty()) throw fail("registers no model");
  // Every name and not-claimed declaration checked before any is registered, so a refused plug-in
  // leaves the registry as it was.
  for (std::size_t i = 0; i < entries.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (entries[j].name == entries[i].name) {
        throw fail(fmt::format("registers the model name '{}' twice", entries[i].name));
      }
    }
    for (const ModelEntry& loaded : registered_models()) {
      if (loaded.name == entries[i].name) {
        throw fail(fmt::format(
            "model '{}' clashes with a loaded model of the same name (a built-in model or one of "
            "an earlier plug-in; valid: a name 'glintlab models' does not list)",
            entries[i].name));
      }
    }
    try {
      check_not_claimed(entries[i]);
    } catch (const ModelParamError& error) {
      throw fail(error.what());
    }
  }
  std::vector<std::string_view> names;
  for (ModelEntry& e : entries) {
    names.push_back(e.name);
    try {
      register_model(std::move(e));
    } catch (const ModelParamError& error) {
      throw fail(error.what());
    }
  }
  return names;
}

std::vector<std::string> plugin_paths_from_environment() {
  std::vector<std::string> paths;
  const char* env = std::getenv("GLINTLAB_PLUGINS");
  if (env == nullptr) return paths;
  std::string_view rest = env;
  while (!rest.empty()) {
    const std::size_t colon = rest.find(':');
    const std::string_view item = rest.substr(0, colon);
    if (!item.empty()) paths.emplace_back(item);
    if (colon == std::string_view::npos) break;
    rest.remove_prefix(colon + 1);
  }
  return paths;
}

std::vector<std::string> take_plugin_options(int& argc, char** argv, bool leading_only) {
  std::vector<std::string> paths;
  int out = 1;
  bool leading = true;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (leading && arg == "--plugin") {
      if (i + 1 >= argc) {
        throw PluginError("--plugin: needs a value (valid: the path of a plug-in module)");
      }
      paths.emplace_back(argv[++i]);
      continue;
    }
    if (leading && arg.rfind("--plugin=", 0) == 0) {
      paths.emplace_back(arg.substr(9));
      continue;
    }
    if (leading_only) leading = false;
    argv[out++] = argv[i];
  }
  for (int i = out; i < argc; ++i) argv[i] = nullptr;
  argc = out;
  return paths;
}

namespace {
std::vector<std::string>& loaded_option_paths() {
  static std::vector<std::string> paths;
  return paths;
}
}  // namespace

void load_plugins(int& argc, char** argv, bool leading_only) {
  // Both lists are read before anything loads: a --plugin without a value fails first.
  const std::vector<std::string> from_options = take_plugin_options(argc, argv, leading_only);
  for (const std::string& p : plugin_paths_from_environment()) load_plugin(p, "GLINTLAB_PLUGINS:");
  for (const std::string& p : from_options) {
    load_plugin(p, "--plugin");
    loaded_option_paths().push_back(p);
  }
}

const std::vector<std::string>& plugin_option_paths() { return loaded_option_paths(); }

}  // namespace glintlab

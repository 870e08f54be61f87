// glintlab command line: registers the subcommands and turns every failure into one line on
// stderr, "glintlab: error: <message>", with exit code 2. `--help` prints help and exits 0.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "cli/commands.h"
#include "cli/input.h"
#include "cli/schema.h"
#include "core/plugin_loader.h"

namespace {

// Collapses a message onto one line (CLI11 and library messages may contain line breaks).
std::string one_line(std::string_view msg) {
  std::string out;
  bool space = false;
  for (char c : msg) {
    if (c == '\n' || c == '\r' || c == '\t' || c == ' ') {
      space = !out.empty();
      continue;
    }
    if (space) out += ' ';
    space = false;
    out += c;
  }
  return out.empty() ? std::string("unknown error") : out;
}

int fail(std::string_view msg) {
  // A failure caused by a signal's cleanup: let the watcher end the process with the signal.
  glintlab::cli::wait_if_signalled();
  fmt::print(stderr, "glintlab: error: {}\n", one_line(msg));
  std::fflush(stderr);
  return 2;
}

std::string_view after(std::string_view s, std::string_view mark) {
  const std::size_t at = s.find(mark);
  return at == std::string_view::npos ? std::string_view() : s.substr(at + mark.size());
}

// CLI11's own parse errors in the house form: the option, the value and the valid values (the
// option's description, which names them).
std::string translate(const CLI::App* sub, const CLI::ParseError& e) {
  const std::string msg = e.what();
  const std::string see =
      sub ? fmt::format("see glintlab {} --help", sub->get_name()) : "see glintlab --help";
  const auto valid = [&](const std::string& name) -> std::string {
    const CLI::Option* o = sub ? sub->get_option_no_throw(name) : nullptr;
    if (o == nullptr || o->get_description().empty()) return see;
    return o->get_description();
  };
  std::string name = msg.substr(0, std::min(msg.find(':'), msg.find(' ')));
  // Flag errors name the flag without its dashes.
  if (!name.empty() && name[0] != '-' && sub && sub->get_option_no_throw("--" + name))
    name = "--" + name;
  const std::string type = e.get_name();
  if (type == "ConversionError" && msg.rfind("Could not convert: ", 0) == 0) {
    const std::string_view rest = after(msg, "Could not convert: ");
    const std::size_t eq = rest.find(" = ");
    const std::string opt(rest.substr(0, eq));
    const std::string value(eq == std::string_view::npos ? "" : rest.substr(eq + 3));
    return fmt::format("{}: '{}' is not a valid value (valid: {})", opt, value, valid(opt));
  }
  if (msg.find("too many inputs for a flag") != std::string::npos ||
      msg.find("Should be true/false") != std::string::npos ||
      msg.find("disallowed flag override") != std::string::npos) {
    return fmt::format("{}: takes no value (valid: {} alone: {})", name, name, valid(name));
  }
  if (type == "ArgumentMismatch") {
    if (msg.find("At Most") != std::string::npos) {
      return fmt::format("{}: given {} times (valid: once; {})", name,
                         after(msg, "required but received "), valid(name));
    }
    if (msg.find("missing") != std::string::npos)
      return fmt::format("{}: needs a value (valid: {})", name, valid(name));
    return fmt::format("{} (valid: {})", msg, valid(name));
  }
  if (msg.find(" not expected: ") != std::string::npos) {
    std::string extras(after(msg, "expected: "));
    // CLI11's message lists the leftover words last first; the parser keeps them in order.
    std::vector<std::string> words = sub ? sub->remaining() : std::vector<std::string>{};
    std::string first = words.empty() ? extras : words.front();
    if (!words.empty()) extras = fmt::format("{}", fmt::join(words, " "));
    std::string options;
    if (sub) {
      for (const CLI::Option* o : sub->get_options()) {
        if (o->get_name() == "--help" || o->get_name().empty()) continue;
        options += fmt::format("{}{}", options.empty() ? "" : ", ", o->get_name());
      }
    }
    const std::string what = first.size() > 1 && first[0] == '-'
                                 ? fmt::format("unknown option '{}'", first)
                                 : fmt::format("unexpected argument '{}'", extras);
    return fmt::format("{}: {} (valid: {}; {})", sub ? sub->get_name() : "glintlab", what,
                       options.empty() ? "no arguments" : "the options " + options, see);
  }
  if (type == "ValidationError") return fmt::format("{} (valid: {})", msg, valid(name));
  if (type == "RequiredError" && msg.size() > 12 &&
      msg.compare(msg.size() - 12, 12, " is required") == 0) {
    const std::string opt = msg.substr(0, msg.size() - 12);
    return fmt::format("{} is required (valid: {})", opt, valid(opt));
  }
  return fmt::format("{} ({})", msg, see);
}

}  // namespace

int main(int argc, char** argv) {
  // Before any thread starts: SIGINT/SIGTERM remove staging folders, then end the process.
  glintlab::cli::install_signal_cleanup();
  CLI::App app{
      "glintlab: microfacet and glint models from the papers, with statistical checks of their "
      "claims.\nDirections are in the local shading frame: x tangent, y bitangent, z the normal.",
      "glintlab"};
  app.require_subcommand(1);
  app.footer(
      "Model plug-ins (docs/adding_a_model.md): 'glintlab --plugin PATH <subcommand> ...' "
      "(repeatable, before the subcommand) and GLINTLAB_PLUGINS=PATH[:PATH...] load modules built "
      "with glintlab_add_model_plugin; their models then work like the built-in ones.\n"
      "Run 'glintlab <subcommand> --help' for the options and output columns of each.\n"
      "Errors print one line, 'glintlab: error: <message>', and exit with code 2; a failed "
      "run writes no output file.");

  try {
    // Plug-ins register their models before any subcommand is set up or run, so every command
    // (and its --help) sees them; the --plugin options leave argv here.
    glintlab::load_plugins(argc, argv, /*leading_only=*/true);

    glintlab::cli::add_eval_command(app);
    glintlab::cli::add_sample_command(app);
    glintlab::cli::add_verify_command(app);
    glintlab::cli::add_figure_command(app);
    glintlab::cli::add_models_command(app);
    glintlab::cli::add_sweep_command(app);
    glintlab::cli::add_report_command(app);
    glintlab::cli::add_ltc_fit_command(app);
    glintlab::cli::add_chermain_dictionary_command(app);
    glintlab::cli::add_adequacy_command(app);
    glintlab::cli::add_compare_command(app);
    glintlab::cli::add_merge_command(app);
    glintlab::cli::add_schema_command(app);

    // No subcommand, or a first argument that is neither an option nor a subcommand: say so and
    // name the valid set.
    std::string names;
    bool known = false;
    const std::string_view first = argc > 1 ? argv[1] : "";
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
      if (sub->get_name() == first) known = true;
      names += names.empty() ? "" : ", ";
      names += sub->get_name();
    }
    if (argc <= 1) {
      return fail(fmt::format("a subcommand is required (valid: {}; see glintlab --help)", names));
    }
    if (first[0] != '-' && !known) {
      return fail(
          fmt::format("unknown subcommand '{}' (valid: {}; see glintlab --help)", first, names));
    }
    if (first[0] == '-' && first != "-h" && first != "--help") {
      // A subcommand's option placed before it (`glintlab --threads 2 verify`): name where it
      // goes when the subcommand further on the line takes it.
      const std::string option(first.substr(0, first.find('=')));
      const std::vector<CLI::App*> subs = app.get_subcommands([](const CLI::App*) { return true; });
      for (int i = 2; i < argc; ++i) {
        const auto sub = std::find_if(subs.begin(), subs.end(),
                                      [&](const CLI::App* s) { return s->get_name() == argv[i]; });
        if (sub == subs.end()) continue;
        if (option.size() > 2 && option[1] == '-' && (*sub)->get_option_no_throw(option) != nullptr)
          return fail(fmt::format("{} goes after the subcommand (valid: glintlab {} {} ...)",
                                  option, (*sub)->get_name(), option));
        break;
      }
      return fail(fmt::format(
          "unknown option '{}' before the subcommand (valid: --help, --plugin PATH, or a "
          "subcommand: {})",
          first, names));
    }

    // A global option placed after the subcommand: CLI11 would report it as an unexpected
    // argument of the subcommand; name it and where it goes instead.
    for (int i = 2; i < argc; ++i) {
      const std::string_view arg = argv[i];
      if (arg != "--plugin" && arg.rfind("--plugin=", 0) != 0) continue;
      const std::string_view path = arg != "--plugin" ? arg.substr(9)
                                    : i + 1 < argc    ? std::string_view(argv[i + 1])
                                                      : std::string_view("PATH");
      return fail(fmt::format(
          "--plugin goes before the subcommand (valid: glintlab --plugin {} {} ...)", path, first));
    }

    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    // A subcommand that ran and chose its own exit status (verify: a control not rejected); it
    // has already printed its one-line message.
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    // --help (and --help-all) are ParseErrors with exit code 0: print the help and succeed.
    if (e.get_exit_code() == 0) return app.exit(e);
    const CLI::App* sub = nullptr;
    for (const CLI::App* s : app.get_subcommands([](const CLI::App*) { return true; }))
      if (argc > 1 && s->get_name() == argv[1]) sub = s;
    return fail(translate(sub, e));
  } catch (const glintlab::cli::InputError& e) {
    return fail(e.what());
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  glintlab::cli::wait_if_signalled();
  return 0;
}

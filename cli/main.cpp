// glintlab command line: registers the subcommands and turns every failure into one line on
// stderr, "glintlab: error: <message>", with exit code 2. `--help` prints help and exits 0.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>

#include "cli/commands.h"

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
  fmt::print(stderr, "glintlab: error: {}\n", one_line(msg));
  std::fflush(stderr);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "glintlab: microfacet and glint models from the papers, with statistical checks of their "
      "claims.\nDirections are in the local shading frame: x tangent, y bitangent, z the normal.",
      "glintlab"};
  app.require_subcommand(1);
  app.footer(
      "Run 'glintlab <subcommand> --help' for the options and output columns of each.\n"
      "Errors print one line, 'glintlab: error: <message>', and exit with code 2; a failed "
      "run writes no output file.");

  try {
    glintlab::cli::add_eval_command(app);
    glintlab::cli::add_sample_command(app);
    glintlab::cli::add_verify_command(app);
    glintlab::cli::add_figure_command(app);
    glintlab::cli::add_models_command(app);
    glintlab::cli::add_sweep_command(app);
    glintlab::cli::add_report_command(app);
    glintlab::cli::add_ltc_fit_command(app);
    glintlab::cli::add_chermain_dictionary_command(app);

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
      return fail(fmt::format(
          "unknown option '{}' before the subcommand (valid: --help, or a subcommand: {})", first,
          names));
    }

    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    // A subcommand that ran and chose its own exit status (verify: a control not rejected); it
    // has already printed its one-line message.
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    // --help (and --help-all) are ParseErrors with exit code 0: print the help and succeed.
    if (e.get_exit_code() == 0) return app.exit(e);
    return fail(e.what());
  } catch (const glintlab::cli::InputError& e) {
    return fail(e.what());
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  return 0;
}

// The subcommands of the `glintlab` executable; main.cpp registers each on the CLI11 app.
#pragma once

#include <stdexcept>
#include <string>

#include "cli/cli11_fwd.h"

namespace glintlab::cli {

// Bad input from the user (a value out of range, a malformed row, a missing file). main() prints
// it as one line, "glintlab: error: <message>", and exits with code 2. The message names the
// parameter (and row, for CSV input) and its valid range.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void add_eval_command(CLI::App& app);                 // cli/eval.cpp
void add_sample_command(CLI::App& app);               // cli/sample.cpp
void add_verify_command(CLI::App& app);               // cli/verify.cpp
void add_figure_command(CLI::App& app);               // cli/figure.cpp
void add_models_command(CLI::App& app);               // cli/models.cpp
void add_sweep_command(CLI::App& app);                // cli/sweep.cpp
void add_report_command(CLI::App& app);               // cli/report.cpp
void add_ltc_fit_command(CLI::App& app);              // cli/ltc_fit.cpp
void add_chermain_dictionary_command(CLI::App& app);  // cli/chermain_dictionary.cpp
void add_adequacy_command(CLI::App& app);             // cli/adequacy.cpp
void add_compare_command(CLI::App& app);              // cli/compare.cpp
void add_merge_command(CLI::App& app);                // cli/merge.cpp

}  // namespace glintlab::cli

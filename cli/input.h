// What every subcommand shares about its options and input: one way to register an option (so
// every --help shows TYPE=DEFAULT the same way), the budget and thread options, comma-separated
// lists and globs, and the checks on output paths made before any long work starts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "cli/cli11_fwd.h"

namespace glintlab::cli {

// The subcommand plumbing the commands share, so that their units need CLI11's types by name
// only (cli/cli11_fwd.h). add_command: a subcommand of `app`; set_footer: the text after its
// option list in --help; set_callback: what runs when it was given; option_count: how often
// `option` was given to `cmd`; set_required: `option` must be given; exit_with_code: ends the run
// through CLI11's error path with exit code `code` (no message).
CLI::App* add_command(CLI::App& app, const std::string& name, const std::string& description);
void set_footer(CLI::App* cmd, const std::string& footer);
void set_callback(CLI::App* cmd, std::function<void()> run);
std::size_t option_count(const CLI::App* cmd, const std::string& option);
void set_required(CLI::Option* option);
[[noreturn]] void exit_with_code(int code);

// A string option stored in `var`. `type` is the help's placeholder (INT, NUMBER, LIST, DIR,
// FILE, NAME, ...); when `var` is not empty it is the default and the help shows TYPE=DEFAULT.
// The description names the valid values; defaults are never repeated in it. Values are parsed
// and checked by the subcommand, so every bad value gets the house error.
CLI::Option* add_text_option(CLI::App* cmd, const std::string& name, std::string& var,
                             const std::string& description, const std::string& type);
// A flag: given or not; `--flag=VALUE` is an error.
CLI::Option* add_bool_flag(CLI::App* cmd, const std::string& name, bool& var,
                           const std::string& description);
// Positional arguments (a name without dashes), any number of them, stored in `var`.
CLI::Option* add_positional_list(CLI::App* cmd, const std::string& name,
                                 std::vector<std::string>& var, const std::string& description,
                                 const std::string& type);

// --budget quick|full, plus the old flag --quick as an alias (prints one note naming
// `--budget quick` and then behaves exactly as it).
struct BudgetOption {
  std::string budget = "quick";
  bool quick_alias = false;
};
void add_budget_option(CLI::App* cmd, BudgetOption& b, const std::string& description);
// "quick" or "full"; InputError otherwise (or when --quick contradicts --budget full).
std::string resolve_budget(const CLI::App* cmd, const BudgetOption& b);

// --threads N: worker threads, 0 = all cores.
inline constexpr std::string_view kThreadsHelp =
    "worker threads: an integer in [0, 1024], 0 = all cores; the output does not depend on it";
void add_threads_option(CLI::App* cmd, std::string& var);
// The thread count to use (> 0); InputError naming --threads otherwise.
int resolve_threads(std::string_view text);

// A non-negative integer option's value in [lo, hi] (parse_integer, with the option's name).
std::uint64_t integer_option(std::string_view text, std::string_view option, std::uint64_t lo,
                             std::uint64_t hi);
// A finite number in the interval given by lo/hi (open ends with lo_open/hi_open).
double number_option(std::string_view text, std::string_view option, double lo, double hi,
                     bool lo_open, bool hi_open);

// The items of a comma-separated list, spaces around each trimmed. An empty list or an empty
// item is an InputError naming the option and `valid`.
std::vector<std::string> split_list(std::string_view text, std::string_view option,
                                    std::string_view valid);
// The names (in their order) matched by any of the globs (fnmatch) of the list `text`. Every
// glob must match at least one name: the ones that match nothing are named in the InputError,
// with `see` (where to find the valid names).
std::vector<std::string> select_by_globs(std::string_view text, std::string_view option,
                                         const std::vector<std::string>& names,
                                         std::string_view see);

// Checks, before any long work, that the folder `dir` can be created (or exists) and takes new
// entries, by creating and removing one probe entry in the nearest existing ancestor. Creates
// nothing that stays. InputError naming `option` otherwise.
void check_output_dir(const std::filesystem::path& dir, std::string_view option);
// The same for the folder that will hold the file `file` (and `file` is not a folder).
void check_output_file(const std::filesystem::path& file, std::string_view option);
// Refuses (InputError naming `option`) an output of about `bytes` bytes when the file system of
// `path` (or its nearest existing ancestor) has less space free.
void check_free_space(const std::filesystem::path& path, std::uint64_t bytes,
                      std::string_view option);

// SIGINT and SIGTERM: a watcher thread removes this process's staging entries (names ending in
// ".tmp.<pid>") in every folder registered here, then the process dies of the signal as it
// would have. install_signal_cleanup() must run in main() before any other thread starts.
void install_signal_cleanup();
void register_staging_parent(const std::filesystem::path& dir);
// The child process a signal is passed on to (0: none).
void set_signal_child(int pid);
// Once a signal arrived, blocks forever (the watcher ends the process); else returns at once.
void wait_if_signalled();

}  // namespace glintlab::cli

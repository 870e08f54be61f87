// Shared option registration and input checks; see input.h.
#include "cli/input.h"

#include <fmt/format.h>
#include <fnmatch.h>
#include <pthread.h>
#include <signal.h>
#include <sys/statvfs.h>
#include <tbb/info.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <thread>

#include "cli/args.h"
#include "cli/commands.h"
#include "core/io/csv.h"

namespace glintlab::cli {

namespace fs = std::filesystem;

CLI::App* add_command(CLI::App& app, const std::string& name, const std::string& description) {
  return app.add_subcommand(name, description);
}

void set_footer(CLI::App* cmd, const std::string& footer) { cmd->footer(footer); }

void set_callback(CLI::App* cmd, std::function<void()> run) { cmd->callback(std::move(run)); }

std::size_t option_count(const CLI::App* cmd, const std::string& option) {
  return cmd->count(option);
}

void set_required(CLI::Option* option) { option->required(); }

void exit_with_code(int code) { throw CLI::RuntimeError(code); }

CLI::Option* add_positional_list(CLI::App* cmd, const std::string& name,
                                 std::vector<std::string>& var, const std::string& description,
                                 const std::string& type) {
  return cmd->add_option(name, var, description)->type_name(type);
}

CLI::Option* add_text_option(CLI::App* cmd, const std::string& name, std::string& var,
                             const std::string& description, const std::string& type) {
  CLI::Option* o = cmd->add_option(name, var, description)->type_name(type);
  if (!var.empty()) o->default_str(var);
  // An explicit empty value is never a choice (it would silently mean "not given").
  o->check(CLI::Validator(
      [](std::string& v) { return v.empty() ? std::string("'' is empty") : std::string(); }, ""));
  return o;
}

CLI::Option* add_bool_flag(CLI::App* cmd, const std::string& name, bool& var,
                           const std::string& description) {
  return cmd->add_flag(name, var, description)->disable_flag_override();
}

void add_budget_option(CLI::App* cmd, BudgetOption& b, const std::string& description) {
  add_text_option(cmd, "--budget", b.budget, "quick or full: " + description, "NAME");
  add_bool_flag(cmd, "--quick", b.quick_alias, "old spelling of --budget quick");
}

std::string resolve_budget(const CLI::App* cmd, const BudgetOption& b) {
  if (b.budget != "quick" && b.budget != "full") {
    std::string text = b.budget;
    for (char& c : text)
      if (static_cast<unsigned char>(c) < 0x20) c = '?';
    throw InputError(fmt::format("--budget: '{}' is not a budget (valid: quick, full)", text));
  }
  if (!b.quick_alias) return b.budget;
  if (cmd->count("--budget") > 0 && b.budget != "quick") {
    throw InputError(fmt::format(
        "--quick: contradicts --budget {} (valid: one of --budget quick, --budget full)",
        b.budget));
  }
  fmt::print(stderr, "glintlab: note: --quick is spelled --budget quick\n");
  return "quick";
}

void add_threads_option(CLI::App* cmd, std::string& var) {
  if (var.empty()) var = "0";
  add_text_option(cmd, "--threads", var, std::string(kThreadsHelp), "INT");
}

int resolve_threads(std::string_view text) {
  const auto n = int(parse_integer(text, "--threads", 0, 1024));
  return n > 0 ? n : tbb::info::default_concurrency();
}

std::uint64_t integer_option(std::string_view text, std::string_view option, std::uint64_t lo,
                             std::uint64_t hi) {
  return parse_integer(text, option, lo, hi);
}

double number_option(std::string_view text, std::string_view option, double lo, double hi,
                     bool lo_open, bool hi_open) {
  const std::string valid = fmt::format("a finite number in {}{}, {}{}", lo_open ? "(" : "[", lo,
                                        hi, hi_open ? ")" : "]");
  const double v = parse_number(text, option, valid);
  if (!((lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi))) {
    throw InputError(fmt::format("{}: {} is out of range (valid: {})", option, v, valid));
  }
  return v;
}

namespace {

// User text in a message: at most 40 characters, control characters as '?'.
std::string shown(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 40)) out += static_cast<unsigned char>(c) < 0x20 ? '?' : c;
  return s.size() > 40 ? out + "..." : out;
}

}  // namespace

std::vector<std::string> split_list(std::string_view text, std::string_view option,
                                    std::string_view valid) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::size_t end = comma == std::string_view::npos ? text.size() : comma;
    std::string_view item = text.substr(start, end - start);
    while (!item.empty() && (item.front() == ' ' || item.front() == '\t')) item.remove_prefix(1);
    while (!item.empty() && (item.back() == ' ' || item.back() == '\t')) item.remove_suffix(1);
    if (item.empty()) {
      throw InputError(fmt::format("{}: '{}' {} (valid: {})", option, shown(text),
                                   comma == std::string_view::npos && items.empty()
                                       ? "is an empty list"
                                       : "has an empty item",
                                   valid));
    }
    items.emplace_back(item);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return items;
}

std::vector<std::string> select_by_globs(std::string_view text, std::string_view option,
                                         const std::vector<std::string>& names,
                                         std::string_view see) {
  const std::vector<std::string> globs =
      split_list(text, option, fmt::format("comma-separated globs over {}", see));
  std::vector<bool> used(globs.size(), false);
  std::vector<std::string> out;
  for (const std::string& name : names) {
    bool take = false;
    for (std::size_t g = 0; g < globs.size(); ++g) {
      if (fnmatch(globs[g].c_str(), name.c_str(), 0) == 0) {
        used[g] = true;
        take = true;
      }
    }
    if (take) out.push_back(name);
  }
  std::string unmatched;
  for (std::size_t g = 0; g < globs.size(); ++g) {
    if (!used[g])
      unmatched += fmt::format("{}'{}'", unmatched.empty() ? "" : ", ", shown(globs[g]));
  }
  if (!unmatched.empty()) {
    throw InputError(fmt::format("{}: {} match{} nothing (valid: comma-separated globs over {})",
                                 option, unmatched,
                                 unmatched.find(',') == std::string::npos ? "es" : "", see));
  }
  return out;
}

namespace {

// The nearest ancestor of `p` (or `p` itself) that exists.
fs::path existing_ancestor(const fs::path& p) {
  std::error_code ec;
  fs::path a = fs::absolute(p, ec);
  if (ec) a = p;
  while (!fs::exists(a, ec) && a.has_relative_path()) a = a.parent_path();
  return a;
}

}  // namespace

void check_output_dir(const fs::path& dir, std::string_view option) {
  std::error_code ec;
  if (dir.empty()) throw InputError(fmt::format("{}: empty path (valid: a folder)", option));
  const fs::path a = existing_ancestor(dir);
  if (!fs::is_directory(a, ec)) {
    throw InputError(
        fmt::format("{}: cannot create the folder '{}': '{}' is not a folder "
                    "(valid: a folder that can be created or written)",
                    option, dir.string(), a.string()));
  }
  const fs::path probe = a / fmt::format(".glintlab-probe.tmp.{}", ::getpid());
  if (!fs::create_directory(probe, ec) || ec) {
    throw InputError(fmt::format(
        "{}: cannot write into '{}' ({}) (valid: a folder that can be created or written)", option,
        a.string(), ec ? ec.message() : "cannot create an entry"));
  }
  fs::remove(probe, ec);
}

void check_output_file(const fs::path& file, std::string_view option) {
  std::error_code ec;
  if (file.empty()) throw InputError(fmt::format("{}: empty path (valid: a file name)", option));
  if (fs::is_directory(file, ec)) {
    throw InputError(
        fmt::format("{}: '{}' is a folder (valid: a file name)", option, file.string()));
  }
  check_output_dir(file.has_parent_path() ? file.parent_path() : fs::path("."), option);
}

void check_free_space(const fs::path& path, std::uint64_t bytes, std::string_view option) {
  const fs::path a = existing_ancestor(path);
  struct statvfs s {};
  if (::statvfs(a.c_str(), &s) != 0) return;  // unknown: the write itself reports a full disk
  const std::uint64_t free = std::uint64_t(s.f_bavail) * std::uint64_t(s.f_frsize);
  if (bytes > free) {
    throw InputError(fmt::format(
        "{}: the output would take about {:.3g} GB but '{}' has {:.3g} GB free (valid: an output "
        "that fits; fewer rows)",
        option, double(bytes) / 1e9, a.string(), double(free) / 1e9));
  }
}

namespace {

std::mutex g_mutex;
std::vector<fs::path> g_staging_parents;
std::atomic<int> g_child{0};
std::atomic<bool> g_signalled{false};

void remove_staging() {
  const std::string suffix = fmt::format(".tmp.{}", ::getpid());
  const std::lock_guard<std::mutex> lock(g_mutex);
  for (const fs::path& dir : g_staging_parents) {
    std::error_code ec;
    std::vector<fs::path> doomed;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      if (name.size() > suffix.size() &&
          name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
        doomed.push_back(it->path());
    }
    for (const fs::path& p : doomed) fs::remove_all(p, ec);
  }
}

void watch_signals(sigset_t set) {
  int sig = 0;
  while (sigwait(&set, &sig) != 0) {
  }
  g_signalled.store(true);
  if (const int child = g_child.load(); child > 0) ::kill(child, sig);
  remove_staging();
  // Die of the signal, as the process would have without the watcher.
  ::signal(sig, SIG_DFL);
  sigset_t one;
  sigemptyset(&one);
  sigaddset(&one, sig);
  pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
  ::raise(sig);
  ::_exit(128 + sig);
}

}  // namespace

void install_signal_cleanup() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::thread(watch_signals, set).detach();
}

void register_staging_parent(const fs::path& dir) {
  std::error_code ec;
  const fs::path abs = fs::absolute(dir.empty() ? fs::path(".") : dir, ec);
  const std::lock_guard<std::mutex> lock(g_mutex);
  g_staging_parents.push_back(ec ? dir : abs);
}

void set_signal_child(int pid) { g_child.store(pid); }

void wait_if_signalled() {
  while (g_signalled.load()) ::pause();
}

}  // namespace glintlab::cli

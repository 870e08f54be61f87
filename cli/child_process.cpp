#include "cli/child_process.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cli/commands.h"
#include "cli/input.h"

extern char** environ;

namespace glintlab::cli {
namespace {
namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

fs::path self_exe() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec)
    throw std::runtime_error("cannot locate the glintlab executable (/proc/self/exe)");
  return p;
}

// The folder of the report scripts: $GLINTLAB_REPORTS_DIR, else <prefix>/share/glintlab/reports
// beside an installed executable (the scripts installed with it, whatever became of the source tree
// it was built from), else the source tree's reports/ (a program run from its build tree).
fs::path reports_dir() {
  if (const char* env = std::getenv("GLINTLAB_REPORTS_DIR"); env && *env) return env;
  std::error_code ec;
  const fs::path installed =
      self_exe().parent_path().parent_path() / "share" / "glintlab" / "reports";
  if (fs::exists(installed / "make_report.py", ec)) return installed;
  const fs::path src = GLINTLAB_REPORTS_SOURCE_DIR;
  if (fs::exists(src / "make_report.py", ec)) return src;
  return installed;
}

// Runs argv with stdout to `out_file` and stderr to `err_file` (empty: inherited, so a child's
// progress shows on the terminal); returns its exit status (128 + signal when killed).
int run_process(const std::vector<std::string>& args, const fs::path& out_file,
                const fs::path& err_file) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, out_file.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (!err_file.empty()) {
    posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, err_file.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  // The child gets SIGINT and SIGTERM unblocked (this process blocks them for its watcher).
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &fa, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) throw std::runtime_error(fmt::format("cannot run {}", args[0]));
  set_signal_child(pid);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
  }
  set_signal_child(0);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}


// The last non-empty line a child wrote to stderr, without a "glintlab: error: " prefix.
std::string last_error_line(const fs::path& err_file) {
  std::string last;
  std::istringstream in(read_text(err_file));
  for (std::string line; std::getline(in, line);) {
    const auto cr = line.rfind('\r');
    if (cr != std::string::npos) line = line.substr(cr + 1);
    if (!line.empty()) last = line;
  }
  const std::string prefix = "glintlab: error: ";
  if (last.rfind(prefix, 0) == 0) last = last.substr(prefix.size());
  return last.empty() ? "no message" : last;
}

void draw_figure_charts(const fs::path& dir) { draw_folders_charts({dir}, {}); }

void draw_folders_charts(const std::vector<fs::path>& dirs, const fs::path& root) {
  std::error_code ec;
  const std::string suffix = ".chart.json";
  std::vector<std::string> args;
  for (const fs::path& dir : dirs) {
    bool any = false;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      const std::string name = e.path().filename().string();
      any = any || (name.size() > suffix.size() &&
                    name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0);
    }
    if (any) args.insert(args.end(), {"--dir", dir.string()});
  }
  if (args.empty()) return;  // no chart: no Python
  const fs::path script = reports_dir() / "figure_charts.py";
  if (!fs::is_regular_file(script, ec))
    throw InputError(fmt::format(
        "charts: {} not found (set GLINTLAB_REPORTS_DIR to the reports/ folder)", script.string()));
  // The script's output beside the root (or the one folder), removed after.
  const fs::path beside = root.empty() ? dirs.front() : root;
  const fs::path base =
      beside.parent_path() / fmt::format("{}.charts", beside.filename().string());
  const fs::path out = fmt::format("{}.out.tmp.{}", base.string(), ::getpid());
  const fs::path err = fmt::format("{}.err.tmp.{}", base.string(), ::getpid());
  struct Remove {
    fs::path a, b;
    ~Remove() {
      std::error_code e;
      fs::remove(a, e);
      fs::remove(b, e);
    }
  } remove{out, err};
  args.insert(args.begin(), {"/usr/bin/python3", script.string()});
  if (!root.empty()) args.insert(args.end(), {"--root", root.string()});
  const int rc = run_process(args, out, err);
  if (rc != 0) throw InputError(last_error_line(err));
}

}  // namespace glintlab::cli

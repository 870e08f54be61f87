// SIGINT and SIGTERM during a long run remove the run's staging folders (".NAME.tmp.PID"), and
// the process still ends by the signal.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;

// Entries under `dir` (recursively) whose name contains ".tmp.".
std::vector<std::string> staging_entries(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().filename().string().find(".tmp.") != std::string::npos)
      out.push_back(fs::relative(it->path(), dir).generic_string());
  }
  return out;
}

using SignalCleanupTest = CliTest;

// Starts glintlab with `args` in work(), waits until a staging entry exists, sends `sig`.
void interrupt(const fs::path& work, const std::vector<std::string>& args, int sig) {
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (::chdir(work.c_str()) != 0) ::_exit(126);
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    std::vector<char*> argv;
    std::vector<std::string> all = {"glintlab"};
    all.insert(all.end(), args.begin(), args.end());
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(kGlintlabExe, argv.data());
    ::_exit(127);
  }
  // Whether a staging entry was seen, as the loop saw it: a second listing can miss it, since
  // the directory walk stops at an entry the run renames or removes meanwhile.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool staged = !staging_entries(work).empty();
  while (!staged && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    staged = !staging_entries(work).empty();
  }
  // Let it write a little into the staging folder first.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(pid, sig);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(staged) << "no staging folder appeared within 60 s";
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig)
      << "the process did not end by signal " << sig << " (status " << status << ")";
  EXPECT_EQ(staging_entries(work), std::vector<std::string>{})
      << "staging left after signal " << sig;
}

TEST_F(SignalCleanupTest, FigureRemovesItsStagingFolderOnSigintAndSigterm) {
  for (const int sig : {SIGINT, SIGTERM}) {
    interrupt(work(),
              {"figure", "eto2023-fig4", "--budget", "full", "--threads", "1", "--out", "out"},
              sig);
  }
}

TEST_F(SignalCleanupTest, ReportRemovesItsStagingFolderOnSigint) {
  interrupt(work(),
            {"report", "--skip", "claims,conformance,bench,stability", "--figures", "eto2023-fig4", "--budget",
             "full", "--threads", "1", "--out", "r"},
            SIGINT);
}

}  // namespace
}  // namespace glintlab::cli_test

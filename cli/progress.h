// Progress for long runs: "done/total, rate, ETA" on one updating line when stderr is a terminal,
// nothing when it is a pipe or a file (so logs and CI stay clean).
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

#include <fmt/format.h>

namespace glintlab::cli {

class Progress {
 public:
  Progress(std::string what, long total)
      : what_(std::move(what)), total_(total), tty_(::isatty(STDERR_FILENO) == 1),
        start_(std::chrono::steady_clock::now()) {}
  ~Progress() {
    if (tty_ && shown_) fmt::print(stderr, "\n");
  }

  // Call after each finished item; `label` names what finished.
  void step(const std::string& label) {
    ++done_;
    if (!tty_) return;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double rate = s > 0 ? static_cast<double>(done_) / s : 0;
    const double eta = rate > 0 ? static_cast<double>(total_ - done_) / rate : 0;
    fmt::print(stderr, "\r\033[K{} {}/{} ({:.2f}/s, ETA {:.0f} s) {}", what_, done_, total_, rate, eta,
               label);
    std::fflush(stderr);
    shown_ = true;
  }

 private:
  std::string what_;
  long total_;
  long done_ = 0;
  bool tty_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace glintlab::cli

// Running other programs from a subcommand (report's children, the report scripts of reports/):
// where this executable and the scripts are, a child process with its output in files, and the
// one line a failed child left on stderr.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace glintlab::cli {

// This executable (/proc/self/exe).
std::filesystem::path self_exe();
// The folder of the report scripts: $GLINTLAB_REPORTS_DIR, else the source tree's reports/, else
// <prefix>/share/glintlab/reports beside an installed executable.
std::filesystem::path reports_dir();
// Runs argv with stdout to `out_file` and stderr to `err_file` (empty: inherited, so a child's
// progress shows on the terminal); returns its exit status (128 + signal when killed). SIGINT and
// SIGTERM reach the child (set_signal_child).
int run_process(const std::vector<std::string>& args, const std::filesystem::path& out_file,
                const std::filesystem::path& err_file);
// The last non-empty line a child wrote to stderr, without a "glintlab: error: " prefix.
std::string last_error_line(const std::filesystem::path& err_file);

// Draws the charts of a figure's folder (every NAME.chart.json into NAME.png) with
// reports/figure_charts.py under /usr/bin/python3; its output goes to files beside `dir` that
// end in ".tmp.<pid>" (removed after, and by the signal cleanup). A failure throws InputError
// with the script's one line.
void draw_figure_charts(const std::filesystem::path& dir);
// The same for several folders in one run of the script (one Python start: glintlab sweep's
// targets); a failing spec is named by its path below `root` (empty: by its file name), and a
// failure leaves none of the PNGs drawn.
void draw_folders_charts(const std::vector<std::filesystem::path>& dirs,
                         const std::filesystem::path& root);

}  // namespace glintlab::cli

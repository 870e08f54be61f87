// Helpers for the CLI tests; see cli_test_util.h.
#include "cli/cli_test_util.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

namespace glintlab::cli_test {
namespace fs = std::filesystem;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  if (!out) ADD_FAILURE() << "cannot write test file " << path;
}

double cell_value(const io::CsvTable& table, std::size_t row, std::size_t col) {
  const std::string_view t = table.text(row, col);
  if (t == "nan" || t == "-nan") return std::numeric_limits<double>::quiet_NaN();
  if (t == "inf") return std::numeric_limits<double>::infinity();
  if (t == "-inf") return -std::numeric_limits<double>::infinity();
  return table.number(row, col);
}

bool same_value(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

std::vector<std::string> unexpected_files(const fs::path& dir,
                                          const std::set<std::string>& expected) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string rel = fs::relative(e.path(), dir).generic_string();
    if (!expected.count(rel)) found.push_back(rel);
  }
  std::sort(found.begin(), found.end());
  return found;
}

namespace {

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') {
      q += "'\\''";
    } else {
      q += c;
    }
  }
  return q + "'";
}

}  // namespace

void CliTest::SetUp() {
  static std::atomic<int> counter{0};
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string(info->test_suite_name()) + "_" + info->name();
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  root_ = fs::temp_directory_path() / ("glintlab_cli_" + std::to_string(::getpid()) + "_" +
                                       std::to_string(counter++) + "_" + name);
  fs::remove_all(root_);
  work_ = root_ / "work";
  capture_ = root_ / "capture";
  fs::create_directories(work_);
  fs::create_directories(capture_);
}

void CliTest::TearDown() {
  std::error_code ec;
  fs::remove_all(root_, ec);
}

RunResult CliTest::run(const std::vector<std::string>& args) const {
  std::string cmd = "cd " + shell_quote(work_.string()) + " && ";
  if (!reports_.empty()) cmd += "GLINTLAB_REPORTS_DIR=" + shell_quote(reports_.string()) + " ";
  cmd += shell_quote(kGlintlabExe);
  for (const std::string& a : args) cmd += " " + shell_quote(a);
  const fs::path out = capture_ / "stdout", err = capture_ / "stderr";
  cmd += " >" + shell_quote(out.string()) + " 2>" + shell_quote(err.string()) + " </dev/null";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  r.out = read_text(out);
  r.err = read_text(err);
  return r;
}

void CliTest::stand_in_charts() {
  reports_ = root_ / "stand_in_chart_reports";
  fs::create_directories(reports_);
  write_text(reports_ / "figure_charts.py",
             "import glob, os, sys\na = sys.argv\n"
             "for i, d in enumerate(a):\n"
             "    if i and a[i - 1] == '--dir':\n"
             "        for spec in sorted(glob.glob(os.path.join(d, '*.chart.json'))):\n"
             "            text = open(spec, 'rb').read()\n"
             "            csv = text.split(b'\"csv\": \"')[1].split(b'\"')[0].decode()\n"
             "            text += open(os.path.join(d, csv), 'rb').read()\n"
             "            open(spec[:-len('.chart.json')] + '.png', 'wb').write(text)\n");
  // compare's page (reports/compare_page.py --dir DIR) is drawn from DIR/compare.json alone.
  write_text(reports_ / "compare_page.py",
             "import os, sys\nd = sys.argv[sys.argv.index('--dir') + 1]\n"
             "text = open(os.path.join(d, 'compare.json'), 'rb').read()\n"
             "for page in ('equal_time.png', 'index.html'):\n"
             "    open(os.path.join(d, page), 'wb').write(text)\n");
}

void CliTest::expect_input_error(const RunResult& r, const std::vector<std::string>& needles,
                                 const std::set<std::string>& expected_files) const {
  EXPECT_EQ(r.exit_code, 2) << "stderr: " << r.err;
  EXPECT_EQ(r.out, "");
  const std::vector<std::string> lines = lines_of(r.err);
  ASSERT_EQ(lines.size(), 1u) << "stderr: " << r.err;
  EXPECT_EQ(r.err.back(), '\n');
  const std::string prefix = "glintlab: error: ";
  ASSERT_EQ(lines[0].rfind(prefix, 0), 0u) << lines[0];
  const std::string msg = lines[0].substr(prefix.size());
  for (const std::string& n : needles) {
    EXPECT_NE(msg.find(n), std::string::npos) << "message lacks '" << n << "': " << msg;
  }
  EXPECT_EQ(unexpected_files(work_, expected_files), std::vector<std::string>{})
      << "a failed run left files behind";
}


std::string level_costs_json(const std::vector<std::string>& models,
                             const std::array<double, 4>& ns, const std::string& skip) {
  nlohmann::json rows = nlohmann::json::array();
  const char* level[] = {"smooth", "realtime", "small_count", "exact"};
  for (const std::string& model : models)
    for (const char* isa : {"scalar", "sse4.2", "avx2", "avx512"})
      for (std::size_t l = 0; l < 4; ++l) {
        const std::string name = "adequacy/" + model + "/level=" + level[l] + "/" + isa;
        if (!skip.empty() && name.find(skip) != std::string::npos) continue;
        rows.push_back({{"name", name}, {"run_name", name}, {"run_type", "iteration"},
                        {"real_time", 1e6}, {"time_unit", "ns"},
                        {"items_per_second", 1e9 / ns[l]}});
      }
  return nlohmann::json{{"context", nlohmann::json::object()}, {"benchmarks", rows}}.dump(1);
}


std::map<std::string, std::string> CliTest::file_tree(const std::string& dir) const {
  std::map<std::string, std::string> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(path(dir)))
    if (e.is_regular_file())
      files[std::filesystem::relative(e.path(), path(dir)).string()] = read_text(e.path());
  return files;
}

std::set<std::string> CliTest::work_paths() const {
  std::set<std::string> paths;
  for (const auto& e : std::filesystem::recursive_directory_iterator(work_))
    paths.insert(std::filesystem::relative(e.path(), work_).string());
  return paths;
}

}  // namespace glintlab::cli_test

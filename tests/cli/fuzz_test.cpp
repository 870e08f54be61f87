// Deterministic mutation fuzzing of what reads user input: the CSV reader, the environment-map EXR
// reader, --grid and --param, and the claim and model globs. Mutations come from a fixed seed, so
// a failure reproduces; each target runs a fixed number of inputs (never a time budget, so what is
// tested does not depend on the machine's load). Every input must end in a clean outcome: accepted
// with every number finite, or rejected with the one-line error (in process: the reader's own
// exception type) and no file left behind. A crash fails the test.
#include <fnmatch.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "cli/cli_test_util.h"
#include "core/io/csv.h"
#include "core/io/environment_exr.h"
#include "core/io/exr.h"
#include "core/render/image.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
// Tokens that break parsers: non-finite and huge numbers, separators, quotes, control bytes.
const std::vector<std::string> kTokens = {
    "nan", "-nan", "inf", "-inf", "1e308", "1e400", "-0",   "0",  "1e-400", "99999999999999999999",
    "",    ",",    ",,",  ":",    "=",     "\n",    "\r",   "\"", " ",      "\t",
    "*",   "?",    "[",   "]",    "-",     "+",     "0x10", "1.", ".5",     "e5"};

class Mutator {
 public:
  explicit Mutator(std::uint64_t seed) : rng_(seed) {}

  std::string mutate(std::string s) {
    const int edits = 1 + int(pick(3));
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = s.empty() ? 0 : pick(s.size() + 1);
      switch (pick(7)) {
        case 0:  // flip a bit
          if (!s.empty()) s[std::min(at, s.size() - 1)] ^= char(1u << pick(8));
          break;
        case 1:  // a random byte
          s.insert(s.begin() + std::ptrdiff_t(at), char(pick(256)));
          break;
        case 2: {  // delete a range
          if (s.empty()) break;
          const std::size_t from = std::min(at, s.size() - 1);
          s.erase(from, 1 + pick(std::min<std::size_t>(8, s.size() - from)));
          break;
        }
        case 3: {  // duplicate a range
          if (s.empty()) break;
          const std::size_t from = std::min(at, s.size() - 1);
          s.insert(from, s.substr(from, 1 + pick(8)));
          break;
        }
        case 4:  // insert a token
          s.insert(at, kTokens[pick(kTokens.size())]);
          break;
        case 5: {  // replace a number-like run by a token
          std::size_t b = std::min(at, s.size()), e2 = b;
          while (e2 < s.size() &&
                 (std::isalnum(static_cast<unsigned char>(s[e2])) || s[e2] == '.' || s[e2] == '-'))
            ++e2;
          s.replace(b, e2 - b, kTokens[pick(kTokens.size())]);
          break;
        }
        default:  // truncate
          s.resize(std::min(at, s.size()));
          break;
      }
    }
    return s;
  }

  std::size_t pick(std::size_t n) { return n == 0 ? 0 : std::size_t(rng_() % n); }

 private:
  std::mt19937_64 rng_;
};

// Runs `body(i)` for i = 0 .. max_inputs-1, stopping at the first failure.
template <class F>
void fuzz_loop(int max_inputs, F body) {
  for (int i = 0; i < max_inputs && !::testing::Test::HasFailure(); ++i) body(i);
}

// The input for a failure message, bytes outside printable ASCII as \xNN.
std::string printable(const std::string& s) {
  static const char* kDigits = "0123456789abcdef";
  std::string out;
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u >= 0x7f) {
      out += std::string("\\x") + kDigits[u >> 4] + kDigits[u & 15];
    } else {
      out += c;
    }
  }
  return out;
}

// --- The CSV reader, in process ------------------------------------------------------------------

TEST(FuzzCsvReader, MutatedTablesParseOrFailCleanlyAndNeverYieldNonFiniteNumbers) {
  const std::vector<std::string> seeds = {
      "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\nggx,0.3,0.3,0,0.6,0.8,0.6,0,0.8\n",
      "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,u,v\n0,0,1,0,0,1,0.5,0.5\r\n0.6,0,0.8,0,0.6,0.8,1e-3,2\n",
      "\xEF\xBB\xBF"
      "a,b\n1,2\n3,4\n"};
  Mutator m(0x5eed0001);
  fuzz_loop(4000, [&](int i) {
    const std::string text = m.mutate(seeds[std::size_t(i) % seeds.size()]);
    try {
      const io::CsvTable t = io::parse_csv(text, "fuzz.csv");
      for (std::size_t r = 0; r < t.num_rows(); ++r) {
        for (std::size_t c = 0; c < t.header().size(); ++c) {
          try {
            const double v = t.number(r, c);
            ASSERT_TRUE(std::isfinite(v)) << "non-finite number accepted from " << printable(text);
          } catch (const io::CsvError& e) {
            ASSERT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
          }
        }
      }
    } catch (const io::CsvError& e) {
      ASSERT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  });
}

// --- The environment-map EXR reader, in process ------------------------------------------------

TEST(FuzzEnvironmentExr, MutatedFilesLoadWithFiniteRadianceOrFailWithExrError) {
  const fs::path dir =
      fs::temp_directory_path() / ("glintlab_fuzz_exr_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Image im(16, 8, {"R", "G", "B"});
  for (std::size_t k = 0; k < im.data.size(); ++k) im.data[k] = 0.25 + double(k % 7) * 0.125;
  io::write_exr(dir / "seed.exr", im, {{"note", "fuzz seed"}});
  const std::string seed = read_text(dir / "seed.exr");
  ASSERT_GT(seed.size(), 100u);
  Mutator m(0x5eed0002);
  fuzz_loop(600, [&](int) {
    std::string bytes = seed;
    // Mostly small corruptions anywhere (header and data), sometimes the generic mutations.
    if (m.pick(4) == 0) {
      bytes = m.mutate(bytes);
    } else {
      const int flips = 1 + int(m.pick(4));
      for (int f = 0; f < flips; ++f) bytes[m.pick(bytes.size())] ^= char(1u << m.pick(8));
    }
    const fs::path p = dir / "fuzz.exr";
    write_text(p, bytes);
    try {
      const EnvironmentMap env = io::load_environment_map(p);
      for (float v : env.image().rgb) {
        ASSERT_TRUE(std::isfinite(v) && v >= 0) << "radiance " << v << " accepted";
      }
    } catch (const io::ExrError& e) {
      ASSERT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  });
  std::error_code ec;
  fs::remove_all(dir, ec);
}

// --- --grid and --param through the executable, against an independent statement of the rules --

using FuzzCli = CliTest;

// The error line's message, or "" when the run did not end in exactly one house error line.
std::string one_error(const RunResult& r) {
  const std::vector<std::string> lines = lines_of(r.err);
  if (r.exit_code != 2 || lines.size() != 1 || lines[0].rfind("glintlab: error: ", 0) != 0)
    return "";
  return lines[0].substr(17);
}

std::vector<std::string> items_of(const std::string& text, bool& ok) {
  std::vector<std::string> items;
  std::string cur;
  ok = true;
  const auto flush = [&] {
    std::size_t a = cur.find_first_not_of(" \t"), b = cur.find_last_not_of(" \t");
    std::string t = a == std::string::npos ? "" : cur.substr(a, b - a + 1);
    if (t.empty()) ok = false;
    items.push_back(t);
    cur.clear();
  };
  for (char c : text) {
    if (c == ',') {
      flush();
    } else {
      cur += c;
    }
  }
  flush();
  return items;
}

bool is_count(const std::string& t, std::uint64_t& v) {
  if (t.empty() || t.size() > 19) return false;
  v = 0;
  for (char c : t) {
    if (c < '0' || c > '9') return false;
    v = v * 10 + std::uint64_t(c - '0');
  }
  return v >= 1 && v <= 10000;
}

// Whether the grid text is valid by the documented rules (eval --help).
bool grid_valid(const std::string& text) {
  bool ok = true;
  const std::vector<std::string> items = items_of(text, ok);
  if (!ok) return false;
  std::set<std::string> seen;
  std::uint64_t rows = 1;
  for (const std::string& it : items) {
    const std::size_t eq = it.find('=');
    if (eq == std::string::npos) return false;
    const std::string name = it.substr(0, eq), range = it.substr(eq + 1);
    if (name != "theta_i" && name != "phi_i" && name != "theta_o" && name != "phi_o") return false;
    if (!seen.insert(name).second) return false;
    const std::size_t c1 = range.find(':');
    if (c1 == std::string::npos) return false;
    const std::size_t c2 = range.find(':', c1 + 1);
    if (c2 == std::string::npos) return false;
    const auto lo = io::parse_finite_double(range.substr(0, c1));
    const auto hi = io::parse_finite_double(range.substr(c1 + 1, c2 - c1 - 1));
    std::uint64_t count = 0;
    if (!lo || !hi || !is_count(range.substr(c2 + 1), count)) return false;
    if (name[0] == 't' && !(*lo >= 0 && *lo <= 180 && *hi >= 0 && *hi <= 180)) return false;
    rows *= count;
  }
  return rows <= 100000000;
}

TEST_F(FuzzCli, GridTextIsAcceptedExactlyWhenValid) {
  // --out under a file: a grid that parses is then refused for --out, before any row is computed,
  // so only the parser's verdict is observed.
  write_text(path("blocker"), "x");
  const std::vector<std::string> seeds = {"theta_i=0:90:3", "theta_i=0:90:3,phi_i=0:360:4",
                                          "theta_o=10:170:5, phi_o=-30:30:2",
                                          "phi_i=0:1:10000,theta_i=0:180:10000"};
  Mutator m(0x5eed0003);
  int accepted = 0;
  fuzz_loop(150, [&](int i) {
    std::string g = m.mutate(seeds[std::size_t(i) % seeds.size()]);
    g.erase(std::remove(g.begin(), g.end(), '\0'), g.end());
    if (!g.empty() && g[0] == '-') g.insert(0, "x");  // an argument, not an option
    const RunResult r =
        run({"eval", "--model", "smooth_ggx", "--grid", g, "--out", "blocker/r.csv"});
    const std::string msg = one_error(r);
    ASSERT_FALSE(msg.empty()) << "grid " << printable(g) << ": exit " << r.exit_code << ", "
                              << r.err;
    if (grid_valid(g)) {
      ++accepted;
      EXPECT_EQ(msg.rfind("--out", 0), 0u) << "valid grid " << printable(g) << " refused: " << msg;
    } else {
      EXPECT_EQ(msg.rfind("--grid", 0), 0u) << "invalid grid " << printable(g) << ": " << msg;
    }
    EXPECT_EQ(unexpected_files(work(), {"blocker"}), std::vector<std::string>{});
  });
  EXPECT_GT(accepted, 0) << "no mutated grid was valid: the mutations are too coarse";
}

TEST_F(FuzzCli, ParamTextIsAcceptedExactlyWhenValid) {
  write_text(path("blocker"), "x");
  const std::vector<std::string> seeds = {"alpha_x=0.3", "alpha_y=100", "alpha_x=1e-3"};
  Mutator m(0x5eed0004);
  int accepted = 0;
  fuzz_loop(150, [&](int i) {
    std::string p = m.mutate(seeds[std::size_t(i) % seeds.size()]);
    p.erase(std::remove(p.begin(), p.end(), '\0'), p.end());
    if (!p.empty() && p[0] == '-') p.insert(0, "x");
    const RunResult r = run({"eval", "--model", "smooth_ggx", "--param", p, "--grid",
                             "theta_i=0:90:2", "--out", "blocker/r.csv"});
    const std::string msg = one_error(r);
    ASSERT_FALSE(msg.empty()) << "param " << printable(p) << ": exit " << r.exit_code << ", "
                              << r.err;
    const std::size_t eq = p.find('=');
    bool valid = false;
    if (eq != std::string::npos) {
      const std::string name = p.substr(0, eq);
      const auto v = io::parse_finite_double(p.substr(eq + 1));
      valid = (name == "alpha_x" || name == "alpha_y") && v && *v > 0 && *v <= 100;
    }
    if (valid) {
      ++accepted;
      EXPECT_EQ(msg.rfind("--out", 0), 0u) << "valid param " << printable(p) << " refused: " << msg;
    } else {
      EXPECT_EQ(msg.rfind("--param", 0), 0u) << "invalid param " << printable(p) << ": " << msg;
    }
  });
  EXPECT_GT(accepted, 0);
}

// --- eval on mutated CSV through the executable: an accepted table gives finite numbers only ----

TEST_F(FuzzCli, EvalOnMutatedCsvWritesOnlyFiniteNumbersOrNothing) {
  const std::string seed =
      "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n"
      "ggx,0.3,0.3,0,0.6,0.8,0.6,0,0.8\nbeckmann,0.5,0.2,0.6,0,0.8,0,0,1\n";
  Mutator m(0x5eed0005);
  int accepted = 0;
  fuzz_loop(120, [&](int) {
    write_text(path("q.csv"), m.mutate(seed));
    const RunResult r = run({"eval", "--in", "q.csv", "--out", "r.csv"});
    if (r.exit_code == 0) {
      ++accepted;
      const io::CsvTable t = io::read_csv(path("r.csv"));
      const std::size_t ndf = t.column("ndf");
      // The GGX-only samplers' pdf columns are 'nan' for beckmann by definition.
      const auto ggx_only = [&](std::size_t c) {
        return t.header()[c] == "pdf_spherical_caps" ||
               t.header()[c].starts_with("pdf_bounded_caps");
      };
      for (std::size_t row = 0; row < t.num_rows(); ++row)
        for (std::size_t c = 1; c < t.header().size(); ++c) {
          if (ggx_only(c) && t.text(row, ndf) == "beckmann") continue;
          ASSERT_NO_THROW((void)t.number(row, c))
              << "row " << row << " column " << t.header()[c] << ": " << t.text(row, c)
              << " from input " << printable(read_text(path("q.csv")));
        }
      fs::remove(path("r.csv"));
    } else {
      ASSERT_FALSE(one_error(r).empty()) << "exit " << r.exit_code << ": " << r.err;
      EXPECT_EQ(unexpected_files(work(), {"q.csv"}), std::vector<std::string>{});
    }
  });
  EXPECT_GT(accepted, 0);
}

// --- claim and model globs -----------------------------------------------------------------------

std::vector<std::string> first_words(const std::string& text, char end) {
  std::vector<std::string> out;
  for (const std::string& line : lines_of(text)) {
    if (line.empty() || line[0] == ' ') continue;
    const std::size_t e = line.find(end);
    out.push_back(line.substr(0, e));
  }
  return out;
}

// The names the globs of `text` select, or an empty optional when the list is invalid (an empty
// item, or a glob that matches nothing).
std::optional<std::vector<std::string>> selected(const std::string& text,
                                                 const std::vector<std::string>& names) {
  bool ok = true;
  const std::vector<std::string> globs = items_of(text, ok);
  if (!ok) return std::nullopt;
  std::vector<std::string> out;
  std::vector<bool> used(globs.size(), false);
  for (const std::string& n : names) {
    bool take = false;
    for (std::size_t g = 0; g < globs.size(); ++g)
      if (fnmatch(globs[g].c_str(), n.c_str(), 0) == 0) used[g] = take = true;
    if (take) out.push_back(n);
  }
  for (bool u : used)
    if (!u) return std::nullopt;
  return out;
}

TEST_F(FuzzCli, ClaimGlobsSelectExactlyTheMatchingClaimsOrFailNamingThem) {
  const RunResult all = run({"verify", "--list"});
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const std::vector<std::string> ids = first_words(all.out, ' ');
  ASSERT_GT(ids.size(), 10u);
  const std::vector<std::string> seeds = {"eto.*", "eto.bound-is-infimum,smooth.*", "*.stability",
                                          "kneiphof.*, podee.*", "[ek]*"};
  Mutator m(0x5eed0006);
  int accepted = 0;
  fuzz_loop(150, [&](int i) {
    std::string g = m.mutate(seeds[std::size_t(i) % seeds.size()]);
    g.erase(std::remove(g.begin(), g.end(), '\0'), g.end());
    if (!g.empty() && g[0] == '-') g.insert(0, "x");
    const RunResult r = run({"verify", "--list", "--claims", g});
    const auto want = selected(g, ids);
    if (want) {
      ++accepted;
      ASSERT_EQ(r.exit_code, 0) << "globs " << printable(g) << ": " << r.err;
      EXPECT_EQ(first_words(r.out, ' '), *want) << "globs " << printable(g);
    } else {
      EXPECT_EQ(one_error(r).rfind("--claims", 0), 0u) << "globs " << printable(g) << ": " << r.err;
    }
  });
  EXPECT_GT(accepted, 0);
}

TEST_F(FuzzCli, ModelGlobsAreCheckedBeforeAnySweep) {
  const RunResult all = run({"models"});
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const std::vector<std::string> names = first_words(all.out, ':');
  ASSERT_GT(names.size(), 2u);
  write_text(path("blocker"), "x");
  const std::vector<std::string> seeds = {"smooth_*", "smooth_ggx,podee", "*glints*", "[sp]*"};
  Mutator m(0x5eed0007);
  int accepted = 0;
  fuzz_loop(150, [&](int i) {
    std::string g = m.mutate(seeds[std::size_t(i) % seeds.size()]);
    g.erase(std::remove(g.begin(), g.end(), '\0'), g.end());
    if (!g.empty() && g[0] == '-') g.insert(0, "x");
    // --out under a file: valid globs are then refused for --out, before any plane is swept.
    const RunResult r =
        run({"sweep", "--budget", "quick", "--models", g, "--out", "blocker/s", "--threads", "1"});
    const std::string msg = one_error(r);
    ASSERT_FALSE(msg.empty()) << "globs " << printable(g) << ": exit " << r.exit_code << ", "
                              << r.err;
    if (selected(g, names)) {
      ++accepted;
      EXPECT_EQ(msg.rfind("--out", 0), 0u) << "valid globs " << printable(g) << ": " << msg;
    } else {
      EXPECT_EQ(msg.rfind("--models", 0), 0u) << "globs " << printable(g) << ": " << msg;
    }
    EXPECT_EQ(unexpected_files(work(), {"blocker"}), std::vector<std::string>{});
  });
  EXPECT_GT(accepted, 0);
}

}  // namespace
}  // namespace glintlab::cli_test

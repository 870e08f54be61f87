// docs/adding_a_model.md against the program it documents: its member table has a row for every
// member core/model.h lists for a model (kSmoothLimit and kNotClaimed included), the valid
// not-claimed property names it gives are the program's list (kConformanceProperties) in its
// order, its example of a misspelled property is the line glintlab prints for one, and its
// `eval --grid --query` example (run on the example plug-in, the same model as the guide's
// my_glints) gives the rows and the error it shows. So the guide a plug-in author follows cannot go
// stale when a member, a property or the grid's columns change.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "cli/build_paths.h"
#include "cli/cli_test_util.h"
#include "core/model.h"

namespace glintlab::cli_test {
namespace {

std::filesystem::path source_dir() {
  // kReportFixtures is <source>/tests/reports/fixtures.
  return std::filesystem::path(kReportFixtures).parent_path().parent_path().parent_path();
}

bool is_ident(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// The members core/model.h's opening comment lists for a model, required and optional: on each
// entry line ("//   NAME ...", continuation lines are indented further) its first identifier and
// every other kName-style identifier (the line "kName, kDescription, kSource" names three).
std::vector<std::string> listed_members(const std::string& model_h) {
  std::vector<std::string> names;
  bool in_block = false;
  for (const std::string& line : lines_of(model_h)) {
    if (line.rfind("// A model is a struct", 0) == 0) in_block = true;
    if (!in_block) continue;
    if (line.rfind("// params<T> reads", 0) == 0) break;
    if (line.size() < 6 || line.rfind("//   ", 0) != 0 || line[5] == ' ') continue;
    const auto add = [&](std::string name) {
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    };
    std::size_t end = 5;
    while (end < line.size() && is_ident(line[end])) ++end;
    add(line.substr(5, end - 5));
    for (std::size_t i = end; i + 1 < line.size(); ++i) {
      if (line[i] == 'k' && std::isupper(static_cast<unsigned char>(line[i + 1])) &&
          !is_ident(line[i - 1])) {
        std::size_t j = i;
        while (j < line.size() && is_ident(line[j])) ++j;
        add(line.substr(i, j - i));
        i = j;
      }
    }
  }
  return names;
}

// The first cells of the guide's member table (the table whose header is "| member |").
std::vector<std::string> member_cells(const std::string& guide) {
  std::vector<std::string> cells;
  bool in_table = false;
  for (const std::string& line : lines_of(guide)) {
    if (line.rfind("| member |", 0) == 0) {
      in_table = true;
      continue;
    }
    if (!in_table) continue;
    if (line.rfind("|", 0) != 0) break;
    if (line.rfind("|---", 0) == 0) continue;
    cells.push_back(line.substr(1, line.find('|', 1) - 1));
  }
  return cells;
}

// What the guide's member table misses of `members`: each must open a `code span` of a row's
// first cell ("`kNotClaimed`", "`eval<T>(...)`").
std::vector<std::string> undocumented_members(const std::string& guide,
                                              const std::vector<std::string>& members) {
  const std::vector<std::string> cells = member_cells(guide);
  std::vector<std::string> missing;
  for (const std::string& m : members) {
    bool found = false;
    for (const std::string& cell : cells) {
      for (std::size_t at = cell.find("`" + m); at != std::string::npos && !found;
           at = cell.find("`" + m, at + 1)) {
        const std::size_t after = at + 1 + m.size();
        found = after >= cell.size() || !is_ident(cell[after]);
      }
    }
    if (!found) missing.push_back(m);
  }
  return missing;
}

// The property names the kNotClaimed row gives as valid: the code spans after "Valid names
// (...):" up to the sentence's ";". Empty when the row or the phrase is missing.
std::vector<std::string> documented_properties(const std::string& guide) {
  for (const std::string& line : lines_of(guide)) {
    if (line.rfind("| `kNotClaimed`", 0) != 0) continue;
    std::size_t at = line.find("Valid names");
    if (at == std::string::npos) return {};
    at = line.find("):", at);
    if (at == std::string::npos) return {};
    const std::string list = line.substr(at + 2, line.find(';', at) - at - 2);
    std::vector<std::string> names;
    for (std::size_t open = list.find('`'); open != std::string::npos;) {
      const std::size_t close = list.find('`', open + 1);
      if (close == std::string::npos) break;
      names.push_back(list.substr(open + 1, close - open - 1));
      open = list.find('`', close + 1);
    }
    return names;
  }
  return {};
}

std::vector<std::string> program_properties() {
  return {kConformanceProperties.begin(), kConformanceProperties.end()};
}

// The part of a line from `from` to its end, or "" when `text` has no line holding `from`.
std::string line_tail(const std::string& text, const std::string& from) {
  for (const std::string& line : lines_of(text)) {
    const std::size_t at = line.find(from);
    if (at != std::string::npos) return line.substr(at);
  }
  return "";
}

std::string guide() { return read_text(source_dir() / "docs" / "adding_a_model.md"); }
std::string model_h() { return read_text(source_dir() / "core" / "model.h"); }

TEST(AddingAModelDoc, MemberTableHasEveryMemberOfTheModelInterface) {
  const std::vector<std::string> members = listed_members(model_h());
  // The list is read, not empty: the required members and the optional ones the guide must name.
  for (const char* m : {"kName", "kSource", "kNeeds", "kParams", "kIntermediates", "sample",
                        "validate", "kDoubleOnly", "kBatched", "kSmoothLimit", "kNotClaimed"})
    EXPECT_NE(std::find(members.begin(), members.end(), m), members.end())
        << m << " not read from core/model.h's list of members";
  EXPECT_EQ(undocumented_members(guide(), members), std::vector<std::string>{})
      << "docs/adding_a_model.md's member table lacks these members of core/model.h";
}

// A guide whose table lacks a row, or names a member only as the prefix of another, is caught.
TEST(AddingAModelDoc, MemberTableCheckFindsAMissingRow) {
  const std::string table =
      "| member | what it is |\n|---|---|\n| `kNotClaimed` (optional) | x |\n"
      "| `eval<T>(Params, ModelQuery)` | y |\n\nafter the table: `kSmoothLimit`\n";
  EXPECT_EQ(undocumented_members(table, {"kNotClaimed", "eval"}), std::vector<std::string>{});
  EXPECT_EQ(undocumented_members(table, {"kNotClaimed", "kSmoothLimit", "eval", "kNot"}),
            (std::vector<std::string>{"kSmoothLimit", "kNot"}));
}

TEST(AddingAModelDoc, ValidPropertyNamesAreTheProgramsList) {
  EXPECT_EQ(documented_properties(guide()), program_properties())
      << "docs/adding_a_model.md's kNotClaimed row: the valid names differ from "
         "kConformanceProperties (core/model.h)";
}

// A list with a property left out, renamed or not given at all differs from the program's.
TEST(AddingAModelDoc, PropertyListCheckFindsAStaleList) {
  std::string row = "| `kNotClaimed` (optional) | ... Valid names (`kConformanceProperties`): ";
  std::string all = row, dropped = row, renamed = row;
  for (std::string_view p : kConformanceProperties) {
    all += "`" + std::string(p) + "`, ";
    if (p != "energy") dropped += "`" + std::string(p) + "`, ";
    renamed += "`" + std::string(p == "energy" ? "energy-gain" : p) + "`, ";
  }
  for (std::string* r : {&all, &dropped, &renamed}) *r += "; any other name refuses it |\n";
  EXPECT_EQ(documented_properties(all), program_properties());
  EXPECT_NE(documented_properties(dropped), program_properties());
  EXPECT_NE(documented_properties(renamed), program_properties());
  EXPECT_EQ(documented_properties("| `kNotClaimed` (optional) | no list here |"),
            std::vector<std::string>{});
}

class AddingAModelDocCli : public CliTest {};

// The guide's example line for a misspelled not-claimed property is what glintlab prints for one
// (tests/plugin/misspelled_not_claimed_plugin.cpp declares 'enrgy'), from the model's name on.
TEST_F(AddingAModelDocCli, MisspelledPropertyExampleIsTheProgramsLine) {
  const RunResult r = run({"--plugin", kTestPluginMisspelledNotClaimed, "models"});
  ASSERT_EQ(r.exit_code, 2) << r.err;
  const std::string from = "declares 'enrgy' not claimed";
  const std::string printed = line_tail(r.err, from);
  ASSERT_FALSE(printed.empty()) << r.err;
  EXPECT_EQ(line_tail(guide(), from), printed)
      << "docs/adding_a_model.md (A4) shows another line than glintlab prints";
}

// The words of the guide's ```sh command that starts with `start` and contains `needle` (lines
// joined at their trailing backslash, single quotes removed, the part before any "&&").
std::vector<std::string> doc_command(const std::string& text, const std::string& start,
                                     const std::string& needle) {
  std::string joined;
  bool in_sh = false;
  for (const std::string& line : lines_of(text)) {
    if (line == "```sh") {
      in_sh = true;
      joined.clear();
      continue;
    }
    if (!in_sh) continue;
    if (line == "```") {
      in_sh = false;
      continue;
    }
    joined += line;
    if (!joined.empty() && joined.back() == '\\') {
      joined.pop_back();
      continue;
    }
    if (joined.rfind(start, 0) == 0 && joined.find(needle) != std::string::npos) {
      const std::string command = joined.substr(0, joined.find("&&"));
      std::vector<std::string> words;
      std::string word;
      for (char c : command + " ") {
        if (c == ' ') {
          if (!word.empty()) words.push_back(word);
          word.clear();
        } else if (c != '\'') {
          word += c;
        }
      }
      return words;
    }
    joined.clear();
  }
  return {};
}

// The ```text block of the guide whose first line is `first` (its lines, that one included).
std::vector<std::string> doc_block(const std::string& text, const std::string& first) {
  std::vector<std::string> block;
  bool in = false, fresh = false;
  for (const std::string& line : lines_of(text)) {
    if (line == "```text") {
      fresh = true;
      continue;
    }
    if (fresh && line == first) in = true;
    fresh = false;
    if (!in) continue;
    if (line == "```") break;
    block.push_back(line);
  }
  return block;
}

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> cells(1);
  for (char c : line) {
    if (c == ',')
      cells.emplace_back();
    else
      cells.back().push_back(c);
  }
  return cells;
}

// The rows of a CSV text restricted to the columns named in `header` (a comma-separated list).
std::vector<std::string> select_columns(const std::string& csv, const std::string& header) {
  const std::vector<std::string> lines = lines_of(csv);
  if (lines.empty()) return {};
  const std::vector<std::string> names = split_commas(lines[0]);
  std::vector<std::size_t> pick;
  for (const std::string& want : split_commas(header)) {
    const auto at = std::find(names.begin(), names.end(), want);
    if (at == names.end()) return {"no column " + want + " in " + lines[0]};
    pick.push_back(std::size_t(at - names.begin()));
  }
  std::vector<std::string> out;
  for (const std::string& line : lines) {
    const std::vector<std::string> cells = split_commas(line);
    std::string row;
    for (std::size_t k : pick) row += (row.empty() ? "" : ",") + cells.at(k);
    out.push_back(row);
  }
  return out;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + 1))
    text.replace(at, from.size(), to), at += to.size() - 1;
  return text;
}

// A5's grid example: the guide's command, run with the example plug-in's model for my_glints,
// writes the rows the guide shows (in its columns), and without --query stops with the guide's
// error line.
TEST_F(AddingAModelDocCli, GridExampleIsWhatTheProgramGives) {
  const std::string text = guide();
  std::vector<std::string> command = doc_command(text, "glintlab eval --model my_glints", "--grid");
  ASSERT_GE(command.size(), 4u) << "no `glintlab eval --model my_glints ... --grid` example";
  command.erase(command.begin());  // "glintlab"
  for (std::string& w : command) w = replace_all(w, "my_glints", "example_glints");
  command.insert(command.begin(), {"--plugin", kTestPlugin});
  const auto out = std::find(command.begin(), command.end(), "--out");
  ASSERT_TRUE(out != command.end() && out + 1 != command.end());
  const std::string out_file = *(out + 1);
  const std::string header = "theta_i,theta_o,value,pdf,expected_facets,p_hit";
  const std::vector<std::string> shown = doc_block(text, header);
  ASSERT_GT(shown.size(), 1u) << "no rows of the grid example in the guide";

  const RunResult r = run(command);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(select_columns(read_text(path(out_file)), header), shown)
      << "docs/adding_a_model.md (A5): the grid example's rows are not what glintlab writes";

  std::vector<std::string> no_query = command;
  const auto q = std::find(no_query.begin(), no_query.end(), "--query");
  ASSERT_TRUE(q != no_query.end() && q + 1 != no_query.end());
  no_query.erase(q, q + 2);
  std::filesystem::remove(path(out_file));
  const RunResult e = run(no_query);
  expect_input_error(e, {"--query", "example_glints", "u, v, dudx, dvdx, dudy, dvdy"}, {});
  const std::string from = "glintlab: error: --query: model ";
  EXPECT_EQ(replace_all(line_tail(text, from + "my_glints"), "my_glints", "example_glints"),
            line_tail(e.err, from))
      << "docs/adding_a_model.md (A5) shows another error than glintlab prints without --query";
}

// The guide's command and block readers: a command split over lines, a block found by its header.
TEST(AddingAModelDoc, CommandAndBlockReadersReadTheGuidesForm) {
  const std::string text =
      "```sh\nglintlab eval --model m \\\n  --grid 'a=1:2:3' --out g.csv && cut g.csv\n```\n"
      "```text\nx,y\n1,2\n```\n";
  EXPECT_EQ(doc_command(text, "glintlab eval --model m", "--grid"),
            (std::vector<std::string>{"glintlab", "eval", "--model", "m", "--grid", "a=1:2:3",
                                      "--out", "g.csv"}));
  EXPECT_EQ(doc_command(text, "glintlab eval --model m", "--query"), std::vector<std::string>{});
  EXPECT_EQ(doc_block(text, "x,y"), (std::vector<std::string>{"x,y", "1,2"}));
  EXPECT_EQ(select_columns("a,b,c\n1,2,3\n", "c,a"), (std::vector<std::string>{"c,a", "3,1"}));
}

}  // namespace
}  // namespace glintlab::cli_test

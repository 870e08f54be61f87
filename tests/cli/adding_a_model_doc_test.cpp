// docs/adding_a_model.md against the program it documents: its member table has a row for every
// member core/model.h lists for a model (kSmoothLimit and kNotClaimed included), the valid
// not-claimed property names it gives are the program's list (kConformanceProperties) in its
// order, and its example of a misspelled property is the line glintlab prints for one. So the
// guide a plug-in author follows cannot go stale when a member or a property is added.
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

}  // namespace
}  // namespace glintlab::cli_test

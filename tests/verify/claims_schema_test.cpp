// The schema `glintlab schema claims.json` prints describes exactly the rows verify writes: every
// field of every row is named by it, and required, with a type or value it allows, whether the
// row's optional parts are filled or empty.
#include "verify/claims_schema.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "verify/results.h"

namespace glintlab::verify {
namespace {

using nlohmann::json;

std::string json_type(const json& v) {
  if (v.is_null()) return "null";
  if (v.is_boolean()) return "boolean";
  if (v.is_number_integer()) return "integer";
  if (v.is_number()) return "number";
  if (v.is_string()) return "string";
  if (v.is_array()) return "array";
  return "object";
}

// True when `value` has a type (or value) the property schema allows; an integer is a number.
bool allowed(const json& value, const json& property) {
  if (property.contains("enum")) {
    for (const json& e : property["enum"])
      if (e == value) return true;
    return false;
  }
  const json types =
      property["type"].is_array() ? property["type"] : json::array({property["type"]});
  const std::string t = json_type(value);
  for (const json& u : types)
    if (u == t || (u == "number" && t == "integer")) return true;
  return false;
}

const Check& first_check_with_alternatives() {
  for (const Check& c : registered_checks())
    if (!c.alternatives.empty()) return c;
  return registered_checks().front();
}

std::vector<RunRecord> filled_and_empty_rows() {
  const Check& check = first_check_with_alternatives();
  CheckResult full;
  full.verdict = Verdict::kFails;
  full.measured_verdict = Verdict::kFails;
  full.detail = "measured";
  full.statistic = "chi-square";
  full.value = 3.5;
  full.bound = 1e-3;
  full.p_value = 1e-9;
  full.raw_p_values = {1e-9, 0.5};
  full.control = "corrected input";
  full.control_p_value = 0.4;
  full.control_rejected = true;
  full.control_verdict = Verdict::kHolds;
  full.regime = "alpha in [0.1, 1]";
  full.power = "2 % at 90 %";
  full.configurations = 2;
  CheckResult empty;
  empty.verdict = Verdict::kError;
  empty.value = std::numeric_limits<double>::quiet_NaN();
  return {{&check, full, 1.5, Budget::kQuick, 2e-9}, {&check, empty, 0.0, Budget::kFull}};
}

TEST(ClaimsSchema, EveryRowVerifyWritesHasExactlyTheSchemasFieldsWithAllowedTypes) {
  const json schema = json::parse(claims_json_schema());
  ASSERT_EQ(schema["type"], "array");
  const json& items = schema["items"];
  EXPECT_EQ(items["additionalProperties"], false);
  std::set<std::string> names;
  for (const auto& p : items["properties"].items()) names.insert(p.key());
  EXPECT_EQ(items["required"].get<std::set<std::string>>(), names);

  const json rows = json::parse(to_json(filled_and_empty_rows(), {"quick", 2, "test"}));
  ASSERT_EQ(rows.size(), 2u);
  for (const json& row : rows) {
    std::set<std::string> keys;
    for (const auto& f : row.items()) keys.insert(f.key());
    EXPECT_EQ(keys, names) << row["verdict"];
    for (const auto& f : row.items())
      EXPECT_TRUE(allowed(f.value(), items["properties"][f.key()]))
          << f.key() << " = " << f.value().dump() << " is not allowed by the schema";
  }
}

TEST(ClaimsSchema, ListsEveryVerdictAndRejectsOthers) {
  const json schema = json::parse(claims_json_schema());
  const json& verdict = schema["items"]["properties"]["verdict"];
  ASSERT_EQ(verdict["enum"].size(), kEveryVerdict.size());
  for (Verdict v : kEveryVerdict) EXPECT_TRUE(allowed(to_string(v), verdict));
  EXPECT_FALSE(allowed("passes", verdict));
  EXPECT_FALSE(allowed(nullptr, verdict));
  EXPECT_TRUE(allowed(nullptr, schema["items"]["properties"]["control_verdict"]));
  // A number where text is required is not allowed: the check can fail.
  EXPECT_FALSE(allowed(3, schema["items"]["properties"]["detail"]));
}

}  // namespace
}  // namespace glintlab::verify

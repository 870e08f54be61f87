// The JSON Schema of claims.json; see claims_schema.h. The field list follows to_json in
// verify/results.cpp; ClaimsSchema tests check that every row it writes has exactly these fields.
#include "verify/claims_schema.h"

#include <nlohmann/json.hpp>

namespace glintlab::verify {
namespace {

using nlohmann::ordered_json;

ordered_json typed(const char* type, const char* description) {
  return {{"type", type}, {"description", description}};
}

// A field that is absent from a result (no p-value, no regime, ...) is written as null.
ordered_json or_null(const char* type, const char* description) {
  return {{"type", ordered_json::array({type, "null"})}, {"description", description}};
}

ordered_json verdict_names(bool nullable) {
  ordered_json names = ordered_json::array();
  for (Verdict v : kEveryVerdict) names.push_back(to_string(v));
  if (nullable) names.push_back(nullptr);
  return names;
}

ordered_json verdict_field(bool nullable, const char* description) {
  return {{"enum", verdict_names(nullable)}, {"description", description}};
}

// A reviewed competing explanation of a finding: its cause and how it was excluded, or why it is
// still open.
ordered_json alternatives_field(const char* reason_key, const char* description) {
  return {{"type", "array"},
          {"description", description},
          {"items",
           {{"type", "object"},
            {"required", ordered_json::array({"cause", reason_key})},
            {"additionalProperties", false},
            {"properties",
             {{"cause", typed("string", "the competing explanation")},
              {reason_key, typed("string", "how it was ruled out by measurement, or why not")}}}}}};
}

ordered_json row_properties() {
  ordered_json p;
  p["id"] = typed("string", "the claim's id: <paper>.<claim>, or model.<name>.<property>");
  p["paper"] = typed("string", "the paper (or glintlab) the statement comes from");
  p["source"] = typed("string", "where in the paper: section, equation, figure");
  p["kind"] = {{"enum", ordered_json::array({"paper's claim", "glintlab rule", "conformance"})},
               {"description", "what kind of statement the check tests"}};
  p["paper_quote"] = or_null("string", "the paper's own sentence the check tests");
  p["stronger_reading"] =
      or_null("string", "a stronger reading of the sentence the check does not test, and why");
  p["verdict"] = verdict_field(false, "the verdict: what the measurement says of the statement");
  p["measured_verdict"] = verdict_field(
      true,
      "what the measurement alone said, where the finding rule changed the verdict (e.g. "
      "fails kept inconclusive while a competing cause is open)");
  p["alternatives_excluded"] =
      alternatives_field("how", "competing explanations of a finding, each ruled out, and how");
  p["alternatives_open"] =
      alternatives_field("why", "competing explanations not ruled out, and why not");
  p["correction"] = or_null("string", "what the paper's statement should say instead");
  p["expected_verdict"] =
      verdict_field(false, "the verdict recorded in the repository for this budget");
  p["budget_note"] =
      or_null("string", "why the recorded verdicts of the quick and full budgets differ");
  p["detail"] = typed("string", "what was measured, with its numbers");
  p["statistic"] = typed("string", "the name of the measured statistic");
  p["value"] = or_null("number", "the measured statistic (null: not a finite number)");
  p["bound"] = or_null("number", "the bound or tolerance the value is judged against");
  p["p_value"] = or_null("number", "the combined, corrected p-value of a statistical check");
  p["suite_adjusted_p_value"] =
      or_null("number", "the p-value after Holm-Sidak over the run's checks of its family");
  p["raw_p_values"] = {{"type", "array"},
                       {"items", {{"type", ordered_json::array({"number", "null"})}}},
                       {"description", "every configuration's raw p-value"}};
  p["control"] = typed("string",
                       "the negative control: the deliberately wrong input, and its "
                       "outcome");
  p["control_p_value"] = or_null("number", "the control's p-value, for statistical checks");
  p["control_rejected"] =
      typed("boolean", "true when the control got the verdict opposite to the input's");
  p["control_verdict"] = verdict_field(true, "the verdict the control received");
  p["regime"] = or_null("string",
                        "the parameter region a verdict speaks for, declared in code "
                        "before measuring");
  p["power"] = typed("string", "the smallest effect detected at 90 % power, where computed");
  p["configurations"] = typed("integer", "how many configurations were measured");
  p["budget"] = {{"enum", ordered_json::array({"quick", "full"})},
                 {"description", "the sample budget of the run"}};
  p["seconds"] = typed("number", "wall time of the check (a measurement of the machine)");
  return p;
}

}  // namespace

std::string claims_json_schema() {
  const ordered_json properties = row_properties();
  ordered_json required = ordered_json::array();
  for (const auto& item : properties.items()) required.push_back(item.key());
  const ordered_json schema = {
      {"$schema", "https://json-schema.org/draft/2020-12/schema"},
      {"title", "glintlab verify claims.json"},
      {"description",
       "The rows glintlab verify writes, one object per check; docs/verification.md says how a "
       "check decides."},
      {"type", "array"},
      {"items",
       {{"type", "object"},
        {"required", required},
        {"additionalProperties", false},
        {"properties", properties}}}};
  return schema.dump(2) + "\n";
}

}  // namespace glintlab::verify

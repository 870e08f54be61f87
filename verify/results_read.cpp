// Reading claims.json back into RunRecords; see results_read.h.
#include "verify/results_read.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "verify/claims_schema.h"

namespace glintlab::verify {
namespace {

using nlohmann::json;

Verdict verdict_named(const std::string& name, const std::string& where) {
  for (Verdict v : kEveryVerdict)
    if (to_string(v) == name) return v;
  throw std::invalid_argument(fmt::format("{}: unknown verdict '{}'", where, name));
}

std::optional<double> optional_number(const json& row, const char* key) {
  const json& v = row.at(key);
  if (v.is_null()) return std::nullopt;
  return v.get<double>();
}

std::optional<Verdict> optional_verdict(const json& row, const char* key,
                                        const std::string& where) {
  const json& v = row.at(key);
  if (v.is_null()) return std::nullopt;
  return verdict_named(v.get<std::string>(), where);
}

const Check* registered(const std::string& id) {
  for (const Check& c : registered_checks())
    if (c.id == id) return &c;
  return nullptr;
}

RunRecord record_of(const json& row, Budget budget, const std::string& where) {
  const std::string id = row.at("id").get<std::string>();
  const Check* check = registered(id);
  if (!check) throw std::invalid_argument(fmt::format("{}: '{}' is not a registered check", where, id));
  const std::string row_budget = row.at("budget").get<std::string>();
  if (row_budget != (budget == Budget::kFull ? "full" : "quick"))
    throw std::invalid_argument(fmt::format("{}: '{}' was run at budget {}", where, id, row_budget));
  CheckResult x;
  x.verdict = verdict_named(row.at("verdict").get<std::string>(), where);
  x.measured_verdict = optional_verdict(row, "measured_verdict", where);
  x.detail = row.at("detail").get<std::string>();
  x.statistic = row.at("statistic").get<std::string>();
  x.value = row.at("value").is_null() ? std::numeric_limits<double>::quiet_NaN()
                                      : row.at("value").get<double>();
  x.bound = optional_number(row, "bound");
  x.p_value = optional_number(row, "p_value");
  x.raw_p_values = row.at("raw_p_values").get<std::vector<double>>();
  x.control = row.at("control").get<std::string>();
  x.control_p_value = optional_number(row, "control_p_value");
  x.control_rejected = row.at("control_rejected").get<bool>();
  x.control_verdict = optional_verdict(row, "control_verdict", where);
  x.regime = row.at("regime").is_null() ? std::string() : row.at("regime").get<std::string>();
  x.power = row.at("power").get<std::string>();
  x.configurations = row.at("configurations").get<int>();
  return {check, std::move(x), row.at("seconds").get<double>(), budget};
}

}  // namespace

std::vector<RunRecord> read_records(const std::string& claims_json, Budget budget,
                                    const std::string& source) {
  std::vector<RunRecord> out;
  try {
    const json rows = json::parse(claims_json);
    if (!rows.is_array()) throw std::invalid_argument(fmt::format("{}: not a list of rows", source));
    for (std::size_t i = 0; i < rows.size(); ++i)
      out.push_back(record_of(rows[i], budget, fmt::format("{} row {}", source, i + 1)));
  } catch (const json::exception& e) {
    throw std::invalid_argument(fmt::format("{}: not a glintlab verify claims.json ({})", source,
                                            e.what()));
  }
  return out;
}

}  // namespace glintlab::verify

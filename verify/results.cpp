// Serialisation of a verify run; see results.h.
#include "verify/results.h"

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "verify/stats/multiple_testing.h"

namespace glintlab::verify {
namespace {

nlohmann::json optional_number(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

std::string csv_field(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string md_cell(const std::string& s) {
  std::string r;
  for (char c : s) r += c == '|' ? std::string("\\|") : std::string(1, c);
  return r;
}

std::string number_or_dash(const std::optional<double>& v) {
  return v ? fmt::format("{:.3g}", *v) : std::string("—");
}

// What kind of statement the check tests: a paper's claim, glintlab's own rule, or a model's
// conformance property.
const char* kind_of(const Check& c) {
  if (!c.family.empty()) return "conformance";
  return c.glintlab_rule ? "glintlab rule" : "paper's claim";
}

nlohmann::json alternatives_json(const Check& c, bool excluded) {
  nlohmann::json list = nlohmann::json::array();
  for (const Alternative& a : c.alternatives)
    if (a.excluded == excluded)
      list.push_back(
          {{"cause", std::string(a.cause)}, {excluded ? "how" : "why", std::string(a.how)}});
  return list;
}

nlohmann::json text_or_null(const std::string& s) {
  return s.empty() ? nlohmann::json(nullptr) : nlohmann::json(s);
}

}  // namespace

void adjust_for_suite(std::vector<RunRecord>& records) {
  // Each false-positive family on its own (Check::family: the papers' claims, and each model's
  // conformance checks), so that selecting a model's checks never moves a paper claim's number.
  std::vector<std::string> families;
  for (const RunRecord& r : records)
    if (std::find(families.begin(), families.end(), r.check->family) == families.end())
      families.push_back(r.check->family);
  for (const std::string& family : families) {
    std::vector<double> p;
    std::vector<std::size_t> index;
    for (std::size_t i = 0; i < records.size(); ++i)
      if (records[i].check->family == family && records[i].result.p_value) {
        p.push_back(*records[i].result.p_value);
        index.push_back(i);
      }
    const HolmSidakResult h = holm_sidak(p, kFamilyWiseRate);
    for (std::size_t j = 0; j < index.size(); ++j)
      records[index[j]].suite_adjusted_p = h.adjusted[j];
  }
}

std::string budget_note(const Check& c) {
  return fmt::format("recorded {} at the quick budget and {} at the full budget: {}",
                     to_string(c.expected_for(Budget::kQuick)),
                     to_string(c.expected_for(Budget::kFull)), c.budget_note);
}

bool as_expected(const RunRecord& r) {
  return r.result.verdict == r.check->expected_for(r.budget) && control_ok(r.result);
}

std::string to_json(const std::vector<RunRecord>& records, const RunInfo& info) {
  nlohmann::json list = nlohmann::json::array();
  for (const RunRecord& r : records) {
    const CheckResult& x = r.result;
    list.push_back(
        {{"id", r.check->id},
         {"paper", r.check->paper},
         {"source", r.check->source},
         {"kind", kind_of(*r.check)},
         {"paper_quote", text_or_null(r.check->paper_quote)},
         {"stronger_reading", text_or_null(r.check->stronger_reading)},
         {"verdict", to_string(x.verdict)},
         {"measured_verdict", x.measured_verdict ? nlohmann::json(to_string(*x.measured_verdict))
                                                 : nlohmann::json(nullptr)},
         {"alternatives_excluded", alternatives_json(*r.check, true)},
         {"alternatives_open", alternatives_json(*r.check, false)},
         {"correction", text_or_null(r.check->correction)},
         {"expected_verdict", to_string(r.check->expected_for(r.budget))},
         {"budget_note", r.check->budget_note.empty() ? nlohmann::json(nullptr)
                                                      : nlohmann::json(budget_note(*r.check))},
         {"detail", x.detail},
         {"statistic", x.statistic},
         {"value", x.value},
         {"bound", optional_number(x.bound)},
         {"p_value", optional_number(x.p_value)},
         {"suite_adjusted_p_value", optional_number(r.suite_adjusted_p)},
         {"raw_p_values", x.raw_p_values},
         {"control", x.control},
         {"control_p_value", optional_number(x.control_p_value)},
         {"control_rejected", x.control_rejected},
         {"control_verdict", x.control_verdict ? nlohmann::json(to_string(*x.control_verdict))
                                               : nlohmann::json(nullptr)},
         {"regime", x.regime.empty() ? nlohmann::json(nullptr) : nlohmann::json(x.regime)},
         {"power", x.power},
         {"configurations", x.configurations},
         {"budget", info.budget},
         {"seconds", r.seconds}});
  }
  return list.dump(2) + "\n";
}

std::string registry_to_json(const std::vector<const Check*>& checks) {
  nlohmann::json list = nlohmann::json::array();
  for (const Check* c : checks) {
    nlohmann::json alternatives = nlohmann::json::array();
    for (const Alternative& a : c->alternatives)
      alternatives.push_back({{"cause", std::string(a.cause)},
                              {"how", std::string(a.how)},
                              {"excluded", a.excluded}});
    list.push_back(
        {{"id", c->id},
         {"paper", c->paper},
         {"source", c->source},
         {"kind", kind_of(*c)},
         {"family", c->family},
         {"statistical", is_statistical(*c)},
         {"expected_verdict",
          {{"quick", to_string(c->expected_for(Budget::kQuick))},
           {"full", to_string(c->expected_for(Budget::kFull))}}},
         {"budget_note", text_or_null(c->budget_note)},
         {"paper_quote", text_or_null(c->paper_quote)},
         {"stronger_reading", text_or_null(c->stronger_reading)},
         {"alternatives", alternatives},
         {"correction", text_or_null(c->correction)}});
  }
  return list.dump(2) + "\n";
}

std::string to_csv(const std::vector<RunRecord>& records) {
  std::string csv =
      "id,paper,source,kind,paper_quote,verdict,measured_verdict,expected_verdict,detail,statistic,"
      "value,bound,p_value,"
      "suite_adjusted_p_value,control_p_value,control_rejected,control_verdict,control,regime,"
      "power,"
      "configurations,seconds\n";
  auto num = [](const std::optional<double>& v) {
    return v ? fmt::format("{:.17g}", *v) : std::string();
  };
  for (const RunRecord& r : records) {
    const CheckResult& x = r.result;
    csv += fmt::format(
        "{},{},{},{},{},{},{},{},{},{},{:.17g},{},{},{},{},{},{},{},{},{},{},{:.3f}\n", r.check->id,
        csv_field(r.check->paper), csv_field(r.check->source), kind_of(*r.check),
        csv_field(r.check->paper_quote), to_string(x.verdict),
        x.measured_verdict ? to_string(*x.measured_verdict) : "",
        to_string(r.check->expected_for(r.budget)), csv_field(x.detail), csv_field(x.statistic),
        x.value, num(x.bound), num(x.p_value), num(r.suite_adjusted_p), num(x.control_p_value),
        x.control_rejected ? 1 : 0, x.control_verdict ? to_string(*x.control_verdict) : "",
        csv_field(x.control), csv_field(x.regime), csv_field(x.power), x.configurations, r.seconds);
  }
  return csv;
}

std::string to_markdown(const std::vector<RunRecord>& records, const RunInfo& info) {
  std::string md = fmt::format("# glintlab verify — budget {}, {} thread(s), {}\n\n", info.budget,
                               info.threads, info.machine);
  md += "| claim | paper | source | verdict | measured | bound | p | control | evidence | time |\n";
  md += "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const RunRecord& r : records) {
    const CheckResult& x = r.result;
    std::string verdict = fmt::format("**{}**", to_string(x.verdict));
    if (x.verdict != r.check->expected_for(r.budget))
      verdict += fmt::format(" (recorded: {})", to_string(r.check->expected_for(r.budget)));
    if (!x.regime.empty()) verdict += fmt::format(" in {}", x.regime);
    if (!r.check->budget_note.empty()) verdict += fmt::format(" ({})", budget_note(*r.check));
    if (x.measured_verdict)
      verdict += fmt::format(" (measured {}, a competing cause not excluded)",
                             to_string(*x.measured_verdict));
    const std::string control =
        x.control_verdict ? fmt::format("**{}**: {}", to_string(*x.control_verdict), x.control)
                          : x.control;
    md += fmt::format("| {} | {} | {} | {} | {} = {:.3g} | {} | {} | {} | {} | {:.1f} s |\n",
                      r.check->id, md_cell(r.check->paper), md_cell(r.check->source), verdict,
                      md_cell(x.statistic), x.value, number_or_dash(x.bound),
                      number_or_dash(x.p_value), md_cell(control), md_cell(x.detail), r.seconds);
  }
  return md;
}

}  // namespace glintlab::verify

// The files, table and exit status of a verify run; see verify_output.h.
#include "cli/verify_output.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "core/io/atomic_file.h"

namespace glintlab::cli {

int write_verify_run(std::vector<verify::RunRecord>& records, const verify::RunInfo& info,
                     const std::string& out) {
  verify::adjust_for_suite(records);
  const std::filesystem::path dir(out);
  io::write_file_atomic(dir / "claims.json", verify::to_json(records, info));
  io::write_file_atomic(dir / "claims.csv", verify::to_csv(records));
  io::write_file_atomic(dir / "claims.md", verify::to_markdown(records, info));

  int unexpected = 0;
  // The measured value is printed with what it measures (its statistic names the unit).
  fmt::print("{:<30} {:<16} {:>10} {:>10}  {:<8}  {}\n", "claim", "verdict", "p", "control p",
             "control", "measured");
  for (const auto& r : records) {
    const auto& x = r.result;
    const bool ok = verify::as_expected(r);
    unexpected += ok ? 0 : 1;
    // A property that ran nothing (not claimed) or could not compute has no measured value.
    const bool measured =
        x.verdict != verify::Verdict::kNotClaimed && x.verdict != verify::Verdict::kError;
    const verify::Verdict expected = r.check->expected_for(r.budget);
    fmt::print("{:<30} {:<16} {:>10} {:>10}  {:<8}  {}{}\n", r.check->id,
               verify::to_string(x.verdict), x.p_value ? fmt::format("{:.3g}", *x.p_value) : "—",
               x.control_p_value ? fmt::format("{:.3g}", *x.control_p_value) : "—",
               x.verdict == verify::Verdict::kNotClaimed ? "none (not claimed)"
               : x.verdict == verify::Verdict::kError    ? "none (error)"
               : x.control_rejected                      ? "rejected"
               // Neither decided: the check lacks power here (its detail says how much it needs).
               : x.verdict == verify::Verdict::kInconclusive &&
                       x.control_verdict == verify::Verdict::kInconclusive
                   ? "undecided (both inconclusive)"
                   : "NOT REJECTED (check is broken)",
               measured ? fmt::format("{:.3g} = {}", x.value, x.statistic) : x.statistic,
               x.verdict == expected ? ""
               : r.check->recorded
                   ? fmt::format("  [recorded verdict: {}]", verify::to_string(expected))
                   : fmt::format("  [a conforming model: {}; nothing recorded for this model]",
                                 verify::to_string(expected)));
  }
  for (const auto& r : records)
    if (!r.check->budget_note.empty())
      fmt::print("note: {}: {}\n", r.check->id, verify::budget_note(*r.check));
  fmt::print("{} claims, budget {}, {} thread(s); results in {}/claims.{{json,csv,md}}\n",
             records.size(), info.budget, info.threads, out);
  const auto errors = std::count_if(records.begin(), records.end(), [](const auto& r) {
    return r.result.verdict == verify::Verdict::kError;
  });
  if (errors) {
    for (const auto& r : records)
      if (r.result.verdict == verify::Verdict::kError)
        fmt::print(stderr, "glintlab: error: {}\n", r.result.detail);
    fmt::print(stderr,
               "glintlab: error: {} claim(s) could not be checked (verdict error); the other "
               "claims ran and the results are in {}\n",
               errors, out);
    return 3;
  }
  if (unexpected) {
    fmt::print(stderr,
               "glintlab: error: {} claim(s) differ from their recorded verdict or did not reject "
               "their negative control\n",
               unexpected);
    return 1;
  }
  return 0;
}

}  // namespace glintlab::cli

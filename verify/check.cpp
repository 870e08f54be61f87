// Verdict names and seed derivation for registered checks.
#include "verify/check.h"

#include <exception>

#include "core/math/rng.h"

namespace glintlab::verify {

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::kHolds: return "holds";
    case Verdict::kHoldsWithin: return "holds-within";
    case Verdict::kHoldsInRegime: return "holds-in-regime";
    case Verdict::kFails: return "fails";
    case Verdict::kInconclusive: return "inconclusive";
    case Verdict::kNotClaimed: return "not-claimed";
    case Verdict::kError: return "error";
  }
  return "inconclusive";
}

CheckResult error_result(const std::string& what) {
  CheckResult r;
  r.verdict = Verdict::kError;
  r.detail = what;
  r.statistic = "none (the check could not compute its statistic)";
  r.control = "none: the check could not run";
  return r;
}

std::function<CheckResult(Budget)> contained(std::string subject,
                                             std::function<CheckResult(Budget)> run) {
  return [subject = std::move(subject), run = std::move(run)](Budget b) {
    try {
      return run(b);
    } catch (const std::exception& e) {
      return error_result(subject + ": exception: " + e.what());
    } catch (...) {
      return error_result(subject + ": exception: (not a std::exception, no message)");
    }
  };
}

std::uint64_t check_seed(const std::string& id, std::uint64_t configuration) {
  return mix64(hash_string(id.c_str()) ^ mix64(configuration + 1));
}

}  // namespace glintlab::verify

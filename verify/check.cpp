// Verdict names and seed derivation for registered checks.
#include "verify/check.h"

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
  }
  return "inconclusive";
}

std::uint64_t check_seed(const std::string& id, std::uint64_t configuration) {
  return mix64(hash_string(id.c_str()) ^ mix64(configuration + 1));
}

}  // namespace glintlab::verify

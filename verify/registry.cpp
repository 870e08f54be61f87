// The registry of every check, in the order of shared/CLAIMS.md.
#include "verify/check.h"
#include "verify/claims/claims.h"

namespace glintlab::verify {

const std::vector<Check>& registered_checks() {
  static const std::vector<Check> checks = [] {
    std::vector<Check> all;
    for (auto* list : {&smooth_checks}) {
      for (Check& c : list()) all.push_back(std::move(c));
    }
    return all;
  }();
  return checks;
}

}  // namespace glintlab::verify

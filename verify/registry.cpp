// The registry of every check, in the order of shared/CLAIMS.md.
#include "verify/check.h"

#include <algorithm>

#include "verify/claims/claims.h"
#include "verify/conformance/conformance.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify {

const std::vector<Check>& registered_checks() {
  static const std::vector<Check> checks = [] {
    std::vector<Check> all;
    for (auto* list : {&smooth_checks, &smooth_sampler_checks, &smooth_consistency_checks,
                       &eto_pdf_checks, &eto_checks, &kemppinen_checks, &kneiphof_checks,
                       &kneiphof_ltc_checks,
                       &chermain_checks, &podee_checks, &across_checks, &adequacy_checks}) {
      for (Check& c : list()) all.push_back(std::move(c));
    }
    // Every registered model's conformance checks, generated from the registry as it stands now
    // (after start-up has loaded the plug-ins).
    for (Check& c : conformance_checks()) all.push_back(std::move(c));
    return all;
  }();
  return checks;
}

double check_level() {
  static const double level = [] {
    const auto& all = registered_checks();
    // Only the papers' claims: a model's conformance checks are their own family
    // (verify/conformance/), so registering models never moves this level.
    const auto k = std::size_t(std::count_if(all.begin(), all.end(), [](const Check& c) {
      return is_statistical(c) && c.family.empty();
    }));
    return sidak_level(kFamilyWiseRate, std::max<std::size_t>(k, 1));
  }();
  return level;
}

}  // namespace glintlab::verify

// The registry of every check, in the order docs/claims.md lists them.
#include <algorithm>

#include "verify/check.h"
#include "verify/claim.h"
#include "verify/claims/across/list.h"
#include "verify/claims/adequacy/list.h"
#include "verify/claims/chermain/list.h"
#include "verify/claims/eto/list.h"
#include "verify/claims/kemppinen/list.h"
#include "verify/claims/kneiphof/list.h"
#include "verify/claims/podee/list.h"
#include "verify/claims/smooth/list.h"
#include "verify/conformance/conformance.h"
#include "verify/finding_rule.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify {
namespace {

// Routes a claim's result through the finding rule (its quote and reviewed causes come with its
// type: claim_check), so that every caller of run() sees the verdict the rule gives; an exception
// escaping the run is the claim's error verdict.
void apply_finding_rule_to(Check& c) {
  Check reviewed;  // what the rule reads: the id, the family and the alternatives
  reviewed.id = c.id;
  reviewed.family = c.family;
  reviewed.alternatives = c.alternatives;
  c.run = contained("claim " + c.id,
                    [measure = std::move(c.run), reviewed = std::move(reviewed)](Budget b) {
                      CheckResult r = measure(b);
                      apply_finding_rule(reviewed, r);
                      return r;
                    });
}

}  // namespace

const std::vector<Check>& registered_checks() {
  static const std::vector<Check> checks = [] {
    std::vector<Check> all;
    for (auto* list : {&list_checks<smooth_claims::Claims>, &list_checks<eto_claims::Claims>,
                       &list_checks<kemppinen_claims::Claims>, &list_checks<kneiphof_claims::Claims>,
                       &list_checks<chermain_claims::Claims>, &list_checks<podee_claims::Claims>,
                       &list_checks<across_claims::Claims>, &list_checks<adequacy_claims::Claims>}) {
      for (Check& c : list()) {
        apply_finding_rule_to(c);
        all.push_back(std::move(c));
      }
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

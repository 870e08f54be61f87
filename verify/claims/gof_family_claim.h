// The protocol of a claim decided by one chi-square family (verify/claims/gof_family.h): a grid
// of sampler configurations, each sampled and binned against the density the claim states, the
// family's p-values Holm–Šidák-corrected, and negative controls (wrong densities, wrong samplers)
// each decided in place of the configuration it is built on. To the runner (verify/claim_runner.h)
// the family is one configuration: it is planned and run as one, its controls reusing the
// configurations' plans and continuing their seeds (run_gof_family).
//
// A claim derives from GofFamilyClaim<Itself, Config> and gives its id, paper, source, statistic,
// expected verdicts, sizes(budget), probe_sizes(), calibrate(seed) and
//   static GofSpec spec(const Sizes&): the cases and controls of its grid;
//   static std::string genuine_text(const Sizes&, const GofSpec&, const GofOutcome&,
//                                   const GofControlVerdicts&, const CheckResult& family,
//                                   std::size_t worst): what the genuine input's row says.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "verify/claim.h"
#include "verify/claims/gof_family.h"

namespace glintlab::verify {

// The configurations of grid g that a control case is built on, in grid order: a family's probe
// grid (its controls keep their power there, the rest is the budget's).
template <typename Config>
std::vector<Config> configurations_under_controls(const std::vector<Config>& g,
                                                  const std::vector<GofControl>& controls) {
  std::vector<bool> used(g.size(), false);
  for (const GofControl& c : controls)
    for (const GofControlCase& cc : c.cases) used[std::size_t(cc.position())] = true;
  std::vector<Config> out;
  for (std::size_t i = 0; i < g.size(); ++i)
    if (used[i]) out.push_back(g[i]);
  return out;
}

// A family's spec: one case per configuration of g, and its controls.
template <typename Config, typename MakeCase>
GofSpec gof_spec(const std::vector<Config>& g, MakeCase&& make_case,
                 std::vector<GofControl> controls) {
  GofSpec s;
  for (const Config& c : g) s.cases.push_back(make_case(c));
  s.controls = std::move(controls);
  return s;
}

template <typename Derived, typename Config>
struct GofFamilyClaim {
  struct Sizes {
    std::vector<Config> grid;
    GofSize size;  // samples per configuration and per control case
  };

  // Every configuration and control case by chi-square: the family is one configuration here.
  struct Evidence {
    GofSpec spec;
    GofOutcome outcome;
  };
  static int configurations(const Sizes&) { return 1; }
  static Evidence observe(const Sizes& z, int, std::uint64_t) {
    Evidence e{Derived::spec(z), {}};
    e.outcome = run_gof_family(std::string(Derived::kId), e.spec.cases, e.spec.controls, z.size);
    return e;
  }

  // The family decided on its configurations (genuine) or with each control case in its
  // configuration's place (perturbed; there is no corrected input).
  struct Measured {
    Verdict verdict = Verdict::kInconclusive;
    std::optional<double> p_value = {};
    std::vector<double> raw_p_values = {};
    int configurations = 0;
    std::string text = {}, power = {};
  };
  static Measured measure(const Sizes& z, std::span<const Evidence> evidence, Input input) {
    const Evidence& e = evidence.front();
    const GofOutcome& o = e.outcome;
    const GofControlVerdicts cv = decide_gof_controls(o, e.spec.controls);
    // describe_gof gives the family's p-values and power, the controls' largest p and their text.
    CheckResult family;
    family.verdict = decide_gof(o.results);
    const std::size_t worst = describe_gof(o, e.spec.controls, cv, family);
    Measured m{.configurations = family.configurations, .power = family.power};
    if (input == Input::kGenuine) {
      m.verdict = family.verdict;
      m.p_value = family.p_value;
      m.raw_p_values = family.raw_p_values;
      m.text = Derived::genuine_text(z, e.spec, o, cv, family, worst);
    } else {
      m.verdict = cv.verdict;
      m.p_value = family.control_p_value;
      m.text = family.control;
    }
    return m;
  }

  static Decision decide(const Sizes&, const Measured& m) {
    return {.verdict = m.verdict,
            .value = m.p_value.value_or(1),
            .p_value = m.p_value,
            .raw_p_values = m.raw_p_values,
            .configurations = m.configurations};
  }
  static std::string describe(const Sizes&, const Measured& m, Input) { return m.text; }
  static std::string power(const Sizes&, const Measured& m, const Measured&) { return m.power; }
};

}  // namespace glintlab::verify

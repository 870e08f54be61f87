// A family of chi-square goodness-of-fit configurations checked as one claim, with its negative
// controls: shared by smooth.sampler-matches-pdf, eto.pdf-matches and kemppinen.jacobian.
//
// Every configuration is planned (cubature of the expected counts) and run with the seed
// check_seed(id, index); the family's raw p-values are corrected by Holm–Šidák at check_level().
// A control is a list of deliberately wrong cases (a wrong pdf, a wrong sampler); it counts as
// rejected only when every one of its cases is rejected at the level of the family's first Holm
// step, sidak_level(check_level(), M) for M configurations: placed in the grid, the wrong case
// would make the check fail. Configurations run in parallel, each with its own plan and seed, so
// the outcome does not depend on the thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/math/vec.h"
#include "verify/check.h"
#include "verify/stats/chi_square.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify {

// A statistical check's configurations as one Holm–Šidák family at check_level().
struct Family {
  HolmSidakResult hs;
  double min_adjusted = 1;
};
Family correct_family(const std::vector<double>& p);

// The family as the check's p-values: every configuration's raw p, and the smallest adjusted p as
// the check's p-value.
void record_p_values(CheckResult& r, const Family& f);

using SeededDirections = std::function<Vec3<double>(std::uint64_t seed, std::uint64_t index)>;
using SeededPoints = std::function<Vec2<double>(std::uint64_t seed, std::uint64_t index)>;
// Directions begin .. begin + count − 1 under `seed` at once (a batched sampler, core/simd/).
using SeededDirectionBatch = std::function<void(std::uint64_t seed, std::uint64_t begin,
                                                std::size_t count, Vec3<double>* out)>;

// One configuration: samples of directions on the sphere (or points on the disk of
// core/maps/disk_square.h) and the density they are claimed to follow.
struct GofCase {
  std::string label;
  SampleDomain domain = SampleDomain::kSphere;  // kSphere or kDisk
  ChiSquareOptions options;  // lobe and breakpoints; `level` is set by the family
  DirectionPdf direction_pdf;
  SeededDirections directions;
  PointPdf point_pdf;
  SeededPoints points;
  SeededDirectionBatch direction_batch = {};  // where set, used instead of `directions`
};

// A wrong case of a control. With plan_of ≥ 0 the claimed pdf is configuration plan_of's pdf times
// pdf_scale, and that configuration's plan is reused with its expectations scaled (exact: the
// expected counts are linear in the pdf), so only `wrong.directions` / `wrong.points` and `label`
// are used; with plan_of < 0 `wrong` is planned on its own.
struct GofControlCase {
  GofCase wrong;
  int plan_of = -1;
  double pdf_scale = 1;
  // The configuration whose place the case takes when the control is decided as the family
  // (decide_gof_controls); plan_of where that is ≥ 0.
  int replaces = -1;
  int position() const { return plan_of >= 0 ? plan_of : replaces; }
};

struct GofControl {
  std::string name;  // what is wrong, e.g. "pdf × 1.02"
  std::vector<GofControlCase> cases;
  // Samples per case: GofSize::control_n (subtle errors need the samples), or GofSize::n where
  // the error is gross (a pdf of the wrong mass or shape fails at any sample count).
  bool gross = false;
};

struct GofOutcome {
  std::vector<ChiSquareResult> results;  // per configuration
  HolmSidakResult family;                // over the configurations' combined p-values
  double configuration_level = 0;        // sidak_level(check_level(), M)
  std::vector<std::vector<ChiSquareResult>> control_results;
  std::vector<double> control_p;  // per control: the largest p over its cases
  std::vector<bool> control_rejected;
  std::size_t inconclusive = 0, hard_failures = 0;
};

// Sample counts and the fine resolution's bin cap of a family run (the cubature cost grows with
// the number of bins; the coarse resolution carries the power against global errors).
struct GofSize {
  std::uint64_t n = 0;          // samples per configuration
  std::uint64_t control_n = 0;  // samples per case of a control that is not gross
  std::size_t fine_max_bins = 4096;
};

ChiSquarePlan plan_gof_case(const GofCase& c, std::uint64_t n, double level,
                            std::size_t fine_max_bins = 4096);
ChiSquareResult run_gof_case(const ChiSquarePlan& plan, const GofCase& c, std::uint64_t seed);

// Plans and runs every configuration with size.n samples (seed check_seed(id, i)) and every
// control case with size.control_n (seeds continuing after the configurations).
GofOutcome run_gof_family(const std::string& id, const std::vector<GofCase>& cases,
                          const std::vector<GofControl>& controls, const GofSize& size);

// Decide: the family's verdict from its configurations' results alone: fails where Holm–Šidák at
// check_level() rejects a configuration or one fails hard, inconclusive where none does but the
// cubature could not decide one, holds otherwise.
Verdict decide_gof(const std::vector<ChiSquareResult>& results);

// The controls decided by the same decision: each wrong case in place of the configuration it is
// built on (GofControlCase::position), the family with it decided by decide_gof. A case that fails
// there is one the check would catch; a control counts as rejected when every case fails.
struct GofControlVerdicts {
  std::vector<std::vector<Verdict>> cases;   // per control, per case
  Verdict verdict = Verdict::kInconclusive;  // control_verdict_of_cases over every case
  bool rejected(std::size_t control) const;  // every case of that control fails
};
GofControlVerdicts decide_gof_controls(const GofOutcome& o,
                                       const std::vector<GofControl>& controls);

// Describe: fills raw_p_values, p_value, configurations and power of r from the outcome, and the
// control's text (its verdict is the runner's to add) and largest p. Returns the index of the
// configuration with the smallest raw p.
std::size_t describe_gof(const GofOutcome& o, const std::vector<GofControl>& controls,
                         const GofControlVerdicts& cv, CheckResult& r);

// The older single step, kept for the Kemppinen checks: fills the fields describe_gof fills, with
// each control case judged at the first Holm level (run_gof_family's control_rejected) and the
// control's verdict set without the runner's control step; returns decide_gof's verdict. `worst` receives the
// index of the configuration with the smallest raw p.
Verdict summarize_gof(const GofOutcome& o, const std::vector<GofControl>& controls, CheckResult& r,
                      std::size_t& worst);

// The verdict of a control made of several wrong cases, each decided alone by the check's own
// decision: fails only where every case fails (each alone would make the check fail); otherwise
// the verdict of the first case that does not. Shared by the checks whose controls have cases.
Verdict control_verdict_of_cases(const std::vector<Verdict>& cases);

// A chi-square claim's configurations and controls at one budget, as its check runs them (exposed
// for the tests in tests/verify/claims/, which run the controls at reduced sample counts).
struct GofSpec {
  std::vector<GofCase> cases;
  std::vector<GofControl> controls;
};
GofSpec smooth_sampler_spec(Budget b);  // verify/claims/smooth/sampler_matches_pdf.cpp
GofSpec eto_pdf_spec(Budget b);         // verify/claims/eto/pdf_matches.cpp
GofSpec kemppinen_spec(Budget b);  // verify/claims/kemppinen/jacobian.cpp (the chi-square family)

// ---- Reflection samplers ------------------------------------------------------------------------

// The incidence at polar angle theta_deg and the azimuth kIncidencePhi (generic against the
// anisotropy axes); exactly +z at 0°.
inline constexpr double kIncidencePhi = 0.7;
Vec3<double> incidence(double theta_deg);

// The uniform pair (u1, u2) ∈ [0, 1)² of sample `index` under `seed` (counter RNG).
Vec2<double> uniform_pair(std::uint64_t seed, std::uint64_t index);

// Bins for a reflection density of incidence wi over the sphere: the pole at the mirror direction
// (−wi_x, −wi_y, wi_z) for wi_z > 0; at +z for a back-facing wi_z ≤ 0, where the support of every
// VNDF reflection density is the cap wo_z > −wi_z (h_z > 0), a parallel of that frame. −wi is a
// point feature of the cubature: there the half vector turns over, and Walter's density has its
// 1/|wi + wo| singularity (missed otherwise: measured, 5e-4 of the mass lost in one layout).
ChiSquareOptions reflection_options(const Vec3<double>& wi);

}  // namespace glintlab::verify

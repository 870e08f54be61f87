// What the smooth-NDF claims share: the normalisation claims' protocol (smooth.projected-area,
// smooth.vndf-normalized: one integral per configuration by adaptive cubature, within a tolerance,
// the control D × 1.02), and the count of distinct samplers the sampler claims report.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "verify/claim.h"
#include "verify/claims/gof_family.h"
#include "verify/stats/ndf_cubature.h"

namespace glintlab::verify::smooth_claims {

// How many distinct samplers (indices into sampler_table()) the configurations name.
template <class Config>
std::size_t sampler_count(std::span<const Config> configs) {
  std::vector<std::size_t> s;
  for (const Config& c : configs)
    if (std::find(s.begin(), s.end(), c.sampler) == s.end()) s.push_back(c.sampler);
  return s.size();
}

// ---- Normalisation by cubature ------------------------------------------------------------------

struct NdfConfig {
  bool ggx;
  double ax, ay;
  double theta_i_deg = 0;  // for the VNDF claim
};

// Isotropic α log-spaced 1e-3 … 2 and anisotropic ratios at αy ∈ {0.5, 1}, for GGX and Beckmann.
std::vector<NdfConfig> roughness_grid(Budget b);

inline constexpr double kNormalizationTolerance = 1e-6;  // far above cubature error (~1e-10),
                                                         // far below 2 %
inline constexpr double kControlScale = 1.02;

// A scale on D turns the true NDF into the negative control (2 % too much mass).
template <class Ndf>
struct ScaledNdf {
  Ndf ndf;
  double scale;
  double D(const Vec3<double>& m) const { return scale * ndf.D(m); }
  double projected_area(const Vec3<double>& w) const { return scale * ndf.projected_area(w); }
};

// One configuration's |integral − 1| and the cubature's error estimate.
struct NormalizationRow {
  NdfConfig c;
  double error = 0;       // |integral − 1|
  double quadrature = 0;  // cubature error estimate
};

// The row of configuration c with D scaled by `scale` (1: the true NDF); integrand_of_ndf(ndf, c)
// is the Integral over the scaled GGX or Beckmann NDF.
template <class F>
NormalizationRow normalization(const NdfConfig& c, double scale, F&& integrand_of_ndf) {
  auto run = [&](auto ndf) {
    const ScaledNdf<decltype(ndf)> scaled{ndf, scale};
    const Integral r = integrand_of_ndf(scaled, c);
    return NormalizationRow{c, std::abs(r.value - 1), r.error};
  };
  return c.ggx ? run(GGX<double>{c.ax, c.ay}) : run(Beckmann<double>{c.ax, c.ay});
}

std::size_t worst_row(std::span<const NormalizationRow> rows);
double largest_quadrature(std::span<const NormalizationRow> rows);
// Inconclusive where the cubature cannot resolve the tolerance; otherwise holds when the worst
// error is within it.
Verdict decide_normalization(std::span<const NormalizationRow> rows);
// Where the worst error is and how well the cubature resolved it.
std::string describe_normalization(std::span<const NormalizationRow> rows);
// The configurations the control is measured on: the first, the middle and the last.
std::vector<std::size_t> control_configurations(std::size_t n);

// The protocol of a normalisation claim D: D supplies kId, kPaper, kSource, kStatistic,
// grid(budget) and row(config, scale). Measured: every configuration's row
// (genuine); the control D × 1.02 on the first, the middle and the last configuration, each
// decided alone by the same decision (perturbed). Deterministic, no regime.
template <class D>
struct NormalizationClaim {
  static constexpr Expected kExpected{.quick = Verdict::kHolds};

  struct Sizes {
    std::vector<NdfConfig> grid;
  };
  static Sizes sizes(Budget b) { return {D::grid(b)}; }
  // The tests' probe: the quick grid's configurations the control is measured on.
  static Sizes probe_sizes() {
    const std::vector<NdfConfig> g = D::grid(Budget::kQuick);
    Sizes z;
    for (std::size_t i : control_configurations(g.size())) z.grid.push_back(g[i]);
    return z;
  }
  static int configurations(const Sizes& z) { return int(z.grid.size()); }

  // The configuration's row, and its row under the control where the control is measured there.
  struct Evidence {
    NormalizationRow genuine;
    std::optional<NormalizationRow> control;
  };
  static Evidence observe(const Sizes& z, int k, std::uint64_t) {
    const NdfConfig& c = z.grid[std::size_t(k)];
    Evidence e{D::row(c, 1.0), {}};
    for (std::size_t i : control_configurations(z.grid.size()))
      if (i == std::size_t(k)) e.control = D::row(c, kControlScale);
    return e;
  }

  struct Measured {
    std::vector<NormalizationRow> rows;
    std::vector<Verdict> cases = {};  // the control's, each configuration decided alone
  };
  static Measured measure(const Sizes& z, std::span<const Evidence> evidence, Input input) {
    Measured m;
    if (input == Input::kGenuine) {
      for (const Evidence& e : evidence) m.rows.push_back(e.genuine);
      return m;
    }
    for (std::size_t i : control_configurations(z.grid.size())) {
      const NormalizationRow& row = *evidence[i].control;
      m.rows.push_back(row);
      m.cases.push_back(decide_normalization(std::span(&row, 1)));
    }
    return m;
  }

  static Decision decide(const Sizes&, const Measured& m) {
    if (!m.cases.empty()) return {.verdict = control_verdict_of_cases(m.cases)};
    return {.verdict = decide_normalization(m.rows),
            .value = m.rows[worst_row(m.rows)].error,
            .bound = kNormalizationTolerance,
            .configurations = int(m.rows.size())};
  }
  static std::string describe(const Sizes&, const Measured& m, Input input) {
    if (input == Input::kGenuine) return describe_normalization(m.rows);
    double smallest = 1e300;
    for (const NormalizationRow& r : m.rows) smallest = std::min(smallest, r.error);
    return fmt::format(
        "D scaled by {:g}, each of {} configurations decided alone: smallest error "
        "{:.3g}",
        kControlScale, m.cases.size(), smallest);
  }
  static std::string power(const Sizes&, const Measured& genuine, const Measured&) {
    return fmt::format(
        "deterministic (cubature, error estimate ≤ {:.1e}): any normalisation error above {:g} is "
        "detected, every time",
        largest_quadrature(genuine.rows), kNormalizationTolerance);
  }
};

}  // namespace glintlab::verify::smooth_claims

#include "verify/claims/kemppinen/common.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/glints/kemppinen_reference.h"
#include "core/math/rng.h"
#include "verify/claims/gof_family.h"
#include "verify/scenes/kemppinen_presets.h"

namespace glintlab::verify::kemppinen_claims {

V3 direction(double theta_deg) {
  const double t = theta_deg * std::numbers::pi / 180;
  return {std::sin(t) * std::cos(kIncidencePhi), std::sin(t) * std::sin(kIncidencePhi),
          std::cos(t)};
}

V2 position(std::uint64_t seed, std::uint64_t i) {
  return {1000 * counter_uniform<double>(seed, i, 0), 1000 * counter_uniform<double>(seed, i, 1)};
}

const char* ndf_name(const Ndfs& n) { return n.ggx ? "GGX" : "Beckmann"; }

Band band(double estimate, double half_width, double tolerance) {
  if (std::abs(estimate) + half_width <= tolerance) return Band::kWithin;
  if (std::abs(estimate) - half_width > tolerance) return Band::kBeyond;
  return Band::kUndecided;
}

RelBias rel_bias(const std::vector<double>& model, const std::vector<double>& ref) {
  const std::size_t n = ref.size();
  double sm = 0, sr = 0;
  for (std::size_t i = 0; i < n; ++i) sm += model[i], sr += ref[i];
  if (n < 2 || sr <= 0) return {};
  const double bias = (sm - sr) / sr;
  double ss = 0;
  for (std::size_t i = 0; i < n; ++i) ss += sqr(model[i] - ref[i] - bias * ref[i]);
  return {bias, std::sqrt(ss / double(n * (n - 1))) / (sr / double(n))};
}

std::string comp_setting(const CompConfig& c) {
  return fmt::format("{} α★={:g} θ={:g}° footprint {:g} cells", ndf_name(c.ndf), c.alpha_star,
                     c.theta, c.cells);
}

std::uint64_t comp_positions(const CompConfig& c, const CompSize& sz, std::uint64_t seed) {
  const P p = kemppinen2025::preset_params(kCompSide, c.alpha_star, seed);
  return with_ndf(c.ndf, [&](const auto& ndf) {
    std::int64_t visited = 0;
    kemppinen2025::reference_filtered_parts(
        p, ndf, kemppinen2025::footprint_cells(position(seed, 0), c.cells, p), direction(c.theta),
        kCompSide, kCompReferenceSigmas, &visited);
    const double n = sz.pairs / double(std::max<std::int64_t>(visited, 1));
    return std::clamp<std::uint64_t>(std::uint64_t(n), sz.min, sz.max);
  });
}

CompSamples sample_comp(const CompConfig& c, std::uint64_t n, std::uint64_t seed, int side) {
  struct AtPosition {
    kemppinen2025::ReferenceParts<double> ref;
    kemppinen2025::Result<double> model;
  };
  std::vector<AtPosition> at(n);
  const P p = kemppinen2025::preset_params(side, c.alpha_star, seed);
  const V3 h = direction(c.theta);
  with_ndf(c.ndf, [&](const auto& ndf) {
    // Each position on its own (the brute force costs thousands of points each), merged below in
    // position order: the sums do not depend on the thread count.
    tbb::parallel_for(std::uint64_t(0), n, [&](std::uint64_t i) {
      const auto fp = kemppinen2025::footprint_cells(position(seed, i), c.cells, p);
      at[i] = {kemppinen2025::reference_filtered_parts(p, ndf, fp, h, side, kCompReferenceSigmas),
               kemppinen2025::eval(p, ndf, fp, h)};
    });
    return 0;
  });
  CompSamples s;
  double peak = 0, worst = 0;
  for (const AtPosition& a : at) {
    const auto& ref = a.ref;
    const auto& r = a.model;
    s.ref.push_back(ref.total.x);
    s.whole.push_back(ref.neighbourhood.x + r.compensation_part.x);
    s.block.push_back(r.d.x);
    s.no_c.push_back(ref.neighbourhood.x);
    s.explicit_whole += ref.neighbourhood.x;
    s.explicit_block += ref.block.x;
    s.c_sum += r.compensation_part.x;
    peak = std::max(peak, ref.total.x);
    worst = std::max(worst, std::abs(ref.block.x - r.explicit_part.x));
  }
  s.cross_check = peak > 0 ? worst / peak : 0;
  return s;
}

}  // namespace glintlab::verify::kemppinen_claims

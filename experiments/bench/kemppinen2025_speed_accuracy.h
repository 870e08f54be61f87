// Speed vs accuracy of Kemppinen et al. 2025's constant-time D★^f (Eq. 11, Algorithm 1): the
// fixed query sets and error measures of the `method/kemppinen_*` benchmarks
// (experiments/bench/kemppinen2025_bench.cpp, schema in the method-benchmark notes) and of the
// kemppinen2025-speed-accuracy figure, which recomputes the errors when no benchmark JSON exists.
//
// Two references:
// * dstar_f_vs_bruteforce: Eq. 5 summed over every point (core/glints/kemppinen_reference.h),
//   footprints of 0.25 … 16 level-0 cells, where the brute force is affordable. The error is
//   |D★^f − D★_Eq.5| / D(ω_h): the brute force is 0 between glints, so it is scaled by the smooth
//   D at the query (the value both fluctuate around) instead of by itself.
// * dstar_f_vs_smooth: the far field, footprints of 256 … 16384 cells, where Eq. 2 says D★ → D;
//   error |D★^f − D| / D (a true relative error).
// ω_h is drawn from D(ω)cosθ (Walter et al. 2007) so the queries sit where the NDF has mass.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/glints/kemppinen.h"
#include "core/glints/kemppinen_reference.h"
#include "core/math/rng.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/ndf/ndf_kind.h"
#include "core/samplers/walter.h"
#include "verify/scenes/kemppinen_presets.h"

namespace glintlab::kemppinen_sa {

enum class Reference { kBruteForce = 0, kSmooth = 1 };

// Base roughness and microroughness of every query (the model defaults of kemppinen_ggx).
inline constexpr double kAlpha = 0.3;
inline constexpr double kMicroroughness = 0.02;
// Queries per method in the benchmarks; the quick figure uses the first kQuickQueries of them.
inline constexpr int kBruteForceQueries = 192;
inline constexpr int kSmoothQueries = 1024;
inline constexpr int kQuickQueries = 24;

inline const char* ndf_name(bool ggx) { return ggx ? "kemppinen_ggx" : "kemppinen_beckmann"; }
inline const char* reference_name(Reference r) {
  return r == Reference::kBruteForce ? "dstar_f_vs_bruteforce" : "dstar_f_vs_smooth";
}
// The `<method>` part of a benchmark name, e.g. "kemppinen_ggx.dstar_f_vs_bruteforce".
inline std::string method_id(bool ggx, Reference r) {
  return std::string(ndf_name(ggx)) + "." + reference_name(r);
}
inline const char* reference_label(Reference r) {
  return r == Reference::kBruteForce
             ? "ref: Eq. 5 brute force over all points, footprints 0.25-16 cells; err = |D*f - "
               "D*| / D(h)"
             : "ref: smooth D (far field), footprints 256-16384 cells; err = |D*f - D| / D";
}

// One setting of Algorithm 1: k = side², erf of Eq. 10, MIP blending.
struct Setting {
  int side;
  kemppinen2025::Erf erf;
  kemppinen2025::Blend blend;
};
// "k=4,erf=fast" (roulette, the paper's choice) or "k=4,erf=fast,blend=linear".
inline std::string setting_name(const Setting& s) {
  std::string n = "k=" + std::to_string(s.side * s.side) +
                  (s.erf == kemppinen2025::Erf::kExact ? ",erf=exact" : ",erf=fast");
  if (s.blend == kemppinen2025::Blend::kLinear) n += ",blend=linear";
  return n;
}

inline kemppinen2025::Params<double> params(const Setting& s, std::uint64_t seed) {
  kemppinen2025::Params<double> p = kemppinen2025::preset_params(s.side, kMicroroughness, seed);
  p.erf = s.erf;
  p.blend = s.blend;
  return p;
}

struct Query {
  FootprintQuery<double> fp;
  Vec3<double> h;
  double cells;  // filter standard deviation in level-0 cells
};

// The n queries of `method_id(ggx, r)`, seeded by the hash of that id: uv uniform on [0, 100)²,
// footprint log-uniform over the reference's range, ω_h ~ D cosθ.
inline std::vector<Query> queries(bool ggx, Reference r, int n) {
  const std::uint64_t seed = hash_string(method_id(ggx, r).c_str());
  const kemppinen2025::Params<double> p =
      params({1, kemppinen2025::Erf::kExact, kemppinen2025::Blend::kRoulette}, 1);
  const double lo = r == Reference::kBruteForce ? 0.25 : 256,
               hi = r == Reference::kBruteForce ? 16 : 16384;
  std::vector<Query> out;
  out.reserve(std::size_t(n));
  for (int i = 0; i < n; ++i) {
    const auto u = [&](std::uint64_t d) {
      return counter_uniform<double>(seed, std::uint64_t(i), d);
    };
    const double cells = lo * std::pow(hi / lo, u(0));
    const Vec2<double> uv{100 * u(1), 100 * u(2)};
    const Vec2<double> w{u(3), u(4)};
    const Vec3<double> h = ggx ? sample_normal_walter(GGX<double>{kAlpha, kAlpha}, w)
                               : sample_normal_walter(Beckmann<double>{kAlpha, kAlpha}, w);
    out.push_back({kemppinen2025::footprint_cells(uv, cells, p), h, cells});
  }
  return out;
}

// D★^f (white facets: the x channel) of Algorithm 1 for every query.
inline std::vector<double> eval_all(bool ggx, const Setting& s, const std::vector<Query>& q) {
  const kemppinen2025::Params<double> p = params(s, 1);
  std::vector<double> v(q.size());
  with_ndf(ndf_kind(ggx), kAlpha, kAlpha, [&](const auto& ndf) {
    for (std::size_t i = 0; i < q.size(); ++i)
      v[i] = kemppinen2025::eval(p, ndf, q[i].fp, q[i].h).d.x;
    return 0;
  });
  return v;
}

// The reference value of every query: Eq. 5 by brute force (which depends on the blending, not
// on k or erf) or the smooth D; `scale` receives D(ω_h), the error's denominator.
inline std::vector<double> reference_all(bool ggx, Reference r, kemppinen2025::Blend blend,
                                         const std::vector<Query>& q, std::vector<double>* scale) {
  const kemppinen2025::Params<double> p = params({1, kemppinen2025::Erf::kExact, blend}, 1);
  std::vector<double> v(q.size());
  scale->assign(q.size(), 0.0);
  with_ndf(ndf_kind(ggx), kAlpha, kAlpha, [&](const auto& ndf) {
    for (std::size_t i = 0; i < q.size(); ++i) {
      (*scale)[i] = ndf.D(q[i].h);
      v[i] = r == Reference::kBruteForce
                 ? kemppinen2025::reference_filtered(p, ndf, q[i].fp, q[i].h).x
                 : (*scale)[i];
    }
    return 0;
  });
  return v;
}

struct Errors {
  double max = 0, rms = 0, p99 = 0;
  int n = 0;
};

// max, RMS and 99th percentile (nearest rank) of |value − reference| / scale.
inline Errors errors(const std::vector<double>& value, const std::vector<double>& ref,
                     const std::vector<double>& scale) {
  std::vector<double> e(value.size());
  double ss = 0;
  for (std::size_t i = 0; i < value.size(); ++i) {
    e[i] = std::abs(value[i] - ref[i]) / scale[i];
    ss += e[i] * e[i];
  }
  Errors out;
  out.n = int(e.size());
  if (e.empty()) return out;
  std::sort(e.begin(), e.end());
  out.max = e.back();
  out.rms = std::sqrt(ss / double(e.size()));
  const std::size_t rank = std::size_t(std::ceil(0.99 * double(e.size())));
  out.p99 = e[std::max<std::size_t>(rank, 1) - 1];
  return out;
}

// Every setting of the benchmarks: k ∈ {1, 4, 9, 16} × erf ∈ {exact, fast}, roulette; for the
// brute-force reference also linear blending.
inline std::vector<Setting> settings(Reference r) {
  std::vector<Setting> out;
  const int blends = r == Reference::kBruteForce ? 2 : 1;
  for (int b = 0; b < blends; ++b)
    for (int side = 1; side <= kemppinen2025::kMaxSide; ++side)
      for (kemppinen2025::Erf e : {kemppinen2025::Erf::kExact, kemppinen2025::Erf::kRational})
        out.push_back({side, e, static_cast<kemppinen2025::Blend>(b)});
  return out;
}

// Footprints (level-0 cells) of the cost-vs-footprint rows: constant time over all of them, the
// brute force up to kBruteForceMaxCells (its cost grows with the footprint's area).
inline constexpr int kCostCells[] = {1, 2, 4, 8, 16, 32, 64, 256, 1024, 4096};
inline constexpr int kBruteForceMaxCells = 32;

// The query of cost row i at `cells` (uv and ω_h vary; the footprint is fixed).
inline Query cost_query(std::uint64_t i, double cells) {
  const kemppinen2025::Params<double> p =
      params({1, kemppinen2025::Erf::kExact, kemppinen2025::Blend::kRoulette}, 1);
  const Vec2<double> uv{counter_uniform<double>(9, i, 0) * 100,
                        counter_uniform<double>(9, i, 1) * 100};
  const Vec3<double> h = normalize(Vec3<double>{0.1 * counter_uniform<double>(9, i, 2), 0.05, 1});
  return {kemppinen2025::footprint_cells(uv, cells, p), h, cells};
}

}  // namespace glintlab::kemppinen_sa

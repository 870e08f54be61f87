// Random kernel inputs over each Domain's edge cases (see inputs.h for the distributions).
#include "core/simd/inputs.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/math/orthonormal_basis.h"
#include "core/math/rng.h"
#include "core/model.h"
#include "core/model_layout.h"
#include "core/samplers/walter.h"
#include "core/simd/kernels.h"

namespace glintlab::simd {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr double kDeg = kPiD / 180.0;

Vec3<double> from_angles(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

struct Row {
  double ax, ay, alpha;
  Vec3<double> wi, wo, m;
  double u1, u2, px, py, f0, eta, kappa;
};

Row make_row(std::uint64_t seed, std::uint64_t i) {
  int dim = 0;
  const auto u = [&] {
    return counter_uniform<double>(seed, i, static_cast<std::uint64_t>(dim++));
  };
  const auto log_alpha = [](double t) { return 1e-3 * std::pow(2e3, t); };
  Row r{};
  r.ax = log_alpha(u());
  const double iso = u();
  const double ratio = std::pow(10.0, 6.0 * u() - 3.0);
  r.ay = iso < 0.3 ? r.ax : std::clamp(r.ax * ratio, 1e-3, 2.0);
  r.alpha = log_alpha(u());

  const double mode_wi = u(), phi_wi = 2.0 * kPiD * u(), t_wi = u();
  if (mode_wi < 0.40) {
    r.wi = from_angles(std::acos(1.0 - t_wi), phi_wi);  // cosθ in (0, 1]
  } else if (mode_wi < 0.65) {
    r.wi = from_angles((80.0 + 9.9 * t_wi) * kDeg, phi_wi);
  } else if (mode_wi < 0.85) {
    r.wi = from_angles(std::acos(-t_wi), phi_wi + 0.0);  // cosθ in [−1, 0]
    if (r.wi.z == 0.0) r.wi.z = -1e-6;
  } else if (mode_wi < 0.90) {
    r.wi = {0.0, 0.0, 1.0};
  } else {
    r.wi = from_angles((89.9 + 0.1 * t_wi) * kDeg, phi_wi);
  }

  const Vec2<double> um{u(), u()};
  const Vec3<double> m_ndf = sample_normal_walter(GGX<double>{r.ax, r.ay}, um);
  const double mode_m = u(), phi_m = 2.0 * kPiD * u(), t_m = u();
  if (mode_m < 0.5) {
    r.m = m_ndf;
  } else if (mode_m < 0.8) {
    r.m = from_angles(std::acos(1.0 - t_m), phi_m);
  } else {
    r.m = from_angles(std::acos(1.0 - 2.0 * t_m), phi_m);
  }
  const double mode_wo = u(), phi_wo = 2.0 * kPiD * u(), t_wo = u();
  r.wo = mode_wo < 0.5 ? normalize(reflect(r.wi, m_ndf))
                       : from_angles(std::acos(1.0 - 2.0 * t_wo), phi_wo);

  const auto uniform_with_edges = [&] {
    const double mode = u(), v = u();
    if (mode >= 0.05) return v;
    constexpr double kEdges[4] = {0.0, 0x1p-24, 0.5, 1.0 - 0x1p-24};
    return kEdges[std::min(3, static_cast<int>(v * 4.0))];
  };
  r.u1 = uniform_with_edges();
  r.u2 = uniform_with_edges();

  const double mode_p = u(), phi_p = 2.0 * kPiD * u(), t_p = u();
  const double rho = mode_p < 0.1 ? 1.0 - 1e-4 * t_p : std::sqrt(t_p);
  r.px = 0.5 + 0.5 * rho * std::cos(phi_p);
  r.py = 0.5 + 0.5 * rho * std::sin(phi_p);
  r.f0 = u();
  r.eta = 0.2 + 2.8 * u();
  r.kappa = 5.0 * u();
  return r;
}

double pick(const Row& r, Domain d) {
  switch (d) {
    case Domain::kAlphaX:
      return r.ax;
    case Domain::kAlphaY:
      return r.ay;
    case Domain::kAlpha:
      return r.alpha;
    case Domain::kWiX:
      return r.wi.x;
    case Domain::kWiY:
      return r.wi.y;
    case Domain::kWiZ:
      return r.wi.z;
    case Domain::kWoX:
      return r.wo.x;
    case Domain::kWoY:
      return r.wo.y;
    case Domain::kWoZ:
      return r.wo.z;
    case Domain::kMX:
      return r.m.x;
    case Domain::kMY:
      return r.m.y;
    case Domain::kMZ:
      return r.m.z;
    case Domain::kU1:
      return r.u1;
    case Domain::kU2:
      return r.u2;
    case Domain::kPX:
      return r.px;
    case Domain::kPY:
      return r.py;
    case Domain::kF0:
      return r.f0;
    case Domain::kEta:
      return r.eta;
    case Domain::kKappa:
      return r.kappa;
  }
  return 0.0;
}

}  // namespace

std::vector<std::vector<double>> make_inputs(std::span<const int> domains, std::size_t n,
                                             std::uint64_t seed) {
  std::vector<std::vector<double>> cols(domains.size(), std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const Row r = make_row(seed, i);
    for (std::size_t j = 0; j < domains.size(); ++j) {
      cols[j][i] = pick(r, static_cast<Domain>(domains[j]));
    }
  }
  return cols;
}

void add_scene_columns(unsigned needs, std::vector<std::vector<double>>& query,
                       std::uint64_t seed) {
  const std::size_t n = query.empty() ? 0 : query[0].size();
  const auto u = [&](std::size_t i, std::uint64_t d) {
    return counter_uniform<double>(seed, i, d);
  };
  const auto sphere = [&](std::size_t i, std::uint64_t d) {
    const double z = 2 * u(i, d) - 1, phi = 2 * kPiD * u(i, d + 1);
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    return Vec3<double>{r * std::cos(phi), r * std::sin(phi), z};
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (needs & kNeedsFootprint) {
      const bool origin = u(i, 0) < 0.05;
      query[query_column_index("u")][i] = origin ? 0.0 : 4 * u(i, 1);
      query[query_column_index("v")][i] = origin ? 0.0 : 4 * u(i, 2);
      const double area = u(i, 3) < 0.04 ? 0.0 : std::pow(10.0, -14 + 12 * u(i, 4));
      const double t = std::pow(10.0, 2 * u(i, 5) - 1);  // aspect 1:10 .. 10:1
      const double a = 2 * kPiD * u(i, 6), b = a + 0.2 + 2.7 * u(i, 7);
      const double s2 = area / (t * std::abs(std::sin(b - a)));
      const double s1 = std::sqrt(s2);
      query[query_column_index("dudx")][i] = s1 * std::cos(a);
      query[query_column_index("dvdx")][i] = s1 * std::sin(a);
      query[query_column_index("dudy")][i] = s1 * t * std::cos(b);
      query[query_column_index("dvdy")][i] = s1 * t * std::sin(b);
    }
    if (needs & (kNeedsPointLight | kNeedsAreaLight)) {
      query[query_column_index("light_cos_half_angle")][i] =
          u(i, 8) < 0.2 ? 1.0 : std::cos(std::pow(10.0, -4 + 3.7 * u(i, 9)));
    }
    if (needs & kNeedsPixelCorners) {
      const Vec3<double> l{query[query_column_index("wo_x")][i],
                           query[query_column_index("wo_y")][i],
                           query[query_column_index("wo_z")][i]};
      const OrthonormalBasis<double> f = basis_from_z(l);
      const double kind = u(i, 10);
      std::array<Vec3<double>, 4> r{};
      if (kind < 0.8) {
        const double h = std::pow(10.0, -4 + 3.5 * u(i, 11));
        const double shift = 3 * h * u(i, 12), phi = 2 * kPiD * u(i, 13);
        const double sx[4] = {-1, 1, -1, 1}, sy[4] = {-1, -1, 1, 1};
        for (std::size_t c = 0; c < 4; ++c) {
          const double x = shift * std::cos(phi) + h * (sx[c] + 0.6 * (u(i, 14 + 2 * c) - 0.5));
          const double y = shift * std::sin(phi) + h * (sy[c] + 0.6 * (u(i, 15 + 2 * c) - 0.5));
          r[c] = normalize(l + x * f.x + y * f.y);
        }
      } else if (kind < 0.85) {
        r = {l, l, l, l};
      } else if (kind < 0.9) {
        const Vec3<double> d = sphere(i, 22);
        r = {d, d, d, d};
      } else {
        for (std::size_t c = 0; c < 4; ++c) r[c] = sphere(i, 24 + 2 * c);
      }
      for (std::size_t c = 0; c < 4; ++c) {
        query[query_column_index("r0_x") + 3 * c][i] = r[c].x;
        query[query_column_index("r0_y") + 3 * c][i] = r[c].y;
        query[query_column_index("r0_z") + 3 * c][i] = r[c].z;
      }
    }
  }
}

}  // namespace glintlab::simd

// kemppinen.jacobian's part (a) (verify/claims/kemppinen/jacobian.cpp): Eq. 3's printed factor
// D/|U_Ω| and core/maps' analytic Jacobian of T against the map's Jacobian by finite differences,
// for the GGX map T = L∘M̃ (Sec. 3.2.1, Eq. 6–7) and the Beckmann map T = B1⁻¹∘B2⁻¹ (Sec. 3.2.2).
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/maps/beckmann_map.h"
#include "core/maps/ggx_map.h"
#include "verify/claims/kemppinen/common.h"

namespace glintlab::verify::kemppinen_claims {

// The roughnesses every part of the check is measured at.
struct Alpha {
  double x, y;
};
inline const std::vector<Alpha> kAlphas = {{0.1, 0.1}, {0.5, 0.5}, {1, 1}, {0.2, 0.6}, {1, 0.1}};

// The density of the uniform disk inscribed in the unit square, where T takes the lobe.
inline double uniform_disk_pdf(const V2& p) {
  const double dx = p.x - 0.5, dy = p.y - 0.5;
  return dx * dx + dy * dy <= 0.25 ? 4 / std::numbers::pi : 0.0;
}

// |det dT/dω| per steradian by central differences on the tangent plane at ω (ω(s, t) =
// normalize(ω + s e1 + t e2), e1, e2 orthonormal ⊥ ω), step h ≪ the lobe width.
template <class Ndf>
inline double fd_jacobian(const Ndf& ndf, const V3& w, double h) {
  const double st = std::hypot(w.x, w.y);
  const V3 e1 = st > 1e-12 ? V3{-w.y / st, w.x / st, 0} : V3{0, 1, 0};
  const V3 e2 = cross(w, e1);
  auto at = [&](double s, double t) { return map_to_square(ndf, normalize(w + s * e1 + t * e2)); };
  const V2 ds = (0.5 / h) * (at(h, 0) - at(-h, 0)), dt = (0.5 / h) * (at(0, h) - at(0, -h));
  return std::abs(ds.x * dt.y - ds.y * dt.x);
}

struct JacobianReport {
  double fd_vs_true = 0;   // max |log(J_fd / J_true)|: the analytic Jacobian is the map's
  double paper_vs_fd = 0;  // max |log(J_paper / J_fd)|: Eq. 3 against the map
  double ratio_min = 1e300, ratio_max = 0;  // J_paper / J_fd
  double formula_error = 0;  // max |ratio / (32/(π²‖Mᵀω‖)) − 1| (GGX), |ratio / (16/(π² ωz)) − 1|
  std::string worst;           // where paper_vs_fd is largest
  double control_min = 1e300;  // min |log(J_fd / (1.02 J_true))|: a 2 % error must be seen
  double control_max = 0;      // max |log(J_fd / (1.02 J_true))|: J_T × 1.02 as the formula
};

template <class Ndf>
inline void measure_jacobian(const Ndf& ndf, bool ggx, JacobianReport& rep) {
  const double h = 1e-5 * std::min({ndf.alpha_x, ndf.alpha_y, 1.0});
  for (double deg : {0.0, 15.0, 30.0, 45.0, 60.0, 75.0})
    for (double phi : {0.3, 2.0, 4.4}) {
      const double t = deg * std::numbers::pi / 180;
      const V3 w{std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t)};
      // Beckmann's map squeezes the Gaussian tail towards the rim exponentially (|J_T| ∝ e^{−t},
      // t = |(ωx/αx, ωy/αy)|²/ωz²); beyond t = 10 finite differences mostly see rounding
      // (measured: 1 % at t = 23).
      if (!ggx && (sqr(w.x / ndf.alpha_x) + sqr(w.y / ndf.alpha_y)) / sqr(w.z) > 10) continue;
      const double fd = fd_jacobian(ndf, w, h);
      const double jt = map_jacobian_true(ndf, w), jp = map_jacobian_paper(ndf, w);
      rep.fd_vs_true = std::max(rep.fd_vs_true, std::abs(std::log(fd / jt)));
      rep.control_min = std::min(rep.control_min, std::abs(std::log(fd / (1.02 * jt))));
      rep.control_max = std::max(rep.control_max, std::abs(std::log(fd / (1.02 * jt))));
      const double ratio = jp / fd;
      rep.ratio_min = std::min(rep.ratio_min, ratio);
      rep.ratio_max = std::max(rep.ratio_max, ratio);
      const double expect =
          ggx ? 32 / (std::numbers::pi * std::numbers::pi *
                      std::sqrt(sqr(w.x / ndf.alpha_x) + sqr(w.y / ndf.alpha_y) + sqr(w.z)))
              : 16 / (std::numbers::pi * std::numbers::pi * w.z);
      rep.formula_error = std::max(rep.formula_error, std::abs(ratio / expect - 1));
      if (std::abs(std::log(ratio)) > rep.paper_vs_fd) {
        rep.paper_vs_fd = std::abs(std::log(ratio));
        rep.worst = fmt::format("{} α=({:g},{:g}) θ={:g}° (J_paper/J_T = {:.4g})",
                                ggx ? "GGX" : "Beckmann", ndf.alpha_x, ndf.alpha_y, deg, ratio);
      }
    }
}

}  // namespace glintlab::verify::kemppinen_claims

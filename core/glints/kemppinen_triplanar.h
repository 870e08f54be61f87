// The triplanar (UV-free) mode of Kemppinen et al. 2025 Sec. 3.3.6 as the models kemppinen_ggx /
// kemppinen_beckmann expose it (`mapping=triplanar`): the object-space inputs it needs derived
// from a model query, and Algorithm 2 extended to the blend of the three point processes.
//
// A model query carries a footprint (uv and ∂uv/∂pixel), not a position. In triplanar mode the
// shaded surface is the plane through the object-space origin with unit normal n(θ_n, φ_n) (the
// parameters normal_theta, normal_phi), with the tangent frame (t, b) of Duff et al. 2017
// (core/math/orthonormal_basis.h); the footprint's uv is the position in that frame:
// p = u t + v b, ∂p/∂x = ∂u/∂x t + ∂v/∂x b (likewise y). For n = +z, t = x and b = y, so p = (u, v,
// 0): the z plane's process is the uv process (triplanar_process) and triplanar D★^f
// equals the uv path's exactly.
//
// Sampling (the paper gives no triplanar sampler): choose plane i with probability w_i (the blend
// weights), then Algorithm 2 on that plane's process; density Σ_i w_i p_i(ω_h), each p_i the
// marginal of kemppinen_sampling.h. The "printed" pdf option returns w_i × the chosen plane's
// Algorithm 2 pdf (lines 16–17), a function of the draw as in the uv case.
#pragma once

#include <cstdint>

#include "core/glints/kemppinen.h"
#include "core/glints/kemppinen_sampling.h"
#include "core/math/orthonormal_basis.h"

namespace glintlab::kemppinen2025 {

// The object-space inputs of eval_triplanar for one query.
template <class T>
struct TriplanarInput {
  Vec3<T> pos, dpos_dx, dpos_dy, normal;
};

// n(θ, φ) from degrees: (sin θ cos φ, sin θ sin φ, cos θ).
template <class T>
GLINTLAB_FN Vec3<T> object_normal(T theta_deg, T phi_deg) {
  const T k = T(kPi<T>) / T(180);
  const T st = sin(theta_deg * k);
  return {st * cos(phi_deg * k), st * sin(phi_deg * k), cos(theta_deg * k)};
}

template <class T>
GLINTLAB_FN TriplanarInput<T> triplanar_input(const FootprintQuery<T>& fp, Vec3<T> normal) {
  const OrthonormalBasis<T> f = basis_from_z(normal);
  const auto on_plane = [&](Vec2<T> a) { return a.x * f.x + a.y * f.y; };
  return {on_plane(fp.uv), on_plane(fp.duv_dx), on_plane(fp.duv_dy), normal};
}

template <class Ndf, class T>
GLINTLAB_FN Result<T> eval_triplanar(const Params<T>& p, const Ndf& ndf, const TriplanarInput<T>& in,
                         Vec3<T> h) {
  return eval_triplanar(p, ndf, in.pos, in.dpos_dx, in.dpos_dy, in.normal, h);
}

// One ω_h: plane i with probability w_i (sampler dimension 6, unused by Algorithm 2's draws),
// then Algorithm 2 on its process. pdf_printed_h carries the factor w_i. Generic over T: the
// plane is a mask per lane, and a plane's sampler runs when any lane chose it.
template <class Ndf, class T>
GLINTLAB_FN HalfSample<T> triplanar_sample_half(const Params<T>& p, const Ndf& ndf, const TriplanarInput<T>& in,
                                    const LaneInt<T, std::uint64_t>& key) {
  const Vec3<T> wv = triplanar_weights(in.normal);
  const T w[3] = {wv.x, wv.y, wv.z};
  const Mask<T> nonempty[3] = {w[0] > T(0), w[1] > T(0), w[2] > T(0)};
  const T u = sampler_uniform<T>(key, 6);
  // The first plane whose running sum of weights exceeds u; where rounding leaves u ≥ Σw, the
  // last non-empty plane.
  Mask<T> chosen[3];
  Mask<T> found = T(0) > T(1);
  T acc = T(0);
  for (int i = 0; i < 3; ++i) {
    acc += w[i];
    chosen[i] = !found && (u < acc) && nonempty[i];
    found = found || chosen[i];
  }
  chosen[2] = chosen[2] || (!found && nonempty[2]);
  chosen[1] = chosen[1] || (!found && !nonempty[2] && nonempty[1]);
  chosen[0] = chosen[0] || (!found && !nonempty[2] && !nonempty[1]);
  HalfSample<T> out{};
  for (int i = 0; i < 3; ++i) {
    if (!any_lane<T>(chosen[i])) continue;
    HalfSample<T> s = sample_half(p, ndf, triplanar_footprint(i, in.pos, in.dpos_dx, in.dpos_dy),
                                  key, triplanar_process(i));
    s.pdf_printed_h *= w[i];
    const Mask<T>& m = chosen[i];
    out.x = {select(m, s.x.x, out.x.x), select(m, s.x.y, out.x.y)};
    out.h = {select(m, s.h.x, out.h.x), select(m, s.h.y, out.h.y), select(m, s.h.z, out.h.z)};
    out.pdf_printed_h = select(m, s.pdf_printed_h, out.pdf_printed_h);
    out.pdf_conditional_x = select(m, s.pdf_conditional_x, out.pdf_conditional_x);
    out.level = int_select<T>(m, s.level, out.level);
    out.ok = (m && s.ok) || (!m && out.ok);
  }
  return out;
}

// The density of triplanar_sample_half's ω_h per steradian: Σ_i w_i p_i(ω_h).
template <class Ndf, class T>
GLINTLAB_FN T triplanar_density_half(const Params<T>& p, const Ndf& ndf, const TriplanarInput<T>& in,
                         Vec3<T> h) {
  const Vec3<T> wv = triplanar_weights(in.normal);
  const T w[3] = {wv.x, wv.y, wv.z};
  T sum = T(0);
  for (int i = 0; i < 3; ++i) {
    const Mask<T> nonempty = w[i] > T(0);
    if (!any_lane<T>(nonempty)) continue;
    sum += select(
        nonempty,
        w[i] * sample_density_half(p, ndf, triplanar_footprint(i, in.pos, in.dpos_dx, in.dpos_dy),
                                   h, triplanar_process(i)),
        T(0));
  }
  return sum;
}

}  // namespace glintlab::kemppinen2025

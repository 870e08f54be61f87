// Importance sampling of the whole filtered glinty NDF D★^f of Kemppinen et al. 2025 (Eq. 11:
// explicit points + compensation C of Eq. 10) as a one-sample mixture of Algorithm 2 (the explicit
// part, Sec. 3.3.5) and the smooth NDF's sampler ω_h ~ D cosθ (Walter et al. 2007 Eq. 28–29,
// 35–36) for the compensation, with the exact mixture density and with Algorithm 2's printed pdf.
//
// What the paper specifies: Algorithm 2 samples the sum of Gaussians of Eq. 11 and "we choose to
// not sample the compensation term" (Sec. 3.3.5). An estimator that divides the whole D★^f by a
// density of Algorithm 2 alone has a weight C/p that is unbounded wherever the explicit lobes'
// tails vanish, so it cannot be used where C matters. What is our choice here:
// * the mixture: strategy 1 (Algorithm 2, sample_half) with probability q, strategy 2
//   (ω_h ~ D cosθ) with 1 − q; one sample, its density the balance of both:
//   p(ω_h) = q p₁(ω_h) + (1 − q) D(ω_h) cosθ_h (one-sample MIS with the balance heuristic, Veach
//   1997 Sec. 9.2.4). p₁ is Algorithm 2's marginal (sample_density_half; defective by
//   its rejections, which return no direction and contribute 0, so f/p stays unbiased).
// * q, the explicit share: the fraction of the Gaussian lobe mass that lies in B(k) rather than in
//   the compensation's □ \ B(k), averaged over a 4 × 4 grid of x_a in the angular cell at the
//   centre of U_Ω for both levels (weights 1 − w₁, w₁), with the lobe width σ there (the widest,
//   D being largest at the centre for GGX and Beckmann); clamped to [0.1, 0.9] so that each
//   strategy keeps at least a tenth of the samples (f/p ≤ 10 f/p_k for either strategy k: the
//   mixture is never much noisier than either alone). q depends on the query only, not on ω_h.
// * the printed variant (what a user of the paper writes): the same mixture with p₁ replaced by
//   Algorithm 2's returned pdf (lines 16–17, pdf_printed_h of kemppinen_sampling.h) for a sample
//   of strategy 1, and for a sample of strategy 2 by the printed formula evaluated without a draw:
//   x_a := T(ω_h) and both levels summed with their weights w_l (Algorithm 2 only returns the pdf
//   of its own draw, so some evaluation rule is needed for MIS; this is the natural one).
//
// Like Algorithm 2 in kemppinen_sampling.h these are host functions for scalar T (a thread-local
// block buffer, loops over the k⁴ candidates of the drawn block), not SIMD kernels.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/glints/kemppinen.h"
#include "core/glints/kemppinen_sampling.h"
#include "core/samplers/walter.h"

namespace glintlab::kemppinen2025 {

// Bounds of the explicit-strategy probability q (see above).
inline constexpr double kMixtureMin = 0.1;
inline constexpr double kMixtureMax = 0.9;

// The fraction of the lobe mass inside B(k) at level `level`, averaged over a 4 × 4 grid of x_a in
// the angular cell at the centre of □.
template <class Ndf, class T>
T level_explicit_share(const Params<T>& p, const Ndf& ndf, int level) {
  const std::int64_t n_a = std::int64_t(1) << level;
  const T res_a = angular_resolution<T>(level);
  const std::int64_t c = std::max<std::int64_t>(n_a / 2 - 1, 0);
  T near_sum = T(0), whole_sum = T(0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const Vec2<T> x_a{(T(c) + (T(i) + T(0.5)) / T(4)) / res_a,
                        (T(c) + (T(j) + T(0.5)) / T(4)) / res_a};
      const Vec2<T> sigma = point_sigma(p, ndf, x_a);
      const std::int64_t ax0 = block_start(x_a.x * res_a, p.side);
      const std::int64_t ay0 = block_start(x_a.y * res_a, p.side);
      const Vec2<T> lo{T(std::max<std::int64_t>(ax0, 0)) / res_a,
                       T(std::max<std::int64_t>(ay0, 0)) / res_a};
      const Vec2<T> hi{T(std::min<std::int64_t>(ax0 + p.side, n_a)) / res_a,
                       T(std::min<std::int64_t>(ay0 + p.side, n_a)) / res_a};
      near_sum += gaussian_rect_mass(lo, hi, x_a, sigma, Erf::kExact);
      whole_sum +=
          gaussian_rect_mass(Vec2<T>{T(0), T(0)}, Vec2<T>{T(1), T(1)}, x_a, sigma, Erf::kExact);
    }
  return whole_sum > T(0) ? near_sum / whole_sum : T(1);
}

// q: the probability of sampling the explicit part with Algorithm 2 (our choice, see the header).
template <class Ndf, class T>
T mixture_probability(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp) {
  const Spatial<T> sp = spatial(p, fp);
  const T share = (T(1) - sp.w1) * level_explicit_share(p, ndf, sp.l0) +
                  sp.w1 * level_explicit_share(p, ndf, sp.l0 + 1);
  return clamp(share, T(kMixtureMin), T(kMixtureMax));
}

// Algorithm 2's printed pdf (lines 16–17) evaluated at ω_h without a draw: x_a := T(ω_h), summed
// over both levels with their weights, per steradian (the MIS evaluation rule of the header).
template <class Ndf, class T>
T printed_pdf_at(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp, Vec3<T> h) {
  if (!(h.z > T(0))) return T(0);
  const Vec2<T> x = map_to_square(ndf, h);
  if (sqr(x.x - T(0.5)) + sqr(x.y - T(0.5)) > T(0.25)) return T(0);
  const Spatial<T> sp = spatial(p, fp);
  static thread_local Block<T> block;
  T total = T(0);
  for (int up = 0; up < 2; ++up) {
    const int level = sp.l0 + up;
    const T w_l = up ? sp.w1 : T(1) - sp.w1;
    if (!(w_l > T(0))) continue;
    const T res_a = angular_resolution<T>(level);
    kemppinen2025::block(p, ndf, sp, level, w_l, block_start(x.x * res_a, p.side),
                         block_start(x.y * res_a, p.side), block);
    const T area_b = (block.hi.x - block.lo.x) * (block.hi.y - block.lo.y);
    total += block_density(block, x) * area_b * w_l;
  }
  return total * map_jacobian_paper(ndf, h) * h.z;
}

template <class T>
struct FullSample {
  Vec3<T> h;           // ω_h
  T pdf_h;             // exact mixture density q p₁ + (1 − q) D cosθ, per steradian of ω_h
  T pdf_printed_h;     // the same mixture with Algorithm 2's printed pdf as p₁
  T q;                 // probability of the explicit strategy
  bool from_explicit;  // drawn by Algorithm 2 (else by D cosθ)
  bool ok;             // false: Algorithm 2 produced no direction (contributes 0)
};

// The random number `dim` of the mixture's own choices (Algorithm 2 uses the key's dims 0–5).
template <class T>
T mixture_uniform(std::uint64_t key, std::uint64_t dim) {
  return counter_uniform<T>(key, 0x66756c6cULL, dim);
}

// The exact mixture density of ω_h (q from mixture_probability).
template <class Ndf, class T>
T full_sample_density_half(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp,
                           Vec3<T> h, T q) {
  if (!(h.z > T(0))) return T(0);
  return q * sample_density_half(p, ndf, fp, h) + (T(1) - q) * ndf.D(h) * h.z;
}

// One ω_h from the mixture, random numbers from `key`, with both densities.
template <class Ndf, class T>
FullSample<T> sample_full(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp,
                          std::uint64_t key, T q) {
  FullSample<T> out{};
  out.q = q;
  out.from_explicit = mixture_uniform<T>(key, 0) < q;
  T p1_printed = T(0);
  if (out.from_explicit) {
    const HalfSample<T> s = sample_half(p, ndf, fp, key);
    if (!s.ok) return out;
    out.h = s.h;
    p1_printed = s.pdf_printed_h;
  } else {
    out.h =
        sample_normal_walter(ndf, Vec2<T>{mixture_uniform<T>(key, 1), mixture_uniform<T>(key, 2)});
    if (!(out.h.z > T(0))) return out;
    p1_printed = printed_pdf_at(p, ndf, fp, out.h);
  }
  const T p2 = ndf.D(out.h) * out.h.z;
  out.pdf_h = q * sample_density_half(p, ndf, fp, out.h) + (T(1) - q) * p2;
  out.pdf_printed_h = q * p1_printed + (T(1) - q) * p2;
  out.ok = out.pdf_h > T(0);
  return out;
}

}  // namespace glintlab::kemppinen2025

// Importance sampling of the whole filtered glinty NDF D★^f of Kemppinen et al. 2025 (Eq. 11:
// explicit points + compensation C of Eq. 10) as a one-sample mixture of Algorithm 2 (the explicit
// part, Sec. 3.3.5) and the smooth NDF's sampler ω_h ~ D cosθ (Walter et al. 2007 Eq. 28–29,
// 35–36) for the compensation, with the exact mixture density and with Algorithm 2's printed pdf.
// The models kemppinen_ggx / kemppinen_beckmann sample with it (core/models/kemppinen_model.h),
// and so do the figures and the environment-light claims (verify/scenes/kemppinen_env_radiance.h).
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
// * triplanar (Sec. 3.3.6): strategy 1 is the blend of the three planes' Algorithm 2
//   (triplanar_sample_half), q the planes' explicit shares blended by their weights w_i, and the
//   printed formula at ω_h the planes' printed_pdf_at blended by w_i.
//
// Generic over T (float, double, a SIMD batch), as Algorithm 2 in kemppinen_sampling.h: the
// strategy is a mask per lane, and each strategy's code runs when any lane chose it (uniform
// early-outs, never per-lane branches). For double the results are those of the scalar code.
#pragma once

#include <bit>
#include <cstdint>
#include <type_traits>

#include "core/glints/kemppinen.h"
#include "core/glints/kemppinen_sampling.h"
#include "core/glints/kemppinen_triplanar.h"
#include "core/samplers/walter.h"

namespace glintlab::kemppinen2025 {

// Bounds of the explicit-strategy probability q (see above).
inline constexpr double kMixtureMin = 0.1;
inline constexpr double kMixtureMax = 0.9;

// One grid point (fi, fj) ∈ {0…3}² of level_explicit_share at `level`: its lobe's mass inside B(k)
// (`near`) and in □ (`whole`), x_a = (c + (fi + ½)/4, c + (fj + ½)/4)/res_a.
template <class T>
struct ShareTerms {
  T near, whole;
};

template <class Ndf, class T>
GLINTLAB_FN ShareTerms<T> level_share_terms(const Params<T>& p, const Ndf& ndf,
                                            const LaneInt<T, int>& level, T fi, T fj) {
  const LaneInt<T> n_a = level_cells<T>(level);
  const T res_a = angular_resolution<T>(level);
  const T c = max(floor(res_a * T(0.5)) - T(1), T(0));
  const Vec2<T> x_a{(c + (fi + T(0.5)) / T(4)) / res_a, (c + (fj + T(0.5)) / T(4)) / res_a};
  const Vec2<T> sigma = point_sigma(p, ndf, x_a);
  const LaneInt<T> ax0 = block_start(x_a.x * res_a, p.side);
  const LaneInt<T> ay0 = block_start(x_a.y * res_a, p.side);
  const Vec2<T> lo{int_to_float<T>(int_max(ax0, std::int64_t(0))) / res_a,
                   int_to_float<T>(int_max(ay0, std::int64_t(0))) / res_a};
  const Vec2<T> hi{int_to_float<T>(int_min(ax0 + p.side, n_a)) / res_a,
                   int_to_float<T>(int_min(ay0 + p.side, n_a)) / res_a};
  // gaussian_rect_mass over B(k) and over □, their shared erfs computed once.
  const UnitAndPartMass<T> mx = unit_and_part_mass(lo.x, hi.x, x_a.x, sigma.x, Erf::kExact);
  const UnitAndPartMass<T> my = unit_and_part_mass(lo.y, hi.y, x_a.y, sigma.y, Erf::kExact);
  return {mx.part * my.part, mx.whole * my.whole};
}

// The fraction of the lobe mass inside B(k) at level `level`, averaged over a 4 × 4 grid of x_a in
// the angular cell at the centre of □ (index max(n_a/2 − 1, 0) on both axes).
template <class Ndf, class T>
GLINTLAB_FN T level_explicit_share(const Params<T>& p, const Ndf& ndf, const LaneInt<T, int>& level) {
  T near_sum = T(0), whole_sum = T(0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const ShareTerms<T> t = level_share_terms(p, ndf, level, T(i), T(j));
      near_sum += t.near;
      whole_sum += t.whole;
    }
  const Mask<T> has = whole_sum > T(0);
  return select(has, near_sum / select(has, whole_sum, T(1)), T(1));
}

// Whether every lane of x has the bits of lane 0.
template <class T>
GLINTLAB_FN bool same_in_every_lane(const T& x) {
  using Bits = std::conditional_t<sizeof(Scalar<T>) == 4, std::uint32_t, std::uint64_t>;
  const LanesOf<T> v(x);
  for (std::size_t l = 1; l < kLaneCount<T>; ++l)
    if (std::bit_cast<Bits>(v[l]) != std::bit_cast<Bits>(v[0])) return false;
  return true;
}

// level_explicit_share at levels l0 and l0 + 1 of a batch, bit for bit, where the share's
// parameters (α★, a, the NDF's α) are the same in every lane: the share is then a function of the
// level alone, so each distinct level's 16 grid points are computed once, spread over the lanes
// (16 per level instead of a batch of lanes per grid point), and summed per level in the loop's
// order. False (nothing written) where a parameter differs between lanes or a level is outside
// [0, kMaxLevel].
template <class Ndf, class T>
GLINTLAB_FN bool level_explicit_shares_by_level(const Params<T>& p, const Ndf& ndf,
                                                const LaneInt<T, int>& l0, T& share0, T& share1) {
  using S = Scalar<T>;
  constexpr std::size_t kLanes = kLaneCount<T>;
  constexpr std::size_t kGrid = 16;
  if (!same_in_every_lane(p.microroughness) || !same_in_every_lane(p.anisotropy) ||
      !same_in_every_lane(ndf.alpha_x) || !same_in_every_lane(ndf.alpha_y))
    return false;
  bool present[kMaxLevel + 1] = {};
  for (std::size_t l = 0; l < kLanes; ++l) {
    const int level = lane(l0, l);
    if (level < 0 || level + 1 > kMaxLevel) return false;
    present[level] = present[level + 1] = true;
  }
  int levels[kMaxLevel + 1] = {};
  int slot[kMaxLevel + 1] = {};
  std::size_t count = 0;
  for (int level = 0; level <= kMaxLevel; ++level)
    if (present[level]) {
      slot[level] = int(count);
      levels[count++] = level;
    }
  constexpr std::size_t kItems = (kMaxLevel + 1) * kGrid;
  S near[kItems + kLanes], whole[kItems + kLanes];
  const std::size_t items = count * kGrid;
  for (std::size_t first = 0; first < items; first += kLanes) {
    // Item t: level levels[t / 16], grid point (i, j) = ((t % 16) / 4, t % 4); lanes past the
    // last item repeat item 0.
    const auto item = [&](std::size_t l) { return first + l < items ? first + l : 0; };
    const LaneInt<T, int> level =
        int_lanes<T, int>([&](std::size_t l) { return levels[item(l) / kGrid]; });
    const T fi = float_lanes<T>([&](std::size_t l) { return S(int(item(l) % kGrid / 4)); });
    const T fj = float_lanes<T>([&](std::size_t l) { return S(int(item(l) % 4)); });
    const ShareTerms<T> t = level_share_terms(p, ndf, level, fi, fj);
    LaneAccess<T>::store(t.near, near + first);
    LaneAccess<T>::store(t.whole, whole + first);
  }
  S share[kMaxLevel + 1];
  for (std::size_t k = 0; k < count; ++k) {
    S near_sum = S(0), whole_sum = S(0);
    for (std::size_t g = 0; g < kGrid; ++g) {
      near_sum += near[k * kGrid + g];
      whole_sum += whole[k * kGrid + g];
    }
    share[k] = whole_sum > S(0) ? near_sum / whole_sum : S(1);
  }
  share0 = float_lanes<T>([&](std::size_t l) { return share[slot[lane(l0, l)]]; });
  share1 = float_lanes<T>([&](std::size_t l) { return share[slot[lane(l0, l) + 1]]; });
  return true;
}

// The explicit share at a footprint, both levels with their weights (before the clamp of q).
template <class Ndf, class T>
GLINTLAB_FN T explicit_share(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp) {
  const Spatial<T> sp = spatial(p, fp);
  if constexpr (kLaneCount<T> > 1) {
    T share0, share1;
    if (level_explicit_shares_by_level(p, ndf, sp.l0, share0, share1))
      return (T(1) - sp.w1) * share0 + sp.w1 * share1;
  }
  return (T(1) - sp.w1) * level_explicit_share(p, ndf, sp.l0) +
         sp.w1 * level_explicit_share(p, ndf, sp.l0 + 1);
}

// q: the probability of sampling the explicit part with Algorithm 2 (our choice, see the header).
template <class Ndf, class T>
GLINTLAB_FN T mixture_probability(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp) {
  return clamp(explicit_share(p, ndf, fp), T(kMixtureMin), T(kMixtureMax));
}

// Algorithm 2's printed pdf (lines 16–17) evaluated at ω_h without a draw: x_a := T(ω_h), summed
// over both levels with their weights, per steradian (the MIS evaluation rule of the header).
template <class Ndf, class T>
GLINTLAB_FN T printed_pdf_at(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp, Vec3<T> h,
                 int process = 0) {
  const Mask<T> up = h.z > T(0);
  if (!any_lane<T>(up)) return T(0);
  const Vec2<T> x = map_to_square(ndf, select(up, h, Vec3<T>{T(0), T(0), T(1)}));
  const Mask<T> in_disk = up && !(sqr(x.x - T(0.5)) + sqr(x.y - T(0.5)) > T(0.25));
  if (!any_lane<T>(in_disk)) return T(0);
  const Spatial<T> sp = spatial(p, fp);
  Block<T> block;  // on the stack, as in sample_half
  T total = T(0);
  for (int upper = 0; upper < 2; ++upper) {
    const LaneInt<T, int> level = sp.l0 + upper;
    const T w_l = upper ? sp.w1 : T(1) - sp.w1;
    const Mask<T> w_positive = w_l > T(0);
    if (!any_lane<T>(w_positive)) continue;
    const T res_a = angular_resolution<T>(level);
    kemppinen2025::block(p, ndf, sp, level, w_l, block_start(x.x * res_a, p.side),
                         block_start(x.y * res_a, p.side), block, process);
    const T area_b = (block.hi.x - block.lo.x) * (block.hi.y - block.lo.y);
    total += select(w_positive, block_density(block, x) * area_b * w_l, T(0));
  }
  return select(in_disk, total * map_jacobian_paper(ndf, h) * h.z, T(0));
}

template <class T>
struct FullSample {
  Vec3<T> h;              // ω_h
  T pdf_h;                // exact mixture density q p₁ + (1 − q) D cosθ, per steradian of ω_h
  T pdf_printed_h;        // the same mixture with Algorithm 2's printed pdf as p₁
  T q;                    // probability of the explicit strategy
  Mask<T> from_explicit;  // drawn by Algorithm 2 (else by D cosθ)
  Mask<T> ok;             // false: Algorithm 2 produced no direction (contributes 0)
};

// The random number `dim` of the mixture's own choices (Algorithm 2 uses the key's dims 0–6).
template <class T>
GLINTLAB_FN T mixture_uniform(std::uint64_t key, std::uint64_t dim) {
  return counter_uniform<T>(key, 0x66756c6cULL, dim);
}
template <class T, class I, std::size_t N>
GLINTLAB_FN T mixture_uniform(const IntLanes<I, N>& key, std::uint64_t dim) {
  return float_lanes<T>(
      [&](std::size_t l) { return counter_uniform<Scalar<T>>(key.v[l], 0x66756c6cULL, dim); });
}

// Strategy 1 on the uv point process: Algorithm 2, its marginal, its printed pdf at ω_h.
template <class Ndf, class T>
struct UvExplicit {
  const Params<T>& p;
  const Ndf& ndf;
  const FootprintQuery<T>& fp;
  GLINTLAB_FN HalfSample<T> draw(const LaneInt<T, std::uint64_t>& key) const {
    return sample_half(p, ndf, fp, key);
  }
  GLINTLAB_FN T density(Vec3<T> h) const { return sample_density_half(p, ndf, fp, h); }
  GLINTLAB_FN T printed_at(Vec3<T> h) const { return printed_pdf_at(p, ndf, fp, h); }
};

// Strategy 1 in triplanar mode: the planes' blend (kemppinen_triplanar.h).
template <class Ndf, class T>
struct TriplanarExplicit {
  const Params<T>& p;
  const Ndf& ndf;
  const TriplanarInput<T>& in;
  GLINTLAB_FN HalfSample<T> draw(const LaneInt<T, std::uint64_t>& key) const {
    return triplanar_sample_half(p, ndf, in, key);
  }
  GLINTLAB_FN T density(Vec3<T> h) const { return triplanar_density_half(p, ndf, in, h); }
  // Σ_i w_i × plane i's printed pdf at ω_h.
  GLINTLAB_FN T printed_at(Vec3<T> h) const {
    const Vec3<T> wv = triplanar_weights(in.normal);
    const T w[3] = {wv.x, wv.y, wv.z};
    T sum = T(0);
    for (int i = 0; i < 3; ++i) {
      const Mask<T> nonempty = w[i] > T(0);
      if (!any_lane<T>(nonempty)) continue;
      sum += select(nonempty,
                    w[i] * printed_pdf_at(p, ndf,
                                          triplanar_footprint(i, in.pos, in.dpos_dx, in.dpos_dy),
                                          h, triplanar_process(i)),
                    T(0));
    }
    return sum;
  }
};

// The explicit share of the triplanar blend: the planes' shares weighted by w_i, clamped as q.
template <class Ndf, class T>
GLINTLAB_FN T triplanar_mixture_probability(const Params<T>& p, const Ndf& ndf, const TriplanarInput<T>& in) {
  const Vec3<T> wv = triplanar_weights(in.normal);
  const T w[3] = {wv.x, wv.y, wv.z};
  T share = T(0);
  for (int i = 0; i < 3; ++i) {
    const Mask<T> nonempty = w[i] > T(0);
    if (!any_lane<T>(nonempty)) continue;
    share += select(
        nonempty,
        w[i] * explicit_share(p, ndf, triplanar_footprint(i, in.pos, in.dpos_dx, in.dpos_dy)),
        T(0));
  }
  return clamp(share, T(kMixtureMin), T(kMixtureMax));
}

// The exact mixture density of ω_h, q p₁(ω_h) + (1 − q) D(ω_h) cosθ_h, strategy 1 `e`.
template <class Ndf, class T, class Explicit>
GLINTLAB_FN T mixture_density_half(const Ndf& ndf, const Explicit& e, Vec3<T> h, T q) {
  const Mask<T> up = h.z > T(0);
  if (!any_lane<T>(up)) return T(0);
  const Vec3<T> hu = select(up, h, Vec3<T>{T(0), T(0), T(1)});
  return select(up, q * e.density(hu) + (T(1) - q) * ndf.D(hu) * hu.z, T(0));
}

// One ω_h from the mixture with strategy 1 `e`, random numbers from `key`, with the exact density
// and, when `printed`, the printed one (else pdf_printed_h is 0: it costs a block per draw of
// strategy 2).
template <class Ndf, class T, class Explicit>
GLINTLAB_FN FullSample<T> sample_mixture(const Ndf& ndf, const Explicit& e,
                             const LaneInt<T, std::uint64_t>& key, T q, bool printed) {
  const Mask<T> kNone = T(0) > T(1);
  const Vec3<T> zenith{T(0), T(0), T(1)};
  FullSample<T> out;
  out.h = {T(0), T(0), T(0)};
  out.pdf_h = T(0);
  out.pdf_printed_h = T(0);
  out.q = q;
  out.from_explicit = mixture_uniform<T>(key, 0) < q;
  out.ok = kNone;
  Mask<T> drawn = kNone;
  T p1_printed = T(0);
  if (any_lane<T>(out.from_explicit)) {
    const HalfSample<T> s = e.draw(key);
    const Mask<T> m = out.from_explicit && s.ok;
    out.h = select(m, s.h, out.h);
    p1_printed = select(m, s.pdf_printed_h, p1_printed);
    drawn = m;
  }
  const Mask<T> smooth = !out.from_explicit;
  if (any_lane<T>(smooth)) {
    const Vec3<T> h2 =
        sample_normal_walter(ndf, Vec2<T>{mixture_uniform<T>(key, 1), mixture_uniform<T>(key, 2)});
    out.h = select(smooth, h2, out.h);
    const Mask<T> m = smooth && (h2.z > T(0));
    drawn = drawn || m;
    if (printed && any_lane<T>(m))
      p1_printed = select(m, e.printed_at(select(m, h2, zenith)), p1_printed);
  }
  if (!any_lane<T>(drawn)) return out;
  const Vec3<T> h = select(drawn, out.h, zenith);
  const T p2 = ndf.D(h) * h.z;
  out.pdf_h = select(drawn, q * e.density(h) + (T(1) - q) * p2, T(0));
  out.pdf_printed_h = select(drawn, q * p1_printed + (T(1) - q) * p2, T(0));
  out.ok = drawn && (out.pdf_h > T(0));
  return out;
}

// The exact mixture density of ω_h on the uv point process (q from mixture_probability).
template <class Ndf, class T>
GLINTLAB_FN T full_sample_density_half(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp,
                           Vec3<T> h, T q) {
  return mixture_density_half(ndf, UvExplicit<Ndf, T>{p, ndf, fp}, h, q);
}

// One ω_h from the uv mixture, random numbers from `key`, with both densities.
template <class Ndf, class T>
GLINTLAB_FN FullSample<T> sample_full(const Params<T>& p, const Ndf& ndf, const FootprintQuery<T>& fp,
                          const LaneInt<T, std::uint64_t>& key, T q) {
  return sample_mixture(ndf, UvExplicit<Ndf, T>{p, ndf, fp}, key, q, true);
}

}  // namespace glintlab::kemppinen2025

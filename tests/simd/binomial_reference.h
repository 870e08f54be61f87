// The exact binomial kernel of core/glints/binomial_kernel.h as it was before its loops skipped
// the work no lane uses (the acceptance test's logs on attempts that the squeeze decides) and drew
// its uniforms in 32-bit lanes: both loops' set-up, every attempt's logs on every lane, one
// hash32_draw per uniform in the batch's hash lanes (64-bit lanes on double batches). The kernel
// must give these counts bit for bit on every ISA (binomial_lanes_test.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "core/glints/binomial_kernel.h"

namespace glintlab::simd::test::reference {

template <class T>
struct DrawPerUniform {
  HashLanes<T> key;
  T uniform(std::uint32_t dim) const {
    return hash32_uniform<T>(hash32_draw(key, HashLanes<T>(dim)));
  }
};

template <class D>
D log_factorial_ratio(D a, D b) {
  const D xa = a + D(1), xb = b + D(1), d = a - b;
  const D big = d * log(xa) + (xb - D(0.5)) * log1p(d / xb) - d +
                detail::stirling_correction(xa) - detail::stirling_correction(xb);
  return select(a < D(16) || b < D(16),
                detail::log_factorial_lanes(a) - detail::log_factorial_lanes(b), big);
}

template <class D>
D inversion(D nd, D p, D u, Mask<D> active) {
  const D q = D(1) - p, r = p / q;
  D f = exp(nd * log1p(-p));
  D cdf = f;
  D k = D(0);
  Mask<D> running = active;
  for (int it = 0; it < kBinomialInversionMaxSteps; ++it) {
    const Mask<D> step = running && (u > cdf) && (k < nd);
    if (!any_lane<D>(step)) break;
    const D f1 = f * ((nd - k) / (k + D(1)) * r);
    const D k1 = k + D(1);
    const D c1 = cdf + f1;
    f = select(step, f1, f);
    k = select(step, k1, k);
    cdf = select(step, c1, cdf);
    const Mask<D> stop = (k > nd * p + D(1)) && (f < D(1e-18) * cdf);
    running = step && !stop;
  }
  return k;
}

template <class D, class Stream>
D btrs(D nd, D p, const Stream& stream, Mask<D> active) {
  const D q = D(1) - p;
  const D spq = sqrt(nd * p * q);
  const D b = D(1.15) + D(2.53) * spq;
  const D a = D(-0.0873) + D(0.0248) * b + D(0.01) * p;
  const D c = nd * p + D(0.5);
  const D vr = D(0.92) - D(4.2) / b;
  const D alpha = (D(2.83) + D(5.1) / b) * spq;
  const D lpq = log(p / q);
  const D m = floor((nd + D(1)) * p);
  D result = m;
  Mask<D> left = active;
  for (int j = 0; j < kBinomialBtrsMaxAttempts && any_lane<D>(left); ++j) {
    const D u = stream.uniform(2 * std::uint32_t(j)) - D(0.5);
    const D v = stream.uniform(2 * std::uint32_t(j) + 1);
    const D us = D(0.5) - abs(u);
    const D kd = floor((D(2) * a / us + b) * u + c);
    const Mask<D> in_range = !(kd < D(0) || kd > nd);
    const Mask<D> squeeze = us >= D(0.07) && v <= vr;
    const D lv = log(v * alpha / (a / (us * us) + b));
    const D lr = log_factorial_ratio(m, kd) + log_factorial_ratio(nd - m, nd - kd) +
                 (kd - m) * lpq;
    const Mask<D> accept = left && in_range && (squeeze || lv <= lr);
    result = select(accept, kd, result);
    left = left && !accept;
  }
  return result;
}

template <class D, class Stream>
D exact_double(D nd, D p, const Stream& stream) {
  const Mask<D> none = nd == D(0) || !(p > D(0));
  const Mask<D> all_n = p >= D(1);
  const Mask<D> live = !none && !all_n;
  const Mask<D> flip = p > D(0.5);
  const D pp = select(flip, D(1) - p, p);
  const Mask<D> small = nd * pp < D(10);
  const D k_inv = inversion(nd, pp, stream.uniform(0), live && small);
  const D k_btrs = btrs(nd, pp, stream, live && !small);
  D k = select(small, k_inv, k_btrs);
  k = select(flip, nd - k, k);
  return select(none, D(0), select(all_n, nd, k));
}

template <class T>
T binomial_exact_lanes(T n, T p, const HashLanes<T>& key) {
  using D = typename LaneTraits<T>::Double;
  if constexpr (std::is_floating_point_v<T>) {
    return T(exact_double(double(n), double(p), DrawPerUniform<double>{key}));
  } else {
    constexpr std::size_t kL = LaneTraits<T>::kLanes, kD = LaneTraits<D>::kLanes;
    alignas(64) Scalar<T> ns[kL], ps[kL], out[kL];
    alignas(64) std::uint32_t keys[kL];
    LaneTraits<T>::store(n, ns);
    LaneTraits<T>::store(p, ps);
    detail::store_hash_lanes(key, keys);
    for (std::size_t part = 0; part < kL; part += kD) {
      alignas(64) double nd[kD], pd[kD], kd[kD];
      for (std::size_t l = 0; l < kD; ++l) {
        nd[l] = double(ns[part + l]);
        pd[l] = double(ps[part + l]);
      }
      const D k = exact_double(LaneTraits<D>::load(nd), LaneTraits<D>::load(pd),
                               DrawPerUniform<D>{detail::load_hash_lanes<HashLanes<D>>(keys + part)});
      LaneTraits<D>::store(k, kd);
      for (std::size_t l = 0; l < kD; ++l) out[part + l] = Scalar<T>(kd[l]);
    }
    return LaneTraits<T>::load(out);
  }
}

}  // namespace glintlab::simd::test::reference

// The dictionary lookups of Chermain et al. 2020/2021 as kernels generic over the float type:
// textureLod and textureGrad (2021 Eq. 19, Sec. 6.1) of the 1D marginal tables with mirrored
// repeat or clamp-to-edge (OpenGL 4.6 Sec. 8.14.2), trilinear between MIP levels, the anisotropic
// probes of EXT_texture_filter_anisotropic; texels gathered from the dictionary's float table.
#pragma once

// Why generic: the batched model (core/model_list.h, BatchedModels) runs one lookup per lane, each
// lane with its own distribution, level, MIP level and probe count; indices are integer-valued T
// (exact: every index is below 2^24), texel addresses per lane are gathers, and every per-lane
// choice is a select, so the scalar double instantiation is the host code the dictionary always
// had, op for op (Dictionary::lookup_lod/lookup_grad call these at T = double).

#include <cmath>
#include <cstddef>

#include "core/glints/chermain_lanes.h"
#include "core/math/config.h"
#include "core/math/lanes.h"
#include "core/math/ops.h"

namespace glintlab::chermain2021 {

// How out-of-range texel indices are resolved (OpenGL 4.6 Sec. 8.14.2): mirrored repeat is what
// the 2021 paper requires (Sec. 6.1); clamp-to-edge exists only as the negative control of
// chermain.kernel-normalized.
enum class TableWrap { kMirroredRepeat, kClampToEdge };

// A plain view of the dictionary's texels for the kernels (Dictionary::table()): table
// (n, k) starts at (n·levels + k)·per_table, its MIP level m (size resolution/2^m) at
// 2·resolution − 2·(resolution/2^m) within it.
struct Table {
  const float* texels;
  int levels;             // L
  int resolution;         // texels of MIP level 0
  int mip_levels;         // log2(resolution) + 1
  std::size_t per_table;  // floats of one table with its whole MIP chain
  double extent;          // the tables cover |x| < extent = 4σ_o
};

// std::max / std::min / std::clamp on T, with their exact rules ((a < b) ? b : a, …, including
// NaN and signed zeros), so that the scalar instantiation keeps the host code's results bit for
// bit.
template <class T>
GLINTLAB_FN T std_max(T a, T b) {
  return select(a < b, b, a);
}
template <class T>
GLINTLAB_FN T std_min(T a, T b) {
  return select(b < a, b, a);
}
template <class T>
GLINTLAB_FN T std_clamp(T v, T lo, T hi) {
  return select(v < lo, lo, select(hi < v, hi, v));
}

// log2 per lane (std::log2 of each lane: the ops layer has no log2; the two uses, the footprint's
// LOD and textureGrad's λ, are a few per lookup, and each lane is then the scalar value exactly).
template <class T>
GLINTLAB_FN T log2(const T& x) {
  const LanesOf<T> xl(x);
  return float_lanes<T>([&](std::size_t l) { return std::log2(xl[l]); });
}

// log2 of the lanes of x that are above 1, 0 in the others: max(0, log2 x) (log2 x ≤ 0 there, and
// max(0, NaN) = 0), without a libm call for a lane at or below 1.
template <class T>
GLINTLAB_FN T log2_above_one(const T& x) {
  const LanesOf<T> xl(x);
  return float_lanes<T>(
      [&](std::size_t l) { return xl[l] > Scalar<T>(1) ? std::log2(xl[l]) : Scalar<T>(0); });
}

// table.texels[i] as T in every lane, i the lane's integer-valued index (in range: the callers
// wrap or clamp it); a gather.
template <class T>
GLINTLAB_FN T gather(const float* texels, const T& index) {
  return lanes::gather_texels(texels, index);
}

// First texel of table (n, k) (n, k integer-valued, k < levels).
template <class T>
GLINTLAB_FN T table_base(const Table& t, T n, T k) {
  return (n * T(t.levels) + k) * T(double(t.per_table));
}

// A MIP level's size in texels and the inverse of the mirrored period, 1/(2·size) (both powers of
// two, so i·(1/(2·size)) is i/(2·size) exactly).
template <class T>
struct LevelSize {
  T size, inv_period;
};

// Texel i (any integer) of the MIP level of `size` texels starting at `level_base`, wrapped.
// Mirrored repeat: period 2·size, the second half reversed; the residue i − P⌊i/P⌋ is exact (P a
// power of two).
template <class T>
GLINTLAB_FN T wrapped(const LevelSize<T>& level, T i, TableWrap wrap) {
  const T size = level.size;
  if (wrap == TableWrap::kClampToEdge) return std_clamp(i, T(0), size - T(1));
  const T period = T(2) * size;
  const T r = i - period * floor(i * level.inv_period);
  return select(r >= size, period - T(1) - r, r);
}
template <class T>
GLINTLAB_FN T fetch(const Table& t, T level_base, const LevelSize<T>& level, T i, TableWrap wrap) {
  return gather(t.texels, level_base + wrapped(level, i, wrap));
}

// textureLod at MIP level m (integer-valued, size = resolution/2^m texels): linear interpolation
// between texel centres, u = x / extent the normalized coordinate.
template <class T>
GLINTLAB_INLINE T linear(const Table& t, T base, const LevelSize<T>& level, T u, TableWrap wrap) {
  const T size = level.size;
  const T s = u * size - T(0.5);
  const T f = floor(s);
  const T w = s - f;
  const T level_base = base + T(2 * t.resolution) - T(2) * size;
  if constexpr (lanes::kVectorDoubles<T> >= 4) {
    // The two taps, equal or adjacent after wrapping, from one gather of texel pairs.
    T a, b;
    lanes::gather_texel_pair(t.texels, level_base + wrapped(level, f, wrap),
                             level_base + wrapped(level, f + T(1), wrap), &a, &b);
    return (T(1) - w) * a + w * b;
  } else {
    return (T(1) - w) * fetch(t, level_base, level, f, wrap) +
           w * fetch(t, level_base, level, f + T(1), wrap);
  }
}

// resolution / 2^m per lane (m integer-valued in [0, mip_levels)) and its inverse period: on the
// batches 2^(mip_levels − 1 − m) and 2^(m − mip_levels) from the exponent bits (the resolution is
// a power of two), else the integer shift.
template <class T>
GLINTLAB_FN LevelSize<T> level_size(const Table& t, T m) {
  if constexpr (lanes::kVectorDoubles < T >> 0) {
    return {lanes::exp2_int(T(t.mip_levels - 1) - m), lanes::exp2_int(m - T(t.mip_levels))};
  } else {
    const LanesOf<T> ml(m);
    const T size = float_lanes<T>(
        [&](std::size_t l) { return Scalar<T>(t.resolution >> static_cast<int>(ml[l])); });
    return {size, T(0.5) / size};
  }
}

// Trilinear lookup at level of detail lambda (clamped to the pyramid): linear within ⌊λ⌋ and
// ⌊λ⌋ + 1, linear between them. Where every lane sits exactly on a level (λ = ⌊λ⌋, e.g. λ = 0), the
// second level is not read: a + 0·(b − a) = a for the finite, non-negative a here. Forced inline
// (as lookup_grad): out of line, each call waited for its own gathers, which inline overlap with
// the other marginal's lookup and the next cell's draws.
template <class T>
GLINTLAB_INLINE T trilinear(const Table& t, T base, T u, T lambda, TableWrap wrap) {
  const T top = T(t.mip_levels - 1);
  const T l = std_clamp(lambda, T(0), top);
  const T m0 = floor(l);
  const T m1 = std_min(m0 + T(1), top);
  const T a = linear(t, base, level_size(t, m0), u, wrap);
  if (!any_lane<T>(m1 != m0 && l != m0)) return a;
  const T b = linear(t, base, level_size(t, m1), u, wrap);
  return select(m1 == m0, a, a + (l - m0) * (b - a));
}

// textureLod(P_o(n, k), x, mip) with a uniform MIP level: 0 for |x| ≥ extent (the table domain,
// outside of which the marginal vanishes).
template <class T>
GLINTLAB_FN T lookup_lod(const Table& t, T base, T x, double mip, TableWrap wrap) {
  const Mask<T> inside = abs(x) < T(t.extent);
  return select(inside, trilinear(t, base, x / T(t.extent), T(mip), wrap), T(0));
}

// One textureGrad lookup: the value, the MIP level of detail it used (clamped to the pyramid) and
// the number of probes.
template <class T>
struct Grad {
  T value, lambda, probes;
};

// textureGrad(P_o(n, k), x, dx_dpx, dx_dpy) (2021 Eq. 19), the 1D form of the anisotropic rule:
// footprint lengths in texels ρ_x = |dx/dpx|·res/extent, ρ_y likewise; N = min(⌈P_max/P_min⌉,
// max_anisotropy) probes (max_anisotropy where P_min = 0 < P_max, 1 where both are 0);
// λ = max(0, log2(P_max/N)); the mean of N trilinear lookups at x + ((i + ½)/N − ½)·d, d the
// major-axis derivative. The probe loop runs to the largest N over the lanes, masked. Where every
// lane has N = 1 the divisions by N are left out (x/1 = x), and the ratio P_max/P_min where no
// lane has P_min > 0 (it is not used there). Forced inline: out of line, its batch arguments and
// results crossed the call through memory.
template <class T>
GLINTLAB_INLINE Grad<T> lookup_grad(const Table& t, T base, T x, T dx_dpx, T dx_dpy, TableWrap wrap,
                                    int max_anisotropy) {
  const T scale = T(double(t.resolution) / t.extent);  // texels per slope unit
  const T px = abs(dx_dpx) * scale, py = abs(dx_dpy) * scale;
  const T pmax = std_max(px, py), pmin = std_min(px, py);
  const T major = select(px >= py, dx_dpx, dx_dpy);  // slope units per pixel
  const T aniso = T(max_anisotropy);
  const Mask<T> has_min = pmin > T(0), has_max = pmax > T(0);
  T probes = select(has_max, aniso, T(1));
  if (any_lane<T>(has_min)) {
    const T ratio = pmax / select(has_min, pmin, T(1));
    const T ceil_ratio = -floor(-ratio);
    probes = select(has_min, std_min(ceil_ratio, aniso), probes);
  }
  probes = std_max(probes, T(1));
  const bool single = !any_lane<T>(probes != T(1));
  // λ = max(0, log2(P_max/N)) where P_max > 0, else 0: log2 only on the lanes where P_max/N > 1
  // (elsewhere it is 0 either way), none where no lane has a footprint over one texel.
  const T texels_per_probe =
      single ? select(has_max, pmax, T(1)) : select(has_max, pmax, T(1)) / probes;
  const Mask<T> coarse = has_max && texels_per_probe > T(1);
  const T lambda = any_lane<T>(coarse) ? log2_above_one(texels_per_probe) : T(0);
  Grad<T> r;
  r.lambda = std_min(lambda, T(t.mip_levels - 1));
  r.probes = probes;
  const Mask<T> inside = abs(x) < T(t.extent);
  // The largest probe count over the lanes (uniform loop bound).
  const LanesOf<T> pl(probes);
  int count = 0;
  for (std::size_t l = 0; l < kLaneCount<T>; ++l)
    count = count < static_cast<int>(pl[l]) ? static_cast<int>(pl[l]) : count;
  T sum = T(0);
  for (int i = 0; i < count; ++i) {
    const T offset = single ? T(i) + T(0.5) : (T(i) + T(0.5)) / probes;
    const T xi = x + (offset - T(0.5)) * major;
    const T v = trilinear(t, base, xi / T(t.extent), lambda, wrap);
    sum = select(T(i) < probes, sum + v, sum);
  }
  r.value = select(inside, single ? sum : sum / probes, T(0));
  return r;
}

}  // namespace glintlab::chermain2021

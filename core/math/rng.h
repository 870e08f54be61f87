// Counter-based random numbers: a value depends only on (seed, index, dimension), never on the
// order of evaluation, so results are identical for any thread count or batch width.
// Mixer: the SplitMix64 finalizer (Steele, Lea, Flood 2014, "Fast splittable pseudorandom number
// generators"), applied to a combination of the three counters.
#pragma once

#include <cstdint>

#include "core/math/config.h"

namespace glintlab {

[[gnu::always_inline]] GLINTLAB_FN std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// 64 random bits for (seed, index, dim); each counter goes through the mixer so that nearby
// seeds, indices and dimensions give unrelated streams. Always inlined: the per-lane loops of the
// ISA translation units (core/simd/isa_*.cpp) would otherwise each emit a weak copy compiled for
// their ISA, and the linker may keep any one of them for every caller.
[[gnu::always_inline]] GLINTLAB_FN std::uint64_t counter_bits(std::uint64_t seed, std::uint64_t index,
                                       std::uint64_t dim) {
  std::uint64_t h = mix64(seed + 0x9e3779b97f4a7c15ULL);
  h = mix64(h ^ (index + 0x632be59bd9b4e019ULL));
  return mix64(h ^ (dim * 0xd1b54a32d192ed03ULL + 0x8cb92ba72f3d8dd7ULL));
}

// Uniform in [0, 1) with the full mantissa of the type (24 bits for float, 53 for double).
template <class T>
[[gnu::always_inline]] GLINTLAB_FN T counter_uniform(std::uint64_t seed, std::uint64_t index, std::uint64_t dim) {
  constexpr int kBits = sizeof(T) == 4 ? 24 : 53;
  const std::uint64_t b = counter_bits(seed, index, dim) >> (64 - kBits);
  return T(b) * (T(1) / T(std::uint64_t(1) << kBits));
}

// Hash of a string (FNV-1a 64), for seeds derived from a check's id.
inline std::uint64_t hash_string(const char* s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (; *s; ++s) h = (h ^ static_cast<unsigned char>(*s)) * 0x100000001b3ULL;
  return mix64(h);
}

}  // namespace glintlab

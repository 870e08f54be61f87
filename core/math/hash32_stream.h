// Keyed streams of core/math/hash32.h's counter hash: a key made once per footprint (or per any
// tuple of indices, each nested in turn) and the uniforms of dims 0, 1, … drawn from it, so a
// kernel that draws several uniforms per lane hashes its indices once. hash32_draw(hash32_key(s,
// i), d) is hash32_counter(s, i, d) bit for bit (tests/core/math/hash32_test.cpp); the steps are
// spelled out here so that the stream can stop after the key.
#pragma once

#include "core/math/config.h"
#include "core/math/hash32.h"

namespace glintlab {

// The key of the counter stream (seed, index): seed and index mixed in turn (nested hashing,
// Jarzynski & Olano Sec. 2), the seed offset so that all-zero counters do not hit hash32's fixed
// point. hash32_nest mixes one more counter into a key (a stream keyed by several indices).
template <class U>
[[gnu::always_inline]] GLINTLAB_FN U hash32_key(const U& seed, const U& index) {
  return hash32(hash32(detail::wrap32(seed + U(0x9e3779b9u))) ^ index);
}
template <class U>
[[gnu::always_inline]] GLINTLAB_FN U hash32_nest(const U& key, const U& counter) {
  return hash32(key ^ counter);
}

// 32 random bits of dimension dim of a key's stream.
template <class U>
[[gnu::always_inline]] GLINTLAB_FN U hash32_draw(const U& key, const U& dim) {
  return hash32(key ^ detail::wrap32(dim * U(0x85ebca6bu) + U(0xc2b2ae35u)));
}

}  // namespace glintlab

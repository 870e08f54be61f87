// The two NDFs as a runtime choice, and the one dispatch from that choice to the templated code:
// with_ndf(kind, αx, αy, f) calls f(GGX<double>{αx, αy}) or f(Beckmann<double>{αx, αy}).
#pragma once

#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"

namespace glintlab {

enum class NdfKind { kGGX, kBeckmann };

constexpr NdfKind ndf_kind(bool ggx) { return ggx ? NdfKind::kGGX : NdfKind::kBeckmann; }

// f(GGX<double>{alpha_x, alpha_y}) or f(Beckmann<double>{alpha_x, alpha_y}), and its result (both
// calls return the same type).
template <class F>
decltype(auto) with_ndf(NdfKind kind, double alpha_x, double alpha_y, F&& f) {
  if (kind == NdfKind::kGGX) return f(GGX<double>{alpha_x, alpha_y});
  return f(Beckmann<double>{alpha_x, alpha_y});
}

}  // namespace glintlab

// Kemppinen et al. 2025 glinty Beckmann reflection as a model (core/model.h): D★^f of Eq. 11 by
// Algorithm 1 on the Beckmann map T (core/maps/beckmann_map.h), sampled by the mixture of
// Algorithm 2 and D cosθ (core/glints/kemppinen_full_sampling.h).
#pragma once

#include <string_view>

#include "core/models/kemppinen_model.h"
#include "core/ndf/beckmann.h"

namespace glintlab {

struct KemppinenBeckmann : detail::KemppinenModel<Beckmann> {
  static constexpr std::string_view kName = "kemppinen_beckmann";
  // The smooth model its footprint average tends to (conformance: converges-to-smooth).
  static constexpr std::string_view kSmoothLimit = "smooth_beckmann";
  static constexpr std::string_view kDescription =
      "glinty Beckmann NDF in constant time (Algorithm 1), Smith G2, F = 1; sampler: Algorithm 2 "
      "mixed with D cos(theta_h) for the compensation (pdf=marginal: the mixture's exact density; "
      "pdf=printed: the mixture with Algorithm 2's lines 16-17)";
  static constexpr std::string_view kSource =
      "Kemppinen et al. 2025 Eq. 1, 4, 5, 8-11, Algorithms 1-2, Sec. 3.2.2";
};

static_assert(Model<KemppinenBeckmann>);

}  // namespace glintlab

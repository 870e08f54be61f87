// A model-generic check over registry entries (core/model_registry.h): does a model's sample()
// draw ωo from the density its pdf() reports? The chi-square goodness of fit of verify/stats/
// chi_square.h on the sphere (bins about the mirror direction, reflection_options of
// gof_family.h), for any registered model at one parameter setting and query — the check the
// smooth samplers get from smooth.sampler-matches-pdf, available to every new model. Rejected
// samples (below the horizon: weight 0) are directions of the density too, as in
// smooth.sampler-matches-pdf; a zero ωo is "no sample" (its probability is 1 − ∫ pdf).
#pragma once

#include <cstdint>
#include <vector>

#include "core/model_registry.h"
#include "verify/stats/chi_square.h"

namespace glintlab::verify {

struct ModelGofOptions {
  std::uint64_t samples = 1u << 16;
  double pdf_scale = 1;  // ≠ 1: the negative control (the claimed pdf scaled)
  std::size_t fine_max_bins = 1024;
};

ChiSquareResult model_sampler_chi_square(const ModelEntry& model, const std::vector<double>& values,
                                         const ModelQuery<double>& query, std::uint64_t seed,
                                         const ModelGofOptions& options = {});

}  // namespace glintlab::verify

// Chi-square goodness of fit of any registered model's sample() against its pdf().
#include "verify/generic/model_sampler_gof.h"

#include "core/math/rng.h"
#include "verify/claims/gof_family.h"

namespace glintlab::verify {

ChiSquareResult model_sampler_chi_square(const ModelEntry& model, const std::vector<double>& values,
                                         const ModelQuery<double>& query, std::uint64_t seed,
                                         const ModelGofOptions& options) {
  ChiSquareOptions o = reflection_options(query.wi);
  o.fine_max_bins = options.fine_max_bins;
  const double scale = options.pdf_scale;
  const DirectionPdf pdf = [&model, &values, query, scale](const Vec3<double>& wo) {
    ModelQuery<double> q = query;
    q.wo = wo;
    return scale * model.pdf(values, q);
  };
  const ChiSquarePlan plan =
      plan_direction_chi_square(SampleDomain::kSphere, pdf, options.samples, o);
  return run_direction_chi_square(plan, [&](std::uint64_t i) {
    // A rejected sample is still a direction of the density (its estimator weight is 0); a zero
    // or non-finite ωo is "no sample".
    return model.sample(values, query, uniform_pair(seed, i)).wo;
  });
}

}  // namespace glintlab::verify

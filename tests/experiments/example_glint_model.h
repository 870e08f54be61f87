// A small example glint model for docs/adding_a_model.md and its test: not a paper's model, a toy
// that shows every part of core/model.h a glint model fills in. Its value is the smooth GGX mean
// (Walter et al. 2007 Eq. 20), and it reports, as intermediates, the expected number of facets
// of a Poisson facet distribution (density per unit uv area) that reflect into ωo inside the
// footprint and the probability p_hit = 1 − exp(−N) that at least one does. It has no sampler of
// its own: it samples the smooth VNDF (Heitz 2018) and returns that pdf, as the conventions ask.
#pragma once

#include <array>
#include <span>
#include <string_view>

#include "core/model.h"
#include "core/models/smooth_microfacet.h"
#include "core/ndf/ggx.h"
#include "core/samplers/heitz_vndf.h"

namespace glintlab::example {

struct ExampleGlints {
  static constexpr std::string_view kName = "example_glints";
  static constexpr std::string_view kDescription =
      "toy glint model (docs/adding_a_model.md): smooth GGX mean, Poisson facet count in the "
      "footprint as intermediates; samples the smooth VNDF (Heitz 2018) and returns its pdf";
  static constexpr std::string_view kSource = "example only; Walter et al. 2007 Eq. 20";
  static constexpr unsigned kNeeds = kNeedsFootprint;
  static constexpr std::array<ParamSpec, 3> kParams = {{
      {"alpha_x", 0.3, 0.0, 100.0, true, false, "roughness along the tangent (x)"},
      {"alpha_y", 0.3, 0.0, 100.0, true, false, "roughness along the bitangent (y)"},
      {"density", 1e4, 1.0, 1e8, false, false, "facets per unit uv area"},
  }};
  // p_hit is a probability: its name starts with p_, so the stability sweeps count p_hit > 1.
  static constexpr std::array<std::string_view, 2> kIntermediates = {"expected_facets", "p_hit"};

  template <class T>
  struct Params {
    GGX<T> ggx;
    T density;
  };

  template <class T>
  static Params<T> params(std::span<const double> v) {
    return {GGX<T>{T(v[param_index<ExampleGlints>("alpha_x")]),
                   T(v[param_index<ExampleGlints>("alpha_y")])},
            T(v[param_index<ExampleGlints>("density")])};
  }

  template <class T>
  GLINTLAB_INLINE static T pdf(const Params<T>& p, const ModelQuery<T>& q) {
    return pdf_heitz_vndf(p.ggx, q.wi, q.wo);
  }

  template <class T>
  GLINTLAB_INLINE static ModelEval<T, 2> eval(const Params<T>& p, const ModelQuery<T>& q) {
    const auto smooth = detail::smooth_eval(p.ggx, q, pdf(p, q));
    const FootprintQuery<T>& f = q.footprint;
    const T area = abs(f.duv_dx.x * f.duv_dy.y - f.duv_dx.y * f.duv_dy.x);
    // Facets aimed at ωo: the footprint's count times D(h) h_z, the NDF's projected density at h
    // (index 3 of the smooth intermediates is D, index 2 is h_z).
    const T n = p.density * area * smooth.intermediates[3] * max(smooth.intermediates[2], T(0));
    return {smooth.value, smooth.pdf, {n, -expm1(-n)}};
  }

  template <class T>
  GLINTLAB_INLINE static ModelSample<T> sample(const Params<T>& p, const ModelQuery<T>& q, Vec2<T> u) {
    return detail::smooth_sample(p.ggx, q.wi, sample_heitz_vndf(p.ggx, q.wi, u));
  }
};

static_assert(Model<ExampleGlints>);

}  // namespace glintlab::example

#include "verify/claims/kemppinen/sampling.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <numbers>

#include "core/glints/kemppinen.h"
#include "core/glints/kemppinen_full_sampling.h"
#include "core/glints/kemppinen_sampling.h"
#include "core/math/rng.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/ggx.h"
#include "core/render/convergence.h"
#include "core/samplers/walter.h"
#include "verify/scenes/kemppinen_env_radiance.h"
#include "verify/scenes/kemppinen_presets.h"

namespace glintlab::verify::kemppinen_claims {

std::vector<SampConfig> samp_configs() {
  return {{{true, 0.3}, 0.05, 2.5, 1},
          {{false, 0.3}, 0.05, 2.5, 1},
          {{true, 0.2}, 0.02, 12, 1},
          {{false, 0.5}, 0.1, 12, 1},
          {{true, 0.3}, 0.05, 5, 2}};
}

std::vector<SampConfig> est_configs() {
  return {{{true, 0.3}, 0.05, 2.5, 1},
          {{false, 0.3}, 0.05, 2.5, 1},
          {{true, 0.3}, 0.05, 5, 2},
          {{false, 0.3}, 0.05, 5, 2}};
}

std::string describe_samp_configs(const std::vector<SampConfig>& cs) {
  std::string out;
  for (const SampConfig& c : cs)
    out += fmt::format("{}{} α = {:g}, α★ = {:g}, k = {}", out.empty() ? "" : "; ", ndf_name(c.ndf),
                       c.ndf.alpha, c.alpha_star, c.side * c.side);
  return out;
}

GofCase samp_case(const SampConfig& c, std::uint64_t seed_process, double pdf_scale) {
  const P p = kemppinen2025::preset_params(c.side, c.alpha_star, seed_process);
  const FootprintQuery<double> fp = kemppinen2025::footprint_cells({0.37, 0.61}, c.cells, p);
  GofCase g;
  g.label = fmt::format("{} α={:g} α★={:g} footprint {:g} cells k={}", ndf_name(c.ndf), c.ndf.alpha,
                        c.alpha_star, c.cells, c.side * c.side);
  g.domain = SampleDomain::kDisk;
  const Ndfs nd = c.ndf;
  g.point_pdf = [p, fp, nd, pdf_scale](const V2& x) {
    return pdf_scale * with_ndf(nd, [&](const auto& ndf) {
             return kemppinen2025::sample_density_square(p, ndf, fp, x);
           });
  };
  g.points = [p, fp, nd](std::uint64_t seed, std::uint64_t i) {
    return with_ndf(nd, [&](const auto& ndf) {
      const auto s = kemppinen2025::sample_half(p, ndf, fp, mix64(seed ^ mix64(i + 1)));
      return s.ok ? s.x : V2{std::nan(""), std::nan("")};
    });
  };
  return g;
}

namespace {
double sky(const V3& w) { return 1 + 0.5 * w.x + w.z * w.z; }
}  // namespace

SampEstimate run_estimates(const SampConfig& c, std::uint64_t n, std::uint64_t seed) {
  SampEstimate e;
  const P p = kemppinen2025::preset_params(c.side, c.alpha_star, seed);
  const FootprintQuery<double> fp = kemppinen2025::footprint_cells({0.37, 0.61}, c.cells, p);
  with_ndf(c.ndf, [&](const auto& ndf) {
    for (std::uint64_t i = 0; i < n; ++i) {
      const auto s = kemppinen2025::sample_half(p, ndf, fp, mix64(seed ^ mix64(i + 7)));
      double m = 0, pr = 0;
      if (s.ok) {
        const double g = kemppinen2025::eval(p, ndf, fp, s.h).explicit_part.x * sky(s.h);
        const double pm = kemppinen2025::sample_density_half(p, ndf, fp, s.h);
        m = pm > 0 ? g / pm : 0;
        pr = s.pdf_printed_h > 0 ? g / s.pdf_printed_h : 0;
      }
      e.marginal.add(m);
      e.printed.add(pr);
      // Smooth NDF sampling: ω_h of density D cosθ (Walter et al. 2007 Eq. 28–29, 35–36).
      const V2 u{counter_uniform<double>(seed, i, 11), counter_uniform<double>(seed, i, 12)};
      const V3 h = sample_normal_walter(ndf, u);
      const double pdf = ndf.D(h) * h.z;
      e.smooth.add(pdf > 0 ? kemppinen2025::eval(p, ndf, fp, h).explicit_part.x * sky(h) / pdf : 0);
    }
    return 0;
  });
  return e;
}

MeanAccumulator scaled_estimate(const MeanAccumulator& a, double s) {
  MeanAccumulator out = a;
  out.mean /= s;
  out.m2 /= s * s;
  return out;
}

std::vector<RenderConfig> render_configs(Budget b) {
  std::vector<RenderConfig> c = {
      {{true, 0.3}, 0.02, 2.5, 1}, {{false, 0.3}, 0.02, 2.5, 1}, {{true, 0.2}, 0.02, 1, 2}};
  if (b == Budget::kFull) {
    c.push_back({{false, 0.2}, 0.02, 1, 2});
    c.push_back({{true, 0.3}, 0.05, 2.5, 1});
  }
  return c;
}

std::string render_label(const RenderConfig& c) {
  return fmt::format("{} α={:g} α★={:g} {:g} cells k={}", ndf_name(c.ndf), c.ndf.alpha,
                     c.alpha_star, c.cells, c.side * c.side);
}

RenderSize render_size(Budget b) {
  return b == Budget::kQuick ? RenderSize{4, 4096, 2048, 256} : RenderSize{4, 65536, 16384, 768};
}

namespace {
// Two-sided normal p of (estimate − reference) with both variances.
double bias_p(const Moments& m, double ref, double ref_var) {
  const double se = std::sqrt(m.var + ref_var);
  return se > 0 ? std::erfc(std::abs(m.mean - ref) / se / std::numbers::sqrt2) : 1.0;
}
}  // namespace

RenderRow run_render(const RenderConfig& c, const RenderSize& sz, std::uint64_t seed) {
  RenderRow row;
  row.c = c;
  row.n = c.side == 1 ? sz.n_k1 : sz.n_k4;
  const P p = kemppinen2025::preset_params(c.side, c.alpha_star, seed);
  const EnvironmentMap env(kemppinen2025::env_sky());
  const kemppinen2025::PlaneView view{30 * std::numbers::pi / 180, {0, 0}, 0};
  const V3 v = view.view();
  const std::size_t np = std::size_t(sz.pixels);
  std::vector<kemppinen2025::EnvReference> refs(np);
  std::vector<kemppinen2025::EnvSamples> smp(np);
  tbb::parallel_for(std::size_t(0), 2 * np, [&](std::size_t t) {
    const std::size_t i = t % np;
    const FootprintQuery<double> fp = kemppinen2025::footprint_cells(position(seed, i), c.cells, p);
    with_ndf(c.ndf, [&](const auto& ndf) {
      if (t < np)
        refs[i] =
            kemppinen2025::env_reference(p, ndf, fp, env, v, sz.ref_n, mix64(seed ^ (i + 17)));
      else
        smp[i] = kemppinen2025::env_samples(p, ndf, fp, env, v, row.n, mix64(seed ^ (i + 29)));
      return 0;
    });
  });
  std::vector<std::vector<double>> lum[3];
  std::vector<double> ref_pixels;
  Moments* mom[3] = {&row.exact, &row.printed, &row.smooth};
  std::uint64_t explicit_count = 0;
  for (std::size_t i = 0; i < np; ++i) {
    const double inv = 1.0 / double(np);
    ref_pixels.push_back(kemppinen2025::luminance(refs[i].mean));
    row.ref += inv * ref_pixels.back();
    row.ref_var += inv * inv * refs[i].luminance_variance;
    const std::vector<Vec3<double>>* src[3] = {&smp[i].exact, &smp[i].printed, &smp[i].smooth};
    for (int k = 0; k < 3; ++k) {
      MeanAccumulator acc;
      std::vector<double> y;
      for (const Vec3<double>& e : *src[k]) {
        y.push_back(kemppinen2025::luminance(e));
        acc.add(y.back());
      }
      mom[k]->mean += inv * acc.mean;
      mom[k]->var += inv * inv * acc.variance() / double(acc.n);
      lum[k].push_back(std::move(y));
    }
    row.q = smp[i].q;
    explicit_count += smp[i].from_explicit;
  }
  row.explicit_fraction = double(explicit_count) / double(row.n * np);
  row.p_exact = bias_p(row.exact, row.ref, row.ref_var);
  row.p_printed = bias_p(row.printed, row.ref, row.ref_var);
  row.p_smooth = bias_p(row.smooth, row.ref, row.ref_var);
  // Sensitivity: the exact mixture density × kSampRenderSensitivity (every estimate divided).
  row.p_control =
      bias_p({row.exact.mean / kSampRenderSensitivity, row.exact.var / sqr(kSampRenderSensitivity)},
             row.ref, row.ref_var);
  std::vector<int> spps;
  for (std::uint64_t s = 1; s * 16 <= row.n; s *= 4) spps.push_back(int(s));
  row.slope_exact = loglog_slope(rmse_at_spp(lum[0], ref_pixels, spps));
  row.slope_printed = loglog_slope(rmse_at_spp(lum[1], ref_pixels, spps));
  row.slope_smooth = loglog_slope(rmse_at_spp(lum[2], ref_pixels, spps));
  return row;
}

}  // namespace glintlab::verify::kemppinen_claims

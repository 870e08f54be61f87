// Generation, MIP pyramids and filtered lookups of the Chermain et al. 2020 dictionary (2021 Sec.
// 3, Fig. 3; Sec. 6.1 and Eq. 19 for the pyramids and textureGrad).
#include "core/glints/chermain_dictionary.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/io/exr.h"
#include "core/math/ops.h"
#include "core/math/rng.h"
#include "core/parameter_check.h"

namespace glintlab::chermain2021 {

void validate(const DictionaryConfig& c) {
  const char* what = "chermain dictionary";
  detail::require(c.distributions >= 3 && c.distributions <= 3 * 4096 && c.distributions % 3 == 0,
                  what, "distributions (N)", c.distributions,
                  "a positive multiple of 3, at most 12288");
  detail::require(c.levels >= 1 && c.levels <= 20, what, "levels (L)", c.levels, "1 to 20");
  detail::require(
      c.resolution >= 4 && c.resolution <= 4096 && (c.resolution & (c.resolution - 1)) == 0, what,
      "resolution", c.resolution, "a power of two from 4 to 4096");
  detail::require(std::isfinite(c.alpha_dict) && c.alpha_dict > 0 && c.alpha_dict <= 2, what,
                  "alpha_dict", c.alpha_dict, "(0, 2]");
  detail::require(std::isfinite(c.mean_scale) && c.mean_scale > 0 && c.mean_scale <= 4, what,
                  "mean_scale", c.mean_scale, "(0, 4]");
  const double sigma_o = c.alpha_dict / std::sqrt(2.0);
  if (!(std::isfinite(c.lobe_std) && c.lobe_std > 0 && c.lobe_std < sigma_o))
    throw ParameterError(fmt::format(
        "{}: lobe_std = {} is out of range (valid: (0, alpha_dict/sqrt(2)) = (0, {:.6g}))", what,
        c.lobe_std, sigma_o));
}

namespace {

// Uniform in (0, 1): the counter uniform shifted by half an ulp so that its log stays finite.
double open_uniform(std::uint64_t seed, std::uint64_t index, std::uint64_t dim) {
  return counter_uniform<double>(seed, index, dim) + std::ldexp(1.0, -54);
}

// G(z) = ½ erf(z/√2), the standard normal mass in [0, z], by cubic Hermite interpolation of a
// table at spacing 1/256 with the exact derivatives φ(z) (error below 1e-13, ten times faster than
// std::erf; generation is dominated by these evaluations). |z| ≥ 8.5: ±½ (the rest is < 1e-16).
class NormalMass {
 public:
  NormalMass() {
    for (int i = 0; i <= kCount; ++i) {
      const double z = -kRange + i * kStep;
      value_[std::size_t(i)] = 0.5 * std::erf(z / std::sqrt(2.0));
      slope_[std::size_t(i)] = std::exp(-0.5 * z * z) / std::sqrt(2 * kPi<double>);
    }
  }
  double operator()(double z) const {
    if (z <= -kRange) return -0.5;
    if (z >= kRange) return 0.5;
    const double s = (z + kRange) / kStep;
    const int i = std::min(int(s), kCount - 1);
    const double t = s - i;
    const double t2 = t * t, t3 = t2 * t;
    const std::size_t a = std::size_t(i), b = a + 1;
    return (2 * t3 - 3 * t2 + 1) * value_[a] + (t3 - 2 * t2 + t) * kStep * slope_[a] +
           (-2 * t3 + 3 * t2) * value_[b] + (t3 - t2) * kStep * slope_[b];
  }

 private:
  static constexpr double kRange = 8.5, kStep = 1.0 / 256;
  static constexpr int kCount = int(2 * kRange * 256);
  std::array<double, kCount + 1> value_{}, slope_{};
};

}  // namespace

// Lobe j of distribution n: a Box–Muller normal (Box & Muller 1958) from the counters
// (seed, n, 256 j + 2a) and (seed, n, 256 j + 2a + 1), redrawn (a = 1, 2, …) while its mean lies
// outside the table (|μ| ≥ 4σ_o, probability 6e-5 per draw): a lobe wholly outside the table would
// leave a level empty. The limit is therefore the Gaussian truncated at 4σ_o, whose variance is
// 0.9989 σ_o² before the lobe width is added back.
double Dictionary::lobe_mean(int n, int j) const {
  const double sd =
      config_.mean_scale * std::sqrt(sigma_o_ * sigma_o_ - config_.lobe_std * config_.lobe_std);
  double mu = 0;
  for (std::uint64_t a = 0; a < 128; ++a) {
    const std::uint64_t dim = (std::uint64_t(j) << 8) + 2 * a;
    const double r = std::sqrt(-2 * std::log(open_uniform(config_.seed, std::uint64_t(n), dim)));
    const double phi =
        2 * kPi<double> * counter_uniform<double>(config_.seed, std::uint64_t(n), dim + 1);
    mu = sd * r * std::cos(phi);
    if (std::abs(mu) < extent()) break;
  }
  return std::clamp(mu, -0.999 * extent(), 0.999 * extent());
}

Dictionary::Dictionary(const DictionaryConfig& config) : config_(config) {
  validate(config_);
  sigma_o_ = config_.alpha_dict / std::sqrt(2.0);
  const int res = config_.resolution;
  mip_levels_ = 1;
  while ((res >> (mip_levels_ - 1)) > 1) ++mip_levels_;
  per_table_ = 0;
  for (int m = 0; m < mip_levels_; ++m) {
    mip_offset_.push_back(per_table_);
    per_table_ += std::size_t(res >> m);
  }
  const int N = config_.distributions, L = config_.levels;
  // One float past the last table: the batched lookups read texel pairs (core/glints/
  // chermain_lanes.h, gather_texel_pair), whose second float may lie one past the table's end.
  mips_.assign(std::size_t(N) * std::size_t(L) * per_table_ + 1, 0.0f);
  const double delta = extent() / res;
  const double s = config_.lobe_std;
  const double inv = 1 / s;
  static const NormalMass G;
  // Distributions are independent: each is filled by one task, in lobe order, so the tables do not
  // depend on the thread count.
  tbb::parallel_for(0, N, [&](int n) {
    std::vector<double> mass(std::size_t(res), 0.0);
    // Mass of the symmetrized lobe pair ½N(μ, s²) + ½N(−μ, s²) in each texel of |x|: both halves
    // fold to the mass of N(|μ|, s²) in x ∈ [a, b) plus its mirror part in x ∈ (−b, −a], summed
    // only over the texels within 6 s of |μ| (the rest is below 2e-9 of the lobe, and the table
    // is renormalized below). the normal mass at each texel edge is computed once.
    const auto add_lobe = [&](double mu) {
      const double m = std::abs(mu);
      const int t0 = std::max(0, int(std::floor((m - 6 * s) / delta)));
      const int t1 = std::min(res - 1, int(std::floor((m + 6 * s) / delta)));
      const bool mirror = m < 6 * s;  // the mirror part is negligible away from 0
      double ea = G((t0 * delta - m) * inv);
      double fa = mirror ? G((-t0 * delta - m) * inv) : 0.0;
      for (int t = t0; t <= t1; ++t) {
        const double b = (t + 1) * delta;
        const double eb = G((b - m) * inv);
        double p = eb - ea;
        if (mirror) {
          const double fb = G((-b - m) * inv);
          p += fa - fb;
          fa = fb;
        }
        mass[std::size_t(t)] += p;
        ea = eb;
      }
    };
    int lobes = 0;
    for (int k = 0; k < L; ++k) {
      for (; lobes < (1 << k); ++lobes) add_lobe(lobe_mean(n, lobes));
      double total = 0;
      for (double v : mass) total += v;
      float* table = &mips_[offset(n, k)];
      for (int t = 0; t < res; ++t) table[t] = float(mass[std::size_t(t)] / (2 * delta * total));
      // MIP chain: each coarser texel the mean of its two children (the 1D box filter of
      // glGenerateMipmap), which keeps Δ_m Σ texels constant.
      for (int m = 1; m < mip_levels_; ++m) {
        const float* fine = table + mip_offset_[std::size_t(m - 1)];
        float* coarse = table + mip_offset_[std::size_t(m)];
        for (int t = 0; t < (res >> m); ++t)
          coarse[t] = float(0.5 * (double(fine[2 * t]) + double(fine[2 * t + 1])));
      }
    }
  });
}

double Dictionary::lookup_lod(int n, int k, double x, double mip, TableWrap wrap) const {
  const Table t = table();
  return chermain2021::lookup_lod(t, table_base(t, double(n), double(k)), x, mip, wrap);
}

double Dictionary::lookup_grad(int n, int k, double x, double dx_dpx, double dx_dpy, TableWrap wrap,
                               int max_anisotropy, TableFilter* filter) const {
  const Table t = table();
  const Grad<double> g = chermain2021::lookup_grad(t, table_base(t, double(n), double(k)), x,
                                                   dx_dpx, dx_dpy, wrap, max_anisotropy);
  if (filter) *filter = {g.lambda, int(g.probes)};
  return g.value;
}

double Dictionary::table_integral(int n, int k, int mip) const {
  double s = 0;
  const int size = config_.resolution >> mip;
  for (int t = 0; t < size; ++t) s += double(texel(n, k, mip, t));
  return 2 * (extent() / size) * s;
}

Image Dictionary::image() const {
  const int rows = config_.distributions / 3 * config_.levels;
  Image img(config_.resolution, rows, {"R", "G", "B"});
  for (int g = 0; g < config_.distributions / 3; ++g)
    for (int k = 0; k < config_.levels; ++k)
      for (int t = 0; t < config_.resolution; ++t)
        for (int c = 0; c < 3; ++c)
          img.at(t, g * config_.levels + k, std::size_t(c)) = double(texel(3 * g + c, k, 0, t));
  return img;
}

double lookup_grad_integral(const Dictionary& d, int n, int k, double dx_dpx, double dx_dpy,
                            TableWrap wrap, int per_texel) {
  const int steps = 2 * d.resolution() * per_texel;
  const double h = 2 * d.extent() / steps;
  double s = 0;
  for (int i = 0; i < steps; ++i)
    s += d.lookup_grad(n, k, -d.extent() + (i + 0.5) * h, dx_dpx, dx_dpy, wrap);
  return s * h;
}

const Dictionary& default_chermain_dictionary() {
  static const Dictionary kDictionary{DictionaryConfig{}};
  return kDictionary;
}

void write_chermain_dictionary_exr(const std::string& path, const Dictionary& d) {
  const DictionaryConfig& c = d.config();
  io::write_exr(path, d.image(),
                {{"glintlab.chermain.distributions", fmt::format("{}", c.distributions)},
                 {"glintlab.chermain.levels", fmt::format("{}", c.levels)},
                 {"glintlab.chermain.resolution", fmt::format("{}", c.resolution)},
                 {"glintlab.chermain.alpha_dict", fmt::format("{}", c.alpha_dict)},
                 {"glintlab.chermain.lobe_std", fmt::format("{}", c.lobe_std)},
                 {"glintlab.chermain.seed", fmt::format("{}", c.seed)},
                 {"glintlab.chermain.layout",
                  "row (n/3)*levels + k holds distributions 3(n/3)..+2 of level k in R,G,B; "
                  "texel t covers |slope| in [t, t+1) * 4 sigma_o / resolution"}});
}

}  // namespace glintlab::chermain2021

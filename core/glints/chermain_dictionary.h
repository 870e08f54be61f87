// The dictionary of multiscale 1D slope marginals of Chermain et al. 2020 (recapitulated in
// Chermain et al. 2021 Sec. 3, Fig. 3), the MIP pyramid of every table (2021 Sec. 6.1) and the
// textureLod / textureGrad with mirrored repeat that Eq. 19 filters them with (host entry points of
// the generic kernels of core/glints/chermain_lookup.h).
//
// Distribution n, level k: a normalized sum of 2^k Gaussian lobes of standard deviation s (the
// lobe std), symmetrized (a lobe at μ and one at −μ), whose means μ_0, μ_1, … are one fixed
// sequence per distribution, so level k is a prefix of level k + 1. The means are drawn from a
// centred Gaussian of variance σ_o² − s² (truncated to the table, |μ| < 4σ_o), σ_o = α_dict/√2 the
// standard deviation of the Beckmann slope marginal of roughness α_dict: the lobe mixture then
// converges to that marginal (variance (σ_o² − s²) + s² = σ_o², less 0.1 % for the truncation)
// as k grows (Fig. 3). Our choice: the 2021 paper only says the highest level is the Beckmann
// marginal; narrowing the means by the lobe variance makes the limit exact. Tables hold
// `resolution` texels over |x| ∈ [0, 4σ_o); texel t stores the mass of the symmetrized mixture in
// |x| ∈ [tΔ, (t+1)Δ) over 2Δ (Δ = 4σ_o/resolution), renormalized so that 2Δ Σ_t P[t] = 1: the
// piecewise-linear lookup below integrates to exactly 1 over x ∈ (−4σ_o, 4σ_o) at every MIP level.
// Generated at run time (about 0.5 s for the defaults), never stored in the repository: the same
// configuration and seed give bit-identical tables on every machine and thread count.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/glints/chermain_lookup.h"
#include "core/render/image.h"

namespace glintlab::chermain2021 {

struct DictionaryConfig {
  int distributions = 192;  // N: a positive multiple of 3 (three marginals per RGB texel)
  int levels = 16;          // L: levels 0 … L−1, level k with 2^k lobes; 1 … 20
  int resolution = 64;      // texels over |x| ∈ [0, 4σ_o); a power of two, 4 … 4096
  double alpha_dict = 0.5;  // α of the Beckmann marginal the levels converge to; (0, 2]
  double lobe_std = 0.02;   // s, standard deviation of each lobe; (0, σ_o)
  std::uint64_t seed = 2020;
  // Spread of the lobe means relative to the dictionary's (1 = as described above). Only for the
  // negative control of chermain.dictionary-converges (1.02: lobe means spread 2 % too wide);
  // (0, 4].
  double mean_scale = 1.0;
};

// Throws ParameterError (core/parameter_check.h) naming the first bad field and its valid range.
void validate(const DictionaryConfig& c);

// One textureGrad-style lookup's filter, reported for the intermediates.
struct TableFilter {
  double lambda = 0;  // MIP level of detail used (0 = full resolution)
  int probes = 1;     // anisotropic probes averaged
};

class Dictionary {
 public:
  explicit Dictionary(const DictionaryConfig& config);

  const DictionaryConfig& config() const { return config_; }
  int distributions() const { return config_.distributions; }
  int levels() const { return config_.levels; }
  int resolution() const { return config_.resolution; }
  int mip_levels() const { return mip_levels_; }  // log2(resolution) + 1
  double sigma_o() const { return sigma_o_; }     // α_dict / √2
  double extent() const { return 4 * sigma_o_; }  // tables cover |x| < extent()

  // Texel t of MIP level m (m = 0: the generated table) of distribution n, level k.
  float texel(int n, int k, int mip, int t) const {
    return mips_[offset(n, k) + mip_offset_[std::size_t(mip)] + std::size_t(t)];
  }
  // The texels as the lookup kernels read them (core/glints/chermain_lookup.h).
  Table table() const {
    return {mips_.data(), config_.levels, config_.resolution, mip_levels_, per_table_, extent()};
  }
  // Mean of lobe j of distribution n (before symmetrization), for the tests.
  double lobe_mean(int n, int j) const;

  // textureLod(P_o(n, k), x, mip): linear interpolation between texel centres at one MIP level,
  // the slope x mapped to the normalized coordinate u = x / (4σ_o); 0 for |x| ≥ 4σ_o (the table
  // domain, outside of which the marginal vanishes).
  double lookup_lod(int n, int k, double x, double mip = 0,
                    TableWrap wrap = TableWrap::kMirroredRepeat) const;

  // textureGrad(P_o(n, k), x, dx_dpx, dx_dpy) (2021 Eq. 19) on the CPU, the 1D form of the
  // anisotropic rule of EXT_texture_filter_anisotropic: the footprint lengths in texels
  // ρ_x = |dx/dpx|·res/(4σ_o), ρ_y likewise; P_max, P_min their max and min; N =
  // min(⌈P_max/P_min⌉, max_anisotropy) probes; λ = log2(P_max/N) clamped to the pyramid; the
  // result is the mean of N trilinear lookups (linear within a level, linear between ⌊λ⌋ and
  // ⌊λ⌋+1) at x + (i + ½ − N/2)/N · d, d the major-axis derivative. Every step is a normalized
  // average of shifted copies of a mirrored-periodic table, so the filtered marginal keeps unit
  // integral over (−4σ_o, 4σ_o) (Eq. 15). With both derivatives 0 it equals lookup_lod(·, 0).
  double lookup_grad(int n, int k, double x, double dx_dpx, double dx_dpy,
                     TableWrap wrap = TableWrap::kMirroredRepeat, int max_anisotropy = 16,
                     TableFilter* filter = nullptr) const;

  // Integral of the lookup over x ∈ (−4σ_o, 4σ_o) at one MIP level, exact for the piecewise-linear
  // interpolant (Δ_m Σ texels ·2 with mirrored repeat).
  double table_integral(int n, int k, int mip) const;

  // The dictionary as an image: width = resolution, height = (N/3)·L rows, row (n/3)·L + k holds
  // distributions 3(n/3), +1, +2 of level k in R, G, B (MIP level 0 only).
  Image image() const;

 private:
  std::size_t offset(int n, int k) const {
    return (std::size_t(n) * std::size_t(config_.levels) + std::size_t(k)) * per_table_;
  }

  DictionaryConfig config_;
  double sigma_o_ = 0;
  int mip_levels_ = 0;
  std::size_t per_table_ = 0;  // floats of one table with its whole MIP chain
  std::vector<std::size_t> mip_offset_;
  std::vector<float> mips_;  // [n][k][mip chain]
};

// ∫ lookup_grad(n, k, x, dx_dpx, dx_dpy) dx over x ∈ (−4σ_o, 4σ_o) by the midpoint rule with
// `per_texel` points per level-0 texel (the integrand is piecewise linear on a grid no coarser
// than that, so the rule converges fast): 1 up to float rounding where Eq. 15 holds.
double lookup_grad_integral(const Dictionary& d, int n, int k, double dx_dpx, double dx_dpy,
                            TableWrap wrap, int per_texel = 16);

// The default dictionary (DictionaryConfig{}), generated on first use.
const Dictionary& default_chermain_dictionary();

// Writes `d.image()` as an EXR with the configuration in the header (atomic).
void write_chermain_dictionary_exr(const std::string& path, const Dictionary& d);

}  // namespace glintlab::chermain2021

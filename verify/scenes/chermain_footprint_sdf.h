// The patch-SDF of Chermain et al. 2021 (Eq. 3, 4–6, with M of Eq. 18; no GGAA) at many slopes for
// one footprint. What depends only on the footprint — the matrix M, the LOD, the two LODs' weights
// and each of their four cells' draws (rotation θ and marginals, a counter hash and a sincos each)
// — is drawn once; each slope then runs the remaining operations of chermain2021::patch_sdf in
// the same order, so every value is that function's bit for bit. glint_values evaluates the
// glinty BRDF of many samples of one footprint at once, in the double lanes of the widest ISA
// with fused multiply-add (every remaining operation is exactly rounded there, so the lanes give
// the scalar bits too; tests/verify/scenes/chermain_footprint_sdf_test.cpp). For the references
// that shade many samples with the pixel's footprint (chermain_scenes.cpp), where the draws and
// the table lookups are the work.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/glints/chermain.h"
#include "core/simd/batch.h"

namespace glintlab::verify {

class FootprintSdf {
 public:
  // One term of Eq. 3: a cell's weight w(l) W_P(l, s_0), its marginals' first texels and its
  // rotation, or the smooth limit's weight (past the last dictionary level).
  struct Term {
    double w;
    bool smooth;
    double base_x, base_y, cos_t, sin_t;
  };

  FootprintSdf(const chermain2021::SdfParams& p, const FootprintQuery<double>& fp)
      : p_(without_ggaa(p)),
        table_(p.dictionary->table()),
        M_(chermain2021::matrix(p.sigma_x, p.sigma_y, p.rho, p.dictionary->sigma_o(), p.with_rho)) {
    draw_terms(p, table_, fp, [&](const Term& t) {
      has_smooth_ = has_smooth_ || t.smooth;
      terms_[std::size_t(count_++)] = t;
    });
  }
  // The footprint whose terms were drawn already (draw_terms, none of them smooth).
  FootprintSdf(const chermain2021::SdfParams& p, std::span<const Term> terms)
      : p_(without_ggaa(p)),
        table_(p.dictionary->table()),
        M_(chermain2021::matrix(p.sigma_x, p.sigma_y, p.rho, p.dictionary->sigma_o(), p.with_rho)) {
    for (const Term& t : terms) terms_[std::size_t(count_++)] = t;
  }

  // The terms patch_sdf's visitor adds for footprint fp, in its order (its inactive visits add
  // nothing): add(term) for each.
  template <class Add>
  static void draw_terms(const chermain2021::SdfParams& p, const chermain2021::Table& table,
                         const FootprintQuery<double>& fp, Add&& add) {
    const double last_level = double(p.dictionary->levels() - 1);
    chermain2021::for_each_cell(
        p, fp, [&](bool on, double w, double k, const chermain2021::Cell<double>& s) {
          if (!on) return;
          Term t{};
          t.w = w;
          t.smooth = k > last_level;
          if (!t.smooth) {
            const double kc = chermain2021::std_min(k, last_level);
            t.base_x = chermain2021::table_base(table, s.nx, kc);
            t.base_y = chermain2021::table_base(table, s.ny, kc);
            t.cos_t = s.cos_t, t.sin_t = s.sin_t;
          }
          add(t);
        });
  }

  // chermain2021::patch_sdf(p, m, fp, {0, 0, 0, 0}) for this footprint's p and fp.
  double operator()(Vec2<double> m) const {
    const double rho_used = p_.with_rho ? p_.rho : 0.0;
    const double mx = M_.i00 * m.x + M_.i01 * m.y, my = M_.i11 * m.y;  // M⁻¹ m̃
    double gauss = 0;
    bool have_gauss = false;
    double total = 0;
    for (const Term& t : terms()) {
      if (t.smooth) {
        if (!have_gauss)
          gauss = chermain2021::gaussian_sdf(m.x, m.y, p_.sigma_x, p_.sigma_y, rho_used);
        have_gauss = true;
        total = total + t.w * gauss;
        continue;
      }
      const double xo = t.cos_t * mx + t.sin_t * my, yo = -t.sin_t * mx + t.cos_t * my;
      const double px = chermain2021::lookup_lod(table_, t.base_x, xo, 0, p_.wrap);
      const double py = chermain2021::lookup_lod(table_, t.base_y, yo, 0, p_.wrap);
      total = total + t.w * px * py / M_.det;
    }
    return total;
  }

  std::span<const Term> terms() const { return {terms_.data(), std::size_t(count_)}; }
  bool has_smooth() const { return has_smooth_; }
  const chermain2021::SdfParams& params() const { return p_; }
  const chermain2021::Table& table() const { return table_; }
  const chermain2021::Matrix& matrix() const { return M_; }

 private:
  static const chermain2021::SdfParams& without_ggaa(const chermain2021::SdfParams& p) {
    if (p.kernel != chermain2021::kNoGgaa)
      throw std::invalid_argument("FootprintSdf: GGAA kernels need per-slope derivatives");
    return p;
  }

  chermain2021::SdfParams p_;
  chermain2021::Table table_;
  chermain2021::Matrix M_;
  std::array<Term, 10> terms_{};  // at most 2 LODs × (the smooth limit or 4 cells)
  int count_ = 0;
  bool has_smooth_ = false;
};

// Eq. 1 with D from the patch-SDF `sdf` at slope h̃ − `shift` (Eq. 2 / 8), V-cavity G2, F = 1,
// times ω_o·n: the cosine-weighted BRDF for light from ω_l.
template <class Sdf>
double glint_value_of(const Sdf& sdf, Vec3<double> wi, Vec3<double> wl, Vec2<double> shift) {
  if (!(wi.z > 0 && wl.z > 0)) return 0;
  const Vec3<double> h = half_vector(wi, wl);
  if (!(h.z > 0)) return 0;
  const Vec2<double> m{-h.x / h.z - shift.x, -h.y / h.z - shift.y};
  const double z2 = h.z * h.z;
  const double D = sdf(m) / (z2 * z2);
  return D * chermain2021::v_cavity_g2(wi, wl, h) / (4 * wi.z);  // f · ω_l.z
}

// Samples of one footprint in columns: ω_i, ω_l (local frame) and the slope shift.
struct GlintSamples {
  std::vector<double> wi_x, wi_y, wi_z, wl_x, wl_y, wl_z, shift_x, shift_y;
  std::size_t size() const { return wi_x.size(); }
  void reserve(std::size_t n) {
    for (std::vector<double>* c : {&wi_x, &wi_y, &wi_z, &wl_x, &wl_y, &wl_z, &shift_x, &shift_y})
      c->reserve(n);
  }
  void clear() {
    for (std::vector<double>* c : {&wi_x, &wi_y, &wi_z, &wl_x, &wl_y, &wl_z, &shift_x, &shift_y})
      c->clear();
  }
  void push(Vec3<double> wi, Vec3<double> wl, Vec2<double> shift) {
    wi_x.push_back(wi.x), wi_y.push_back(wi.y), wi_z.push_back(wi.z);
    wl_x.push_back(wl.x), wl_y.push_back(wl.y), wl_z.push_back(wl.z);
    shift_x.push_back(shift.x), shift_y.push_back(shift.y);
  }
};

// The terms of many footprints, one per sample (each sample's cells drawn on the host, as
// FootprintSdf draws them), for glint_values over samples that each have their own footprint.
// Slot t of sample i is its t-th term; slots past its count hold weight 0 (adding +0 to the sum
// leaves it as it is: every term is ≥ 0). A sample with a smooth term is flagged: glint_values
// evaluates it on the host.
class SampleFootprints {
 public:
  static constexpr int kSlots = 8;                                  // 2 LODs × 4 cells
  static constexpr FootprintSdf::Term kNone{0, false, 0, 0, 0, 0};  // a slot past the count
  explicit SampleFootprints(const chermain2021::SdfParams& p)
      : p_(p), table_(p.dictionary->table()) {}
  void clear() {
    for (int t = 0; t < kSlots; ++t)
      for (std::vector<double>* c : {&w_[t], &base_x_[t], &base_y_[t], &cos_t_[t], &sin_t_[t]})
        c->clear();
    count_.clear(), footprints_.clear(), smooth_.clear();
  }
  void reserve(std::size_t n) {
    for (int t = 0; t < kSlots; ++t)
      for (std::vector<double>* c : {&w_[t], &base_x_[t], &base_y_[t], &cos_t_[t], &sin_t_[t]})
        c->reserve(n);
    count_.reserve(n), footprints_.reserve(n), smooth_.reserve(n);
  }
  void push(const FootprintQuery<double>& fp) {
    std::array<FootprintSdf::Term, 10> terms{};
    std::size_t count = 0;
    bool smooth = false;
    FootprintSdf::draw_terms(p_, table_, fp, [&](const FootprintSdf::Term& t) {
      smooth = smooth || t.smooth;
      terms[count++] = t;
    });
    if (smooth) count = 0;  // evaluated on the host
    for (std::size_t t = 0; t < std::size_t(kSlots); ++t) {
      const FootprintSdf::Term& term = t < count ? terms[t] : kNone;
      w_[t].push_back(term.w), base_x_[t].push_back(term.base_x);
      base_y_[t].push_back(term.base_y);
      cos_t_[t].push_back(term.cos_t), sin_t_[t].push_back(term.sin_t);
    }
    count_.push_back(int(count));
    footprints_.push_back(fp);
    smooth_.push_back(smooth);
  }
  std::size_t size() const { return count_.size(); }
  const chermain2021::SdfParams& params() const { return p_; }
  int count(std::size_t i) const { return count_[i]; }
  bool smooth(std::size_t i) const { return smooth_[i] != 0; }
  const FootprintQuery<double>& footprint(std::size_t i) const { return footprints_[i]; }
  // Sample i's footprint for the host: from its slots, or drawn again where a term is smooth.
  FootprintSdf sdf(std::size_t i) const {
    if (smooth(i)) return FootprintSdf(p_, footprints_[i]);
    std::array<FootprintSdf::Term, kSlots> terms{};
    for (int t = 0; t < count_[i]; ++t)
      terms[std::size_t(t)] = {w_[t][i],      false,        base_x_[t][i],
                               base_y_[t][i], cos_t_[t][i], sin_t_[t][i]};
    return FootprintSdf(p_,
                        std::span<const FootprintSdf::Term>(terms.data(), std::size_t(count_[i])));
  }
  const double* w(int t) const { return w_[t].data(); }
  const double* base_x(int t) const { return base_x_[t].data(); }
  const double* base_y(int t) const { return base_y_[t].data(); }
  const double* cos_t(int t) const { return cos_t_[t].data(); }
  const double* sin_t(int t) const { return sin_t_[t].data(); }

 private:
  chermain2021::SdfParams p_;
  chermain2021::Table table_;
  std::vector<double> w_[kSlots], base_x_[kSlots], base_y_[kSlots], cos_t_[kSlots], sin_t_[kSlots];
  std::vector<int> count_;
  std::vector<FootprintQuery<double>> footprints_;
  std::vector<char> smooth_;
};

// out[i] = glint_value_of(sdf, ω_i, ω_l, shift of sample i), bit for bit, on `isa`'s double lanes
// (AVX2 or AVX-512; one sample at a time on the others, or where a term is the smooth limit, whose
// exp the lanes would not round as glibc). out.size() = samples.size().
void glint_values(const FootprintSdf& sdf, const GlintSamples& samples, std::span<double> out,
                  simd::Isa isa);
// The same on simd::default_isa() (GLINTLAB_ISA or the CPU's widest).
void glint_values(const FootprintSdf& sdf, const GlintSamples& samples, std::span<double> out);
// out[i] = glint_value_of(FootprintSdf(p, footprint i), ω_i, ω_l, shift of sample i), bit for
// bit: each sample with its own footprint (footprints.size() = samples.size()).
void glint_values(const SampleFootprints& footprints, const GlintSamples& samples,
                  std::span<double> out, simd::Isa isa);
void glint_values(const SampleFootprints& footprints, const GlintSamples& samples,
                  std::span<double> out);

}  // namespace glintlab::verify

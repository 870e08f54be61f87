// Shared parts of the conformance properties (verify/conformance/conformance.h): the settings a
// model is checked at, queries, copies of an entry made wrong (the controls), deterministic
// parallel loops.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/model_registry.h"
#include "verify/conformance/conformance.h"

namespace glintlab::verify::conformance {

// One parameter setting and query: the model's defaults, ωi at θi (the generic azimuth of
// incidence_at), the footprint at uv (0.5, 0.5) with side `footprint`, the light the stability
// sweep gives the model (a 1° cone for area lights, a delta otherwise), the corner reflections for
// kNeedsPixelCorners models.
struct Setting {
  std::vector<double> values;
  ModelQuery<double> query;
  double theta_deg = 0;
  std::string label;
  // The share of the property's sample count (and of its reference integral's draws) this setting
  // gets: 1 at the defaults, variant_share for a parameter choice (variant_settings).
  double share = 1;
};
ModelQuery<double> make_query(const ModelEntry& m, double theta_deg, double footprint);
// The footprint side of the settings and the precision comparisons: 0.1 in uv, where the glint
// models' default densities put tens to thousands of glints in a footprint (at the sweep's 1e-3
// most footprints hold none and every value is ~0, which tests nothing).
inline constexpr double kFootprint = 0.1;
// A footprint 4 × wider, where sampler-covers-value also measures footprint models: there
// kneiphof_klein's default density puts about ten times the glints into the footprint (∫ value at
// θi = 70°: 0.066 at 0.1, 0.64 at 0.4), and the per-sample relative spread of both of the test's
// estimates falls about threefold (measured), so a 3 % loss of the value's support is detectable.
inline constexpr double kWideFootprint = 0.4;
// Quick: θi ∈ {30°, 70°}; full: θi ∈ {0°, 30°, 60°, 80°}; the model's default parameters.
std::vector<Setting> settings(const ModelEntry& m, Budget b);
// Every declared choice is a configuration: besides the defaults, the sampling properties
// (eval-pdf-consistency, sampler-matches-pdf, sampler-covers-value, pdf-normalized) and the numeric
// ones (float-vs-double, simd-equivalence) run at
//   - each non-default choice of each parameter with choices (samplers, pdf forms, counting
//     modes), the other parameters at their defaults, and
//   - a roughness grid kRoughnessGrid (alpha_x and alpha_y together, or alpha; values outside the
//     declared range or equal to the default left out), the rest at the defaults.
// Each is one more configuration of the property, inside its Holm–Šidák correction at the
// model's level, so the model's family-wise false-positive rate stays kFamilyWiseRate. To bound
// the cost, the choices of a model together get the samples of one default setting per θi (half
// of one for footprint models): each variant_share of the defaults' samples (and reference
// draws), at one θi (70°) at quick and two (30°, 70°) at full; the rows state their power apart
// from the defaults'.
// energy, stability (which sweeps every sampler choice itself), converges-to-smooth and
// constant-time stay at the defaults.
struct Variant {
  std::vector<double> values;
  std::string label;   // "sampler=ndf", "alpha_x=alpha_y=0.05"
  std::string choice;  // "param=name" for an enumerated choice, empty for the roughness grid
};
inline constexpr std::array<double, 3> kRoughnessGrid = {0.05, 0.3, 0.8};
std::vector<Variant> variants(const ModelEntry& m);
// 1 / V, V the number of variants (1 / 2V for footprint models), at most kMaxVariantShare: a
// model with few choices does not get more than a quarter of the defaults' samples per choice.
// Measured on kemppinen_ggx at quick (CPU time of the checks, without controls): its 10 choices at
// a quarter each took sampler-matches-pdf from about 40 s to 109 s; at 1/V the six properties the
// choices run in took 244 s against about 127 s (k = 9 and 16 evaluate 2–4 × the cells of the
// default k = 4), which is why a footprint model's choices get half of that.
inline constexpr double kMaxVariantShare = 0.25;
double variant_share(const ModelEntry& m);
// The variants' settings for `property` (each variant at the budget's θi above, share
// variant_share); the variants the model declares not claimed for the property (NotClaimed with a
// choice) are left out and described in *left_out ("pdf=printed (not claimed: why)").
std::vector<Setting> variant_settings(const ModelEntry& m, Budget b, std::string_view property,
                                      std::string* left_out);
// "2 at the defaults + 7 parameter choices (sampler=ndf, ...) at 1/4 of the samples", and
// "; not run: ..." where variants were left out.
std::string describe_configurations(std::size_t defaults, const std::vector<Setting>& variants,
                                    const std::string& left_out);

// Settings where a part of the value that the model's paper does not sample carries most of it,
// at their own footprints (never widened), for the properties that check a sampler against the
// value (eval-pdf-consistency, sampler-covers-value and, at the full budget, the weighted
// histogram of sampler-matches-pdf); empty for most models. The Kemppinen models (kemppinen_ggx,
// kemppinen_beckmann): the compensation C of Eq. 10, which Algorithm 2 does not draw (common.cpp
// lists the settings and their measured shares).
std::vector<Setting> compensation_settings(const ModelEntry& m);

// value of eval at ωo, 0 where the model's own validate rejects the query (podee: ωo below the
// horizon, outside its domain) and below the horizon (the value is cosine-weighted).
double value_at(const ModelEntry& m, const std::vector<double>& values, ModelQuery<double> q,
                const Vec3<double>& wo);

// value_at for many directions: out[i] = value_at(m, values, q, wo[i]), with one call of the entry's
// rows function (ModelEntry::eval_rows) for the directions that reach eval.
void values_at(const ModelEntry& m, const std::vector<double>& values, const ModelQuery<double>& q,
               std::span<const Vec3<double>> wo, std::span<double> out);
// values_at with eval's pdf alongside: pdf[i] is eval's pdf at wo[i], 0 where value_at is 0
// without asking eval (below the horizon, a query validate rejects).
void values_and_pdfs_at(const ModelEntry& m, const std::vector<double>& values,
                        const ModelQuery<double>& q, std::span<const Vec3<double>> wo,
                        std::span<double> value, std::span<double> pdf);
// A function of many directions at once: out[i] = f(w[i]).
using DirectionRows = std::function<void(std::span<const Vec3<double>> w, std::span<double> out)>;
// Two functions of many directions computed together (one eval call for both):
// first[i] = f(w[i]), second[i] = g(w[i]).
using DirectionRowPairs = std::function<void(std::span<const Vec3<double>> w,
                                             std::span<double> first, std::span<double> second)>;

// A roughness scale for cubature breakpoints: the model's alpha_x (or alpha), else 0.3.
double roughness_hint(const ModelEntry& m, const std::vector<double>& values);

// ∫ f(ωo) dωo over the sphere in a frame whose pole is the mirror direction of ωi (where glossy
// lobes sit), with breakpoints at the lobe's width and along the horizon.
struct Cubature {
  double value = 0, error = 0;
};
// The relative tolerance the cubature is asked for: differences below it are not resolved.
constexpr double cubature_rel_tol(Budget b) { return b == Budget::kQuick ? 1e-4 : 1e-6; }
Cubature integrate_about_mirror(const std::function<double(const Vec3<double>&)>& f,
                                const Vec3<double>& wi, double width, Budget b);
// The same with f asked for many directions per call (verify/stats/sphere_cubature.h).
Cubature integrate_about_mirror(const DirectionRows& f, const Vec3<double>& wi, double width,
                                Budget b);

// ∫ f(ωo) dωo over the upper hemisphere, by cubature about the mirror direction for models
// without a footprint, and by n Monte Carlo samples for footprint models: a glint model's value
// and pdf hold thousands of peaks of the microroughness' width at the settings' footprint, which
// the adaptive cubature resolved only after minutes per setting. The samples come from a fixed
// mixture about the mirror direction (uniform hemisphere, a GGX VNDF lobe at the roughness width,
// two wider caps; common.cpp), never from the model's sampler; the estimate is unbiased, with a
// standard error that the tests take in (returned as `error`, one σ).
// The Monte Carlo integral's sample count: blocks of the samplers' count (10^5 quick, 2·10^6
// full), as many as a pilot block says reach kReferenceRelativeError (a 2 % difference is then
// about 5 of its standard errors, detected at the models' levels by the integral alone), at most
// kMaxReferenceBlocks. Its per-sample relative spread measured 2–3 × the samplers' (podee,
// kneiphof_klein at θi = 70°), so one block is often not enough.
inline constexpr double kReferenceRelativeError = 0.004;
inline constexpr std::uint64_t kMaxReferenceBlocks = 4;
std::uint64_t reference_block(Budget b);
// f is asked for each chunk's directions at once (Monte Carlo), or one direction at a time
// (cubature).
// share: the blocks are that share of reference_block(b) (a variant's, Setting::share).
HemisphereIntegral integrate_hemisphere(const ModelEntry& m, const DirectionRows& f,
                                        const Vec3<double>& wi, double width, Budget b,
                                        std::uint64_t seed, double share = 1);
// The same with f of one direction.
HemisphereIntegral integrate_hemisphere(const ModelEntry& m,
                                        const std::function<double(const Vec3<double>&)>& f,
                                        const Vec3<double>& wi, double width, Budget b,
                                        std::uint64_t seed);

// Whether `m` is an entry of registered_models() itself (not a copy of one): what the suite keeps
// per entry for the process (value_integral) is kept only for those, whose address is never
// reused (register_model never reallocates the registry).
bool is_registered(const ModelEntry& m);

// ∫ value dωo at a setting by integrate_hemisphere, seeded by the model's name and the setting's
// label, not by the property asking: sampler-covers-value and energy (and any later property) get
// the same integral at the same setting. For a registered entry the result is kept for the
// process, so a suite run computes each setting's integral once; an altered copy (a control's
// model) is never kept, its address may be reused.
HemisphereIntegral value_integral(const ModelEntry& m, const Setting& s, Budget b);

// The sphere cut into cells about the mirror direction of ωi, for the weighted histogram of
// sampler-matches-pdf: four rings, bounded at 2, 8 and 32 × the roughness width from the mirror
// direction, of four azimuth sectors each.
struct MirrorCells {
  static constexpr std::size_t kCount = 16;
  MirrorCells(const Vec3<double>& wi, double width);
  std::size_t cell(const Vec3<double>& w) const;
  Vec3<double> t, s, r;
  std::array<double, 3> ring_cos{};
};
// Per-cell Σ y and Σ y² over n draws, y the draw's contribution to its cell (0 to the others).
struct CellSums {
  std::array<double, MirrorCells::kCount> sum{}, sum_sq{};
  std::array<std::uint64_t, MirrorCells::kCount> hits{};
  std::uint64_t n = 0;
};
// ∫_cell f over the upper hemisphere for every cell, by the Monte Carlo of integrate_hemisphere
// (its mirror mixture; n draws).
// f is asked for each chunk's directions above the horizon at once.
CellSums integrate_cells(const DirectionRows& f, const Vec3<double>& wi, double width,
                         std::uint64_t n, std::uint64_t seed);
// integrate_cells of two integrands at the same n draws (the draws integrate_cells takes with
// this seed and n): the cell sums of f (first) and of g (second).
struct CellSumPair {
  CellSums first, second;
};
CellSumPair integrate_cell_pair(const DirectionRowPairs& fg, const Vec3<double>& wi, double width,
                                std::uint64_t n, std::uint64_t seed);

// The uniform pair of sample i under seed (gof_family.h's uniform_pair).
Vec2<double> pair_at(std::uint64_t seed, std::uint64_t i);

// Holm–Šidák over a property's configurations at `level`: whether any is rejected, and the
// smallest adjusted p.
struct FamilyOutcome {
  bool any_rejected = false;
  double min_adjusted = 1;
  std::size_t rejections = 0;
  std::vector<bool> reject;  // per raw p-value, in input order
};
FamilyOutcome family_at(const std::vector<double>& raw_p, double level);

// for_chunks(n, f): f(begin, end, chunk) over fixed chunks of 4096 indices in parallel; results
// written per chunk and combined in chunk order by the caller (thread-count independent).
std::size_t chunk_count(std::uint64_t n);
void for_chunks(std::uint64_t n, const std::function<void(std::uint64_t, std::uint64_t,
                                                          std::size_t)>& f);

// Copies of an entry changed in one way (the controls and the tests' broken models); each changes
// the entry's rows functions (ModelEntry::eval_rows, ...) the same way as its per-row thunks.
ModelEntry with_pdf_scaled(const ModelEntry& m, double scale);
// with_pdf_scaled's pdf thunk: scale × the original's, and the entry it was made from where that
// is a registered one (whose SIMD batches then give the original density: sampler-matches-pdf's
// cubature takes the batch × scale).
struct ScaledPdf {
  std::function<double(const std::vector<double>&, const ModelQuery<double>&)> pdf;
  double scale = 1;
  const ModelEntry* registered = nullptr;
  double operator()(const std::vector<double>& v, const ModelQuery<double>& q) const {
    return scale * pdf(v, q);
  }
};
ModelEntry with_value_scaled(const ModelEntry& m, double scale);   // eval value and sample weight
ModelEntry with_weight_scaled(const ModelEntry& m, double scale);  // sample weight only
// The sampler never reaches a part of its primary sample space of measure `share` (the pairs u
// whose hash falls below it, spread over the whole square, so the missing part carries its share
// of the value wherever the sampler puts the value's mass): those samples get weight 0 (counted
// as rejected), while pdf and eval are unchanged.
ModelEntry with_sampler_restricted(const ModelEntry& m, double share);
// eval's value is NaN in about `rate` of calls (a hash of the query's directions).
ModelEntry with_sparse_nan(const ModelEntry& m, double rate);
// The sampler replaced by uniform sampling of the sphere (pdf 1/4π, weight value·4π): a sampler
// that covers every value, the corrected input where a model's own sampler misses part of it.
ModelEntry with_uniform_sampler(const ModelEntry& m);
// sample's pdf and weight recomputed from pdf() and eval() at the sampled ωo, eval's pdf from pdf().
ModelEntry with_consistent_sample(const ModelEntry& m);
// float thunks replaced by the double ones (the corrected input of float-vs-double).
ModelEntry with_float_as_double(const ModelEntry& m);
// NaN, Inf and negative outputs of eval and sample replaced by 0.
ModelEntry with_outputs_sanitized(const ModelEntry& m);
// eval at footprints wider than 1.5 × `base_side` repeated at max_parts² positions across it and
// averaged: a cost that grows with the footprint (max_parts² × at the large end).
ModelEntry with_cost_per_area(const ModelEntry& m, double base_side, int max_parts);
// eval with the footprint's Jacobian clamped to side `side` (constant cost, the corrected input).
ModelEntry with_footprint_clamped(const ModelEntry& m, double side);

// Per-property measure + decide (assess dispatches to these).
Assessment assess_eval_pdf(const ModelEntry& m, Budget b, const std::string& id, double level);
Assessment assess_sampler_gof(const ModelEntry& m, Budget b, const std::string& id, double level);
Assessment assess_covers_value(const ModelEntry& m, Budget b, const std::string& id,
                               double level, const std::vector<HemisphereIntegral>* reuse);
// The settings of sampler-covers-value, whose integrals energy shares (sampling.cpp).
std::vector<Setting> value_settings(const ModelEntry& m, Budget b);
// sampler-covers-value at the given settings (assess_covers_value: at the property's settings).
Assessment covers_value_at(const ModelEntry& m, const std::vector<Setting>& set, Budget b,
                           const std::string& id, double level,
                           const std::vector<HemisphereIntegral>* reuse);
Assessment assess_pdf_normalized(const ModelEntry& m, Budget b, const std::string& id,
                                 double level);
Assessment assess_energy(const ModelEntry& m, Budget b, const std::string& id, double level);
Assessment assess_float_double(const ModelEntry& m, Budget b, const std::string& id,
                               double level);
// batch_value_scale: the batch's value column × this before the comparison (the control's
// perturbation of the path under test; 1 for the model's own check).
Assessment assess_simd(const ModelEntry& m, Budget b, const std::string& id, double level,
                       double batch_value_scale);
Assessment assess_stability(const ModelEntry& m, Budget b, const std::string& id, double level);
Assessment assess_converges(const ModelEntry& m, Budget b, const std::string& id, double level);
Assessment assess_constant_time(const ModelEntry& m, Budget b, const std::string& id,
                                double level);

// The largest albedo energy's assessment measured (its value), for the control's scale.
inline constexpr double kControlOffset = 1.03;  // near-truth perturbations: 3 %

}  // namespace glintlab::verify::conformance

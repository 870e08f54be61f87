// Pearson chi-square goodness-of-fit tests for samplers of directions (sphere, hemisphere) and of
// points on the unit disk, with cubature-computed expected counts, two bin resolutions, honest
// quadrature error and a power report.
//
// Bins. Directions are binned in a frame whose pole is a caller-given lobe direction ℓ, as rings in
// θ' (the angle to ℓ) × equal sectors in φ' (the azimuth about ℓ):
//   * kEqualArea: rings of equal Δcosθ' and equal sectors, i.e. a regular grid in (cosθ', φ'), so
//     every bin has the same solid angle;
//   * kEqualProbability: ring edges at quantiles of the density's ring mass, found by cubature of
//     the density over thin rings (a uniform grid in θ' plus geometric refinement towards ℓ, each
//     ring refined until it holds < 1/16 of a target ring's mass) and linear inversion in cosθ';
//     equal sectors per ring (ring masses to a looser tolerance, rel 1e-5, since they only place
//     edges). A lobe of width 1e-3 around ℓ is spread over every ring. Where the
//     ring mass is zero at the start (around ℓ) or the end (away from ℓ), that range becomes one
//     extra zero-mass bin, which any sample landing there fails hard.
// Rings × sectors follow the aspect that makes bins near the widest ring roughly square:
// R = round(√(B/a)) rings of round(B/R) sectors, a = π (sphere), 2π (hemisphere), 4π (disk).
// Points on the disk (centre (½, ½), radius ½) use the same machinery in polar coordinates (r, φ):
// equal-area rings (equal Δr²) × equal sectors by default.
//
// Expected counts. E_b = N ∫_bin pdf, by nested adaptive Gauss–Kronrod (15-point) over the bin in
// (u, φ'), u = 1 − cosθ' (u = r² on the disk), where dω = du dφ'. The u range is split at geometric
// breakpoints towards the pole (θ' = θ_max·2^−k), where lobes around ℓ vary, at caller breakpoints,
// and, for a hemisphere binned in a tilted frame, at the horizon crossing. Each bin's integral stops
// when its error estimate is below max(rel_tol·E_b, abs_tol_counts) counts or its subdivision budget
// is spent. The estimate (outer |Kronrod − Gauss| plus the integrated inner estimates) is kept per
// bin.
//
// Quadrature error → inconclusive. With Δ_c the error estimate of a pooled cell's expectation E_c,
// the change of X² caused by the error is bounded to first order by
//   S = q + 2√q + Σ_c |Δ_c|/E_c,  q = Σ_c Δ_c²/E_c
// (q: the worst-case non-centrality the error adds; 2√q: the standard deviation of the cross term
// 2Σ(O − E)Δ/E under the null; Σ|Δ|/E: the rescaling of each term). When S exceeds
// inconclusive_shift (0.1) × √(2·dof), the null standard deviation of X², the error could move the
// statistic by more than a tenth of its noise and the resolution is inconclusive — it neither
// passes nor fails. A per-bin rule N·err ≤ c√E alone would not do: with B bins it allows q = c²B,
// which for B = 4096 and c = 0.1 is 41, half the null standard deviation √(2B) = 90.
//
// Pooling. Bins whose expectation is exactly 0 are never pooled: a sample there is a hard failure
// (p = 0) when the pdf is also 0 at the sample, and makes the test inconclusive when the pdf is
// positive there (the cubature missed mass). The other bins, in index order (ring by ring, sector by
// sector, then the "no sample" cell), are merged into consecutive groups, each closed once its
// expectation reaches min_expected (5); a last group below it joins the previous group.
//
// "No sample". A direction generator may return the zero vector (and a point generator a NaN
// coordinate) for "no sample", as samplers of defective densities do. These fall into one extra
// cell with expectation N·(1 − Σ∫pdf) when Σ∫pdf < 1; where Σ∫pdf is 1 or more within its
// cubature error (1 − Σ∫pdf ≤ 10·error + 1e-12) a "no sample" is a hard failure. The total
// expected mass Σ∫pdf is reported; where it exceeds 1 the counts are compared with the
// unnormalised expectations, so a pdf scaled by 1.02 is rejected.
//
// Limitation: the cubature only sees the pdf at its nodes. A feature narrower than the node spacing,
// away from the lobe axis (where the geometric breakpoints are) and from caller breakpoints, can
// be missed with a small error estimate. Where the pdf is otherwise 0 the samples expose it
// (inconclusive, above); over a positive background the test would reject. Centre the frame on such
// features (lobe) or pass radial_breaks / phi_breaks.
//
// Other hard failures: a malformed sample (non-finite, or a direction whose length is off 1 by more
// than 1e-5), a hemisphere direction with z < −1e-12, a disk point farther than ½(1 + 1e-12) from
// the centre.
//
// Resolutions and significance. A coarse resolution (coarse_bins ≈ 100: broad errors) and a fine one
// (N/fine_expected_per_bin bins, capped at fine_max_bins: localised errors) are tested on the same
// samples; the reported p-value is the Šidák-adjusted minimum 1 − (1 − min p)^k over the k
// resolutions (valid, conservative, for these positively dependent tests); every raw p is kept.
// dof = cells after pooling − 1.
//
// Power. Each resolution reports the non-centrality λ detected with probability `power` at its share
// of `level`, and the relative pdf error it corresponds to in the model λ = N·f·δ² (a relative error
// δ of the sampler's density against the claimed pdf over cells carrying probability f,
// compensation elsewhere neglected — for a pdf scaled by 1 + δ, f = 1, the true λ is N·δ²/(1 + δ);
// a compensated error has λ = N·f·δ²/(1 − f)): for f = 1 and for f = one average cell.
//
// Determinism. Samples are generated in fixed chunks of indices in parallel (TBB) into integer
// histograms; cubature is per bin, stored by index; all floating-point reductions run serially in
// bin order. Results are bit-identical for any thread count. The generator and the pdf are called
// concurrently and must be thread-safe; the generator must depend only on its index.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/math/vec.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab::verify {

// ---- Pearson's statistic with pooling -------------------------------------------------------

inline constexpr std::size_t kZeroExpectationBin = std::numeric_limits<std::size_t>::max();

struct Pooling {
  std::vector<std::size_t> group;  // cell of each bin; kZeroExpectationBin where E is exactly 0
  std::size_t cells = 0;
};

// The pooling rule described above: consecutive bins (in index order, zero-expectation bins
// skipped) merged until each cell's expectation reaches min_expected; a short last cell joins the
// previous one.
Pooling pool_bins(std::span<const double> expected, double min_expected = 5);

struct PearsonResult {
  double statistic = 0;   // X² = Σ_cells (O − E)² / E
  double dof = 0;         // cells − constraints
  double p_value = 1;     // P(χ²_dof ≥ X²); 0 on a hard failure; NaN when dof ≤ 0
  std::size_t cells = 0;  // after pooling
  bool hard_fail = false; // an observation in a bin whose expectation is exactly 0
  std::uint64_t observations_in_zero_bins = 0;
};

// Pearson's test of observed counts against expected counts (same length), pooled as above.
// `constraints` is subtracted from the number of cells for the degrees of freedom: 1 when the
// expectations are normalised to the total count (multinomial), plus one per fitted parameter.
PearsonResult pearson_chi_square(std::span<const std::int64_t> observed,
                                 std::span<const double> expected, double min_expected = 5,
                                 double constraints = 1);

// ---- Power ------------------------------------------------------------------------------------

// The non-centrality λ at which a χ² test with `dof` degrees of freedom at significance `level`
// rejects with probability `power`: P(χ'²_dof(λ) > χ²_{dof, 1−level}) = power.
double min_detectable_noncentrality(double dof, double level, double power = 0.9);

// The smallest relative density error δ detected with probability `power`, in the model
// λ = n·f·δ² (relative error δ over cells carrying probability f; see the header comment):
// δ = √(λ_min(dof, level, power) / (n·f)).
double min_detectable_relative_error(double n, double dof, double level, double mass_fraction,
                                     double power = 0.9);

// ---- Goodness of fit of samplers ---------------------------------------------------------------

using DirectionSampler = std::function<Vec3<double>(std::uint64_t index)>;
using DirectionPdf = std::function<double(const Vec3<double>&)>;  // per unit solid angle
// The same pdf at many directions in one call: out[i] = pdf(w[i]), to within its rounding (a SIMD
// batch of the pdf's kernel may differ from the scalar pdf by a few ULPs).
using DirectionPdfRows =
    std::function<void(std::span<const Vec3<double>> w, std::span<double> out)>;
using PointSampler = std::function<Vec2<double>(std::uint64_t index)>;
using PointPdf = std::function<double(const Vec2<double>&)>;      // per unit area

enum class SampleDomain { kSphere, kHemisphere, kDisk };
// kAuto: equal probability for directions, equal area for the disk.
enum class BinLayout { kAuto, kEqualArea, kEqualProbability };

struct ChiSquareOptions {
  BinLayout layout = BinLayout::kAuto;
  Vec3<double> lobe{0, 0, 1};           // taken to the pole of the bin frame (directions only)
  std::size_t coarse_bins = 100;
  double fine_expected_per_bin = 50;    // fine bins = N / this, capped; skipped if ≤ coarse_bins
  std::size_t fine_max_bins = 4096;
  double min_expected = 5;              // pooling threshold
  double rel_tol = 1e-7;                // per-bin cubature tolerance: max(rel_tol·E, abs_tol_counts)
  double abs_tol_counts = 1e-3;
  unsigned max_subdivisions = 200;      // bisections per 1D integration (inner and outer)
  std::vector<double> radial_breaks;    // extra cubature splits in θ' (rad) or r (disk)
  std::vector<double> phi_breaks;       // extra cubature splits in φ' ∈ (0, 2π), from frame_x
  // Directions where the pdf has a point feature (an integrable singularity, a kink): the cubature
  // is split through each in θ' and φ' of the bin frame, so the feature sits on a corner of the
  // integration pieces, and at geometrically closing breaks around it (half-widths 0.5·2^−k rad,
  // k = 1 … 12), so that pieces shrink towards it as polar coordinates about it would; adaptive
  // bisection then resolves a singularity there and a small excised region around it, whose rim
  // a single corner can miss (directions only).
  std::vector<Vec3<double>> point_features;
  double inconclusive_shift = 0.1;      // in units of the null standard deviation √(2·dof)
  double level = kFamilyWiseRate;       // significance level for the power report
  double power = 0.9;
  std::uint64_t chunk = 1 << 14;        // samples per parallel task (results do not depend on it)
  // Optional, directions only: the pdf over many directions per call (a SIMD batch of the pdf, or
  // a pdf whose every call costs far more than its arithmetic, such as a Python model's). The
  // planner's cubature always runs the inner integrals of each step of its outer rule in lockstep
  // and evaluates the nodes of all of their rules at once: through this where it is set (the plan
  // then moves by the rows' rounding only), else through the pdf one direction at a time. The run
  // (samples landing in zero-expectation bins) uses the pdf alone.
  DirectionPdfRows direction_pdf_rows;
};

// One resolution's bins: rings [t_i, t_{i+1}) in the radial coordinate t (θ' about the lobe, or r
// on the disk) × equal sectors in φ' ∈ [0, 2π); bin index offset[i] + sector.
struct BinGrid {
  std::vector<double> t_edges;       // t_edges.front() = 0, t_edges.back() = t_max
  std::vector<std::size_t> sectors;  // per ring
  std::vector<std::size_t> offset;   // per ring, plus the total at the end
  std::vector<double> expected;      // E_b = N ∫_bin pdf (counts)
  std::vector<double> error;         // quadrature error estimate of E_b (counts)
  double mass = 0;                   // Σ_b ∫_bin pdf
  double mass_error = 0;

  std::size_t rings() const { return sectors.size(); }
  std::size_t bins() const { return offset.empty() ? 0 : offset.back(); }
  // The bin holding radial coordinate t ∈ [0, t_max] and azimuth phi ∈ [0, 2π).
  std::size_t bin_of(double t, double phi) const;
};

// Bins and expected counts for one pdf and sample count, reusable across generators and seeds.
struct ChiSquarePlan {
  SampleDomain domain = SampleDomain::kSphere;
  std::uint64_t n = 0;
  ChiSquareOptions options;
  Vec3<double> frame_x{1, 0, 0}, frame_y{0, 1, 0}, frame_z{0, 0, 1};  // frame_z = lobe
  bool tilted_hemisphere = false;  // hemisphere binned over the whole sphere about a tilted lobe
  double t_max = 0;                // π, π/2 (hemisphere about +z) or ½ (disk)
  std::vector<BinGrid> grids;      // coarse first
  DirectionPdf direction_pdf;
  PointPdf point_pdf;
  bool inconclusive = false;       // the expectations could not be computed (non-finite, < 0, 0)
  std::string reason;

  // Frame coordinates of a direction: (t, φ) = (θ', φ') about the lobe.
  void to_bin_coordinates(const Vec3<double>& w, double& t, double& phi) const;
};

struct ChiSquareResolution {
  std::size_t bins = 0;    // bins in the layout
  std::size_t cells = 0;   // cells after pooling (with the "no sample" cell where present)
  double statistic = 0;
  double dof = 0;
  double p_value = 1;      // raw
  double mass = 0, mass_error = 0;
  double max_error_ratio = 0;  // max over cells of N·err / √E
  double error_shift = 0;      // the bound S on the change of X² from quadrature error
  bool inconclusive = false;
  std::string reason;
  double min_noncentrality = 0;    // λ detected at `power`, at this resolution's share of `level`
  double detectable_global = 0;    // δ for f = 1 (e.g. a pdf scaled by 1 + δ)
  double detectable_one_cell = 0;  // δ confined to one average cell (f = 1/cells)
};

struct ChiSquareResult {
  std::uint64_t n = 0;
  std::vector<ChiSquareResolution> resolutions;  // coarse first
  std::vector<double> raw_p_values;              // per resolution
  double p_value = 1;  // Šidák-combined minimum; 0 on a hard failure
  bool inconclusive = false;
  std::string reason;
  bool hard_fail = false;
  std::string hard_fail_reason;
  std::uint64_t first_bad_sample = 0;  // index of the first sample behind a hard failure
  std::uint64_t no_samples = 0;        // "no sample" results
  double mass = 0, mass_error = 0;     // Σ∫pdf from the coarse resolution
  double max_error_ratio = 0;          // over all resolutions

  // Hard failure, or a conclusive test with p < alpha.
  bool rejects(double alpha) const { return hard_fail || (!inconclusive && p_value < alpha); }
  std::string summary() const;  // one line for reports
};

ChiSquarePlan plan_direction_chi_square(SampleDomain domain, DirectionPdf pdf, std::uint64_t n,
                                        const ChiSquareOptions& options = {});
ChiSquarePlan plan_disk_chi_square(PointPdf pdf, std::uint64_t n,
                                   const ChiSquareOptions& options = {});
ChiSquareResult run_direction_chi_square(const ChiSquarePlan& plan, const DirectionSampler& sample);
ChiSquareResult run_disk_chi_square(const ChiSquarePlan& plan, const PointSampler& sample);
// The same with a batched sampler: sample(begin, count, out) writes samples begin .. begin +
// count − 1, each a function of its index only (the chunks it is asked for do not change them).
using DirectionBatchSampler =
    std::function<void(std::uint64_t begin, std::size_t count, Vec3<double>* out)>;
ChiSquareResult run_direction_chi_square(const ChiSquarePlan& plan,
                                         const DirectionBatchSampler& sample);

// Plan and run in one call.
ChiSquareResult chi_square_sphere(const DirectionSampler& sample, std::uint64_t n,
                                  const DirectionPdf& pdf, const ChiSquareOptions& options = {});
ChiSquareResult chi_square_hemisphere(const DirectionSampler& sample, std::uint64_t n,
                                      const DirectionPdf& pdf, const ChiSquareOptions& options = {});
ChiSquareResult chi_square_disk(const PointSampler& sample, std::uint64_t n, const PointPdf& pdf,
                                const ChiSquareOptions& options = {});

}  // namespace glintlab::verify

// `glintlab sample`: draws reflected directions from one of the samplers and writes them as CSV.
#include "core/samplers/sample.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

#include "cli/args.h"
#include "cli/batch_options.h"
#include "cli/commands.h"
#include "cli/input.h"
#include "cli/model_options.h"
#include "cli/out_csv.h"
#include "cli/sample_model.h"
#include "core/io/csv.h"
#include "core/math/rng.h"
#include "core/model_registry.h"
#include "core/models/smooth_ggx.h"
#include "core/samplers/sampler_list.h"

namespace glintlab::cli {
namespace {

// --sampler and --bound name the rows of the sampler list (core/samplers/sampler_list.h) as the
// smooth models' `sampler` and `bound` parameters do; the NDF picks among a choice's rows.
using AllChoices = samplers::Choices<samplers::All>;

constexpr std::uint64_t kMaxSamples = 1000000000;  // 1e9 rows is already ~200 GB of CSV

struct SampleArgs {
  std::string ndf, alpha, wi, sampler, n, seed = "0", bound = "listing1", out;
  bool bound_given = false;
  std::string threads = "0";
};

struct SampleJob {
  NdfKind ndf;
  double alpha_x, alpha_y;
  Vec3<double> wi;
  int sampler;  // the row of samplers::All
  std::uint64_t n, seed;
};

SampleJob validate(const SampleArgs& a) {
  SampleJob job{};
  job.ndf = parse_ndf(a.ndf, "--ndf");

  const std::vector<double> alpha = parse_number_list(
      a.alpha, "--alpha", "one value, or two comma-separated values alpha_x,alpha_y; finite, > 0");
  if (alpha.size() != 1 && alpha.size() != 2) {
    throw InputError(
        fmt::format("--alpha: '{}' has {} values (valid: one value, or two comma-separated values "
                    "alpha_x,alpha_y; finite, > 0)",
                    a.alpha, alpha.size()));
  }
  job.alpha_x = alpha[0];
  job.alpha_y = alpha.size() == 2 ? alpha[1] : alpha[0];
  // The range of the registered smooth model of this NDF: sample accepts what the model accepts.
  const ModelEntry& model = find_model(job.ndf == NdfKind::kGGX ? "smooth_ggx" : "smooth_beckmann");
  for (const auto& [value, name, param] :
       {std::tuple{job.alpha_x, alpha.size() == 2 ? "--alpha (alpha_x)" : "--alpha", "alpha_x"},
        std::tuple{job.alpha_y, "--alpha (alpha_y)", "alpha_y"}}) {
    check_alpha(value, name);
    for (const ParamSpec& p : model.params) {
      if (p.name != param) continue;
      if (!((p.lo_open ? value > p.lo : value >= p.lo) &&
            (p.hi_open ? value < p.hi : value <= p.hi)))
        throw InputError(fmt::format("{}: roughness {} is out of range (valid: {}, as model {})",
                                     name, value, describe_range(p), model.name));
    }
  }

  job.wi = parse_unit_direction(a.wi, "--wi");

  const std::string sampler = canonical_spelling("--sampler", a.sampler);
  const auto& names = AllChoices::kNames;
  // The choices some NDF lacks, e.g. spherical_caps and bounded_caps (ggx only).
  std::vector<std::string> partial;
  for (std::string_view c : names) {
    std::vector<std::string_view> ndfs;
    for (const SamplerInfo& r : AllChoices::kRows)
      if (r.choice == c && std::find(ndfs.begin(), ndfs.end(), r.ndf) == ndfs.end())
        ndfs.push_back(r.ndf);
    if (ndfs.size() == 1) partial.push_back(fmt::format("{} with --ndf {} only", c, ndfs[0]));
  }
  if (std::find(names.begin(), names.end(), sampler) == names.end()) {
    throw InputError(fmt::format("--sampler: unknown sampler '{}' (valid: {}; {})", sampler,
                                 fmt::join(names, ", "), fmt::join(partial, "; ")));
  }
  const std::string bound = canonical_spelling("--bound", a.bound);
  const auto& bounds = AllChoices::kBounds;
  if (std::find(bounds.begin(), bounds.end(), bound) == bounds.end()) {
    throw InputError(
        fmt::format("--bound: unknown bound '{}' (valid: {})", bound, fmt::join(bounds, ", ")));
  }
  // The row of this choice, NDF and bound; the choices this NDF has, for the message.
  const std::string_view ndf = ndf_name(job.ndf);
  std::vector<std::string_view> of_ndf;
  const SamplerInfo* row = nullptr;
  bool has_bounds = false;
  for (std::size_t i = 0; i < AllChoices::kRows.size(); ++i) {
    const SamplerInfo& r = AllChoices::kRows[i];
    if (r.ndf != ndf) continue;
    if (std::find(of_ndf.begin(), of_ndf.end(), r.choice) == of_ndf.end())
      of_ndf.push_back(r.choice);
    if (r.choice != sampler) continue;
    has_bounds = has_bounds || !r.bound.empty();
    if (row == nullptr && (r.bound.empty() || r.bound == bound)) {
      row = &r;
      job.sampler = int(i);
    }
  }
  if (row == nullptr) {
    std::vector<std::string_view> ndfs;  // the NDFs this choice samples
    for (const SamplerInfo& r : AllChoices::kRows)
      if (r.choice == sampler && std::find(ndfs.begin(), ndfs.end(), r.ndf) == ndfs.end())
        ndfs.push_back(r.ndf);
    throw InputError(
        fmt::format("--sampler: '{}' samples only --ndf {}, not --ndf {} (valid for --ndf {}: {})",
                    sampler, fmt::join(ndfs, ", "), ndf, ndf, fmt::join(of_ndf, ", ")));
  }
  if (!row->allows_backfacing && !(job.wi.z > 0.0)) {
    std::vector<std::string_view> backfacing;
    for (const SamplerInfo& r : AllChoices::kRows)
      if (r.allows_backfacing &&
          std::find(backfacing.begin(), backfacing.end(), r.choice) == backfacing.end())
        backfacing.push_back(r.choice);
    throw InputError(fmt::format(
        "--wi: wi.z = {} is not above the surface, which the {} sampler needs (valid: wi.z > 0; "
        "the {} samplers also accept wi.z <= 0)",
        job.wi.z, sampler, fmt::join(backfacing, " and ")));
  }
  if (a.bound_given && !has_bounds) {
    std::vector<std::string_view> bounded;  // the choices with several bounds
    for (const SamplerInfo& r : AllChoices::kRows)
      if (!r.bound.empty() && std::find(bounded.begin(), bounded.end(), r.choice) == bounded.end())
        bounded.push_back(r.choice);
    throw InputError(
        fmt::format("--bound: only applies to --sampler {}, not '{}' (valid: omit --bound)",
                    fmt::join(bounded, " or "), sampler));
  }

  job.n = parse_integer(a.n, "--n", 1, kMaxSamples);
  job.seed = parse_integer(a.seed, "--seed", 0, UINT64_MAX);
  return job;
}

// Draws sample i of the job. The uniforms depend only on (seed, i), never on evaluation order.
template <class Ndf>
MicrofacetSample<double> draw(const Ndf& ndf, const SampleJob& job, std::uint64_t i) {
  const Vec2<double> u{counter_uniform<double>(job.seed, i, 0),
                       counter_uniform<double>(job.seed, i, 1)};
  return samplers::with<samplers::All>(job.sampler, [&]<class S>() -> MicrofacetSample<double> {
    // validate() chose a row of this NDF.
    if constexpr (std::is_same_v<typename S::template Ndf<double>, Ndf>)
      return S::sample(ndf, job.wi, u);
    else
      return {};
  });
}

void run_sample(const SampleArgs& args) {
  const SampleJob job = validate(args);
  BatchOptions threads{};
  threads.threads = resolve_threads(args.threads);
  check_output_file(args.out, "--out");
  // About 20 bytes per number (17 significant digits, sign, exponent, comma), 8 per row.
  check_free_space(args.out, job.n * (8 * 20 + 2), "--out");
  // Blocks of rows drawn in parallel (each row depends only on (seed, i)), written in order.
  struct Row {
    MicrofacetSample<double> s;
    double weight;
  };
  constexpr std::uint64_t kBlock = std::uint64_t(1) << 18;
  std::vector<Row> block;
  write_out_csv(args.out,
                {"wo_x", "wo_y", "wo_z", "h_x", "h_y", "h_z", "pdf", "weight", "rejected"},
                [&](io::CsvWriter& w) {
                  with_ndf(job.ndf, job.alpha_x, job.alpha_y, [&](const auto& ndf) {
                    for (std::uint64_t b = 0; b < job.n; b += kBlock) {
                      const std::uint64_t count = std::min(kBlock, job.n - b);
                      block.resize(count);
                      for_each_chunk(count, threads, [&](std::size_t begin, std::size_t k) {
                        for (std::size_t i = begin; i < begin + k; ++i) {
                          const MicrofacetSample<double> s = draw(ndf, job, b + i);
                          block[i] = {s, s.rejected ? 0.0 : sample_weight(ndf, job.wi, s)};
                        }
                      });
                      for (const Row& r : block) {
                        const MicrofacetSample<double>& s = r.s;
                        w.cell(s.wo.x).cell(s.wo.y).cell(s.wo.z);
                        w.cell(s.m.x).cell(s.m.y).cell(s.m.z);
                        w.cell(s.pdf).cell(r.weight).cell_int(s.rejected ? 1 : 0);
                        w.end_row();
                      }
                    }
                  });
                });
}

constexpr const char* kSampleFooter =
    R"(SAMPLERS (--sampler, named as smooth_ggx's sampler parameter names them):
  ndf             Walter et al. 2007: h drawn from D(h) h.z, wo = reflect(wi, h); ggx and beckmann
  vndf            visible normals D_wi(h): Heitz 2018 for ggx, the Beckmann VNDF sampler for
                  beckmann
  spherical_caps  spherical caps VNDF sampling (Dupuy & Benyoub 2023); ggx only
  bounded_caps    bounded VNDF sampling (Eto & Tokuyoshi 2023), bound chosen by --bound; ggx only
ndf and vndf need wi above the surface (wi.z > 0); spherical_caps and bounded_caps also accept
wi.z <= 0. Old spellings still accepted, with a note on stderr: caps (spherical_caps), bounded
(bounded_caps), --bound exact-isotropic (exact_isotropic).
Directions are in the local shading frame: x tangent, y bitangent, z the macrosurface normal.

OUTPUT (--out): a CSV file with one row per sample i = 0 .. N-1, columns
  wo_x, wo_y, wo_z  the sampled reflected direction wo (unit vector)
  h_x, h_y, h_z     the sampled microfacet normal m (wo = reflect(wi, m))
  pdf               density of wo per steradian over the whole sphere: the sampler's standalone
                    pdf (pdf_walter, pdf_heitz_vndf, ...) evaluated at this wo
  weight            the Monte Carlo weight of the sample for the F = 1 microfacet BRDF,
                    sample_weight(ndf, wi, sample) = brdf * wo.z / pdf; 0 for a rejected sample
  rejected          1 if the sampler rejected the sample (wo below the surface, or m facing
                    away from wi: no opaque reflection), else 0; wo, m and pdf are still written
Doubles are printed with 17 significant digits. Sample i uses the uniforms
u = (counter_uniform(S, i, 0), counter_uniform(S, i, 1)) of the counter-based generator, so the
file depends only on the arguments: the same seed gives a byte-identical file.
Invalid arguments stop the run with a one-line error naming the option and its valid range;
no output file is written then.)";

}  // namespace

void add_sample_command(CLI::App& app) {
  CLI::App* cmd = add_command(
      app, "sample",
      "Draw N reflected directions from a microfacet sampler, with pdf and weight, as CSV");
  auto a = std::make_shared<SampleArgs>();
  add_text_option(cmd, "--ndf", a->ndf, "normal distribution: ggx or beckmann", "NAME");
  add_text_option(cmd, "--alpha", a->alpha,
                  "roughness 'ax,ay' (tangent, bitangent), or one value for isotropic; each in "
                  "[0.0001, 100], the range of the smooth_ggx and smooth_beckmann models",
                  "LIST");
  add_text_option(cmd, "--wi", a->wi,
                  "incident direction 'x,y,z' toward the viewer, unit length within 1e-6 (write "
                  "--wi=-0.6,0,0.8 when x is negative)",
                  "LIST");
  add_text_option(cmd, "--sampler", a->sampler,
                  "ndf, vndf, spherical_caps or bounded_caps (see below)", "NAME");
  add_text_option(cmd, "--bound", a->bound,
                  "bound of the bounded_caps sampler: listing1 (Eto & Tokuyoshi 2023 Listing 1) "
                  "or exact_isotropic; only with --sampler bounded_caps",
                  "NAME");
  add_text_option(cmd, "--n", a->n, "number of samples: an integer in [1, 1000000000]", "INT");
  add_text_option(cmd, "--seed", a->seed,
                  "seed of the counter-based generator: an integer in [0, "
                  "18446744073709551615]",
                  "INT");
  set_required(
      add_text_option(cmd, "--out", a->out,
                      "output CSV file; written to a temporary file and renamed into place only "
                      "when the run succeeded",
                      "FILE"));
  auto m = std::make_shared<ModelSampleArgs>();
  add_model_options(cmd, m->model, m->params,
                    "Sample this registered model's sampler instead (see glintlab models and "
                    "below); --param sets its parameters");
  add_batch_options(cmd, m->batch);
  set_footer(cmd, std::string(kSampleFooter) + kModelSampleFooter + kBatchOptionsFooter);
  add_text_option(cmd, "--query", m->query,
                  "with --model: the query columns the model needs besides wi, 'name=value,...' "
                  "(footprint u, v, dudx, dvdx, dudy, dvdy; light light_cos_half_angle, "
                  "light_intensity; corners r0_x..r3_z), as eval --model reads them",
                  "LIST");
  set_callback(cmd, [a, m, cmd] {
    register_staging_parent(std::filesystem::path(a->out).has_parent_path()
                                ? std::filesystem::path(a->out).parent_path()
                                : std::filesystem::path("."));
    if (option_count(cmd, "--model") > 0 && m->model.empty())
      throw InputError("--model: '' is empty (valid: a model of glintlab models)");
    if (!m->model.empty()) {
      for (const char* o : {"--ndf", "--alpha", "--sampler", "--bound"}) {
        if (option_count(cmd, o) > 0) {
          throw InputError(fmt::format(
              "{}: does not apply with --model (the model's --param sets it; see glintlab models)",
              o));
        }
      }
      for (const char* o : {"--wi", "--n"})
        if (option_count(cmd, o) == 0)
          throw InputError(fmt::format("{} is required (valid: see glintlab sample --help)", o));
      m->query_given = option_count(cmd, "--query") > 0;
      m->wi = a->wi;
      m->n = a->n;
      m->seed = a->seed;
      m->out = a->out;
      run_model_sample(*m);
      return;
    }
    if (!m->params.empty())
      throw InputError("--param: needs --model (valid: a model of glintlab models)");
    if (option_count(cmd, "--query") > 0)
      throw InputError("--query: needs --model (valid: a model of glintlab models)");
    if (batch_options_given(cmd)) {
      throw InputError(
          "--isa/--precision/--math: need --model (valid: a model of glintlab models)");
    }
    // Required without --model (CLI11 cannot express "required unless --model").
    for (const char* o : {"--ndf", "--alpha", "--wi", "--sampler", "--n"})
      if (option_count(cmd, o) == 0)
        throw InputError(fmt::format("{} is required (valid: see glintlab sample --help)", o));
    a->bound_given = option_count(cmd, "--bound") > 0;
    a->threads = m->batch.threads;
    run_sample(*a);
  });
}

}  // namespace glintlab::cli

// `glintlab ltc-fit [--out DIR] [--size N] [--threads N] [--samples N]`: regenerates the LTC tables
// (Heitz et al. 2016 Sec. 4 fit; Kneiphof & Klein 2024 NDF lobe and Eq. 19 D_PR), core/ltc_fit.h.
#include "core/ltc/ltc_fit.h"

#include <fmt/format.h>

#include <chrono>
#include <memory>
#include <mutex>
#include <string>

#include "cli/commands.h"
#include "cli/progress.h"

namespace glintlab::cli {
namespace {

struct LtcFitCliOptions {
  std::string out = "out/ltc";
  int size = kLtcTableSize;
  int threads = 0;
  int samples = 24;
};

void run(const LtcFitCliOptions& o) {
  if (o.size < 2 || o.size > kLtcMaxTableSize)
    throw InputError(fmt::format("--size: {} is out of range (valid: an integer in [2, {}])",
                                 o.size, kLtcMaxTableSize));
  if (o.threads < 0 || o.threads > 1024)
    throw InputError(
        fmt::format("--threads: {} is out of range (valid: an integer in [0, 1024], 0 = all cores)",
                    o.threads));
  if (o.samples < 4 || o.samples > 1024)
    throw InputError(
        fmt::format("--samples: {} is out of range (valid: an integer in [4, 1024])", o.samples));
  LtcFitOptions fit;
  fit.size = o.size;
  fit.threads = o.threads;
  fit.samples = o.samples;
  Progress bar("ltc-fit rows", 3L * o.size);
  std::mutex mutex;
  fit.progress = [&](int, int) {
    const std::lock_guard<std::mutex> lock(mutex);
    bar.step("");
  };
  const auto start = std::chrono::steady_clock::now();
  const LtcTables tables = fit_ltc_tables(fit);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_ltc_tables(o.out, tables,
                   fmt::format("Written by: glintlab ltc-fit --size {} --samples {} (identical for "
                               "any --threads).\nFit: Nelder-Mead on the MIS-weighted L3 error "
                               "(Heitz et al. 2016 Sec. 4), warm starts from the neighbouring "
                               "entry; cubature: see core/ltc/ltc_fit.h.",
                               o.size, o.samples));
  double max_b = 0, max_n = 0;
  for (std::size_t k = 0; k < tables.brdf_error.size(); ++k) {
    max_b = std::max(max_b, tables.brdf_error[k]);
    max_n = std::max(max_n, tables.ndf_error[k]);
  }
  fmt::print(
      "ltc-fit: wrote {0}/ggx_brdf.csv and {0}/ggx_ndf.csv ({1} x {1}, {2:.1f} s); max L1 "
      "error: BRDF lobe {3:.4f}, NDF lobe {4:.4f}\n",
      o.out, o.size, seconds, max_b, max_n);
}

}  // namespace

void add_ltc_fit_command(CLI::App& app) {
  auto o = std::make_shared<LtcFitCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "ltc-fit", "Fit the GGX LTC tables (BRDF lobe, albedo, Fresnel; NDF lobe, D_PR)");
  cmd->add_option("--out", o->out,
                  "Output folder (default out/ltc; core/ltc/tables holds the committed tables)");
  cmd->add_option("--size", o->size, "Table size N (N x N entries; default 64, valid 2 to 256)");
  cmd->add_option("--threads", o->threads,
                  "Worker threads (0 = all cores; the tables are the same)");
  cmd->add_option("--samples", o->samples,
                  "Per-axis samples of each sampler in the fit's error estimate (default 24)");
  cmd->footer(
      "Writes DIR/ggx_brdf.csv (sqrt_alpha, theta_o [rad], m00, m02, m20, m22, albedo, fresnel, "
      "l1_error) and DIR/ggx_ndf.csv (sqrt_alpha, theta_o, m00, m02, m20, m22, d_pr, l1_error), "
      "one row per entry ordered by sqrt_alpha then theta_o, each with a '#' header saying how it "
      "was made. M^-1 = [[m00,0,m02],[0,1,0],[m20,0,m22]] for a view in the xz-plane. To update "
      "the committed tables: glintlab ltc-fit --out core/ltc/tables, then rebuild.");
  cmd->callback([o] { run(*o); });
}

}  // namespace glintlab::cli

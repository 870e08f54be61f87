// `glintlab ltc-fit [--out DIR] [--size N] [--threads N] [--samples N]`: regenerates the LTC tables
// (Heitz et al. 2016 Sec. 4 fit; Kneiphof & Klein 2024 NDF lobe and Eq. 19 D_PR), core/ltc_fit.h.
#include "core/ltc/ltc_fit.h"

#include <fmt/format.h>

#include <chrono>
#include <memory>
#include <mutex>
#include <string>

#include "cli/commands.h"
#include "cli/input.h"
#include "cli/progress.h"

namespace glintlab::cli {
namespace {

struct LtcFitCliOptions {
  std::string out = "out/ltc";
  std::string size = std::to_string(kLtcTableSize);
  std::string threads;
  std::string samples = "24";
};

void run(const LtcFitCliOptions& o) {
  LtcFitOptions fit;
  fit.size = int(integer_option(o.size, "--size", 2, std::uint64_t(kLtcMaxTableSize)));
  // 0 = all cores is passed on: the fit sizes its own pool.
  fit.threads = int(integer_option(o.threads, "--threads", 0, 1024));
  fit.samples = int(integer_option(o.samples, "--samples", 4, 1024));
  // The fit takes minutes to tens of minutes: the folder is checked first.
  check_output_dir(o.out, "--out");
  register_staging_parent(o.out);
  Progress bar("ltc-fit rows", 3L * fit.size);
  std::mutex mutex;
  fit.progress = [&](int, int) {
    const std::lock_guard<std::mutex> lock(mutex);
    bar.step("");
  };
  const auto start = std::chrono::steady_clock::now();
  const LtcTables tables = fit_ltc_tables(fit);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  try {
    write_ltc_tables(
        o.out, tables,
        fmt::format("Written by: glintlab ltc-fit --size {} --samples {} (identical for "
                    "any --threads).\nFit: Nelder-Mead on the MIS-weighted L3 error "
                    "(Heitz et al. 2016 Sec. 4), warm starts from the neighbouring "
                    "entry; cubature: see core/ltc/ltc_fit.h.",
                    fit.size, fit.samples));
  } catch (const std::exception& e) {
    throw InputError(fmt::format("--out: cannot write the tables into '{}': {}", o.out, e.what()));
  }
  double max_b = 0, max_n = 0;
  for (std::size_t k = 0; k < tables.brdf_error.size(); ++k) {
    max_b = std::max(max_b, tables.brdf_error[k]);
    max_n = std::max(max_n, tables.ndf_error[k]);
  }
  fmt::print(
      "ltc-fit: wrote {0}/ggx_brdf.csv and {0}/ggx_ndf.csv ({1} x {1}, {2:.1f} s); max L1 "
      "error: BRDF lobe {3:.4f}, NDF lobe {4:.4f}\n",
      o.out, fit.size, seconds, max_b, max_n);
}

}  // namespace

void add_ltc_fit_command(CLI::App& app) {
  auto o = std::make_shared<LtcFitCliOptions>();
  CLI::App* cmd = add_command(
      app, "ltc-fit", "Fit the GGX LTC tables (BRDF lobe, albedo, Fresnel; NDF lobe, D_PR)");
  add_text_option(cmd, "--out", o->out,
                  "output folder (core/ltc/tables holds the committed tables)", "DIR");
  add_text_option(
      cmd, "--size", o->size,
      fmt::format("table size N (N x N entries): an integer in [2, {}]", kLtcMaxTableSize), "INT");
  add_threads_option(cmd, o->threads);
  add_text_option(cmd, "--samples", o->samples,
                  "per-axis samples of each sampler in the fit's error estimate: an integer in "
                  "[4, 1024]",
                  "INT");
  set_footer(
      cmd,
      "Writes DIR/ggx_brdf.csv (sqrt_alpha, theta_o [rad], m00, m02, m20, m22, albedo, fresnel, "
      "l1_error) and DIR/ggx_ndf.csv (sqrt_alpha, theta_o, m00, m02, m20, m22, d_pr, l1_error), "
      "one row per entry ordered by sqrt_alpha then theta_o, each with a '#' header saying how it "
      "was made. M^-1 = [[m00,0,m02],[0,1,0],[m20,0,m22]] for a view in the xz-plane. To update "
      "the committed tables: glintlab ltc-fit --out core/ltc/tables, then rebuild.");
  set_callback(cmd, [o] { run(*o); });
}

}  // namespace glintlab::cli

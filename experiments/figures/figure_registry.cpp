// The figure registry (one registration line per experiment) and the staged, atomic run.
#include "experiments/figures/figure_registry.h"

#include <fmt/format.h>
#include <unistd.h>

#include <system_error>

#include "experiments/figures/adequacy_maps.h"
#include "experiments/figures/adequacy_scene.h"
#include "experiments/figures/chermain2021.h"
#include "experiments/figures/eto2023.h"
#include "experiments/figures/models_hemisphere.h"
#include "experiments/figures/podee.h"
#include "experiments/figures/kneiphof2024.h"
#include "experiments/figures/kemppinen2025.h"
#include "experiments/figures/kemppinen2025_table3.h"

namespace glintlab::experiments {

const std::vector<FigureEntry>& registered_figures() {
  static const std::vector<FigureEntry> kFigures = {
      eto2023_fig4_entry(),
      eto2023_rmse_spp_entry(),
      models_hemisphere_entry(),
      podee_table1_entry(),
      podee_fig4_distance_entry(),
      podee_fig4_flicker_entry(),
      kneiphof2024_fig6_entry(),
      kneiphof2024_fig9_entry(),
      kneiphof2024_fig10_entry(),
      kneiphof2024_table1_entry(),
      chermain2021_fig3_entry(),
      chermain2021_fig7_entry(),
      chermain2021_fig8_entry(),
      chermain2021_fig9_entry(),
      chermain2021_fig10_entry(),
      kemppinen2025_fig2_3_entry(),
      kemppinen2025_fig6_entry(),
      kemppinen2025_fig10_entry(),
      kemppinen2025_fig14_entry(),
      kemppinen2025_fig15_entry(),
      kemppinen2025_table3_entry(),
      kemppinen2025_speed_accuracy_entry(),
      kemppinen2025_fig7_entry(),
      adequacy_maps_entry(),
      adequacy_scene_entry(),
  };
  return kFigures;
}

const FigureEntry& find_figure(std::string_view id) {
  std::string ids;
  for (const FigureEntry& e : registered_figures()) {
    if (e.id == id) return e;
    ids += fmt::format("{}{}", ids.empty() ? "" : ", ", e.id);
  }
  throw FigureError(
      fmt::format("figure: unknown figure id '{}' (valid: {}; see glintlab figure "
                  "--list)",
                  id, ids));
}

std::string_view glintlab_version() { return GLINTLAB_VERSION; }

std::filesystem::path run_figure(const FigureEntry& entry, const std::filesystem::path& out_dir,
                                 FigureContext context) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec || !fs::is_directory(out_dir)) {
    throw FigureError(fmt::format("--out: cannot create output folder '{}' ({})", out_dir.string(),
                                  ec ? ec.message() : "not a folder"));
  }
  const fs::path final_dir = out_dir / std::string(entry.id);
  const fs::path staging = out_dir / fmt::format(".{}.tmp.{}", entry.id, ::getpid());
  fs::remove_all(staging, ec);
  if (!fs::create_directory(staging, ec) || ec) {
    throw FigureError(fmt::format("--out: output folder '{}' is not writable ({})",
                                  out_dir.string(), ec ? ec.message() : "cannot create a folder"));
  }
  // Removes the staging folder on any failure.
  struct Cleanup {
    fs::path dir;
    bool armed = true;
    ~Cleanup() {
      std::error_code e;
      if (armed) fs::remove_all(dir, e);
    }
  } cleanup{staging};
  context.dir = staging;
  entry.run(context);
  if (context.finish) context.finish(staging);
  fs::remove_all(final_dir, ec);
  fs::rename(staging, final_dir, ec);
  if (ec) {
    throw FigureError(
        fmt::format("--out: cannot move results into '{}' ({})", final_dir.string(), ec.message()));
  }
  cleanup.armed = false;
  return final_dir;
}

}  // namespace glintlab::experiments

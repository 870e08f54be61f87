// NAME.panels.json beside a montage PNG (panel_layout.h).
#include "experiments/figures/panel_layout.h"

#include <nlohmann/json.hpp>

#include "core/io/atomic_file.h"

namespace glintlab::experiments {

void write_panel_layout(const std::filesystem::path& png, const PanelLayout& layout) {
  nlohmann::json j = {{"image", png.filename().string()},
                      {"title", layout.title},
                      {"columns", layout.columns},
                      {"gap", layout.gap},
                      {"labels", layout.labels}};
  std::filesystem::path sidecar = png;
  io::write_file_atomic(sidecar.replace_extension(".panels.json"), j.dump(1) + "\n");
}

}  // namespace glintlab::experiments

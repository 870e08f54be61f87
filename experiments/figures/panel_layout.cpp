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
  if (!layout.axes.x_label.empty()) {
    const PanelAxes& a = layout.axes;
    j["axes"] = {{"x_label", a.x_label},          {"y_label", a.y_label},
                 {"value_label", a.value_label},  {"x_range", {a.x_min, a.x_max}},
                 {"y_range", {a.y_min, a.y_max}}, {"exposure", a.exposure}};
  }
  std::filesystem::path sidecar = png;
  io::write_file_atomic(sidecar.replace_extension(".panels.json"), j.dump(1) + "\n");
}

}  // namespace glintlab::experiments

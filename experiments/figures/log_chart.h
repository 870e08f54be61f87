// The raster text of the adequacy-scene sheet, drawn with a built-in 5×7 pixel font (no font files
// needed). Every other chart is drawn by matplotlib from its chart spec (chart_spec.h; the adequacy
// maps: adequacy_outputs.h); this goes the same way next.
#pragma once

#include <string>

#include "core/math/vec.h"
#include "core/render/image.h"

namespace glintlab::experiments {

// `text` drawn into the first three channels of `image` in the charts' 5×7 pixel font (lower case
// as upper), its top-left corner at (x, y), 6 pixels per character; pixels outside are skipped.
void draw_text(Image& image, int x, int y, const std::string& text, Vec3<double> color);

}  // namespace glintlab::experiments

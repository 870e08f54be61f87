// The deliberately broken model of all.stability's negative control (NaN for αx < 0.01).
#include "verify/stability/nan_control.h"

#include <cmath>

namespace glintlab::verify::stability {

const ModelEntry& nan_control_model() {
  static const ModelEntry kEntry = [] {
    ModelEntry e = find_model("smooth_ggx");
    e.name = "nan_control_ggx";
    e.description = "smooth_ggx with value × √(αx − 0.01)/√(αx − 0.01): NaN for αx < 0.01";
    auto broken = [](auto inner) {
      return [inner](const std::vector<double>& v, const ModelQuery<double>& q) {
        ErasedEval r = inner(v, q);
        const double s = std::sqrt(v[0] - kNanControlAlpha);
        r.value *= s / s;
        return r;
      };
    };
    e.eval = broken(e.eval);
    if (e.eval_float) e.eval_float = broken(e.eval_float);
    return e;
  }();
  return kEntry;
}

}  // namespace glintlab::verify::stability

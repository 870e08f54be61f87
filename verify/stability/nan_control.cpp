// The deliberately broken (or corrected) models of the all.* stability checks' controls.
#include "verify/stability/nan_control.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "core/math/rng.h"
#include "verify/stability/cell_stats.h"

namespace glintlab::verify::stability {
namespace {

// A uniform number in [0, 1) from the query's two directions: the same query, the same number.
double query_hash(const ModelQuery<double>& q) {
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (double x : {q.wi.x, q.wi.y, q.wi.z, q.wo.x, q.wo.y, q.wo.z})
    h = mix64(h ^ std::bit_cast<std::uint64_t>(x));
  return double(h >> 11) * 0x1.0p-53;
}

template <class F>
ModelEntry wrap_eval(ModelEntry e, F&& change) {
  auto wrap = [change](auto inner) {
    return [inner, change](const std::vector<double>& v, const ModelQuery<double>& q) {
      ErasedEval r = inner(v, q);
      change(v, q, r);
      return r;
    };
  };
  e.eval = wrap(e.eval);
  e.eval_rows = {};  // the wrapped thunk is the only route
  if (e.eval_float) e.eval_float = wrap(e.eval_float);
  e.static_model = nullptr;  // batched as a scalar loop over the wrapped thunks
  return e;
}

}  // namespace

const ModelEntry& nan_control_model() {
  static const ModelEntry kEntry = [] {
    ModelEntry e =
        wrap_eval(find_model("smooth_ggx"),
                  [](const std::vector<double>& v, const ModelQuery<double>&, ErasedEval& r) {
                    const double s = std::sqrt(v[0] - kNanControlAlpha);
                    r.value *= s / s;
                  });
    e.name = "nan_control_ggx";
    e.description = "smooth_ggx with value × √(αx − 0.01)/√(αx − 0.01): NaN for αx < 0.01";
    return e;
  }();
  return kEntry;
}

const ModelEntry& sparse_nan_control_model() {
  static const ModelEntry kEntry = [] {
    ModelEntry e =
        wrap_eval(find_model("smooth_ggx"),
                  [](const std::vector<double>&, const ModelQuery<double>& q, ErasedEval& r) {
                    if (query_hash(q) < kSparseNanRate)
                      r.value = std::numeric_limits<double>::quiet_NaN();
                  });
    e.name = "sparse_nan_ggx";
    e.description = "smooth_ggx with a NaN value in about 0.05 % of eval calls";
    return e;
  }();
  return kEntry;
}

// `e` with every sample's weight multiplied by scale(u) (also the float instantiation's).
template <class F>
ModelEntry scale_sample_weight(ModelEntry e, F&& scale) {
  auto wrap = [scale](auto inner) {
    return
        [inner, scale](const std::vector<double>& v, const ModelQuery<double>& q, Vec2<double> u) {
          ModelSample<double> s = inner(v, q, u);
          s.weight *= scale(u);
          return s;
        };
  };
  e.sample = wrap(e.sample);
  e.sample_rows = {};  // the wrapped thunk is the only route
  if (e.sample_float) e.sample_float = wrap(e.sample_float);
  e.static_model = nullptr;
  return e;
}

const ModelEntry& gain_control_model() {
  static const ModelEntry kEntry = [] {
    ModelEntry e = wrap_eval(find_model("smooth_ggx"),
                             [](const std::vector<double>&, const ModelQuery<double>&,
                                ErasedEval& r) { r.value *= kGainControlScale; });
    e = scale_sample_weight(e, [](Vec2<double>) { return kGainControlScale; });
    e.name = "gain_control_ggx";
    e.description = "smooth_ggx with value and sample weight × 1.03: a 3 % energy gain";
    return e;
  }();
  return kEntry;
}

const ModelEntry& spike_control_model() {
  static const ModelEntry kEntry = [] {
    ModelEntry e = scale_sample_weight(find_model("smooth_ggx"), [](Vec2<double> u) {
      const double h = double(mix64(std::bit_cast<std::uint64_t>(u.x) ^
                                    mix64(std::bit_cast<std::uint64_t>(u.y))) >>
                              11) *
                       0x1.0p-53;
      // Mean kept: (1 − r)·a + r·kSpikeWeight = 1 with a the weight scale off the spikes.
      const double off = (1 - kSpikeRate * kSpikeWeight) / (1 - kSpikeRate);
      return h < kSpikeRate ? kSpikeWeight : off;
    });
    e.name = "spike_control_ggx";
    e.description = "smooth_ggx with sample weights × 300 in about 0.2 % of samples";
    return e;
  }();
  return kEntry;
}

ModelEntry probability_control_model(std::string_view base, double scale) {
  const ModelEntry& m = find_model(base);
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < m.intermediates.size(); ++i)
    if (is_probability_name(m.intermediates[i])) index.push_back(i);
  ModelEntry e = wrap_eval(
      m, [index, scale](const std::vector<double>&, const ModelQuery<double>&, ErasedEval& r) {
        for (std::size_t i : index)
          if (i < r.intermediates.size())
            r.intermediates[i] =
                scale > 0 ? scale * r.intermediates[i] : std::clamp(r.intermediates[i], 0.0, 1.0);
      });
  return e;
}

}  // namespace glintlab::verify::stability

// Error metrics; see metrics.h.
#include "core/render/metrics.h"

#include <cmath>
#include <stdexcept>

namespace glintlab {
namespace {

// Σ g(x − r, r) / K over the selected pixels and channels.
template <class G>
double mean_over(const Image& x, const Image& ref, const MetricOptions& o, G g) {
  if (x.width != ref.width || x.height != ref.height) {
    throw std::invalid_argument("metric: images differ in size");
  }
  if (o.mask && o.mask->size() != static_cast<std::size_t>(x.width) * x.height) {
    throw std::invalid_argument("metric: mask size differs from the image size");
  }
  std::vector<std::size_t> cx, cr;
  for (const std::string& c : o.channels) {
    cx.push_back(x.channel(c));
    cr.push_back(ref.channel(c));
  }
  double sum = 0.0;
  long count = 0;
  for (int y = 0; y < x.height; ++y) {
    for (int i = 0; i < x.width; ++i) {
      if (o.mask && !(*o.mask)[static_cast<std::size_t>(y) * x.width + i]) continue;
      for (std::size_t c = 0; c < cx.size(); ++c) {
        const double r = ref.at(i, y, cr[c]);
        sum += g(x.at(i, y, cx[c]) - r, r);
        ++count;
      }
    }
  }
  if (count == 0) throw std::invalid_argument("metric: no pixel selected");
  return sum / static_cast<double>(count);
}

}  // namespace

double rmse(const Image& x, const Image& ref, const MetricOptions& options) {
  return std::sqrt(mean_over(x, ref, options, [](double d, double) { return d * d; }));
}

double rel_mse(const Image& x, const Image& ref, const MetricOptions& options) {
  return mean_over(x, ref, options,
                   [](double d, double r) { return d * d / (r * r + kRelMseEpsilon); });
}

}  // namespace glintlab

// A float image with named channels (interleaved, row-major, row 0 at the top), stored in double
// so that metrics see the estimator's values before the EXR's float rounding.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace glintlab {

struct Image {
  int width = 0, height = 0;
  std::vector<std::string> channels;
  std::vector<double> data;

  Image() = default;
  Image(int w, int h, std::vector<std::string> names)
      : width(w),
        height(h),
        channels(std::move(names)),
        data(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * channels.size(), 0.0) {}

  std::size_t num_channels() const { return channels.size(); }
  std::size_t index(int x, int y, std::size_t c) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
            static_cast<std::size_t>(x)) *
               channels.size() +
           c;
  }
  double& at(int x, int y, std::size_t c) { return data[index(x, y, c)]; }
  double at(int x, int y, std::size_t c) const { return data[index(x, y, c)]; }
  // Index of a channel; throws std::out_of_range naming it if absent.
  std::size_t channel(const std::string& name) const {
    for (std::size_t i = 0; i < channels.size(); ++i) {
      if (channels[i] == name) return i;
    }
    throw std::out_of_range("image has no channel '" + name + "'");
  }
};

}  // namespace glintlab

// The tables of the exact binomial kernel (core/glints/binomial_kernel.h): log k! and the lane
// permutations of its packed draw.
#include "core/glints/binomial_kernel.h"

namespace glintlab::detail {

const std::array<double, 16> kLogFactorialTable = [] {
  std::array<double, 16> t{};
  for (std::size_t k = 0; k < t.size(); ++k) t[k] = std::lgamma(double(k) + 1);
  return t;
}();

const LanePermutations kLanePermutations = [] {
  LanePermutations t;
  for (std::size_t m = 0; m < 256; ++m) {
    std::size_t at = 0;
    for (int set = 1; set >= 0; --set)
      for (std::size_t l = 0; l < 8; ++l)
        if (int((m >> l) & 1u) == set) {
          t.pack[m][at] = std::uint8_t(l);
          t.unpack[m][l] = std::uint8_t(at);
          ++at;
        }
  }
  return t;
}();

}  // namespace glintlab::detail

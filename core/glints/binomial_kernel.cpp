// The log-factorial table of the exact binomial kernel (core/glints/binomial_kernel.h).
#include "core/glints/binomial_kernel.h"

namespace glintlab::detail {

const std::array<double, 16> kLogFactorialTable = [] {
  std::array<double, 16> t{};
  for (std::size_t k = 0; k < t.size(); ++k) t[k] = std::lgamma(double(k) + 1);
  return t;
}();

}  // namespace glintlab::detail

// The shared random input set of the SIMD tests (one column per kernels.h Domain, 10^6 rows).
#include "tests/simd/simd_test_util.h"

#include "core/math/rng.h"
#include "core/simd/inputs.h"

namespace glintlab::simd::test {

const std::vector<std::vector<double>>& shared_inputs_double() {
  static const std::vector<std::vector<double>> cols = [] {
    std::vector<int> all(kDomainCount);
    for (int d = 0; d < kDomainCount; ++d) all[d] = d;
    return make_inputs(all, kRows, hash_string("tests/simd/equivalence"));
  }();
  return cols;
}

const std::vector<std::vector<float>>& shared_inputs_float() {
  static const std::vector<std::vector<float>> cols = [] {
    const auto& d = shared_inputs_double();
    std::vector<std::vector<float>> f(d.size());
    for (std::size_t j = 0; j < d.size(); ++j) f[j].assign(d[j].begin(), d[j].end());
    return f;
  }();
  return cols;
}

}  // namespace glintlab::simd::test

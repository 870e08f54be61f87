// Distribution error of the binomial approximations of core/glints/binomial.h against the exact
// Binomial(n, p) over an (n, p) grid, computed from their exact distributions (no sampling):
// Kolmogorov–Smirnov distance, total variation (discrete samplers) and relative mean error, as CSV.
// Usage: glintlab_binomial_error OUT.csv (experiments/data/binomial_error.csv is its output).
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "core/glints/binomial_distribution.h"
#include "core/io/atomic_file.h"

int main(int argc, char** argv) {
  using namespace glintlab;
  if (argc != 2) {
    std::fprintf(stderr, "glintlab: error: usage: glintlab_binomial_error OUT.csv\n");
    return 2;
  }
  std::string csv = "n,p,np,sampler,ks_distance,total_variation,mean_relative_error\n";
  const double ps[] = {1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.05, 0.1, 0.3, 0.5};
  for (int e = 0; e <= 20; e += 2) {
    const std::uint64_t n = std::uint64_t(1) << e;
    for (double p : ps) {
      const BinomialError rt = realtime_error(n, p);
      const BinomialError sc = small_count_error(n, p);
      csv += fmt::format("{},{},{:.6g},realtime,{:.6e},nan,{:.6e}\n", n, p, double(n) * p, rt.ks,
                         rt.mean_rel);
      csv += fmt::format("{},{},{:.6g},small_count,{:.6e},{:.6e},{:.6e}\n", n, p, double(n) * p,
                         sc.ks, sc.tv, sc.mean_rel);
    }
  }
  try {
    io::write_file_atomic(argv[1], csv);
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "glintlab: error: %s\n", ex.what());
    return 2;
  }
  return 0;
}

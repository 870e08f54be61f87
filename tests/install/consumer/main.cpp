// Uses the installed glintlab core: GGX D at the normal must be 1/(π α²).
#include <cmath>
#include <cstdio>

#include "core/io/atomic_file.h"
#include "core/ndf/ggx.h"

int main() {
  const glintlab::GGX<double> ggx{0.5, 0.5};
  const double d = ggx.D({0.0, 0.0, 1.0});
  const double expected = 1.0 / (3.14159265358979323846 * 0.25);
  std::printf("consumer: D(n) = %.17g\n", d);
  return std::abs(d - expected) < 1e-12 ? 0 : 1;
}

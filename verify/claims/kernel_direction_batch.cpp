#include "verify/claims/kernel_direction_batch.h"

#include <vector>

#include "core/simd/batch.h"

namespace glintlab::verify {

SeededDirectionBatch kernel_direction_batch(int kernel, Vec3<double> wi, double ax, double ay,
                                            bool upper_only) {
  const simd::Isa isa = simd::default_isa();
  return [kernel, isa, wi, ax, ay, upper_only](std::uint64_t seed, std::uint64_t begin,
                                                std::size_t count, Vec3<double>* out) {
    std::vector<double> u1(count), u2(count), o(8 * count);
    for (std::size_t i = 0; i < count; ++i) {
      const Vec2<double> u = uniform_pair(seed, begin + i);
      u1[i] = u.x;
      u2[i] = u.y;
    }
    const double w[3] = {wi.x, wi.y, wi.z};
    double* p = o.data();
    simd::sample_batch<double>(kernel, ax, ay, w, u1.data(), u2.data(),
                               {p, p + count, p + 2 * count, p + 3 * count, p + 4 * count,
                                p + 5 * count, p + 6 * count, p + 7 * count},
                               count, isa);
    for (std::size_t i = 0; i < count; ++i) {
      const Vec3<double> wo{p[i], p[count + i], p[2 * count + i]};
      out[i] = upper_only && !(wo.z > 0) ? Vec3<double>{0, 0, 0} : wo;
    }
  };
}

namespace {

// The directions as three columns (x, then y, then z), the layout the batch kernels read.
std::vector<double> direction_columns(std::span<const Vec3<double>> w) {
  const std::size_t n = w.size();
  std::vector<double> wo(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    wo[i] = w[i].x;
    wo[n + i] = w[i].y;
    wo[2 * n + i] = w[i].z;
  }
  return wo;
}

}  // namespace

DirectionPdfRows kernel_direction_pdf_rows(int kernel, Vec3<double> wi, double ax, double ay,
                                           bool upper_only) {
  const simd::Isa isa = simd::default_isa();
  return [kernel, isa, wi, ax, ay, upper_only](std::span<const Vec3<double>> w,
                                               std::span<double> out) {
    const std::size_t n = w.size();
    const std::vector<double> wo = direction_columns(w);
    const double params[5] = {ax, ay, wi.x, wi.y, wi.z};
    const double* columns[3] = {wo.data(), wo.data() + n, wo.data() + 2 * n};
    double* outputs[1] = {out.data()};
    simd::eval_batch<double>(kernel, params, columns, outputs, n, isa);
    if (upper_only)
      for (std::size_t i = 0; i < n; ++i)
        if (!(w[i].z > 0)) out[i] = 0.0;
  };
}

DirectionPdfRows kernel_swapped_pdf_rows(int kernel, Vec3<double> wi, double ax, double ay) {
  const simd::Isa isa = simd::default_isa();
  return [kernel, isa, wi, ax, ay](std::span<const Vec3<double>> w, std::span<double> out) {
    const std::size_t n = w.size();
    const std::vector<double> wo = direction_columns(w);
    const simd::Column<double> inputs[8] = {{&ax, 0},          {&ay, 0},
                                            {wo.data(), 1},    {wo.data() + n, 1},
                                            {wo.data() + 2 * n, 1}, {&wi.x, 0},
                                            {&wi.y, 0},        {&wi.z, 0}};
    double* outputs[1] = {out.data()};
    simd::eval_batch(kernel, inputs, outputs, n, isa);
  };
}

}  // namespace glintlab::verify

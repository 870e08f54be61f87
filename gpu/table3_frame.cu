// The Table 3 frames on the device (gpu/table3_frame.h).
#include <cuda_runtime.h>

#include <algorithm>
#include <string>
#include <vector>

#include "experiments/bench/kemppinen2025_table3_scene.h"
#include "gpu/device_models.h"
#include "gpu/table3_frame.h"

namespace glintlab::gpu {
namespace {

namespace t3 = kemppinen_table3;

void check(cudaError_t status, const char* call) {
  if (status != cudaSuccess)
    throw DeviceError(std::string(call) + ": " + cudaGetErrorName(status) + ": " +
                      cudaGetErrorString(status));
}

// One thread per pixel: the CPU benchmark's shade_pixel with the glint model or, for `smooth`,
// the base NDF (a uniform choice: every thread takes the same branch).
template <class Params>
__global__ void frame_kernel(t3::Scene scene, Params p, bool smooth, double* out) {
  const std::uint64_t pixel = std::uint64_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (pixel >= t3::kPixels) return;
  if (smooth) {
    out[pixel] = t3::shade_pixel(scene, pixel, [&](const ModelQuery<double>& q) {
      return detail::smooth_eval(p.ndf, q, 0.0).value;
    });
  } else {
    out[pixel] = t3::shade_pixel(scene, pixel, [&](const ModelQuery<double>& q) {
      return detail::kemppinen_model_eval(p, q, 0.0).value;
    });
  }
}

template <class Params>
Table3FrameRun run_cell(const t3::Cell& c, const Params& p, double* frame, int repetitions,
                        std::size_t sampled) {
  const t3::Scene scene = t3::scene(c.plane_deg);
  constexpr unsigned kThreads = 128;
  const unsigned blocks = static_cast<unsigned>((t3::kPixels + kThreads - 1) / kThreads);
  const auto launch = [&] { frame_kernel<<<blocks, kThreads>>>(scene, p, c.smooth, frame); };
  Table3FrameRun run;
  run.cell = t3::cell_name(c);
  launch();
  check(cudaGetLastError(), "frame_kernel");
  check(cudaDeviceSynchronize(), "cudaDeviceSynchronize");
  cudaEvent_t start{}, stop{};
  check(cudaEventCreate(&start), "cudaEventCreate");
  check(cudaEventCreate(&stop), "cudaEventCreate");
  std::vector<float> ms(static_cast<std::size_t>(std::max(repetitions, 1)));
  for (float& t : ms) {
    check(cudaEventRecord(start), "cudaEventRecord");
    launch();
    check(cudaEventRecord(stop), "cudaEventRecord");
    check(cudaEventSynchronize(stop), "cudaEventSynchronize");
    check(cudaGetLastError(), "frame_kernel");
    check(cudaEventElapsedTime(&t, start, stop), "cudaEventElapsedTime");
  }
  cudaEventDestroy(start);
  cudaEventDestroy(stop);
  std::sort(ms.begin(), ms.end());
  run.timing = {static_cast<int>(ms.size()), ms[ms.size() / 2], ms.front(),
                double(t3::kPixels) / (ms[ms.size() / 2] * 1e-3)};
  std::vector<double> host(t3::kPixels);
  check(cudaMemcpy(host.data(), frame, t3::kPixels * sizeof(double), cudaMemcpyDeviceToHost),
        "cudaMemcpy");
  for (std::uint64_t n = 0; n < sampled; ++n) {
    run.pixels.push_back(t3::pixel_of(n));
    run.radiance.push_back(host[t3::pixel_of(n)]);
  }
  return run;
}

}  // namespace

std::vector<Table3FrameRun> run_table3_frames(int repetitions, std::size_t sampled_pixels) {
  sampled_pixels = std::min<std::size_t>(sampled_pixels, t3::kPixels);
  double* frame = nullptr;
  check(cudaMalloc(reinterpret_cast<void**>(&frame), t3::kPixels * sizeof(double)), "cudaMalloc");
  std::vector<Table3FrameRun> runs;
  try {
    for (const t3::Cell& c : t3::cells()) {
      const std::vector<double> v = t3::model_values(c.high ? t3::kHighAlpha : t3::kLowAlpha);
      if (c.ggx)
        runs.push_back(run_cell(c, detail::kemppinen_model_params<GGX<double>, double>(v), frame,
                                repetitions, sampled_pixels));
      else
        runs.push_back(run_cell(c, detail::kemppinen_model_params<Beckmann<double>, double>(v),
                                frame, repetitions, sampled_pixels));
    }
  } catch (...) {
    cudaFree(frame);
    throw;
  }
  cudaFree(frame);
  return runs;
}

}  // namespace glintlab::gpu

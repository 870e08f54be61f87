// Which built-in models have device (CUDA) kernels, and why the others have none. The CUDA build
// (gpu/device_models.cu) instantiates the listed models' own eval, pdf and sample templates from
// their core headers; nothing of a kernel is written again for the GPU. No CUDA in this header: the
// CPU side (the result comparison, the tests, docs/gpu.md) reads it too.
#pragma once

#include <array>
#include <string_view>

namespace glintlab::gpu {

struct DeviceSupport {
  std::string_view model;    // a built-in model's name (core/model_list.h)
  std::string_view why_not;  // empty: the model has device kernels; else why not (docs/gpu.md)
};

// Every built-in model, in registration order (a test checks it against core/model_list.h).
inline constexpr std::array<DeviceSupport, 9> kDeviceSupport = {{
    {"smooth_ggx", ""},
    {"smooth_beckmann", ""},
    {"podee", ""},
    {"deliot_belcour", ""},
    {"kneiphof_klein", ""},
    {"kneiphof_klein_area",
     "kBatched = false: its LTC table (core/ltc/ltc_table.h) is a host table read by a scalar "
     "double lookup; the device would need a copy of the table"},
    {"chermain",
     "its multiscale dictionary is a host table built at first use (chermain2021::Dictionary): "
     "a device copy of the table would be needed"},
    {"kemppinen_ggx", ""},
    {"kemppinen_beckmann", ""},
}};

constexpr bool has_device_kernels(std::string_view model) {
  for (const DeviceSupport& s : kDeviceSupport)
    if (s.model == model) return s.why_not.empty();
  return false;
}

}  // namespace glintlab::gpu

// The timing of one kernel over a query set on the device (CUDA events).
#pragma once

namespace glintlab::gpu {

struct DeviceTiming {
  int repetitions = 0;   // timed launches, after one untimed warm-up launch
  double median_ms = 0;  // one launch over every row
  double min_ms = 0;
  double items_per_second = 0;  // rows / median
};

}  // namespace glintlab::gpu

// Memory for the result arrays that eval and sample return, from a pool that keeps freed large
// blocks mapped, so that a call after the previous results were dropped writes into pages that are
// already there instead of faulting in fresh ones (glibc maps an 8 MB array fresh from the kernel
// and unmaps it when freed: nine result arrays of 10^6 rows cost about 10 ms of page faults per
// call, about as much as evaluating smooth_ggx on them).
//
// The arrays are ordinary numpy arrays that own their memory: they are made while numpy's data
// memory handler (NEP 49, PyDataMem_SetHandler) is this pool's, so numpy itself gives the memory
// back to the pool when the array (and every view of it) is deallocated, whatever the user did
// with it (kept, written, sliced, pickled, resized). A block of at least kPoolMinBytes comes from
// the pool's idle blocks (the smallest one that fits, at most a quarter larger than asked) or is
// mapped fresh, with an unused page on either side (so that no two blocks lie end to end, which
// numpy's loops would take for an overlap of an input and an output: another path, other last
// bits); a smaller one is malloc's. A freed block is kept idle while the idle blocks
// together stay within the limit (default kDefaultIdleLimit; the oldest idle blocks are unmapped
// to make room), else unmapped. Thread-safe (numpy may free without the GIL).
#pragma once

#include <pybind11/pybind11.h>

#include <cstddef>
#include <cstdint>
#include <memory>

namespace glintlab::python {

// Blocks below this come from malloc (glibc's default threshold for mapping a block itself).
inline constexpr std::size_t kPoolMinBytes = std::size_t(128) << 10;
// The default bound on the idle blocks' bytes.
inline constexpr std::size_t kDefaultIdleLimit = std::size_t(256) << 20;

struct ResultPoolStats {
  std::size_t idle_bytes = 0, idle_blocks = 0;  // kept mapped for reuse
  std::size_t live_bytes = 0, live_blocks = 0;  // held by arrays now
  std::uint64_t reused = 0;    // blocks handed out again from the idle ones
  std::uint64_t mapped = 0;    // blocks mapped fresh
  std::uint64_t unmapped = 0;  // blocks given back to the system
  std::size_t idle_limit = kDefaultIdleLimit;
};

// Loads numpy's C API for the pool (once, with the GIL; from the module's init).
void init_result_pool();

// While one lives (on a thread holding the GIL), the numpy arrays this thread makes take their
// memory from the pool.
class PooledArrays {
 public:
  PooledArrays();
  ~PooledArrays();
  PooledArrays(const PooledArrays&) = delete;
  PooledArrays& operator=(const PooledArrays&) = delete;

 private:
  PyObject* previous_ = nullptr;
};

// A block of at least `bytes` from the pool (malloc's below kPoolMinBytes), given back when the
// last copy of the pointer goes: memory that is not an array's (a numpy model's chunk storage,
// which its functions' views share). Any thread, with or without the GIL.
std::shared_ptr<void> pooled_block(std::size_t bytes);

ResultPoolStats result_pool_stats();
// Sets the bound on the idle blocks' bytes (0: every freed block is unmapped), unmapping the
// oldest idle blocks beyond it.
void set_result_pool_limit(std::size_t bytes);

}  // namespace glintlab::python

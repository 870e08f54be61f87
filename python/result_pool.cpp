// The result arrays' memory pool; see result_pool.h.
// numpy's C API in this file only (its own API table, imported by init_result_pool).
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#include "python/result_pool.h"

#include <numpy/arrayobject.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <new>
#include <unordered_map>
#include <vector>

#if NPY_API_VERSION < 0x00000010
#error "numpy 1.22 or later is needed (its data memory handlers, NEP 49)"
#endif

namespace glintlab::python {
namespace {

struct Block {
  void* data;
  std::size_t bytes;
};

class Pool {
 public:
  // A block of at least `bytes` (>= kPoolMinBytes); `fresh`: mapped now (its pages are zero).
  void* take(std::size_t bytes, bool& fresh) {
    const std::size_t want = round_up(bytes);
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      // The smallest idle block that fits, at most a quarter larger; of equal ones the one freed
      // last (its lines the likeliest to be still cached).
      std::size_t best = idle_.size();
      for (std::size_t k = 0; k < idle_.size(); ++k)
        if (idle_[k].bytes >= want && idle_[k].bytes - want <= want / 4 &&
            (best == idle_.size() || idle_[k].bytes <= idle_[best].bytes))
          best = k;
      if (best != idle_.size()) {
        const Block b = idle_[best];
        idle_.erase(idle_.begin() + std::ptrdiff_t(best));
        stats_.idle_bytes -= b.bytes;
        --stats_.idle_blocks;
        ++stats_.reused;
        live(b);
        fresh = false;
        return b.data;
      }
    }
    // With a page on either side that no block uses (never touched, so never backed by memory):
    // two blocks the system maps next to each other would otherwise lie end to end, and numpy's
    // loops treat an input and an output that do as overlapping and take another path, whose
    // results differ in their last bits (log1p of float64 in numpy 1.24), so that a numpy model's
    // results would depend on where its temporaries were mapped.
    void* m = mmap(nullptr, want + 2 * page(), PROT_READ | PROT_WRITE,
                   MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (m == MAP_FAILED) return nullptr;
    void* p = static_cast<char*>(m) + page();
    const std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.mapped;
    live({p, want});
    fresh = true;
    return p;
  }

  // Whether p is a block of the pool's (then it is taken back: kept idle or unmapped).
  bool give_back(void* p) {
    std::vector<Block> unmap;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      const auto it = live_.find(p);
      if (it == live_.end()) return false;
      const Block b{p, it->second};
      live_.erase(it);
      stats_.live_bytes -= b.bytes;
      --stats_.live_blocks;
      if (b.bytes > stats_.idle_limit) {
        unmap.push_back(b);
      } else {
        idle_.push_back(b);
        stats_.idle_bytes += b.bytes;
        ++stats_.idle_blocks;
        evict(unmap);
      }
    }
    release(unmap);
    return true;
  }

  // The bytes of a live block p, or 0 when p is not one.
  std::size_t size_of(void* p) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = live_.find(p);
    return it == live_.end() ? 0 : it->second;
  }

  void set_limit(std::size_t bytes) {
    std::vector<Block> unmap;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stats_.idle_limit = bytes;
      evict(unmap);
    }
    release(unmap);
  }

  ResultPoolStats stats() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return stats_;
  }

 private:
  static std::size_t page() {
    static const std::size_t bytes = std::size_t(sysconf(_SC_PAGESIZE));
    return bytes;
  }
  static std::size_t round_up(std::size_t bytes) { return (bytes + page() - 1) / page() * page(); }
  void live(const Block& b) {
    live_.emplace(b.data, b.bytes);
    stats_.live_bytes += b.bytes;
    ++stats_.live_blocks;
  }
  // The oldest idle blocks beyond the limit into `unmap` (locked).
  void evict(std::vector<Block>& unmap) {
    std::size_t drop = 0;
    while (drop < idle_.size() && stats_.idle_bytes > stats_.idle_limit) {
      unmap.push_back(idle_[drop]);
      stats_.idle_bytes -= idle_[drop].bytes;
      --stats_.idle_blocks;
      ++drop;
    }
    idle_.erase(idle_.begin(), idle_.begin() + std::ptrdiff_t(drop));
  }
  void release(const std::vector<Block>& unmap) {
    for (const Block& b : unmap) munmap(static_cast<char*>(b.data) - page(), b.bytes + 2 * page());
    if (unmap.empty()) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    stats_.unmapped += unmap.size();
  }

  std::mutex mutex_;
  std::vector<Block> idle_;  // oldest first
  std::unordered_map<void*, std::size_t> live_;
  ResultPoolStats stats_;
};

// Never destroyed: arrays may be freed at any time up to the process's exit.
Pool& pool() {
  static Pool* const p = new Pool;
  return *p;
}

// numpy's data memory handler over the pool (ctx unused).
void* pool_malloc(void*, std::size_t size) {
  if (size < kPoolMinBytes) return std::malloc(size);
  bool fresh = false;
  return pool().take(size, fresh);
}
void* pool_calloc(void*, std::size_t count, std::size_t size) {
  if (size != 0 && count > SIZE_MAX / size) return nullptr;
  const std::size_t bytes = count * size;
  if (bytes < kPoolMinBytes) return std::calloc(count, size);
  bool fresh = false;
  void* p = pool().take(bytes, fresh);
  if (p != nullptr && !fresh) std::memset(p, 0, bytes);
  return p;
}
void pool_free(void*, void* p, std::size_t) {
  if (p != nullptr && !pool().give_back(p)) std::free(p);
}
void* pool_realloc(void* ctx, void* p, std::size_t size) {
  const std::size_t old = p == nullptr ? 0 : pool().size_of(p);
  if (old == 0) return std::realloc(p, size);  // malloc's (or null)
  void* q = pool_malloc(ctx, size);
  if (q == nullptr) return nullptr;
  std::memcpy(q, p, std::min(old, size));
  pool_free(ctx, p, old);
  return q;
}

PyDataMem_Handler pool_handler = {
    "glintlab_result_pool", 1, {nullptr, pool_malloc, pool_calloc, pool_realloc, pool_free}};

// The handler as numpy takes it: a capsule named "mem_handler" (never freed).
PyObject* handler_capsule() {
  static PyObject* const capsule = PyCapsule_New(&pool_handler, "mem_handler", nullptr);
  return capsule;
}

}  // namespace

void init_result_pool() {
  if (_import_array() < 0) throw pybind11::error_already_set();
  if (handler_capsule() == nullptr) throw pybind11::error_already_set();
}

PooledArrays::PooledArrays() {
  previous_ = PyDataMem_SetHandler(handler_capsule());
  if (previous_ == nullptr) throw pybind11::error_already_set();
}

PooledArrays::~PooledArrays() {
  // Also while an error is pending (kept as it is).
  PyObject *type = nullptr, *value = nullptr, *traceback = nullptr;
  PyErr_Fetch(&type, &value, &traceback);
  PyObject* ours = PyDataMem_SetHandler(previous_);
  if (ours == nullptr) PyErr_Clear();  // nothing to do about it in a destructor
  Py_XDECREF(ours);
  Py_DECREF(previous_);
  PyErr_Restore(type, value, traceback);
}

std::shared_ptr<void> pooled_block(std::size_t bytes) {
  void* p = pool_malloc(nullptr, bytes);
  if (p == nullptr) throw std::bad_alloc();
  return std::shared_ptr<void>(p, [](void* q) { pool_free(nullptr, q, 0); });
}

ResultPoolStats result_pool_stats() { return pool().stats(); }

void set_result_pool_limit(std::size_t bytes) { pool().set_limit(bytes); }

}  // namespace glintlab::python

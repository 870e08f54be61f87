// made_once: a measurement several of Chermain et al.'s claims share, made once per process
// (common.cpp's tube replicates, bumpy_tubes.cpp's normal-mapped ones).
#pragma once

#include <exception>
#include <future>
#include <map>
#include <mutex>

namespace glintlab::verify::chermain_claims {

// The value of `key`, made by make() the first time it is asked for in this process and read from
// the cache after (the claims that share a measurement each observe it). Made outside the lock, so
// the replicates of one claim are still made in parallel.
template <typename Value, typename Key, typename Make>
Value made_once(const Key& key, Make make) {
  static std::mutex mutex;
  static std::map<Key, std::shared_future<Value>> cache;
  std::promise<Value> promise;
  std::shared_future<Value> future;
  bool mine = false;
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto [it, inserted] = cache.try_emplace(key);
    if (inserted) it->second = promise.get_future().share(), mine = true;
    future = it->second;
  }
  if (mine) {
    try {
      promise.set_value(make());
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
  }
  return future.get();
}

}  // namespace glintlab::verify::chermain_claims

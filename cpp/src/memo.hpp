// A process-wide memo of a pure function of a few numbers (the critical
// speeds, a graded top's series): looked up under a mutex, computed outside
// it, forgotten wholesale past 4096 entries. Internal header.
#pragma once

#include <map>
#include <mutex>

namespace movingpunch::detail {

template <class Key, class Value, class Compute>
Value memoized(std::mutex& mutex, std::map<Key, Value>& cache, const Key& key,
               const Compute& compute) {
  {
    std::lock_guard<std::mutex> lock(mutex);
    const auto it = cache.find(key);
    if (it != cache.end()) return it->second;
  }
  const Value v = compute();
  std::lock_guard<std::mutex> lock(mutex);
  if (cache.size() > 4096) cache.clear();
  cache[key] = v;
  return v;
}

}  // namespace movingpunch::detail

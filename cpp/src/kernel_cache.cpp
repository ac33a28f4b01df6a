// The process-wide cache of k1 tables (see kernel.hpp).
#include <algorithm>
#include <list>
#include <memory>
#include <mutex>

#include "movingpunch/kernel.hpp"

namespace movingpunch {

namespace {

struct Entry {
  double vstar, kw, nu, tol;
  std::shared_ptr<const KernelK1> kernel;
  bool matches(const LayerModel& m, double t) const {
    // Exact comparison: the same inputs give the same table.
    return vstar == m.vstar() && kw == m.kw() && nu == m.nu() && tol == t;
  }
};

struct Cache {
  std::mutex mutex;
  std::list<Entry> entries;  // most recently used first
  KernelCacheInfo info;
};

Cache& cache() {
  static Cache c;
  return c;
}

}  // namespace

std::shared_ptr<const KernelK1> cached_kernel(const LayerModel& model, double tol,
                                              double min_range, double build_range,
                                              bool* built) {
  Cache& c = cache();
  {
    std::lock_guard<std::mutex> lock(c.mutex);
    auto best = c.entries.end();
    for (auto it = c.entries.begin(); it != c.entries.end(); ++it) {
      const double r = it->kernel->range();
      if (!it->matches(model, tol) || r < min_range || r > kMaxRangeRatio * min_range) continue;
      if (best == c.entries.end() || r < best->kernel->range()) best = it;
    }
    if (best != c.entries.end()) {
      c.entries.splice(c.entries.begin(), c.entries, best);
      ++c.info.hits;
      if (built) *built = false;
      return c.entries.front().kernel;
    }
  }
  // Built outside the lock: other threads keep using the cache meanwhile (two
  // threads may build the same table; both results are equal and both kept
  // only until eviction).
  auto k = std::make_shared<const KernelK1>(model, tol, std::max(build_range, min_range));
  std::lock_guard<std::mutex> lock(c.mutex);
  c.entries.push_front(Entry{model.vstar(), model.kw(), model.nu(), tol, k});
  while (c.entries.size() > kKernelCacheCapacity) c.entries.pop_back();
  ++c.info.misses;
  c.info.size = c.entries.size();
  if (built) *built = true;
  return k;
}

KernelCacheInfo kernel_cache_info() {
  Cache& c = cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  KernelCacheInfo i = c.info;
  i.size = c.entries.size();
  return i;
}

void clear_kernel_cache() {
  Cache& c = cache();
  std::lock_guard<std::mutex> lock(c.mutex);
  c.entries.clear();
  c.info = KernelCacheInfo{};
}

}  // namespace movingpunch

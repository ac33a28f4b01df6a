// The process-wide caches of kernel tables: the real k1 tables (kernel.hpp)
// and the damped kernel tables (asymmetric.hpp). One LRU policy for both.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <list>
#include <memory>
#include <mutex>
#include <vector>

#include "movingpunch/asymmetric.hpp"
#include "movingpunch/kernel.hpp"

namespace movingpunch {

namespace {

// Tables of one kind, keyed on the inputs they depend on (compared exactly:
// the same inputs give the same table) and covering |u| <= range().
constexpr double kStep = 1.25;

template <class Table, class KeyType>
class RangeCache {
 public:
  using Key = KeyType;
  using Ptr = std::shared_ptr<const Table>;

  RangeCache(std::size_t capacity, double max_ratio) : capacity_(capacity), max_ratio_(max_ratio) {}

  // The shortest cached table of this key with min_range <= range <=
  // max_ratio min_range, or one built by build(range, shorter) and cached.
  // When a table of this key exists but is too short (a widening sweep), the
  // new range is at least kGrowth times the longest such table's: geometric
  // growth, so a sweep in any order builds a few tables, not one per point
  // (and a solve whose width iteration overshoots its first guess builds
  // the table it asks for, no wider). `shorter` is the
  // longest of those (its range-independent parts may be reused).
  template <class Build>
  Ptr get(const Key& key, double min_range, double build_range, Build build, bool* built,
          double growth = kGrowth) {
    Ptr shorter;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto best = entries_.end();
      for (auto it = entries_.begin(); it != entries_.end(); ++it) {
        if (it->key != key) continue;
        const double r = it->table->range();
        if (r < min_range) {
          if (!shorter || r > shorter->range()) shorter = it->table;
          continue;
        }
        if (r > max_ratio_ * min_range) continue;
        if (best == entries_.end() || r < best->table->range()) best = it;
      }
      if (best != entries_.end()) {
        entries_.splice(entries_.begin(), entries_, best);
        ++info_.hits;
        if (built) *built = false;
        return entries_.front().table;
      }
    }
    double range = std::max(build_range, min_range);
    // Only a sweep's small step (the need within kStep of the shorter
    // table) grows: a far wider request is another problem, built as asked.
    if (shorter && min_range <= kStep * shorter->range())
      range = std::max(range, growth * shorter->range());
    // Built outside the lock: other threads keep using the cache meanwhile
    // (two threads may build the same table; both are equal and both kept
    // only until eviction).
    Ptr t = build(range, shorter);
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.push_front(Entry{key, t});
    while (entries_.size() > capacity_) entries_.pop_back();
    ++info_.misses;
    if (built) *built = true;
    return t;
  }

  KernelCacheInfo info() {
    std::lock_guard<std::mutex> lock(mutex_);
    KernelCacheInfo i = info_;
    i.size = entries_.size();
    return i;
  }

  void clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.clear();
    info_ = KernelCacheInfo{};
  }

 private:
  struct Entry {
    Key key;
    Ptr table;
  };
  std::size_t capacity_;
  double max_ratio_;
  std::mutex mutex_;
  std::list<Entry> entries_;  // most recently used first
  KernelCacheInfo info_;
};

RangeCache<KernelK1, std::vector<double>>& k1_cache() {
  static RangeCache<KernelK1, std::vector<double>> c(kKernelCacheCapacity, kMaxRangeRatio);
  return c;
}

// A damped table's evaluation costs the same whatever its range (pieces):
// no upper ratio. Keyed on the medium (Medium::key()) and the friction.
RangeCache<AsymmetricKernel, std::vector<double>>& asymmetric_cache() {
  static RangeCache<AsymmetricKernel, std::vector<double>> c(
      kDampedKernelCacheCapacity, std::numeric_limits<double>::infinity());
  return c;
}

}  // namespace

std::shared_ptr<const KernelK1> cached_kernel(const LayerModel& model, double tol, double min_range,
                                              double build_range, bool* built, bool grow) {
  return cached_kernel(
      make_medium(homogeneous_medium(model.kw(), model.nu(), model.kp()), model.vstar()), tol,
      min_range, build_range, built, grow);
}

std::shared_ptr<const KernelK1> cached_kernel(const std::shared_ptr<const Medium>& model,
                                              double tol, double min_range, double build_range,
                                              bool* built, bool grow) {
  std::vector<double> key = model->key();  // kp is irrelevant on a rigid base: one key for it
  key.push_back(tol);
  return k1_cache().get(
      key, min_range, build_range,
      [&](double range, const std::shared_ptr<const KernelK1>& shorter) {
        // Growth never turns a global table piecewise when the range needed
        // fits a global one: a piecewise table's error bound is of any shape
        // (a looser a/h estimate), and near V*_cr its gap check sits at its
        // round-off floor (contact.cpp's table_range).
        if (shorter && !shorter->piecewise()) {
          const double global_max = KernelK1::kPieceBandwidth / shorter->quadrature().alpha_max;
          if (std::max(build_range, min_range) <= global_max) range = std::min(range, global_max);
        }
        return std::make_shared<const KernelK1>(model, tol, range, shorter.get());
      },
      built, grow ? kGrowth : 1.0);
}

std::shared_ptr<const AsymmetricKernel> cached_damped_kernel(
    const std::shared_ptr<const Medium>& medium, double min_range, double build_range, bool* built,
    double friction) {
  std::vector<double> key = medium->key();  // kp is irrelevant on a rigid base: one key for it
  key.push_back(friction);
  return asymmetric_cache().get(
      key, min_range, build_range,
      [&](double range, const std::shared_ptr<const AsymmetricKernel>& shorter) {
        if (shorter) return std::make_shared<const AsymmetricKernel>(*shorter, range);
        return std::make_shared<const AsymmetricKernel>(medium, range, friction);
      },
      built);
}

std::shared_ptr<const AsymmetricKernel> cached_damped_kernel(double vstar, double kw, double nu,
                                                             double damping, double min_range,
                                                             double build_range, bool* built,
                                                             double kp, double friction) {
  return cached_damped_kernel(make_medium(homogeneous_medium(kw, nu, kp, damping), vstar),
                              min_range, build_range, built, friction);
}

KernelCacheInfo kernel_cache_info() { return k1_cache().info(); }
KernelCacheInfo asymmetric_kernel_cache_info() { return asymmetric_cache().info(); }

void clear_kernel_cache() {
  k1_cache().clear();
  asymmetric_cache().clear();
}

}  // namespace movingpunch

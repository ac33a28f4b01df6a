// The process-wide k1 cache: reuse rules, counters, and that a reused table
// gives the same contact as a fresh one.
#include <gtest/gtest.h>

#include <cmath>

#include "movingpunch/contact.hpp"
#include "movingpunch/kernel.hpp"

using namespace movingpunch;

TEST(KernelCache, ReusesAdequateTablesOnly) {
  clear_kernel_cache();
  const LayerModel m(0.2, 1.0, 0.2);
  bool built = false;
  const auto k1 = cached_kernel(m, 1e-10, 2.0, 4.0, &built);
  EXPECT_TRUE(built);
  EXPECT_DOUBLE_EQ(k1->range(), 4.0);
  // Narrower request within the ratio: the same table.
  const auto k2 = cached_kernel(m, 1e-10, 1.0, 2.0, &built);
  EXPECT_FALSE(built);
  EXPECT_EQ(k1.get(), k2.get());
  // Wider than the table: a new one.
  const auto k3 = cached_kernel(m, 1e-10, 5.0, 6.0, &built);
  EXPECT_TRUE(built);
  EXPECT_NE(k1.get(), k3.get());
  // Far narrower than every table (beyond kMaxRangeRatio): a new, small one.
  const auto k4 = cached_kernel(m, 1e-10, 0.01, 0.02, &built);
  EXPECT_TRUE(built);
  EXPECT_DOUBLE_EQ(k4->range(), 0.02);
  // Another tolerance, speed, stiffness or Poisson's ratio: never shared.
  cached_kernel(m, 1e-9, 2.0, 4.0, &built);
  EXPECT_TRUE(built);
  cached_kernel(LayerModel(0.2000001, 1.0, 0.2), 1e-10, 2.0, 4.0, &built);
  EXPECT_TRUE(built);
  cached_kernel(LayerModel(0.2, 1.5, 0.2), 1e-10, 2.0, 4.0, &built);
  EXPECT_TRUE(built);
  cached_kernel(LayerModel(0.2, 1.0, 0.3), 1e-10, 2.0, 4.0, &built);
  EXPECT_TRUE(built);
  const KernelCacheInfo info = kernel_cache_info();
  EXPECT_EQ(info.hits, 1u);
  EXPECT_EQ(info.misses, 7u);
  EXPECT_EQ(info.size, 7u);
  clear_kernel_cache();
  EXPECT_EQ(kernel_cache_info().size, 0u);
  EXPECT_EQ(kernel_cache_info().misses, 0u);
}

TEST(KernelCache, Evicts) {
  clear_kernel_cache();
  for (std::size_t i = 0; i < kKernelCacheCapacity + 5; ++i)
    cached_kernel(LayerModel(0.01 * static_cast<double>(i), 1.0, 0.2), 1e-8, 1.0, 1.0);
  EXPECT_EQ(kernel_cache_info().size, kKernelCacheCapacity);
  clear_kernel_cache();
}

TEST(KernelCache, ALoadSweepReusesOneTableAndMatchesFreshSolves) {
  ContactParams p;
  p.vstar = 0.4;
  p.kw = 1.0;
  p.radius = 100.0;
  clear_kernel_cache();
  int builds = 0;
  double previous = INFINITY;
  // Largest contact first: its table covers the rest.
  for (double load : {0.02, 0.01, 0.005, 0.002, 0.001}) {
    p.load = load;
    const SymmetricSolution warm = solve_contact(p);
    builds += warm.kernel_builds();
    EXPECT_LT(warm.a(), previous);
    previous = warm.a();
    clear_kernel_cache();
    const SymmetricSolution fresh = solve_contact(p);
    EXPECT_GE(fresh.kernel_builds(), 1);
    // Both tables are accurate far below tol: the widths agree to the root
    // finder's tolerance (1e-2 tol), not bit for bit.
    EXPECT_NEAR(warm.a(), fresh.a(), 1e-11 * fresh.a()) << "load " << load;
    EXPECT_NEAR(warm.indentation(), fresh.indentation(), 1e-10 * fresh.indentation());
    // Restore the sweep's table: the widest solve again (a cache hit or a build).
    p.load = 0.02;
    solve_contact(p);
  }
  EXPECT_GE(builds, 1);
  clear_kernel_cache();
}

TEST(KernelCache, SweepBuildsOnce) {
  ContactParams p;
  p.vstar = 0.2;
  p.kw = 1.0;
  p.radius = 100.0;
  clear_kernel_cache();
  int builds = 0;
  for (int i = 0; i < 14; ++i) {
    p.load = 0.01 * std::pow(0.8, i);  // descending: a/h from about 0.9 down to 0.2
    const SymmetricSolution s = solve_contact(p);
    if (i > 0) {
      EXPECT_EQ(s.kernel_builds(), 0) << "load " << p.load;
    }
    builds += s.kernel_builds();
    const auto& t = s.stage_seconds();
    EXPECT_GE(t.critical_speed, 0.0);
    EXPECT_GE(t.kernel, 0.0);
    EXPECT_GE(t.width, 0.0);
    EXPECT_GE(t.checks, 0.0);
    const double sum = t.critical_speed + t.kernel + t.width + t.checks;
    EXPECT_LE(sum, s.elapsed() * (1 + 1e-9));
    EXPECT_GE(sum, 0.9 * s.elapsed() - 1e-5);
  }
  clear_kernel_cache();
}

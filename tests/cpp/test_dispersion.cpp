// Critical speed: the published table, the rigid-base limit, monotonicity.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "movingpunch/dispersion.hpp"
#include "movingpunch/layer_response.hpp"

using namespace movingpunch;

TEST(CriticalSpeed, PublishedTableAtNu02) {
  const double kw[] = {0.01, 0.1, 1.0, 10.0};
  const double want[] = {0.0869126, 0.2475216, 0.5716928, 0.8185946};
  const double t_min[] = {0.48, 0.93, 1.99, 4.99};
  for (int i = 0; i < 4; ++i) {
    const CriticalSpeed c = critical_speed(kw[i], 0.2);
    EXPECT_NEAR(c.vstar, want[i], 2e-6) << "kw " << kw[i];
    EXPECT_NEAR(c.t, t_min[i], 0.01) << "kw " << kw[i];
  }
  EXPECT_NEAR(critical_vstar(0.03, 0.2), 0.1453, 1e-4);
  EXPECT_NEAR(critical_vstar(0.3, 0.2), 0.3843, 1e-4);
  EXPECT_NEAR(critical_vstar(3.0, 0.2), 0.7308, 1e-4);
}

TEST(CriticalSpeed, OtherPoissonRatios) {
  EXPECT_NEAR(critical_vstar(0.1, 0.25), 0.2547, 1e-4);
  EXPECT_NEAR(critical_vstar(1.0, 0.25), 0.5850, 1e-4);
  EXPECT_NEAR(critical_vstar(10.0, 0.25), 0.8341, 1e-4);
  EXPECT_NEAR(critical_vstar(0.1, 0.3), 0.2625, 1e-4);
  EXPECT_NEAR(critical_vstar(1.0, 0.3), 0.5992, 1e-4);
  EXPECT_NEAR(critical_vstar(10.0, 0.3), 0.8492, 1e-4);
}

TEST(CriticalSpeed, RigidBaseIsRayleighAndHasNoSlowerWave) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_DOUBLE_EQ(critical_vstar(inf, 0.2), rayleigh_vstar(0.2));
  for (double t : {0.01, 0.3, 1.0, 3.0, 10.0, 100.0})
    EXPECT_DOUBLE_EQ(first_wave_vstar(t, inf, 0.2), rayleigh_vstar(0.2)) << "t " << t;
}

TEST(CriticalSpeed, IsTheMinimumOfTheFirstWaveSpeed) {
  const CriticalSpeed c = critical_speed(1.0, 0.2);
  for (double f : {0.5, 0.9, 0.99, 1.01, 1.1, 2.0})
    EXPECT_GE(first_wave_vstar(c.t * f, 1.0, 0.2), c.vstar - 1e-12);
  // At the critical wavenumber the response really has a pole: the
  // dispersion function changes sign across V*_cr.
  const double below = LayerModel(c.vstar * (1 - 1e-6), 1.0, 0.2).dispersion(c.t);
  const double above = LayerModel(c.vstar * (1 + 1e-6), 1.0, 0.2).dispersion(c.t);
  EXPECT_LT(below * above, 0.0);
}

TEST(CriticalSpeed, IncreasesWithFoundationStiffness) {
  double prev = 0.0;
  for (double kw : {1e-4, 1e-3, 0.01, 0.1, 1.0, 10.0, 100.0}) {
    const double v = critical_vstar(kw, 0.2);
    EXPECT_GT(v, prev) << "kw " << kw;
    EXPECT_LT(v, rayleigh_vstar(0.2));
    prev = v;
  }
}

// The search (a coarse grid and Brent's minimiser) finds the minimum of the
// first-wave speed everywhere: no point of a dense, independent log grid of
// 20 points per decade over t in [1e-5, 1e5] lies below it, and the grid's
// best point is within the grid's own resolution of it.
TEST(CriticalSpeed, NoDenseGridPointLiesBelowIt) {
  for (double nu : {0.0, 0.2, 0.45}) {
    for (double kw : {1e-6, 0.01, 0.3, 1.0, 10.0, 30.0, 100.0}) {
      const CriticalSpeed c = critical_speed(kw, nu);
      double grid_min = rayleigh_vstar(nu);
      for (int i = 0; i <= 200; ++i) {
        const double t = std::pow(10.0, -5.0 + 0.05 * i);
        const double v = first_wave_vstar(t, kw, nu);
        EXPECT_GE(v, c.vstar * (1.0 - 1e-12)) << "kw " << kw << " nu " << nu << " t " << t;
        grid_min = std::min(grid_min, v);
      }
      EXPECT_LE(c.vstar, grid_min) << "kw " << kw << " nu " << nu;
      EXPECT_NEAR(c.vstar, grid_min, 2e-2 * c.vstar) << "kw " << kw << " nu " << nu;
      if (std::isfinite(c.t)) {
        EXPECT_NEAR(first_wave_vstar(c.t, kw, nu), c.vstar, 1e-13) << "kw " << kw;
      }
    }
  }
}

// The default scan for the first sign change (kFirstWaveScan points) finds
// the same lowest free wave as a scan six times denser, from the soft to the
// stiff foundation, the compressible to the nearly incompressible layer, and
// the longest to the shortest waves.
TEST(CriticalSpeed, DefaultScanFindsTheLowestBranch) {
  for (double nu : {0.0, 0.3, 0.499}) {
    for (double kw : {1e-10, 1e-4, 0.03, 1.0, 30.0, 1e6}) {
      for (int i = 0; i <= 80; ++i) {
        const double t = std::pow(10.0, -5.0 + 0.125 * i);
        const double coarse = first_wave_vstar(t, kw, nu);
        const double dense = first_wave_vstar(t, kw, nu, 0.0, 6 * kFirstWaveScan);
        EXPECT_NEAR(coarse, dense, 1e-12 * std::max(dense, 1e-3))
            << "nu " << nu << " kw " << kw << " t " << t;
      }
    }
  }
}

// Coulomb friction on the asymmetric solver: the tangential response against
// its half-plane limit, f = 0 unchanged, the static half-plane's sliding
// cylinder (Johnson, Contact Mechanics (1985), section 7.1), equilibrium.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "movingpunch/asymmetric.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/jacobi.hpp"
#include "test_helpers.hpp"

namespace mp = movingpunch;

namespace {
constexpr double kPi = 3.14159265358979323846;

mp::AsymmetricParams sliding(double vstar, double kw, double damping, double f) {
  return mp::testing::paper_asymmetric(vstar, kw, damping, f);
}
}  // namespace

TEST(Friction, TangentialResponseTendsToTheHalfPlane) {
  for (double s : {0.0, 0.3, 0.7}) {
    const mp::DampedLayerModel m(s, 1.0, 0.2, 0.1);
    const mp::DampedResponse r = m.response(30.0);
    EXPECT_NEAR(r.Wq.real(), m.tangential().Wq, 1e-11 * std::fabs(m.tangential().Wq));
    EXPECT_NEAR(r.Uq.real(), m.tangential().Uq, 1e-11 * std::fabs(m.tangential().Uq));
    // The transfer and modal forms agree at t = 0.5.
    const mp::DampedResponse a = m.response_transfer(0.5), b = m.response_modal(0.5);
    EXPECT_LT(std::abs(a.Wq - b.Wq), 1e-12);
    EXPECT_LT(std::abs(a.Uq - b.Uq), 1e-12);
  }
}

TEST(Friction, BarPoleAtSmallWavenumber) {
  // The shear-free base carries no horizontal force: t Ep Uq -> Ep/(Ep - s).
  const double s = 0.3;
  const mp::DampedLayerModel m(s, 1.0, 0.2, 0.0);
  const double c2 = m.constants().c2, ep = 4.0 * (c2 - 1.0) / c2;
  const mp::DampedResponse r = m.response(1e-5);
  EXPECT_NEAR(1e-5 * ep * r.Uq.real(), ep / (ep - s), 1e-8);
}

TEST(Friction, ZeroFrictionIsUnchanged) {
  const mp::AsymmetricSolution a = mp::solve_asymmetric(sliding(0.2, 1.0, 0.1, 0.0));
  mp::AsymmetricParams p = sliding(0.2, 1.0, 0.1, 0.0);
  const mp::AsymmetricSolution b = mp::solve_asymmetric(p);
  EXPECT_EQ(a.left(), b.left());
  EXPECT_EQ(a.end_exponents().back, 0.5);
  EXPECT_EQ(a.tangential_force(), 0.0);
}

TEST(Friction, HalfPlaneSlidingCylinder) {
  // Rigid base at rest, a << h: w^2 = phi1 R P/(2 pi gb gf), c = w (gb - gf).
  mp::AsymmetricParams p = sliding(0.0, std::numeric_limits<double>::infinity(), 0.0, 0.5);
  p.load = 2e-11;
  const mp::AsymmetricSolution s = mp::solve_asymmetric(p);
  const double phi = 0.375, gb = std::atan2(1.0, 0.5 * phi) / kPi, gf = 1.0 - gb;
  const double w = std::sqrt(0.8 * 100.0 * 2e-11 / (2.0 * kPi * gb * gf));
  EXPECT_NEAR(s.end_exponents().back, gb, 1e-14);
  EXPECT_NEAR(s.half_width(), w, 1e-7 * w);
  EXPECT_NEAR(s.centre(), w * (gb - gf), 1e-4 * w);
}

TEST(Friction, RefusesBadInput) {
  EXPECT_THROW(mp::solve_asymmetric(sliding(0.2, 1.0, 0.0, -0.1)), std::invalid_argument);
  EXPECT_THROW(mp::solve_asymmetric(sliding(0.2, 1.0, 0.0, std::nan(""))), std::invalid_argument);
  EXPECT_THROW(mp::solve_asymmetric(sliding(0.2, 1.0, 0.0, 0.0)), std::invalid_argument);
  EXPECT_THROW(mp::solve_asymmetric(sliding(0.6, 1.0, 0.0, 0.3)), mp::SupercriticalSpeedError);
}

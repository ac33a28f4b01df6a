// The flat punch on the asymmetric solver (cpp/src/asymmetric_flat.cpp) against
// closed forms: the half-plane's p = P/(pi sqrt(b^2 - x^2)) and, with
// friction, the static half-plane's Gauss-Jacobi form (K. L. Johnson, Contact
// Mechanics 1985, section 2.8); the energy balance (dissipation by Parseval on
// the bottom face = the edges' forces load phi1 (K_front^2 - K_back^2)/4).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "movingpunch/asymmetric.hpp"
#include "movingpunch/errors.hpp"

namespace mp = movingpunch;

namespace {
constexpr double kPi = 3.14159265358979323846;

mp::AsymmetricParams flat(double b) {
  mp::AsymmetricParams p;
  p.profile = mp::ProfileKind::flat;
  p.half_width = b;
  p.vstar = 0.2;
  p.kw = 100.0;
  p.load = 0.002;
  return p;
}
}  // namespace

TEST(AsymmetricFlat, HalfPlaneLimit) {
  mp::AsymmetricParams p = flat(1e-4);
  p.damping = 0.5;
  const mp::AsymmetricSolution s = mp::solve_asymmetric(p);
  const double b = 1e-4, k = 1.0 / std::sqrt(kPi * b);
  EXPECT_NEAR(s.end_coefficient_back(), k, 1e-6 * k);
  EXPECT_NEAR(s.end_coefficient_front(), k, 1e-6 * k);
  for (double r : {-0.95, -0.3, 0.0, 0.5, 0.9}) {
    const double x = r * b, exact = 1.0 / (kPi * std::sqrt(b * b - x * x));
    EXPECT_NEAR(s.pressure(x), exact, 1e-6 * exact) << r;
  }
  EXPECT_EQ(s.pressure(b), std::numeric_limits<double>::infinity());
  EXPECT_EQ(s.left(), -b);
  EXPECT_EQ(s.right(), b);
  EXPECT_TRUE(s.valid());
}

TEST(AsymmetricFlat, StaticFrictionalHalfPlaneClosedForm) {
  // p = C (b - x)^(gf - 1) (b + x)^(gb - 1), cot(pi gb) = f Phi, C = sin(pi gb)/pi.
  mp::AsymmetricParams p = flat(1e-8);
  p.vstar = 0.0;
  p.kw = std::numeric_limits<double>::infinity();
  p.friction = 0.6;
  const mp::AsymmetricSolution s = mp::solve_asymmetric(p);
  const double phi = (1.0 - 2.0 * 0.2) / (2.0 * (1.0 - 0.2));
  const double gb = std::atan2(1.0, 0.6 * phi) / kPi, gf = 1.0 - gb, b = 1e-8;
  EXPECT_NEAR(s.end_exponents().back, gb - 1.0, 1e-14);
  EXPECT_NEAR(s.end_exponents().front, gf - 1.0, 1e-14);
  const double c = std::sin(kPi * gb) / kPi;
  for (double r : {-0.9, 0.0, 0.7}) {
    const double x = r * b, exact = c * std::pow(b - x, gf - 1.0) * std::pow(b + x, gb - 1.0);
    EXPECT_NEAR(s.pressure(x), exact, 1e-6 * exact) << r;
  }
  EXPECT_EQ(s.tangential_force(), 0.6);
}

TEST(AsymmetricFlat, DissipationIsTheEdgesForces) {
  mp::AsymmetricParams p = flat(1.0);
  p.kw = 1.0;
  p.damping = 0.5;
  const mp::AsymmetricSolution s = mp::solve_asymmetric(p);
  const double kb = s.end_coefficient_back(), kf = s.end_coefficient_front();
  EXPECT_GT(kf, kb);
  const double edges = p.load * s.phi1() * (kf * kf - kb * kb) / 4.0;
  EXPECT_NEAR(s.drag(), edges, 1e-14 * edges);
  EXPECT_NEAR(s.dissipation(), edges, 1e-8 * edges);
}

TEST(AsymmetricFlat, BadInputsAreRefused) {
  mp::AsymmetricParams p = flat(0.5);
  p.damping = 0.0;  // neither damping nor friction: the undamped solver's
  EXPECT_THROW(mp::solve_asymmetric(p), mp::InvalidParameter);
  p.damping = 0.1;
  p.half_width = 0.0;
  EXPECT_THROW(mp::solve_asymmetric(p), mp::InvalidParameter);
}

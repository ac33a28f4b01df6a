// Stresses and displacements: boundary conditions, the classical Hertz field,
// the two evaluations of the surface displacement, the mode fields.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "movingpunch/contact.hpp"
#include "test_helpers.hpp"

using namespace movingpunch;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
using movingpunch::testing::paper;
const auto grid = [](std::initializer_list<double> v) { return movingpunch::testing::vec(v); };
}  // namespace

TEST(ModeField, TopStateMatchesResponseAndModesAgree) {
  for (double kw : {0.1, 1.0, kInf}) {
    const LayerModel m(0.2, kw, 0.2);
    for (double t : {0.1, 0.45, 0.55, 3.0}) {
      const ModeField f = m.mode_field(t);
      const Eigen::Vector4d z0 = f.state(0.0);
      const Response r = m.response(t);
      EXPECT_NEAR(z0(1), r.W0, 1e-12);
      EXPECT_NEAR(z0(2), 0.0, 1e-12);
      EXPECT_NEAR(z0(3), -1.0, 1e-12);
      const Eigen::Vector4d zb = f.state(-1.0);
      EXPECT_NEAR(zb(2), 0.0, 1e-11);  // tau = 0 at the base
      if (std::isinf(kw))
        EXPECT_NEAR(zb(1), 0.0, 1e-11);
      else
        EXPECT_NEAR(t * zb(3), kw * zb(1), 1e-11 * (1 + std::fabs(kw * zb(1))));
    }
  }
}

TEST(ModeField, HalfPlanePartSatisfiesTheTopLoadAndDominatesShortWaves) {
  for (double s : {0.0, 1e-9, 0.3}) {
    const LayerModel m(s, 1.0, 0.2);
    const ModeField f = m.mode_field(40.0);
    for (double y : {0.0, -0.05, -0.3}) {
      const Eigen::Vector4d d = f.state(y) - f.half_plane_state(y);
      EXPECT_LT(d.cwiseAbs().maxCoeff(), 1e-12) << "s " << s << " y " << y;
    }
    const Eigen::Vector4d top = m.mode_field(0.8).half_plane_state(0.0);
    EXPECT_NEAR(top(2), 0.0, 1e-14);
    EXPECT_NEAR(top(3), -1.0, 1e-14);
    EXPECT_NEAR(-top(1), m.phi1(), 1e-14);
  }
}

TEST(Stresses, SurfaceAndBaseConditions) {
  for (double kw : {0.1, 1.0, kInf})
    for (double v : {0.0, 0.2}) {
      const SymmetricSolution s = solve_contact(paper(v, kw));
      const double a = s.a();
      const Eigen::VectorXd x = grid({0.0, 0.3 * a, 0.99 * a, 1.01 * a, 2 * a, 3.0});
      const Eigen::VectorXd y = grid({0.0, -1.0});
      const StressField f = s.stress_field(x, y);
      const Eigen::MatrixXd v_base = s.displacement(x, grid({-1.0}));
      for (Eigen::Index i = 0; i < x.size(); ++i) {
        EXPECT_NEAR(f.sigma_y(0, i), -s.pressure(x(i)), 1e-11);
        EXPECT_NEAR(f.tau_xy(0, i), 0.0, 1e-13);
        EXPECT_NEAR(f.tau_xy(1, i), 0.0, 1e-12);
        if (std::isinf(kw))
          EXPECT_NEAR(v_base(0, i), 0.0, 1e-14);
        else  // sigma_y (P/h) = kw v (both in units of mu)
          EXPECT_NEAR(f.sigma_y(1, i) * 0.002, kw * v_base(0, i), 1e-12);
      }
    }
}

TEST(Stresses, DisplacementAgreesWithTheSurfaceEvaluation) {
  const SymmetricSolution s = solve_contact(paper(0.2, 0.1));
  const Eigen::VectorXd x = grid({0.0, 0.2, 0.7, 1.3, 2.5});
  const Eigen::MatrixXd v = s.displacement(x, grid({0.0}));
  for (Eigen::Index i = 0; i < x.size(); ++i)
    EXPECT_NEAR(v(0, i), s.surface_displacement(x(i)), 1e-12);
}

TEST(Stresses, ClassicalHertzFieldOnTheAxis) {
  // A contact much smaller than the layer (a/h ~ 1e-3), static, rigid base:
  // under the centre sigma_y = -p0 a / sqrt(a^2 + z^2) and
  // sigma_x = -p0 [(a^2 + 2 z^2) / (a sqrt(a^2 + z^2)) - 2 z / a], z = -y.
  // The finite layer adds a sigma_x of order P/h that varies on the scale h
  // (its bending on the base): a constant over these depths, ~4e-4 p0 here.
  ContactParams p = paper(0.0, kInf);
  p.radius = 1.0;
  p.load = 5e-7;
  const SymmetricSolution s = solve_contact(p);
  const double a = s.a(), p0 = s.p0();
  ASSERT_LT(a, 1e-3);
  auto hertz_x = [&](double z) {
    const double r = std::sqrt(a * a + z * z);
    return -p0 * ((a * a + 2 * z * z) / (a * r) - 2 * z / a);
  };
  const double sx0 = s.stress_field(grid({0.0}), grid({0.0})).sigma_x(0, 0);
  EXPECT_NEAR(sx0, hertz_x(0.0), 1e-3 * p0);
  for (double zr : {0.0, 0.3, 1.0, 3.0}) {
    const double z = zr * a, r = std::sqrt(a * a + z * z);
    const StressField f = s.stress_field(grid({0.0}), grid({-z}));
    EXPECT_NEAR(f.sigma_y(0, 0), -p0 * a / r, 1e-4 * p0) << "z/a " << zr;
    EXPECT_NEAR(f.sigma_x(0, 0) - sx0, hertz_x(z) - hertz_x(0.0), 1e-4 * p0) << "z/a " << zr;
  }
}

TEST(Stresses, ContinuousUpToTheSurface) {
  const SymmetricSolution s = solve_contact(paper(0.2, 1.0));
  const Eigen::VectorXd x = grid({0.0, 0.5 * s.a(), 1.2 * s.a(), 2.0});
  const StressField f0 = s.stress_field(x, grid({0.0}));
  const StressField f1 = s.stress_field(x, grid({-1e-7}));
  for (Eigen::Index i = 0; i < x.size(); ++i)
    EXPECT_NEAR(f0.sigma_x(0, i), f1.sigma_x(0, i), 1e-4 * std::fabs(f0.sigma_x(0, 0)));
}

TEST(Stresses, RejectsPointsOutsideTheLayer) {
  const SymmetricSolution s = solve_contact(paper(0.2, 1.0));
  EXPECT_THROW(s.stress_field(grid({0.0}), grid({0.1})), std::invalid_argument);
  EXPECT_THROW(s.stress_field(grid({0.0}), grid({-1.5})), std::invalid_argument);
  EXPECT_THROW(s.stress_field(grid({std::nan("")}), grid({-0.5})), std::invalid_argument);
  EXPECT_THROW(s.displacement(grid({kInf}), grid({0.0})), std::invalid_argument);
}

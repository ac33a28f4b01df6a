// The damped solver's stress field (sigma_x, sigma_y, tau_xy)(x, y) (issue 13)
// against a direct Fourier sum written here independently: no split of the
// half-plane part, no Filon rule, no closed form; plain composite
// Gauss-Legendre in alpha over the layer's state at depth y, which decays like
// exp(nT alpha y) below the surface (so the sum needs alpha up to 40/(nT |y|)).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include "movingpunch/asymmetric.hpp"
#include "movingpunch/errors.hpp"

namespace mp = movingpunch;
using mp::cplx;

namespace {

constexpr double kPi = 3.14159265358979323846;

// sigma(x, y)/(P/h) = (1/pi) Re int_0^A [Sigma_x, S, -iT](alpha, y) p^(alpha) e^{i alpha x},
// [U, W, T, S] = DampedLayerModel::state, Sigma_x = 4 (c2 - 1)/c2 U + (c2 - 2)/c2 S
// (Hooke's law, c2 = cL^2/cT^2 = 2 (1 - nu)/(1 - 2 nu)), by 8-point Gauss-Legendre
// on panels of width 0.02 below alpha = 10 (the resonant peaks) and 0.25
// beyond (|x| <= 2: with p^ at most 1 radian per panel).
// Returns one row per x: (sigma_x, sigma_y, tau_xy).
Eigen::MatrixXd direct_stresses(const mp::AsymmetricSolution& s, const Eigen::VectorXd& xs,
                                double y) {
  static const double gx[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                               0.9602898564975363};
  static const double gw[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                               0.1012285362903763};
  const double nu = s.params().nu, c2 = 2.0 * (1.0 - nu) / (1.0 - 2.0 * nu);
  const double nT = std::sqrt(1.0 - s.params().vstar);
  const double top = 40.0 / (nT * std::fabs(y));  // exp(-40) of the decay
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(xs.size(), 3);
  double lo = 0.0;
  while (lo < top) {
    const double width = lo < 10.0 ? 0.02 : 0.25;
    const double c = lo + 0.5 * width, h = 0.5 * width;
    for (int k = 0; k < 8; ++k) {
      const double al = c + (k < 4 ? -1.0 : 1.0) * h * gx[k % 4];
      const Eigen::Vector4cd z = s.model().normal_state(al, y);
      const cplx ph = h * gw[k % 4] * s.pressure_transform(al);
      const cplx sx = (4.0 * (c2 - 1.0) / c2 * z(0) + (c2 - 2.0) / c2 * z(3)) * ph;
      const cplx sy = z(3) * ph, tau = cplx(0.0, -1.0) * z(2) * ph;
      for (Eigen::Index j = 0; j < xs.size(); ++j) {
        const cplx e = std::exp(cplx(0.0, al * xs(j)));
        out(j, 0) += (sx * e).real() / kPi;
        out(j, 1) += (sy * e).real() / kPi;
        out(j, 2) += (tau * e).real() / kPi;
      }
    }
    lo += width;
  }
  return out;
}

mp::AsymmetricSolution solve(double vstar, double damping) {
  mp::AsymmetricParams p;  // the paper's radius, load and nu by default
  p.vstar = vstar;
  p.kw = 1.0;
  p.damping = damping;
  return mp::solve_asymmetric(p);
}

}  // namespace

TEST(AsymmetricStressField, DepthFieldEqualsDirectFourierSum) {
  struct Case {
    double vstar, damping;
    std::vector<double> ys;
  };
  // Subcritical, and above V*_cr(kw = 1) = 0.5717 (the contact lies ahead);
  // y = -1e-3 is the depth the old plain Fourier integral stopped at.
  for (const Case& cs :
       {Case{0.2, 1.0, {-1e-3, -0.15, -0.5, -1.0}}, Case{0.65, 0.1, {-0.02, -0.3, -0.85, -1.0}}}) {
    const mp::AsymmetricSolution s = solve(cs.vstar, cs.damping);
    Eigen::VectorXd xs(6);
    xs << -2.0, s.left() + 0.01 * s.half_width(), s.left() + 0.3 * s.half_width(), s.centre(),
        s.right() - 0.01 * s.half_width(), 1.5;
    const Eigen::VectorXd ys =
        Eigen::Map<const Eigen::VectorXd>(cs.ys.data(), static_cast<Eigen::Index>(cs.ys.size()));
    const mp::StressField f = s.stress_field(xs, ys);
    const double scale = s.max_pressure();
    ASSERT_GT(scale, 0.0);
    for (Eigen::Index i = 0; i < ys.size(); ++i) {
      const Eigen::MatrixXd d = direct_stresses(s, xs, ys(i));
      for (Eigen::Index j = 0; j < xs.size(); ++j) {
        EXPECT_NEAR(f.sigma_x(i, j), d(j, 0), 1e-10 * scale)
            << "vstar " << cs.vstar << " x " << xs(j) << " y " << ys(i);
        EXPECT_NEAR(f.sigma_y(i, j), d(j, 1), 1e-10 * scale)
            << "vstar " << cs.vstar << " x " << xs(j) << " y " << ys(i);
        EXPECT_NEAR(f.tau_xy(i, j), d(j, 2), 1e-10 * scale)
            << "vstar " << cs.vstar << " x " << xs(j) << " y " << ys(i);
      }
    }
  }
}

TEST(AsymmetricStressField, SurfaceRowIsTheSurfaceValues) {
  const mp::AsymmetricSolution s = solve(0.65, 0.1);
  Eigen::VectorXd xs(5);
  xs << -2.0, s.left() + 0.2 * s.half_width(), s.centre(), s.right() - 1e-6, 3.0;
  const mp::StressField f = s.stress_field(xs, Eigen::VectorXd::Zero(1));
  for (Eigen::Index j = 0; j < xs.size(); ++j) {
    EXPECT_EQ(f.sigma_x(0, j), s.surface_stress(xs(j)));
    EXPECT_EQ(f.sigma_y(0, j), -s.pressure(xs(j)));
    EXPECT_EQ(f.tau_xy(0, j), 0.0);
    EXPECT_EQ(s.stress_x(xs(j), 0.0), s.surface_stress(xs(j)));
  }
}

TEST(AsymmetricStressField, RefusesBadPoints) {
  const mp::AsymmetricSolution s = solve(0.2, 0.1);
  const Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 0.1);
  for (const double y : {0.25, 1e-300, -1.0 - 1e-12, std::nan("")})
    EXPECT_THROW((void)s.stress_field(x, Eigen::VectorXd::Constant(1, y)), mp::InvalidParameter)
        << y;
  EXPECT_THROW((void)s.stress_field(Eigen::VectorXd::Constant(1, std::nan("")), x * 0.0),
               mp::InvalidParameter);
  EXPECT_THROW((void)s.stresses(std::numeric_limits<double>::infinity(), -0.5),
               mp::InvalidParameter);
  EXPECT_EQ(s.stresses(2e9, -0.5), Eigen::Vector3d::Zero());  // beyond kFarField
}

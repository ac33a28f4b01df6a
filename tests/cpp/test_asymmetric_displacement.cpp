// The damped solver's displacement field v(x, y) (issue 13) against a direct
// Fourier sum written here independently: no split of the log-singular
// half-plane part, no Filon rule, no closed form; plain composite
// Gauss-Legendre in alpha over the layer's state at depth y, which decays like
// exp(nT alpha y) below the surface. Agreement: 4e-14 of the indentation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include <Eigen/Dense>

#include "movingpunch/asymmetric.hpp"
#include "movingpunch/errors.hpp"

namespace mp = movingpunch;
using mp::cplx;

namespace {

constexpr double kPi = 3.14159265358979323846;

// v(x, y)/h = (load/pi) Re int_0^A (W(alpha, y)/alpha) p^(alpha) e^{i alpha x} d alpha,
// W = alpha v^/p^ (the state's second row), by 8-point Gauss-Legendre on
// panels of width `fine` below alpha = 10 (the resonant peaks) and 0.1 beyond.
double direct_displacement(const mp::AsymmetricSolution& s, double x, double y) {
  static const double gx[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                               0.9602898564975363};
  static const double gw[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                               0.1012285362903763};
  const double nT = std::sqrt(1.0 - s.params().vstar);
  const double top = 40.0 / (nT * std::fabs(y));  // exp(-40) of the decay
  double sum = 0.0, lo = 0.0;
  while (lo < top) {
    const double width = lo < 10.0 ? 0.02 : 0.1;
    const double c = lo + 0.5 * width, h = 0.5 * width;
    for (int k = 0; k < 8; ++k) {
      const double al = c + (k < 4 ? -1.0 : 1.0) * h * gx[k % 4];
      const cplx w = s.model().normal_state(al, y)(1);
      sum +=
          h * gw[k % 4] * (w / al * s.pressure_transform(al) * std::exp(cplx(0.0, al * x))).real();
    }
    lo += width;
  }
  return s.params().load * sum / kPi;
}

}  // namespace

TEST(AsymmetricDisplacement, DepthFieldEqualsDirectFourierSum) {
  struct Case {
    double vstar, damping;
  };
  // Subcritical, and above V*_cr(kw = 1) = 0.5717 (the contact lies ahead).
  for (const Case cs : {Case{0.2, 1.0}, Case{0.65, 0.1}}) {
    mp::AsymmetricParams p;  // the paper's radius, load and nu by default
    p.vstar = cs.vstar;
    p.kw = 1.0;
    p.damping = cs.damping;
    const mp::AsymmetricSolution s = mp::solve_asymmetric(p);
    const Eigen::Vector4d xs(-2.0, s.left() + 0.3 * s.half_width(), s.centre(), 1.5);
    const Eigen::Vector3d ys(-0.15, -0.5, -0.85);
    const Eigen::MatrixXd v = s.displacement(xs, ys);
    const double scale = s.indentation();
    ASSERT_GT(scale, 0.0);
    for (Eigen::Index i = 0; i < ys.size(); ++i)
      for (Eigen::Index j = 0; j < xs.size(); ++j)
        EXPECT_NEAR(v(i, j), direct_displacement(s, xs(j), ys(i)), 1e-12 * scale)
            << "vstar " << cs.vstar << " x " << xs(j) << " y " << ys(i);
  }
}

TEST(AsymmetricDisplacement, RefusesBadPoints) {
  mp::AsymmetricParams p;
  p.vstar = 0.2;
  p.damping = 0.1;
  const mp::AsymmetricSolution s = mp::solve_asymmetric(p);
  const Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 0.1);
  const Eigen::VectorXd bad_y = Eigen::VectorXd::Constant(1, 0.25);
  const Eigen::VectorXd nan_x = Eigen::VectorXd::Constant(1, std::nan(""));
  EXPECT_THROW((void)s.displacement(x, bad_y), mp::InvalidParameter);
  EXPECT_THROW((void)s.displacement(nan_x, x * 0.0), mp::InvalidParameter);
  EXPECT_THROW((void)s.surface_displacement(std::nan("")), mp::InvalidParameter);
  EXPECT_THROW((void)s.surface_displacement(std::numeric_limits<double>::infinity()),
               mp::InvalidParameter);
  EXPECT_EQ(s.surface_displacement(2e9), 0.0);  // beyond kFarField, as SymmetricSolution
}

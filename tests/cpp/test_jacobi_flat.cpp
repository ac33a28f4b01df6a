// The index +1 Jacobi series (alpha + beta = -1: the flat punch on the
// asymmetric solver, docs/theory.md section 14) against independent anchors:
// the Cauchy identity's constant 1/2 checked by tanh-sinh quadrature (which
// resolves the weight's algebraic end singularities), first-kind
// Gauss-Chebyshev at alpha = beta = -1/2, Beta-function moments, the discrete
// rule at the companion zeros.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "movingpunch/collocation.hpp"
#include "movingpunch/jacobi.hpp"

namespace mp = movingpunch;

namespace {
constexpr double kPi = 3.14159265358979323846;

// int_{-1}^{1} f(t, 1 - t, 1 + t) dt by tanh-sinh quadrature (step 1/128,
// |tau| <= 6.5), the distances to the ends computed without cancellation.
template <class F>
double tanh_sinh(F f) {
  const double h = 1.0 / 128.0;
  double sum = 0.0;
  for (int k = -832; k <= 832; ++k) {
    const double tau = k * h, u = 0.5 * kPi * std::sinh(tau);
    const double om = 2.0 / (1.0 + std::exp(2.0 * u));   // 1 - t
    const double op = 2.0 / (1.0 + std::exp(-2.0 * u));  // 1 + t
    const double t = std::tanh(u);
    const double c = std::cosh(u);
    const double wt = 0.5 * kPi * std::cosh(tau) / (c * c);
    if (!(om > 0.0) || !(op > 0.0) || wt == 0.0) continue;
    sum += wt * f(t, om, op);
  }
  return h * sum;
}

double jac(int n, double a, double b, double x) {
  double p = 0.0;
  mp::jacobi_p(n, a, b, x, &p);
  return p;
}
}  // namespace

TEST(JacobiFlat, CauchyIdentityConstantIsOneHalf) {
  // (1/pi) PV int w P_n/(t - x) dt = cot(pi a) w P_n(x) - (1/2)/sin(pi a)
  // P_{n-1}^(-a,-b)(x) for a + b = -1 (n = 0: the cot term alone), by
  // quadrature: PV int w P_n/(t - x) = int [w(t) P_n(t) - w(x) P_n(x)]/(t - x)
  // + w(x) P_n(x) ln((1 - x)/(1 + x)).
  for (double a : {-0.5, -0.3, -0.81}) {
    const double b = -1.0 - a;
    for (int n : {0, 1, 2, 5}) {
      for (double x : {-0.7, 0.05, 0.6}) {
        const double wx = std::pow(1.0 - x, a) * std::pow(1.0 + x, b);
        const double fx = wx * jac(n, a, b, x);
        const double pv = tanh_sinh([&](double t, double om, double op) {
          return (std::pow(om, a) * std::pow(op, b) * jac(n, a, b, t) - fx) / (t - x);
        });
        const double quadrature = (pv + fx * std::log((1.0 - x) / (1.0 + x))) / kPi;
        double closed = std::cos(kPi * a) / std::sin(kPi * a) * fx;
        if (n > 0) closed -= 0.5 / std::sin(kPi * a) * jac(n - 1, -a, -b, x);
        EXPECT_NEAR(quadrature, closed, 1e-9 * (1.0 + std::fabs(closed)))
            << "a = " << a << " n = " << n << " x = " << x;
        Eigen::VectorXd c = Eigen::VectorXd::Zero(n + 1);
        c(n) = 1.0;
        const mp::JacobiSeries s(a, b, c);
        EXPECT_NEAR(s.cauchy(x), quadrature, 1e-9 * (1.0 + std::fabs(closed)));
      }
    }
  }
}

TEST(JacobiFlat, CauchyOffTheCutMatchesQuadrature) {
  // Outside the face the integral is regular: the near-cut closed form
  // (|x| < 1.2), the far rule and the complex form against quadrature.
  const double a = -0.27, b = -0.73;
  Eigen::VectorXd c(4);
  c << 1.0, -0.4, 0.2, 0.05;
  const mp::JacobiSeries s(a, b, c);
  for (double x : {1.0001, 1.05, 1.19, 1.21, 2.5, -1.02, -1.3, -9.0}) {
    const double q = tanh_sinh([&](double t, double om, double op) {
                       return std::pow(om, a) * std::pow(op, b) * s.g(t) / (t - x);
                     }) /
                     kPi;
    EXPECT_NEAR(s.cauchy(x), q, 1e-9 * (1.0 + std::fabs(q))) << x;
    EXPECT_NEAR(s.cauchy_upper({x, 0.0}).real(), q, 1e-9 * (1.0 + std::fabs(q))) << x;
  }
  // Off the axis: Im z = 0.3, against quadrature of the complex integrand.
  for (double x : {-0.5, 0.2, 0.95}) {
    const std::complex<double> z(x, 0.3);
    double re = 0.0, im = 0.0;
    re = tanh_sinh([&](double t, double om, double op) {
           return (std::pow(om, a) * std::pow(op, b) * s.g(t) / (t - z)).real();
         }) /
         kPi;
    im = tanh_sinh([&](double t, double om, double op) {
           return (std::pow(om, a) * std::pow(op, b) * s.g(t) / (t - z)).imag();
         }) /
         kPi;
    const std::complex<double> got = s.cauchy_upper(z);
    EXPECT_NEAR(got.real(), re, 1e-9);
    EXPECT_NEAR(got.imag(), im, 1e-9);
  }
}

TEST(JacobiFlat, FarRuleValueAndDerivativeOfALongSeries) {
  // A 300-term series (closed form only within rho < 10^(5/300) ~ 1.04):
  // the far rule off the cut against quadrature of the complex integrand,
  // its derivative against a central difference of the value.
  const double a = -0.3, b = -0.7;
  Eigen::VectorXd c(300);
  for (Eigen::Index m = 0; m < c.size(); ++m)
    c(m) = std::cos(0.7 * static_cast<double>(m)) / (1.0 + static_cast<double>(m * m));
  const mp::JacobiSeries s(a, b, c);
  for (const std::complex<double> z :
       {std::complex<double>(0.2, 0.4), std::complex<double>(-0.9, 0.15),
        std::complex<double>(1.3, 0.05), std::complex<double>(-4.0, 2.0)}) {
    const std::complex<double> got = s.cauchy_upper(z);
    const double re = tanh_sinh([&](double t, double om, double op) {
                        return (std::pow(om, a) * std::pow(op, b) * s.g(t) / (t - z)).real();
                      }) /
                      kPi;
    const double im = tanh_sinh([&](double t, double om, double op) {
                        return (std::pow(om, a) * std::pow(op, b) * s.g(t) / (t - z)).imag();
                      }) /
                      kPi;
    EXPECT_NEAR(got.real(), re, 1e-9 * (1.0 + std::abs(got))) << z;
    EXPECT_NEAR(got.imag(), im, 1e-9 * (1.0 + std::abs(got))) << z;
    std::complex<double> der;
    // The same value with it (its loop groups the products differently).
    EXPECT_NEAR(std::abs(s.cauchy_upper(z, &der) - got), 0.0, 1e-14 * std::abs(got)) << z;
    const double h = 1e-5;
    const std::complex<double> fd = (s.cauchy_upper(z + h) - s.cauchy_upper(z - h)) / (2.0 * h);
    EXPECT_NEAR(std::abs(der - fd), 0.0, 1e-7 * (1.0 + std::abs(der))) << z;
  }
}

TEST(JacobiFlat, HalfIsFirstKindGaussChebyshev) {
  // alpha = beta = -1/2: r_i = cos((2i - 1) pi/(2N)), W_i/pi = 1/N, s_k = cos(k pi/N).
  for (int n : {2, 7, 24}) {
    const mp::ChebyshevNodes nd = mp::jacobi_flat_nodes(n, -0.5, -0.5);
    ASSERT_EQ(nd.r.size(), n);
    ASSERT_EQ(nd.s.size(), n - 1);
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(nd.r(i), std::cos((2 * i + 1) * kPi / (2.0 * n)), 1e-14);
      EXPECT_NEAR(nd.w(i), 1.0 / n, 1e-14);
    }
    for (int k = 0; k < n - 1; ++k) EXPECT_NEAR(nd.s(k), std::cos((k + 1) * kPi / n), 1e-14);
  }
}

TEST(JacobiFlat, MomentsAreTheBetaIntegrals) {
  const double a = -0.35, b = -0.65;
  // int w = Gamma(1 + a) Gamma(1 + b) (a + b = -1); int w r = m0 (b - a).
  const double m0 = std::tgamma(1.0 + a) * std::tgamma(1.0 + b);
  const mp::JacobiSeries one(a, b, Eigen::VectorXd::Ones(1));
  EXPECT_NEAR(one.moment0(), m0, 1e-14 * m0);
  EXPECT_NEAR(one.moment1(), m0 * (b - a), 1e-13);
  Eigen::VectorXd c(3);
  c << 0.7, 0.3, -0.2;
  const mp::JacobiSeries s(a, b, c);
  const double q0 = tanh_sinh(
      [&](double t, double om, double op) { return std::pow(om, a) * std::pow(op, b) * s.g(t); });
  const double q1 = tanh_sinh([&](double t, double om, double op) {
    return std::pow(om, a) * std::pow(op, b) * s.g(t) * t;
  });
  EXPECT_NEAR(s.moment0(), q0, 1e-11);
  EXPECT_NEAR(s.moment1(), q1, 1e-11);
  // The transform at omega = 0 is the moment; at omega = 3 the quadrature's.
  const mp::JacobiTransform tr(s, 10.0);
  EXPECT_NEAR(tr(0.0).real(), q0, 1e-11);
  const double c3 = tanh_sinh([&](double t, double om, double op) {
    return std::pow(om, a) * std::pow(op, b) * s.g(t) * std::cos(3.0 * t);
  });
  const double s3 = -tanh_sinh([&](double t, double om, double op) {
    return std::pow(om, a) * std::pow(op, b) * s.g(t) * std::sin(3.0 * t);
  });
  EXPECT_NEAR(tr(3.0).real(), c3, 1e-11);
  EXPECT_NEAR(tr(3.0).imag(), s3, 1e-11);
}

TEST(JacobiFlat, DiscreteRuleAtTheCompanionZerosAndInterpolation) {
  // (1/pi) sum W_i g(r_i)/(r_i - s_k) = -cot(pi a) w g(s_k) + cauchy(s_k) for
  // g of degree < N at the N - 1 zeros s_k of P_{N-1}^(-a,-b).
  const double a = -0.22, b = -0.78;
  const int n = 9;
  const mp::ChebyshevNodes nd = mp::jacobi_flat_nodes(n, a, b);
  Eigen::VectorXd c(6);
  c << 0.3, -1.0, 0.25, 0.0, 0.1, -0.05;
  const mp::JacobiSeries s(a, b, c);
  const double fphi = -std::cos(kPi * a) / std::sin(kPi * a);
  for (int k = 0; k < n - 1; ++k) {
    double lhs = 0.0;
    for (int i = 0; i < n; ++i) lhs += nd.w(i) * s.g(nd.r(i)) / (nd.r(i) - nd.s(k));
    EXPECT_NEAR(lhs, fphi * s.density(nd.s(k)) + s.cauchy(nd.s(k)), 1e-12);
  }
  Eigen::VectorXd g(n);
  for (int i = 0; i < n; ++i) g(i) = s.g(nd.r(i));
  const mp::JacobiSeries back = mp::JacobiSeries::from_nodes(a, b, nd.r, g);
  EXPECT_TRUE(back.singular());
  for (double r : {-1.0, -0.4, 0.5, 1.0}) EXPECT_NEAR(back.g(r), s.g(r), 1e-13);
  // Bad exponents are refused.
  EXPECT_THROW(mp::JacobiSeries(-0.3, -0.6, c), std::invalid_argument);
  EXPECT_THROW(mp::jacobi_flat_nodes(8, 0.3, -1.3), std::invalid_argument);
}

// The regular kernel k1: table vs quadrature vs an independent integration.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <vector>

#include "movingpunch/kernel.hpp"

using namespace movingpunch;

namespace {
// Independent composite 20-point Gauss-Legendre integration on [0, 40] of
// f(t, M1(t)), M1 the closed-form static rigid-base response (4000 panels).
template <class F>
double static_rigid_integral(double nu, const F& f) {
  static const double x[10] = {0.0765265211334973, 0.2277858511416451, 0.3737060887154195,
                               0.5108670019508271, 0.6360536807265150, 0.7463319064601508,
                               0.8391169718222188, 0.9122344282513259, 0.9639719272779138,
                               0.9931285991850949};
  static const double w[10] = {0.1527533871307258, 0.1491729864726037, 0.1420961093183820,
                               0.1316886384491766, 0.1181945319615184, 0.1019301198172404,
                               0.0832767415767048, 0.0626720483341091, 0.0406014298003869,
                               0.0176140071391521};
  const double phi1 = 1.0 - nu;
  double sum = 0.0;
  const int panels = 4000;
  const double hw = 40.0 / panels / 2.0;
  for (int p = 0; p < panels; ++p) {
    const double c = (2 * p + 1) * hw;
    for (int j = 0; j < 10; ++j)
      for (double sg : {-1.0, 1.0}) {
        const double t = c + sg * hw * x[j];
        const double m1 = phi1 * (std::cosh(2 * t) - 1.0) / (std::sinh(2 * t) + 2 * t);
        sum += hw * w[j] * f(t, m1);
      }
  }
  return sum;
}

// k1(u) = int_0^40 (M1 - phi1) sin(alpha u) / phi1.
double static_rigid_k1(double u, double nu) {
  const double phi1 = 1.0 - nu;
  return static_rigid_integral(nu,
                               [&](double t, double m1) { return (m1 - phi1) * std::sin(t * u); }) /
         phi1;
}

// The smooth part of the Green's function, G_s(u) = int_0^40 [M1 - phi1 (1 -
// e^-t)]/t cos(t u) dt (beyond 40, phi1 E1(40) < 1e-19).
double static_rigid_greens_smooth(double u, double nu) {
  const double phi1 = 1.0 - nu;
  return static_rigid_integral(
      nu, [&](double t, double m1) { return (m1 + phi1 * std::expm1(-t)) / t * std::cos(t * u); });
}
}  // namespace

// The displacement's Green's function from the table (greens_zero and the
// antiderivative K1 of k1): G_s(u) = G_s(0) - phi1 K1(u) - (phi1/2) ln(1 +
// u^2) against the independent integration of its cosine transform.
TEST(Kernel, TabulatedGreensFunctionMatchesIndependentIntegration) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nu = 0.2, phi1 = 1.0 - nu;
  const KernelK1 k(LayerModel(0.0, inf, nu), 1e-12, 3.0);
  ASSERT_TRUE(k.greens_tabulated());
  EXPECT_NEAR(k.greens_zero(), static_rigid_greens_smooth(0.0, nu), 1e-11);
  std::vector<double> u{0.0, 0.05, 0.4, 1.0, 2.2, -2.2, 3.0, -0.7, 1.3};
  std::vector<double> K(u.size());
  k.k1_integrals(u.data(), K.data(), u.size());  // four chains and a remainder
  for (std::size_t i = 0; i < u.size(); ++i) {
    const double g = k.greens_zero() - phi1 * (K[i] + 0.5 * std::log1p(u[i] * u[i]));
    EXPECT_NEAR(g, static_rigid_greens_smooth(u[i], nu), 3e-11) << "u " << u[i];
  }
  EXPECT_NEAR(K[0], 0.0, 1e-15);  // K1(0) = 0 up to the series' round-off
  EXPECT_EQ(K[4], K[5]);          // even
  // K1' = k1: a central difference of the antiderivative is the table.
  for (double v : {0.3, 1.7}) {
    const double h = 1e-4;
    std::array<double, 2> uu{v - h, v + h}, kk{};
    k.k1_integrals(uu.data(), kk.data(), 2);
    EXPECT_NEAR((kk[1] - kk[0]) / (2 * h), k(v), 1e-8) << v;
  }
  // A piecewise table is not tabulated (the solution reads the Filon route).
  const auto spring = make_medium(homogeneous_medium(1.0, 0.2), 0.3);
  EXPECT_FALSE(KernelK1(spring, 1e-10, 40.0).greens_tabulated());
  EXPECT_TRUE(KernelK1(spring, 1e-10, 2.0).greens_tabulated());
}

TEST(Kernel, StaticRigidBaseMatchesIndependentIntegration) {
  const double inf = std::numeric_limits<double>::infinity();
  const LayerModel m(0.0, inf, 0.2);
  const KernelK1 k(m, 1e-12, 3.0);
  for (double u : {0.05, 0.4, 1.0, 2.2, 3.0})
    EXPECT_NEAR(k(u), static_rigid_k1(u, 0.2), 1e-10) << "u " << u;
}

TEST(Kernel, TableMatchesDirectQuadratureAndIsOdd) {
  for (double kw : {0.1, 1.0, 10.0}) {
    const LayerModel m(0.2, kw, 0.2);
    const KernelK1 k(m, 1e-11, 2.0);
    for (double u : {0.0, 0.1, 0.77, 1.5, 2.0}) {
      EXPECT_NEAR(k(u), k.direct(u), 1e-11 * (1 + std::fabs(k.direct(u))));
      EXPECT_NEAR(k(-u), -k(u), 1e-13);
    }
  }
}

TEST(Kernel, ResolvesTheSharpPeakNearTheCriticalSpeed) {
  // vstar just below V*_cr for kw = 0.1: the low-alpha peak is sharp but the
  // quadrature converges: halving the tolerance changes nothing beyond it.
  const LayerModel m(0.2475216 * (1 - 1e-4), 0.1, 0.2);
  const KernelK1 k1(m, 1e-9, 4.0), k2(m, 1e-12, 4.0);
  for (double u : {0.3, 1.0, 3.5}) EXPECT_NEAR(k1(u), k2(u), 1e-8 * (1 + std::fabs(k2(u))));
  // The estimated error is small relative to the integral of |M1 - phi1|/phi1,
  // which the peak makes large (round-off grows with the resonance).
  const AlphaQuadrature& q = k2.quadrature();
  double scale = 0.0;
  for (std::size_t i = 0; i < q.alpha.size(); ++i)
    scale += q.weight[i] * std::fabs(q.m1[i] - m.phi1()) / m.phi1();
  EXPECT_GT(scale, 100.0);
  EXPECT_LT(q.error_estimate, 1e-8 * scale);
}

TEST(Filon, ExactFourierIntegralsOfPolynomialsAndSmoothFunctions) {
  // g(alpha) = exp(-alpha) on the quadrature's panels: int_0^A e^{-alpha} e^{i alpha x}
  // = (1 - e^{-(1 - i x) A}) / (1 - i x), exactly, for small and huge x.
  const AlphaQuadrature q =
      build_alpha_quadrature(*make_medium(homogeneous_medium(1.0, 0.2), 0.2), 1e-10, 1.0);
  const FilonIntegrator f(q);
  std::vector<double> g(q.alpha.size());
  for (std::size_t i = 0; i < g.size(); ++i) g[i] = std::exp(-q.alpha[i]);
  const std::vector<double> c = f.coefficients(g);
  const double A = q.panel_centre.back() + q.panel_half.back();
  std::vector<std::complex<double>> K;
  for (double x : {0.0, 0.3, 7.0, 150.0, 1e4, 1e7, -3.0}) {
    f.weights(x, K);
    const std::complex<double> got = FilonIntegrator::apply(K, c);
    const std::complex<double> s(1.0, -x);
    const std::complex<double> want = (1.0 - std::exp(-s * A)) / s;
    EXPECT_NEAR(got.real(), want.real(), 1e-12) << "x " << x;
    EXPECT_NEAR(got.imag(), want.imag(), 1e-12) << "x " << x;
    // The k1 tables' fused sum is the same arithmetic, bit for bit.
    const std::complex<double> fused = f.weights_applied(x, c);
    EXPECT_EQ(fused.real(), got.real()) << "x " << x;
    EXPECT_EQ(fused.imag(), got.imag()) << "x " << x;
  }
}

TEST(Filon, SphericalBesselAgainstTheLibraryAndClosedForms) {
  // Through the Filon weights of a single panel [-h, h] with c = 0: K(k) = 2 h i^k j_k(h x).
  AlphaQuadrature q;
  q.panel_centre = {0.0};
  q.panel_half = {1.0};
  const FilonIntegrator f(q);
  std::vector<std::complex<double>> K;
  for (double z : {1e-9, 1e-3, 0.5, 3.0, 9.42477796076938, 14.9, 15.1, 40.0, 1e5}) {
    f.weights(z, K);
    for (unsigned k = 0; k < 15; ++k) {
      const std::complex<double> ik = std::pow(std::complex<double>(0, 1), static_cast<int>(k));
      const double jk = (K[k] / (2.0 * ik)).real();
      const double want = z < 1e3 ? std::sph_bessel(k, z) : (k == 0 ? std::sin(z) / z : jk);
      EXPECT_NEAR(jk, want, 1e-13 * (1 + std::fabs(want))) << "z " << z << " k " << k;
    }
  }
}

TEST(Kernel, LongTableIsPiecewiseAndMatchesDirectQuadrature) {
  // 0.993 V*_cr of a very stiff foundation on a table of range 210: k1
  // oscillates thousands of times. It is held piecewise (one evaluation costs
  // 25 terms, not 16384) and must match the direct Filon sum everywhere.
  const LayerModel m(0.8539047076137971, 6504951049.121735, 0.3);
  const KernelK1 k(m, 1e-10, 210.0);
  ASSERT_TRUE(k.piecewise());
  double scale = 0.0;
  for (int i = 0; i <= 400; ++i) scale = std::max(scale, std::fabs(k.direct(0.5 * i)));
  for (int i = 0; i <= 700; ++i) {
    const double u = 210.0 * std::pow(i / 700.0, 1.3) * (i % 2 == 0 ? 1.0 : -1.0);
    EXPECT_NEAR(k(u), k.direct(u), 1e-12 * std::max(1.0, scale)) << u;
  }
  // A short table keeps the global series (the default solves).
  const KernelK1 short_table(LayerModel(0.2, 1.0, 0.2), 1e-10, 1.6);
  EXPECT_FALSE(short_table.piecewise());
}

// k1(u) + k1(v) evaluated together (the collocation's entries) equals the two
// evaluations, for the global odd series and for a piecewise table; and the
// odd-term Clenshaw recurrence matches the direct quadrature.
TEST(Kernel, PairSumMatchesTwoEvaluations) {
  const KernelK1 global(LayerModel(0.2, 0.1, 0.2), 1e-10, 5.0);
  ASSERT_FALSE(global.piecewise());
  const KernelK1 pieces(LayerModel(0.8539047076137971, 6504951049.121735, 0.3), 1e-10, 210.0);
  ASSERT_TRUE(pieces.piecewise());
  for (const KernelK1* k : {&global, &pieces}) {
    const double L = k->range();
    for (int i = 0; i <= 200; ++i) {
      const double u = L * std::sin(0.37 * i), v = -L * std::cos(0.11 * i) * 0.999;
      EXPECT_NEAR(k->sum(u, v), (*k)(u) + (*k)(v),
                  1e-14 * (1.0 + std::fabs((*k)(u)) + std::fabs((*k)(v))));
    }
  }
  // sum_many: sum() at every pair (interleaved recurrences, the same
  // arithmetic), for any count (blocks and the rest).
  for (const KernelK1* k : {&global, &pieces}) {
    const double L = k->range();
    for (std::size_t n : {0u, 1u, 3u, 4u, 9u, 64u}) {
      std::vector<double> u(n), v(n), out(n, -1.0);
      for (std::size_t i = 0; i < n; ++i) {
        u[i] = L * std::sin(0.37 * static_cast<double>(i) + 0.1);
        v[i] = -L * 0.999 * std::cos(0.11 * static_cast<double>(i));
      }
      k->sum_many(u.data(), v.data(), out.data(), n);
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(out[i], k->sum(u[i], v[i])) << n << " " << i;
    }
  }
  for (int i = -20; i <= 20; ++i) {
    const double u = 5.0 * i / 20.0;
    EXPECT_NEAR(global(u), global.direct(u), 1e-10) << u;
    EXPECT_DOUBLE_EQ(global(-u), -global(u));
  }
}

// A longer table grown from a shorter one of the same medium (the cache's
// growth) reuses its quadrature when the panels it needs are the same, and
// is then the table built afresh, bit for bit; a range that needs narrower
// panels builds its own.
TEST(Kernel, GrownTableReusesTheQuadratureOnlyWhenItIsTheSame) {
  const auto medium = make_medium(homogeneous_medium(1.0, 0.2), 0.3);
  const KernelK1 shorter(medium, 1e-10, 1.5);
  const KernelK1 fresh(medium, 1e-10, 6.0);
  const KernelK1 grown(medium, 1e-10, 6.0, &shorter);
  EXPECT_EQ(grown.quadrature().alpha, fresh.quadrature().alpha);
  EXPECT_EQ(&grown.filon(), &shorter.filon());  // shared, not rebuilt
  for (int i = -12; i <= 12; ++i) {
    const double u = 6.0 * i / 12.0;
    EXPECT_EQ(grown(u), fresh(u)) << u;
  }
  // range 40: panels of width 2/(40/4) = 0.2 < 1: its own quadrature.
  const KernelK1 wide(medium, 1e-10, 40.0, &shorter);
  EXPECT_NE(&wide.filon(), &shorter.filon());
  EXPECT_GT(wide.quadrature().alpha.size(), shorter.quadrature().alpha.size());
  // Another medium's table is never reused.
  const KernelK1 other(make_medium(homogeneous_medium(2.0, 0.2), 0.3), 1e-10, 6.0, &shorter);
  EXPECT_NE(&other.filon(), &shorter.filon());
}

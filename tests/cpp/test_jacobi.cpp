// Gauss-Jacobi collocation (cpp/src/jacobi.cpp) against independent anchors:
// Gauss-Chebyshev at alpha = 1/2, polynomial exactness, brute-force
// quadrature of the Cauchy integral, the discrete rule at the companion zeros.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <tuple>
#include <vector>

#include "movingpunch/collocation.hpp"
#include "movingpunch/jacobi.hpp"

namespace mp = movingpunch;

namespace {
constexpr double kPi = 3.14159265358979323846;

// int_{-1}^{1} f by composite Gauss-Legendre after t = cos(theta) (smooths the
// end behaviour of the Jacobi weight): 4000 midpoint panels in theta.
template <class F>
double by_theta(F f) {
  const int m = 20000;
  double sum = 0.0;
  for (int j = 0; j < m; ++j) {
    const double th = kPi * (j + 0.5) / m;
    sum += f(std::cos(th)) * std::sin(th) * kPi / m;
  }
  return sum;
}
}  // namespace

TEST(Jacobi, HalfIsGaussChebyshev) {
  for (int n : {2, 8, 24, 64}) {
    const mp::ChebyshevNodes c = mp::chebyshev_nodes(n);
    const mp::ChebyshevNodes j = mp::jacobi_collocation_nodes(n, 0.5);
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(j.r(i), c.r(i), 1e-14);
      EXPECT_NEAR(j.w(i), c.w(i), 1e-14);
    }
    for (int k = 0; k <= n; ++k) EXPECT_NEAR(j.s(k), c.s(k), 1e-14);
  }
}

TEST(Jacobi, RuleIsExactForPolynomials) {
  // int (1-x)^a (1+x)^b x^k against the Beta-function closed form for k = 0, 1, 2.
  const double a = 0.3, b = 0.7;
  const mp::JacobiRule r = mp::gauss_jacobi(12, a, b);
  auto mom = [&](int k) {
    double s = 0.0;
    for (int i = 0; i < 12; ++i) s += r.w(i) * std::pow(r.x(i), k);
    return s;
  };
  const double m0 = std::exp((a + b + 1) * std::log(2.0) + std::lgamma(a + 1) + std::lgamma(b + 1) -
                             std::lgamma(a + b + 2));
  EXPECT_NEAR(mom(0), m0, 1e-14 * m0);
  EXPECT_NEAR(mom(1), m0 * (b - a) / (a + b + 2), 1e-14);
  // E[x^2] for the Beta-distributed (1 + x)/2.
  const double mu = (b + 1) / (a + b + 2),
               var = (a + 1) * (b + 1) / ((a + b + 2) * (a + b + 2) * (a + b + 3));
  EXPECT_NEAR(mom(2), m0 * (4 * (var + mu * mu) - 4 * mu + 1), 1e-14);
}

TEST(Jacobi, CauchyIntegralMatchesBruteForce) {
  // (1/pi) PV int w g/(t - x) with g = 1 + 0.5 P_1 - 0.2 P_3 at points inside,
  // near and far outside the cut, against a subtracted singularity by quadrature.
  const double a = 0.62;
  Eigen::VectorXd c(4);
  c << 1.0, 0.5, 0.0, -0.2;
  const mp::JacobiSeries s(a, c);
  for (double x : {-0.93, -0.2, 0.41, 0.999, 1.05, 1.19, 1.21, 3.0, -1.1, -7.0}) {
    const double fx = std::fabs(x) < 1.0 ? s.density(x) : 0.0;
    const double pv = by_theta([&](double t) { return (s.density(t) - fx) / (t - x); });
    // f(x) PV int dt/(t - x) = f(x) ln((1 - x)/(1 + x)).
    const double rest = std::fabs(x) < 1.0 ? fx * std::log((1.0 - x) / (1.0 + x)) : 0.0;
    EXPECT_NEAR(s.cauchy(x), (pv + rest) / kPi, 2e-7) << x;
  }
}

TEST(Jacobi, DiscreteRuleAtTheCompanionZeros) {
  // (1/pi) sum W_i g(r_i)/(r_i - s_k) = f Phi w g + (1/pi) PV int w g/(t - s_k)
  // with cot(pi alpha) = -f Phi, for g of degree < N.
  const double a = 0.37;
  const int n = 10;
  const mp::ChebyshevNodes nd = mp::jacobi_collocation_nodes(n, a);
  Eigen::VectorXd c(5);
  c << 0.3, -1.0, 0.25, 0.0, 0.1;
  const mp::JacobiSeries s(a, c);
  const double fphi = -std::cos(kPi * a) / std::sin(kPi * a);
  for (int k = 0; k <= n; ++k) {
    double lhs = 0.0;
    for (int i = 0; i < n; ++i) lhs += nd.w(i) * s.g(nd.r(i)) / (nd.r(i) - nd.s(k));
    EXPECT_NEAR(lhs, fphi * s.density(nd.s(k)) + s.cauchy(nd.s(k)), 1e-12);
  }
}

TEST(Jacobi, CollocationNodesAreKeptPerSizeAndExponent) {
  // The nodes are built once per (n, alpha) and kept: a second call gives
  // the same nodes bit for bit, another exponent or size its own (each
  // the zeros of its own P_n), however the calls interleave.
  for (int pass = 0; pass < 2; ++pass)
    for (double a : {0.37, 0.37 + 1e-15, 0.6})
      for (int n : {10, 12}) {
        const mp::ChebyshevNodes nd = mp::jacobi_collocation_nodes(n, a);
        ASSERT_EQ(nd.r.size(), n);
        ASSERT_EQ(nd.s.size(), n + 1);
        for (int i = 0; i < n; ++i) {
          double p = 0.0, dp = 0.0;
          mp::jacobi_p(n, a, 1.0 - a, nd.r(i), &p, &dp);
          EXPECT_LT(std::fabs(p), 1e-12 * std::fabs(dp)) << a << " " << n << " " << i;
        }
        const mp::ChebyshevNodes again = mp::jacobi_collocation_nodes(n, a);
        EXPECT_EQ(again.r, nd.r);
        EXPECT_EQ(again.s, nd.s);
        EXPECT_EQ(again.w, nd.w);
      }
  const mp::ChebyshevNodes f = mp::jacobi_flat_nodes(10, -0.4, -0.6);
  EXPECT_EQ(f.s.size(), 9);  // the flat punch's (its own kind in the cache)
  EXPECT_NE(mp::jacobi_collocation_nodes(10, 0.6).r, f.r);
}

TEST(Jacobi, TransformMatchesQuadrature) {
  Eigen::VectorXd c(3);
  c << 1.0, 0.4, -0.3;
  const mp::JacobiSeries s(0.7, c);
  const mp::JacobiTransform tr(s, 60.0);
  for (double om : {0.0, 1.0, 7.5, 59.0}) {
    const double re = by_theta([&](double t) { return s.density(t) * std::cos(om * t); });
    const double im = -by_theta([&](double t) { return s.density(t) * std::sin(om * t); });
    EXPECT_NEAR(tr(om).real(), re, 1e-7);
    EXPECT_NEAR(tr(om).imag(), im, 1e-7);
  }
  EXPECT_NEAR(s.moment0(), tr(0.0).real(), 1e-12);
}

TEST(Jacobi, SeriesFromNodesInterpolates) {
  const double a = 0.45;
  const mp::ChebyshevNodes nd = mp::jacobi_collocation_nodes(8, a);
  Eigen::VectorXd g(8);
  for (int i = 0; i < 8; ++i) g(i) = 1.0 + nd.r(i) - 2.0 * std::pow(nd.r(i), 5);
  const mp::JacobiSeries s = mp::JacobiSeries::from_nodes(a, nd.r, g);
  for (double r : {-0.9, 0.0, 0.33, 0.8})
    EXPECT_NEAR(s.g(r), 1.0 + r - 2.0 * std::pow(r, 5), 1e-13);
}

TEST(Jacobi, ExponentsAndCoupling) {
  const mp::EndExponents e = mp::end_exponents(0.3, 0.375);
  EXPECT_NEAR(1.0 / std::tan(kPi * e.back), 0.3 * 0.375, 1e-14);
  EXPECT_NEAR(e.back + e.front, 1.0, 1e-15);
  const mp::TangentialHalfPlane t0 = mp::tangential_half_plane(mp::wave_constants(0.0, 0.2));
  EXPECT_NEAR(t0.Phi, 0.6 / 1.6, 1e-15);  // (1 - 2 nu)/(2 (1 - nu))
  EXPECT_NEAR(t0.Wq, 0.3, 1e-15);         // (1 - 2 nu)/2
  EXPECT_NEAR(t0.Uq, 0.8, 1e-15);         // c2/(2 (c2 - 1)), c2 = 8/3
}

TEST(Jacobi, CachedRulesOutliveTheCachesClearing) {
  // A rule held while other rules fill the cache past its capacity (256: it
  // is then emptied) stays valid: the profile projections hold one rule while
  // fetching the norms' (a long fuzz run once crashed on a dangling one).
  const auto held = mp::cached_gauss_jacobi(40, 0.3, -0.3);
  for (int k = 0; k < 300; ++k) mp::cached_gauss_jacobi(6 + k % 7, 0.1 + 1e-3 * k, 0.2);
  const mp::JacobiRule fresh = mp::gauss_jacobi(40, 0.3, -0.3);
  ASSERT_EQ(held->x.size(), fresh.x.size());
  for (Eigen::Index i = 0; i < fresh.x.size(); ++i) {
    EXPECT_EQ(held->x(i), fresh.x(i));
    EXPECT_EQ(held->w(i), fresh.w(i));
  }
  // And the cache still answers (a new entry after the clearing).
  const auto again = mp::cached_gauss_jacobi(40, 0.3, -0.3);
  EXPECT_EQ(again->x(0), fresh.x(0));
}

// The moments of P_m^(a, b) against its weight over [s0, 1] and [-1, s0]
// (Rodrigues' formula and the recurrence of s P_m) against brute force: a
// 400-node Gauss-Jacobi rule on the piece carrying its end's singular factor,
// P_m by the three-term recurrence (jacobi_p) at each node. That rule's own
// weights are good to about 2e-12 at 400 nodes (checked against the
// incomplete beta function below), hence the tolerance.
TEST(Jacobi, MomentsOverAPieceMatchBruteForce) {
  struct Case {
    double a, b;
  };
  for (const Case cs : {Case{-0.539284, -0.460716}, Case{0.539284, 0.460716}, Case{0.3, -0.7},
                        Case{-0.5, -0.5}, Case{0.5, 0.5}}) {
    for (double s0 : {-0.97, -0.48, 0.0, 0.31, 0.9}) {
      const int count = 41;
      const mp::JacobiMoments up = mp::jacobi_upper_moments(cs.a, cs.b, s0, count);
      const mp::JacobiMoments lo = mp::jacobi_lower_moments(cs.a, cs.b, s0, count);
      // [s0, 1]: s = s0 + L (1 + x)/2, (1 - s)^a = (L/2)^a (1 - x)^a.
      const mp::JacobiRule ru = mp::gauss_jacobi(400, cs.a, 0.0);
      const mp::JacobiRule rl = mp::gauss_jacobi(400, 0.0, cs.b);
      for (int m = 0; m < count; ++m) {
        double iu = 0, ju = 0, il = 0, jl = 0;
        const double L = 1.0 - s0, Ll = 1.0 + s0;
        for (int i = 0; i < 400; ++i) {
          const double s = s0 + L * 0.5 * (1.0 + ru.x(i));
          double p;
          mp::jacobi_p(m, cs.a, cs.b, s, &p);
          const double wt = ru.w(i) * 0.5 * L * std::pow(0.5 * L, cs.a) * std::pow(1.0 + s, cs.b);
          iu += wt * p;
          ju += wt * p * s;
          const double t = -1.0 + Ll * 0.5 * (1.0 + rl.x(i));
          mp::jacobi_p(m, cs.a, cs.b, t, &p);
          const double wl = rl.w(i) * 0.5 * Ll * std::pow(0.5 * Ll, cs.b) * std::pow(1.0 - t, cs.a);
          il += wl * p;
          jl += wl * p * t;
        }
        const double scale = 1.0 + std::sqrt(mp::jacobi_norm(m, cs.a, cs.b));
        const std::size_t k = static_cast<std::size_t>(m);
        EXPECT_NEAR(up.I[k], iu, 4e-12 * scale)
            << cs.a << " " << cs.b << " s0 " << s0 << " m " << m;
        EXPECT_NEAR(up.J[k], ju, 4e-12 * scale)
            << cs.a << " " << cs.b << " s0 " << s0 << " m " << m;
        EXPECT_NEAR(lo.I[k], il, 4e-12 * scale)
            << cs.a << " " << cs.b << " s0 " << s0 << " m " << m;
        EXPECT_NEAR(lo.J[k], jl, 4e-12 * scale)
            << cs.a << " " << cs.b << " s0 " << s0 << " m " << m;
      }
    }
  }
  // I_0 against the regularised incomplete beta function (t = (1 + s)/2:
  // int_{s0}^{1} w = 2^(a+b+1) B(b+1, a+1) (1 - I_t0(b+1, a+1))), computed
  // aside to 40 digits (mpmath.betainc, a = 0.3, b = -0.7).
  EXPECT_NEAR(mp::jacobi_upper_moments(0.3, -0.7, 0.9, 1).I[0], 0.02421595959261280649, 1e-15);
  EXPECT_NEAR(mp::jacobi_upper_moments(0.3, -0.7, 0.31, 1).I[0], 0.34300065891050121982, 1e-14);
  EXPECT_NEAR(mp::jacobi_upper_moments(0.3, -0.7, 0.0, 1).I[0], 0.6105548773144193644, 2e-14);
  EXPECT_NEAR(mp::jacobi_lower_moments(0.3, -0.7, -0.48, 1).I[0], 3.3085809416188511727, 1e-13);
  // The whole interval: orthogonality (I_m = h_0 delta_m0) and the ends.
  const mp::JacobiMoments all = mp::jacobi_upper_moments(0.3, -0.7, -1.0, 5);
  EXPECT_NEAR(all.I[0], mp::jacobi_norm(0, 0.3, -0.7), 1e-14);
  for (int m = 1; m < 5; ++m) EXPECT_EQ(all.I[static_cast<std::size_t>(m)], 0.0);
  EXPECT_EQ(mp::jacobi_upper_moments(0.3, -0.7, 1.0, 5).I[0], 0.0);
  EXPECT_THROW(mp::jacobi_upper_moments(-1.0, 0.0, 0.0, 5), std::invalid_argument);
  EXPECT_THROW(mp::jacobi_lower_moments(0.0, 0.0, std::nan(""), 5), std::invalid_argument);
}

// A long series (a profile's tail-extended one: a thousand terms falling like
// n^-2) evaluated eight points at a time (g_values), one point at a time (g)
// and by the textbook recurrence term by term (jacobi_p); the Cauchy integral
// on and off the cut against its closed form's ingredients summed by jacobi_p.
TEST(Jacobi, LongSeriesEvaluationsAgree) {
  const double alpha = 0.539284;
  const int n = 1024;
  Eigen::VectorXd c(n);
  for (int k = 0; k < n; ++k) c(k) = (k % 3 == 0 ? 1.0 : -0.7) / ((k + 1.0) * (k + 1.0));
  const mp::JacobiSeries s(alpha, c);
  std::vector<double> r;
  for (int j = 0; j <= 60; ++j) r.push_back(std::cos(kPi * j / 60.0));
  std::vector<double> gv(r.size());
  s.g_values(r.data(), static_cast<int>(r.size()), gv.data());
  for (std::size_t i = 0; i < r.size(); ++i) {
    double ref = 0.0;
    for (int k = 0; k < n; ++k) {
      double p;
      mp::jacobi_p(k, alpha, 1.0 - alpha, r[i], &p);
      ref += c(k) * p;
    }
    EXPECT_NEAR(gv[i], ref, 1e-12) << r[i];
    EXPECT_NEAR(s.g(r[i]), gv[i], 1e-14 * (1.0 + std::fabs(gv[i]))) << r[i];
  }
  // cauchy(x) inside: cot(pi a) w g - (2/sin(pi a)) sum c_n P_{n+1}^(-a,-b)(x).
  for (double x : {-0.93, -0.2, 0.41, 0.88}) {
    double poly = 0.0;
    for (int k = 0; k < n; ++k) {
      double p;
      mp::jacobi_p(k + 1, -alpha, alpha - 1.0, x, &p);
      poly += c(k) * p;
    }
    const double sa = std::sin(kPi * alpha);
    const double ref = std::cos(kPi * alpha) / sa * s.density(x) - 2.0 / sa * poly;
    EXPECT_NEAR(s.cauchy(x), ref, 1e-12) << x;
  }
}

// The transform of a long series keeps only the terms that reach |omega| <=
// omega_max (bounded by sqrt(h_0 h_m) omega^m/m!): against every term
// integrated by a rule of its own, exact for the whole series.
TEST(Jacobi, TruncatedTransformMatchesTheWholeSeries) {
  const double alpha = 0.6;
  const int n = 600;
  Eigen::VectorXd c(n);
  for (int k = 0; k < n; ++k) c(k) = std::cos(0.7 * k) / ((k + 1.0) * (k + 1.0));
  const mp::JacobiSeries s(alpha, c);
  const double omega_max = 40.0;
  const mp::JacobiTransform t(s, omega_max, &s);
  const mp::JacobiRule rule = mp::gauss_jacobi(n + 100, alpha, 1.0 - alpha);
  for (double om : {0.0, 0.3, 7.5, 22.0, 39.9}) {
    std::complex<double> ref = 0.0;
    for (Eigen::Index i = 0; i < rule.x.size(); ++i)
      ref += rule.w(i) * s.g(rule.x(i)) *
             std::complex<double>(std::cos(om * rule.x(i)), -std::sin(om * rule.x(i)));
    // (The reference's own round-off, 600-term recurrences at 700 nodes:
    // 3e-13 at omega = 0 against the exact c_0 h_0.)
    EXPECT_NEAR(std::abs(t(om) - ref), 0.0, 1e-12) << om;
    const auto both = t.both(om);
    EXPECT_NEAR(std::abs(both.first - ref), 0.0, 1e-12) << om;
    EXPECT_NEAR(std::abs(both.second - ref), 0.0, 1e-12) << om;
  }
  // Orthogonality: at omega = 0 the transform is c_0 h_0 (to the rule's
  // weights, good to about 2e-13 at a few hundred nodes).
  EXPECT_NEAR(t(0.0).real(), c(0) * mp::jacobi_norm(0, alpha, 1.0 - alpha), 5e-13);
  EXPECT_NEAR(t(0.0).imag(), 0.0, 1e-15);
}

// The transform's Chebyshev interpolant in omega against the direct sum on the
// same rule (no interpolant), at 200 frequencies across [0, omega_max] and at
// its ends; beyond omega_max both are the direct sum.
TEST(Jacobi, TransformInterpolantMatchesTheDirectSum) {
  for (double omega_max : {0.7, 13.0, 64.0, 180.0}) {
    Eigen::VectorXd c(30);
    for (int k = 0; k < 30; ++k) c(k) = std::sin(1.3 * k + 0.2) / (1.0 + k);
    const mp::JacobiSeries s(0.62, c);
    Eigen::VectorXd c2 = 0.5 * c;
    const mp::JacobiSeries s2(0.62, c2);
    const mp::JacobiTransform fast(s, omega_max, &s2);
    const mp::JacobiTransform direct(s, omega_max, &s2, false);
    const double scale = c.cwiseAbs().sum() * 2.0;
    for (int j = 0; j <= 200; ++j) {
      const double om = omega_max * j / 200.0 * (j % 7 == 3 ? 0.999 : 1.0);
      const auto f = fast.both(om), d = direct.both(om);
      EXPECT_LE(std::abs(f.first - d.first), 2e-14 * scale) << omega_max << " " << om;
      EXPECT_LE(std::abs(f.second - d.second), 2e-14 * scale) << omega_max << " " << om;
      EXPECT_LE(std::abs(fast(om) - f.first), 0.0);
    }
    EXPECT_EQ(fast(1.5 * omega_max), direct(1.5 * omega_max));
  }
}

TEST(Jacobi, LargeRulesAreTheZerosWithTheirWeights) {
  // gauss_jacobi evaluates P_n at several nodes together (and finds a large
  // rule's nodes by Newton from asymptotic guesses): its nodes are zeros of
  // P_n (a Newton step from each moves it by less than 1e-15), its weights are
  // cst/((1 - x^2) P_n'(x)^2) with jacobi_p's derivative bit for bit, and the rule
  // is exact for a high-degree polynomial (P_{n-1}^2 against h_{n-1}).
  for (const auto& [n, a, b] : std::vector<std::tuple<int, double, double>>{{1, 0.3, 0.7},
                                                                            {7, -0.4, -0.6},
                                                                            {9, 0.46, 0.54},
                                                                            {1100, -0.46, -0.54},
                                                                            {1152, 0.2, 0.8}}) {
    const mp::JacobiRule r = mp::gauss_jacobi(n, a, b);
    const double ln_c = (a + b + 1.0) * std::log(2.0) + std::lgamma(n + a + 1.0) +
                        std::lgamma(n + b + 1.0) - std::lgamma(n + a + b + 1.0) -
                        std::lgamma(n + 1.0);
    for (int i = 0; i < n; i += std::max(1, n / 97)) {
      double p, dp;
      mp::jacobi_p(n, a, b, r.x(i), &p, &dp);
      EXPECT_LT(std::fabs(p / dp), 1e-15) << n << " " << i;
      EXPECT_EQ(r.w(i), std::exp(ln_c) / ((1.0 - r.x(i) * r.x(i)) * dp * dp)) << n << " " << i;
    }
    if (n > 1) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) {
        double p;
        mp::jacobi_p(n - 1, a, b, r.x(i), &p);
        sum += r.w(i) * p * p;
      }
      EXPECT_NEAR(sum, mp::jacobi_norm(n - 1, a, b), 1e-11 * mp::jacobi_norm(n - 1, a, b)) << n;
    }
  }
}

// Gauss-Chebyshev nodes, weights, the singular quadrature, and the Hertz solve.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "movingpunch/collocation.hpp"

using namespace movingpunch;

namespace {
double cheb_u(int n, double x) {
  const double th = std::acos(x);
  return std::sin((n + 1) * th) / std::sin(th);
}
double cheb_t(int n, double x) { return std::cos(n * std::acos(x)); }
}  // namespace

TEST(Collocation, NodesAreChebyshevZeros) {
  for (int n : {2, 8, 20, 64}) {
    const ChebyshevNodes c = chebyshev_nodes(n);
    ASSERT_EQ(c.r.size(), n);
    ASSERT_EQ(c.s.size(), n + 1);
    for (int i = 0; i < n; ++i) EXPECT_NEAR(std::sin((n + 1) * std::acos(c.r(i))), 0.0, 1e-13);
    for (int k = 0; k <= n; ++k) EXPECT_NEAR(cheb_t(n + 1, c.s(k)), 0.0, 1e-12);
    EXPECT_EQ(c.s(n / 2), 0.0);
  }
}

TEST(Collocation, WeightsIntegratePolynomialsExactly) {
  // (1/pi) int sqrt(1-r^2) r^{2m} dr = Gamma(m+1/2) Gamma(3/2) / (pi Gamma(m+2)).
  const ChebyshevNodes c = chebyshev_nodes(16);
  for (int m = 0; m < 16; ++m) {
    double sum = 0.0;
    for (int i = 0; i < 16; ++i) sum += c.w(i) * std::pow(c.r(i), 2 * m);
    const double exact = std::tgamma(m + 0.5) * std::tgamma(1.5) / (M_PI * std::tgamma(m + 2.0));
    EXPECT_NEAR(sum, exact, 1e-15) << "m " << m;
  }
}

TEST(Collocation, SingularQuadratureIsExact) {
  // (1/pi) int sqrt(1-r^2) U_n(r)/(r - s) dr = -T_{n+1}(s) at the zeros of T_{N+1}.
  const int N = 12;
  const ChebyshevNodes c = chebyshev_nodes(N);
  for (int n = 0; n < N; ++n)
    for (int k = 0; k <= N; ++k) {
      double sum = 0.0;
      for (int i = 0; i < N; ++i) sum += c.w(i) * cheb_u(n, c.r(i)) / (c.r(i) - c.s(k));
      EXPECT_NEAR(sum, -cheb_t(n + 1, c.s(k)), 1e-12);
    }
}

TEST(Collocation, HertzKernelSolveMatchesClosedForm) {
  // k = 0: p = p0 sqrt(1 - r^2) solves the equation, i.e. G = -1 for unit RHS,
  // so the load is pi a^2 / (2 phi1 R): a^2 = 2 phi1 R P / pi.
  for (int N : {2, 8, 24, 64}) {
    const ChebyshevNodes c = chebyshev_nodes(N);
    const Eigen::VectorXd G = solve_unit_collocation(c, 0.7, [](double) { return 0.0; });
    for (int j = 0; j < N / 2; ++j) EXPECT_NEAR(G(j), -1.0, 1e-13);
    Eigen::VectorXd full(N);
    for (int j = 0; j < N / 2; ++j) full(j) = full(N - 1 - j) = G(j);
    const Eigen::VectorXd b = u_coefficients(c, full);
    EXPECT_NEAR(b(0), -1.0, 1e-13);
    for (int m = 1; m < N; ++m) EXPECT_NEAR(b(m), 0.0, 1e-13);
    EXPECT_NEAR(u_series(b, 0.3), -1.0, 1e-13);
    const double phi1 = 0.8, R = 100.0, a = 0.7;
    const double load = -M_PI * a * a / (phi1 * R) * 2.0 * c.w.head(N / 2).dot(G);
    EXPECT_NEAR(load, M_PI * a * a / (2.0 * phi1 * R), 1e-15);
  }
}

TEST(Collocation, UCoefficientsInterpolate) {
  const ChebyshevNodes c = chebyshev_nodes(10);
  Eigen::VectorXd g(10);
  for (int i = 0; i < 10; ++i) g(i) = 1.0 + c.r(i) * c.r(i) - 3.0 * std::pow(c.r(i), 4);
  const Eigen::VectorXd b = u_coefficients(c, g);
  for (double r : {-0.9, -0.2, 0.0, 0.55, 1.0})
    EXPECT_NEAR(u_series(b, r), 1.0 + r * r - 3.0 * std::pow(r, 4), 1e-13);
}

TEST(Collocation, EvenSeriesMatchesTheFullRecurrence) {
  // An even g (no odd terms), both kinds, odd and even lengths: Clenshaw in
  // steps of two against the full recurrence and against the defining sums
  // U_n(cos t) = sin((n + 1) t)/sin t, T_n(cos t) = cos(n t).
  for (const int size : {1, 2, 7, 34}) {
    Eigen::VectorXd b = Eigen::VectorXd::Zero(size);
    for (int n = 0; n < size; n += 2) b(n) = std::cos(1.3 * n + 0.4) / (1.0 + n);
    ASSERT_TRUE(odd_terms_zero(b));
    for (const double t : {0.0, 0.3, 1.1, 1.5707963267948966, 2.9, 3.1}) {
      const double r = std::cos(t);
      double u = 0.0, tt = 0.0;
      for (int n = 0; n < size; ++n) {
        u += b(n) * (t == 0.0 ? n + 1.0 : std::sin((n + 1) * t) / std::sin(t));
        tt += b(n) * std::cos(n * t);
      }
      for (const SeriesKind kind : {SeriesKind::U, SeriesKind::T}) {
        const double want = kind == SeriesKind::U ? u : tt;
        EXPECT_NEAR(even_series(b, r, kind), series(b, r, kind), 1e-14) << size << " " << t;
        EXPECT_NEAR(even_series(b, r, kind), want, 1e-12) << size << " " << t;
      }
    }
  }
  Eigen::VectorXd odd = Eigen::VectorXd::Zero(4);
  odd(3) = 1e-300;
  EXPECT_FALSE(odd_terms_zero(odd));
}

TEST(Collocation, RejectsOddOrTinyN) {
  EXPECT_THROW(chebyshev_nodes(7), std::invalid_argument);
  EXPECT_THROW(chebyshev_nodes(0), std::invalid_argument);
  EXPECT_THROW(chebyshev_nodes(-4), std::invalid_argument);
}

TEST(Collocation, CosineTransformHoldsAtHighBesselOrders) {
  // The transform of U_n sums J_{n+1}(alpha a). The C++ library's
  // cyl_bessel_j is wrong by up to 1e30 for orders above ~300 at arguments
  // ~1000 (it made a valid wide contact look like a 0.017 h penetration);
  // the transform now uses one recurrence over all orders. Reference values
  // of J_nu(1098) from mpmath (30 digits, rounded).
  const struct {
    int order;
    double j;
  } ref[] = {{1, -0.0172582542424398},  {101, 0.0179036417657971}, {301, 0.0244519296645075},
             {401, 0.0125424777145836}, {451, 0.013134375424562},  {491, -0.0136687069391376},
             {511, 0.012606647413878}};
  const double kPi = 3.14159265358979323846, w = 1098.0;
  for (const auto& r : ref) {
    const int n = r.order - 1;  // U_n transforms to J_{n+1}
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n + 1);
    b(n) = 1.0;
    const double sg = (n / 2) % 2 == 0 ? 1.0 : -1.0;
    const double expect = sg * (n + 1) * r.j * 0.5 * kPi / w;
    EXPECT_NEAR(u_series_cosine_transform(b, 1.0, w), expect, 1e-13 * (n + 1) / w)
        << "order " << r.order;
  }
  // Large arguments at low orders (the upward recurrence from Hankel's
  // expansion of J_0, J_1): T_0 sums J_0, U_0 J_1, U_2 J_3. References from
  // scipy.special.jv (the C++ library's J_0(200.5) is off by 2e-12
  // relative).
  const struct {
    double w, j0, j1, j3;
  } large[] = {{200.5, 0.012453299390357279, -0.054924246437864151, 0.054664871431923397},
               {317.0, -0.020858619092434669, 0.039630479778886743, -0.039364124527591193},
               {1000.0, 0.024786686152420172, 0.0047283119070895231, -0.0048274208252039466},
               {4321.5, -0.0063038485189203172, -0.010372615950565111, 0.010378446378008114},
               {30000.0, -0.0045573449277751983, -0.00067183951934767492, 0.00067244715936613819}};
  for (const auto& r : large) {
    Eigen::VectorXd b = Eigen::VectorXd::Zero(3);
    b(0) = 1.0;
    const double tol = 4e-16 / std::sqrt(r.w);  // of J ~ sqrt(2 / (pi w))
    EXPECT_NEAR(series_cosine_transform(b, SeriesKind::T, 1.0, r.w), r.j0 * 0.5 * kPi,
                tol * 0.5 * kPi)
        << r.w;
    EXPECT_NEAR(u_series_cosine_transform(b, 1.0, r.w), r.j1 * 0.5 * kPi / r.w,
                tol * 0.5 * kPi / r.w)
        << r.w;
    b.setZero();
    b(2) = 1.0;
    EXPECT_NEAR(u_series_cosine_transform(b, 1.0, r.w), -3.0 * r.j3 * 0.5 * kPi / r.w,
                3.0 * tol * 0.5 * kPi / r.w)
        << r.w;
  }
  // Moderate arguments above the orders (25 < w <= 200: Hankel's J_0, J_1
  // and the upward recurrence since the graded top's panels reach there):
  // T_0 sums J_0, U_0 J_1, U_2 J_3, U_22 J_23. References from a long-double
  // Miller recurrence started at order 2w + 100 (its J_0, J_1 agree with
  // scipy.special.j0, j1 to 6e-16; scipy's jv is 7e-14 off here), within
  // 2e-15 of the amplitude sqrt(2 / (pi w)).
  const struct {
    double w, j0, j1, j3, j23;
  } moderate[] = {
      {25.5, 0.14406215754684787, -0.062048536491484105, 0.0386871703066162, 0.23201924188732115},
      {31.25, 0.08239920414269862, -0.11522838548383534, 0.10373733641968633, -0.17213328371184894},
      {47.75, -0.11395261382459274, 0.017420362617125266, -0.007813471515923343,
       -0.08780227816414866},
      {66.5, -0.0945348255659813, 0.024511501476355956, -0.01878085404295398,
       -0.058334576561289334},
      {99.125, -0.04668290030976295, -0.06537475612182513, 0.06720532817191374,
       -0.03807851907763939},
      {150.375, 0.023110765671267772, -0.060746326609006494, 0.060110085295896266,
       -0.0344709308510282}};
  for (const auto& r : moderate) {
    const double tol = 2e-15 * std::sqrt(2.0 / (kPi * r.w));
    Eigen::VectorXd b = Eigen::VectorXd::Zero(23);
    b(0) = 1.0;
    EXPECT_NEAR(series_cosine_transform(b.head(1), SeriesKind::T, 1.0, r.w), r.j0 * 0.5 * kPi,
                tol * 0.5 * kPi)
        << r.w;
    EXPECT_NEAR(u_series_cosine_transform(b.head(1), 1.0, r.w), r.j1 * 0.5 * kPi / r.w,
                tol * 0.5 * kPi / r.w)
        << r.w;
    for (int n : {2, 22}) {
      b.setZero();
      b(n) = 1.0;
      const double j = n == 2 ? r.j3 : r.j23;
      const double sg = (n / 2) % 2 == 0 ? 1.0 : -1.0;
      // The batched transform (four lanes, or one by one) and the single one.
      double batched = 0.0;
      u_series_cosine_transforms(b, 1.0, &r.w, &batched, 1);
      for (const double got : {u_series_cosine_transform(b, 1.0, r.w), batched})
        EXPECT_NEAR(got, sg * (n + 1) * j * 0.5 * kPi / r.w, (n + 1) * tol * 0.5 * kPi / r.w)
            << r.w << " order " << n + 1;
    }
  }
  // Small arguments (downward recurrence) against the library, which is
  // accurate there.
  for (int n : {0, 2, 10, 40}) {
    for (double w2 : {0.3, 5.0, 30.0}) {
      Eigen::VectorXd b = Eigen::VectorXd::Zero(n + 1);
      b(n) = 1.0;
      const double sg = (n / 2) % 2 == 0 ? 1.0 : -1.0;
      const double expect = sg * (n + 1) * std::cyl_bessel_j(n + 1.0, w2) * 0.5 * kPi / w2;
      EXPECT_NEAR(u_series_cosine_transform(b, 1.0, w2), expect, 1e-14 * (n + 1)) << n << " " << w2;
    }
  }
}

// The batched transform equals the one-at-a-time one: for wide and narrow
// contacts, tiny and large arguments (both recurrences), in any order.
TEST(Collocation, BatchedCosineTransformMatchesScalar) {
  for (double a : {1e-6, 0.37, 5.0, 40.0}) {
    Eigen::VectorXd b = Eigen::VectorXd::Zero(40);
    for (Eigen::Index n = 0; n < b.size(); n += 2)
      b(n) = std::pow(-0.6, static_cast<double>(n / 2)) / (1.0 + static_cast<double>(n));
    std::vector<double> alpha;
    for (int i = 0; i < 203; ++i) alpha.push_back(1e-10 * std::pow(1.2, i));  // 1e-10 .. 1e6
    alpha.push_back(0.0);
    alpha.push_back(3.0);
    std::vector<double> out(alpha.size());
    u_series_cosine_transforms(b, a, alpha.data(), out.data(), alpha.size());
    for (std::size_t i = 0; i < alpha.size(); ++i) {
      const double want = u_series_cosine_transform(b, a, alpha[i]);
      EXPECT_NEAR(out[i], want, 1e-14 * (std::fabs(want) + a))
          << "a " << a << " alpha " << alpha[i];
    }
  }
}

TEST(Collocation, SeriesMinimumMatchesADenseScan) {
  // g(r) = 1 - 0.3 U_2 + 0.05 U_4 + 0.4 U_6: its minimum against a scan of
  // 2e6 points (independent: U_n by their trigonometric form).
  Eigen::VectorXd b = Eigen::VectorXd::Zero(8);
  b(0) = 1.0;
  b(2) = -0.3;
  b(4) = 0.05;
  b(6) = 0.4;
  double best = 1e300;
  for (int i = 0; i <= 2000000; ++i) {
    const double r = -1.0 + 2.0 * i / 2000000.0;
    const double g = std::fabs(r) == 1.0
                         ? b(0) + 3 * b(2) + 5 * b(4) + 7 * b(6)
                         : b(0) + b(2) * cheb_u(2, r) + b(4) * cheb_u(4, r) + b(6) * cheb_u(6, r);
    best = std::min(best, g);
  }
  double r_min = 0.0;
  const double m = u_series_minimum(b, &r_min);
  EXPECT_NEAR(m, best, 1e-10);  // the scan resolves the minimum to ~g'' (1e-6)^2 / 8
  EXPECT_LE(m, best + 1e-15);
  EXPECT_NEAR(u_series(b, r_min), m, 1e-15);
  // A constant: the minimum is the constant.
  Eigen::VectorXd c = Eigen::VectorXd::Zero(4);
  c(0) = 0.7;
  EXPECT_DOUBLE_EQ(u_series_minimum(c), 0.7);
  EXPECT_THROW(u_series_minimum(Eigen::VectorXd()), std::invalid_argument);
}

TEST(Collocation, MatrixIsTheOneTheSolveUses) {
  const ChebyshevNodes c = chebyshev_nodes(12);
  auto k = [](double u, double v) { return 0.3 * std::sin(u) + 0.3 * std::sin(v); };
  const Eigen::MatrixXd M = unit_collocation_matrix(c, 0.8, k);
  const Eigen::VectorXd G = solve_unit_collocation_sum(c, 0.8, k);
  EXPECT_LT((M * G - c.s.head(6)).norm(), 1e-13);
}

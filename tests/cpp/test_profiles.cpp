// Punch profiles: the table's spline, its checks, the slope's Chebyshev
// projection, and the flat punch's T-series closed forms (transform, log and
// Cauchy potentials) against direct quadrature.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "movingpunch/collocation.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/jacobi.hpp"
#include "movingpunch/profile.hpp"
#include "potentials.hpp"

using namespace movingpunch;

namespace {
constexpr double kPi = 3.14159265358979323846;

// (1/pi) int_{-1}^{1} f(t)/sqrt(1 - t^2) dt by Gauss-Chebyshev with m nodes.
template <class F>
double gauss_t(const F& f, int m) {
  double s = 0.0;
  for (int i = 1; i <= m; ++i) s += f(std::cos((2 * i - 1) * kPi / (2.0 * m)));
  return s / m;
}
}  // namespace

TEST(Profiles, SplineReproducesCubicsAndParabolas) {
  std::vector<double> x, y;
  for (int i = -6; i <= 6; ++i) {
    const double xi = 0.25 * i + 0.01 * (i * i % 3) * (i < 0 ? -1 : 1);
    x.push_back(xi);
  }
  // make it exactly symmetric
  for (std::size_t i = 0; i < x.size() / 2; ++i) x[x.size() - 1 - i] = -x[i];
  for (double xi : x) y.push_back(xi * xi / 7.0);
  const PunchProfile p(ProfileKind::table, 0.0, 0.0, x, y);
  for (double t : {-1.3, -0.4, 0.0, 0.11, 0.9, 1.49}) {
    EXPECT_NEAR(p.height(t), t * t / 7.0, 1e-14);
    EXPECT_NEAR(p.slope(t), 2.0 * t / 7.0, 1e-14);
  }
  EXPECT_THROW(p.slope(2.0), std::domain_error);
}

TEST(Profiles, TableChecksNameTheirParameter) {
  const std::vector<double> x = {-2, -1, 0, 1, 2};
  auto name_of = [](const std::vector<double>& tx, const std::vector<double>& ty,
                    bool symmetric = true) {
    try {
      check_profile_table(tx, ty, symmetric);
    } catch (const InvalidParameter& e) {
      return e.name();
    }
    return std::string("none");
  };
  EXPECT_EQ(name_of(x, {4, 1, 0, 1, 4}), "none");
  EXPECT_EQ(name_of({-1, 0, 1}, {1, 0, 1}), "profile.x");               // short
  EXPECT_EQ(name_of({-2, -1, 0, 2, 1}, {4, 1, 0, 1, 4}), "profile.x");  // unsorted
  EXPECT_EQ(name_of(x, {4, 1, 0, 1}), "profile.y");                     // length
  EXPECT_EQ(name_of(x, {4, 1, 0, 1.5, 4}), "profile.y");                // asymmetric
  EXPECT_EQ(name_of(x, {1, 2, 0, 2, 1}), "profile.y");                  // not convex
  EXPECT_EQ(name_of({-2, -1, 0, 1, 3}, {4, 1, 0, 1, 4}), "profile.x");  // asymmetric x
  EXPECT_EQ(name_of(x, {4, 1, std::nan(""), 1, 4}), "profile.y");
  // Asymmetric tables are valid for the asymmetric solver (require_symmetric
  // false); the table must still span x = 0 and be convex.
  EXPECT_EQ(name_of(x, {4, 1, 0, 1.5, 4}, false), "none");
  EXPECT_EQ(name_of({-2, -1, 0, 1, 3}, {4, 1, 0, 1, 4}, false), "none");
  EXPECT_EQ(name_of({0.5, 1, 2, 3, 4}, {4, 1, 0, 1, 4}, false), "profile.x");  // misses x = 0
  EXPECT_EQ(name_of(x, {1, 2, 0, 2, 1}, false), "profile.y");                  // not convex
  EXPECT_TRUE(profile_table_symmetric(x, {4, 1, 0, 1, 4}));
  EXPECT_FALSE(profile_table_symmetric(x, {4, 1, 0, 1.5, 4}));
}

TEST(Profiles, AsymmetricTableKeepsItsOwnExtents) {
  // f = (x - 0.5)^2 on [-1, 3]: heights from the axis x = 0, extents both sides.
  std::vector<double> x, y;
  for (int i = 0; i <= 40; ++i) {
    x.push_back(-1.0 + 0.1 * i);
    y.push_back((x.back() - 0.5) * (x.back() - 0.5));
  }
  const PunchProfile p(ProfileKind::table, 1.0, 0.0, x, y);
  EXPECT_FALSE(p.symmetric());
  EXPECT_DOUBLE_EQ(p.lower(), -1.0);
  EXPECT_NEAR(p.upper(), 3.0, 1e-14);
  EXPECT_NEAR(p.extent(), 1.0, 1e-14);
  EXPECT_NEAR(p.height(2.5), 4.0 - 0.25, 1e-13);  // exact for a parabola
  EXPECT_NEAR(p.slope(-0.9), 2.0 * (-1.4), 1e-13);
  EXPECT_THROW(p.slope(3.1), std::domain_error);
  EXPECT_THROW(p.slope(-1.1), std::domain_error);
}

TEST(Profiles, OffCentreProjectionMatchesQuadrature) {
  // d_m = (2/pi) int_0^pi f'(c + w cos th) cos(m th) dth on an off-centre
  // contact: the rounded flat's closed form (split at its kinks) and the
  // cylinder's against a fine composite midpoint rule.
  const PunchProfile rf(ProfileKind::rounded_flat, 2.0, 0.3);
  const PunchProfile cyl(ProfileKind::cylinder, 5.0, 0.0);
  for (const auto* p : {&rf, &cyl}) {
    const double c = -0.12, w = 0.65;
    const std::vector<double> d = p->slope_chebyshev_at(c, w, 9);
    const int M = 400000;
    for (int m = 0; m < 9; ++m) {
      double sum = 0.0;
      for (int j = 0; j < M; ++j) {
        const double th = (j + 0.5) * M_PI / M;
        sum += p->slope(c + w * std::cos(th)) * std::cos(m * th);
      }
      EXPECT_NEAR(d[static_cast<std::size_t>(m)], 2.0 / M * sum, 1e-9) << m;
    }
  }
}

TEST(Profiles, KinkedSlopeSeriesClosedFormsAgreeWithSumsAndQuadrature) {
  // The rounded flat's slope on an off-centre contact (both kinks inside,
  // one inside, none): its far coefficients d_m against a composite
  // midpoint rule split at the kinks; the closed-form bound on sum_{m > L}
  // |d_m| against the sum itself (bounds it, by at most 4 times); the
  // Poisson sum d_0/2 + sum d_k q^k against the series summed term by term
  // (zones.cpp sums a zone's whole Cauchy tail with it).
  const PunchProfile rf(ProfileKind::rounded_flat, 2.0, 0.3);
  struct Case {
    double c, w;
  };
  for (const Case cs : {Case{-0.12, 0.65}, Case{0.2, 0.3}, Case{0.9, 0.4}}) {
    const int count = 20001;
    const std::vector<double> d = rf.slope_chebyshev_at(cs.c, cs.w, count);
    std::vector<double> cuts{0.0, kPi};
    for (double x : {0.3, -0.3})
      if (std::fabs(x - cs.c) < cs.w) cuts.push_back(std::acos((x - cs.c) / cs.w));
    std::sort(cuts.begin(), cuts.end());
    for (int m : {2, 3, 17, 400, 3001}) {
      double sum = 0.0;
      for (std::size_t p = 0; p + 1 < cuts.size(); ++p) {
        const int M = 400000;
        const double h = (cuts[p + 1] - cuts[p]) / M;
        for (int j = 0; j < M; ++j) {
          const double th = cuts[p] + (j + 0.5) * h;
          sum += h * rf.slope(cs.c + cs.w * std::cos(th)) * std::cos(m * th);
        }
      }
      EXPECT_NEAR(d[static_cast<std::size_t>(m)], 2.0 / kPi * sum, 1e-12) << cs.c << " " << m;
    }
    for (int L : {16, 128, 4096}) {
      double sum = 0.0;
      for (int m = L + 1; m < count; ++m) sum += std::fabs(d[static_cast<std::size_t>(m)]);
      const double bound = rf.slope_chebyshev_tail(cs.c, cs.w, L);
      EXPECT_GE(bound, sum) << cs.c << " " << L;
      if (cs.c != 0.9) EXPECT_LE(bound, 4.0 * sum) << cs.c << " " << L;  // (0.9: no kink inside)
    }
    for (double q : {-0.97, -0.6, -0.3, 0.1, 0.4, 0.9, 0.99}) {
      double sum = 0.5 * d[0], qk = 1.0;
      for (int k = 1; k < count; ++k) {
        qk *= q;
        sum += d[static_cast<std::size_t>(k)] * qk;
      }
      const double rest = rf.slope_chebyshev_tail(cs.c, cs.w, count - 1);
      EXPECT_NEAR(rf.slope_chebyshev_poisson(cs.c, cs.w, q), sum, 1e-15 + rest) << cs.c << " " << q;
    }
  }
  // The cylinder: its two terms; a table: no closed form.
  const PunchProfile cyl(ProfileKind::cylinder, 5.0, 0.0);
  EXPECT_DOUBLE_EQ(cyl.slope_chebyshev_poisson(0.1, 0.4, 0.5), (0.1 + 0.4 * 0.5) / 5.0);
  EXPECT_EQ(cyl.slope_chebyshev_tail(0.1, 0.4, 3), 0.0);
  const PunchProfile tab(ProfileKind::table, 0.0, 0.0, {-1.0, -0.5, 0.0, 0.5, 1.0},
                         {0.1, 0.02, 0.0, 0.02, 0.1});
  EXPECT_TRUE(std::isnan(tab.slope_chebyshev_poisson(0.0, 0.5, 0.5)));
  EXPECT_TRUE(std::isinf(tab.slope_chebyshev_tail(0.0, 0.5, 8)));
}

TEST(Profiles, SlopeProjectionMatchesQuadrature) {
  // d_m = (2/pi) int_0^pi f'(a cos th) cos(m th) dth: the rounded flat's
  // closed form and a table's midpoint rule against a fine quadrature.
  const double a = 0.7, b = 0.3, R = 2.0;
  const PunchProfile rf(ProfileKind::rounded_flat, R, b);
  const std::vector<double> d = rf.slope_chebyshev(a, 6);
  for (int q = 0; q < 6; ++q) {
    const int m = 2 * q + 1;
    const int M = 400000;
    double s = 0.0;
    for (int j = 0; j < M; ++j) {
      const double th = (j + 0.5) * kPi / M;
      s += rf.slope(a * std::cos(th)) * std::cos(m * th);
    }
    EXPECT_NEAR(d[static_cast<std::size_t>(q)], 2.0 * s / M, 1e-10) << m;
  }
  // The cylinder: a single term a/R.
  const PunchProfile cyl(ProfileKind::cylinder, R, 0.0);
  const std::vector<double> dc = cyl.slope_chebyshev(a, 3);
  EXPECT_DOUBLE_EQ(dc[0], a / R);
  EXPECT_EQ(dc[1], 0.0);
}

TEST(Profiles, TSeriesCosineTransformIsExact) {
  // int_0^a p cos(alpha x) dx for p(a r) = g(r)/sqrt(1 - r^2), g = sum b_n T_n.
  Eigen::VectorXd b = Eigen::VectorXd::Zero(7);
  b << 0.8, 0.0, -0.3, 0.0, 0.05, 0.0, 0.01;
  const double a = 0.9;
  for (double alpha : {0.0, 1e-9, 0.5, 3.0, 17.0, 250.0}) {
    // (a/2) int_{-1}^{1} g(r)/sqrt(1 - r^2) cos(alpha a r) dr
    const double direct =
        0.5 * a * kPi *
        gauss_t([&](double r) { return t_series(b, r) * std::cos(alpha * a * r); }, 4000);
    const double one = series_cosine_transform(b, SeriesKind::T, a, alpha);
    double many = 0.0;
    series_cosine_transforms(b, SeriesKind::T, a, &alpha, &many, 1);
    EXPECT_NEAR(one, direct, 1e-13 * (1.0 + std::fabs(direct))) << alpha;
    EXPECT_NEAR(many, direct, 1e-13 * (1.0 + std::fabs(direct))) << alpha;
  }
}

TEST(Profiles, TSeriesPotentialsAgreeWithQuadrature) {
  // log: (1/pi) int T_n/sqrt(1-t^2) ln|x - t| = -ln 2 (n = 0), -T_n(x)/n;
  // beyond the face against quadrature. Cauchy: (1/pi) int T_n/(sqrt(1-t^2)(z - t))
  // = w^n/sqrt(z^2 - 1) off the real axis.
  for (int n : {0, 1, 2, 4}) {
    for (double x : {-2.5, -1.2, 1.7, 3.0}) {
      const double q = gauss_t(
          [&](double t) { return std::cos(n * std::acos(t)) * std::log(std::fabs(x - t)); }, 20000);
      EXPECT_NEAR(detail::log_potential(n, x, SeriesKind::T), q, 1e-12) << n << " " << x;
    }
    EXPECT_NEAR(detail::log_potential(n, 0.3, SeriesKind::T),
                n == 0 ? -std::log(2.0) : -std::cos(n * std::acos(0.3)) / n, 1e-15);
  }
  Eigen::VectorXd b = Eigen::VectorXd::Zero(5);
  b << 0.7, 0.0, 0.2, 0.0, -0.1;
  for (std::complex<double> z : {std::complex<double>(0.3, 0.4), {1.5, 0.2}, {-0.8, 1.1}}) {
    std::complex<double> direct = 0.0, dlog = 0.0;
    const int m = 20000;
    for (int i = 1; i <= m; ++i) {
      const double t = std::cos((2 * i - 1) * kPi / (2.0 * m));
      direct += t_series(b, t) / (z - t);
      dlog += t_series(b, t) * std::log(z - t);
    }
    direct /= m;
    dlog /= m;
    EXPECT_LT(std::abs(detail::cauchy_potential(b, z, 2, SeriesKind::T) - direct), 1e-10);
    EXPECT_LT(std::abs(detail::log_potential(b, z, 2, SeriesKind::T) - dlog), 1e-10);
    // The derivative by a central difference.
    const double h = 1e-6;
    const std::complex<double> fd = (detail::cauchy_potential(b, z + h, 2, SeriesKind::T) -
                                     detail::cauchy_potential(b, z - h, 2, SeriesKind::T)) /
                                    (2.0 * h);
    EXPECT_LT(std::abs(detail::cauchy_potential_derivative(b, z, 2, SeriesKind::T) - fd), 1e-7);
  }
}

TEST(Profiles, FlatCollocationWithoutKernelIsTheHalfPlanePunch) {
  // k1 = 0: g = 1/(pi a) (p = P/(pi sqrt(a^2 - x^2))) at every N.
  for (int n : {2, 8, 32}) {
    const FirstKindNodes nd = first_kind_nodes(n);
    const double a = 0.37;
    const Eigen::MatrixXd M = flat_collocation_matrix(nd, a, [](double, double) { return 0.0; });
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n / 2);
    rhs(n / 2 - 1) = 1.0;
    const Eigen::VectorXd g = M.partialPivLu().solve(rhs);
    for (int j = 0; j < n / 2; ++j) EXPECT_NEAR(g(j), 1.0 / (kPi * a), 1e-13);
  }
}

// The even-term sum of the log potentials as greens_integral takes it (the
// series' complex log potential on the real axis, its real part: one w for
// all terms) against the term-by-term sum, for both series kinds, inside and
// outside the contact, to 192 terms.
TEST(Profiles, EvenLogPotentialSumMatchesTermByTerm) {
  for (const SeriesKind kind : {SeriesKind::U, SeriesKind::T})
    for (const int n : {1, 12, 96, 192}) {
      Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
      for (int m = 0; m < n; m += 2) b(m) = std::cos(0.7 * m) / (1.0 + m);
      for (const double x : {0.0, 0.3, -0.99, 1.0, -1.0, 1.001, 1.7, -2.5, 40.0}) {
        double direct = 0.0, scale = 0.0;
        for (int m = 0; m < n; m += 2) {
          const double t = b(m) * detail::log_potential(m, x, kind);
          direct += t;
          scale += std::fabs(t);
        }
        EXPECT_NEAR(detail::log_potential(b, std::complex<double>(x, 0.0), 2, kind).real(), direct,
                    1e-14 * (1.0 + scale))
            << n << " " << x;
      }
    }
}

// The stress field's potentials of a long U-series cut at potential_terms
// agree with the whole sums to the bound's 1e-17 of sum (m + 1)|b_m| (plus
// the sums' own round-off), and are cut short off the contact.
TEST(Potentials, CutSeriesMatchTheWholeSums) {
  Eigen::VectorXd b = Eigen::VectorXd::Zero(4096);
  for (Eigen::Index m = 0; m < b.size(); m += 2)
    b(m) = std::cos(0.3 * static_cast<double>(m)) / (1.0 + static_cast<double>(m) * m);
  const Eigen::VectorXd tail = detail::potential_tails(b);
  ASSERT_EQ(tail.size(), b.size() + 1);
  EXPECT_EQ(tail(b.size()), 0.0);
  for (const std::complex<double> z :
       {std::complex<double>(0.3, 0.01), std::complex<double>(0.3, 0.4),
        std::complex<double>(1.5, 0.02), std::complex<double>(-4.0, 0.5),
        std::complex<double>(0.999, 1e-6)}) {
    const Eigen::Index n = detail::potential_terms(tail, std::abs(detail::w_of(z)));
    const std::complex<double> whole = detail::cauchy_potential(b, z, 2);
    const std::complex<double> cut = detail::cauchy_potential(b, z, 2, SeriesKind::U, &tail);
    const std::complex<double> dwhole = detail::cauchy_potential_derivative(b, z, 2);
    const std::complex<double> dcut =
        detail::cauchy_potential_derivative(b, z, 2, SeriesKind::U, &tail);
    const double r = std::abs(std::sqrt(z - 1.0) * std::sqrt(z + 1.0));
    EXPECT_LE(std::abs(cut - whole), 1e-15 * tail(0)) << z;
    EXPECT_LE(std::abs(dcut - dwhole), 1e-15 * tail(0) / r) << z;
    if (std::abs(detail::w_of(z)) < 0.5) EXPECT_LT(n, 64) << z;  // off the contact: few terms
  }
}

TEST(Profiles, TableProjectionIsExactOnTheSplinePieces) {
  // A table's slope projection is summed in closed form over the spline's
  // pieces. Anchors: (1) a table of a cubic, which the not-a-knot spline
  // reproduces, has the slope's three coefficients and nothing else; (2) an
  // unevenly spaced convex table against Gauss-Legendre quadrature in th
  // split at every knot (exact to round-off on each smooth piece), off
  // centre (slope_chebyshev_at) and centred (slope_chebyshev's odd terms).
  {
    std::vector<double> x, y;
    for (int i = 0; i <= 40; ++i) {
      const double xi = -2.0 + 0.1 * i;
      x.push_back(xi);
      y.push_back(0.5 * xi * xi + xi * xi * xi / 30.0);
    }
    const PunchProfile cubic(ProfileKind::table, 0.0, 0.0, x, y);
    const double c = 0.31, w = 1.2;
    const std::vector<double> d = cubic.slope_chebyshev_at(c, w, 40);
    EXPECT_NEAR(d[0], 2.0 * (c + c * c / 10.0 + w * w / 20.0), 1e-13);
    EXPECT_NEAR(d[1], w * (1.0 + c / 5.0), 1e-13);
    EXPECT_NEAR(d[2], w * w / 20.0, 1e-13);
    for (int m = 3; m < 40; ++m) EXPECT_NEAR(d[static_cast<std::size_t>(m)], 0.0, 1e-13) << m;
  }
  std::vector<double> x, y;
  for (int i = 0; i <= 60; ++i) {
    const double t = -1.0 + 2.0 * i / 60.0;
    const double xi = 2.5 * t + 0.4 * std::sin(3.0 * t);  // uneven spacing
    x.push_back(xi);
    y.push_back(std::exp(0.8 * xi) - 0.8 * xi + 0.05 * xi * xi * xi * xi);
  }
  const PunchProfile tab(ProfileKind::table, 0.0, 0.0, x, y);
  const auto gl = gauss_jacobi(24, 0.0, 0.0);
  // (2/pi) int_0^th_end f'(c + w cos th) cos(m th), split at the knots.
  auto reference = [&](double c, double w, double th_end, int m) {
    std::vector<double> cuts = {0.0, th_end};
    for (double xk : x) {
      const double u = (xk - c) / w;
      if (u > -1.0 && u < 1.0 && std::acos(u) < th_end) cuts.push_back(std::acos(u));
    }
    std::sort(cuts.begin(), cuts.end());
    double s = 0.0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      // Sub-pieces of at most one radian of m th.
      const int parts = 1 + static_cast<int>((m + 1) * (cuts[i + 1] - cuts[i]));
      for (int p = 0; p < parts; ++p) {
        const double lo = cuts[i] + (cuts[i + 1] - cuts[i]) * p / parts;
        const double hi = cuts[i] + (cuts[i + 1] - cuts[i]) * (p + 1) / parts;
        const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
        for (Eigen::Index j = 0; j < gl.x.size(); ++j) {
          const double th = mid + half * gl.x(j);
          s += half * gl.w(j) * tab.slope(c + w * std::cos(th)) * std::cos(m * th);
        }
      }
    }
    return 2.0 / kPi * s;
  };
  const double c = -0.37, w = 1.6;
  const std::vector<double> d = tab.slope_chebyshev_at(c, w, 301);
  double scale = 0.0;
  for (double v : d) scale = std::max(scale, std::fabs(v));
  for (int m : {0, 1, 2, 3, 7, 20, 64, 150, 300})
    EXPECT_NEAR(d[static_cast<std::size_t>(m)], reference(c, w, kPi, m), 1e-13 * scale) << m;
  // Centred: slope_chebyshev(a, .)[q] = (4/pi) int_0^{pi/2} f'(a cos th) cos((2q + 1) th).
  const double a = 1.3;
  const std::vector<double> ds = tab.slope_chebyshev(a, 40);
  for (int q : {0, 1, 5, 39})
    EXPECT_NEAR(ds[static_cast<std::size_t>(q)], 2.0 * reference(0.0, a, 0.5 * kPi, 2 * q + 1),
                1e-13 * scale)
        << q;
  EXPECT_THROW(tab.slope_chebyshev_at(0.5, 2.5, 8), std::domain_error);
}

TEST(Profiles, TableSlopesAtManyPointsAreSlopeAtEach) {
  // slopes() walks a table's knots once for ascending points (its slope's
  // polynomial per interval): slope()'s values to round-off, any order, the
  // knots themselves included; outside the table it throws as slope() does.
  std::vector<double> x, y;
  for (int i = 0; i <= 50; ++i) {
    const double t = -1.0 + 2.0 * i / 50.0;
    x.push_back(2.0 * t + 0.3 * std::sin(2.0 * t));
    y.push_back(std::cosh(x.back()) + 0.1 * x.back());
  }
  const PunchProfile tab(ProfileKind::table, 0.0, 0.0, x, y);
  std::vector<double> pts;
  for (int i = 0; i <= 700; ++i) pts.push_back(x.front() + (x.back() - x.front()) * i / 700.0);
  pts.insert(pts.end(), x.begin(), x.end());
  std::sort(pts.begin(), pts.end());
  std::vector<double> out(pts.size());
  tab.slopes(pts.data(), static_cast<int>(pts.size()), out.data());
  for (std::size_t i = 0; i < pts.size(); ++i)
    EXPECT_NEAR(out[i], tab.slope(pts[i]), 1e-13 * (1.0 + std::fabs(tab.slope(pts[i])))) << i;
  std::reverse(pts.begin(), pts.end());  // descending: one by one
  tab.slopes(pts.data(), static_cast<int>(pts.size()), out.data());
  for (std::size_t i = 0; i < pts.size(); ++i) EXPECT_EQ(out[i], tab.slope(pts[i])) << i;
  const double beyond[2] = {0.0, x.back() + 0.1};
  double two[2];
  EXPECT_THROW(tab.slopes(beyond, 2, two), std::domain_error);
}

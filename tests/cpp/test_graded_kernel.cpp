// A graded TOP sublayer (issue 26): the kernel's slow asymptotics taken out
// exactly (docs/theory.md section 16.5), each piece against an independent
// anchor: the series of the graded half-space (Cauchy's integral at complex
// gamma/t) against graded_top_asymptotics' real differences and against the
// propagated M1 at large t; the closed-form sine transforms of the
// subtracted functions against quadrature; the exact moments of the singular
// terms against adaptive quadrature; the contact's N convergence against a
// tight reference, and the limit gamma -> 0 against the homogeneous layer.
// And a stack's kernel from its wide first panels (Medium::panel_scale)
// against a plain adaptive quadrature on unit intervals.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include "gauss_kronrod.hpp"
#include "movingpunch/collocation.hpp"
#include "movingpunch/contact.hpp"
#include "movingpunch/kernel.hpp"
#include "movingpunch/medium.hpp"
#include "stack.hpp"

using namespace movingpunch;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Adaptive Gauss-Kronrod (15 points) of f on [lo, hi] to absolute tol.
double adaptive(const std::function<double(double)>& f, double lo, double hi, double tol,
                int depth = 0) {
  const double c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
  double k = 0.0, g = 0.0;
  for (int j = 0; j < 8; ++j) {
    const double x = detail::kXgk[j];
    const double fs = j == 7 ? f(c) : f(c - h * x) + f(c + h * x);
    k += detail::kWgk[j] * fs;
    if (j % 2 == 1) g += detail::kWg[j / 2] * fs;
  }
  if (std::fabs(k - g) * h <= tol || depth > 50) return k * h;
  return adaptive(f, lo, c, 0.5 * tol, depth + 1) + adaptive(f, c, hi, 0.5 * tol, depth + 1);
}

// Tanh-sinh quadrature of f on [lo, hi] (step 1/64, |t| <= 3.5): exact to
// ~1e-15 for integrands with logarithmic or power singularities at the ends;
// the abscissae near an end are formed from their distance to it.
double tanh_sinh(const std::function<double(double)>& f, double lo, double hi) {
  const double half = 0.5 * (hi - lo), hstep = 1.0 / 64.0;
  double sum = 0.0;
  for (int i = -224; i <= 224; ++i) {
    const double t = i * hstep;
    const double y = 0.5 * kPi * std::sinh(std::fabs(t));
    const double delta = 2.0 / (1.0 + std::exp(2.0 * y));  // 1 - tanh(y)
    const double w = 0.5 * kPi * std::cosh(t) / (std::cosh(y) * std::cosh(y));
    if (delta <= 0.0) continue;
    const double x = t >= 0.0 ? hi - half * delta : lo + half * delta;
    sum += w * f(x);
  }
  return sum * half * hstep;
}

MediumSpec graded_top(double gamma, double kw, double nu = 0.2) {
  MediumSpec m;
  Sublayer l;
  l.thickness = 1.0;
  l.nu = nu;
  l.gamma = gamma;
  m.layers = {l};
  m.base.kind = BaseKind::springs;
  m.base.kw = kw;
  return m;
}

ContactParams graded_params(double gamma, double vstar, double kw, double tol, int n = 0) {
  ContactParams p;
  p.vstar = vstar;
  p.kw = kw;
  p.nu = 0.2;
  p.radius = 10.0;
  p.load = 0.05;
  p.tol = tol;
  p.n = n;
  p.medium = std::make_shared<const MediumSpec>(graded_top(gamma, kw));
  return p;
}

}  // namespace

// c1, c2 by Cauchy's integral on a circle of complex gamma/t against the
// Richardson-extrapolated real differences of graded_top_asymptotics.
TEST(GradedKernel, SeriesAgreesWithRealDifferences) {
  for (const auto& [vstar, nu] : {std::pair{0.0, 0.2}, {0.3, 0.2}, {0.5, 0.3}, {0.8, 0.25}}) {
    const GradedSeries s = graded_top_series(vstar, nu, 10);
    const GradedAsymptotics g = graded_top_asymptotics(vstar, nu);
    EXPECT_LT(s.agreement, 1e-11) << vstar;
    EXPECT_NEAR(s.c[0], wave_constants(vstar, nu).phi1, 1e-11 * std::fabs(s.c[0]));
    // Near the Rayleigh speed (vstar 0.8, phi1 = 7.5: a pole of F at |eps|
    // ~ 0.09) the real differences (step 2e-3) carry ~1e-7 relative.
    const double rel = vstar > 0.6 ? 2e-7 : 1e-8;
    EXPECT_NEAR(s.c[1], g.c1, rel * std::max(1.0, std::fabs(g.c1))) << vstar;
    EXPECT_NEAR(s.c[2], g.c2, 10.0 * rel * std::max(1.0, std::fabs(g.c2))) << vstar;
  }
}

// The propagated M1 of a graded layer (stack.cpp: Taylor slices of the
// graded generator) at large t against the series sum c_k (gamma/t)^k:
// the bottom's reflection is below e^-2 nT t there.
TEST(GradedKernel, SeriesMatchesThePropagatedResponseAtLargeT) {
  for (const double gamma : {1.0, 5.0, -3.0}) {
    for (const double vstar : {0.0, 0.3}) {
      const auto med = make_stack_medium(graded_top(gamma, 1.0), vstar);
      const GradedSeries s = graded_top_series(vstar, 0.2, 20);
      for (const double t : {40.0, 80.0, 200.0}) {
        const double eps = gamma / t;
        double F = 0.0;
        for (int k = 20; k >= 0; --k) F = F * eps + s.c[static_cast<std::size_t>(k)];
        const double m1 = med->surface_response(t).M1.real();
        EXPECT_NEAR(m1, F, 5e-13 * std::fabs(F)) << gamma << " " << vstar << " " << t;
      }
    }
  }
}

// The closed-form sine transforms of R_k (kernel.hpp's KernelSubtraction):
// the singular and smooth parts together against the defining integral
// (1/(k-1)!) int_0^L s^(k-1) u/(s^2 + u^2) ds, and S(t) against its own
// integral representation, and the whole transform against a direct
// quadrature of int_0^inf R_k(t) sin(t u) dt (tail by integration by parts).
TEST(GradedKernel, ClosedFormTransformsAgreeWithQuadrature) {
  const double L = 0.3;
  for (int k = 1; k <= 8; ++k) {
    KernelSubtraction s;
    s.L = L;
    s.b.assign(static_cast<std::size_t>(k), 0.0);
    s.b.back() = 1.0;
    double fact = 1.0;
    for (int i = 2; i < k; ++i) fact *= i;  // (k-1)!
    for (const double u : {-2.5, -0.4, 0.05, 0.7, 3.0}) {
      const double exact = s.smooth(u) + s.singular(u);
      const double ref =
          adaptive([&](double x) { return std::pow(x, k - 1) * u / (x * x + u * u); }, 0.0, L,
                   1e-16) /
          fact;
      EXPECT_NEAR(exact, ref, 1e-13 * std::max(1.0, std::fabs(ref))) << k << " " << u;
    }
    for (const double t : {0.0, 0.01, 1.0, 30.0, 150.0, 1000.0}) {
      // Absolute tolerance 1e-15 of the integral's size, min(L^k/k, (k-1)!/t^k).
      const double size = std::min(std::pow(L, k) / k, fact / std::pow(t, k));
      const double ref = adaptive([&](double x) { return std::pow(x, k - 1) * std::exp(-t * x); },
                                  0.0, L, 1e-15 * size) /
                         fact;
      EXPECT_NEAR(s.value(t), ref, 1e-13 * std::fabs(ref) + 1e-300) << k << " " << t;
    }
    // The sine transform itself, the integral in t: on [0, T] by quadrature,
    // beyond T (R_k = t^-k to e^-LT) by the asymptotic series of
    // int_T^inf t^-k sin(t u) dt.
    if (k != 1 && k != 2 && k != 5) continue;
    for (const double u : {1.3}) {
      const double T = 60.0;
      double num = 0.0;
      for (double lo = 0.0; lo < T; lo += 1.0)
        num +=
            adaptive([&](double x) { return s.value(x) * std::sin(x * u); }, lo, lo + 1.0, 1e-14);
      // int_T^inf t^-k sin(tu) dt = sum_j (k)_j u^-(j+1) T^-(k+j) cos(T u - j pi/2)
      // (integration by parts; (k)_j the rising factorial).
      double tail = 0.0, coef = 1.0 / u;
      double pw = std::pow(T, -k);
      for (int j = 0; j < 12; ++j) {
        tail += coef * pw * std::cos(T * u - 0.5 * kPi * j);
        coef *= (k + j) / u;
        pw /= T;
      }
      const double exact = s.smooth(u) + s.singular(u);
      EXPECT_NEAR(num + tail, exact, 1e-9) << k << " " << u;
    }
  }
}

// The exact moments int sqrt(1 - r^2) U_n(r) (r - s)^p sigma(r - s) dr
// against tanh-sinh quadrature in theta = acos r (sqrt(1 - r^2) U_n dr =
// sin((n+1) theta) sin(theta) d theta, smooth), split at theta = acos s.
TEST(GradedKernel, SingularMomentsAgreeWithQuadrature) {
  for (const double s : {0.0, 0.37, 0.93}) {
    const double ts = std::acos(s);
    for (const int p : {0, 1, 2, 5}) {
      for (int sigma = 0; sigma <= 2; ++sigma) {
        const std::vector<double> m = singular_moments(10, p, sigma, s);
        for (int n = 0; n < 10; ++n) {
          auto f = [&](double th) {
            const double d = std::cos(th) - s;
            const double sg = sigma == 0   ? 1.0
                              : sigma == 1 ? (d < 0 ? -1.0 : 1.0)
                                           : (d == 0 ? 0.0 : std::log(std::fabs(d)));
            return std::sin((n + 1) * th) * std::sin(th) * std::pow(d, p) * sg;
          };
          const double ref = tanh_sinh(f, 0.0, ts) + tanh_sinh(f, ts, kPi);
          EXPECT_NEAR(m[static_cast<std::size_t>(n)], ref, 1e-11)
              << s << " " << p << " " << sigma << " " << n;
        }
      }
    }
  }
}

// The kernel: direct Filon values of the whole k1 (table + closed forms)
// against an independent plain quadrature of int_0^A (M1 - phi1)/phi1 sin(t u)
// plus the series' tail beyond A in closed form (sum of a_k gamma^k times
// int_A^inf t^-k sin(tu) dt by integration by parts).
TEST(GradedKernel, KernelAgreesWithPlainQuadratureAndSeriesTail) {
  const double gamma = 2.0, vstar = 0.3;
  const auto med = make_stack_medium(graded_top(gamma, 1.0), vstar);
  const KernelK1 k(med, 1e-12, 4.0);
  ASSERT_FALSE(k.singular().empty());
  const double phi1 = med->phi1();
  const GradedSeries s = graded_top_series(vstar, 0.2, 20);
  const double A = 300.0;
  for (const double u : {0.3, 1.1, 3.0}) {
    double num = 0.0;
    for (double lo = 0.0; lo < A; lo += 0.5)
      num += adaptive(
          [&](double t) {
            return (med->surface_response(t).M1.real() - phi1) / phi1 * std::sin(t * u);
          },
          lo, lo + 0.5, 1e-15);
    double tail = 0.0;
    for (int kk = 1; kk <= 20; ++kk) {
      const double b = s.c[static_cast<std::size_t>(kk)] / phi1 * std::pow(gamma, kk);
      double part = 0.0, coef = 1.0 / u, pw = std::pow(A, -kk);
      for (int j = 0; j < 12; ++j) {
        part += coef * pw * std::cos(A * u - 0.5 * kPi * j);
        coef *= (kk + j) / u;
        pw /= A;
      }
      tail += b * part;
    }
    EXPECT_NEAR(k(u), num + tail, 1e-9) << u;
    EXPECT_NEAR(k.direct(u), k(u), 1e-11) << u;
  }
}

// The contact on a graded top (gamma 1, vstar 0.2): a/h at fixed N = 16, 32
// against a reference at tol 1e-10 (automatic N). Measured: 1.43e-6,
// 9.66e-8, 6.33e-9: N^-4 (the pressure itself carries (1 - r) ln(1 - r) at
// the ends, docs/theory.md section 16.5: no polynomial g converges faster),
// and every fixed-N estimate bounds its true error.
TEST(GradedKernel, ContactConvergesLikeNMinus4WithHonestEstimates) {
  const SymmetricSolution ref = solve_contact(graded_params(1.0, 0.2, 1.0, 1e-10));
  ASSERT_TRUE(ref.valid());
  EXPECT_LT(ref.error_estimate(), 1e-10 * ref.a());
  std::vector<double> err;
  for (const int n : {16, 32}) {
    const SymmetricSolution s = solve_contact(graded_params(1.0, 0.2, 1.0, 1e-12, n));
    err.push_back(std::fabs(s.a() - ref.a()));
    EXPECT_LE(err.back(), s.error_estimate() + ref.error_estimate()) << n;
  }
  EXPECT_LT(err[0], 3e-6);
  const double rate = std::log2(err[0] / err[1]);
  EXPECT_GT(rate, 3.5);
  EXPECT_LT(rate, 5.0);
}

// gamma -> 0: the homogeneous layer, linearly in gamma.
TEST(GradedKernel, SmallGammaTendsToTheHomogeneousLayerLinearly) {
  ContactParams p0 = graded_params(0.0, 0.3, 1.0, 1e-13);  // the homogeneous layer
  p0.medium.reset();
  const SymmetricSolution h = solve_contact(p0);
  ASSERT_TRUE(h.valid());
  const SymmetricSolution g4 = solve_contact(graded_params(1e-4, 0.3, 1.0, 1e-13));
  const SymmetricSolution g6 = solve_contact(graded_params(1e-6, 0.3, 1.0, 1e-13));
  const double d4 = (g4.a() - h.a()) / 1e-4, d6 = (g6.a() - h.a()) / 1e-6;
  EXPECT_GT(std::fabs(d4), 1e-3);  // the grading moves a/h at first order
  EXPECT_NEAR(d4, d6, 2e-3 * std::fabs(d6));
}

// The collocation's pair sums on a graded top (the regular part: the table
// holds the quadrature's values plus the smooth closed forms): sum_many
// interleaves the table's recurrences, the same arithmetic as sum(), bit for
// bit; and sum is the whole k1 less its singular terms at both points.
TEST(GradedKernel, PairSumsOfTheRegularPartMatchBitForBit) {
  const auto med = make_stack_medium(graded_top(2.0, 1.0), 0.05);
  const KernelK1 k(med, 1e-10, 2.0);
  ASSERT_FALSE(k.singular().empty());
  ASSERT_FALSE(k.piecewise());
  const double L = k.range();
  for (std::size_t n : {0u, 1u, 3u, 4u, 9u, 64u}) {
    std::vector<double> u(n), v(n), out(n, -1.0);
    for (std::size_t i = 0; i < n; ++i) {
      u[i] = L * std::sin(0.37 * static_cast<double>(i) + 0.1);
      v[i] = -L * 0.999 * std::cos(0.11 * static_cast<double>(i));
    }
    k.sum_many(u.data(), v.data(), out.data(), n);
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_EQ(out[i], k.sum(u[i], v[i])) << n << " " << i;
      const double whole = k(u[i]) + k(v[i]);
      const double singular = k.subtraction().singular(u[i]) + k.subtraction().singular(v[i]);
      EXPECT_NEAR(out[i], whole - singular, 1e-12 * (1.0 + std::fabs(whole) + std::fabs(singular)));
    }
  }
}

// A stack's surface quadrature starts from panels Medium::panel_scale() wide
// (8 / decay_rate: a thin top sublayer's slow exponential tail), split where
// its own error estimate asks. Its k1 table against a plain adaptive
// quadrature of (M1 - phi1)/phi1 sin(alpha u) on unit intervals (the
// homogeneous layer's panels), and it takes fewer panels than unit ones.
TEST(StackKernel, ThinTopFromWidePanelsMatchesPlainQuadrature) {
  // bench_media's pavement: {thickness, mu, nu, rho, gamma} top to bottom.
  MediumSpec m;
  m.layers = {{0.2, 1.0, 0.35, 1.0, 0.0}, {0.3, 0.3, 0.3, 0.9, 0.0}, {0.5, 0.1, 0.3, 0.8, 0.0}};
  m.base.kind = BaseKind::springs;
  m.base.kw = 1.0;
  EXPECT_EQ(make_medium(homogeneous_medium(1.0, 0.2), 0.05)->panel_scale(), 1.0);
  for (const double vstar : {0.05, 0.11}) {
    const auto med = make_stack_medium(m, vstar);
    EXPECT_GT(med->panel_scale(), 4.0);
    const KernelK1 k(med, 1e-10, 2.0);
    const AlphaQuadrature& q = k.quadrature();
    EXPECT_LT(static_cast<double>(q.panel_centre.size()), 0.5 * q.alpha_max);
    const double phi1 = med->phi1();
    for (const double u : {0.05, 0.4, 1.1, 1.9}) {
      double plain = 0.0;
      for (double lo = 0.0; lo < q.alpha_max; lo += 1.0)
        plain += adaptive(
            [&](double t) {
              return (med->surface_response(t).M1.real() - phi1) / phi1 * std::sin(t * u);
            },
            lo, std::min(lo + 1.0, q.alpha_max), 1e-14);
      EXPECT_NEAR(k(u), plain, 1e-10) << "vstar " << vstar << " u " << u;
    }
  }
}

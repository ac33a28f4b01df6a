// Cooperative cancellation (movingpunch/interrupt.hpp): a poll that asks to
// stop ends a solve with Interrupted, through the ladders' own catch blocks;
// one that never asks changes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <utility>
#include <vector>

#include "movingpunch/asymmetric.hpp"
#include "movingpunch/contact.hpp"
#include "movingpunch/dispersion.hpp"
#include "movingpunch/interrupt.hpp"
#include "movingpunch/kernel.hpp"
#include "movingpunch/layer_response.hpp"
#include "roots.hpp"

namespace mp = movingpunch;
using namespace std::chrono_literals;

namespace {

// A solve that builds its own kernel table (a key no other test uses), so
// that it runs the quadrature, the table, the width secant and the ladder.
mp::ContactParams fresh_params() {
  mp::ContactParams p;
  p.vstar = 0.2137;
  p.kw = 1.37;
  p.radius = 100.0;
  p.load = 0.002;
  p.nu = 0.2;
  p.tol = 1e-8;
  return p;
}

}  // namespace

TEST(Interrupt, NoScopeNeverThrows) {
  EXPECT_EQ(mp::detail::current_interrupt_scope(), nullptr);
  for (int i = 0; i < 1000; ++i) EXPECT_NO_THROW(mp::check_interrupt());
}

TEST(Interrupt, PollIsRateLimited) {
  int calls = 0;
  mp::InterruptScope scope(
      [&] {
        ++calls;
        return false;
      },
      1h);
  for (int i = 0; i < 100000; ++i) mp::check_interrupt();
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(scope.polls(), 0u);
}

TEST(Interrupt, StoppedScopeStaysStoppedAndScopesNest) {
  int outer_calls = 0;
  mp::InterruptScope outer(
      [&] {
        ++outer_calls;
        return false;
      },
      0ns);
  {
    mp::InterruptScope inner([] { return true; }, 0ns);
    EXPECT_THROW(mp::check_interrupt(), mp::Interrupted);
    EXPECT_THROW(mp::check_interrupt(), mp::Interrupted);  // without polling again
    EXPECT_EQ(inner.polls(), 1u);
  }
  // The outer scope is back and does not stop.
  EXPECT_NO_THROW(mp::check_interrupt());
  EXPECT_EQ(outer_calls, 1);
  EXPECT_EQ(outer.polls(), 1u);
}

TEST(Interrupt, RootFindingStopsWhenAsked) {
  int evaluations = 0;
  auto f = [&](double x) {
    ++evaluations;
    return std::cos(x) - x;
  };
  {
    int polls = 0;
    mp::InterruptScope scope([&] { return ++polls >= 3; }, 0ns);
    EXPECT_THROW(mp::detail::bracketed_root(f, 0.0, 1.0, f(0.0), f(1.0), 1e-300, 200, 0.0),
                 mp::Interrupted);
  }
  EXPECT_LE(evaluations, 2 + 3);
  // Without a scope the same root is found (0.739085...).
  const double r = mp::detail::bracketed_root(f, 0.0, 1.0, f(0.0), f(1.0), 1e-14);
  EXPECT_NEAR(r, 0.7390851332151607, 1e-13);
}

// The ladder catches std::exception from a size that fails and moves on to
// the next: Interrupted is no std::exception, so the solve ends at once.
TEST(Interrupt, SolveEndsWithInterruptedNotAnotherError) {
  mp::clear_kernel_cache();
  int polls = 0;
  mp::InterruptScope scope([&] { return ++polls >= 2; }, 0ns);
  try {
    (void)mp::solve_contact(fresh_params());
    FAIL() << "the solve was not interrupted";
  } catch (const mp::Interrupted&) {
    SUCCEED();
  } catch (const std::exception& e) {
    FAIL() << "interrupted solve raised " << e.what();
  }
  EXPECT_EQ(polls, 2);
}

TEST(Interrupt, AsymmetricSolveEndsWithInterrupted) {
  mp::AsymmetricParams p;
  p.vstar = 0.2137;
  p.kw = 1.37;
  p.radius = 100.0;
  p.load = 0.002;
  p.damping = 0.0137;
  mp::clear_kernel_cache();
  mp::InterruptScope scope([] { return true; }, 0ns);
  EXPECT_THROW((void)mp::solve_asymmetric(p), mp::Interrupted);
}

// A poll that never stops changes nothing: the same result, bit for bit, as
// the solve without a scope (both build the kernel table afresh), and it was
// asked.
TEST(Interrupt, PollThatNeverStopsChangesNothing) {
  mp::clear_kernel_cache();
  const mp::SymmetricSolution plain = mp::solve_contact(fresh_params());
  mp::clear_kernel_cache();
  std::uint64_t polls = 0;
  double a = 0, err = 0;
  {
    mp::InterruptScope scope([] { return false; }, 0ns);
    const mp::SymmetricSolution s = mp::solve_contact(fresh_params());
    a = s.a();
    err = s.error_estimate();
    polls = scope.polls();
  }
  EXPECT_EQ(a, plain.a());
  EXPECT_EQ(err, plain.error_estimate());
  EXPECT_GT(polls, 10u);
}

// Red-team item 4: 1e-7 below V*_cr on a stiff Pasternak base (V*_cr = V*_R
// there) the damped quadrature's panels reached its bottom response's
// round-off and kept splitting to the evaluation cap (20145 panels; every
// kernel table built on them then took minutes). Now they stop at the
// round-off, and the integral of (M1 - phi1)/phi1 agrees with the undamped
// quadrature's (an independent rule and stopping test on the same M1) to
// 1e-10 relative.
TEST(BoundedWork, AsymmetricQuadratureNearCriticalStopsAtRoundOff) {
  const double kw = 1e4, nu = 0.4048225797622928, kp = 3.0;
  const double v = mp::critical_vstar(kw, nu, kp) * (1.0 - 1e-7);
  const auto damped = mp::make_medium(mp::homogeneous_medium(kw, nu, kp, 0.0), v);
  const mp::AsymmetricQuadrature q = mp::build_damped_quadrature(*damped, 1e-15, 0.0);
  EXPECT_LT(q.panels.panel_centre.size(), 2000u);
  const auto undamped = mp::make_medium(mp::homogeneous_medium(kw, nu, kp), v);
  // Reach::field (the decay of the field at the bottom): the undamped rule then ends near the
  // damped one's alpha_max (144.2 and 144.5). So close to V*_R, (M1 - phi1)/phi1 carries a
  // round-off offset of about eps/(1 - V/V*_R) = 2e-9 at every alpha (phi1 is computed to that
  // relative accuracy), which the integral gathers over its range: the two must end at about the
  // same alpha to agree to 1e-10.
  const mp::AlphaQuadrature u = mp::build_alpha_quadrature(*undamped, 1e-13, 1.0, mp::Reach::field);
  EXPECT_NEAR(u.alpha_max, q.panels.alpha_max, 1.0);
  const double phi1 = damped->phi1();
  auto integral = [&](const mp::AlphaQuadrature& a) {
    double s = 0.0, s_abs = 0.0;
    for (std::size_t i = 0; i < a.alpha.size(); ++i) {
      s += a.weight[i] * (a.m1[i] - phi1) / phi1;
      s_abs += a.weight[i] * std::fabs((a.m1[i] - phi1) / phi1);
    }
    return std::pair{s, s_abs};
  };
  const auto [sd, sd_abs] = integral(q.panels);
  const auto [su, su_abs] = integral(u);
  EXPECT_NEAR(sd, su, 1e-10 * std::max(sd_abs, su_abs));
}

// The damped kernel's tables take both Filon sums of a point at once
// (integral_pair_exact: one sin/cos per panel for both): the same numbers,
// bit for bit, as two integral() calls.
TEST(BoundedWork, ExactFilonPairIsTwoIntegralsBitForBit) {
  const mp::AlphaQuadrature q = mp::build_alpha_quadrature(
      *mp::make_medium(mp::homogeneous_medium(1.0, 0.2), 0.3), 1e-10, 5.0);
  const mp::FilonIntegrator f(q);
  std::vector<double> g1(q.alpha.size()), g2(q.alpha.size());
  for (std::size_t i = 0; i < g1.size(); ++i) {
    g1[i] = std::exp(-q.alpha[i]) * std::cos(3.0 * q.alpha[i]);
    g2[i] = 1.0 / (1.0 + q.alpha[i] * q.alpha[i]);
  }
  const std::vector<double> c1 = f.coefficients(g1), c2 = f.coefficients(g2);
  for (double x : {-37.5, -1.0, -1e-3, 0.0, 0.25, 2.0, 11.0, 400.0}) {
    const auto [a, b] = f.integral_pair_exact(x, c1, c2);
    const auto a1 = f.integral_exact(x, c1), b1 = f.integral_exact(x, c2);
    EXPECT_EQ(a.real(), a1.real()) << x;
    EXPECT_EQ(a.imag(), a1.imag()) << x;
    EXPECT_EQ(b.real(), b1.real()) << x;
    EXPECT_EQ(b.imag(), b1.imag()) << x;
    // integral(): the phases by rotation, to a few 1e-15 of the sum of |terms|.
    const auto a2 = f.integral(x, c1);
    EXPECT_NEAR(a2.real(), a1.real(), 1e-14) << x;
    EXPECT_NEAR(a2.imag(), a1.imag(), 1e-14) << x;
  }
  // Coefficients of the first P panels only: the sum over those panels,
  // which is the whole sum less the rest's (g = 0 beyond them).
  const std::size_t P = static_cast<std::size_t>(f.panels()) / 2;
  std::vector<double> g_head(g1.begin(), g1.begin() + static_cast<std::ptrdiff_t>(15 * P));
  std::vector<double> g_zero = g1;
  std::fill(g_zero.begin() + static_cast<std::ptrdiff_t>(15 * P), g_zero.end(), 0.0);
  const std::vector<double> ch = f.coefficients(g_head), cz = f.coefficients(g_zero);
  ASSERT_EQ(ch.size(), 15 * P);
  for (double x : {0.0, 0.7, 9.0}) {
    EXPECT_NEAR(f.integral_exact(x, ch).real(), f.integral_exact(x, cz).real(), 1e-15) << x;
    EXPECT_NEAR(f.integral_exact(x, ch).imag(), f.integral_exact(x, cz).imag(), 1e-15) << x;
  }
  EXPECT_THROW(f.coefficients(std::vector<double>(16, 0.0)), std::invalid_argument);
}

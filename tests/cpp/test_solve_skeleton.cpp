// The solve skeleton shared by the undamped and damped contact solves
// (cpp/src/solve_skeleton.hpp, cpp/src/roots.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "chebyshev.hpp"
#include "movingpunch/asymmetric.hpp"
#include "movingpunch/contact.hpp"
#include "roots.hpp"
#include "solve_skeleton.hpp"
#include "test_helpers.hpp"

namespace mp = movingpunch;
namespace d = movingpunch::detail;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Runs bracketed_root on f, counting evaluations.
struct Counted {
  double root = 0;
  int evaluations = 0;
};
template <class F>
Counted root_of(F f, double lo, double hi, double xtol, d::Safeguard sg, double ftol = 0.0) {
  Counted c;
  auto g = [&](double x) {
    ++c.evaluations;
    return f(x);
  };
  c.root = d::bracketed_root(g, lo, hi, f(lo), f(hi), xtol, 200, ftol, sg);
  return c;
}

}  // namespace

TEST(BracketedRoot, BothSafeguardsFindTheClosedFormRoot) {
  // x^3 = 2 on [0, 2]: the root is 2^(1/3).
  const auto f = [](double x) { return x * x * x - 2.0; };
  for (auto sg :
       {d::Safeguard::kFrequentBisection, d::Safeguard::kStalledBracket, d::Safeguard::kSecant}) {
    const Counted c = root_of(f, 0.0, 2.0, 1e-15, sg);
    EXPECT_NEAR(c.root, std::cbrt(2.0), 4e-15);
  }
}

TEST(BracketedRoot, StalledBracketSafeguardKeepsIllinoisFast) {
  // The 1 % / every-fourth-step bisections make the frequent safeguard
  // linear near the root; the stalled-bracket one keeps Illinois' order
  // (the damped width needs ~10 evaluations per size, not ~50).
  const auto f = [](double x) { return std::log(x) + 2.0 * x - 1.0; };  // increasing
  const Counted slow = root_of(f, 0.1, 3.0, 1e-15, d::Safeguard::kFrequentBisection);
  const Counted fast = root_of(f, 0.1, 3.0, 1e-15, d::Safeguard::kStalledBracket);
  EXPECT_NEAR(fast.root, slow.root, 4e-15);
  EXPECT_LT(std::fabs(f(fast.root)), 1e-14);
  EXPECT_LE(fast.evaluations, 15);
  EXPECT_LT(fast.evaluations, slow.evaluations);
}

TEST(BracketedRoot, SecantConvergesFromOneSideOfAConvexFunction) {
  // The shape of the width's load in x = ln w: ln lambda = 2 x + ln(1 + e^x)
  // (Hertz's w^2, stiffened by the foundation), convex, bracketed about as
  // the solver brackets it. Regula falsi keeps one end of the bracket and
  // waits for Illinois' halving; the secant on the last two points goes on
  // from one side. The root is -1.25 by construction.
  const double c = -2.5 + std::log1p(std::exp(-1.25));
  const auto f = [c](double x) { return 2.0 * x + std::log1p(std::exp(x)) - c; };
  const Counted illinois = root_of(f, -1.45, -1.15, 1e-15, d::Safeguard::kStalledBracket, 1e-15);
  const Counted secant = root_of(f, -1.45, -1.15, 1e-15, d::Safeguard::kSecant, 1e-15);
  EXPECT_NEAR(secant.root, -1.25, 1e-15);
  EXPECT_NEAR(illinois.root, -1.25, 1e-15);
  EXPECT_LT(secant.evaluations, illinois.evaluations);
}

TEST(BracketedRoot, NonMonotoneFunctionGivesOneOfItsRoots) {
  // cos on [1, 8] changes sign once overall but has three roots inside
  // (pi/2, 3 pi/2, 5 pi/2): the answer is one of them, to round-off.
  const auto f = [](double x) { return std::cos(x); };
  for (auto sg :
       {d::Safeguard::kFrequentBisection, d::Safeguard::kStalledBracket, d::Safeguard::kSecant}) {
    const Counted c = root_of(f, 1.0, 8.0, 1e-14, sg);
    double best = std::numeric_limits<double>::infinity();
    for (int k : {1, 3, 5}) best = std::min(best, std::fabs(c.root - 0.5 * k * kPi));
    EXPECT_LT(best, 1e-13) << "root " << c.root;
  }
}

TEST(BracketedRoot, StopsAtAdjacentDoublesInsteadOfSpinning) {
  // xtol = 0 cannot be met: it stops when lo and hi are adjacent doubles
  // (before: all 200 steps), within a double of 1/3.
  const auto f = [](double x) { return x - 1.0 / 3.0; };
  for (auto sg :
       {d::Safeguard::kFrequentBisection, d::Safeguard::kStalledBracket, d::Safeguard::kSecant}) {
    const Counted c = root_of(f, 0.0, 1.0, 0.0, sg);
    EXPECT_LE(std::fabs(c.root - 1.0 / 3.0), 2.0 * std::numeric_limits<double>::epsilon());
    EXPECT_LT(c.evaluations, 200);
  }
}

TEST(BracketedRoot, FunctionToleranceReturnsTheTrialPoint) {
  const auto f = [](double x) { return x - 0.7; };
  const Counted c = root_of(f, 0.0, 1.0, 0.0, d::Safeguard::kStalledBracket, 1e-3);
  EXPECT_LE(std::fabs(f(c.root)), 1e-3);
  EXPECT_LE(c.evaluations, 3);  // regula falsi on a line: the first point is exact
}

TEST(SmoothInterpolant, NestedPointsReachRoundOffAndRefuseAKink) {
  // e^x sin(3x) on [0.2, 1.7]: entire, resolved at degree 32 or 64; each
  // degree evaluates only the points the last one lacked (second-kind
  // points nest), always in descending batches.
  int values = 0;
  bool descending = true;
  auto f = [](double x) { return std::exp(x) * std::sin(3.0 * x); };
  const d::SmoothInterpolant smooth(
      d::SmoothInterpolant::Batch{},
      [&](const std::vector<double>& xs, std::vector<double>& v) {
        for (std::size_t j = 0; j < xs.size(); ++j) {
          if (j > 0 && !(xs[j] < xs[j - 1])) descending = false;
          v[j] = f(xs[j]);
        }
        values += static_cast<int>(xs.size());
      },
      0.2, 1.7);
  ASSERT_TRUE(smooth.ok());
  EXPECT_TRUE(descending);
  EXPECT_TRUE(values == 17 || values == 33 || values == 65 || values == 129) << values;
  double worst = 0.0;
  for (int i = 0; i <= 1000; ++i) {
    const double x = 0.2 + 1.5 * i / 1000.0;
    worst = std::max(worst, std::fabs(smooth(x) - f(x)));
  }
  EXPECT_LT(worst, 1e-13);
  // |x - 1| has a kink: no degree reaches round-off.
  const d::SmoothInterpolant kink([](double x) { return std::fabs(x - 1.0); }, 0.2, 1.7);
  EXPECT_FALSE(kink.ok());
}

TEST(SolveSkeleton, LadderIsEvenIncreasingAndCapped) {
  const std::vector<int> all = d::size_ladder(1 << 20);
  ASSERT_EQ(all.size(), d::kSizes.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i] % 2, 0);
    if (i > 0) {
      EXPECT_GT(all[i], all[i - 1]);
    }
  }
  EXPECT_EQ(all.front(), 8);
  EXPECT_EQ(all.back(), 1024);
  const std::vector<int> damped = d::size_ladder(512);
  ASSERT_EQ(damped.size(), 13u);
  EXPECT_EQ(damped.back(), 512);
  EXPECT_TRUE(std::equal(damped.begin(), damped.end(), all.begin()));
}

TEST(SolveSkeleton, WidthGuessFollowsItsRule) {
  // Paper's case: the half-plane (Hertz) width sqrt(2 phi1 lambda / pi).
  const double phi1 = 1.3, lambda = 0.2;
  const d::WidthGuess hertz = d::width_guess(phi1, lambda, 1.0, 0.25);
  EXPECT_FALSE(hertz.use_wide);
  EXPECT_DOUBLE_EQ(hertz.a, std::sqrt(2.0 * phi1 * lambda / kPi));
  // Soft foundation: a_W = (1.5 lambda (1/kw + (1 - nu)/2))^(1/3) > max(1, a_H).
  const d::WidthGuess soft = d::width_guess(phi1, lambda, 1e-2, 0.25);
  EXPECT_TRUE(soft.use_wide);
  EXPECT_DOUBLE_EQ(soft.a, std::cbrt(1.5 * lambda * (100.0 + 0.375)));
  // Near V*_R (phi1 huge): a_H > 8 a_W, the layer's thickness bounds the contact.
  const d::WidthGuess rayleigh = d::width_guess(1e6, lambda, INFINITY, 0.25);
  EXPECT_TRUE(rayleigh.use_wide);
  EXPECT_DOUBLE_EQ(rayleigh.a, std::cbrt(1.5 * lambda * 0.375));
  // Always within the supported widths.
  EXPECT_EQ(d::width_guess(phi1, lambda, 1e-12, 0.25).a, d::kMaxA);
  EXPECT_EQ(d::width_guess(phi1, 1e-300, 1.0, 0.25).a, d::kMinA);
}

TEST(SolveSkeleton, BothSolversRefuseOutOfRangeWidthsWithTheSharedMessage) {
  mp::ContactParams u;
  u.vstar = 0.3;
  u.radius = 100.0;
  u.load = 1e-300;
  mp::AsymmetricParams dp;
  dp.vstar = 0.3;
  dp.radius = 100.0;
  dp.load = 1e-300;
  dp.damping = 0.1;
  const std::string range = "below the supported range 1e-10 <= a/h <= 50";
  try {
    (void)mp::solve_contact(u);
    FAIL() << "undamped: no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(range), std::string::npos) << e.what();
  }
  try {
    (void)mp::solve_asymmetric(dp);
    FAIL() << "damped: no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(range), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("radius * load must be >="), std::string::npos)
        << e.what();
  }
}

TEST(AsymmetricLazyOutputs, StressEstimateIsTheSameWhateverIsReadFirstAndFromAnyThread) {
  // The surface sigma_x's error estimate and the fine Fourier nodes are
  // computed on first use (about half a warm solve): the estimate must not
  // depend on whether the stress was read before it, nor on which of two
  // threads asks first; the stress must not depend on whether the estimate's
  // build (which also transforms the pressure's change) made the nodes.
  for (double friction : {0.0, 0.3}) {
    const mp::AsymmetricParams p = mp::testing::paper_asymmetric(0.3, 1.0, 0.1, friction);
    const mp::AsymmetricSolution first = mp::solve_asymmetric(p);
    const double est = first.stress_error_estimate();
    const double sx = first.surface_stress(first.centre() + 0.3 * first.half_width());
    ASSERT_TRUE(std::isfinite(est) && est > 0.0) << est;
    const mp::AsymmetricSolution second = mp::solve_asymmetric(p);
    EXPECT_EQ(second.surface_stress(second.centre() + 0.3 * second.half_width()), sx);
    EXPECT_EQ(second.stress_error_estimate(), est);
    // A copy shares the lazy state: two threads at once, one value.
    const mp::AsymmetricSolution third = mp::solve_asymmetric(p);
    const mp::AsymmetricSolution copy = third;
    double e1 = 0.0, e2 = 0.0, s1 = 0.0;
    std::thread a([&] { e1 = third.stress_error_estimate(); });
    std::thread b([&] {
      s1 = copy.surface_stress(copy.centre() + 0.3 * copy.half_width());
      e2 = copy.stress_error_estimate();
    });
    a.join();
    b.join();
    EXPECT_EQ(e1, est);
    EXPECT_EQ(e2, est);
    EXPECT_EQ(s1, sx);
  }
}

TEST(AsymmetricScanMemo, WarmSolvesReuseTheScanWithoutChangingAnyResult) {
  // Above V*_cr with light damping three contacts carry R P/(mu h^2) = 0.25
  // (docs/damped.md section 5). The scan's lambda(w) at its lattice points is
  // memoised per kernel table and N: a warm solve (memo hit), and one after a
  // fixed-n solve on the same table (another N in the memo), must give the
  // cold solve's numbers exactly; a cold solve from an empty cache too.
  mp::AsymmetricParams p = mp::testing::paper_asymmetric(0.65, 1.0, 0.01);
  p.load = 0.0025;
  auto same = [](const mp::AsymmetricSolution& a, const mp::AsymmetricSolution& b) {
    EXPECT_EQ(a.left(), b.left());
    EXPECT_EQ(a.right(), b.right());
    EXPECT_EQ(a.error_estimate(), b.error_estimate());
    EXPECT_EQ(a.stress_error_estimate(), b.stress_error_estimate());
    EXPECT_EQ(a.min_gap(), b.min_gap());
    EXPECT_EQ(a.other_half_widths(), b.other_half_widths());
  };
  mp::clear_kernel_cache();
  const mp::AsymmetricSolution cold = mp::solve_asymmetric(p);
  ASSERT_EQ(cold.other_half_widths().size(), 2u) << cold.validity();
  const mp::AsymmetricSolution warm = mp::solve_asymmetric(p);
  same(cold, warm);
  mp::AsymmetricParams fixed = p;
  fixed.n = 48;
  (void)mp::solve_asymmetric(fixed);
  same(cold, mp::solve_asymmetric(p));
  mp::clear_kernel_cache();
  same(cold, mp::solve_asymmetric(p));
  // The three states as docs/damped.md section 5 gives them (0.459, 0.728,
  // 1.120; the scan's linear interpolation: to ~1 %).
  const double w = 0.5 * (cold.right() - cold.left());
  EXPECT_NEAR(w, 0.459, 0.005);
  EXPECT_NEAR(cold.other_half_widths()[0], 0.728, 0.01);
  EXPECT_NEAR(cold.other_half_widths()[1], 1.120, 0.015);
}

// The graded top's ladder limit (contact.cpp, solve_bounded): exact for
// a_N = a + C N^-4 + D N^-5 at any three sizes, and it removes N^-4 from a
// sequence with an N^-6 remainder (the error falls from C N^-4 to O(N^-6)).
TEST(SolveSkeleton, LimitThroughThreeSizesRemovesNMinus4AndNMinus5) {
  auto seq = [](double n, double e) {
    return 0.4650568523 + 3.1 * std::pow(n, -4.0) - 7.0 * std::pow(n, -5.0) + e * std::pow(n, -6.0);
  };
  const int n[3] = {16, 24, 32};
  const double x[3] = {seq(16, 0.0), seq(24, 0.0), seq(32, 0.0)};
  EXPECT_NEAR(d::extrapolate_n4n5(n, x), 0.4650568523, 1e-15);
  const double y[3] = {seq(16, 50.0), seq(24, 50.0), seq(32, 50.0)};
  const double raw = std::fabs(y[2] - 0.4650568523);
  const double lim = std::fabs(d::extrapolate_n4n5(n, y) - 0.4650568523);
  EXPECT_LT(lim, 0.05 * raw);
  EXPECT_LT(lim, 50.0 * std::pow(32.0, -6.0));  // measured 0.6 of it
}

// Brent's minimiser (cpp/src/roots.hpp), the one behind the gap scan's dips
// (gap_scan.hpp) and the V*_cr search (dispersion.cpp), against closed-form
// minima: smooth, at an end of the interval, flat, with a kink, and
// non-unimodal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "roots.hpp"

namespace d = movingpunch::detail;

namespace {

constexpr double kPi = 3.14159265358979323846;

// brent_minimum from the golden point, recording every abscissa it evaluates.
struct BrentRun {
  d::Minimum min;
  std::vector<double> xs, fs;
};
template <class F>
BrentRun run_brent(F f, double a, double b, double xtol, double rtol = 0.0, int max_iter = 100) {
  BrentRun r;
  auto g = [&](double x) {
    const double v = f(x);
    r.xs.push_back(x);
    r.fs.push_back(v);
    return v;
  };
  r.min = d::brent_minimum(g, a, b, xtol, rtol, max_iter);
  return r;
}

// The contract every run keeps: f evaluated only inside [a, b], the returned
// value is f at the returned abscissa and the smallest value evaluated, and
// at most max_iter + 1 evaluations.
void expect_contract(const BrentRun& r, double a, double b, int max_iter) {
  ASSERT_FALSE(r.xs.empty());
  EXPECT_LE(static_cast<int>(r.xs.size()), max_iter + 1);
  for (double x : r.xs) {
    EXPECT_GE(x, a);
    EXPECT_LE(x, b);
  }
  EXPECT_EQ(r.min.f, *std::min_element(r.fs.begin(), r.fs.end()));
  const auto at = std::find(r.xs.begin(), r.xs.end(), r.min.x);
  ASSERT_NE(at, r.xs.end()) << "the returned x was never evaluated";
  EXPECT_EQ(r.fs[static_cast<std::size_t>(at - r.xs.begin())], r.min.f);
}

}  // namespace

// How far from a smooth minimum x* the computed f cannot tell points apart:
// f(x* + d) - f* = f'' d^2/2 is below the round-off of f* (about eps |f*|)
// for |d| < sqrt(2 eps |f*| / f''). No minimiser resolves x* better.
double round_off_width(double fmin, double fpp) {
  return std::sqrt(2.0 * std::numeric_limits<double>::epsilon() * std::fabs(fmin) / fpp);
}

TEST(BrentMinimum, SmoothMinimaToTheAbscissaTolerance) {
  // For a unimodal f the minimum stays inside the final bracket, which is
  // within 2 tol of x: |x - x*| <= 2 tol, or the round-off width of f* when
  // that is wider (the computed f is flat there).
  struct Case {
    double (*f)(double);
    double a, b, xmin, fmin, fpp;
  };
  const Case cases[] = {
      {[](double x) { return (x - 0.7) * (x - 0.7) + 2.0; }, 0.0, 2.0, 0.7, 2.0, 2.0},
      {[](double x) { return std::cos(x); }, 2.0, 5.0, kPi, -1.0, 1.0},
      {[](double x) { return x * std::log(x); }, 0.05, 2.0, std::exp(-1.0), -std::exp(-1.0),
       std::exp(1.0)},
      // A quartic minimum: flat to fourth order, the parabola fits it poorly
      // (f* = 0: no round-off floor).
      {[](double x) { return std::pow(x - 1.25, 4); }, -3.0, 4.0, 1.25, 0.0, 1.0},
      // exp(x) - 2x: minimum at ln 2, value 2 - 2 ln 2.
      {[](double x) { return std::exp(x) - 2.0 * x; }, -1.0, 3.0, std::log(2.0),
       2.0 - 2.0 * std::log(2.0), 2.0},
  };
  for (const Case& c : cases) {
    const double tol = 1e-8;
    const BrentRun r = run_brent(c.f, c.a, c.b, tol);
    expect_contract(r, c.a, c.b, 100);
    const double width = std::max(2.0 * tol, 2.0 * round_off_width(c.fmin, c.fpp));
    EXPECT_NEAR(r.min.x, c.xmin, width * (1.0 + 1e-9)) << "minimum at " << c.xmin;
    EXPECT_GE(r.min.f, c.fmin - 1e-15);
    // A quadratic minimum: f within (2 tol)^2 f''/2 of it; the quartic within (2 tol)^4.
    EXPECT_NEAR(r.min.f, c.fmin, 1e-14) << "minimum at " << c.xmin;
  }
}

TEST(BrentMinimum, ParabolicStepsConvergeInFewEvaluations) {
  // (x - 1)^2 e^x: minimum 0 at x = 1 (no round-off floor: f is a product).
  // Golden section alone needs log(3/1e-10)/log(1.618) ~ 50 evaluations;
  // the parabolic steps of a smooth minimum far fewer.
  const double tol = 1e-10;
  const BrentRun r =
      run_brent([](double x) { return (x - 1.0) * (x - 1.0) * std::exp(x); }, 0.0, 3.0, tol);
  expect_contract(r, 0.0, 3.0, 100);
  EXPECT_NEAR(r.min.x, 1.0, 2.0 * tol * (1.0 + 1e-9));
  EXPECT_LE(r.min.f, std::exp(1.0) * 4.0 * tol * tol * 1.01);
  EXPECT_LE(r.xs.size(), 20u);
}

TEST(BrentMinimum, RoundOffBoundsTheAbscissaNotTheValue) {
  // cos at pi: the computed cos is -1 exactly for |x - pi| below ~1.5e-8,
  // so a tol of 1e-12 cannot be met in x; x ends within the round-off width
  // and f is the minimum to the last bit.
  const double tol = 1e-12;
  const BrentRun r = run_brent([](double x) { return std::cos(x); }, 2.0, 5.0, tol);
  expect_contract(r, 2.0, 5.0, 100);
  EXPECT_NEAR(r.min.x, kPi, 2.0 * tol + 2.0 * round_off_width(-1.0, 1.0));
  EXPECT_EQ(r.min.f, -1.0);
}

TEST(BrentMinimum, MinimumAtAnEndOfTheInterval) {
  // Monotone on [a, b]: the minimum is the end, reached to within 2 tol
  // (f is never evaluated outside [a, b]).
  const double tol = 1e-9;
  {
    const BrentRun r = run_brent([](double x) { return std::exp(x); }, -1.0, 2.0, tol);
    expect_contract(r, -1.0, 2.0, 100);
    EXPECT_GE(r.min.x, -1.0);
    EXPECT_LE(r.min.x, -1.0 + 2.0 * tol * (1.0 + 1e-9));
    EXPECT_NEAR(r.min.f, std::exp(-1.0), 3.0 * tol);
  }
  {
    const BrentRun r = run_brent([](double x) { return -x * x * x; }, 0.5, 3.0, tol);
    expect_contract(r, 0.5, 3.0, 100);
    EXPECT_LE(r.min.x, 3.0);
    EXPECT_GE(r.min.x, 3.0 - 2.0 * tol * (1.0 + 1e-9));
    EXPECT_NEAR(r.min.f, -27.0, 27.0 * 2.0 * tol * 1.01);
  }
}

TEST(BrentMinimum, FromAGivenStartAtTheIntervalsEnd) {
  // The V*_cr search starts from its best grid point, which may be the
  // interval's end (the grid's first point): x0 = a with f(x0) known.
  auto f = [](double x) { return (x - 0.3) * (x - 0.3); };
  int evaluations = 0;
  auto g = [&](double x) {
    ++evaluations;
    EXPECT_GE(x, 0.0);
    EXPECT_LE(x, 1.0);
    return f(x);
  };
  const double tol = 1e-9;
  const d::Minimum m = d::brent_minimum(g, 0.0, 1.0, 0.0, f(0.0), tol, 0.0, 100);
  EXPECT_NEAR(m.x, 0.3, 2.0 * tol * (1.0 + 1e-9));
  EXPECT_LE(m.f, 4.0 * tol * tol * 1.01);
  EXPECT_LE(evaluations, 100);
  // The start is already the best point of a monotone function: x stays at
  // it (within 2 tol), never below a.
  auto rising = [](double x) { return x * x; };
  const d::Minimum e = d::brent_minimum(rising, 0.0, 1.0, 0.0, 0.0, tol, 0.0, 100);
  EXPECT_EQ(e.x, 0.0);
  EXPECT_EQ(e.f, 0.0);
}

TEST(BrentMinimum, FlatRegionAndConstantFunction) {
  // Zero on [0.3, 0.7], rising quadratically outside: any point of the flat
  // bottom is a minimum, and f there is exactly 0.
  auto flat = [](double x) {
    const double s = std::max(0.0, std::fabs(x - 0.5) - 0.2);
    return s * s;
  };
  const double tol = 1e-8;
  const BrentRun r = run_brent(flat, 0.0, 1.0, tol);
  expect_contract(r, 0.0, 1.0, 100);
  EXPECT_EQ(r.min.f, 0.0);
  EXPECT_GE(r.min.x, 0.3 - 2.0 * tol);
  EXPECT_LE(r.min.x, 0.7 + 2.0 * tol);
  // A constant: every point is a minimum; the search ends within its budget.
  const BrentRun c = run_brent([](double) { return 4.0; }, -2.0, 5.0, tol, 0.0, 30);
  expect_contract(c, -2.0, 5.0, 30);
  EXPECT_EQ(c.min.f, 4.0);
}

TEST(BrentMinimum, KinkedMinimum) {
  // |x - c| and an asymmetric kink: no parabola fits, golden section
  // brackets the kink; the same 2 tol bound holds.
  const double tol = 1e-9;
  {
    const BrentRun r = run_brent([](double x) { return std::fabs(x - 0.3); }, 0.0, 1.0, tol);
    expect_contract(r, 0.0, 1.0, 100);
    EXPECT_NEAR(r.min.x, 0.3, 2.0 * tol * (1.0 + 1e-9));
    EXPECT_LE(r.min.f, 2.0 * tol * (1.0 + 1e-9));
  }
  {
    const double c = 1.0 / 3.0;
    auto f = [c](double x) { return x < c ? 5.0 * (c - x) + 1.0 : 0.2 * (x - c) + 1.0; };
    const BrentRun r = run_brent(f, -4.0, 2.0, tol);
    expect_contract(r, -4.0, 2.0, 100);
    EXPECT_NEAR(r.min.x, c, 2.0 * tol * (1.0 + 1e-9));
    EXPECT_NEAR(r.min.f, 1.0, 5.0 * 2.0 * tol);
  }
}

TEST(BrentMinimum, RelativeToleranceAtALargeAbscissa) {
  // At x ~ 1e6 an absolute 1e-12 is below the spacing of doubles; the
  // relative part of tol (1e-12 |x|, as the gap scan uses) ends the search.
  const double x0 = 1.0e6 + 0.125;
  auto f = [x0](double x) { return (x - x0) * (x - x0); };
  const BrentRun r = run_brent(f, 1.0e6 - 50.0, 1.0e6 + 70.0, 1e-12, 1e-12, 60);
  expect_contract(r, 1.0e6 - 50.0, 1.0e6 + 70.0, 60);
  EXPECT_NEAR(r.min.x, x0, 2.0 * (1e-12 + 1e-12 * 1.0e6 * 1.001));
}

TEST(BrentMinimum, SeveralMinimaGiveALocalOne) {
  // cos(3x) on [0, 2 pi / 3 + 2 pi]: minima at pi/3, pi, 5 pi/3, 7 pi/3
  // (all -1): the result is one of them, never a point between.
  const double tol = 1e-9;
  const double b = 2.0 * kPi / 3.0 + 2.0 * kPi;
  const BrentRun r = run_brent([](double x) { return std::cos(3.0 * x); }, 0.0, b, tol);
  expect_contract(r, 0.0, b, 100);
  const double k = std::round((3.0 * r.min.x / kPi - 1.0) / 2.0);
  EXPECT_NEAR(r.min.x, (2.0 * k + 1.0) * kPi / 3.0, 1e-6);
  EXPECT_NEAR(r.min.f, -1.0, 1e-12);
}

TEST(BrentMinimum, BudgetEndsANonConvergingSearch) {
  // xtol 0 and rtol 0 never end by tolerance once the bracket reaches the
  // spacing of doubles: max_iter bounds the evaluations (no hang).
  const BrentRun r =
      run_brent([](double x) { return (x - 0.5) * (x - 0.5); }, 0.0, 1.0, 0.0, 0.0, 40);
  expect_contract(r, 0.0, 1.0, 40);
  EXPECT_NEAR(r.min.x, 0.5, 1e-7);
}

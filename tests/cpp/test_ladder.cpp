// The N-ladder driver (cpp/src/ladder.hpp: run_ladder) on synthetic step
// sequences: the sizes it visits, the chain and its changes, the stop on a
// verdict, and each failure policy (rethrow, refine with the chain
// restarted, counted or not, stop at the last size that solved).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "ladder.hpp"
#include "movingpunch/asymmetric.hpp"
#include "movingpunch/errors.hpp"
#include "solve_skeleton.hpp"

namespace mp = movingpunch;
namespace d = movingpunch::detail;

namespace {

// x_N = 1 + exp(-rate N): geometric convergence in N, exact limit 1.
double geometric(int n, double rate) { return 1.0 + std::exp(-rate * n); }

std::array<double, 1> change1(double prev, double cur) { return {std::fabs(cur - prev)}; }

// The symmetric solver's rule: the last change within tol, over three sizes.
d::Verdict change_rule(const d::LadderChain<double, 1>& c, double tol) {
  if (c.size() < 3) return d::Verdict::go_on;
  return c.changes[0].back() <= tol ? d::Verdict::converged : d::Verdict::go_on;
}

}  // namespace

TEST(Ladder, StopsAtTheFirstSizeWhoseChangeMeetsTol) {
  const std::vector<int> sizes = d::size_ladder(1024);
  std::vector<int> visited;
  int verdicts = 0;
  const auto run = d::run_ladder<1, double>(
      sizes,
      [&](int n) {
        visited.push_back(n);
        return geometric(n, 0.5);
      },
      change1,
      [&](const d::LadderChain<double, 1>& c) {
        ++verdicts;
        return change_rule(c, 1e-10);
      },
      d::RethrowFailures{});
  // Independently: the first size n_k (k >= 2) with |x_k - x_{k-1}| <= 1e-10.
  std::size_t stop = 2;
  while (std::fabs(geometric(sizes[stop], 0.5) - geometric(sizes[stop - 1], 0.5)) > 1e-10) ++stop;
  ASSERT_EQ(visited, std::vector<int>(sizes.begin(), sizes.begin() + stop + 1));
  EXPECT_EQ(run.verdict, d::Verdict::converged);
  EXPECT_FALSE(run.failed);
  EXPECT_EQ(verdicts, static_cast<int>(stop + 1));  // one per solved size, the first too
  EXPECT_EQ(run.chain.sizes, visited);
  ASSERT_EQ(run.chain.changes[0].size(), visited.size() - 1);
  for (std::size_t k = 1; k < visited.size(); ++k) {
    EXPECT_EQ(run.chain.states[k], geometric(visited[k], 0.5));
    // changes[k - 1] belongs to sizes[k] (refinement_estimate's convention).
    EXPECT_EQ(run.chain.changes[0][k - 1],
              std::fabs(geometric(visited[k], 0.5) - geometric(visited[k - 1], 0.5)));
  }
}

TEST(Ladder, RunsOutOfSizesWithoutAVerdict) {
  const std::vector<int> sizes = {8, 12, 16};
  const auto run = d::run_ladder<1, double>(
      sizes, [](int n) { return geometric(n, 0.01); }, change1,
      [](const d::LadderChain<double, 1>& c) { return change_rule(c, 1e-12); },
      d::RethrowFailures{});
  EXPECT_EQ(run.verdict, d::Verdict::go_on);
  EXPECT_FALSE(run.failed);
  EXPECT_EQ(run.chain.sizes, sizes);
}

TEST(Ladder, AStalledVerdictStopsTheLadder) {
  std::vector<int> visited;
  const auto run = d::run_ladder<1, double>(
      d::size_ladder(1024),
      [&](int n) {
        visited.push_back(n);
        return 1.0;
      },
      change1,
      [](const d::LadderChain<double, 1>& c) {
        return c.size() >= 2 ? d::Verdict::stalled : d::Verdict::go_on;
      },
      d::RethrowFailures{});
  EXPECT_EQ(run.verdict, d::Verdict::stalled);
  EXPECT_EQ(visited, (std::vector<int>{8, 12}));
}

TEST(Ladder, RethrowKeepsTheFailuresType) {
  auto solve = [](int n) -> double {
    if (n == 16) throw mp::ConvergenceError("no root at N = 16");
    return 1.0;
  };
  auto never = [](const d::LadderChain<double, 1>&) { return d::Verdict::go_on; };
  EXPECT_THROW(
      (d::run_ladder<1, double>({8, 12, 16, 24}, solve, change1, never, d::RethrowFailures{})),
      mp::ConvergenceError);
  // A failure policy may throw a failure of its own (a better message).
  EXPECT_THROW(
      (d::run_ladder<1, double>({8, 12, 16, 24}, solve, change1, never,
                                [](const std::exception&, const d::LadderAt&) -> d::OnFailure {
                                  throw std::invalid_argument("refused");
                                })),
      std::invalid_argument);
}

TEST(Ladder, RefineRestartsTheChainAndCountsFailuresInARow) {
  // Sizes 12 and 16 fail; 24, 32, 48 solve: the chain restarts at 24.
  std::vector<d::LadderAt> seen;
  const auto run = d::run_ladder<1, double>(
      {8, 12, 16, 24, 32, 48},
      [](int n) -> double {
        if (n == 12 || n == 16) throw mp::ConvergenceError("under-resolved");
        return geometric(n, 0.3);
      },
      change1, [](const d::LadderChain<double, 1>&) { return d::Verdict::go_on; },
      [&](const std::exception&, const d::LadderAt& at) {
        seen.push_back(at);
        return d::OnFailure::refine;
      });
  EXPECT_EQ(run.chain.sizes, (std::vector<int>{24, 32, 48}));
  EXPECT_EQ(run.chain.changes[0].size(), 2u);
  EXPECT_EQ(run.chain.changes[0][0], std::fabs(geometric(32, 0.3) - geometric(24, 0.3)));
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].n, 12);
  EXPECT_EQ(seen[0].index, 1u);
  EXPECT_EQ(seen[0].solved, 1);
  EXPECT_EQ(seen[0].failures, 0);
  EXPECT_FALSE(seen[0].last);
  EXPECT_EQ(seen[1].n, 16);
  EXPECT_EQ(seen[1].failures, 1);  // one counted failure before it
}

TEST(Ladder, UncountedFailuresDoNotCountAndASuccessResetsTheCount) {
  // 12 fails (counted), 16 fails (uncounted), 24 solves, 32 fails, 48 (last) fails.
  std::vector<d::LadderAt> seen;
  auto fail_at = [](int n) { return n == 12 || n == 16 || n == 32 || n == 48; };
  EXPECT_THROW((d::run_ladder<1, double>(
                   {8, 12, 16, 24, 32, 48},
                   [&](int n) -> double {
                     if (fail_at(n)) throw mp::ConvergenceError("N = " + std::to_string(n));
                     return 1.0;
                   },
                   change1, [](const d::LadderChain<double, 1>&) { return d::Verdict::go_on; },
                   [&](const std::exception&, const d::LadderAt& at) {
                     seen.push_back(at);
                     if (at.last) return d::OnFailure::rethrow;
                     return at.n == 16 ? d::OnFailure::refine_uncounted : d::OnFailure::refine;
                   })),
               mp::ConvergenceError);
  ASSERT_EQ(seen.size(), 4u);
  EXPECT_EQ(seen[1].failures, 1);  // 16: after the counted failure at 12
  EXPECT_EQ(seen[2].n, 32);
  EXPECT_EQ(seen[2].failures, 0);  // 24 solved in between
  EXPECT_EQ(seen[2].solved, 2);
  EXPECT_EQ(seen[3].n, 48);
  EXPECT_EQ(seen[3].failures, 1);
  EXPECT_TRUE(seen[3].last);
}

TEST(Ladder, StopKeepsTheLastSizeThatSolved) {
  const auto run = d::run_ladder<1, double>(
      {8, 12, 16, 24},
      [](int n) -> double {
        if (n == 16) throw mp::ConvergenceError("no root near the coarser one");
        return geometric(n, 0.2);
      },
      change1, [](const d::LadderChain<double, 1>&) { return d::Verdict::go_on; },
      [](const std::exception&, const d::LadderAt&) { return d::OnFailure::stop; });
  EXPECT_TRUE(run.failed);
  EXPECT_EQ(run.failed_n, 16);
  EXPECT_EQ(run.verdict, d::Verdict::go_on);
  EXPECT_EQ(run.chain.sizes, (std::vector<int>{8, 12}));
  EXPECT_EQ(run.chain.last(), geometric(12, 0.2));
}

// Two quantities with the asymmetric solver's estimates and rule
// (refinement_estimate, ladder_stop): the ladder stops converged, and the
// reported estimates bound the true errors of the last size.
TEST(Ladder, TwoQuantitiesWithTheRefinementEstimatesBoundTheirErrors) {
  struct State {
    double u, v;
  };
  auto u_at = [](int n) { return 2.0 + 3.0 * std::exp(-0.4 * n); };
  auto v_at = [](int n) { return -1.0 + 0.5 * std::exp(-0.25 * n); };
  mp::RefinementEstimate eu, ev;
  const double tol = 1e-9;
  const auto run = d::run_ladder<2, State>(
      d::size_ladder(512), [&](int n) { return State{u_at(n), v_at(n)}; },
      [](const State& a, const State& b) {
        return std::array<double, 2>{std::fabs(b.u - a.u), std::fabs(b.v - a.v)};
      },
      [&](const d::LadderChain<State, 2>& c) {
        if (c.size() < 3) return d::Verdict::go_on;
        eu = mp::refinement_estimate(c.sizes, c.changes[0], 1e-16);
        ev = mp::refinement_estimate(c.sizes, c.changes[1], 1e-16);
        return d::ladder_verdict(
            mp::ladder_stop(tol, eu, c.changes[0].back(), 2.0, ev, c.changes[1].back(), 1.0));
      },
      d::RethrowFailures{});
  ASSERT_EQ(run.verdict, d::Verdict::converged);
  const int n = run.chain.sizes.back();
  EXPECT_GE(eu.estimate, std::fabs(u_at(n) - 2.0));
  EXPECT_GE(ev.estimate, std::fabs(v_at(n) + 1.0));
  EXPECT_LE(ev.estimate, tol * 1.0);
  // Not one size later than needed: the previous size's true error was
  // above tol (v converges slower, and drives the stop).
  const int prev = run.chain.sizes[run.chain.size() - 2];
  EXPECT_GT(std::fabs(v_at(prev) + 1.0), 1e-2 * tol);
}

TEST(Ladder, VerdictOfLadderStop) {
  EXPECT_EQ(d::ladder_verdict(mp::LadderStop::go_on), d::Verdict::go_on);
  EXPECT_EQ(d::ladder_verdict(mp::LadderStop::converged), d::Verdict::converged);
  EXPECT_EQ(d::ladder_verdict(mp::LadderStop::stalled), d::Verdict::stalled);
}

TEST(Ladder, OnlyTheSolvesFailuresGoToTheFailurePolicy) {
  int seen = 0;
  auto count = [&](const std::exception&, const d::LadderAt&) {
    ++seen;
    return d::OnFailure::refine;
  };
  auto go_on = [](const d::LadderChain<double, 1>&) { return d::Verdict::go_on; };
  // A change or a verdict that throws is a bug of the solver, not a size
  // without a solution: it throws through.
  EXPECT_THROW(
      (d::run_ladder<1, double>(
          {8, 12, 16}, [](int n) { return 1.0 * n; },
          [](double, double) -> std::array<double, 1> { throw std::logic_error("change"); }, go_on,
          count)),
      std::logic_error);
  EXPECT_THROW(
      (d::run_ladder<1, double>(
          {8, 12, 16}, [](int n) { return 1.0 * n; }, change1,
          [](const d::LadderChain<double, 1>&) -> d::Verdict { throw std::logic_error("verdict"); },
          count)),
      std::logic_error);
  EXPECT_EQ(seen, 0);
}

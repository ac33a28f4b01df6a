// Internal: the N-ladder driver shared by every solver that refines its
// collocation size N (the symmetric solver's width and flat-punch g(1)
// ladders, contact.cpp; the asymmetric solver, asymmetric.cpp; the damped flat
// punch, asymmetric_flat.cpp; several zones, zones.cpp). The driver owns the loop
// over the sizes, the chain of solved sizes and the changes of each refined
// quantity between successive sizes, the failure policy (a size that has no
// solution: give up, refine N with the chain restarted, or keep the last size
// that solved) and the stop. A solver supplies only its solve at N, the
// changes between two of its states, its verdict (its own estimates and
// stopping rule) and how it treats a failure. The estimates themselves
// (refinement_estimate, ladder_stop) are in movingpunch/asymmetric.hpp. Not a
// public header.
#pragma once

#include <array>
#include <cstddef>
#include <exception>
#include <optional>
#include <utility>
#include <vector>

namespace movingpunch::detail {

// What a solver's verdict says after a size: refine on, or stop (its
// estimates meet tol; or no size can improve them any further).
enum class Verdict { go_on, converged, stalled };

// What the driver does when a size has no solution (its solve threw):
// rethrow the failure; refine N, restarting the chain (`refine` counts the
// failure in LadderAt::failures, `refine_uncounted` does not: a failure that
// is not the problem's, as an under-resolved load curve); or stop at the last
// size that solved (the solver has restored its state to that size).
enum class OnFailure { rethrow, refine, refine_uncounted, stop };

// Where the ladder is when a size fails.
struct LadderAt {
  std::size_t index = 0;  // of the size in the ladder
  int n = 0;              // the size
  bool last = false;      // the ladder's last size
  int solved = 0;         // sizes solved so far (0: the first solve failed)
  int failures = 0;       // counted failures in a row before this one
};

// The chain since the last restart: its sizes, its states and the changes of
// the Q refined quantities between successive members (changes[q][k - 1]
// belongs to sizes[k], as refinement_estimate reads them).
template <class State, std::size_t Q>
struct LadderChain {
  std::vector<int> sizes;
  std::vector<State> states;
  std::array<std::vector<double>, Q> changes;
  std::size_t size() const { return sizes.size(); }
  const State& last() const { return states.back(); }
  void clear() {
    sizes.clear();
    states.clear();
    for (auto& c : changes) c.clear();
  }
};

// How the ladder ended: the verdict that stopped it (go_on: the sizes ran
// out, or a failure stopped it at the last size that solved: `failed`).
template <class State, std::size_t Q>
struct LadderRun {
  LadderChain<State, Q> chain;
  Verdict verdict = Verdict::go_on;
  bool failed = false;
  int failed_n = 0;  // the size that failed when `failed`
};

// Runs the ladder over `sizes`:
//   solve(n) -> State                   the solve at N (throws when it has none);
//   change(prev, cur) -> array<double, Q>  the changes of the quantities;
//   verdict(chain) -> Verdict           after each solved size (the chain
//                                       holds it), whatever the count of changes;
//   on_failure(const std::exception&, const LadderAt&) -> OnFailure
//                                       (it may throw a failure of its own).
template <std::size_t Q, class State, class Solve, class Change, class Decide, class Fail>
LadderRun<State, Q> run_ladder(const std::vector<int>& sizes, Solve&& solve, Change&& change,
                               Decide&& verdict, Fail&& on_failure) {
  LadderRun<State, Q> run;
  int solved = 0, failures = 0;
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    const int n = sizes[k];
    std::optional<State> s;
    try {
      s.emplace(solve(n));
    } catch (const std::exception& e) {
      // Only the solve's own failures (the changes and the verdict below
      // throw through).
      const LadderAt at{k, n, k + 1 == sizes.size(), solved, failures};
      switch (on_failure(e, at)) {
        case OnFailure::rethrow:
          throw;
        case OnFailure::refine:
          ++failures;
          run.chain.clear();
          continue;
        case OnFailure::refine_uncounted:
          run.chain.clear();
          continue;
        case OnFailure::stop:
          run.failed = true;
          run.failed_n = n;
          return run;
      }
    }
    if (run.chain.size() > 0) {
      const std::array<double, Q> d = change(run.chain.last(), *s);
      for (std::size_t q = 0; q < Q; ++q) run.chain.changes[q].push_back(d[q]);
    }
    run.chain.sizes.push_back(n);
    run.chain.states.push_back(std::move(*s));
    ++solved;
    failures = 0;
    run.verdict = verdict(static_cast<const LadderChain<State, Q>&>(run.chain));
    if (run.verdict != Verdict::go_on) break;
  }
  return run;
}

// A verdict from ladder_stop (movingpunch/asymmetric.hpp: go_on, converged,
// stalled).
template <class Stop>
Verdict ladder_verdict(Stop s) {
  if (s == Stop::converged) return Verdict::converged;
  if (s == Stop::stalled) return Verdict::stalled;
  return Verdict::go_on;
}

// The failure policy of a solve that has no way round a failure: rethrow.
struct RethrowFailures {
  OnFailure operator()(const std::exception&, const LadderAt&) const { return OnFailure::rethrow; }
};

}  // namespace movingpunch::detail

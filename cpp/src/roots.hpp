// Internal: bracketed root finding shared by the core (not a public header).
#pragma once

#include <cmath>
#include <functional>

#include "movingpunch/interrupt.hpp"

namespace movingpunch::detail {

// How bracketed_root keeps its bracket shrinking.
enum class Safeguard {
  // Bisect when the regula falsi point is not within the middle 98 % of the
  // bracket, and every fourth step: robust, but linear near the root.
  kFrequentBisection,
  // Bisect only when the bracket has not halved over three steps (a stalled
  // regula falsi): keeps Illinois' superlinear convergence, for functions
  // that are smooth down to their round-off (the contact width's load).
  kStalledBracket,
};

// The stalled-bracket safeguard of a secant or regula falsi on a bracket
// [lo, hi]: the trial point x, or the midpoint when the bracket has not
// halved over three steps or x is not strictly inside.
class StallGuard {
 public:
  explicit StallGuard(double ref_width) : ref_width_(ref_width) {}
  double operator()(double x, double lo, double hi) {
    check_interrupt();  // one step of a secant: a solve per step
    const double w = hi - lo;
    if (w <= 0.5 * ref_width_) {
      ref_width_ = w;
      slow_ = 0;
    } else if (++slow_ >= 3) {
      ref_width_ = w;
      slow_ = 0;
      x = 0.5 * (lo + hi);
    }
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    return x;
  }

 private:
  double ref_width_;
  int slow_ = 0;
};

// Root of f in [lo, hi] (lo < hi) where f(lo) and f(hi) differ in sign
// (Illinois regula falsi with a bisection safeguard). Stops when the bracket
// is below xtol, |f| <= ftol at a trial point (returned), or lo and hi are
// adjacent doubles (no step can shrink the bracket further); otherwise after
// max_iter steps. Returns the bracket's midpoint unless a trial point met ftol.
inline double bracketed_root(const std::function<double(double)>& f, double lo, double hi,
                             double flo, double fhi, double xtol, int max_iter = 200,
                             double ftol = 0.0,
                             Safeguard safeguard = Safeguard::kFrequentBisection) {
  int side = 0;
  StallGuard stall(hi - lo);
  for (int i = 0; i < max_iter && std::fabs(hi - lo) > xtol; ++i) {
    double x = (lo * fhi - hi * flo) / (fhi - flo);
    const double w = hi - lo;
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    if (safeguard == Safeguard::kFrequentBisection) {
      if (!(x > lo + 0.01 * w && x < hi - 0.01 * w) || (i % 4 == 3)) x = mid;
    } else {
      x = stall(x, lo, hi);
    }
    check_interrupt();
    const double fx = f(x);
    if (std::fabs(fx) <= ftol) return x;
    if ((fx < 0.0) == (flo < 0.0)) {
      lo = x;
      flo = fx;
      if (side == -1) fhi *= 0.5;
      side = -1;
    } else {
      hi = x;
      fhi = fx;
      if (side == 1) flo *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace movingpunch::detail

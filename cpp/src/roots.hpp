// Internal: bracketed root finding shared by the core (not a public header).
#pragma once

#include <cmath>
#include <functional>

namespace movingpunch::detail {

// Root of f in [lo, hi] where f(lo) and f(hi) differ in sign (Illinois
// regula falsi with a bisection safeguard). Stops when the bracket is below
// xtol or f vanishes.
inline double bracketed_root(const std::function<double(double)>& f, double lo, double hi,
                             double flo, double fhi, double xtol, int max_iter = 200) {
  int side = 0;
  for (int i = 0; i < max_iter && std::fabs(hi - lo) > xtol; ++i) {
    double x = (lo * fhi - hi * flo) / (fhi - flo);
    const double w = hi - lo;
    // Fall back to bisection when the secant point is not well inside.
    if (!(x > lo + 0.01 * w && x < hi - 0.01 * w) || (i % 4 == 3)) x = 0.5 * (lo + hi);
    const double fx = f(x);
    if (fx == 0.0) return x;
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

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
  // The secant through the last two trial points while it stays inside the
  // bracket and |f| at least halves a step, else kStalledBracket's step:
  // regula falsi keeps one end of a convex f's bracket fixed and needs the
  // safeguard's bisection; the secant converges from one side (order 1.6).
  kSecant,
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
  double xa = lo, fa = flo, xb = hi, fb = fhi;  // the last two trial points (xb the latest)
  for (int i = 0; i < max_iter && std::fabs(hi - lo) > xtol; ++i) {
    double x = (lo * fhi - hi * flo) / (fhi - flo);
    const double w = hi - lo;
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    if (safeguard == Safeguard::kFrequentBisection) {
      if (!(x > lo + 0.01 * w && x < hi - 0.01 * w) || (i % 4 == 3)) x = mid;
    } else {
      const double xs = fb != fa ? xb - fb * (xb - xa) / (fb - fa) : mid;
      const bool secant = safeguard == Safeguard::kSecant && i > 0 && xs > lo && xs < hi &&
                          std::fabs(fb) <= 0.5 * std::fabs(fa);
      x = secant ? xs : stall(x, lo, hi);
    }
    check_interrupt();
    const double fx = f(x);
    xa = xb;
    fa = fb;
    xb = x;
    fb = fx;
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

// A local minimum found by brent_minimum: its abscissa and f there.
struct Minimum {
  double x = 0.0;
  double f = 0.0;
};

// Brent's (1973) "localmin" on [a, b] (a < b): golden section with
// parabolic steps, from x in [a, b] with fx = f(x) already known. Each step
// keeps the best point x and a sub-interval [a, b] around it; stops when
// that interval is within 2 tol of x (tol = xtol + rtol |x|, the abscissa's
// accuracy), or after max_iter evaluations of f. A step is never shorter
// than tol. For a function unimodal on [a, b] the minimum lies within 2 tol
// of the returned x (at an end of [a, b]: x within 2 tol of that end), or
// within the width where f's round-off hides its change, whichever is wider
// (about sqrt(2 eps |f*| / f'') at a smooth minimum f*: a tol below it
// cannot be met in x, only in f); otherwise x is a local minimum of f or
// the best point evaluated. The returned f is f(x), the smallest value
// evaluated.
template <class F>
Minimum brent_minimum(const F& f, double a, double b, double x, double fx, double xtol, double rtol,
                      int max_iter) {
  constexpr double kGold = 0.3819660112501051;  // (3 - sqrt 5)/2
  double w = x, v = x, fw = fx, fv = fx;
  double d = 0.0, e = 0.0;
  for (int it = 0; it < max_iter; ++it) {
    const double m = 0.5 * (a + b);
    const double tol1 = xtol + rtol * std::fabs(x), tol2 = 2.0 * tol1;
    if (std::fabs(x - m) <= tol2 - 0.5 * (b - a)) break;
    bool golden = true;
    if (std::fabs(e) > tol1) {
      // The parabola through (x, fx), (w, fw), (v, fv): its vertex at x + p/q.
      const double r = (x - w) * (fx - fv);
      double q = (x - v) * (fx - fw);
      double p = (x - v) * q - (x - w) * r;
      q = 2.0 * (q - r);
      if (q > 0.0) p = -p;
      q = std::fabs(q);
      const double etemp = e;
      e = d;
      // Taken when it moves less than half the step before last and stays in (a, b).
      if (std::fabs(p) < std::fabs(0.5 * q * etemp) && p > q * (a - x) && p < q * (b - x)) {
        d = p / q;
        const double u = x + d;
        if (u - a < tol2 || b - u < tol2) d = x < m ? tol1 : -tol1;
        golden = false;
      }
    }
    if (golden) {
      e = (x >= m ? a : b) - x;
      d = kGold * e;
    }
    const double u = std::fabs(d) >= tol1 ? x + d : x + (d > 0.0 ? tol1 : -tol1);
    const double fu = f(u);
    if (fu <= fx) {
      (u >= x ? a : b) = x;
      v = w;
      fv = fw;
      w = x;
      fw = fx;
      x = u;
      fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w;
        fv = fw;
        w = u;
        fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u;
        fv = fu;
      }
    }
  }
  return Minimum{x, fx};
}

// brent_minimum from the golden-section point of [a, b] (one evaluation more).
template <class F>
Minimum brent_minimum(const F& f, double a, double b, double xtol, double rtol, int max_iter) {
  const double x = a + 0.3819660112501051 * (b - a);
  return brent_minimum(f, a, b, x, f(x), xtol, rtol, max_iter);
}

}  // namespace movingpunch::detail

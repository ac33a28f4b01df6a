// The minimum over the wavenumber of a medium's lowest free-wave speed: the
// search both critical speeds share (dispersion.cpp's homogeneous layer,
// stack.cpp's media). Internal header.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "roots.hpp"

namespace movingpunch::detail {

// The lowest branch c1(t) falls from the foundation-dominated long waves to
// one broad minimum (about a decade wide in t) and rises to its short-wave
// limit: a log grid on 1e-5 <= t <= 1e5 of 21 points finds it, of 201 when
// the dip is shallower than 1e-6 of `top` (stiff foundations: narrow and
// shallow), and Brent's parabolic minimiser refines it between the best
// grid point's neighbours (1e-7 in ln t leaves ~1e-14 in the speed).
// first_wave(t) is c1(t) (top where there is none below it). Returns false
// when no grid value lies below top (1 - floor): the minimum is then the
// infimum `top` itself; else true with (speed, t) in `out`.
template <class FirstWave>
bool log_grid_minimum(const FirstWave& first_wave, double top, double floor, double& speed,
                      double& t) {
  const double lt0 = std::log(1e-5), lt1 = std::log(1e5);
  int n = 0, best = 0;
  double best_s = std::numeric_limits<double>::infinity();
  for (const int size : {21, 201}) {
    n = size;
    best = 0;
    best_s = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
      const double v = first_wave(std::exp(lt0 + (lt1 - lt0) * i / (n - 1)));
      if (v < best_s) {
        best_s = v;
        best = i;
      }
    }
    if (best_s < top * (1.0 - 1e-6)) break;
  }
  if (best_s >= top * (1.0 - floor)) return false;
  const double h = (lt1 - lt0) / (n - 1);
  auto F = [&](double lt) { return first_wave(std::exp(lt)); };
  const double a = lt0 + h * std::max(best - 1, 0), b = lt0 + h * std::min(best + 1, n - 1);
  const Minimum m = brent_minimum(F, a, b, lt0 + h * best, best_s, 1e-7, 0.0, 100);
  speed = m.f;
  t = std::exp(m.x);
  return true;
}

}  // namespace movingpunch::detail

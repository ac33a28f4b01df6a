#include "movingpunch/dispersion.hpp"

#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <mutex>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "critical_search.hpp"
#include "memo.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/layer_response.hpp"
#include "roots.hpp"

namespace movingpunch {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;
}  // namespace

double first_wave_vstar(double t, double kw, double nu, double kp) {
  return first_wave_vstar(t, kw, nu, kp, kFirstWaveScan);
}

double first_wave_vstar(double t, double kw, double nu, double kp, int scan) {
  require_in_range("kw", kw, 0.0, kInf, true, false, true);
  require_in_range("kp", kp, 0.0, kMaxKp, false, false);
  if (scan < 2) throw std::invalid_argument("first_wave_vstar: scan must be >= 2");
  const double vr = rayleigh_vstar(nu);
  if (!(t > 0.0) || !std::isfinite(t))
    throw std::invalid_argument("first_wave_vstar: t = alpha h must be finite and > 0");
  auto D = [&](double s) { return LayerModel(s, kw, nu, kp).dispersion(t); };
  // Scan with points clustered at both ends (waves near 0 for soft
  // foundations, near the Rayleigh value for short waves); the lowest branch
  // is the first sign change.
  const int m = scan;
  const double top = vr * (1.0 - 1e-13);
  double s_prev = 0.0, d_prev = D(0.0);
  for (int j = 1; j <= m; ++j) {
    const double s = top * 0.5 * (1.0 - std::cos(kPi * j / m));
    const double d = D(s);
    if (d == 0.0) return s;
    if ((d < 0.0) != (d_prev < 0.0))
      return detail::bracketed_root(D, s_prev, s, d_prev, d, 1e-15 * vr);
    s_prev = s;
    d_prev = d;
  }
  return vr;
}

namespace {

CriticalSpeed compute_critical(double kw, double nu, double kp) {
  const double vr = rayleigh_vstar(nu);
  if (std::isinf(kw)) return {vr, kInf};
  // On stiff foundations (kw >~ 30) the dip below the Rayleigh value is
  // shallow (2.6e-10 relative at kw = 100, nu = 0) and narrow: the grid of
  // 201 points (critical_search.hpp). A Pasternak layer (kp > 0) adds kp t^2
  // to the base's stiffness: it lifts the whole branch (by about kp on soft
  // foundations) without moving the minimum of a soft foundation (t^4 ~ kw/D
  // as for springs alone); as kp grows the dip becomes shallow and moves to
  // larger t (kw = 10, nu = 0.2, kp = 0.3: 6e-5 relative at t = 7.2), and
  // beyond kp ~ 1 no free wave is slower than the Rayleigh wave of the top
  // face: V*_cr = V*_R, t = inf (a dip shallower than the scan's 1e-13 below
  // V*_R counts as none).
  CriticalSpeed c{vr, kInf};
  detail::log_grid_minimum([&](double t) { return first_wave_vstar(t, kw, nu, kp); }, vr, 0.0,
                           c.vstar, c.t);
  return c;
}

}  // namespace

CriticalSpeed critical_speed(double kw, double nu, double kp) {
  // The search grid reaches t = 1e-5: enough for kw >= 1e-12 (t_min ~ kw^(1/4)).
  require_in_range("kw", kw, 1e-12, kInf, false, false, true);
  require_in_range("nu", nu, 0.0, 0.5, false, true);
  require_in_range("kp", kp, 0.0, kMaxKp, false, false);
  // kp is irrelevant on a rigid base: one cache entry for it.
  if (std::isinf(kw)) kp = 0.0;
  static std::mutex mutex;
  static std::map<std::tuple<double, double, double>, CriticalSpeed> cache;
  return detail::memoized(mutex, cache, std::make_tuple(kw, nu, kp),
                          [&] { return compute_critical(kw, nu, kp); });
}

}  // namespace movingpunch

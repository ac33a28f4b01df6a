#include "movingpunch/dispersion.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <utility>

#include "movingpunch/errors.hpp"
#include "movingpunch/layer_response.hpp"
#include "roots.hpp"

namespace movingpunch {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;
}  // namespace

double first_wave_vstar(double t, double kw, double nu) {
  require_in_range("kw", kw, 0.0, kInf, true, false, true);
  const double vr = rayleigh_vstar(nu);
  if (!(t > 0.0) || !std::isfinite(t))
    throw std::invalid_argument("first_wave_vstar: t = alpha h must be finite and > 0");
  auto D = [&](double s) { return LayerModel(s, kw, nu).dispersion(t); };
  // Scan with points clustered at both ends (waves near 0 for soft
  // foundations, near the Rayleigh value for short waves); the lowest branch
  // is the first sign change.
  const int m = 96;
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

CriticalSpeed compute_critical(double kw, double nu) {
  const double vr = rayleigh_vstar(nu);
  if (std::isinf(kw)) return {vr, kInf};
  // Coarse log grid in t, then golden-section refinement around the minimum.
  const double lt0 = std::log(1e-5), lt1 = std::log(1e5);
  const int n = 201;
  int best = 0;
  double best_s = kInf;
  std::vector<double> vals(n);
  for (int i = 0; i < n; ++i) {
    const double lt = lt0 + (lt1 - lt0) * i / (n - 1);
    vals[static_cast<std::size_t>(i)] = first_wave_vstar(std::exp(lt), kw, nu);
    if (vals[static_cast<std::size_t>(i)] < best_s) {
      best_s = vals[static_cast<std::size_t>(i)];
      best = i;
    }
  }
  if (best_s >= vr) return {vr, kInf};
  const double h = (lt1 - lt0) / (n - 1);
  double a = lt0 + h * std::max(best - 1, 0), b = lt0 + h * std::min(best + 1, n - 1);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  auto F = [&](double lt) { return first_wave_vstar(std::exp(lt), kw, nu); };
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = F(x1), f2 = F(x2);
  while (b - a > 1e-9) {
    if (f1 < f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - g * (b - a);
      f1 = F(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + g * (b - a);
      f2 = F(x2);
    }
  }
  double s = std::min(f1, f2);
  double lt = f1 < f2 ? x1 : x2;
  if (best_s < s) {
    s = best_s;
    lt = lt0 + h * best;
  }
  return {s, std::exp(lt)};
}

}  // namespace

CriticalSpeed critical_speed(double kw, double nu) {
  // The search grid reaches t = 1e-5: enough for kw >= 1e-12 (t_min ~ kw^(1/4)).
  require_in_range("kw", kw, 1e-12, kInf, false, false, true);
  require_in_range("nu", nu, 0.0, 0.5, false, true);
  static std::mutex mutex;
  static std::map<std::pair<double, double>, CriticalSpeed> cache;
  const auto key = std::make_pair(kw, nu);
  {
    std::lock_guard<std::mutex> lock(mutex);
    const auto it = cache.find(key);
    if (it != cache.end()) return it->second;
  }
  const CriticalSpeed c = compute_critical(kw, nu);
  std::lock_guard<std::mutex> lock(mutex);
  if (cache.size() > 4096) cache.clear();
  cache[key] = c;
  return c;
}

}  // namespace movingpunch

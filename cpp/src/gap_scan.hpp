#pragma once
// The one check of the gap beside a contact (single contact, damped,
// separated zones): the gap sampled finely enough to resolve the surface's
// shortest wave, then every local minimum of the samples refined (Brent), so
// that no dip between samples is missed. (A fixed 24..48-point scan missed a
// dip of -7 h near V*_cr on a stiff foundation, where the surface carries
// waves shorter than the contact: a valid result that penetrated.)
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "roots.hpp"

namespace movingpunch::detail {

// The wavenumber below which all but `share` of the integral of
// |M1(alpha) - phi1| lies (nodes ascending): the surface's displacement
// beside a contact carries wavenumbers up to about it (its transform is the
// pressure's times (M1 - phi1)/alpha, the pressure's no larger than P).
template <class AbsDiff>
double response_band(const std::vector<double>& alpha, const std::vector<double>& weight,
                     const AbsDiff& absdiff, double share = 1e-6) {
  double total = 0.0;
  for (std::size_t i = 0; i < alpha.size(); ++i) total += weight[i] * absdiff(i);
  if (!(total > 0.0) || alpha.empty()) return alpha.empty() ? 1.0 : alpha.back();
  double tail = 0.0;
  for (std::size_t i = alpha.size(); i-- > 0;) {
    tail += weight[i] * absdiff(i);
    if (tail > share * total) return alpha[i];
  }
  return alpha.front();
}

// The sampling step of the gap for a surface band-limited to `band` (per
// unit length): 8 samples per shortest wavelength 2 pi/band, so that the
// gap's curvature between samples (at most band^2 times its wave's
// amplitude) cannot hide a dip: every dip spans several samples.
inline double gap_step(double band) {
  constexpr double kPi = 3.14159265358979323846;
  return 2.0 * kPi / (8.0 * std::max(band, 1e-300));
}

struct GapMinimum {
  double gap = std::numeric_limits<double>::infinity();
  double x = 0.0;
};

// Brent's minimisation of f on [a, b] (f's samples bracket a minimum), to
// an abscissa tolerance xtol (and 1e-12 relative); at most 61 evaluations.
template <class F>
GapMinimum brent_gap_minimum(const F& f, double a, double b, double xtol) {
  const Minimum m = brent_minimum(f, a, b, xtol, 1e-12, 60);
  return GapMinimum{m.f, m.x};
}

// The minimum of a gap known at equally spaced samples xs (gs its values,
// both in order along the scan) and anywhere by value(x): the smallest
// sample, and each local minimum of the samples refined by Brent on its two
// neighbouring intervals. A scan's end at a contact's end (skip_first,
// skip_last: the gap is 0 there by construction) is not a candidate.
template <class Value>
GapMinimum refine_minimum(const std::vector<double>& xs, const std::vector<double>& gs,
                          const Value& value, bool skip_first, bool skip_last) {
  GapMinimum best;
  const std::size_t n = xs.size();
  for (std::size_t i = skip_first ? 1 : 0; i < (skip_last ? n - 1 : n); ++i)
    if (gs[i] < best.gap) best = GapMinimum{gs[i], xs[i]};
  for (std::size_t i = 1; i + 1 < n; ++i) {
    // (Beside a skipped end, a negative sample rising towards the scan is a
    // dip whatever the end's value: the gap may have its minimum just off it.)
    const bool left = gs[i] <= gs[i - 1] || (i == 1 && skip_first && gs[i] < 0.0);
    const bool right = gs[i] <= gs[i + 1] || (i + 2 == n && skip_last && gs[i] < 0.0);
    if (!(left && right)) continue;
    const double lo = std::min(xs[i - 1], xs[i + 1]), hi = std::max(xs[i - 1], xs[i + 1]);
    const double xtol = 1e-6 * (hi - lo);
    const GapMinimum m = brent_gap_minimum(value, lo, hi, xtol);
    // Converged onto a skipped end: the gap rises from it (no dip).
    if ((i == 1 && skip_first && std::fabs(m.x - xs[0]) <= 10.0 * xtol) ||
        (i + 2 == n && skip_last && std::fabs(m.x - xs[n - 1]) <= 10.0 * xtol))
      continue;
    if (m.gap < best.gap) best = m;
  }
  // A non-finite sample: the scan is not trusted (the caller throws).
  for (double g : gs)
    if (!std::isfinite(g)) return GapMinimum{std::numeric_limits<double>::quiet_NaN(), 0.0};
  return best;
}

// The scan's sample fractions t in [0, 1] of [x0, x1]: equally spaced at
// most step/len apart, joined by m points clustered as t = (j/m)^2 at a
// contact's end (cusp0 at t = 0, cusp1 at t = 1; the gap's dips right
// beside an end are far narrower than the surface's waves there).
inline std::vector<double> scan_fractions(double len, double step, int m, bool cusp0, bool cusp1) {
  // (The clustered points at an end give the scan m points already.)
  const int n = std::max({cusp0 || cusp1 ? 2 : m, 2, static_cast<int>(std::ceil(len / step))});
  std::vector<double> t;
  t.reserve(static_cast<std::size_t>(n + 2 * m + 1));
  for (int i = 0; i <= n; ++i) t.push_back(static_cast<double>(i) / n);
  for (int j = 1; j < m; ++j) {
    const double q = static_cast<double>(j) / m;
    if (cusp0) t.push_back(q * q);
    if (cusp1) t.push_back(1.0 - q * q);
  }
  std::sort(t.begin(), t.end());
  std::vector<double> out;
  for (double v : t)
    if (out.empty() || v - out.back() > 1e-9 * std::max(1.0, std::fabs(v))) out.push_back(v);
  out.back() = 1.0;
  return out;
}

// The gap's minimum for x from x0 to x1 (either order) of a gap known by
// value(x) directly: samples at most `step` apart (at least `min_points`),
// then refine_minimum (x0 a contact's end: skip_first).
template <class Value>
GapMinimum scan_gap_values(const Value& value, double x0, double x1, double step, int min_points,
                           bool skip_first) {
  const std::vector<double> t =
      scan_fractions(std::fabs(x1 - x0), step, min_points, skip_first, false);
  std::vector<double> xs(t.size()), gs(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    xs[i] = x0 + (x1 - x0) * t[i];
    gs[i] = value(xs[i]);
  }
  return refine_minimum(xs, gs, value, skip_first, false);
}

// The gap's minimum for x from x0 to x1 (either order) of a gap known by its
// slope d gap/dx: gap(x) = g0 + int_x0^x slope. A contact's end (cusp0 at
// x0, cusp1 at x1: the gap is 0 there, the slope has a square-root cusp) is
// integrated from in q, x = end +- q^2 (smooth in q), 8 Gauss points per
// interval between samples; with both, each half from its own end (the
// gap is 0 at both by the zones' conditions). Samples as scan_fractions.
template <class Slope>
GapMinimum scan_gap_slope(const Slope& slope, double x0, double x1, double g0, double step,
                          int min_panels, bool cusp0, bool cusp1) {
  static const double gx[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                               -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                               0.7966664774136267,  0.9602898564975363};
  static const double gw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                               0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                               0.2223810344533745, 0.1012285362903763};
  // int_from^to slope dx; from a cusped end e (cusp): x = e + sg q^2.
  auto integral = [&](double from, double to, bool cusp, double e) {
    double sum = 0.0;
    if (cusp) {
      const double sg = (from + to) * 0.5 >= e ? 1.0 : -1.0;
      const double qa = std::sqrt(std::fabs(from - e)), qb = std::sqrt(std::fabs(to - e));
      const double c = 0.5 * (qa + qb), h = 0.5 * (qb - qa);
      for (int g = 0; g < 8; ++g) {
        const double q = c + h * gx[g];
        sum += gw[g] * h * 2.0 * sg * q * slope(e + sg * q * q);
      }
      return sum;
    }
    const double c = 0.5 * (from + to), h = 0.5 * (to - from);
    for (int g = 0; g < 8; ++g) sum += gw[g] * h * slope(c + h * gx[g]);
    return sum;
  };
  std::vector<double> t = scan_fractions(std::fabs(x1 - x0), step, min_panels, cusp0, cusp1);
  if (cusp1 && cusp0 && !std::binary_search(t.begin(), t.end(), 0.5)) {
    t.push_back(0.5);
    std::sort(t.begin(), t.end());
  }
  const int n = static_cast<int>(t.size()) - 1;
  // Samples with t <= split integrate forwards from x0, beyond it backwards from x1.
  const double split = cusp1 ? (cusp0 ? 0.5 : -1.0) : 2.0;
  std::vector<double> xs(t.size()), gs(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) xs[i] = x0 + (x1 - x0) * t[i];
  const auto un = static_cast<std::size_t>(n);
  gs[0] = g0;
  for (std::size_t i = 0; i < un && t[i + 1] <= split; ++i)
    gs[i + 1] = gs[i] + integral(xs[i], xs[i + 1], cusp0, x0);
  if (cusp1) {
    gs[un] = 0.0;
    for (std::size_t i = un; i-- > 0 && t[i] >= split;)
      gs[i] = gs[i + 1] + integral(xs[i + 1], xs[i], true, x1);
  }
  auto value = [&](double x) {
    const double f = (x - x0) / (x1 - x0);
    const auto at = std::upper_bound(t.begin(), t.end(), f);
    const auto i =
        static_cast<std::size_t>(std::clamp(static_cast<int>(at - t.begin()) - 1, 0, n - 1));
    if (t[i] >= split) return gs[i + 1] + integral(xs[i + 1], x, true, x1);
    return gs[i] + integral(xs[i], x, cusp0, x0);
  };
  return refine_minimum(xs, gs, value, cusp0, cusp1);
}

}  // namespace movingpunch::detail

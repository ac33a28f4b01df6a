// Internal: the parts of the contact-width solve shared by the symmetric
// (undamped, contact.cpp) and the asymmetric (damped, asymmetric.cpp) problems:
// the supported widths, the collocation-size ladder, the first width guess
// and the messages (the bracketed root on ln(width): roots.hpp). The two
// problems differ only where the physics does (the kernel, one unknown end
// or two, their error estimates). Not a public header.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "movingpunch/errors.hpp"
#include "movingpunch/medium.hpp"
#include "roots.hpp"

namespace movingpunch::detail {

// Supported contact half-widths (in h): the kernel's table grows with the
// width, and far beyond 50 h the layer is a plate on springs under a
// distributed load.
inline constexpr double kMinA = 1e-10, kMaxA = 50.0;

// Collocation sizes tried in turn; the last is the undamped solver's cap.
inline constexpr std::array<int, 17> kSizes = {8,   12,  16,  24,  32,  48,  64,  96,  128,
                                               192, 256, 384, 512, 640, 768, 896, 1024};

// The ladder's sizes up to max_n (inclusive).
inline std::vector<int> size_ladder(int max_n) {
  std::vector<int> out;
  for (int n : kSizes)
    if (n <= max_n) out.push_back(n);
  return out;
}

// The limit of a/h on a graded top (docs/theory.md section 16.5), whose g
// carries (1 - r) ln(1 - r) at both ends: a_N = a + C N^-4 + D N^-5 + ...
// (Navot's expansion for an end singularity theta^3 ln theta in the
// collocation's angle), eliminated through three sizes n[0] < n[1] < n[2].
inline double extrapolate_n4n5(const int* n, const double* x) {
  // x_i - x_2 = C (t_i^4 - 1) + D (t_i^5 - 1), t_i = n_2/n_i; a = x_2 - C - D.
  double m[2][2], d[2];
  for (int i = 0; i < 2; ++i) {
    const double t = static_cast<double>(n[2]) / n[i];
    m[i][0] = t * t * t * t - 1.0;
    m[i][1] = t * t * t * t * t - 1.0;
    d[i] = x[i] - x[2];
  }
  const double det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
  const double c = (d[0] * m[1][1] - d[1] * m[0][1]) / det;
  const double dd = (m[0][0] * d[1] - m[1][0] * d[0]) / det;
  return x[2] - c - dd;
}

// The first width guess for a contact carrying lambda = R P/(mu h^2) on a
// layer with phi1 (its half-plane compliance), Winkler kw and nu: the
// half-plane (Hertz) width a_H, unless the wide-contact width a_W of a layer
// squeezed on springs (docs/hard-cases.md section 5) is far off it: near V*_R
// phi1 (and a_H) grows without bound while the layer's thickness keeps the
// contact finite (a_H > 8 a_W), and on soft foundations the contact is wide
// (a_W > max(1, a_H)). A far guess builds kernel tables for widths never
// needed. The guess is within [kMinA, kMaxA].
//
// A Pasternak layer kp (the base's stiffness kw + kp t^2 per mode) stiffens
// the waves of the contact's own length: a_W then solves
// a = (1.5 lambda (1/(kw + kp (3/a)^2) + (1 - nu)/2))^(1/3) (a fixed point,
// decreasing in a). The 3 is fitted (kw = 1e-3 ... 0.1, kp = 0.01 ... 10,
// lambda = 0.2 ... 1): the guess is then within the factor 1 to 3.3 of the
// true width, as a_W is for springs alone (1.9 to 5); a_W of the springs
// alone was 21 times too wide at kw = 1e-3, kp = 10.
struct WidthGuess {
  double hertz = 0;  // a_H = sqrt(2 phi1 lambda / pi)
  double wide = 0;   // a_W = (1.5 lambda (1/kw + (1 - nu)/2))^(1/3)
  bool use_wide = false;
  double a = 0;  // the guess
};
inline WidthGuess width_guess(double phi1, double lambda, double kw, double nu, double kp = 0.0) {
  constexpr double kPi = 3.14159265358979323846;
  WidthGuess g;
  g.hertz = std::sqrt(2.0 * phi1 * lambda / kPi);
  g.wide = std::cbrt(1.5 * lambda * ((std::isinf(kw) ? 0.0 : 1.0 / kw) + 0.5 * (1.0 - nu)));
  if (kp > 0.0 && std::isfinite(kw)) {
    for (int i = 0; i < 100; ++i) {
      const double stiff = kw + kp * 9.0 / (g.wide * g.wide);
      const double next = std::cbrt(1.5 * lambda * (1.0 / stiff + 0.5 * (1.0 - nu)));
      const bool done = std::fabs(next - g.wide) <= 1e-3 * next;
      // Averaged: the plain iteration can overshoot where the stiffness
      // changes fast with a.
      g.wide = 0.5 * (g.wide + next);
      if (done) break;
    }
  }
  g.use_wide = g.hertz > 8.0 * g.wide || g.wide > std::max(1.0, g.hertz);
  g.a = std::clamp(g.use_wide ? g.wide : g.hertz, kMinA, kMaxA);
  return g;
}

// The same for any medium, from its long-wave compliance C = lim M1(t)/t
// (the homogeneous layer's 1/kw + (1 - nu)/2 above, up to the layer's own
// term): the wide contact of a cylinder on springs of compliance C.
inline WidthGuess width_guess_compliance(double phi1, double lambda, double compliance) {
  constexpr double kPi = 3.14159265358979323846;
  WidthGuess g;
  g.hertz = std::sqrt(2.0 * phi1 * lambda / kPi);
  g.wide = std::cbrt(1.5 * lambda * std::max(compliance, 0.0));
  g.use_wide = g.hertz > 8.0 * g.wide || g.wide > std::max(1.0, g.hertz);
  g.a = std::clamp(g.use_wide ? g.wide : g.hertz, kMinA, kMaxA);
  return g;
}

// The first width of a non-cylindrical profile (any class with slope(x)):
// the half-plane width, where P = (1/phi1) int_{-a}^{a} x f'(x)/sqrt(a^2 - x^2) dx
// (the consistency condition of a bounded contact on a half-plane; Hertz's
// a^2 = 2 phi1 R P/pi for the cylinder), by bisection in ln(a - a0) on
// a0 + [kMinA, amax - a0].
template <class Profile>
double profile_half_plane_width(const Profile& prof, double phi1, double P, double a0,
                                double amax) {
  constexpr double kPi = 3.14159265358979323846;
  constexpr int m = 64;
  auto load = [&](double a) {
    double sum = 0.0;
    for (int i = 1; i <= m; ++i) {
      const double t = std::cos((2 * i - 1) * kPi / (2.0 * m));
      sum += a * t * prof.slope(a * t);
    }
    return sum * kPi / m / phi1;
  };
  double lo = std::log(kMinA), hi = std::log(amax - a0);
  if (load(a0 + std::exp(hi)) <= P) return a0 + 0.9 * std::exp(hi);
  if (load(a0 + std::exp(lo)) >= P) return a0 + 2.0 * std::exp(lo);
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (load(a0 + std::exp(mid)) < P ? lo : hi) = mid;
  }
  return a0 + std::exp(0.5 * (lo + hi));
}

// The foundation as messages name it: "kw = 1" for springs alone, "kw = 1,
// kp = 0.2" with a Pasternak shear layer (any parameter struct with kw, kp).
template <class Params, class = void>
struct HasMedium : std::false_type {};
template <class Params>
struct HasMedium<Params, std::void_t<decltype(std::declval<Params>().medium)>> : std::true_type {};

// A layered medium (ContactParams::medium) is named by describe().
template <class Params>
std::string foundation_text(const Params& p) {
  if constexpr (HasMedium<Params>::value) {
    if (p.medium && !p.medium->homogeneous()) return describe(*p.medium);
  }
  std::ostringstream m;
  m.precision(6);
  m << "kw = " << p.kw;
  if (p.kp != 0.0) m << ", kp = " << p.kp;
  return m.str();
}

// "1e-10 <= a/h <= 50".
inline std::string supported_range_text() {
  std::ostringstream m;
  m << kMinA << " <= a/h <= " << kMaxA;
  return m.str();
}

// The refusal of a load whose contact lies outside [kMinA, kMaxA] (any
// parameter struct with radius, load, kw and vstar); with a finite
// lambda_bound, the bound radius * load must keep to as well.
template <class Params>
std::string width_out_of_range_message(const Params& p, bool too_wide,
                                       double lambda_bound = std::nan("")) {
  std::ostringstream m;
  m.precision(6);
  m << "radius * load = " << p.radius * p.load << " (radius " << p.radius << ", load " << p.load
    << ") needs a contact half-width " << (too_wide ? "above" : "below") << " the supported range "
    << supported_range_text() << " for " << foundation_text(p) << ", vstar = " << p.vstar << ": "
    << (too_wide ? "reduce" : "increase") << " the radius or the load";
  if (std::isfinite(lambda_bound))
    m << " (radius * load must be " << (too_wide ? "<= " : ">= ") << lambda_bound << ")";
  return m.str();
}
template <class Params>
[[noreturn]] void width_out_of_range(const Params& p, bool too_wide,
                                     double lambda_bound = std::nan("")) {
  throw std::invalid_argument(width_out_of_range_message(p, too_wide, lambda_bound));
}

// "did not converge" at the end of the ladder: what, to which tol, by which N,
// and why (the last change or error estimate).
inline std::string not_converged_message(const std::string& what, double tol, int max_n,
                                         const std::string& detail) {
  std::ostringstream m;
  m << what << " did not converge to tol = " << tol << " with N up to " << max_n
    << " collocation points (" << detail << ")";
  return m.str();
}

}  // namespace movingpunch::detail

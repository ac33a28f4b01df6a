// Private: logarithmic and Cauchy potentials of a Chebyshev-U pressure
// p(a r) = sqrt(1 - r^2) sum_n b_n U_n(r) on (-a, a) (positions relative to
// the contact's centre), the closed-form (half-plane, log-singular) parts of
// the displacements and stresses. Shared by the undamped outputs
// (contact.cpp, stresses.cpp: g even, `step` 2 sums the even terms only) and
// the damped ones (asymmetric.cpp: any g, `step` 1). A flat punch's pressure
// p(a r) = sum_n b_n T_n(r)/sqrt(1 - r^2) (square-root singular ends) has its
// own closed forms, chosen by the trailing SeriesKind argument (default U).
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "movingpunch/collocation.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/layer_response.hpp"

namespace movingpunch::detail {

namespace potentials {
constexpr double kPi = 3.14159265358979323846;
constexpr double kLn2 = 0.69314718055994530942;
}  // namespace potentials

// Throws InvalidParameter naming x or y unless every x is finite and
// -1 <= y <= 0 (the points of a field grid, either solver).
inline void check_grid(const Eigen::Ref<const Eigen::VectorXd>& x,
                       const Eigen::Ref<const Eigen::VectorXd>& y) {
  for (Eigen::Index i = 0; i < x.size(); ++i)
    if (!std::isfinite(x(i)))
      throw InvalidParameter("x", "finite", "x must be finite, got " + std::to_string(x(i)));
  for (Eigen::Index j = 0; j < y.size(); ++j)
    if (!(y(j) >= -1.0 && y(j) <= 0.0))
      throw InvalidParameter("y", "[-1, 0]",
                             "y must be in [-1, 0] (y/h, the layer), got " + std::to_string(y(j)));
}

// (1/pi) int_{-1}^{1} sqrt(1 - t^2) U_n(t) ln|x - t| dt, real x, any n >= 0;
// for kind T, (1/pi) int T_n(t)/sqrt(1 - t^2) ln|x - t| dt: -ln 2 (n = 0),
// -T_n(x)/n (n >= 1) for |x| <= 1, and Re of -ln(2 w), -w^n/n beyond.
inline double log_potential(int n, double x, SeriesKind kind = SeriesKind::U) {
  using potentials::kLn2;
  const double ax = std::fabs(x);
  if (kind == SeriesKind::T) {
    if (ax <= 1.0) {
      if (n == 0) return -kLn2;
      return -std::cos(n * std::acos(std::clamp(x, -1.0, 1.0))) / n;
    }
    const double th = std::acosh(ax);  // |w| = e^{-th}
    if (n == 0) return th - kLn2;
    const double sg = (x > 0.0 || n % 2 == 0) ? 1.0 : -1.0;
    return -sg * std::exp(-n * th) / n;
  }
  if (ax <= 1.0) {
    if (n == 0) return 0.5 * x * x - 0.25 - 0.5 * kLn2;
    const double th = std::acos(std::clamp(x, -1.0, 1.0));
    return 0.5 * (std::cos((n + 2) * th) / (n + 2) - std::cos(n * th) / n);
  }
  const double th = std::acosh(ax);
  if (n == 0) return 0.5 * th + 0.25 * std::exp(-2.0 * th) - 0.5 * kLn2;
  const double sg = (x > 0.0 || n % 2 == 0) ? 1.0 : -1.0;
  return sg * 0.5 * (-std::exp(-n * th) / n + std::exp(-(n + 2) * th) / (n + 2));
}

using cplx_t = std::complex<double>;

// w(z) = z - sqrt(z^2 - 1) on the branch ~ 1/(2z) at infinity (cut [-1, 1]),
// written as 1/(z + sqrt(z^2-1)) to avoid cancellation; |w| <= 1 for Im z >= 0.
inline cplx_t w_of(cplx_t z, cplx_t* root = nullptr) {
  const cplx_t r = std::sqrt(z - 1.0) * std::sqrt(z + 1.0);
  if (root) *root = r;
  return 1.0 / (z + r);
}

// The suffix sums tail(k) = sum_{m >= k} (m + 1) |b_m| (k = 0 .. size; tail(size)
// = 0) of a U-series: what potential_terms needs to cut its potentials short.
inline Eigen::VectorXd potential_tails(const Eigen::VectorXd& b) {
  Eigen::VectorXd t = Eigen::VectorXd::Zero(b.size() + 1);
  for (Eigen::Index k = b.size(); k-- > 0;)
    t(k) = t(k + 1) + static_cast<double>(k + 1) * std::fabs(b(k));
  return t;
}

// The terms of a U-series' potentials (cauchy_potential and its derivative)
// that reach 1e-17 of sum (m + 1) |b_m| at z: the terms m >= N add at most
// |w|^(N+1) tail(N) to either (|b_m w^(m+1)| and (m + 1)|b_m w^(m+1)|), so N is
// the first with |w(z)|^(N+1) tail(N) <= 1e-17 tail(0) (binary search: both
// factors fall with N). Off the contact |w| is well below 1 and a profile's
// tail-extended series (thousands of terms) is summed for a few dozen.
inline Eigen::Index potential_terms(const Eigen::VectorXd& tail, double q) {
  const Eigen::Index n = tail.size() - 1;
  if (n <= 0 || !(q < 1.0) || !(tail(0) > 0.0)) return std::max<Eigen::Index>(n, 0);
  if (!(q > 0.0)) return 1;
  const double lq = std::log(q), limit = std::log(1e-17 * tail(0));
  const auto enough = [&](Eigen::Index k) {
    return !(tail(k) > 0.0) || static_cast<double>(k + 1) * lq + std::log(tail(k)) <= limit;
  };
  Eigen::Index lo = 0, hi = n;  // enough(hi) holds (tail(n) = 0)
  while (lo < hi) {
    const Eigen::Index mid = lo + (hi - lo) / 2;
    if (enough(mid))
      hi = mid;
    else
      lo = mid + 1;
  }
  return lo;
}

// Phi(z) = sum b_n w^{n+1} = (1/pi) int p(a t)/(P/h) / (z - t) dt (n = 0, step, 2 step, ...);
// kind T: Phi(z) = sum b_n w^n / sqrt(z^2 - 1). `tail` (potential_tails of a
// U-series b, or null: every term): only the terms that reach z
// (potential_terms).
inline cplx_t cauchy_potential(const Eigen::VectorXd& b, cplx_t z, int step,
                               SeriesKind kind = SeriesKind::U,
                               const Eigen::VectorXd* tail = nullptr) {
  if (kind == SeriesKind::T) {
    cplx_t r;
    const cplx_t w = w_of(z, &r), ws = step == 1 ? w : w * w;
    cplx_t pw = 1.0, sum = 0.0;
    for (Eigen::Index n = 0; n < b.size(); n += step) {
      sum += b(n) * pw;
      pw *= ws;
    }
    return sum / r;
  }
  const cplx_t w = w_of(z), ws = step == 1 ? w : w * w;
  const Eigen::Index end =
      tail != nullptr ? std::min(potential_terms(*tail, std::abs(w)), b.size()) : b.size();
  cplx_t pw = w, sum = 0.0;
  for (Eigen::Index n = 0; n < end; n += step) {
    sum += b(n) * pw;
    pw *= ws;
  }
  return sum;
}

// Phi'(z) = -sum b_n (n+1) w^{n+1} / sqrt(z^2 - 1); kind T:
// Phi'(z) = -sum b_n w^n (n sqrt(z^2 - 1) + z) / sqrt(z^2 - 1)^3.
inline cplx_t cauchy_potential_derivative(const Eigen::VectorXd& b, cplx_t z, int step,
                                          SeriesKind kind = SeriesKind::U,
                                          const Eigen::VectorXd* tail = nullptr) {
  cplx_t r;
  const cplx_t w = w_of(z, &r), ws = step == 1 ? w : w * w;
  if (kind == SeriesKind::T) {
    cplx_t pw = 1.0, sum = 0.0;
    for (Eigen::Index n = 0; n < b.size(); n += step) {
      sum += b(n) * pw * (static_cast<double>(n) * r + z);
      pw *= ws;
    }
    return -sum / (r * r * r);
  }
  const Eigen::Index end =
      tail != nullptr ? std::min(potential_terms(*tail, std::abs(w)), b.size()) : b.size();
  cplx_t pw = w, sum = 0.0;
  for (Eigen::Index n = 0; n < end; n += step) {
    sum += b(n) * static_cast<double>(n + 1) * pw;
    pw *= ws;
  }
  return -sum / r;
}

// Lsum(z) = sum b_n L_n(z), L_n(z) = (1/pi) int sqrt(1-t^2) U_n(t) ln(z - t) dt;
// kind T: L_n(z) = (1/pi) int T_n(t)/sqrt(1-t^2) ln(z - t) dt = -ln(2 w) (n = 0),
// -w^n/n (n >= 1) (their derivatives are w^n/sqrt(z^2 - 1)).
inline cplx_t log_potential(const Eigen::VectorXd& b, cplx_t z, int step,
                            SeriesKind kind = SeriesKind::U) {
  const cplx_t w = w_of(z), w2 = w * w, ws = step == 1 ? w : w2;
  if (kind == SeriesKind::T) {
    cplx_t sum = b(0) * (-std::log(w) - potentials::kLn2);
    cplx_t pw = ws;
    for (Eigen::Index n = step; n < b.size(); n += step) {
      sum -= b(n) * pw / static_cast<double>(n);
      pw *= ws;
    }
    return sum;
  }
  cplx_t sum = b(0) * (-0.5 * std::log(w) + 0.25 * w2 - 0.5 * potentials::kLn2);
  cplx_t pw = ws;  // w^n for n = step
  for (Eigen::Index n = step; n < b.size(); n += step) {
    const double dn = static_cast<double>(n);
    sum += b(n) * 0.5 * (-pw / dn + pw * w2 / (dn + 2.0));
    pw *= ws;
  }
  return sum;
}

// Gauss-Legendre, 8 points on [0, 1].
constexpr double kGx[8] = {0.019855071751231856, 0.10166676129318664, 0.23723379504183550,
                           0.40828267875217510,  0.59171732124782490, 0.76276620495816450,
                           0.89833323870681340,  0.98014492824876810};
constexpr double kGw[8] = {0.050614268145188130, 0.11119051722668724, 0.15685332293894364,
                           0.18134189168918100,  0.18134189168918100, 0.15685332293894364,
                           0.11119051722668724,  0.050614268145188130};

// [F(zL) - F(zT)] / delta where zL - zT = h_over_delta * delta; uses the
// average of F' along the segment when it is short (delta -> 0: F' h/delta).
template <class F, class DF>
cplx_t divided_difference(const F& f, const DF& df, cplx_t zT, cplx_t zL, double delta,
                          cplx_t h_over_delta) {
  const cplx_t h = zL - zT;
  const double near = std::min(std::abs(zT - 1.0), std::abs(zT + 1.0));
  if (delta > 0.0 && std::abs(h) >= 0.25 * near) return (f(zL) - f(zT)) / delta;
  if (h_over_delta == 0.0) return 0.0;
  cplx_t avg = 0.0;
  for (int k = 0; k < 8; ++k) avg += kGw[k] * df(zT + kGx[k] * h);
  return avg * h_over_delta;
}

// The point z_n = (x - i n y)/a with Im z >= +0 (y <= 0).
inline cplx_t z_of(double x, double n, double y, double a) {
  const double im = y < 0.0 ? -n * y / a : 0.0;  // +0.0 at the surface: upper side of the cut
  return {x / a, im};
}

// The half-plane part of the vertical displacement v(x, y) mu/P,
// (1/pi) int p(xi) int_0^inf W_hp(alpha, y) (1 - e^-alpha)/alpha cos(alpha (x - xi)) d alpha d xi
// with W_hp the half-plane mode mix (WaveConstants::hp1, hp2), in closed form:
// int_0^inf (1 - e^-alpha) e^{n alpha y}/alpha cos(alpha u) = Re ln((p+1)/p), so
// V(z) = a sum b_n [L_n(z + i/a) - L_n(z)] at z = (x - i n y)/a, V'(z) = a [Phi(z + i/a) - Phi(z)].
inline double half_plane_displacement(const WaveConstants& c, const Eigen::VectorXd& b, double a,
                                      double x, double y, int step,
                                      SeriesKind kind = SeriesKind::U) {
  const double nT = c.nT, nL = c.nL, d = c.delta;
  const double kT = c.hp1 * (-1.0 / nT), kL = c.hp2 * c.dW, kD = c.hp2 * (-1.0 / nT);
  const cplx_t shift(0.0, 1.0 / a);
  auto V = [&](cplx_t z) {
    return a * (log_potential(b, z + shift, step, kind) - log_potential(b, z, step, kind));
  };
  auto dV = [&](cplx_t z) {
    return a * (cauchy_potential(b, z + shift, step, kind) - cauchy_potential(b, z, step, kind));
  };
  const cplx_t zT = z_of(x, nT, y, a), zL = z_of(x, nL, y, a);
  const cplx_t vD = divided_difference(V, dV, zT, zL, d, cplx_t(0.0, -y / a));
  return kT * V(zT).real() + kL * V(zL).real() + kD * vD.real();
}

// The half-plane part of the stresses (sigma_x, sigma_y, tau_xy)/(P/h) at
// (x, y), y <= 0, x from the contact's centre: (1/pi) Re int_0^inf
// [Sigma_x, S, -i T]_hp(alpha, y) p^ e^{i alpha x} d alpha with the half-plane
// mode mix hp1 e_T v_T + hp2 [e_L dv + v_T (e_L - e_T)/delta] (its stresses
// per unit p^, independent of the base), in closed form: a cos-type term
// e^{n alpha y} gives Re F(z_n), the sin-type tau Im F(z_n), F = i Phi,
// z_n = (x - i n y)/a. At y = 0 (upper side of the cut) sigma_x = -phi2 p,
// sigma_y = -p, tau = 0.
// `tail` (potential_tails of a U-series b, or null): each potential sums only
// the terms that reach it (potential_terms).
inline Eigen::Vector3d half_plane_stresses(const WaveConstants& c, const Eigen::VectorXd& b,
                                           double a, double x, double y, int step,
                                           SeriesKind kind = SeriesKind::U,
                                           const Eigen::VectorXd* tail = nullptr) {
  const double nT = c.nT, nL = c.nL, d = c.delta;
  const Eigen::Vector4d vT(1.0, -1.0 / nT, (1.0 + nT * nT) / nT, -2.0);
  const Eigen::Vector4d dv(0.0, c.dW, c.dT, c.dS);
  // Coefficients of e_T, e_L and the divided difference for [sigma_x, sigma_y, tau].
  const double kT[3] = {c.hp1 * sigma_x_hat(c, vT), c.hp1 * vT(3), c.hp1 * vT(2)};
  const double kL[3] = {c.hp2 * sigma_x_hat(c, dv), c.hp2 * dv(3), c.hp2 * dv(2)};
  const double kD[3] = {c.hp2 * sigma_x_hat(c, vT), c.hp2 * vT(3), c.hp2 * vT(2)};
  auto F = [&](cplx_t z) { return cplx_t(0.0, 1.0) * cauchy_potential(b, z, step, kind, tail); };
  auto dF = [&](cplx_t z) {
    return cplx_t(0.0, 1.0) * cauchy_potential_derivative(b, z, step, kind, tail);
  };
  const cplx_t zT = z_of(x, nT, y, a), zL = z_of(x, nL, y, a);
  const cplx_t fT = F(zT), fL = F(zL);
  const cplx_t fD = divided_difference(F, dF, zT, zL, d, cplx_t(0.0, -y / a));
  // cos-type (sigma_x, sigma_y): Re; sin-type (tau): Im.
  return {kT[0] * fT.real() + kL[0] * fL.real() + kD[0] * fD.real(),
          kT[1] * fT.real() + kL[1] * fL.real() + kD[1] * fD.real(),
          kT[2] * fT.imag() + kL[2] * fL.imag() + kD[2] * fD.imag()};
}

// Gauss-Chebyshev (U) rule for int_{-1}^{1} sqrt(1 - r^2) g(r) ln(1 + (u - a r)^2) dr,
// g = sum b_n U_n: nodes r_i and weights times g(r_i) (independent of u).
// The integrand is analytic but for ln(1 + (u - a r)^2) at r = (u +- i)/a:
// Gauss-Chebyshev converges like rho^(-2m), rho = 1/a + sqrt(1 + 1/a^2),
// beyond the degree of g. This m keeps it at round-off (checked against
// m = 8000 for 0.37 <= a/h <= 35: 7.5e-16 relative).
// Kind T: int g(r)/sqrt(1 - r^2) ln(1 + (u - a r)^2) dr, g = sum b_n T_n, by
// Gauss-Chebyshev of the first kind (nodes cos((2i - 1) pi/(2m)), weights pi/m).
// Only the terms that the logarithm sees: ln(1 + (u - a r)^2) = 2 Re ln(r - z0)
// + const, z0 = (u + i)/a, whose T_k coefficients are at most 4 rho(z0)^-k / k
// with rho(z0) >= rho; its moments against sqrt(1 - r^2) U_n (pi/4 (t_n (1 +
// delta_n0) - t_{n+2})) or T_n/sqrt(1 - r^2) (pi/2 t_n) are therefore at most
// 3 pi rho^-n / n, and the terms n >= K of g whose share sum |b_n| 4 pi
// rho^-n / n stays below 1e-17 of sum |b_n| are left out
// (a profile's tail-extended series has thousands of terms, the logarithm
// sees a few dozen).
inline void log1p_rule(const Eigen::VectorXd& b_all, double a, std::vector<double>& r,
                       std::vector<double>& wg, SeriesKind kind = SeriesKind::U) {
  const double rho = 1.0 / a + std::sqrt(1.0 + 1.0 / (a * a));
  Eigen::Index keep = b_all.size();
  {
    const double total = b_all.cwiseAbs().sum(), lr = std::log(rho);
    double tail = 0.0;
    while (keep > 1) {
      const double n = static_cast<double>(keep - 1);
      const double share =
          std::fabs(b_all(keep - 1)) * 4.0 * potentials::kPi * std::exp(-n * lr) / std::max(n, 1.0);
      if (tail + share > 1e-17 * total) break;
      tail += share;
      --keep;
    }
  }
  const Eigen::VectorXd b = b_all.head(keep);
  const int m = std::max(
      16, static_cast<int>(b.size()) / 2 + static_cast<int>(std::ceil(8.5 / std::log10(rho))) + 8);
  r.resize(static_cast<std::size_t>(m));
  wg.resize(static_cast<std::size_t>(m));
  if (kind == SeriesKind::T) {
    for (int i = 1; i <= m; ++i) {
      const double ri = std::cos((2 * i - 1) * potentials::kPi / (2.0 * m));
      r[static_cast<std::size_t>(i - 1)] = ri;
      wg[static_cast<std::size_t>(i - 1)] = t_series(b, ri) * potentials::kPi / m;
    }
    return;
  }
  for (int i = 1; i <= m; ++i) {
    const double th = i * potentials::kPi / (m + 1);
    const double ri = std::cos(th), sn = std::sin(th);
    r[static_cast<std::size_t>(i - 1)] = ri;
    wg[static_cast<std::size_t>(i - 1)] = sn * sn * u_series(b, ri) * potentials::kPi / (m + 1);
  }
}

// The rule of log1p_rule at u.
inline double log1p_sum(const std::vector<double>& r, const std::vector<double>& wg, double a,
                        double u) {
  double sum = 0.0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const double d = u - a * r[i];
    sum += wg[i] * std::log1p(d * d);
  }
  return sum;
}

}  // namespace movingpunch::detail

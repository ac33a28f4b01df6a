// Response of the elastic layer on a Winkler foundation to one Fourier mode of
// surface pressure, p(x) = cos(alpha x), in units h = 1, mu = 1.
//
// The layer occupies -1 <= y <= 0 (y up). Top: sigma_y = -p, tau_xy = 0. Bottom:
// tau_xy = 0 and sigma_y = kw * v (kw = inf: v = 0, a smooth rigid base); with
// a two-parameter (Pasternak) foundation sigma_y = kw v - kp d^2v/dx^2, i.e. the
// stiffness kw + kp t^2 per mode (docs/theory.md section 12).
// The steady motion at speed V enters through vstar = rho V^2 / mu.
//
// Two independent evaluations are used (see docs/theory.md):
//  * t = alpha h < kSmallT: the transfer matrix exp(-t A) by a Taylor series
//    (exact in the static limit, no loss of relative accuracy as t -> 0);
//  * t >= kSmallT: the exponential modes written relative to the face each
//    decays from, with the shear/dilatation pair replaced by its divided
//    difference (regular at vstar = 0, never overflows).
#pragma once

#include <complex>

#include <Eigen/Dense>

namespace movingpunch {

// Wave constants of the layer for one (vstar, nu); everything the layer
// response and the closed forms need, computed without cancellation.
// T = double: a real speed (every elastic medium); T = std::complex<double>:
// the complex vstar/m(t) of a viscoelastic layer with inertia, whose square
// roots are the principal ones (Re > 0: s is never real beyond 1 there).
template <class T>
struct BasicWaveConstants {
  T s{0};         // vstar
  double nu = 0;  // Poisson's ratio
  double c2 = 0;  // c_L^2 / c_T^2 = (kappa + 1) / (kappa - 1)
  T nT{1};        // sqrt(1 - s)
  T nL{1};        // sqrt(1 - s / c2)
  T delta{0};     // nL - nT >= 0, computed without cancellation
  T phi1{0};      // lim_{alpha -> inf} M1 (moving half-plane factor)
  T phi2{0};      // lim_{alpha -> inf} M2
  // Divided differences (v_L - v_T) / delta of the mode vectors [U, W, T, S].
  T dW{0}, dT{0}, dS{0};
  // Rows of the first-order system z' = alpha A z, z = [U, W, tau/alpha, sigma_y/alpha].
  Eigen::Matrix<T, 4, 4> A;
  // Half-plane solution (sigma_y/alpha = -1, tau = 0 at y = 0) on the top
  // regularised basis: z_hp(y) = hp1 e^{nT t y} v_T + hp2 d(t, y), with
  // d = e^{nL t y} dv + v_T (e^{nL t y} - e^{nT t y}) / delta. Independent of t.
  T hp1{0}, hp2{0};
};
using WaveConstants = BasicWaveConstants<double>;
using ComplexWaveConstants = BasicWaveConstants<std::complex<double>>;

// sigma_x / alpha from the state [U, W, tau/alpha, sigma_y/alpha] (Hooke's law).
inline double sigma_x_hat(const WaveConstants& c, const Eigen::Vector4d& z) {
  return 4.0 * (c.c2 - 1.0) / c.c2 * z(0) + (c.c2 - 2.0) / c.c2 * z(3);
}

// The full solution of one wavenumber, normalised so that sigma_y/alpha = -1
// and tau = 0 at y = 0 (so its stresses are per unit transformed pressure and
// its displacements are alpha times the per-unit-pressure values).
class ModeField {
 public:
  // State z(y) = [U, W, tau/alpha, sigma_y/alpha] at -1 <= y <= 0.
  Eigen::Vector4d state(double y) const;
  // The half-plane part of the state (the same top load on a half-plane).
  Eigen::Vector4d half_plane_state(double y) const;
  double t() const noexcept { return t_; }

 private:
  friend class LayerModel;
  const WaveConstants* c_ = nullptr;
  double t_ = 0;
  bool transfer_ = false;
  Eigen::Vector4d top_;  // transfer form: z(0)
  Eigen::Vector4d amp_;  // modal form: amplitudes of the four columns
};

// Throws std::invalid_argument unless 0 <= vstar < 1 and 0 <= nu < 0.5.
WaveConstants wave_constants(double vstar, double nu);
// The same closed forms at a complex speed (a viscoelastic layer with inertia:
// s = vstar/m(t), Im s >= 0); throws std::invalid_argument unless s is finite,
// not real >= 1 and 0 <= nu < 0.5.
ComplexWaveConstants complex_wave_constants(std::complex<double> s, double nu);
// Only its phi1 and phi2 (the half-plane factors, per wavenumber on the
// kernel's and the stresses' hot paths), the same checks.
struct ComplexHalfPlane {
  std::complex<double> phi1, phi2;
};
ComplexHalfPlane complex_half_plane(std::complex<double> s, double nu);

// Rayleigh speed rho c_R^2 / mu for Poisson's ratio nu.
double rayleigh_vstar(double nu);
// Closed forms of the half-plane limits, regular at vstar = 0
// (phi1(0) = 1 - nu, phi2(0) = 1). Require vstar < rayleigh_vstar(nu).
double phi1(double vstar, double nu);
double phi2(double vstar, double nu);

// Per unit transformed pressure at t = alpha h:
//   M1 = -alpha * W(alpha, 0)   (surface slope response; -> phi1)
//   M2 = -Sigma_x(alpha, 0)     (surface sigma_x; -> phi2)
struct Response {
  double M1 = 0;
  double M2 = 0;
  double U0 = 0;  // alpha * transformed u at the top, per unit pressure
  double W0 = 0;  // alpha * transformed v at the top, per unit pressure
};

class LayerModel {
 public:
  static constexpr double kSmallT = 0.5;

  // kw = k_w h / mu in (0, inf] (0, no foundation, has no equilibrium);
  // kp = k_p / (mu h) in [0, kMaxKp], the Pasternak shear layer (0: Winkler;
  // irrelevant for kw = inf); throws std::invalid_argument otherwise.
  LayerModel(double vstar, double kw, double nu, double kp = 0.0);

  const WaveConstants& constants() const noexcept { return c_; }
  double vstar() const noexcept { return c_.s; }
  double kw() const noexcept { return kw_; }
  double kp() const noexcept { return kp_; }
  // The base's stiffness per mode, kw + kp t^2 (t = alpha h; inf: rigid).
  double foundation(double t) const noexcept { return kw_ + kp_ * t * t; }
  double nu() const noexcept { return c_.nu; }
  double phi1() const noexcept { return c_.phi1; }
  double phi2() const noexcept { return c_.phi2; }
  bool rigid_base() const noexcept { return rigid_; }

  // Response at t = alpha h > 0 (t = 0 returns the exact limit M1 = 0 for
  // finite kw). Finite for every t up to 1e300.
  Response response(double t) const;

  // Same, forcing one of the two evaluations (for cross-checks in tests).
  Response response_modal(double t) const;
  Response response_transfer(double t) const;

  // The full solution at t = alpha h > 0 (keeps a pointer to this model's
  // constants: the model must outlive it).
  ModeField mode_field(double t) const;

  // A function of (t, vstar) that changes sign exactly where a free wave of
  // wavenumber t exists (a real pole of the response), as vstar varies at a
  // fixed t (the critical-speed search scans vstar). Its sign convention is
  // arbitrary and differs between t < kSmallT (the transfer matrix) and t >=
  // kSmallT (the modal columns): scanned over t at a fixed vstar it also
  // changes sign at kSmallT.
  double dispersion(double t) const;

 private:
  WaveConstants c_;
  double kw_;
  bool rigid_;
  double kp_ = 0.0;
};

// Largest Pasternak stiffness kp = k_p/(mu h) accepted. Beyond ~1 the
// critical speed is already the Rayleigh speed and the base acts as a rigid
// one for every wave shorter than sqrt(kp/kw) h; 1e12 keeps kp t^2 finite
// for every t the layer response evaluates (t nT < 400) and its effect on
// the long waves resolved. Shared by every validation of kp.
inline constexpr double kMaxKp = 1e12;

}  // namespace movingpunch

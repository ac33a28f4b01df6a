// Gauss-Jacobi collocation for the singular integral equation of the second
// kind of a punch sliding with Coulomb friction (docs/theory.md section 14):
//   f Phi p(x) + (1/pi) int p(xi)/(xi - x) d xi + (regular) = (slope term),
// whose bounded solution is p(c + w r) = (1 - r)^alpha (1 + r)^beta g(r),
// alpha + beta = 1, cot(pi beta) = f Phi (alpha: the leading end r = +1).
//
// The rule (Erdogan, Gupta & Cook 1973; Krenk 1975): with r_i the zeros of
// P_N^(alpha, beta), W_i the Gauss-Jacobi weights and s_k the N + 1 zeros of
// P_{N+1}^(-alpha, -beta),
//   f Phi w(s_k) g(s_k) + (1/pi) int w g/(t - s_k) dt = (1/pi) sum_i W_i g(r_i)/(r_i - s_k)
// exactly for polynomials g of degree < N, because
//   (1/pi) int w P_n^(alpha,beta)/(t - x) dt = cot(pi alpha) w P_n^(alpha,beta)(x)
//       - 2/sin(pi alpha) P_{n+1}^(-alpha,-beta)(x)   (-1 < x < 1)
// and cot(pi alpha) = -f Phi. alpha = beta = 1/2 is Gauss-Chebyshev.
#pragma once

#include <complex>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "movingpunch/collocation.hpp"
#include "movingpunch/layer_response.hpp"

namespace movingpunch {

// The moving half-plane's response to a unit tangential surface load (top
// state [U, W, T, S] = [Uq, Wq, 1, 0]; the physical amplitudes of a load
// tau_xy = e^{i alpha x} are i times these) and the coupling constant
//   Phi = Wq / phi1 = (2 - s - 2 nL nT) / (s nL) = (2X/(1 + Y) - 1)/nL,
// (1 - 2 nu)/(2 (1 - nu)) at s = 0; finite at the Rayleigh speed.
struct TangentialHalfPlane {
  double Uq = 0;   // nT / D', D' = 4 - s - 4X/(1 + Y)
  double Wq = 0;   // (2X/(1 + Y) - 1) / D'
  double Phi = 0;  // Wq / phi1
};
TangentialHalfPlane tangential_half_plane(const WaveConstants& c);

// The end exponents for friction f >= 0 and coupling Phi: p ~ (a - x)^front
// (x + b)^back, front = 1/2 + atan(f Phi)/pi, back = 1 - front (cot(pi back)
// = f Phi). Throws std::invalid_argument unless f Phi is finite.
struct EndExponents {
  double back = 0.5, front = 0.5;
};
EndExponents end_exponents(double f, double Phi);

// P_n^(a, b)(x) and its derivative by the three-term recurrence (any a, b
// with a + b != -2, including a + b = -1).
void jacobi_p(int n, double a, double b, double x, double* p, double* dp = nullptr);

// The n zeros of P_n^(a, b) (ascending), a, b > -1 or a + b = -1 with
// -1 < a, b < 1: eigenvalues of the Jacobi matrix, polished by Newton steps.
Eigen::VectorXd jacobi_zeros(int n, double a, double b);

// Gauss-Jacobi rule: int_{-1}^{1} (1-x)^a (1+x)^b f ~ sum w_i f(x_i), a, b > -1.
struct JacobiRule {
  Eigen::VectorXd x, w;
};
JacobiRule gauss_jacobi(int n, double a, double b);
// The same rule from a process-wide cache keyed on (n, a, b) (thread-safe; at
// 256 rules the cache is emptied, and the pointer keeps its rule alive).
std::shared_ptr<const JacobiRule> cached_gauss_jacobi(int n, double a, double b);

// h_n = int_{-1}^{1} (1 - x)^a (1 + x)^b (P_n^(a, b))^2 dx (a, b > -1).
double jacobi_norm(int n, double a, double b);

// The moments of P_m = P_m^(a, b) (a, b > -1) against its weight w = (1 - s)^a
// (1 + s)^b over part of [-1, 1], m = 0 .. count - 1:
//   upper: I_m = int_{s0}^{1} w P_m ds, J_m = int_{s0}^{1} s w P_m ds;
//   lower: the same over [-1, s0].
// I_m (m >= 1) in closed form by Rodrigues' formula, w P_m = -(1/(2m)) d/ds
// [(1 - s)^(a+1) (1 + s)^(b+1) P_{m-1}^(a+1, b+1)]; I_0 by a 32-node
// Gauss-Jacobi rule from the nearer end (its other factor is analytic well
// beyond the piece); J from I by the three-term recurrence of s P_m. The
// projections of a piecewise linear slope (the rounded flat punch's) onto
// the P_m are sums of these: O(count), exact to round-off, where a quadrature
// needs O(count^2) work and a rule of 2 count nodes.
struct JacobiMoments {
  std::vector<double> I, J;
};
JacobiMoments jacobi_upper_moments(double a, double b, double s0, int count);
JacobiMoments jacobi_lower_moments(double a, double b, double s0, int count);

// The collocation nodes of the rule above in ChebyshevNodes' layout (so that
// the damped solver's width evaluation applies unchanged): r = zeros of
// P_N^(alpha, 1 - alpha), s = zeros of P_{N+1}^(-alpha, alpha - 1), w =
// Gauss-Jacobi weights / pi. alpha = 1/2 gives chebyshev_nodes(n) up to round-off.
ChebyshevNodes jacobi_collocation_nodes(int n, double alpha);

// The flat punch's rule (index +1, alpha + beta = -1, -1 < alpha, beta < 0;
// docs/theory.md section 14, "The flat punch on the asymmetric solver"): r =
// the N zeros of P_N^(alpha, beta), s = the N - 1 zeros of
// P_{N-1}^(-alpha, -beta), w = Gauss-Jacobi weights / pi (descending, as
// chebyshev_nodes). Exact as in the rule above because for alpha + beta = -1
//   (1/pi) int w P_n^(alpha,beta)/(t - x) dt = cot(pi alpha) w P_n^(alpha,beta)(x)
//       - (1/2)/sin(pi alpha) P_{n-1}^(-alpha,-beta)(x)   (n >= 1; n = 0: the cot term).
// alpha = beta = -1/2 is first-kind Gauss-Chebyshev (the undamped flat punch).
ChebyshevNodes jacobi_flat_nodes(int n, double alpha, double beta);

// g(r) = sum_n c_n P_n^(alpha, beta)(r) with alpha + beta = 1 (bounded ends,
// 0 < alpha < 1) or alpha + beta = -1 (index +1, unbounded ends: the flat
// punch, -1 < alpha < 0), the density w(r) g(r), w = (1 - r)^alpha (1 + r)^beta,
// and its integrals in closed form.
class JacobiSeries {
 public:
  JacobiSeries() = default;
  // alpha + beta = 1.
  JacobiSeries(double alpha, Eigen::VectorXd c);
  // alpha + beta = 1 or -1 (to 1e-12); throws std::invalid_argument otherwise.
  JacobiSeries(double alpha, double beta, Eigen::VectorXd c);
  // From the values g(r_i) at the zeros r_i of P_N^(alpha, beta) (exact for
  // polynomials of degree < N).
  static JacobiSeries from_nodes(double alpha, const Eigen::VectorXd& r, const Eigen::VectorXd& g);
  static JacobiSeries from_nodes(double alpha, double beta, const Eigen::VectorXd& r,
                                 const Eigen::VectorXd& g);

  double alpha() const noexcept { return alpha_; }
  double beta() const noexcept { return beta_; }
  // Index +1 (alpha + beta = -1): the density is unbounded at r = +-1.
  bool singular() const noexcept { return alpha_ + beta_ < 0.0; }
  const Eigen::VectorXd& coefficients() const noexcept { return c_; }
  int size() const noexcept { return static_cast<int>(c_.size()); }

  double g(double r) const;  // the series (any real r)
  // g at m points r[0..m-1] into out[0..m-1] (the recurrences of eight points
  // interleaved: several times faster than m calls of g on long series).
  void g_values(const double* r, int m, double* out) const;
  double weight(double r) const;   // (1 - r)^alpha (1 + r)^beta on [-1, 1], 0 outside
  double density(double r) const;  // weight(r) g(r)
  // int_{-1}^{1} w g dr (= int p / (P/h) / half-width) and int w g r dr.
  double moment0() const;
  double moment1() const;
  // (1/pi) int_{-1}^{1} w(t) g(t)/(t - x) dt for real x (principal value on
  // the cut): the closed form inside and near the cut, Gauss-Jacobi
  // quadrature (converging like (|x| + sqrt(x^2 - 1))^(-2M)) beyond the
  // Bernstein ellipse rho(x) = closed_form_radius() (|x| >= 1.2 for N <= 18).
  double cauchy(double x) const;
  // min(1.86, 10^(5/N)): the closed forms' Bernstein radius (their terms grow
  // like rho^N off the cut; beyond it the Gauss-Jacobi rule).
  double closed_form_radius() const;
  // (1/pi) int_{-1}^{1} w(t) g(t)/(t - z) dt and its derivative in z, for
  // Im z >= 0 (z off the cut or on its upper side): the closed form
  // [Z(z) g(z) - q sum c_n P_{n+shift}^(-alpha,-beta)(z)]/sin(pi alpha) (q, shift
  // as in shift() below), Z = (z-1)^alpha
  // (z+1)^beta, inside the Bernstein ellipse rho(z) < closed_form_radius(), else
  // the rule of cauchy().
  std::complex<double> cauchy_upper(std::complex<double> z,
                                    std::complex<double>* derivative = nullptr) const;
  // The same for series with other coefficients: this - other (same alpha).
  JacobiSeries minus(const JacobiSeries& other) const;
  // max over [-1, 1] of |w g| sampled at 8 (N + 1) + 64 Chebyshev angles (the
  // ends included: +inf for a singular series with g(+-1) != 0).
  double max_abs_density() const;
  // max over [-1, 1] of |g|, sampled the same way.
  double max_abs_g() const;
  // min over (-1, 1) of g (the margin before separation), scanned and refined.
  double min_g() const;

 private:
  double alpha_ = 0.5, beta_ = 0.5;
  Eigen::VectorXd c_;
  // The Cauchy integral's polynomial part: q sum c_n P_{n + shift}^(-alpha, -beta),
  // q = 2, shift = 1 (alpha + beta = 1); q = 1/2, shift = -1 (alpha + beta = -1).
  int shift() const noexcept { return singular() ? -1 : 1; }
  double poly_factor() const noexcept { return singular() ? 0.5 : 2.0; }
  // The three-term recurrences of P^(alpha, beta) and P^(-alpha, -beta) with
  // their coefficients divided out once, and cauchy()'s Gauss-Jacobi rule for
  // |x| >= 1.2 (N + 60 nodes) times g there, built on first use (thread-safe;
  // copies share it: a series never changes).
  struct Derived;
  std::shared_ptr<Derived> derived_;
  const Derived& derived() const;
  struct Far {
    Eigen::VectorXd x, wg;
  };
  const Far& far() const;
};

// int_{-1}^{1} w(r) g(r) e^{-i omega r} dr at many omega (|omega| <= omega_max)
// by one Gauss-Jacobi rule of L + omega_max + 40 nodes (exact to round-off:
// the integrand is entire, the rule resolves the oscillation), L the length
// beyond which the terms' transforms, bounded by sqrt(h_0 h_m) omega^m/m!,
// add less than 1e-17 of sum |c_m| sqrt(h_0 h_m).
class JacobiTransform {
 public:
  // With `second` (same alpha, at most as long as s): its transform too (second()).
  // `interpolate` false: no interpolant (for a transform wanted at one omega).
  JacobiTransform(const JacobiSeries& s, double omega_max, const JacobiSeries* second = nullptr,
                  bool interpolate = true);
  std::complex<double> operator()(double omega) const { return both(omega).first; }
  std::complex<double> second(double omega) const { return both(omega).second; }
  // Both at once.
  std::pair<std::complex<double>, std::complex<double>> both(double omega) const;

 private:
  JacobiRule rule_;
  Eigen::VectorXd gw_, gw2_;
  // Both by the rule's sums (one set of phases).
  std::pair<std::complex<double>, std::complex<double>> direct(double omega) const;
  // On 0 <= omega <= omega_max the transforms are entire of exponential type
  // 1: their Chebyshev interpolants in omega (K + 1 points, L = omega_max/2)
  // are within 8 sum|gw| (L/2)^(K+1)/(K+1)! of them (Jacobi-Anger: the
  // coefficients of e^{-i omega x} are 2 |J_k(L x)| <= 2 (L/2)^k/k!), K chosen
  // so that this is below 1e-17 sum|gw|; evaluated by the barycentric formula
  // (no sines per call: a fine quadrature calls it thousands of times).
  double half_range_ = 0;
  std::vector<double> nodes_, bary_;
  Eigen::VectorXcd v1_, v2_;
};

}  // namespace movingpunch

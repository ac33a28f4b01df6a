// Viscoelastic sublayers: a generalised Maxwell (Prony) solid in shear with a
// constant Poisson's ratio (docs/theory.md section 17).
//
// Time convention: a mode e^{i alpha x}, x = x1 - V t, oscillates at a
// material point as e^{-i omega t} with omega = alpha V, and the shear modulus
// at that frequency, over the relaxed (long-time) modulus mu_0, is
//   m(t) = 1 + sum_j g_j (-i t D_j)/(1 - i t D_j),   t = alpha h,
// D_j = shift V tau_j / h (tau_j: the branch's relaxation time at constant
// strain, shift: a time-temperature shift factor a_T). Im m < 0 for t > 0:
// the material dissipates (positive work per cycle). The standard linear
// solid (Zener) is one branch: g = ratio - 1, D = deborah, and then
//   m(t) = (1 - i ratio deborah t)/(1 - i deborah t).
// m(inf) = 1 + sum g_j = mu_inf/mu_0 (the unrelaxed, instantaneous modulus).
//
// Quasi-statically (no inertia) the half-plane's surface compliance is
// (1 - nu)/m(t) (over mu_0); over its unrelaxed value (1 - nu)/m(inf),
//   m(inf)/m(t) - 1 = sum_k c_k / (1 - i beta_k t)   (c_k > 0, beta_k > 0),
// the retardation spectrum: -1/beta_k (in s = -i t) are the zeros of m, which
// interlace its poles -1/D_j. Its kernel is a causal memory: in x it is the
// convolution with sum_k (c_k/beta_k) e^{x/beta_k} (x < 0: the material ahead
// of a point was loaded earlier), and the collocation integrates it exactly
// against the pressure's Chebyshev series (MemoryKernel).
#pragma once

#include <complex>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace movingpunch {

struct ChebyshevNodes;  // collocation.hpp

// The material of a viscoelastic sublayer. Empty (no branches): elastic.
struct Viscoelastic {
  std::vector<double> weights;   // g_j > 0: the branch's modulus over mu_0
  std::vector<double> deborahs;  // V tau_j / h > 0 (before the shift)
  double shift = 1.0;            // a_T > 0, multiplies every tau_j
  // No branch that relaxes in time (shift * deborah > 0; a branch of deborah
  // 0 relaxes at once and adds nothing at any frequency): elastic.
  bool empty() const noexcept;
  // mu_inf / mu_0 = 1 + sum g_j over those branches (the spectrum's ratio).
  double ratio() const noexcept;
  // m(t) (above), t >= 0.
  std::complex<double> modulus(double t) const;
};

// The standard linear solid: ratio = mu_inf/mu_0 >= 1 (1: elastic, no branch),
// deborah = V tau / h >= 0 (0: elastic with mu_0, no branch).
Viscoelastic zener(double ratio, double deborah);

// The limits a material's numbers must stay within (InvalidParameter names
// them): at most kMaxBranches branches, each g_j in (0, kMaxViscoRatio - 1],
// D_j shift in [kMinDeborah, kMaxDeborah] (or exactly 0 with the branch then
// dropped: the relaxed limit), 1 + sum g_j <= kMaxViscoRatio.
inline constexpr std::size_t kMaxBranches = 32;
inline constexpr double kMaxViscoRatio = 1e6;
inline constexpr double kMinDeborah = 1e-12;
inline constexpr double kMaxDeborah = 1e12;

// Throws InvalidParameter naming `where` (e.g. "layers[0].viscoelastic")
// and the offending number and its range.
void validate(const Viscoelastic& v, const std::string& where);

// The retardation spectrum of a material (above): c_k, beta_k, ascending in
// beta; sum c_k = m(inf) - 1. Exact for one branch; otherwise the zeros of
// m by bisection in log(-s) between its poles (to round-off).
struct RetardationSpectrum {
  std::vector<double> c, beta;
  double ratio = 1.0;  // m(inf)
  // m(inf)/m(t) - 1 by the sum (t >= 0).
  std::complex<double> memory(double t) const;
};
RetardationSpectrum retardation_spectrum(const Viscoelastic& v);

// With inertia (docs/theory.md section 17.6): the half-plane's surface
// compliance H(t) = phi1(vstar/m(t))/m(t) (over mu_0) over its unrelaxed value
// H_inf = phi1(vstar/m_inf)/m_inf, less 1, as the same sum (the memory of
// the material ahead of a point): f = H/H_inf - 1 is analytic off the
// negative imaginary t axis, where m is real; there it has a pole where
// vstar/m reaches the Rayleigh speed (one per branch: c_k exact from its
// residue) and a cut where vstar/m >= 1 (the supersonic, radiating modes, up
// to the zero of m), whose density Im f/(pi y) at t = -i y is integrated by
// Gauss-Legendre nodes in angles that make its square-root ends analytic
// (each node one term; the c_k of the cut may be of either sign). The nodes
// are doubled until the sum matches f to `tol` (default 1e-12: near the
// Rayleigh speed round-off in the cut's density holds it to about 5e-14)
// relative to max |f| (f(0) =
// H(0)/H_inf - 1 ~ m_inf - 1; over real t on a grid spanning the spectrum);
// `error` is the largest difference found (absolute).
// vstar = 0: retardation_spectrum. Requires 0 <= vstar < rayleigh_vstar(nu)
// (std::invalid_argument otherwise); ConvergenceError if tol is not met at
// 256 nodes a piece.
// which = stress: the same for the surface sigma_x's half-plane symbol
// phi2(vstar/m(t)) (no 1/m: stresses per unit pressure), over phi2(vstar/
// m_inf): at rest it is constant (an empty spectrum).
enum class HalfPlaneSymbol { compliance, stress };
struct InertialSpectrum {
  RetardationSpectrum spectrum;
  double h_inf = 0;  // H_inf (phi2(vstar/m_inf) for the stress symbol)
  double error = 0;  // max |sum - f| on the check grid
};
InertialSpectrum inertial_spectrum(const Viscoelastic& v, double vstar, double nu,
                                   double tol = 1e-12,
                                   HalfPlaneSymbol which = HalfPlaneSymbol::compliance);
// H_inf = phi1(vstar/m_inf)/m_inf: the Cauchy term's coefficient.
double unrelaxed_phi1(const Viscoelastic& v, double vstar, double nu);
// phi2(vstar/m(t)), t >= 0: the surface sigma_x's half-plane symbol.
std::complex<double> half_plane_stress(const Viscoelastic& v, double vstar, double nu, double t);
// H(t) = phi1(vstar/m(t))/m(t), t >= 0 (principal roots).
std::complex<double> half_plane_compliance(const Viscoelastic& v, double vstar, double nu,
                                           double t);

// The memory part of the kernel of the asymmetric equation (docs/damped.md
// section 2, the term -(1/pi) int p(xi) K(x - xi) d xi) for a quasi-static
// viscoelastic top:
//   K_m(u) = sum_k c_k pi H[e_k](u),  e_k(u) = e^{u/beta_k}/beta_k (u < 0),
// H the Hilbert transform (1/pi) p.v. int f(xi)/(u - xi) d xi. Against the
// density g(r) sqrt(1 - r^2) = sum_n b_n U_n(r) sqrt(1 - r^2) on a contact
// of half-width w (r = (xi - c)/w, s = (x - c)/w):
//   (w/pi) int sqrt(1 - r^2) U_n(r) K_m(w (s - r)) dr = sum_k c_k lambda_k J_n(s, lambda_k),
//   J_n(s, l) = int_s^inf e^{-l (x - s)} h_n(x) dx,  lambda_k = w/beta_k,
// h_n = H[sqrt(1 - r^2) U_n]: T_{n+1}(x) on [-1, 1], (x - sgn(x) sqrt(x^2 -
// 1))^{n+1} beyond. J_n has no singularity (the kernel's logarithm is in the
// Hilbert transform of the basis, taken exactly), and l J_n -> h_n(s) as l
// -> inf (the relaxed limit: c_k times the Cauchy term), -> 0 as l -> 0.
// The density's basis for the memory's moments: U, sqrt(1 - r^2) U_n(r)
// (bounded ends: h_n as above); T, T_n(r)/sqrt(1 - r^2) (a flat face's
// square-root edges: h_n = H[T_n/sqrt(1 - r^2)] = -U_{n-1}(x) on [-1, 1]
// (0 for n = 0), sgn(x) rho^n/sqrt(x^2 - 1) beyond). sqrt(1 - r^2) U_n =
// (T_n - T_{n+2})/(2 sqrt(1 - r^2)) ties the two: J^U_n = (J^T_n - J^T_{n+2})/2.
enum class MemoryBasis { U, T };

class MemoryKernel {
 public:
  explicit MemoryKernel(RetardationSpectrum spectrum);
  const RetardationSpectrum& spectrum() const noexcept { return spec_; }
  bool empty() const noexcept { return spec_.c.empty(); }
  // out[n] = sum_k c_k lambda_k J_n(s, lambda_k), n < count, for the half-width w.
  void moments(double s, double w, int count, double* out,
               MemoryBasis basis = MemoryBasis::U) const;
  // The collocation block B(k, i), (N + 1) x N, added to the asymmetric
  // matrix's W_i [1/(r_i - s_k) - w K(w (s_k - r_i))]:
  //   B(k, i) = -2 W_i sum_n U_n(r_i) moments_n(s_k).
  Eigen::MatrixXd collocation_block(const ChebyshevNodes& nodes, double w) const;
  // The same block at `rows` descending points s[0] > s[1] > ... in the
  // density's frame (any real s: another contact zone's collocation points,
  // (x - c)/w): rows x N, -2 W_i sum_n U_n(r_i) moments_n(s_k).
  Eigen::MatrixXd block_at(const double* s, int rows, const ChebyshevNodes& nodes, double w) const;
  // w (1/pi) int sqrt(1 - r^2) g(r) K_m(x - c - w r) dr for g = sum b_n U_n
  // (the slope's memory part at any x; s = (x - c)/w any real).
  double apply(const Eigen::VectorXd& b, double s, double w,
               MemoryBasis basis = MemoryBasis::U) const;
  // apply at `rows` descending points s[0] > s[1] > ... (out[k] at s[k]):
  // one downward sweep (each row adds the segment to the previous one).
  void apply_descending(const Eigen::VectorXd& b, const double* s, int rows, double w,
                        double* out) const;
  // moments at descending points, rows x count row-major in out.
  void moments_descending(const double* s, int rows, double w, int count, double* out,
                          MemoryBasis basis = MemoryBasis::U) const;
  // -2 W_i U_q(r_i) (q, i < N): the block's basis, kept per size N.
  static std::shared_ptr<const Eigen::MatrixXd> basis_weights(const ChebyshevNodes& nodes);

 private:
  RetardationSpectrum spec_;
  // The terms by beta ascending, in clusters of nearby retardation times
  // (viscoelastic.cpp: kClusterRatio) that share their quadrature nodes:
  // cluster i is order_[starts_[i]] .. order_[starts_[i + 1] - 1].
  std::vector<std::size_t> order_, starts_;
  // The m terms of the cluster from order_[j0]: lambda = w/beta and c.
  void cluster_terms(std::size_t j0, std::size_t m, double w, std::vector<double>& l,
                     std::vector<double>& c) const;
};

// A viscoelastic TOP material's half-plane parts at one speed (every medium
// whose top sublayer is viscoelastic: the layer on springs, a stack): the
// Cauchy term's coefficient H_inf and the surface sigma_x's phi2(vstar/m_inf),
// the symbols H(t) and phi2(vstar/m(t)) the kernel and the surface stress
// subtract, and their memories (inertial_spectrum; at rest the retardation
// spectrum and no stress memory).
class ViscoelasticTop {
 public:
  ViscoelasticTop(const Viscoelastic& v, double vstar, double nu);
  double h_inf() const noexcept { return compliance_.h_inf; }
  double phi2_inf() const noexcept { return stress_.h_inf; }
  std::complex<double> m1(double t) const { return half_plane_compliance(v_, vstar_, nu_, t); }
  std::complex<double> m2(double t) const { return half_plane_stress(v_, vstar_, nu_, t); }
  std::complex<double> modulus(double t) const { return v_.modulus(t); }
  const MemoryKernel& memory() const noexcept { return memory_; }
  // Null at rest (phi2 does not depend on the modulus there).
  const RetardationSpectrum* stress_memory() const noexcept {
    return stress_.spectrum.c.empty() ? nullptr : &stress_.spectrum;
  }
  // The material's own compliance memory m_inf/m(t) - 1.
  const RetardationSpectrum& compliance_memory() const noexcept { return relaxation_; }

 private:
  Viscoelastic v_;
  double vstar_, nu_;
  InertialSpectrum compliance_, stress_;
  RetardationSpectrum relaxation_;
  MemoryKernel memory_;
};

// int_T^inf (beta t/(1 + beta^2 t^2)) t^-3 dt = beta (1/T - beta atan(1/(beta T)))
// (cancellation-free): one retardation time's part of the dissipation's
// Parseval integral beyond T, where |p^|^2 has reached its t^-3 asymptotics.
double memory_tail_integral(double beta, double T);

// l J_n(s, l) for n < count (one retardation time; MemoryKernel sums them).
void memory_moments(double s, double l, int count, double* out, MemoryBasis basis = MemoryBasis::U);
// The same at rows points s[0] > s[1] > ... (out: rows x count, row-major),
// by the recursion G(s_k) = (the segment [s_k, s_{k-1}]) + e^{-l (s_{k-1} -
// s_k)} G(s_{k-1}): one short segment a row after the first.
void memory_moments_descending(const double* s, int rows, double l, int count, double* out,
                               MemoryBasis basis = MemoryBasis::U);

}  // namespace movingpunch

// The moving punch on a layer over a damped (Kelvin-Voigt) Winkler foundation.
//
// Base condition (moving frame, units h = 1, mu = 1, c_T = 1):
//   sigma_y(x, -1) = kw v + c_w dv/dt = kw v - damping sqrt(vstar) dv/dx,
// with damping = c_w c_T / mu (c_w: pressure per unit velocity). With Fourier
// modes e^{i alpha x} (f^(alpha) = int f e^{-i alpha x} dx) the foundation
// becomes the complex, alpha-dependent stiffness
//   kw(alpha) = kw - i damping sqrt(vstar) alpha,
// so the layer response is complex: M1(-alpha) = conj(M1(alpha)). A
// Pasternak shear layer kp adds kp alpha^2 to it (- kp d^2v/dx^2 in the base
// condition; docs/theory.md section 12). The
// contact (-b, a) is asymmetric and both ends are unknown; see docs/damped.md.
//
// damping = 0 is the paper's model and is NOT handled here: solve_contact()
// (contact.hpp) is the undamped path and is unchanged.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "movingpunch/contact.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/jacobi.hpp"
#include "movingpunch/kernel.hpp"
#include "movingpunch/layer_response.hpp"
#include "movingpunch/profile.hpp"
#include "movingpunch/stresses.hpp"

namespace movingpunch {

using cplx = std::complex<double>;

// The asymmetric solver's response per unit transformed load (medium.hpp's
// FullResponse: M1, M2, U0, W0, the base face's Wb, the unit tangential
// load's Uq, Wq, Wqb).
using DampedResponse = FullResponse;

// The homogeneous layer on damped springs: make_medium's implementation of
// Medium for a damped homogeneous spec (medium.cpp), and the closed-form
// modal fields of the asymmetric solver's depth outputs on that layer.
class DampedLayerModel {
 public:
  static constexpr double kSmallT = 0.5;

  // vstar in [0, 1), kw in (0, inf], nu in [0, 0.5), damping >= 0 finite,
  // kp in [0, kMaxKp] (the Pasternak shear layer; 0: springs alone);
  // throws std::invalid_argument naming the parameter otherwise.
  // visco: a viscoelastic layer (viscoelastic.hpp): the layer in units of
  // its modulus at each frequency, mu_0 m(t), so that the foundation is
  // kw(alpha)/m(t), the speed vstar/m(t) (complex wave constants at each t
  // when vstar > 0) and the displacements of the response are per mu_0 m(t)
  // (the medium divides them by m(t), medium.cpp).
  DampedLayerModel(double vstar, double kw, double nu, double damping, double kp = 0.0,
                   Viscoelastic visco = {});

  const WaveConstants& constants() const noexcept { return c_; }
  double vstar() const noexcept { return c_.s; }
  double kw() const noexcept { return kw_; }
  double nu() const noexcept { return c_.nu; }
  double damping() const noexcept { return damping_; }
  double kp() const noexcept { return kp_; }
  double phi1() const noexcept { return c_.phi1; }
  double phi2() const noexcept { return c_.phi2; }
  bool rigid_base() const noexcept { return rigid_; }
  // kw(alpha) = kw + kp t^2 - i damping sqrt(vstar) t for alpha = t > 0
  // (over m(t) for a viscoelastic layer).
  cplx foundation(double t) const noexcept;

  // Response at t = alpha h >= 0 (t = 0: the exact limit M1 = 0, Wb = 0).
  DampedResponse response(double t) const;
  // The moving half-plane's tangential response (jacobi.hpp).
  const TangentialHalfPlane& tangential() const noexcept { return tq_; }
  // Forcing one of the two evaluations (cross-checks in tests).
  DampedResponse response_modal(double t) const;
  DampedResponse response_transfer(double t) const;
  // State [U, W, tau/alpha, sigma_y/alpha] at depth -1 <= y <= 0 of the mode
  // normalised by sigma_y/alpha = -1, tau = 0 at y = 0 (complex amplitudes of
  // u = -i U e^{i alpha x}, v = W e^{i alpha x}, ...), t > 0.
  Eigen::Vector4cd state(double t, double y) const;
  // state's part independent of y, z(t) (t > 0): for t < kSmallT the top
  // state (state = exp(t y A) z), else the amplitudes of the regularised
  // modal columns (state = modal_columns(t, y) z).
  Eigen::Vector4cd state_coefficients(double t) const;
  // The state of the unit tangential load (top T = 1, S = 0; the physical
  // amplitudes of tau_xy = e^{i alpha x} are i times it) at -1 <= y <= 0, t > 0.
  Eigen::Vector4cd tangential_state(double t, double y) const;

 private:
  WaveConstants c_;
  double kw_;
  double damping_;
  bool rigid_;
  double beta_;  // damping sqrt(vstar)
  double kp_ = 0.0;
  TangentialHalfPlane tq_;
  Viscoelastic visco_;
  // A viscoelastic layer with inertia (vstar > 0): the wave constants of
  // vstar/m(t) at each t (complex), constants_at.
  bool inertial_ = false;
  ComplexWaveConstants constants_at(double t) const;
};

// Adaptive (Gauss-Kronrod 7/15) panels on [0, alpha_max] resolving
// M1 - phi1, M2 - phi2 and Wb of a damped layer; nodes in the order of
// kernel.hpp's AlphaQuadrature (so FilonIntegrator applies).
struct AsymmetricQuadrature {
  AlphaQuadrature panels;  // nodes, weights, panel centres/half-widths
  std::vector<cplx> m1, m2, wb;
  std::vector<DampedResponse> r;  // the whole response at each node
  double error_estimate = 0;      // of the integral of |M1 - phi1|/phi1
  // QUADPACK's (qk15) estimate of the error of the Kronrod sums actually used
  // (|K15 - G7| above bounds the Gauss rule's error, far larger once resolved).
  double kronrod_error = 0;
};
// friction > 0: the panels resolve friction (Wq - Wq_inf)/phi1 too. Any
// medium (its full_response; the panels end where its slowest field decays
// below 1e-18, field_decay_rate).
AsymmetricQuadrature build_damped_quadrature(const Medium& model, double tol,
                                             double friction = 0.0);

// The regular kernel K(u) of the damped equation (asymmetric_kernel() below) for
// one medium (Medium::key()) and friction: the alpha quadrature and its Filon
// coefficients (range-independent, shared by every table of these inputs) and
// a piecewise Chebyshev table (degree 24 on equal pieces of width <= 1) on
// |u| <= range(), built from direct Filon sums and checked piece by piece
// (the last coefficients at round-off). Beyond the range: direct sums.
// Immutable and shared between solves (cached_damped_kernel).
class AsymmetricKernel {
 public:
  // friction > 0: the kernel of the frictional equation, K - f K_t with the
  // effective response M1 - i f Wq (docs/theory.md section 14).
  AsymmetricKernel(std::shared_ptr<const Medium> model, double range, double friction = 0.0);
  // A wider table on the quadrature of `other` (no new layer responses).
  AsymmetricKernel(const AsymmetricKernel& other, double range);

  double operator()(double u) const;  // the table on |u| <= range(), direct() beyond
  void many(const double* u, double* out, std::size_t n) const;  // out[i] = (*this)(u[i])
  double direct(double u) const;                                 // Filon sums, any u
  double range() const noexcept { return range_; }
  double friction() const noexcept { return base_->friction; }
  // Bound on |table - direct| (truncation of the pieces plus their values'
  // round-off), absolute.
  double table_error() const noexcept { return table_error_; }
  const Medium& model() const noexcept { return *base_->model; }
  const std::shared_ptr<const Medium>& model_ptr() const noexcept { return base_->model; }
  const AsymmetricQuadrature& quadrature() const noexcept { return base_->quad; }
  const FilonIntegrator& filon() const noexcept { return *base_->filon; }
  const std::vector<double>& kr() const noexcept { return base_->kr; }
  const std::vector<double>& ki() const noexcept { return base_->ki; }
  // Whether the medium has a positive quadratic form: Re M1 > 0 at every
  // wavenumber (on the quadrature's nodes with a margin, and its half-plane
  // part beyond them), decided once when the quadrature is built. Then a
  // frictionless steady contact is unique: a valid one is the only one (no
  // scan for other steady states is needed; docs/theory.md section 9).
  bool positive_form() const noexcept { return base_->positive_form; }
  // The surface's band beside a contact (gap_scan.hpp's response_band of
  // |M1 - H|, H the medium's half-plane part, whose memory a viscoelastic
  // top's gap takes exactly): the gap checks' sampling step, decided once
  // per quadrature as positive_form.
  double surface_band() const noexcept { return base_->surface_band; }

 private:
  static constexpr int kDegree = 24;
  struct Base {
    std::shared_ptr<const Medium> model;
    AsymmetricQuadrature quad;
    std::shared_ptr<const FilonIntegrator> filon;
    std::vector<double> kr, ki;  // Filon coefficients of Re, Im (M1 - phi1)/phi1
    double friction = 0.0;
    bool positive_form = false;
    double surface_band = 0.0;
  };
  std::shared_ptr<const Base> base_;
  double range_ = 0, width_ = 0, table_error_ = 0;
  std::vector<double> coef_;  // (kDegree + 1) per piece, pieces from u = -range
  void tabulate();
};

// Process-wide cache of the asymmetric solver's kernel tables, keyed on the
// medium (Medium::key(): its speed and description) and the friction (the
// table is built to round-off whatever tol, so tol is not part of the key):
// a table whose range is at least min_range, or one of range build_range
// built and cached (at least kGrowth times the longest shorter table of the
// same inputs when one exists: its quadrature is reused). Least recently used
// evicted beyond kDampedKernelCacheCapacity; thread-safe; emptied by
// clear_kernel_cache() (kernel.hpp).
inline constexpr std::size_t kDampedKernelCacheCapacity = 16;
std::shared_ptr<const AsymmetricKernel> cached_damped_kernel(
    const std::shared_ptr<const Medium>& medium, double min_range, double build_range,
    bool* built = nullptr, double friction = 0.0);
// The homogeneous layer of (vstar, kw, nu, damping, kp) (make_medium).
std::shared_ptr<const AsymmetricKernel> cached_damped_kernel(double vstar, double kw, double nu,
                                                             double damping, double min_range,
                                                             double build_range,
                                                             bool* built = nullptr, double kp = 0.0,
                                                             double friction = 0.0);
KernelCacheInfo asymmetric_kernel_cache_info();

// Dimensionless inputs (h = 1, mu = 1).
struct AsymmetricParams {
  double vstar = 0;     // 0 <= vstar < V*_R (supercritical allowed)
  double kw = 1;        // k_w h / mu in [1e-12, inf]
  double radius = 100;  // R / h > 0
  double load = 0.002;  // P / (mu h) > 0
  double nu = 0.2;      // [0, 0.5)
  double damping = 0;   // c_w c_T / mu > 0 (finite); >= 0 when friction > 0
  double friction =
      0;  // Coulomb coefficient f >= 0 (finite): tau_xy = f p, in the direction of motion
  double tol = 1e-8;  // relative tolerance on the contact ends and the pressure, [1e-14, 1e-2]
  bool allow_unphysical = false;
  int n = 0;      // fixed collocation size (even, 2..1024); 0: refine
  double kp = 0;  // k_p / (mu h) in [0, kMaxKp]: Pasternak shear layer (0: Winkler)
  // The medium (medium.hpp), as ContactParams': null, the homogeneous layer
  // of (kw, nu, kp, damping); otherwise this stack and base (kw, nu, kp and
  // damping are then ignored: solve_asymmetric reads them from it).
  std::shared_ptr<const MediumSpec> medium;
  // The punch's shape, as ContactParams' (profile.hpp, docs/theory.md
  // section 13): a cylinder of `radius` (the default); a rounded flat
  // (half_width, corners of `radius`); a convex table (table_x, table_y),
  // symmetric or not (an asymmetric table solves here with damping = 0 and
  // friction = 0 too). `radius` is unused by a table.
  ProfileKind profile = ProfileKind::cylinder;
  double half_width = 0;
  std::vector<double> table_x, table_y;
  PunchProfile punch() const { return PunchProfile(profile, radius, half_width, table_x, table_y); }
};

// The medium of p: *p.medium, or the homogeneous layer of (kw, nu, kp, damping).
MediumSpec medium_of(const AsymmetricParams& p);
// p with kw, nu, kp and damping read from p.medium when it is set (nu: the
// top sublayer's; kw = inf, kp = 0 under a half-space), so that messages
// and width guesses see the medium's own values.
AsymmetricParams with_medium_scalars(const AsymmetricParams& p);
// The critical vstar of p's medium (critical_vstar(kw, nu, kp) for the
// homogeneous layer; critical_speed(spec) otherwise).
double critical_vstar_of(const AsymmetricParams& p);
// The Cauchy term's coefficient of p's medium: the top material's half-plane
// phi1 at vstar (p's scalars: with_medium_scalars), a viscoelastic top's
// unrelaxed one (unrelaxed_phi1; = Medium::phi1()).
double cauchy_phi1_of(const AsymmetricParams& p);
// Throws SupercriticalSpeedError unless p's speed has a bounded steady
// state: vstar < V*_R (vr), and below V*_cr (vcr) unless the medium
// dissipates at every wavenumber (dashpots; one viscoelastic layer on springs).
void require_steady_speed(const AsymmetricParams& p, double vcr, double vr);

// Throws std::invalid_argument naming the parameter and its valid range (a
// medium: its own checks, and InvalidParameter for what the asymmetric
// solver cannot take on it: a graded top sublayer, a damped base under a
// stack or a half-space).
void validate(const AsymmetricParams& p);
// The medium's own checks (validate(MediumSpec)) and what the asymmetric
// solver cannot take on it yet, as InvalidParameter naming it: a graded top
// sublayer (layers), damped springs under a stack (damping). Shared by
// solve_asymmetric's and solve_zones' checks.
void validate_asymmetric_medium(const MediumSpec& m);

class AsymmetricSolution {
 public:
  const AsymmetricParams& params() const noexcept { return params_; }
  double left() const noexcept { return centre_ - half_; }   // -b/h (trailing end)
  double right() const noexcept { return centre_ + half_; }  // a/h (leading end)
  double centre() const noexcept { return centre_; }
  double half_width() const noexcept { return half_; }
  // Horizontal force on the punch over P, int p x/R dx / P: positive when it
  // opposes the motion (the punch moves towards +x). A flat punch: its
  // edges' forces load phi1 (K_front^2 - K_back^2)/4 without friction (the
  // limit of rounded corners; = dissipation()), 0 with friction (no finite
  // sharp-corner limit; docs/theory.md section 14).
  double drag() const noexcept { return drag_; }
  double critical_vstar() const noexcept { return vcr_; }
  double rayleigh_vstar() const noexcept { return vr_; }
  double phi1() const noexcept { return model_->phi1(); }
  // Coulomb friction f (the shear traction on the layer is f p, towards +x,
  // the direction of motion); the tangential force on the punch over P, f
  // (it opposes the motion, as drag() when positive); the end exponents
  // (back, front): p ~ (x + b)^back (a - x)^front, (0.5, 0.5) without
  // friction; the coupling constant Phi(V*, nu) of the local term f Phi p.
  double friction() const noexcept { return params_.friction; }
  double tangential_force() const noexcept { return params_.friction; }
  EndExponents end_exponents() const noexcept { return exps_; }
  double coupling() const noexcept { return model_->tangential().Phi; }
  // Absolute error estimate of the contact ends (-b, a), in h (a bound of
  // |error| of each end; docs/damped.md section 8).
  double error_estimate() const noexcept { return err_; }
  // Bound on the error of the pressure shape, max over r in (-1, 1) of
  // |p(c + w r) - p_exact(c_exact + w_exact r)|, in P/h (pointwise in x add
  // |dp/dx| error_estimate()). A flat punch (unbounded ends): the bound is on
  // g = p/((P/h) w(r)), so |dp| <= it times w(r).
  double pressure_error_estimate() const noexcept { return perr_; }
  // Bound on the error of the surface sigma_x/(P/h) at points more than
  // 1e-3 (a + b)/2 from the contact ends (sigma_x has a square-root cusp there).
  // Computed on first call (it needs the pressure's transform at the fine
  // nodes: about half a warm solve of a smooth punch), then kept; thread-safe.
  double stress_error_estimate() const;
  // Maximum of p/(P/h) on the contact (+inf for a flat punch, whose
  // pressure is unbounded at its edges).
  double max_pressure() const noexcept { return max_p_; }
  // min over r in (-1, 1) of p/((P/h) sqrt(1 - r^2)) = min g(r), r = (x - c)/w:
  // the safety margin before the contact separates (> 0: both ends smooth).
  double pressure_margin() const noexcept { return margin_; }
  // One line per requested accuracy that was not met (what and by how much);
  // empty when tol was met.
  const std::vector<std::string>& warnings() const noexcept { return warnings_; }
  int iterations() const noexcept { return iterations_; }
  // Kernel tables this solve built (0: all reused from the process-wide cache).
  int kernel_builds() const noexcept { return kernel_builds_; }
  // Seconds spent in each stage (as SymmetricSolution's): the critical-speed
  // lookup, fetching or building the kernel table, the width iteration over
  // the N ladder (without the kernel), and the rest (the scan for other
  // steady states, the estimates, the validity checks). They sum to elapsed().
  using StageSeconds = SymmetricSolution::StageSeconds;
  const StageSeconds& stage_seconds() const noexcept { return stage_seconds_; }
  int collocation_n() const noexcept { return n_; }
  double elapsed() const noexcept { return elapsed_; }
  bool valid() const noexcept { return valid_; }
  const std::string& validity() const noexcept { return validity_; }
  double min_pressure() const noexcept { return min_p_; }
  double min_gap() const noexcept { return min_gap_; }
  // Half-widths (a+b)/2 of other contacts carrying the same load (roots of
  // lambda(w) = lambda on [w/8, 4w], to about 1 %); empty when unique there.
  const std::vector<double>& other_half_widths() const noexcept { return other_widths_; }

  // p(x)/(P/h) (0 outside the contact; x not NaN). The overloads on a vector
  // of points here and below are SymmetricSolution's (one binding for both).
  double pressure(double x) const;
  Eigen::VectorXd pressure(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // Transformed pressure p^(alpha)/(P/h) = int p e^{-i alpha x} dx, any alpha.
  cplx pressure_transform(double alpha) const;
  // Surface slope dv/dx(x, 0) (any x; = x/R inside the contact).
  double surface_slope(double x) const;
  // surface_slope's parts per load phi1: its Cauchy integral (with
  // friction the local term too) and its kernel's part: the smooth
  // remainder's (regular_part) and a viscoelastic top's memory
  // (memory_part, 0 for an elastic one; kernel_part is their sum).
  double cauchy_part(double x) const;
  double kernel_part(double x) const;
  double regular_part(double x) const;
  double memory_part(double x) const;
  // sigma_x(x, 0)/(P/h), any x.
  double surface_stress(double x) const;
  Eigen::VectorXd surface_stress(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // sigma_x(x, y)/(P/h) for -1 <= y <= 0 (y = 0: surface_stress).
  double stress_x(double x, double y) const;
  // (sigma_x, sigma_y, tau_xy)(x, y)/(P/h) for finite x and -1 <= y <= 0.
  Eigen::Vector3d stresses(double x, double y) const;
  // The three on the grid x (finite) by y (-1 <= y <= 0, the surface
  // included), each shaped (len(y), len(x)) (the derived stresses are left
  // empty); throws InvalidParameter naming x or y otherwise. The half-plane
  // part in closed form, the rest by Filon sums: the cost does not depend on
  // y. 0 beyond |x| > kFarField.
  // below: at an interface depth of a layered medium, sigma_x of the
  // material below it (sigma_y and tau are continuous).
  StressField stress_field(const Eigen::Ref<const Eigen::VectorXd>& x,
                           const Eigen::Ref<const Eigen::VectorXd>& y, bool below = false) const;
  // The stresses through the compliance of the material at each depth, on
  // the same grid: (1/m_inf) [sigma + sum_k c_k (e_k * sigma)] along x (e_k
  // the material's causal exponentials) in a viscoelastic sublayer, whose
  // Hooke strains at its relaxed modulus are its strains (a mode's strain is
  // its stress over mu m(alpha), Poisson's ratio constant); the stresses
  // themselves in an elastic one. below: as stress_field's.
  StressField compliance_stress_field(const Eigen::Ref<const Eigen::VectorXd>& x,
                                      const Eigen::Ref<const Eigen::VectorXd>& y,
                                      bool below = false) const;
  // Slope dv/dx(x, -1) and displacement v(x, -1)/h of the bottom face (any x;
  // the displacement needs a finite kw).
  double bottom_slope(double x) const;
  double bottom_displacement(double x) const;
  // Vertical surface displacement v(x, 0)/h (any finite x; negative under the
  // punch; 0 beyond |x| > kFarField as the undamped SymmetricSolution's).
  double surface_displacement(double x) const;
  Eigen::VectorXd surface_displacement(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // Indentation delta/h, the punch's rigid approach: the gap
  // -delta + x^2/(2R) - v(x, 0) vanishes on the contact; taken at its centre,
  // delta = c^2/(2R) - v(c, 0) (= -v(0, 0) for a symmetric contact).
  double indentation() const;
  // Vertical displacement v(x, y)/h on the grid x (finite) by y (-1 <= y <= 0),
  // shaped (len(y), len(x)); throws InvalidParameter naming x or y otherwise.
  Eigen::MatrixXd displacement(const Eigen::Ref<const Eigen::VectorXd>& x,
                               const Eigen::Ref<const Eigen::VectorXd>& y) const;
  // Power dissipated in the dashpots over P V: damping sqrt(vstar)/load *
  // int (dv/dx(x, -1))^2 dx, by Parseval on the layer's bottom response;
  // equals drag() by the energy balance.
  double dissipation() const;

  // A flat punch (profile flat; its contact is the face (-b, b), index +1):
  // the end coefficients K_end = lim sqrt(2 pi) d^(-gamma_end) p(x) over
  // (P/h) h^(-gamma_end) as the distance d to that end goes to 0 (gamma_end =
  // end_exponents(), -1/2 without friction: K = lim sqrt(2 pi d) p, the
  // undamped SymmetricSolution::end_coefficient), and the bound on the error of
  // each. 0 for bounded ends.
  double end_coefficient_back() const noexcept { return end_k_back_; }
  double end_coefficient_front() const noexcept { return end_k_front_; }
  double end_coefficient_error() const noexcept { return end_k_err_; }

  // g's coefficients: Chebyshev U_n without friction, Jacobi P_n^(front, back) with it
  // (a flat punch: Jacobi P_n^(front, back) of its exponents, front + back = -1).
  const Eigen::VectorXd& g_coefficients() const noexcept { return b_; }
  // The punch's shape (AsymmetricParams::punch()).
  const PunchProfile& punch() const noexcept { return *punch_; }
  // A profile whose slope has a kink (a rounded flat) or a table: bound on
  // what the series of g leaves out beyond its (half-plane tail extended)
  // length, in P/h (pointwise on the pressure); 0 for a cylinder.
  double series_truncation() const noexcept { return trunc_; }
  // The medium solved on.
  const Medium& model() const noexcept { return *model_; }

 private:
  friend AsymmetricSolution solve_asymmetric(const AsymmetricParams& p);
  friend AsymmetricSolution solve_asymmetric_flat(const AsymmetricParams& p);
  friend AsymmetricSolution zone_solution(const AsymmetricParams& p,
                                          std::shared_ptr<const AsymmetricKernel> kernel,
                                          double centre, double half, const Eigen::VectorXd& b,
                                          int head);
  AsymmetricParams params_{};
  double end_k_back_ = 0, end_k_front_ = 0, end_k_err_ = 0;
  double centre_ = 0, half_ = 0, drag_ = 0, vcr_ = 0, vr_ = 0, err_ = 0, elapsed_ = 0;
  double perr_ = 0, max_p_ = 0, margin_ = 0, trunc_ = 0;
  std::shared_ptr<const PunchProfile> punch_;
  std::vector<std::string> warnings_;
  int iterations_ = 0, n_ = 0, kernel_builds_ = 0;
  StageSeconds stage_seconds_{};
  bool valid_ = true;
  // A flat face on a viscoelastic top whose shortest memory is below the
  // collocation's node spacing at the edges (said in warnings_): its
  // dissipation is then refused (ConvergenceError).
  bool memory_unresolved_ = false;
  std::string validity_;
  double min_p_ = 0, min_gap_ = 0;
  std::vector<double> other_widths_;
  Eigen::VectorXd b_;
  // A flat face on a viscoelastic top: g's Chebyshev (T) coefficients, the
  // memory's basis (MemoryBasis::T); empty otherwise.
  Eigen::VectorXd t_coef_;
  // InvalidParameter naming profile for an output the flat face on a
  // viscoelastic top does not have yet (`what`); nothing otherwise.
  void refuse_flat_memory(const char* what) const;
  // Friction > 0: the Jacobi series of g and its transform rule (light_'s
  // alpha range).
  EndExponents exps_{};
  std::shared_ptr<const JacobiSeries> jac_;
  std::shared_ptr<const JacobiTransform> jtr_;
  double jtr_omega_ = 0;     // the largest alpha w jtr_ resolves
  JacobiRule atan_rule_;     // Gauss-Jacobi rule of friction_surface_terms' arctan integral
  Eigen::VectorXd atan_wg_;  // its weights times jac_'s g at its nodes
  // A series' weights on atan_rule_ (its weights times the series' g there).
  Eigen::VectorXd atan_weights(const JacobiSeries& ser) const;
  // alpha v^(alpha, -1)/p^ of the loads together: Wb (+ i f Wqb with friction).
  cplx bottom_w(const DampedResponse& r) const;
  // The surface sigma_x integrand's regular part per unit p^ at alpha > 0:
  // M2 - phi2, with friction less i f (Ep Uq - Ep Uq_inf - C0 e^-alpha/alpha).
  cplx surface_stress_integrand(const DampedResponse& r, double alpha) const;
  // The surface sigma_x's parts that are closed forms of p with friction:
  // f Cq (1/pi) int p/(xi - x) - (f C0/pi) int p arctan(x - xi) (theory.md section 14).
  // `wg`: atan_weights(s).
  double friction_surface_terms(double x, const JacobiSeries& s, const Eigen::VectorXd& wg,
                                double c, double w) const;
  std::shared_ptr<const Medium> model_;
  std::shared_ptr<const AsymmetricKernel> kernel_;
  // The homogeneous layer behind model_ (its closed-form modal fields: the
  // depth outputs' fast path), or null: a layered medium, whose depth
  // outputs are refused (layered_refusal names them).
  const DampedLayerModel* layer() const;
  // Gauss-Chebyshev (U) nodes r_i and weights times g(r_i) of surface_slope's
  // kernel integral.
  std::vector<double> slope_r_, slope_wg_;
  // slope_r_ and slope_wg_ for the U-series b_ on m Gauss-Chebyshev nodes.
  void set_u_slope_nodes(int m);
  // Fine Gauss-Kronrod nodes (the quadrature's panels split so that each
  // resolves oscillations of frequency `freq`), with the response and the
  // transformed pressure at each node.
  struct Fine {
    double freq = 0;
    std::vector<double> alpha, weight;
    std::vector<DampedResponse> r;
    std::vector<cplx> phat;
    // Filon rule on the fine panels, and the coefficients of the real and
    // imaginary parts of (M2 - phi2) p^ e^{i alpha c} (the surface sigma_x
    // integrand with the centre's phase taken out: evaluate at x - c).
    std::shared_ptr<const FilonIntegrator> filon;
    std::vector<double> sx_re, sx_im;
    // Re int_0^amax (g_re + i g_im) e^{i alpha x} d alpha from coefficients.
    double fourier(const std::vector<double>& c_re, const std::vector<double>& c_im,
                   double x) const;
    // The Filon coefficients of each column of G (one row per node).
    std::shared_ptr<Eigen::MatrixXd> filon_columns(const Eigen::MatrixXd& G) const;
    // Filon coefficients of Re and Im of g given at the nodes.
    void coefficients(const std::vector<cplx>& g, std::vector<double>& c_re,
                      std::vector<double>& c_im) const;
  };
  // Resolving p^'s own oscillation (freq 2w; the centre's phase is shifted
  // out): Filon integrals at any x (surface sigma_x, the estimates, the
  // dissipation). Built on first use (light()), then shared between copies.
  struct LightCache {
    std::mutex mutex;
    std::shared_ptr<const Fine> fine;
  };
  std::shared_ptr<LightCache> light_cache_ = std::make_shared<LightCache>();
  const Fine& light() const;
  // Installs f as light() unless one is there already (a build that came
  // with more, as the stress estimate's).
  void offer_light(Fine f) const;
  // The stress estimate, computed on first read by `compute` (the solve's
  // inputs to it captured by value), or given (`done`) by the solve.
  struct StressCache {
    std::mutex mutex;
    bool done = false;
    double value = 0.0;
    std::function<double(const AsymmetricSolution&)> compute;
  };
  std::shared_ptr<StressCache> stress_cache_ = std::make_shared<StressCache>();
  // Resolving e^{i alpha x} for |x| <= 3 (a + b) too (the direct sums of the
  // bottom outputs): built on first use, then shared.
  struct FineCache {
    std::mutex mutex;
    std::shared_ptr<const Fine> fine;
  };
  std::shared_ptr<FineCache> fine_cache_ = std::make_shared<FineCache>();
  std::shared_ptr<const Fine> fine_for(double x) const;
  // The surface displacement, prepared on first use (shared between copies):
  // the Filon coefficients (on light_) of the smooth part
  // [M1 - phi1 (1 - e^-alpha)]/alpha p^ e^{i alpha c}, the Gauss-Chebyshev rule
  // of the ln(1 + u^2) part, and the indentation.
  struct Surface {
    std::vector<double> smooth_re, smooth_im, log1p_r, log1p_w;
    double indentation = 0;
    // Under a half-space (Medium::long_wave_m1() = m0 != 0): m0 e^-alpha/alpha
    // is taken out of the Fourier sum and added as its logarithm in x, and
    // every value is measured from the one at x = kDisplacementReference.
    double m0 = 0, reference = 0;
  };
  struct SurfaceCache {
    std::mutex mutex;
    std::shared_ptr<const Surface> surface;
  };
  std::shared_ptr<SurfaceCache> surface_cache_ = std::make_shared<SurfaceCache>();
  std::shared_ptr<const Surface> surface() const;
  // A viscoelastic top's memory part of the surface displacement per load
  // phi1 at x, given U(x) (the half-plane potential, hp).
  double memory_displacement(const Surface& s, double x, double hp) const;
  // A viscoelastic top with inertia: the surface sigma_x's memory,
  // sum_k d_k (e_k * p)(x) (Medium::stress_memory()), added to p in -phi2 p.
  double stress_memory_part(double x) const;
  // A viscoelastic top with inertia: the stress remainder's tail beyond the
  // fine nodes (from `from`) at shallow depths, added to rem (nx, 3 ny:
  // stress_field's columns).
  void inertial_tail(const Eigen::Ref<const Eigen::VectorXd>& x,
                     const Eigen::Ref<const Eigen::VectorXd>& y, double from, Eigen::MatrixXd& rem,
                     bool below = false) const;
  // InvalidParameter naming y for a depth closer to the surface than the
  // tail's reach allows (about 0.002 h).
  void check_inertial_depths(const Eigen::Ref<const Eigen::VectorXd>& y, const char* what) const;
  // Its nodes: Gauss-Kronrod panels on [from, reach] as wide as the fine
  // nodes', and p^ e^{i alpha c} at them (ph).
  AlphaQuadrature tail_panels(double from, double reach, std::vector<cplx>& ph) const;
  // A viscoelastic top with inertia: v(x, y)/(P/(mu h)) at depth y < 0 (one
  // row): the elastic layer's split below the relaxed half-plane, its
  // remainder's tail beyond the fine nodes summed to 36/(nT |y|).
  Eigen::VectorXd inertial_depth_displacement(const Eigen::Ref<const Eigen::VectorXd>& x,
                                              double y) const;
  // A viscoelastic top's v(x, y)/(P/(mu h)) at depth y < 0 (one row).
  // Under a half-space: the substrate's long-wave part at x - c = u, the
  // same at every depth (0 on springs); displacement's sums leave it out.
  double far_field(double u) const;
  Eigen::VectorXd memory_depth_displacement(const Eigen::Ref<const Eigen::VectorXd>& x,
                                            double y) const;
  // The stress field's y-independent node data (on light_), prepared on first
  // use: per node p^ e^{i alpha c} and d (real and imaginary parts): for
  // alpha < kSmallT the top state z(0) (DampedLayerModel::state_coefficients),
  // else the modal amplitudes minus the half-plane mix's (hp1, hp2, 0, 0), so
  // that the remainder state is modal_columns(alpha, y) d; with bounds
  // |p^| kc (|d0| + |d1|), |p^| kc (|d2| + |d3|) (kc the largest entry of the
  // columns' vectors) that let stress_field skip negligible nodes.
  struct FieldNodes {
    Eigen::Matrix4Xd d_re, d_im;
    std::vector<cplx> ph;
    std::vector<double> top_bound, bottom_bound;
    double negligible = 0;  // a node's contribution below this is dropped
    // Any other medium: each node's mode (Medium::mode, built once; its
    // remainder at any depth), instead of d_re, d_im and the bounds.
    std::vector<std::unique_ptr<const ModeProfile>> modes;
  };
  // A viscoelastic top with inertia: the tail panels beyond the fine nodes
  // (inertial_tail) up to `reach`, p^ e^{i alpha c} and the mode at each node.
  struct TailNodes {
    double reach = 0;
    AlphaQuadrature q;
    std::vector<cplx> ph;
    std::vector<std::unique_ptr<const ModeProfile>> modes;
    std::shared_ptr<const FilonIntegrator> filon;
  };
  // A depth and, at an interface, the side whose sigma_x is asked.
  using DepthKey = std::pair<double, bool>;
  struct FieldCache {
    std::mutex mutex;
    std::shared_ptr<const FieldNodes> nodes;
    // The tail of a layer with inertia and its last few depths' coefficients.
    std::shared_ptr<const TailNodes> tail;
    // (Keyed by the depth and the side of an interface: DepthKey.)
    std::vector<std::pair<DepthKey, std::shared_ptr<const Eigen::MatrixXd>>> tail_depths;
    // The Filon coefficients of the remainder at the last few depths
    // (nq x 6: sigma_x, sigma_y, tau real parts, then imaginary parts): they do
    // not depend on x, so a search along one depth (the bottom's peaks, the
    // foundation reaction) computes them once.
    std::vector<std::pair<DepthKey, std::shared_ptr<const Eigen::MatrixXd>>> depths;
  };
  std::shared_ptr<const Eigen::MatrixXd> depth_coefficients(const FieldNodes& nodes, double y,
                                                            bool below = false) const;
  std::shared_ptr<FieldCache> field_cache_ = std::make_shared<FieldCache>();
  // Friction: the stresses on the bottom face y = -1 by the direct Fourier
  // integral (it converges there like e^{-nT alpha}: no half-plane part to
  // split off), the normal load's and the shear traction's together: Filon
  // coefficients of sigma_x (the bar pole C0/alpha taken out), sigma_y and
  // tau on light_, built on first use.
  struct BottomFriction {
    std::vector<double> sx_re, sx_im, sy_re, sy_im, t_re, t_im;
  };
  struct BottomFrictionCache {
    std::mutex mutex;
    std::shared_ptr<const BottomFriction> data;
  };
  std::shared_ptr<BottomFrictionCache> bottom_friction_cache_ =
      std::make_shared<BottomFrictionCache>();
  std::shared_ptr<const BottomFriction> bottom_friction() const;
  // Friction, -1 < y < 0: the shear traction's remainder at depth y (Filon
  // coefficients, columns [sigma_x, sigma_y, tau] real then imaginary parts).
  std::shared_ptr<const Eigen::MatrixXd> friction_depth_coefficients(double y) const;
  // Friction: v(x, y)/h at one depth (the surface included), and
  // int p(xi) arctan(x - xi) d xi/(P/h); the indentation, computed on first use.
  Eigen::VectorXd friction_displacement(const Eigen::Ref<const Eigen::VectorXd>& x, double y) const;
  double arctan_integral(double x) const;
  mutable double friction_indentation_ = std::nan("");
  // -(f C0/pi) int p(xi) arctan(x - xi) d xi: the layer's bar term (the
  // shear-free base carries no horizontal force; theory.md section 14).
  // (`wg`: atan_weights of the series.)
  double bar_term(double x, const Eigen::VectorXd& wg, double c, double w) const;
  std::shared_ptr<const FieldNodes> field_nodes() const;
  double surface_value(const Surface& s, double x) const;  // v(x, 0)/(P/(mu h))
  // With db: dphat[i] = the transform of the U-series db (centre 0) at node i.
  Fine build_fine(double freq, const Eigen::VectorXd* db = nullptr,
                  std::vector<cplx>* dphat = nullptr) const;
};

// Solves the damped contact problem (damping > 0). Throws std::invalid_argument
// (bad input), SupercriticalSpeedError (vstar >= V*_R), UnphysicalContactError
// (unless allow_unphysical) and ConvergenceError.
AsymmetricSolution solve_asymmetric(const AsymmetricParams& p);

// The flat punch (profile flat) on the asymmetric solver (asymmetric_flat.cpp;
// docs/theory.md section 14, "The flat punch on the asymmetric solver"): the
// contact is the face (-b, b), p = (P/h) w(r) g(r) with w = (1 - r)^alpha
// (1 + r)^beta, alpha = gamma_front - 1, beta = gamma_back - 1, by
// Gauss-Jacobi collocation (jacobi_flat_nodes) and equilibrium, over the N
// ladder until the end coefficients meet tol. solve_asymmetric dispatches here.
AsymmetricSolution solve_asymmetric_flat(const AsymmetricParams& p);

// One zone of a several-zone contact (zones.hpp) as a solution of its own:
// the pressure p = (P/h) sqrt(1 - r^2) sum b_n U_n(r), r = (x - centre)/half,
// P = p.load (the zone's share of the load), frictionless and bounded at both
// ends, with the outputs of the layer's response to it (surface slope,
// stress, displacement, fields). The several-zone result sums its zones'
// outputs (superposition); its own checks and estimates replace this one's
// (valid(), the estimates and drag() are not set here). A tail-extended
// series (a rounded flat's zone) gives its collocated `head` (0: all of b):
// the kernel's quadrature nodes and the margin take that head's size.
AsymmetricSolution zone_solution(const AsymmetricParams& p,
                                 std::shared_ptr<const AsymmetricKernel> kernel, double centre,
                                 double half, const Eigen::VectorXd& b, int head = 0);

// Error estimate of the last member of a sequence x_0, x_1, ... computed at
// sizes n_0 < n_1 < ..., from the changes d_k = |x_k - x_{k-1}| (changes[k-1]
// belongs to sizes[k]; exposed for tests). Geometric convergence in N is
// assumed: with q = rho^(n_k - n_{k-1}) from the last two changes the error
// is d q/(1 - q), reported times a safety factor 10, plus `floor` (round-off).
// A change within 4 floor, or two changes in a row that shrink by less than
// 20 % (stagnation), mark the round-off level: the estimate is then the
// larger of the last two changes plus the floor. With a single rate reading
// (two changes) the error is also read as algebraic convergence (x_N = x +
// C N^-p, p from the two changes: algebraic_error) and the larger is used.
struct RefinementEstimate {
  double estimate = 0;
  bool at_floor = false;   // the last change is round-off
  bool stagnated = false;  // the changes stopped shrinking
  // A single rate reading (two changes) from a drop of more than 1e3 in one
  // step: the start of the ladder, not yet its rate (a rounded flat with
  // friction: changes 9.2e-5, 1.05e-8 at N = 12, 16, then an error 1.8e-8 at
  // 16, the extrapolation 1.2e-11). ladder_stop goes on to the next size.
  bool unconfirmed = false;
};
RefinementEstimate refinement_estimate(const std::vector<int>& sizes,
                                       const std::vector<double>& changes, double floor);
// The error of x_{n2} when x_N = x + C N^-p and the changes d1 = |x_{n0} -
// x_{n1}|, d2 = |x_{n1} - x_{n2}| (n0 < n1 < n2) fix p (clamped to [1/2,
// 64]); 0 unless 0 < d2 < d1 (no rate to read).
double algebraic_error(int n0, int n1, int n2, double d1, double d2);

// A fixed collocation size N (the caller's n) on the asymmetric solver: its
// error read from finer sizes, as the symmetric solver's (a coarse N may be
// far from resolved, and the changes from still coarser sizes can shrink
// faster than its error). Sizes up to kFixedFinerMax are checked against
// references at m = max(2N, 8), doubled up to kFixedReferenceMax, until the
// references' own estimate (refinement_estimate over them) is at most a
// tenth of N's distance from the last one, or at round-off. `sample(m)`
// solves at m and returns a FixedSample: N's result's distance from it, its
// change from the previous reference (ignored for the first) and the
// round-off floors at m, for two quantities (v: the ends or a flat punch's
// end coefficients; p: the pressure). The error is that distance plus twice
// the reference's estimate (|v_N - v| <= |v_N - v_ref| + |v_ref - v|);
// infinite when a reference has no solution (ConvergenceError). Larger
// sizes (a rate under way) keep the estimate from N/2 and 3N/4.
inline constexpr int kFixedFinerMax = 32;
inline constexpr int kFixedReferenceMax = 512;
struct FixedSample {
  double d_n_v = 0, d_n_p = 0;      // N's result against this reference
  double d_v = 0, d_p = 0;          // this reference against the previous one
  double floor_v = 0, floor_p = 0;  // round-off at this reference
};
struct FixedError {
  double v = std::numeric_limits<double>::infinity();
  double p = std::numeric_limits<double>::infinity();
  int ref_n = 0;  // the last reference's size (0: none)
};
template <class Sample>
FixedError fixed_size_error(int n, Sample&& sample) {
  FixedError out;
  std::vector<int> sizes;
  std::vector<double> dv, dp;
  try {
    for (int m = std::max(2 * n, 8); m <= kFixedReferenceMax; m *= 2) {
      const FixedSample fs = sample(m);
      if (!std::isfinite(fs.d_n_v) || !std::isfinite(fs.d_n_p)) return FixedError{};
      sizes.push_back(m);
      if (sizes.size() < 2) continue;
      dv.push_back(fs.d_v);
      dp.push_back(fs.d_p);
      const RefinementEstimate rv = refinement_estimate(sizes, dv, fs.floor_v);
      const RefinementEstimate rp = refinement_estimate(sizes, dp, fs.floor_p);
      out.v = fs.d_n_v + 2.0 * rv.estimate;
      // (x1.05: d_n_p is the largest of the difference's values on a scan
      // of angles, which can lie a little below its maximum: measured
      // 0.99992 of the pointwise difference at N = 8.)
      out.p = 1.05 * fs.d_n_p + 2.0 * rp.estimate;
      out.ref_n = m;
      const bool ok_v = rv.at_floor || (dv.size() >= 2 && rv.estimate <= 0.1 * fs.d_n_v);
      const bool ok_p = rp.at_floor || (dp.size() >= 2 && rp.estimate <= 0.1 * fs.d_n_p);
      if (ok_v && ok_p) break;
    }
  } catch (const ConvergenceError&) {
    return FixedError{};
  }
  return out;
}

// The N ladder's verdict on two refined quantities (the contact's ends, or a
// flat punch's end coefficients, and the pressure), from their estimates,
// last changes and scales: converged when both estimates meet tol times
// their scales; stalled when neither can improve further (its change at the
// round-off floor, or stagnated at a level round-off amplification can
// explain, sqrt(eps) of its scale); else go on. An unconfirmed rate (above)
// off the floor goes on.
enum class LadderStop { go_on, converged, stalled };
LadderStop ladder_stop(double tol, const RefinementEstimate& a, double last_a, double scale_a,
                       const RefinementEstimate& b, double last_b, double scale_b);

// max over theta in [0, pi] of |sum_k b_k sin((k + 1) theta)| (= max over r of
// |sqrt(1 - r^2) sum b_k U_k(r)|), sampled at 8 (len(b) + 1) + 64 angles.
double max_abs_sine_series(const Eigen::VectorXd& b);
// The same for a long series (a profile's tail-extended one): the first
// `head` terms locate the three largest values, the whole series is sampled
// finely around them (the tail only shifts them a little) and the largest
// sample refined by golden section.
double max_abs_sine_series_long(const Eigen::VectorXd& b, int head);
// A bound on max |sqrt(1 - r^2) sum b_k U_k(r)| of a long series: the
// sampled maximum of its first `head` terms (max_abs_sine_series) plus
// sum |b_k| beyond them (|sqrt(1 - r^2) U_k| <= 1).
double head_sine_bound(const Eigen::VectorXd& b, int head);
// The same for a Jacobi series' density w g.
double max_abs_density_long(const JacobiSeries& js, int head);

// The regular kernel of the damped equation,
//   K(u) = (1/phi1) int_0^inf [Re(M1 - phi1) sin(alpha u) + Im(M1 - phi1) cos(alpha u)] d alpha,
// (= k1(u) of kernel.hpp when damping -> 0), by Filon quadrature; exposed for tests.
double asymmetric_kernel(const FilonIntegrator& f, const std::vector<double>& kr,
                         const std::vector<double>& ki, double u);

}  // namespace movingpunch

// Stresses and displacements of a solved contact anywhere in the layer.
//
// Each field quantity is (2/pi) int_0^inf F(alpha, y) ptilde(alpha) {cos|sin}(alpha x)
// d alpha, with F the response of the layer to unit transformed pressure and
// ptilde the exact transform of the contact pressure. F is split into
//  * its half-plane part (the same top load on a half-plane, modes e^{n alpha y}),
//    integrated in closed form: the Cauchy integral of the Chebyshev series of p,
//    (1/pi) int sqrt(1-t^2) U_n(t)/(z - t) dt = w(z)^{n+1}, w = z - sqrt(z^2 - 1),
//    at z = (x - i n y)/a; exact at and near the surface, where the transforms
//    decay only algebraically;
//  * the layer remainder, which decays like e^{-n alpha (2 + y)}, integrated on
//    an adaptive alpha grid with the exact (Bessel) transform of p, by a Filon
//    rule (exact Fourier integrals of the panel interpolants): the cost and the
//    accuracy do not depend on x, and x is processed in blocks (bounded memory).
#pragma once

#include <memory>

#include <Eigen/Dense>

#include "movingpunch/collocation.hpp"
#include "movingpunch/kernel.hpp"

namespace movingpunch {

// Beyond this distance from the punch every field is zero to far below double
// precision of its scale (the layer's far field decays), and the phases of the
// Fourier integrals would no longer be representable: the fields return 0 there.
constexpr double kFarField = 1e9;

struct StressField {
  // Shaped (len(y), len(x)), per P/h; tension positive.
  Eigen::MatrixXd sigma_x, sigma_y, tau_xy;
};

class FieldEvaluator {
 public:
  // a: contact half-width; b: Chebyshev coefficients of p/(P/h) (even) of
  // the series `kind` (U: bounded ends; T: a flat punch's square-root
  // singular ends, collocation.hpp); tol: quadrature tolerance.
  FieldEvaluator(std::shared_ptr<const Medium> medium, double a, const Eigen::VectorXd& b,
                 double tol, SeriesKind kind = SeriesKind::U);

  // Stresses on the grid x (any finite x) by y (-1 <= y <= 0); at an
  // interface between sublayers, sigma_x of the material above it (below:
  // of the material below it; at y = -1 the half-space's, if any).
  StressField stresses(const Eigen::Ref<const Eigen::VectorXd>& x,
                       const Eigen::Ref<const Eigen::VectorXd>& y, bool below = false) const;
  // Vertical displacement v(x, y) mu / (P) (multiply by P/(mu h) for v/h),
  // shaped (len(y), len(x)); under a half-space base relative to the surface
  // at |x| = kDisplacementReference (medium.hpp).
  Eigen::MatrixXd displacement(const Eigen::Ref<const Eigen::VectorXd>& x,
                               const Eigen::Ref<const Eigen::VectorXd>& y) const;

 private:
  std::shared_ptr<const Medium> model_;  // outlives the mode profiles
  double a_;
  Eigen::VectorXd b_;
  Eigen::VectorXd tails_;  // detail::potential_tails of b_ (kind U)
  SeriesKind kind_ = SeriesKind::U;
  AlphaQuadrature quad_;
  std::unique_ptr<FilonIntegrator> filon_;
  std::vector<double> ptilde_;  // (2/pi) ptilde(alpha_q) at the nodes
  std::vector<std::unique_ptr<const ModeProfile>> modes_;
  // A half-space base: v at the reference point (medium.hpp); 0 on springs.
  double reference_ = 0.0;

  // Remainder integrals: for each column of `values` (one function of alpha
  // per column, at the nodes) the cosine or sine transform at every x.
  Eigen::MatrixXd transform(const Eigen::MatrixXd& values, bool sine,
                            const Eigen::Ref<const Eigen::VectorXd>& x) const;
};

}  // namespace movingpunch

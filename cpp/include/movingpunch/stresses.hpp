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
//  * the layer remainder, which decays like e^{-n alpha (2 + y)}, integrated by
//    adaptive quadrature in alpha with the exact (Bessel) transform of p.
#pragma once

#include <memory>

#include <Eigen/Dense>

#include "movingpunch/kernel.hpp"

namespace movingpunch {

struct StressField {
  // Shaped (len(y), len(x)), per P/h; tension positive.
  Eigen::MatrixXd sigma_x, sigma_y, tau_xy;
};

class FieldEvaluator {
 public:
  // a: contact half-width; b: Chebyshev-U coefficients of p/(P/h) (even);
  // tol: quadrature tolerance; x_extent: the evaluator is accurate for |x| <= x_extent.
  FieldEvaluator(const LayerModel& model, double a, const Eigen::VectorXd& b, double tol,
                 double x_extent);

  double x_extent() const noexcept { return x_extent_; }

  // Stresses on the grid x (any, |x| <= x_extent) by y (-1 <= y <= 0).
  StressField stresses(const Eigen::Ref<const Eigen::VectorXd>& x,
                       const Eigen::Ref<const Eigen::VectorXd>& y) const;
  // Vertical displacement v(x, y) mu / (P) (multiply by P/(mu h) for v/h),
  // shaped (len(y), len(x)).
  Eigen::MatrixXd displacement(const Eigen::Ref<const Eigen::VectorXd>& x,
                               const Eigen::Ref<const Eigen::VectorXd>& y) const;

 private:
  std::shared_ptr<const LayerModel> model_;  // stable address for the mode fields
  double a_;
  Eigen::VectorXd b_;
  double x_extent_;
  AlphaQuadrature quad_;
  std::vector<double> ptilde_w_;  // (2/pi) w_q ptilde(alpha_q)
  std::vector<ModeField> modes_;
};

}  // namespace movingpunch

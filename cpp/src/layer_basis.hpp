// The layer's regularised exponential basis and its small-t transfer matrix,
// shared by the undamped (layer_response.cpp) and damped (asymmetric.cpp) layer
// responses: the basis is real for both, only the bottom condition differs.
// Internal header.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "movingpunch/layer_response.hpp"

namespace movingpunch::detail {

// The shear mode's state vector for decay rate m (the basis' first column
// at its own face).
Eigen::Vector4d shear_vector(double m);
// Columns (top shear mode, top divided difference, bottom shear mode, bottom
// divided difference) at depth y, -1 <= y <= 0.
// Real or complex constants (layer_response.hpp; instantiated for both).
template <class T>
Eigen::Matrix<T, 4, 4> modal_columns(const BasicWaveConstants<T>& c, double t, double y);
// exp(t y A) by its Taylor series (|t y| < 0.5).
template <class T>
Eigen::Matrix<T, 4, 4> transfer_matrix(const BasicWaveConstants<T>& c, double t, double y);

// Edges of the first quadrature panels on [0, w] for a base of stiffness
// kw + kp t^2: a Pasternak layer puts the long-wave feature of the response
// at t* = sqrt(kw/kp) (M1/alpha ~ 1/(kw + kp t^2), of height 1/kw: the
// membrane's sinking, P/(2 sqrt(kw kp)) at the load), which can be far
// narrower than the panels while M1 itself barely shows it (its bump is
// 1/(2 sqrt(kw kp)) high), so the adaptive refinement on M1 would not find
// it. Below w the panels are [0, t*/4], then doubling up to w: each is a
// fraction of its distance to the poles +-i t*. {0, w} for springs alone
// (kp = 0) or a rigid base, and when t*/4 >= w/2.
inline std::vector<double> foundation_panel_edges(double kw, double kp, double w) {
  std::vector<double> edges{0.0};
  if (kp > 0.0 && std::isfinite(kw)) {
    for (double e = 0.25 * std::sqrt(kw / kp); e < 0.5 * w; e *= 2.0) edges.push_back(e);
  }
  edges.push_back(w);
  return edges;
}

}  // namespace movingpunch::detail

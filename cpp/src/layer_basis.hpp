// The layer's regularised exponential basis and its small-t transfer matrix,
// shared by the undamped (layer_response.cpp) and damped (damped.cpp) layer
// responses: the basis is real for both, only the bottom condition differs.
// Internal header.
#pragma once

#include <Eigen/Dense>

#include "movingpunch/layer_response.hpp"

namespace movingpunch::detail {

// The shear mode's state vector for decay rate m (the basis' first column
// at its own face).
Eigen::Vector4d shear_vector(double m);
// Columns (top shear mode, top divided difference, bottom shear mode, bottom
// divided difference) at depth y, -1 <= y <= 0.
Eigen::Matrix4d modal_columns(const WaveConstants& c, double t, double y);
// exp(t y A) by its Taylor series (|t y| < 0.5).
Eigen::Matrix4d transfer_matrix(const WaveConstants& c, double t, double y);

}  // namespace movingpunch::detail

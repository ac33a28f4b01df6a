// Shared fixtures of the C++ tests.
#pragma once

#include <initializer_list>

#include <Eigen/Dense>

#include "movingpunch/asymmetric.hpp"
#include "movingpunch/contact.hpp"

namespace movingpunch::testing {

// The paper's case (nu = 0.2, R/h = 100, P/(mu h) = 0.002) at a speed and stiffness.
inline ContactParams paper(double vstar, double kw) {
  ContactParams p;
  p.vstar = vstar;
  p.kw = kw;
  p.radius = 100.0;
  p.load = 0.002;
  p.nu = 0.2;
  return p;
}

// The same on the asymmetric solver: damping and Coulomb friction f.
inline AsymmetricParams paper_asymmetric(double vstar, double kw, double damping, double f = 0.0) {
  AsymmetricParams p;
  p.vstar = vstar;
  p.kw = kw;
  p.radius = 100.0;
  p.load = 0.002;
  p.nu = 0.2;
  p.damping = damping;
  p.friction = f;
  return p;
}

inline Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd x(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double d : v) x(i++) = d;
  return x;
}

}  // namespace movingpunch::testing

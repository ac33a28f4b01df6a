// Layered media: a stack of elastic sublayers (homogeneous or exponentially
// graded) on springs (Winkler/Pasternak, rigid) or on an elastic half-space
// (bonded or in frictionless contact). Internal header; docs/media.md is the
// derivation and the choice of the propagation.
//
// Propagation: the two-dimensional space of solutions that satisfy the base
// conditions is carried from the base up to the surface as an orthonormal
// 4 x 2 basis of the state z = [U, W, tau/alpha, sigma_y/alpha] (stresses
// over the top sublayer's mu; continuous across bonded interfaces):
//  * a homogeneous sublayer with t d >= 0.5 maps it with its regularised
//    exponential modes (layer_basis.hpp: each mode normalised at the face it
//    decays from, exact at vstar = 0), never overflowing;
//  * a homogeneous sublayer with t d < 0.5 maps it with exp(t d A) (Taylor);
//  * a graded sublayer maps it with slices exp(h (t d A - gamma d diag(0,0,1,1)))
//    (Taylor, ||.|| <= 0.5 per slice) in the variables whose stresses are
//    divided by the local modulus (constant coefficients);
// after each step the basis is re-orthonormalised by column operations
// (Gram-Schmidt), which keep every row's relative accuracy (the tau row is
// O(t) as t -> 0). Where the part of the medium below a depth is below
// e^-50 of the surface state (the basis' attraction over a sublayer,
// (Re lambda_2 - Re lambda_3) of its generator times its depth, exceeds 100),
// the deeper structure is not evaluated: the propagation starts there from
// the sublayer's own downward-decaying modes.
#pragma once

#include <memory>
#include <vector>

#include "movingpunch/dispersion.hpp"
#include "movingpunch/medium.hpp"

namespace movingpunch {

// The medium of `spec` at speed vstar, for elastic sublayers on springs
// (damping 0) or on a half-space. Throws InvalidParameter for an invalid
// spec or vstar outside [0, stack_max_vstar(spec)), std::invalid_argument
// for a damped base.
std::shared_ptr<const Medium> make_stack_medium(const MediumSpec& spec, double vstar);

// The speed below which the medium is built: the least of every sublayer's
// and the substrate's shear-wave vstar (mu_i / rho_i) and the top's Rayleigh
// vstar.
double stack_max_vstar(const MediumSpec& spec);

// The lowest vstar of a free steady wave over all t, including the infima
// reached only as t -> inf (the top's Rayleigh speed; the bottom sublayer's
// Rayleigh speed over Winkler springs, kp = 0; the shear speeds: t = inf) or
// t -> 0 (the substrate's Rayleigh speed: t = 0). Cached per spec;
// thread-safe.
CriticalSpeed stack_critical_speed(const MediumSpec& spec);

// lim_{t -> 0} M1 on a half-space base (bonded or smooth): the substrate's
// own half-plane factor, phi1(vstar rho2 / mu2, nu2) / mu2 (the thin stack
// passes the pressure through; docs/media.md). NaN for a springs base.
double stack_small_t_m1(const MediumSpec& spec, double vstar);

// A graded TOP sublayer: M1(t) = phi1 + c1 (gamma/t) + c2 (gamma/t)^2 +
// O(t^-3) as t -> inf. With eps = gamma/t the graded half-space's generator
// is t (A - eps diag(0,0,1,1)); its surface response F(eps) comes from the
// invariant subspace of the two eigenvalues with positive real part
// (spectral projector by the Newton iteration for the matrix sign
// function: robust where the eigenvalues merge, vstar = 0), and
// c1 = F'(0), c2 = F''(0)/2 by Richardson-extrapolated central differences
// (accurate to ~1e-9). Depends on the top material's (vstar, nu) only.
struct GradedAsymptotics {
  double c1 = 0;
  double c2 = 0;
};
GradedAsymptotics graded_top_asymptotics(double vstar, double nu);

// The whole series F(eps) = sum_k c_k eps^k (c_0 = phi1), k <= kmax, of the
// graded half-space's M1 (M1(t) = F(gamma/t) + O(e^(-2 nT d t))), from its
// values at complex eps: Cauchy's integral by the trapezoidal rule on the
// circle |eps| = radius (64 points; nT/2, halved until c_0 = phi1 and the
// circle 0.8 radius agrees: `agreement`, the largest difference of c_k r2^k,
// relative to max(1, |phi1|)). `next` = |c_{kmax+1}|. Independent of
// graded_top_asymptotics' real differences (tests compare the two).
struct GradedSeries {
  std::vector<double> c;
  double next = 0;
  double radius = 0;
  double agreement = 0;
};
GradedSeries graded_top_series(double vstar, double nu, int kmax);

// The kernel asymptotics of spec's top sublayer at vstar (medium.hpp): empty
// for a homogeneous top; for a graded one a_k = c_k/phi1 (k <= 10) from
// graded_top_series, next = 2 |c_11|/phi1, the series' radius, margin |gamma| d.
KernelAsymptotics graded_kernel_asymptotics(const MediumSpec& spec, double vstar);

}  // namespace movingpunch

// Several contact zones: one punch whose contact has separated, or a train
// of rigid punches moving together (docs/theory.md section 15).
//
// The contact set is a union of disjoint intervals (zones), each under one
// punch k (its profile f_k placed at x = at_k, its load P_k). On every zone
//   v'(x) = (phi1/pi) int p(t) [1/(x - t) + K(x - t)] dt = f_k'(x - at_k),
// the integral over all zones (the kernel couples them), p bounded at every
// end (one consistency condition per zone), the zones of one punch carry its
// load and share its rigid indentation: between consecutive zones j, j + 1 of
// one punch, int_{r_j}^{l_{j+1}} v' = f_k(l_{j+1}) - f_k(r_j). That is 2 Nz
// conditions for the 2 Nz ends, solved by Newton's method (finite-difference
// Jacobian, backtracking) from the given zones. Per zone p = sqrt(1 - r^2)
// G(r), Gauss-Chebyshev (U) collocation; a zone's Cauchy integral at another
// zone's points in closed form, so zones may nearly touch. Which zones (the
// contact set) is decided by the caller (movingpunch.zones: splits where p <
// 0, merges where the gap closes); this solves one given topology and
// reports the complementarity checks.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "movingpunch/asymmetric.hpp"
#include "movingpunch/profile.hpp"

namespace movingpunch {

struct ZonePunch {
  ProfileKind profile = ProfileKind::cylinder;
  double radius = 100;  // cylinder's R/h, a rounded flat's corners
  double half_width = 0;
  std::vector<double> table_x, table_y;
  double load = 0.002;  // P_k/(mu h) > 0
  double at = 0;        // x/h of the punch's axis
  PunchProfile punch() const { return PunchProfile(profile, radius, half_width, table_x, table_y); }
};

struct ZoneSpan {
  int punch = 0;  // index into ZonesParams::punches
  double left = 0, right = 0;
};

struct ZonesParams {
  // The layer and the numerics: vstar, kw, nu, damping, kp, tol, n (0: the
  // ladder 16, 24, 32, ...; else that size alone); friction must be 0; the
  // load and the profile fields are unused (each punch has its own).
  AsymmetricParams layer;
  std::vector<ZonePunch> punches;
  std::vector<ZoneSpan> zones;  // the start: disjoint, every punch at least one zone
  // The ladder's first size (layer.n = 0): 8 from a close start (a train
  // from its punches' own contacts: movingpunch.zones), 24 from a rough one
  // (a split contact: Newton's method from far away is safer on the finer
  // system).
  int first_n = 24;
};

struct ZoneResult {
  int punch = 0;
  // The group of punches it was solved with (solve_zones solves punches
  // too far apart to interact, to the tolerance, as separate groups).
  int group = 0;
  double left = 0, right = 0;
  double load = 0;  // int p over the zone, P_zone/(mu h)
  // p = (P_zone/h) sqrt(1 - r^2) sum b_n U_n(r), r = (x - centre)/half.
  // A rounded flat's zone: the collocated `head` terms and the half-plane's
  // tail beyond them (its slope's kinks), 4096 terms in all.
  Eigen::VectorXd b;
  int head = 0;             // the collocated terms (the zone's N)
  double min_pressure = 0;  // min p/(|P_zone|/h) on the zone
  double margin = 0;        // min over the open zone of p/((|P_zone|/h) sqrt(1 - r^2))
  double margin_x = 0;      // where
  // The zone as a solution of its own (load = the zone's): its pressure and
  // the layer's response to it; the whole response is the sum over zones.
  // Built on each call (its Fourier nodes cost about a millisecond).
  // Relative to its punch's axis `origin` (= that punch's at): evaluate it
  // at x - origin (so that a train far from x = 0 keeps its digits).
  AsymmetricSolution solution() const;
  double origin = 0;                               // x/h of its punch's axis
  double offset = 0;                               // its centre relative to origin
  double half = 0;                                 // its half-width
  AsymmetricParams params;                         // the layer, load = the zone's
  std::shared_ptr<const AsymmetricKernel> kernel;  // the solve's kernel table
};

struct ZonesSolution {
  std::vector<ZoneResult> zones;  // sorted by left end
  std::vector<double> drag;       // per punch: int p f_k' dx / P_k
  // Per punch: where its indentation is taken (its most loaded zone's
  // centre) and f_k there; delta_k = f_k(x) - v(x, 0) (the caller sums the
  // zones' surface displacements, on first use).
  std::vector<double> indentation_x, indentation_height;
  double error_estimate = 0;           // of the zone ends, in h
  double pressure_error_estimate = 0;  // of p/(mu) at fixed relative positions
  // Bound on the error of the surface sigma_x/(P/h), P the total load, more
  // than 1e-3 of a zone's half-width from its ends (from the change of the
  // zones' series between the last two sizes and the ends' error).
  double stress_error_estimate = 0;
  double max_pressure = 0;  // max p/(P/h), P the total load
  double drag_total = 0;    // int p f' dx over all punches / P
  double residual = 0;      // max |F| of the end conditions at the solution
  int collocation_n = 0, iterations = 0, kernel_builds = 0;
  // Complementarity: the smallest gap beside the zones (each punch's own gap
  // within 2 times its contact's hull width of it and between its zones),
  // where, and between which zones (-1: outside every pair of one punch's
  // consecutive zones).
  double min_gap = 0, min_gap_x = 0, gap_scale = 0;
  int min_gap_after_zone = -1;
  std::vector<std::string> warnings;
  double elapsed = 0;
  double critical_vstar = 0, rayleigh_vstar = 0, phi1 = 0;
};

// Power dissipated in the dashpots over P V (P the total load): damping
// sqrt(vstar)/P int (dv/dx(x, -1))^2 dx by Parseval, (P/pi) int_0^inf |Wb
// sum_j (P_j/P) p_j^|^2 d alpha on the kernel's quadrature split to resolve
// the train's length; 0 without damping. By the energy balance it equals the
// punches' drag (the independent check of the solve).
double zones_dissipation(const ZonesSolution& s);

// Throws std::invalid_argument (bad input, overlapping or unordered zones),
// SupercriticalSpeedError and ConvergenceError (Newton's method failed: a
// zone closed or the ends left the supported range).
ZonesSolution solve_zones(const ZonesParams& p);

}  // namespace movingpunch

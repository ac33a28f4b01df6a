// The moving-punch contact problem: contact half-width, pressure, indentation.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "movingpunch/collocation.hpp"
#include "movingpunch/kernel.hpp"
#include "movingpunch/medium.hpp"
#include "movingpunch/profile.hpp"
#include "movingpunch/stresses.hpp"

namespace movingpunch {

// Dimensionless inputs (h = 1, mu = 1).
struct ContactParams {
  double vstar = 0;               // rho V^2 / mu, 0 <= vstar < V*_cr
  double kw = 1;                  // k_w h / mu in [1e-12, inf]
  double radius = 100;            // R / h > 0
  double load = 0.002;            // P / (mu h) > 0
  double nu = 0.2;                // Poisson's ratio in [0, 0.5)
  double tol = 1e-8;              // relative tolerance on a/h, in [1e-14, 1e-2]
  bool allow_unphysical = false;  // if true, return invalid solutions flagged
  int n = 0;  // fixed collocation size (even, 2..4096); 0: refine N until a/h converges
  // The punch's shape (profile.hpp, docs/theory.md section 13): a cylinder of
  // `radius`; a flat face of half-width `half_width` (b/h); a rounded flat
  // (half_width, corners of `radius`); a symmetric convex table (table_x,
  // table_y). `radius` is unused by the flat punch and the table.
  ProfileKind profile = ProfileKind::cylinder;
  double half_width = 0;                 // b/h (flat, rounded_flat)
  std::vector<double> table_x, table_y;  // the table's x/h and heights y/h (table)
  double kp = 0;  // k_p / (mu h) in [0, kMaxKp]: Pasternak shear layer (0: Winkler)
  // The medium (medium.hpp): null, the homogeneous layer of (kw, nu, kp);
  // otherwise this stack and base (kw, nu and kp are then ignored).
  std::shared_ptr<const MediumSpec> medium;
};

// The medium of p: *p.medium, or the homogeneous layer of (kw, nu, kp).
MediumSpec medium_of(const ContactParams& p);

// Throws std::invalid_argument naming the parameter and its valid range.
void validate(const ContactParams& p);

class SymmetricSolution {
 public:
  const ContactParams& params() const noexcept { return params_; }
  double a() const noexcept { return a_; }                // a/h
  double p0() const noexcept { return p0_; }              // p(0)/(P/h)
  double indentation() const noexcept { return delta_; }  // delta/h
  double critical_vstar() const noexcept { return vcr_; }
  double rayleigh_vstar() const noexcept { return vr_; }
  double phi1() const noexcept { return phi1_; }
  double error_estimate() const noexcept { return err_; }  // absolute, of a/h
  // The parts of error_estimate (absolute, of a/h; they add up to it):
  // collocation (the N truncation, extrapolated from the last sizes), root (the
  // residual of the width iteration), kernel (the k1 table's quadrature and
  // interpolation errors carried through the collocation solve to first
  // order) and roundoff (of the solve, and of phi1 near V*_R).
  struct ErrorBudget {
    double collocation = 0, root = 0, kernel = 0, roundoff = 0;
  };
  const ErrorBudget& error_budget() const noexcept { return budget_; }
  // One line per requested accuracy that was not met (empty: none); e.g. the
  // error estimate of a/h above tol * a.
  const std::vector<std::string>& warnings() const noexcept { return warnings_; }
  double elapsed() const noexcept { return elapsed_; }     // seconds
  int iterations() const noexcept { return iterations_; }  // load evaluations, all N
  int collocation_n() const noexcept { return n_; }
  // Seconds spent in each stage: the critical-speed check, fetching or
  // building the k1 kernel, the width iteration (without the kernel), and the
  // indentation and validity checks. They sum to elapsed() up to timer reads.
  struct StageSeconds {
    double critical_speed = 0, kernel = 0, width = 0, checks = 0;
  };
  const StageSeconds& stage_seconds() const noexcept { return stage_seconds_; }
  // Kernel tables this solve built (0: all reused from the process-wide cache).
  int kernel_builds() const noexcept { return kernel_builds_; }
  bool valid() const noexcept { return valid_; }
  const std::string& validity() const noexcept { return validity_; }
  double min_pressure() const noexcept { return min_p_; }  // min p/(P/h) on [-a, a]
  // min over -1 < r < 1 of g(r) = p(a r)/((P/h) sqrt(1 - r^2)): how far the
  // contact is from separating (0 or below: p < 0 somewhere, or at an edge).
  double pressure_margin() const noexcept { return p_margin_; }
  double min_gap() const noexcept { return min_gap_; }  // min gap/h on a < |x| <= 3a

  // p(x)/(P/h) at x/h (0 outside the contact).
  double pressure(double x) const;
  Eigen::VectorXd pressure(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // Vertical surface displacement v(x, 0)/h (negative under the punch).
  double surface_displacement(double x) const;
  Eigen::VectorXd surface_displacement(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // Stresses over P/h on the grid x by y (-1 <= y <= 0), shaped (len(y), len(x));
  // below: at an interface between sublayers (and at y = -1 over a half-space),
  // sigma_x of the material below it (the others are continuous).
  StressField stress_field(const Eigen::Ref<const Eigen::VectorXd>& x,
                           const Eigen::Ref<const Eigen::VectorXd>& y, bool below = false) const;
  // sigma_x(x, 0)/(P/h) and sigma_x(0, y)/(P/h).
  Eigen::VectorXd surface_stress(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  Eigen::VectorXd depth_stress(const Eigen::Ref<const Eigen::VectorXd>& y) const;
  // Vertical displacement v(x, y)/h on the grid x by y, shaped (len(y), len(x)).
  Eigen::MatrixXd displacement(const Eigen::Ref<const Eigen::VectorXd>& x,
                               const Eigen::Ref<const Eigen::VectorXd>& y) const;
  // Pressure of the base on the layer, -sigma_y(x, -h)/(P/h).
  Eigen::VectorXd foundation_reaction(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // The field evaluator (built on first use, then shared).
  std::shared_ptr<const FieldEvaluator> field() const;

  // Chebyshev-U coefficients of g(r) = p(a r) / ((P/h) sqrt(1 - r^2)); for a
  // flat punch (series_kind() T) Chebyshev-T coefficients of
  // g(r) = p(a r) sqrt(1 - r^2) / (P/h).
  const Eigen::VectorXd& g_coefficients() const noexcept { return b_; }
  // U (bounded ends) or T (the flat punch's square-root singular ends).
  SeriesKind series_kind() const noexcept { return kind_; }
  // The flat punch's end coefficient K = lim_{x -> a} sqrt(2 pi (a - x)) p(x)
  // over (P/h) sqrt(h) (= g(1) sqrt(pi a); 1/sqrt(pi a) on a half-plane); the
  // same at both ends (symmetric). 0 for bounded ends.
  double end_coefficient() const noexcept { return end_k_; }
  // Estimated absolute error of end_coefficient() (0 for bounded ends).
  double end_coefficient_error() const noexcept { return end_k_err_; }
  // A bound on the pressure's error over P/h from the Chebyshev series'
  // truncation (the rounded flat's and a table's slopes have kinks: their g
  // converges algebraically; 0 for the cylinder and the flat punch, whose
  // series converge geometrically and whose estimates cover it).
  double series_truncation() const noexcept { return trunc_; }
  // The punch's shape, one line (PunchProfile::describe).
  const std::string& profile_description() const noexcept { return profile_text_; }
  const KernelK1& kernel() const noexcept { return *kernel_; }

 private:
  friend SymmetricSolution solve_contact(const ContactParams& p);
  // The indentation and validity checks of a solved contact (contact.cpp).
  friend void finish_checks(SymmetricSolution& sol, const ContactParams& p,
                            const PunchProfile& profile);
  ContactParams params_{};
  double a_ = 0, p0_ = 0, delta_ = 0, vcr_ = 0, vr_ = 0, phi1_ = 0, err_ = 0, elapsed_ = 0;
  int iterations_ = 0, n_ = 0, kernel_builds_ = 0;
  StageSeconds stage_seconds_{};
  bool valid_ = true;
  std::string validity_;
  double min_p_ = 0, min_gap_ = 0, p_margin_ = 0;
  ErrorBudget budget_{};
  std::vector<std::string> warnings_;
  Eigen::VectorXd b_;  // U_n (or T_n) coefficients of g, normalised by P/h
  SeriesKind kind_ = SeriesKind::U;
  double end_k_ = 0, end_k_err_ = 0, trunc_ = 0;
  // Estimated error of g (the series above) pointwise, over P/h: at a fixed
  // collocation size N from the comparison with finer sizes; 0 where the N
  // ladder converged (g's error is then below the validity check's floor).
  double g_err_ = 0;
  std::string profile_text_;
  std::shared_ptr<const KernelK1> kernel_;
  struct FieldCache;
  std::shared_ptr<FieldCache> field_cache_;
  // lim M1(t -> 0) of the medium (0 on springs; medium.hpp).
  double m0_ = 0.0;
  // The displacement by the kernel's table (KernelK1::greens_tabulated):
  // (1/pi) int p(xi)/(P/h) G(x - xi) d xi = table_const_ - (phi1/pi) a
  // sum_j table_w_[j] K1(x - a table_r_[j]) + the log part, exact
  // Gauss-Chebyshev for the polynomial K1 (g cut at K1's degree: the rest is
  // orthogonal to it), for |x| <= table_reach_ (the table's range less a;
  // negative: not tabulated).
  std::vector<double> table_r_, table_w_;
  double table_const_ = 0.0, table_reach_ = -1.0;
  // The convolution sum_j table_w_[j] K1(x - a table_r_[j]) as a Chebyshev
  // series in T_2(x/X) on |x| <= X = table_reach_ (empty: summed at each x).
  std::vector<double> table_f_;
  void prepare_table();
  double k1_convolution(double x) const;
  double greens_table(double x) const;
  // -(phi1/pi) int p ln|x - xi| d xi (exact, the series' log potential).
  double log_part(double x) const;
  // The Filon route (any x): built on first use (beyond the table's reach,
  // or every x where there is no table), then shared by copies.
  struct FilonDisplacement;
  std::shared_ptr<FilonDisplacement> filon_;
  const FilonDisplacement& filon_displacement() const;
  double filon_integral(const FilonDisplacement& f, double x) const;
  // (1/pi) int p(xi)/(P/h) G(x - xi) d xi by the route that reaches x.
  double greens_integral(double x) const;
};

// Solves the contact problem. Throws std::invalid_argument (bad input),
// SupercriticalSpeedError (vstar >= V*_cr), UnphysicalContactError (unless
// allow_unphysical) and ConvergenceError.
SymmetricSolution solve_contact(const ContactParams& p);

}  // namespace movingpunch

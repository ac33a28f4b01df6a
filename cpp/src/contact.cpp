#include "movingpunch/contact.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "chebyshev.hpp"
#include "gap_scan.hpp"
#include "ladder.hpp"
#include "movingpunch/collocation.hpp"
#include "movingpunch/dispersion.hpp"
#include "movingpunch/errors.hpp"
#include "potentials.hpp"
#include "solve_skeleton.hpp"

namespace movingpunch {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
// Below this the lowest free wave lies beyond the critical-speed search.
constexpr double kMinKw = 1e-12;
using detail::foundation_text;
using detail::kMaxA;
using detail::kMinA;
using detail::kSizes;

// Table range of the kernel for a contact half-width a: covers the
// collocation (|u| <= 2a) and the displacement checks (|u| <= 4a). (A wider
// first table, 5.5 a, saved the paper's case its second table but moved the
// table near V*_cr, kw = 1, eps <= 1e-13, onto pieces, where the gap check
// sits at its round-off floor and flagged a false penetration.)
double table_range(double a) { return 4.2 * a; }

using detail::log_potential;

struct Timer {
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
};

}  // namespace

MediumSpec medium_of(const ContactParams& p) {
  return p.medium ? *p.medium : homogeneous_medium(p.kw, p.nu, p.kp);
}

void validate(const ContactParams& p) {
  require_in_range("nu", p.nu, 0.0, 0.5, false, true);
  // Any finite vstar >= 0 is a valid question: at or above V*_cr the answer
  // is SupercriticalSpeedError (raised by solve_contact with both speeds).
  require_in_range("vstar", p.vstar, 0.0, 1e300, false, false);
  require_in_range("kw", p.kw, kMinKw, kInf, false, false, true);
  require_in_range("kp", p.kp, 0.0, kMaxKp, false, false);
  if (p.medium) {
    validate(*p.medium);
    if (p.medium->layers[0].gamma != 0.0 && p.profile == ProfileKind::flat)
      throw InvalidParameter(
          "profile", "a bounded contact (cylinder, rounded flat, table) on a graded top sublayer",
          "profile: a flat punch on a graded top sublayer is not solved yet (its first-kind "
          "collocation does not integrate the graded kernel's sgn and u ln|u| terms exactly); "
          "use a rounded flat, or put a homogeneous sublayer on top");
    if (p.medium->base.kind == BaseKind::springs && p.medium->base.damping != 0.0)
      throw InvalidParameter("damping", "0 on the symmetric solver",
                             "damping: a damped base is solved by the asymmetric solver");
  }
  // The shape's parameters (the cylinder's radius, a flat face's half-width,
  // a table), named as the API names them.
  (void)PunchProfile(p.profile, p.radius, p.half_width, p.table_x, p.table_y);
  // The undamped solver is symmetric: an asymmetric table takes the
  // asymmetric one (solve_asymmetric; movingpunch.solve routes it there).
  if (p.profile == ProfileKind::table) check_profile_table(p.table_x, p.table_y, true);
  require_in_range("load", p.load, 0.0, 1e6, true, false);
  require_in_range("tol", p.tol, 1e-14, 1e-2, false, false);
  if (p.n != 0 && (p.n < 2 || p.n > 4096 || p.n % 2 != 0))
    throw InvalidParameter("n", "0 (automatic) or even in [2, 4096]",
                           "n (collocation size) must be 0 (automatic) or even in [2, 4096], got " +
                               std::to_string(p.n));
}

namespace {

constexpr double kLoosestKernelTol = 1e-10;

// a/h is never solved looser than 1e-8 a (the N ladder's last change, 1e-2 of
// it for the width iteration), as the kernel is never built looser than 1e-10.
// Looser, the ladder stops at N = 16 or 24 and the iteration early: the rate
// read from the chain is not yet steady, the iteration's residual is read to
// first order only (10 % under the error at kw = 10, tol 1e-4), and near
// V*_cr the kernel's round-off moves a/h by 1e-9 ... 5e-8 from one table to the
// next, so an estimate that bounds the error can exceed a lucky one by
// 100 ... 230 (kw = 0.1, eps = 1e-12, tol 1e-6: 6.3e-8 for 5.6e-10). The price
// is ~0.1 ms at a loose tol (docs/performance.md).
constexpr double kLoosestWidthTol = 1e-8;

// Everything the iteration on a needs for one (vstar, kw, nu).
class Problem {
 public:
  Problem(const ContactParams& p, std::shared_ptr<const Medium> model, bool may_grow,
          const PunchProfile& profile)
      : p_(p),
        model_(std::move(model)),
        prof_(profile),
        phi1_(model_->phi1()),
        may_grow_(may_grow) {
    // Never looser than 1e-10: the kernel's error estimates (QUADPACK's
    // panel estimate, a Chebyshev table's last coefficients) bound a kernel
    // built loosely by 1e2 ... 1e4 times its actual error, and the a/h error
    // budget carries that; a kernel at 1e-10 costs a loose solve ~0.2 ms.
    kernel_tol_ = std::clamp(1e-2 * p.tol, 1e-15, kLoosestKernelTol);
  }

  const KernelK1& kernel(double a) {
    if (!kernel_ || 2.0 * a > kernel_->range()) fetch(2.0 * a, table_range(a));
    return *kernel_;
  }
  std::shared_ptr<const KernelK1> kernel_ptr() const { return kernel_; }
  void ensure_range(double range) {
    if (!kernel_ || kernel_->range() < range) fetch(range, range * 1.05);
  }
  // Kernel tables built by this solve (0 if all came from the cache), and the
  // time spent fetching or building them.
  int kernel_builds() const { return builds_; }
  double kernel_seconds() const { return kernel_seconds_; }

  // Unit solution G (g = -(a / (phi1 R)) G) and the load this a carries.
  // Any other profile: G solves M G = f'(a s_k) (g = -G/(phi1 P)).
  double load_of(const ChebyshevNodes& nodes, double a, Eigen::VectorXd* G_out) {
    const KernelK1& k = kernel(a);
    ++evaluations_;
    const Eigen::VectorXd G = matrix(nodes, a, k).partialPivLu().solve(rhs(nodes, a));
    const double sum = 2.0 * nodes.w.head(nodes.n / 2).dot(G);
    if (G_out) *G_out = G;
    return load_factor(a) * sum;
  }
  bool cylinder() const { return prof_.kind() == ProfileKind::cylinder; }
  // The folded collocation matrix: the regular part of k1 by Gauss-Chebyshev,
  // a graded top's singular terms exactly (singular_collocation_matrix).
  static Eigen::MatrixXd matrix(const ChebyshevNodes& nodes, double a, const KernelK1& k) {
    Eigen::MatrixXd M = unit_collocation_matrix(
        nodes, a, [&k](const double* u, const double* v, double* out, std::size_t n) {
          k.sum_many(u, v, out, n);
        });
    if (!k.singular().empty()) M += singular_collocation_matrix(nodes, a, k.singular());
    return M;
  }
  // The right-hand side of the folded system, k = 1..N/2: s_k (cylinder: the
  // slope a s_k/R over a/R) or the profile's slope, through its exact
  // Chebyshev projection of degree < N + 1, sum_m d_m T_m(s_k) (m odd),
  // rather than its values f'(a s_k): the half-plane part of the system maps
  // U_{m-1} onto T_m, so the collocation then solves the projected equation
  // exactly and a slope with a kink (a rounded flat at |x| = b) aliases
  // nothing onto the load (a/h converges as fast as for the cylinder instead
  // of like N^-1.5).
  Eigen::VectorXd rhs(const ChebyshevNodes& nodes, double a) const {
    const int h = nodes.n / 2;
    if (cylinder()) return nodes.s.head(h);
    const std::vector<double> d = prof_.slope_chebyshev(a, (nodes.n + 2) / 2);
    Eigen::VectorXd r(h);
    for (int k = 0; k < h; ++k) {
      const double th = std::acos(nodes.s(k));
      double sum = 0.0;
      for (std::size_t q = 0; q < d.size(); ++q)
        sum += d[q] * std::cos((2.0 * static_cast<double>(q) + 1.0) * th);
      r(k) = sum;
    }
    return r;
  }
  // The load per unit sum_i W_i G_i (equilibrium a pi sum W g = 1).
  double load_factor(double a) const {
    return cylinder() ? -kPi * a * a / (phi1_ * p_.radius) : -kPi * a / phi1_;
  }
  // g = g_scale(a, load) G.
  double g_scale(double a, double load) const {
    return cylinder() ? -(a / (phi1_ * p_.radius)) / load : -1.0 / (phi1_ * load);
  }

  // The final solve at a, with what the error estimate needs: the matrix M,
  // the unit solution G (M G = s) and the adjoint lambda (M^T lambda = W), so
  // that a change dM moves sum W G by -lambda^T dM G to first order.
  struct Linearised {
    Eigen::MatrixXd M;
    Eigen::VectorXd G, lambda;
    double load = 0;
  };
  Linearised linearise(const ChebyshevNodes& nodes, double a) {
    const KernelK1& k = kernel(a);
    ++evaluations_;
    const int h = nodes.n / 2;
    Linearised L;
    L.M = matrix(nodes, a, k);
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(L.M);
    L.G = lu.solve(rhs(nodes, a));
    L.lambda = lu.transpose().solve(nodes.w.head(h));
    L.load = load_factor(a) * 2.0 * nodes.w.head(h).dot(L.G);
    return L;
  }

  int evaluations() const { return evaluations_; }
  // lim M1(t)/t at long waves, read at t = 0.05 h: the medium's compliance
  // for the wide-contact first width (a half-space base's M1 stays finite
  // as t -> 0: a large compliance, a wide first guess).
  double long_wave_compliance() const {
    constexpr double t0 = 0.05;
    return model_->surface_response(t0).M1.real() / t0;
  }
  void count_evaluation() { ++evaluations_; }

 private:
  const ContactParams& p_;
  std::shared_ptr<const Medium> model_;
  const PunchProfile& prof_;
  double phi1_;
  double kernel_tol_;
  bool may_grow_;
  std::shared_ptr<const KernelK1> kernel_;
  int evaluations_ = 0;
  int builds_ = 0;
  double kernel_seconds_ = 0.0;

  void fetch(double min_range, double build_range) {
    const Timer t;
    bool built = false;
    // Geometric growth only for this solve's first table (the width of an
    // earlier solve of a sweep was outgrown); later tables of this solve are
    // its own width iteration's, built as asked.
    kernel_ = cached_kernel(model_, kernel_tol_, min_range, build_range, &built,
                            may_grow_ && builds_ == 0);
    builds_ += built ? 1 : 0;
    kernel_seconds_ += t.seconds();
  }
};

// The load curve at this N is not monotone: the collocation under-resolves
// the kernel (near V*_cr it oscillates like sin(alpha_cr u) with an amplitude
// growing like 1/sqrt(eps)); a finer N is needed, not a wider contact.
class UnderResolved : public ConvergenceError {
 public:
  using ConvergenceError::ConvergenceError;
};

// Solves load(a) = P for a at fixed N: safeguarded secant on F(ln a) =
// ln load(a) - ln P (monotone increasing, nearly 2 ln a for Hertz). While
// searching for a bracket, a load that falls as a grows proves the curve
// under-resolved (UnderResolved) before the search wanders off to a = kMaxA.
// The widths a trial may take: a = a0 + e^x (a0 = 0: x = ln a; a rounded
// flat's face a0 = b: x = ln(a - b), since its load grows like (a - b)^(3/2)),
// a - a0 in [kMinA, amax - a0]; `refuse(too_wide)` throws the refusal of a
// load beyond them (default: width_out_of_range).
struct WidthRange {
  double a0 = 0.0;
  double amax = kMaxA;
  std::function<void(bool)> refuse;
};

double solve_width(Problem& prob, const ContactParams& params, const ChebyshevNodes& nodes,
                   double P, double a_guess, double xtol, const WidthRange& range = {}) {
  const double a0 = range.a0;
  auto width_out_of_range = [&](const ContactParams& q, bool too_wide) {
    if (range.refuse) range.refuse(too_wide);
    detail::width_out_of_range(q, too_wide);
  };
  auto F = [&](double la) {
    const double load = prob.load_of(nodes, a0 + std::exp(la), nullptr);
    if (!(load > 0.0) || !std::isfinite(load)) return kInf;  // treat as "a too large"
    return std::log(load) - std::log(P);
  };
  double x0 = std::log(a_guess - a0), f0 = F(x0);
  if (f0 == 0.0) return a_guess;
  // Bracket: [lo, hi] with F(lo) < 0 < F(hi), found by steps of the local
  // slope (about 2) limited to a factor e^2 in a.
  double lo = -kInf, hi = kInf;
  (f0 < 0.0 ? lo : hi) = x0;
  double x1 = x0 - (std::isfinite(f0) ? std::clamp(f0 / 2.0, -2.0, 2.0) : 1.0);
  // The first step stays within the supported widths too (a trial beyond
  // kMaxA would build a kernel table for a width never returned); from a
  // guess at a bound, step inwards and let the search below decide.
  const double lmin = std::log(kMinA), lmax = std::log(range.amax - a0);
  x1 = std::clamp(x1, lmin, lmax);
  if (x1 == x0) x1 = x0 >= lmax ? x0 - 1.0 : x0 + 1.0;
  detail::StallGuard stall(kInf);
  for (int it = 0; it < 200; ++it) {
    const double f1 = F(x1);
    if (f1 == 0.0) return a0 + std::exp(x1);
    if (!std::isfinite(lo) || !std::isfinite(hi)) {
      // Still searching: the load must grow with a (slope 2 to 3 in log-log
      // on every resolved curve). Steps below 1 % in a are left alone: there
      // the difference can be round-off.
      if (std::isfinite(f0) && std::isfinite(f1) && std::fabs(x1 - x0) >= 1e-2 &&
          (f1 - f0) * (x1 - x0) <= 0.0)
        throw UnderResolved("the load carried by a trial width is not monotone at N = " +
                            std::to_string(nodes.n));
    }
    if (f1 < 0.0)
      lo = std::max(lo, x1);
    else
      hi = std::min(hi, x1);
    const bool bracketed = std::isfinite(lo) && std::isfinite(hi);
    if (bracketed && hi - lo <= xtol) return a0 + std::exp(0.5 * (lo + hi));
    double x2 = (std::isfinite(f0) && std::isfinite(f1) && f1 != f0)
                    ? x1 - f1 * (x1 - x0) / (f1 - f0)  // secant
                    : x1 - 1.0;
    if (bracketed) {
      // Safeguards: stay strictly inside the bracket, and bisect when the
      // bracket has not halved over three steps (a stalled secant).
      x2 = stall(x2, lo, hi);
    } else {
      x2 = std::clamp(x2, x1 - 2.0, x1 + 2.0);  // expanding search for a bracket
    }
    if (!std::isfinite(x2))
      throw ConvergenceError("contact width iteration failed (non-finite step)");
    // Outside the supported widths: the load there proves the target lies beyond.
    if (x2 > lmax) {
      if (std::isfinite(hi) && hi <= lmax)
        x2 = 0.5 * (std::max(lo, x1) + hi);
      else {
        const double fmax = F(lmax);
        if (lmax - x1 >= 1e-2 && std::isfinite(f1) && fmax <= f1)
          throw UnderResolved("the load carried by a trial width is not monotone at N = " +
                              std::to_string(nodes.n));
        if (fmax < 0.0) width_out_of_range(params, true);
        x2 = lmax;
      }
    } else if (x2 < lmin) {
      if (std::isfinite(lo) && lo >= lmin)
        x2 = 0.5 * (lo + std::min(hi, x1));
      else {
        const double fmin = F(lmin);
        if (x1 - lmin >= 1e-2 && std::isfinite(f1) && fmin >= f1)
          throw UnderResolved("the load carried by a trial width is not monotone at N = " +
                              std::to_string(nodes.n));
        if (fmin > 0.0) width_out_of_range(params, false);
        x2 = lmin;
      }
    }
    if (std::fabs(x2 - x1) <= xtol) return a0 + std::exp(x2);
    x0 = x1;
    f0 = f1;
    x1 = x2;
  }
  throw ConvergenceError("contact width iteration did not converge in 200 steps");
}

// The N-truncation error of the last of a chain of widths a_k at sizes n_k
// (the k-th solve failing resets the chain). Convergence in N is geometric,
// and the change c_k = |a_k - a_{k-1}| is about the error of a_{k-1}: the error
// of a_k is about c_k q, q the ratio per step c_k / c_{k-1}, or, with three
// changes, the geometric mean of the last two ratios if larger, or where the
// two agree within 4 over equal steps (a steady rate) the larger per node
// over the last step; taken 10 times and never above c_k. Per step, not per node, and over two
// steps: the rate is not steady before N resolves the kernel (kw = 1e-4: changes 1.4e-3,
// 2.5e-5, 8.7e-9 at N = 12, 16, 24, then an error 6.4e-11 at 24, a ratio
// 7e-3), while the larger ratio alone overestimates a rate that speeds up
// (kw = 0.1 near V*_cr) by 500. With two sizes, the decay `rate` per index of
// g's Chebyshev coefficients over the step stands in for q (taken 3 times;
// 1: unknown); infinite with a single size. (Calibrated against N = 256
// references on 72 cases: docs/performance.md.)
double collocation_error(const std::vector<int>& n, const std::vector<double>& a,
                         double rate = 1.0) {
  const std::size_t m = a.size();
  if (m < 2) return kInf;
  const double c2 = std::fabs(a[m - 1] - a[m - 2]);
  if (m < 3) {
    const double qc = rate < 1.0 ? std::pow(rate, n[m - 1] - n[m - 2]) : 1.0;
    return c2 * std::min(1.0, 3.0 * qc);
  }
  const double c1 = std::fabs(a[m - 2] - a[m - 3]);
  if (!(c1 > c2)) return c2;
  double q = c2 / c1;
  if (m >= 4) {
    const double c0 = std::fabs(a[m - 3] - a[m - 4]);
    if (!(c0 > c1)) return c2;
    const double q0 = c1 / c0;
    if (q0 <= 4.0 * q && q <= 4.0 * q0 && n[m - 2] - n[m - 3] == n[m - 3] - n[m - 4]) {
      // A steady rate over two equal steps: per node, over the last step.
      q = std::pow(std::max(q, q0), static_cast<double>(n[m - 1] - n[m - 2]) /
                                        static_cast<double>(n[m - 2] - n[m - 3]));
    } else {
      q = std::max(q, std::sqrt(q * q0));
    }
  }
  return c2 * std::min(1.0, 10.0 * q);
}

// Decay rate per index of the even Chebyshev coefficients of g over their
// last eight: (max|b_{N-2}|, |b_{N-4}| / max|b_{N-6}|, |b_{N-8}|)^(1/4), at
// most 1 (1: too few coefficients to tell).
double coefficient_rate(const Eigen::VectorXd& b) {
  const Eigen::Index n = b.size();
  if (n < 10) return 1.0;
  const double top = std::max(std::fabs(b(n - 2)), std::fabs(b(n - 4)));
  const double below = std::max(std::fabs(b(n - 6)), std::fabs(b(n - 8)));
  if (!(below > 0.0)) return 1.0;
  return std::min(1.0, std::pow(top / below, 0.25));
}

// The largest difference of two series of g (U or T) on 401 points of
// [-1, 1] (twice it bounds the error of a fixed N's g against a reference).
double max_series_difference(const Eigen::VectorXd& b, const Eigen::VectorXd& c, SeriesKind kind) {
  double out = 0.0;
  for (int i = 0; i <= 400; ++i) {
    const double r = std::cos(kPi * i / 400.0);
    out = std::max(out, std::fabs(series(b, r, kind) - series(c, r, kind)));
  }
  return out;
}

// A fixed collocation size N (the caller's `n`): the error of a quantity v
// (a/h, a flat punch's end value g(1)) read from finer sizes, not coarser
// ones: a coarse N may be far from resolved (N = 2: a/h 22 % off the
// converged width, where the comparison with a half size had nothing to
// compare with and said 0). References at m = max(2N, 8), doubled up to
// kFixedReferenceMax, until two successive changes shrink by 4 or more with
// a reference of at least 32 (a geometric rate under way) or two references
// agree to round-off. The estimate is
// |v(N) - v(m_last)| plus the reference's own error (collocation_error over
// the references); infinite if a reference has no solution (an
// under-resolved load curve). `value(m)` returns v at size m.
constexpr int kFixedReferenceMax = 1024;
// Fixed sizes up to this one are checked against finer ones (two references
// at least); larger ones against a half and a quarter of the size.
constexpr int kFixedFinerMax = kFixedReferenceMax / 4;

struct FixedReference {
  int n = 0;           // the last reference size (0: none)
  double value = 0.0;  // v there
  double error = kInf;
};

template <class Value>
FixedReference fixed_size_reference(int n, double v_n, Value value) {
  FixedReference out;
  std::vector<int> sizes;
  std::vector<double> values;
  try {
    for (int m = std::max(2 * n, 8); m <= kFixedReferenceMax; m *= 2) {
      sizes.push_back(m);
      values.push_back(value(m));
      const std::size_t k = values.size();
      // Two references agreeing to round-off: converged.
      if (k >= 2 && std::fabs(values[k - 1] - values[k - 2]) <=
                        100.0 * std::numeric_limits<double>::epsilon() * std::fabs(values[k - 1]))
        break;
      if (k >= 3 && m >= 32) {
        const double c2 = std::fabs(values[k - 1] - values[k - 2]);
        const double c1 = std::fabs(values[k - 2] - values[k - 3]);
        if (c2 <= 0.25 * c1) break;
      }
    }
  } catch (const ConvergenceError&) {
    return out;
  } catch (const std::invalid_argument&) {
    return out;
  }
  if (sizes.empty() || !std::isfinite(values.back())) return out;
  out.n = sizes.back();
  out.value = values.back();
  out.error = std::fabs(v_n - out.value) + collocation_error(sizes, values);
  return out;
}

std::string format_g(double x, int precision = 3) {
  std::ostringstream o;
  o.precision(precision);
  o << x;
  return o.str();
}

// The kernel part of an error budget: a first-order bound on |lambda^T dM G|
// for the errors dk of the k1 kernel, where the folded matrix has entries
// w_j [... + a (k(a (c_j - r_k)) + k(a (-c_j - r_k)))] (rows at r_k =
// row_nodes, columns at c_j = col_nodes, wG_j = w_j G_j, lambda the adjoint of
// the quantity S whose error this is). An error c sin(alpha u) of k1 moves it
// by c |2 a (sum_k lambda_k sin(alpha a r_k)) (sum_j wG_j cos(alpha a c_j))|
// (rank one in alpha), which weights each quadrature panel's error bound
// (the largest over its ends and nodes) and each node's round-off
// 2 eps (1 + |f| + f^2) w (independent, in quadrature, 3 sigma); the table's
// truncation (its first omitted Chebyshev terms) and round-off follow.
double kernel_perturbation(const KernelK1& k, double a, const Eigen::VectorXd& lambda,
                           const Eigen::VectorXd& row_nodes, const Eigen::VectorXd& wG,
                           const Eigen::VectorXd& col_nodes, double S) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const AlphaQuadrature& q = k.value_quadrature();
  const double phi1 = k.model().phi1();
  const Eigen::Index rows = lambda.size(), cols = wG.size();
  const double lam1 = lambda.cwiseAbs().sum(), wg1 = wG.cwiseAbs().sum();
  // Truncation errors are systematic: they add. Round-off is independent from
  // panel to panel and from one u to the next: it adds in quadrature, taken 3
  // times (3 sigma).
  double dS = 0.0, dS_round2 = 0.0;
  if (q.panel_error.size() == q.panel_centre.size() &&
      q.panel_roundoff.size() == q.panel_centre.size()) {
    const double worst = 2.0 * a * lam1 * wg1;  // |dS| per unit error of k1, any shape
    // |S| at a panel's ends and its 15 nodes, alpha = c + h x_k, from the
    // phases e^{i a c r_j} of its centre (per panel) times e^{i a h x_k r_j}
    // (per distinct half-width h): 2 (rows + cols) sin/cos per panel in place
    // of 17 times as many (they were most of a stack's solve).
    constexpr int kPoints = 17;  // the two ends, then the 15 nodes
    std::array<double, kPoints> x{};
    x[0] = -1.0;
    x[1] = 1.0;
    for (int n = 0; n < 15; ++n)
      x[static_cast<std::size_t>(n) + 2] =
          (q.alpha[static_cast<std::size_t>(n)] - q.panel_centre[0]) / q.panel_half[0];
    std::vector<double> widths;
    // Per width, the offsets e^{i a h x_k r_j} as cos and sin in separate
    // arrays: [k][row j] then [k][col j].
    std::vector<std::vector<double>> off_c, off_s;
    // Per panel, the weights times the centre's phases: lambda_j e^{i a c r_j}
    // and wG_j e^{i a c c_j} (real and imaginary parts).
    std::vector<double> lr(static_cast<std::size_t>(rows)), li(lr.size());
    std::vector<double> gr(static_cast<std::size_t>(cols)), gi(gr.size());
    const std::size_t nr = lr.size(), nc = gr.size(), per = nr + nc;
    // The panels by their bound at any shape, (e + 3 sum sigma) worst, the
    // largest first; once what the rest could add at most is below 1 % of
    // what the sensitivity-weighted ones add, it is added as it stands (an
    // upper bound: most panels of a long algebraic tail are far below).
    const std::size_t panels = q.panel_centre.size();
    std::vector<double> crude(panels, 0.0);
    double rest = 0.0;
    auto sigma_of = [&](std::size_t n) {
      const double f = std::fabs((q.m1[n] - phi1) / phi1);
      return 2.0 * eps * (1.0 + f + f * f) * q.weight[n];
    };
    for (std::size_t i = 0; i < panels; ++i) {
      double sig = 0.0;
      for (std::size_t n = 15 * i; n < 15 * i + 15 && n < q.alpha.size(); ++n) sig += sigma_of(n);
      crude[i] = (q.panel_error[i] + 3.0 * sig) * worst;
      rest += crude[i];
    }
    std::vector<std::size_t> order(panels);
    for (std::size_t i = 0; i < panels; ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t l, std::size_t r) { return crude[l] > crude[r]; });
    // The distinct half-widths (bisections of one width, equal but for their
    // last bits within 1e-12: a graded top's 14 were 4; a phase a h x r
    // off by 1e-12 of itself is nothing to a bound), ascending, and their
    // offsets: the narrowest by sin/cos, each twice as wide as the one
    // before by squaring its (e^{2 i phi} = (e^{i phi})^2: a few 1e-16).
    for (std::size_t i = 0; i < panels; ++i) {
      const double hw = q.panel_half[i];
      if (std::none_of(widths.begin(), widths.end(),
                       [hw](double v) { return std::fabs(v - hw) <= 1e-12 * hw; }))
        widths.push_back(hw);
    }
    std::sort(widths.begin(), widths.end());
    for (std::size_t w = 0; w < widths.size(); ++w) {
      const double hw = widths[w];
      std::vector<double> tc(kPoints * per), ts(kPoints * per);
      if (w > 0 && std::fabs(hw - 2.0 * widths[w - 1]) <= 1e-12 * hw) {
        const std::vector<double>&pc = off_c[w - 1], &ps = off_s[w - 1];
        for (std::size_t e = 0; e < tc.size(); ++e) {
          tc[e] = pc[e] * pc[e] - ps[e] * ps[e];
          ts[e] = 2.0 * pc[e] * ps[e];
        }
      } else {
        for (std::size_t k = 0; k < static_cast<std::size_t>(kPoints); ++k) {
          const double ahx = a * hw * x[k];
          for (std::size_t j = 0; j < nr; ++j) {
            const double ph = ahx * row_nodes(static_cast<Eigen::Index>(j));
            tc[k * per + j] = std::cos(ph);
            ts[k * per + j] = std::sin(ph);
          }
          for (std::size_t j = 0; j < nc; ++j) {
            const double ph = ahx * col_nodes(static_cast<Eigen::Index>(j));
            tc[k * per + nr + j] = std::cos(ph);
            ts[k * per + nr + j] = std::sin(ph);
          }
        }
      }
      off_c.push_back(std::move(tc));
      off_s.push_back(std::move(ts));
    }
    for (const std::size_t i : order) {
      if (rest <= 1e-2 * (dS + 3.0 * std::sqrt(dS_round2))) break;
      rest -= crude[i];
      const double e = q.panel_error[i], r = q.panel_roundoff[i];
      if (!((e + r) * worst > 1e-4 * eps * std::fabs(S))) continue;  // negligible
      const double hw = q.panel_half[i], c = q.panel_centre[i];
      std::size_t w = 0;
      while (w < widths.size() && !(std::fabs(widths[w] - hw) <= 1e-12 * hw)) ++w;
      const double* tc = off_c[w].data();
      const double* ts = off_s[w].data();
      for (std::size_t j = 0; j < nr; ++j) {
        const double ph = a * c * row_nodes(static_cast<Eigen::Index>(j));
        const double l = lambda(static_cast<Eigen::Index>(j));
        lr[j] = l * std::cos(ph);
        li[j] = l * std::sin(ph);
      }
      for (std::size_t j = 0; j < nc; ++j) {
        const double ph = a * c * col_nodes(static_cast<Eigen::Index>(j));
        const double g = wG(static_cast<Eigen::Index>(j));
        gr[j] = g * std::cos(ph);
        gi[j] = g * std::sin(ph);
      }
      // |S| at point k: 2 a |Im(sum lambda_j e^{i alpha a r_j})| |Re(sum wG_j
      // e^{i alpha a c_j})|, alpha a r_j = a c r_j + a h x_k r_j.
      auto sens = [&](std::size_t k) {
        const double* cr = tc + k * per;
        const double* sr = ts + k * per;
        double s1 = 0.0, s2 = 0.0;
        for (std::size_t j = 0; j < nr; ++j) s1 += lr[j] * sr[j] + li[j] * cr[j];
        for (std::size_t j = 0; j < nc; ++j) s2 += gr[j] * cr[nr + j] - gi[j] * sr[nr + j];
        return 2.0 * a * std::fabs(s1 * s2);
      };
      double smax = std::max(sens(0), sens(1));
      double round2 = 0.0;
      for (std::size_t n = 15 * i; n < 15 * i + 15 && n < q.alpha.size(); ++n) {
        const double sn = sens(n - 15 * i + 2);
        smax = std::max(smax, sn);
        const double sigma = sigma_of(n);
        round2 += (sigma * sn) * (sigma * sn);
      }
      dS += e * smax;
      dS_round2 += round2;
    }
    dS += std::max(rest, 0.0);
  } else {
    dS += q.error_estimate * 2.0 * a * lam1 * wg1;
  }
  // The table: its truncation, of the shape of its first omitted Chebyshev
  // terms T_m(u / range) (m = order, order + 2; 3 times the larger effect), or of
  // any shape in the worst case for a piecewise table; its round-off,
  // independent for each of the N^2/2 entries.
  if (k.table_order() > 0) {
    // T_m(u) = cos(m theta) and T_{m+2}(u) = cos(m theta) cos 2 theta -
    // sin(m theta) sin 2 theta, theta = acos u: one acos and one sincos per
    // entry for both orders.
    const int m = k.table_order();
    double sum_m = 0.0, sum_m2 = 0.0;
    for (Eigen::Index kk = 0; kk < rows; ++kk)
      for (Eigen::Index j = 0; j < cols; ++j) {
        const double lw = lambda(kk) * wG(j);
        for (const double sg : {1.0, -1.0}) {
          const double u =
              std::clamp(a * (sg * col_nodes(j) - row_nodes(kk)) / k.range(), -1.0, 1.0);
          const double th = std::acos(u);
          const double cm = std::cos(m * th), sm = std::sin(m * th);
          const double c2 = 2.0 * u * u - 1.0, s2 = 2.0 * u * std::sqrt(1.0 - u * u);
          sum_m += lw * cm;
          sum_m2 += lw * (cm * c2 - sm * s2);
        }
      }
    const double tmax = std::max(std::fabs(a * sum_m), std::fabs(a * sum_m2));
    dS += 3.0 * k.table_error() * tmax;
  } else {
    dS += k.table_error() * 2.0 * a * lam1 * wg1;
  }
  const double rms_entries = std::sqrt(2.0) * a * lambda.norm() * wG.norm();
  dS_round2 += (k.table_roundoff() * rms_entries) * (k.table_roundoff() * rms_entries);
  dS += 3.0 * std::sqrt(dS_round2);
  return dS;
}

// The parts of the error estimate of a/h (SymmetricSolution::ErrorBudget) from
// the final solve at a. Every perturbation of the collocation matrix dM moves
// S = sum W G by -lambda^T dM G; S moves the load by dS/S and a by
// (dS/S)/slope, slope = d ln load/d ln a (measured here, about 2). k1 enters M
// as a W_j (k1(a (r_j - s_k)) + k1(a (-r_j - s_k))); an error c sin(alpha u) of
// k1 moves S by c |2 a (sum_k lambda_k sin(alpha a s_k)) (sum_j W_j G_j
// cos(alpha a r_j))|, which is how each quadrature panel's error bound
// counts (the largest over five points of the panel). Near V*_cr this is what
// keeps the estimate honest: the resonance's round-off (eps |M1|^2 over a
// width sqrt(eps)) lies where this sensitivity nearly vanishes.
SymmetricSolution::ErrorBudget error_budget(Problem& prob, const ContactParams& p,
                                            const ChebyshevNodes& nodes,
                                            const Problem::Linearised& lin, double a,
                                            double collocation, double roundoff, double root_a) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const int h = nodes.n / 2;
  const Eigen::VectorXd w = nodes.w.head(h);
  const double S = w.dot(lin.G);
  // d ln load / d ln a from a second load a step 1e-6 wider.
  const double step = 1e-6;
  const double load2 = prob.load_of(nodes, a * (1.0 + step), nullptr);
  double slope = (std::log(load2) - std::log(lin.load)) / std::log1p(step);
  if (!std::isfinite(slope) || slope < 0.5) slope = 0.5;  // a flat curve: be cautious
  const double to_a = a / (std::fabs(S) * slope);         // dS -> da

  SymmetricSolution::ErrorBudget b;
  b.collocation = collocation;
  // Newton's step from the residual (the residual's own noise is the
  // round-off part below): of the width solved at N, root_a (an
  // extrapolated a, BoundedSolve, carries the collocation's load error by
  // design: its estimate is `collocation`).
  const double root_load = root_a == a ? lin.load : prob.load_of(nodes, root_a, nullptr);
  b.root = root_a * std::fabs(std::log(root_load / p.load)) / slope;

  const KernelK1& k = prob.kernel(a);
  const Eigen::VectorXd wG = w.cwiseProduct(lin.G);
  const double dS = kernel_perturbation(k, a, lin.lambda, nodes.s.head(h), wG, nodes.r.head(h), S);
  b.kernel = dS * to_a;

  // Round-off: of the matrix entries and the solve's backward error, 2 eps
  // |M_kj| each, independent (3 sigma), the relative round-off of phi1 near
  // V*_R, and a floor of 2 eps a.
  double solve2 = 0.0;
  for (int kk = 0; kk < h; ++kk)
    for (int j = 0; j < h; ++j) {
      const double t = lin.lambda(kk) * lin.M(kk, j) * lin.G(j);
      solve2 += t * t;
    }
  const double solve = 3.0 * 2.0 * eps * std::sqrt(solve2);
  b.roundoff = solve * to_a + a * roundoff + 2.0 * eps * a;
  return b;
}

// The widths a non-cylindrical profile's contact may take: beyond a rounded
// flat's face (a0 = b), within the supported widths and the profile's table,
// with a refusal that names the profile (the cylinder keeps the default,
// which names radius * load).
WidthRange profile_range(const ContactParams& p, const PunchProfile& prof) {
  WidthRange r;
  if (prof.kind() == ProfileKind::cylinder) return r;
  r.a0 = prof.kind() == ProfileKind::rounded_flat ? prof.face() : 0.0;
  r.amax = std::min(kMaxA, prof.extent());
  const std::string what = prof.describe();
  const double amax = r.amax, a0 = r.a0;
  const bool table_bound = prof.extent() < kMaxA;
  r.refuse = [p, what, amax, a0, table_bound](bool too_wide) {
    std::ostringstream m;
    m.precision(6);
    m << "load = " << p.load << " on the " << what << " (" << foundation_text(p)
      << ", vstar = " << p.vstar << ") needs a contact half-width ";
    if (too_wide && table_bound)
      m << "above " << amax << " h, the extent of the profile's table: the contact must stay "
        << "within the table; extend the table beyond that width or reduce the load";
    else if (too_wide)
      m << "above the supported range " << detail::supported_range_text() << ": reduce the load";
    else if (a0 > 0.0)
      m << "within " << kMinA << " h of the flat face's edge b/h = " << a0
        << " (a > b always: the rounded corners always carry some load): increase the load, or "
           "use a flat punch (square corners)";
    else
      m << "below the supported range " << detail::supported_range_text() << ": increase the load";
    throw std::invalid_argument(m.str());
  };
  return r;
}

// The first width of a non-cylindrical profile: the half-plane width
// (solve_skeleton.hpp) within the range.
double half_plane_width(const PunchProfile& prof, double phi1, double P, const WidthRange& r) {
  return detail::profile_half_plane_width(prof, phi1, P, r.a0, r.amax);
}

// The flat punch (index +1): g(r) = p(a r) sqrt(1 - r^2)/(P/h) by
// Gauss-Chebyshev collocation of the first kind (collocation.hpp) over the N
// ladder until the end value g(1) converges (or at the fixed N, compared
// with a half and a quarter of it): its T coefficients, N and the estimated
// error of g(1) (the N truncation read from the chain as for a/h, plus
// round-off).
struct FlatSolve {
  Eigen::VectorXd b;
  int n = 0;
  double error = kInf;
  // The pointwise error of g at a fixed N (max_series_difference against the
  // reference); at a converged N, `error` stands for it.
  double g_error = -1.0;
};

// The symmetric solver's verdict on one refined quantity (a width, or a flat
// punch's g(1)) after a size of its ladder: converged when the last change
// meets tol times `scale`, over at least three sizes unless the change is at
// round-off: from two, the N error is only bounded by the change itself,
// which overstates it by up to 1e3 where N converges fast. `change` keeps the
// last change (for the message when the ladder runs out).
template <class State>
detail::Verdict change_verdict(const detail::LadderChain<State, 1>& c, double scale, double tol,
                               double& change) {
  if (c.size() < 2) return detail::Verdict::go_on;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  change = c.changes[0].back();
  const bool ok = change <= tol * scale && (c.size() >= 3 || change <= 100.0 * eps * scale);
  return ok ? detail::Verdict::converged : detail::Verdict::go_on;
}

FlatSolve solve_flat(Problem& prob, const ContactParams& p, double a) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  // The displacement's Filon integrals need the kernel's panels to |u| = 4a.
  prob.ensure_range(table_range(a));
  auto coefficients = [&](int n) {
    const FirstKindNodes nd = first_kind_nodes(n);
    const KernelK1& k = prob.kernel(a);
    prob.count_evaluation();
    const int h = n / 2;
    const Eigen::MatrixXd M =
        flat_collocation_matrix(nd, a, [&k](double u, double v) { return k.sum(u, v); });
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(h);
    rhs(h - 1) = 1.0;  // equilibrium
    const Eigen::VectorXd G = M.partialPivLu().solve(rhs);
    Eigen::VectorXd g_full(n);
    for (int j = 0; j < h; ++j) g_full(j) = g_full(n - 1 - j) = G(j);
    Eigen::VectorXd c = t_coefficients(nd, g_full);
    for (Eigen::Index q = 1; q < c.size(); q += 2) c(q) = 0.0;  // g is even
    return c;
  };
  const double half_plane = 1.0 / (kPi * a);  // g of the half-plane
  const double width_tol = std::min(p.tol, kLoosestWidthTol);
  std::vector<int> chain_n;
  std::vector<double> chain_k;
  FlatSolve out;
  if (p.n != 0 && p.n <= kFixedFinerMax) {
    // Against finer sizes (fixed_size_reference), g pointwise too.
    out.b = coefficients(p.n);
    out.n = p.n;
    Eigen::VectorXd ref_b;
    const FixedReference ref = fixed_size_reference(p.n, t_series(out.b, 1.0), [&](int m) {
      ref_b = coefficients(m);
      return t_series(ref_b, 1.0);
    });
    chain_n.push_back(p.n);
    chain_k.push_back(t_series(out.b, 1.0));
    out.error = ref.error;
    out.g_error = ref.n > 0 ? 2.0 * max_series_difference(out.b, ref_b, SeriesKind::T) : kInf;
  } else if (p.n != 0) {
    const int coarse = std::max(2, (p.n / 4) * 2);
    const int coarser = std::max(2, (coarse / 4) * 2);
    Eigen::VectorXd coarse_b;
    for (int m : {coarser, coarse}) {
      if (m >= p.n || (!chain_n.empty() && m <= chain_n.back())) continue;
      chain_n.push_back(m);
      coarse_b = coefficients(m);
      chain_k.push_back(t_series(coarse_b, 1.0));
    }
    out.b = coefficients(p.n);
    out.n = p.n;
    chain_n.push_back(p.n);
    chain_k.push_back(t_series(out.b, 1.0));
    out.error = collocation_error(chain_n, chain_k);
    out.g_error = 2.0 * max_series_difference(out.b, coarse_b, SeriesKind::T);
  } else {
    // The ladder on the end value K = g(1) (ladder.hpp); no failure to refine
    // past (a flat punch's system has no width to search).
    double change = kInf;
    const detail::LadderRun<double, 1> run = detail::run_ladder<1, double>(
        detail::size_ladder(kSizes.back()),
        [&](int n) {
          out.b = coefficients(n);
          out.n = n;
          return t_series(out.b, 1.0);
        },
        [](double prev, double K) { return std::array<double, 1>{std::fabs(K - prev)}; },
        [&](const detail::LadderChain<double, 1>& c) {
          return change_verdict(c, std::max(half_plane, std::fabs(c.last())), width_tol, change);
        },
        detail::RethrowFailures{});
    if (run.verdict != detail::Verdict::converged) {
      std::ostringstream last;
      last << "last change of the end value g(1) " << change;
      throw ConvergenceError(detail::not_converged_message("the flat punch's pressure", p.tol,
                                                           kSizes.back(), last.str()));
    }
    chain_n = run.chain.sizes;
    chain_k = run.chain.states;
    out.error = collocation_error(chain_n, chain_k, coefficient_rate(out.b));
  }
  const double scale = std::max(half_plane, std::fabs(chain_k.back()));
  out.error += 64.0 * eps * out.n * scale;
  // The kernel's error, through the adjoint of g(1) (kernel_perturbation):
  // g(1) = w1^T G for the nodal values G, lambda = M^-T w1 (the equilibrium
  // row has no kernel).
  {
    const int n = out.n, h = n / 2;
    const FirstKindNodes nd = first_kind_nodes(n);
    const KernelK1& k = prob.kernel(a);
    const Eigen::MatrixXd M =
        flat_collocation_matrix(nd, a, [&k](double u, double v) { return k.sum(u, v); });
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(h);
    rhs(h - 1) = 1.0;
    const Eigen::VectorXd G = lu.solve(rhs);
    Eigen::VectorXd w1(h);
    for (int j = 0; j < h; ++j) {
      const double th = (2 * j + 1) * kPi / (2.0 * n);
      double sum = 1.0 / n;
      for (int m = 2; m < n; m += 2) sum += 2.0 / n * std::cos(m * th);
      w1(j) = 2.0 * sum;  // the node and its mirror
    }
    const Eigen::VectorXd lambda = lu.transpose().solve(w1);
    out.error += kernel_perturbation(k, a, lambda.head(h - 1), nd.x.head(h - 1), G / n,
                                     nd.t.head(h), std::fabs(w1.dot(G)));
  }
  out.g_error = out.g_error < 0.0 ? out.error : std::max(out.g_error, out.error);
  return out;
}

// A bounded contact under a profile's slope f' (not the cylinder's): the
// half-plane part of the collocation maps U_{m-1} onto T_m, so the
// coefficients of g beyond the collocated ones are the half-plane's,
// b_{m-1} = d_m/(phi1 P) (d_m the slope's Chebyshev coefficients), up to the
// layer's coupling, which decays like J_m(alpha_max a) (negligible once
// m >> alpha_max a). A slope with a kink (the rounded flat at |x| = b) has
// d_m ~ m^-2, so g converges pointwise only like 1/m: the series is extended
// with the half-plane tail to 4096 terms (rounded flat; a table's spline, whose
// slope is C^1, to 256), and `truncation` bounds what is left,
// sum_{n >= length} |b_n| (|sqrt(1 - r^2) U_n(r)| <= 1, so this bounds the
// pressure's error over P/h): d_m summed to 4 times the length and the rest
// extrapolated as m^-2.
void extend_series(Eigen::VectorXd& b, double& truncation, const PunchProfile& prof, double a,
                   double phi1_load) {
  const Eigen::Index n = b.size();
  const Eigen::Index len =
      std::max<Eigen::Index>(n, prof.kind() == ProfileKind::rounded_flat ? 4096 : 256);
  const std::vector<double> d = prof.slope_chebyshev(a, static_cast<int>(2 * len));
  if (len > n) {
    b.conservativeResize(len);
    for (Eigen::Index m = n; m < len; ++m)
      b(m) = m % 2 == 0 ? d[static_cast<std::size_t>(m / 2)] / phi1_load : 0.0;
  }
  double sum = 0.0;
  for (std::size_t q = static_cast<std::size_t>(len / 2); q < d.size(); ++q) sum += std::fabs(d[q]);
  // The rest beyond m = 4 len, as ~m^-2: about the last term times its index.
  const double last = std::fabs(d.back()) + std::fabs(d[d.size() - 2]);
  sum += last * static_cast<double>(d.size());
  truncation = sum / std::fabs(phi1_load);
}

// The width iteration of a contact with bounded ends (index -1): over the N
// ladder (or at the fixed N), the width a, the final nodes and the chain of
// sizes and widths its N error is read from.
struct BoundedSolve {
  double a = 0.0;
  ChebyshevNodes nodes;
  std::vector<int> chain_n;
  std::vector<double> chain_a;
  double change = kInf;
  // A fixed N's finest reference (fixed_size_reference): its size (0: none)
  // and width.
  int ref_n = 0;
  double ref_a = 0.0;
  // A graded top's ladder (algebraic convergence): a is the limit
  // extrapolated through the chain's last three sizes (extrapolate_n4n5),
  // `change` its estimate, and raw_a the width solved at the final N.
  bool extrapolated = false;
  double raw_a = 0.0;
};

BoundedSolve solve_bounded(Problem& prob, const ContactParams& p, const PunchProfile& prof,
                           double phi1) {
  // Refuse at once what is surely outside the supported widths. The static
  // rigid base is the stiffest support (a grows as kw falls and as vstar
  // rises), and for a >> h its contact is at least 0.5 (0.75 lambda)^(1/3) wide
  // (a layer compressed under the punch, measured for 0 <= nu < 0.5); tiny
  // contacts are half-plane (Hertz) contacts.
  // Any other profile starts from its half-plane width (half_plane_width)
  // and is refused by the width iteration once it leaves the supported
  // widths or the profile's table (profile_range).
  const WidthRange range = profile_range(p, prof);
  double a = 0.0;
  if (prof.kind() == ProfileKind::cylinder) {
    const double lambda = p.radius * p.load;
    const MediumSpec spec = medium_of(p);
    const detail::WidthGuess guess =
        spec.homogeneous()
            ? detail::width_guess(phi1, lambda, spec.base.kw, spec.layers[0].nu, spec.base.kp)
            : detail::width_guess_compliance(phi1, lambda, prob.long_wave_compliance());
    if (0.5 * std::cbrt(0.75 * lambda) > kMaxA) detail::width_out_of_range(p, true);
    if (10.0 * guess.hertz < kMinA) detail::width_out_of_range(p, false);

    // Start from the half-plane (Hertz) width, or the wide-contact width when
    // that is far off it (solve_skeleton.hpp).
    a = guess.a;
  } else {
    a = half_plane_width(prof, phi1, p.load, range);
  }
  const double width_tol = std::min(p.tol, kLoosestWidthTol);
  const double xtol = std::max(1e-2 * width_tol, 1e-15);

  double change = kInf;
  // The chain of sizes and widths the N error is read from (collocation_error).
  std::vector<int> chain_n;
  std::vector<double> chain_a;
  ChebyshevNodes nodes;
  int ref_n = 0;
  double ref_a = 0.0;
  bool extrapolated = false;
  double raw_a = 0.0;
  if (p.n != 0 && p.n <= kFixedFinerMax) {
    // Fixed N: the estimate compares with finer sizes (fixed_size_reference);
    // the finest is kept to estimate g's error (solve_contact).
    nodes = chebyshev_nodes(p.n);
    a = solve_width(prob, p, nodes, p.load, a, xtol, range);
    chain_n.push_back(p.n);
    chain_a.push_back(a);
    double a_ref = a;
    const FixedReference ref = fixed_size_reference(p.n, a, [&](int m) {
      a_ref = solve_width(prob, p, chebyshev_nodes(m), p.load, a_ref, xtol, range);
      return a_ref;
    });
    change = ref.error;
    ref_n = ref.n;
    ref_a = ref.value;
  } else if (p.n != 0) {
    // A large fixed N: the estimate compares with the solves at about a half
    // and a quarter of the size (infinite if the half-size solve has no root:
    // an under-resolved load curve); there the rate is geometric.
    const int coarse = std::max(2, (p.n / 4) * 2);
    const int coarser = std::max(2, (coarse / 4) * 2);
    for (int m : {coarser, coarse}) {
      if (m >= p.n || (!chain_n.empty() && m <= chain_n.back())) continue;
      try {
        const double am = solve_width(prob, p, chebyshev_nodes(m), p.load, a, xtol, range);
        a = am;
        chain_n.push_back(m);
        chain_a.push_back(am);
      } catch (const ConvergenceError&) {
        chain_n.clear();
        chain_a.clear();
      } catch (const std::invalid_argument&) {
        chain_n.clear();
        chain_a.clear();
      }
    }
    if (!chain_n.empty() && chain_n.back() != coarse) {
      chain_n.clear();
      chain_a.clear();
    }
    nodes = chebyshev_nodes(p.n);
    a = solve_width(prob, p, nodes, p.load, a, xtol, range);
    chain_n.push_back(p.n);
    chain_a.push_back(a);
    change = collocation_error(chain_n, chain_a);
  } else {
    // Refine N (ladder.hpp). A coarse N can under-resolve the load curve (it
    // may even be non-monotone, with no root): a failure there moves on to
    // the next N with the chain restarted; an UnderResolved is not a failure
    // of this problem (refine: cheap, the kernel is kept); two other failures
    // in a row, or any at the largest N, are reported.
    struct Member {
      double a;
      ChebyshevNodes nodes;
    };
    // A cylinder on a graded top converges like N^-4 (docs/theory.md section
    // 16.5): its ladder also reads the limit extrapolated through the last
    // three sizes, and stops once two successive limits agree to tol while
    // the raw changes fall (the extrapolated limit's error is 4 ... 20 times
    // below that difference on five graded media; the raw a at the same N is
    // 80 to 230 times further off).
    const bool algebraic =
        prof.kind() == ProfileKind::cylinder && !prob.kernel(a).singular().empty();
    auto limit = [](const detail::LadderChain<Member, 1>& c, std::size_t last) {
      const int n[3] = {c.sizes[last - 2], c.sizes[last - 1], c.sizes[last]};
      const double x[3] = {c.states[last - 2].a, c.states[last - 1].a, c.states[last].a};
      return detail::extrapolate_n4n5(n, x);
    };
    double limit_a = 0.0, limit_error = kInf;
    const detail::LadderRun<Member, 1> run = detail::run_ladder<1, Member>(
        detail::size_ladder(kSizes.back()),
        [&](int n) {
          ChebyshevNodes nd = chebyshev_nodes(n);
          a = solve_width(prob, p, nd, p.load, a, xtol, range);
          return Member{a, std::move(nd)};
        },
        [](const Member& prev, const Member& cur) {
          return std::array<double, 1>{std::fabs(cur.a - prev.a)};
        },
        [&](const detail::LadderChain<Member, 1>& c) {
          const detail::Verdict v = change_verdict(c, c.last().a, width_tol, change);
          if (v != detail::Verdict::go_on || !algebraic || c.size() < 4) return v;
          const std::vector<double>& ch = c.changes[0];
          const std::size_t k = ch.size();
          if (!(ch[k - 1] < ch[k - 2] && ch[k - 2] < ch[k - 3])) return v;
          const double now = limit(c, c.size() - 1), before = limit(c, c.size() - 2);
          const double e = std::fabs(now - before);
          if (!(std::isfinite(now) && e <= width_tol * now)) return v;
          limit_a = now;
          limit_error = e;
          return detail::Verdict::converged;
        },
        [](const std::exception& e, const detail::LadderAt& at) {
          if (at.last) return detail::OnFailure::rethrow;
          if (dynamic_cast<const UnderResolved*>(&e) != nullptr)
            return detail::OnFailure::refine_uncounted;
          return at.failures + 1 >= 2 ? detail::OnFailure::rethrow : detail::OnFailure::refine;
        });
    if (run.verdict != detail::Verdict::converged) {
      std::ostringstream last;
      last << "last change " << change;
      throw ConvergenceError(
          detail::not_converged_message("a/h", p.tol, kSizes.back(), last.str()));
    }
    nodes = run.chain.last().nodes;
    for (const Member& m : run.chain.states) chain_a.push_back(m.a);
    chain_n = run.chain.sizes;
    if (std::isfinite(limit_error)) {
      // The extrapolated limit (its estimate, not the raw chain's).
      extrapolated = true;
      raw_a = a;
      a = limit_a;
      change = limit_error;
    } else {
      change = collocation_error(chain_n, chain_a);
    }
  }

  // The displacement (indentation, validity) integrates the transform of p,
  // which oscillates with frequency a, on the kernel's panels: if the width
  // grew past what they resolve, extend the kernel and re-solve on it.
  if (prob.kernel_ptr()->range() < 4.0 * a) {
    prob.ensure_range(table_range(a));
    if (extrapolated) {
      // The same N on the wider table: the limit moves with the raw width.
      const double moved = solve_width(prob, p, nodes, p.load, raw_a, xtol, range);
      a += moved - raw_a;
      raw_a = moved;
    } else {
      a = solve_width(prob, p, nodes, p.load, a, xtol, range);
    }
  }

  return BoundedSolve{a, nodes, chain_n, chain_a, change, ref_n, ref_a, extrapolated, raw_a};
}

// g at a fixed N against the finest reference (BoundedSolve): the bound on
// its pointwise error, max_series_difference twice (the reference's own
// error is a small part of it where the rate is geometric); a large N
// against the next coarser size of its chain; infinite without either.
double fixed_size_g_error(Problem& prob, const BoundedSolve& bs, const Eigen::VectorXd& b) {
  int n = bs.ref_n;
  double a = bs.ref_a;
  if (n == 0 && bs.chain_n.size() >= 2) {
    n = bs.chain_n[bs.chain_n.size() - 2];
    a = bs.chain_a[bs.chain_a.size() - 2];
  }
  if (n == 0) return kInf;
  const ChebyshevNodes nodes = chebyshev_nodes(n);
  const Problem::Linearised lin = prob.linearise(nodes, a);
  const int h = n / 2;
  Eigen::VectorXd g_full(n);
  const double scale = prob.g_scale(a, lin.load);
  for (int j = 0; j < h; ++j) g_full(j) = g_full(n - 1 - j) = scale * lin.G(j);
  Eigen::VectorXd c = u_coefficients(nodes, g_full);
  for (Eigen::Index m = 1; m < c.size(); m += 2) c(m) = 0.0;
  const double d = 2.0 * max_series_difference(b, c, SeriesKind::U);
  return std::isfinite(d) ? d : kInf;
}

}  // namespace

// The Filon route of the displacement: the Filon coefficients of f(alpha)
// ptilde(alpha), f = [M1 - phi1 (1 - e^-alpha)]/alpha and ptilde the exact
// transform of the Chebyshev series of p; the band of |f ptilde|; the nodes
// of the ln(1 + u^2) part.
struct SymmetricSolution::FilonDisplacement {
  std::mutex mutex;
  bool ready = false;
  std::vector<double> smooth_coef;
  // The wavenumber band of the displacement beside the contact (the gap
  // scan's sampling): of |f ptilde|, all but 1e-6 of its integral below it.
  double band = 0.0;
  // The Green's integral at the reference point (m0 != 0; medium.hpp).
  double greens_reference = 0.0;
  // Gauss-Chebyshev (U) nodes r_i of the ln(1 + (x - xi)^2) part and their
  // weights times sqrt(1 - r^2)^2 g(r_i).
  std::vector<double> log1p_r, log1p_w;
};

// The band of the displacement beside the contact on the table's route,
// which computes no pressure transform: the lowest panel edge A beyond which
// the displacement's waves, at most (2 load/pi) int_A^inf |f| |ptilde| (f the
// Green's function's smooth part), stay below 1e-8 of the indentation (a
// hundredth of the gap check's floor), with |ptilde(alpha)| <= Pb min(1/2,
// c (alpha a)^(-4/3)) at each panel's lower end: ptilde = (pi/2) a sum b_n (n + 1) i^n
// J_{n+1}(z)/z (z = alpha a), |J_nu(z)| <= min(z/2, 1) (nu >= 1) and
// Landau's |J_nu(z)| <= c z^(-1/3), c = 0.7858; Pb = (pi/2) a sum |b_n| (n + 1).
double table_band(const SymmetricSolution& sol, double load) {
  const KernelK1& k = sol.kernel();
  const AlphaQuadrature& q = k.quadrature();
  const std::vector<double>& mass = k.greens_panel_mass();
  const Eigen::VectorXd& b = sol.g_coefficients();
  const double a = sol.a();
  double pb = 0.0;
  for (Eigen::Index n = 0; n < b.size(); ++n) pb += std::fabs(b(n)) * static_cast<double>(n + 1);
  pb *= 0.5 * kPi * a;
  const double limit = 1e-8 * std::fabs(sol.indentation()) * kPi / (2.0 * load);
  double tail = 0.0;
  for (std::size_t i = mass.size(); i-- > 0;) {
    const double z = (q.panel_centre[i] - q.panel_half[i]) * a;
    const double envelope = pb * std::min(0.5, 0.7858 / (z * std::cbrt(z)));
    tail += mass[i] * envelope;
    if (tail > limit) return q.panel_centre[i] + q.panel_half[i];
  }
  return q.panel_centre.empty() ? 1.0 : q.panel_centre[0] - q.panel_half[0];
}

// The indentation delta = -v(0, 0) and the validity checks: p >= 0 on the
// contact (g >= 0, including a flat punch's end coefficients) and, beside a
// contact with bounded ends, no penetration on a < |x| <= 3a (within a table's
// extent). A flat punch has no surface beside its face (square corners):
// min_gap is +inf.
// A graded top (docs/theory.md section 16.5): the alpha integrals stop at
// alpha_max while the response reaches the half-plane's only like gamma/alpha.
// Bounds of what they leave out, from |r(alpha)| <= C/alpha beyond alpha_max
// (C measured at alpha_max and 2 alpha_max, the larger) and the transform of
// p, |p~(alpha)| <= E alpha^(-3/2) (the square-root ends; E sampled on
// [alpha_max, 64 alpha_max], doubled):
//  * the indentation, (2/pi) P int |p~| |M1 - phi1|/alpha: (2/pi) P C E (2/5) A^(-5/2);
//  * the surface sigma_x/(P/h), whose field quadrature stops at the reach of
//    the mode's exponential part (the remainder at y = 0 is C/alpha, not
//    exponentially small): (2/pi) C E (2/3) A^(-3/2), falling like
//    e^(nT A y) below the surface.
struct GradedTails {
  double indentation = 0.0;     // absolute, in the indentation's units
  double surface_stress = 0.0;  // absolute, sigma_x/(P/h) at y = 0
  double field_reach = 0.0;     // alpha_max h of the field quadrature
};

// max |p~(alpha)| alpha^(3/2) over [A, 64 A], doubled, for each A in `from`
// (p~ the cosine transform of the series b): one sweep over their union,
// 256 samples per factor 64 in alpha. Beyond alpha a ~ 400 the samples are
// farther apart than the transform's period 2 pi/a and fall at unrelated
// phases of it: the largest of 256 |cos| is below 0.95 with probability
// 0.8^256 ~ 1e-25, and the doubling covers the rest.
template <std::size_t K>
std::array<double, K> transform_envelopes(SeriesKind kind, double a, const Eigen::VectorXd& b,
                                          const std::array<double, K>& from) {
  constexpr double kPerFactor64 = 256.0;
  const double lo = *std::min_element(from.begin(), from.end());
  const double hi = 64.0 * *std::max_element(from.begin(), from.end());
  const int samples =
      1 + static_cast<int>(std::ceil(kPerFactor64 * std::log(hi / lo) / std::log(64.0)));
  std::vector<double> al(static_cast<std::size_t>(samples)), g(al.size());
  for (int i = 0; i < samples; ++i)
    al[static_cast<std::size_t>(i)] = lo * std::pow(hi / lo, i / (samples - 1.0));
  series_cosine_transforms(b, kind, a, al.data(), g.data(), g.size());
  std::array<double, K> e{};
  for (std::size_t k = 0; k < K; ++k) {
    for (std::size_t i = 0; i < al.size(); ++i)
      if (al[i] >= from[k] * (1.0 - 1e-12) && al[i] <= 64.0 * from[k] * (1.0 + 1e-12))
        e[k] = std::max(e[k], std::fabs(g[i]) * std::pow(al[i], 1.5));
    e[k] *= 2.0;
  }
  return e;
}

GradedTails graded_tails(const KernelK1& k, SeriesKind kind, double a, const Eigen::VectorXd& b,
                         double load) {
  GradedTails out;
  // The indentation: the kernel's quadrature (the displacement's panels);
  // the surface stress: the field quadrature's reach.
  const KernelK1::GradedTailConstants& c = k.graded_tail_constants();
  const double A = k.quadrature().alpha_max, Af = c.field_reach;
  const std::array<double, 2> env = transform_envelopes<2>(kind, a, b, {A, Af});
  out.indentation = 2.0 / kPi * load * c.surface_c * env[0] * 0.4 * std::pow(A, -2.5);
  out.field_reach = Af;
  out.surface_stress = 2.0 / kPi * c.field_c * env[1] * (2.0 / 3.0) * std::pow(Af, -1.5);
  return out;
}

void finish_checks(SymmetricSolution& sol, const ContactParams& p, const PunchProfile& prof) {
  const double a = sol.a_;
  const bool t_kind = sol.kind_ == SeriesKind::T;
  // Indentation: delta = -v(0, 0).
  sol.m0_ = sol.kernel_->model().long_wave_m1();
  sol.prepare_table();
  sol.delta_ = -sol.surface_displacement(0.0);
  if (!std::isfinite(sol.delta_))
    throw ConvergenceError("the indentation came out non-finite (N = " + std::to_string(sol.n_) +
                           "); the solution is not trusted");
  if (!sol.kernel_->singular().empty()) {
    const GradedTails t = graded_tails(*sol.kernel_, sol.kind_, a, sol.b_, p.load);
    if (!(t.indentation <= p.tol * std::fabs(sol.delta_)))
      sol.warnings_.push_back(
          "tol not met: the indentation on a graded top leaves out the displacement's "
          "gamma/alpha tail beyond alpha h = " +
          format_g(sol.kernel_->quadrature().alpha_max) + ", bounded by " +
          format_g(t.indentation) + " (" + format_g(t.indentation / std::fabs(sol.delta_)) +
          " relative, above tol = " + format_g(p.tol) + ")");
    if (!(t.surface_stress <= p.tol * std::fabs(sol.p0_)))
      sol.warnings_.push_back(
          "approximate near the surface: on a graded top the stresses at y = 0 leave out the "
          "mode remainder's gamma/alpha tail beyond alpha h = " +
          format_g(t.field_reach) +
          " (not counted in stress_error_estimate): sigma_x/(P/h) "
          "there may be off by up to " +
          format_g(t.surface_stress) + " (" + format_g(t.surface_stress / std::fabs(sol.p0_)) +
          " of p0), falling like exp(" + format_g(t.field_reach) +
          " nT y) below it; sigma_y = -p and tau = 0 there are exact");
  }

  // Validity: p >= 0 on the contact and no penetration on a < |x| <= 3a.
  double pmin = kInf, gmin = kInf, gmax = 0.0, x_pmin = 0.0;
  const bool even = odd_terms_zero(sol.b_);
  // An even g: the half r >= 0 (i <= 200) holds every value, each first.
  for (int i = 0, last = even ? 200 : 400; i <= last; ++i) {
    // cos(pi i/400) as sin(pi (200 - i)/400): the same points, exactly 0 on
    // the axis (cos(pi/2) is 6e-17: "near x/h = 1e-16" in the messages).
    const double r = std::sin(kPi * (200 - i) / 400.0);
    const double g = even ? even_series(sol.b_, r, sol.kind_) : series(sol.b_, r, sol.kind_);
    gmax = std::max(gmax, std::fabs(g));
    if (g < gmin) {
      gmin = g;
      x_pmin = a * r;
    }
    if (!t_kind)
      pmin = std::min(pmin, g * std::sqrt(std::max(0.0, 1.0 - r * r)));
    else if (i > 0 && i < 400)  // p = g / sqrt(1 - r^2) is infinite at the ends
      pmin = std::min(pmin, g / std::sqrt(1.0 - r * r));
  }
  sol.min_p_ = pmin;
  double r_margin = 0.0;
  if (sol.b_.size() > sol.n_) {
    // An extended series (extend_series): the minimum's place from the
    // collocated terms (the scan is dense in their degree), its value from all.
    series_minimum(sol.b_.head(sol.n_), sol.kind_, &r_margin);
    sol.p_margin_ = std::min(series(sol.b_, r_margin, sol.kind_), gmin);
  } else {
    sol.p_margin_ = series_minimum(sol.b_, sol.kind_, &r_margin);
  }
  double gap_min = kInf, x_gap = 0.0;
  if (!t_kind) {
    // On a < x <= 3a (up to a table's end: beyond, no punch to touch),
    // sampled to resolve the surface's shortest wave and refined at every
    // dip (gap_scan.hpp): near V*_cr on a stiff foundation the surface
    // carries waves shorter than a.
    const double x_end = std::min(3.0 * a, prof.extent());
    if (x_end > a) {
      // The band of the route the scan reads (the table's: from an
      // envelope of the pressure's transform, which it does not compute).
      const double step = detail::gap_step(
          x_end <= sol.table_reach_ ? table_band(sol, p.load) : sol.filon_displacement().band);
      const detail::GapMinimum m = detail::scan_gap_values(
          [&](double x) { return -sol.delta_ + prof.height(x) - sol.surface_displacement(x); }, a,
          x_end, step, 48, true);
      gap_min = m.gap;
      x_gap = m.x;
    }
    if (!std::isfinite(gap_min))
      throw ConvergenceError(
          "the gap outside the contact came out non-finite; the solution is not trusted");
  }
  sol.min_gap_ = gap_min;
  // The verdict is physical, never tol's: p < 0 beyond g's own error estimate
  // (g_err_: a fixed N's, from finer sizes) and a floor of 1e-6 of max |g|
  // (the converged ladder's g is good to far better; a loose tol does not
  // loosen the N ladder, which stops at 1e-8 or tighter), penetration beyond
  // the same relative floor or a/h's relative error estimate of the gap's
  // scale. (The slack once was 100 tol: tol = 5e-3 passed a flat punch with
  // p(0) = -0.9 as valid.)
  constexpr double kFloor = 1e-6;
  const double p_slack = std::max(kFloor * gmax, sol.g_err_);
  const double rel_a = t_kind ? 0.0 : sol.err_ / a;
  double gap_slack = 0.0;
  std::ostringstream why;
  why.precision(6);
  if (t_kind && sol.p_margin_ < -p_slack && std::fabs(r_margin) > 0.999) {
    sol.valid_ = false;
    why << "the pressure at the flat punch's edges is tensile (end coefficient " << sol.end_k_
        << "): the face lifts off at its edges and the single-contact "
        << "solution (the whole face in contact) is unphysical";
  } else if (gmin < -p_slack) {
    sol.valid_ = false;
    why << "the contact pressure is negative near x/h = " << x_pmin
        << " (the punch would pull on the layer): the contact separates and the "
           "single-contact solution is unphysical";
  } else if (!t_kind) {
    const double gap_scale = std::max(prof.height(a), std::fabs(sol.delta_));
    gap_slack = std::max(kFloor, rel_a) * gap_scale;
    if (gap_min < -gap_slack) {
      sol.valid_ = false;
      why << "the layer surface rises above the punch at x/h = " << x_gap << " (gap " << gap_min
          << " h): the punch would penetrate outside the contact "
             "and the single-contact solution is unphysical";
    }
  }
  if (sol.valid_) {
    sol.validity_ = t_kind ? "valid: p >= 0 on the punch's face (its edges included)"
                           : "valid: p >= 0 on the contact, no penetration for a < |x| <= 3a";
    if (!t_kind && prof.extent() < 3.0 * a) sol.validity_ += " (within the profile's table)";
    // Valid within its error estimate only: say so (a fixed N too small to
    // tell the sign).
    if (gmin < -kFloor * gmax) {
      sol.validity_ += " (up to the pressure's error estimate)";
      sol.warnings_.push_back(
          "the sign of the pressure is not resolved: g (p over its end factor, per P/h) reaches " +
          format_g(gmin) + " near x/h = " + format_g(x_pmin) + ", within its error estimate " +
          format_g(sol.g_err_) + " (N = " + std::to_string(sol.n_) +
          "); the contact may separate there: raise n or leave it automatic");
    }
    if (!t_kind && gap_min < -kFloor * std::max(prof.height(a), std::fabs(sol.delta_))) {
      sol.validity_ += " (no penetration up to a/h's error estimate)";
      sol.warnings_.push_back(
          "the layer surface rises above the punch at x/h = " + format_g(x_gap) + " (gap " +
          format_g(gap_min) + " h), within the error estimate of a/h (N = " +
          std::to_string(sol.n_) + "): raise n or leave it automatic");
    }
  } else {
    sol.validity_ = why.str();
    if (!p.allow_unphysical) {
      std::ostringstream m;
      m.precision(8);
      m << "vstar=" << p.vstar << ", ";
      if (p.medium && !p.medium->homogeneous())
        m << describe(*p.medium);
      else
        m << "kw=" << p.kw;
      if (prof.kind() == ProfileKind::cylinder)
        m << ", radius=" << p.radius;
      else
        m << ", profile: " << prof.describe();
      m << ", load=" << p.load << ", nu=" << p.nu << ": " << sol.validity_ << " (a/h = " << a
        << ")";
      throw UnphysicalContactError(m.str());
    }
  }
}

SymmetricSolution solve_contact(const ContactParams& p) {
  Timer timer;
  validate(p);
  const MediumSpec spec = medium_of(p);
  const double vr = rayleigh_vstar(spec.layers[0].nu);
  const CriticalSpeed crit = critical_speed(spec);
  const double t_critical = timer.seconds();
  if (p.vstar >= crit.vstar) {
    if (!spec.homogeneous() || spec.base.kp > 0.0)
      throw SupercriticalSpeedError(p.vstar, crit.vstar, vr, describe(spec));
    throw SupercriticalSpeedError(p.vstar, crit.vstar, vr);
  }

  const std::shared_ptr<const Medium> model = cached_medium(spec, p.vstar);
  const double phi1 = model->phi1();
  // Round-off of a/h (relative) from the layer response: within a hair of the
  // Rayleigh speed phi1 = nL / R(vstar) carries a relative error of about
  // eps phi1 (the Rayleigh function cancels), and so do M1 and k1. Measured
  // scatter of a/h over N = 64 ... 1024 (kw = inf, nu = 0.2, eps = 1e-10, 1e-12;
  // kw = 1000, nu = 0.499, eps = 3.4e-13): 0.5e-3 to 1.6e-3 eps phi1. Where it
  // exceeds tol, a/h cannot be resolved in double precision: say so at once.
  // The medium says how its M1 - phi1 carries that round-off
  // (Medium::roundoff_gain: a stack's M1 is not computed from phi1's own
  // closed form, so their errors do not cancel).
  const double roundoff =
      model->roundoff_gain() * std::numeric_limits<double>::epsilon() * std::fabs(phi1);
  if (roundoff > p.tol) {
    std::ostringstream m;
    m.precision(10);
    m << "vstar = " << p.vstar << " (" << describe(spec) << ", nu = " << spec.layers[0].nu
      << ") is within a relative " << 1.0 - p.vstar / vr << " of the Rayleigh speed V*_R = " << vr
      << ": the layer response there (phi1 = " << phi1
      << ") is computed with a round-off of ~eps*phi1, which limits a/h to a relative " << roundoff
      << ", above tol = " << p.tol
      << "; this is unsupported in double precision: raise tol or lower vstar";
    throw ConvergenceError(m.str());
  }
  // Tables grow with headroom (kernel.hpp) except within 1 % of V*_cr:
  // there the resonance's quadrature panels dominate the a/h error budget,
  // and a longer table (more panels) loosens it beyond the factor 100 of
  // issue 12 (tests/python/test_estimates.py).
  const PunchProfile prof(p.profile, p.radius, p.half_width, p.table_x, p.table_y);
  Problem prob(p, model, p.vstar < 0.99 * crit.vstar, prof);
  SymmetricSolution sol;
  sol.params_ = p;
  sol.vcr_ = crit.vstar;
  sol.vr_ = vr;
  sol.phi1_ = phi1;
  sol.profile_text_ = prof.describe();
  sol.field_cache_ = std::make_shared<SymmetricSolution::FieldCache>();
  sol.filon_ = std::make_shared<SymmetricSolution::FilonDisplacement>();
  double t_width = 0.0;
  if (prof.singular_ends()) {
    // A flat punch: the contact is its face, the pressure is linear in the
    // load (g over P/h does not depend on it), no width iteration.
    const double a = prof.face();
    const FlatSolve fs = solve_flat(prob, p, a);
    t_width = timer.seconds();
    sol.a_ = a;
    sol.kind_ = SeriesKind::T;
    sol.b_ = fs.b;
    sol.n_ = fs.n;
    sol.kernel_ = prob.kernel_ptr();
    sol.kernel_builds_ = prob.kernel_builds();
    sol.iterations_ = prob.evaluations();
    sol.p0_ = t_series(sol.b_, 0.0);
    const double root = std::sqrt(kPi * a);
    sol.end_k_ = t_series(sol.b_, 1.0) * root;
    sol.end_k_err_ = fs.error * root;
    sol.g_err_ = fs.g_error;
    sol.err_ = 0.0;  // the ends are the face's: exact
    sol.budget_ = {};
    const double scale = 1.0 / (kPi * a);  // g of the half-plane
    if (!(fs.error <= p.tol * std::max(scale, std::fabs(t_series(sol.b_, 1.0)))))
      sol.warnings_.push_back(
          "tol not met: the end coefficient's error estimate " + format_g(sol.end_k_err_) + " is " +
          format_g(fs.error / std::max(scale, std::fabs(t_series(sol.b_, 1.0)))) +
          " relative, above tol = " + format_g(p.tol) +
          " (the collocation size N = " + std::to_string(fs.n) + ")");
  } else {
    const BoundedSolve bs = solve_bounded(prob, p, prof, phi1);
    const double a = bs.a;
    const ChebyshevNodes& nodes = bs.nodes;
    const std::vector<int>& chain_n = bs.chain_n;
    const std::vector<double>& chain_a = bs.chain_a;
    double change = bs.change;
    t_width = timer.seconds();
    sol.kernel_builds_ = prob.kernel_builds();
    sol.a_ = a;
    sol.n_ = nodes.n;
    sol.kernel_ = prob.kernel_ptr();

    // Final unit solution at the converged a; g normalised by the load.
    const Problem::Linearised lin = prob.linearise(nodes, a);
    const Eigen::VectorXd& G = lin.G;
    const double load = lin.load;
    const int h = nodes.n / 2;
    Eigen::VectorXd g_full(nodes.n);
    const double scale = prob.g_scale(a, load);
    for (int j = 0; j < h; ++j) {
      g_full(j) = scale * G(j);
      g_full(nodes.n - 1 - j) = scale * G(j);
    }
    sol.b_ = u_coefficients(nodes, g_full);
    for (Eigen::Index m = 1; m < sol.b_.size(); m += 2) sol.b_(m) = 0.0;  // g is even
    sol.p0_ = u_series(sol.b_, 0.0);
    sol.kind_ = SeriesKind::U;
    if (p.n != 0) sol.g_err_ = fixed_size_g_error(prob, bs, sol.b_);
    sol.iterations_ = prob.evaluations();
    if (chain_a.size() >= 2 && std::isfinite(change) && !bs.extrapolated) {
      change = collocation_error(chain_n, chain_a, coefficient_rate(sol.b_));
      // A profile's kinks (a rounded flat's corners, a table's spline) make
      // the ends converge irregularly as N moves the nodes against them: a
      // geometric extrapolation from one large change to a small one can
      // claim far too much (a rounded flat on a 4-sublayer stack: 8.9e-13
      // claimed at N = 16, 3.8e-10 off). Never below the last change, as
      // the asymmetric solver's and the flat punch's estimates.
      if (prof.kind() != ProfileKind::cylinder)
        change = std::max(change, std::fabs(chain_a.back() - chain_a[chain_a.size() - 2]));
    }
    sol.budget_ =
        error_budget(prob, p, nodes, lin, a, change, roundoff, bs.extrapolated ? bs.raw_a : a);
    const SymmetricSolution::ErrorBudget& eb = sol.budget_;
    sol.err_ = eb.collocation + eb.root + eb.kernel + eb.roundoff;
    if (!(sol.err_ <= p.tol * a)) {
      // Name the largest part: that is what kept a/h from tol.
      const double parts[4] = {eb.collocation, eb.root, eb.kernel, eb.roundoff};
      const char* why[4] = {
          p.n != 0 ? "the fixed collocation size N is too small" : "the collocation size N",
          "the width iteration's residual",
          "the k1 kernel's quadrature round-off (near V*_cr the resonance of M1 is "
          "computed to ~eps |M1|)",
          "round-off of the collocation solve and of phi1"};
      int worst = 0;
      for (int i = 1; i < 4; ++i)
        if (!(parts[i] <= parts[worst])) worst = i;
      sol.warnings_.push_back("tol not met: a/h error estimate " + format_g(sol.err_) + " is " +
                              format_g(sol.err_ / a) + " relative, above tol = " + format_g(p.tol) +
                              " (mostly " + why[worst] + ", N = " + std::to_string(nodes.n) + ")");
    }

    if (!prob.cylinder()) extend_series(sol.b_, sol.trunc_, prof, a, phi1 * p.load);
    sol.p0_ = u_series(sol.b_, 0.0);
    const std::string kinks = kink_truncation_warning(
        sol.trunc_, sol.p0_, sol.profile_text_,
        prof.kind() == ProfileKind::rounded_flat ? a - prof.face() : std::nan(""));
    if (!kinks.empty()) sol.warnings_.push_back(kinks);
  }
  finish_checks(sol, p, prof);
  sol.elapsed_ = timer.seconds();
  sol.stage_seconds_ = {t_critical, prob.kernel_seconds(),
                        t_width - t_critical - prob.kernel_seconds(), sol.elapsed_ - t_width};
  return sol;
}

struct SymmetricSolution::FieldCache {
  std::mutex mutex;
  std::shared_ptr<const FieldEvaluator> evaluator;
};

std::shared_ptr<const FieldEvaluator> SymmetricSolution::field() const {
  std::lock_guard<std::mutex> lock(field_cache_->mutex);
  auto& ev = field_cache_->evaluator;
  if (!ev)
    ev = std::make_shared<const FieldEvaluator>(kernel_->medium(), a_, b_, kernel_->tol(), kind_);
  return ev;
}

StressField SymmetricSolution::stress_field(const Eigen::Ref<const Eigen::VectorXd>& x,
                                            const Eigen::Ref<const Eigen::VectorXd>& y,
                                            bool below) const {
  return field()->stresses(x, y, below);
}

Eigen::VectorXd SymmetricSolution::surface_stress(
    const Eigen::Ref<const Eigen::VectorXd>& x) const {
  const Eigen::VectorXd y0 = Eigen::VectorXd::Zero(1);
  return stress_field(x, y0).sigma_x.row(0).transpose();
}

Eigen::VectorXd SymmetricSolution::depth_stress(const Eigen::Ref<const Eigen::VectorXd>& y) const {
  const Eigen::VectorXd x0 = Eigen::VectorXd::Zero(1);
  return stress_field(x0, y).sigma_x.col(0);
}

Eigen::MatrixXd SymmetricSolution::displacement(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                const Eigen::Ref<const Eigen::VectorXd>& y) const {
  return params_.load * field()->displacement(x, y);
}

Eigen::VectorXd SymmetricSolution::foundation_reaction(
    const Eigen::Ref<const Eigen::VectorXd>& x) const {
  const Eigen::VectorXd yb = Eigen::VectorXd::Constant(1, -1.0);
  return -stress_field(x, yb).sigma_y.row(0).transpose();
}

double SymmetricSolution::pressure(double x) const {
  if (std::isnan(x)) throw std::invalid_argument("pressure: x must not be NaN");
  const double r = x / a_;
  if (kind_ == SeriesKind::T && std::fabs(r) == 1.0) {
    // A flat punch's edge: p = g(1)/sqrt(1 - r^2) is infinite there.
    const double g1 = t_series(b_, 1.0);
    return g1 == 0.0 ? 0.0 : std::copysign(std::numeric_limits<double>::infinity(), g1);
  }
  if (!(std::fabs(r) < 1.0)) return 0.0;
  if (kind_ == SeriesKind::T) return t_series(b_, r) / std::sqrt((1.0 - r) * (1.0 + r));
  return u_series(b_, r) * std::sqrt((1.0 - r) * (1.0 + r));
}

Eigen::VectorXd SymmetricSolution::pressure(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Eigen::VectorXd out(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) out(i) = pressure(x(i));
  return out;
}

const SymmetricSolution::FilonDisplacement& SymmetricSolution::filon_displacement() const {
  FilonDisplacement& out = *filon_;
  std::lock_guard<std::mutex> lock(out.mutex);
  if (out.ready) return out;
  const AlphaQuadrature& q = kernel_->quadrature();
  // f = [M1 - phi1 (1 - e^-alpha)]/alpha at the nodes. A half-space base:
  // M1 -> m0 != 0 as alpha -> 0; m0 e^-alpha/alpha is taken out too (its
  // cosine transform is a constant, dropped with the reference point, minus
  // (m0/2) ln(1 + u^2)).
  const std::size_t panels = q.panel_centre.size();
  std::vector<double> g(q.alpha.size());
  for (std::size_t i = 0; i < q.alpha.size(); ++i) {
    const double al = q.alpha[i];
    if (m0_ == 0.0)
      g[i] = (q.m1[i] - phi1_ * (-std::expm1(-al))) / al;
    else
      g[i] = (q.m1[i] - phi1_ * (-std::expm1(-al)) - m0_ * std::exp(-al)) / al;
  }
  // The panels reach alpha_max for k1 (|M1 - phi1| negligible); the
  // displacement's integrand f ptilde also carries the pressure's transform
  // ptilde (exact, per node: the costly part). Its Filon sums stop at the
  // panel beyond which the integral of |f ptilde| is below 2^-56 of its
  // whole, under the sums' own round-off: first by the bound |ptilde| <=
  // int_0^a |p| <= a (pi/2) sum |b_n| (n + 1) (kind U; kind T: a pi sum |b_n|)
  // times the rule's integral of |f| beyond (ptilde is evaluated only up to
  // there), then by the values themselves. (A thin top sublayer makes
  // alpha_max 5x the homogeneous layer's; ptilde at every node and the gap
  // scan's Filon sums over every panel then cost most of a solve.)
  // The rule's integral of |g| over panel p.
  const auto mass = [&](std::size_t p) {
    double m = 0.0;
    for (std::size_t i = 15 * p; i < 15 * p + 15; ++i) m += q.weight[i] * std::fabs(g[i]);
    return m;
  };
  std::vector<double> f_tail(panels + 1, 0.0);
  for (std::size_t p = panels; p-- > 0;) f_tail[p] = f_tail[p + 1] + mass(p);
  double p_bound = 0.0;
  for (Eigen::Index n = 0; n < b_.size(); ++n)
    p_bound += std::fabs(b_(n)) * (kind_ == SeriesKind::T ? 1.0 : static_cast<double>(n + 1));
  p_bound *= a_ * (kind_ == SeriesKind::T ? kPi : 0.5 * kPi);
  double total = 0.0;
  std::size_t keep = 0;
  std::vector<double> pt(q.alpha.size(), 0.0);  // ptilde at the kept panels' nodes
  while (keep < panels) {
    series_cosine_transforms(b_, kind_, a_, q.alpha.data() + 15 * keep, pt.data() + 15 * keep, 15);
    for (std::size_t j = 15 * keep; j < 15 * keep + 15; ++j) g[j] *= pt[j];
    total += mass(keep);
    ++keep;
    if (f_tail[keep] * p_bound <= 0x1p-56 * total) break;
  }
  double tail = 0.0;
  while (keep > 1) {
    const double panel = mass(keep - 1);
    if (!(tail + panel <= 0x1p-56 * total)) break;
    tail += panel;
    --keep;
  }
  g.resize(15 * keep);
  out.smooth_coef = kernel_->filon().coefficients(g);
  // The displacement's band (the gap scan's sampling, finish_checks): the
  // wavenumber below which all but 1e-6 of the integral of |f ptilde| lies.
  // (The band of |M1 - phi1| alone, without the pressure's transform, is
  // several times wider on a thin top: three times the samples.) On a graded
  // top, of f less the kernel's subtracted series, phi1 S(alpha) (1 -
  // e^-alpha)/alpha (S = sum b_k R_k, KernelSubtraction): that part's
  // displacement is p convolved with the cosine transform of a sum of
  // Laplace transforms on [0, L], int_0^L poly(s) s/(s^2 + u^2) ds, analytic
  // but at u = 0. Beside the contact (x > a) it is smooth, its only short
  // scale the distance to the contact's end, where the scan clusters its
  // points (scan_fractions): it carries no wave, and its slow gamma/alpha
  // tail (to alpha_max) made the scan 14 times denser than the surface's
  // waves need, the gap check 40 % of a solve.
  out.band = detail::response_band(q.alpha, q.weight, [&](std::size_t i) {
    if (i >= g.size()) return 0.0;
    const double al = q.alpha[i];
    const double s = i < q.sub.size() ? q.sub[i] : 0.0;
    return std::fabs(g[i] - phi1_ * s * (-std::expm1(-al)) / al * pt[i]);
  });
  // (phi1 / (2 pi)) int p ln(1 + (x - xi)^2) d xi by Gauss-Chebyshev (U)
  // quadrature: the nodes and g at them do not depend on x (potentials.hpp).
  detail::log1p_rule(b_, a_, out.log1p_r, out.log1p_w, kind_);
  out.ready = true;
  if (m0_ != 0.0) out.greens_reference = filon_integral(out, kDisplacementReference);
  return out;
}

// The table route (KernelK1::greens_tabulated). With G(u) = G_s(0) - phi1
// [K1(u) + ln|u|]: (1/pi) int p G(x - xi) = G_s(0) int p/pi - (phi1/pi)
// int p K1(x - xi) + the log part. K1(x - a r) is a polynomial of degree D
// in r: the terms of g above D are orthogonal to it (U: weight sqrt(1 -
// r^2); T: 1/sqrt(1 - r^2)), and Gauss-Chebyshev with M nodes, exact to
// degree 2M - 1, integrates g K1 exactly once 2M - 1 >= deg g + D.
void SymmetricSolution::prepare_table() {
  table_reach_ = -1.0;
  const KernelK1& k = *kernel_;
  if (!k.greens_tabulated() || k.range() <= a_) return;
  const int D = k.k1_integral_degree();
  Eigen::Index deg = std::min<Eigen::Index>(b_.size() - 1, D);
  while (deg > 0 && b_(deg) == 0.0) --deg;
  const Eigen::VectorXd b = b_.head(deg + 1);
  const int m = static_cast<int>(deg + D) / 2 + 1;
  // A scan of many points (bounded ends: the gap beside the contact) reads
  // the route that costs least per point: the table's m recurrences of D/2
  // steps against the Filon sum's ~100 steps per panel (measured).
  if (kind_ == SeriesKind::U && static_cast<double>(m) * (D / 2 + 1) >
                                    100.0 * static_cast<double>(k.quadrature().panel_centre.size()))
    return;
  table_r_.resize(static_cast<std::size_t>(m));
  table_w_.resize(static_cast<std::size_t>(m));
  for (int i = 1; i <= m; ++i) {
    const auto j = static_cast<std::size_t>(i - 1);
    if (kind_ == SeriesKind::T) {
      table_r_[j] = std::cos((2 * i - 1) * kPi / (2.0 * m));
      table_w_[j] = t_series(b, table_r_[j]) * kPi / m;
    } else {
      const double th = i * kPi / (m + 1), sn = std::sin(th);
      table_r_[j] = std::cos(th);
      table_w_[j] = sn * sn * u_series(b, table_r_[j]) * kPi / (m + 1);
    }
  }
  // int p/(P/h): a pi b0 (T) or a (pi/2) b0 (U).
  const double load_integral = a_ * b_(0) * (kind_ == SeriesKind::T ? kPi : 0.5 * kPi);
  table_const_ = k.greens_zero() * load_integral / kPi;
  table_reach_ = k.range() - a_;
  // The convolution is itself a polynomial in x, of degree D (even with g:
  // D/2 in y = T_2(x/X)), X the reach: interpolated at as many first-kind
  // nodes as it has terms it is exact (up to round-off), and each point of
  // the gap scan (about 60) then costs one short recurrence instead of m.
  // Where it has more terms than the scan has points, each point is summed.
  // (An even g, as every symmetric solve's: D/2 + 1 terms in y.)
  table_f_.clear();
  if (!odd_terms_zero(b_) || D / 2 + 1 > 48) return;
  const auto J = static_cast<std::size_t>(D / 2 + 1);
  std::vector<double> y(J), f(J);
  for (std::size_t i = 0; i < J; ++i) {
    y[i] = std::cos(kPi * (static_cast<double>(i) + 0.5) / static_cast<double>(J));
    f[i] = k1_convolution(table_reach_ * std::sqrt(0.5 * (1.0 + y[i])));
  }
  // c_j = (2 - [j = 0])/J sum_i f_i T_j(y_i), T_j by its recurrence.
  table_f_.assign(J, 0.0);
  for (std::size_t i = 0; i < J; ++i) {
    double t0 = 1.0, t1 = y[i];
    table_f_[0] += f[i];
    for (std::size_t j = 1; j < J; ++j) {
      table_f_[j] += f[i] * t1;
      const double t2 = 2.0 * y[i] * t1 - t0;
      t0 = t1;
      t1 = t2;
    }
  }
  for (std::size_t j = 0; j < J; ++j) table_f_[j] *= (j == 0 ? 1.0 : 2.0) / static_cast<double>(J);
}

// sum_j w_j K1(x - a r_j): the pressure against K1, exactly (prepare_table).
double SymmetricSolution::k1_convolution(double x) const {
  constexpr std::size_t kBatch = 64;
  std::array<double, kBatch> u{}, v{};
  double sum = 0.0;
  for (std::size_t i = 0; i < table_r_.size(); i += kBatch) {
    const std::size_t w = std::min(kBatch, table_r_.size() - i);
    for (std::size_t l = 0; l < w; ++l) u[l] = x - a_ * table_r_[i + l];
    kernel_->k1_integrals(u.data(), v.data(), w);
    for (std::size_t l = 0; l < w; ++l) sum += table_w_[i + l] * v[l];
  }
  return sum;
}

double SymmetricSolution::greens_table(double x) const {
  double f = 0.0;
  if (table_f_.empty()) {
    f = k1_convolution(x);
  } else {
    // sum_j c_j T_j(y), y = T_2(x/X).
    const double t = x / table_reach_;
    f = detail::chebyshev_sum(table_f_.data(), static_cast<int>(table_f_.size()) - 1,
                              2.0 * t * t - 1.0);
  }
  return table_const_ - phi1_ / kPi * a_ * f + log_part(x);
}

double SymmetricSolution::log_part(double x) const {
  // -(phi1/pi) int p ln|x - xi| = -phi1 a [ln a (b0/2) + sum b_n L_n(s)]
  // (T: (1/pi) int T_0/sqrt(1 - t^2) = 1, so ln a b0). The even terms at
  // once (one w for all: the series' log potential on the real axis, its
  // real part).
  const double s = x / a_;
  double lp = (kind_ == SeriesKind::T ? 1.0 : 0.5) * b_(0) * std::log(a_);
  lp += detail::log_potential(b_, detail::cplx_t(s, 0.0), 2, kind_).real();
  return -phi1_ * a_ * lp;
}

// (1/pi) int p(xi)/(P/h) G(x - xi) d xi with G(u) = int_0^inf (M1/alpha) cos(alpha u)
// d alpha, split as int [M1 - phi1 (1 - e^-alpha)]/alpha cos + (phi1/2) ln(1 + 1/u^2)
// (a half-space base: [M1 - phi1 (1 - e^-alpha) - m0 e^-alpha]/alpha, and
// -(m0/2) ln(1 + u^2) up to a constant; beyond kFarField the smooth part is 0).
double SymmetricSolution::filon_integral(const FilonDisplacement& f, double x) const {
  const double smooth = std::fabs(x) > kFarField
                            ? 0.0
                            : 2.0 / kPi * kernel_->filon().integral(x, f.smooth_coef).real();
  // (phi1 / (2 pi)) int p ln(1 + (x - xi)^2) d xi on the precomputed nodes:
  // int sqrt(1 - r^2) g(r) ln(1 + (x - a r)^2) dr.
  const double l1 = detail::log1p_sum(f.log1p_r, f.log1p_w, a_, x);
  const double log1p_part = (phi1_ - m0_) / (2.0 * kPi) * a_ * l1;
  return smooth + log_part(x) + log1p_part;
}

double SymmetricSolution::greens_integral(double x) const {
  if (std::fabs(x) <= table_reach_) return greens_table(x);
  return filon_integral(filon_displacement(), x);
}

double SymmetricSolution::surface_displacement(double x) const {
  if (!std::isfinite(x)) throw std::invalid_argument("surface_displacement: x must be finite");
  if (m0_ != 0.0) {
    const FilonDisplacement& f = filon_displacement();
    return -params_.load * (filon_integral(f, x) - f.greens_reference);
  }
  if (std::fabs(x) > kFarField) return 0.0;  // see stresses.hpp
  return -params_.load * greens_integral(x);
}

Eigen::VectorXd SymmetricSolution::surface_displacement(
    const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Eigen::VectorXd out(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) out(i) = surface_displacement(x(i));
  return out;
}

}  // namespace movingpunch

// Gauss-Jacobi collocation and the closed-form integrals of Jacobi densities
// (the sliding punch with Coulomb friction; docs/theory.md section 14).
#include "movingpunch/jacobi.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>

#include <Eigen/Eigenvalues>

namespace movingpunch {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TangentialHalfPlane tangential_half_plane(const WaveConstants& c) {
  // The downward-decaying shear and dilatational modes a v_T + b v_L with top
  // T = 1, S = 0 (v_T = [1, -1/nT, (1 + nT^2)/nT, -2], v_L = [1, -nL, 2 nL, -(2 - s)]):
  // b = 2 nT/(s D'), a = -(2 - s) b/2, written without the 0/0 at s = 0 through
  // 4 nL nT - (2 - s)^2 = s D' and 2 - s - 2 nL nT = s (2X/(1 + Y) - 1).
  const double s = c.s, X = 1.0 + 1.0 / c.c2 - s / c.c2, Y = c.nL * c.nT;
  const double den = 4.0 - s - 4.0 * X / (1.0 + Y);
  TangentialHalfPlane t;
  t.Uq = c.nT / den;
  t.Wq = (2.0 * X / (1.0 + Y) - 1.0) / den;
  t.Phi = (2.0 * X / (1.0 + Y) - 1.0) / c.nL;
  return t;
}

EndExponents end_exponents(double f, double Phi) {
  const double q = f * Phi;
  if (!std::isfinite(q)) throw std::invalid_argument("end_exponents: f Phi must be finite");
  EndExponents e;
  e.front = 0.5 + std::atan(q) / kPi;
  e.back = 0.5 - std::atan(q) / kPi;
  return e;
}

namespace {
// sum_k c_k P_{k + shift}^(a, b)(z) and its derivative (*dsum, if given) by
// the three-term recurrence, real or complex z; any a, b with a + b != -2.
template <class T>
T jacobi_series(const Eigen::VectorXd& c, double a, double b, T z, int shift, T* dsum) {
  const int n = static_cast<int>(c.size());
  T p0 = 1.0, p1 = 0.5 * ((a + b + 2.0) * z + (a - b)), d0 = 0.0, d1 = 0.5 * (a + b + 2.0);
  T sum = 0.0, ds = 0.0;
  auto add = [&](int degree, const T& p, const T& d) {
    const int k = degree - shift;
    if (k >= 0 && k < n) {
      sum += c(k) * p;
      ds += c(k) * d;
    }
  };
  add(0, p0, d0);
  add(1, p1, d1);
  for (int k = 1; k < n + shift - 1; ++k) {
    const double kk = k, s = 2.0 * kk + a + b;
    const double c0 = 2.0 * (kk + 1.0) * (kk + a + b + 1.0) * s;
    const T c1 = (s + 1.0) * ((s + 2.0) * s * z + a * a - b * b);
    const double c1x = (s + 1.0) * (s + 2.0) * s;
    const double c2 = 2.0 * (kk + a) * (kk + b) * (s + 2.0);
    const T p2 = (c1 * p1 - c2 * p0) / c0;
    const T d2 = (c1 * d1 + c1x * p1 - c2 * d0) / c0;
    p0 = p1;
    p1 = p2;
    d0 = d1;
    d1 = d2;
    add(k + 1, p1, d1);
  }
  if (dsum) *dsum = ds;
  return sum;
}
}  // namespace

void jacobi_p(int n, double a, double b, double x, double* p, double* dp) {
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(n + 1);
  unit(n) = 1.0;
  *p = jacobi_series(unit, a, b, x, 0, dp);
}

Eigen::VectorXd jacobi_zeros(int n, double a, double b) {
  if (n < 1) throw std::invalid_argument("jacobi_zeros: n must be >= 1");
  Eigen::VectorXd diag(n), sub(std::max(n - 1, 0));
  for (int k = 0; k < n; ++k) {
    const double s = 2.0 * k + a + b;
    diag(k) = k == 0 ? (b - a) / (a + b + 2.0) : (b * b - a * a) / (s * (s + 2.0));
  }
  for (int k = 1; k < n; ++k) {
    const double kk = k, s = 2.0 * kk + a + b;
    double bk;
    if (k == 1)
      bk = 4.0 * (1.0 + a) * (1.0 + b) / ((2.0 + a + b) * (2.0 + a + b) * (3.0 + a + b));
    else
      bk = 4.0 * kk * (kk + a) * (kk + b) * (kk + a + b) / (s * s * (s + 1.0) * (s - 1.0));
    sub(k - 1) = std::sqrt(bk);
  }
  Eigen::VectorXd x(n);
  if (n == 1) {
    x(0) = diag(0);
  } else {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es;
    es.computeFromTridiagonal(diag, sub, Eigen::EigenvaluesOnly);
    x = es.eigenvalues();
  }
  for (int i = 0; i < n; ++i) {  // Newton polish
    for (int it = 0; it < 3; ++it) {
      double p, dp;
      jacobi_p(n, a, b, x(i), &p, &dp);
      if (dp == 0.0) break;
      const double step = p / dp;
      x(i) -= step;
      if (std::fabs(step) < 1e-17) break;
    }
  }
  std::sort(x.data(), x.data() + n);
  return x;
}

JacobiRule gauss_jacobi(int n, double a, double b) {
  if (!(a > -1.0) || !(b > -1.0)) throw std::invalid_argument("gauss_jacobi: need a, b > -1");
  JacobiRule r;
  r.x = jacobi_zeros(n, a, b);
  r.w.resize(n);
  const double ln_c = (a + b + 1.0) * std::log(2.0) + std::lgamma(n + a + 1.0) +
                      std::lgamma(n + b + 1.0) - std::lgamma(n + a + b + 1.0) -
                      std::lgamma(n + 1.0);
  const double cst = std::exp(ln_c);
  for (int i = 0; i < n; ++i) {
    double p, dp;
    jacobi_p(n, a, b, r.x(i), &p, &dp);
    r.w(i) = cst / ((1.0 - r.x(i) * r.x(i)) * dp * dp);
  }
  return r;
}

std::shared_ptr<const JacobiRule> cached_gauss_jacobi(int n, double a, double b) {
  static std::mutex mu;
  static std::map<std::tuple<int, double, double>, std::shared_ptr<const JacobiRule>> cache;
  {
    const std::lock_guard<std::mutex> lock(mu);
    const auto it = cache.find({n, a, b});
    if (it != cache.end()) return it->second;
  }
  // Built outside the lock (another thread may build the same rule: both
  // are the same); a holder keeps its rule alive when the cache is emptied.
  auto rule = std::make_shared<const JacobiRule>(gauss_jacobi(n, a, b));
  const std::lock_guard<std::mutex> lock(mu);
  if (cache.size() >= 256) cache.clear();  // a long sweep over many exponents
  cache.emplace(std::make_tuple(n, a, b), rule);
  return rule;
}

ChebyshevNodes jacobi_collocation_nodes(int n, double alpha) {
  if (n < 2) throw std::invalid_argument("jacobi_collocation_nodes: n must be >= 2");
  if (!(alpha > 0.0 && alpha < 1.0))
    throw std::invalid_argument("jacobi_collocation_nodes: alpha must be in (0, 1)");
  const double beta = 1.0 - alpha;
  const JacobiRule rule = gauss_jacobi(n, alpha, beta);
  ChebyshevNodes nd;
  nd.n = n;
  // Descending, as chebyshev_nodes (r_1 = cos(pi/(N + 1)) is the largest).
  nd.r = rule.x.reverse();
  nd.w = rule.w.reverse() / kPi;
  nd.s = jacobi_zeros(n + 1, -alpha, -beta).reverse();
  return nd;
}

ChebyshevNodes jacobi_flat_nodes(int n, double alpha, double beta) {
  if (n < 2) throw std::invalid_argument("jacobi_flat_nodes: n must be >= 2");
  if (!(alpha > -1.0 && alpha < 0.0) || !(std::fabs(alpha + beta + 1.0) <= 1e-12))
    throw std::invalid_argument("jacobi_flat_nodes: need alpha in (-1, 0) and alpha + beta = -1");
  const JacobiRule rule = gauss_jacobi(n, alpha, beta);
  ChebyshevNodes nd;
  nd.n = n;
  nd.r = rule.x.reverse();
  nd.w = rule.w.reverse() / kPi;
  nd.s = jacobi_zeros(n - 1, -alpha, -beta).reverse();
  return nd;
}

namespace {
// The norm h_n = int w P_n^2 (alpha + beta = 1 or -1). n = 0 apart: the
// general formula's 1/((a + b + 1) Gamma(a + b + 1)) is 0 * inf at a + b = -1
// (its limit 1/Gamma(a + b + 2)).
double jacobi_norm(int n, double a, double b) {
  if (n == 0)
    return std::exp((a + b + 1.0) * std::log(2.0) + std::lgamma(a + 1.0) + std::lgamma(b + 1.0) -
                    std::lgamma(a + b + 2.0));
  return std::exp((a + b + 1.0) * std::log(2.0) - std::log(2.0 * n + a + b + 1.0) +
                  std::lgamma(n + a + 1.0) + std::lgamma(n + b + 1.0) -
                  std::lgamma(n + a + b + 1.0) - std::lgamma(n + 1.0));
}

}  // namespace

JacobiSeries::JacobiSeries(double alpha, Eigen::VectorXd c)
    : JacobiSeries(alpha, 1.0 - alpha, std::move(c)) {}

JacobiSeries::JacobiSeries(double alpha, double beta, Eigen::VectorXd c)
    : alpha_(alpha), beta_(beta), c_(std::move(c)) {
  const bool bounded = std::fabs(alpha + beta - 1.0) <= 1e-12 && alpha > 0.0 && alpha < 1.0;
  const bool singular = std::fabs(alpha + beta + 1.0) <= 1e-12 && alpha > -1.0 && alpha < 0.0;
  if (!bounded && !singular)
    throw std::invalid_argument(
        "JacobiSeries: need alpha + beta = 1 with alpha in (0, 1), or alpha + beta = -1 with "
        "alpha in (-1, 0)");
  const auto held = cached_gauss_jacobi(size() + 60, alpha_, beta_);
  const JacobiRule& rule = *held;
  far_x_ = rule.x;
  far_wg_.resize(rule.x.size());
  for (Eigen::Index i = 0; i < rule.x.size(); ++i) far_wg_(i) = rule.w(i) * g(rule.x(i));
}

JacobiSeries JacobiSeries::from_nodes(double alpha, const Eigen::VectorXd& r,
                                      const Eigen::VectorXd& g) {
  return from_nodes(alpha, 1.0 - alpha, r, g);
}

JacobiSeries JacobiSeries::from_nodes(double alpha, double beta, const Eigen::VectorXd& r,
                                      const Eigen::VectorXd& g) {
  const int n = static_cast<int>(r.size());
  // Gauss-Jacobi weights at the nodes (recomputed from the formula).
  const JacobiRule rule = gauss_jacobi(n, alpha, beta);
  // Match the nodes' order (r may be descending).
  Eigen::VectorXd gv(n);
  const bool descending = n > 1 && r(0) > r(n - 1);
  for (int i = 0; i < n; ++i) gv(i) = descending ? g(n - 1 - i) : g(i);
  Eigen::VectorXd c(n);
  for (int k = 0; k < n; ++k) {
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      double p;
      jacobi_p(k, alpha, beta, rule.x(i), &p);
      sum += rule.w(i) * gv(i) * p;
    }
    c(k) = sum / jacobi_norm(k, alpha, beta);
  }
  return JacobiSeries(alpha, beta, c);
}

double JacobiSeries::g(double r) const {
  return jacobi_series(c_, alpha_, beta(), r, 0, static_cast<double*>(nullptr));
}

double JacobiSeries::weight(double r) const {
  if (!(std::fabs(r) <= 1.0)) return 0.0;
  return std::pow(1.0 - r, alpha_) * std::pow(1.0 + r, beta());
}

double JacobiSeries::density(double r) const {
  const double w = weight(r);
  return w == 0.0 ? 0.0 : w * g(r);
}

double JacobiSeries::moment0() const {
  return c_.size() ? c_(0) * jacobi_norm(0, alpha_, beta()) : 0.0;
}

double JacobiSeries::moment1() const {
  // r = (2 P_1 - (a - b))/(a + b + 2) (a + b + 2 = 3, or 1 for index +1).
  const double a = alpha_, b = beta(), d = a + b + 2.0;
  double m = -(a - b) / d * moment0();
  if (c_.size() > 1) m += 2.0 / d * c_(1) * jacobi_norm(1, a, b);
  return m;
}

double JacobiSeries::cauchy(double x) const {
  const double a = alpha_, b = beta();
  const double sa = std::sin(kPi * a);
  // sum c_n P_{n+1}^(-a,-b)(x) (index -1), sum c_n P_{n-1}^(-a,-b)(x) (index +1).
  const double poly = jacobi_series(c_, -a, -b, x, shift(), static_cast<double*>(nullptr));
  const double q = poly_factor();
  if (std::fabs(x) < 1.0 || (!singular() && std::fabs(x) == 1.0))
    return std::cos(kPi * a) / sa * density(x) - q / sa * poly;
  if (std::fabs(x) == 1.0) {
    // A singular series' end: w g/(t - x) is not integrable at t = x unless
    // the cot term vanishes (alpha = -1/2) or g(x) = 0; else infinite.
    const double cot = std::cos(kPi * a) / sa, gx = g(x);
    if (std::fabs(cot) < 1e-15 || gx == 0.0) return -q / sa * poly;
    const double side = x > 0.0 ? std::pow(2.0, b) : std::pow(2.0, a);
    return cot * gx * side * std::numeric_limits<double>::infinity();
  }
  const double rmax = closed_form_radius();
  if (std::fabs(x) < 0.5 * (rmax + 1.0 / rmax)) {  // rho(x) < rmax (1.2 for rmax = 1.86)
    const double Z =
        (x > 0 ? 1.0 : -1.0) * std::pow(std::fabs(x - 1.0), a) * std::pow(std::fabs(x + 1.0), b);
    return (Z * g(x) - q * poly) / sa;
  }
  double sum = 0.0;
  for (Eigen::Index i = 0; i < far_x_.size(); ++i) sum += far_wg_(i) / (far_x_(i) - x);
  return sum / kPi;
}

std::complex<double> JacobiSeries::cauchy_upper(std::complex<double> z,
                                                std::complex<double>* derivative) const {
  using C = std::complex<double>;
  const double a = alpha_, b = beta();
  const C root = std::sqrt(z - 1.0) * std::sqrt(z + 1.0);
  const double rho = std::max(std::abs(z + root), std::abs(z - root));
  if (rho < closed_form_radius()) {
    const double sa = std::sin(kPi * a);
    const C Z = std::pow(z - 1.0, a) * std::pow(z + 1.0, b);
    C dg, dpoly;
    const C gz = jacobi_series(c_, a, b, z, 0, &dg);
    const C poly = jacobi_series(c_, -a, -b, z, shift(), &dpoly);
    const double q = poly_factor();
    if (derivative) {
      const C dZ = Z * (a / (z - 1.0) + b / (z + 1.0));
      *derivative = (dZ * gz + Z * dg - q * dpoly) / sa;
    }
    return (Z * gz - q * poly) / sa;
  }
  C sum = 0.0, dsum = 0.0;
  for (Eigen::Index i = 0; i < far_x_.size(); ++i) {
    const C d = 1.0 / (far_x_(i) - z);
    sum += far_wg_(i) * d;
    dsum += far_wg_(i) * d * d;
  }
  if (derivative) *derivative = dsum / kPi;
  return sum / kPi;
}

double JacobiSeries::closed_form_radius() const {
  // The closed form's terms grow like rho^N off the cut: their round-off
  // (eps |c| rho^N) stays below 1e-11 |c| for rho^N <= 1e5, where the far
  // rule of N + 60 nodes is already accurate to rho^(-2 (N + 60)) < 1e-10.
  const double n = std::max(1.0, static_cast<double>(size()));
  return std::min(1.86, std::pow(10.0, 5.0 / n));
}

JacobiSeries JacobiSeries::minus(const JacobiSeries& other) const {
  const Eigen::Index n = std::max(c_.size(), other.c_.size());
  Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
  d.head(c_.size()) += c_;
  d.head(other.c_.size()) -= other.c_;
  return JacobiSeries(alpha_, beta_, d);
}

double JacobiSeries::max_abs_density() const {
  const int m = 8 * (size() + 1) + 64;
  double best = 0.0;
  for (int j = 0; j <= m; ++j) best = std::max(best, std::fabs(density(std::cos(kPi * j / m))));
  return best;
}

double JacobiSeries::max_abs_g() const {
  const int m = 8 * (size() + 1) + 64;
  double best = 0.0;
  for (int j = 0; j <= m; ++j) best = std::max(best, std::fabs(g(std::cos(kPi * j / m))));
  return best;
}

double JacobiSeries::min_g() const {
  const int m = std::max(401, 16 * (size() + 1) + 257);
  int jb = 0;
  double best = std::numeric_limits<double>::infinity();
  for (int j = 0; j <= m; ++j) {
    const double v = g(std::cos(kPi * j / m));
    if (v < best) {
      best = v;
      jb = j;
    }
  }
  // Golden section in theta between the neighbours.
  double lo = kPi * std::max(0, jb - 1) / m, hi = kPi * std::min(m, jb + 1) / m;
  const double gr = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
  double f1 = g(std::cos(x1)), f2 = g(std::cos(x2));
  for (int it = 0; it < 80 && hi - lo > 1e-15; ++it) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - gr * (hi - lo);
      f1 = g(std::cos(x1));
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + gr * (hi - lo);
      f2 = g(std::cos(x2));
    }
  }
  return std::min({best, f1, f2});
}

JacobiTransform::JacobiTransform(const JacobiSeries& s, double omega_max,
                                 const JacobiSeries* second) {
  const int m = s.size() + static_cast<int>(std::ceil(std::fabs(omega_max))) + 40;
  rule_ = *cached_gauss_jacobi(m, s.alpha(), s.beta());
  gw_.resize(m);
  gw2_ = Eigen::VectorXd::Zero(m);
  for (int i = 0; i < m; ++i) {
    gw_(i) = rule_.w(i) * s.g(rule_.x(i));
    if (second) gw2_(i) = rule_.w(i) * second->g(rule_.x(i));
  }
}

std::complex<double> JacobiTransform::sum(const Eigen::VectorXd& gw, double omega) const {
  std::complex<double> out = 0.0;
  for (Eigen::Index i = 0; i < gw.size(); ++i)
    out +=
        gw(i) * std::complex<double>(std::cos(omega * rule_.x(i)), -std::sin(omega * rule_.x(i)));
  return out;
}

}  // namespace movingpunch

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
// The recurrence P_0 = 1, P_1 = A_0 z + B_0, P_{k+1} = (A_k z + B_k) P_k -
// C_k P_{k-1} (k >= 1) of P^(a, b), for degrees up to `top` (the coefficients
// of jacobi_p's recurrence, divided once).
struct Recurrence {
  std::vector<double> A, B, C;
};

Recurrence recurrence(double a, double b, int top) {
  Recurrence r;
  const std::size_t len = static_cast<std::size_t>(std::max(top, 1));
  r.A.resize(len);
  r.B.resize(len);
  r.C.resize(len);
  r.A[0] = 0.5 * (a + b + 2.0);
  r.B[0] = 0.5 * (a - b);
  r.C[0] = 0.0;
  for (std::size_t k = 1; k < len; ++k) {
    const double kk = static_cast<double>(k), s = 2.0 * kk + a + b;
    const double c0 = 2.0 * (kk + 1.0) * (kk + a + b + 1.0) * s;
    r.A[k] = (s + 1.0) * (s + 2.0) * s / c0;
    r.B[k] = (s + 1.0) * (a * a - b * b) / c0;
    r.C[k] = 2.0 * (kk + a) * (kk + b) * (s + 2.0) / c0;
  }
  return r;
}

// sum_k c_k P_{k + shift}(z) (and its derivative into *dsum, if given) by the
// recurrence R (covering degree n - 1 + shift).
template <class T>
T recurrence_series(const Recurrence& R, const Eigen::VectorXd& c, T z, int shift, T* dsum) {
  const int n = static_cast<int>(c.size());
  const int top = n - 1 + shift;  // the highest degree summed
  T sum = 0.0, ds = 0.0;
  if (n == 0 || top < 0) {
    if (dsum) *dsum = ds;
    return sum;
  }
  T p0 = 1.0, p1 = R.A[0] * z + R.B[0];
  if (-shift >= 0 && -shift < n) sum += c(-shift);
  if (top >= 1 && 1 - shift < n) sum += c(1 - shift) * p1;
  if (dsum) {
    T d0 = 0.0, d1 = R.A[0];
    if (top >= 1 && 1 - shift < n) ds += c(1 - shift) * d1;
    for (int k = 1; k < top; ++k) {
      const T f = R.A[static_cast<std::size_t>(k)] * z + R.B[static_cast<std::size_t>(k)];
      const double C = R.C[static_cast<std::size_t>(k)];
      const T p2 = f * p1 - C * p0;
      const T d2 = f * d1 + R.A[static_cast<std::size_t>(k)] * p1 - C * d0;
      p0 = p1;
      p1 = p2;
      d0 = d1;
      d1 = d2;
      const double ck = c(k + 1 - shift);
      sum += ck * p1;
      ds += ck * d1;
    }
    *dsum = ds;
    return sum;
  }
  for (int k = 1; k < top; ++k) {
    const T p2 = (R.A[static_cast<std::size_t>(k)] * z + R.B[static_cast<std::size_t>(k)]) * p1 -
                 R.C[static_cast<std::size_t>(k)] * p0;
    p0 = p1;
    p1 = p2;
    sum += c(k + 1 - shift) * p1;
  }
  return sum;
}
}  // namespace

namespace {
constexpr int kLanes = 8;
// P_n^(a, b) and its derivative at count <= kLanes points together by the
// three-term recurrence (any a, b with a + b != -2), each step's
// coefficients computed once for all the points and no allocation (a rule of
// a thousand nodes evaluates P_n at each node three to five times; jacobi_p
// is its one-lane case).
template <int L = kLanes>
void jacobi_p_lanes(int n, double a, double b, const double* x, int count, double* p, double* dp) {
  double z[L], p0[L], p1[L], d0[L], d1[L];
  for (int l = 0; l < L; ++l) {
    z[l] = l < count ? x[l] : 0.0;
    p0[l] = 1.0;
    p1[l] = 0.5 * ((a + b + 2.0) * z[l] + (a - b));
    d0[l] = 0.0;
    d1[l] = 0.5 * (a + b + 2.0);
  }
  for (int k = 1; k < n; ++k) {
    const double kk = k, s = 2.0 * kk + a + b;
    const double c0 = 2.0 * (kk + 1.0) * (kk + a + b + 1.0) * s;
    const double c1x = (s + 1.0) * (s + 2.0) * s;
    const double c2 = 2.0 * (kk + a) * (kk + b) * (s + 2.0);
    for (int l = 0; l < L; ++l) {
      const double c1 = (s + 1.0) * ((s + 2.0) * s * z[l] + a * a - b * b);
      const double p2 = (c1 * p1[l] - c2 * p0[l]) / c0;
      const double d2 = (c1 * d1[l] + c1x * p1[l] - c2 * d0[l]) / c0;
      p0[l] = p1[l];
      p1[l] = p2;
      d0[l] = d1[l];
      d1[l] = d2;
    }
  }
  for (int l = 0; l < count; ++l) {
    p[l] = n == 0 ? 1.0 : p1[l];
    dp[l] = n == 0 ? 0.0 : d1[l];
  }
}
}  // namespace

void jacobi_p(int n, double a, double b, double x, double* p, double* dp) {
  double d = 0.0;
  jacobi_p_lanes<1>(n, a, b, &x, 1, p, &d);
  if (dp) *dp = d;
}

namespace {
// Newton's method on P_n from the guesses x, kLanes nodes at a time, at most
// `steps` steps a node (a node stops once its step is below `done`). Returns
// the largest last step taken.
double newton_zeros(int n, double a, double b, Eigen::VectorXd& x, int steps, double done) {
  double worst = 0.0;
  for (int i0 = 0; i0 < n; i0 += kLanes) {
    const int count = std::min(kLanes, n - i0);
    bool active[kLanes];
    double last[kLanes] = {};
    for (int l = 0; l < kLanes; ++l) active[l] = l < count;
    for (int it = 0; it < steps; ++it) {
      double p[kLanes], dp[kLanes];
      jacobi_p_lanes(n, a, b, x.data() + i0, count, p, dp);
      bool any = false;
      for (int l = 0; l < count; ++l) {
        if (!active[l]) continue;
        if (dp[l] == 0.0) {
          active[l] = false;
          last[l] = std::numeric_limits<double>::infinity();
          continue;
        }
        const double step = p[l] / dp[l];
        x(i0 + l) -= step;
        last[l] = std::fabs(step);
        if (std::fabs(step) < done) active[l] = false;
        any = any || active[l];
      }
      if (!any) break;
    }
    for (int l = 0; l < count; ++l) worst = std::max(worst, last[l]);
  }
  return worst;
}

// The zeros from Gatteschi and Pittaluga's asymptotic approximation
// (accurate to O(n^-4) inside, |a|, |b| <= 1/2 best; Szego, Orthogonal
// Polynomials, section 8.9): theta_k = phi_k + [(1/4 - a^2) cot(phi_k/2) -
// (1/4 - b^2) tan(phi_k/2)]/(2 rho)^2, phi_k = (k + a/2 - 1/4) pi/rho,
// rho = n + (a + b + 1)/2, x_k = cos theta_k; then Newton until a step is
// below 1e-13 (the next would be below C 1e-26, C = |P''/(2 P')| <= n^3 at
// the ends: round-off). O(n^2) with a small constant (the eigenvalues cost
// several times as much at n = 1000). False unless every node converged to
// n distinct zeros in (-1, 1): the caller then takes the eigenvalues.
bool asymptotic_zeros(int n, double a, double b, Eigen::VectorXd& x) {
  const double rho = n + 0.5 * (a + b + 1.0);
  x.resize(n);
  for (int k = 1; k <= n; ++k) {
    const double phi = (k + 0.5 * a - 0.25) * kPi / rho, t = std::tan(0.5 * phi);
    const double th = phi + ((0.25 - a * a) / t - (0.25 - b * b) * t) / (4.0 * rho * rho);
    x(k - 1) = std::cos(std::clamp(th, 0.0, kPi));
  }
  const double worst = newton_zeros(n, a, b, x, 10, 1e-13);
  std::sort(x.data(), x.data() + n);
  if (!(worst < 1e-13)) return false;
  for (int i = 0; i < n; ++i)
    if (!(std::fabs(x(i)) < 1.0) || (i > 0 && !(x(i) - x(i - 1) > 1e-12))) return false;
  return true;
}
}  // namespace

Eigen::VectorXd jacobi_zeros(int n, double a, double b) {
  if (n < 1) throw std::invalid_argument("jacobi_zeros: n must be >= 1");
  Eigen::VectorXd x(n);
  // Large rules (a long series' far-field and arctan rules, a profile's
  // projections) from the asymptotic guesses; small ones, and any the
  // guesses fail, from the Jacobi matrix's eigenvalues.
  if (n >= 32 && std::fabs(a) <= 1.0 && std::fabs(b) <= 1.0 && asymptotic_zeros(n, a, b, x))
    return x;
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
  if (n == 1) {
    x(0) = diag(0);
  } else {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es;
    es.computeFromTridiagonal(diag, sub, Eigen::EigenvaluesOnly);
    x = es.eigenvalues();
  }
  newton_zeros(n, a, b, x, 3, 1e-17);  // polish
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
  for (int i0 = 0; i0 < n; i0 += kLanes) {
    const int count = std::min(kLanes, n - i0);
    double p[kLanes], dp[kLanes];
    jacobi_p_lanes(n, a, b, r.x.data() + i0, count, p, dp);
    for (int l = 0; l < count; ++l) {
      const double xi = r.x(i0 + l);
      r.w(i0 + l) = cst / ((1.0 - xi * xi) * dp[l] * dp[l]);
    }
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

namespace {
// The collocation nodes of P_n^(a, b): its Gauss-Jacobi rule (descending,
// as chebyshev_nodes: r_1 = cos(pi/(N + 1)) is the largest) and the zeros
// of P_m^(-a, -b), m = n + 1 (friction) or n - 1 (the flat punch); built
// once per process (a sweep over loads at one speed and friction solves
// with the same exponents at every point) and kept, as gauss_jacobi's rules
// are (cached_gauss_jacobi).
ChebyshevNodes cached_nodes(int n, double a, double b, int m) {
  static std::mutex mu;
  static std::map<std::tuple<int, double, double, int>, ChebyshevNodes> cache;
  const auto key = std::make_tuple(n, a, b, m);
  {
    const std::lock_guard<std::mutex> lock(mu);
    const auto it = cache.find(key);
    if (it != cache.end()) return it->second;
  }
  const JacobiRule rule = gauss_jacobi(n, a, b);
  ChebyshevNodes nd;
  nd.n = n;
  nd.r = rule.x.reverse();
  nd.w = rule.w.reverse() / kPi;
  nd.s = jacobi_zeros(m, -a, -b).reverse();
  const std::lock_guard<std::mutex> lock(mu);
  if (cache.size() >= 512) cache.clear();  // a long sweep over many exponents
  cache.emplace(key, nd);
  return nd;
}
}  // namespace

ChebyshevNodes jacobi_collocation_nodes(int n, double alpha) {
  if (n < 2) throw std::invalid_argument("jacobi_collocation_nodes: n must be >= 2");
  if (!(alpha > 0.0 && alpha < 1.0))
    throw std::invalid_argument("jacobi_collocation_nodes: alpha must be in (0, 1)");
  return cached_nodes(n, alpha, 1.0 - alpha, n + 1);
}

ChebyshevNodes jacobi_flat_nodes(int n, double alpha, double beta) {
  if (n < 2) throw std::invalid_argument("jacobi_flat_nodes: n must be >= 2");
  if (!(alpha > -1.0 && alpha < 0.0) || !(std::fabs(alpha + beta + 1.0) <= 1e-12))
    throw std::invalid_argument("jacobi_flat_nodes: need alpha in (-1, 0) and alpha + beta = -1");
  return cached_nodes(n, alpha, beta, n - 1);
}

// The norm h_n = int w P_n^2. n = 0 apart: the general formula's
// 1/((a + b + 1) Gamma(a + b + 1)) is 0 * inf at a + b = -1 (its limit
// 1/Gamma(a + b + 2)).
double jacobi_norm(int n, double a, double b) {
  if (n == 0)
    return std::exp((a + b + 1.0) * std::log(2.0) + std::lgamma(a + 1.0) + std::lgamma(b + 1.0) -
                    std::lgamma(a + b + 2.0));
  return std::exp((a + b + 1.0) * std::log(2.0) - std::log(2.0 * n + a + b + 1.0) +
                  std::lgamma(n + a + 1.0) + std::lgamma(n + b + 1.0) -
                  std::lgamma(n + a + b + 1.0) - std::lgamma(n + 1.0));
}

namespace {
// int_{s0}^{1} (1 - s)^a (1 + s)^b ds, from the nearer end: with L the
// piece's length and t = L u from that end, L^(e+1) int_0^1 u^e (2 - L u)^f du
// (e the near end's exponent), whose second factor is analytic for |u| < 2/L
// (>= 2: 32 Gauss-Jacobi nodes are exact to round-off).
double weight_upper(double a, double b, double s0) {
  const double total = jacobi_norm(0, a, b);
  if (!(s0 > -1.0)) return total;
  if (!(s0 < 1.0)) return 0.0;
  auto part = [](double e, double f, double L) {
    const auto held = cached_gauss_jacobi(32, 0.0, e);  // weight (1 + x)^e, u = (1 + x)/2
    const JacobiRule& rule = *held;
    double sum = 0.0;
    for (Eigen::Index i = 0; i < rule.x.size(); ++i)
      sum += rule.w(i) * std::pow(2.0 - L * 0.5 * (1.0 + rule.x(i)), f);
    return std::pow(L, e + 1.0) * std::pow(2.0, -e - 1.0) * sum;
  };
  return s0 >= 0.0 ? part(a, b, 1.0 - s0) : total - part(b, a, 1.0 + s0);
}

// s P_m = al_m P_{m+1} + be_m P_m + ga_m P_{m-1} for P^(a, b).
void times_s(double a, double b, int m, double* al, double* be, double* ga) {
  if (m == 0) {
    *al = 2.0 / (a + b + 2.0);
    *be = (b - a) / (a + b + 2.0);
    *ga = 0.0;
    return;
  }
  const double mm = m, t = 2.0 * mm + a + b;
  *al = 2.0 * (mm + 1.0) * (mm + a + b + 1.0) / ((t + 1.0) * (t + 2.0));
  *be = (b * b - a * a) / (t * (t + 2.0));
  *ga = 2.0 * (mm + a) * (mm + b) / (t * (t + 1.0));
}

// J from I (I holds count + 1 values).
std::vector<double> s_moments(double a, double b, const std::vector<double>& I, int count) {
  std::vector<double> J(static_cast<std::size_t>(count));
  for (int m = 0; m < count; ++m) {
    double al, be, ga;
    times_s(a, b, m, &al, &be, &ga);
    const std::size_t k = static_cast<std::size_t>(m);
    J[k] = al * I[k + 1] + be * I[k] + (m > 0 ? ga * I[k - 1] : 0.0);
  }
  return J;
}

// I_m = sign W1(s0) P_{m-1}^(a+1, b+1)(s0) / (2m), m = 1 .. count.
std::vector<double> rodrigues_moments(double a, double b, double s0, int count, double sign) {
  std::vector<double> I(static_cast<std::size_t>(count) + 1, 0.0);
  if (!(s0 > -1.0 && s0 < 1.0)) return I;
  const double W1 = std::pow(1.0 - s0, a + 1.0) * std::pow(1.0 + s0, b + 1.0);
  const Recurrence R = recurrence(a + 1.0, b + 1.0, count);
  double p0 = 1.0, p1 = R.A[0] * s0 + R.B[0];
  for (int m = 1; m <= count; ++m) {
    double p;  // P_{m-1}^(a+1, b+1)(s0)
    if (m == 1) {
      p = p0;
    } else if (m == 2) {
      p = p1;
    } else {
      const std::size_t k = static_cast<std::size_t>(m - 2);
      const double p2 = (R.A[k] * s0 + R.B[k]) * p1 - R.C[k] * p0;
      p0 = p1;
      p1 = p2;
      p = p2;
    }
    I[static_cast<std::size_t>(m)] = sign * W1 * p / (2.0 * m);
  }
  return I;
}
}  // namespace

JacobiMoments jacobi_upper_moments(double a, double b, double s0, int count) {
  if (!(a > -1.0 && b > -1.0) || !std::isfinite(s0) || count < 1)
    throw std::invalid_argument("jacobi_upper_moments: need a, b > -1, finite s0, count >= 1");
  s0 = std::clamp(s0, -1.0, 1.0);
  std::vector<double> I = rodrigues_moments(a, b, s0, count, 1.0);
  I[0] = weight_upper(a, b, s0);
  JacobiMoments out;
  out.J = s_moments(a, b, I, count);
  I.resize(static_cast<std::size_t>(count));
  out.I = std::move(I);
  return out;
}

JacobiMoments jacobi_lower_moments(double a, double b, double s0, int count) {
  if (!(a > -1.0 && b > -1.0) || !std::isfinite(s0) || count < 1)
    throw std::invalid_argument("jacobi_lower_moments: need a, b > -1, finite s0, count >= 1");
  s0 = std::clamp(s0, -1.0, 1.0);
  std::vector<double> I = rodrigues_moments(a, b, s0, count, -1.0);
  I[0] = jacobi_norm(0, a, b) - weight_upper(a, b, s0);
  JacobiMoments out;
  out.J = s_moments(a, b, I, count);
  I.resize(static_cast<std::size_t>(count));
  out.I = std::move(I);
  return out;
}

JacobiSeries::JacobiSeries(double alpha, Eigen::VectorXd c)
    : JacobiSeries(alpha, 1.0 - alpha, std::move(c)) {}

struct JacobiSeries::Derived {
  Recurrence rec, shifted;  // P^(alpha, beta); P^(-alpha, -beta)
  std::once_flag once;
  Far far;
};

JacobiSeries::JacobiSeries(double alpha, double beta, Eigen::VectorXd c)
    : alpha_(alpha), beta_(beta), c_(std::move(c)) {
  const bool bounded = std::fabs(alpha + beta - 1.0) <= 1e-12 && alpha > 0.0 && alpha < 1.0;
  const bool singular = std::fabs(alpha + beta + 1.0) <= 1e-12 && alpha > -1.0 && alpha < 0.0;
  if (!bounded && !singular)
    throw std::invalid_argument(
        "JacobiSeries: need alpha + beta = 1 with alpha in (0, 1), or alpha + beta = -1 with "
        "alpha in (-1, 0)");
  auto d = std::make_shared<Derived>();
  d->rec = recurrence(alpha_, beta_, size());
  d->shifted = recurrence(-alpha_, -beta_, size() + 1);
  derived_ = std::move(d);
}

const JacobiSeries::Derived& JacobiSeries::derived() const {
  if (!derived_) {  // a default-constructed (empty) series
    static const Derived empty;
    return empty;
  }
  return *derived_;
}

const JacobiSeries::Far& JacobiSeries::far() const {
  static const Far none;
  if (!derived_) return none;
  Derived& d = *derived_;
  std::call_once(d.once, [&] {
    const auto held = cached_gauss_jacobi(size() + 60, alpha_, beta_);
    d.far.x = held->x;
    d.far.wg.resize(held->x.size());
    g_values(held->x.data(), static_cast<int>(held->x.size()), d.far.wg.data());
    d.far.wg.array() *= held->w.array();
  });
  return d.far;
}

void JacobiSeries::g_values(const double* r, int m, double* out) const {
  const int n = size();
  if (n == 0 || !derived_) {
    std::fill(out, out + std::max(m, 0), 0.0);
    return;
  }
  const Recurrence& R = derived_->rec;
  constexpr int L = 8;
  for (int i0 = 0; i0 < m; i0 += L) {
    const int lanes = std::min(L, m - i0);
    double z[L], p0[L], p1[L], sum[L];
    for (int l = 0; l < L; ++l) {
      z[l] = l < lanes ? r[i0 + l] : 0.0;
      p0[l] = 1.0;
      p1[l] = R.A[0] * z[l] + R.B[0];
      sum[l] = c_(0) + (n > 1 ? c_(1) * p1[l] : 0.0);
    }
    for (int k = 1; k + 1 < n; ++k) {
      const double A = R.A[static_cast<std::size_t>(k)], B = R.B[static_cast<std::size_t>(k)],
                   C = R.C[static_cast<std::size_t>(k)], ck = c_(k + 1);
      for (int l = 0; l < L; ++l) {
        const double p2 = (A * z[l] + B) * p1[l] - C * p0[l];
        p0[l] = p1[l];
        p1[l] = p2;
        sum[l] += ck * p2;
      }
    }
    for (int l = 0; l < lanes; ++l) out[i0 + l] = sum[l];
  }
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
  // c_k = sum_i W_i g_i P_k(r_i) / h_k, the P_k(r_i) by the recurrence at
  // every node together.
  const Recurrence R = recurrence(alpha, beta, n);
  Eigen::VectorXd c = Eigen::VectorXd::Zero(n);
  const Eigen::ArrayXd wg = rule.w.array() * gv.array();
  Eigen::ArrayXd p0 = Eigen::ArrayXd::Ones(n), p1 = R.A[0] * rule.x.array() + R.B[0];
  c(0) = wg.sum();
  if (n > 1) c(1) = (wg * p1).sum();
  for (int k = 1; k + 1 < n; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    Eigen::ArrayXd p2 = (R.A[kk] * rule.x.array() + R.B[kk]) * p1 - R.C[kk] * p0;
    p0.swap(p1);
    p1.swap(p2);
    c(k + 1) = (wg * p1).sum();
  }
  for (int k = 0; k < n; ++k) c(k) /= jacobi_norm(k, alpha, beta);
  return JacobiSeries(alpha, beta, c);
}

double JacobiSeries::g(double r) const {
  return recurrence_series(derived().rec, c_, r, 0, static_cast<double*>(nullptr));
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
  const double poly =
      recurrence_series(derived().shifted, c_, x, shift(), static_cast<double*>(nullptr));
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
  const Far& f = far();
  for (Eigen::Index i = 0; i < f.x.size(); ++i) sum += f.wg(i) / (f.x(i) - x);
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
    const C gz = recurrence_series(derived().rec, c_, z, 0, &dg);
    const C poly = recurrence_series(derived().shifted, c_, z, shift(), &dpoly);
    const double q = poly_factor();
    if (derivative) {
      const C dZ = Z * (a / (z - 1.0) + b / (z + 1.0));
      *derivative = (dZ * gz + Z * dg - q * dpoly) / sa;
    }
    return (Z * gz - q * poly) / sa;
  }
  // sum wg_i/(x_i - z) (and wg_i/(x_i - z)^2) in real arithmetic: 1/(x - z)
  // = (dx + i y)/(dx^2 + y^2), dx = x - Re z, y = Im z (z is off the cut
  // here: no overflow for the library's complex division to guard against,
  // which had taken three quarters of a stress map).
  const Far& f = far();
  const double zr = z.real(), zi = z.imag();
  double sr = 0.0, si = 0.0, dr = 0.0, di = 0.0;
  const Eigen::Index m = f.x.size();
  if (derivative) {
    for (Eigen::Index i = 0; i < m; ++i) {
      const double dx = f.x(i) - zr, inv = 1.0 / (dx * dx + zi * zi);
      const double re = dx * inv, im = zi * inv, w = f.wg(i);
      sr += w * re;
      si += w * im;
      dr += w * (re - im) * (re + im);
      di += w * 2.0 * re * im;
    }
    *derivative = C(dr, di) / kPi;
  } else {
    for (Eigen::Index i = 0; i < m; ++i) {
      const double dx = f.x(i) - zr, inv = f.wg(i) / (dx * dx + zi * zi);
      sr += dx * inv;
      si += zi * inv;
    }
  }
  return C(sr, si) / kPi;
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

namespace {
// cos(pi j/m), j = 0..m.
std::vector<double> cosine_angles(int m) {
  std::vector<double> r(static_cast<std::size_t>(m) + 1);
  for (int j = 0; j <= m; ++j) r[static_cast<std::size_t>(j)] = std::cos(kPi * j / m);
  return r;
}
}  // namespace

double JacobiSeries::max_abs_density() const {
  const int m = 8 * (size() + 1) + 64;
  const std::vector<double> r = cosine_angles(m);
  std::vector<double> gv(r.size());
  g_values(r.data(), m + 1, gv.data());
  double best = 0.0;
  for (std::size_t j = 0; j < r.size(); ++j) {
    const double w = weight(r[j]);
    best = std::max(best, std::fabs(w == 0.0 ? 0.0 : w * gv[j]));
  }
  return best;
}

double JacobiSeries::max_abs_g() const {
  const int m = 8 * (size() + 1) + 64;
  const std::vector<double> r = cosine_angles(m);
  std::vector<double> gv(r.size());
  g_values(r.data(), m + 1, gv.data());
  double best = 0.0;
  for (double v : gv) best = std::max(best, std::fabs(v));
  return best;
}

double JacobiSeries::min_g() const {
  const int m = std::max(401, 16 * (size() + 1) + 257);
  const std::vector<double> r = cosine_angles(m);
  std::vector<double> gv(r.size());
  g_values(r.data(), m + 1, gv.data());
  int jb = 0;
  double best = std::numeric_limits<double>::infinity();
  for (int j = 0; j <= m; ++j) {
    const double v = gv[static_cast<std::size_t>(j)];
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

namespace {
// The length beyond which a series' terms add less than 1e-17 of sum |c_m|
// sqrt(h_0 h_m) to its transform at any |omega| <= omega_max: w P_m is
// orthogonal to every polynomial of degree < m, so |int w P_m e^{-i omega r}|
// <= int w |P_m| min_q max |e^{-i omega r} - q| <= sqrt(h_0 h_m) omega^m / m!
// (Cauchy-Schwarz and the Taylor remainder).
int transform_length(const JacobiSeries& s, double omega_max) {
  const int n = s.size();
  if (n == 0) return 0;
  const double a = s.alpha(), b = s.beta(), h0 = jacobi_norm(0, a, b);
  const double lw = std::log(std::max(std::fabs(omega_max), 1e-300));
  double total = 0.0;
  std::vector<double> size(static_cast<std::size_t>(n));
  for (int m = 0; m < n; ++m) {
    size[static_cast<std::size_t>(m)] =
        std::fabs(s.coefficients()(m)) * std::sqrt(h0 * jacobi_norm(m, a, b));
    total += size[static_cast<std::size_t>(m)];
  }
  double tail = 0.0;
  int len = n;
  while (len > 0) {
    const int m = len - 1;
    const double bound =
        size[static_cast<std::size_t>(m)] *
        (omega_max == 0.0 ? (m == 0 ? 1.0 : 0.0) : std::exp(m * lw - std::lgamma(m + 1.0)));
    if (tail + bound > 1e-17 * total) break;
    tail += bound;
    len = m;
  }
  return len;
}
}  // namespace

JacobiTransform::JacobiTransform(const JacobiSeries& s, double omega_max,
                                 const JacobiSeries* second, bool interpolate) {
  // Only the terms that reach |omega| <= omega_max (a profile's tail-extended
  // series has a thousand, of which the transform sees a few dozen), by a
  // rule exact for them (its size rounded up to 64: shared between solves).
  const double om = std::ceil(std::fabs(omega_max));
  const int len = std::max(transform_length(s, om), second ? transform_length(*second, om) : 0);
  const int m = (len + static_cast<int>(om) + 40 + 63) / 64 * 64;
  rule_ = *cached_gauss_jacobi(m, s.alpha(), s.beta());
  gw_.resize(m);
  gw2_ = Eigen::VectorXd::Zero(m);
  const JacobiSeries head(s.alpha(), s.beta(), s.coefficients().head(std::min(len, s.size())));
  head.g_values(rule_.x.data(), m, gw_.data());
  gw_.array() *= rule_.w.array();
  if (second) {
    const JacobiSeries head2(second->alpha(), second->beta(),
                             second->coefficients().head(std::min(len, second->size())));
    head2.g_values(rule_.x.data(), m, gw2_.data());
    gw2_.array() *= rule_.w.array();
  }
  // The Chebyshev interpolant in omega (see the header).
  const double L = 0.5 * std::fabs(omega_max);
  if (interpolate && L > 0.0 && std::isfinite(L)) {
    int K = std::max(8, static_cast<int>(std::ceil(L)));
    while (std::log(8.0) + (K + 1.0) * std::log(0.5 * L) - std::lgamma(K + 2.0) > std::log(1e-17))
      ++K;
    half_range_ = L;
    nodes_.resize(static_cast<std::size_t>(K) + 1);
    bary_.resize(nodes_.size());
    v1_.resize(K + 1);
    v2_.resize(K + 1);
    for (int j = 0; j <= K; ++j) {
      const double t = std::cos(kPi * j / K);
      nodes_[static_cast<std::size_t>(j)] = t;
      bary_[static_cast<std::size_t>(j)] =
          (j % 2 == 0 ? 1.0 : -1.0) * (j == 0 || j == K ? 0.5 : 1.0);
      const auto [a, b] = direct(L * (1.0 + t));
      v1_(j) = a;
      v2_(j) = b;
    }
  }
}

std::pair<std::complex<double>, std::complex<double>> JacobiTransform::both(double omega) const {
  if (half_range_ > 0.0 && omega >= 0.0 && omega <= 2.0 * half_range_) {
    const double t = omega / half_range_ - 1.0;
    std::complex<double> num1 = 0.0, num2 = 0.0;
    double den = 0.0;
    for (std::size_t j = 0; j < nodes_.size(); ++j) {
      const double d = t - nodes_[j];
      if (d == 0.0) return {v1_(static_cast<Eigen::Index>(j)), v2_(static_cast<Eigen::Index>(j))};
      const double q = bary_[j] / d;
      num1 += q * v1_(static_cast<Eigen::Index>(j));
      num2 += q * v2_(static_cast<Eigen::Index>(j));
      den += q;
    }
    return {num1 / den, num2 / den};
  }
  return direct(omega);
}

std::pair<std::complex<double>, std::complex<double>> JacobiTransform::direct(double omega) const {
  std::complex<double> a = 0.0, b = 0.0;
  for (Eigen::Index i = 0; i < gw_.size(); ++i) {
    const std::complex<double> e(std::cos(omega * rule_.x(i)), -std::sin(omega * rule_.x(i)));
    a += gw_(i) * e;
    b += gw2_(i) * e;
  }
  return {a, b};
}

}  // namespace movingpunch

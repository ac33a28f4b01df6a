#include "movingpunch/collocation.hpp"

#include "bessel.hpp"
#include "movingpunch/kernel.hpp"

#include <array>
#include <map>
#include <memory>
#include <mutex>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace movingpunch {

namespace {
constexpr double kPi = 3.14159265358979323846;

// Both node sets take an even N in [2, 100000].
void check_size(int n) {
  if (n < 2 || n % 2 != 0 || n > 100000)
    throw std::invalid_argument("collocation N must be even and in [2, 100000], got " +
                                std::to_string(n));
}
}  // namespace

ChebyshevNodes chebyshev_nodes(int n) {
  check_size(n);
  ChebyshevNodes c;
  c.n = n;
  c.r.resize(n);
  c.w.resize(n);
  c.s.resize(n + 1);
  for (int i = 1; i <= n; ++i) {
    const double th = i * kPi / (n + 1);
    c.r(i - 1) = std::cos(th);
    const double sn = std::sin(th);
    c.w(i - 1) = sn * sn / (n + 1);  // (1 - r^2)/(N+1), without cancellation
  }
  for (int k = 1; k <= n + 1; ++k) c.s(k - 1) = std::cos(kPi * (2 * k - 1) / (2.0 * (n + 1)));
  c.s(n / 2) = 0.0;  // the middle point exactly
  return c;
}

Eigen::VectorXd solve_unit_collocation(const ChebyshevNodes& nodes, double a,
                                       const std::function<double(double)>& kernel) {
  return solve_unit_collocation_sum(
      nodes, a, [&kernel](double u, double v) { return kernel(u) + kernel(v); });
}

Eigen::MatrixXd unit_collocation_matrix(const ChebyshevNodes& nodes, double a,
                                        const std::function<double(double, double)>& kernel_sum) {
  return unit_collocation_matrix(
      nodes, a, [&kernel_sum](const double* u, const double* v, double* out, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) out[i] = kernel_sum(u[i], v[i]);
      });
}

Eigen::MatrixXd unit_collocation_matrix(const ChebyshevNodes& nodes, double a,
                                        const KernelSums& sums) {
  const int h = nodes.n / 2;
  const std::size_t hh = static_cast<std::size_t>(h) * static_cast<std::size_t>(h);
  thread_local std::vector<double> up, um, ks;
  up.resize(hh);
  um.resize(hh);
  ks.resize(hh);
  // Entry (k, j) at k h + j: s_k > 0 for k = 1..N/2; r_j > 0, its mirror -r_j
  // carries the same g.
  for (int k = 0; k < h; ++k)
    for (int j = 0; j < h; ++j) {
      const std::size_t e = static_cast<std::size_t>(k * h + j);
      up[e] = a * (nodes.r(j) - nodes.s(k));
      um[e] = a * (-nodes.r(j) - nodes.s(k));
    }
  sums(up.data(), um.data(), ks.data(), hh);
  Eigen::MatrixXd M(h, h);
  for (int k = 0; k < h; ++k) {
    const double s = nodes.s(k);
    for (int j = 0; j < h; ++j) {
      const double r = nodes.r(j);
      M(k, j) = nodes.w(j) *
                (1.0 / (r - s) + 1.0 / (-r - s) + a * ks[static_cast<std::size_t>(k * h + j)]);
    }
  }
  return M;
}

Eigen::VectorXd solve_unit_collocation_sum(
    const ChebyshevNodes& nodes, double a,
    const std::function<double(double, double)>& kernel_sum) {
  const int h = nodes.n / 2;
  return unit_collocation_matrix(nodes, a, kernel_sum).partialPivLu().solve(nodes.s.head(h));
}

std::vector<double> singular_moments(int n_max, int power, int sigma, double s) {
  if (n_max < 1 || power < 0 || sigma < 0 || sigma > 2 || !(std::fabs(s) < 1.0))
    throw std::invalid_argument("singular_moments: n_max >= 1, power >= 0, |s| < 1 required");
  const int top = n_max + power;
  const double th = std::acos(s);
  // M_{0,n} = int sqrt(1 - r^2) U_n(r) sigma(r - s) dr (r = cos theta:
  // sqrt(1 - r^2) U_n dr = -sin((n+1) theta) sin(theta) d theta).
  std::vector<double> m(static_cast<std::size_t>(top + 1), 0.0);
  for (int n = 0; n <= top; ++n) {
    double v = 0.0;
    if (sigma == 0) {
      v = n == 0 ? 0.5 * kPi : 0.0;
    } else if (sigma == 1) {
      // int_0^th - int_th^pi of (cos(n x) - cos((n+2) x))/2.
      const double G = n == 0 ? 0.5 * (th - 0.5 * std::sin(2.0 * th))
                              : 0.5 * (std::sin(n * th) / n - std::sin((n + 2) * th) / (n + 2));
      v = 2.0 * G - (n == 0 ? 0.5 * kPi : 0.0);
    } else {
      // sqrt(1 - r^2) U_n = (T_n - T_{n+2}) / (2 sqrt(1 - r^2)) and
      // int ln|r - s| T_m / sqrt(1 - r^2) dr = -pi ln 2 (m = 0), -pi T_m(s)/m.
      auto Lm = [&](int q) { return q == 0 ? -kPi * std::log(2.0) : -kPi * std::cos(q * th) / q; };
      v = 0.5 * (Lm(n) - Lm(n + 2));
    }
    m[static_cast<std::size_t>(n)] = v;
  }
  // Moments of r^l: r U_n = (U_{n+1} + U_{n-1})/2 (U_{-1} = 0); then
  // (r - s)^power by the binomial sum.
  std::vector<double> out(static_cast<std::size_t>(n_max), 0.0);
  double binom = 1.0;  // C(power, l)
  std::vector<double> cur = m;
  for (int l = 0; l <= power; ++l) {
    const double c = binom * std::pow(-s, power - l);
    for (int n = 0; n < n_max; ++n)
      out[static_cast<std::size_t>(n)] += c * cur[static_cast<std::size_t>(n)];
    if (l == power) break;
    std::vector<double> next(cur.size(), 0.0);
    for (int n = 0; n + 1 < static_cast<int>(cur.size()); ++n)
      next[static_cast<std::size_t>(n)] =
          0.5 * (cur[static_cast<std::size_t>(n + 1)] +
                 (n > 0 ? cur[static_cast<std::size_t>(n - 1)] : 0.0));
    cur.swap(next);
    binom = binom * (power - l) / (l + 1);
  }
  return out;
}

namespace {

// B(k, j) = W_j (4/pi) sum_{n even < N} U_n(r_j) M_n(s_k) for the moments M of
// (r - s)^p sigma(r - s): independent of a and of the coefficients, cached
// per (N, p, sigma) (the width iteration assembles many matrices at one N).
// (Shared, not a reference into the cache: another thread's insertion may
// clear it.)
std::shared_ptr<const Eigen::MatrixXd> moment_block(const ChebyshevNodes& nodes, int p, int sigma) {
  static std::mutex mutex;
  static std::map<std::array<int, 3>, std::shared_ptr<const Eigen::MatrixXd>> cache;
  const std::array<int, 3> key{nodes.n, p, sigma};
  {
    std::lock_guard<std::mutex> lock(mutex);
    const auto it = cache.find(key);
    if (it != cache.end()) return it->second;
  }
  const int n = nodes.n, h = n / 2;
  Eigen::MatrixXd U(h, n);
  for (int j = 0; j < h; ++j) {
    const double th = (j + 1) * kPi / (n + 1);
    for (int q = 0; q < n; ++q)
      U(j, q) = (q % 2 == 0) ? std::sin((q + 1) * th) / std::sin(th) : 0.0;
  }
  Eigen::MatrixXd Mom(h, n);
  for (int k = 0; k < h; ++k) {
    const std::vector<double> m = singular_moments(n, p, sigma, nodes.s(k));
    for (int q = 0; q < n; ++q) Mom(k, q) = m[static_cast<std::size_t>(q)];
  }
  auto B = std::make_shared<Eigen::MatrixXd>(Mom * U.transpose());
  for (int j = 0; j < h; ++j) B->col(j) *= nodes.w(j) * (4.0 / kPi);
  std::lock_guard<std::mutex> lock(mutex);
  if (cache.size() > 256) cache.clear();
  auto& slot = cache[key];
  if (!slot) slot = std::move(B);
  return slot;
}

}  // namespace

Eigen::MatrixXd singular_collocation_matrix(const ChebyshevNodes& nodes, double a,
                                            const std::vector<KernelSingularTerm>& terms) {
  const int h = nodes.n / 2;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(h, h);
  for (const KernelSingularTerm& t : terms) {
    const double scale = a * t.coef * std::pow(a, t.power);
    M += scale * *moment_block(nodes, t.power, t.log ? 2 : 1);
    if (t.log) M += scale * std::log(a) * *moment_block(nodes, t.power, 0);
  }
  return M;
}

Eigen::VectorXd u_coefficients(const ChebyshevNodes& nodes, const Eigen::VectorXd& g_full) {
  const int n = nodes.n;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  // (1 - r^2) U_m(r) = sin(th) sin((m+1) th), th = i pi/(n + 1): every
  // sine is one of sin(k pi/(n + 1)), k = (m + 1) i mod 2 (n + 1) (a table
  // of 2 (n + 1) in place of n^2 sines).
  const int period = 2 * (n + 1);
  thread_local std::vector<double> sines;
  sines.resize(static_cast<std::size_t>(period));
  for (int k = 0; k < period; ++k) sines[static_cast<std::size_t>(k)] = std::sin(k * kPi / (n + 1));
  thread_local std::vector<double> sg;  // sin(th_i) g_i
  sg.resize(static_cast<std::size_t>(n));
  for (int i = 1; i <= n; ++i)
    sg[static_cast<std::size_t>(i - 1)] = sines[static_cast<std::size_t>(i)] * g_full(i - 1);
  for (int m = 0; m < n; ++m) {
    double sum = 0.0;
    int k = 0;
    for (int i = 1; i <= n; ++i) {
      k += m + 1;
      if (k >= period) k -= period;
      sum += sg[static_cast<std::size_t>(i - 1)] * sines[static_cast<std::size_t>(k)];
    }
    b(m) = 2.0 * sum / (n + 1);
  }
  return b;
}

double series_minimum(const Eigen::VectorXd& b, SeriesKind kind, double* r_min) {
  if (b.size() == 0) throw std::invalid_argument("series_minimum: no coefficients");
  const bool even = odd_terms_zero(b);
  auto g_of = [kind, even](const Eigen::VectorXd& c, double r) {
    return even ? even_series(c, r, kind) : series(c, r, kind);
  };
  // 16 (N + 1) + 256 angles resolve every extremum of the degree-N polynomial.
  // An even g takes the same value at r and -r, the later of the two never
  // below the earlier: the half r >= 0 finds the same first minimum.
  const int m = std::max(400, 16 * static_cast<int>(b.size() + 1) + 256);
  thread_local std::vector<double> cosines;
  if (cosines.size() != static_cast<std::size_t>(m + 1)) {
    cosines.resize(static_cast<std::size_t>(m + 1));
    for (int i = 0; i <= m; ++i) cosines[static_cast<std::size_t>(i)] = std::cos(kPi * i / m);
  }
  int best = 0;
  double gbest = g_of(b, 1.0);
  for (int i = 1, last = even ? m / 2 : m; i <= last; ++i) {
    const double g = g_of(b, cosines[static_cast<std::size_t>(i)]);
    if (g < gbest) {
      gbest = g;
      best = i;
    }
  }
  // Golden section on the two sample intervals around the best sample.
  double lo = std::cos(kPi * std::min(best + 1, m) / m),
         hi = std::cos(kPi * std::max(best - 1, 0) / m);
  double rbest = std::cos(kPi * best / m);
  const double gr = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
  double f1 = g_of(b, x1), f2 = g_of(b, x2);
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - gr * (hi - lo);
      f1 = g_of(b, x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + gr * (hi - lo);
      f2 = g_of(b, x2);
    }
  }
  for (const auto& [x, f] : {std::pair<double, double>{x1, f1}, {x2, f2}})
    if (f < gbest) {
      gbest = f;
      rbest = x;
    }
  if (r_min) *r_min = rbest;
  return gbest;
}

double u_series_minimum(const Eigen::VectorXd& b, double* r_min) {
  return series_minimum(b, SeriesKind::U, r_min);
}

Eigen::Index last_even_term(const Eigen::VectorXd& b) {
  Eigen::Index last = 0;
  const double bmax = b.cwiseAbs().maxCoeff();
  for (Eigen::Index n = 0; n < b.size(); n += 2)
    if (std::fabs(b(n)) > 1e-17 * bmax) last = n;
  return last;
}

namespace detail {

// Below this argument Hankel's expansion of J_0, J_1 (bessel_j01_large)
// runs out of terms before double precision (at w = 20 it needs 37 of its
// 40, at 12 it is 1e-11 off); above it, 21 or fewer give 4e-16 of the
// amplitude, and the upward recurrence to orders below w keeps 1e-14
// (against a long-double Miller recurrence; scipy's jv is 7e-14 off there).
constexpr double kHankelMin = 25.0;

// J_0(w) and J_1(w) at w > kHankelMin by Hankel's asymptotic expansion,
// J_nu = sqrt(2/(pi w)) (P cos chi - Q sin chi), chi = w - (nu/2 + 1/4) pi,
// with P, Q the even and odd terms of sum_k (-1)^floor(k/2) a_k(nu) / w^k,
// a_k = a_{k-1} (4 nu^2 - (2k - 1)^2) / (8k): the terms fall by ~k/(4w) each,
// so a few give double precision (the library's J_0, J_1 took 10 % of a
// graded top's solve, in the transform's envelope at w up to 3e4, and its
// J_0(200.5) is 2e-12 off scipy's).
void bessel_j01_large(double w, double& j0, double& j1) {
  // 1/(k + 1) for the terms' ratios (no division in the loop).
  static const std::array<double, 40> recip = [] {
    std::array<double, 40> r{};
    for (std::size_t k = 0; k < r.size(); ++k) r[k] = 1.0 / static_cast<double>(k + 1);
    return r;
  }();
  double p0 = 0.0, q0 = 0.0, p1 = 0.0, q1 = 0.0;
  double t0 = 1.0, t1 = 1.0;  // a_k(nu) / w^k
  const double inv8 = 0.125 / w;
  // Terms k = 2j (into P) and 2j + 1 (into Q), both of sign (-1)^j.
  double sg = 1.0;
  for (std::size_t k = 0; k < 40; k += 2) {
    p0 += sg * t0;
    p1 += sg * t1;
    double d = static_cast<double>(2 * k + 1) * static_cast<double>(2 * k + 1);
    double c = inv8 * recip[k];
    t0 *= -d * c;
    t1 *= (4.0 - d) * c;
    q0 += sg * t0;
    q1 += sg * t1;
    d = static_cast<double>(2 * k + 3) * static_cast<double>(2 * k + 3);
    c = inv8 * recip[k + 1];
    t0 *= -d * c;
    t1 *= (4.0 - d) * c;
    sg = -sg;
    if (std::fabs(t0) + std::fabs(t1) < 1e-18) break;
  }
  const double sn = std::sin(w), cs = std::cos(w);
  // chi_0 = w - pi/4, chi_1 = w - 3 pi/4.
  constexpr double r = 0.70710678118654752440;
  const double c0 = r * (cs + sn), s0 = r * (sn - cs);
  const double c1 = r * (sn - cs), s1 = -r * (sn + cs);
  const double amp = std::sqrt(2.0 / (kPi * w));
  j0 = amp * (p0 * c0 - q0 * s0);
  j1 = amp * (p1 * c1 - q1 * s1);
}

// J_0(w) .. J_kmax(w), w > 0, all at once: upward recurrence from
// bessel_j01_large's J_0, J_1 while the order stays below w > kHankelMin
// (stable there: it costs kmax steps where Miller's costs w + 20 + 4 sqrt(w)),
// Miller's downward recurrence normalised by J_0 + 2 sum J_2k = 1 otherwise
// (within 5e-15 of scipy's J_n up to w = 200, and without the library's slow
// J_0, J_1; see u_series_cosine_transforms).
void bessel_orders(double w, int kmax, std::vector<double>& J) {
  J.assign(static_cast<std::size_t>(kmax) + 1, 0.0);
  if (kmax + 1 < w && w > kHankelMin) {
    double j0, j1;
    bessel_j01_large(w, j0, j1);
    J[0] = j0;
    if (kmax >= 1) J[1] = j1;
    for (int k = 1; k < kmax; ++k)
      J[static_cast<std::size_t>(k) + 1] =
          2.0 * k / w * J[static_cast<std::size_t>(k)] - J[static_cast<std::size_t>(k) - 1];
    return;
  }
  const double top = std::max(static_cast<double>(kmax), w);
  int start = static_cast<int>(top + 20.0 + 4.0 * std::sqrt(top));
  start += start % 2;  // even, so the normalisation sum ends on J_0
  double up = 0.0, cur = 1e-280, norm = 0.0;
  for (int k = start; k >= 1; --k) {
    const double down = 2.0 * k / w * cur - up;  // J_{k-1}
    up = cur;
    cur = down;
    if (k - 1 <= kmax) J[static_cast<std::size_t>(k) - 1] = cur;
    if ((k - 1) % 2 == 0 && k - 1 > 0) norm += 2.0 * cur;
    if (std::fabs(cur) > 1e250) {  // rescale to avoid overflow
      for (int m = k - 1; m <= kmax; ++m) J[static_cast<std::size_t>(m)] *= 1e-250;
      up *= 1e-250;
      cur *= 1e-250;
      norm *= 1e-250;
    }
  }
  norm += cur;  // J_0
  for (double& v : J) v /= norm;
}

}  // namespace detail

using detail::bessel_orders;

namespace {
// series_cosine_transform with b's last even term (last_even_term) given.
double cosine_transform_to(const Eigen::VectorXd& b, SeriesKind kind, double a, double alpha,
                           Eigen::Index last) {
  const bool t_kind = kind == SeriesKind::T;
  const double w = alpha * a;
  if (w < 1e-8) {
    // U: J_1(w)/w -> 1/2; T: J_0(w) -> 1; higher orders vanish.
    return t_kind ? 0.5 * b(0) * kPi * a : 0.5 * b(0) * 0.5 * kPi * a;
  }
  // J_nu(w) <= (w/2)^nu / nu!: negligible once the order exceeds the argument
  // by 40; higher orders are smaller.
  while (last > 0 && static_cast<double>(last + 1) > w + 40.0) last -= 2;
  thread_local std::vector<double> J;
  bessel_orders(w, static_cast<int>(last) + 1, J);
  double sum = 0.0;
  for (Eigen::Index n = 0; n <= last; n += 2) {
    const double sg = (n / 2) % 2 == 0 ? 1.0 : -1.0;
    if (t_kind)
      sum += b(n) * sg * J[static_cast<std::size_t>(n)];
    else
      sum += b(n) * static_cast<double>(n + 1) * sg * J[static_cast<std::size_t>(n) + 1];
  }
  return t_kind ? sum * 0.5 * kPi * a : sum * 0.5 * kPi * a / w;
}
}  // namespace

double series_cosine_transform(const Eigen::VectorXd& b, SeriesKind kind, double a, double alpha) {
  return cosine_transform_to(b, kind, a, alpha, last_even_term(b));
}

double u_series_cosine_transform(const Eigen::VectorXd& b, double a, double alpha) {
  return series_cosine_transform(b, SeriesKind::U, a, alpha);
}

void u_series_cosine_transforms(const Eigen::VectorXd& b, double a, const double* alpha,
                                double* out, std::size_t count) {
  series_cosine_transforms(b, SeriesKind::U, a, alpha, out, count);
}

namespace {
// coef[m], m < size: the weight of J_m in a cosine transform's sum (orders
// up to kmax): U, b_n (n+1) (-1)^{n/2} at m = n + 1 (odd); T, b_n
// (-1)^{n/2} at m = n (even); 0 elsewhere.
void bessel_weights(const Eigen::VectorXd& b, bool t_kind, int kmax, std::size_t size,
                    std::vector<double>& coef) {
  coef.assign(size, 0.0);
  if (t_kind) {
    for (int m = 0; m < kmax; m += 2)
      coef[static_cast<std::size_t>(m)] = b(m) * ((m / 2) % 2 == 0 ? 1.0 : -1.0);
  } else {
    for (int m = 1; m <= kmax; m += 2)
      coef[static_cast<std::size_t>(m)] =
          b(m - 1) * static_cast<double>(m) * (((m - 1) / 2) % 2 == 0 ? 1.0 : -1.0);
  }
}
}  // namespace

void series_cosine_transforms(const Eigen::VectorXd& b, SeriesKind kind, double a,
                              const double* alpha, double* out, std::size_t count) {
  constexpr int L = 4;
  const bool t_kind = kind == SeriesKind::T;
  const Eigen::Index last_all = last_even_term(b);
  // Arguments above the orders and kHankelMin: the upward branch, four at a
  // time after the others (upward_transforms).
  thread_local std::vector<std::size_t> upward;
  upward.clear();
  std::size_t i = 0;
  while (i < count) {
    // Gather up to L arguments for Miller's recurrence; the others (tiny or
    // large arguments) go one by one.
    std::array<std::size_t, L> idx{};
    std::array<double, L> w{};
    int lanes = 0;
    int kmax = 0;
    double wmax = 0.0;
    while (i < count && lanes < L) {
      const double wi = alpha[i] * a;
      Eigen::Index last = last_all;
      while (last > 0 && static_cast<double>(last + 1) > wi + 40.0) last -= 2;
      // Miller's recurrence (normalised by J_0 + 2 sum J_2k = 1, within 5e-15
      // of scipy's J_n up to w = 200) where the orders reach the argument;
      // above them, from w = kHankelMin, the upward branch (bessel_orders:
      // a graded top's panels reach w ~ 60, where Miller's start is 3 times
      // the orders).
      if (wi < 1e-8) {
        out[i] = cosine_transform_to(b, kind, a, alpha[i], last_all);
      } else if (wi > detail::kHankelMin && static_cast<double>(last) + 2.0 < wi) {
        upward.push_back(i);
      } else {
        idx[static_cast<std::size_t>(lanes)] = i;
        w[static_cast<std::size_t>(lanes)] = wi;
        ++lanes;
        kmax = std::max(kmax, static_cast<int>(last) + 1);
        wmax = std::max(wmax, wi);
      }
      ++i;
    }
    if (lanes == 0) continue;
    for (int l = lanes; l < L; ++l) w[static_cast<std::size_t>(l)] = w[0];  // padding
    // Common start (a higher start is as accurate): even, so the
    // normalisation J_0 + 2 sum J_2k ends on J_0.
    const double top = std::max(static_cast<double>(kmax), wmax);
    int start = static_cast<int>(top + 20.0 + 4.0 * std::sqrt(top));
    start += start % 2;
    thread_local std::vector<double> coef;
    bessel_weights(b, t_kind, kmax, static_cast<std::size_t>(start) + 1, coef);
    std::array<double, L> up{}, cur{}, norm{}, sum{}, inv{};
    for (int l = 0; l < L; ++l) {
      cur[static_cast<std::size_t>(l)] = 1e-280;
      inv[static_cast<std::size_t>(l)] = 2.0 / w[static_cast<std::size_t>(l)];
    }
    // Steps in pairs (start is even): J_{k-1} (odd order) then J_{k-2} (even
    // order, into the normalisation, J_0 included twice and taken out below);
    // the sum takes the odd orders (U) or the even ones (T). Rescaled when
    // large: two steps grow by at most (2 start / w)^2 < 1e30, far from
    // overflow above 1e250.
    for (int k = start; k >= 2; k -= 2) {
      const double c = coef[static_cast<std::size_t>(k) - 1];
      const double ce = coef[static_cast<std::size_t>(k) - 2];
      const double f1 = static_cast<double>(k), f2 = static_cast<double>(k - 1);
      bool big = false;
      for (int l = 0; l < L; ++l) {
        const std::size_t q = static_cast<std::size_t>(l);
        const double odd = f1 * inv[q] * cur[q] - up[q];
        const double even = f2 * inv[q] * odd - cur[q];
        if (t_kind)
          sum[q] += ce * even;
        else
          sum[q] += c * odd;
        norm[q] += 2.0 * even;
        up[q] = odd;
        cur[q] = even;
        big = big || std::fabs(even) > 1e250;
      }
      if (big) {
        for (int l = 0; l < L; ++l) {
          const std::size_t q = static_cast<std::size_t>(l);
          if (std::fabs(cur[q]) > 1e200) {
            up[q] *= 1e-250;
            cur[q] *= 1e-250;
            norm[q] *= 1e-250;
            sum[q] *= 1e-250;
          }
        }
      }
    }
    for (int l = 0; l < lanes; ++l) {
      const std::size_t q = static_cast<std::size_t>(l);
      const double total = norm[q] - cur[q];  // J_0 + 2 sum J_2k
      out[idx[q]] = t_kind ? sum[q] / total * 0.5 * kPi * a : sum[q] / total * 0.5 * kPi * a / w[q];
    }
  }
  if (upward.empty()) return;
  // The upward branch, L lanes at once: J_0, J_1 by Hankel's expansion, then
  // J_{k+1} = (2k/w) J_k - J_{k-1} to kmax < w - 1, summed on the way (no
  // table of J).
  const int kmax = static_cast<int>(last_all) + 1;
  thread_local std::vector<double> cu;
  bessel_weights(b, t_kind, kmax, static_cast<std::size_t>(kmax) + 1, cu);
  for (std::size_t g = 0; g < upward.size(); g += L) {
    const std::size_t lanes = std::min<std::size_t>(L, upward.size() - g);
    std::array<double, L> w{}, inv{}, prev{}, cur{}, sum{};
    for (std::size_t l = 0; l < L; ++l) {
      w[l] = alpha[upward[g + std::min(l, lanes - 1)]] * a;  // padding repeats the last
      inv[l] = 2.0 / w[l];
      detail::bessel_j01_large(w[l], prev[l], cur[l]);
      sum[l] = cu[0] * prev[l] + (kmax >= 1 ? cu[1] * cur[l] : 0.0);
    }
    for (int k = 1; k < kmax; ++k) {
      const double c = cu[static_cast<std::size_t>(k) + 1], fk = static_cast<double>(k);
      for (std::size_t l = 0; l < L; ++l) {
        const double next = fk * inv[l] * cur[l] - prev[l];
        sum[l] += c * next;
        prev[l] = cur[l];
        cur[l] = next;
      }
    }
    for (std::size_t l = 0; l < lanes; ++l)
      out[upward[g + l]] = t_kind ? sum[l] * 0.5 * kPi * a : sum[l] * 0.5 * kPi * a / w[l];
  }
}

namespace {
// Clenshaw's recurrence b_m = c_m + 2 r b_{m+1} - b_{m+2} down to m = last
// (both Chebyshev kinds share it): (b_last, b_{last+1}).
std::pair<double, double> clenshaw(const Eigen::VectorXd& c, double r, Eigen::Index last) {
  double b1 = 0.0, b2 = 0.0;
  for (Eigen::Index m = c.size() - 1; m >= last; --m) {
    const double b0 = c(m) + 2.0 * r * b1 - b2;
    b2 = b1;
    b1 = b0;
  }
  return {b1, b2};
}
}  // namespace

double u_series(const Eigen::VectorXd& b, double r) {
  // U_{n+1} = 2 r U_n - U_{n-1}, U_0 = 1, U_{-1} = 0: the sum is b_0.
  return clenshaw(b, r, 0).first;
}

void u_series(const Eigen::VectorXd& b, const double* r, double* out, int count) {
  constexpr int W = 8;
  const double* c = b.data();
  int i = 0;
  for (; i + W <= count; i += W) {
    double x[W], b1[W] = {}, b2[W] = {};
    for (int k = 0; k < W; ++k) x[k] = r[i + k];
    for (Eigen::Index m = b.size() - 1; m >= 0; --m)
      for (int k = 0; k < W; ++k) {
        const double b0 = c[m] + 2.0 * x[k] * b1[k] - b2[k];
        b2[k] = b1[k];
        b1[k] = b0;
      }
    for (int k = 0; k < W; ++k) out[i + k] = b1[k];
  }
  for (; i < count; ++i) out[i] = u_series(b, r[i]);
}

double min_pressure_on_grid(const Eigen::VectorXd& b, double sign) {
  std::array<double, 401> r{}, g{};
  for (int i = 0; i <= 400; ++i) r[static_cast<std::size_t>(i)] = -1.0 + 2.0 * i / 400.0;
  u_series(b, r.data(), g.data(), 401);
  double out = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < r.size(); ++i)
    out = std::min(out, sign * g[i] * std::sqrt(std::max(0.0, 1.0 - r[i] * r[i])));
  return out;
}

double t_series(const Eigen::VectorXd& b, double r) {
  // T_{n+1} = 2 r T_n - T_{n-1}, T_0 = 1, T_1 = r: c_0 + r b_1 - b_2.
  const auto [b1, b2] = clenshaw(b, r, 1);
  return (b.size() > 0 ? b(0) : 0.0) + r * b1 - b2;
}

double series(const Eigen::VectorXd& b, double r, SeriesKind kind) {
  return kind == SeriesKind::T ? t_series(b, r) : u_series(b, r);
}

double even_series(const Eigen::VectorXd& b, double r, SeriesKind kind) {
  // phi_k = X_{2k}: phi_{k+1} = x phi_k - phi_{k-1}, x = 2 T_2(r) = 4 r^2 - 2;
  // Clenshaw's y_k = b_{2k} + x y_{k+1} - y_{k+2} sums to y_0 phi_0 + y_1
  // (phi_1 - x phi_0): U, phi_1 = x + 1, so y_0 + y_1; T, phi_1 = x/2, so
  // y_0 - (x/2) y_1.
  const double x = 4.0 * r * r - 2.0;
  double y1 = 0.0, y2 = 0.0;
  const Eigen::Index top = b.size() == 0 ? -2 : 2 * ((b.size() - 1) / 2);
  for (Eigen::Index m = top; m >= 0; m -= 2) {
    const double y0 = b(m) + x * y1 - y2;
    y2 = y1;
    y1 = y0;
  }
  // Here y1 = y_0 and y2 = y_1.
  return kind == SeriesKind::T ? y1 - 0.5 * x * y2 : y1 + y2;
}

bool odd_terms_zero(const Eigen::VectorXd& b) {
  for (Eigen::Index m = 1; m < b.size(); m += 2)
    if (b(m) != 0.0) return false;
  return true;
}

FirstKindNodes first_kind_nodes(int n) {
  check_size(n);
  FirstKindNodes c;
  c.n = n;
  c.t.resize(n);
  c.x.resize(n - 1);
  for (int i = 1; i <= n; ++i) c.t(i - 1) = std::cos((2 * i - 1) * kPi / (2.0 * n));
  for (int k = 1; k <= n - 1; ++k) c.x(k - 1) = std::cos(k * kPi / n);
  c.x(n / 2 - 1) = 0.0;  // the middle point exactly
  return c;
}

Eigen::MatrixXd flat_collocation_matrix(const FirstKindNodes& nodes, double a,
                                        const std::function<double(double, double)>& kernel_sum) {
  const int h = nodes.n / 2;
  const double wq = 1.0 / nodes.n;
  Eigen::MatrixXd M(h, h);
  for (int k = 0; k + 1 < h; ++k) {  // x_k > 0 for k = 1..N/2-1
    const double x = nodes.x(k);
    for (int j = 0; j < h; ++j) {  // t_j > 0; its mirror -t_j carries the same g
      const double t = nodes.t(j);
      const double up = t - x, um = -t - x;
      M(k, j) = wq * (1.0 / up + 1.0 / um + a * kernel_sum(a * up, a * um));
    }
  }
  M.row(h - 1).setConstant(2.0 * kPi * a * wq);  // equilibrium
  return M;
}

Eigen::VectorXd t_coefficients(const FirstKindNodes& nodes, const Eigen::VectorXd& g_full) {
  const int n = nodes.n;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  for (int m = 0; m < n; ++m) {
    double sum = 0.0;
    for (int i = 1; i <= n; ++i) sum += std::cos(m * (2 * i - 1) * kPi / (2.0 * n)) * g_full(i - 1);
    b(m) = (m == 0 ? 1.0 : 2.0) * sum / n;
  }
  return b;
}

std::string kink_truncation_warning(double truncation, double p_centre, const std::string& what,
                                    double beyond_face) {
  const double scale = std::fabs(p_centre);
  if (!(truncation > 1e-3 * scale)) return {};
  std::ostringstream m;
  m.precision(3);
  m << "the pressure's Chebyshev series resolves the profile's kinks (" << what;
  if (std::isfinite(beyond_face))
    m << ", the contact reaching " << beyond_face << " h past the face";
  m << ") only to " << truncation << " P/h (series_truncation; " << truncation / scale
    << " of p at the contact's centre): corners much sharper than the contact are better "
       "modelled by a flat punch";
  return m.str();
}

}  // namespace movingpunch

#include "movingpunch/profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/Sparse>

#include "movingpunch/errors.hpp"

namespace movingpunch {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string num(double v) {
  std::ostringstream o;
  o.precision(10);
  o << v;
  return o.str();
}

[[noreturn]] void bad_table(const char* name, const std::string& allowed, const std::string& why) {
  throw InvalidParameter(name, allowed, std::string(name) + ": " + why);
}

}  // namespace

const char* profile_kind_name(ProfileKind kind) {
  switch (kind) {
    case ProfileKind::cylinder:
      return "cylinder";
    case ProfileKind::flat:
      return "flat";
    case ProfileKind::rounded_flat:
      return "rounded_flat";
    case ProfileKind::table:
      return "table";
  }
  return "?";
}

bool profile_table_symmetric(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  if (n == 0 || y.size() != n) return false;
  const double xmax = std::max(std::fabs(x.front()), std::fabs(x.back()));
  const auto [ylo, yhi] = std::minmax_element(y.begin(), y.end());
  const double yrange = *yhi - *ylo;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = n - 1 - i;
    if (std::fabs(x[i] + x[j]) > 1e-9 * xmax || std::fabs(y[i] - y[j]) > 1e-9 * yrange)
      return false;
  }
  return true;
}

void check_profile_table(const std::vector<double>& x, const std::vector<double>& y,
                         bool require_symmetric) {
  const std::size_t n = x.size();
  if (n < 5)
    bad_table("profile.x", "at least 5 points",
              "x must have at least 5 points (a cubic spline through the table), got " +
                  std::to_string(n));
  if (y.size() != n)
    bad_table("profile.y", "as many values as x",
              "y must have as many values as x (" + std::to_string(n) + "), got " +
                  std::to_string(y.size()));
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(x[i]))
      bad_table("profile.x", "finite, strictly ascending",
                "x must be finite, got x[" + std::to_string(i) + "] = " + num(x[i]));
    if (!std::isfinite(y[i]))
      bad_table("profile.y", "finite",
                "y must be finite, got y[" + std::to_string(i) + "] = " + num(y[i]));
    if (i > 0 && !(x[i] > x[i - 1]))
      bad_table("profile.x", "finite, strictly ascending",
                "x must be strictly ascending, got x[" + std::to_string(i - 1) +
                    "] = " + num(x[i - 1]) + " then x[" + std::to_string(i) + "] = " + num(x[i]));
  }
  if (!(x.front() < 0.0 && x.back() > 0.0))
    bad_table("profile.x", "x_0 < 0 < x_{n-1} (the table spans the punch's axis x = 0)",
              "the table must span the punch's axis x = 0 (x_0 < 0 < x_{n-1}: heights are "
              "taken relative to x = 0), got x from " +
                  num(x.front()) + " to " + num(x.back()));
  const auto [ylo, yhi] = std::minmax_element(y.begin(), y.end());
  const double yrange = *yhi - *ylo;
  if (require_symmetric) {
    const double xmax = std::max(std::fabs(x.front()), std::fabs(x.back()));
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = n - 1 - i;
      if (std::fabs(x[i] + x[j]) > 1e-9 * xmax)
        bad_table("profile.x", "symmetric about 0 (x_i = -x_{n-1-i} to 1e-9 max|x|)",
                  "x must be symmetric about 0 (x[i] = -x[n-1-i] to 1e-9 of max |x|): x[" +
                      std::to_string(i) + "] = " + num(x[i]) + " but x[" + std::to_string(j) +
                      "] = " + num(x[j]) +
                      "; the undamped solver is symmetric, an asymmetric punch takes the "
                      "asymmetric solver (movingpunch.solve routes it there)");
      if (std::fabs(y[i] - y[j]) > 1e-9 * yrange)
        bad_table("profile.y", "symmetric (y_i = y_{n-1-i} to 1e-9 of the range of y)",
                  "the profile must be symmetric, y(-x) = y(x) (to 1e-9 of the range of y): y[" +
                      std::to_string(i) + "] = " + num(y[i]) + " but y[" + std::to_string(j) +
                      "] = " + num(y[j]) +
                      "; the undamped solver is symmetric, an asymmetric punch takes the "
                      "asymmetric solver (movingpunch.solve routes it there)");
    }
  }
  if (!(yrange > 0.0))
    bad_table("profile.y", "not constant",
              "y is constant: a flat table has no shape to press with (use a flat punch)");
  double dmax = 0.0;
  std::vector<double> d(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    d[i] = (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
    dmax = std::max(dmax, std::fabs(d[i]));
  }
  for (std::size_t i = 0; i + 2 < n; ++i)
    if (d[i + 1] < d[i] - 1e-9 * dmax)
      bad_table("profile.y", "convex (chord slopes non-decreasing)",
                "the profile must be convex: the chord slope falls from " + num(d[i]) + " to " +
                    num(d[i + 1]) + " at x = " + num(x[i + 1]) +
                    " (a non-convex punch can touch in several places, which the single-contact "
                    "solver does not model)");
}

PunchProfile::PunchProfile(ProfileKind kind, double radius, double half_width,
                           const std::vector<double>& x, const std::vector<double>& y)
    : kind_(kind), extent_(kInf), lower_(-kInf), upper_(kInf) {
  switch (kind) {
    case ProfileKind::cylinder:
      require_in_range("radius", radius, 0.0, 1e12, true, false);
      radius_ = radius;
      break;
    case ProfileKind::flat:
      require_in_range("half_width", half_width, 1e-10, 50.0, false, false);
      face_ = half_width;
      break;
    case ProfileKind::rounded_flat:
      require_in_range("half_width", half_width, 0.0, 50.0, false, false);
      require_in_range("radius", radius, 0.0, 1e12, true, false);
      face_ = half_width;
      radius_ = radius;
      break;
    case ProfileKind::table: {
      check_profile_table(x, y);
      x_ = x;
      y_ = y;
      extent_ = std::min(-x.front(), x.back());
      lower_ = x.front();
      upper_ = x.back();
      symmetric_ = profile_table_symmetric(x, y);
      // Not-a-knot cubic spline (it reproduces cubics exactly): second
      // derivatives M_1 .. M_{n-2} from the interior rows, M_0 and M_{n-1} from
      // the continuity of the third derivative at x_1 and x_{n-2}.
      const int n = static_cast<int>(x.size());
      std::vector<double> h(static_cast<std::size_t>(n - 1)), d(static_cast<std::size_t>(n - 1));
      for (int i = 0; i + 1 < n; ++i) {
        const auto s = static_cast<std::size_t>(i);
        h[s] = x[s + 1] - x[s];
        d[s] = (y[s + 1] - y[s]) / h[s];
      }
      const int m = n - 2;  // unknowns M_1 .. M_{n-2}
      std::vector<Eigen::Triplet<double>> t;
      Eigen::VectorXd rhs(m);
      const double h0 = h[0], h1 = h[1], hl = h[static_cast<std::size_t>(n - 2)],
                   hm = h[static_cast<std::size_t>(n - 3)];
      for (int i = 1; i <= m; ++i) {
        const auto s = static_cast<std::size_t>(i);
        const int r = i - 1;
        double diag = 2.0 * (h[s - 1] + h[s]), lower = h[s - 1], upper = h[s];
        rhs(r) = 6.0 * (d[s] - d[s - 1]);
        if (i == 1) {  // M_0 = (1 + h0/h1) M_1 - (h0/h1) M_2
          diag += h0 * (1.0 + h0 / h1);
          upper -= h0 * h0 / h1;
          lower = 0.0;
        }
        if (i == m) {  // M_{n-1} = (1 + hl/hm) M_{n-2} - (hl/hm) M_{n-3}
          diag += hl * (1.0 + hl / hm);
          lower -= hl * hl / hm;
          upper = 0.0;
        }
        t.emplace_back(r, r, diag);
        if (i > 1) t.emplace_back(r, r - 1, lower);
        if (i < m) t.emplace_back(r, r + 1, upper);
      }
      Eigen::SparseMatrix<double> A(m, m);
      A.setFromTriplets(t.begin(), t.end());
      Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
      lu.compute(A);
      if (lu.info() != Eigen::Success)
        bad_table("profile.x", "distinct, well spaced points",
                  "the spline through the table is singular (points too unevenly spaced)");
      const Eigen::VectorXd inner = lu.solve(rhs);
      m_.assign(static_cast<std::size_t>(n), 0.0);
      for (int i = 1; i <= m; ++i) m_[static_cast<std::size_t>(i)] = inner(i - 1);
      m_[0] = (1.0 + h0 / h1) * m_[1] - (h0 / h1) * m_[2];
      const auto last = static_cast<std::size_t>(n - 1);
      m_[last] = (1.0 + hl / hm) * m_[last - 1] - (hl / hm) * m_[last - 2];
      y0_ = spline(0.0, nullptr);
      // The slope on interval i in r = x - x_i: d0 + d1 r + d2 r^2 (spline()'s
      // slope expanded), for slopes().
      dq_.resize(3 * (x.size() - 1));
      for (std::size_t i = 0; i + 1 < x.size(); ++i) {
        const double hi = x_[i + 1] - x_[i];
        dq_[3 * i] = -m_[i] * hi / 2.0 + (y_[i + 1] - y_[i]) / hi - (m_[i + 1] - m_[i]) * hi / 6.0;
        dq_[3 * i + 1] = m_[i];
        dq_[3 * i + 2] = (m_[i + 1] - m_[i]) / (2.0 * hi);
      }
      break;
    }
  }
}

double PunchProfile::spline(double x, double* slope) const {
  const auto it = std::upper_bound(x_.begin(), x_.end(), x);
  std::size_t i = it == x_.begin() ? 0 : static_cast<std::size_t>(it - x_.begin()) - 1;
  i = std::min(i, x_.size() - 2);
  const double h = x_[i + 1] - x_[i], l = x_[i + 1] - x, r = x - x_[i];
  const double A = y_[i] / h - m_[i] * h / 6.0, B = y_[i + 1] / h - m_[i + 1] * h / 6.0;
  if (slope) *slope = (-m_[i] * l * l + m_[i + 1] * r * r) / (2.0 * h) - A + B;
  return (m_[i] * l * l * l + m_[i + 1] * r * r * r) / (6.0 * h) + A * l + B * r;
}

namespace {
[[noreturn]] void beyond(double x, double lo, double hi) {
  throw std::domain_error("the profile table covers " + num(lo) + " <= x <= " + num(hi) +
                          ", asked at x = " + num(x));
}
bool outside(double x, double lo, double hi) {
  const double slack = 1e-12 * std::max(-lo, hi);
  return x < lo - slack || x > hi + slack;
}
}  // namespace

double PunchProfile::slope(double x) const {
  switch (kind_) {
    case ProfileKind::cylinder:
      return x / radius_;
    case ProfileKind::flat:
      return 0.0;
    case ProfileKind::rounded_flat: {
      const double ax = std::fabs(x);
      return ax <= face_ ? 0.0 : std::copysign((ax - face_) / radius_, x);
    }
    case ProfileKind::table: {
      if (outside(x, lower_, upper_)) beyond(x, lower_, upper_);
      double s = 0.0;
      spline(std::clamp(x, lower_, upper_), &s);
      return s;
    }
  }
  return 0.0;
}

void PunchProfile::slopes(const double* x, int n, double* out) const {
  if (kind_ != ProfileKind::table || n <= 0) {
    for (int i = 0; i < n; ++i) out[i] = slope(x[i]);
    return;
  }
  // Ascending points walk the knots once (any other order: one by one).
  for (int i = 1; i < n; ++i)
    if (!(x[i] >= x[i - 1])) {
      for (int j = 0; j < n; ++j) out[j] = slope(x[j]);
      return;
    }
  if (outside(x[0], lower_, upper_)) beyond(x[0], lower_, upper_);
  if (outside(x[n - 1], lower_, upper_)) beyond(x[n - 1], lower_, upper_);
  const std::size_t last = x_.size() - 2;
  std::size_t k = static_cast<std::size_t>(
      std::clamp<std::ptrdiff_t>(std::upper_bound(x_.begin(), x_.end(), x[0]) - x_.begin() - 1, 0,
                                 static_cast<std::ptrdiff_t>(last)));
  for (int i = 0; i < n; ++i) {
    const double xi = std::clamp(x[i], lower_, upper_);
    while (k < last && x_[k + 1] <= xi) ++k;
    const double r = xi - x_[k];
    out[i] = dq_[3 * k] + r * (dq_[3 * k + 1] + r * dq_[3 * k + 2]);
  }
}

double PunchProfile::height(double x) const {
  switch (kind_) {
    case ProfileKind::cylinder:
      return x * x / (2.0 * radius_);
    case ProfileKind::flat:
      return 0.0;
    case ProfileKind::rounded_flat: {
      const double e = std::max(0.0, std::fabs(x) - face_);
      return e * e / (2.0 * radius_);
    }
    case ProfileKind::table:
      if (outside(x, lower_, upper_)) beyond(x, lower_, upper_);
      return spline(std::clamp(x, lower_, upper_), nullptr) - y0_;
  }
  return 0.0;
}

std::vector<double> PunchProfile::slope_chebyshev(double a, int count) const {
  constexpr double kPi = 3.14159265358979323846;
  std::vector<double> d(static_cast<std::size_t>(std::max(count, 0)), 0.0);
  if (count <= 0) return d;
  switch (kind_) {
    case ProfileKind::cylinder:
      d[0] = a / radius_;
      return d;
    case ProfileKind::flat:
      return d;
    case ProfileKind::rounded_flat: {
      // f'(a cos th) = (a cos th - b)/R for th < th_b = acos(b/a), 0 on the
      // face; odd m: d_m = (4/(pi R)) int_0^th_b (a cos th - b) cos(m th) d th.
      const double tb = std::acos(std::min(1.0, face_ / a));
      for (int q = 0; q < count; ++q) {
        const double m = 2.0 * q + 1.0;
        const double c1 = q == 0 ? 0.5 * tb + 0.25 * std::sin(2.0 * tb)
                                 : std::sin((m - 1.0) * tb) / (2.0 * (m - 1.0)) +
                                       std::sin((m + 1.0) * tb) / (2.0 * (m + 1.0));
        d[static_cast<std::size_t>(q)] =
            4.0 / (kPi * radius_) * (a * c1 - face_ * std::sin(m * tb) / m);
      }
      return d;
    }
    case ProfileKind::table: {
      // (4/pi) int_0^{pi/2}: twice the half range's moments, odd m (exact).
      if (outside(a, lower_, upper_)) beyond(a, lower_, upper_);
      if (outside(-a, lower_, upper_)) beyond(-a, lower_, upper_);
      const std::vector<double> half = table_cos_moments(0.0, a, 0.5 * kPi, 2 * count);
      for (int q = 0; q < count; ++q)
        d[static_cast<std::size_t>(q)] = 2.0 * half[static_cast<std::size_t>(2 * q + 1)];
      return d;
    }
  }
  return d;
}

std::vector<double> PunchProfile::kinks() const {
  if (kind_ == ProfileKind::rounded_flat) return {-face_, face_};
  return {};
}

namespace {
// int_{t0}^{t1} (A + w cos th) cos(m th) d th in closed form.
double linear_cos_integral(int m, double A, double w, double t0, double t1) {
  auto F = [&](double t) {
    if (m == 0) return A * t + w * std::sin(t);
    if (m == 1) return A * std::sin(t) + w * (0.5 * t + 0.25 * std::sin(2.0 * t));
    const double mm = m;
    return A * std::sin(mm * t) / mm + w * (std::sin((mm - 1.0) * t) / (2.0 * (mm - 1.0)) +
                                            std::sin((mm + 1.0) * t) / (2.0 * (mm + 1.0)));
  };
  return F(t1) - F(t0);
}
}  // namespace

std::vector<SlopePiece> PunchProfile::slope_pieces(double c, double w) const {
  std::vector<SlopePiece> out;
  if (kind_ != ProfileKind::table) return out;
  const int last = static_cast<int>(x_.size()) - 2;  // the last interval
  // f' = d0 + d1 r + d2 r^2 on interval i (dq_), r = x - x_i = R0 + w t.
  auto piece = [&](int i, double lo, double hi) {
    const auto k = static_cast<std::size_t>(i);
    const double d0 = dq_[3 * k], d1 = dq_[3 * k + 1], d2 = dq_[3 * k + 2], R0 = c - x_[k];
    out.push_back({lo, hi, d0 + R0 * (d1 + R0 * d2), w * (d1 + 2.0 * R0 * d2), w * w * d2});
  };
  // The interval just above c - w, then one piece per knot inside (c - w, c + w).
  const auto first = std::upper_bound(x_.begin(), x_.end(), c - w);
  int i = std::clamp(static_cast<int>(first - x_.begin()) - 1, 0, last);
  double lo = -1.0;
  for (int k = i + 1; k <= last && x_[static_cast<std::size_t>(k)] < c + w; ++k) {
    const double t = std::clamp((x_[static_cast<std::size_t>(k)] - c) / w, -1.0, 1.0);
    if (t <= lo) continue;
    piece(i, lo, t);
    lo = t;
    i = k;
  }
  piece(i, lo, 1.0);
  return out;
}

std::vector<double> PunchProfile::table_cos_moments(double c, double w, double theta_end,
                                                    int count) const {
  // The spline's slope is a quadratic e0 + e1 t + e2 t^2 on each piece
  // (slope_pieces); with t = cos th it is g0 + g1 cos th + g2 cos 2 th, and
  // int cos(k th) cos(m th) = (F_{|m-k|} + F_{m+k})/2 with F_j(th) = sin(j th)/j
  // (F_0 = th). Summed over the pieces between the breakpoints th_b (the
  // knots inside the range), the antiderivatives telescope: each breakpoint
  // contributes F_j(th_b) times the jump of (g0, g1, g2) across it, the range's
  // end the last piece's F_j(theta_end) (F_j(0) = 0).
  constexpr double kPi = 3.14159265358979323846;
  std::vector<double> d(static_cast<std::size_t>(std::max(count, 0)), 0.0);
  if (count <= 0) return d;
  const std::vector<SlopePiece> pieces = slope_pieces(c, w);
  auto cosines = [](const SlopePiece& p, double g[3]) {
    g[0] = p.e0 + 0.5 * p.e2;  // t^2 = (1 + cos 2 th)/2
    g[1] = p.e1;
    g[2] = 0.5 * p.e2;
  };
  // H_k(j) = sum_b jump_k(b) F_j(th_b) + g_k(last piece) F_j(theta_end), j <= count + 1.
  const int J = count + 2;
  std::vector<double> H(3 * static_cast<std::size_t>(J), 0.0);
  // th = acos(u), u = cos th (the breakpoint's t).
  auto add = [&](double th, double u, const double g[3]) {
    // F_j(th) = sin(j th)/j by rotation, recomputed every 32 steps.
    const double s1 = std::sqrt((1.0 - u) * (1.0 + u)), c1 = u;
    double sj = 0.0, cj = 1.0;
    for (int j = 0; j < J; ++j) {
      if (j % 32 == 0) {
        if (j > 0) {
          sj = std::sin(j * th);
          cj = std::cos(j * th);
        }
      } else {
        const double sn = sj * c1 + cj * s1;
        cj = cj * c1 - sj * s1;
        sj = sn;
      }
      const double F = j == 0 ? th : sj / j;
      const auto o = static_cast<std::size_t>(j);
      H[o] += g[0] * F;
      H[static_cast<std::size_t>(J) + o] += g[1] * F;
      H[2 * static_cast<std::size_t>(J) + o] += g[2] * F;
    }
  };
  // From the top piece (th = 0) down to t_end = cos theta_end.
  const double t_end = std::cos(theta_end);
  std::size_t idx = pieces.size() - 1;
  double ga[3];
  cosines(pieces[idx], ga);
  for (; idx > 0 && pieces[idx].lo > t_end; --idx) {
    double gb[3];
    cosines(pieces[idx - 1], gb);
    const double jump[3] = {ga[0] - gb[0], ga[1] - gb[1], ga[2] - gb[2]};
    const double u = pieces[idx].lo;
    add(std::acos(u), u, jump);
    std::copy(gb, gb + 3, ga);
  }
  add(theta_end, t_end, ga);
  for (int m = 0; m < count; ++m) {
    double sum = 0.0;
    for (int k = 0; k <= 2; ++k) {
      const double* Hk = H.data() + static_cast<std::size_t>(k) * static_cast<std::size_t>(J);
      sum += Hk[std::abs(m - k)] + Hk[m + k];
    }
    d[static_cast<std::size_t>(m)] = sum / kPi;
  }
  return d;
}

std::vector<double> PunchProfile::slope_chebyshev_at(double c, double w, int count) const {
  constexpr double kPi = 3.14159265358979323846;
  std::vector<double> d(static_cast<std::size_t>(std::max(count, 0)), 0.0);
  if (count <= 0) return d;
  switch (kind_) {
    case ProfileKind::cylinder:
      // f'(c + w cos th) = (c + w cos th)/R.
      d[0] = 2.0 * c / radius_;
      if (count > 1) d[1] = w / radius_;
      return d;
    case ProfileKind::flat:
      return d;
    case ProfileKind::rounded_flat: {
      // f' = (x - b)/R for x > b, (x + b)/R for x < -b, 0 between: with
      // x = c + w cos th, x > b for th < t1 = acos((b - c)/w) and x < -b for
      // th > t2 = acos((-b - c)/w).
      auto angle = [&](double x) { return std::acos(std::clamp((x - c) / w, -1.0, 1.0)); };
      const double t1 = angle(face_), t2 = angle(-face_);
      for (int m = 0; m < std::min(count, 2); ++m)
        d[static_cast<std::size_t>(m)] = 2.0 / (kPi * radius_) *
                                         (linear_cos_integral(m, c - face_, w, 0.0, t1) +
                                          linear_cos_integral(m, c + face_, w, t2, kPi));
      // m >= 2: the slope vanishes at the kink (A + w cos t_k = 0), so the
      // antiderivative's 1/m terms cancel exactly, leaving
      // d_m = (2 w/(pi R)) [H_m(t1) - H_m(t2)], H_m(t) = (cos t sin(m t)/m -
      // sin t cos(m t))/(m^2 - 1): no cancellation (a kink outside the
      // contact, t_k = 0 or pi, gives H_m = 0).
      // (cos m t, sin m t) by rotation, recomputed every 32 steps: within
      // about 64 ulps.
      const double s1 = std::sin(t1), c1 = std::cos(t1), s2 = std::sin(t2), c2 = std::cos(t2);
      const double scale = 2.0 * w / (kPi * radius_);
      double cm1 = 0, sm1 = 0, cm2 = 0, sm2 = 0;
      for (int m = 2; m < count; ++m) {
        const double mm = m;
        if ((m - 2) % 32 == 0) {
          cm1 = std::cos(mm * t1);
          sm1 = std::sin(mm * t1);
          cm2 = std::cos(mm * t2);
          sm2 = std::sin(mm * t2);
        } else {
          const double a1 = cm1 * c1 - sm1 * s1, a2 = cm2 * c2 - sm2 * s2;
          sm1 = sm1 * c1 + cm1 * s1;
          sm2 = sm2 * c2 + cm2 * s2;
          cm1 = a1;
          cm2 = a2;
        }
        const double h1 = c1 * sm1 / mm - s1 * cm1;
        const double h2 = c2 * sm2 / mm - s2 * cm2;
        d[static_cast<std::size_t>(m)] = scale * (h1 - h2) / ((mm - 1.0) * (mm + 1.0));
      }
      return d;
    }
    case ProfileKind::table: {
      if (outside(c - w, lower_, upper_)) beyond(c - w, lower_, upper_);
      if (outside(c + w, lower_, upper_)) beyond(c + w, lower_, upper_);
      return table_cos_moments(c, w, kPi, count);
    }
  }
  return d;
}

double PunchProfile::slope_chebyshev_tail(double c, double w, int from) const {
  constexpr double kPi = 3.14159265358979323846;
  switch (kind_) {
    case ProfileKind::cylinder:
    case ProfileKind::flat:
      return 0.0;
    case ProfileKind::rounded_flat: {
      // |d_m| <= (2 w/(pi R)) sum_k (|cos t_k|/(m (m^2 - 1)) + |sin t_k|/(m^2 - 1))
      // (slope_chebyshev_at's closed form); sum_{m > L} 1/(m^2 - 1) =
      // (2L + 1)/(2L(L + 1)) and sum_{m > L} 1/(m (m^2 - 1)) = 1/(2L(L + 1)).
      const double L = std::max(from, 1);
      auto angle = [&](double x) { return std::acos(std::clamp((x - c) / w, -1.0, 1.0)); };
      double sum = 0.0;
      for (double t : {angle(face_), angle(-face_)})
        sum += std::fabs(std::cos(t)) / (2.0 * L * (L + 1.0)) +
               std::fabs(std::sin(t)) * (2.0 * L + 1.0) / (2.0 * L * (L + 1.0));
      return 2.0 * w / (kPi * radius_) * sum;
    }
    case ProfileKind::table:
      break;
  }
  return std::numeric_limits<double>::infinity();
}

double PunchProfile::slope_chebyshev_poisson(double c, double w, double q) const {
  constexpr double kPi = 3.14159265358979323846;
  // d_0/2 + sum d_k q^k = (1/pi) int_0^pi f'(c + w cos th) P(th) d th with
  // the Poisson kernel P = (1 - q^2)/(1 - 2 q cos th + q^2); on a piece where
  // f' = (A + w cos th)/R: int P = I0 = 2 atan2((1 + q) sin(th/2), (1 - q)
  // cos(th/2)) and int cos th P = ((1 + q^2) I0 - (1 - q^2) th)/(2 q).
  switch (kind_) {
    case ProfileKind::cylinder:
      return (c + w * q) / radius_;  // d_0/2 = c/R, d_1 = w/R
    case ProfileKind::flat:
      return 0.0;
    case ProfileKind::rounded_flat: {
      if (!(std::fabs(q) < 1.0)) return std::numeric_limits<double>::quiet_NaN();
      auto angle = [&](double x) { return std::acos(std::clamp((x - c) / w, -1.0, 1.0)); };
      const double t1 = angle(face_), t2 = angle(-face_);
      auto i0 = [&](double t) {
        return 2.0 * std::atan2((1.0 + q) * std::sin(0.5 * t), (1.0 - q) * std::cos(0.5 * t));
      };
      auto piece = [&](double A, double a, double b) {  // int_a^b (A + w cos th) P d th
        const double d0 = i0(b) - i0(a);
        // Small |q|: int cos th P = int cos th + sum_k 2 q^k int cos th cos k th
        // (40 terms: below 0.25^40); the closed form's 1/q would cancel.
        if (std::fabs(q) < 0.25) {
          double sum = std::sin(b) - std::sin(a), qk = 1.0;
          for (int k = 1; k < 40; ++k) {
            qk *= q;
            sum +=
                2.0 * qk *
                (k == 1 ? 0.5 * (b - a) + 0.25 * (std::sin(2.0 * b) - std::sin(2.0 * a))
                        : 0.5 * ((std::sin((k - 1.0) * b) - std::sin((k - 1.0) * a)) / (k - 1.0) +
                                 (std::sin((k + 1.0) * b) - std::sin((k + 1.0) * a)) / (k + 1.0)));
          }
          return A * d0 + w * sum;
        }
        const double d1 = ((1.0 + q * q) * d0 - (1.0 - q * q) * (b - a)) / (2.0 * q);
        return A * d0 + w * d1;
      };
      return (piece(c - face_, 0.0, t1) + piece(c + face_, t2, kPi)) / (kPi * radius_);
    }
    case ProfileKind::table:
      break;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

std::string PunchProfile::describe() const {
  switch (kind_) {
    case ProfileKind::cylinder:
      return "cylinder, R/h = " + num(radius_);
    case ProfileKind::flat:
      return "flat punch, half-width b/h = " + num(face_);
    case ProfileKind::rounded_flat:
      return "rounded flat punch, half-width b/h = " + num(face_) +
             ", corner radius R/h = " + num(radius_);
    case ProfileKind::table:
      if (symmetric_)
        return "tabulated profile of " + std::to_string(x_.size()) +
               " points, |x|/h <= " + num(extent_);
      return "asymmetric tabulated profile of " + std::to_string(x_.size()) + " points, " +
             num(lower_) + " <= x/h <= " + num(upper_);
  }
  return "?";
}

}  // namespace movingpunch

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

void check_profile_table(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  if (n < 5)
    bad_table("profile.x", "at least 5 points",
              "x must have at least 5 points (a cubic spline through a symmetric table), got " +
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
  const double xmax = std::max(std::fabs(x.front()), std::fabs(x.back()));
  const auto [ylo, yhi] = std::minmax_element(y.begin(), y.end());
  const double yrange = *yhi - *ylo;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = n - 1 - i;
    if (std::fabs(x[i] + x[j]) > 1e-9 * xmax)
      bad_table("profile.x", "symmetric about 0 (x_i = -x_{n-1-i} to 1e-9 max|x|)",
                "x must be symmetric about 0 (x[i] = -x[n-1-i] to 1e-9 of max |x|): x[" +
                    std::to_string(i) + "] = " + num(x[i]) + " but x[" + std::to_string(j) +
                    "] = " + num(x[j]) +
                    "; the undamped solver is symmetric, an asymmetric punch needs the "
                    "asymmetric solver (not yet available)");
    if (std::fabs(y[i] - y[j]) > 1e-9 * yrange)
      bad_table("profile.y", "symmetric (y_i = y_{n-1-i} to 1e-9 of the range of y)",
                "the profile must be symmetric, y(-x) = y(x) (to 1e-9 of the range of y): y[" +
                    std::to_string(i) + "] = " + num(y[i]) + " but y[" + std::to_string(j) +
                    "] = " + num(y[j]) +
                    "; the undamped solver is symmetric, an asymmetric punch needs the "
                    "asymmetric solver (not yet available)");
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
    : kind_(kind), extent_(kInf) {
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
[[noreturn]] void beyond(double x, double extent) {
  throw std::domain_error("the profile table covers |x| <= " + num(extent) +
                          ", asked at x = " + num(x));
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
      if (std::fabs(x) > extent_ * (1.0 + 1e-12)) beyond(x, extent_);
      double s = 0.0;
      spline(std::clamp(x, -extent_, extent_), &s);
      return s;
    }
  }
  return 0.0;
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
      if (std::fabs(x) > extent_ * (1.0 + 1e-12)) beyond(x, extent_);
      return spline(std::clamp(x, -extent_, extent_), nullptr) - y0_;
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
      // Midpoint rule: per angle, cos(m th) for odd m by the recurrence
      // cos((m + 2) th) = 2 cos(2 th) cos(m th) - cos((m - 2) th).
      const int M = std::max(16 * count + 64, 8192);
      for (int j = 0; j < M; ++j) {
        const double th = (j + 0.5) * kPi / M;
        const double f = slope(a * std::cos(th)) * 2.0 / M;
        const double c2 = 2.0 * std::cos(2.0 * th);
        double prev = std::cos(-th), cur = std::cos(th);  // cos(-th), cos(th)
        for (int q = 0; q < count; ++q) {
          d[static_cast<std::size_t>(q)] += f * cur;
          const double next = c2 * cur - prev;
          prev = cur;
          cur = next;
        }
      }
      return d;
    }
  }
  return d;
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
      return "tabulated profile of " + std::to_string(x_.size()) +
             " points, |x|/h <= " + num(extent_);
  }
  return "?";
}

}  // namespace movingpunch

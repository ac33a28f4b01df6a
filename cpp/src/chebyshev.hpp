// Private: evaluation of Chebyshev series shared by the k1 and damped tables,
// and the interpolant of a smooth function the gap checks read.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace movingpunch::detail {

// sum_{m=0..degree} c[m] T_m(x) for |x| <= 1 by Clenshaw's recurrence.
inline double chebyshev_sum(const double* c, int degree, double x) {
  double b1 = 0.0, b2 = 0.0;
  const double x2 = 2.0 * x;
  for (int m = degree; m >= 1; --m) {
    const double b0 = c[m] + x2 * b1 - b2;
    b2 = b1;
    b1 = b0;
  }
  return c[0] + x * b1 - b2;
}

// cos(pi k (j + 1/2)/m), row k, column j (m x m, row-major), for the
// interpolants' sizes m = d + 1, d = 16, 32, 64, 128: computed once (a
// degree-128 interpolant's transform needs 16641 of them; the gap checks of
// every solve build several).
inline const double* interpolant_cosines(int d) {
  static const std::array<std::vector<double>, 4> tables = [] {
    std::array<std::vector<double>, 4> t;
    for (std::size_t i = 0; i < t.size(); ++i) {
      const int m = (16 << i) + 1;
      t[i].resize(static_cast<std::size_t>(m) * static_cast<std::size_t>(m));
      for (int k = 0; k < m; ++k)
        for (int j = 0; j < m; ++j)
          t[i][static_cast<std::size_t>(k) * static_cast<std::size_t>(m) +
               static_cast<std::size_t>(j)] = std::cos(3.14159265358979323846 * k * (j + 0.5) / m);
    }
    return t;
  }();
  const std::size_t i = d == 16 ? 0 : d == 32 ? 1 : d == 64 ? 2 : 3;
  return tables[i].data();
}

// A smooth function on [a, b] as its Chebyshev interpolant at the points of
// the first kind, of degree 16, 32, 64 or 128: the first whose last two
// coefficients are at the round-off of its values (64 eps of the largest);
// none (ok() false: evaluate directly) when even 128 is not.
class SmoothInterpolant {
 public:
  template <class F>
  SmoothInterpolant(const F& f, double a, double b)
      : SmoothInterpolant(
            Batch{},
            [&f](const std::vector<double>& xs, std::vector<double>& v) {
              for (std::size_t j = 0; j < xs.size(); ++j) v[j] = f(xs[j]);
            },
            a, b) {}
  // The same from a batch of values: fill(xs, v) sets v[j] = f(xs[j]) (v
  // sized as xs; the points descend, x_j = mid + half cos(pi (j + 1/2)/m)).
  struct Batch {};
  template <class Fill>
  SmoothInterpolant(Batch, const Fill& fill, double a, double b)
      : mid_(0.5 * (a + b)), half_(0.5 * (b - a)) {
    for (int d = 16; d <= 128 && half_ > 0.0; d *= 2) {
      const int m = d + 1;
      const auto um = static_cast<std::size_t>(m);
      const double* cs = interpolant_cosines(d);
      std::vector<double> xs(um), v(um);
      for (std::size_t j = 0; j < um; ++j) xs[j] = mid_ + half_ * cs[um + j];  // (row k = 1)
      fill(xs, v);
      double vmax = 0.0;
      for (double x : v) vmax = std::max(vmax, std::fabs(x));
      c_.assign(um, 0.0);
      for (std::size_t k = 0; k < um; ++k) {
        double sum = 0.0;
        for (std::size_t j = 0; j < um; ++j) sum += v[j] * cs[k * um + j];
        c_[k] = (k == 0 ? 1.0 : 2.0) * sum / m;
      }
      if (!std::isfinite(vmax)) break;
      if (std::fabs(c_[static_cast<std::size_t>(d - 1)]) +
              std::fabs(c_[static_cast<std::size_t>(d)]) <=
          64.0 * 2.220446049250313e-16 * vmax)
        return;
    }
    c_.clear();
  }
  bool ok() const { return !c_.empty(); }
  double operator()(double x) const {
    return chebyshev_sum(c_.data(), static_cast<int>(c_.size()) - 1,
                         std::clamp((x - mid_) / half_, -1.0, 1.0));
  }

 private:
  double mid_, half_;
  std::vector<double> c_;
};

}  // namespace movingpunch::detail

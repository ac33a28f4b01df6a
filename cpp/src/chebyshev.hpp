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

// cos(pi m/d), m = 0 .. 2d - 1, for the interpolants' degrees d = 16, 32,
// 64, 128: computed once (the transform of a degree-d interpolant takes
// (d + 1)^2 of them; the gap checks of every solve build several).
inline const double* interpolant_cosines(int d) {
  static const std::array<std::vector<double>, 4> tables = [] {
    std::array<std::vector<double>, 4> t;
    for (std::size_t i = 0; i < t.size(); ++i) {
      const int deg = 16 << i;
      t[i].resize(2 * static_cast<std::size_t>(deg));
      for (int m = 0; m < 2 * deg; ++m)
        t[i][static_cast<std::size_t>(m)] = std::cos(3.14159265358979323846 * m / deg);
    }
    return t;
  }();
  const std::size_t i = d == 16 ? 0 : d == 32 ? 1 : d == 64 ? 2 : 3;
  return tables[i].data();
}

// A smooth function on [a, b] as its Chebyshev interpolant at the points of
// the second kind x_j = mid + half cos(pi j/d), of degree d = 16, 32, 64 or
// 128: the first whose last two coefficients are at the round-off of its
// values (64 eps of the largest); none (ok() false: evaluate directly) when
// even 128 is not. The points nest: each degree evaluates f only at the d/2
// points the last one lacked (129 values in all up to 128, not 245).
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
  // sized as xs; the points descend).
  struct Batch {};
  template <class Fill>
  SmoothInterpolant(Batch, const Fill& fill, double a, double b)
      : mid_(0.5 * (a + b)), half_(0.5 * (b - a)) {
    std::vector<double> vals, xs, v;  // vals: f at cos(pi j/d), j = 0 .. d
    for (int d = 16; d <= 128 && half_ > 0.0; d *= 2) {
      const auto ud = static_cast<std::size_t>(d);
      const double* cs = interpolant_cosines(d);
      // The new points: all at the first degree, else the odd j (the even
      // ones, j = 2i, are the last degree's point i).
      const bool all = d == 16;
      xs.clear();
      for (std::size_t j = all ? 0 : 1; j <= ud; j += all ? 1 : 2)
        xs.push_back(mid_ + half_ * cs[j]);
      v.assign(xs.size(), 0.0);
      fill(xs, v);
      std::vector<double> next(ud + 1);
      for (std::size_t j = 0; j <= ud; ++j)
        next[j] = all ? v[j] : (j % 2 == 1 ? v[j / 2] : vals[j / 2]);
      vals = std::move(next);
      double vmax = 0.0;
      for (double x : vals) vmax = std::max(vmax, std::fabs(x));
      // c_k = (2/d) sum_j'' f_j cos(pi j k/d) (the end terms halved; c_0 and
      // c_d halved too).
      c_.assign(ud + 1, 0.0);
      for (std::size_t k = 0; k <= ud; ++k) {
        double sum = 0.5 * (vals[0] + vals[ud] * cs[(ud * k) % (2 * ud)]);
        for (std::size_t j = 1; j < ud; ++j) sum += vals[j] * cs[(j * k) % (2 * ud)];
        c_[k] = ((k == 0 || k == ud) ? 1.0 : 2.0) * sum / d;
      }
      if (!std::isfinite(vmax)) break;
      if (std::fabs(c_[ud - 1]) + std::fabs(c_[ud]) <= 64.0 * 2.220446049250313e-16 * vmax) return;
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

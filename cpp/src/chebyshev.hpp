// Private: evaluation of Chebyshev series shared by the k1 and damped tables.
#pragma once

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

}  // namespace movingpunch::detail

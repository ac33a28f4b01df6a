// Gauss-Kronrod 7-15 rule (QUADPACK qk15), shared by the k1 quadrature
// (kernel.cpp) and the damped layer's (asymmetric.cpp). Internal header.
#pragma once

namespace movingpunch::detail {

// Gauss-Kronrod 7-15 (QUADPACK qk15): Kronrod nodes (positive half, the last
// is 0), Kronrod weights, and Gauss weights for nodes xgk[1], xgk[3], xgk[5], xgk[7].
constexpr double kXgk[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
constexpr double kWgk[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                           0.381830050505118944950369775488975,
                           0.417959183673469387755102040816327};

// Node j (0..14, ascending) of the rule on [c - h, c + h] and its Kronrod weight.
inline double gk_node(int j, double c, double h) {
  const int k = j < 7 ? j : (j == 7 ? 7 : 14 - j);
  return c + (j < 7 ? -1.0 : 1.0) * h * kXgk[k];
}
inline double gk_weight(int j, double h) {
  const int k = j < 7 ? j : (j == 7 ? 7 : 14 - j);
  return kWgk[k] * h;
}

}  // namespace movingpunch::detail

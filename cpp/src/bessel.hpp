// Bessel functions of the first kind of many orders at once (internal).
#pragma once

#include <vector>

namespace movingpunch::detail {

// J_0(w) .. J_kmax(w) for w > 0 into J (resized to kmax + 1): upward
// recurrence from Hankel's expansion of J_0, J_1 while the order stays below
// w > 25, Miller's downward recurrence normalised by J_0 + 2 sum J_2k = 1
// otherwise.
void bessel_orders(double w, int kmax, std::vector<double>& J);

}  // namespace movingpunch::detail

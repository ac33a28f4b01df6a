// The shape of the punch (docs/theory.md section 13): its surface height f(x)
// above its lowest point (f(0) = 0 for the symmetric shapes here) and the
// slope f'(x), the right-hand side of the contact equation.
#pragma once

#include <string>
#include <vector>

namespace movingpunch {

// A table's slope on a contact (c - w, c + w) is a quadratic in t = (x - c)/w
// between the knots: f'(c + w t) = e0 + e1 t + e2 t^2 on lo <= t <= hi.
struct SlopePiece {
  double lo, hi, e0, e1, e2;
};

enum class ProfileKind {
  cylinder,      // f = x^2/(2 R) (the parabolic approximation of a circle)
  flat,          // a flat face |x| <= b with square corners: the contact is the face
  rounded_flat,  // flat on |x| <= b, corners of radius R: f = (|x| - b)^2/(2 R) beyond
  table,         // a convex table (x_i, y_i), interpolated by a cubic spline
};

// "cylinder", "flat", "rounded_flat", "table".
const char* profile_kind_name(ProfileKind kind);

class PunchProfile {
 public:
  // Validates the parameters of `kind` (throws InvalidParameter naming them):
  // cylinder: 0 < radius <= 1e12; flat: 1e-10 <= half_width <= 50;
  // rounded_flat: 0 <= half_width <= 50 and 0 < radius <= 1e12; table: x, y of
  // equal length >= 5, finite, x strictly ascending with x_0 < 0 < x_{n-1}
  // (heights are taken relative to the punch's axis x = 0), and convex (the
  // slopes of its chords never fall by more than 1e-9 of their largest
  // magnitude). A table need not be symmetric (symmetric() says whether it is:
  // the undamped solver takes symmetric tables only, the asymmetric one any).
  PunchProfile(ProfileKind kind, double radius, double half_width,
               const std::vector<double>& x = {}, const std::vector<double>& y = {});

  ProfileKind kind() const noexcept { return kind_; }
  // f'(x). Throws std::domain_error beyond extent().
  double slope(double x) const;
  // slope() at n points (a table's ascending points in one walk over its
  // knots, its slope's polynomial per interval: slope()'s values to
  // round-off). Throws as slope() does.
  void slopes(const double* x, int n, double* out) const;
  // f(x) - f(0). Throws std::domain_error beyond extent().
  double height(double x) const;
  // The largest |x| the shape is defined to on both sides: min(-x_0, x_{n-1})
  // of a table (inf otherwise); lower() and upper() are the table's x_0 and
  // x_{n-1} (-inf and inf otherwise).
  double extent() const noexcept { return extent_; }
  double lower() const noexcept { return lower_; }
  double upper() const noexcept { return upper_; }
  // False for a table that is not symmetric about x = 0 (x_i = -x_{n-1-i} and
  // y_i = y_{n-1-i} to 1e-9 of max |x| and of the range of y); true otherwise.
  bool symmetric() const noexcept { return symmetric_; }
  // The flat face's half-width b (0 for a cylinder or a table).
  double face() const noexcept { return face_; }
  // The cylinder's radius or the rounded flat's corner radius (0 otherwise).
  double radius() const noexcept { return radius_; }
  // True for the flat punch: the contact is the face, its ends are
  // square-root singular (index +1, SeriesKind::T).
  bool singular_ends() const noexcept { return kind_ == ProfileKind::flat; }
  // The Chebyshev-T coefficients d_1, d_3, ..., d_{2 count - 1} of the slope
  // on a contact of half-width a, f'(a s) = sum_m d_m T_m(s) (odd in s):
  // d_m = (2/pi) int_0^pi f'(a cos th) cos(m th) d th; in closed form for the
  // cylinder, the rounded flat (whose slope has a kink at |x| = b) and a table
  // (its spline's slope is piecewise quadratic: summed over the knots, no
  // quadrature error, so a/h does not drift with N).
  std::vector<double> slope_chebyshev(double a, int count) const;
  // The Chebyshev-T coefficients d_0 .. d_{count-1} of the slope on the
  // contact (c - w, c + w), f'(c + w s) = d_0/2 + sum_{m>=1} d_m T_m(s), any
  // parity: d_m = (2/pi) int_0^pi f'(c + w cos th) cos(m th) d th; in closed
  // form for the cylinder, the rounded flat (split at its kinks) and a table
  // (over its spline's pieces: O(knots on the contact x count)). Throws
  // std::domain_error when (c - w, c + w) leaves a table.
  std::vector<double> slope_chebyshev_at(double c, double w, int count) const;
  // A bound on sum_{m > from} |d_m| of slope_chebyshev_at(c, w, .) (from >=
  // 1): in closed form for the rounded flat (|d_m| <= C/(m^2 - 1)), 0 for the
  // cylinder and the flat punch (whose slope on a contact is linear or 0),
  // infinity for a table (no bound is known).
  double slope_chebyshev_tail(double c, double w, int from) const;
  // The sum d_0/2 + sum_{k>=1} d_k q^k of slope_chebyshev_at(c, w, .) for
  // |q| < 1 (its Poisson integral, in closed form): for the cylinder, the
  // flat punch and the rounded flat; NaN for a table and |q| >= 1. (A
  // bounded zone's half-plane Cauchy integral beside it, every term of its
  // series at once: zones.cpp.)
  double slope_chebyshev_poisson(double c, double w, double q) const;
  // A table's slope on (c - w, c + w) piece by piece, ascending in t and
  // covering [-1, 1] (one piece per knot interval; a contact past the table's
  // ends extends its end pieces); empty for the other shapes.
  std::vector<SlopePiece> slope_pieces(double c, double w) const;
  // The x where the shape's kinks lie (the rounded flat's face ends -b, b;
  // none otherwise): quadratures of the slope split there.
  std::vector<double> kinks() const;
  // One line: e.g. "flat punch, half-width b/h = 0.5".
  std::string describe() const;

 private:
  ProfileKind kind_;
  double radius_ = 0, face_ = 0, extent_ = 0;
  double lower_ = 0, upper_ = 0;
  bool symmetric_ = true;
  // The table's not-a-knot cubic spline: knots, values, second derivatives.
  std::vector<double> x_, y_, m_;
  double y0_ = 0;           // the spline at x = 0
  std::vector<double> dq_;  // the slope on interval i: d0 + d1 r + d2 r^2, r = x - x_i
  double spline(double x, double* slope) const;
  // (2/pi) int_0^theta_end f'(c + w cos th) cos(m th) d th, m < count, for the
  // table's spline, exactly (its slope is piecewise quadratic): O(knots in
  // the range x count).
  std::vector<double> table_cos_moments(double c, double w, double theta_end, int count) const;
};

// Checks a profile table as PunchProfile does (the same messages), without
// solving anything: the API checks a table when it is made. With
// require_symmetric, an asymmetric table is refused too (naming profile.x or
// profile.y).
void check_profile_table(const std::vector<double>& x, const std::vector<double>& y,
                         bool require_symmetric = false);
// True when the table is symmetric about x = 0 to 1e-9 (see PunchProfile).
bool profile_table_symmetric(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace movingpunch

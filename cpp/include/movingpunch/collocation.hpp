// Gauss-Chebyshev collocation for the Cauchy singular integral equation of
// index -1 (density bounded at both ends): p(a r) = g(r) sqrt(1 - r^2).
#pragma once

#include <cstddef>

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace movingpunch {

// The kind of Chebyshev series a contact pressure is written in (docs/theory.md
// section 13): U, bounded at both ends (index -1), p(a r) = sqrt(1 - r^2) sum b_n U_n(r);
// T, square-root singular at both ends (index +1, a flat punch),
// p(a r) = sum b_n T_n(r) / sqrt(1 - r^2).
enum class SeriesKind { U, T };

struct ChebyshevNodes {
  int n = 0;
  Eigen::VectorXd r;  // r_i = cos(i pi / (N + 1)), i = 1..N (zeros of U_N)
  Eigen::VectorXd s;  // s_k = cos(pi (2k - 1) / (2 (N + 1))), k = 1..N+1 (zeros of T_{N+1})
  Eigen::VectorXd w;  // W_i = (1 - r_i^2) / (N + 1): (1/pi) int sqrt(1-r^2) f ~ sum W_i f(r_i)
};

// N must be even and >= 2; throws std::invalid_argument otherwise.
ChebyshevNodes chebyshev_nodes(int n);

// Solves sum_i W_i g_i [1/(r_i - s_k) + a k(a (r_i - s_k))] = s_k for the even
// g, folded to N/2 unknowns (s_k > 0 only; the middle equation s = 0 holds by
// symmetry). Returns g at r_1..r_{N/2} (r > 0). `kernel` must be odd.
Eigen::VectorXd solve_unit_collocation(const ChebyshevNodes& nodes, double a,
                                       const std::function<double(double)>& kernel);
// The same with kernel_sum(u, v) = k(u) + k(v) (one call per matrix entry).
Eigen::VectorXd solve_unit_collocation_sum(const ChebyshevNodes& nodes, double a,
                                           const std::function<double(double, double)>& kernel_sum);

// The folded N/2 x N/2 matrix of solve_unit_collocation_sum (right-hand side
// s_1 .. s_{N/2}): M(k, j) = W_j [1/(r_j - s_k) + 1/(-r_j - s_k) + a (k(a (r_j - s_k))
// + k(a (-r_j - s_k)))].
Eigen::MatrixXd unit_collocation_matrix(const ChebyshevNodes& nodes, double a,
                                        const std::function<double(double, double)>& kernel_sum);
// The same with the kernel's sums at every entry in one call: sums(u, v, out,
// n) sets out[i] = k(u[i]) + k(v[i]) for i < n (KernelK1::sum_many).
using KernelSums = std::function<void(const double*, const double*, double*, std::size_t)>;
Eigen::MatrixXd unit_collocation_matrix(const ChebyshevNodes& nodes, double a,
                                        const KernelSums& sums);

// The singular terms of a graded top's kernel (kernel.hpp), integrated
// exactly: the folded N/2 x N/2 matrix to add to unit_collocation_matrix's
// (whose kernel_sum then carries the regular part only), entry (k, j) =
// a W_j (4/pi) sum_{n even < N} U_n(r_j) Q_n(s_k), Q_n(s) = sum over the terms of
// coef int_{-1}^{1} sqrt(1 - r^2) U_n(r) (a (r - s))^power sigma(a (r - s)) dr,
// sigma = sgn or ln|.|: the exact integral of the degree N - 1 interpolant of g
// against each term (moments in closed form, docs/theory.md section 16.5).
struct KernelSingularTerm;
Eigen::MatrixXd singular_collocation_matrix(const ChebyshevNodes& nodes, double a,
                                            const std::vector<KernelSingularTerm>& terms);

// int_{-1}^{1} sqrt(1 - r^2) U_n(r) (r - s)^power sigma(r - s) dr for n = 0..n_max - 1
// (sigma: 0 = 1, 1 = sgn, 2 = ln|.|), |s| < 1.
std::vector<double> singular_moments(int n_max, int power, int sigma, double s);

// Coefficients b_n (n = 0..N-1) of g(r) = sum b_n U_n(r) from the nodal values
// at all N nodes (exact for polynomials of degree < N).
Eigen::VectorXd u_coefficients(const ChebyshevNodes& nodes, const Eigen::VectorXd& g_full);

// g(r) = sum b_n U_n(r) for |r| <= 1 (Clenshaw).
double u_series(const Eigen::VectorXd& b, double r);
// The same at count points r[i] into out[i], eight recurrences interleaved
// (each point's arithmetic as u_series', bit for bit: a long series' many
// points at the speed of the multiplier, not of its latency).
void u_series(const Eigen::VectorXd& b, const double* r, double* out, int count);

// min of sign sqrt(1 - r^2) sum b_n U_n(r) on the 401 points r = -1 + i/200:
// the solutions' min_pressure (per P/h) from their U-series.
double min_pressure_on_grid(const Eigen::VectorXd& b, double sign = 1.0);

// The minimum of g(r) = sum b_n U_n(r) on -1 <= r <= 1 (a dense scan of
// max(401, 16 (N + 1) + 257) Chebyshev points, then golden-section refinement
// between the neighbours of the best one, to ~1e-15 in r); its abscissa in
// *r_min. Both solvers' pressure_margin.
double u_series_minimum(const Eigen::VectorXd& b, double* r_min = nullptr);

// Highest even n with |b_n| above round-off of the largest coefficient.
Eigen::Index last_even_term(const Eigen::VectorXd& b);

// Exact cosine transform of p(x) = sqrt(1 - (x/a)^2) g(x/a) on |x| < a, g even:
// int_0^a p(x) cos(alpha x) dx = (a/2) sum_n b_n pi (n+1) (-1)^{n/2} J_{n+1}(alpha a)/(alpha a)
// (the Chebyshev-Bessel identity). Odd coefficients are ignored.
double u_series_cosine_transform(const Eigen::VectorXd& b, double a, double alpha);
// The same at many alpha: out[i] = u_series_cosine_transform(b, a, alpha[i]),
// four at a time (Miller's recurrences of four arguments interleaved, the sum
// accumulated on the way down): several times faster than one by one.
void u_series_cosine_transforms(const Eigen::VectorXd& b, double a, const double* alpha,
                                double* out, std::size_t count);

// g(r) = sum b_n T_n(r) for |r| <= 1 (Clenshaw).
double t_series(const Eigen::VectorXd& b, double r);
// g(r) = sum b_n U_n(r) or sum b_n T_n(r).
double series(const Eigen::VectorXd& b, double r, SeriesKind kind);
// The same for a series with no odd terms (b_1 = b_3 = ... = 0, an even g:
// the symmetric contacts), by Clenshaw's recurrence in steps of two,
// X_{n+2} = 2 T_2(r) X_n - X_{n-2}: half the work.
double even_series(const Eigen::VectorXd& b, double r, SeriesKind kind);
// Whether every odd coefficient is exactly 0.
bool odd_terms_zero(const Eigen::VectorXd& b);
// The minimum of series(b, r, kind) on -1 <= r <= 1 (the scan and refinement
// of u_series_minimum); its abscissa in *r_min.
double series_minimum(const Eigen::VectorXd& b, SeriesKind kind, double* r_min = nullptr);

// Exact cosine transform int_0^a p(x) cos(alpha x) dx of an even pressure of
// either kind (odd coefficients ignored): U as u_series_cosine_transform;
// T: (a/2) sum_n b_n pi (-1)^{n/2} J_n(alpha a), from
// int_{-1}^{1} T_n(r)/sqrt(1 - r^2) e^{i w r} dr = pi i^n J_n(w).
double series_cosine_transform(const Eigen::VectorXd& b, SeriesKind kind, double a, double alpha);
void series_cosine_transforms(const Eigen::VectorXd& b, SeriesKind kind, double a,
                              const double* alpha, double* out, std::size_t count);

// Gauss-Chebyshev collocation of the first kind for the index +1 equation
// (a flat punch: the density p(a r) = g(r)/sqrt(1 - r^2), unbounded at both
// ends): nodes t_i = cos((2i - 1) pi/(2N)) (i = 1..N, zeros of T_N) and
// collocation points x_k = cos(k pi/N) (k = 1..N-1, zeros of U_{N-1}):
// (1/pi) int g(t)/sqrt(1-t^2) f(t) dt ~ (1/N) sum g(t_i) f(t_i).
struct FirstKindNodes {
  int n = 0;
  Eigen::VectorXd t;  // t_i, i = 1..N
  Eigen::VectorXd x;  // x_k, k = 1..N-1
};
// N must be even and >= 2; throws std::invalid_argument otherwise.
FirstKindNodes first_kind_nodes(int n);
// The folded N/2 x N/2 system of an even g: the N/2 - 1 points x_k > 0,
// M(k, j) = (1/N) [1/(t_j - x_k) + 1/(-t_j - x_k) + a (k(a (t_j - x_k)) + k(a (-t_j - x_k)))]
// (right-hand side 0, the slope of a flat face), and the equilibrium row
// (2 pi a / N) sum_j g_j = 1 (int p = P, g over P/h). Returns the matrix.
Eigen::MatrixXd flat_collocation_matrix(const FirstKindNodes& nodes, double a,
                                        const std::function<double(double, double)>& kernel_sum);
// Coefficients b_n (n = 0..N-1) of g(r) = sum b_n T_n(r) from its values at
// all N nodes t_i (exact for polynomials of degree < N).
Eigen::VectorXd t_coefficients(const FirstKindNodes& nodes, const Eigen::VectorXd& g_full);

// The one warning both solvers give when a profile's pressure series resolves
// its kinks (a rounded flat's corners, a table's spline) only to `truncation`
// over P/h (series_truncation) and that is above 1e-3 of `p_centre`, the
// pressure at the contact's centre over P/h (the undamped solver's p(0)):
// empty otherwise. `what` names the profile (PunchProfile::describe),
// `beyond_face` is how far a rounded flat's contact reaches past its face, on
// average per side (NaN: not shown).
std::string kink_truncation_warning(double truncation, double p_centre, const std::string& what,
                                    double beyond_face);

}  // namespace movingpunch

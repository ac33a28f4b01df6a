// The regular part of the singular integral equation's kernel,
//   k1(u) = (1/phi1) * int_0^inf (M1(alpha) - phi1) sin(alpha u) d alpha,
// an odd, smooth difference kernel independent of the contact width. It is
// computed once per (vstar, kw, nu) by adaptive Gauss-Kronrod quadrature in
// alpha and tabulated as an odd Chebyshev series on |u| <= L.
#pragma once

#include <array>
#include <complex>
#include <memory>
#include <utility>
#include <vector>

#include "movingpunch/layer_response.hpp"
#include "movingpunch/medium.hpp"

namespace movingpunch {

// The exact part of a graded top's kernel (docs/theory.md section 16.5).
// f(t) = (M1 - phi1)/phi1 ~ sum_k b_k t^-k (b_k = a_k gamma^k) as t -> inf;
// the quadrature integrates f - S, S(t) = sum_{k=1}^{K} b_k R_k(t),
//   R_k(t) = (1/(k-1)!) int_0^L s^(k-1) e^(-t s) ds = t^-k P(k, L t)
// (P the regularised lower incomplete gamma function: R_k = t^-k up to
// e^(-L t) (L t)^(k-1)/(k-1)!, finite at t = 0), and adds the sine transform
// of S in closed form:
//   int_0^inf R_k(t) sin(t u) dt = (1/(k-1)!) int_0^L s^(k-1) u/(s^2 + u^2) ds
//     = singular_k(u) + smooth_k(u),
// singular_k = (-1)^m (pi/2)/(2m)! u^(2m) sgn(u)  (k = 2m + 1),
//            = -(-1)^m/(2m+1)! u^(2m+1) ln|u|     (k = 2m + 2),
// smooth_k analytic for |Im u| < L (arctan(u/L), ln(L^2 + u^2) and
// polynomials). The collocation integrates the singular parts exactly
// against the density's Chebyshev expansion (collocation.hpp).
struct KernelSubtraction {
  std::vector<double> b;  // b_1 .. b_K
  double L = 1.0;
  bool empty() const noexcept { return b.empty(); }
  // S(t) = sum_k b_k R_k(t), t >= 0.
  double value(double t) const;
  // sum_k b_k smooth_k(u).
  double smooth(double u) const;
  // sum_k b_k singular_k(u) (u != 0; 0 at u = 0).
  double singular(double u) const;
};

// One singular term coef * u^power * (log ? ln|u| : sgn(u)) of a kernel.
struct KernelSingularTerm {
  int power = 0;
  bool log = false;
  double coef = 0.0;
};
std::vector<KernelSingularTerm> singular_terms(const KernelSubtraction& s);

struct AlphaQuadrature {
  std::vector<double> alpha;                     // nodes, 15 per panel, ascending
  std::vector<double> weight;                    // weights
  std::vector<double> m1;                        // M1(alpha) at the nodes
  std::vector<double> panel_centre, panel_half;  // panel p holds nodes 15p .. 15p+14
  double alpha_max = 0;                          // M1 = phi1 to double precision beyond it
  double error_estimate = 0;                     // sum of |K15 - G7| of (M1 - phi1)/phi1
  // Per panel (same order as panel_centre), the error of the rule for
  // f = (M1 - phi1)/phi1 on the panel: its truncation (QUADPACK's estimate, a
  // bound; the panel's share of tol where it stopped at its round-off floor,
  // its |K15 - G7| being round-off there) and the rms round-off of the nodal values (2 eps (1 + |f|
  // + f^2) each, independent: eps |f|^2 near a resonance). Empty if not filled.
  std::vector<double> panel_error, panel_roundoff;
  // The subtracted asymptotics (empty but for a graded top: then the rule
  // integrates f - S), S at the nodes, and a bound of the integral of
  // |f - S| beyond alpha_max (the algebraic tail; 0 otherwise).
  KernelSubtraction subtraction;
  std::vector<double> sub;
  double tail_bound = 0;
};

// How far in alpha a quadrature must reach: until M1 - phi1 at the surface
// is negligible (Medium::decay_rate), or the mode's remainder at every depth
// (Medium::field_decay_rate).
enum class Reach { surface, field };
// Adaptive quadrature nodes for integrals of (M1 - phi1) times an oscillation
// of frequency up to `max_frequency`, resolved to absolute tolerance `tol`,
// on [0, alpha_max] where the medium's decay (of `reach`) is negligible.
// With a non-empty `sub` (reach surface only) the integrand is f - S
// (KernelSubtraction) and alpha_max also covers the algebraic tail of f - S,
// |a_{K+1}| (gamma/t)^(K+1) (Medium::kernel_asymptotics), up to kMaxAlphaGraded.
AlphaQuadrature build_alpha_quadrature(const Medium& model, double tol, double max_frequency,
                                       Reach reach = Reach::surface,
                                       const KernelSubtraction& sub = {});
inline constexpr double kMaxAlphaGraded = 2e4;

// Fourier integrals int g(alpha) e^{i alpha x} d alpha over the panels of a
// quadrature, exact for the degree-14 interpolant of g on each panel (Filon):
// accurate for every x, however large, at a cost independent of x. The
// integrand g must be smooth on the panels (the quadrature resolved it).
class FilonIntegrator {
 public:
  using cplx = std::complex<double>;
  explicit FilonIntegrator(const AlphaQuadrature& q);
  int panels() const noexcept { return static_cast<int>(centre_.size()); }
  // The upper end of the last panel (0 without panels).
  double upper() const noexcept { return centre_.empty() ? 0.0 : centre_.back() + half_.back(); }
  // Legendre coefficients (15 per panel) of g given at the quadrature nodes
  // (of every panel, or of the first ones only).
  std::vector<double> coefficients(const std::vector<double>& g) const;
  // Row of weights K(p, k) with int g e^{i alpha x} = sum K(p, k) c(p, k).
  void weights(double x, std::vector<cplx>& K) const;
  // int g cos(alpha x) (real part) and int g sin(alpha x) (imaginary part).
  static cplx apply(const std::vector<cplx>& K, const std::vector<double>& c);
  // apply(weights(x), c), bit for bit (but signed zeros), without the
  // weight vector (the k1 tables' values).
  cplx weights_applied(double x, const std::vector<double>& c) const;
  // The same as apply(weights(x), c), fused: no weight vector, one complex
  // multiplication per panel instead of one per coefficient, most phases by
  // rotation (as integral_pair: a few 1e-15 relative). A c holding the
  // first P panels' coefficients only (15 P values) sums those panels.
  cplx integral(double x, const std::vector<double>& c) const;
  // integral(x, c) with every phase by sin/cos (to round-off: the k1 tables).
  cplx integral_exact(double x, const std::vector<double>& c) const;
  // integral(x, c1) and integral(x, c2) (to a few 1e-15 relative) sharing
  // the Bessel functions and the phases, most phases by rotation.
  std::pair<cplx, cplx> integral_pair(double x, const std::vector<double>& c1,
                                      const std::vector<double>& c2) const;
  // integral(x, c1) and integral(x, c2), bit for bit, sharing the Bessel
  // functions and the sin/cos of each phase (the damped kernel's tables).
  std::pair<cplx, cplx> integral_pair_exact(double x, const std::vector<double>& c1,
                                            const std::vector<double>& c2) const;

 private:
  std::vector<double> centre_, half_;
  std::vector<double> widths_;         // the distinct half-widths
  std::vector<std::size_t> width_of_;  // panel -> index into widths_
  // j_0 .. j_14 (h ax) for every distinct half-width h.
  void bessel_by_width(double ax, std::vector<std::array<double, 15>>& j) const;
  // Rotate: most phases by rotation from the previous panel's (M > 1).
  template <std::size_t M, bool Rotate>
  void integrals(double x, const std::array<const std::vector<double>*, M>& c,
                 std::array<cplx, M>& out) const;
};

class KernelK1 {
 public:
  // Tables with range * alpha_max above this are held piecewise (below).
  static constexpr double kPieceBandwidth = 600.0;
  // Tabulates k1 on |u| <= range to tolerance tol (absolute, k1 is O(1)),
  // for a medium with a real response (Medium::real()).
  // `shorter`: a table of the same medium and tol (the cache's growth) whose
  // quadrature is reused when it is the one this range needs.
  KernelK1(std::shared_ptr<const Medium> medium, double tol, double range,
           const KernelK1* shorter = nullptr);
  // The homogeneous layer of `model`.
  KernelK1(const LayerModel& model, double tol, double range);

  double operator()(double u) const;  // any |u| <= range(): the whole k1
  // The regular part k1 - singular terms at u and v, added (faster than two
  // calls): the whole k1(u) + k1(v) unless singular() is non-empty (a graded
  // top), whose terms the collocation integrates exactly.
  double sum(double u, double v) const;
  // out[i] = sum(u[i], v[i]) for i < n, several recurrences interleaved.
  void sum_many(const double* u, const double* v, double* out, std::size_t n) const;
  // The singular terms of k1 (empty but for a graded top).
  const std::vector<KernelSingularTerm>& singular() const noexcept { return singular_; }
  // A graded top's slow tails beyond the quadratures' reach, medium
  // constants of the bounds a solve makes of what they leave out
  // (graded_tails, contact.cpp): |M1 - phi1| <= surface_c/alpha beyond
  // alpha_max and the mode remainder's |sigma_x(0)| <= field_c/alpha beyond
  // field_reach (each the larger of alpha |.| at the reach and twice it).
  // Zero but for a graded top.
  struct GradedTailConstants {
    double surface_c = 0.0;
    double field_reach = 0.0;
    double field_c = 0.0;
  };
  const GradedTailConstants& graded_tail_constants() const noexcept { return tails_; }
  const KernelSubtraction& subtraction() const noexcept { return sub_; }
  double range() const noexcept { return range_; }
  const AlphaQuadrature& quadrature() const noexcept { return quad_; }
  const Medium& model() const noexcept { return *model_; }
  const std::shared_ptr<const Medium>& medium() const noexcept { return model_; }
  double tol() const noexcept { return tol_; }
  // Coefficients held (of the global series, or of all pieces).
  int terms() const noexcept {
    return static_cast<int>(piece_coef_.empty() ? coef_.size() : piece_coef_.size());
  }
  bool piecewise() const noexcept { return !piece_coef_.empty(); }
  // Direct Filon quadrature (no Chebyshev table); any u.
  double direct(double u) const;
  // What the table holds: the quadrature's part plus, on a graded top, the
  // subtracted series' smooth closed forms (direct() less the singular
  // terms; one table read per entry instead of an arctan and a log).
  double regular(double u) const;
  // Where the tabulated k1 can be wrong, for error estimates: the quadrature
  // whose panels produced the table's values (its panel_error and
  // panel_roundoff bound the error of each panel's share of k1(u) =
  // int f sin(alpha u), f = (M1 - phi1)/phi1).
  const AlphaQuadrature& value_quadrature() const noexcept {
    return piece_coef_.empty() ? quad_ : value_quad_;
  }
  // The table's own error bounds (absolute, any |u| <= range): of its
  // truncation (systematic) and of the round-off of its values (a few eps of
  // the Filon sums, which vary from one u to the next).
  double table_error() const noexcept { return table_error_; }
  // The first omitted Chebyshev order of the global table (0 for a piecewise
  // one): its truncation error has about the shape T_order(u / range).
  int table_order() const noexcept { return table_order_; }
  double table_roundoff() const noexcept { return table_roundoff_; }
  const FilonIntegrator& filon() const noexcept { return *filon_; }

  // The surface displacement's Green's function from the table (a global
  // table of a medium with M1(0) = 0 and no subtracted series):
  //   G(u) = int_0^inf (M1/alpha) cos(alpha u) d alpha
  //        = greens_zero() - phi1 [K1(u) + ln|u|],   K1(u) = int_0^u k1,
  // since d/du of the smooth part int [M1 - phi1 (1 - e^-alpha)]/alpha cos
  // is -phi1 k1(u) - phi1 u/(1 + u^2) (docs/theory.md section 6).
  bool greens_tabulated() const noexcept { return !k1_integral_.empty(); }
  // G_s(0) = int_0^inf [M1 - phi1 (1 - e^-alpha)]/alpha d alpha (the
  // quadrature to alpha_max, phi1 E1(alpha_max) beyond).
  double greens_zero() const noexcept { return greens_zero_; }
  // K1(u) for |u| <= range(): out[i] = K1(u[i]), eight recurrences
  // interleaved. Its degree in u is k1_integral_degree() (the table's + 1).
  void k1_integrals(const double* u, double* out, std::size_t n) const;
  int k1_integral_degree() const noexcept { return 2 * static_cast<int>(k1_integral_.size()) - 2; }
  // Per panel of quadrature(), the rule's integral of |f|, f = [M1 - phi1
  // (1 - e^-alpha)]/alpha (the Green's function's smooth part): with a bound
  // of the pressure's transform, how much of the displacement lies beyond a
  // wavenumber (the gap scan's sampling; SymmetricSolution). Filled when
  // greens_tabulated().
  const std::vector<double>& greens_panel_mass() const noexcept { return greens_mass_; }

 private:
  std::shared_ptr<const Medium> model_;
  double tol_;
  double range_;
  KernelSubtraction sub_;
  std::vector<KernelSingularTerm> singular_;
  GradedTailConstants tails_;
  double numeric(double u) const;  // the tabulated part (Filon sum)
  double table(double u) const;
  AlphaQuadrature quad_;
  std::shared_ptr<const FilonIntegrator> filon_;
  std::vector<double> f_coef_;  // Legendre coefficients of (M1 - phi1)/phi1 per panel
  std::vector<double> coef_;    // Chebyshev coefficients in u / range
  std::vector<double> odd_;     // coef_[1], coef_[3], ...: the series is odd
  // Long tables (range * alpha_max above kPieceBandwidth: k1 oscillates many
  // times on |u| <= range) are held as piecewise Chebyshev interpolants of
  // degree kPieceDegree on equal pieces of [0, range], built from direct()
  // values: building and evaluating them costs O(range) and O(kPieceDegree),
  // where one global series would need thousands of terms per evaluation.
  static constexpr int kPieceDegree = 24;
  std::vector<double> piece_coef_;  // (kPieceDegree + 1) per piece; empty: global series
  AlphaQuadrature value_quad_;      // the coarse quadrature of a piecewise table
  double table_error_ = 0, table_roundoff_ = 0;
  int table_order_ = 0;
  double piece_width_ = 0;
  // K1(u) = range * sum_j k1_integral_[j] T_j(T_2(u / range)) (empty: not
  // greens_tabulated()).
  std::vector<double> k1_integral_;
  double greens_zero_ = 0.0;
  std::vector<double> greens_mass_;
  void tabulate_greens();
  double global(double u) const;
  double piece(double u) const;
  void build_pieces();
};

// Process-wide cache of k1 tables, keyed on the medium (Medium::key()) and tol: solves that
// share a material and speed (a load or radius sweep) reuse one table.
// Returns a cached table whose range is at least `min_range` (and at most
// kMaxRangeRatio times it, so a tiny contact never pays for a huge table), or
// builds one of range `build_range` (>= min_range) and caches it; when a
// table of the same key exists but is shorter than min_range (a widening
// sweep), of range at least kGrowth times the longest such table's
// (geometric growth: a sweep in any order builds a few tables), unless that
// would turn a global table piecewise where a global one suffices, or
// `grow` is false (a solve that already built a table for a narrower trial
// width: its own tables stay as it asks, which its error budget is
// calibrated on). `built`
// (optional) is set to whether a table was built. Thread-safe; the least
// recently used tables are evicted beyond kCapacity.
struct KernelCacheInfo {
  std::size_t size = 0;    // tables held
  std::size_t hits = 0;    // requests served from the cache
  std::size_t misses = 0;  // requests that built a table
};
inline constexpr double kMaxRangeRatio = 24.0;
inline constexpr std::size_t kKernelCacheCapacity = 32;
inline constexpr double kGrowth = 2.0;
std::shared_ptr<const KernelK1> cached_kernel(const std::shared_ptr<const Medium>& medium,
                                              double tol, double min_range, double build_range,
                                              bool* built = nullptr, bool grow = true);
// The homogeneous layer of `model`.
std::shared_ptr<const KernelK1> cached_kernel(const LayerModel& model, double tol, double min_range,
                                              double build_range, bool* built = nullptr,
                                              bool grow = true);
KernelCacheInfo kernel_cache_info();
// Clears the k1 tables and the damped kernel tables (asymmetric.hpp).
void clear_kernel_cache();

}  // namespace movingpunch

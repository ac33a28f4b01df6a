#include "movingpunch/kernel.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Dense>
#include <sstream>
#include <stdexcept>

#include "chebyshev.hpp"
#include "gauss_kronrod.hpp"
#include "layer_basis.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/interrupt.hpp"

namespace movingpunch {

namespace {

constexpr double kPi = 3.14159265358979323846;

using detail::kWg;
using detail::kWgk;
using detail::kXgk;

struct Panel {
  double lo, hi;
  double nodes[15];
  double m1[15];
  double sub[15];
  double kronrod, error;
  double resabs;      // integral of |f|
  double floor;       // round-off floor of the rule on this panel
  double truncation;  // QUADPACK's rescaled |K15 - G7|
  double round_rms;   // rms round-off of the rule from independent nodal errors
  double systematic;  // the part of truncation that is not round-off
};

Panel eval_panel(const Medium& model, double lo, double hi, const KernelSubtraction& sub) {
  check_interrupt();  // 15 layer responses: microseconds
  Panel p{};
  p.lo = lo;
  p.hi = hi;
  const double c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
  const double phi1 = model.phi1();
  double fk = 0.0, fg = 0.0, fabs_sum = 0.0;
  double fv[15];
  for (int j = 0; j < 15; ++j) {
    const int k = j < 7 ? j : (j == 7 ? 7 : 14 - j);
    const double sgn = j < 7 ? -1.0 : 1.0;
    const double x = c + sgn * h * kXgk[k];
    p.nodes[j] = x;
    p.m1[j] = model.surface_response(x).M1.real();
    p.sub[j] = sub.empty() ? 0.0 : sub.value(x);
    const double f = (p.m1[j] - phi1) / phi1 - p.sub[j];
    fv[j] = f;
    fk += kWgk[k] * f;
    fabs_sum += kWgk[k] * std::fabs(f);
    if (k % 2 == 1) fg += kWg[k / 2] * f;
  }
  // QUADPACK's estimate: the raw |K15 - G7| rescaled by the integrand's
  // variation, floored at the round-off of the rule.
  const double mean = 0.5 * fk;
  double resasc = 0.0;
  for (int j = 0; j < 15; ++j) {
    const int k = j < 7 ? j : (j == 7 ? 7 : 14 - j);
    resasc += kWgk[k] * std::fabs(fv[j] - mean);
  }
  resasc *= h;
  p.kronrod = fk * h;
  p.resabs = fabs_sum * h;
  double err = std::fabs((fk - fg) * h);
  if (resasc > 0.0 && err > 0.0) err = resasc * std::min(1.0, std::pow(200.0 * err / resasc, 1.5));
  constexpr double eps = 2.220446049250313e-16;
  // f = (M1 - phi1)/phi1 carries an absolute round-off of a few eps where
  // M1 ~ phi1, and eps |f|^2 near a resonance, where the 4 x 4 boundary
  // system is ill-conditioned in proportion to |M1|.
  double fmax = 0.0;
  for (double v : fv) fmax = std::max(fmax, std::fabs(v));
  p.floor = 4.0 * eps * (2.0 * h + p.resabs * (1.0 + fmax));
  // The same node by node, as independent errors of 2 eps (1 + |f| + f^2)
  // (M1 near a resonance: about eps |M1| relative, measured against the
  // transfer-matrix evaluation), added in quadrature.
  double r2 = 0.0;
  for (int j = 0; j < 15; ++j) {
    const int k = j < 7 ? j : (j == 7 ? 7 : 14 - j);
    const double e = kWgk[k] * h * 2.0 * eps * (1.0 + std::fabs(fv[j]) + fv[j] * fv[j]);
    r2 += e * e;
  }
  p.round_rms = std::sqrt(r2);
  p.truncation = err;
  p.error = std::max(err, p.floor);
  return p;
}

double kronrod_weight(int j, double h) {
  const int k = j < 7 ? j : (j == 7 ? 7 : 14 - j);
  return kWgk[k] * h;
}

}  // namespace

namespace {

// 1/k!, k = 0 .. 20.
double inv_factorial(int k) {
  double f = 1.0;
  for (int i = 2; i <= k; ++i) f /= i;
  return f;
}

}  // namespace

double KernelSubtraction::value(double t) const {
  const double x = L * t;
  double out = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const int k = static_cast<int>(i) + 1;
    double r;
    if (x <= 40.0) {
      // R_k = L^k e^-x sum_j x^j/(k+j)!: positive terms, no cancellation.
      double term = inv_factorial(k), sum = 0.0;
      for (int j = 0; j < 400; ++j) {
        sum += term;
        term *= x / (k + j + 1);
        if (term <= 1e-18 * sum && j > x) break;
      }
      r = std::pow(L, k) * std::exp(-x) * sum;
    } else {
      // R_k = t^-k (1 - e^-x sum_{j<k} x^j/j!): the correction is below e^-40 x^k.
      double term = 1.0, sum = 0.0;
      for (int j = 0; j < k; ++j) {
        sum += term;
        term *= x / (j + 1);
      }
      r = std::pow(t, -k) * (1.0 - std::exp(-x) * sum);
    }
    out += b[i] * r;
  }
  return out;
}

double KernelSubtraction::smooth(double u) const {
  // Term j = k - 1 (of b_k / j!): u^(2q+1) L^e / e summed over q < m by
  // Horner's rule in u^2 (e = 2(m - q) - 1 for j = 2m, 2(m - q) for
  // j = 2m + 1; the powers of L by running products: no pow), then one
  // arctan or log for all (j = 2m: -(-1)^m u^(2m) arctan(u/L); j = 2m + 1:
  // (-1)^m u^(2m+1) ln(L^2 + u^2)/2). Called at every collocation entry.
  if (b.empty()) return 0.0;
  const double at = std::atan(u / L), lg = 0.5 * std::log(L * L + u * u);
  const double u2 = u * u, L2 = L * L;
  double out = 0.0, fact = 1.0;  // j!
  double u2m = 1.0;              // u^(2m)
  int m_have = 0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const int j = static_cast<int>(i);
    if (j > 1) fact *= j;
    const bool even = j % 2 == 0;
    const int m = even ? j / 2 : (j - 1) / 2;
    for (; m_have < m; ++m_have) u2m *= u2;
    double poly = 0.0, Lp = even ? L : L2;  // L^e at q = m - 1 (e = 1 or 2)
    for (int q = m - 1; q >= 0; --q) {
      const double e = static_cast<double>(even ? 2 * (m - q) - 1 : 2 * (m - q));
      poly = poly * u2 + ((q % 2) ? -Lp : Lp) / e;
      Lp *= L2;
    }
    const double sign_m = (m % 2) ? -1.0 : 1.0;
    const double v = u * poly + (even ? -sign_m * u2m * at : sign_m * u2m * u * lg);
    out += b[i] * v / fact;
  }
  return out;
}

std::vector<KernelSingularTerm> singular_terms(const KernelSubtraction& s) {
  std::vector<KernelSingularTerm> out;
  for (std::size_t i = 0; i < s.b.size(); ++i) {
    const int j = static_cast<int>(i);
    KernelSingularTerm t;
    t.power = j;
    if (j % 2 == 0) {
      const int m = j / 2;
      t.log = false;
      t.coef = s.b[i] * ((m % 2) ? -1.0 : 1.0) * 0.5 * kPi * inv_factorial(j);
    } else {
      const int m = (j - 1) / 2;
      t.log = true;
      t.coef = -s.b[i] * ((m % 2) ? -1.0 : 1.0) * inv_factorial(j);
    }
    out.push_back(t);
  }
  return out;
}

double KernelSubtraction::singular(double u) const {
  if (u == 0.0) return 0.0;
  double out = 0.0;
  for (const KernelSingularTerm& t : singular_terms(*this))
    out +=
        t.coef * std::pow(u, t.power) * (t.log ? std::log(std::fabs(u)) : (u < 0.0 ? -1.0 : 1.0));
  return out;
}

// The most panels a graded top's kernel quadrature may take (about 1e3 per
// few seconds cold on one loaded core; build_alpha_quadrature refuses more).
constexpr int kMaxGradedPanels = 3000;

namespace {
// The width of build_alpha_quadrature's first panels: sin(alpha u) turns at
// most ~2 radians on one for u up to max_frequency, and at most the medium's
// panel_scale() (the surface's; 1 for the field).
double panel_width(const Medium& model, double max_frequency, Reach reach) {
  return std::min(reach == Reach::surface ? model.panel_scale() : 1.0, 2.0 / max_frequency);
}
}  // namespace

AlphaQuadrature build_alpha_quadrature(const Medium& model, double tol, double max_frequency,
                                       Reach reach, const KernelSubtraction& sub) {
  if (!(tol > 0.0)) throw std::invalid_argument("kernel quadrature: tol must be > 0");
  if (!(max_frequency > 0.0) || !std::isfinite(max_frequency))
    throw std::invalid_argument("kernel quadrature: max_frequency must be finite and > 0");
  AlphaQuadrature q;
  // M1 - phi1 decays like (1 + 4t) exp(-rate t) (the homogeneous layer: rate
  // 2 nT at the surface, nT for the field at its bottom): below 1e-18 beyond
  // this.
  const double rate = reach == Reach::surface ? model.decay_rate() : model.field_decay_rate();
  if (!(rate > 0.0) || !std::isfinite(rate))
    throw std::invalid_argument(
        "kernel quadrature: the medium's decay rate must be finite and > 0");
  q.alpha_max = (std::log(1e18) + std::log1p(4.0 * 60.0 / rate)) / rate;
  const KernelAsymptotics& as = model.kernel_asymptotics();
  if (!as.a.empty() && reach == Reach::surface && sub.empty())
    throw std::invalid_argument(
        "kernel quadrature: a graded top's M1 - phi1 decays algebraically; its asymptotics "
        "must be subtracted");
  if (!sub.empty()) {
    if (reach != Reach::surface)
      throw std::invalid_argument("kernel quadrature: a subtraction applies to the surface only");
    // The reflection off the top sublayer's bottom (its grading's margin),
    // the regularisation e^(-L t) (L t)^(K-1), the series' own range
    // (t > |gamma|/radius) and the algebraic tail |a_{K+1}| (|gamma|/t)^(K+1),
    // whose integral beyond A is below 1e-3 tol.
    const int K = static_cast<int>(sub.b.size());
    const double g = std::fabs(as.gamma);
    const double next =
        static_cast<std::size_t>(K) < as.a.size() ? std::fabs(as.a[K]) : std::fabs(as.next);
    const double a_exp = (std::log(1e18) + as.margin + std::log1p(4.0 * 60.0 / rate)) / rate;
    const double a_reg = (45.0 + 3.0 * K) / sub.L;
    const double a_ser = 4.0 * g / as.radius;
    const double a_alg = std::pow(next * std::pow(g, K + 1) / (K * 1e-3 * tol), 1.0 / K);
    q.alpha_max = std::min(kMaxAlphaGraded, std::max({a_exp, a_reg, a_ser, a_alg}));
    q.tail_bound = next * std::pow(g, K + 1) / (K * std::pow(q.alpha_max, K));
    q.subtraction = sub;
  }
  // Panels narrow enough that sin(alpha u) turns at most ~2 radians on one.
  const double width = panel_width(model, max_frequency, reach);
  const int n0 = std::max(1, static_cast<int>(std::ceil(q.alpha_max / width)));
  const double w0 = q.alpha_max / n0;
  // A graded top whose series needs few terms over a wide table (|gamma|
  // times the contact's half-width large: the terms' size caps K) leaves a
  // slow tail the panels must follow to alpha_max: beyond this many panels
  // (about 10 s on one core) it is refused rather than run for minutes.
  if (!sub.empty() && n0 > kMaxGradedPanels) {
    std::ostringstream msg;
    msg << "gamma_h: a graded top sublayer with gamma_h = " << as.gamma
        << " under a contact this wide (the kernel's range |u| <= " << 4.0 * max_frequency
        << ") needs its series' tail integrated to alpha h = " << q.alpha_max << " (" << n0
        << " panels, above " << kMaxGradedPanels
        << "): not solved in reasonable time; a smaller |gamma_h| of the top sublayer, a "
           "narrower contact (smaller load or radius), or a homogeneous top sublayer over the "
           "graded one is solved";
    throw InvalidParameter("gamma_h",
                           "|gamma_h| of the top sublayer times the contact's half-width a/h "
                           "within the kernel's reach (|gamma_h| <= 5 at a/h <= 2 solves)",
                           msg.str());
  }
  std::vector<Panel> work, done;
  for (int i = n0 - 1; i >= 1; --i) work.push_back(eval_panel(model, i * w0, (i + 1) * w0, sub));
  // The first panel, split down to a Pasternak base's long-wave scale
  // (layer_basis.hpp; one panel for springs alone).
  const std::vector<double> first = model.first_panel_edges(w0);
  for (std::size_t i = first.size() - 1; i >= 1; --i)
    work.push_back(eval_panel(model, first[i - 1], first[i], sub));
  const double panel_tol = tol / n0;
  int evaluations = n0 + static_cast<int>(first.size()) - 2;
  while (!work.empty()) {
    Panel p = work.back();
    work.pop_back();
    const double len = p.hi - p.lo;
    // Converged, or already at the round-off floor of the integrand.
    const bool fine = p.error <= std::max(panel_tol * len / w0, p.floor);
    if (fine || len < 1e-9 * w0 || evaluations > 20000) {
      // A panel that stopped at its round-off floor (not at its tolerance):
      // its |K15 - G7| is the nodal round-off's, already in round_rms, and
      // its truncation is below what refining could show. It counts as
      // meeting its share of tol, not as a systematic error of |K15 - G7|.
      p.systematic = std::min(p.truncation, panel_tol * len / w0);
      done.push_back(p);
      continue;
    }
    const double mid = 0.5 * (p.lo + p.hi);
    work.push_back(eval_panel(model, mid, p.hi, sub));
    work.push_back(eval_panel(model, p.lo, mid, sub));
    evaluations += 2;
  }
  std::sort(done.begin(), done.end(), [](const Panel& a, const Panel& b) { return a.lo < b.lo; });
  q.alpha.reserve(done.size() * 15);
  for (const Panel& p : done) {
    const double h = 0.5 * (p.hi - p.lo);
    q.panel_centre.push_back(0.5 * (p.lo + p.hi));
    q.panel_half.push_back(h);
    for (int j = 0; j < 15; ++j) {
      q.alpha.push_back(p.nodes[j]);
      q.weight.push_back(kronrod_weight(j, h));
      q.m1.push_back(p.m1[j]);
      q.sub.push_back(p.sub[j]);
    }
    // Truncation (QUADPACK's rescaled estimate, not the stopping floor) plus
    // the round-off of the sum itself.
    q.error_estimate += p.truncation + 16.0 * 2.220446049250313e-16 * p.resabs;
    q.panel_error.push_back(p.systematic);
    q.panel_roundoff.push_back(p.round_rms);
  }
  q.error_estimate += q.tail_bound;
  return q;
}

namespace {

// Inverse of V(j, k) = P_k(t_j) at the 15 Kronrod nodes t_j in [-1, 1]
// (ascending): maps nodal values to Legendre coefficients.
const Eigen::Matrix<double, 15, 15>& legendre_from_nodes() {
  static const Eigen::Matrix<double, 15, 15> inv = [] {
    Eigen::Matrix<double, 15, 15> V;
    for (int j = 0; j < 15; ++j) {
      const int k = j < 7 ? j : (j == 7 ? 7 : 14 - j);
      const double t = (j < 7 ? -1.0 : 1.0) * kXgk[k];
      double p0 = 1.0, p1 = t;
      V(j, 0) = p0;
      V(j, 1) = p1;
      for (int n = 1; n < 14; ++n) {
        const double p2 = ((2 * n + 1) * t * p1 - n * p0) / (n + 1);
        V(j, n + 1) = p2;
        p0 = p1;
        p1 = p2;
      }
    }
    return Eigen::Matrix<double, 15, 15>(V.inverse());
  }();
  return inv;
}

// Spherical Bessel functions j_0 .. j_14 at z >= 0. Above the largest order the
// upward recurrence from j_0 = sin z / z is stable; below it, Miller's downward
// recurrence normalised by the larger of j_0 = sin z / z and
// j_1 = sin z / z^2 - cos z / z (both exact).
std::array<double, 15> spherical_bessel(double z) {
  std::array<double, 15> j{};
  if (z == 0.0) {
    j[0] = 1.0;
    return j;
  }
  if (z < 1e-4) {
    // j_k(z) = z^k / (2k+1)!! (1 - z^2 / (2 (2k+3)) + O(z^4)): exact to rounding here.
    double lead = 1.0;
    for (unsigned k = 0; k < 15; ++k) {
      j[k] = lead * (1.0 - z * z / (2.0 * (2.0 * k + 3.0)));
      lead *= z / (2.0 * k + 3.0);
    }
    return j;
  }
  const double s = std::sin(z), c = std::cos(z);
  const double j0 = s / z;
  const double j1 = s / (z * z) - c / z;
  const double inv = 1.0 / z;
  if (z > 15.0) {
    j[0] = j0;
    j[1] = j1;
    for (unsigned k = 1; k < 14; ++k) j[k + 1] = (2.0 * k + 1.0) * inv * j[k] - j[k - 1];
    return j;
  }
  // j_{k-1} = (2k+1)/z j_k - j_{k+1}, started 10 + z above order 14 (checked
  // against scipy: 3e-14 relative for 1e-4 <= z <= 15, as with any later start).
  const int start = 14 + 10 + static_cast<int>(z);
  double up = 0.0, cur = 1e-300;
  for (int k = start; k >= 1; --k) {
    const double down = (2.0 * k + 1.0) * inv * cur - up;
    up = cur;
    cur = down;
    if (k - 1 <= 14) j[static_cast<std::size_t>(k - 1)] = cur;
    if (std::fabs(cur) > 1e250) {  // rescale to avoid overflow
      for (int m = k - 1; m <= 14; ++m) j[static_cast<std::size_t>(m)] *= 1e-250;
      up *= 1e-250;
      cur *= 1e-250;
    }
  }
  const double scale = std::fabs(j0) >= std::fabs(j1) ? j0 / j[0] : j1 / j[1];
  for (double& v : j) v *= scale;
  return j;
}

// spherical_bessel at many arguments: the downward recurrences (1e-4 <= z <=
// 15) four at a time, interleaved (they are latency-bound one by one).
void spherical_bessel_many(const double* z, std::size_t n, std::array<double, 15>* out) {
  constexpr int L = 4;
  std::size_t i = 0;
  while (i < n) {
    std::array<std::size_t, L> idx{};
    std::array<double, L> zz{};
    int lanes = 0;
    double zmax = 0.0;
    while (i < n && lanes < L) {
      if (z[i] < 1e-4 || z[i] > 15.0) {
        out[i] = spherical_bessel(z[i]);
      } else {
        idx[static_cast<std::size_t>(lanes)] = i;
        zz[static_cast<std::size_t>(lanes)] = z[i];
        zmax = std::max(zmax, z[i]);
        ++lanes;
      }
      ++i;
    }
    if (lanes == 0) continue;
    for (int l = lanes; l < L; ++l) zz[static_cast<std::size_t>(l)] = zz[0];
    const int start = 14 + 10 + static_cast<int>(zmax);
    std::array<double, L> inv{}, up{}, cur{};
    std::array<std::array<double, 15>, L> j{};
    for (int l = 0; l < L; ++l) {
      inv[static_cast<std::size_t>(l)] = 1.0 / zz[static_cast<std::size_t>(l)];
      cur[static_cast<std::size_t>(l)] = 1e-300;
    }
    // No rescaling needed: from 1e-300, the start - 1 steps with factors
    // (2k + 1)/z (1e-4 <= z <= 15, start = 24 + z) reach at most about 1e-172.
    for (int k = start; k > 15; --k) {
      const double f = 2.0 * k + 1.0;
      for (int l = 0; l < L; ++l) {
        const std::size_t q = static_cast<std::size_t>(l);
        const double down = f * inv[q] * cur[q] - up[q];
        up[q] = cur[q];
        cur[q] = down;
      }
    }
    for (int k = 15; k >= 1; --k) {
      const double f = 2.0 * k + 1.0;
      for (int l = 0; l < L; ++l) {
        const std::size_t q = static_cast<std::size_t>(l);
        const double down = f * inv[q] * cur[q] - up[q];
        up[q] = cur[q];
        cur[q] = down;
        j[q][static_cast<std::size_t>(k - 1)] = down;
      }
    }
    for (int l = 0; l < lanes; ++l) {
      const std::size_t q = static_cast<std::size_t>(l);
      const double x = zz[q], sn = std::sin(x), cs = std::cos(x);
      const double j0 = sn / x, j1 = sn / (x * x) - cs / x;
      const double scale = std::fabs(j0) >= std::fabs(j1) ? j0 / j[q][0] : j1 / j[q][1];
      for (double& v : j[q]) v *= scale;
      out[idx[q]] = j[q];
    }
  }
}

}  // namespace

FilonIntegrator::FilonIntegrator(const AlphaQuadrature& q)
    : centre_(q.panel_centre), half_(q.panel_half) {
  // Panels share a few half-widths (bisections of one width). (Widths equal
  // but for their last bits stay apart: sharing one's Bessel functions moved
  // k1 near V*_cr by more than a/h's error estimate allowed.)
  width_of_.reserve(half_.size());
  for (const double h : half_) {
    const auto it = std::find(widths_.begin(), widths_.end(), h);
    width_of_.push_back(static_cast<std::size_t>(it - widths_.begin()));
    if (it == widths_.end()) widths_.push_back(h);
  }
}

void FilonIntegrator::bessel_by_width(double ax, std::vector<std::array<double, 15>>& j) const {
  thread_local std::vector<double> z;
  z.resize(widths_.size());
  for (std::size_t w = 0; w < widths_.size(); ++w) z[w] = widths_[w] * ax;
  j.resize(widths_.size());
  spherical_bessel_many(z.data(), z.size(), j.data());
}

std::vector<double> FilonIntegrator::coefficients(const std::vector<double>& g) const {
  if (g.size() % 15 != 0 || g.size() > centre_.size() * 15)
    throw std::invalid_argument("Filon: one value per quadrature node (of the first panels)");
  const auto& inv = legendre_from_nodes();
  std::vector<double> c(g.size());
  for (std::size_t p = 0; p < g.size() / 15; ++p) {
    const Eigen::Map<const Eigen::Matrix<double, 15, 1>> v(g.data() + 15 * p);
    Eigen::Map<Eigen::Matrix<double, 15, 1>> out(c.data() + 15 * p);
    out = inv * v;
  }
  return c;
}

void FilonIntegrator::weights(double x, std::vector<cplx>& K) const {
  check_interrupt();  // a sum over every panel (kernel tables, stresses)
  // int_{c-h}^{c+h} P_k((alpha - c)/h) e^{i alpha x} = h e^{i c x} 2 i^k j_k(h x).
  K.resize(centre_.size() * 15);
  const cplx ipow[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  const double ax = std::fabs(x), sgn = x < 0.0 ? -1.0 : 1.0;
  thread_local std::vector<std::array<double, 15>> bessel;
  bessel_by_width(ax, bessel);
  for (std::size_t p = 0; p < centre_.size(); ++p) {
    const std::array<double, 15>& j = bessel[width_of_[p]];
    const cplx phase = half_[p] * std::exp(cplx(0.0, centre_[p] * x));
    for (int k = 0; k < 15; ++k) {
      // j_k(-z) = (-1)^k j_k(z)
      const double jk = (k % 2 == 1 && sgn < 0.0) ? -j[static_cast<std::size_t>(k)]
                                                  : j[static_cast<std::size_t>(k)];
      K[15 * p + static_cast<std::size_t>(k)] = phase * (2.0 * jk) * ipow[k % 4];
    }
  }
}

FilonIntegrator::cplx FilonIntegrator::weights_applied(double x,
                                                       const std::vector<double>& c) const {
  check_interrupt();
  // apply(weights(x), c)'s arithmetic in its order, each weight made where
  // it is used: i^k multiplies by a sign and swaps parts (exact).
  const double ax = std::fabs(x), sgn = x < 0.0 ? -1.0 : 1.0;
  thread_local std::vector<std::array<double, 15>> bessel;
  bessel_by_width(ax, bessel);
  double re = 0.0, im = 0.0;
  for (std::size_t p = 0; p < centre_.size(); ++p) {
    const std::array<double, 15>& j = bessel[width_of_[p]];
    const cplx phase = half_[p] * std::exp(cplx(0.0, centre_[p] * x));
    const double* cp = c.data() + 15 * p;
    for (int k = 0; k < 15; ++k) {
      const double jk = (k % 2 == 1 && sgn < 0.0) ? -j[static_cast<std::size_t>(k)]
                                                  : j[static_cast<std::size_t>(k)];
      const double wr = phase.real() * (2.0 * jk), wi = phase.imag() * (2.0 * jk);
      double kr = wr, ki = wi;  // times i^k
      switch (k % 4) {
        case 1:
          kr = -wi;
          ki = wr;
          break;
        case 2:
          kr = -wr;
          ki = -wi;
          break;
        case 3:
          kr = wi;
          ki = -wr;
          break;
        default:
          break;
      }
      re += kr * cp[k];
      im += ki * cp[k];
    }
  }
  return {re, im};
}

template <std::size_t M, bool Rotate>
void FilonIntegrator::integrals(double x, const std::array<const std::vector<double>*, M>& c,
                                std::array<cplx, M>& out) const {
  check_interrupt();  // a sum over every panel (the damped kernel's tables)
  // Per panel: h e^{i c x} sum_k c_k 2 i^k j_k(h x); i^k alternates between
  // the real (k even) and imaginary (k odd) axes with signs + + - -.
  const double ax = std::fabs(x), sgn = x < 0.0 ? -1.0 : 1.0;
  thread_local std::vector<std::array<double, 15>> bessel;
  bessel_by_width(ax, bessel);
  out.fill(0.0);
  // Rotate (integral_pair): e^{i c x} of a panel adjoining the previous one is
  // that panel's times e^{i h_prev x} e^{i h x} (one sin/cos per distinct
  // half-width), re-anchored by sin/cos every 8 panels: a relative error of
  // a few 1e-15 in place of 1e-16, half the time.
  thread_local std::vector<cplx> rot;
  if (Rotate) {
    rot.resize(widths_.size());
    for (std::size_t w = 0; w < widths_.size(); ++w)
      rot[w] = cplx(std::cos(widths_[w] * x), std::sin(widths_[w] * x));
  }
  cplx e(1.0, 0.0);
  // Coefficients for the first panels only (an integrand negligible beyond
  // them, SymmetricSolution::prepare_displacement): the sum stops there.
  std::size_t panels = centre_.size();
  for (std::size_t v = 0; v < M; ++v) panels = std::min(panels, c[v]->size() / 15);
  for (std::size_t p = 0; p < panels; ++p) {
    const std::array<double, 15>& j = bessel[width_of_[p]];
    const double arg = centre_[p] * x;
    const bool adjoins = Rotate && p % 8 != 0 &&
                         std::fabs(centre_[p - (p > 0 ? 1 : 0)] + half_[p - (p > 0 ? 1 : 0)] +
                                   half_[p] - centre_[p]) <= 1e-14 * std::fabs(centre_[p]);
    if (adjoins)
      e *= rot[width_of_[p - 1]] * rot[width_of_[p]];
    else
      e = cplx(std::cos(arg), std::sin(arg));
    const cplx phase = (2.0 * half_[p]) * e;
    for (std::size_t v = 0; v < M; ++v) {
      const double* cp = c[v]->data() + 15 * p;
      double re = 0.0, im = 0.0;
      for (int k = 0; k < 15; k += 4) re += cp[k] * j[static_cast<std::size_t>(k)];
      for (int k = 2; k < 15; k += 4) re -= cp[k] * j[static_cast<std::size_t>(k)];
      for (int k = 1; k < 15; k += 4) im += cp[k] * j[static_cast<std::size_t>(k)];
      for (int k = 3; k < 15; k += 4) im -= cp[k] * j[static_cast<std::size_t>(k)];
      out[v] += phase * cplx(re, sgn * im);
    }
  }
}

FilonIntegrator::cplx FilonIntegrator::integral(double x, const std::vector<double>& c) const {
  std::array<cplx, 1> out;
  integrals<1, true>(x, {&c}, out);
  return out[0];
}

FilonIntegrator::cplx FilonIntegrator::integral_exact(double x,
                                                      const std::vector<double>& c) const {
  std::array<cplx, 1> out;
  integrals<1, false>(x, {&c}, out);
  return out[0];
}

std::pair<FilonIntegrator::cplx, FilonIntegrator::cplx> FilonIntegrator::integral_pair(
    double x, const std::vector<double>& c1, const std::vector<double>& c2) const {
  std::array<cplx, 2> out;
  integrals<2, true>(x, {&c1, &c2}, out);
  return {out[0], out[1]};
}

std::pair<FilonIntegrator::cplx, FilonIntegrator::cplx> FilonIntegrator::integral_pair_exact(
    double x, const std::vector<double>& c1, const std::vector<double>& c2) const {
  std::array<cplx, 2> out;
  integrals<2, false>(x, {&c1, &c2}, out);
  return {out[0], out[1]};
}

FilonIntegrator::cplx FilonIntegrator::apply(const std::vector<cplx>& K,
                                             const std::vector<double>& c) {
  cplx sum = 0.0;
  for (std::size_t i = 0; i < K.size(); ++i) sum += K[i] * c[i];
  return sum;
}

namespace {
// int |M1 - phi1| / |phi1| d alpha by the quadrature's own rule.
double abs_integral(const AlphaQuadrature& q, double phi1) {
  double sum = 0.0;
  for (std::size_t i = 0; i < q.alpha.size(); ++i)
    sum += q.weight[i] * std::fabs((q.m1[i] - phi1) / phi1 - q.sub[i]);
  return sum;
}

// The integrand f - S at the nodes of q.
std::vector<double> integrand(const AlphaQuadrature& q, double phi1) {
  std::vector<double> f(q.alpha.size());
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = (q.m1[i] - phi1) / phi1 - q.sub[i];
  return f;
}

// The largest size of a subtraction's terms on the table, sum_k |b_k|
// u^(k-1)/(k-1)! at u = range/2 (the collocation's |u| <= 2a): the singular
// and smooth parts cancel beyond u ~ L, each carrying eps times it.
double subtraction_magnitude(const KernelSubtraction& s, double range) {
  double out = 0.0;
  for (std::size_t i = 0; i < s.b.size(); ++i)
    out += std::fabs(s.b[i]) * std::pow(0.5 * range, static_cast<double>(i)) *
           inv_factorial(static_cast<int>(i));
  return out;
}

// The subtraction of a graded top for a table of range `range` and
// tolerance `tol`: terms while the largest, b_k u^(k-1)/(k-1)! at u =
// range/2, stays below max(1e3, 1e-2 tol/eps) (its cancellation's round-off,
// counted in the table's round-off, stays below 1e-2 tol), at most 8. Fewer
// terms leave a slower algebraic tail, which the quadrature must follow far
// (alpha_max up to 2e4: minutes at |gamma| a ~ 5 with the old cap 1e3).
KernelSubtraction graded_subtraction(const Medium& m, double range, double tol) {
  const KernelAsymptotics& as = m.kernel_asymptotics();
  KernelSubtraction s;
  if (as.a.empty()) return s;
  constexpr double eps = 2.220446049250313e-16;
  const double g = std::fabs(as.gamma), uc = 0.5 * range;
  const double cap = std::max(1e3, 1e-2 * tol / eps);
  s.L = 1.0 / std::max(1.0, g);
  for (std::size_t i = 0; i < std::min<std::size_t>(8, as.a.size()); ++i) {
    const int k = static_cast<int>(i) + 1;
    const double bk = as.a[i] * std::pow(as.gamma, k);
    const double mag = std::fabs(bk) * std::pow(uc, k - 1) * inv_factorial(k - 1);
    if (i > 0 && mag > cap) break;
    s.b.push_back(bk);
  }
  return s;
}
}  // namespace

KernelK1::KernelK1(const LayerModel& model, double tol, double range)
    : KernelK1(make_medium(homogeneous_medium(model.kw(), model.nu(), model.kp()), model.vstar()),
               tol, range) {}

KernelK1::KernelK1(std::shared_ptr<const Medium> medium, double tol, double range,
                   const KernelK1* shorter)
    : model_(std::move(medium)), tol_(tol), range_(range) {
  if (!model_ || !model_->real())
    throw std::invalid_argument("KernelK1: a medium with a real response is required");
  require_in_range("kernel tol", tol, 0.0, 1.0, true, false);
  require_in_range("kernel range", range, 0.0, 1e6, true, false);
  // The panels resolve M1 (and, for the displacement, the transform of a
  // pressure of half-width ~ range/4); sin(alpha u) is integrated exactly by
  // the Filon rule, so the grid does not grow with the range.
  sub_ = graded_subtraction(*model_, range_, tol_);
  singular_ = singular_terms(sub_);
  // A longer table of the same medium (the cache's growth) keeps the
  // shorter one's quadrature when its inputs are the same: the panels'
  // width (panel_width) and the subtraction (the first solve on a
  // stack grows its table once: the quadrature was half of each build).
  if (shorter && shorter->tol_ == tol_ && shorter->model_->key() == model_->key() &&
      panel_width(*model_, 0.25 * shorter->range_, Reach::surface) ==
          panel_width(*model_, 0.25 * range_, Reach::surface) &&
      shorter->sub_.b == sub_.b && shorter->sub_.L == sub_.L) {
    quad_ = shorter->quad_;
    filon_ = shorter->filon_;
    f_coef_ = shorter->f_coef_;
  } else {
    quad_ = build_alpha_quadrature(*model_, tol_, 0.25 * range_, Reach::surface, sub_);
    filon_ = std::make_shared<const FilonIntegrator>(quad_);
    f_coef_ = filon_->coefficients(integrand(quad_, model_->phi1()));
  }
  if (!singular_.empty()) {
    // Per medium and reach: four responses a solve need not repeat (they
    // were a twentieth of a warm graded-top solve).
    const double A = quad_.alpha_max, phi1 = model_->phi1();
    tails_.surface_c =
        std::max(std::fabs(model_->surface_response(A).M1.real() - phi1) * A,
                 std::fabs(model_->surface_response(2.0 * A).M1.real() - phi1) * 2.0 * A);
    // The field quadrature's reach (build_alpha_quadrature, Reach::field: no
    // subtraction there).
    const double rate = model_->field_decay_rate();
    const double Af = (std::log(1e18) + std::log1p(4.0 * 60.0 / rate)) / rate;
    tails_.field_reach = Af;
    tails_.field_c =
        std::max(std::fabs(model_->mode(Af)->remainder(0.0).sx.real()) * Af,
                 std::fabs(model_->mode(2.0 * Af)->remainder(0.0).sx.real()) * 2.0 * Af);
  }
  // A long table (many oscillations of k1 on |u| <= range) is held piecewise:
  // its cost is then proportional to the range, and so is no evaluation's.
  if (range_ * quad_.alpha_max > kPieceBandwidth) {
    build_pieces();
    return;
  }
  // Odd Chebyshev series on [-range, range]; values at the positive half of
  // the first-kind nodes, doubled until the tail is below tol.
  for (int n = 32;; n *= 2) {
    std::vector<double> vals(static_cast<std::size_t>(n / 2));
    for (int j = 0; j < n / 2; ++j) {
      const double x = std::cos(kPi * (j + 0.5) / n);
      vals[static_cast<std::size_t>(j)] = regular(range_ * x);
    }
    std::vector<double> c(static_cast<std::size_t>(n), 0.0);
    double cmax = 0.0;
    for (int m = 1; m < n; m += 2) {
      double sum = 0.0;
      for (int j = 0; j < n / 2; ++j)
        sum += vals[static_cast<std::size_t>(j)] * std::cos(kPi * m * (j + 0.5) / n);
      c[static_cast<std::size_t>(m)] = 4.0 * sum / n;  // both halves (odd symmetry)
      cmax = std::max(cmax, std::fabs(c[static_cast<std::size_t>(m)]));
    }
    double tail = 0.0;
    for (int m = n - 7; m < n; m += 2)
      tail = std::max(tail, std::fabs(c[static_cast<std::size_t>(m)]));
    constexpr double eps = 2.220446049250313e-16;
    double vmax = 0.0;
    for (double v : vals) vmax = std::max(vmax, std::fabs(v));
    // Below this the coefficients are round-off of the quadrature sum.
    const double goal = std::max(1e-2 * tol_, 64.0 * eps * std::max(cmax, vmax));
    if (tail <= goal || n >= 16384) {
      // Drop the negligible tail.
      std::size_t last = c.size();
      while (last > 1 && std::fabs(c[last - 1]) <= 1e-2 * goal) --last;
      double dropped = 0.0;
      for (std::size_t m = std::max<std::size_t>(last, 2); m < c.size(); ++m)
        dropped += std::fabs(c[m]);
      // The table's error: the series' tail, what was dropped, and the
      // round-off of the values (Filon sums of terms up to int |f|).
      table_error_ = 2.0 * tail + dropped + quad_.tail_bound;
      table_order_ = n + 1;
      table_roundoff_ =
          4.0 * eps *
          (abs_integral(quad_, model_->phi1()) + vmax + subtraction_magnitude(sub_, range_));
      c.resize(std::max<std::size_t>(last, 2));
      coef_ = std::move(c);
      for (std::size_t m = 1; m < coef_.size(); m += 2) odd_.push_back(coef_[m]);
      break;
    }
  }
  tabulate_greens();
}

namespace {

// E1(x) for x >= 1 by its continued fraction (modified Lentz).
double exponential_integral_e1(double x) {
  constexpr double tiny = 1e-300, eps = 1e-16;
  double b = x + 1.0, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 200; ++i) {
    const double an = -static_cast<double>(i) * i;
    b += 2.0;
    d = 1.0 / (an * d + b);
    c = b + an / c;
    const double del = c * d;
    h *= del;
    if (std::fabs(del - 1.0) < eps) break;
  }
  return h * std::exp(-x);
}

}  // namespace

// The antiderivative of the odd table, sum_k c_k T_k(t) (k odd, t = u/range):
// int_0^t T_1 = (T_2 + T_0)/4 and, for k >= 3, int T_k = [T_{k+1}/(k+1) -
// T_{k-1}/(k-1)]/2 + const; the constant makes K1(0) = 0. An even series in
// t, held as sum_j E_j T_j(T_2(t)) (T_{2j}(t) = T_j(T_2(t))).
void KernelK1::tabulate_greens() {
  if (!piece_coef_.empty() || !sub_.empty() || model_->long_wave_m1() != 0.0 || odd_.empty())
    return;
  std::vector<double> e(odd_.size() + 1, 0.0);  // e[j]: of T_{2j}(t)
  for (std::size_t j = 0; j < odd_.size(); ++j) {
    const double k = 2.0 * static_cast<double>(j) + 1.0;
    if (j == 0) {
      e[1] += 0.25 * odd_[0];
      continue;
    }
    e[j + 1] += odd_[j] / (2.0 * (k + 1.0));
    e[j] -= odd_[j] / (2.0 * (k - 1.0));
  }
  // T_{2j}(0) = (-1)^j.
  double at0 = 0.0;
  for (std::size_t j = 0; j < e.size(); ++j) at0 += (j % 2 == 0 ? 1.0 : -1.0) * e[j];
  e[0] -= at0;
  for (double& v : e) v *= range_;
  const double phi1 = model_->phi1();
  double g0 = 0.0;
  for (std::size_t i = 0; i < quad_.alpha.size(); ++i) {
    const double al = quad_.alpha[i];
    g0 += quad_.weight[i] * (quad_.m1[i] - phi1 * (-std::expm1(-al))) / al;
  }
  greens_zero_ = g0 + phi1 * exponential_integral_e1(std::max(quad_.alpha_max, 1.0));
  greens_mass_.assign(quad_.panel_centre.size(), 0.0);
  for (std::size_t i = 0; i < quad_.alpha.size(); ++i) {
    const double al = quad_.alpha[i];
    greens_mass_[i / 15] +=
        quad_.weight[i] * std::fabs(quad_.m1[i] - phi1 * (-std::expm1(-al))) / al;
  }
  k1_integral_ = std::move(e);
}

void KernelK1::k1_integrals(const double* u, double* out, std::size_t n) const {
  // Clenshaw on sum_j E_j T_j(y), y = T_2(u / range): four chains at once,
  // in registers (independent chains of dependent steps).
  const std::size_t J = k1_integral_.size();
  const double* E = k1_integral_.data();
  const double inv = 1.0 / range_;
  const auto y2 = [&](double v) {
    const double x = v * inv;
    return 2.0 * (2.0 * x * x - 1.0);
  };
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const double ya = y2(u[i]), yb = y2(u[i + 1]), yc = y2(u[i + 2]), yd = y2(u[i + 3]);
    double a1 = 0, a2 = 0, b1 = 0, b2 = 0, c1 = 0, c2 = 0, d1 = 0, d2 = 0;
    for (std::size_t j = J; j-- > 1;) {
      const double c = E[j];
      const double a0 = c + ya * a1 - a2, b0 = c + yb * b1 - b2;
      const double c0 = c + yc * c1 - c2, d0 = c + yd * d1 - d2;
      a2 = a1;
      a1 = a0;
      b2 = b1;
      b1 = b0;
      c2 = c1;
      c1 = c0;
      d2 = d1;
      d1 = d0;
    }
    out[i] = E[0] + 0.5 * ya * a1 - a2;
    out[i + 1] = E[0] + 0.5 * yb * b1 - b2;
    out[i + 2] = E[0] + 0.5 * yc * c1 - c2;
    out[i + 3] = E[0] + 0.5 * yd * d1 - d2;
  }
  for (; i < n; ++i) {
    const double y = y2(u[i]);
    double b1 = 0, b2 = 0;
    for (std::size_t j = J; j-- > 1;) {
      const double b0 = E[j] + y * b1 - b2;
      b2 = b1;
      b1 = b0;
    }
    out[i] = E[0] + 0.5 * y * b1 - b2;
  }
}

void KernelK1::build_pieces() {
  // k1 is band-limited: the quadrature stops at alpha_max. On a piece of
  // width w, sin(alpha u) turns by at most alpha_max w / 2 = 4 radians about
  // the piece's centre, where a degree-24 Chebyshev interpolant is exact to
  // (e 4 / 50)^25 ~ 1e-17 relative. The values come from a Filon sum on
  // panels that resolve M1 only (Filon integrates sin(alpha u) exactly for
  // any u): the panels of quad_ also resolve the transform of a pressure of
  // half-width range/4 (the displacement), many times more of them on a wide
  // table.
  constexpr int D = kPieceDegree;
  // (quad_ when its panels, for max_frequency range/4, are these.)
  const bool same = panel_width(*model_, 0.25 * range_, Reach::surface) ==
                    panel_width(*model_, 1.0, Reach::surface);
  const AlphaQuadrature coarse =
      same ? quad_ : build_alpha_quadrature(*model_, tol_, 1.0, Reach::surface, sub_);
  const std::shared_ptr<const FilonIntegrator> filon =
      same ? filon_ : std::make_shared<const FilonIntegrator>(coarse);
  const std::vector<double> fc =
      same ? f_coef_ : filon->coefficients(integrand(coarse, model_->phi1()));
  double vmax = 0.0;
  // (A graded top's smooth closed forms tabulated with the quadrature's part.)
  auto value = [&](double u) {
    const double q = filon->integral_exact(u, fc).imag();
    return sub_.empty() ? q : q + sub_.smooth(u);
  };
  const double band = std::max(quad_.alpha_max, coarse.alpha_max);
  const std::size_t pieces = static_cast<std::size_t>(std::ceil(range_ * band / 8.0));
  const double w = range_ / static_cast<double>(pieces);
  piece_coef_.assign(pieces * (D + 1), 0.0);
  piece_width_ = w;
  double vals[D + 1];
  for (std::size_t p = 0; p < pieces; ++p) {
    const double c0 = (static_cast<double>(p) + 0.5) * w;
    for (int j = 0; j <= D; ++j) {
      vals[j] = value(c0 + 0.5 * w * std::cos(kPi * (j + 0.5) / (D + 1)));
      vmax = std::max(vmax, std::fabs(vals[j]));
    }
    for (int m = 0; m <= D; ++m) {
      double sum = 0.0;
      for (int j = 0; j <= D; ++j) sum += vals[j] * std::cos(kPi * m * (j + 0.5) / (D + 1));
      piece_coef_[p * (D + 1) + static_cast<std::size_t>(m)] = (m == 0 ? 1.0 : 2.0) * sum / (D + 1);
    }
  }
  // Interpolation is exact to ~1e-17 relative; the values carry the round-off
  // of Filon sums of terms up to int |f|.
  constexpr double eps = 2.220446049250313e-16;
  table_error_ = coarse.tail_bound;
  table_roundoff_ =
      4.0 * eps *
      (abs_integral(coarse, model_->phi1()) + vmax + subtraction_magnitude(sub_, range_));
  value_quad_ = coarse;
}

double KernelK1::numeric(double u) const { return filon_->weights_applied(u, f_coef_).imag(); }

double KernelK1::regular(double u) const {
  return sub_.empty() ? numeric(u) : numeric(u) + sub_.smooth(u);
}

double KernelK1::direct(double u) const {
  return sub_.empty() ? numeric(u) : regular(u) + sub_.singular(u);
}

double KernelK1::piece(double u) const {
  constexpr int D = kPieceDegree;
  const double au = std::fabs(u);
  const std::size_t pieces = piece_coef_.size() / (D + 1);
  const std::size_t p = std::min(pieces - 1, static_cast<std::size_t>(au / piece_width_));
  const double x = 2.0 * (au - (static_cast<double>(p) + 0.5) * piece_width_) / piece_width_;
  const double v = detail::chebyshev_sum(piece_coef_.data() + p * (D + 1), D, x);
  return u < 0.0 ? -v : v;
}

double KernelK1::table(double u) const { return piece_coef_.empty() ? global(u) : piece(u); }

double KernelK1::operator()(double u) const {
  if (sub_.empty()) return table(u);
  return table(u) + sub_.singular(u);
}

// The series is odd, sum_j c_{2j+1} T_{2j+1}(x): Clenshaw on the odd terms
// with T_{m+2} = 2 T_2 T_m - T_{m-2}, T_2 = 2 x^2 - 1, gives x (b_0 - b_1)
// (half the terms of the plain recurrence).
double KernelK1::global(double u) const {
  const double x = u / range_;
  const double y2 = 2.0 * (2.0 * x * x - 1.0);
  double b1 = 0.0, b2 = 0.0;
  for (std::size_t j = odd_.size(); j-- > 0;) {
    const double b0 = odd_[j] + y2 * b1 - b2;
    b2 = b1;
    b1 = b0;
  }
  return x * (b1 - b2);
}

void KernelK1::sum_many(const double* u, const double* v, double* out, std::size_t n) const {
  std::size_t i = 0;
  if (piece_coef_.empty()) {
    // Eight recurrences interleaved (four pairs): each is a chain of
    // dependent steps, the chains independent. The same arithmetic as sum().
    constexpr std::size_t L = 8;
    for (; i + L / 2 <= n; i += L / 2) {
      std::array<double, L> x{}, y{}, b1{}, b2{};
      for (std::size_t l = 0; l < L / 2; ++l) {
        x[2 * l] = u[i + l] / range_;
        x[2 * l + 1] = v[i + l] / range_;
      }
      for (std::size_t l = 0; l < L; ++l) y[l] = 2.0 * (2.0 * x[l] * x[l] - 1.0);
      for (std::size_t j = odd_.size(); j-- > 0;) {
        const double c = odd_[j];
        for (std::size_t l = 0; l < L; ++l) {
          const double b0 = c + y[l] * b1[l] - b2[l];
          b2[l] = b1[l];
          b1[l] = b0;
        }
      }
      for (std::size_t l = 0; l < L / 2; ++l)
        out[i + l] =
            x[2 * l] * (b1[2 * l] - b2[2 * l]) + x[2 * l + 1] * (b1[2 * l + 1] - b2[2 * l + 1]);
    }
  }
  for (; i < n; ++i) out[i] = sum(u[i], v[i]);
}

double KernelK1::sum(double u, double v) const {
  if (!piece_coef_.empty()) return piece(u) + piece(v);
  // Two recurrences interleaved (each is a chain of dependent steps).
  const double x = u / range_, z = v / range_;
  const double yx = 2.0 * (2.0 * x * x - 1.0), yz = 2.0 * (2.0 * z * z - 1.0);
  double b1 = 0.0, b2 = 0.0, d1 = 0.0, d2 = 0.0;
  for (std::size_t j = odd_.size(); j-- > 0;) {
    const double b0 = odd_[j] + yx * b1 - b2;
    const double d0 = odd_[j] + yz * d1 - d2;
    b2 = b1;
    b1 = b0;
    d2 = d1;
    d1 = d0;
  }
  return x * (b1 - b2) + z * (d1 - d2);
}

}  // namespace movingpunch

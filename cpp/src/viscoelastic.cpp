// Viscoelastic sublayers: the material, its retardation spectrum and the
// memory part of the kernel (movingpunch/viscoelastic.hpp; docs/theory.md
// section 17).
#include "movingpunch/viscoelastic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <utility>

#include "movingpunch/collocation.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/jacobi.hpp"
#include "movingpunch/layer_response.hpp"

namespace movingpunch {

namespace {

constexpr double kPiV = 3.14159265358979323846;
constexpr double kInfV = std::numeric_limits<double>::infinity();

using cplx = std::complex<double>;

std::string num(double x) {
  std::ostringstream o;
  o.precision(17);
  o << x;
  return o.str();
}

// The branches with D_j = shift deborah_j > 0, equal relaxation times merged,
// sorted by D descending (poles -1/D_j of m in s = -i t ascending in |s|).
std::vector<std::pair<double, double>> branches(const Viscoelastic& v) {
  std::vector<std::pair<double, double>> out;  // (D, g)
  for (std::size_t j = 0; j < v.weights.size(); ++j) {
    const double D = v.shift * v.deborahs[j];
    if (!(D > 0.0)) continue;  // instantaneous relaxation: the relaxed modulus
    auto it = std::find_if(out.begin(), out.end(), [D](const auto& b) { return b.first == D; });
    if (it != out.end())
      it->second += v.weights[j];
    else
      out.emplace_back(D, v.weights[j]);
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  return out;
}

}  // namespace

bool Viscoelastic::empty() const noexcept {
  for (std::size_t j = 0; j < weights.size() && j < deborahs.size(); ++j)
    if (shift * deborahs[j] > 0.0) return false;
  return true;
}

double Viscoelastic::ratio() const noexcept {
  double r = 1.0;
  for (std::size_t j = 0; j < weights.size() && j < deborahs.size(); ++j)
    if (shift * deborahs[j] > 0.0) r += weights[j];
  return r;
}

std::complex<double> Viscoelastic::modulus(double t) const {
  cplx m = 1.0;
  for (std::size_t j = 0; j < weights.size(); ++j) {
    const double D = shift * deborahs[j];
    const cplx z(0.0, -t * D);  // -i t D
    m += weights[j] * z / (1.0 + z);
  }
  return m;
}

Viscoelastic zener(double ratio, double deborah) {
  require_in_range("ratio", ratio, 1.0, kMaxViscoRatio, false, false);
  require_in_range("deborah", deborah, 0.0, kMaxDeborah, false, false);
  Viscoelastic v;
  if (ratio > 1.0 && deborah > 0.0) {
    v.weights = {ratio - 1.0};
    v.deborahs = {deborah};
  }
  return v;
}

void validate(const Viscoelastic& v, const std::string& where) {
  if (v.weights.size() != v.deborahs.size())
    throw InvalidParameter(where, "as many deborah numbers as weights",
                           where + ": " + std::to_string(v.weights.size()) + " weights and " +
                               std::to_string(v.deborahs.size()) +
                               " deborah numbers given; one relaxation time per branch");
  if (v.weights.size() > kMaxBranches)
    throw InvalidParameter(where, "at most " + std::to_string(kMaxBranches) + " branches",
                           where + ": " + std::to_string(v.weights.size()) +
                               " branches given, at most " + std::to_string(kMaxBranches));
  require_in_range((where + ".shift").c_str(), v.shift, 0.0, 1e12, true, false);
  for (std::size_t j = 0; j < v.weights.size(); ++j) {
    const std::string at = where + "[" + std::to_string(j) + "]";
    require_in_range((at + ".weight").c_str(), v.weights[j], 0.0, kMaxViscoRatio - 1.0, true,
                     false);
    require_in_range((at + ".deborah").c_str(), v.deborahs[j], 0.0, kMaxDeborah, false, false);
    const double D = v.shift * v.deborahs[j];
    if (D != 0.0 && !(D >= kMinDeborah && D <= kMaxDeborah))
      throw InvalidParameter(
          at + ".deborah",
          "shift * deborah 0 or in [" + num(kMinDeborah) + ", " + num(kMaxDeborah) + "]",
          at + ": shift * deborah = " + num(D) + " is outside [" + num(kMinDeborah) + ", " +
              num(kMaxDeborah) + "] (0: the branch relaxes at once, the relaxed modulus)");
  }
  if (!(v.ratio() <= kMaxViscoRatio))
    throw InvalidParameter(where, "1 + sum of the weights <= " + num(kMaxViscoRatio),
                           where + ": mu_inf/mu_0 = 1 + sum of the weights = " + num(v.ratio()) +
                               " exceeds " + num(kMaxViscoRatio));
}

std::complex<double> RetardationSpectrum::memory(double t) const {
  cplx out = 0.0;
  for (std::size_t k = 0; k < c.size(); ++k) out += c[k] / cplx(1.0, -beta[k] * t);
  return out;
}

RetardationSpectrum retardation_spectrum(const Viscoelastic& v) {
  const auto br = branches(v);
  RetardationSpectrum out;
  out.ratio = 1.0;
  for (const auto& b : br) out.ratio += b.second;
  if (br.empty()) return out;
  if (br.size() == 1) {
    // The Zener solid: m = (1 - i ratio D t)/(1 - i D t), beta = ratio D, c = ratio - 1.
    out.c = {br[0].second};
    out.beta = {out.ratio * br[0].first};
    return out;
  }
  // m(y) = 1 - sum g_j y D_j/(1 - y D_j) (s = -y): decreasing between its
  // poles y_j = 1/D_j, from +inf to -inf; one zero in (0, y_1) and in each
  // (y_j, y_{j+1}), none beyond the last (m -> ratio > 0).
  auto m_of = [&br](double y) {
    double m = 1.0;
    for (const auto& b : br) m -= b.second * y * b.first / (1.0 - y * b.first);
    return m;
  };
  for (std::size_t k = 0; k < br.size(); ++k) {
    double lo = k == 0 ? 1e-30 / br[0].first : 1.0 / br[k - 1].first;
    double hi = 1.0 / br[k].first;
    // Bisection in log y to the last bit (m is monotone between the poles).
    for (int it = 0; it < 400; ++it) {
      const double mid = std::sqrt(lo * hi);
      if (!(mid > lo && mid < hi)) break;
      (m_of(mid) > 0.0 ? lo : hi) = mid;
    }
    const double y = std::sqrt(lo * hi);
    double dm = 0.0;  // dm/ds = -dm/dy at the zero
    for (const auto& b : br) dm += b.second * b.first / ((1.0 - y * b.first) * (1.0 - y * b.first));
    const double beta = 1.0 / y;
    out.beta.push_back(beta);
    out.c.push_back(out.ratio * beta / dm);
  }
  // Ascending beta (the zeros were found ascending in y).
  std::reverse(out.beta.begin(), out.beta.end());
  std::reverse(out.c.begin(), out.c.end());
  return out;
}

// ---------------------------------------------------------------------------
// The inertial half-plane's memory (a continuous spectrum)

std::complex<double> half_plane_stress(const Viscoelastic& v, double vstar, double nu, double t) {
  if (vstar == 0.0) return 1.0;  // phi2(0): no modulus in it
  return complex_half_plane(vstar / v.modulus(t), nu).phi2;
}

ViscoelasticTop::ViscoelasticTop(const Viscoelastic& v, double vstar, double nu)
    : v_(v),
      vstar_(vstar),
      nu_(nu),
      compliance_(inertial_spectrum(v, vstar, nu)),
      stress_(inertial_spectrum(v, vstar, nu, 1e-12, HalfPlaneSymbol::stress)),
      relaxation_(retardation_spectrum(v)),
      memory_(compliance_.spectrum) {}

double memory_tail_integral(double beta, double T) {
  const double z = 1.0 / (beta * T);
  if (z > 0.1) return beta * (1.0 / T - beta * std::atan(z));
  // beta^2 (z - atan z) by its series (the difference cancels).
  double term = z * z * z, sum = 0.0;
  for (int k = 1; k < 40; ++k) {
    const double add = ((k % 2) ? 1.0 : -1.0) * term / (2 * k + 1);
    sum += add;
    if (std::fabs(add) < 1e-18 * std::fabs(sum)) break;
    term *= z * z;
  }
  return beta * beta * sum;
}

double unrelaxed_phi1(const Viscoelastic& v, double vstar, double nu) {
  const double ratio = v.ratio();
  return wave_constants(vstar / ratio, nu).phi1 / ratio;
}

std::complex<double> half_plane_compliance(const Viscoelastic& v, double vstar, double nu,
                                           double t) {
  const cplx m = v.modulus(t);
  if (vstar == 0.0) return (1.0 - nu) / m;
  return complex_half_plane(vstar / m, nu).phi1 / m;
}

namespace {

// phi1(z + i0), phi2(z + i0) at real z >= 0 and the parts of their pole:
// nT = sqrt(1 - z - i0) and nL = sqrt(1 - z/c2 - i0) (-i sqrt(.) beyond
// their branch points), phi1 = nL/den, phi2 = num2/den (wave_constants').
struct CutValue {
  cplx phi1, phi2, nL, num2, den_prime;
};
CutValue on_cut(double z, double c2) {
  const cplx nT = z < 1.0 ? cplx(std::sqrt(1.0 - z), 0.0) : cplx(0.0, -std::sqrt(z - 1.0));
  const cplx nL = z < c2 ? cplx(std::sqrt(1.0 - z / c2), 0.0) : cplx(0.0, -std::sqrt(z / c2 - 1.0));
  const cplx X = 1.0 + 1.0 / c2 - z / c2, Y = nL * nT;
  // (1 - Y)(1 + Y) = z X: beyond the shear point 4 X/(1 + Y) = 4 (1 - Y)/z
  // (1 + Y and X both vanish at z = c2 + 1).
  const cplx q = z > 1.0 ? 4.0 * (1.0 - Y) / z : 4.0 * X / (1.0 + Y);
  const cplx den = 4.0 - z - q;
  const cplx num2 = q - 2.0 + 2.0 * (c2 - 2.0) / c2 - z * (c2 - 2.0) / c2;
  // d den/dz (below the shear branch point: the Rayleigh pole's residue).
  const cplx dY = -nT / (2.0 * c2 * nL) - nL / (2.0 * nT);
  const cplx dden = -1.0 - 4.0 * ((-1.0 / c2) * (1.0 + Y) - X * dY) / ((1.0 + Y) * (1.0 + Y));
  return {nL / den, num2 / den, nL, num2, dden};
}

// m at t = -i y (real): 1 - sum g_j y D_j/(1 - y D_j); and S = sum g_j D_j/(1 - y D_j)^2
// (m'(-i y) = -i S).
struct AxisModulus {
  double m, S;
};
AxisModulus modulus_on_axis(const std::vector<std::pair<double, double>>& br, double y) {
  AxisModulus a{1.0, 0.0};
  for (const auto& b : br) {
    const double q = 1.0 - y * b.first;
    a.m -= b.second * y * b.first / q;
    a.S += b.second * b.first / (q * q);
  }
  return a;
}

}  // namespace

InertialSpectrum inertial_spectrum(const Viscoelastic& v, double vstar, double nu, double tol,
                                   HalfPlaneSymbol which) {
  if (!(vstar >= 0.0) || !(vstar < rayleigh_vstar(nu)))
    throw std::invalid_argument("inertial_spectrum: 0 <= vstar < the Rayleigh vstar required");
  const bool stress = which == HalfPlaneSymbol::stress;
  InertialSpectrum out;
  const RetardationSpectrum qs = retardation_spectrum(v);
  out.spectrum.ratio = qs.ratio;
  if (vstar == 0.0 || qs.c.empty()) {
    // At rest phi2 = 1 whatever the modulus: no memory in the stress symbol.
    if (!stress) out.spectrum = qs;
    out.h_inf = stress ? wave_constants(vstar / qs.ratio, nu).phi2 : unrelaxed_phi1(v, vstar, nu);
    return out;
  }
  const auto br = branches(v);  // D descending: poles 1/D ascending
  const double ratio = qs.ratio;
  const double c2 = wave_constants(0.0, nu).c2;
  const double vr = rayleigh_vstar(nu);
  out.h_inf = stress ? wave_constants(vstar / ratio, nu).phi2 : unrelaxed_phi1(v, vstar, nu);
  const double hinf = out.h_inf;
  // The exact f on the real axis (the check).
  auto f_exact = [&](double t) {
    return (stress ? half_plane_stress(v, vstar, nu, t) : half_plane_compliance(v, vstar, nu, t)) /
               hinf -
           1.0;
  };
  // Per interval k (between the poles 1/D_{k-1} (0) and 1/D_k of m on the
  // axis, m falling from +inf (1) to -inf through its zero 1/beta_k): the
  // Rayleigh pole, the shear point y_s (m = vstar), the P point y_p (m =
  // vstar/c2) and the zero y_b.
  struct Piece {
    double ga, gb;     // the piece in gaps below the interval's zero (ga > gb >= 0)
    std::size_t zero;  // the index of that zero 1/beta in qs
  };
  std::vector<double> pole_c, pole_beta;
  std::vector<Piece> pieces;
  // m at y = y_K - gap in its factored form prod_k (1 - y beta_k)/prod_j (1 -
  // y D_j) (m(0) = 1), the factor of the interval's own zero 1/beta_K taken
  // from gap: near that zero m is small and its sum form (or y itself) would
  // lose the relative accuracy that the cut's square-root ends need.
  auto m_at = [&](std::size_t zero, double gap) {
    const double y = 1.0 / qs.beta[zero] - gap;
    double m = 1.0;
    for (std::size_t k = 0; k < qs.beta.size(); ++k)
      m *= k == zero ? qs.beta[k] * gap : 1.0 - y * qs.beta[k];
    for (const auto& b : br) m /= 1.0 - y * b.first;
    return m;
  };
  // The gap in (0, span) where m (increasing in the gap) equals target.
  auto gap_root = [&](std::size_t zero, double span, double target) {
    // Bisection in log(gap) to the last bit (m ~ beta_K gap S_K near 0).
    // (span >= 1e-18: lo stays a normal number; the midpoint in logarithms,
    // whose product would underflow.)
    double lo = span * 1e-280, hi = span;
    if (!(m_at(zero, lo) < target)) return lo;
    auto mid_of = [](double a, double b) { return std::exp(0.5 * (std::log(a) + std::log(b))); };
    for (int it = 0; it < 2000; ++it) {
      const double mid = mid_of(lo, hi);
      if (!(mid > lo && mid < hi)) break;
      (m_at(zero, mid) < target ? lo : hi) = mid;
    }
    return mid_of(lo, hi);
  };
  for (std::size_t k = 0; k < br.size(); ++k) {
    const double lo = k == 0 ? 0.0 : 1.0 / br[k - 1].first;
    const std::size_t zero = qs.beta.size() - 1 - k;  // the zeros ascend in y
    const double yb = 1.0 / qs.beta[zero], span = yb - lo;
    const double gR = gap_root(zero, span, vstar / vr);
    const double gs = gap_root(zero, gR, vstar);
    const double gp = gap_root(zero, gs, vstar / c2);
    // The pole at z = v_R (m_R = vstar/v_R; m'(-i y) = -i S, z' = i vstar
    // S/m^2): c = -i Res/y_R, beta = 1/y_R, Res the residue in t of
    // phi1(z)/(m H_inf) (c = -nL m_R/(H_inf den' vstar S y_R)) or of
    // phi2(z)/H_inf (c = -num2 m_R^2/(H_inf den' vstar S y_R)).
    const double yR = yb - gR;
    const double S = modulus_on_axis(br, yR).S;
    const CutValue cv = on_cut(vr, c2);
    const double mR = vstar / vr;
    const double top = stress ? cv.num2.real() * mR * mR : cv.nL.real() * mR;
    pole_c.push_back(-top / (hinf * cv.den_prime.real() * vstar * S * yR));
    pole_beta.push_back(1.0 / yR);
    pieces.push_back({gs, gp, zero});
    pieces.push_back({gp, 0.0, zero});
  }
  // The cut's density at y = y_K - gap: Im f_+/(pi y), f_+ = phi1(z + i0)/(m
  // H_inf) - 1 (or phi2(z + i0)/H_inf - 1).
  auto density = [&](std::size_t zero, double gap) {
    const double m = m_at(zero, gap);
    if (!(m > 0.0)) return 0.0;
    const double y = 1.0 / qs.beta[zero] - gap;
    const CutValue cv = on_cut(vstar / m, c2);
    return (stress ? cv.phi2.imag() : cv.phi1.imag() / m) / hinf / (kPiV * y);
  };
  // Check grid: real t from 1e-3 y_min to 1e3 y_max, 40 a decade, and t = 0.
  const double ymin = 1.0 / *std::max_element(pole_beta.begin(), pole_beta.end());
  const double ymax = 1.0 / qs.beta.front();
  std::vector<double> grid{0.0};
  // (1/(1 - i beta t) varies where t is about 1/beta = y.)
  const double t0 = 1e-3 * ymin, t1 = 1e3 * ymax;
  const int npts = static_cast<int>(std::ceil(40.0 * std::log10(t1 / t0)));
  for (int i = 0; i <= npts; ++i) grid.push_back(t0 * std::pow(t1 / t0, double(i) / npts));
  std::vector<cplx> exact(grid.size());
  double scale = 1.0;  // tol is relative to the largest |f| (f(0) = H(0)/H_inf - 1 ~ ratio)
  for (std::size_t i = 0; i < grid.size(); ++i) {
    exact[i] = f_exact(grid[i]);
    scale = std::max(scale, std::abs(exact[i]));
  }
  auto error_of = [&](const RetardationSpectrum& sp) {
    double err = 0.0;
    for (std::size_t i = 0; i < grid.size(); ++i)
      err = std::max(err, std::abs(sp.memory(grid[i]) - exact[i]));
    return err;
  };
  auto finish = [&](RetardationSpectrum sp, double err) {
    // Ascending beta, as retardation_spectrum's.
    std::vector<std::size_t> idx(sp.beta.size());
    for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
    std::sort(idx.begin(), idx.end(), [&](auto a, auto b) { return sp.beta[a] < sp.beta[b]; });
    out.spectrum.c.clear();
    out.spectrum.beta.clear();
    for (std::size_t i : idx) {
      out.spectrum.c.push_back(sp.c[i]);
      out.spectrum.beta.push_back(sp.beta[i]);
    }
    out.error = err;
    return out;
  };
  for (int n = 16; n <= 256; n *= 2) {
    RetardationSpectrum sp;
    sp.ratio = ratio;
    sp.c = pole_c;
    sp.beta = pole_beta;
    // The cut's terms of each interval (their beta span [lo, hi]).
    std::vector<std::vector<std::pair<double, double>>> cut(br.size());  // (beta, c)
    const std::shared_ptr<const JacobiRule> gl = cached_gauss_jacobi(n, 0.0, 0.0);
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const Piece& p = pieces[i];
      for (Eigen::Index q = 0; q < gl->x.size(); ++q) {
        // gap = gb + (ga - gb) cos^2(th/2), th in [0, pi] (the square roots
        // at both ends analytic in th); |d gap| = (ga - gb)/2 sin th d th.
        const double th = 0.5 * kPiV * (gl->x(q) + 1.0);
        const double cb = std::cos(0.5 * th);
        const double gap = p.gb + (p.ga - p.gb) * cb * cb;
        const double wgt = 0.5 * kPiV * gl->w(q) * 0.5 * (p.ga - p.gb) * std::sin(th);
        const double c = density(p.zero, gap) * wgt;
        if (c == 0.0) continue;
        cut[i / 2].emplace_back(1.0 / (1.0 / qs.beta[p.zero] - gap), c);
      }
    }
    RetardationSpectrum full = sp;
    for (const auto& terms : cut)
      for (const auto& [beta, c] : terms) {
        full.beta.push_back(beta);
        full.c.push_back(c);
      }
    const double err = error_of(full);
    out.error = err;
    if (!(err <= tol * scale)) continue;
    // Compressed: each interval's cut terms moved onto d + 1 Chebyshev points
    // in log beta over their span (c'_j = sum_k c_k l_j(log beta_k), l_j the
    // Lagrange basis): 1/(1 - i beta t) is analytic in log beta within pi/2
    // of the real axis at every t, so a span of a few e-folds needs a few
    // dozen points where the quadrature has 2n. Accepted once the whole
    // sum still matches f to tol; else the quadrature's own terms.
    for (int d = 4; d <= 64 && d + 1 < n; d += 4) {
      RetardationSpectrum cmp = sp;
      for (const auto& terms : cut) {
        if (terms.empty()) continue;
        double lo = kInfV, hi = -kInfV;
        for (const auto& tc : terms) {
          lo = std::min(lo, std::log(tc.first));
          hi = std::max(hi, std::log(tc.first));
        }
        std::vector<double> xs(static_cast<std::size_t>(d) + 1), cs(xs.size(), 0.0);
        for (int j = 0; j <= d; ++j)
          xs[static_cast<std::size_t>(j)] = std::cos(kPiV * j / d);  // Chebyshev extrema
        for (const auto& [beta, c] : terms) {
          const double x = hi > lo ? (2.0 * std::log(beta) - lo - hi) / (hi - lo) : 0.0;
          // Barycentric Lagrange basis at x (weights (-1)^j, halved at the ends).
          double den = 0.0;
          std::vector<double> l(xs.size());
          std::size_t exact_node = xs.size();
          for (std::size_t j = 0; j < xs.size(); ++j) {
            const double wj = ((j % 2) ? -1.0 : 1.0) * ((j == 0 || j + 1 == xs.size()) ? 0.5 : 1.0);
            if (x == xs[j]) exact_node = j;
            l[j] = x == xs[j] ? 0.0 : wj / (x - xs[j]);
            den += l[j];
          }
          for (std::size_t j = 0; j < xs.size(); ++j)
            cs[j] += c * (exact_node < xs.size() ? (j == exact_node ? 1.0 : 0.0) : l[j] / den);
        }
        for (std::size_t j = 0; j < xs.size(); ++j) {
          cmp.beta.push_back(std::exp(0.5 * (lo + hi) + 0.5 * (hi - lo) * xs[j]));
          cmp.c.push_back(cs[j]);
          if (!(hi > lo)) break;  // one point carries it all
        }
      }
      const double e = error_of(cmp);
      if (e <= tol * scale) return finish(cmp, e);
    }
    return finish(full, err);
  }
  std::ostringstream m;
  m << "viscoelastic half-plane with inertia: the memory's spectrum did not reach " << tol
    << " at 256 nodes a piece (vstar = " << vstar << ", error " << out.error << ")";
  throw ConvergenceError(m.str());
}

// ---------------------------------------------------------------------------
// The memory moments l J_n(s, l)

namespace {

constexpr double kPi = 3.14159265358979323846;

// acosh(1 + e), accurate for small e >= 0.
double acosh1p(double e) { return std::log1p(e + std::sqrt(e * (2.0 + e))); }

// The exponential weight's segments in eta = x - s (units 1/l): each a
// factor e^8 at most, to e^-48 (2e-21).
constexpr double kSteps[] = {0, 1, 2, 4, 8, 16, 24, 32, 40, 48};
constexpr double kReach = 48.0;
constexpr double kMaxEfolds = 8.0;  // kSteps' longest segment

// The retardation times of one cluster of a MemoryKernel lie within this
// factor. Its terms share one set of nodes, whose segments follow the
// fastest decay out to the slowest one's reach (up to about 6 kClusterRatio
// + 3 segments where one term has 9), so that the values h_n there (the
// recurrences to order N) are evaluated once for all of them. Wider clusters
// mean more nodes, narrower ones more clusters: on random spectra 4 did a
// little better than 2 or 1.5 (the layers' spectra come in groups a factor
// 1.01 ... 1.2 wide, far apart, which any of these keeps whole).
constexpr double kClusterRatio = 4.0;

// Quadrature nodes of one kind: inside [-1, 1] the value is x (h_n =
// T_{n+1}(x)); beyond, rho = x - sgn(x) sqrt(x^2 - 1) (h_n = rho^{n+1}).
// The weight at a node is jac times the exponential weight at eta.
struct NodeList {
  std::vector<double> eta;    // x - s
  std::vector<double> jac;    // the Jacobian times the Gauss weight
  std::vector<double> value;  // x or rho
  void clear() {
    eta.clear();
    jac.clear();
    value.clear();
  }
  void push(double e, double j, double v) {
    eta.push_back(e);
    jac.push_back(j);
    value.push_back(v);
  }
  std::size_t size() const { return eta.size(); }
};

struct NodeSet {
  NodeList inside, beyond;
  // The density's basis: U (h_n = T_{n+1} inside, rho^{n+1} beyond) or T
  // (h_n = -U_{n-1} inside, sgn(x) rho^n/sqrt(x^2 - 1) beyond: the beyond
  // nodes' jac then carries 1/(|rho| sqrt(x^2 - 1)), their powers as U's).
  MemoryBasis basis = MemoryBasis::U;
  void clear() {
    inside.clear();
    beyond.clear();
  }
};

// Work arrays, one set a thread (one thread_local look-up a call).
struct Scratch {
  std::vector<double> cuts, ecuts, w_in, w_out, acc;
  NodeSet nodes;
  Eigen::MatrixXd H, W, M, P, G;
};

Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

// The ends (eta, ascending from 0) of the exponential weights' segments for
// the decay rates l[0] >= l[1] >= ... >= l[m - 1] > 0: kSteps/l[0], then
// steps of kMaxEfolds e-folds of the fastest term not yet below e^-kReach,
// to the slowest one's reach kReach/l[m - 1]. So no term varies by more than
// e^kMaxEfolds on a segment while it matters, and beyond its own reach it is
// below e^-kReach (as when it is cut off there alone). One term: kSteps/l.
void exponential_cuts(const double* l, std::size_t m, std::vector<double>& cuts) {
  cuts.clear();
  for (double k : kSteps) cuts.push_back(k / l[0]);
  const double end = kReach / l[m - 1];
  std::size_t j = 0;
  for (double e = cuts.back(); e < end; cuts.push_back(e)) {
    while (j + 1 < m && l[j] * e >= kReach) ++j;
    e = std::min(end, e + kMaxEfolds / l[j]);
  }
}

// Appends the nodes of int_{s + e0}^{s + e1} (.) dx (0 <= e0 < e1) that
// integrate h_n (n < count) against an exponential weight whose segments end
// at `ecuts` (exponential_cuts): 16 Gauss-Legendre nodes on each piece, the
// pieces analytic and short for the weight and for h_n's oscillation or
// decay, the branch points x = +-1 taken in angles.
void build_nodes(double s, double e0_in, double e1_in, const std::vector<double>& ecuts, int count,
                 std::vector<double>& cuts, NodeSet& nodes, MemoryBasis basis) {
  nodes.basis = basis;
  const bool tb = basis == MemoryBasis::T;
  static const std::shared_ptr<const JacobiRule> gl = cached_gauss_jacobi(16, 0.0, 0.0);
  const Eigen::VectorXd& gx = gl->x;
  const Eigen::VectorXd& gw = gl->w;
  cuts.clear();
  cuts.push_back(e0_in);
  cuts.push_back(e1_in);
  for (double e : ecuts)
    if (e > e0_in && e < e1_in) cuts.push_back(e);
  // The branch points x = +-1 of h_n.
  for (double e : {-1.0 - s, 1.0 - s})
    if (e > e0_in && e < e1_in) cuts.push_back(e);
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  const double freq = static_cast<double>(count + 1);
  // eta-parametrised piece [e0, e1] (x = s + eta, analytic on it): n0 pieces.
  auto eta_piece = [&](double e0, double e1, bool inside) {
    const double c = 0.5 * (e0 + e1), h = 0.5 * (e1 - e0);
    NodeList& list = inside ? nodes.inside : nodes.beyond;
    for (Eigen::Index q = 0; q < gx.size(); ++q) {
      const double eta = c + h * gx(q), x = s + eta;
      double v = x, jac = h * gw(q);
      if (!inside) {
        const double ax = std::fabs(x), root = std::sqrt((ax - 1.0) * (ax + 1.0));
        const double r = 1.0 / (ax + root);
        v = x > 0.0 ? r : -r;
        if (tb) jac /= r * root;
      }
      list.push(eta, jac, v);
    }
  };
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double e0 = cuts[i], e1 = cuts[i + 1];
    if (!(e1 > e0)) continue;
    const double xm = s + 0.5 * (e0 + e1);
    if (std::fabs(xm) <= 1.0) {
      // Inside: pieces of at most 8/(count + 1) in theta (T_{n+1} = cos((n+1) theta)).
      const double t0 = std::acos(std::clamp(s + e0, -1.0, 1.0));
      const double t1 = std::acos(std::clamp(s + e1, -1.0, 1.0));
      const int m = std::max(1, static_cast<int>(std::ceil(std::fabs(t0 - t1) * freq / 8.0)));
      double prev = e0;
      for (int j = 1; j <= m; ++j) {
        const double next = j == m ? e1 : std::cos(t0 + (t1 - t0) * static_cast<double>(j) / m) - s;
        if (next > prev) eta_piece(prev, next, true);
        prev = std::max(prev, next);
      }
      continue;
    }
    // Beyond +-1: rho^{n+1} = e^{-(n+1) phi}, |x| = cosh phi.
    const bool right = xm > 0.0;
    const double d0 = right ? s + e0 - 1.0 : -1.0 - (s + e1);  // distance of the near end from 1
    const double len = e1 - e0;
    if (d0 >= 2.0 * len) {
      // Far from the branch point for its length: analytic in eta.
      const double ax = right ? s + e0 : -(s + e1);
      const double dphi = len / std::sqrt((ax - 1.0) * (ax + 1.0));
      const int m = std::max(1, static_cast<int>(std::ceil(dphi * freq / 8.0)));
      for (int j = 0; j < m; ++j)
        eta_piece(e0 + len * j / m, j + 1 == m ? e1 : e0 + len * (j + 1) / m, false);
      continue;
    }
    // Near the branch point: parametrised by phi (x - 1 or -1 - x exact).
    const double ea = right ? s + e0 - 1.0 : -1.0 - (s + e1);
    const double eb = right ? s + e1 - 1.0 : -1.0 - (s + e0);
    // The branch point's own cut lands within a rounding of s + (1 - s) of
    // it: from there phi starts at 0 (acosh of a 2e-16 excess is 2e-8, and
    // the T basis' integrand in phi, e^{-n phi}, does not vanish there).
    const double at_branch = 4.0 * std::numeric_limits<double>::epsilon() * (1.0 + std::fabs(s));
    const double pa = ea <= at_branch ? 0.0 : acosh1p(ea), pb = acosh1p(std::max(0.0, eb));
    // eta at |x| = cosh phi: right: (cosh phi - 1) - (s - 1); left: (-1 - s) - (cosh phi - 1).
    double p = pa;
    while (p < pb) {
      const double step = std::min({1.0, std::max(8.0 / freq, 0.5 * p), pb - p});
      const double q1 = p + step >= pb ? pb : p + step;
      const double c = 0.5 * (p + q1), h = 0.5 * (q1 - p);
      for (Eigen::Index q = 0; q < gx.size(); ++q) {
        const double phi = c + h * gx(q);
        // One exponential: e = e^{phi/2} = 1 + em (em = expm1, exact for small phi).
        const double em = std::expm1(0.5 * phi), e = 1.0 + em;
        const double sh = 0.5 * em * (2.0 + em) / e;  // sinh(phi/2)
        const double cm1 = 2.0 * sh * sh;             // cosh phi - 1
        const double sinh_phi = sh * (e + 1.0 / e);   // 2 sinh(phi/2) cosh(phi/2)
        const double eta = right ? cm1 - (s - 1.0) : (-1.0 - s) - cm1;
        const double r = 1.0 / (e * e);  // e^{-phi}
        // (T: dx/sqrt(x^2 - 1) = d phi, over |rho| = e^-phi.)
        nodes.beyond.push(eta, tb ? h * gw(q) * e * e : sinh_phi * h * gw(q), right ? r : -r);
      }
      p = q1;
    }
  }
}

// Eight nodes at a time (independent recurrences side by side).
constexpr int kLanes = 8;
// Powers rho^{n+1}, or their products with the weights (below about 1: they
// make up unit integrals), are dropped below this: they cannot matter, and
// denormal arithmetic is slow.
constexpr double kNegligible = 1e-300;

// out[n] += sum over the nodes of w h_n, n < count (w_in: the weights of
// nodes.inside, w_out: of nodes.beyond): T_{n+1}(x) by its recurrence
// (|x| <= 1), rho^{n+1} by powers.
void weighted_sum(const NodeSet& nodes, const std::vector<double>& w_in,
                  const std::vector<double>& w_out, int count, std::vector<double>& acc,
                  double* out) {
  constexpr int L = kLanes;
  // Per lane and order, summed over the lanes at the end.
  acc.assign(static_cast<std::size_t>(count) * L, 0.0);
  // Lanes past the end: zero weights.
  auto lanes = [](const std::vector<double>& v, const std::vector<double>& w, std::size_t b,
                  double* vl, double* wl) {
    for (int l = 0; l < L; ++l) {
      const std::size_t i = b + static_cast<std::size_t>(l);
      vl[l] = i < v.size() ? v[i] : 0.0;
      wl[l] = i < v.size() ? w[i] : 0.0;
    }
  };
  for (std::size_t b = 0; b < w_in.size(); b += L) {
    double x2[L], wt[L], tm[L], t[L];
    lanes(nodes.inside.value, w_in, b, t, wt);
    // U: T_{n+1} from T_1 = x, T_0 = 1; T: -U_{n-1} from 0 (n = 0) and -U_{-2} = 1.
    const bool tb = nodes.basis == MemoryBasis::T;
    for (int l = 0; l < L; ++l) {
      x2[l] = 2.0 * t[l];
      tm[l] = 1.0;
      if (tb) t[l] = 0.0;
    }
    double* a = acc.data();
    for (int n = 0; n < count; ++n, a += L) {
      for (int l = 0; l < L; ++l) {
        a[l] += wt[l] * t[l];
        const double tn = x2[l] * t[l] - tm[l];
        tm[l] = t[l];
        t[l] = tn;
      }
    }
  }
  for (std::size_t b = 0; b < w_out.size(); b += L) {
    double r[L], wt[L], pw[L];
    lanes(nodes.beyond.value, w_out, b, r, wt);
    double wmax = 0.0, rmax = 0.0;
    for (int l = 0; l < L; ++l) {
      pw[l] = wt[l] * r[l];
      wmax = std::max(wmax, std::fabs(wt[l]));
      rmax = std::max(rmax, std::fabs(r[l]));
    }
    double bound = wmax * rmax;  // |w rho^{n+1}| <= wmax rmax^{n+1}
    double* a = acc.data();
    for (int n = 0; n < count && bound > kNegligible; ++n, a += L) {
      for (int l = 0; l < L; ++l) {
        a[l] += pw[l];
        pw[l] *= r[l];
      }
      bound *= rmax;
    }
  }
  for (int n = 0; n < count; ++n) {
    double sum = 0.0;
    for (int l = 0; l < L; ++l) sum += acc[static_cast<std::size_t>(n) * L + l];
    out[n] += sum;
  }
}

// Adds l int_{s + e0}^{s + e1} e^{-l (x - s)} h_n(x) dx to out[n], n < count
// (0 <= e0 < e1 <= kReach/l).
void add_segment(double s, double l, double e0, double e1, int count, double* out,
                 MemoryBasis basis) {
  Scratch& w = scratch();
  exponential_cuts(&l, 1, w.ecuts);
  w.nodes.clear();
  build_nodes(s, e0, e1, w.ecuts, count, w.cuts, w.nodes, basis);
  w.w_in.resize(w.nodes.inside.size());
  w.w_out.resize(w.nodes.beyond.size());
  for (auto [list, wt] : {std::pair{&w.nodes.inside, &w.w_in}, {&w.nodes.beyond, &w.w_out}})
    for (std::size_t q = 0; q < list->size(); ++q)
      (*wt)[q] = l * std::exp(-l * list->eta[q]) * list->jac[q];
  weighted_sum(w.nodes, w.w_in, w.w_out, count, w.acc, out);
}

// One cluster of terms, l[0] >= ... >= l[m - 1] (c: their coefficients),
// and the Taylor expansion of their exponentials about the middle rate lc:
// with D = (l[0] - l[m - 1])/2 (|l_t - lc| <= D) and y = D eta,
//   l_t e^{-l_t eta} = e^{-lc eta} sum_j mix(t, j) y^j,
//   mix(t, j) = l_t (-(l_t - lc)/D)^j / j!,
// and the sum of the weights sum_t c_t l_t e^{-l_t eta} = e^{-lc eta}
// sum_j comb_j y^j (comb = mix^T c). Where D eta stays small (a narrow
// cluster, a short segment) a few orders stand for all the terms: one
// exponential a node and a short polynomial instead of one exponential a
// term (and in the collocation block's matrix products fewer rows).
struct Cluster {
  const double* l = nullptr;
  const double* c = nullptr;
  std::size_t m = 0;
  double lc = 0.0, D = 0.0;
  // Orders below these cost less than the terms (for the sum of the
  // weights; for term_sums at the moments' count).
  int comb_cap = 0, term_cap = 0;
  Eigen::MatrixXd mix;  // m x the orders used so far (extend)
  Eigen::VectorXd comb;
};

// The expansion's truncation, below the sums' round-off.
constexpr double kTaylorTol = 0.0625 * std::numeric_limits<double>::epsilon();
// Costs a node in exponentials (a libm call, about 5.6 ns here): an order of
// the expansion (a multiply-add over the nodes side by side, about 0.45 ns),
// and a flop of term_sums' matrix products (about 4 a cycle, against some 16
// cycles an exponential).
constexpr double kOrderCost = 1.0 / 12.0;
constexpr double kFlopCost = 1.0 / 64.0;

// The orders j < cap that cost less than the terms: 1 exponential + j
// per_order < m per_term.
int order_cap(std::size_t m, double per_term, double per_order) {
  return std::max(
      1, static_cast<int>(std::ceil((static_cast<double>(m) * per_term - 1.0) / per_order)));
}

// The cluster of the rates l (descending) and coefficients c of m terms, for
// moments to order count.
void prepare_cluster(const double* l, const double* c, std::size_t m, int count, Cluster& cl) {
  cl.l = l;
  cl.c = c;
  cl.m = m;
  cl.lc = 0.5 * (l[0] + l[m - 1]);
  cl.D = 0.5 * (l[0] - l[m - 1]);
  const double flops = 2.0 * count * kFlopCost;  // a node's row of a matrix product
  cl.comb_cap = order_cap(m, 1.0, kOrderCost);
  cl.term_cap = order_cap(m, 1.0 + flops, kOrderCost + flops);
  cl.mix.resize(static_cast<Eigen::Index>(m), 0);
}

// mix and comb to at least `orders` orders.
void extend(Cluster& cl, int orders) {
  const Eigen::Index have = cl.mix.cols();
  if (orders <= have) return;
  const auto mm = static_cast<Eigen::Index>(cl.m);
  cl.mix.conservativeResize(mm, orders);
  for (Eigen::Index t = 0; t < mm; ++t) {
    const double ratio = cl.D > 0.0 ? -(cl.l[t] - cl.lc) / cl.D : 0.0;  // in [-1, 1]
    double v = have == 0 ? cl.l[t] : cl.mix(t, have - 1) * ratio / static_cast<double>(have);
    for (Eigen::Index j = have; j < orders; ++j) {
      cl.mix(t, j) = v;
      v *= ratio / static_cast<double>(j + 1);
    }
  }
  cl.comb = cl.mix.transpose() * Eigen::Map<const Eigen::VectorXd>(cl.c, mm);
}

// The orders of the expansion (at most cap; cap: none found) for an
// integral over eta in [0, len]. Its truncation after J orders, per unit c_t
// and relative to the integral's scale 1, is below r (D len)^J/J! e^{D len}
// (r = l_max/l_min: the remainder (D eta)^J/J! e^{D eta} on [0, len], times
// the weight's mass), and below r (D/l_min)^J (the same remainder against
// the weight e^{-lc eta} over all eta > 0). A segment `chained` to others in
// one sum (the descending recursion) takes the first only: its bound is
// relative to the segment's own mass, and the masses add up to one integral.
int taylor_order(const Cluster& cl, double len, int cap, bool chained) {
  const double lmin = cl.l[cl.m - 1], r = cl.l[0] / lmin, x = cl.D * len;
  double whole = chained ? kInfV : r, part = r * std::exp(x);
  for (int j = 1; j < cap; ++j) {
    whole *= cl.D / lmin;
    part *= x / j;
    if (std::min(whole, part) <= kTaylorTol) return j;
  }
  return cap;
}

// The weights jac sum_t c_t l_t e^{-l_t eta} at the nodes (w_in:
// nodes.inside, w_out: nodes.beyond; eta <= len): by the expansion when it
// is cheaper, else term by term.
void combined_weights(const NodeSet& nodes, Cluster& cl, double len, std::vector<double>& w_in,
                      std::vector<double>& w_out) {
  const int cap = cl.comb_cap;
  const int order = taylor_order(cl, len, cap, false);
  if (order < cap) extend(cl, order);
  w_in.resize(nodes.inside.size());
  w_out.resize(nodes.beyond.size());
  for (auto [list, wt] : {std::pair{&nodes.inside, &w_in}, {&nodes.beyond, &w_out}}) {
    const std::size_t size = list->size();
    double* out = wt->data();
    const double* eta = list->eta.data();
    if (order < cap) {
      // Horner's rule in y = D eta, over the nodes side by side.
      for (std::size_t q = 0; q < size; ++q) out[q] = cl.comb(order - 1);
      for (int j = order - 2; j >= 0; --j) {
        const double cj = cl.comb(j);
        for (std::size_t q = 0; q < size; ++q) out[q] = out[q] * (cl.D * eta[q]) + cj;
      }
      for (std::size_t q = 0; q < size; ++q) out[q] *= std::exp(-cl.lc * eta[q]) * list->jac[q];
      continue;
    }
    for (std::size_t q = 0; q < size; ++q) {
      double sum = 0.0;
      for (std::size_t t = 0; t < cl.m; ++t) sum += cl.c[t] * cl.l[t] * std::exp(-cl.l[t] * eta[q]);
      out[q] = sum * list->jac[q];
    }
  }
}

// P(t, n) = sum over the nodes (eta <= len) of l_t e^{-l_t eta} jac h_n,
// t < m, n < count: the values h_n at a chunk of nodes as a matrix H, once
// for all the terms, against a few functions of eta (the expansion's orders
// when they cost less, else the terms' own weights) in one matrix product a
// chunk; then mixed into the terms. `chained`: taylor_order.
void term_sums(const NodeSet& nodes, Cluster& cl, double len, bool chained, int count, Scratch& w,
               Eigen::MatrixXd& P) {
  constexpr int L = kLanes;
  constexpr Eigen::Index kChunk = 16 * L;  // nodes (a few pieces) a product
  const auto mm = static_cast<Eigen::Index>(cl.m);
  const int order = taylor_order(cl, len, cl.term_cap, chained);
  const bool expand = order < cl.term_cap;
  if (expand) extend(cl, order);
  const Eigen::Index rows = expand ? order : mm;
  w.H.resize(kChunk, count);
  w.W.resize(rows, kChunk);
  Eigen::MatrixXd& M = expand ? w.M : P;
  M.setZero(rows, count);
  for (const NodeList* list : {&nodes.inside, &nodes.beyond}) {
    const bool inside = list == &nodes.inside;
    const auto size = static_cast<Eigen::Index>(list->size());
    for (Eigen::Index b0 = 0; b0 < size; b0 += kChunk) {
      const Eigen::Index c = std::min(kChunk, size - b0);
      for (Eigen::Index q = 0; q < c; ++q) {
        const auto i = static_cast<std::size_t>(b0 + q);
        const double eta = list->eta[i], jac = list->jac[i];
        if (expand) {
          const double y = cl.D * eta;
          double v = std::exp(-cl.lc * eta) * jac;
          for (Eigen::Index j = 0; j < rows; ++j, v *= y) w.W(j, q) = v;
        } else {
          for (Eigen::Index t = 0; t < mm; ++t)
            w.W(t, q) = cl.l[t] * std::exp(-cl.l[t] * eta) * jac;
        }
      }
      // H(q, n) = h_n at node b0 + q, lanes past the end at value 0 (unused).
      for (Eigen::Index b = 0; b < c; b += L) {
        double v[L];
        for (int k = 0; k < L; ++k)
          v[k] = b + k < c ? list->value[static_cast<std::size_t>(b0 + b + k)] : 0.0;
        double* h = w.H.data() + b;  // column n at h + n kChunk
        if (inside) {
          double x2[L], tm[L];
          for (int k = 0; k < L; ++k) {
            x2[k] = 2.0 * v[k];
            tm[k] = 1.0;
            if (nodes.basis == MemoryBasis::T) v[k] = 0.0;  // (weighted_sum's)
          }
          for (int n = 0; n < count; ++n, h += kChunk) {
            for (int k = 0; k < L; ++k) {
              h[k] = v[k];
              const double tn = x2[k] * v[k] - tm[k];
              tm[k] = v[k];
              v[k] = tn;
            }
          }
        } else {
          double r[L], rmax = 0.0;
          for (int k = 0; k < L; ++k) {
            r[k] = v[k];
            rmax = std::max(rmax, std::fabs(r[k]));
          }
          double bound = rmax;  // |rho^{n+1}| <= rmax^{n+1}
          int n = 0;
          for (; n < count && bound > kNegligible; ++n, h += kChunk) {
            for (int k = 0; k < L; ++k) {
              h[k] = v[k];
              v[k] *= r[k];
            }
            bound *= rmax;
          }
          for (; n < count; ++n, h += kChunk)
            for (int k = 0; k < L; ++k) h[k] = 0.0;
        }
      }
      M.noalias() += w.W.leftCols(c) * w.H.topRows(c);
    }
  }
  if (expand) P.noalias() = cl.mix.leftCols(rows) * M;
}

// Adds sum_t c_t l_t J_n(s, l_t) (n < count) over one cluster: one set of
// nodes for all its terms (exponential_cuts), against the sum of their
// exponential weights.
void add_cluster(double s, Cluster& cl, int count, double* out, MemoryBasis basis) {
  Scratch& w = scratch();
  exponential_cuts(cl.l, cl.m, w.ecuts);
  const double reach = w.ecuts.back();
  w.nodes.clear();
  build_nodes(s, 0.0, reach, w.ecuts, count, w.cuts, w.nodes, basis);
  combined_weights(w.nodes, cl, reach, w.w_in, w.w_out);
  weighted_sum(w.nodes, w.w_in, w.w_out, count, w.acc, out);
}

// mom(k, n) += sum_t c_t l_t J_n(s_k, l_t) at the rows s[0] > s[1] > ...
// (mom: rows x count, row-major) over one cluster: the descending recursion
// of memory_moments_descending for each term, G_t(s_k) = (the segment [s_k,
// s_{k-1}]) + e^{-l_t (s_{k-1} - s_k)} G_t(s_{k-1}), its segments' node
// values evaluated once for all the terms (term_sums). A row whose gap to
// the previous one exceeds the cluster's reach starts afresh (the carried
// part is below e^-kReach), and one whose next row starts afresh needs no
// G_t: the sum of the weights will do.
void add_cluster_descending(const double* s, int rows, Cluster& cl, int count, double* mom,
                            MemoryBasis basis) {
  Scratch& w = scratch();
  exponential_cuts(cl.l, cl.m, w.ecuts);
  const double reach = w.ecuts.back();
  const auto mm = static_cast<Eigen::Index>(cl.m);
  const Eigen::Map<const Eigen::VectorXd> c(cl.c, mm);
  Eigen::VectorXd cf(mm);  // c_t e^{-l_t gap}: the carried part of a row without G_t
  w.G.resize(mm, count);
  for (int k = 0; k < rows; ++k) {
    Eigen::Map<Eigen::RowVectorXd> row(mom + static_cast<std::size_t>(k) * count, count);
    const double gap = k == 0 ? kInfV : s[k - 1] - s[k], len = std::min(gap, reach);
    const bool fresh = !(gap < reach);
    const bool feeds = k + 1 < rows && s[k] - s[k + 1] < reach;
    w.nodes.clear();
    build_nodes(s[k], 0.0, len, w.ecuts, count, w.cuts, w.nodes, basis);
    if (feeds) {
      term_sums(w.nodes, cl, len, !fresh, count, w, w.P);
      if (fresh) {
        w.G = w.P;
      } else {
        for (Eigen::Index t = 0; t < mm; ++t) w.G.row(t) *= std::exp(-cl.l[t] * gap);
        w.G += w.P;
      }
      row += c.transpose() * w.G;
      continue;
    }
    combined_weights(w.nodes, cl, len, w.w_in, w.w_out);
    weighted_sum(w.nodes, w.w_in, w.w_out, count, w.acc, row.data());
    if (!fresh) {
      for (Eigen::Index t = 0; t < mm; ++t) cf(t) = c(t) * std::exp(-cl.l[t] * gap);
      row += cf.transpose() * w.G;
    }
  }
}

void check_moment_args(double s, double l) {
  if (!std::isfinite(s) || !(l > 0.0) || !std::isfinite(l))
    throw std::invalid_argument("memory_moments: s finite and l > 0 finite required");
}

void check_descending(const double* s, int rows) {
  for (int k = 1; k < rows; ++k)
    if (!(s[k] < s[k - 1]))
      throw std::invalid_argument("memory_moments_descending: s must be strictly descending");
}

}  // namespace

void memory_moments(double s, double l, int count, double* out, MemoryBasis basis) {
  if (count <= 0) return;
  check_moment_args(s, l);
  std::fill(out, out + count, 0.0);
  add_segment(s, l, 0.0, kReach / l, count, out, basis);
}

void memory_moments_descending(const double* s, int rows, double l, int count, double* out,
                               MemoryBasis basis) {
  if (count <= 0 || rows <= 0) return;
  for (int k = 0; k < rows; ++k) check_moment_args(s[k], l);
  check_descending(s, rows);
  memory_moments(s[0], l, count, out, basis);
  // G(s_k) = l int_{s_k}^{s_{k-1}} e^{-l (x - s_k)} h_n + e^{-l (s_{k-1} - s_k)} G(s_{k-1}):
  // one short segment a row (the factor <= 1: stable downwards).
  for (int k = 1; k < rows; ++k) {
    double* row = out + static_cast<std::size_t>(k) * count;
    const double* prev = row - count;
    const double gap = s[k - 1] - s[k], f = std::exp(-l * gap);
    for (int n = 0; n < count; ++n) row[n] = f * prev[n];
    add_segment(s[k], l, 0.0, std::min(gap, kReach / l), count, row, basis);
  }
}

MemoryKernel::MemoryKernel(RetardationSpectrum spectrum) : spec_(std::move(spectrum)) {
  // Clusters of retardation times within kClusterRatio, greedily from the
  // shortest (the fastest decay, which sets a cluster's segments). A beta
  // that is not a number sorts last, alone (refused there as memory_moments
  // refuses it).
  order_.resize(spec_.c.size());
  for (std::size_t k = 0; k < order_.size(); ++k) order_[k] = k;
  auto key = [this](std::size_t k) { return std::isnan(spec_.beta[k]) ? kInfV : spec_.beta[k]; };
  std::stable_sort(order_.begin(), order_.end(),
                   [&key](std::size_t a, std::size_t b) { return key(a) < key(b); });
  for (std::size_t j = 0; j < order_.size(); ++j)
    if (j == 0 || !(spec_.beta[order_[j]] <= kClusterRatio * spec_.beta[order_[starts_.back()]]))
      starts_.push_back(j);
  starts_.push_back(order_.size());
}

void MemoryKernel::moments(double s, double w, int count, double* out, MemoryBasis basis) const {
  if (count <= 0) return;
  std::fill(out, out + count, 0.0);
  thread_local std::vector<double> one, l, c;
  thread_local Cluster cluster;
  one.resize(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i + 1 < starts_.size(); ++i) {
    const std::size_t j0 = starts_[i], m = starts_[i + 1] - j0;
    if (m == 1) {
      // One term: memory_moments itself.
      const std::size_t k = order_[j0];
      memory_moments(s, w / spec_.beta[k], count, one.data(), basis);
      for (int n = 0; n < count; ++n) out[n] += spec_.c[k] * one[static_cast<std::size_t>(n)];
      continue;
    }
    cluster_terms(j0, m, w, l, c);
    for (double lt : l) check_moment_args(s, lt);
    prepare_cluster(l.data(), c.data(), m, count, cluster);
    add_cluster(s, cluster, count, out, basis);
  }
}

void MemoryKernel::cluster_terms(std::size_t j0, std::size_t m, double w, std::vector<double>& l,
                                 std::vector<double>& c) const {
  l.resize(m);
  c.resize(m);
  for (std::size_t t = 0; t < m; ++t) {
    const std::size_t k = order_[j0 + t];
    l[t] = w / spec_.beta[k];
    c[t] = spec_.c[k];
  }
}

Eigen::MatrixXd MemoryKernel::collocation_block(const ChebyshevNodes& nodes, double w) const {
  // The collocation points descend (s_k = cos((2k - 1) pi/(2(N + 1)))).
  return block_at(nodes.s.data(), nodes.n + 1, nodes, w);
}

void MemoryKernel::moments_descending(const double* s, int rows, double w, int count, double* out,
                                      MemoryBasis basis) const {
  // The moments of all rows in one downward sweep per cluster of retardation times.
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  Eigen::Map<RowMajor> mom(out, rows, count);
  mom.setZero();
  if (rows <= 0 || count <= 0) return;
  RowMajor one(rows, count);
  std::vector<double> l, c;
  Cluster cluster;
  for (std::size_t i = 0; i + 1 < starts_.size(); ++i) {
    const std::size_t j0 = starts_[i], m = starts_[i + 1] - j0;
    if (m == 1) {
      // One term: memory_moments_descending itself.
      const std::size_t k = order_[j0];
      memory_moments_descending(s, rows, w / spec_.beta[k], count, one.data(), basis);
      mom += spec_.c[k] * one;
      continue;
    }
    cluster_terms(j0, m, w, l, c);
    for (double lt : l)
      for (int r = 0; r < rows; ++r) check_moment_args(s[r], lt);
    check_descending(s, rows);
    prepare_cluster(l.data(), c.data(), m, count, cluster);
    add_cluster_descending(s, rows, cluster, count, mom.data(), basis);
  }
}

Eigen::MatrixXd MemoryKernel::block_at(const double* s, int rows, const ChebyshevNodes& nodes,
                                       double w) const {
  const int n = nodes.n;
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor mom(rows, n);
  moments_descending(s, rows, w, n, mom.data());
  return mom * *basis_weights(nodes);
}

void MemoryKernel::apply_descending(const Eigen::VectorXd& b, const double* s, int rows, double w,
                                    double* out) const {
  const auto n = static_cast<int>(b.size());
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor mom(rows, n);
  moments_descending(s, rows, w, n, mom.data());
  Eigen::Map<Eigen::VectorXd>(out, rows) = mom * b;
}

std::shared_ptr<const Eigen::MatrixXd> MemoryKernel::basis_weights(const ChebyshevNodes& nodes) {
  // -2 W_i U_q(r_i) (U_q(r_i) = sin((q + 1) th_i)/sin(th_i), th_i = i pi/(n + 1)),
  // per size: the width iteration assembles many blocks at one N.
  static std::mutex mutex;
  static std::map<int, std::shared_ptr<const Eigen::MatrixXd>> cache;
  const int n = nodes.n;
  {
    std::lock_guard<std::mutex> lock(mutex);
    const auto it = cache.find(n);
    if (it != cache.end()) return it->second;
  }
  auto U = std::make_shared<Eigen::MatrixXd>(n, n);
  for (int i = 0; i < n; ++i) {
    const double th = (i + 1) * kPi / (n + 1);
    for (int q = 0; q < n; ++q)
      (*U)(q, i) = -2.0 * nodes.w(i) * std::sin((q + 1) * th) / std::sin(th);
  }
  std::lock_guard<std::mutex> lock(mutex);
  if (cache.size() > 64) cache.clear();
  auto& slot = cache[n];
  if (!slot) slot = std::move(U);
  return slot;
}

double MemoryKernel::apply(const Eigen::VectorXd& b, double s, double w, MemoryBasis basis) const {
  const int n = static_cast<int>(b.size());
  thread_local std::vector<double> mom;
  mom.resize(static_cast<std::size_t>(n));
  moments(s, w, n, mom.data(), basis);
  double sum = 0.0;
  for (int q = 0; q < n; ++q) sum += b(q) * mom[static_cast<std::size_t>(q)];
  return sum;
}

}  // namespace movingpunch

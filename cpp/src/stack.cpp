// Layered media (stack.hpp; docs/media.md).
#include "stack.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "critical_search.hpp"
#include "layer_basis.hpp"
#include "memo.hpp"
#include "movingpunch/errors.hpp"
#include "roots.hpp"

namespace movingpunch {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;
// Attraction (in e-folds of the basis) beyond which the deeper structure is
// not evaluated: its effect on the surface is below e^-100, on the state
// at the start depth below e^-50.
constexpr double kCut = 100.0;
// Largest ||generator||_inf of one Taylor slice (growth <= e^2 per slice, no
// cancellation in its series); the modal step from t d = kModalT.
constexpr double kSliceNorm = 2.0;
constexpr double kModalT = 0.5;

using cplx = std::complex<double>;
template <class S>
using Mat42T = Eigen::Matrix<S, 4, 2>;
template <class S>
using Vec4T = Eigen::Matrix<S, 4, 1>;
template <class S>
using Mat4T = Eigen::Matrix<S, 4, 4>;
template <class S>
using Mat2T = Eigen::Matrix<S, 2, 2>;
using Mat42 = Mat42T<double>;
using Vec4 = Vec4T<double>;
using Mat4 = Mat4T<double>;

// The real part of a real or complex quantity (the elastic sublayers of a
// complex propagation have real constants stored as complex).
inline double real_of(double x) { return x; }
inline double real_of(cplx x) { return x.real(); }
// |x| of a positive real root (as is) or of a complex one.
inline double size_of(double x) { return x; }
inline double size_of(cplx x) { return std::abs(x); }

// exp(B) by its Taylor series (||B||_inf <= ~0.5).
template <class S>
Mat4T<S> taylor_exp(const Mat4T<S>& B) {
  Mat4T<S> P = Mat4T<S>::Identity(), term = Mat4T<S>::Identity();
  for (int k = 1; k < 80; ++k) {
    term = term * B / static_cast<double>(k);
    P += term;
    if (k > 3 && term.cwiseAbs().maxCoeff() <= 1e-18 * P.cwiseAbs().maxCoeff()) break;
  }
  return P;
}

// Orthonormalises the columns of S by column operations (classical
// Gram-Schmidt, twice; the Hermitian product when complex): S_in = S_out R,
// R upper triangular with a positive diagonal (the orientation of the basis
// is kept).
template <class S>
Mat2T<S> orthonormalise(Mat42T<S>& M) {
  Mat2T<S> R = Mat2T<S>::Identity();
  for (int pass = 0; pass < 2; ++pass) {
    const double r11 = M.col(0).norm();
    M.col(0) /= r11;
    const S r12 = M.col(0).dot(M.col(1));
    M.col(1) -= r12 * M.col(0);
    const double r22 = M.col(1).norm();
    M.col(1) /= r22;
    Mat2T<S> Rp;
    Rp << S(r11), r12, S(0.0), S(r22);
    R = Rp * R;
  }
  return R;
}

template <class S>
Mat4T<S> stress_scale(S m) {
  return Vec4T<S>(S(1.0), S(1.0), m, m).asDiagonal();
}

// An elastic sublayer's constants in a complex propagation (the same numbers).
ComplexWaveConstants cast_constants(const WaveConstants& w) {
  ComplexWaveConstants c;
  c.s = w.s;
  c.nu = w.nu;
  c.c2 = w.c2;
  c.nT = w.nT;
  c.nL = w.nL;
  c.delta = w.delta;
  c.phi1 = w.phi1;
  c.phi2 = w.phi2;
  c.dW = w.dW;
  c.dT = w.dT;
  c.dS = w.dS;
  c.A = w.A.cast<cplx>();
  c.hp1 = w.hp1;
  c.hp2 = w.hp2;
  return c;
}

// One sublayer at the speed (and, complex, at one wavenumber: a
// viscoelastic sublayer's modulus mu m(t) and constants at vstar rho/(mu m)).
template <class S>
struct Sub {
  double y_top = 0, y_bot = -1, d = 1;
  S m_top{1.0};      // mu at the top (top sublayer's relaxed units)
  double gamma = 0;  // gamma_h
  bool graded = false;
  BasicWaveConstants<S> c;  // local constants at s = vstar rho / mu
  S m_at(double y) const { return graded ? m_top * std::exp(gamma * (y - y_top)) : m_top; }
  S m_bot() const { return m_at(y_bot); }
  S sx(const Vec4T<S>& z, S m) const {
    return m * 4.0 * (c.c2 - 1.0) / c.c2 * z(0) + (c.c2 - 2.0) / c.c2 * z(3);
  }
};

// One sublayer's map of the basis from its bottom to its top (scaled
// variables: stresses over the local modulus).
template <class S>
struct Segment {
  int layer = 0;
  bool modal = false;
  bool start = false;  // the deepest evaluated sublayer: no input from below
  double t_loc = 0;    // t d
  // Slices: from yhat = lo to 0 in n slices of width h, each exp(Bh).
  double lo = -1.0, h = 1.0;
  int n = 1;
  Mat4T<S> Bh = Mat4T<S>::Zero();
  std::vector<Mat42T<S>> basis;         // at each slice's bottom (normalised)
  std::vector<Mat2T<S>> R;              // basis[k+1] R[k] = exp(Bh) basis[k]
  Mat42T<S> Nul;                        // modal: amplitudes a = Nul c_raw
  Mat42T<S> in = Mat42T<S>::Zero();     // normalised scaled input
  Mat2T<S> Rin = Mat2T<S>::Identity();  // in = scaled input Rin^-1
};

template <class S>
struct Propagation {
  std::vector<Segment<S>> segs;  // top sublayer first
  Mat42T<S> S_top;               // orthonormal basis at the surface
  double orient = 1.0;           // +-1: the orientation relative to the transfer maps
  bool cut = false;              // structure below segs.back() not evaluated
};

// The medium's data at one speed (no validation of the speed against the
// critical one: the critical-speed search uses it at every speed). S =
// double: the elastic stack (a viscoelastic sublayer: its relaxed elastic
// one); S = complex: every sublayer at the wavenumber t of the constructor,
// a viscoelastic one with its modulus mu m(t) (docs/media.md).
template <class S>
class Core {
 public:
  // The (relaxed) elastic stack at vstar (S = double).
  Core(const MediumSpec& spec, double vstar) : base_(spec.base), s_(vstar) {
    static_assert(std::is_same_v<S, double>, "a complex core is built from the relaxed one");
    double y = 0.0;
    for (const Sublayer& l : spec.layers) {
      Sub<S> sb;
      sb.y_top = y;
      sb.d = l.thickness;
      y -= l.thickness;
      sb.y_bot = y;
      sb.gamma = l.gamma;
      sb.graded = l.gamma != 0.0;
      sb.m_top = l.mu;
      sb.c = wave_constants(vstar * l.rho / l.mu, l.nu);
      subs_.push_back(sb);
    }
    subs_.back().y_bot = -1.0;
    subs_.back().d = subs_.back().y_top + 1.0;
    const BaseSpec& b = spec.base;
    if (b.kind != BaseKind::springs) sub_ = wave_constants(vstar * b.rho / b.mu, b.nu);
  }

  // The stack at wavenumber t (S = complex) from the relaxed one: its
  // elastic sublayers and the substrate as they are (their constants do not
  // depend on t), each viscoelastic sublayer of `spec` at mu m(t) and the
  // speed vstar rho/(mu m(t)).
  Core(const Core<double>& relaxed, const MediumSpec& spec, double t)
      : base_(relaxed.base()), s_(relaxed.vstar()), sub_(relaxed.substrate()) {
    static_assert(!std::is_same_v<S, double>, "the relaxed core is the real one");
    const std::vector<Sub<double>>& rs = relaxed.subs();
    subs_.reserve(rs.size());
    for (std::size_t i = 0; i < rs.size(); ++i) {
      const Sub<double>& r = rs[i];
      const Sublayer& l = spec.layers[i];
      Sub<S> sb;
      sb.y_top = r.y_top;
      sb.y_bot = r.y_bot;
      sb.d = r.d;
      sb.gamma = r.gamma;
      sb.graded = r.graded;
      const cplx m = l.visco.empty() ? cplx(1.0) : l.visco.modulus(t);
      sb.m_top = r.m_top * m;
      sb.c = m == 1.0 ? cast_constants(r.c) : complex_wave_constants(s_ * l.rho / sb.m_top, l.nu);
      subs_.push_back(sb);
    }
  }

  const BaseSpec& base() const { return base_; }
  double vstar() const { return s_; }
  const WaveConstants& substrate() const { return sub_; }

  const std::vector<Sub<S>>& subs() const { return subs_; }

  // The base's two-dimensional solution space at y = -1 (unscaled).
  Mat42T<S> base_space(double t) const {
    const BaseSpec& b = base_;
    Mat42 M = Mat42::Zero();
    M(0, 0) = 1.0;
    if (b.kind == BaseKind::springs) {
      const double k = b.kw + b.kp * t * t;
      if (std::isinf(k)) {
        M(3, 1) = 1.0;
      } else {
        // t sigma/alpha = k W, as [t/(t+k)] sigma/alpha = [k/(t+k)] W.
        M(1, 1) = 1.0 / (1.0 + k / t);
        M(3, 1) = 1.0 / (1.0 + t / k);
      }
    } else if (b.kind == BaseKind::half_space_smooth) {
      // tau = 0; sigma = alpha mu2 v / phi1_2: phi1_2 = nL / den, regular form.
      const double sub_den = sub_.nL / sub_.phi1;
      M(1, 1) = sub_.nL;
      M(3, 1) = b.mu * sub_den;
    } else {
      // The substrate's downward-decaying modes at its face (independent of t).
      const Mat4 C = detail::modal_columns(sub_, 1.0, 0.0);
      M = stress_scale(b.mu) * C.leftCols<2>();
    }
    orthonormalise(M);
    return M.template cast<S>();
  }

  // The attraction of the basis over the whole sublayer i at t.
  double attraction(const Sub<S>& sb, double t) const {
    const double td = t * sb.d;
    if (!sb.graded) return 2.0 * td * real_of(sb.c.nT);
    // (A graded sublayer is elastic: its constants are real.)
    Mat4 G;
    for (int r = 0; r < 4; ++r)
      for (int k = 0; k < 4; ++k) G(r, k) = real_of(sb.c.A(r, k));
    const double g = sb.gamma / t;  // per unit t: the generator is t (A - g D)
    G(2, 2) -= g;
    G(3, 3) -= g;
    Eigen::EigenSolver<Mat4> es(G, false);
    std::vector<double> re;
    for (int i = 0; i < 4; ++i) re.push_back(es.eigenvalues()(i).real());
    std::sort(re.begin(), re.end(), std::greater<double>());
    return (re[1] - re[2]) * td;
  }

  // dispersion: homogeneous sublayers are never cut (their modal maps keep
  // a continuous orientation at every t), and the orientation is tracked.
  Propagation<S> propagate(double t, bool dispersion) const {
    Propagation<S> P;
    const int K = static_cast<int>(subs_.size());
    int i0 = K;
    double start_depth = 1.0;
    for (int i = 0; i < K; ++i) {
      const Sub<S>& sb = subs_[static_cast<size_t>(i)];
      if (dispersion && !sb.graded) continue;
      if (t * sb.d * 2.0 * std::max(size_of(sb.c.nL), 1.0) + std::fabs(sb.gamma) * sb.d <
          0.5 * kCut)
        continue;  // cannot reach kCut (|eigenvalues| <= t |nL| + |gamma|)
      const double a = attraction(sb, t);
      if (a >= kCut) {
        i0 = i;
        start_depth = kCut / a;
        break;
      }
    }
    P.cut = i0 < K;
    const int last = P.cut ? i0 : K - 1;
    std::vector<Segment<S>> segs(static_cast<size_t>(last + 1));
    Mat42T<S> M =
        P.cut ? Mat42T<S>(Mat42T<S>::Zero()) : base_space(t);  // unscaled, at the current depth
    for (int i = last; i >= 0; --i) {
      const Sub<S>& sb = subs_[static_cast<size_t>(i)];
      Segment<S>& g = segs[static_cast<size_t>(i)];
      g.layer = i;
      g.t_loc = t * sb.d;
      g.start = P.cut && i == i0;
      Mat42T<S> top;
      if (g.start && !sb.graded) {
        g.modal = true;
        g.Nul.setZero();
        g.Nul(0, 0) = g.Nul(1, 1) = S(1.0);
        top = detail::modal_columns(sb.c, g.t_loc, 0.0).template leftCols<2>();
      } else if (!sb.graded && g.t_loc >= kModalT) {
        g.modal = true;
        g.in = stress_scale<S>(1.0 / sb.m_bot()) * M;
        g.Rin = orthonormalise(g.in);
        modal_step(sb, g, dispersion ? &P.orient : nullptr);
        top = detail::modal_columns(sb.c, g.t_loc, 0.0) * g.Nul;
      } else {
        // Slices of the constant-coefficient generator (scaled variables).
        if (g.start) {
          g.lo = -start_depth;
          g.in = detail::modal_columns(sb.c, g.t_loc, 0.0).template leftCols<2>();
        } else {
          g.lo = -1.0;
          g.in = stress_scale<S>(1.0 / sb.m_bot()) * M;
        }
        g.Rin = orthonormalise(g.in);
        const double span = -g.lo;
        Mat4T<S> Dg = Mat4T<S>::Zero();
        Dg(2, 2) = Dg(3, 3) = S(sb.gamma * sb.d);
        const Mat4T<S> Bspan = (g.t_loc * span) * sb.c.A - span * Dg;
        const double norm = Bspan.cwiseAbs().rowwise().sum().maxCoeff();
        g.n = std::max(1, static_cast<int>(std::ceil(norm / kSliceNorm)));
        g.h = span / g.n;
        g.Bh = (g.t_loc * g.h) * sb.c.A - g.h * Dg;
        const Mat4T<S> E = taylor_exp<S>(g.Bh);
        g.basis.reserve(static_cast<size_t>(g.n) + 1);
        g.R.reserve(static_cast<size_t>(g.n));
        g.basis.push_back(g.in);
        for (int k = 0; k < g.n; ++k) {
          Mat42T<S> nxt = E * g.basis.back();
          g.R.push_back(orthonormalise(nxt));
          g.basis.push_back(nxt);
        }
        top = g.basis.back();
      }
      if (g.modal) orthonormalise(top);
      M = stress_scale<S>(sb.m_top) * top;
      orthonormalise(M);  // the coefficient change is recovered by least squares
    }
    P.S_top = M;
    P.segs = std::move(segs);
    return P;
  }

  // The modal map of a homogeneous sublayer: amplitudes a (4) of its
  // regularised modes whose bottom state lies in span(in): a = Nul c.
  static void modal_step(const Sub<S>& sb, Segment<S>& g, double* orient) {
    const Mat4T<S> Cb = detail::modal_columns(sb.c, g.t_loc, -1.0);
    // The complement of the input span (its orthogonal complement's adjoint).
    Eigen::HouseholderQR<Mat42T<S>> qr(g.in);
    const Mat4T<S> Q = qr.householderQ();
    const Eigen::Matrix<S, 2, 4> G = Q.template rightCols<2>().adjoint() * Cb;
    const Mat2T<S> G1 = G.template leftCols<2>(), G2 = G.template rightCols<2>();
    const double scale = G2.cwiseAbs().maxCoeff();
    if (scale > 0.0 && std::abs(G2.determinant()) > 1e-8 * scale * scale) {
      // Canonical: the amplitudes of the top-face modes are the coordinates.
      g.Nul.template topRows<2>().setIdentity();
      g.Nul.template bottomRows<2>() = -G2.partialPivLu().solve(G1);
      if constexpr (std::is_same_v<S, double>) {
        if (orient) {
          // exp(t d A) in = C0 Cb^-1 in = C0 Nul W_top: the sign of det W_top.
          // Cb's first two columns are [vT+, dv+] U with U upper triangular,
          // positive diagonal (e^{-nT t d}, e^{-nL t d}): the same sign from
          // the t-independent, well-conditioned [vT+, dv+, Cb(2), Cb(3)].
          const WaveConstants& c = sb.c;
          Mat4 Ct = Cb;
          Ct.col(0) = detail::shear_vector(c.nT);
          Ct.col(1) = Vec4(0.0, c.dW, c.dT, c.dS);
          const Mat42 W = Ct.partialPivLu().solve(g.in);
          if (W.topRows<2>().determinant() < 0.0) *orient = -*orient;
        }
      }
    } else {
      // A (rare) singular canonical form: any basis of the null space.
      Eigen::FullPivLU<Eigen::Matrix<S, 2, 4>> lu(G);
      Eigen::Matrix<S, 4, Eigen::Dynamic> k = lu.kernel();
      g.Nul = k.template leftCols<2>();
    }
  }

  // The surface solution: coefficients c of P.S_top with tau = 0, sigma/alpha = -1.
  static Eigen::Matrix<S, 2, 1> top_coefficients(const Propagation<S>& P,
                                                 double* p23_out = nullptr) {
    Mat42T<S> M = P.S_top;
    const S p23_raw = M(2, 0) * M(3, 1) - M(2, 1) * M(3, 0);
    if constexpr (std::is_same_v<S, double>) {
      if (p23_out) *p23_out = p23_raw * P.orient;
    }
    // The tau row is O(t) as t -> 0: rescale it (the solution is unchanged).
    const double tmax = std::max(std::abs(M(2, 0)), std::abs(M(2, 1)));
    if (tmax > 0.0) M.row(2) /= tmax;
    const S p23 = M(2, 0) * M(3, 1) - M(2, 1) * M(3, 0);
    return Eigen::Matrix<S, 2, 1>(M(2, 1), -M(2, 0)) / p23;
  }

  // The unit tangential load's surface solution: coefficients c of P.S_top
  // with tau/alpha = 1, sigma_y = 0 (on a shear-free base they grow like
  // 1/t as t -> 0: the bar pole).
  static Eigen::Matrix<S, 2, 1> tangential_coefficients(const Propagation<S>& P) {
    const Mat42T<S>& M = P.S_top;
    const S p23 = M(2, 0) * M(3, 1) - M(2, 1) * M(3, 0);
    return Eigen::Matrix<S, 2, 1>(M(3, 1), -M(3, 0)) / p23;
  }

  // The surface state of the normal load (as StackProfile's top state,
  // without its downward pass) and M2 (sigma_x = mu(t) Ep U + ... at the
  // top; mu = 1 for an elastic top).
  FullResponse surface(double t) const {
    const Propagation<S> P = propagate(t, false);
    const Vec4T<S> z0 = P.S_top * top_coefficients(P);
    const auto& k = subs_[0].c;
    FullResponse r;
    r.U0 = z0(0);
    r.W0 = z0(1);
    r.M1 = -z0(1);
    r.M2 = (k.c2 - 2.0) / k.c2 - 4.0 * (k.c2 - 1.0) / k.c2 * (subs_[0].m_top * z0(0));
    return r;
  }

  double dispersion(double t) const {
    static_assert(std::is_same_v<S, double>, "the dispersion of the relaxed (real) stack");
    const Propagation<S> P = propagate(t, true);
    double p23 = 0.0;
    top_coefficients(P, &p23);
    return p23;
  }

 private:
  BaseSpec base_;  // (the sublayers are subs_: a complex core is built per wavenumber)
  double s_;
  std::vector<Sub<S>> subs_;
  WaveConstants sub_;
};

// The solution of one wavenumber at every depth.
template <class S>
class StackProfile final : public ModeProfile {
 public:
  // The normal load's (tangential = false) or the unit tangential load's
  // solution; P: the propagation at t (core.propagate(t, false)). top: the
  // top material's (relaxed) half-plane constants at vstar, m_top its
  // modulus at t (a viscoelastic top: the half-plane part is the relaxed
  // one in units of mu_0 m(t), as the homogeneous viscoelastic layer's).
  StackProfile(const Core<S>& core, const WaveConstants& top, double t,
               std::shared_ptr<const Propagation<S>> P, bool tangential = false)
      : subs_(core.subs()), top_(top), t_(t), P_(std::move(P)), tangential_(tangential) {
    // Downward pass: the state at each sublayer's top, its coordinates in
    // the sublayer's own basis (least squares: the state lies in its span),
    // and the state at its bottom, the next sublayer's top state.
    Vec4T<S> z = P_->S_top * (tangential ? Core<S>::tangential_coefficients(*P_)
                                         : Core<S>::top_coefficients(*P_));
    z_top_ = z;
    for (const Segment<S>& g : P_->segs) {
      const Sub<S>& sb = subs_[static_cast<size_t>(g.layer)];
      const Mat42T<S> out =
          g.modal ? Mat42T<S>(detail::modal_columns(sb.c, g.t_loc, 0.0) * g.Nul) : g.basis.back();
      const Mat42T<S> out_u = stress_scale<S>(sb.m_top) * out;
      const Eigen::Matrix<S, 2, 1> cg = out_u.colPivHouseholderQr().solve(z);
      Vec4T<S> zb;  // the unscaled state at the segment's bottom
      if (g.modal) {
        amp_.push_back(g.Nul * cg);
        slice_c_.emplace_back();
        zb = stress_scale<S>(sb.m_bot()) * detail::modal_columns(sb.c, g.t_loc, -1.0) * amp_.back();
      } else {
        amp_.push_back(Vec4T<S>::Zero());
        std::vector<Eigen::Matrix<S, 2, 1>> ck(static_cast<size_t>(g.n) + 1);
        ck[static_cast<size_t>(g.n)] = cg;
        for (int k = g.n - 1; k >= 0; --k)
          ck[static_cast<size_t>(k)] =
              g.R[static_cast<size_t>(k)].template triangularView<Eigen::Upper>().solve(
                  ck[static_cast<size_t>(k) + 1]);
        zb = stress_scale<S>(sb.m_at(sb.y_top + g.lo * sb.d)) * g.basis[0] * ck[0];
        slice_c_.push_back(std::move(ck));
      }
      ++done_;
      z_bottom_ = zb;
      if (g.start) {
        z_bottom_.setZero();  // below the evaluated structure: under e^-50
        break;
      }
      z = zb;
    }
  }

  // The unscaled state at the surface and at the base face y = -1.
  const Vec4T<S>& top_state() const { return z_top_; }
  const Vec4T<S>& bottom_state() const { return z_bottom_; }

  ModeState remainder(double y, bool below) const override {
    const ModeState hp = half_plane(y);
    ModeState st;
    S sxv{0.0};
    Vec4T<S> z = Vec4T<S>::Zero();
    int i = locate(y, below);
    if (i >= 0 && i < done_) {
      const Sub<S>& sb = subs_[static_cast<size_t>(i)];
      const Segment<S>& g = P_->segs[static_cast<size_t>(i)];
      const double yh = std::min(0.0, std::max(-1.0, (y - sb.y_top) / sb.d));
      const S m = sb.m_at(y);
      if (g.modal) {
        z = stress_scale<S>(m) * detail::modal_columns(sb.c, g.t_loc, yh) *
            amp_[static_cast<size_t>(i)];
      } else if (yh >= g.lo) {
        const auto& ck = slice_c_[static_cast<size_t>(i)];
        int k = static_cast<int>(std::floor((yh - g.lo) / g.h));
        k = std::min(std::max(k, 0), g.n - 1);
        const double f = (yh - (g.lo + k * g.h)) / g.h;
        z = stress_scale<S>(m) * taylor_exp<S>(f * g.Bh) * g.basis[static_cast<size_t>(k)] *
            ck[static_cast<size_t>(k)];
      }
      sxv = sb.sx(z, m);
    } else if (i >= 0) {
      // Below the evaluated structure: the state is below e^-50 of the surface's.
      const Sub<S>& sb = subs_[static_cast<size_t>(i)];
      sxv = sb.sx(z, sb.m_at(y));
    }
    for (int r = 0; r < 4; ++r) st.z(r) = z(r) - hp.z(r);
    st.sx = sxv - hp.sx;
    return st;
  }

  ModeState half_plane(double y) const override {
    const Mat4 C = detail::modal_columns(top_, t_, y);
    Vec4 z;
    if (tangential_) {
      // The unit tangential load's half-plane mix (top T = 1, S = 0) on the
      // regularised basis: h1 v_T + h2 dv, h2 = 1/(q dS/2 + dT), h1 = dS h2/2
      // (q = (1 + nT^2)/nT, v_T's T entry).
      const double q = (1.0 + top_.nT * top_.nT) / top_.nT;
      const double h2 = 1.0 / (0.5 * q * top_.dS + top_.dT);
      z = 0.5 * top_.dS * h2 * C.col(0) + h2 * C.col(1);
    } else {
      z = top_.hp1 * C.col(0) + top_.hp2 * C.col(1);
    }
    ModeState s;
    for (int r = 0; r < 4; ++r) s.z(r) = z(r);
    s.sx = sigma_x_hat(top_, z);
    // A viscoelastic top: the relaxed half-plane in units of its modulus at t
    // (its displacements over m(t); its stresses per unit load unchanged).
    if constexpr (!std::is_same_v<S, double>) s.z.head<2>() /= subs_[0].m_top;
    return s;
  }

 private:
  int locate(double y, bool below) const {
    const int K = static_cast<int>(subs_.size());
    for (int i = 0; i < K; ++i) {
      const Sub<S>& sb = subs_[static_cast<size_t>(i)];
      if (i + 1 < K && y == sb.y_bot) return below ? i + 1 : i;
      if (y >= sb.y_bot || i + 1 == K) return i;
    }
    return K - 1;
  }

  std::vector<Sub<S>> subs_;
  WaveConstants top_;
  double t_;
  std::shared_ptr<const Propagation<S>> P_;
  bool tangential_ = false;
  Vec4T<S> z_top_ = Vec4T<S>::Zero(), z_bottom_ = Vec4T<S>::Zero();
  int done_ = 0;
  std::vector<Vec4T<S>> amp_;
  std::vector<std::vector<Eigen::Matrix<S, 2, 1>>> slice_c_;
};

void check_spec(const MediumSpec& m) {
  validate(m);  // medium.cpp: every range, named
  if (m.base.kind == BaseKind::springs && m.base.damping != 0.0)
    throw std::invalid_argument("stack medium: a damped base (damping != 0) is not supported");
}

// A stack's responses at one wavenumber from its core (real: the elastic
// stack; complex: the stack with its viscoelastic sublayers at t).
template <class S>
FullResponse responses(const Core<S>& core, const WaveConstants& top, double t) {
  const auto P = std::make_shared<const Propagation<S>>(core.propagate(t, false));
  const StackProfile<S> n(core, top, t, P, false);
  const Vec4T<S>& z0 = n.top_state();
  FullResponse r;
  r.U0 = z0(0);
  r.W0 = z0(1);
  r.M1 = -z0(1);
  // sigma_x = mu(t) Ep U + ... at the top (mu = 1 for an elastic top).
  r.M2 = (top.c2 - 2.0) / top.c2 - 4.0 * (top.c2 - 1.0) / top.c2 * (core.subs()[0].m_top * z0(0));
  r.Wb = n.bottom_state()(1);
  const StackProfile<S> q(core, top, t, P, true);
  r.Uq = q.top_state()(0);
  r.Wq = q.top_state()(1);
  r.Wqb = q.bottom_state()(1);
  return r;
}

class StackMedium final : public Medium {
 public:
  StackMedium(const MediumSpec& spec, double vstar)
      : core_(spec, vstar),
        spec_(spec),
        s_(vstar),
        relaxed_(wave_constants(vstar, spec.layers[0].nu)),
        top_(relaxed_),
        asym_(graded_kernel_asymptotics(spec, vstar)),
        visco_(spec.viscoelastic()) {
    if (!spec.layers[0].visco.empty()) {
      // A viscoelastic top: the unrelaxed half-plane's Cauchy coefficient and
      // surface sigma_x, and its memory (as the viscoelastic layer's).
      top_visco_.emplace(spec.layers[0].visco, vstar, spec.layers[0].nu);
      top_.phi1 = top_visco_->h_inf();
      top_.phi2 = top_visco_->phi2_inf();
    }
  }

  double vstar() const noexcept override { return s_; }
  const WaveConstants& top() const noexcept override { return top_; }
  bool real() const noexcept override { return !visco_; }

  MediumResponse surface_response(double t) const override {
    if (std::isnan(t) || t < 0.0)
      throw std::invalid_argument("stack response: t = alpha h must be >= 0");
    // t = 0: the limit, to double precision (every correction is O(t)).
    const double tt = t == 0.0 ? 1e-300 : t;
    const FullResponse r = visco_ ? Core<cplx>(core_, spec_, tt).surface(tt) : core_.surface(tt);
    return MediumResponse{r.M1, r.M2, r.U0, r.W0};
  }
  std::unique_ptr<const ModeProfile> mode(double t) const override {
    if (!(t > 0.0) || !std::isfinite(t))
      throw std::invalid_argument("stack mode: t = alpha h must be finite and > 0");
    if (visco_) {
      const Core<cplx> core(core_, spec_, t);
      return std::make_unique<StackProfile<cplx>>(
          core, relaxed_, t, std::make_shared<const Propagation<cplx>>(core.propagate(t, false)));
    }
    return std::make_unique<StackProfile<double>>(core_, relaxed_, t, propagation(t));
  }

  // The asymmetric solver's reads: one propagation, the normal and the
  // tangential load's downward passes on it.
  FullResponse full_response(double t) const override {
    if (std::isnan(t) || t < 0.0)
      throw std::invalid_argument("stack response: t = alpha h must be >= 0");
    const double tt = t == 0.0 ? 1e-300 : t;
    FullResponse r = visco_ ? responses(Core<cplx>(core_, spec_, tt), relaxed_, tt)
                            : responses(core_, relaxed_, tt);
    if (t == 0.0 && bar_compliance() != 0.0) r.Uq = r.Wq = std::nan("");  // the bar pole
    return r;
  }
  Eigen::Vector4cd normal_state(double t, double y) const override { return state_at(t, y, false); }
  Eigen::Vector4cd tangential_state(double t, double y) const override {
    return state_at(t, y, true);
  }
  const TangentialHalfPlane& tangential() const noexcept override { return tq_; }
  // Shear-free bases (springs, rigid, a smooth half-space): the stack's bar,
  // 1/sum_i int (Ep_i mu_i(y) - vstar rho_i(y)) dy (a graded sublayer's
  // modulus and density both scale by exp(gamma (y - y_top)); a viscoelastic
  // one's relaxed modulus: the bar is the long-wave, zero-frequency limit).
  double bar_compliance() const noexcept override {
    if (spec_.base.kind == BaseKind::half_space_bonded) return 0.0;
    double stiff = 0.0;
    for (const Sublayer& l : spec_.layers) {
      const double ep = 2.0 / (1.0 - l.nu);
      const double g = l.gamma * l.thickness;
      const double span = g == 0.0 ? l.thickness : -std::expm1(-g) / l.gamma;
      stiff += (ep * l.mu - s_ * l.rho) * span;
    }
    return 1.0 / stiff;
  }
  // The relaxed stack's (the critical speed of a viscoelastic medium is its
  // relaxed elastic one's).
  double dispersion(double t) const override {
    if (!(t > 0.0) || !std::isfinite(t))
      throw std::invalid_argument("stack dispersion: t = alpha h must be finite and > 0");
    return core_.dispersion(t);
  }
  double decay_rate() const noexcept override {
    // The reflection off the top sublayer's bottom (a graded top's M1 - phi1
    // also carries its slow series, kernel_asymptotics(); a viscoelastic
    // top's relaxed shear rate is its slowest).
    return 2.0 * relaxed_.nT * spec_.layers[0].thickness;
  }
  // (Medium::panel_scale.) M1 - phi1 falls by at most e^8 across a panel
  // of 8 / decay_rate() (between 1 and 8 wide); the adaptive rule splits it
  // where its |K15 - G7| asks (G7 alone is 5e-8 off on e^(-8t)).
  double panel_scale() const noexcept override { return std::clamp(8.0 / decay_rate(), 1.0, 8.0); }
  const KernelAsymptotics& kernel_asymptotics() const noexcept override { return asym_; }
  // The remainder (state minus the top's half-plane state) at any depth
  // decays at least as slowly as the state at the bottom, exp(-t sum nT_i
  // h_i) (each sublayer's shear rate, the slower of its two; a viscoelastic
  // one's relaxed), or the top's half-plane state there, exp(-nT_1 t), or
  // the surface's reflection.
  double field_decay_rate() const noexcept override {
    double travel = 0.0;
    for (const Sublayer& l : spec_.layers)
      travel += l.thickness * std::sqrt(std::max(0.0, 1.0 - s_ * l.rho / l.mu));
    double rate = std::min(travel, relaxed_.nT);
    const double surface = decay_rate();
    if (surface > 0.0) rate = std::min(rate, surface);
    return rate;
  }
  double roundoff_gain() const noexcept override { return 50.0; }
  double long_wave_m1() const noexcept override {
    return spec_.base.kind == BaseKind::springs ? 0.0 : stack_small_t_m1(spec_, s_);
  }
  std::vector<double> first_panel_edges(double w) const override {
    const BaseSpec& b = spec_.base;
    if (b.kind == BaseKind::springs) return detail::foundation_panel_edges(b.kw, b.kp, w);
    // Half-space: M1 -> phi1_2/mu2 with t log t corrections; panels graded
    // geometrically towards 0 (w 2^-12 ... w/2, w).
    std::vector<double> e{0.0};
    for (int k = 12; k >= 1; --k) e.push_back(std::ldexp(w, -k));
    e.push_back(w);
    return e;
  }
  std::vector<double> interfaces() const override {
    std::vector<double> out;
    double y = 0.0;
    for (size_t i = 0; i + 1 < spec_.layers.size(); ++i) {
      y -= spec_.layers[i].thickness;
      out.push_back(y);
    }
    return out;
  }
  // A viscoelastic top's half-plane parts and memories (ViscoelasticTop).
  cplx half_plane_m1(double t) const override {
    return top_visco_ ? top_visco_->m1(t) : cplx(top_.phi1);
  }
  const MemoryKernel* memory() const noexcept override {
    return top_visco_ ? &top_visco_->memory() : nullptr;
  }
  cplx half_plane_m2(double t) const override {
    return top_visco_ ? top_visco_->m2(t) : cplx(top_.phi2);
  }
  const RetardationSpectrum* stress_memory() const noexcept override {
    return top_visco_ ? top_visco_->stress_memory() : nullptr;
  }
  const RetardationSpectrum* compliance_memory() const noexcept override {
    return top_visco_ ? &top_visco_->compliance_memory() : nullptr;
  }
  const MediumSpec& spec() const noexcept override { return spec_; }

 private:
  std::shared_ptr<const Propagation<double>> propagation(double t) const {
    return std::make_shared<const Propagation<double>>(core_.propagate(t, false));
  }
  Eigen::Vector4cd state_at(double t, double y, bool tangential) const {
    if (!(t > 0.0) || !std::isfinite(t) || !(y >= -1.0) || !(y <= 0.0))
      throw std::invalid_argument("stack state: need t > 0 finite and -1 <= y <= 0");
    if (visco_) {
      const Core<cplx> core(core_, spec_, t);
      const StackProfile<cplx> p(
          core, relaxed_, t, std::make_shared<const Propagation<cplx>>(core.propagate(t, false)),
          tangential);
      return p.state(y).z;
    }
    const StackProfile<double> p(core_, relaxed_, t, propagation(t), tangential);
    return p.state(y).z;
  }

  Core<double> core_;  // the elastic (a viscoelastic stack: relaxed) stack
  MediumSpec spec_;
  double s_;
  WaveConstants relaxed_;  // the top material's half-plane constants (relaxed)
  WaveConstants top_;      // the same with a viscoelastic top's unrelaxed phi1, phi2
  TangentialHalfPlane tq_ = tangential_half_plane(relaxed_);
  KernelAsymptotics asym_;
  bool visco_ = false;
  std::optional<ViscoelasticTop> top_visco_;
};

// The lowest vstar < smax of a free wave of wavenumber t (smax if none).
double first_wave(const MediumSpec& spec, double t, double smax) {
  auto D = [&](double s) { return Core<double>(spec, s).dispersion(t); };
  const int m = kFirstWaveScan;
  const double top = smax * (1.0 - 1e-13);
  double s_prev = 0.0, d_prev = D(0.0);
  for (int j = 1; j <= m; ++j) {
    const double s = top * 0.5 * (1.0 - std::cos(kPi * j / m));
    const double d = D(s);
    if (d == 0.0) return s;
    if ((d < 0.0) != (d_prev < 0.0)) {
      const double r = detail::bracketed_root(D, s_prev, s, d_prev, d, 1e-15 * smax);
      // A sign change of a continuous function has |D| -> 0 at the root; a
      // jump of the basis' orientation (docs/media.md) does not.
      if (std::fabs(D(r)) <= 1e-6 * std::max(std::fabs(d), std::fabs(d_prev))) return r;
    }
    s_prev = s;
    d_prev = d;
  }
  return smax;
}

CriticalSpeed compute_critical(const MediumSpec& spec) {
  // The infima reached only as t -> inf or t -> 0.
  CriticalSpeed inf{rayleigh_vstar(spec.layers[0].nu), kInf};
  auto consider = [&](double v, double t) {
    if (v < inf.vstar) inf = {v, t};
  };
  for (const Sublayer& l : spec.layers) consider(l.mu / l.rho, kInf);
  const BaseSpec& b = spec.base;
  const Sublayer& bot = spec.layers.back();
  if (b.kind == BaseKind::springs) {
    if (std::isfinite(b.kw) && b.kp == 0.0)
      consider(bot.mu / bot.rho * rayleigh_vstar(bot.nu), kInf);
  } else {
    consider(b.mu / b.rho * rayleigh_vstar(b.nu), 0.0);
  }
  const double smax = inf.vstar;
  // As critical_speed (dispersion.cpp). A root within 1e-12 of the infimum
  // is the infimum's own branch seen through round-off (D ~ 1e-13 there at
  // large t): none below it.
  CriticalSpeed c = inf;
  detail::log_grid_minimum([&](double t) { return first_wave(spec, t, smax); }, smax, 1e-12,
                           c.vstar, c.t);
  return c;
}

}  // namespace

double stack_max_vstar(const MediumSpec& spec) {
  check_spec(spec);
  double v = rayleigh_vstar(spec.layers[0].nu);
  for (const Sublayer& l : spec.layers) v = std::min(v, l.mu / l.rho);
  if (spec.base.kind != BaseKind::springs) v = std::min(v, spec.base.mu / spec.base.rho);
  return v;
}

std::shared_ptr<const Medium> make_stack_medium(const MediumSpec& spec, double vstar) {
  const double vmax = stack_max_vstar(spec);
  require_in_range("vstar", vstar, 0.0, vmax, false, true);
  return std::make_shared<StackMedium>(spec, vstar);
}

CriticalSpeed stack_critical_speed(const MediumSpec& spec) {
  check_spec(spec);
  static std::mutex mutex;
  static std::map<std::vector<double>, CriticalSpeed> cache;
  return detail::memoized(mutex, cache, spec.key(), [&] { return compute_critical(spec); });
}

double stack_small_t_m1(const MediumSpec& spec, double vstar) {
  const BaseSpec& b = spec.base;
  if (b.kind == BaseKind::springs) return std::numeric_limits<double>::quiet_NaN();
  return wave_constants(vstar * b.rho / b.mu, b.nu).phi1 / b.mu;
}

namespace {

// sign(M) by Newton's iteration X <- (X + X^-1)/2, real or complex M with no
// eigenvalue on the imaginary axis.
template <class Mat>
Mat matrix_sign(const Mat& M) {
  Mat X = M;
  for (int k = 0; k < 100; ++k) {
    const Mat Xn = 0.5 * (X + X.inverse());
    const double d = (Xn - X).cwiseAbs().maxCoeff();
    X = Xn;
    if (d <= 1e-15 * X.cwiseAbs().maxCoeff()) break;
  }
  return X;
}

// M1 of the graded half-space of generator A - eps D (surface modulus 1).
double graded_half_space_m1(const WaveConstants& c, double eps) {
  Mat4 M = c.A;
  M(2, 2) -= eps;
  M(3, 3) -= eps;
  // sign(M) by Newton's iteration X <- (X + X^-1)/2 (no eigenvalue of M on
  // the imaginary axis: nT > 0, |eps| small).
  const Mat4 X = matrix_sign(M);
  // The projector onto the downward-decaying solutions (Re lambda > 0),
  // applied to the homogeneous half-plane's modes.
  const Mat4 Pr = 0.5 * (Mat4::Identity() + X);
  Mat42 S = Pr * detail::modal_columns(c, 1.0, 0.0).leftCols<2>();
  orthonormalise(S);
  const double p12 = S(1, 0) * S(2, 1) - S(1, 1) * S(2, 0);
  const double p23 = S(2, 0) * S(3, 1) - S(2, 1) * S(3, 0);
  return -p12 / p23;
}

}  // namespace

namespace {

// F(eps) = M1 of the graded half-space at complex eps (as graded_half_space_m1;
// the ratio of minors does not depend on the basis of the subspace).
std::complex<double> graded_half_space_m1c(const WaveConstants& c, std::complex<double> eps) {
  using Mat4c = Eigen::Matrix4cd;
  Mat4c M = c.A.cast<std::complex<double>>();
  M(2, 2) -= eps;
  M(3, 3) -= eps;
  const Mat4c X = matrix_sign(M);
  const Mat4c Pr = 0.5 * (Mat4c::Identity() + X);
  const Eigen::Matrix<std::complex<double>, 4, 2> S =
      Pr * detail::modal_columns(c, 1.0, 0.0).leftCols<2>().cast<std::complex<double>>();
  const std::complex<double> p12 = S(1, 0) * S(2, 1) - S(1, 1) * S(2, 0);
  const std::complex<double> p23 = S(2, 0) * S(3, 1) - S(2, 1) * S(3, 0);
  return -p12 / p23;
}

std::vector<double> series_on_circle(const WaveConstants& c, double r, int kmax) {
  constexpr int M = 64;
  std::vector<std::complex<double>> F(M);
  for (int j = 0; j < M; ++j) F[j] = graded_half_space_m1c(c, std::polar(r, 2.0 * kPi * j / M));
  std::vector<double> out(static_cast<std::size_t>(kmax + 1));
  for (int k = 0; k <= kmax; ++k) {
    std::complex<double> sum = 0.0;
    for (int j = 0; j < M; ++j) sum += F[j] * std::polar(std::pow(r, -k), -2.0 * kPi * j * k / M);
    out[static_cast<std::size_t>(k)] = sum.real() / M;
  }
  return out;
}

GradedSeries compute_graded_top_series(double vstar, double nu, int kmax) {
  const WaveConstants c = wave_constants(vstar, nu);
  // F is analytic in eps within a disc (the half-space's eigenvalues stay
  // off the imaginary axis, no Rayleigh pole): the trapezoidal rule on the
  // circle |eps| = r (64 points, error (r/rho)^64) at r and 0.8 r, from
  // r = nT/2; the two agree to round-off where r is inside the disc.
  // Near the Rayleigh speed F has a pole close to eps = 0 (the graded
  // half-space's Rayleigh wave): the circle is halved until c_0 is the
  // half-plane's phi1 (wave_constants, independent) and the two circles agree.
  GradedSeries g;
  for (double r1 = 0.5 * c.nT; r1 > 1e-6 * c.nT; r1 *= 0.5) {
    const double r2 = 0.8 * r1;
    const std::vector<double> a = series_on_circle(c, r1, kmax + 1);
    const std::vector<double> b = series_on_circle(c, r2, kmax + 1);
    g.radius = r1;
    g.c.assign(a.begin(), a.end() - 1);
    g.next = std::fabs(a.back());
    g.agreement = 0.0;
    const double scale0 = std::max(1.0, std::fabs(c.phi1));
    for (int k = 0; k <= kmax + 1; ++k)
      g.agreement = std::max(
          g.agreement, std::fabs(a[static_cast<std::size_t>(k)] - b[static_cast<std::size_t>(k)]) *
                           std::pow(r2, k) / scale0);
    if (std::fabs(a[0] - c.phi1) <= 1e-11 * scale0 && g.agreement < 1e-11) break;
  }
  return g;
}

}  // namespace

GradedSeries graded_top_series(double vstar, double nu, int kmax) {
  if (kmax < 1 || kmax > 40) throw std::invalid_argument("graded_top_series: kmax in [1, 40]");
  // Each solve on a graded top makes its medium, and the series (two
  // circles of 64 complex matrix sign functions, ~0.6 ms) depends on the
  // speed and nu only: kept as the critical speeds are.
  static std::mutex mutex;
  static std::map<std::tuple<double, double, int>, GradedSeries> cache;
  return detail::memoized(mutex, cache, std::make_tuple(vstar, nu, kmax),
                          [&] { return compute_graded_top_series(vstar, nu, kmax); });
}

KernelAsymptotics graded_kernel_asymptotics(const MediumSpec& spec, double vstar) {
  KernelAsymptotics as;
  const Sublayer& top = spec.layers[0];
  if (top.gamma == 0.0) return as;
  constexpr int kmax = 10;
  const GradedSeries g = graded_top_series(vstar, top.nu, kmax);
  if (!(g.agreement < 1e-9))
    throw std::runtime_error("graded top: the kernel's series in gamma/t did not converge");
  const double phi1 = g.c[0];
  as.gamma = top.gamma;
  for (int k = 1; k <= kmax; ++k) as.a.push_back(g.c[static_cast<std::size_t>(k)] / phi1);
  // The next coefficient, and a margin for those beyond it (they grow like
  // radius^-k): twice it.
  as.next = 2.0 * g.next / std::fabs(phi1);
  as.radius = g.radius;
  // The reflection off the graded top's bottom: its modulus changes by
  // e^(gamma d) across it.
  as.margin = std::fabs(top.gamma) * top.thickness;
  return as;
}

GradedAsymptotics graded_top_asymptotics(double vstar, double nu) {
  const WaveConstants c = wave_constants(vstar, nu);
  const double F0 = graded_half_space_m1(c, 0.0);
  auto diffs = [&](double h) {
    const double fp = graded_half_space_m1(c, h), fm = graded_half_space_m1(c, -h);
    return std::make_pair((fp - fm) / (2.0 * h), (fp - 2.0 * F0 + fm) / (2.0 * h * h));
  };
  const double h = 2e-3;
  const auto a = diffs(h), b = diffs(0.5 * h);
  // Both differences err by O(h^2): Richardson's (4 b - a)/3.
  return {(4.0 * b.first - a.first) / 3.0, (4.0 * b.second - a.second) / 3.0};
}

}  // namespace movingpunch

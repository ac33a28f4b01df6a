#include "movingpunch/layer_response.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "layer_basis.hpp"
#include "movingpunch/errors.hpp"

namespace movingpunch {

namespace detail {

Eigen::Vector4d shear_vector(double m) { return {1.0, -1.0 / m, (1.0 + m * m) / m, -2.0}; }

namespace {

// e^z - 1 without cancellation, real or complex z.
double expm1_of(double z) { return std::expm1(z); }
std::complex<double> expm1_of(std::complex<double> z) {
  // e^{x + iy} - 1 = (expm1(x) cos y - 2 sin^2(y/2)) + i e^x sin y.
  const double sh = std::sin(0.5 * z.imag());
  return {std::expm1(z.real()) * std::cos(z.imag()) - 2.0 * sh * sh,
          std::exp(z.real()) * std::sin(z.imag())};
}

template <class T>
Eigen::Matrix<T, 4, 1> shear_vector_of(T m) {
  return {T(1.0), -1.0 / m, (1.0 + m * m) / m, T(-2.0)};
}

}  // namespace

// The four columns of the regularised exponential basis at depth y.
template <class T>
Eigen::Matrix<T, 4, 4> modal_columns(const BasicWaveConstants<T>& c, double t, double y) {
  using V = Eigen::Matrix<T, 4, 1>;
  const T nT = c.nT, nL = c.nL, d = c.delta;
  // E(x) = (e^{d x} - 1)/d. For tiny d x its series, which holds at full
  // precision down to d = 0: expm1(d x)/d loses every digit once d is
  // subnormal (vstar < ~1e-308: d x is rounded to a few bits and divided
  // back), which moved a/h by 1e-6 at vstar = 1e-320.
  auto E = [d](double x) -> T {
    const T dx = d * x;
    return std::abs(dx) < 1e-5 ? x * (1.0 + dx * (0.5 + dx / 6.0)) : expm1_of(dx) / d;
  };
  const V vTp = shear_vector_of<T>(nT), vTm = shear_vector_of<T>(-nT);
  const V dvp(T(0.0), c.dW, c.dT, c.dS), dvm(T(0.0), -c.dW, -c.dT, c.dS);
  Eigen::Matrix<T, 4, 4> C;
  const T et = std::exp(nT * t * y), el = std::exp(nL * t * y);
  const double yb = y + 1.0;
  const T ebt = std::exp(-nT * t * yb), ebl = std::exp(-nL * t * yb);
  C.col(0) = et * vTp;
  C.col(1) = el * dvp + vTp * (et * E(t * y));
  C.col(2) = ebt * vTm;
  C.col(3) = ebl * dvm + vTm * (ebt * E(-t * yb));
  return C;
}

// Transfer matrix exp(-t A) by its Taylor series (t < 0.5, |A| <= 6); with
// depth y, exp(t y A) (z(y) = exp(t y A) z(0)).
template <class T>
Eigen::Matrix<T, 4, 4> transfer_matrix(const BasicWaveConstants<T>& c, double t, double y) {
  using M = Eigen::Matrix<T, 4, 4>;
  M P = M::Identity();
  M term = M::Identity();
  const M B = (t * y) * c.A;
  for (int k = 1; k < 80; ++k) {
    term = term * B / static_cast<double>(k);
    P += term;
    if (term.cwiseAbs().maxCoeff() <= 1e-18 * P.cwiseAbs().maxCoeff() && k > 3) break;
  }
  return P;
}

template Eigen::Matrix4d modal_columns(const WaveConstants&, double, double);
template Eigen::Matrix4cd modal_columns(const ComplexWaveConstants&, double, double);
template Eigen::Matrix4d transfer_matrix(const WaveConstants&, double, double);
template Eigen::Matrix4cd transfer_matrix(const ComplexWaveConstants&, double, double);

}  // namespace detail

using detail::modal_columns;
using detail::shear_vector;
using detail::transfer_matrix;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Regular form of the Rayleigh function divided by s:
// (4 nL nT - (2 - s)^2) / s = 4 - s - 4 X / (1 + Y).
double rayleigh_over_s(double s, double c2) {
  const double nT = std::sqrt(1.0 - s), nL = std::sqrt(1.0 - s / c2);
  const double X = 1.0 + 1.0 / c2 - s / c2, Y = nL * nT;
  return 4.0 - s - 4.0 * X / (1.0 + Y);
}

double c2_of(double nu) {
  const double kappa = 3.0 - 4.0 * nu;
  return (kappa + 1.0) / (kappa - 1.0);
}

// Mode vector [U, W, tau/alpha, sigma_y/alpha] of the shear root m (U = 1).

}  // namespace

double rayleigh_vstar(double nu) {
  require_in_range("nu", nu, 0.0, 0.5, false, true);
  // The last nu's value (a pure function: every solve asks for its layer's,
  // a sweep the same nu thousands of times; the bisection costs microseconds).
  thread_local double last_nu = -1.0, last_vr = 0.0;
  if (nu == last_nu) return last_vr;
  const double c2 = c2_of(nu);
  // rayleigh_over_s is positive at s = 0 (2 - 2/c2 >= 1) and negative near s = 1.
  double lo = 0.0, hi = 1.0 - 1e-300;
  for (int i = 0; i < 200 && hi - lo > 4e-17; ++i) {
    const double mid = 0.5 * (lo + hi);
    (rayleigh_over_s(mid, c2) > 0.0 ? lo : hi) = mid;
  }
  last_nu = nu;
  last_vr = 0.5 * (lo + hi);
  return last_vr;
}

namespace {

// The half-plane's roots and factors at s: what phi1 and phi2 need (and the
// rest of the constants build on).
template <class T>
struct HalfPlaneParts {
  T nT, nL, X, Y, phi1, phi2;
};
template <class T>
HalfPlaneParts<T> half_plane_parts(T s, double c2) {
  HalfPlaneParts<T> h;
  h.nT = std::sqrt(1.0 - s);
  h.nL = std::sqrt(1.0 - s / c2);
  h.X = 1.0 + 1.0 / c2 - s / c2;
  h.Y = h.nL * h.nT;
  const T den = 4.0 - s - 4.0 * h.X / (1.0 + h.Y);
  h.phi1 = h.nL / den;
  h.phi2 = (4.0 * h.X / (1.0 + h.Y) - 2.0 + 2.0 * (c2 - 2.0) / c2 - s * (c2 - 2.0) / c2) / den;
  return h;
}

// The closed forms of wave_constants, real or complex s (principal roots).
template <class T>
BasicWaveConstants<T> fill_constants(T s, double nu) {
  BasicWaveConstants<T> c;
  c.s = s;
  c.nu = nu;
  c.c2 = c2_of(nu);
  const double c2 = c.c2;
  const HalfPlaneParts<T> hp = half_plane_parts(s, c2);
  c.nT = hp.nT;
  c.nL = hp.nL;
  const T X = hp.X, Y = hp.Y;
  c.phi1 = hp.phi1;
  c.phi2 = hp.phi2;
  const double one_minus_inv_c2 = 1.0 - 1.0 / c2;  // = 2 / (kappa + 1)
  c.delta = s * one_minus_inv_c2 / (c.nL + c.nT);
  const T ratio = (c.nL + c.nT) / (one_minus_inv_c2 * c.nT);
  c.dW = X / (1.0 + Y) * ratio;
  c.dT = ((-s * X / (1.0 + Y) - 2.0 * (1.0 - s) / c2) / (1.0 + Y)) * ratio;
  c.dS = (c.nL + c.nT) / one_minus_inv_c2;
  // Half-plane amplitudes: tau(0) = hp1 q + hp2 dT = 0, sigma(0) = -2 hp1 + hp2 dS = -1.
  {
    const T q = (1.0 + c.nT * c.nT) / c.nT;
    const T det = q * c.dS + 2.0 * c.dT;
    c.hp1 = c.dT / det;
    c.hp2 = -q / det;
  }
  const T zero{0.0}, one{1.0};
  c.A << zero, one, one, zero,                                    //
      T(-(c2 - 2.0) / c2), zero, zero, T(1.0 / c2),               //
      4.0 * (c2 - 1.0) / c2 - s, zero, zero, T((c2 - 2.0) / c2),  //
      zero, -s, -one, zero;
  return c;
}

}  // namespace

WaveConstants wave_constants(double vstar, double nu) {
  require_in_range("nu", nu, 0.0, 0.5, false, true);
  require_in_range("vstar", vstar, 0.0, 1.0, false, true);
  return fill_constants<double>(vstar, nu);
}

namespace {
void check_complex_speed(std::complex<double> s, double nu) {
  require_in_range("nu", nu, 0.0, 0.5, false, true);
  if (!std::isfinite(s.real()) || !std::isfinite(s.imag()) || (s.imag() == 0.0 && s.real() >= 1.0))
    throw std::invalid_argument("complex_wave_constants: s must be finite and not real >= 1");
}
}  // namespace

ComplexWaveConstants complex_wave_constants(std::complex<double> s, double nu) {
  check_complex_speed(s, nu);
  return fill_constants<std::complex<double>>(s, nu);
}

ComplexHalfPlane complex_half_plane(std::complex<double> s, double nu) {
  check_complex_speed(s, nu);
  const HalfPlaneParts<std::complex<double>> h = half_plane_parts(s, c2_of(nu));
  return {h.phi1, h.phi2};
}

double phi1(double vstar, double nu) {
  const double vr = rayleigh_vstar(nu);
  if (!(vstar < vr))
    throw std::invalid_argument("phi1: vstar must be below the Rayleigh value " +
                                std::to_string(vr));
  return wave_constants(vstar, nu).phi1;
}

double phi2(double vstar, double nu) {
  const double vr = rayleigh_vstar(nu);
  if (!(vstar < vr))
    throw std::invalid_argument("phi2: vstar must be below the Rayleigh value " +
                                std::to_string(vr));
  return wave_constants(vstar, nu).phi2;
}

LayerModel::LayerModel(double vstar, double kw, double nu, double kp)
    : c_(wave_constants(vstar, nu)), kw_(kw), rigid_(std::isinf(kw)), kp_(kp) {
  require_in_range("kw", kw, 0.0, kInf, true, false, true);
  require_in_range("kp", kp, 0.0, kMaxKp, false, false);
}

namespace {

// The 4 x 4 boundary matrix on the regularised exponential basis (columns:
// top shear mode, top divided difference, bottom shear mode, bottom divided
// difference); rows: tau(0), sigma(0), tau(-1), bottom condition.
// The bottom condition t sigma/alpha - kw W = 0 normalised as
// [t/(t+kw)] sigma/alpha - [kw/(t+kw)] W, without overflow for any kw, t.
// `kw` here is the stiffness of the mode, kw + kp t^2 (LayerModel::foundation).
double spring_weight_t(double t, double kw) { return 1.0 / (1.0 + kw / t); }
double spring_weight_k(double t, double kw) { return 1.0 / (1.0 + t / kw); }

Eigen::Matrix4d modal_matrix(const WaveConstants& c, double kw, bool rigid, double t,
                             Eigen::Matrix4d* top_columns) {
  const Eigen::Matrix4d top = modal_columns(c, t, 0.0), bot = modal_columns(c, t, -1.0);
  Eigen::Matrix4d M;
  M.row(0) = top.row(2);
  M.row(1) = top.row(3);
  M.row(2) = bot.row(2);
  if (rigid)
    M.row(3) = bot.row(1);
  else
    M.row(3) = spring_weight_t(t, kw) * bot.row(3) - spring_weight_k(t, kw) * bot.row(1);
  if (top_columns) *top_columns = top;
  return M;
}

// Bottom conditions as two rows acting on z(-1) = P z(0).
Eigen::Matrix<double, 2, 4> bottom_rows(const Eigen::Matrix4d& P, double kw, bool rigid, double t) {
  Eigen::Matrix<double, 2, 4> R;
  R.row(0) = P.row(2);
  if (rigid)
    R.row(1) = P.row(1);
  else
    R.row(1) = spring_weight_t(t, kw) * P.row(3) - spring_weight_k(t, kw) * P.row(1);
  return R;
}

Response from_top(const WaveConstants& c, double U0, double W0) {
  Response r;
  r.U0 = U0;
  r.W0 = W0;
  r.M1 = -W0;
  r.M2 = (c.c2 - 2.0) / c.c2 - 4.0 * (c.c2 - 1.0) / c.c2 * U0;
  return r;
}

}  // namespace

Response LayerModel::response_modal(double t) const {
  if (!(t > 0.0)) throw std::invalid_argument("layer response: t = alpha h must be > 0");
  // Beyond this M1 - phi1 ~ exp(-2 nT t) underflows: return the exact limit.
  if (t * c_.nT >= 400.0) {
    const double U0 = ((c_.c2 - 2.0) / c_.c2 - c_.phi2) * c_.c2 / (4.0 * (c_.c2 - 1.0));
    return from_top(c_, U0, -c_.phi1);
  }
  Eigen::Matrix4d top;
  const Eigen::Matrix4d M = modal_matrix(c_, foundation(t), rigid_, t, &top);
  const Eigen::Vector4d rhs(0.0, -1.0, 0.0, 0.0);
  const Eigen::Vector4d amp = M.partialPivLu().solve(rhs);
  const Eigen::Vector4d z0 = top * amp;
  return from_top(c_, z0(0), z0(1));
}

Response LayerModel::response_transfer(double t) const {
  if (!(t >= 0.0) || !(t <= 4.0))
    throw std::invalid_argument("layer response (transfer): t must be in [0, 4]");
  if (t == 0.0) {
    // Exact limit: W0 = 0 for a finite foundation (M1 ~ t); U0 from the row tau(-1).
    const double U0 = c_.A(2, 3) / c_.A(2, 0);
    return from_top(c_, U0, 0.0);
  }
  const Eigen::Matrix4d P = transfer_matrix(c_, t, -1.0);
  const Eigen::Matrix<double, 2, 4> R = bottom_rows(P, foundation(t), rigid_, t);
  // z0 = [U0, W0, 0, -1]: R(:,0:1) [U0, W0] = R(:,3).
  Eigen::Matrix2d M = R.leftCols<2>();
  const Eigen::Vector2d rhs = R.col(3);
  const Eigen::Vector2d x = M.fullPivLu().solve(rhs);
  return from_top(c_, x(0), x(1));
}

Response LayerModel::response(double t) const {
  if (std::isnan(t) || t < 0.0)
    throw std::invalid_argument("layer response: t = alpha h must be >= 0");
  if (t < kSmallT) return response_transfer(t);
  return response_modal(t);
}

ModeField LayerModel::mode_field(double t) const {
  if (!(t > 0.0) || !std::isfinite(t))
    throw std::invalid_argument("mode_field: t = alpha h must be finite and > 0");
  ModeField f;
  f.c_ = &c_;
  f.t_ = t;
  if (t < kSmallT) {
    const Response r = response_transfer(t);
    f.transfer_ = true;
    f.top_ = Eigen::Vector4d(r.U0, r.W0, 0.0, -1.0);
  } else {
    const Eigen::Matrix4d M = modal_matrix(c_, foundation(t), rigid_, t, nullptr);
    f.amp_ = M.partialPivLu().solve(Eigen::Vector4d(0.0, -1.0, 0.0, 0.0));
  }
  return f;
}

Eigen::Vector4d ModeField::state(double y) const {
  if (transfer_) return transfer_matrix(*c_, t_, y) * top_;
  return modal_columns(*c_, t_, y) * amp_;
}

Eigen::Vector4d ModeField::half_plane_state(double y) const {
  const Eigen::Matrix4d C = modal_columns(*c_, t_, y);
  return c_->hp1 * C.col(0) + c_->hp2 * C.col(1);
}

double LayerModel::dispersion(double t) const {
  if (!(t > 0.0) || !std::isfinite(t))
    throw std::invalid_argument("dispersion: t = alpha h must be finite and > 0");
  if (t < kSmallT) {
    const Eigen::Matrix4d P = transfer_matrix(c_, t, -1.0);
    const Eigen::Matrix<double, 2, 4> R = bottom_rows(P, foundation(t), rigid_, t);
    return R(0, 0) * R(1, 1) - R(0, 1) * R(1, 0);
  }
  return modal_matrix(c_, foundation(t), rigid_, t, nullptr).partialPivLu().determinant();
}

}  // namespace movingpunch

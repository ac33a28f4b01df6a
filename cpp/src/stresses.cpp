#include "movingpunch/stresses.hpp"

#include <cmath>
#include <complex>
#include <stdexcept>

#include "movingpunch/collocation.hpp"
#include "movingpunch/errors.hpp"

namespace movingpunch {

namespace {

using cplx = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;
constexpr double kLn2 = 0.69314718055994530942;

// w(z) = z - sqrt(z^2 - 1) on the branch ~ 1/(2z) at infinity (cut [-1, 1]),
// written as 1/(z + sqrt(z^2-1)) to avoid cancellation; |w| <= 1 for Im z >= 0.
cplx w_of(cplx z, cplx* root = nullptr) {
  const cplx r = std::sqrt(z - 1.0) * std::sqrt(z + 1.0);
  if (root) *root = r;
  return 1.0 / (z + r);
}

// Phi(z) = sum b_n w^{n+1} = (1/pi) int p(a t)/(P/h) / (z - t) dt (even n only).
cplx phi(const Eigen::VectorXd& b, cplx z) {
  const cplx w = w_of(z), w2 = w * w;
  cplx pw = w, sum = 0.0;
  for (Eigen::Index n = 0; n < b.size(); n += 2) {
    sum += b(n) * pw;
    pw *= w2;
  }
  return sum;
}

// Phi'(z) = -sum b_n (n+1) w^{n+1} / sqrt(z^2 - 1).
cplx dphi(const Eigen::VectorXd& b, cplx z) {
  cplx r;
  const cplx w = w_of(z, &r), w2 = w * w;
  cplx pw = w, sum = 0.0;
  for (Eigen::Index n = 0; n < b.size(); n += 2) {
    sum += b(n) * static_cast<double>(n + 1) * pw;
    pw *= w2;
  }
  return -sum / r;
}

// Lsum(z) = sum b_n L_n(z), L_n(z) = (1/pi) int sqrt(1-t^2) U_n(t) ln(z - t) dt.
cplx log_potential(const Eigen::VectorXd& b, cplx z) {
  const cplx w = w_of(z), w2 = w * w;
  cplx sum = b(0) * (-0.5 * std::log(w) + 0.25 * w2 - 0.5 * kLn2);
  cplx pw = w2;  // w^n for n = 2
  for (Eigen::Index n = 2; n < b.size(); n += 2) {
    const double dn = static_cast<double>(n);
    sum += b(n) * 0.5 * (-pw / dn + pw * w2 / (dn + 2.0));
    pw *= w2;
  }
  return sum;
}

// Gauss-Legendre, 8 points on [0, 1].
constexpr double kGx[8] = {0.019855071751231856, 0.10166676129318664, 0.23723379504183550,
                           0.40828267875217510,  0.59171732124782490, 0.76276620495816450,
                           0.89833323870681340,  0.98014492824876810};
constexpr double kGw[8] = {0.050614268145188130, 0.11119051722668724, 0.15685332293894364,
                           0.18134189168918100,  0.18134189168918100, 0.15685332293894364,
                           0.11119051722668724,  0.050614268145188130};

// [F(zL) - F(zT)] / delta where zL - zT = h_over_delta * delta; uses the
// average of F' along the segment when it is short (delta -> 0: F' h/delta).
template <class F, class DF>
cplx divided_difference(const F& f, const DF& df, cplx zT, cplx zL, double delta,
                        cplx h_over_delta) {
  const cplx h = zL - zT;
  const double near = std::min(std::abs(zT - 1.0), std::abs(zT + 1.0));
  if (delta > 0.0 && std::abs(h) >= 0.25 * near) return (f(zL) - f(zT)) / delta;
  if (h_over_delta == 0.0) return 0.0;
  cplx avg = 0.0;
  for (int k = 0; k < 8; ++k) avg += kGw[k] * df(zT + kGx[k] * h);
  return avg * h_over_delta;
}

// The point z_n = (x - i n y)/a with Im z >= +0 (y <= 0).
cplx z_of(double x, double n, double y, double a) {
  const double im = y < 0.0 ? -n * y / a : 0.0;  // +0.0 at the surface: upper side of the cut
  return {x / a, im};
}

}  // namespace

FieldEvaluator::FieldEvaluator(const LayerModel& model, double a, const Eigen::VectorXd& b,
                               double tol)
    : model_(std::make_shared<const LayerModel>(model)), a_(a), b_(b) {
  if (!(a > 0.0) || !std::isfinite(a)) throw std::invalid_argument("field: a must be > 0");
  for (Eigen::Index n = 1; n < b_.size(); n += 2) b_(n) = 0.0;
  // Panels resolve the remainder and the transform of p (frequency a); the
  // oscillation in x is integrated exactly by the Filon rule.
  quad_ = build_alpha_quadrature(*model_, tol, 2.0 * a, 1.0);
  filon_ = std::make_unique<FilonIntegrator>(quad_);
  const std::size_t nq = quad_.alpha.size();
  ptilde_.resize(nq);
  modes_.reserve(nq);
  u_series_cosine_transforms(b_, a_, quad_.alpha.data(), ptilde_.data(), nq);
  for (std::size_t q = 0; q < nq; ++q) {
    ptilde_[q] *= 2.0 / kPi;
    modes_.push_back(model_->mode_field(quad_.alpha[q]));
  }
}

Eigen::MatrixXd FieldEvaluator::transform(const Eigen::MatrixXd& values, bool sine,
                                          const Eigen::Ref<const Eigen::VectorXd>& x) const {
  // Legendre coefficients of every column, then blocks of x against them.
  const Eigen::Index m = values.rows(), ncol = values.cols();
  Eigen::MatrixXd coef(m, ncol);
  std::vector<double> col(static_cast<std::size_t>(m));
  for (Eigen::Index c = 0; c < ncol; ++c) {
    Eigen::Map<Eigen::VectorXd>(col.data(), m) = values.col(c);
    const std::vector<double> k = filon_->coefficients(col);
    coef.col(c) = Eigen::Map<const Eigen::VectorXd>(k.data(), m);
  }
  Eigen::MatrixXd out(x.size(), ncol);
  constexpr Eigen::Index kBlock = 256;
  std::vector<std::complex<double>> K;
  for (Eigen::Index start = 0; start < x.size(); start += kBlock) {
    const Eigen::Index nb = std::min(kBlock, x.size() - start);
    Eigen::MatrixXd W(nb, m);
    for (Eigen::Index i = 0; i < nb; ++i) {
      if (std::fabs(x(start + i)) > kFarField) {
        W.row(i).setZero();
        continue;
      }
      filon_->weights(x(start + i), K);
      for (Eigen::Index j = 0; j < m; ++j)
        W(i, j) =
            sine ? K[static_cast<std::size_t>(j)].imag() : K[static_cast<std::size_t>(j)].real();
    }
    out.middleRows(start, nb) = W * coef;
  }
  return out;
}

namespace {
void check_grid(const Eigen::Ref<const Eigen::VectorXd>& x,
                const Eigen::Ref<const Eigen::VectorXd>& y) {
  for (Eigen::Index i = 0; i < x.size(); ++i)
    if (!std::isfinite(x(i)))
      throw InvalidParameter("x", "finite", "x must be finite, got " + std::to_string(x(i)));
  for (Eigen::Index j = 0; j < y.size(); ++j)
    if (!(y(j) >= -1.0 && y(j) <= 0.0))
      throw InvalidParameter("y", "[-1, 0]",
                             "y must be in [-1, 0] (y/h, the layer), got " + std::to_string(y(j)));
}
}  // namespace

StressField FieldEvaluator::stresses(const Eigen::Ref<const Eigen::VectorXd>& x,
                                     const Eigen::Ref<const Eigen::VectorXd>& y) const {
  check_grid(x, y);
  const WaveConstants& c = model_->constants();
  const Eigen::Index nx = x.size(), ny = y.size();
  const auto nq = static_cast<Eigen::Index>(quad_.alpha.size());
  StressField f;
  f.sigma_x.setZero(ny, nx);
  f.sigma_y.setZero(ny, nx);
  f.tau_xy.setZero(ny, nx);

  // Layer remainder: per depth, values over alpha, then their transforms in x.
  Eigen::MatrixXd Rx(nq, ny), Ry(nq, ny), Rt(nq, ny);
  for (Eigen::Index q = 0; q < nq; ++q) {
    const ModeField& m = modes_[static_cast<std::size_t>(q)];
    const double pt = ptilde_[static_cast<std::size_t>(q)];
    for (Eigen::Index j = 0; j < ny; ++j) {
      const Eigen::Vector4d r = m.state(y(j)) - m.half_plane_state(y(j));
      Rx(q, j) = pt * sigma_x_hat(c, r);
      Ry(q, j) = pt * r(3);
      Rt(q, j) = pt * r(2);
    }
  }
  Eigen::MatrixXd cosv(nq, 2 * ny);
  cosv << Rx, Ry;
  const Eigen::MatrixXd cos_part = transform(cosv, false, x);  // (nx, 2 ny)
  f.sigma_x = cos_part.leftCols(ny).transpose();
  f.sigma_y = cos_part.rightCols(ny).transpose();
  f.tau_xy = transform(Rt, true, x).transpose();

  // Half-plane part in closed form. State of the half-plane mode mix:
  // hp1 e_T v_T + hp2 [e_L dv + v_T (e_L - e_T)/delta].
  const double nT = c.nT, nL = c.nL, d = c.delta;
  const Eigen::Vector4d vT(1.0, -1.0 / nT, (1.0 + nT * nT) / nT, -2.0);
  const Eigen::Vector4d dv(0.0, c.dW, c.dT, c.dS);
  auto sx = [&c](const Eigen::Vector4d& z) { return sigma_x_hat(c, z); };
  // Coefficients of e_T, e_L and the divided difference for [sigma_x, sigma_y, tau].
  const double kT[3] = {c.hp1 * sx(vT), c.hp1 * vT(3), c.hp1 * vT(2)};
  const double kL[3] = {c.hp2 * sx(dv), c.hp2 * dv(3), c.hp2 * dv(2)};
  const double kD[3] = {c.hp2 * sx(vT), c.hp2 * vT(3), c.hp2 * vT(2)};
  auto F = [this](cplx z) { return cplx(0.0, 1.0) * phi(b_, z); };
  auto dF = [this](cplx z) { return cplx(0.0, 1.0) * dphi(b_, z); };
  for (Eigen::Index j = 0; j < ny; ++j)
    for (Eigen::Index i = 0; i < nx; ++i) {
      if (std::fabs(x(i)) > kFarField) continue;
      const cplx zT = z_of(x(i), nT, y(j), a_), zL = z_of(x(i), nL, y(j), a_);
      const cplx fT = F(zT), fL = F(zL);
      const cplx fD = divided_difference(F, dF, zT, zL, d, cplx(0.0, -y(j) / a_));
      // cos-type (sigma_x, sigma_y): Re; sin-type (tau): Im.
      f.sigma_x(j, i) += kT[0] * fT.real() + kL[0] * fL.real() + kD[0] * fD.real();
      f.sigma_y(j, i) += kT[1] * fT.real() + kL[1] * fL.real() + kD[1] * fD.real();
      f.tau_xy(j, i) += kT[2] * fT.imag() + kL[2] * fL.imag() + kD[2] * fD.imag();
    }
  return f;
}

Eigen::MatrixXd FieldEvaluator::displacement(const Eigen::Ref<const Eigen::VectorXd>& x,
                                             const Eigen::Ref<const Eigen::VectorXd>& y) const {
  check_grid(x, y);
  const WaveConstants& c = model_->constants();
  const Eigen::Index nx = x.size(), ny = y.size();
  const auto nq = static_cast<Eigen::Index>(quad_.alpha.size());
  // Remainder [W - W_hp (1 - e^-alpha)] / alpha (finite at alpha -> 0).
  Eigen::MatrixXd Rw(nq, ny);
  for (Eigen::Index q = 0; q < nq; ++q) {
    const double al = quad_.alpha[static_cast<std::size_t>(q)];
    const ModeField& m = modes_[static_cast<std::size_t>(q)];
    const double pt = ptilde_[static_cast<std::size_t>(q)];
    for (Eigen::Index j = 0; j < ny; ++j) {
      const double w = m.state(y(j))(1), whp = m.half_plane_state(y(j))(1);
      Rw(q, j) = pt * (w + whp * std::expm1(-al)) / al;
    }
  }
  Eigen::MatrixXd v = transform(Rw, false, x).transpose();
  // Half-plane part: int (1 - e^-alpha) e^{n alpha y} / alpha cos(alpha u) = Re ln((p+1)/p):
  // V(z) = a sum b_n [L_n(z + i/a) - L_n(z)], V'(z) = a [Phi(z + i/a) - Phi(z)].
  const double nT = c.nT, nL = c.nL, d = c.delta;
  const double kT = c.hp1 * (-1.0 / nT), kL = c.hp2 * c.dW, kD = c.hp2 * (-1.0 / nT);
  const cplx shift(0.0, 1.0 / a_);
  auto V = [this, shift](cplx z) {
    return a_ * (log_potential(b_, z + shift) - log_potential(b_, z));
  };
  auto dV = [this, shift](cplx z) { return a_ * (phi(b_, z + shift) - phi(b_, z)); };
  for (Eigen::Index j = 0; j < ny; ++j)
    for (Eigen::Index i = 0; i < nx; ++i) {
      if (std::fabs(x(i)) > kFarField) continue;
      const cplx zT = z_of(x(i), nT, y(j), a_), zL = z_of(x(i), nL, y(j), a_);
      const cplx vD = divided_difference(V, dV, zT, zL, d, cplx(0.0, -y(j) / a_));
      v(j, i) += kT * V(zT).real() + kL * V(zL).real() + kD * vD.real();
    }
  return v;
}

}  // namespace movingpunch

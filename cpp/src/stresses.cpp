#include "movingpunch/stresses.hpp"

#include <cmath>
#include <complex>
#include <stdexcept>

#include "movingpunch/collocation.hpp"
#include "movingpunch/errors.hpp"
#include "potentials.hpp"

namespace movingpunch {

namespace {

using cplx = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;

}  // namespace

FieldEvaluator::FieldEvaluator(std::shared_ptr<const Medium> medium, double a,
                               const Eigen::VectorXd& b, double tol, SeriesKind kind)
    : model_(std::move(medium)), a_(a), b_(b), kind_(kind) {
  if (!(a > 0.0) || !std::isfinite(a)) throw std::invalid_argument("field: a must be > 0");
  for (Eigen::Index n = 1; n < b_.size(); n += 2) b_(n) = 0.0;
  if (kind_ == SeriesKind::U) tails_ = detail::potential_tails(b_);
  // Panels resolve the remainder and the transform of p (frequency a); the
  // oscillation in x is integrated exactly by the Filon rule.
  quad_ = build_alpha_quadrature(*model_, tol, 2.0 * a, Reach::field);
  filon_ = std::make_unique<FilonIntegrator>(quad_);
  const std::size_t nq = quad_.alpha.size();
  ptilde_.resize(nq);
  modes_.reserve(nq);
  series_cosine_transforms(b_, kind_, a_, quad_.alpha.data(), ptilde_.data(), nq);
  for (std::size_t q = 0; q < nq; ++q) {
    ptilde_[q] *= 2.0 / kPi;
    modes_.push_back(model_->mode(quad_.alpha[q]));
  }
  if (model_->long_wave_m1() != 0.0) {
    Eigen::VectorXd xr(1), yr(1);
    xr << kDisplacementReference;
    yr << 0.0;
    reference_ = displacement(xr, yr)(0, 0);
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

using detail::check_grid;

StressField FieldEvaluator::stresses(const Eigen::Ref<const Eigen::VectorXd>& x,
                                     const Eigen::Ref<const Eigen::VectorXd>& y, bool below) const {
  check_grid(x, y);
  const WaveConstants& c = model_->top();
  const Eigen::Index nx = x.size(), ny = y.size();
  const auto nq = static_cast<Eigen::Index>(quad_.alpha.size());
  StressField f;
  f.sigma_x.setZero(ny, nx);
  f.sigma_y.setZero(ny, nx);
  f.tau_xy.setZero(ny, nx);

  // Layer remainder: per depth, values over alpha, then their transforms in x.
  Eigen::MatrixXd Rx(nq, ny), Ry(nq, ny), Rt(nq, ny);
  for (Eigen::Index q = 0; q < nq; ++q) {
    const ModeProfile& m = *modes_[static_cast<std::size_t>(q)];
    const double pt = ptilde_[static_cast<std::size_t>(q)];
    for (Eigen::Index j = 0; j < ny; ++j) {
      const ModeState r = m.remainder(y(j), below);
      Rx(q, j) = pt * r.sx.real();
      Ry(q, j) = pt * r.z(3).real();
      Rt(q, j) = pt * r.z(2).real();
    }
  }
  Eigen::MatrixXd cosv(nq, 2 * ny);
  cosv << Rx, Ry;
  const Eigen::MatrixXd cos_part = transform(cosv, false, x);  // (nx, 2 ny)
  f.sigma_x = cos_part.leftCols(ny).transpose();
  f.sigma_y = cos_part.rightCols(ny).transpose();
  f.tau_xy = transform(Rt, true, x).transpose();

  // Half-plane part in closed form (potentials.hpp; g even).
  for (Eigen::Index j = 0; j < ny; ++j)
    for (Eigen::Index i = 0; i < nx; ++i) {
      if (std::fabs(x(i)) > kFarField) continue;
      if (kind_ == SeriesKind::T && y(j) == 0.0 && std::fabs(x(i)) == a_) {
        // A flat punch's edge: p, and so sigma_x = -phi2 p + ... and
        // sigma_y = -p, are infinite there (square-root singular ends).
        const double g1 = t_series(b_, 1.0);
        const double inf = g1 == 0.0 ? 0.0 : -std::copysign(HUGE_VAL, g1);
        f.sigma_x(j, i) = inf;
        f.sigma_y(j, i) = inf;
        f.tau_xy(j, i) = 0.0;
        continue;
      }
      const Eigen::Vector3d hp =
          detail::half_plane_stresses(c, b_, a_, x(i), y(j), 2, kind_, &tails_);
      f.sigma_x(j, i) += hp(0);
      f.sigma_y(j, i) += hp(1);
      f.tau_xy(j, i) += hp(2);
    }
  return f;
}

Eigen::MatrixXd FieldEvaluator::displacement(const Eigen::Ref<const Eigen::VectorXd>& x,
                                             const Eigen::Ref<const Eigen::VectorXd>& y) const {
  check_grid(x, y);
  const WaveConstants& c = model_->top();
  const Eigen::Index nx = x.size(), ny = y.size();
  const auto nq = static_cast<Eigen::Index>(quad_.alpha.size());
  // Remainder [W - W_hp (1 - e^-alpha)] / alpha (finite at alpha -> 0 on
  // springs). A half-space base: W -> -m0 at every depth as alpha -> 0, and
  // -m0 e^-alpha/alpha is taken out as the surface displacement takes it
  // (contact.cpp): its part of v is (m0/(2 pi)) int p ln(1 + (x - xi)^2) up
  // to a constant, which the reference point removes (medium.hpp).
  const double m0 = model_->long_wave_m1();
  Eigen::MatrixXd Rw(nq, ny);
  for (Eigen::Index q = 0; q < nq; ++q) {
    const double al = quad_.alpha[static_cast<std::size_t>(q)];
    const ModeProfile& m = *modes_[static_cast<std::size_t>(q)];
    const double pt = ptilde_[static_cast<std::size_t>(q)];
    for (Eigen::Index j = 0; j < ny; ++j) {
      const double w = m.state(y(j)).z(1).real(), whp = m.half_plane(y(j)).z(1).real();
      Rw(q, j) = m0 == 0.0 ? pt * (w + whp * std::expm1(-al)) / al
                           : pt * (w + whp * std::expm1(-al) + m0 * std::exp(-al)) / al;
    }
  }
  Eigen::MatrixXd v = transform(Rw, false, x).transpose();
  // Half-plane part in closed form (potentials.hpp).
  std::vector<double> lr, lw;
  if (m0 != 0.0) detail::log1p_rule(b_, a_, lr, lw, kind_);
  for (Eigen::Index j = 0; j < ny; ++j)
    for (Eigen::Index i = 0; i < nx; ++i) {
      if (m0 == 0.0 && std::fabs(x(i)) > kFarField) continue;
      if (std::fabs(x(i)) <= kFarField)
        v(j, i) += detail::half_plane_displacement(c, b_, a_, x(i), y(j), 2, kind_);
      if (m0 != 0.0) v(j, i) += m0 / (2.0 * kPi) * a_ * detail::log1p_sum(lr, lw, a_, x(i));
    }
  // Relative to the surface at the reference point (0 on springs).
  v.array() -= reference_;
  return v;
}

}  // namespace movingpunch

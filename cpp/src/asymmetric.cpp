// The moving punch on a damped (Kelvin-Voigt) Winkler foundation: complex
// layer response, asymmetric contact (-b, a), drag. See docs/damped.md.
#include "movingpunch/asymmetric.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <list>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "bessel.hpp"
#include "chebyshev.hpp"
#include "gap_scan.hpp"
#include "gauss_kronrod.hpp"
#include "ladder.hpp"
#include "layer_basis.hpp"
#include "movingpunch/collocation.hpp"
#include "movingpunch/dispersion.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/stresses.hpp"
#include "potentials.hpp"
#include "roots.hpp"
#include "solve_skeleton.hpp"

namespace movingpunch {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kEps = 2.220446049250313e-16;
constexpr double kInf = std::numeric_limits<double>::infinity();

using detail::kWg;
using detail::kWgk;
using detail::kXgk;
using detail::modal_columns;
using detail::transfer_matrix;

using detail::gk_node;
using detail::gk_weight;
// Gauss weight of node j (0 for Kronrod-only nodes).
double g_weight(int j, double h) {
  const int k = j < 7 ? j : (j == 7 ? 7 : 14 - j);
  return k % 2 == 1 ? kWg[k / 2] * h : 0.0;
}

// The Filon coefficients of the real and imaginary parts of g at the nodes.
void filon_coefficients(const FilonIntegrator& filon, const std::vector<cplx>& g,
                        std::vector<double>& c_re, std::vector<double>& c_im) {
  std::vector<double> re(g.size()), im(g.size());
  for (std::size_t i = 0; i < g.size(); ++i) {
    re[i] = g[i].real();
    im[i] = g[i].imag();
  }
  c_re = filon.coefficients(re);
  c_im = filon.coefficients(im);
}

// Bottom spring row t S - k W, normalised by t + |k| (no overflow for any k,
// t); S, W real or complex rows (cast as the real layer always cast them:
// its results stay bit for bit).
template <class Row>
Eigen::RowVector4cd spring_row(const Row& S, const Row& W, double t, cplx k, bool rigid) {
  if (rigid) return W.template cast<cplx>();
  const double n = t + std::abs(k);
  return (t / n) * S.template cast<cplx>() - (k / n) * W.template cast<cplx>();
}

// The boundary matrix on the modal basis (top tau, sigma_y; bottom tau,
// springs) and the top/bottom columns, in the constants' own scalar (real
// for every elastic layer, complex with a viscoelastic layer's inertia).
template <class C>
struct ModalSystem {
  using Columns = decltype(modal_columns(std::declval<const C&>(), 0.0, 0.0));
  Columns top, bot;
  Eigen::PartialPivLU<Eigen::Matrix4cd> lu;
};
template <class C>
ModalSystem<C> modal_system(const C& c, double t, cplx k, bool rigid) {
  ModalSystem<C> m;
  m.top = modal_columns(c, t, 0.0);
  m.bot = modal_columns(c, t, -1.0);
  Eigen::Matrix4cd M;
  M.row(0) = m.top.row(2).template cast<cplx>();
  M.row(1) = m.top.row(3).template cast<cplx>();
  M.row(2) = m.bot.row(2).template cast<cplx>();
  M.row(3) = spring_row(m.bot.row(3), m.bot.row(1), t, k, rigid);
  m.lu = M.partialPivLu();
  return m;
}

template <class C>
DampedResponse modal_response(const C& c, double t, cplx k, bool rigid) {
  DampedResponse r;
  const double c2 = c.c2;
  const ModalSystem<C> m = modal_system(c, t, k, rigid);
  const Eigen::Vector4cd amp = m.lu.solve(Eigen::Vector4cd(0.0, -1.0, 0.0, 0.0));
  // The unit tangential load (top T = 1, S = 0) on the same factorisation.
  const Eigen::Vector4cd ampq = m.lu.solve(Eigen::Vector4cd(1.0, 0.0, 0.0, 0.0));
  const Eigen::Vector4cd zq = m.top.template cast<cplx>() * ampq;
  r.Uq = zq(0);
  r.Wq = zq(1);
  r.Wqb = (m.bot.row(1).template cast<cplx>() * ampq)(0);
  const Eigen::Vector4cd z0 = m.top.template cast<cplx>() * amp;
  r.U0 = z0(0);
  r.W0 = z0(1);
  r.M1 = -z0(1);
  r.M2 = (c2 - 2.0) / c2 - 4.0 * (c2 - 1.0) / c2 * z0(0);
  r.Wb = (m.bot.row(1).template cast<cplx>() * amp)(0);
  return r;
}

template <class C>
DampedResponse transfer_response(const C& c, double t, cplx k, bool rigid) {
  const double c2 = c.c2;
  DampedResponse r;
  const auto P = transfer_matrix(c, t, -1.0);
  Eigen::Matrix<cplx, 2, 4> R;
  R.row(0) = P.row(2).template cast<cplx>();
  R.row(1) = spring_row(P.row(3), P.row(1), t, k, rigid);
  const Eigen::Matrix2cd M = R.leftCols<2>();
  const Eigen::Vector2cd rhs = R.col(3);
  const Eigen::FullPivLU<Eigen::Matrix2cd> lu = M.fullPivLu();
  const Eigen::Vector2cd x = lu.solve(rhs);
  const Eigen::Vector2cd xq = lu.solve(Eigen::Vector2cd(-R.col(2)));
  r.Uq = xq(0);
  r.Wq = xq(1);
  r.Wqb = (P.row(1).template cast<cplx>() * Eigen::Vector4cd(xq(0), xq(1), 1.0, 0.0))(0);
  const Eigen::Vector4cd z0(x(0), x(1), 0.0, -1.0);
  r.U0 = x(0);
  r.W0 = x(1);
  r.M1 = -x(1);
  r.M2 = (c2 - 2.0) / c2 - 4.0 * (c2 - 1.0) / c2 * x(0);
  r.Wb = (P.row(1).template cast<cplx>() * z0)(0);
  return r;
}

// J_0 .. J_{nmax+1} at x >= 0 (collocation.cpp's recurrences).
void bessel_j(double x, int nmax, std::vector<double>& J) {
  if (x == 0.0) {
    J.assign(static_cast<std::size_t>(nmax) + 2, 0.0);
    J[0] = 1.0;
    return;
  }
  detail::bessel_orders(x, nmax + 1, J);
}

cplx u_series_transform(const Eigen::VectorXd& b, double centre, double half, double alpha,
                        const Eigen::VectorXd* b2 = nullptr, double centre2 = 0.0,
                        cplx* t2 = nullptr);

}  // namespace

// ---------------------------------------------------------------------------
// Complex layer response

DampedLayerModel::DampedLayerModel(double vstar, double kw, double nu, double damping, double kp,
                                   Viscoelastic visco)
    : c_(wave_constants(vstar, nu)),
      kw_(kw),
      damping_(damping),
      rigid_(std::isinf(kw)),
      kp_(kp),
      visco_(std::move(visco)) {
  require_in_range("kw", kw, 0.0, kInf, true, false, true);
  require_in_range("damping", damping, 0.0, kInf, false, true);
  require_in_range("kp", kp, 0.0, kMaxKp, false, false);
  beta_ = damping * std::sqrt(vstar);
  tq_ = tangential_half_plane(c_);
  inertial_ = !visco_.empty() && vstar > 0.0;
}

cplx DampedLayerModel::foundation(double t) const noexcept {
  const cplx k{kw_ + kp_ * t * t, -beta_ * t};
  return visco_.empty() ? k : k / visco_.modulus(t);
}

ComplexWaveConstants DampedLayerModel::constants_at(double t) const {
  return complex_wave_constants(c_.s / visco_.modulus(t), c_.nu);
}

DampedResponse DampedLayerModel::response_modal(double t) const {
  if (!(t > 0.0)) throw std::invalid_argument("damped layer response: t must be > 0");
  if (inertial_) return modal_response(constants_at(t), t, foundation(t), rigid_);
  if (t * c_.nT >= 400.0) {  // M1 - phi1 ~ exp(-2 nT t) underflows: the exact limit
    const double c2 = c_.c2;
    DampedResponse r;
    r.U0 = ((c2 - 2.0) / c2 - c_.phi2) * c2 / (4.0 * (c2 - 1.0));
    r.W0 = -c_.phi1;
    r.M1 = c_.phi1;
    r.M2 = c_.phi2;
    r.Wb = 0.0;
    r.Uq = tq_.Uq;
    r.Wq = tq_.Wq;
    r.Wqb = 0.0;
    return r;
  }
  return modal_response(c_, t, foundation(t), rigid_);
}

DampedResponse DampedLayerModel::response_transfer(double t) const {
  if (!(t >= 0.0) || !(t <= 4.0))
    throw std::invalid_argument("damped layer response (transfer): t must be in [0, 4]");
  if (t == 0.0) {
    // (The material's modulus is 1 at t = 0: the relaxed layer's limits.)
    const double c2 = c_.c2;
    DampedResponse r;
    r.U0 = c_.A(2, 3) / c_.A(2, 0);
    r.W0 = 0.0;
    r.M1 = 0.0;
    r.M2 = (c2 - 2.0) / c2 - 4.0 * (c2 - 1.0) / c2 * r.U0;
    r.Wb = 0.0;
    // The tangential response has a pole at t = 0 (Uq ~ C0/(Ep t), the
    // layer carries the net horizontal force as a bar): not defined there.
    r.Uq = r.Wq = std::nan("");
    r.Wqb = 0.0;
    return r;
  }
  if (inertial_) return transfer_response(constants_at(t), t, foundation(t), rigid_);
  return transfer_response(c_, t, foundation(t), rigid_);
}

DampedResponse DampedLayerModel::response(double t) const {
  if (std::isnan(t) || t < 0.0)
    throw std::invalid_argument("damped layer response: t = alpha h must be >= 0");
  if (t < kSmallT) return response_transfer(t);
  return response_modal(t);
}

Eigen::Vector4cd DampedLayerModel::state(double t, double y) const {
  if (!(t > 0.0) || !std::isfinite(t) || !(y >= -1.0) || !(y <= 0.0))
    throw std::invalid_argument("damped state: need t > 0 finite and -1 <= y <= 0");
  const Eigen::Vector4cd z = state_coefficients(t);
  auto of = [&](const auto& c) -> Eigen::Vector4cd {
    if (t < kSmallT) return transfer_matrix(c, t, y).template cast<cplx>() * z;
    return modal_columns(c, t, y).template cast<cplx>() * z;
  };
  if (inertial_) return of(constants_at(t));
  return of(c_);
}

Eigen::Vector4cd DampedLayerModel::state_coefficients(double t) const {
  if (!(t > 0.0) || !std::isfinite(t))
    throw std::invalid_argument("damped state: need t > 0 finite");
  if (t < kSmallT) {
    const DampedResponse r = response_transfer(t);
    return {r.U0, r.W0, 0.0, -1.0};
  }
  const Eigen::Vector4cd rhs(0.0, -1.0, 0.0, 0.0);
  if (inertial_) return modal_system(constants_at(t), t, foundation(t), rigid_).lu.solve(rhs);
  return modal_system(c_, t, foundation(t), rigid_).lu.solve(rhs);
}

Eigen::Vector4cd DampedLayerModel::tangential_state(double t, double y) const {
  if (!(t > 0.0) || !std::isfinite(t) || !(y >= -1.0) || !(y <= 0.0))
    throw std::invalid_argument("tangential state: need t > 0 finite and -1 <= y <= 0");
  const Eigen::Vector4cd unit(1.0, 0.0, 0.0, 0.0);
  auto of = [&](const auto& c) -> Eigen::Vector4cd {
    if (t < kSmallT) {
      const DampedResponse r = transfer_response(c, t, foundation(t), rigid_);
      return transfer_matrix(c, t, y).template cast<cplx>() *
             Eigen::Vector4cd(r.Uq, r.Wq, 1.0, 0.0);
    }
    const Eigen::Vector4cd amp = modal_system(c, t, foundation(t), rigid_).lu.solve(unit);
    return modal_columns(c, t, y).template cast<cplx>() * amp;
  };
  if (inertial_) return of(constants_at(t));
  return of(c_);
}

// ---------------------------------------------------------------------------
// Quadrature in alpha

namespace {

// The kernel's integrand (M1 - phi1)/phi1; with friction f > 0 that of the
// effective response M1 - i f Wq less its half-plane limit phi1 - i f Wq_inf
// (docs/theory.md section 14).
cplx kernel_integrand(const Medium& m, const DampedResponse& r, double t, double friction) {
  const double phi1 = m.phi1();
  // A viscoelastic top: less its whole half-plane part (the memory's slow
  // tail is the collocation's, MemoryKernel).
  if (m.memory() != nullptr) return (r.M1 - m.half_plane_m1(t)) / phi1;
  if (!(friction > 0.0)) return (r.M1 - phi1) / phi1;
  return (r.M1 - phi1 - cplx(0.0, friction) * (r.Wq - m.tangential().Wq)) / phi1;
}

struct DPanel {
  double lo = 0, hi = 0;
  DampedResponse r[15];
  double error = 0, floor = 0, resabs = 0;
  double sharp = 0;  // QUADPACK's estimate of the Kronrod result's error
  double parent_density = std::numeric_limits<double>::infinity();  // its parent's error / length
};

DPanel eval_dpanel(const Medium& m, double lo, double hi, double friction) {
  check_interrupt();  // Ctrl-C (interrupt.hpp): 15 layer responses
  DPanel p;
  p.lo = lo;
  p.hi = hi;
  const double c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
  cplx kf = 0.0, gf = 0.0, kb = 0.0, gb = 0.0;
  double fmax = 0.0;
  for (int j = 0; j < 15; ++j) {
    p.r[j] = m.full_response(gk_node(j, c, h));
    const cplx f = kernel_integrand(m, p.r[j], gk_node(j, c, h), friction);
    const cplx b = p.r[j].Wb;
    kf += gk_weight(j, h) * f;
    gf += g_weight(j, h) * f;
    kb += gk_weight(j, h) * b;
    gb += g_weight(j, h) * b;
    p.resabs += gk_weight(j, h) * (std::abs(f) + std::abs(b));
    fmax = std::max(fmax, std::max(std::abs(f), std::abs(b)));
  }
  p.error = std::abs(kf - gf) + std::abs(kb - gb);
  // QUADPACK's qk15 estimate of the error of the Kronrod sum (not of the
  // Gauss one, which |K - G| measures): resasc min(1, (200 |K - G|/resasc)^1.5),
  // resasc = int |f - mean f| by the same rule.
  double ra_f = 0.0, ra_b = 0.0;
  for (int j = 0; j < 15; ++j) {
    ra_f += gk_weight(j, h) *
            std::abs(kernel_integrand(m, p.r[j], gk_node(j, c, h), friction) - kf / (2.0 * h));
    ra_b += gk_weight(j, h) * std::abs(p.r[j].Wb - kb / (2.0 * h));
  }
  auto qk = [](double e, double resasc) {
    return resasc > 0.0 ? resasc * std::min(1.0, std::pow(200.0 * e / resasc, 1.5)) : e;
  };
  // (Its round-off part is not added: the solver's floors, calibrated on the
  // scatter of results between collocation sizes, carry the kernel's round-off.)
  p.sharp = qk(std::abs(kf - gf), ra_f) + qk(std::abs(kb - gb), ra_b);
  p.floor = 8.0 * kEps * (2.0 * h + p.resabs * (1.0 + fmax));
  return p;
}

}  // namespace

AsymmetricQuadrature build_damped_quadrature(const Medium& model, double tol, double friction) {
  if (!(tol > 0.0)) throw std::invalid_argument("damped quadrature: tol must be > 0");
  // The slowest field, the base face's response Wb, decays like (1 + t)
  // exp(-nT t) (nT: the homogeneous layer's; a stack's travel time through
  // its sublayers, field_decay_rate): below 1e-18 beyond this.
  const double nT = model.field_decay_rate();
  if (!(nT > 0.0))
    throw std::invalid_argument(
        "asymmetric solver: the medium's response does not decay at short waves (a graded "
        "top sublayer): not supported");
  AsymmetricQuadrature q;
  double& amax = q.panels.alpha_max;
  amax = (std::log(1e18) + std::log1p(4.0 * 60.0 / nT)) / nT;
  const double w0 = 0.5;
  const int n0 = static_cast<int>(std::ceil(amax / w0));
  amax = n0 * w0;  // the panels cover [0, alpha_max] exactly
  std::vector<DPanel> work, done;
  for (int i = n0 - 1; i >= 1; --i)
    work.push_back(eval_dpanel(model, i * w0, (i + 1) * w0, friction));
  // The first panel, split down to a Pasternak base's long-wave scale
  // (layer_basis.hpp; one panel for springs alone).
  const std::vector<double> first = model.first_panel_edges(w0);
  for (std::size_t i = first.size() - 1; i >= 1; --i)
    work.push_back(eval_dpanel(model, first[i - 1], first[i], friction));
  const double panel_tol = tol / n0;
  int evaluations = n0 + static_cast<int>(first.size()) - 2;
  while (!work.empty()) {
    DPanel p = work.back();
    work.pop_back();
    const double len = p.hi - p.lo;
    const bool fine = p.error <= std::max(panel_tol * len / w0, p.floor);
    // At the responses' round-off: |K - G| within a small multiple of the
    // floor and, per unit length, no smaller than the parent's (a truncation
    // error falls like len^23 on halving, round-off like len). Near V*_cr
    // the round-off of Wb is a few times the floor: without this, panels
    // split down to 1e-13 wide, up to the evaluation cap (20000 panels, and
    // minutes for every kernel table built on them).
    const bool noise = p.error <= 64.0 * p.floor && p.error >= 0.25 * p.parent_density * len;
    if (fine || noise || len < 1e-12 * w0 || evaluations > 40000) {
      done.push_back(p);
      continue;
    }
    const double mid = 0.5 * (p.lo + p.hi);
    for (const auto& [lo, hi] : {std::pair{mid, p.hi}, std::pair{p.lo, mid}}) {
      work.push_back(eval_dpanel(model, lo, hi, friction));
      work.back().parent_density = p.error / len;
    }
    evaluations += 2;
  }
  std::sort(done.begin(), done.end(), [](const DPanel& a, const DPanel& b) { return a.lo < b.lo; });
  for (const DPanel& p : done) {
    const double c = 0.5 * (p.lo + p.hi), h = 0.5 * (p.hi - p.lo);
    q.panels.panel_centre.push_back(c);
    q.panels.panel_half.push_back(h);
    for (int j = 0; j < 15; ++j) {
      q.panels.alpha.push_back(gk_node(j, c, h));
      q.panels.weight.push_back(gk_weight(j, h));
      q.panels.m1.push_back(p.r[j].M1.real());
      q.m1.push_back(p.r[j].M1);
      q.m2.push_back(p.r[j].M2);
      q.wb.push_back(p.r[j].Wb);
      q.r.push_back(p.r[j]);
    }
    q.error_estimate += p.error;
    q.kronrod_error += p.sharp;
  }
  q.panels.error_estimate = q.error_estimate;
  return q;
}

double asymmetric_kernel(const FilonIntegrator& f, const std::vector<double>& kr,
                         const std::vector<double>& ki, double u) {
  const auto [re, im] = f.integral_pair_exact(u, kr, ki);  // = integral() twice, bit for bit
  return re.imag() + im.real();
}

// ---------------------------------------------------------------------------
// The tabulated kernel

namespace {

// Whether the medium's quadratic form is positive: the work of a pressure p
// on the surface it displaces, int p (-v) dx = (1/2 pi) int Re M1 |p^|^2/|alpha|
// d alpha (v^ = -M1 p^/|alpha|, Re M1 even), is then > 0 for every p != 0,
// and the frictionless contact problem (a variational inequality of this
// strictly monotone operator, symmetric or not) has one solution at most: a
// valid steady contact is the only one (docs/theory.md section 9). Read
// from the table's nodes, which resolve M1 (Re M1 >= 1e-3 |M1| at each, a
// margin against a dip between nodes), and beyond them from the half-plane
// part (all that is left there), sampled geometrically to 1e12 alpha_max.
// An elastic layer below V*_cr (M1 > 0) passes; above V*_cr, where lambda(w)
// can fold, Re M1 < 0 near the resonance and it fails.
// Once per quadrature (its wider tables share it): AsymmetricKernel::positive_form.
bool form_is_positive(const AsymmetricQuadrature& q, const Medium& md) {
  constexpr double kMargin = 1e-3;
  for (const cplx& m : q.m1)
    if (!(m.real() >= kMargin * std::abs(m))) return false;
  const double top = q.panels.alpha.empty() ? 1.0 : q.panels.alpha.back();
  for (double t = top; t <= 1e12 * top; t *= 1.25) {
    const cplx m = md.half_plane_m1(t);
    if (!(m.real() >= kMargin * std::abs(m))) return false;
  }
  return true;
}

}  // namespace

AsymmetricKernel::AsymmetricKernel(std::shared_ptr<const Medium> model, double range,
                                   double friction)
    : range_(range) {
  require_in_range("kernel range", range, 0.0, 1e6, true, false);
  require_in_range("friction", friction, 0.0, kInf, false, true);
  auto b = std::make_shared<Base>();
  b->model = std::move(model);
  b->friction = friction;
  // Built to round-off whatever tol (it costs no more: its panels are set by
  // the floor already at tol = 1e-6), so that its error is part of the
  // round-off floor of the estimates, not of tol.
  b->quad = build_damped_quadrature(*b->model, 1e-15, friction);
  b->filon = std::make_shared<const FilonIntegrator>(b->quad.panels);
  const double phi1 = b->model->phi1();
  std::vector<double> re(b->quad.m1.size()), im(b->quad.m1.size());
  for (std::size_t i = 0; i < re.size(); ++i) {
    re[i] = (b->quad.m1[i].real() - phi1) / phi1;
    im[i] = b->quad.m1[i].imag() / phi1;
    if (friction > 0.0 || b->model->memory() != nullptr) {  // M1 - i f (Wq - Wq_inf); M1 - H
      const cplx k = kernel_integrand(*b->model, b->quad.r[i], b->quad.panels.alpha[i], friction);
      re[i] = k.real();
      im[i] = k.imag();
    }
  }
  b->kr = b->filon->coefficients(re);
  b->ki = b->filon->coefficients(im);
  b->positive_form = form_is_positive(b->quad, *b->model);
  {
    const AsymmetricQuadrature& q = b->quad;
    const Medium& md = *b->model;
    b->surface_band = detail::response_band(q.panels.alpha, q.panels.weight, [&](std::size_t i) {
      return std::abs(q.m1[i] - md.half_plane_m1(q.panels.alpha[i]));
    });
  }
  base_ = std::move(b);
  tabulate();
}

AsymmetricKernel::AsymmetricKernel(const AsymmetricKernel& other, double range)
    : base_(other.base_), range_(range) {
  require_in_range("kernel range", range, 0.0, 1e6, true, false);
  tabulate();
}

double AsymmetricKernel::direct(double u) const {
  return asymmetric_kernel(*base_->filon, base_->kr, base_->ki, u);
}

void AsymmetricKernel::tabulate() {
  // K is analytic in the strip |Im u| < 2 nT (M1 - phi1 decays like
  // exp(-2 nT alpha)): on pieces of width <= 1 a degree-24 interpolant is at
  // round-off for nT >~ 0.5; each piece is checked by its last coefficients
  // and the width halved until every piece passes.
  constexpr int D = kDegree;
  double abs_f = 0.0;  // int |f|: the scale of the Filon sums' round-off
  const AsymmetricQuadrature& q = base_->quad;
  // (M1 less its half-plane part: phi1, or a viscoelastic top's whole
  // (1 - nu)/m(t), whose slow memory the table does not hold.)
  for (std::size_t i = 0; i < q.m1.size(); ++i)
    abs_f += q.panels.weight[i] * std::abs(q.m1[i] - model().half_plane_m1(q.panels.alpha[i])) /
             std::fabs(model().phi1());
  // Narrower pieces until the last coefficients are at the values' round-off,
  // or stop shrinking (noise: near-resonant peaks make the Filon sums'
  // round-off larger than this estimate of it), or the pieces reach 1/8.
  double prev_tail = std::numeric_limits<double>::infinity();
  for (double target = 1.0;; target *= 0.5) {
    const std::size_t pieces =
        static_cast<std::size_t>(std::max(1.0, std::ceil(2.0 * range_ / target)));
    width_ = 2.0 * range_ / static_cast<double>(pieces);
    coef_.assign(pieces * (D + 1), 0.0);
    double tail = 0.0, vmax = 0.0;
    double vals[D + 1];
    for (std::size_t p = 0; p < pieces; ++p) {
      const double c0 = -range_ + (static_cast<double>(p) + 0.5) * width_;
      for (int j = 0; j <= D; ++j) {
        vals[j] = direct(c0 + 0.5 * width_ * std::cos(kPi * (j + 0.5) / (D + 1)));
        vmax = std::max(vmax, std::fabs(vals[j]));
      }
      double* c = coef_.data() + p * (D + 1);
      for (int m = 0; m <= D; ++m) {
        double sum = 0.0;
        for (int j = 0; j <= D; ++j) sum += vals[j] * std::cos(kPi * m * (j + 0.5) / (D + 1));
        c[m] = (m == 0 ? 1.0 : 2.0) * sum / (D + 1);
      }
      tail = std::max(tail, std::fabs(c[D - 1]) + std::fabs(c[D]));
    }
    // The values carry the round-off of Filon sums of terms up to int |f|.
    const double roundoff = 4.0 * kEps * (abs_f + vmax);
    if (tail <= 4.0 * roundoff || tail > 0.25 * prev_tail || target <= 0.125) {
      table_error_ = 2.0 * tail + roundoff;
      return;
    }
    prev_tail = tail;
  }
}

void AsymmetricKernel::many(const double* u, double* out, std::size_t n) const {
  // Four Clenshaw recurrences interleaved (each is a chain of dependent steps).
  constexpr int D = kDegree, L = 4;
  const std::size_t pieces = coef_.size() / (D + 1);
  std::size_t i = 0;
  for (; i + L <= n; i += L) {
    const double* c[L];
    double x2[L], b1[L] = {0, 0, 0, 0}, b2[L] = {0, 0, 0, 0};
    bool inside = true;
    for (int l = 0; l < L; ++l) {
      const double v = u[i + static_cast<std::size_t>(l)];
      inside = inside && std::fabs(v) <= range_;
      const std::size_t p =
          std::min(pieces - 1, static_cast<std::size_t>(std::max(0.0, (v + range_) / width_)));
      x2[l] = 4.0 * (v + range_ - (static_cast<double>(p) + 0.5) * width_) / width_;
      c[l] = coef_.data() + p * (D + 1);
    }
    if (!inside) {
      for (int l = 0; l < L; ++l)
        out[i + static_cast<std::size_t>(l)] = (*this)(u[i + static_cast<std::size_t>(l)]);
      continue;
    }
    for (int m = D; m >= 1; --m)
      for (int l = 0; l < L; ++l) {
        const double b0 = c[l][m] + x2[l] * b1[l] - b2[l];
        b2[l] = b1[l];
        b1[l] = b0;
      }
    for (int l = 0; l < L; ++l)
      out[i + static_cast<std::size_t>(l)] = c[l][0] + 0.5 * x2[l] * b1[l] - b2[l];
  }
  for (; i < n; ++i) out[i] = (*this)(u[i]);
}

double AsymmetricKernel::operator()(double u) const {
  if (!(std::fabs(u) <= range_)) return direct(u);
  constexpr int D = kDegree;
  const std::size_t pieces = coef_.size() / (D + 1);
  const std::size_t p = std::min(pieces - 1, static_cast<std::size_t>((u + range_) / width_));
  const double x = 2.0 * (u + range_ - (static_cast<double>(p) + 0.5) * width_) / width_;
  return detail::chebyshev_sum(coef_.data() + p * (D + 1), D, x);
}

// ---------------------------------------------------------------------------
// Validation

MediumSpec medium_of(const AsymmetricParams& p) {
  return p.medium ? *p.medium : homogeneous_medium(p.kw, p.nu, p.kp, p.damping);
}

AsymmetricParams with_medium_scalars(const AsymmetricParams& p) {
  AsymmetricParams q = p;
  if (!p.medium) return q;
  const MediumSpec& m = *p.medium;
  q.nu = m.layers[0].nu;
  if (m.base.kind == BaseKind::springs) {
    q.kw = m.base.kw;
    q.kp = m.base.kp;
    q.damping = m.base.damping;
  } else {
    q.kw = kInf;
    q.kp = 0.0;
    q.damping = 0.0;
  }
  return q;
}

double critical_vstar_of(const AsymmetricParams& p) {
  if (!p.medium || p.medium->homogeneous()) {
    const AsymmetricParams q = with_medium_scalars(p);
    return critical_vstar(q.kw, q.nu, q.kp);
  }
  return critical_speed(*p.medium).vstar;
}

void require_steady_speed(const AsymmetricParams& p, double vcr, double vr) {
  if (!(p.vstar < vr)) throw SupercriticalSpeedError(p.vstar, vcr, vr);
  // The undamped layer's steady problem is bounded only below V*_cr (real
  // poles above it). Dashpots, or one viscoelastic layer on springs (Im
  // m(alpha) != 0 at every alpha > 0: no free steady wave below its relaxed
  // Rayleigh speed; docs/theory.md section 17.9), bound it above V*_cr too.
  // (A stack's elastic sublayer, or its bottom face's waves, could carry a
  // free wave: not claimed.)
  const bool visco_layer = p.medium && p.medium->layers.size() == 1 &&
                           p.medium->base.kind == BaseKind::springs &&
                           !p.medium->layers[0].visco.empty();
  if (!(p.damping > 0.0) && !visco_layer && !(p.vstar < vcr))
    throw SupercriticalSpeedError(p.vstar, vcr, vr);
}

double cauchy_phi1_of(const AsymmetricParams& p) {
  const AsymmetricParams q = with_medium_scalars(p);
  // (An elastic top's material is empty: unrelaxed_phi1 is its phi1.)
  return p.medium ? unrelaxed_phi1(p.medium->layers[0].visco, q.vstar, q.nu)
                  : wave_constants(q.vstar, q.nu).phi1;
}

void validate_asymmetric_medium(const MediumSpec& m) {
  validate(m);
  if (m.layers[0].gamma != 0.0)
    throw InvalidParameter(
        "layers", "a homogeneous top sublayer (graded ones below it)",
        "layers: a graded top sublayer is not solved yet (its response reaches the "
        "half-plane's only as a series in gamma/alpha, which the kernel must take out "
        "exactly); put a homogeneous sublayer on top or use a staircase of sublayers");
  if (!m.homogeneous() && m.base.kind == BaseKind::springs && m.base.damping != 0.0)
    throw InvalidParameter(
        "damping", "0 under a stack of sublayers (damped springs: the homogeneous layer only)",
        "damping: damped springs under a stack of sublayers are not supported yet (the stack's "
        "propagation is real); given damping = " +
            std::to_string(m.base.damping) + " under " + describe(m));
}

namespace {
void validate_scalars(const AsymmetricParams& p, bool material_dissipates);
}  // namespace

void validate(const AsymmetricParams& p) {
  if (p.medium) {
    validate_asymmetric_medium(*p.medium);
    // The scalar checks on the medium's own values (nu: the top's; damping
    // > 0 unless friction, an asymmetric table or a viscoelastic layer asks
    // for this solver).
    AsymmetricParams r = with_medium_scalars(p);
    r.medium = nullptr;
    const bool visco = p.medium->viscoelastic();
    if (visco) {
      if (p.friction != 0.0)
        throw InvalidParameter("friction", "0 on a viscoelastic layer (not yet)",
                               "friction: a viscoelastic layer is solved frictionless (friction "
                               "= 0) so far; given friction = " +
                                   std::to_string(p.friction));
      // A smooth punch with bounded ends (the memory's moments against the
      // U-series) or a flat face (against its T-series); on a rounded flat
      // the pressure did not converge (its estimate 3e-3 at N = 512 after
      // 25 s at deborah 1e-12, where the elastic layer's kinks converge:
      // the kinks with the memory are not resolved yet).
      const ProfileKind kind = p.punch().kind();
      if (kind == ProfileKind::rounded_flat)
        throw InvalidParameter(
            "profile", "a cylinder, a flat punch or a convex table on a viscoelastic layer",
            "profile: a " + std::string(profile_kind_name(kind)) +
                " punch on a viscoelastic layer is not solved yet (the memory at the face's "
                "kinks is not resolved); a cylinder, a flat punch or a convex table is; given "
                "the " +
                p.punch().describe());
    }
    validate_scalars(r, visco);
    return;
  }
  validate_scalars(p, false);
}

namespace {
void validate_scalars(const AsymmetricParams& p, bool material_dissipates) {
  require_in_range("vstar", p.vstar, 0.0, 1.0, false, true);
  require_in_range("kw", p.kw, 1e-12, kInf, false, false, true);
  // The shape's parameters (the cylinder's radius, a face's half-width, a
  // table), named as the API names them; an asymmetric table needs no
  // damping or friction to be asymmetric.
  const PunchProfile prof = p.punch();
  const bool asymmetric_shape = prof.kind() == ProfileKind::table && !prof.symmetric();
  require_in_range("load", p.load, 0.0, kInf, true, true);
  require_in_range("nu", p.nu, 0.0, 0.5, false, true);
  // Real Coulomb coefficients lie below about 2; at f = 10 the trailing
  // exponent is below 0.08 (a near-jump) and larger f costs minutes.
  require_in_range("friction", p.friction, 0.0, 10.0, false, false);
  // Without friction damping = 0 is the undamped solver's (contact.hpp).
  require_in_range("damping", p.damping, 0.0, kInf,
                   !(p.friction > 0.0) && !asymmetric_shape && !material_dissipates, true);
  require_in_range("kp", p.kp, 0.0, kMaxKp, false, false);
  require_in_range("tol", p.tol, 1e-14, 1e-2, false, false);
  if (p.n != 0 && (p.n < 2 || p.n > 1024 || p.n % 2 != 0))
    throw InvalidParameter(
        "n", "0 (automatic) or an even integer in [2, 1024]",
        "n must be 0 (automatic) or an even integer in [2, 1024], got " + std::to_string(p.n));
}
}  // namespace

// ---------------------------------------------------------------------------
// Refinement estimates and series scans

double algebraic_error(int n0, int n1, int n2, double d1, double d2) {
  // Changes that do not shrink: no rate to read (the caller's geometric
  // reading, its q capped at 0.99, stands).
  if (!(d2 > 0.0) || !(d1 > d2)) return 0.0;
  // d1/d2 = (n0^-p - n1^-p)/(n1^-p - n2^-p) = (t0^p - 1)/(1 - t2^p), which
  // grows with p; p by bisection in [1/2, 64] (below 1/2: slower than any
  // useful rate, the estimate is large; above 64: the geometric reading is
  // the larger one).
  const double t0 = static_cast<double>(n1) / n0, t2 = static_cast<double>(n1) / n2;
  const double target = d1 / d2;
  auto ratio = [&](double p) { return (std::pow(t0, p) - 1.0) / (1.0 - std::pow(t2, p)); };
  double lo = 0.5, hi = 64.0;
  if (ratio(lo) >= target) {
    hi = lo;
  } else if (ratio(hi) <= target) {
    lo = hi;
  } else {
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (ratio(mid) < target ? lo : hi) = mid;
    }
  }
  // e_{n2} = C n2^-p = d2 / ((n2/n1)^p - 1)
  return d2 / (std::pow(static_cast<double>(n2) / n1, 0.5 * (lo + hi)) - 1.0);
}

RefinementEstimate refinement_estimate(const std::vector<int>& sizes,
                                       const std::vector<double>& changes, double floor) {
  RefinementEstimate r;
  const std::size_t m = changes.size();
  if (m == 0 || sizes.size() != m + 1)
    throw std::invalid_argument("refinement_estimate: need len(sizes) = len(changes) + 1 >= 2");
  const double d = changes[m - 1];
  if (!std::isfinite(d)) {
    r.estimate = std::numeric_limits<double>::infinity();
    return r;
  }
  if (d <= 4.0 * floor) {
    r.at_floor = true;
    r.estimate = d + floor;
    return r;
  }
  if (m >= 3 && d > 0.8 * changes[m - 2] && changes[m - 2] > 0.8 * changes[m - 3]) {
    r.stagnated = true;
    r.estimate = std::max(d, changes[m - 2]) + floor;
    return r;
  }
  if (m == 1) {  // one change: the older member's error, an upper bound
    r.estimate = d + floor;
    return r;
  }
  const double dp = changes[m - 2];
  r.unconfirmed = m == 2 && d < 1e-3 * dp;
  double q = 1.0;
  if (dp > 0.0 && d < dp) {
    const double steps = static_cast<double>(sizes[m] - sizes[m - 1]) /
                         static_cast<double>(sizes[m - 1] - sizes[m - 2]);
    q = std::pow(d / dp, steps);
  }
  // e_k = d_k q/(1 - q) for x_N = x + C rho^N, q = rho^(n_k - n_{k-1}).
  q = std::min(q, 0.99);
  double e = d * q / (1.0 - q);
  if (m == 2) {
    // A single rate reading: also as algebraic convergence, x_N = x + C N^-p
    // (a profile's kinks; and an unresolved start whose first drop is the
    // steepest), and the larger of the two. A rounded flat at tol 2e-3 (the
    // honesty fuzz): changes 2.1e-5, 2.4e-8 at N = 12, 16 and an error 1.1e-9
    // at 16; the geometric reading gave 3.0e-10, the algebraic one 2.0e-9.
    e = std::max(e, algebraic_error(sizes[0], sizes[1], sizes[2], dp, d));
  }
  r.estimate = 10.0 * e + floor;
  return r;
}

LadderStop ladder_stop(double tol, const RefinementEstimate& a, double last_a, double scale_a,
                       const RefinementEstimate& b, double last_b, double scale_b) {
  if ((a.unconfirmed && !a.at_floor) || (b.unconfirmed && !b.at_floor)) return LadderStop::go_on;
  const bool ok_a = a.estimate <= tol * scale_a;
  const bool ok_b = b.estimate <= tol * scale_b;
  if (ok_a && ok_b) return LadderStop::converged;
  const double root_eps = std::sqrt(kEps);
  const bool end_a = ok_a || a.at_floor || (a.stagnated && last_a <= root_eps * scale_a);
  const bool end_b = ok_b || b.at_floor || (b.stagnated && last_b <= root_eps * scale_b);
  return end_a && end_b ? LadderStop::stalled : LadderStop::go_on;
}

namespace {
// sum b_k sin((k + 1) th) by the recurrence s_{k+1} = 2 cos(th) s_k - s_{k-1}.
double sine_series(const Eigen::VectorXd& b, double th) {
  const double c2 = 2.0 * std::cos(th);
  double sm1 = 0.0, s0 = std::sin(th), sum = 0.0;
  for (Eigen::Index k = 0; k < b.size(); ++k) {
    sum += b(k) * s0;
    const double sn = c2 * s0 - sm1;
    sm1 = s0;
    s0 = sn;
  }
  return sum;
}

// sine_series at four angles, the recurrences interleaved (each as
// sine_series', bit for bit).
void sine_series4(const Eigen::VectorXd& b, const double* th, double* out) {
  double c2[4], sm1[4], s0[4], sum[4];
  for (int q = 0; q < 4; ++q) {
    c2[q] = 2.0 * std::cos(th[q]);
    sm1[q] = 0.0;
    s0[q] = std::sin(th[q]);
    sum[q] = 0.0;
  }
  for (Eigen::Index k = 0; k < b.size(); ++k)
    for (int q = 0; q < 4; ++q) {
      sum[q] += b(k) * s0[q];
      const double sn = c2[q] * s0[q] - sm1[q];
      sm1[q] = s0[q];
      s0[q] = sn;
    }
  for (int q = 0; q < 4; ++q) out[q] = sum[q];
}
}  // namespace

namespace {
// Golden-section search for the largest f on [lo, hi] (around a sampled
// maximum), down to a bracket of tol: the larger of its last two values.
template <class F>
double golden_max(const F& f, double lo, double hi, double tol) {
  constexpr double kInvPhi = 0.6180339887498949;
  double x1 = hi - kInvPhi * (hi - lo), x2 = lo + kInvPhi * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  while (hi - lo > tol) {
    if (f1 > f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - kInvPhi * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + kInvPhi * (hi - lo);
      f2 = f(x2);
    }
  }
  return std::max(f1, f2);
}
}  // namespace

double max_abs_sine_series_long(const Eigen::VectorXd& b, int head) {
  const Eigen::Index h = std::min<Eigen::Index>(b.size(), head);
  if (h == b.size()) return max_abs_sine_series(b);
  // The head's samples (8 (h + 1) + 64 angles) locate the largest values;
  // the whole series is then sampled finely within two sample spacings of
  // the three largest.
  const Eigen::VectorXd bh = b.head(h);
  const int m = 8 * static_cast<int>(h + 1) + 64;
  std::vector<std::pair<double, int>> top;
  for (int j = 1; j < m; ++j) top.emplace_back(std::fabs(sine_series(bh, kPi * j / m)), j);
  const std::size_t keep = std::min<std::size_t>(3, top.size());
  std::partial_sort(top.begin(), top.begin() + static_cast<std::ptrdiff_t>(keep), top.end(),
                    [](const auto& x, const auto& y) { return x.first > y.first; });
  // Around each: 41 angles (a tenth of the head's spacing apart), then
  // golden-section refinement on the best one's neighbours (to 1e-9 of
  // that spacing).
  double best = 0.0, best_th = 0.0;
  constexpr int kFine = 44;  // 41 angles and three repeats of the last
  for (std::size_t t = 0; t < keep; ++t) {
    const double th0 = kPi * top[t].second / m, dth = kPi / m;
    double th[kFine], val[4];
    for (int q = 0; q < kFine; ++q)
      th[q] = std::clamp(th0 + dth * (0.1 * std::min(q, 40) - 2.0), 0.0, kPi);
    for (int q = 0; q < kFine; q += 4) {
      sine_series4(b, th + q, val);
      for (int v = 0; v < 4; ++v)
        if (std::fabs(val[v]) > best) {
          best = std::fabs(val[v]);
          best_th = th[q + v];
        }
    }
  }
  const double g = 0.1 * kPi / m;  // the fine spacing
  return std::max(best,
                  golden_max([&](double th) { return std::fabs(sine_series(b, th)); },
                             std::max(0.0, best_th - g), std::min(kPi, best_th + g), 1e-9 * g));
}

double head_sine_bound(const Eigen::VectorXd& b, int head) {
  const Eigen::Index h = std::min<Eigen::Index>(b.size(), head);
  return max_abs_sine_series(b.head(h)) + b.tail(b.size() - h).cwiseAbs().sum();
}

namespace {
// |w g| of a Jacobi series at the angles pi j/m (0 < j < m): the three
// largest, as (value, j), largest first.
std::vector<std::pair<double, int>> largest_density_samples(const JacobiSeries& js, int m) {
  std::vector<double> r(static_cast<std::size_t>(m) - 1), g(r.size());
  for (int j = 1; j < m; ++j) r[static_cast<std::size_t>(j - 1)] = std::cos(kPi * j / m);
  js.g_values(r.data(), static_cast<int>(r.size()), g.data());
  std::vector<std::pair<double, int>> top;
  for (std::size_t i = 0; i < r.size(); ++i)
    top.emplace_back(std::fabs(js.weight(r[i]) * g[i]), static_cast<int>(i) + 1);
  const std::size_t keep = std::min<std::size_t>(3, top.size());
  std::partial_sort(top.begin(), top.begin() + static_cast<std::ptrdiff_t>(keep), top.end(),
                    [](const auto& x, const auto& y) { return x.first > y.first; });
  top.resize(keep);
  return top;
}

// max |w g| of a series whose terms are all of high degree (a tail block):
// sampled at about two angles per degree (four per oscillation), the three
// largest samples refined on 41-point grids spanning a sample spacing on
// either side.
double max_abs_density_coarse(const JacobiSeries& js) {
  const int m = 2 * (js.size() + 1) + 64;
  const std::vector<std::pair<double, int>> top = largest_density_samples(js, m);
  const std::size_t keep = top.size();
  double best = keep ? top.front().first : 0.0;
  std::vector<double> fine;
  for (std::size_t t = 0; t < keep; ++t) {
    const double th0 = kPi * top[t].second / m, dth = kPi / m;
    for (int q = 0; q <= 40; ++q)
      fine.push_back(std::cos(std::clamp(th0 + dth * (q / 20.0 - 1.0), 0.0, kPi)));
  }
  std::vector<double> gf(fine.size());
  js.g_values(fine.data(), static_cast<int>(fine.size()), gf.data());
  for (std::size_t i = 0; i < fine.size(); ++i)
    best = std::max(best, std::fabs(js.weight(fine[i]) * gf[i]));
  return best;
}
}  // namespace

double max_abs_density_long(const JacobiSeries& js, int head) {
  const Eigen::Index h = std::min<Eigen::Index>(js.size(), head);
  if (h == js.size()) return js.max_abs_density();
  // As max_abs_sine_series_long: the head's samples locate the three largest
  // values, the whole series is sampled within two sample spacings of each.
  const JacobiSeries hs(js.alpha(), js.beta(), js.coefficients().head(h));
  const int m = 8 * static_cast<int>(h + 1) + 64;
  const std::vector<std::pair<double, int>> top = largest_density_samples(hs, m);
  const std::size_t keep = top.size();
  // Around each: 41 angles (a tenth of the head's spacing apart), then
  // golden-section refinement on the best one's neighbours (to 1e-9 of that
  // spacing), as max_abs_sine_series_long.
  std::vector<double> fine_th, fine;
  for (std::size_t t = 0; t < keep; ++t) {
    const double th0 = kPi * top[t].second / m, dth = kPi / m;
    for (int q = 0; q <= 40; ++q) {
      fine_th.push_back(std::clamp(th0 + dth * (0.1 * q - 2.0), 0.0, kPi));
      fine.push_back(std::cos(fine_th.back()));
    }
  }
  std::vector<double> gf(fine.size());
  js.g_values(fine.data(), static_cast<int>(fine.size()), gf.data());
  double best = 0.0, best_th = 0.0;
  for (std::size_t i = 0; i < fine.size(); ++i) {
    const double v = std::fabs(js.weight(fine[i]) * gf[i]);
    if (v > best) {
      best = v;
      best_th = fine_th[i];
    }
  }
  const double g = 0.1 * kPi / m;  // the fine spacing
  return std::max(best,
                  golden_max([&](double th) { return std::fabs(js.density(std::cos(th))); },
                             std::max(0.0, best_th - g), std::min(kPi, best_th + g), 1e-9 * g));
}

double max_abs_sine_series(const Eigen::VectorXd& b) {
  const Eigen::Index n = b.size();
  const int m = 8 * static_cast<int>(n + 1) + 64;
  double best = 0.0;
  // sum b_k sin((k+1) th) by the recurrence s_{k+1} = 2 cos(th) s_k - s_{k-1}
  // (sine_series), four angles at a time.
  int j = 1;
  for (; j + 4 <= m; j += 4) {
    const double th[4] = {kPi * j / m, kPi * (j + 1) / m, kPi * (j + 2) / m, kPi * (j + 3) / m};
    double val[4];
    sine_series4(b, th, val);
    for (double v : val) best = std::max(best, std::fabs(v));
  }
  for (; j < m; ++j) best = std::max(best, std::fabs(sine_series(b, kPi * j / m)));
  return best;
}

// ---------------------------------------------------------------------------
// The contact solve

namespace {

struct WidthEval {
  double lambda = 0;  // the load R P/(mu h^2) this half-width carries (a profile's: P)
  double centre = 0;  // the centre c of the contact
  Eigen::VectorXd G;  // unit solution; g = gscale G
  double gscale = 0;  // -(w/(phi1 lambda)) (a profile's: -1/(phi1 P))
};

// For a trial half-width w the collocation system with the centre as the
// extra unknown is square and linear:
//   sum_i W_i G_i [1/(r_i - s_k) - w K(w (s_k - r_i))] + gamma = s_k  (k = 1..N+1),
// g = -(w/(phi1 lambda)) G and c = -w gamma; equilibrium gives lambda(w).
// The (N + 1) x (N + 1) collocation matrix for a trial half-width w:
// W_i [1/(r_i - s_k) - w K(w (s_k - r_i))] and the centre unknown's column of ones.
Eigen::MatrixXd collocation_matrix(const ChebyshevNodes& nd, double w, const AsymmetricKernel& K) {
  const int n = nd.n;
  Eigen::MatrixXd M(n + 1, n + 1);
  // Column-major: the kernel's values column by column, in one batch.
  thread_local std::vector<double> u, kv;
  u.resize(static_cast<std::size_t>(n) * (n + 1));
  kv.resize(u.size());
  for (int i = 0; i < n; ++i)
    for (int k = 0; k <= n; ++k)
      u[static_cast<std::size_t>(i) * (n + 1) + k] = -w * (nd.r(i) - nd.s(k));
  K.many(u.data(), kv.data(), u.size());
  for (int i = 0; i < n; ++i)
    for (int k = 0; k <= n; ++k) {
      const double d = nd.r(i) - nd.s(k);
      M(k, i) = nd.w(i) * (1.0 / d - w * kv[static_cast<std::size_t>(i) * (n + 1) + k]);
    }
  // A viscoelastic top's memory, integrated exactly against the density.
  if (const MemoryKernel* mem = K.model().memory()) M.leftCols(n) += mem->collocation_block(nd, w);
  M.col(n).setOnes();
  return M;
}

WidthEval eval_width(const ChebyshevNodes& nd, double w, const AsymmetricKernel& K, double phi1) {
  const int n = nd.n;
  const Eigen::MatrixXd M = collocation_matrix(nd, w, K);
  const Eigen::VectorXd x = M.partialPivLu().solve(nd.s);
  WidthEval e;
  e.G = x.head(n);
  e.centre = -w * x(n);
  e.lambda = -kPi * w * w * nd.w.dot(e.G) / phi1;
  e.gscale = -(w / (phi1 * e.lambda));
  return e;
}

struct WidthSolve {
  double w = 0, c = 0;
  Eigen::VectorXd g;
  int evaluations = 0;
};

// The root of ln lambda(w) = ln lambda_t in ln w: a bracket by steps of 0.4
// from the guess (lambda grows with w), then the shared bracketed root
// (roots.hpp), and the solution at the root.
// The root variable is ln(w - w0) (w0 = 0, or a rounded flat's face: its
// load grows like (w - b)^(3/2)), on w0 + [kMinA, wmax - w0]; eval(w) is the
// width's WidthEval (its lambda compared with lambda_t), n the size (messages).
template <class Eval>
WidthSolve solve_width(int n, double lambda_t, double w_guess, double w0, double wmax,
                       Eval&& eval) {
  WidthSolve out;
  auto F = [&](double lw, WidthEval& e) {
    const double w = w0 + std::exp(lw);
    e = eval(w);
    ++out.evaluations;
    if (!(e.lambda > 0.0) || !std::isfinite(e.lambda)) return std::nan("");
    return std::log(e.lambda) - std::log(lambda_t);
  };
  const double lmin = std::log(detail::kMinA), lmax = std::log(wmax - w0);
  double x0 = std::clamp(std::log(std::max(w_guess - w0, detail::kMinA)), lmin, lmax);
  WidthEval e;
  double f0 = F(x0, e);
  // A wide first guess can be under-resolved at this N (no positive load):
  // step down towards narrower contacts.
  for (int k = 0; k < 24 && std::isnan(f0) && x0 > lmin; ++k) {
    x0 = std::max(lmin, x0 - 0.7);
    f0 = F(x0, e);
  }
  if (std::isnan(f0))
    throw ConvergenceError(
        "damped contact: the collocation system gives no positive load at "
        "any trial width (N = " +
        std::to_string(n) + ")");
  // Bracket: lambda grows with w. A trial width at round-off distance from
  // the root (|F| <= xftol: the guess, a coarser size's root, often is) is
  // the root.
  constexpr double xftol = 1e-15;
  double last = x0;  // where e was evaluated
  auto finish = [&](double x) {
    out.w = w0 + std::exp(x);
    out.c = e.centre;
    out.g = e.gscale * e.G;
    return out;
  };
  if (std::fabs(f0) <= xftol) return finish(x0);
  // The first step 0.75 |F| (ln lambda grows at least like 1.33 ln w for
  // every punch but a wedge-like table: a cylinder's Hertz contact like 2 ln w,
  // stiffer media faster), so from a coarser size's root (|F| ~ its change)
  // the bracket is about that tight; each step that does not straddle the
  // root is 4 times the last, up to 0.4.
  const double dir = f0 > 0.0 ? -1.0 : 1.0;
  double step = std::min(0.4, 0.75 * std::fabs(f0));
  double x1 = x0, f1 = f0;
  for (int it = 0; it < 80; ++it, step = std::min(0.4, 4.0 * step)) {
    x1 = std::clamp(x0 + dir * step, lmin, lmax);
    f1 = F(x1, e);
    last = x1;
    // No load at x1: a table's contact cannot be that wide where it must be
    // centred (its centres' range shrinks as it widens), or the size is too
    // coarse. Halve the step while the load stays of f0's sign: the root may
    // lie before the trial contact leaves the table (8 halvings: to 0.2 % of
    // the width; a refusal stays cheap).
    for (int h = 0; h < 8 && std::isnan(f1); ++h) {
      const double xm = 0.5 * (x0 + x1);
      if (xm == x0 || xm == x1) break;
      WidthEval em;
      const double fm = F(xm, em);
      last = xm;
      if (std::isnan(fm)) {
        x1 = xm;
      } else if ((fm > 0.0) != (f0 > 0.0) || std::fabs(fm) <= xftol) {
        x1 = xm;
        f1 = fm;
        e = em;
      } else {
        x0 = xm;
        f0 = fm;
        e = em;
      }
    }
    if (std::isnan(f1))
      throw ConvergenceError("damped contact: non-positive load while bracketing");
    if (std::fabs(f1) <= xftol) return finish(x1);
    if ((f1 > 0.0) != (f0 > 0.0)) break;
    if (x1 == lmin || x1 == lmax) {
      // At this N the width leaves the supported range (the caller refines N).
      throw ConvergenceError("damped contact: the contact width leaves the supported range " +
                             detail::supported_range_text() + " at N = " + std::to_string(n));
    }
    x0 = x1;
    f0 = f1;
  }
  if ((f1 > 0.0) == (f0 > 0.0)) throw ConvergenceError("damped contact: no bracket found");
  auto f = [&](double lw) {
    const double v = F(lw, e);
    last = lw;
    if (std::isnan(v)) throw ConvergenceError("damped contact: non-positive load in the iteration");
    return v;
  };
  // To |F| <= xftol (round-off) or a bracket of xftol.
  constexpr auto kSafeguard = detail::Safeguard::kSecant;
  const double x = x0 < x1
                       ? detail::bracketed_root(f, x0, x1, f0, f1, xftol, 200, xftol, kSafeguard)
                       : detail::bracketed_root(f, x1, x0, f1, f0, xftol, 200, xftol, kSafeguard);
  if (!(last == x)) f(x);  // the solution at the root
  return finish(x);
}

// The points of the scan for other steady states on [lo, hi] in ln w: the
// ends and, between them, the lattice i kScanStep (fixed, so that the solves
// of a load sweep share their points; a gap is at most kScanStep). When an
// end is clamped to the supported widths (hi - lo < ln 32) the interval is
// shorter: 49 equal steps, finer than the lattice.
constexpr int kScanSteps = 48;
const double kScanStep = std::log(32.0) / kScanSteps;

std::vector<double> scan_points(double lo, double hi) {
  std::vector<double> xs;
  if (hi - lo < std::log(32.0) * (1.0 - 1e-12)) {
    for (int i = 0; i <= kScanSteps; ++i) xs.push_back(lo + (hi - lo) * i / kScanSteps);
    return xs;
  }
  xs.push_back(lo);
  for (double k = std::floor(lo / kScanStep) + 1.0; k * kScanStep < hi; k += 1.0)
    if (k * kScanStep > lo) xs.push_back(k * kScanStep);
  xs.push_back(hi);
  return xs;
}

// lambda(w) at the lattice points of the scan, memoised per kernel table and
// collocation size (lambda depends on nothing else, not on the load): the
// solves of a load sweep, or a warm solve, share one scan. The ends of a
// scan are computed afresh. Entries of tables no longer alive are dropped.
class ScanMemo {
 public:
  // lambda at the scan's points xs (ln w): from the memo where a lattice
  // point was computed before for this kernel table, shape and size, else by
  // eval(w) (NaN for a width it does not take). `shape` names the punch's
  // shape exactly (empty for the cylinder, whose lambda = R P needs none).
  static std::vector<double> lambdas(const std::shared_ptr<const AsymmetricKernel>& K,
                                     const std::vector<double>& shape, int n,
                                     const std::vector<double>& xs,
                                     const std::function<double(double)>& eval) {
    static ScanMemo memo;
    std::vector<double> out(xs.size(), std::nan(""));
    std::vector<long> keys(xs.size(), kNoKey);
    std::vector<char> known(xs.size(), 0);
    for (std::size_t i = 1; i + 1 < xs.size(); ++i) {
      const double k = std::round(xs[i] / kScanStep);
      if (static_cast<double>(k) * kScanStep == xs[i]) keys[i] = static_cast<long>(k);
    }
    {
      const std::lock_guard<std::mutex> lock(memo.mutex_);
      const auto& values = memo.entry(K, shape);
      for (std::size_t i = 0; i < xs.size(); ++i) {
        const auto it = keys[i] == kNoKey ? values.end() : values.find({n, keys[i]});
        if (it != values.end()) {
          out[i] = it->second;
          known[i] = 1;
        }
      }
    }
    std::vector<std::pair<std::pair<int, long>, double>> fresh;
    for (std::size_t i = 0; i < xs.size(); ++i) {
      if (known[i]) continue;
      out[i] = eval(std::exp(xs[i]));
      if (keys[i] != kNoKey) fresh.push_back({{n, keys[i]}, out[i]});
    }
    if (!fresh.empty()) {
      const std::lock_guard<std::mutex> lock(memo.mutex_);
      auto& values = memo.entry(K, shape);
      for (const auto& kv : fresh) values.insert(kv);
    }
    return out;
  }

 private:
  static constexpr long kNoKey = std::numeric_limits<long>::min();
  static constexpr std::size_t kShapes = 32;  // per table: a sweep over shapes
  using Values = std::map<std::pair<int, long>, double>;
  struct Entry {
    std::weak_ptr<const AsymmetricKernel> table;
    const AsymmetricKernel* raw = nullptr;
    std::map<std::vector<double>, Values> shapes;
  };
  std::mutex mutex_;
  std::vector<Entry> entries_;
  // The values of the live table K and this shape (mutex_ held).
  Values& entry(const std::shared_ptr<const AsymmetricKernel>& K,
                const std::vector<double>& shape) {
    entries_.erase(std::remove_if(entries_.begin(), entries_.end(),
                                  [](const Entry& e) { return e.table.expired(); }),
                   entries_.end());
    Entry* found = nullptr;
    for (Entry& e : entries_)
      if (e.raw == K.get()) found = &e;
    if (!found) {
      entries_.push_back({K, K.get(), {}});
      found = &entries_.back();
    }
    if (found->shapes.size() >= kShapes && !found->shapes.count(shape)) found->shapes.clear();
    return found->shapes[shape];
  }
};

// The exact name of a punch's shape for ScanMemo (kind, radius, face, and a
// table's points).
std::vector<double> shape_key(const AsymmetricParams& prm) {
  std::vector<double> key{static_cast<double>(static_cast<int>(prm.profile)), prm.radius,
                          prm.half_width};
  if (prm.profile == ProfileKind::table) {
    key.insert(key.end(), prm.table_x.begin(), prm.table_x.end());
    key.insert(key.end(), prm.table_y.begin(), prm.table_y.end());
  }
  return key;
}

// ---------------------------------------------------------------------------
// A punch profile's slope on the asymmetric solver (docs/theory.md section
// 13, "Profiles on the asymmetric solver"). The collocation system's
// half-plane part maps the density's N-term series onto the first N + 1
// functions Q_m of the collocation points' family (T_m without friction,
// P_m^(-alpha, -beta) with it; Q_0 is the centre unknown's constant), so the
// slope is collocated through its projection onto Q_0 .. Q_N: exact for the
// half-plane part even where the slope has a kink (a rounded flat's face
// ends), whose point values would alias the projection's slowly decaying
// tail onto the load.

// Gauss-Jacobi rules, cached by (n, a, b) (the projections reuse a few).
std::shared_ptr<const JacobiRule> cached_rule(int n, double a, double b) {
  return cached_gauss_jacobi(n, a, b);
}

// The nodes s and weights of a quadrature of int_{-1}^{1} F(s) (1 - s)^a (1 + s)^b ds
// for F smooth between the profile's kinks at x = c + w s: pieces between
// them, each end's singular weight by its own Gauss-Jacobi rule of M nodes
// (the other factor by value), interior pieces by Gauss-Legendre.
template <class Add>
void weighted_nodes(const PunchProfile& prof, double c, double w, double a, double b, int M,
                    Add&& add) {
  std::vector<double> edges{-1.0};
  for (double x : prof.kinks()) {
    const double s = (x - c) / w;
    if (s > -1.0 && s < 1.0) edges.push_back(s);
  }
  edges.push_back(1.0);
  std::sort(edges.begin(), edges.end());
  for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
    const double lo = edges[k], hi = edges[k + 1];
    if (!(hi - lo > 1e-15)) continue;
    const bool left = lo == -1.0, right = hi == 1.0;
    const auto held = cached_rule(M, right ? a : 0.0, left ? b : 0.0);
    const JacobiRule& rule = *held;
    const double half = 0.5 * (hi - lo);
    for (Eigen::Index i = 0; i < rule.x.size(); ++i) {
      const double s = lo + half * (1.0 + rule.x(i));
      double wt = rule.w(i) * half;
      wt *= right ? std::pow(half, a) : std::pow(1.0 - s, a);
      wt *= left ? std::pow(half, b) : std::pow(1.0 + s, b);
      add(s, wt);
    }
  }
}

// The rounded flat's slope (zero on the face |x| <= b, (|x| - b)/R sgn x
// beyond) on (c - w, c + w) against P_m^(a, b) and its weight: int
// f'(c + w s) (1 - s)^a (1 + s)^b P_m(s) ds, m < count, in closed form (the
// slope is linear on each piece: jacobi_upper_moments, jacobi_lower_moments).
std::vector<double> rounded_flat_moments(const PunchProfile& prof, double c, double w, double a,
                                         double b, int count) {
  std::vector<double> out(static_cast<std::size_t>(std::max(count, 0)), 0.0);
  if (count <= 0) return out;
  const double face = prof.face(), inv_r = 1.0 / prof.radius();
  const double s_right = (face - c) / w, s_left = (-face - c) / w;
  if (s_right < 1.0) {  // x > b: f' = (x - b)/R = ((c - b) + w s)/R
    const JacobiMoments m = jacobi_upper_moments(a, b, s_right, count);
    for (std::size_t k = 0; k < out.size(); ++k)
      out[k] += ((c - face) * m.I[k] + w * m.J[k]) * inv_r;
  }
  if (s_left > -1.0) {  // x < -b: f' = (x + b)/R
    const JacobiMoments m = jacobi_lower_moments(a, b, s_left, count);
    for (std::size_t k = 0; k < out.size(); ++k)
      out[k] += ((c + face) * m.I[k] + w * m.J[k]) * inv_r;
  }
  return out;
}

class SlopeProjection {
 public:
  // Without friction (jacobi false) the T_m; with it P_m^(a, b), (a, b) =
  // (-alpha, -beta) of the density's exponents (alpha at the leading end).
  SlopeProjection(const PunchProfile& prof, bool jacobi, double alpha)
      : prof_(prof), jacobi_(jacobi), a_(-alpha), b_(alpha - 1.0) {}

  bool jacobi() const noexcept { return jacobi_; }
  // A table's Jacobi projection uses fixed nodes: q_m = sum_j A_jm f'(c + w s_j)
  // (its T projection is exact, PunchProfile::slope_chebyshev_at).
  bool nodal() const noexcept { return jacobi_ && prof_.kind() == ProfileKind::table; }
  // For a table and the functional zeta . q: the offsets w s_j and the
  // weights Z_j = sum_m A_jm zeta_m, so that zeta . q(c) = sum_j Z_j f'(c + w s_j)
  // (the same Gauss-Jacobi nodes as coefficients()).
  void nodal_functional(const Eigen::VectorXd& zeta, double w, std::vector<double>& xs,
                        std::vector<double>& zw) const {
    const int count = static_cast<int>(zeta.size());
    const NodalBasis& nb = nodal_basis(count);
    const Eigen::VectorXd z = nb.P.topRows(count).transpose() * zeta;
    xs.resize(nb.s.size());
    zw.resize(nb.s.size());
    for (std::size_t j = 0; j < nb.s.size(); ++j) {
      xs[j] = w * nb.s[j];
      zw[j] = z(static_cast<Eigen::Index>(j));
    }
  }
  double a() const noexcept { return a_; }
  double b() const noexcept { return b_; }

  // Q_0(s) .. Q_{count-1}(s).
  void basis(double s, int count, double* out) const {
    if (count <= 0) return;
    if (!jacobi_) {
      double prev = 1.0, cur = s;
      out[0] = 1.0;
      for (int m = 1; m < count; ++m) {
        out[m] = cur;
        const double next = 2.0 * s * cur - prev;
        prev = cur;
        cur = next;
      }
      return;
    }
    out[0] = 1.0;
    if (count == 1) return;
    const double a = a_, b = b_;
    out[1] = (a + 1.0) + (a + b + 2.0) * (s - 1.0) / 2.0;
    for (int n = 2; n < count; ++n) {
      const double nn = n, ab = a + b, c2 = 2.0 * nn + ab;
      const double A = 2.0 * nn * (nn + ab) * (c2 - 2.0);
      const double B = (c2 - 1.0) * (c2 * (c2 - 2.0) * s + a * a - b * b);
      const double C = 2.0 * (nn + a - 1.0) * (nn + b - 1.0) * c2;
      out[n] = (B * out[n - 1] - C * out[n - 2]) / A;
    }
  }

  // The slope's coefficients q_0 .. q_{count-1} on (c - w, c + w):
  // f'(c + w s) ~ sum q_m Q_m(s). Throws std::domain_error when the
  // contact leaves a table.
  std::vector<double> coefficients(double c, double w, int count) const {
    if (!jacobi_) {
      std::vector<double> d = prof_.slope_chebyshev_at(c, w, count);
      if (!d.empty()) d[0] *= 0.5;
      return d;
    }
    if (prof_.kind() == ProfileKind::rounded_flat) {
      std::vector<double> q = rounded_flat_moments(prof_, c, w, a_, b_, count);
      for (int m = 0; m < count; ++m) q[static_cast<std::size_t>(m)] /= jacobi_norm(m, a_, b_);
      return q;
    }
    if (prof_.kind() == ProfileKind::table) {  // q = B f'(c + w s_j) (nodal_basis)
      const NodalBasis& nb = nodal_basis(count);
      std::vector<double> xs(nb.s.size()), fs(nb.s.size());
      for (std::size_t j = 0; j < xs.size(); ++j) xs[j] = c + w * nb.s[j];
      prof_.slopes(xs.data(), static_cast<int>(xs.size()), fs.data());
      const Eigen::VectorXd q =
          nb.P.topRows(count) * Eigen::Map<const Eigen::VectorXd>(fs.data(), nb.P.cols());
      return std::vector<double>(q.data(), q.data() + count);
    }
    std::vector<double> q(static_cast<std::size_t>(count), 0.0);
    std::vector<double> P(static_cast<std::size_t>(count));
    const int M = 2 * count + 64;
    weighted_nodes(prof_, c, w, a_, b_, M, [&](double s, double weight) {
      const double fs = prof_.slope(c + w * s) * weight;
      if (fs == 0.0) return;
      basis(s, count, P.data());
      for (int m = 0; m < count; ++m) q[static_cast<std::size_t>(m)] += fs * P[m];
    });
    const std::vector<double>& h = norms(count);
    for (int m = 0; m < count; ++m)
      q[static_cast<std::size_t>(m)] /= h[static_cast<std::size_t>(m)];
    return q;
  }

 private:
  const PunchProfile& prof_;
  bool jacobi_;
  double a_, b_;
  mutable std::vector<double> norms_;
  // A table's projection by the Gauss-Jacobi rule of M = max(16 count + 64,
  // 2048) nodes s_j on the whole contact (a table has no kinks): the matrix
  // B_mj = w_j Q_m(s_j)/h_m, so that each projection is one matrix-vector
  // product (it ran the recurrence of Q_m at every node). Kept between
  // solves for the two most recent (M, exponents) (a load sweep's; a ladder's
  // sizes share M = 2048, each M's matrix grown to the largest count asked).
  struct NodalBasis {
    std::vector<double> s;
    Eigen::MatrixXd P;
  };
  mutable std::map<int, std::shared_ptr<const NodalBasis>> nodal_;
  const NodalBasis& nodal_basis(int count) const {
    const int M = std::max(16 * count + 64, 2048);
    std::shared_ptr<const NodalBasis>& mine = nodal_[M];
    if (mine && mine->P.rows() >= count) return *mine;
    using Key = std::tuple<int, double, double>;
    static std::mutex mu;
    static std::list<std::pair<Key, std::shared_ptr<const NodalBasis>>> kept;
    const Key key{M, a_, b_};
    {
      const std::lock_guard<std::mutex> lock(mu);
      for (const auto& [k, nb] : kept)
        if (k == key && nb->P.rows() >= count) return *(mine = nb);
    }
    // (At least 64 rows, or as many as share this M: a ladder grows once.)
    const int rows = std::max(count, std::min(64, (M - 64) / 16));
    auto nb = std::make_shared<NodalBasis>();
    const auto held = cached_rule(M, a_, b_);
    const JacobiRule& rule = *held;
    const std::vector<double>& h = norms(rows);
    nb->s.assign(rule.x.data(), rule.x.data() + rule.x.size());
    nb->P.resize(rows, rule.x.size());
    std::vector<double> P(static_cast<std::size_t>(rows));
    for (Eigen::Index j = 0; j < rule.x.size(); ++j) {
      basis(rule.x(j), rows, P.data());
      for (int m = 0; m < rows; ++m)
        nb->P(m, j) = rule.w(j) * P[static_cast<std::size_t>(m)] / h[static_cast<std::size_t>(m)];
    }
    mine = nb;
    const std::lock_guard<std::mutex> lock(mu);
    kept.remove_if([&](const auto& e) { return e.first == key; });
    kept.emplace_front(key, mine);
    if (kept.size() > 2) kept.pop_back();
    return *mine;
  }
  // h_m = int Q_m^2 (1 - s)^a (1 + s)^b ds by a rule exact for them.
  const std::vector<double>& norms(int count) const {
    if (static_cast<int>(norms_.size()) >= count) return norms_;
    if (jacobi_) {
      norms_.resize(static_cast<std::size_t>(count));
      for (int m = 0; m < count; ++m) norms_[static_cast<std::size_t>(m)] = jacobi_norm(m, a_, b_);
      return norms_;
    }
    const auto held = cached_rule(count + 2, a_, b_);
    const JacobiRule& rule = *held;
    norms_.assign(static_cast<std::size_t>(count), 0.0);
    std::vector<double> P(static_cast<std::size_t>(count));
    for (Eigen::Index i = 0; i < rule.x.size(); ++i) {
      basis(rule.x(i), count, P.data());
      for (int m = 0; m < count; ++m)
        norms_[static_cast<std::size_t>(m)] += rule.w(i) * P[m] * P[m];
    }
    return norms_;
  }
};

// For a trial half-width w under a profile's slope: the collocation matrix
// (as eval_width's) factored once; the centre c solves the consistency
// condition gamma(c) = 0, gamma the centre unknown of M [G; gamma] = B q(c)
// (B: Q_m at the collocation points), i.e. z . B q(c) with z the last row of
// M^-1; then the load P(w) = -pi w W . G/phi1 and g = -G/(phi1 P).
WidthEval eval_width_profile(const ChebyshevNodes& nd, double w, const AsymmetricKernel& K,
                             double phi1, const SlopeProjection& proj, const PunchProfile& prof,
                             double c_guess) {
  const int n = nd.n;
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(collocation_matrix(nd, w, K));
  Eigen::MatrixXd B(n + 1, n + 1);
  std::vector<double> row(static_cast<std::size_t>(n + 1));
  for (int k = 0; k <= n; ++k) {
    proj.basis(nd.s(k), n + 1, row.data());
    for (int m = 0; m <= n; ++m) B(k, m) = row[static_cast<std::size_t>(m)];
  }
  const Eigen::VectorXd z = lu.transpose().solve(Eigen::VectorXd::Unit(n + 1, n));
  const Eigen::VectorXd zeta = B.transpose() * z;
  // gamma(c) = sum_m zeta_m q_m(c): for a table, whose projection's nodes do
  // not move with c, as sum_j Z_j f'(c + w s_j) with Z = A zeta once per width.
  std::vector<double> zs, zw;
  if (proj.nodal()) proj.nodal_functional(zeta, w, zs, zw);
  std::vector<double> xs(zs.size()), fs(zs.size());
  auto gamma = [&](double c) {
    if (proj.nodal()) {
      for (std::size_t j = 0; j < zs.size(); ++j) xs[j] = c + zs[j];
      prof.slopes(xs.data(), static_cast<int>(xs.size()), fs.data());
      double sum = 0.0;
      for (std::size_t j = 0; j < zs.size(); ++j) sum += zw[j] * fs[j];
      return sum;
    }
    const std::vector<double> q = proj.coefficients(c, w, n + 1);
    return zeta.dot(Eigen::Map<const Eigen::VectorXd>(q.data(), n + 1));
  };
  WidthEval e;
  e.lambda = std::nan("");
  // The centres whose contact stays within a table.
  const double clo = prof.lower() + w, chi = prof.upper() - w;
  if (!(clo <= chi)) return e;
  double c0 = std::clamp(c_guess, clo, chi);
  double g0 = gamma(c0);
  if (!std::isfinite(g0)) return e;
  double c1 = c0, g1 = g0;
  double step = 0.05 * w;
  bool found = g0 == 0.0;
  // Expand towards the sign change (gamma grows with c for a convex profile;
  // both directions are tried).
  for (int dir : {g0 > 0.0 ? -1 : 1, g0 > 0.0 ? 1 : -1}) {
    if (found) break;
    double a0 = c0, fa = g0, st = step;
    for (int it = 0; it < 60; ++it) {
      const double cn = std::clamp(a0 + dir * st, clo, chi);
      const double gn = gamma(cn);
      if (!std::isfinite(gn)) break;
      if ((gn > 0.0) != (fa > 0.0) || gn == 0.0) {
        c0 = a0;
        g0 = fa;
        c1 = cn;
        g1 = gn;
        found = true;
        break;
      }
      if (cn == clo || cn == chi) break;
      a0 = cn;
      fa = gn;
      st *= 2.0;
    }
  }
  if (!found) return e;
  double c = c1;
  if (g1 != 0.0 && g0 != 0.0) {
    const double lo = std::min(c0, c1), hi = std::max(c0, c1);
    const double flo = lo == c0 ? g0 : g1, fhi = lo == c0 ? g1 : g0;
    c = detail::bracketed_root(gamma, lo, hi, flo, fhi, 1e-15 * (w + std::fabs(c0)), 200, 0.0,
                               detail::Safeguard::kStalledBracket);
  } else if (g0 == 0.0) {
    c = c0;
  }
  const std::vector<double> q = proj.coefficients(c, w, n + 1);
  const Eigen::VectorXd rhs = B * Eigen::Map<const Eigen::VectorXd>(q.data(), n + 1);
  const Eigen::VectorXd x = lu.solve(rhs);
  e.G = x.head(n);
  e.centre = c;
  e.lambda = -kPi * w * nd.w.dot(e.G) / phi1;
  e.gscale = -1.0 / (phi1 * e.lambda);
  return e;
}

}  // namespace

AsymmetricSolution solve_asymmetric(const AsymmetricParams& prm_in) {
  // The flat punch (index +1, no width iteration): asymmetric_flat.cpp.
  if (prm_in.profile == ProfileKind::flat) return solve_asymmetric_flat(prm_in);
  const auto t0 = std::chrono::steady_clock::now();
  validate(prm_in);
  // kw, nu, kp, damping: the medium's own (nu: the top sublayer's).
  const AsymmetricParams prm = with_medium_scalars(prm_in);
  const bool homogeneous = !prm.medium || prm.medium->homogeneous();
  AsymmetricSolution s;
  s.params_ = prm;
  s.vr_ = rayleigh_vstar(prm.nu);
  s.vcr_ = critical_vstar_of(prm);
  auto since_start = [&t0] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  const double t_critical = since_start();
  require_steady_speed(prm, s.vcr_, s.vr_);
  const WaveConstants wc = wave_constants(prm.vstar, prm.nu);
  const double phi1 = cauchy_phi1_of(prm);
  // Friction: Gauss-Jacobi collocation with the end exponents of
  // cot(pi back) = f Phi (docs/theory.md section 14); none: Gauss-Chebyshev.
  const bool frictional = prm.friction > 0.0;
  if (frictional) s.exps_ = end_exponents(prm.friction, tangential_half_plane(wc).Phi);
  auto nodes_of = [&](int n) {
    return frictional ? jacobi_collocation_nodes(n, s.exps_.front) : chebyshev_nodes(n);
  };
  // The kernel table, fetched from the process-wide cache (or built) for the
  // widths the solve needs: |u| <= 2w for a trial half-width w, 8 w_final for
  // the scan of lambda(w) on [w/8, 4w], 4 w_final for the gap. Twice the need
  // when built: a slightly wider contact (the next point of a sweep) reuses it.
  std::shared_ptr<const AsymmetricKernel> kern;
  std::shared_ptr<const Medium> medium;
  double kernel_seconds = 0.0;
  auto kernel = [&](double need) -> const AsymmetricKernel& {
    if (!kern || kern->range() < need) {
      const auto tk = std::chrono::steady_clock::now();
      bool built = false;
      if (!medium) medium = cached_medium(medium_of(prm), prm.vstar);
      kern = cached_damped_kernel(medium, need, 2.0 * need, &built, prm.friction);
      s.kernel_builds_ += built ? 1 : 0;
      kernel_seconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - tk).count();
    }
    return *kern;
  };

  // The punch: the cylinder keeps its own path (the centre absorbed by the
  // constant unknown, lambda = R P); any other bounded profile collocates its
  // slope's projection and finds the centre per width (eval_width_profile).
  const PunchProfile prof = prm.punch();
  s.punch_ = std::make_shared<const PunchProfile>(prof);
  const bool cylinder = prof.kind() == ProfileKind::cylinder;
  const SlopeProjection proj(*s.punch_, frictional, s.exps_.front);
  // A rounded flat's width runs on ln(w - b); every width within the table.
  const double w0 = prof.kind() == ProfileKind::rounded_flat ? prof.face() : 0.0;
  const double wmax = std::min(detail::kMaxA, 0.5 * (prof.upper() - prof.lower()));
  const double lambda = cylinder ? prm.radius * prm.load : prm.load;
  // The first width guess (solve_skeleton.hpp). A load that a half-plane
  // carries on less than twice the smallest supported width is refused up
  // front (subnormal or tiny radius * load), naming the inputs, instead of
  // failing every N. A profile starts from its half-plane width (as the
  // undamped solver does), through the Hertz load that width would carry.
  double hp_width = 0.0;
  if (!cylinder) {
    hp_width = detail::profile_half_plane_width(prof, phi1, prm.load, w0,
                                                std::min(detail::kMaxA, prof.extent()));
  }
  const double guess_lambda = cylinder ? lambda : 0.5 * kPi * hp_width * hp_width / phi1;
  detail::WidthGuess wg;
  if (homogeneous) {
    wg = detail::width_guess(phi1, guess_lambda, prm.kw, prm.nu, prm.kp);
  } else {
    // Any other medium: from its long-wave compliance (contact.cpp's).
    medium = cached_medium(medium_of(prm), prm.vstar);
    constexpr double t_c = 0.05;
    wg = detail::width_guess_compliance(phi1, guess_lambda,
                                        medium->surface_response(t_c).M1.real() / t_c);
  }
  if (cylinder && !(wg.hertz >= 2.0 * detail::kMinA))
    detail::width_out_of_range(prm, false, 2.0 * kPi * detail::kMinA * detail::kMinA / phi1);
  const bool wide_guess = wg.use_wide;
  double guess = cylinder ? wg.a
                          : std::clamp(wide_guess ? std::max(wg.a, hp_width) : hp_width,
                                       w0 + 2.0 * detail::kMinA, wmax);
  double c_last = 0.0;  // a profile's last centre: the next width's first guess
  // The first table: for the scan (8 w) too when the guess is the half-plane
  // width (close); a wide guess can be far off (the dashpots alone: aW is
  // thousands of h for a contact of 0.4 h), so only its own trial width.
  kernel((wide_guess ? 2.0 : 8.4) * guess);
  s.model_ = kern->model_ptr();

  // A profile's series of g beyond the collocated terms: the half-plane's
  // (the half-plane part maps the n-th term onto Q_{n+1}: b_{m-1} =
  // q_m/(phi1 P) for the U-series, c_{m-1} = sin(pi alpha) q_m/(2 phi1 P) for
  // the Jacobi series), up to the layer's coupling, negligible that far out;
  // to kTail terms (a rounded flat's kinked slope: 4096, 1024 with friction;
  // a table's C^1 spline slope: 256), as the undamped solver extends its
  // series (docs/theory.md section 13).
  const bool kinked = prof.kind() == ProfileKind::rounded_flat;
  const int tail_len = kinked ? (frictional ? 1024 : 4096) : 256;
  const double tail_scale = frictional ? std::sin(kPi * s.exps_.front) / (2.0 * phi1 * prm.load)
                                       : 1.0 / (phi1 * prm.load);
  auto extend_tail = [&](Eigen::VectorXd& coef, double c, double w) {
    const Eigen::Index n = coef.size();
    const Eigen::Index len = std::max<Eigen::Index>(n, tail_len);
    const std::vector<double> q = proj.coefficients(c, w, static_cast<int>(len) + 1);
    coef.conservativeResize(len);
    for (Eigen::Index m = n; m < len; ++m)
      coef(m) = q[static_cast<std::size_t>(m + 1)] * tail_scale;
  };
  // max |sqrt(1 - r^2) sum b_n U_n| of a long series: head_sine_bound. The
  // same for a Jacobi series: |w P_n| <= 2 on [-1, 1] (w <= 2 for
  // alpha + beta = 1; measured |w P_n| <= 0.17 for n >= 64).
  auto head_density_max = [&](const Eigen::VectorXd& c, int head) {
    const Eigen::Index h = std::min<Eigen::Index>(c.size(), head);
    return JacobiSeries(s.exps_.front, c.head(h)).max_abs_density() +
           2.0 * c.tail(c.size() - h).cwiseAbs().sum();
  };

  const std::vector<int> ladder = detail::size_ladder(512);
  std::vector<int> sizes;
  if (prm.n > 0) {
    // Three sizes n/2, 3n/4, n (even): the last two changes give the rate.
    for (int m : {prm.n / 2, (3 * prm.n) / 4, prm.n}) {
      const int e = std::max(2, m - m % 2);
      if (sizes.empty() || e > sizes.back()) sizes.push_back(e);
    }
  } else {
    sizes = ladder;
  }
  bool converged = false, stalled = false;
  RefinementEstimate est_e, est_p;
  double floor_e = 0, floor_p = 0, pmax = 0;
  WidthSolve ws;
  ChebyshevNodes nd;
  Eigen::VectorXd bk;
  JacobiSeries js;  // friction: g's Jacobi series at the last size
  // The kernel's error: its quadrature's (QUADPACK's estimate) and its
  // table's (the pieces' tails and values' round-off: a round-off part).
  const double qerr = kern->quadrature().kronrod_error;
  const double terr = kern->table_error();
  // One size's width solve from a width guess (a profile's centre from the
  // last one found).
  auto width_at = [&](const ChebyshevNodes& nds, double from) {
    if (cylinder)
      return solve_width(nds.n, lambda, from, 0.0, detail::kMaxA,
                         [&](double w) { return eval_width(nds, w, kernel(2.0 * w), phi1); });
    return solve_width(nds.n, lambda, from, w0, wmax, [&](double w) {
      WidthEval e = eval_width_profile(nds, w, kernel(2.0 * w), phi1, proj, prof, c_last);
      if (std::isfinite(e.lambda)) c_last = e.centre;
      return e;
    });
  };
  // g's series at a size: its U-coefficients, or with friction its Jacobi
  // series (jso; a profile's extended by the half-plane tail); pm the
  // largest |p|/(P/h) (a profile's bounded on its head, as the stopping
  // rule's scale).
  auto series_at = [&](const ChebyshevNodes& nds, const WidthSolve& wsz, JacobiSeries& jso,
                       double& pm) {
    Eigen::VectorXd b;
    if (frictional) {
      jso = JacobiSeries::from_nodes(s.exps_.front, nds.r, wsz.g);
      if (!cylinder) {
        Eigen::VectorXd ext = jso.coefficients();
        extend_tail(ext, wsz.c, wsz.w);
        jso = JacobiSeries(s.exps_.front, ext);
      }
      b = jso.coefficients();
      pm = cylinder ? jso.max_abs_density() : head_density_max(b, 4 * nds.n + 64);
    } else {
      b = u_coefficients(nds, wsz.g);
      if (!cylinder) extend_tail(b, wsz.c, wsz.w);
      pm = cylinder ? max_abs_sine_series(b) : head_sine_bound(b, 4 * nds.n + 64);
    }
    return b;
  };
  // The largest difference of p/(P/h) between two sizes' series (a
  // profile's on the first `head` terms: both tails are the half-plane's).
  auto p_change = [&](const Eigen::VectorXd& b1, const Eigen::VectorXd& b2, const JacobiSeries& j1,
                      const JacobiSeries& j2, int head) {
    Eigen::VectorXd diff = Eigen::VectorXd::Zero(std::max(b1.size(), b2.size()));
    diff.head(b1.size()) += b1;
    diff.head(b2.size()) -= b2;
    return cylinder ? (frictional ? j1.minus(j2).max_abs_density() : max_abs_sine_series(diff))
                    : (frictional ? head_density_max(diff, head) : head_sine_bound(diff, head));
  };
  // The ladder (ladder.hpp). Per size: the ends and the U-coefficients of g
  // (with friction its Jacobi series); the changes between successive sizes
  // drive both the stopping rule and the estimates.
  struct Member {
    ChebyshevNodes nd;
    WidthSolve ws;
    Eigen::VectorXd b;
    JacobiSeries js;
    double pmax = 0, floor_e = 0, floor_p = 0;
  };
  const detail::LadderRun<Member, 2> run = detail::run_ladder<2, Member>(
      sizes,
      [&](int n) {
        Member m;
        m.nd = nodes_of(n);
        m.ws = width_at(m.nd, guess);
        s.iterations_ += m.ws.evaluations;
        guess = m.ws.w;
        m.b = series_at(m.nd, m.ws, m.js, m.pmax);
        const double scale_e = m.ws.w + std::fabs(m.ws.c);
        // Round-off floors: a few hundred eps of the scale (growing slowly
        // with N: the collocation matrix's condition), plus the kernel
        // quadrature's error carried into the ends (dw ~ 4 w^2 dK,
        // docs/damped.md section 8).
        m.floor_e = 64.0 * kEps * scale_e + 4.0 * (qerr + terr) * m.ws.w * m.ws.w;
        m.floor_p = (512.0 * kEps * (1.0 + m.nd.n / 64.0) + 4.0 * (qerr + terr) * m.ws.w) * m.pmax;
        return m;
      },
      [&](const Member& prev, const Member& cur) {
        return std::array<double, 2>{
            std::fabs(cur.ws.w - prev.ws.w) + std::fabs(cur.ws.c - prev.ws.c),
            p_change(cur.b, prev.b, cur.js, prev.js, 4 * cur.nd.n + 64)};
      },
      [&](const detail::LadderChain<Member, 2>& c) {
        const Member& m = c.last();
        floor_e = m.floor_e;
        floor_p = m.floor_p;
        pmax = m.pmax;
        if (c.size() < 2) return detail::Verdict::go_on;
        const std::vector<double>& d_ends = c.changes[0];
        const std::vector<double>& d_p = c.changes[1];
        est_e = refinement_estimate(c.sizes, d_ends, floor_e);
        est_p = refinement_estimate(c.sizes, d_p, floor_p);
        // A profile's ends (a rounded flat's, a table's: kinks in the slope's
        // derivative) converge irregularly, fast and slow by turns as N moves
        // the nodes against the kinks: their estimate is never below the last
        // change (the previous size's error), as the flat punch's
        // (asymmetric_flat.cpp) and the symmetric solver's (contact.cpp). A damped
        // rounded flat at tol 2.8e-3 changed by 3.2e-5, 7.0e-8 at N = 16, 24
        // and was 1.05e-9 off at 24: the extrapolation claimed 2.0e-11.
        if (!cylinder) est_e.estimate = std::max(est_e.estimate, d_ends.back() + floor_e);
        // Stop after at least three sizes, so that the rate is seen.
        if (prm.n != 0 || d_p.size() < 2) return detail::Verdict::go_on;
        return detail::ladder_verdict(ladder_stop(
            prm.tol, est_e, d_ends.back(), m.ws.w + std::fabs(m.ws.c), est_p, d_p.back(), pmax));
      },
      [&](const std::exception& ex, const detail::LadderAt& at) {
        const auto* e = dynamic_cast<const ConvergenceError*>(&ex);
        if (e == nullptr) return detail::OnFailure::rethrow;
        // Under-resolved at this N (a non-monotone or non-positive discrete
        // load curve): refine N, unless this was the last size.
        if (at.last && prof.kind() == ProfileKind::table) {
          // No width within the table carries the load (the widest, centred
          // where the table allows, carries less): refused, naming the table.
          std::ostringstream m;
          m.precision(6);
          m << "load = " << prm.load << " on the " << prof.describe() << " (kw = " << prm.kw
            << ", vstar = " << prm.vstar << ") needs a contact that leaves the table ("
            << prof.lower() << " <= x/h <= " << prof.upper()
            << "): the contact must stay within the table; extend the table or reduce the load ("
            << e->what() << ")";
          throw std::invalid_argument(m.str());
        }
        if (at.last) {
          std::ostringstream msg;
          msg << e->what() << "; vstar = " << prm.vstar << ", kw = " << prm.kw
              << ", damping = " << prm.damping << " (very soft foundations far above V*_cr "
              << "have no bounded steady contact)";
          throw ConvergenceError(msg.str());
        }
        return detail::OnFailure::refine;
      });
  converged = run.verdict == detail::Verdict::converged;
  stalled = run.verdict == detail::Verdict::stalled;
  {
    const Member& m = run.chain.last();
    nd = m.nd;
    ws = m.ws;
    bk = m.b;
    js = m.js;
  }
  const std::vector<double>& d_ends = run.chain.changes[0];
  const std::vector<double>& d_p = run.chain.changes[1];
  // The "previous" series for the stress estimate's change (below): the
  // member before the last when the ladder stopped on its verdict, the last
  // one itself when the sizes ran out (as the loop this driver replaced kept
  // it: then the change below is zero).
  Eigen::VectorXd b_prev;
  JacobiSeries js_prev;
  {
    const std::size_t k = run.chain.size();
    const Member& m =
        run.verdict != detail::Verdict::go_on ? run.chain.states[k - 2] : run.chain.last();
    b_prev = m.b;
    if (frictional) js_prev = m.js;
  }
  if (d_ends.empty()) {  // a single size (n = 2) or every smaller size failed
    est_e.estimate = std::numeric_limits<double>::infinity();
    est_p.estimate = std::numeric_limits<double>::infinity();
  } else if (prm.n > 0 && d_ends.size() == 1) {
    // A fixed n with one change (n = 4 after n = 2): the change is about the
    // previous size's error, and with no rate to read this size's can exceed
    // it (1.03 times it with friction, found by the fuzz): twice it.
    est_e.estimate = std::max(est_e.estimate, 2.0 * d_ends.back() + floor_e);
    est_p.estimate = std::max(est_p.estimate, 2.0 * d_p.back() + floor_p);
  }
  // The pressure's estimate from the coarser sizes: the stress estimate's
  // gain is read from their change (below), and is applied to it.
  const double p_coarse = est_p.estimate;
  if (prm.n > 0 && prm.n <= kFixedFinerMax) {
    // A fixed small N: its error read from finer sizes, not from coarser
    // ones (N = 4, 6 after 2: the changes of an unresolved start can shrink
    // faster than the error does; the fuzz found an error 1.07 times the
    // estimate). References at m = max(2N, 8), doubled up to
    // kFixedReferenceMax, until their own estimate (refinement_estimate
    // over the references) is a tenth of the distance from N's result, or
    // round-off. The estimate is that distance plus twice the reference's
    // estimate (|v_N - v| <= |v_N - v_ref| + |v_ref - v|); infinite if a
    // reference has no solution (the result then warns that tol is not met).
    double r_guess = ws.w, r_w = 0.0, r_c = 0.0;
    Eigen::VectorXd r_b;
    JacobiSeries r_j;
    const FixedError fe = fixed_size_error(prm.n, [&](int m) {
      const ChebyshevNodes nr = nodes_of(m);
      const WidthSolve wr = width_at(nr, r_guess);
      s.iterations_ += wr.evaluations;
      JacobiSeries jr;
      double pm_r = 0.0;
      const Eigen::VectorXd br = series_at(nr, wr, jr, pm_r);
      const int head = 4 * m + 64;
      FixedSample out;
      out.d_n_v = std::fabs(ws.w - wr.w) + std::fabs(ws.c - wr.c);
      out.d_n_p = p_change(bk, br, js, jr, head);
      if (r_b.size() > 0) {
        out.d_v = std::fabs(wr.w - r_w) + std::fabs(wr.c - r_c);
        out.d_p = p_change(br, r_b, jr, r_j, head);
      }
      out.floor_v = 64.0 * kEps * (wr.w + std::fabs(wr.c)) + 4.0 * (qerr + terr) * wr.w * wr.w;
      out.floor_p = (512.0 * kEps * (1.0 + m / 64.0) + 4.0 * (qerr + terr) * wr.w) * pm_r;
      r_guess = r_w = wr.w;
      r_c = wr.c;
      r_b = br;
      r_j = jr;
      return out;
    });
    est_e.estimate = fe.v + floor_e;
    est_p.estimate = fe.p + floor_p;
  }
  if (prm.n == 0 && !converged && !stalled && est_e.estimate > prm.tol * (ws.w + std::fabs(ws.c))) {
    std::ostringstream est;
    est << "estimated error " << est_e.estimate;
    throw ConvergenceError(detail::not_converged_message("damped contact: the contact ends",
                                                         prm.tol, sizes.back(), est.str()));
  }
  const double t_width = since_start();
  const double kernel_by_width = kernel_seconds;  // the checks may fetch more
  s.err_ = est_e.estimate;
  s.perr_ = est_p.estimate;
  // A profile's per-size pmax bounds its tail by sum |b_n| (the stopping
  // rule's scale); what is reported is the whole series' largest value.
  if (!cylinder)
    pmax = frictional ? max_abs_density_long(js, 4 * nd.n + 64)
                      : max_abs_sine_series_long(bk, 4 * nd.n + 64);
  s.max_p_ = pmax;
  {
    const double scale_e = ws.w + std::fabs(ws.c);
    // The floors' kernel-quadrature parts (the rest is round-off).
    const double quad_e = 4.0 * qerr * ws.w * ws.w, quad_p = 4.0 * qerr * ws.w * pmax;
    auto note = [&](const char* what, double est, double scale, double floor, double quad) {
      const double want = prm.tol * scale;
      if (!(est <= want)) {
        std::ostringstream m;
        m.precision(3);
        m << what << " not met to tol = " << prm.tol << ": estimated relative error " << est / scale
          << " (" << est / want << " x tol) at N = " << nd.n;
        if (floor > want && quad >= 0.5 * floor)
          m << " (the kernel quadrature's error estimate " << quad / scale
            << " exceeds tol: unresolved near-resonant peaks)";
        else if (floor > want)
          m << " (round-off floor " << floor / scale << " exceeds tol)";
        else if (prm.n > 0)
          m << " (fixed n; raise n or leave it automatic)";
        else if (stalled)
          m << " (the changes between sizes stopped shrinking)";
        else
          m << " (the N ladder ended at " << nd.n << ")";
        s.warnings_.push_back(m.str());
      }
    };
    note("contact ends (-b, a):", s.err_, scale_e, floor_e, quad_e);
    note("pressure p(x):", s.perr_, pmax, floor_p, quad_p);
    // A viscoelastic top's shortest memory beta (ratio V tau) puts a boundary
    // layer of about that width at the trailing end: below the nodes'
    // spacing there it is not resolved, and the ladder, whose sizes all miss
    // it alike, cannot see it. Its weight in the drag and the pressure is
    // about sum c_k beta_k/w: said when that exceeds tol.
    if (const MemoryKernel* mem = kern->model().memory()) {
      const RetardationSpectrum& sp = mem->spectrum();
      const double spacing = ws.w * (1.0 - std::cos(kPi / (nd.n + 1)));
      double weight = 0.0, beta_min = kInf;
      for (std::size_t k = 0; k < sp.c.size(); ++k) {
        // (|c_k|: the terms of a layer with inertia are of either sign.)
        if (sp.beta[k] < 2.0 * spacing) weight += std::fabs(sp.c[k]) * sp.beta[k] / ws.w;
        beta_min = std::min(beta_min, sp.beta[k]);
      }
      if (weight > prm.tol) {
        std::ostringstream m;
        m.precision(3);
        m << "viscoelastic memory: the shortest retardation length ratio V tau = " << beta_min
          << " h is below the collocation's node spacing at the contact's ends (" << spacing
          << " h at N = " << nd.n
          << "): the pressure's boundary layer there is not resolved; the drag, the "
             "dissipation and the pressure near the ends are uncertain to about "
          << weight << " relative (their estimates do not see it)";
        s.warnings_.push_back(m.str());
      }
    }
  }
  s.n_ = nd.n;
  s.half_ = ws.w;
  s.centre_ = ws.c;
  s.b_ = bk;
  // drag = int p x / R dx / P with p = g sqrt(1 - r^2), x = c + w r:
  // int sqrt(1-r^2) U_n = pi/2 delta_n0, int r sqrt(1-r^2) U_n = pi/4 delta_n1.
  const double b1 = s.b_.size() > 1 ? s.b_(1) : 0.0;
  s.drag_ = (s.centre_ + 0.25 * kPi * s.half_ * s.half_ * b1) / prm.radius;
  if (frictional) {
    // int p xi d xi = c w m0 + w^2 m1 (w m0 = int p = 1), by the Jacobi moments.
    s.jac_ = std::make_shared<const JacobiSeries>(js);
    s.drag_ = (s.centre_ * s.half_ * js.moment0() + s.half_ * s.half_ * js.moment1()) / prm.radius;
  }
  if (!cylinder) {
    // drag = int p f'(x) dx / P = w int weight(r) g(r) f'(c + w r) dr.
    const double c = s.centre_, w = s.half_;
    if (frictional && kinked) {  // sum_n c_n int weight P_n f', in closed form
      const std::vector<double> mom =
          rounded_flat_moments(prof, c, w, js.alpha(), js.beta(), js.size());
      double sum = 0.0;
      for (int n = 0; n < js.size(); ++n)
        sum += js.coefficients()(n) * mom[static_cast<std::size_t>(n)];
      s.drag_ = w * sum;
    } else if (frictional) {
      double sum = 0.0;
      weighted_nodes(prof, c, w, s.exps_.front, s.exps_.back, js.size() + 64,
                     [&](double r, double wt) { sum += wt * js.g(r) * prof.slope(c + w * r); });
      s.drag_ = w * sum;
    } else {
      // int sqrt(1 - r^2) U_n T_m dr = (pi/4)(delta_nm (1 + delta_m0) - delta_m,n+2), with
      // f'(c + w r) = d_0/2 + sum d_m T_m: (pi/4) sum_n b_n (d_n - d_{n+2}).
      const Eigen::Index n = s.b_.size();
      const std::vector<double> d = prof.slope_chebyshev_at(c, w, static_cast<int>(n) + 2);
      double sum = 0.0;
      for (Eigen::Index k = 0; k < n; ++k)
        sum += s.b_(k) * (d[static_cast<std::size_t>(k)] - d[static_cast<std::size_t>(k + 2)]);
      s.drag_ = w * 0.25 * kPi * sum;
    }
    // What the extended series leaves out (series_truncation): the
    // half-plane tail's coefficients summed to four times the length (U-series,
    // |sqrt(1 - r^2) U_n| <= 1) and the rest extrapolated as m^-2; with
    // friction from the series' last half (below).
    const Eigen::Index len = s.b_.size();
    if (frictional) {
      // The last half of the series, [len/2, len): for a kinked slope the
      // pointwise error falls like 1/length, so this block's largest density
      // is about what is left beyond len; twice it (measured on a rounded
      // flat with f = 0.3: 2 to 6 times the actual error at lengths 64 to 512).
      Eigen::VectorXd block = s.b_;
      block.head(len / 2).setZero();
      s.trunc_ = 2.0 * max_abs_density_coarse(JacobiSeries(s.exps_.front, block));
    } else {
      const std::vector<double> q = proj.coefficients(c, w, 4 * static_cast<int>(len) + 1);
      double sum = 0.0;
      for (std::size_t m = static_cast<std::size_t>(len) + 1; m < q.size(); ++m)
        sum += std::fabs(q[m]);
      sum += (std::fabs(q.back()) + std::fabs(q[q.size() - 2])) * static_cast<double>(q.size());
      s.trunc_ = sum * std::fabs(tail_scale);
    }
    s.perr_ += s.trunc_;
    // The undamped solver's warning, on the same scale (p at the contact's
    // centre): damping -> 0 warns as damping = 0 does.
    const double p_centre = frictional ? js.density(0.0) : u_series(s.b_, 0.0);
    const std::string kinks = kink_truncation_warning(
        s.trunc_, p_centre, prof.describe(),
        prof.kind() == ProfileKind::rounded_flat ? s.half_ - prof.face() : std::nan(""));
    if (!kinks.empty()) s.warnings_.push_back(kinks);
  }

  // Above V*_cr lambda(w) need not be monotone: a load can be carried by
  // several contacts (the steady problem has several solutions). Scan
  // lambda(w) on [w/8, 4w] (at N >= 32, steps of ln(32)/48 in ln w at most)
  // for other roots and report them. Where the medium's form is positive
  // (AsymmetricKernel::positive_form: Re M1 > 0 at every wavenumber) the frictionless steady
  // contact is unique: a valid one is the only one, and the scan runs only
  // when the solution found is invalid (another single contact might be the
  // valid one).
  const bool unique = !frictional && kern->positive_form();
  auto scan_other_widths = [&] {
    const ChebyshevNodes ns = nodes_of(std::max(32, nd.n));
    kernel(8.4 * s.half_);
    const double lo = std::log(std::max(detail::kMinA, s.half_ / 8.0));
    const double hi = std::log(std::min(detail::kMaxA, 4.0 * s.half_));
    const std::vector<double> xs = scan_points(lo, hi);
    std::vector<double> lam;
    if (cylinder) {
      lam = ScanMemo::lambdas(kern, {}, ns.n, xs,
                              [&](double w) { return eval_width(ns, w, *kern, phi1).lambda; });
    } else {
      // A profile's load curve depends on its shape (not on the load): kept
      // per shape. Each width's centre search starts from the last width's
      // centre (the scan's widths are ordered; the found contact's first).
      double guess = s.centre_;
      lam = ScanMemo::lambdas(kern, shape_key(prm), ns.n, xs, [&](double w) {
        if (!(w > w0 && w <= wmax)) return std::nan("");
        const WidthEval e = eval_width_profile(ns, w, *kern, phi1, proj, prof, guess);
        if (std::isfinite(e.lambda)) guess = e.centre;
        return e.lambda;
      });
    }
    double prev_x = lo, prev_f = std::nan("");
    for (std::size_t i = 0; i < xs.size(); ++i) {
      const double x = xs[i];
      const double f = lam[i] > 0.0 ? std::log(lam[i] / lambda) : std::nan("");
      if (!std::isnan(f) && !std::isnan(prev_f) && (f > 0.0) != (prev_f > 0.0)) {
        const double xr = prev_x - prev_f * (x - prev_x) / (f - prev_f);  // linear estimate
        const double wr = std::exp(xr);
        if (std::fabs(wr - s.half_) > 0.05 * s.half_) s.other_widths_.push_back(wr);
      }
      prev_x = x;
      prev_f = f;
    }
    s.kernel_ = kern;  // (the scan may have widened the table)
  };
  if (!unique) scan_other_widths();

  s.kernel_ = kern;
  // The change of g's coefficients between the last two sizes (for the
  // stress estimate below).
  const bool have_change = !d_p.empty() && d_p.back() > 0.0 && b_prev.size() > 0;
  Eigen::VectorXd db;
  if (have_change) {
    db = Eigen::VectorXd::Zero(std::max(bk.size(), b_prev.size()));
    db.head(bk.size()) += bk;
    db.head(b_prev.size()) -= b_prev;
  }
  // With friction the change's Jacobi series (its transform on the same
  // rule as g's: jtr_).
  JacobiSeries dseries;
  if (frictional) {
    if (have_change) {
      dseries = js.minus(js_prev);
      // A profile's: the change lives in the collocated head (both tails
      // are the half-plane's); the stress gain is read from it.
      if (!cylinder) {
        const Eigen::Index h = std::min<Eigen::Index>(dseries.size(), 4 * nd.n + 64);
        dseries = JacobiSeries(s.exps_.front, dseries.coefficients().head(h));
      }
    }
    s.jtr_ = std::make_shared<const JacobiTransform>(
        js, kern->quadrature().panels.alpha_max * s.half_, have_change ? &dseries : nullptr);
    s.jtr_omega_ = kern->quadrature().panels.alpha_max * s.half_;
    // (Its size rounded up to 64: shared between the solves of a sweep.)
    s.atan_rule_ = *cached_gauss_jacobi(
        (js.size() + 127 + static_cast<int>(std::ceil(8.0 * s.half_))) / 64 * 64, s.exps_.front,
        s.exps_.back);
    s.atan_wg_ = s.atan_weights(js);
  }
  // Surface sigma_x = -phi2 p - (1/pi) Re int_0^inf (M2 - phi2) p^ e^{i alpha x}
  // is linear in p: the change of sigma_x between the last two sizes, from
  // the change of the U-coefficients, measured on the surface (64 points on
  // the contact with |r| <= 0.999, 32 beside it out to 6 w), gives the gain
  // from the pressure error to the stress error (at least |phi2|, the local
  // term). Without two sizes the bound G = |phi2| + (2w/pi) int |M2 - phi2|
  // (|dp^| <= int |dp| <= 2 w max|dp|) is used. The ends' error moves p by
  // about pmax (da/w)(1 + 1/sqrt(2 d)) at a relative distance d >= 1e-3 from
  // an end (the square-root cusp). Round-off of the Fourier sum: 64 eps times
  // the sum of its absolute terms.
  // Computed on first read (stress_error_estimate): the fine nodes' transform
  // of the pressure and of its change are about half a warm solve.
  s.stress_cache_->compute = [have_change, db = std::move(db), dseries = std::move(dseries),
                              frictional, p_coarse, d_last = have_change ? d_p.back() : 0.0](
                                 const AsymmetricSolution& s) {
    std::vector<cplx> dphat;
    AsymmetricSolution::Fine built =
        s.build_fine(2.0 * s.half_, have_change ? &db : nullptr, &dphat);
    const AsymmetricSolution::Fine& f = built;
    const double phi2 = s.model_->phi2();
    double gain = 0.0;
    if (have_change) {
      std::vector<cplx> amp(f.alpha.size());
      for (std::size_t i = 0; i < f.alpha.size(); ++i)
        amp[i] = s.surface_stress_integrand(f.r[i], f.alpha[i]) * dphat[i];
      std::vector<double> amp_re, amp_im;
      f.coefficients(amp, amp_re, amp_im);
      double dmax = 0.0;
      const Eigen::VectorXd dwg = frictional ? s.atan_weights(dseries) : Eigen::VectorXd();
      // (The series' change at the 64 points inside, summed together.)
      std::array<double, 64> rin{}, din{};
      for (int j = 0; j < 64; ++j)
        rin[static_cast<std::size_t>(j)] = 0.999 * std::cos(kPi * (j + 0.5) / 64.0);
      if (!frictional) u_series(db, rin.data(), din.data(), 64);
      for (int j = 0; j < 96; ++j) {
        double r;
        if (j < 64) {
          r = rin[static_cast<std::size_t>(j)];
        } else {
          const int q = j - 64;
          r = (q % 2 == 0 ? 1.0 : -1.0) * (1.0 + 5.0 * std::pow((q / 2 + 0.5) / 16.0, 2.0));
        }
        const double x = s.centre_ + s.half_ * r;
        // f.fourier(amp_re, amp_im, x - c), its two Filon sums sharing the
        // Bessel functions and the phases.
        const auto re_im = f.filon->integral_pair(x - s.centre_, amp_re, amp_im);
        const double sum = re_im.first.real() - re_im.second.imag();
        double dp =
            j < 64 && !frictional ? din[static_cast<std::size_t>(j)] * std::sqrt(1.0 - r * r) : 0.0;
        double local = 0.0;
        if (frictional) {
          dp = dseries.density(r);
          local = s.friction_surface_terms(x, dseries, dwg, s.centre_, s.half_);
        }
        dmax = std::max(dmax, std::fabs(-phi2 * dp - sum / kPi + local));
      }
      gain = std::max(std::fabs(phi2), dmax / d_last);
    } else {
      double im2 = 0.0;
      const AsymmetricQuadrature& quad = s.kernel_->quadrature();
      for (std::size_t i = 0; i < quad.m2.size(); ++i)
        im2 += quad.panels.weight[i] *
               std::abs(s.surface_stress_integrand(quad.r[i], quad.panels.alpha[i]));
      gain = std::fabs(phi2) + 2.0 * s.half_ * im2 / kPi;
      // Friction: the Cauchy and arctan terms are not bounded by max |dp|:
      // no estimate from a single size.
      if (frictional) gain = std::numeric_limits<double>::infinity();
    }
    // A viscoelastic top with inertia: its memory moves sigma_x by -phi2 sum_k
    // d_k e_k * dp, at most |phi2| sum_k |d_k| max |dp| (int e_k = 1).
    if (const RetardationSpectrum* sm = s.model_->stress_memory()) {
      double d = 0.0;
      for (double c : sm->c) d += std::fabs(c);
      gain += std::fabs(phi2) * d;
    }
    double sabs = 0.0;
    for (std::size_t i = 0; i < f.alpha.size(); ++i)
      sabs += f.weight[i] * std::abs(s.surface_stress_integrand(f.r[i], f.alpha[i])) *
              std::abs(f.phat[i]);
    // The end's cusp p ~ d^gamma (gamma = 1/2 without friction).
    const double gmin = std::min(s.exps_.back, s.exps_.front);
    const double ends = s.max_p_ * (s.err_ / s.half_) * (1.0 + std::pow(2e-3, gmin - 1.0));
    const double p_est = std::max(s.perr_, p_coarse + s.trunc_);
    const double serr =
        gain * (p_est + ends) + 64.0 * kEps * (std::fabs(phi2) * s.max_p_ + sabs / kPi);
    s.offer_light(std::move(built));
    return serr;
  };

  // Gauss-Chebyshev (U) nodes and weights times g for surface_slope (friction:
  // Gauss-Jacobi).
  // A profile's tail-extended series: nodes for its collocated head (the
  // kernel is smooth; the tail's share is within series_truncation).
  const int slope_terms =
      static_cast<int>(std::min<Eigen::Index>(s.b_.size(), cylinder ? s.b_.size() : 4 * nd.n + 64));
  if (frictional) {
    const int m = std::max(64, 2 * slope_terms + 2);
    const auto held = cached_gauss_jacobi(m, s.exps_.front, s.exps_.back);
    const JacobiRule& rule = *held;
    for (int i = 0; i < m; ++i) {
      s.slope_r_.push_back(rule.x(i));
      s.slope_wg_.push_back(rule.w(i) / kPi * js.g(rule.x(i)));
    }
  } else {
    s.set_u_slope_nodes(std::max(64, 2 * slope_terms + 2));
  }
  // The margin before separation: min over r of p/((P/h) sqrt(1 - r^2)) = g(r).
  // (A profile's on the collocated head: its tail's kink is resolved only
  // to series_truncation anyway.)
  s.margin_ = frictional ? (cylinder ? js.min_g()
                                     : JacobiSeries(js.alpha(), js.beta(),
                                                    js.coefficients().head(std::min<Eigen::Index>(
                                                        js.size(), 4 * nd.n + 64)))
                                           .min_g())
              : cylinder
                  ? u_series_minimum(s.b_)
                  : u_series_minimum(s.b_.head(std::min<Eigen::Index>(s.b_.size(), 4 * nd.n + 64)));

  // Validity: p >= 0 on the contact, no penetration beside it.
  s.min_p_ = kInf;
  if (frictional) {
    for (int i = 0; i <= 400; ++i)
      s.min_p_ = std::min(s.min_p_, js.density(-1.0 + 2.0 * i / 400.0));
  } else {
    s.min_p_ = min_pressure_on_grid(s.b_);
  }
  // gap(x) = int_edge^x (f'(xi) - v'(xi)) d xi beside each end, out to 2w
  // (up to a table's end: beyond, no punch), sampled to resolve the
  // surface's shortest wave and refined at every dip (gap_scan.hpp).
  s.min_gap_ = kInf;
  {
    // The surface's shortest wave: where M1 differs from its half-plane part
    // (a viscoelastic top's memory is added exactly, memory_part).
    const double step = detail::gap_step(kern->surface_band());
    for (int side = -1; side <= 1; side += 2) {
      const double edge = s.centre_ + side * s.half_;
      const double room = side < 0 ? edge - prof.lower() : prof.upper() - edge;
      const double len = std::min(2.0 * s.half_, room);
      if (!(len > 0.0)) continue;
      // The kernel's part of v' (smooth) from its interpolant on the scanned
      // interval when that reaches round-off (docs/theory.md section 15.2),
      // the Cauchy integral directly.
      const double lo = std::min(edge, edge + side * len), hi = std::max(edge, edge + side * len);
      // (A viscoelastic top's memory part, whose derivative has the pressure's
      // square root at the edge, is added directly.)
      const detail::SmoothInterpolant smooth([&](double x) { return s.regular_part(x); }, lo, hi);
      // The memory part is analytic in phi = acosh(|x - c|/w) (the basis'
      // Hilbert transforms are powers of e^-phi): interpolated in phi.
      const double reach = std::acosh(std::max(1.0, (len + s.half_) / s.half_));
      const bool mem = s.model_->memory() != nullptr;
      // Its points, descending in phi, are one downward sweep of the memory's
      // moments (right of the contact; the left side's reversed).
      const detail::SmoothInterpolant smooth_mem(
          detail::SmoothInterpolant::Batch{},
          [&](const std::vector<double>& phis, std::vector<double>& v) {
            if (!mem) return std::fill(v.begin(), v.end(), 0.0);
            const std::size_t m = phis.size();
            std::vector<double> at(m), out(m);
            for (std::size_t j = 0; j < m; ++j)
              at[side > 0 ? j : m - 1 - j] = side * std::cosh(phis[j]);
            s.model_->memory()->apply_descending(s.b_, at.data(), static_cast<int>(m), s.half_,
                                                 out.data());
            for (std::size_t j = 0; j < m; ++j) v[j] = out[side > 0 ? j : m - 1 - j] / s.half_;
          },
          0.0, mem ? reach : 0.0);
      auto memory_at = [&](double x) {
        if (!mem) return 0.0;
        if (!smooth_mem.ok()) return s.memory_part(x);
        return smooth_mem(std::acosh(std::max(1.0, std::fabs(x - s.centre_) / s.half_)));
      };
      const double lp = prm.load * s.model_->phi1();
      auto gap_slope = [&](double x) {
        if (smooth.ok())
          return prof.slope(x) - lp * (-s.cauchy_part(x) + s.half_ * (smooth(x) + memory_at(x)));
        return prof.slope(x) - s.surface_slope(x);
      };
      const detail::GapMinimum m =
          detail::scan_gap_slope(gap_slope, edge, edge + side * len, 0.0, step, 24, true, false);
      if (!std::isfinite(m.gap))
        throw ConvergenceError(
            "the gap beside the contact came out non-finite; the solution is not trusted");
      s.min_gap_ = std::min(s.min_gap_, m.gap);
    }
  }
  s.valid_ = true;
  std::vector<std::string> why;
  const auto num = [](double x) {
    std::ostringstream o;
    o << x;
    return o.str();
  };
  // The gap's scale: w^2/R for a cylinder, w times the slope at the ends otherwise.
  const double gap_scale =
      cylinder ? s.half_ * s.half_ / prm.radius
               : s.half_ * std::max({std::fabs(prof.slope(s.centre_ - s.half_)),
                                     std::fabs(prof.slope(s.centre_ + s.half_)), 1e-300});
  if (s.min_p_ < -1e-8) {
    s.valid_ = false;
    why.push_back("the pressure is negative inside the contact (min p/(P/h) = " + num(s.min_p_) +
                  "): the contact separates");
  }
  if (s.min_gap_ < -1e-6 * gap_scale) {
    s.valid_ = false;
    why.push_back("the punch penetrates the surface beside the contact (min gap/h = " +
                  num(s.min_gap_) + ")");
  }
  if (unique && !s.valid_) scan_other_widths();
  if (s.valid_) {
    s.validity_ = "valid: p >= 0 on the contact and no penetration within 2(a+b) of it";
    if (unique) s.validity_ += "; unique (the medium's form is positive: Re M1 > 0)";
  } else {
    s.validity_ = "invalid: " + why.front();
    for (std::size_t i = 1; i < why.size(); ++i) s.validity_ += "; " + why[i];
    s.validity_ += "; the single-contact solution is unphysical";
  }
  if (!s.other_widths_.empty()) {
    std::ostringstream note;
    note << "; not unique: the load is also carried by contacts of half-width (a+b)/2 ~";
    for (double w : s.other_widths_) note << " " << w;
    note << " h (lambda(w) is not monotone; this solution continues the half-plane width)";
    s.validity_ += note.str();
  }
  if (!s.valid_ && !prm.allow_unphysical) throw UnphysicalContactError(s.validity_);
  s.elapsed_ = since_start();
  // A kernel fetch by the checks (the scan, the gap) is counted under kernel,
  // not checks; one before t_width under kernel, not width.
  s.stage_seconds_ = {t_critical, kernel_seconds, t_width - t_critical - kernel_by_width,
                      s.elapsed_ - t_width - (kernel_seconds - kernel_by_width)};
  return s;
}

AsymmetricSolution zone_solution(const AsymmetricParams& prm,
                                 std::shared_ptr<const AsymmetricKernel> kernel, double centre,
                                 double half, const Eigen::VectorXd& b, int head) {
  if (prm.friction != 0.0) throw std::invalid_argument("zone_solution: frictionless zones only");
  if (!(half > 0.0) || !std::isfinite(centre) || b.size() < 1)
    throw std::invalid_argument("zone_solution: a zone needs half > 0, a finite centre and b");
  AsymmetricSolution s;
  s.params_ = prm;
  s.vr_ = rayleigh_vstar(prm.nu);
  s.vcr_ = critical_vstar_of(prm);
  s.model_ = kernel->model_ptr();
  s.kernel_ = std::move(kernel);
  s.punch_ = std::make_shared<const PunchProfile>(prm.punch());
  s.centre_ = centre;
  s.half_ = half;
  s.b_ = b;
  s.n_ = static_cast<int>(b.size());
  // A tail-extended series: the kernel's nodes for its collocated head (the
  // kernel is smooth), as a profile's solve (solve_asymmetric).
  const Eigen::Index len = b.size();
  const Eigen::Index lead = head > 0 ? std::min<Eigen::Index>(len, 4 * head + 64) : len;
  s.set_u_slope_nodes(std::max(64, 2 * static_cast<int>(lead) + 2));
  s.max_p_ =
      lead < len ? max_abs_sine_series_long(b, static_cast<int>(lead)) : max_abs_sine_series(b);
  s.margin_ = u_series_minimum(b.head(lead));
  s.min_p_ = min_pressure_on_grid(b);
  return s;
}

// ---------------------------------------------------------------------------
// Outputs

namespace {

// out(i) = f(x(i)): the vector overloads of the pointwise outputs.
template <class F>
Eigen::VectorXd at_points(const Eigen::Ref<const Eigen::VectorXd>& x, F f) {
  Eigen::VectorXd out(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) out(i) = f(x(i));
  return out;
}

// Row k of a stress integrand table: [sigma_x, sigma_y, tau] real parts,
// then imaginary parts (the columns filon_columns transforms).
void set_stress_row(Eigen::MatrixXd& G, Eigen::Index k, cplx sx, cplx sy, cplx tau) {
  G(k, 0) = sx.real();
  G(k, 1) = sy.real();
  G(k, 2) = tau.real();
  G(k, 3) = sx.imag();
  G(k, 4) = sy.imag();
  G(k, 5) = tau.imag();
}

}  // namespace

double AsymmetricSolution::pressure(double x) const {
  if (std::isnan(x)) throw InvalidParameter("x", "not NaN", "pressure: x must not be NaN");
  const double r = (x - centre_) / half_;
  if (jac_ && jac_->singular() && std::fabs(r) == 1.0) {
    // A flat punch's edge: p = w g is infinite there (as SymmetricSolution's).
    const double ge = jac_->g(r);
    return ge == 0.0 ? 0.0 : std::copysign(kInf, ge);
  }
  if (!(std::fabs(r) < 1.0)) return 0.0;
  if (jac_) return jac_->density(r);
  return u_series(b_, r) * std::sqrt(1.0 - r * r);
}

cplx AsymmetricSolution::pressure_transform(double alpha) const {
  if (jac_) {
    // w e^{-i alpha c} int w(r) g(r) e^{-i alpha w r} dr by Gauss-Jacobi (jtr_
    // resolves alpha up to the quadrature's alpha_max; beyond, a rule of its own).
    const double a = std::fabs(alpha), om = a * half_;
    const cplx t = om <= jtr_omega_ ? (*jtr_)(om) : JacobiTransform(*jac_, om, nullptr, false)(om);
    const cplx ph = half_ * std::exp(cplx(0.0, -a * centre_)) * t;
    return alpha < 0.0 ? std::conj(ph) : ph;
  }
  return u_series_transform(b_, centre_, half_, alpha);
}

namespace {

// The bar pole of the surface sigma_x per unit tangential load: ep Uq ~
// bar_pole/alpha as alpha -> 0 (ep/(ep - vstar) for the homogeneous layer;
// 0 on a bonded half-space, which takes the net horizontal force).
double bar_pole(const Medium& m) {
  const WaveConstants& c = m.top();
  return 4.0 * (c.c2 - 1.0) / c.c2 * m.bar_compliance();
}

// What the asymmetric solver does not evaluate on a layered medium yet.
[[noreturn]] void layered_refusal(const Medium& m, const std::string& what) {
  throw std::invalid_argument(
      what + " on " + describe(m.spec()) +
      " is not available from the asymmetric solver yet (the homogeneous layer's only); the "
      "contact, pressure, drag, surface slope and surface stress are (and, without friction, "
      "the stresses at depth)");
}

}  // namespace

const DampedLayerModel* AsymmetricSolution::layer() const { return model_->homogeneous_layer(); }

cplx AsymmetricSolution::bottom_w(const DampedResponse& r) const {
  if (!(params_.friction > 0.0)) return r.Wb;
  return r.Wb + cplx(0.0, params_.friction) * r.Wqb;
}

cplx AsymmetricSolution::surface_stress_integrand(const DampedResponse& r, double alpha) const {
  const double phi2 = model_->phi2();
  if (!(params_.friction > 0.0)) return r.M2 - model_->half_plane_m2(alpha);
  const WaveConstants& c = model_->top();
  const double ep = 4.0 * (c.c2 - 1.0) / c.c2, c0 = bar_pole(*model_);
  const cplx tq = ep * (r.Uq - model_->tangential().Uq) - c0 * std::exp(-alpha) / alpha;
  return r.M2 - phi2 - cplx(0.0, params_.friction) * tq;
}

Eigen::VectorXd AsymmetricSolution::atan_weights(const JacobiSeries& ser) const {
  Eigen::VectorXd wg(atan_rule_.x.size());
  ser.g_values(atan_rule_.x.data(), static_cast<int>(wg.size()), wg.data());
  return (wg.array() * atan_rule_.w.array()).matrix();
}

double AsymmetricSolution::friction_surface_terms(double x, const JacobiSeries& ser,
                                                  const Eigen::VectorXd& wg, double c,
                                                  double w) const {
  // f Cq (1/pi) int p/(xi - x) - (f C0/pi) int p(xi) arctan(x - xi) d xi for p(c + w r) = w(r)
  // g(r).
  const WaveConstants& wc = model_->top();
  const double ep = 4.0 * (wc.c2 - 1.0) / wc.c2;
  const double cq = ep * model_->tangential().Uq, f = params_.friction;
  return f * cq * ser.cauchy((x - c) / w) + bar_term(x, wg, c, w);
}

double AsymmetricSolution::bar_term(double x, const Eigen::VectorXd& wg, double c, double w) const {
  const double c0 = bar_pole(*model_);
  if (c0 == 0.0) return 0.0;  // a bonded half-space takes the net horizontal force
  double at = 0.0;
  for (Eigen::Index j = 0; j < atan_rule_.x.size(); ++j)
    at += wg(j) * std::atan(x - c - w * atan_rule_.x(j));
  return -params_.friction * c0 / kPi * w * at;
}

namespace {

// The half-plane mode mix of the unit tangential load (top T = 1, S = 0) on
// the regularised basis of the normal load's (WaveConstants::hp1, hp2):
// h1 v_T e_T + h2 [e_L dv + v_T (e_L - e_T)/delta].
std::pair<double, double> tangential_mix(const WaveConstants& c) {
  const double q = (1.0 + c.nT * c.nT) / c.nT;  // v_T's T entry
  const double h2 = 1.0 / (0.5 * q * c.dS + c.dT);
  return {0.5 * c.dS * h2, h2};
}

// The half-plane parts (sigma_x, sigma_y, tau_xy)/(P/h) at (u, y), u from the
// contact's centre, y < 0, of the normal load p and of the shear traction f p
// for a Jacobi density (as detail::half_plane_stresses for a U-series):
// F = i Phi, Phi(z) = (1/pi) int w g/(z - t) = -cauchy_upper(z), at
// z_n = (u - i n y)/w. The normal mix's cos-type terms take Re F, its tau
// Im F; the shear traction's amplitudes are i f [Sigma_x, S] and f T:
// -f Im F and f Re F.
Eigen::Vector3d jacobi_half_plane(const WaveConstants& c, const JacobiSeries& js, double w,
                                  double u, double y, double f) {
  const double nT = c.nT, nL = c.nL, d = c.delta;
  const Eigen::Vector4d vT(1.0, -1.0 / nT, (1.0 + nT * nT) / nT, -2.0);
  const Eigen::Vector4d dv(0.0, c.dW, c.dT, c.dS);
  auto F = [&js](cplx z) { return cplx(0.0, -1.0) * js.cauchy_upper(z); };
  auto dF = [&js](cplx z) {
    cplx der;
    js.cauchy_upper(z, &der);
    return cplx(0.0, -1.0) * der;
  };
  const cplx zT = detail::z_of(u, nT, y, w), zL = detail::z_of(u, nL, y, w);
  const cplx fT = F(zT), fL = F(zL);
  const cplx fD = detail::divided_difference(F, dF, zT, zL, d, cplx(0.0, -y / w));
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  const auto [q1, q2] = tangential_mix(c);
  for (int load = 0; load < 2; ++load) {
    const double h1 = load == 0 ? c.hp1 : q1, h2 = load == 0 ? c.hp2 : q2;
    if (load == 1 && !(f > 0.0)) break;
    const double kT[3] = {h1 * sigma_x_hat(c, vT), h1 * vT(3), h1 * vT(2)};
    const double kL[3] = {h2 * sigma_x_hat(c, dv), h2 * dv(3), h2 * dv(2)};
    const double kD[3] = {h2 * sigma_x_hat(c, vT), h2 * vT(3), h2 * vT(2)};
    for (int m = 0; m < 3; ++m) {
      const bool cos_type = m < 2;
      if (load == 0) {
        out(m) += cos_type ? kT[m] * fT.real() + kL[m] * fL.real() + kD[m] * fD.real()
                           : kT[m] * fT.imag() + kL[m] * fL.imag() + kD[m] * fD.imag();
      } else {
        out(m) += cos_type ? -f * (kT[m] * fT.imag() + kL[m] * fL.imag() + kD[m] * fD.imag())
                           : f * (kT[m] * fT.real() + kL[m] * fL.real() + kD[m] * fD.real());
      }
    }
  }
  return out;
}

}  // namespace

std::shared_ptr<const Eigen::MatrixXd> AsymmetricSolution::friction_depth_coefficients(
    double y) const {
  if (!layer()) layered_refusal(*model_, "the stress field below the surface");
  // The shear traction's remainder (state i f z_q less its half-plane mix,
  // the bar pole C0 e^-alpha/alpha out of sigma_x) at depth y: Filon
  // coefficients, columns [sigma_x, sigma_y, tau] real parts, then imaginary.
  const Fine& f = light();
  const WaveConstants& c = model_->top();
  const auto nq = static_cast<Eigen::Index>(f.alpha.size());
  const double ep = 4.0 * (c.c2 - 1.0) / c.c2, c0 = ep / (ep - c.s), fr = params_.friction;
  const auto [q1, q2] = tangential_mix(c);
  const cplx i(0.0, 1.0);
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(nq, 6);
  for (Eigen::Index k = 0; k < nq; ++k) {
    const auto q = static_cast<std::size_t>(k);
    const double al = f.alpha[q];
    const Eigen::Matrix4d C = detail::modal_columns(c, al, y);
    const Eigen::Vector4cd z =
        model_->tangential_state(al, y) - (q1 * C.col(0) + q2 * C.col(1)).cast<cplx>();
    const cplx ph = f.phat[q] * std::exp(cplx(0.0, al * centre_));
    const cplx sx =
        i * fr * (ep * z(0) + (c.c2 - 2.0) / c.c2 * z(3) - c0 * std::exp(-al) / al) * ph;
    const cplx sy = i * fr * z(3) * ph, tau = fr * z(2) * ph;
    set_stress_row(G, k, sx, sy, tau);
  }
  return f.filon_columns(G);
}

std::shared_ptr<const AsymmetricSolution::BottomFriction> AsymmetricSolution::bottom_friction()
    const {
  if (!layer()) layered_refusal(*model_, "the stresses at the base");
  std::lock_guard<std::mutex> lock(bottom_friction_cache_->mutex);
  auto& bp = bottom_friction_cache_->data;
  if (bp) return bp;
  auto b = std::make_shared<BottomFriction>();
  const Fine& f = light();
  const WaveConstants& c = model_->top();
  const double ep = 4.0 * (c.c2 - 1.0) / c.c2, c0 = ep / (ep - c.s), fr = params_.friction;
  const cplx i(0.0, 1.0);
  std::vector<cplx> gx(f.alpha.size()), gy(f.alpha.size()), gt(f.alpha.size());
  for (std::size_t k = 0; k < f.alpha.size(); ++k) {
    const double al = f.alpha[k];
    const Eigen::Vector4cd z = model_->tangential_state(al, -1.0);
    const Eigen::Vector4cd zn = model_->normal_state(al, -1.0);  // the normal load's
    const cplx ph = f.phat[k] * std::exp(cplx(0.0, al * centre_));
    const cplx sx = ep * z(0) + (c.c2 - 2.0) / c.c2 * z(3);
    const cplx sxn = ep * zn(0) + (c.c2 - 2.0) / c.c2 * zn(3);
    // Normal: [Sigma_x, S, -i T]; tangential: i f [Sigma_x, S, -i T].
    gx[k] = (sxn + i * fr * (sx - c0 * std::exp(-al) / al)) * ph;
    gy[k] = (zn(3) + i * fr * z(3)) * ph;
    gt[k] = (-i * zn(2) + fr * z(2)) * ph;
  }
  f.coefficients(gx, b->sx_re, b->sx_im);
  f.coefficients(gy, b->sy_re, b->sy_im);
  f.coefficients(gt, b->t_re, b->t_im);
  bp = b;
  return bp;
}

namespace {

// int p e^{-i alpha x} dx of p(c + w r) = sqrt(1 - r^2) sum b_k U_k(r). With
// b2 (as long as b) and t2: *t2 the same for the coefficients b2 and the
// centre centre2, on the same Bessel functions (the same numbers as a call
// of its own).
cplx u_series_transform(const Eigen::VectorXd& b_, double centre_, double half_, double alpha,
                        const Eigen::VectorXd* b2, double centre2, cplx* t2) {
  const double w = half_, om = std::fabs(alpha) * w;
  // Terms k >= K = e om + 64 add at most (pi/2) max|b| sum_{m >= K}
  // (om/2)^m/m! <= pi max|b| 2^-64 (J_{k+1}(om)/om <= (om/2)^k/(2 (k+1)!) and
  // (e om/(2m))^m <= 2^-m beyond m = e om): below round-off, and a profile's
  // tail-extended series has thousands of terms where K is a few hundred.
  const int n = static_cast<int>(
      std::min<double>(static_cast<double>(b_.size()), std::ceil(2.718281828459045 * om) + 64.0));
  const bool two = b2 != nullptr && t2 != nullptr && b2->size() == b_.size();
  cplx sum = 0.0, sum2 = 0.0;
  if (om < 1e-8) {
    sum = 0.5 * kPi * b_(0);  // J_1(om)/om -> 1/2; higher orders vanish
    if (n > 1) sum += kPi * 2.0 * cplx(0.0, -1.0) * b_(1) * (om / 8.0);
    if (two) {
      sum2 = 0.5 * kPi * (*b2)(0);
      if (n > 1) sum2 += kPi * 2.0 * cplx(0.0, -1.0) * (*b2)(1) * (om / 8.0);
    }
  } else {
    thread_local std::vector<double> J;
    bessel_j(om, n + 1, J);
    cplx ipow = 1.0;  // (-i)^k
    for (int k = 0; k < n; ++k) {
      const double jk = J[static_cast<std::size_t>(k + 1)] / om;
      sum += b_(k) * kPi * (k + 1.0) * ipow * jk;
      if (two) sum2 += (*b2)(k)*kPi * (k + 1.0) * ipow * jk;
      ipow *= cplx(0.0, -1.0);
    }
  }
  if (two) {
    const cplx ph2 = w * std::exp(cplx(0.0, -std::fabs(alpha) * centre2)) * sum2;
    *t2 = alpha < 0.0 ? std::conj(ph2) : ph2;
  } else if (t2 != nullptr) {
    *t2 = u_series_transform(*b2, centre2, half_, alpha);
  }
  cplx ph = w * std::exp(cplx(0.0, -std::fabs(alpha) * centre_)) * sum;
  return alpha < 0.0 ? std::conj(ph) : ph;
}

}  // namespace

void AsymmetricSolution::set_u_slope_nodes(int m) {
  // Gauss-Chebyshev (U): r_i = cos(i pi/(m + 1)), weights sin^2/(m + 1) times g.
  std::vector<double> g(static_cast<std::size_t>(m));
  slope_r_.clear();
  slope_wg_.clear();
  for (int i = 1; i <= m; ++i) slope_r_.push_back(std::cos(i * kPi / (m + 1)));
  u_series(b_, slope_r_.data(), g.data(), m);
  for (int i = 1; i <= m; ++i) {
    const double th = i * kPi / (m + 1);
    slope_wg_.push_back(std::sin(th) * std::sin(th) / (m + 1) * g[static_cast<std::size_t>(i - 1)]);
  }
}

double AsymmetricSolution::surface_slope(double x) const {
  // -(phi1/pi) int p/(xi - x) + (phi1/pi) int p(xi) K(x - xi) d xi, per P/h times load.
  return params_.load * model_->phi1() * (-cauchy_part(x) + half_ * kernel_part(x));
}

double AsymmetricSolution::cauchy_part(double x) const {
  const double w = half_, z = (x - centre_) / w;
  double cauchy = 0.0;  // sum b_n (1/pi) int sqrt(1-r^2) U_n/(r - z) dr
  const int n = static_cast<int>(b_.size());
  if (jac_) {
    // (1/pi) int w g/(r - z) plus the local term f Phi p of the frictional equation.
    cauchy = jac_->cauchy(z) + params_.friction * model_->tangential().Phi * jac_->density(z);
  } else if (std::fabs(z) < 1.0) {
    double tkm1 = 1.0, tk = z;  // T_0, T_1
    for (int k = 0; k < n; ++k) {
      cauchy -= b_(k) * tk;
      const double tn = 2.0 * z * tk - tkm1;
      tkm1 = tk;
      tk = tn;
    }
  } else {
    // Beside the contact: sum b_k q^(k+1), stopped where |q|^(k+1), a bound
    // on what is left relative to sum |b_k| (|q| < 1), falls below 1e-17 (a
    // long, tail-extended series stops far short of its length).
    const double q = z - (z > 0 ? 1.0 : -1.0) * std::sqrt(z * z - 1.0);
    double qk = q;
    for (int k = 0; k < n; ++k) {
      if (std::fabs(qk) < 1e-17) break;
      cauchy -= b_(k) * qk;
      qk *= q;
    }
  }
  return cauchy;
}

double AsymmetricSolution::kernel_part(double x) const { return regular_part(x) + memory_part(x); }

double AsymmetricSolution::memory_part(double x) const {
  // A viscoelastic top's memory part, exact against the U-series of g.
  const MemoryKernel* mem = model_->memory();
  if (mem && t_coef_.size() > 0)  // a flat face: its T-series
    return mem->apply(t_coef_, (x - centre_) / half_, half_, MemoryBasis::T) / half_;
  return mem ? mem->apply(b_, (x - centre_) / half_, half_) / half_ : 0.0;
}

double AsymmetricSolution::regular_part(double x) const {
  // Kernel part by Gauss-Chebyshev (U) quadrature of p K: (1/pi) int
  // sqrt(1-r^2) f ~ sum W_i f(r_i), on the nodes prepared by the solve.
  thread_local std::vector<double> u, kv;
  u.resize(slope_r_.size());
  kv.resize(u.size());
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = x - centre_ - half_ * slope_r_[i];
  kernel_->many(u.data(), kv.data(), u.size());
  double kern = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) kern += slope_wg_[i] * kv[i];
  return kern;
}

const AsymmetricSolution::Fine& AsymmetricSolution::light() const {
  std::lock_guard<std::mutex> lock(light_cache_->mutex);
  if (!light_cache_->fine)
    light_cache_->fine = std::make_shared<const Fine>(build_fine(2.0 * half_));
  return *light_cache_->fine;
}

void AsymmetricSolution::offer_light(Fine f) const {
  std::lock_guard<std::mutex> lock(light_cache_->mutex);
  if (!light_cache_->fine) light_cache_->fine = std::make_shared<const Fine>(std::move(f));
}

double AsymmetricSolution::stress_error_estimate() const {
  std::lock_guard<std::mutex> lock(stress_cache_->mutex);
  StressCache& c = *stress_cache_;
  if (!c.done) {
    if (c.compute) c.value = c.compute(*this);
    c.done = true;
    c.compute = nullptr;  // (its captured series freed)
  }
  return c.value;
}

AsymmetricSolution::Fine AsymmetricSolution::build_fine(double freq, const Eigen::VectorXd* db,
                                                        std::vector<cplx>* dphat) const {
  Fine f;
  f.freq = freq;
  AlphaQuadrature panels;
  const AsymmetricQuadrature& Q = kernel_->quadrature();
  const auto& P = Q.panels;
  const double width = std::min(0.5, 1.5 / std::max(freq, 1e-300));
  // Each panel split into pieces no wider than `width` (counted first: the
  // vectors are reserved, a few hundred nodes).
  std::vector<int> split(P.panel_centre.size());
  std::size_t total = 0;
  for (std::size_t p = 0; p < split.size(); ++p) {
    split[p] = std::max(1, static_cast<int>(std::ceil(2.0 * P.panel_half[p] / width)));
    total += static_cast<std::size_t>(split[p]);
  }
  panels.panel_centre.reserve(total);
  panels.panel_half.reserve(total);
  f.alpha.reserve(15 * total);
  f.weight.reserve(15 * total);
  f.r.reserve(15 * total);
  f.phat.reserve(15 * total);
  if (db != nullptr) dphat->reserve(dphat->size() + 15 * total);
  for (std::size_t p = 0; p < P.panel_centre.size(); ++p) {
    const double lo = P.panel_centre[p] - P.panel_half[p];
    const double len = 2.0 * P.panel_half[p];
    const int m = split[p];
    for (int q = 0; q < m; ++q) {
      const double c = lo + (q + 0.5) * len / m, h = 0.5 * len / m;
      panels.panel_centre.push_back(c);
      panels.panel_half.push_back(h);
      for (int j = 0; j < 15; ++j) {
        // An unsplit panel: the quadrature's own nodes and responses.
        const double a = m == 1 ? P.alpha[15 * p + static_cast<std::size_t>(j)] : gk_node(j, c, h);
        f.alpha.push_back(a);
        f.weight.push_back(m == 1 ? P.weight[15 * p + static_cast<std::size_t>(j)]
                                  : gk_weight(j, h));
        f.r.push_back(m == 1 ? Q.r[15 * p + static_cast<std::size_t>(j)]
                             : model_->full_response(a));
        cplx dp = 0.0;
        if (jac_ && db != nullptr && a >= 0.0 && a * half_ <= jtr_omega_) {
          const auto [t, t2] = jtr_->both(a * half_);
          f.phat.push_back(half_ * std::exp(cplx(0.0, -a * centre_)) * t);
          dp = half_ * t2;
        } else if (jac_) {
          f.phat.push_back(pressure_transform(a));
          if (db != nullptr) dp = half_ * jtr_->second(a * half_);
        } else {
          f.phat.push_back(db == nullptr ? pressure_transform(a)
                                         : u_series_transform(b_, centre_, half_, a, db, 0.0, &dp));
        }
        if (db != nullptr) dphat->push_back(dp);
      }
    }
  }
  f.filon = std::make_shared<const FilonIntegrator>(panels);
  std::vector<cplx> g(f.alpha.size());
  for (std::size_t i = 0; i < g.size(); ++i)
    g[i] = surface_stress_integrand(f.r[i], f.alpha[i]) * f.phat[i] *
           std::exp(cplx(0.0, f.alpha[i] * centre_));
  f.coefficients(g, f.sx_re, f.sx_im);
  return f;
}

std::shared_ptr<Eigen::MatrixXd> AsymmetricSolution::Fine::filon_columns(
    const Eigen::MatrixXd& G) const {
  const Eigen::Index nq = G.rows();
  auto coef = std::make_shared<Eigen::MatrixXd>(nq, G.cols());
  std::vector<double> col(static_cast<std::size_t>(nq));
  for (Eigen::Index m = 0; m < G.cols(); ++m) {
    Eigen::Map<Eigen::VectorXd>(col.data(), nq) = G.col(m);
    const std::vector<double> cm = filon->coefficients(col);
    coef->col(m) = Eigen::Map<const Eigen::VectorXd>(cm.data(), nq);
  }
  return coef;
}

void AsymmetricSolution::Fine::coefficients(const std::vector<cplx>& g, std::vector<double>& c_re,
                                            std::vector<double>& c_im) const {
  filon_coefficients(*filon, g, c_re, c_im);
}

double AsymmetricSolution::Fine::fourier(const std::vector<double>& c_re,
                                         const std::vector<double>& c_im, double x) const {
  return filon->integral(x, c_re).real() - filon->integral(x, c_im).imag();
}

std::shared_ptr<const AsymmetricSolution::Fine> AsymmetricSolution::fine_for(double x) const {
  const double need = 2.0 * half_ + std::fabs(centre_) + std::fabs(x);
  {
    std::lock_guard<std::mutex> lock(fine_cache_->mutex);
    auto& f = fine_cache_->fine;
    if (!f) f = std::make_shared<const Fine>(build_fine(6.0 * half_ + std::fabs(centre_)));
    if (need <= f->freq) return f;
  }
  return std::make_shared<const Fine>(build_fine(need));
}

Eigen::VectorXd AsymmetricSolution::pressure(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  return at_points(x, [this](double v) { return pressure(v); });
}

Eigen::VectorXd AsymmetricSolution::surface_stress(
    const Eigen::Ref<const Eigen::VectorXd>& x) const {
  return at_points(x, [this](double v) { return surface_stress(v); });
}

Eigen::VectorXd AsymmetricSolution::surface_displacement(
    const Eigen::Ref<const Eigen::VectorXd>& x) const {
  return at_points(x, [this](double v) { return surface_displacement(v); });
}

double AsymmetricSolution::surface_stress(double x) const {
  if (!std::isfinite(x)) throw std::invalid_argument("surface_stress: x must be finite");
  const Fine& f = light();
  double local = pressure(x);
  if (model_->stress_memory() != nullptr) local += stress_memory_part(x);
  const double s = -model_->phi2() * local - f.fourier(f.sx_re, f.sx_im, x - centre_) / kPi;
  if (jac_) return s + friction_surface_terms(x, *jac_, atan_wg_, centre_, half_);
  return s;
}

Eigen::Vector3d AsymmetricSolution::stresses(double x, double y) const {
  const Eigen::VectorXd xs = Eigen::VectorXd::Constant(1, x), ys = Eigen::VectorXd::Constant(1, y);
  const StressField g = stress_field(xs, ys);
  return {g.sigma_x(0, 0), g.sigma_y(0, 0), g.tau_xy(0, 0)};
}

// Stresses: sigma(x, y)/(P/h) = (1/pi) Re int_0^inf [Sigma_x, S, -iT](alpha, y) p^ e^{i alpha x},
// from the state [U, W, T, S] (DampedLayerModel::state; tau ~ sin(alpha x) has
// the complex amplitude -iT). At large alpha the amplitudes tend to the
// half-plane mode mix's (real, e^{n alpha y}: the base does not matter), whose
// integral decays only like e^{nT alpha y}, so it is split off as for the
// displacements: the remainder (which decays like e^{-nT alpha (2 + y)} at
// every depth) by Filon sums on light_'s nodes (exact in x; [0, alpha_max]
// covers e^{-nT alpha} to 1e-18, the slowest, at y = -1), and the half-plane
// part in closed form from the U-series of p (potentials.hpp, all n). The
// surface row y = 0 is surface_stress, -p and 0 (the same split: the
// remainder there is -(M2 - phi2), the closed form -phi2 p, -p, 0).

std::shared_ptr<const AsymmetricSolution::FieldNodes> AsymmetricSolution::field_nodes() const {
  std::lock_guard<std::mutex> lock(field_cache_->mutex);
  auto& np = field_cache_->nodes;
  if (np) return np;
  auto n = std::make_shared<FieldNodes>();
  const Fine& f = light();
  if (!layer()) {
    // Any other medium: each node's mode profile (its remainder at any
    // depth: the state less the top material's half-plane state, sigma_x by
    // the material at that depth), the phase p^ e^{i alpha c}.
    n->modes.reserve(f.alpha.size());
    n->ph.resize(f.alpha.size());
    double ref = 0.0;
    for (std::size_t q = 0; q < f.alpha.size(); ++q) {
      check_interrupt();
      n->modes.push_back(model_->mode(f.alpha[q]));
      n->ph[q] = f.phat[q] * std::exp(cplx(0.0, f.alpha[q] * centre_));
      ref = std::max(ref, std::abs(n->ph[q]));
    }
    n->negligible = 1e-18 * ref / static_cast<double>(std::max<std::size_t>(f.alpha.size(), 1));
    np = n;
    return np;
  }
  const WaveConstants& c = model_->top();
  const auto nq = static_cast<Eigen::Index>(f.alpha.size());
  // |entries| of v_T(+-nT) and dv(+-), the columns' vectors (modal_columns).
  const double kc = std::max({2.0, 1.0 / c.nT, (1.0 + c.nT * c.nT) / c.nT, std::fabs(c.dW),
                              std::fabs(c.dT), std::fabs(c.dS)});
  n->d_re.resize(4, nq);
  n->d_im.resize(4, nq);
  n->ph.resize(f.alpha.size());
  n->top_bound.resize(f.alpha.size());
  n->bottom_bound.resize(f.alpha.size());
  double ref = 0.0;
  for (Eigen::Index k = 0; k < nq; ++k) {
    const auto q = static_cast<std::size_t>(k);
    const double al = f.alpha[q];
    Eigen::Vector4cd d = layer()->state_coefficients(al);
    if (al >= DampedLayerModel::kSmallT) d -= Eigen::Vector4cd(c.hp1, c.hp2, 0.0, 0.0);
    n->d_re.col(k) = d.real();
    n->d_im.col(k) = d.imag();
    n->ph[q] = f.phat[q] * std::exp(cplx(0.0, al * centre_));
    const double m = std::abs(n->ph[q]) * kc;
    n->top_bound[q] = m * (std::abs(d(0)) + std::abs(d(1)));
    n->bottom_bound[q] = m * (std::abs(d(2)) + std::abs(d(3)));
    ref = std::max(ref, std::abs(n->ph[q]));
  }
  // The stresses are O(p^(0)) = O(ref) (p^(0) = int p); a node's weight is
  // at most 0.5 and there are nq of them.
  n->negligible = 1e-18 * ref / static_cast<double>(std::max<Eigen::Index>(nq, 1));
  np = n;
  return np;
}

std::shared_ptr<const Eigen::MatrixXd> AsymmetricSolution::depth_coefficients(
    const FieldNodes& nodes, double y, bool below) const {
  constexpr std::size_t kDepthsKept = 4;
  const DepthKey key(y, below);
  {
    std::lock_guard<std::mutex> lock(field_cache_->mutex);
    for (const auto& [depth, coef] : field_cache_->depths)
      if (depth == key) return coef;
  }
  const Fine& f = light();
  const WaveConstants& c = model_->top();
  const auto nq = static_cast<Eigen::Index>(f.alpha.size());
  // Remainder integrands [sigma_x, sigma_y, tau] real parts, then imaginary
  // parts (zero at nodes whose bound is negligible).
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(nq, 6);
  const double ax = 4.0 * (c.c2 - 1.0) / c.c2, ay = (c.c2 - 2.0) / c.c2;
  const double yb = y + 1.0;
  for (Eigen::Index k = 0; k < nq; ++k) {
    const auto q = static_cast<std::size_t>(k);
    const double al = f.alpha[q];
    Eigen::Vector4d r_re, r_im;
    if (!nodes.modes.empty()) {
      // Any other medium: the node's own remainder (sigma_x of the material
      // at y, at an interface the side asked).
      const ModeState st = nodes.modes[q]->remainder(y, below);
      const cplx ph = nodes.ph[q];
      const cplx sx = st.sx * ph, sy = st.z(3) * ph, tau = cplx(0.0, -1.0) * st.z(2) * ph;
      set_stress_row(G, k, sx, sy, tau);
      continue;
    }
    if (al < DampedLayerModel::kSmallT) {
      const Eigen::Matrix4d T = detail::transfer_matrix(c, al, y);
      const Eigen::Matrix4d C = detail::modal_columns(c, al, y);
      r_re = T * nodes.d_re.col(k) - (c.hp1 * C.col(0) + c.hp2 * C.col(1));
      r_im = T * nodes.d_im.col(k);
    } else {
      // |columns 0, 1| <= kc e^{nT al y} (1 + al |y|), |columns 2, 3| <= kc
      // e^{-nT al (y + 1)} (1 + al (y + 1)) (|E(x)| <= |x| in modal_columns).
      const double bound = nodes.top_bound[q] * std::exp(c.nT * al * y) * (1.0 - al * y) +
                           nodes.bottom_bound[q] * std::exp(-c.nT * al * yb) * (1.0 + al * yb);
      if (bound < nodes.negligible) continue;
      const Eigen::Matrix4d C = detail::modal_columns(c, al, y);
      r_re = C * nodes.d_re.col(k);
      r_im = C * nodes.d_im.col(k);
    }
    const cplx ph = nodes.ph[q];
    const cplx sx = cplx(ax * r_re(0) + ay * r_re(3), ax * r_im(0) + ay * r_im(3)) * ph;
    const cplx sy = cplx(r_re(3), r_im(3)) * ph, tau = cplx(r_im(2), -r_re(2)) * ph;
    set_stress_row(G, k, sx, sy, tau);
  }
  auto coef = f.filon_columns(G);
  std::lock_guard<std::mutex> lock(field_cache_->mutex);
  auto& kept = field_cache_->depths;
  if (kept.size() >= kDepthsKept) kept.erase(kept.begin());
  kept.emplace_back(key, coef);
  return coef;
}

void AsymmetricSolution::check_inertial_depths(const Eigen::Ref<const Eigen::VectorXd>& y,
                                               const char* what) const {
  // The tail beyond the fine nodes reaches 36/(nT |y|); a depth shallower
  // than 36/(nT kTailReach) would need more of it: refused by name (the
  // surface row y = 0 is the surface's own).
  constexpr double kTailReach = 2e4;
  const double shallowest = 36.0 / (model_->top().nT * kTailReach);
  for (Eigen::Index i = 0; i < y.size(); ++i)
    if (y(i) < 0.0 && y(i) > -shallowest) {
      std::ostringstream o;
      o.precision(6);
      o << "y: the " << what << " of a viscoelastic layer with inertia (vstar = " << model_->vstar()
        << ") are computed on the surface (y = 0) and at depths -1 <= y/h <= " << -shallowest
        << " (shallower, the modes' tail beyond alpha h = " << kTailReach
        << " would be summed); given y = " << y(i);
      throw InvalidParameter("y", "0 or -1 <= y <= " + std::to_string(-shallowest), o.str());
    }
}

AlphaQuadrature AsymmetricSolution::tail_panels(double from, double reach,
                                                std::vector<cplx>& ph) const {
  // Gauss-Kronrod panels on [from, reach] as wide as the fine nodes' (min(0.5,
  // 1.5/(2w)): p^ e^{i alpha c} oscillates like e^{+-i alpha w}), and p^ e^{i
  // alpha c} at their nodes.
  const double width = std::min(0.5, 1.5 / std::max(2.0 * half_, 1e-300));
  const int panels = std::max(1, static_cast<int>(std::ceil((reach - from) / width)));
  const double h = 0.5 * (reach - from) / panels;
  AlphaQuadrature q;
  q.panel_centre.reserve(static_cast<std::size_t>(panels));
  q.panel_half.assign(static_cast<std::size_t>(panels), h);
  q.alpha.reserve(15 * static_cast<std::size_t>(panels));
  q.weight.reserve(q.alpha.capacity());
  ph.clear();
  ph.reserve(q.alpha.capacity());
  for (int p = 0; p < panels; ++p) {
    check_interrupt();  // Ctrl-C: the caller evaluates 15 layer modes a panel
    const double c = from + (2 * p + 1) * h;
    q.panel_centre.push_back(c);
    for (int j = 0; j < 15; ++j) {
      const double a = gk_node(j, c, h);
      q.alpha.push_back(a);
      q.weight.push_back(gk_weight(j, h));
      ph.push_back(pressure_transform(a) * std::exp(cplx(0.0, a * centre_)));
    }
  }
  return q;
}

void AsymmetricSolution::inertial_tail(const Eigen::Ref<const Eigen::VectorXd>& x,
                                       const Eigen::Ref<const Eigen::VectorXd>& y, double from,
                                       Eigen::MatrixXd& rem, bool below) const {
  // (1/pi) Re int_from^{36/(nT |y|)} [sx, sy, -i tau]_rem(alpha, y) p^ e^{i alpha x} d alpha
  // for the depths whose remainder (the state less the relaxed half-plane's,
  // ModeProfile::remainder) has not decayed by `from` (e^{-nT alpha |y|} >
  // e^-36 there): Filon panels as the fine nodes' (width min(0.5, 1.5/(2w)):
  // p^ e^{i alpha c} oscillates like e^{+-i alpha w}). The panels and their
  // modes are kept for the farthest reach asked so far, and the Filon
  // coefficients of the last few depths (they do not depend on x: the
  // strains' convolutions along x ask one depth at many points).
  const double rate = model_->top().nT;
  const Eigen::Index nx = x.size(), ny = y.size();
  double reach = from;
  for (Eigen::Index i = 0; i < ny; ++i)
    if (y(i) < 0.0) reach = std::max(reach, 36.0 / (rate * -y(i)));
  if (!(reach > from)) return;
  std::shared_ptr<const TailNodes> tail;
  {
    std::lock_guard<std::mutex> lock(field_cache_->mutex);
    tail = field_cache_->tail;
  }
  if (!tail || tail->reach < reach) {
    auto built = std::make_shared<TailNodes>();
    built->reach = reach;
    built->q = tail_panels(from, reach, built->ph);
    built->modes.reserve(built->q.alpha.size());
    for (double a : built->q.alpha) built->modes.push_back(model_->mode(a));
    built->filon = std::make_shared<const FilonIntegrator>(built->q);
    tail = built;
    std::lock_guard<std::mutex> lock(field_cache_->mutex);
    if (!field_cache_->tail || field_cache_->tail->reach < reach) {
      field_cache_->tail = tail;
      field_cache_->tail_depths.clear();
    } else {
      tail = field_cache_->tail;  // (a wider one built meanwhile)
    }
  }
  const AlphaQuadrature& q = tail->q;
  const FilonIntegrator& filon = *tail->filon;
  const double h = q.panel_half.front();
  const auto nq = static_cast<Eigen::Index>(q.alpha.size());
  Eigen::MatrixXd Wre = Eigen::MatrixXd::Zero(nx, nq), Wim = Eigen::MatrixXd::Zero(nx, nq);
  std::vector<cplx> K;
  for (Eigen::Index j = 0; j < nx; ++j) {
    if (std::fabs(x(j)) > kFarField) continue;
    filon.weights(x(j) - centre_, K);
    for (Eigen::Index k = 0; k < nq; ++k) {
      Wre(j, k) = K[static_cast<std::size_t>(k)].real();
      Wim(j, k) = K[static_cast<std::size_t>(k)].imag();
    }
  }
  constexpr std::size_t kDepthsKept = 4;
  std::vector<double> col(static_cast<std::size_t>(nq));
  for (Eigen::Index i = 0; i < ny; ++i) {
    if (!(y(i) < 0.0) || !(36.0 / (rate * -y(i)) > from)) continue;
    std::shared_ptr<const Eigen::MatrixXd> coef;
    {
      std::lock_guard<std::mutex> lock(field_cache_->mutex);
      if (field_cache_->tail == tail)
        for (const auto& [depth, c] : field_cache_->tail_depths)
          if (depth == DepthKey(y(i), below)) coef = c;
    }
    if (!coef) {
      const double end = 36.0 / (rate * -y(i));
      Eigen::MatrixXd G = Eigen::MatrixXd::Zero(nq, 6);
      for (Eigen::Index k = 0; k < nq; ++k) {
        const auto qk = static_cast<std::size_t>(k);
        if (q.alpha[qk] > end + 2.0 * h) break;  // (the rest below e^-36)
        const ModeState st = tail->modes[qk]->remainder(y(i), below);
        const cplx ph = tail->ph[qk];
        set_stress_row(G, k, st.sx * ph, st.z(3) * ph, cplx(0.0, -1.0) * st.z(2) * ph);
      }
      auto made = std::make_shared<Eigen::MatrixXd>(nq, 6);
      for (Eigen::Index m = 0; m < 6; ++m) {
        Eigen::Map<Eigen::VectorXd>(col.data(), nq) = G.col(m);
        const std::vector<double> cm = filon.coefficients(col);
        made->col(m) = Eigen::Map<const Eigen::VectorXd>(cm.data(), nq);
      }
      coef = made;
      std::lock_guard<std::mutex> lock(field_cache_->mutex);
      if (field_cache_->tail == tail) {
        auto& kept = field_cache_->tail_depths;
        if (kept.size() >= kDepthsKept) kept.erase(kept.begin());
        kept.emplace_back(DepthKey(y(i), below), coef);
      }
    }
    const Eigen::MatrixXd add = (Wre * coef->leftCols(3) - Wim * coef->rightCols(3)) / kPi;
    rem.col(i) += add.col(0);
    rem.col(ny + i) += add.col(1);
    rem.col(2 * ny + i) += add.col(2);
  }
}

StressField AsymmetricSolution::stress_field(const Eigen::Ref<const Eigen::VectorXd>& x,
                                             const Eigen::Ref<const Eigen::VectorXd>& y,
                                             bool below) const {
  detail::check_grid(x, y);
  refuse_flat_memory("stress field below the surface");
  // A viscoelastic layer with inertia: the modes' half-plane part moves with
  // vstar/m(alpha), so the remainder below the relaxed half-plane's decays
  // only like e^{-nT alpha |y|}. Beyond the fine nodes, depths where that is
  // not below e^-36 at their end take the tail up to 36/(nT |y|)
  // (inertial_tail; check_inertial_depths refuses the shallowest).
  const bool inertial = model_->memory() != nullptr && model_->vstar() > 0.0;
  const double fine_end = light().filon->upper();
  if (inertial) check_inertial_depths(y, "stresses");
  if (jac_ && !layer())
    layered_refusal(*model_, "the stress field below the surface with friction");
  const Fine& f = light();
  const auto nodes = field_nodes();
  const WaveConstants& c = model_->top();
  const Eigen::Index nx = x.size(), ny = y.size(), nq = static_cast<Eigen::Index>(f.alpha.size());
  // The Filon coefficients of the remainder, columns [sigma_x, sigma_y, tau] x
  // depth, real parts then imaginary parts (zero on the surface row, which is
  // done apart).
  Eigen::MatrixXd coef = Eigen::MatrixXd::Zero(nq, 6 * ny);
  // Friction: the shear traction's remainder too (columns after the normal's).
  Eigen::MatrixXd fcoef = jac_ ? Eigen::MatrixXd::Zero(nq, 6 * ny) : Eigen::MatrixXd();
  for (Eigen::Index i = 0; i < ny; ++i) {
    if (y(i) == 0.0 || (jac_ && y(i) == -1.0)) continue;
    const auto ci = depth_coefficients(*nodes, y(i), below);
    for (Eigen::Index m = 0; m < 6; ++m) coef.col(m * ny + i) = ci->col(m);
    if (jac_) {
      const auto fi = friction_depth_coefficients(y(i));
      for (Eigen::Index m = 0; m < 6; ++m) fcoef.col(m * ny + i) = fi->col(m);
    }
  }
  Eigen::MatrixXd Wre = Eigen::MatrixXd::Zero(nx, nq), Wim = Eigen::MatrixXd::Zero(nx, nq);
  std::vector<cplx> K;
  for (Eigen::Index j = 0; j < nx; ++j) {
    if (std::fabs(x(j)) > kFarField) continue;
    f.filon->weights(x(j) - centre_, K);
    for (Eigen::Index k = 0; k < nq; ++k) {
      Wre(j, k) = K[static_cast<std::size_t>(k)].real();
      Wim(j, k) = K[static_cast<std::size_t>(k)].imag();
    }
  }
  Eigen::MatrixXd rem =
      (Wre * coef.leftCols(3 * ny) - Wim * coef.rightCols(3 * ny)) / kPi;  // (nx, 3 ny)
  if (jac_) rem += (Wre * fcoef.leftCols(3 * ny) - Wim * fcoef.rightCols(3 * ny)) / kPi;
  if (inertial) inertial_tail(x, y, fine_end, rem, below);
  StressField g;
  g.sigma_x.resize(ny, nx);
  g.sigma_y.resize(ny, nx);
  g.tau_xy.resize(ny, nx);
  // The half-plane potentials of a U-series sum the terms that reach them.
  const Eigen::VectorXd tails = jac_ ? Eigen::VectorXd() : detail::potential_tails(b_);
  // The shear traction's arctan term depends on x alone: once per column.
  Eigen::VectorXd bar = Eigen::VectorXd::Zero(nx);
  if (jac_)
    for (Eigen::Index j = 0; j < nx; ++j)
      if (std::fabs(x(j)) <= kFarField) bar(j) = bar_term(x(j), atan_wg_, centre_, half_);
  for (Eigen::Index i = 0; i < ny; ++i)
    for (Eigen::Index j = 0; j < nx; ++j) {
      if (y(i) == 0.0) {
        g.sigma_x(i, j) = surface_stress(x(j));
        g.sigma_y(i, j) = -pressure(x(j));
        // The shear traction on the layer, f p (towards +x).
        g.tau_xy(i, j) = params_.friction > 0.0 ? params_.friction * pressure(x(j)) : 0.0;
        continue;
      }
      if (std::fabs(x(j)) > kFarField) {
        g.sigma_x(i, j) = g.sigma_y(i, j) = g.tau_xy(i, j) = 0.0;
        continue;
      }
      if (jac_ && y(i) == -1.0) {
        // Friction at y = -1: the normal load's field by a direct
        // Filon sum (the half-plane split is for U-series only; at y = -1 the
        // integrand decays like e^{-nT alpha}), plus the shear traction's.
        const BottomFriction& bf = *bottom_friction();
        const double u = x(j) - centre_;
        g.sigma_x(i, j) = f.fourier(bf.sx_re, bf.sx_im, u) / kPi + bar(j);
        g.sigma_y(i, j) = f.fourier(bf.sy_re, bf.sy_im, u) / kPi;
        g.tau_xy(i, j) = f.fourier(bf.t_re, bf.t_im, u) / kPi;
        continue;
      }
      if (jac_) {
        const Eigen::Vector3d hp =
            jacobi_half_plane(c, *jac_, half_, x(j) - centre_, y(i), params_.friction);
        g.sigma_x(i, j) = rem(j, i) + hp(0) + bar(j);
        g.sigma_y(i, j) = rem(j, ny + i) + hp(1);
        g.tau_xy(i, j) = rem(j, 2 * ny + i) + hp(2);
        continue;
      }
      const Eigen::Vector3d hp =
          detail::half_plane_stresses(c, b_, half_, x(j) - centre_, y(i), 1, SeriesKind::U, &tails);
      g.sigma_x(i, j) = rem(j, i) + hp(0);
      g.sigma_y(i, j) = rem(j, ny + i) + hp(1);
      g.tau_xy(i, j) = rem(j, 2 * ny + i) + hp(2);
    }
  return g;
}

double AsymmetricSolution::stress_x(double x, double y) const {
  if (y == 0.0) return surface_stress(x);  // the surface: the local term split off
  return stresses(x, y)(0);
}

double AsymmetricSolution::bottom_displacement(double x) const {
  // v(x, -1) = (1/2pi) int (Wb/alpha) p^ e^{i alpha x}; Wb/alpha -> -1/kw at alpha -> 0.
  // Friction: Wb + i f Wqb (the shear traction's bottom W vanishes at alpha -> 0).
  if (model_->long_wave_m1() != 0.0)
    layered_refusal(*model_, "the base face's displacement (a logarithmic far field)");
  const auto f = fine_for(x);
  double sum = 0.0;
  for (std::size_t i = 0; i < f->alpha.size(); ++i)
    if (f->alpha[i] > 0.0)
      sum += f->weight[i] *
             (bottom_w(f->r[i]) / f->alpha[i] * f->phat[i] * std::exp(cplx(0.0, f->alpha[i] * x)))
                 .real();
  return params_.load * sum / kPi;
}

double AsymmetricSolution::bottom_slope(double x) const {
  // dv/dx(x, -1) = (1/2pi) int i alpha (Wb/alpha) p^ e^{i alpha x}, per P/h times load.
  const auto f = fine_for(x);
  double sum = 0.0;
  for (std::size_t i = 0; i < f->alpha.size(); ++i)
    sum += f->weight[i] *
           (cplx(0.0, 1.0) * bottom_w(f->r[i]) * f->phat[i] * std::exp(cplx(0.0, f->alpha[i] * x)))
               .real();
  return params_.load * sum / kPi;
}

double AsymmetricSolution::dissipation() const {
  if (model_->memory() != nullptr && t_coef_.size() > 0) {
    // A flat face on a viscoelastic top: |p^|^2 decays only like 1/alpha
    // (its square-root edges), too slowly for the Parseval sum's tail. The
    // same power in x instead: the surface slope's even kernel is Im M1's,
    // the Cauchy term odd, so load phi1 w int p (regular + memory) dx is
    // (load/pi) int Im M1 |p^|^2 (an absolutely convergent integral; the
    // edges' suction, which the drag is, is the Cauchy term's finite part,
    // not used here). In theta (x = c + w cos theta: p dx = (P/h) w g
    // d theta; the memory's square roots at the edges are analytic in
    // theta), by Gauss-Legendre on pieces graded geometrically towards both
    // edges down to a tenth of the shortest memory's layer there (theta ~
    // sqrt(2 beta/w): within beta of an edge the memory turns from the
    // relaxed to the unrelaxed response, and that layer carries the power
    // as deborah -> 0), each piece's nodes doubled until the sum agrees to
    // 1e-13 of it (or of the round-off of its terms when it is ~0).
    if (memory_unresolved_)
      throw ConvergenceError(
          "dissipation: the viscoelastic memory's boundary layer at the flat face's edges (its "
          "shortest retardation length V tau) is below the collocation's node spacing there: "
          "the power it carries is not computed (the drag is the edges' suction)");
    const RetardationSpectrum& sp = model_->memory()->spectrum();
    const double beta_min = *std::min_element(sp.beta.begin(), sp.beta.end());
    const double th_min = std::min(0.1, 0.1 * std::sqrt(2.0 * beta_min / half_));
    std::vector<double> cuts{0.0};
    for (double t = th_min; t < 0.25 * kPi; t *= 2.0) cuts.push_back(t);
    cuts.push_back(0.5 * kPi);
    for (std::size_t i = cuts.size() - 1; i-- > 0;) cuts.push_back(kPi - cuts[i]);
    const double scale = params_.load * model_->phi1() * half_ * half_;
    double prev = std::numeric_limits<double>::quiet_NaN();
    for (int m = 16; m <= 256; m *= 2) {
      const std::shared_ptr<const JacobiRule> gl = cached_gauss_jacobi(m, 0.0, 0.0);
      double sum = 0.0, abs_sum = 0.0;
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double c = 0.5 * (cuts[k] + cuts[k + 1]), h = 0.5 * (cuts[k + 1] - cuts[k]);
        for (Eigen::Index q = 0; q < gl->x.size(); ++q) {
          const double r = std::cos(c + h * gl->x(q));
          const double term = h * gl->w(q) * jac_->g(r) * kernel_part(centre_ + half_ * r);
          sum += term;
          abs_sum += std::fabs(term);
        }
      }
      const double now = scale * sum;
      if (std::fabs(now - prev) <= 1e-13 * std::fabs(now) + 1e-13 * scale * abs_sum) return now;
      prev = now;
    }
    std::ostringstream msg;
    msg << "dissipation: the flat face's power integral did not settle at 256 nodes a piece "
           "(last "
        << prev << ")";
    throw ConvergenceError(msg.str());
  }
  const Fine& f = light();
  if (model_->spec().viscoelastic()) {
    // A viscoelastic medium: the power the surface takes in, by Parseval,
    // (load/pi) int_0^inf Im M1 |p^|^2 (Im M1 >= 0 mode by mode: the
    // materials' loss). Im (M1 - H) decays exponentially: the fine nodes
    // (H = phi1, real, under an elastic top: the whole of it). A
    // viscoelastic top's
    // Im H = phi1 sum_k c_k beta_k t/(1 + beta_k^2 t^2) only like 1/t:
    // Gauss-Legendre panels to T = 2000/w (geometric from the spectrum's
    // shortest scale, at most pi/w wide: |p^|^2 oscillates with period pi/w),
    // and beyond T the leading term of |p^|^2, (pi/4)(A_a^2 + A_b^2)/t^3
    // (p ~ A sqrt(distance) at each end), in closed form.
    double sum = 0.0;
    for (std::size_t i = 0; i < f.alpha.size(); ++i)
      sum += f.weight[i] * (f.r[i].M1 - model_->half_plane_m1(f.alpha[i])).imag() *
             std::norm(f.phat[i]);
    const MemoryKernel* mem = model_->memory();
    if (mem == nullptr) return params_.load * sum / kPi;
    const RetardationSpectrum& sp = mem->spectrum();
    const double phi1 = model_->phi1();
    auto im_h = [&](double t) {
      double v = 0.0;
      for (std::size_t k = 0; k < sp.c.size(); ++k)
        v += sp.c[k] * sp.beta[k] * t / (1.0 + sp.beta[k] * sp.beta[k] * t * t);
      return phi1 * v;
    };
    const double w = half_, wide = kPi / w;
    const double beta_max = *std::max_element(sp.beta.begin(), sp.beta.end());
    static const std::shared_ptr<const JacobiRule> gl = cached_gauss_jacobi(16, 0.0, 0.0);
    double ga = 0.0, gb = 0.0;  // g(1), g(-1)
    for (Eigen::Index n = 0; n < b_.size(); ++n) {
      ga += b_(n) * static_cast<double>(n + 1);
      gb += b_(n) * static_cast<double>(n + 1) * ((n % 2) ? -1.0 : 1.0);
    }
    auto tail_beyond = [&](double T) {
      double t = 0.0;
      for (std::size_t k = 0; k < sp.c.size(); ++k)
        t += sp.c[k] * memory_tail_integral(sp.beta[k], T);
      return t * phi1 * 0.25 * kPi * (2.0 / w) * (ga * ga + gb * gb);
    };
    // Panels to T = 2000/w, then T doubled until the total (panels plus the
    // tail beyond T) changes by less than 1e-13 of it: the tail's leading
    // term holds only where |p^|^2 has reached its asymptotics, beyond the
    // pressure's finest scale (a short memory puts a boundary layer of width
    // about beta in it). At most 2^16 panels.
    double lo = 0.0, hi = std::min(wide, 1e-3 / beta_max), mem_sum = 0.0;
    double T = 2000.0 / w, total = std::numeric_limits<double>::quiet_NaN();
    int panels = 0;
    for (;;) {
      while (lo < T) {
        const double c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
        for (Eigen::Index q = 0; q < gl->x.size(); ++q) {
          const double t = c + h * gl->x(q);
          mem_sum += h * gl->w(q) * im_h(t) * std::norm(pressure_transform(t));
        }
        lo = hi;
        hi = std::min({T, 2.0 * lo, lo + wide});
        ++panels;
      }
      const double now = mem_sum + tail_beyond(T);
      // Settled: a change of 1e-13 of the total, or 1e-12 once the panels'
      // terms (16 a panel) are so many that their round-off is of that
      // order; at the cap, 1e-10 (the energy balance's own tolerance).
      const double change = std::fabs(now - total) / std::fabs(sum + now);
      const double settled = panels > (1 << 16) ? 1e-10 : (panels >= 4096 ? 1e-12 : 1e-13);
      if (change <= settled) {
        total = now;
        break;
      }
      if (panels > (1 << 16)) {
        // Never a silent number: the reach stopped before the total settled.
        std::ostringstream m;
        m << "dissipation: the Parseval integral of the viscoelastic memory did not settle "
             "within 2^16 panels (reach alpha h = "
          << T << ", last change " << change
          << " of the total); the drag, from the pressure, stands";
        throw ConvergenceError(m.str());
      }
      total = now;
      T *= 2.0;
      hi = std::min({T, 2.0 * lo, lo + wide});
    }
    const double mem_total = total;
    return params_.load * (sum + mem_total) / kPi;
  }
  // damping sqrt(s) int (v_b')^2 dx / load, with int (v_b')^2 = (load^2/pi) int_0^inf |Wb p^|^2.
  double sum = 0.0;
  for (std::size_t i = 0; i < f.alpha.size(); ++i)
    sum += f.weight[i] * std::norm(bottom_w(f.r[i]) * f.phat[i]);
  return model_->base_damper() * params_.load * sum / kPi;
}

// ---------------------------------------------------------------------------
// Displacements: v(x, y)/(P/(mu h)) = (1/pi) Re int_0^inf (W(alpha, y)/alpha) p^ e^{i alpha x},
// W = alpha v^/p^ (state row 1; -M1 at the top). W/alpha behaves like
// W_hp(alpha, y)/alpha at large alpha (log-singular at the surface), so it is
// split as the undamped code splits it: the smooth [W - W_hp (1 - e^-alpha)]/alpha
// by Filon sums on light_ (exact in x), and the half-plane part
// W_hp (1 - e^-alpha)/alpha, which is real (it does not see the base), in
// closed form from the U-series of p (potentials.hpp). W/alpha stays finite at
// alpha -> 0 (kw > 0: v^(0) = -p^(0)/kw).

double AsymmetricSolution::arctan_integral(double x) const {
  // int p(xi) arctan(x - xi) d xi / (P/h) by atan_rule_ (friction only).
  double at = 0.0;
  for (Eigen::Index j = 0; j < atan_rule_.x.size(); ++j)
    at += atan_wg_(j) * std::atan(x - centre_ - half_ * atan_rule_.x(j));
  return half_ * at;
}

Eigen::VectorXd AsymmetricSolution::friction_displacement(
    const Eigen::Ref<const Eigen::VectorXd>& x, double y) const {
  // v(x, y)/h = load (1/pi) Re int [W_n + i f W_q]/alpha p^ e^{i alpha x}, split as
  // the frictionless displacement is (the half-plane mixes times (1 - e^-alpha)
  // in closed form), and the shear traction's pole W_q(0, y)/alpha (the bar's
  // Poisson thinning: a step in v) as e^-alpha/alpha, in closed form through
  // int p arctan(x - xi). The half-plane part: V(z) = w [Lambda(z + i/w) -
  // Lambda(z)], Lambda' = Phi = -cauchy_upper, by a graded Gauss-Legendre
  // rule on the vertical segment; V' = w [Phi(z + i/w) - Phi(z)].
  const Fine& f = light();
  const WaveConstants& c = model_->top();
  const double fr = params_.friction, w = half_;
  const auto [q1, q2] = tangential_mix(c);
  // W_q(0, y) by Richardson from two small wavenumbers (error O(t^2)).
  const double t0 = 1e-5;
  const double w0 = 2.0 * model_->tangential_state(t0, y)(1).real() -
                    model_->tangential_state(2.0 * t0, y)(1).real();
  std::vector<cplx> g(f.alpha.size());
  for (std::size_t k = 0; k < g.size(); ++k) {
    const double al = f.alpha[k];
    const Eigen::Matrix4d C = detail::modal_columns(c, al, y);
    const double wn_hp = c.hp1 * C(1, 0) + c.hp2 * C(1, 1);
    const double wq_hp = q1 * C(1, 0) + q2 * C(1, 1);
    const cplx wn = y == 0.0 ? -f.r[k].M1 : model_->normal_state(al, y)(1);
    const cplx wq = y == 0.0 ? f.r[k].Wq : model_->tangential_state(al, y)(1);
    const cplx rn = (wn + wn_hp * std::expm1(-al)) / al;
    const cplx rq = (wq + wq_hp * std::expm1(-al) - w0 * std::exp(-al)) / al;
    g[k] = (rn + cplx(0.0, fr) * rq) * f.phat[k] * std::exp(cplx(0.0, al * centre_));
  }
  std::vector<double> g_re, g_im;
  f.coefficients(g, g_re, g_im);
  const JacobiSeries& js = *jac_;
  auto Phi = [&js](cplx z) { return -js.cauchy_upper(z); };
  auto V = [&](cplx z) {
    // w int_0^{1/w} Phi(z + i tau) i d tau, panels graded towards tau = 0.
    cplx sum = 0.0;
    double lo = 0.0;
    for (int k = 64; k >= 0; --k) {                    // ratio 10^(1/4.5): each panel resolves
      const double hi = std::pow(10.0, -k / 4.5) / w;  // a singularity its length away
      for (int j = 0; j < 8; ++j)
        sum += detail::kGw[j] * (hi - lo) * Phi(z + cplx(0.0, lo + detail::kGx[j] * (hi - lo)));
      lo = hi;
    }
    return cplx(0.0, w) * sum;
  };
  auto dV = [&](cplx z) { return w * (Phi(z + cplx(0.0, 1.0 / w)) - Phi(z)); };
  Eigen::VectorXd v(x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    if (std::fabs(x(j)) > kFarField) {
      v(j) = 0.0;
      continue;
    }
    const double u = x(j) - centre_;
    const cplx zT = detail::z_of(u, c.nT, y, w), zL = detail::z_of(u, c.nL, y, w);
    const cplx vT = V(zT), vL = V(zL);
    const cplx vD = detail::divided_difference(V, dV, zT, zL, c.delta, cplx(0.0, -y / w));
    double hp = 0.0;
    for (int load = 0; load < 2; ++load) {
      const double h1 = load == 0 ? c.hp1 : q1, h2 = load == 0 ? c.hp2 : q2;
      const cplx sum = h1 * (-1.0 / c.nT) * vT + h2 * c.dW * vL + h2 * (-1.0 / c.nT) * vD;
      hp += load == 0 ? sum.real() : -fr * sum.imag();
    }
    const double pole = -fr * w0 / kPi * arctan_integral(x(j));
    v(j) = params_.load * (f.fourier(g_re, g_im, u) / kPi + hp + pole);
  }
  return v;
}

std::shared_ptr<const AsymmetricSolution::Surface> AsymmetricSolution::surface() const {
  std::lock_guard<std::mutex> lock(surface_cache_->mutex);
  auto& sp = surface_cache_->surface;
  if (sp) return sp;
  auto s = std::make_shared<Surface>();
  const Fine& f = light();
  // Under a half-space M1 -> m0 as alpha -> 0 (the substrate's half-plane):
  // m0 e^-alpha/alpha comes out of the sum (its logarithm in x below).
  s->m0 = model_->long_wave_m1();
  std::vector<cplx> g(f.alpha.size());
  for (std::size_t i = 0; i < g.size(); ++i) {
    // M1 less its half-plane part H (1 - e^-alpha): H = phi1 for an elastic
    // top, (1 - nu)/m(alpha) for a viscoelastic one (memory_displacement).
    const double al = f.alpha[i];
    g[i] = (f.r[i].M1 + model_->half_plane_m1(al) * std::expm1(-al) - s->m0 * std::exp(-al)) / al *
           f.phat[i] * std::exp(cplx(0.0, al * centre_));
  }
  f.coefficients(g, s->smooth_re, s->smooth_im);
  detail::log1p_rule(b_, half_, s->log1p_r, s->log1p_w);
  if (s->m0 != 0.0) s->reference = surface_value(*s, kDisplacementReference);
  s->indentation = punch_->height(centre_) - params_.load * surface_value(*s, centre_);
  if (!std::isfinite(s->indentation))
    throw ConvergenceError("damped contact: the indentation came out non-finite (N = " +
                           std::to_string(n_) + "); the displacement is not trusted");
  sp = s;
  return sp;
}

double AsymmetricSolution::surface_value(const Surface& s, double x) const {
  // -(1/pi) Re int [M1 - phi1 (1 - e^-a)]/a p^ e^{iax}
  // - (phi1/(2 pi)) int p ln(1 + (x - xi)^2) + (phi1/pi) int p ln|x - xi|,
  // the last = phi1 w [(b0/2) ln w + sum b_n L_n((x - c)/w)].
  const Fine& f = light();
  const double phi1 = model_->phi1(), w = half_, u = x - centre_;
  const double smooth = f.fourier(s.smooth_re, s.smooth_im, u) / kPi;
  const double l1 = detail::log1p_sum(s.log1p_r, s.log1p_w, w, u);
  double lp = 0.5 * b_(0) * std::log(w);
  for (Eigen::Index n = 0; n < b_.size(); ++n)
    lp += b_(n) * detail::log_potential(static_cast<int>(n), u / w);
  const double hp = -w * l1 / (2.0 * kPi) + w * lp;  // U(x), the half-plane potential
  // Under a half-space: -(m0/pi) Re int e^-a/a p^ e^{iax} = (m0/(2 pi)) int p
  // ln(1 + (x - xi)^2) up to a constant, and the value at the reference point
  // taken off (s.reference: 0 while it is computed).
  const double far = s.m0 != 0.0 ? s.m0 * w * l1 / (2.0 * kPi) - s.reference : 0.0;
  return -smooth + phi1 * hp + far +
         (model_->memory() ? phi1 * memory_displacement(s, x, hp) : 0.0);
}

double AsymmetricSolution::memory_displacement(const Surface& s, double x, double hp) const {
  // -(1/pi) Re int g(alpha)(1 - e^-alpha)/alpha p^ e^{i alpha x} = sum_k c_k (e_k * U)(x)
  // (g = sum_k c_k/(1 - i beta_k alpha), e_k its causal exponential (1/beta_k)
  // e^{u/beta_k}, u < 0; U = (1/pi) int p ln|x - xi| - (1/2pi) int p ln(1 + (x - xi)^2),
  // hp). The logarithm's part through the basis' potentials L_n (L_n' = h_n):
  // e * L_n = L_n + J_n (by parts), the moments' J_n = (lambda J_n)/lambda;
  // the smooth ln(1 + .^2) part by Gauss-Legendre against the exponential.
  const RetardationSpectrum& sp = model_->memory()->spectrum();
  const double w = half_, sx = (x - centre_) / w;
  const int count = static_cast<int>(b_.size());
  std::vector<double> mom(static_cast<std::size_t>(count));
  static const std::shared_ptr<const JacobiRule> gl = cached_gauss_jacobi(16, 0.0, 0.0);
  double out = 0.0;
  for (std::size_t k = 0; k < sp.c.size(); ++k) {
    const double beta = sp.beta[k], lam = w / beta;
    memory_moments(sx, lam, count, mom.data());
    double jn = 0.0;
    for (int n = 0; n < count; ++n) jn += b_(n) * mom[static_cast<std::size_t>(n)];
    // int_0^inf (1/beta) e^{-eta/beta} Lambda(x + eta) d eta, Lambda = int p ln(1 + (.)^2):
    // panels at the weight's e-folds and geometric from 1/4 (Lambda is
    // analytic within 1 of the real axis and logarithmic far out).
    std::vector<double> cuts{0.0};
    for (double e = 0.25; e < 48.0 * beta; e *= 2.0) cuts.push_back(e);
    for (double m : {1.0, 2.0, 4.0, 8.0, 16.0, 24.0, 32.0, 40.0, 48.0}) cuts.push_back(m * beta);
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    double conv = 0.0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      const double c = 0.5 * (cuts[i] + cuts[i + 1]), h = 0.5 * (cuts[i + 1] - cuts[i]);
      for (Eigen::Index q = 0; q < gl->x.size(); ++q) {
        const double eta = c + h * gl->x(q);
        conv += h * gl->w(q) * std::exp(-eta / beta) / beta *
                detail::log1p_sum(s.log1p_r, s.log1p_w, w, x + eta - centre_);
      }
    }
    // e * U = e * (w lp) - (1/2pi) e * Lambda, with e * (w lp) = w lp + w sum b_n J_n and
    // w lp = hp + (1/2pi) Lambda(x).
    const double lam_x = w * detail::log1p_sum(s.log1p_r, s.log1p_w, w, x - centre_);
    out += sp.c[k] * (hp + lam_x / (2.0 * kPi) + w * jn / lam - w * conv / (2.0 * kPi));
  }
  return out;
}

namespace {

// A material's memory along x at one point: int_0^40 e^-tau F(u + beta tau)
// d tau (e^-40: 4e-18; the causal exponential e_k * F of memory_displacement,
// over beta), F valued in R^D. `panel(lo, hi)` is the 16-point Gauss-Legendre
// sum of e^-tau F(u + beta tau) on [lo, hi] (in tau). Panels at the weight's
// e-folds and where u + beta tau meets the contact's ends [left, right] (F's
// kinks or cusps there), each halved until two halves agree with it to
// `tol` (or are 1e-13 long in x); ConvergenceError naming `what` after 20000
// halvings.
template <class Panel>
auto exponential_convolution(const Panel& panel, double u, double beta, double left, double right,
                             double tol, const std::string& what) {
  using V = decltype(panel(0.0, 1.0));
  std::vector<double> cuts{0.0, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 24.0, 32.0, 40.0};
  for (double end : {left - u, right - u})
    if (end > 0.0 && end < 40.0 * beta) cuts.push_back(end / beta);
  std::sort(cuts.begin(), cuts.end());
  V conv = V::Zero();
  int splits = 0;
  for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
    if (!(cuts[c + 1] > cuts[c])) continue;
    std::vector<std::pair<double, double>> todo{{cuts[c], cuts[c + 1]}};
    while (!todo.empty()) {
      const auto [lo, hi] = todo.back();
      todo.pop_back();
      const double mid = 0.5 * (lo + hi);
      const V whole = panel(lo, hi);
      const V halves = panel(lo, mid) + panel(mid, hi);
      if ((whole - halves).cwiseAbs().maxCoeff() <= tol || (hi - lo) * beta < 1e-13) {
        conv += halves;
        continue;
      }
      if (++splits > 20000)
        throw ConvergenceError(
            what + ": the memory's convolution did not settle (x = " + std::to_string(u) + ")");
      todo.emplace_back(lo, mid);
      todo.emplace_back(mid, hi);
    }
  }
  return conv;
}

// sum_k c_k int_0^40 e^-tau F(u + beta_k tau) d tau for a scalar F (the
// spectrum's causal exponentials applied to F at u; exponential_convolution
// per term, 16-point Gauss-Legendre panels).
template <class F>
double spectrum_convolution(const RetardationSpectrum& sp, const F& f, double u, double left,
                            double right, double tol, const std::string& what) {
  static const std::shared_ptr<const JacobiRule> gl = cached_gauss_jacobi(16, 0.0, 0.0);
  double out = 0.0;
  for (std::size_t k = 0; k < sp.c.size(); ++k) {
    const double beta = sp.beta[k];
    auto panel = [&](double lo, double hi) {
      const double m = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
      double sum = 0.0;
      for (Eigen::Index q = 0; q < gl->x.size(); ++q) {
        const double t = m + h * gl->x(q);
        sum += gl->w(q) * std::exp(-t) * f(u + beta * t);
      }
      return Eigen::Matrix<double, 1, 1>(h * sum);
    };
    out += sp.c[k] * exponential_convolution(panel, u, beta, left, right, tol, what)(0);
  }
  return out;
}

}  // namespace

double AsymmetricSolution::stress_memory_part(double x) const {
  // sum_k d_k (e_k * p)(x), e_k * p = int_0^inf e^-tau p(x + beta_k tau) d tau
  // (the material ahead of x; memory_displacement's convention), to 1e-14 of
  // the largest pressure: 0 beyond the contact's front end.
  const double left = centre_ - half_, right = centre_ + half_;
  if (x >= right) return 0.0;
  return spectrum_convolution(
      *model_->stress_memory(), [this](double at) { return pressure(at); }, x, left, right,
      1e-14 * max_p_, "surface stress");
}

namespace {

// The index of the sublayer of `spec` at depth y (at an interface: the one
// above it, or below it when `below`); -1 for the half-space's face (y = -1
// below, under a half-space).
int sublayer_at(const MediumSpec& spec, double y, bool below) {
  const int K = static_cast<int>(spec.layers.size());
  double bottom = 0.0;
  for (int i = 0; i < K; ++i) {
    bottom -= spec.layers[static_cast<std::size_t>(i)].thickness;
    if (i + 1 == K) bottom = -1.0;
    if (y == bottom) {
      if (!below) return i;
      return i + 1 < K ? i + 1 : (spec.base.kind == BaseKind::springs ? i : -1);
    }
    if (y > bottom || i + 1 == K) return i;
  }
  return K - 1;
}

}  // namespace

StressField AsymmetricSolution::compliance_stress_field(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                        const Eigen::Ref<const Eigen::VectorXd>& y,
                                                        bool below) const {
  StressField out = stress_field(x, y, below);
  if (!model_->spec().viscoelastic()) return out;
  // (1/m_inf) [sigma + sum_k c_k e_k * sigma] along x at each depth, the
  // convolution to 1e-13 of the largest stress at the depth (the contact's
  // ends: sigma's square-root cusps at the surface). The material's own
  // compliance (that of the sublayer at the depth), with or without the
  // medium's inertia.
  const MediumSpec& spec = model_->spec();
  std::vector<std::optional<RetardationSpectrum>> spectra(spec.layers.size());
  const double left = centre_ - half_, right = centre_ + half_;
  static const std::shared_ptr<const JacobiRule> gl = cached_gauss_jacobi(16, 0.0, 0.0);
  for (Eigen::Index i = 0; i < y.size(); ++i) {
    const double yi = y(i);
    const int layer = sublayer_at(spec, yi, below);
    if (layer < 0 || spec.layers[static_cast<std::size_t>(layer)].visco.empty()) continue;
    auto& cached = spectra[static_cast<std::size_t>(layer)];
    if (!cached) cached = retardation_spectrum(spec.layers[static_cast<std::size_t>(layer)].visco);
    const RetardationSpectrum& sp = *cached;
    const Eigen::VectorXd row = Eigen::VectorXd::Constant(1, yi);
    double scale = stresses(centre_, yi).cwiseAbs().maxCoeff();
    for (Eigen::Index j = 0; j < x.size(); ++j)
      for (const Eigen::MatrixXd* m : {&out.sigma_x, &out.sigma_y, &out.tau_xy})
        scale = std::max(scale, std::fabs((*m)(i, j)));
    for (Eigen::Index j = 0; j < x.size(); ++j) {
      const double u = x(j);
      if (std::fabs(u) > kFarField) continue;  // 0 there, as the stresses
      Eigen::Vector3d total(out.sigma_x(i, j), out.sigma_y(i, j), out.tau_xy(i, j));
      for (std::size_t k = 0; k < sp.c.size(); ++k) {
        const double beta = sp.beta[k];
        auto panel = [&](double lo, double hi) {
          // The 16 nodes in one stress_field call (its sums shared).
          const double m = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
          const Eigen::Index nq = gl->x.size();
          Eigen::VectorXd at(nq), wt(nq);
          for (Eigen::Index q = 0; q < nq; ++q) {
            const double t = m + h * gl->x(q);
            at(q) = u + beta * t;
            wt(q) = gl->w(q) * std::exp(-t);
          }
          const StressField f = stress_field(at, row, below);
          return Eigen::Vector3d(h * f.sigma_x.row(0).dot(wt), h * f.sigma_y.row(0).dot(wt),
                                 h * f.tau_xy.row(0).dot(wt));
        };
        total += sp.c[k] * exponential_convolution(panel, u, beta, left, right, 1e-13 * scale,
                                                   "strains at y = " + std::to_string(yi));
      }
      total /= sp.ratio;
      out.sigma_x(i, j) = total(0);
      out.sigma_y(i, j) = total(1);
      out.tau_xy(i, j) = total(2);
    }
  }
  return out;
}

Eigen::VectorXd AsymmetricSolution::memory_depth_displacement(
    const Eigen::Ref<const Eigen::VectorXd>& x, double y) const {
  // v = (1/pi) Re int_0^inf W(alpha, y)/alpha p^ e^{i alpha u} d alpha, u = x - c,
  // W the layer's (over m(alpha)). Its half-plane part W_hp(alpha, y)/m(alpha),
  // W_hp the relaxed elastic half-plane's mode mix, regularised by (1 - e^-alpha)
  // as on the elastic layer, is taken whole: with
  //   1/m(alpha) = (1/m_inf) (1 + sum_k c_k/(1 - i beta_k alpha)),
  // it is (1/m_inf) [HP(u) + sum_k c_k (e_k * HP)(u)], HP the closed-form
  // half-plane displacement (potentials.hpp) and e_k * F = int_0^inf
  // (1/beta_k) e^{-eta/beta_k} F(u + eta) d eta (the surface's convention,
  // memory_displacement); what is left, [W - W_hp (1 - e^-alpha)/m(alpha)]/alpha,
  // decays as on the elastic layer and is summed on the fine nodes.
  const Fine& f = light();
  const WaveConstants& c = model_->top();
  const RetardationSpectrum& sp = model_->memory()->spectrum();
  const double ratio = sp.ratio, phi1 = model_->phi1(), w = half_;
  const double m0 = model_->long_wave_m1();  // (a half-space base: far_field)
  std::vector<cplx> g(f.alpha.size());
  for (std::size_t k = 0; k < g.size(); ++k) {
    const double al = f.alpha[k];
    const Eigen::Matrix4d C = detail::modal_columns(c, al, y);
    const double w_hp = c.hp1 * C(1, 0) + c.hp2 * C(1, 1);
    const cplx inv_m = model_->half_plane_m1(al) / (phi1 * ratio);  // 1/m(alpha)
    const cplx wl = model_->normal_state(al, y)(1);
    g[k] = (wl + w_hp * inv_m * std::expm1(-al) + m0 * std::exp(-al)) / al * f.phat[k] *
           std::exp(cplx(0.0, al * centre_));
  }
  std::vector<double> g_re, g_im;
  f.coefficients(g, g_re, g_im);
  auto hp = [&](double u) { return detail::half_plane_displacement(c, b_, w, u, y, 1); };
  // The convolution's tolerance: 1e-14 of HP at the contact's centre (its
  // scale) or of HP here, whichever is larger (HP varies on the scale |y|
  // near the contact's ends).
  const double scale = std::fabs(hp(0.0));
  Eigen::VectorXd v(x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    if (std::fabs(x(j)) > kFarField) {
      v(j) = 0.0;
      continue;
    }
    const double u = x(j) - centre_, here = hp(u);
    const double mem =
        spectrum_convolution(sp, hp, u, -w, w, 1e-14 * std::max(std::fabs(here), scale),
                             "displacement at y = " + std::to_string(y));
    v(j) = params_.load * (f.fourier(g_re, g_im, u) / kPi + (here + mem) / ratio + far_field(u));
  }
  return v;
}

Eigen::VectorXd AsymmetricSolution::inertial_depth_displacement(
    const Eigen::Ref<const Eigen::VectorXd>& x, double y) const {
  // v = (1/pi) Re int_0^inf W(alpha, y)/alpha p^ e^{i alpha x} d alpha (W per
  // mu_0: the medium's state over m(alpha)), split as on the elastic layer:
  // [W - W_hp (1 - e^-alpha)]/alpha with W_hp the relaxed half-plane's mode
  // mix (closed form: half_plane_displacement), by Filon sums on the fine
  // nodes and, since with inertia the remainder decays only like
  // e^{-nT alpha |y|}, on tail panels beyond them to 36/(nT |y|) (the
  // stresses' inertial_tail). y < 0.
  const WaveConstants& c = model_->top();
  const double m0 = model_->long_wave_m1();  // (a half-space base: far_field)
  auto integrand = [&](double al, cplx ph) {
    const Eigen::Matrix4d C = detail::modal_columns(c, al, y);
    const double w_hp = c.hp1 * C(1, 0) + c.hp2 * C(1, 1);
    const cplx wl = model_->normal_state(al, y)(1);
    return (wl + w_hp * std::expm1(-al) + m0 * std::exp(-al)) / al * ph;
  };
  const Fine& f = light();
  std::vector<cplx> g(f.alpha.size());
  for (std::size_t k = 0; k < g.size(); ++k)
    g[k] = integrand(f.alpha[k], f.phat[k] * std::exp(cplx(0.0, f.alpha[k] * centre_)));
  std::vector<double> g_re, g_im;
  f.coefficients(g, g_re, g_im);
  const double from = f.filon->upper(), reach = 36.0 / (c.nT * -y);
  std::vector<cplx> ph;
  std::vector<double> t_re, t_im;
  std::unique_ptr<const FilonIntegrator> tail;
  if (reach > from) {
    const AlphaQuadrature q = tail_panels(from, reach, ph);
    std::vector<cplx> gt(q.alpha.size());
    for (std::size_t k = 0; k < gt.size(); ++k) gt[k] = integrand(q.alpha[k], ph[k]);
    tail = std::make_unique<const FilonIntegrator>(q);
    filon_coefficients(*tail, gt, t_re, t_im);
  }
  Eigen::VectorXd v(x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    if (std::fabs(x(j)) > kFarField) {
      v(j) = 0.0;
      continue;
    }
    const double u = x(j) - centre_;
    double sum = f.fourier(g_re, g_im, u);
    if (tail) sum += tail->integral(u, t_re).real() - tail->integral(u, t_im).imag();
    v(j) = params_.load *
           (sum / kPi + detail::half_plane_displacement(c, b_, half_, u, y, 1) + far_field(u));
  }
  return v;
}

double AsymmetricSolution::surface_displacement(double x) const {
  if (!std::isfinite(x))
    throw InvalidParameter("x", "finite",
                           "surface_displacement: x must be finite, got " + std::to_string(x));
  if (std::fabs(x) > kFarField) return 0.0;  // as SymmetricSolution's (stresses.hpp)
  refuse_flat_memory("surface displacement");
  if (jac_ && model_->long_wave_m1() != 0.0)
    layered_refusal(*model_, "the displacement with friction (a logarithmic far field)");
  if (jac_) return friction_displacement(Eigen::VectorXd::Constant(1, x), 0.0)(0);
  return params_.load * surface_value(*surface(), x);
}

void AsymmetricSolution::refuse_flat_memory(const char* what) const {
  if (model_->memory() == nullptr || t_coef_.size() == 0) return;
  throw InvalidParameter(
      "profile", "a cylinder or a convex table for this output on a viscoelastic layer",
      std::string("profile: the ") + what +
          " of a flat punch on a viscoelastic layer is not computed yet (the memory's "
          "displacement against the face's square-root edges); its contact, pressure, drag, "
          "dissipation, surface slope and surface stress are");
}

double AsymmetricSolution::indentation() const {
  refuse_flat_memory("indentation");
  if (jac_ && model_->long_wave_m1() != 0.0)
    layered_refusal(*model_, "the indentation with friction (a logarithmic far field)");
  if (jac_) {  // the punch's rigid approach at the contact's centre
    std::lock_guard<std::mutex> lock(surface_cache_->mutex);
    if (!std::isnan(friction_indentation_)) return friction_indentation_;
    friction_indentation_ = punch_->height(centre_) -
                            friction_displacement(Eigen::VectorXd::Constant(1, centre_), 0.0)(0);
    return friction_indentation_;
  }
  return surface()->indentation;
}

Eigen::MatrixXd AsymmetricSolution::displacement(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                 const Eigen::Ref<const Eigen::VectorXd>& y) const {
  detail::check_grid(x, y);
  refuse_flat_memory("displacement");
  // Under a half-space (m0 != 0) every depth is measured from the surface at
  // x = kDisplacementReference (surface_value's reference; far_field below).
  if (jac_ && model_->long_wave_m1() != 0.0)
    layered_refusal(*model_, "the displacement with friction (a logarithmic far field)");
  if (model_->memory()) {
    // A viscoelastic top: the surface (its memory in closed form), and
    // below it the half-plane part's memory by a convolution in x
    // (memory_depth_displacement).
    Eigen::MatrixXd v(y.size(), x.size());
    const bool inertial = model_->vstar() > 0.0;
    if (inertial) check_inertial_depths(y, "displacements");
    for (Eigen::Index i = 0; i < y.size(); ++i) {
      if (y(i) < 0.0) {
        v.row(i) =
            inertial ? inertial_depth_displacement(x, y(i)) : memory_depth_displacement(x, y(i));
        continue;
      }
      const std::shared_ptr<const Surface> sf = surface();
      for (Eigen::Index j = 0; j < x.size(); ++j)
        v(i, j) = std::fabs(x(j)) > kFarField ? 0.0 : params_.load * surface_value(*sf, x(j));
    }
    return v;
  }
  if (jac_) {
    Eigen::MatrixXd v(y.size(), x.size());
    for (Eigen::Index i = 0; i < y.size(); ++i) v.row(i) = friction_displacement(x, y(i));
    return v;
  }
  const Fine& f = light();
  const WaveConstants& c = model_->top();
  Eigen::MatrixXd v(y.size(), x.size());
  if (model_->long_wave_m1() != 0.0 && (y.array() == 0.0).any()) {
    const std::shared_ptr<const Surface> sf = surface();  // the surface row: its own
    for (Eigen::Index i = 0; i < y.size(); ++i)
      if (y(i) == 0.0)
        for (Eigen::Index j = 0; j < x.size(); ++j)
          v(i, j) = std::fabs(x(j)) > kFarField ? 0.0 : params_.load * surface_value(*sf, x(j));
  }
  const double m0 = model_->long_wave_m1();
  std::vector<cplx> g(f.alpha.size());
  std::vector<double> g_re, g_im;
  for (Eigen::Index i = 0; i < y.size(); ++i) {
    if (m0 != 0.0 && y(i) == 0.0) continue;
    for (std::size_t k = 0; k < g.size(); ++k) {
      const double al = f.alpha[k];
      const Eigen::Matrix4d C = detail::modal_columns(c, al, y(i));
      const double w_hp = c.hp1 * C(1, 0) + c.hp2 * C(1, 1);
      const cplx w = y(i) == 0.0 ? -f.r[k].M1 : model_->normal_state(al, y(i))(1);
      g[k] = (w + w_hp * std::expm1(-al) + m0 * std::exp(-al)) / al * f.phat[k] *
             std::exp(cplx(0.0, al * centre_));
    }
    f.coefficients(g, g_re, g_im);
    for (Eigen::Index j = 0; j < x.size(); ++j) {
      if (std::fabs(x(j)) > kFarField) {
        v(i, j) = 0.0;
        continue;
      }
      const double u = x(j) - centre_;
      v(i, j) =
          params_.load * (f.fourier(g_re, g_im, u) / kPi +
                          detail::half_plane_displacement(c, b_, half_, u, y(i), 1) + far_field(u));
    }
  }
  return v;
}

double AsymmetricSolution::far_field(double u) const {
  // Under a half-space the layer's W(alpha, y) -> -m0 at every depth as alpha
  // -> 0 (the substrate's half-plane carries it): -(m0/pi) Re int e^-alpha/alpha
  // p^ e^{i alpha u} = (m0/(2 pi)) int p ln(1 + (u - xi)^2) up to a constant (the
  // same at every depth), taken out of the sums (their integrands carry
  // + m0 e^-alpha/alpha) and measured, as the surface's, from its value at
  // the surface point x = kDisplacementReference (surface()->reference).
  const double m0 = model_->long_wave_m1();
  if (m0 == 0.0) return 0.0;
  const std::shared_ptr<const Surface> sf = surface();
  return m0 * half_ * detail::log1p_sum(sf->log1p_r, sf->log1p_w, half_, u) / (2.0 * kPi) -
         sf->reference;
}

}  // namespace movingpunch

// The flat punch on the asymmetric solver (damping > 0 and/or friction > 0):
// the contact is the face (-b, b), the pressure is unbounded at both ends
// (index +1). See docs/theory.md section 14, "The flat punch on the
// asymmetric solver".
//
// p(b r) = (P/h) w(r) g(r), w = (1 - r)^alpha (1 + r)^beta with alpha =
// gamma_front - 1, beta = gamma_back - 1 (alpha + beta = -1; -1/2 each
// without friction), g a polynomial. The equation on the face (the flat face
// has no slope and the punch is held: the right-hand side is 0),
//   f Phi p(x) + (1/pi) int p(xi)/(xi - x) d xi - int p(xi) K(x - xi) d xi = 0,
// is collocated at the N - 1 zeros s_k of P_{N-1}^(-alpha, -beta) with the
// N-node Gauss-Jacobi rule of P_N^(alpha, beta) (jacobi_flat_nodes: exact
// for polynomial g of degree < N), and equilibrium int p = P closes the
// square system. No width iteration: g over P/h does not depend on the load.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "ladder.hpp"
#include "movingpunch/asymmetric.hpp"
#include "movingpunch/dispersion.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/viscoelastic.hpp"
#include "solve_skeleton.hpp"

namespace movingpunch {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kInf = std::numeric_limits<double>::infinity();

// g at the nodes of the collocation system of size nd.n (the kernel's values
// in one batch, as eval_width's).
Eigen::VectorXd flat_nodal_g(const ChebyshevNodes& nd, double w, const AsymmetricKernel& K) {
  const int n = nd.n, m = n - 1;
  Eigen::MatrixXd M(n, n);
  std::vector<double> u(static_cast<std::size_t>(n) * m), kv(u.size());
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < m; ++k) u[static_cast<std::size_t>(i) * m + k] = -w * (nd.r(i) - nd.s(k));
  K.many(u.data(), kv.data(), u.size());
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < m; ++k) {
      const double d = nd.r(i) - nd.s(k);
      M(k, i) = nd.w(i) * (1.0 / d - w * kv[static_cast<std::size_t>(i) * m + k]);
    }
    // Equilibrium: int p dx/(P/h) = w int w(r) g(r) dr = pi w sum W_i g_i = 1.
    M(m, i) = kPi * w * nd.w(i);
  }
  // A viscoelastic top's memory (frictionless: the weight 1/sqrt(1 - r^2),
  // g = sum_q c_q T_q with c_q = (2 - delta_q0) sum_i W_i T_q(r_i) g_i at
  // the N Chebyshev nodes), exactly against the T basis:
  //   B(k, i) = -W_i sum_q (2 - delta_q0) T_q(r_i) mom_q(s_k).
  if (const MemoryKernel* mem = K.model().memory()) {
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    RowMajor mom(m, n);
    mem->moments_descending(nd.s.data(), m, w, n, mom.data(), MemoryBasis::T);
    Eigen::MatrixXd basis(n, n);  // (q, i): -(2 - delta_q0) W_i T_q(r_i)
    for (int i = 0; i < n; ++i) {
      const double th = std::acos(std::clamp(nd.r(i), -1.0, 1.0));
      for (int q = 0; q < n; ++q) basis(q, i) = -(q == 0 ? 1.0 : 2.0) * nd.w(i) * std::cos(q * th);
    }
    M.topRows(m) += mom * basis;
  }
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  rhs(m) = 1.0;
  return M.partialPivLu().solve(rhs);
}

}  // namespace

AsymmetricSolution solve_asymmetric_flat(const AsymmetricParams& prm_in) {
  const auto t0 = std::chrono::steady_clock::now();
  validate(prm_in);
  // kw, nu, kp, damping: the medium's own (nu: the top sublayer's).
  const AsymmetricParams prm = with_medium_scalars(prm_in);
  if (prm.profile != ProfileKind::flat)
    throw std::invalid_argument("solve_asymmetric_flat: the profile must be flat");
  auto since_start = [&t0] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  AsymmetricSolution s;
  s.params_ = prm;
  s.punch_ = std::make_shared<const PunchProfile>(prm.punch());
  s.vr_ = rayleigh_vstar(prm.nu);
  s.vcr_ = critical_vstar_of(prm);
  const double t_critical = since_start();
  require_steady_speed(prm, s.vcr_, s.vr_);
  const WaveConstants wc = wave_constants(prm.vstar, prm.nu);
  const double w = prm.punch().face();
  const bool frictional = prm.friction > 0.0;
  // A viscoelastic top's shortest retardation length (0: none), and whether
  // its boundary layer at the edges is below the node spacing at size n.
  double beta_min = 0.0;
  auto layer_below_nodes = [&](int n) {
    return beta_min > 0.0 && beta_min < 2.0 * w * (1.0 - std::cos(kPi / (2.0 * n)));
  };
  // The bounded case's exponents less 1 (cot(pi gamma_back) = f Phi).
  const EndExponents bounded =
      frictional ? end_exponents(prm.friction, tangential_half_plane(wc).Phi) : EndExponents{};
  const double al = bounded.front - 1.0, be = -1.0 - al;
  s.exps_.back = be;
  s.exps_.front = al;

  double kernel_seconds = 0.0;
  std::shared_ptr<const AsymmetricKernel> kern;
  {
    const auto tk = std::chrono::steady_clock::now();
    bool built = false;
    // |u| = w |s_k - r_i| < 2 w; twice that when built (a sweep's next face).
    kern = cached_damped_kernel(cached_medium(medium_of(prm), prm.vstar), 2.0 * w, 4.0 * w, &built,
                                prm.friction);
    s.kernel_builds_ = built ? 1 : 0;
    kernel_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tk).count();
  }
  s.model_ = kern->model_ptr();
  s.kernel_ = kern;
  if (const MemoryKernel* mem = s.model_->memory()) {
    const RetardationSpectrum& sp = mem->spectrum();
    beta_min = *std::min_element(sp.beta.begin(), sp.beta.end());
  }

  std::vector<int> sizes;
  if (prm.n > 0) {
    for (int m : {prm.n / 2, (3 * prm.n) / 4, prm.n}) {
      const int e = std::max(2, m - m % 2);
      if (sizes.empty() || e > sizes.back()) sizes.push_back(e);
    }
  } else {
    sizes = detail::size_ladder(512);
  }
  // K_end = sqrt(2 pi) b^(-gamma_end) 2^(gamma_other) g(end) (section 14).
  const double kf_scale = std::sqrt(2.0 * kPi) * std::pow(w, -al) * std::pow(2.0, be);
  const double kb_scale = std::sqrt(2.0 * kPi) * std::pow(w, -be) * std::pow(2.0, al);
  const double qerr = kern->quadrature().kronrod_error, terr = kern->table_error();
  double kb = 0, kf = 0, gmax = 0, floor_k = 0, floor_g = 0;
  RefinementEstimate est_k, est_g;
  // The ladder (ladder.hpp): per size the end coefficients and g's Jacobi
  // series; a singular system is reported at once (no width to refine past).
  struct Member {
    JacobiSeries js;
    double kb = 0, kf = 0, gmax = 0, floor_k = 0, floor_g = 0;
  };
  const detail::LadderRun<Member, 2> run = detail::run_ladder<2, Member>(
      sizes,
      [&](int n) {
        const ChebyshevNodes nd = jacobi_flat_nodes(n, al, be);
        const Eigen::VectorXd g = flat_nodal_g(nd, w, *kern);
        ++s.iterations_;
        if (!g.allFinite())
          throw ConvergenceError(
              "damped flat punch: the collocation system came out singular or non-finite at N = " +
              std::to_string(n));
        Member m;
        m.js = JacobiSeries::from_nodes(al, be, nd.r, g);
        m.kb = kb_scale * m.js.g(-1.0);
        m.kf = kf_scale * m.js.g(1.0);
        m.gmax = m.js.max_abs_g();
        const double scale_k = std::max(std::fabs(m.kb), std::fabs(m.kf));
        // Round-off (the collocation matrix's condition grows about like N)
        // and the kernel's error carried into g (a relative dK w, as the
        // widths').
        m.floor_k = (64.0 * kEps * n + 4.0 * (qerr + terr) * w) * scale_k;
        m.floor_g = (64.0 * kEps * n + 4.0 * (qerr + terr) * w) * m.gmax;
        return m;
      },
      [](const Member& prev, const Member& cur) {
        return std::array<double, 2>{
            std::max(std::fabs(cur.kb - prev.kb), std::fabs(cur.kf - prev.kf)),
            cur.js.minus(prev.js).max_abs_g()};
      },
      [&](const detail::LadderChain<Member, 2>& c) {
        const Member& m = c.last();
        floor_k = m.floor_k;
        floor_g = m.floor_g;
        if (c.size() < 2) return detail::Verdict::go_on;
        const std::vector<double>& d_k = c.changes[0];
        const std::vector<double>& d_g = c.changes[1];
        // The geometric extrapolation of refinement_estimate, but never below
        // the last change (the previous member's error): the flat punch's
        // changes can shrink faster before they settle to their rate (16 ->
        // 24 -> 32 gave 2e-4, 5e-7, then an error 4e-8 at 32 on a wide face
        // with friction).
        est_k = refinement_estimate(c.sizes, d_k, floor_k);
        est_g = refinement_estimate(c.sizes, d_g, floor_g);
        est_k.estimate = std::max(est_k.estimate, d_k.back() + floor_k);
        est_g.estimate = std::max(est_g.estimate, d_g.back() + floor_g);
        if (prm.n != 0 || d_k.size() < 2) return detail::Verdict::go_on;
        // A viscoelastic top's memory layer at the edges (width beta_min)
        // must lie within the nodes: the sizes' changes cannot see a layer
        // they all miss (and a flat face's drag lives in it, below).
        if (layer_below_nodes(c.sizes.back())) return detail::Verdict::go_on;
        return detail::ladder_verdict(ladder_stop(prm.tol, est_k, d_k.back(),
                                                  std::max(std::fabs(m.kb), std::fabs(m.kf)), est_g,
                                                  d_g.back(), m.gmax));
      },
      detail::RethrowFailures{});
  const bool converged = run.verdict == detail::Verdict::converged;
  const bool stalled = run.verdict == detail::Verdict::stalled;
  const std::vector<double>& d_k = run.chain.changes[0];
  const std::vector<double>& d_g = run.chain.changes[1];
  const int n_done = run.chain.sizes.back();
  const JacobiSeries& js = run.chain.last().js;
  kb = run.chain.last().kb;
  kf = run.chain.last().kf;
  gmax = run.chain.last().gmax;
  // The member before the last (for the stress estimate's change, below).
  const JacobiSeries js_prev =
      run.chain.size() >= 2 ? run.chain.states[run.chain.size() - 2].js : JacobiSeries();
  // g's estimate from the coarser sizes: the stress estimate's gain is read
  // from their change (below), and is applied to it.
  const double g_coarse = d_g.empty() ? kInf
                                      : (prm.n > 0 && d_g.size() == 1
                                             ? std::max(est_g.estimate, 2.0 * d_g.back() + floor_g)
                                             : est_g.estimate);
  if (prm.n > 0 && prm.n <= kFixedFinerMax && n_done == prm.n) {
    // A fixed small N: its error from finer sizes (fixed_size_error,
    // asymmetric.hpp), on the end coefficients and on g.
    JacobiSeries r_js;
    double r_kb = 0.0, r_kf = 0.0;
    bool r_have = false;
    const FixedError fe = fixed_size_error(prm.n, [&](int m) {
      const ChebyshevNodes nr = jacobi_flat_nodes(m, al, be);
      const Eigen::VectorXd gr = flat_nodal_g(nr, w, *kern);
      ++s.iterations_;
      if (!gr.allFinite())
        throw ConvergenceError("damped flat punch: a reference size's system is singular");
      const JacobiSeries jr = JacobiSeries::from_nodes(al, be, nr.r, gr);
      const double kbr = kb_scale * jr.g(-1.0), kfr = kf_scale * jr.g(1.0);
      FixedSample out;
      out.d_n_v = std::max(std::fabs(kb - kbr), std::fabs(kf - kfr));
      out.d_n_p = js.minus(jr).max_abs_g();
      if (r_have) {
        out.d_v = std::max(std::fabs(kbr - r_kb), std::fabs(kfr - r_kf));
        out.d_p = jr.minus(r_js).max_abs_g();
      }
      const double rel = 64.0 * kEps * m + 4.0 * (qerr + terr) * w;
      out.floor_v = rel * std::max(std::fabs(kbr), std::fabs(kfr));
      out.floor_p = rel * jr.max_abs_g();
      r_js = jr;
      r_kb = kbr;
      r_kf = kfr;
      r_have = true;
      return out;
    });
    est_k.estimate = fe.v + floor_k;
    est_g.estimate = fe.p + floor_g;
  } else if (d_k.empty()) {
    est_k.estimate = kInf;
    est_g.estimate = kInf;
  } else if (prm.n > 0 && d_k.size() == 1) {
    // A fixed n with one change: twice it (as the cylinder's, asymmetric.cpp).
    est_k.estimate = std::max(est_k.estimate, 2.0 * d_k.back() + floor_k);
    est_g.estimate = std::max(est_g.estimate, 2.0 * d_g.back() + floor_g);
  }
  const double scale_k = std::max(std::fabs(kb), std::fabs(kf));
  if (!std::isfinite(kb) || !std::isfinite(kf) || !std::isfinite(gmax))
    throw ConvergenceError("damped flat punch: the end coefficients came out non-finite (N = " +
                           std::to_string(n_done) + ")");
  if (prm.n == 0 && !converged && !stalled && !(est_k.estimate <= prm.tol * scale_k)) {
    std::ostringstream est;
    est << "estimated error " << est_k.estimate << " of the end coefficients";
    throw ConvergenceError(detail::not_converged_message("damped flat punch: the end coefficients",
                                                         prm.tol, sizes.back(), est.str()));
  }
  const double t_width = since_start() - kernel_seconds;

  s.n_ = n_done;
  s.half_ = w;
  s.centre_ = 0.0;
  s.b_ = js.coefficients();
  s.jac_ = std::make_shared<const JacobiSeries>(js);
  if (s.model_->memory() != nullptr) {
    // g's T coefficients (the memory's basis), exact from M > deg g values at
    // the Chebyshev points: c_q = (2 - delta_q0)/M sum_j g(cos th_j) cos(q th_j).
    const int M = static_cast<int>(js.size()) + 1;
    s.t_coef_ = Eigen::VectorXd::Zero(M - 1);
    for (int j = 0; j < M; ++j) {
      const double th = kPi * (j + 0.5) / M, gj = js.g(std::cos(th));
      for (int q = 0; q + 1 < M; ++q)
        s.t_coef_(q) += (q == 0 ? 1.0 : 2.0) * gj * std::cos(q * th) / M;
    }
  }
  s.err_ = 0.0;  // the ends are the face's: exact
  // The horizontal force: the face's normal pressure has none (f' = 0), but
  // each square-root singular edge carries one, the limit of corners rounded
  // ever more sharply (as an aerofoil's leading-edge suction): with
  // int p (-H p) over the face = (K_back^2 - K_front^2)/4 (H the half-plane's
  // Cauchy operator; the two-term T-series gives the constant) and
  // int p_eps H p_eps = 0 for the rounded pressure, drag = load phi1
  // (K_front^2 - K_back^2)/4 (docs/theory.md section 14), which the
  // dashpots' dissipation equals (the energy balance; tested). With friction
  // the trailing edge's p^2 is not integrable: the rounded corners' force
  // has no finite sharp limit, and drag reports the face's part, 0.
  // (A viscoelastic top: the edges see its unrelaxed half-plane, H_inf.)
  s.drag_ = frictional ? 0.0
                       : prm.load * (s.model_->memory() ? s.model_->phi1() : wc.phi1) *
                             (kf * kf - kb * kb) / 4.0;
  s.end_k_back_ = kb;
  s.end_k_front_ = kf;
  s.end_k_err_ = est_k.estimate;
  s.perr_ = est_g.estimate;  // on g = p/((P/h) w(r)): |dp| <= perr_ w(r)
  s.max_p_ = js.max_abs_density();
  auto note = [&](const char* what, double est, double scale, double floor) {
    const double want = prm.tol * scale;
    if (est <= want) return;
    std::ostringstream m;
    m.precision(3);
    m << what << " not met to tol = " << prm.tol << ": estimated relative error " << est / scale
      << " (" << est / want << " x tol) at N = " << n_done;
    if (floor > want)
      m << " (round-off and kernel floor " << floor / scale << " exceeds tol)";
    else if (prm.n > 0)
      m << " (fixed n; raise n or leave it automatic)";
    else if (stalled)
      m << " (the changes between sizes stopped shrinking)";
    s.warnings_.push_back(m.str());
  };
  note("end coefficients (K_back, K_front):", est_k.estimate, scale_k, floor_k);
  note("pressure p(x)/w(r) = g(r):", est_g.estimate, gmax, floor_g);
  // A viscoelastic top's shortest memory beta puts a boundary layer of that
  // width at the leading edge, where the material arriving responds with
  // its unrelaxed modulus: K_front tends to m_inf times the relaxed K as
  // deborah -> 0, and the drag to P H_inf K_0^2 (m_inf^2 - 1)/4, not to 0
  // (docs/theory.md section 17.10). The ladder goes on until the layer lies
  // within the nodes; beyond N = 512 it is said, and the dissipation (its
  // power in x needs the layer in g) refused.
  if (layer_below_nodes(n_done)) {
    s.memory_unresolved_ = true;
    std::ostringstream m;
    m.precision(3);
    m << "viscoelastic memory: the shortest retardation length V tau = " << beta_min
      << " h is below the collocation's node spacing at the flat face's edges ("
      << w * (1.0 - std::cos(kPi / (2.0 * n_done))) << " h at N = " << n_done
      << "): the leading edge's layer of unrelaxed material is not resolved, so its end "
         "coefficient and the drag are not computed to tol (as deborah -> 0 a flat punch's "
         "drag tends to P H_inf K_0^2 (m_inf^2 - 1)/4, not to 0), and the dissipation is not "
         "computed";
    s.warnings_.push_back(m.str());
  }

  // The transforms, the Fourier nodes, the arctan rule (friction), with the
  // change between the last two sizes for the stress estimate.
  // dseries: the change between the last two sizes; when that change is
  // round-off (or there is one size only), a unit change of the top
  // coefficient instead (the shape of a truncation error): the ratio of
  // sigma_x's change to g's is what the estimate needs.
  const bool have_change = true;
  JacobiSeries dseries;
  if (!d_g.empty() && d_g.back() > 4.0 * floor_g) {
    dseries = js.minus(js_prev);
  } else {
    Eigen::VectorXd top = Eigen::VectorXd::Zero(js.size());
    top(js.size() - 1) = 1.0;
    dseries = JacobiSeries(al, be, top);
  }
  const double dg_ref = dseries.max_abs_g();
  s.jtr_omega_ = kern->quadrature().panels.alpha_max * w;
  s.jtr_ =
      std::make_shared<const JacobiTransform>(js, s.jtr_omega_, have_change ? &dseries : nullptr);
  s.atan_rule_ =
      *cached_gauss_jacobi(js.size() + 64 + static_cast<int>(std::ceil(8.0 * w)), al, be);
  s.atan_wg_ = s.atan_weights(js);

  // Surface sigma_x is linear in p: its change between the last two sizes at
  // 64 points of the face with |r| <= 0.999 and 32 beside it out to 6 w, over
  // the change of g, is the gain from g's error to the stress's (the local
  // term -phi2 w(r) dg included). Round-off of the Fourier sum as the
  // cylinder's.
  // Computed on first read (stress_error_estimate), as the cylinder's.
  s.stress_cache_->compute = [have_change, dseries = std::move(dseries), dg_ref, js, frictional, w,
                              g_coarse](const AsymmetricSolution& s) {
    std::vector<cplx> dphat;
    const Eigen::VectorXd unused_db;
    AsymmetricSolution::Fine built =
        s.build_fine(2.0 * w, have_change ? &unused_db : nullptr, &dphat);
    const AsymmetricSolution::Fine& f = built;
    const double phi2 = s.model_->phi2();
    double gain = kInf, pin = 0.0;
    std::vector<double> rs;
    for (int j = 0; j < 96; ++j) {
      if (j < 64) {
        rs.push_back(0.999 * std::cos(kPi * (j + 0.5) / 64.0));
      } else {
        const int q = j - 64;
        rs.push_back((q % 2 == 0 ? 1.0 : -1.0) * (1.0 + 5.0 * std::pow((q / 2 + 0.5) / 16.0, 2.0)));
      }
    }
    for (double r : rs)
      if (std::fabs(r) < 1.0) pin = std::max(pin, std::fabs(js.density(r)));
    if (have_change) {
      std::vector<cplx> amp(f.alpha.size());
      for (std::size_t i = 0; i < f.alpha.size(); ++i)
        amp[i] = s.surface_stress_integrand(f.r[i], f.alpha[i]) * dphat[i];
      std::vector<double> amp_re, amp_im;
      f.coefficients(amp, amp_re, amp_im);
      double dmax = 0.0;
      const Eigen::VectorXd dwg = frictional ? s.atan_weights(dseries) : Eigen::VectorXd();
      for (double r : rs) {
        const double x = w * r;
        const auto re_im = f.filon->integral_pair(x, amp_re, amp_im);
        const double sum = re_im.first.real() - re_im.second.imag();
        const double dp = std::fabs(r) < 1.0 ? dseries.density(r) : 0.0;
        const double local = frictional ? s.friction_surface_terms(x, dseries, dwg, 0.0, w) : 0.0;
        dmax = std::max(dmax, std::fabs(-phi2 * dp - sum / kPi + local));
      }
      gain = std::max(std::fabs(phi2), dmax / dg_ref);
    }
    // A viscoelastic top with inertia: its memory moves sigma_x by -phi2
    // sum_k d_k e_k * dp, at most |phi2| sum_k |d_k| max |dp| (as the
    // cylinder's estimate).
    if (const RetardationSpectrum* sm = s.model_->stress_memory()) {
      double d = 0.0;
      for (double c : sm->c) d += std::fabs(c);
      gain += std::fabs(phi2) * d;
    }
    double sabs = 0.0;
    for (std::size_t i = 0; i < f.alpha.size(); ++i)
      sabs += f.weight[i] * std::abs(s.surface_stress_integrand(f.r[i], f.alpha[i])) *
              std::abs(f.phat[i]);
    const double serr =
        gain * std::max(s.perr_, g_coarse) + 64.0 * kEps * (std::fabs(phi2) * pin + sabs / kPi);
    s.offer_light(std::move(built));
    return serr;
  };

  // Gauss-Jacobi nodes and weights times g for surface_slope.
  {
    const int m = std::max(64, 2 * static_cast<int>(s.b_.size()) + 2);
    const JacobiRule rule = gauss_jacobi(m, al, be);
    for (int i = 0; i < m; ++i) {
      s.slope_r_.push_back(rule.x(i));
      s.slope_wg_.push_back(rule.w(i) / kPi * js.g(rule.x(i)));
    }
  }

  // Validity: g >= 0 on the face, its ends included (a negative end
  // coefficient: the edge pulls on the layer). No surface beside the face
  // (square corners): min_gap is +inf.
  s.margin_ = js.min_g();
  s.min_p_ = kInf;
  for (int i = 1; i < 400; ++i)
    s.min_p_ = std::min(s.min_p_, js.density(std::cos(kPi * i / 400.0)));
  s.min_gap_ = kInf;
  // The verdict is physical, never tol's: g < 0 beyond its own error
  // estimate and a floor of 1e-6 of max |g| (the slack once was 100 tol:
  // tol = 1e-2 passed a face with p(0) = -0.9 as valid).
  constexpr double kFloor = 1e-6;
  const double slack = std::max(kFloor * gmax, s.perr_);
  std::ostringstream why;
  why.precision(6);
  s.valid_ = true;
  const double g_back = js.g(-1.0), g_front = js.g(1.0);
  if (g_back < -slack || g_front < -slack) {
    s.valid_ = false;
    why << "the pressure at the flat punch's "
        << (g_back < -slack && g_front < -slack
                ? "trailing and leading edges x/h = -+" + std::to_string(w) + " is"
            : g_back < -slack ? "trailing edge x/h = " + std::to_string(-w) + " is"
                              : "leading edge x/h = " + std::to_string(w) + " is")
        << " tensile (end coefficients K_back = " << kb << ", K_front = " << kf
        << "): the face lifts off at that edge and the single-contact solution (the whole face "
           "in contact) is unphysical";
  } else if (s.margin_ < -slack) {
    s.valid_ = false;
    why << "the contact pressure is negative inside the face (min p/(P/h) = " << s.min_p_
        << "): the face separates and the single-contact solution is unphysical";
  }
  s.validity_ =
      s.valid_ ? "valid: p >= 0 on the punch's face (its edges included)" : "invalid: " + why.str();
  if (s.valid_ && std::min({g_back, g_front, s.margin_}) < -kFloor * gmax) {
    // Valid within the estimate only (a fixed or coarse N): say so.
    std::ostringstream m;
    m.precision(3);
    m << "the sign of the pressure is not resolved: g = p/((P/h) w(r)) reaches "
      << std::min({g_back, g_front, s.margin_}) << ", within its error estimate " << s.perr_
      << " (N = " << n_done << "); the face may lift off: raise n or lower tol";
    s.warnings_.push_back(m.str());
    s.validity_ += " (up to the pressure's error estimate)";
  }
  if (!s.valid_ && !prm.allow_unphysical) throw UnphysicalContactError(s.validity_);
  s.elapsed_ = since_start();
  s.stage_seconds_ = {t_critical, kernel_seconds, t_width - t_critical,
                      s.elapsed_ - t_width - kernel_seconds};
  return s;
}

}  // namespace movingpunch

// The damped (Kelvin-Voigt) foundation: complex layer response, asymmetric
// contact, drag. Every check is against an independent anchor: the undamped
// code (damping -> 0), a Moebius map in kw built from the real response, the
// energy balance per mode and for the whole contact, the paper's Table 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "movingpunch/asymmetric.hpp"
#include "movingpunch/collocation.hpp"
#include "movingpunch/contact.hpp"
#include "movingpunch/dispersion.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/kernel.hpp"
#include "movingpunch/medium.hpp"
#include "movingpunch/viscoelastic.hpp"
#include "test_helpers.hpp"

namespace mp = movingpunch;
using mp::cplx;

namespace {

mp::AsymmetricParams damped(double vstar, double kw, double damping) {
  return mp::testing::paper_asymmetric(vstar, kw, damping);
}

const double kTs[] = {1e-3, 0.2, 0.49, 0.5, 0.8, 2.0, 5.0, 30.0, 500.0};

}  // namespace

TEST(DampedLayer, ZeroDampingIsTheUndampedResponse) {
  for (double s : {0.0, 1e-3, 0.2, 0.6}) {
    for (double kw : {0.1, 1.0, 10.0, std::numeric_limits<double>::infinity()}) {
      const mp::DampedLayerModel d(s, kw, 0.2, 0.0);
      const mp::LayerModel r(s, kw, 0.2);
      for (double t : kTs) {
        const auto a = d.response(t);
        const auto b = r.response(t);
        EXPECT_NEAR(a.M1.real(), b.M1, 1e-13 * std::max(1.0, std::fabs(b.M1)))
            << s << " " << kw << " " << t;
        EXPECT_NEAR(a.M2.real(), b.M2, 1e-13 * std::max(1.0, std::fabs(b.M2)));
        EXPECT_EQ(a.M1.imag(), 0.0);
      }
    }
  }
}

// kw enters one boundary row linearly, so M1 is a Moebius function of kw:
// three real stiffnesses of the undamped code fix it, and it must then give
// the damped response at the complex stiffness kw - i damping sqrt(s) t.
TEST(DampedLayer, MoebiusMapOfTheRealResponse) {
  for (double s : {0.2, 0.65}) {
    for (double kw : {0.1, 1.0}) {
      const double damping = 0.7;
      const mp::DampedLayerModel d(s, kw, 0.2, damping);
      for (double t : {0.3, 1.0, 2.0, 4.0}) {
        const double k[3] = {0.5 * kw, kw, 2.0 * kw};
        Eigen::Matrix3d A;
        Eigen::Vector3d m;
        for (int j = 0; j < 3; ++j) {
          m(j) = mp::LayerModel(s, k[j], 0.2).response(t).M1;
          A.row(j) << k[j], 1.0, -k[j] * m(j);  // M (c k + 1) = a k + b
        }
        const Eigen::Vector3d abc = A.fullPivLu().solve(m);
        const cplx kc(kw, -damping * std::sqrt(s) * t);
        const cplx expect = (abc(0) * kc + abc(1)) / (abc(2) * kc + 1.0);
        const cplx got = d.response(t).M1;
        EXPECT_LT(std::abs(got - expect), 1e-8 * std::abs(expect)) << s << " " << kw << " " << t;
      }
    }
  }
}

// Per wavenumber, the power put in at the top (Im M1) equals the power taken
// by the dashpots at the bottom (damping sqrt(s) |Wb|^2).
TEST(DampedLayer, EnergyBalancePerMode) {
  for (double s : {0.05, 0.2, 0.65, 0.8}) {
    for (double damping : {1e-3, 0.3, 30.0}) {
      const mp::DampedLayerModel d(s, 1.0, 0.2, damping);
      for (double t : kTs) {
        const auto r = d.response(t);
        const double diss = damping * std::sqrt(s) * std::norm(r.Wb);
        EXPECT_GE(r.M1.imag(), 0.0);
        EXPECT_NEAR(r.M1.imag(), diss, 1e-11 * std::max(diss, 1e-300) + 1e-300)
            << s << " " << damping << " " << t;
      }
    }
  }
}

TEST(DampedLayer, TransferAndModalAgree) {
  const mp::DampedLayerModel d(0.65, 0.3, 0.25, 0.5);
  for (double t : {0.3, 0.5, 1.0, 2.0, 3.5}) {
    const auto a = d.response_transfer(t), b = d.response_modal(t);
    EXPECT_LT(std::abs(a.M1 - b.M1), 1e-11 * std::abs(b.M1)) << t;
    EXPECT_LT(std::abs(a.Wb - b.Wb), 1e-11 * std::abs(b.Wb)) << t;
    EXPECT_LT(std::abs(a.M2 - b.M2), 1e-11 * std::abs(b.M2)) << t;
  }
}

TEST(DampedLayer, HalfPlaneLimitAndStaticCase) {
  const mp::DampedLayerModel d(0.4, 1.0, 0.2, 2.0);
  EXPECT_LT(std::abs(d.response(60.0).M1 - d.phi1()), 1e-14);
  EXPECT_DOUBLE_EQ(d.phi1(), mp::phi1(0.4, 0.2));
  // At rest the dashpots do nothing: identical to the springs alone.
  const mp::DampedLayerModel st(0.0, 1.0, 0.2, 5.0);
  const mp::LayerModel r(0.0, 1.0, 0.2);
  for (double t : kTs) {
    const cplx m = st.response(t).M1;
    EXPECT_EQ(m.imag(), 0.0) << t;
    EXPECT_NEAR(m.real(), r.response(t).M1, 1e-14 * std::fabs(m.real())) << t;
  }
}

TEST(DampedLayer, RejectsBadDamping) {
  for (double d : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    try {
      mp::DampedLayerModel m(0.2, 1.0, 0.2, d);
      ADD_FAILURE() << d;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("damping"), std::string::npos);
    }
  }
}

TEST(AsymmetricKernel, ZeroDampingIsK1) {
  const auto d = mp::make_medium(mp::homogeneous_medium(1.0, 0.2, 0.0, 0.0), 0.2);
  const auto q = mp::build_damped_quadrature(*d, 1e-12);
  const mp::FilonIntegrator f(q.panels);
  std::vector<double> re(q.m1.size()), im(q.m1.size());
  for (std::size_t i = 0; i < re.size(); ++i) {
    re[i] = (q.m1[i].real() - d->phi1()) / d->phi1();
    im[i] = q.m1[i].imag() / d->phi1();
  }
  const auto kr = f.coefficients(re), ki = f.coefficients(im);
  const mp::KernelK1 k1(mp::LayerModel(0.2, 1.0, 0.2), 1e-12, 3.0);
  for (double u : {-2.5, -0.4, 0.0, 0.1, 0.7, 2.9})
    EXPECT_NEAR(mp::asymmetric_kernel(f, kr, ki, u), k1(u), 1e-9) << u;
}

// damping = 1e-9 reproduces the undamped solver and the paper's Table 1.
TEST(DampedContact, TinyDampingReproducesTable1) {
  const double kws[] = {0.1, 1.0, 10.0, std::numeric_limits<double>::infinity()};
  const double paper[] = {0.3729, 0.3306, 0.3152, 0.3117};
  for (int i = 0; i < 4; ++i) {
    const auto s = mp::solve_asymmetric(damped(1e-3, kws[i], 1e-9));
    const auto u = mp::solve_contact(mp::testing::paper(1e-3, kws[i]));
    EXPECT_NEAR(s.right(), paper[i], 5e-5);
    EXPECT_NEAR(s.right(), u.a(), 1e-8);
    EXPECT_NEAR(s.left(), -u.a(), 1e-8);
    EXPECT_LT(std::fabs(s.drag()), 1e-12);
    for (double x : {0.0, 0.1, 0.25, 0.3}) {
      EXPECT_NEAR(s.pressure(x), u.pressure(x), 1e-7);
      EXPECT_NEAR(s.pressure(-x), u.pressure(-x), 1e-7);
    }
    const Eigen::VectorXd xs = mp::testing::vec({0.0, 0.2, 0.5, 1.5});
    const Eigen::VectorXd sx = u.surface_stress(xs);
    for (Eigen::Index j = 0; j < xs.size(); ++j)
      EXPECT_NEAR(s.surface_stress(xs(j)), sx(j), 1e-7) << kws[i] << " " << xs(j);
  }
}

TEST(DampedContact, DepthStressMatchesUndampedSolver) {
  const auto s = mp::solve_asymmetric(damped(0.2, 1.0, 1e-9));
  const auto u = mp::solve_contact(mp::testing::paper(0.2, 1.0));
  // The damped and the undamped evaluations (each a closed-form half-plane
  // part plus a remainder, on their own nodes), down to and at the surface.
  const Eigen::VectorXd ys =
      mp::testing::vec({-1.0, -0.75, -0.5, -0.1, -0.01, -0.002, -1e-4, -1e-7, 0.0});
  const Eigen::VectorXd sx = u.depth_stress(ys);
  for (Eigen::Index j = 0; j < ys.size(); ++j)
    EXPECT_NEAR(s.stress_x(0.0, ys(j)), sx(j), 1e-8) << ys(j);
  EXPECT_THROW((void)s.stress_x(0.0, 1e-4), std::invalid_argument);
  EXPECT_THROW((void)s.stress_x(0.0, -1.5), std::invalid_argument);
}

// The field at the faces, in real space: traction-free top (tau = 0,
// sigma_y -> -p), and at the bottom tau = 0 and the Kelvin-Voigt condition
// sigma_y = kw v - damping sqrt(vstar) dv/dx, sub- and supercritical.
TEST(DampedContact, FaceConditionsInRealSpace) {
  for (const double vstar : {0.2, 0.65}) {
    const auto p = damped(vstar, 1.0, 0.3);
    const auto s = mp::solve_asymmetric(p);
    const double beta = p.damping * std::sqrt(vstar);
    for (double x : {-1.5, -0.3, 0.0, 0.4, 1.0, 2.5}) {
      const Eigen::Vector3d b = s.stresses(x, -1.0);
      const double vb = s.bottom_displacement(x), sb = s.bottom_slope(x);
      EXPECT_NEAR(p.load * b(1), p.kw * vb - beta * sb, 1e-9 * p.load) << vstar << " " << x;
      EXPECT_NEAR(b(2), 0.0, 1e-9);
    }
    // Bottom slope against a central difference of the bottom displacement.
    const double hstep = 1e-3;
    EXPECT_NEAR(
        s.bottom_slope(0.3),
        (s.bottom_displacement(0.3 + hstep) - s.bottom_displacement(0.3 - hstep)) / (2 * hstep),
        1e-8);
    // Towards the top, sigma_y -> -p and tau -> 0 linearly in y.
    const double xc = s.centre();
    const Eigen::Vector3d t2 = s.stresses(xc, -2e-3), t4 = s.stresses(xc, -4e-3);
    EXPECT_NEAR(2.0 * t2(1) - t4(1), -s.pressure(xc), 1e-4 * s.pressure(xc));
    EXPECT_NEAR(t2(2) / t4(2), 0.5, 0.02);
  }
}

// The whole field (sigma_x, sigma_y, tau_xy) against the undamped solver.
TEST(DampedContact, StressFieldMatchesUndampedSolver) {
  const auto s = mp::solve_asymmetric(damped(0.2, 1.0, 1e-9));
  const auto u = mp::solve_contact(mp::testing::paper(0.2, 1.0));
  const Eigen::VectorXd xs = mp::testing::vec({-0.6, 0.0, 0.2, 0.37, 1.0});
  const Eigen::VectorXd ys = mp::testing::vec({-1.0, -0.5, -0.05, -0.002, -1e-5, 0.0});
  const auto f = u.stress_field(xs, ys);
  for (Eigen::Index i = 0; i < ys.size(); ++i)
    for (Eigen::Index j = 0; j < xs.size(); ++j) {
      const Eigen::Vector3d t = s.stresses(xs(j), ys(i));
      EXPECT_NEAR(t(0), f.sigma_x(i, j), 1e-8) << xs(j) << " " << ys(i);
      EXPECT_NEAR(t(1), f.sigma_y(i, j), 1e-8) << xs(j) << " " << ys(i);
      EXPECT_NEAR(t(2), f.tau_xy(i, j), 1e-8) << xs(j) << " " << ys(i);
    }
}

TEST(DampedContact, NoEffectAtRest) {
  const auto s = mp::solve_asymmetric(damped(0.0, 1.0, 5.0));
  EXPECT_NEAR(s.right(), 0.330419, 1e-6);  // the static study cited by the paper
  EXPECT_NEAR(s.left(), -s.right(), 1e-12);
  EXPECT_LT(std::fabs(s.drag()), 1e-14);
}

TEST(DampedContact, DragVanishesWithSpeed) {
  double prev = std::numeric_limits<double>::infinity();
  for (double v : {1e-2, 1e-4, 1e-6}) {
    const double drag = mp::solve_asymmetric(damped(v, 1.0, 1.0)).drag();
    EXPECT_GT(drag, 0.0);
    EXPECT_LT(drag, 0.2 * prev);  // drag ~ damping sqrt(vstar) at low speed
    prev = drag;
  }
  EXPECT_LT(prev, 1e-6);
}

// drag P V = int c_w (V dv/dx(x, -h))^2 dx: the drag from the contact solution
// against the dissipation from the layer's bottom response (Parseval).
TEST(DampedContact, EnergyBalance) {
  struct Case {
    double vstar, kw, damping;
  };
  for (const Case c :
       {Case{0.2, 1.0, 0.1}, Case{0.2, 1.0, 1.0}, Case{0.2, 0.1, 3.0}, Case{0.65, 1.0, 0.1},
        Case{0.65, 1.0, 0.01}, Case{0.3, 0.01, 0.1}, Case{0.8, 1.0, 0.01}}) {
    const auto s = mp::solve_asymmetric(damped(c.vstar, c.kw, c.damping));
    EXPECT_GT(s.drag(), 0.0);
    EXPECT_NEAR(s.dissipation() / s.drag(), 1.0, 1e-6)
        << c.vstar << " " << c.kw << " " << c.damping;
    EXPECT_TRUE(s.valid()) << s.validity();
    // The punch profile is followed on the contact: slope x/R.
    for (double r : {-0.9, 0.0, 0.6})
      EXPECT_NEAR(s.surface_slope(s.centre() + r * s.half_width()),
                  (s.centre() + r * s.half_width()) / 100.0, 1e-9);
  }
}

// As damping -> 0 above V*_cr the solution converges (limiting absorption),
// at first order in the damping.
TEST(DampedContact, LimitingAbsorptionAboveCriticalSpeed) {
  ASSERT_GT(0.65, mp::critical_vstar(1.0, 0.2));
  double r[4], l[4], dr[4];
  const double ds[4] = {1e-3, 1e-4, 1e-5, 1e-6};
  for (int i = 0; i < 4; ++i) {
    const auto s = mp::solve_asymmetric(damped(0.65, 1.0, ds[i]));
    r[i] = s.right();
    l[i] = s.left();
    dr[i] = s.drag();
  }
  for (int i = 0; i < 2; ++i) {
    const double ratio = (r[i + 1] - r[i]) / (r[i + 2] - r[i + 1]);
    EXPECT_GT(ratio, 8.0);
    EXPECT_LT(ratio, 12.0);
    const double lratio = (l[i + 1] - l[i]) / (l[i + 2] - l[i + 1]);
    EXPECT_GT(lratio, 8.0);
    EXPECT_LT(lratio, 12.0);
  }
  EXPECT_LT(std::fabs(r[3] - r[2]), 1e-5);
  EXPECT_LT(std::fabs(dr[3] - dr[2]) / dr[3], 1e-5);
  EXPECT_GT(l[3], 0.0);  // the whole contact lies ahead of the punch's lowest point
}

// Above V*_cr lambda(w) is not monotone: between the local maximum and
// minimum of lambda(w) three contacts carry the same load; all are reported.
TEST(DampedContact, MultipleSteadyStatesAreReported) {
  EXPECT_TRUE(mp::solve_asymmetric(damped(0.65, 1.0, 0.01)).other_half_widths().empty());
  auto p = damped(0.65, 1.0, 0.01);
  p.load = 0.0025;  // lambda = 0.25, inside the fold (0.21, 0.31)
  const auto s = mp::solve_asymmetric(p);
  ASSERT_EQ(s.other_half_widths().size(), 2u);
  EXPECT_NEAR(s.half_width(), 0.459, 0.01);
  EXPECT_NEAR(s.other_half_widths()[0], 0.728, 0.02);
  EXPECT_NEAR(s.other_half_widths()[1], 1.120, 0.02);
  EXPECT_NE(s.validity().find("not unique"), std::string::npos);
}

TEST(DampedContact, RayleighSpeedIsRefused) {
  const double vr = mp::rayleigh_vstar(0.2);
  EXPECT_THROW(mp::solve_asymmetric(damped(vr, 1.0, 0.1)), mp::SupercriticalSpeedError);
  EXPECT_THROW(mp::solve_asymmetric(damped(0.9, 1.0, 0.1)), mp::SupercriticalSpeedError);
  EXPECT_NO_THROW(mp::solve_asymmetric(damped(0.8, 1.0, 0.1)));
}

TEST(DampedContact, ValidatesDamping) {
  for (double d : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    try {
      (void)mp::solve_asymmetric(damped(0.2, 1.0, d));
      ADD_FAILURE() << d;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("damping"), std::string::npos) << e.what();
    }
  }
}

TEST(DampedContact, HardCases) {
  // Large damping: the dashpots lock the base; drag small, energy balanced.
  const auto big = mp::solve_asymmetric(damped(0.6, 1.0, 1e3));
  EXPECT_NEAR(big.dissipation() / big.drag(), 1.0, 1e-6);
  // Tiny damping a hair below V*_cr: the undamped width.
  const double vcr = mp::critical_vstar(1.0, 0.2);
  const auto near = mp::solve_asymmetric(damped(vcr * (1.0 - 1e-6), 1.0, 1e-8));
  const auto und = mp::solve_contact(mp::testing::paper(vcr * (1.0 - 1e-6), 1.0));
  EXPECT_NEAR(near.right(), und.a(), 1e-5);
  EXPECT_NEAR(near.left(), -und.a(), 1e-5);
  // The near-resonant peaks (width ~ damping) keep the kernel quadrature's
  // error estimate above tol = 1e-8 there: said in the warnings, not silent.
  ASSERT_FALSE(near.warnings().empty());
  EXPECT_NE(near.warnings().front().find("kernel quadrature"), std::string::npos)
      << near.warnings().front();
  EXPECT_GT(near.error_estimate(), 1e-8 * (near.half_width() + std::fabs(near.centre())));
  // Supercritical on a very soft foundation with a wide contact (a + b ~ 5h).
  auto p = damped(0.3, 0.01, 0.1);
  p.load = 0.02;
  const auto wide = mp::solve_asymmetric(p);
  EXPECT_GT(wide.half_width(), 2.0);
  EXPECT_NEAR(wide.dissipation() / wide.drag(), 1.0, 1e-6);
  EXPECT_TRUE(wide.valid());
  // Dashpots alone (kw -> 0) far above V*_cr: a bounded steady state (the
  // wake stays sunk); the limit is reached smoothly and energy balances.
  const auto d12 = mp::solve_asymmetric(damped(0.3, 1e-12, 1.0));
  const auto d6 = mp::solve_asymmetric(damped(0.3, 1e-6, 1.0));
  EXPECT_NEAR(d12.right(), d6.right(), 1e-6);
  EXPECT_NEAR(d12.left(), d6.left(), 1e-6);
  EXPECT_NEAR(d12.dissipation() / d12.drag(), 1.0, 1e-6);
  // Lighter damping there separates the contact: flagged, never silent.
  p.damping = 0.01;
  EXPECT_THROW(mp::solve_asymmetric(p), mp::UnphysicalContactError);
  p.allow_unphysical = true;
  const auto bad = mp::solve_asymmetric(p);
  EXPECT_FALSE(bad.valid());
  EXPECT_LT(bad.min_pressure(), 0.0);
}

// The refinement rule on a synthetic sequence with a known error: x_N =
// rho^N. The estimate of the last member bounds its error and is within a
// factor 100 of it; round-off changes and stagnation are recognised.
TEST(AsymmetricRefinement, EstimateOfAGeometricSequence) {
  for (double rho : {0.3, 0.6, 0.85}) {
    const std::vector<int> n = {8, 12, 16, 24, 32};
    for (std::size_t m = 3; m <= n.size(); ++m) {
      std::vector<int> sizes(n.begin(), n.begin() + static_cast<long>(m));
      std::vector<double> changes;
      for (std::size_t k = 1; k < m; ++k)
        changes.push_back(std::pow(rho, sizes[k - 1]) - std::pow(rho, sizes[k]));
      const double error = std::pow(rho, sizes.back());
      const auto e = mp::refinement_estimate(sizes, changes, 1e-30);
      EXPECT_FALSE(e.at_floor);
      EXPECT_FALSE(e.stagnated);
      EXPECT_GE(e.estimate, error) << rho << " " << m;
      EXPECT_LE(e.estimate, 100.0 * error) << rho << " " << m;
    }
  }
  // A change within 4 floors: round-off.
  const auto f = mp::refinement_estimate({8, 12, 16}, {1e-6, 3e-15}, 1e-15);
  EXPECT_TRUE(f.at_floor);
  EXPECT_DOUBLE_EQ(f.estimate, 4e-15);
  // Changes that stop shrinking: stagnation, the larger change is reported.
  const auto s = mp::refinement_estimate({8, 12, 16, 24}, {1e-9, 9e-10, 9.5e-10}, 1e-16);
  EXPECT_TRUE(s.stagnated);
  EXPECT_NEAR(s.estimate, 9.5e-10, 1e-15);
  EXPECT_THROW(mp::refinement_estimate({8}, {1.0}, 0.0), std::invalid_argument);
}

// A single rate reading (two changes) of an algebraically converging
// sequence x_N = N^-p (a profile's kinks) is bounded too, within a factor
// 100; so is the honesty fuzz's rounded flat (changes 2.09e-5, 2.4e-8 at
// N = 12, 16; error 1.14e-9 at 16; the geometric reading alone: 3.0e-10).
TEST(AsymmetricRefinement, ASingleReadingOfAnAlgebraicRate) {
  for (double p : {1.0, 2.0, 4.0, 10.6, 20.0}) {
    const std::vector<int> sizes = {8, 12, 16};
    auto x = [&](int n) { return std::pow(static_cast<double>(n), -p); };
    const auto e = mp::refinement_estimate(sizes, {x(8) - x(12), x(12) - x(16)}, 1e-300);
    EXPECT_GE(e.estimate, x(16)) << p;
    EXPECT_LE(e.estimate, 100.0 * x(16)) << p;
    EXPECT_NEAR(mp::algebraic_error(8, 12, 16, x(8) - x(12), x(12) - x(16)), x(16), 1e-9 * x(16))
        << p;
  }
  const auto f = mp::refinement_estimate({8, 12, 16}, {2.09e-5, 2.4e-8}, 1e-18);
  EXPECT_GE(f.estimate, 1.14e-9);
  // Changes that do not shrink: no algebraic reading; the geometric one
  // (q capped at 0.99) stands.
  EXPECT_EQ(mp::algebraic_error(8, 12, 16, 1e-8, 1e-8), 0.0);
  EXPECT_NEAR(mp::refinement_estimate({8, 12, 16}, {1e-8, 2e-8}, 0.0).estimate, 10.0 * 2e-8 * 99.0,
              1e-15);
}

// A single rate reading from a drop of more than 1e3 in one step is not
// trusted: the ladder goes on (a rounded flat with friction: changes 9.2e-5,
// 1.05e-8 at N = 12, 16, then an error 1.8e-8 at 16); a third change that
// keeps the rate confirms it.
TEST(AsymmetricRefinement, AnUnconfirmedRateGoesOn) {
  const auto u = mp::refinement_estimate({8, 12, 16}, {9.2e-5, 1.05e-8}, 1e-18);
  EXPECT_TRUE(u.unconfirmed);
  EXPECT_LT(u.estimate, 1.8e-8);  // the extrapolation alone would stop here
  const auto ok = mp::refinement_estimate({8, 12, 16}, {1e-9, 1e-11}, 1e-18);
  EXPECT_EQ(mp::ladder_stop(1e-3, u, 1.05e-8, 1.0, ok, 1e-11, 1.0), mp::LadderStop::go_on);
  EXPECT_EQ(mp::ladder_stop(1e-3, ok, 1e-11, 1.0, u, 1.05e-8, 1.0), mp::LadderStop::go_on);
  // At the round-off floor it is not in the way.
  const auto f = mp::refinement_estimate({8, 12, 16}, {1e-6, 3e-15}, 1e-15);
  EXPECT_FALSE(f.unconfirmed);
  EXPECT_EQ(mp::ladder_stop(1e-3, f, 3e-15, 1.0, f, 3e-15, 1.0), mp::LadderStop::converged);
  // A geometric rate (ratio 1e-2 per step) is read at once.
  const auto g = mp::refinement_estimate({8, 12, 16}, {1e-4, 1e-6}, 1e-18);
  EXPECT_FALSE(g.unconfirmed);
  // Three changes: the rate is no longer a single reading.
  const auto t = mp::refinement_estimate({8, 12, 16, 24}, {9.2e-5, 1.05e-8, 1.8e-8}, 1e-18);
  EXPECT_FALSE(t.unconfirmed);
  EXPECT_GE(t.estimate, 1.8e-8);
}

// A fixed N's error from finer references (fixed_size_error) on a synthetic
// sequence x_m = rho^m: it bounds |x_N| within a small factor, stops once
// the references' own estimate is small, and is infinite when a reference
// has no solution.
TEST(AsymmetricRefinement, FixedSizeErrorFromFinerSizes) {
  for (double rho : {0.5, 0.8, 0.95}) {
    for (int n : {2, 4, 6, 16}) {
      std::vector<int> asked;
      double prev = 0.0;
      const mp::FixedError fe = mp::fixed_size_error(n, [&](int m) {
        asked.push_back(m);
        mp::FixedSample s;
        const double x = std::pow(rho, m);
        s.d_n_v = std::pow(rho, n) - x;
        s.d_n_p = s.d_n_v;
        s.d_v = prev - x;
        s.d_p = s.d_v;
        s.floor_v = s.floor_p = 1e-300;
        prev = x;
        return s;
      });
      const double error = std::pow(rho, n);
      EXPECT_GE(fe.v, error) << rho << " " << n;
      EXPECT_LE(fe.v, 3.0 * error) << rho << " " << n;
      EXPECT_GE(fe.p, error);
      EXPECT_EQ(asked.front(), std::max(2 * n, 8));
      EXPECT_EQ(fe.ref_n, asked.back());
      EXPECT_LE(asked.back(), mp::kFixedReferenceMax);
    }
  }
  const mp::FixedError none = mp::fixed_size_error(4, [](int m) -> mp::FixedSample {
    if (m > 8) throw mp::ConvergenceError("no root");
    return mp::FixedSample{};
  });
  EXPECT_TRUE(std::isinf(none.v));
  EXPECT_TRUE(std::isinf(none.p));
}

// Series scans against direct evaluation on a fine grid.
TEST(AsymmetricRefinement, SeriesScans) {
  Eigen::VectorXd b(5);
  b << 1.0, -0.3, 0.45, 0.2, -0.1;
  double mx = 0.0, mn = 1e300, arg = 0.0;
  for (int j = 0; j <= 200000; ++j) {
    const double th = 3.14159265358979323846 * j / 200000.0, r = std::cos(th);
    double p = 0.0;
    for (int k = 0; k < 5; ++k) p += b(k) * std::sin((k + 1) * th);
    mx = std::max(mx, std::fabs(p));
    const double g = mp::u_series(b, r);
    if (g < mn) {
      mn = g;
      arg = r;
    }
  }
  EXPECT_NEAR(mp::max_abs_sine_series(b), mx, 2e-3 * mx);
  EXPECT_LE(mp::max_abs_sine_series(b), mx * (1.0 + 1e-12));
  double where = 0.0;
  EXPECT_NEAR(mp::u_series_minimum(b, &where), mn, 1e-9);
  EXPECT_LE(mp::u_series_minimum(b), mn + 1e-15);
  EXPECT_NEAR(where, arg, 1e-4);
}

// The N ladder refines on the pressure, not only the ends: at the issue's
// case the ends are converged at N = 12 but p is not (2e-9 there); the
// pressure against a fixed-N reference meets tol and the estimates bound it.
TEST(AsymmetricRefinement, PressureMeetsTol) {
  auto p = damped(0.65, 1.0, 0.1);
  p.tol = 1e-11;
  const auto s = mp::solve_asymmetric(p);
  auto q = p;
  q.n = 32;
  q.tol = 1e-14;
  const auto ref = mp::solve_asymmetric(q);
  EXPECT_GT(s.collocation_n(), 12);
  EXPECT_TRUE(s.warnings().empty()) << s.warnings().front();
  double err = 0.0;
  for (int j = 1; j < 400; ++j) {
    const double r = -1.0 + 2.0 * j / 400.0;
    err = std::max(err, std::fabs(s.pressure(s.centre() + s.half_width() * r) -
                                  ref.pressure(ref.centre() + ref.half_width() * r)));
  }
  EXPECT_LE(err, p.tol * s.max_pressure());
  EXPECT_LE(err, s.pressure_error_estimate());
  EXPECT_LE(s.pressure_error_estimate(), p.tol * s.max_pressure());
  EXPECT_LE(std::fabs(s.right() - ref.right()), s.error_estimate());
  EXPECT_LE(std::fabs(s.left() - ref.left()), s.error_estimate());
  EXPECT_GT(s.pressure_margin(), 0.0);
  // A fixed small n cannot reach tol = 1e-13: said, with the amount.
  auto f = p;
  f.n = 8;
  f.tol = 1e-13;
  const auto coarse = mp::solve_asymmetric(f);
  ASSERT_FALSE(coarse.warnings().empty());
  EXPECT_NE(coarse.warnings().front().find("x tol"), std::string::npos);
}

// The tabulated kernel against its direct Filon sums (a second evaluation
// of the same integral, point by point): within the table's own error bound,
// and that bound at round-off, sub- and supercritical and near resonance.
TEST(AsymmetricKernelTable, MatchesDirectSumsWithinItsBound) {
  struct Case {
    double vstar, kw, damping;
  };
  for (const Case c :
       {Case{0.2, 1.0, 0.1}, Case{0.65, 1.0, 0.1}, Case{0.8, 1.0, 0.01}, Case{0.3, 0.01, 1.0}}) {
    const auto model = mp::make_medium(mp::homogeneous_medium(c.kw, 0.2, 0.0, c.damping), c.vstar);
    const mp::AsymmetricKernel k(model, 3.0);
    EXPECT_LT(k.table_error(), 1e-13) << c.vstar;
    double worst = 0.0;
    std::vector<double> us, batch;
    for (int i = 0; i <= 240; ++i) us.push_back(-3.0 + 6.0 * i / 240.0 + 1e-3 * std::sin(i));
    us.push_back(3.0);
    batch.resize(us.size());
    k.many(us.data(), batch.data(), us.size());
    for (std::size_t i = 0; i < us.size(); ++i) {
      const double u = std::clamp(us[i], -3.0, 3.0);
      const double d = k.direct(u);
      worst = std::max(worst, std::fabs(k(u) - d));
      EXPECT_EQ(batch[i], k(us[i])) << u;  // the batch is the same evaluation
    }
    EXPECT_LE(worst, k.table_error()) << c.vstar;
    // Beyond the range: the direct sums.
    EXPECT_EQ(k(7.5), k.direct(7.5));
    // A wider table on the same quadrature agrees inside the narrower range.
    const mp::AsymmetricKernel wide(k, 9.0);
    for (double u : {-2.9, -0.3, 0.0, 0.7, 2.5})
      EXPECT_NEAR(wide(u), k(u), k.table_error() + wide.table_error()) << u;
  }
}

// The process-wide cache: a second solve that changes only the load or the
// radius builds nothing and equals a solve from an empty cache; other inputs
// build their own table; clear_kernel_cache() empties it.
TEST(AsymmetricKernelTable, CachedAcrossSolves) {
  mp::clear_kernel_cache();
  const auto first = mp::solve_asymmetric(damped(0.65, 1.0, 0.1));
  EXPECT_GE(first.kernel_builds(), 1);
  auto p = damped(0.65, 1.0, 0.1);
  p.load = 0.0021;
  const auto second = mp::solve_asymmetric(p);
  EXPECT_EQ(second.kernel_builds(), 0);
  p.radius = 90.0;
  EXPECT_EQ(mp::solve_asymmetric(p).kernel_builds(), 0);
  p.radius = 100.0;
  mp::clear_kernel_cache();
  EXPECT_EQ(mp::asymmetric_kernel_cache_info().size, 0u);
  const auto fresh = mp::solve_asymmetric(p);
  EXPECT_GE(fresh.kernel_builds(), 1);
  EXPECT_NEAR(second.left(), fresh.left(), 1e-13);
  EXPECT_NEAR(second.right(), fresh.right(), 1e-13);
  EXPECT_NEAR(second.drag(), fresh.drag(), 1e-12 * fresh.drag());
  bool built = false;
  mp::cached_damped_kernel(0.65, 1.0, 0.2, 0.2, 1.0, 2.0, &built);  // another damping
  EXPECT_TRUE(built);
  // Stage times sum to the elapsed time.
  const auto& t = fresh.stage_seconds();
  EXPECT_NEAR(t.critical_speed + t.kernel + t.width + t.checks, fresh.elapsed(),
              1e-3 * fresh.elapsed() + 1e-6);
  mp::clear_kernel_cache();
}

// A positive form (Re M1 > 0 at every wavenumber) makes the frictionless
// contact unique; above V*_cr (the fold above) Re M1 < 0 near the
// resonance and the scan for other steady states runs. Anchors: the
// undamped layer below V*_cr (M1 real and positive, Ji's sign of the
// dispersion), the supercritical damped layer (its three contacts above),
// and a Zener layer (Re 1/m(omega) > 0 for any passive material).
TEST(DampedContact, APositiveFormMakesTheContactUnique) {
  auto kernel = [](double vstar, double damping) {
    return mp::cached_damped_kernel(vstar, 1.0, 0.2, damping, 1.0, 2.0);
  };
  EXPECT_TRUE(kernel(0.0, 0.0)->positive_form());
  EXPECT_TRUE(kernel(0.3, 0.0)->positive_form());
  EXPECT_TRUE(kernel(0.3, 0.5)->positive_form());
  EXPECT_FALSE(kernel(0.65, 0.01)->positive_form());
  mp::MediumSpec spec = mp::homogeneous_medium(1.0, 0.25);
  spec.layers[0].visco = mp::zener(4.0, 0.3);
  for (double vstar : {0.0, 0.2}) {
    const auto zener = mp::cached_damped_kernel(mp::make_medium(spec, vstar), 1.0, 2.0);
    EXPECT_TRUE(zener->positive_form()) << vstar;
  }
  // The solutions say so; the supercritical one (not unique) does not.
  const auto below = mp::solve_asymmetric(damped(0.3, 1.0, 0.5));
  EXPECT_NE(below.validity().find("unique (the medium's form is positive"), std::string::npos);
  auto p = damped(0.65, 1.0, 0.01);
  p.load = 0.0025;
  const auto above = mp::solve_asymmetric(p);
  EXPECT_EQ(above.validity().find("unique (the medium"), std::string::npos);
  // With friction the operator has another part: no claim, the scan runs.
  const auto rough = mp::solve_asymmetric(mp::testing::paper_asymmetric(0.3, 1.0, 0.5, 0.3));
  EXPECT_EQ(rough.validity().find("unique (the medium"), std::string::npos);
}

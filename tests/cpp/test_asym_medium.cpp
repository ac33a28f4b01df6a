// The asymmetric solver on the medium interface (medium.hpp): the tangential
// response of a stack against a naive long-double product of the sublayers'
// transfer matrices and against the homogeneous layer (DampedLayerModel), its
// bar pole against bar theory, and the solver on K identical sublayers against
// the homogeneous layer and on a bonded half-space of the layer's own
// material against the moving half-plane's closed form with friction.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "media_reference.hpp"
#include "movingpunch/asymmetric.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/jacobi.hpp"
#include "movingpunch/medium.hpp"

using namespace movingpunch;
using namespace movingpunch::testing;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

std::vector<Sublayer> mixed() {
  return {{0.3, 1.0, 0.2, 1.0, 0.0}, {0.45, 0.35, 0.3, 0.8, 0.0}, {0.25, 2.5, 0.25, 1.6, 0.0}};
}

// The top load (T0, S0) = (tau/alpha, sigma/alpha) at y = 0: the surface's
// U, W and the W of the base face, by the naive product of the sublayers'
// transfer matrices (z(-1) = P z(0)) and the base conditions.
struct Naive {
  double U = 0, W = 0, Wb = 0;
  // The state at depth y (the product down to y).
  std::array<double, 4> at(double y) const {
    M4 P = to(y);
    std::array<double, 4> z{};
    for (int r = 0; r < 4; ++r)
      z[static_cast<size_t>(r)] = static_cast<double>(P[r][0] * z0[0] + P[r][1] * z0[1] +
                                                      P[r][2] * z0[2] + P[r][3] * z0[3]);
    return z;
  }
  M4 to(double y) const {
    M4 P{};
    for (int i = 0; i < 4; ++i) P[i][i] = 1;
    LD top = 0;
    for (const Sublayer& l : spec.layers) {
      const LD bot = top - l.thickness;
      const LD d = std::min<LD>(l.thickness, top - y);
      if (d <= 0) break;
      const LD s = static_cast<LD>(vstar) * l.rho / l.mu;
      M4 B = state_matrix(s, l.nu);
      for (auto& r : B)
        for (LD& x : r) x *= -static_cast<LD>(t) * d;
      M4 E = expm(B);
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
          E[i][j] *= (i >= 2 ? static_cast<LD>(l.mu) : 1.0L);
          E[i][j] /= (j >= 2 ? static_cast<LD>(l.mu) : 1.0L);
        }
      P = mul(E, P);
      top = bot;
    }
    return P;
  }
  MediumSpec spec;
  double vstar = 0, t = 0;
  V4 z0{};
};

Naive naive(const MediumSpec& m, double vstar, double t, LD T0, LD S0) {
  Naive n;
  n.spec = m;
  n.vstar = vstar;
  n.t = t;
  const M4 P = n.to(-1.0);
  const auto x = naive_top_unknowns(P, m, vstar, t, T0, S0);
  n.z0 = {x[0], x[1], T0, S0};
  n.U = static_cast<double>(x[0]);
  n.W = static_cast<double>(x[1]);
  n.Wb = static_cast<double>(P[1][0] * x[0] + P[1][1] * x[1] + P[1][2] * T0 + P[1][3] * S0);
  return n;
}

double rel(cplx a, double b, double scale) { return std::abs(a - b) / scale; }

}  // namespace

// The tangential (and the normal) load's responses of a mixed stack on every
// base against the naive long-double product, 1e-12 of the responses' scale.
TEST(AsymMedium, StackTangentialResponseMatchesNaiveLongDoubleProduct) {
  const double s = 0.12;
  for (const MediumSpec& spec :
       {springs(mixed(), 1.7), springs(mixed(), 0.4, 0.3), springs(mixed(), kInf),
        half_space(mixed(), BaseKind::half_space_bonded, 3.0, 0.3, 1.5),
        half_space(mixed(), BaseKind::half_space_smooth, 0.8, 0.25, 1.2)}) {
    const auto m = make_medium(spec, s);
    for (double t : {0.05, 0.4, 1.5, 4.0}) {
      const FullResponse r = m->full_response(t);
      const Naive q = naive(spec, s, t, 1.0L, 0.0L), n = naive(spec, s, t, 0.0L, -1.0L);
      const double sq = std::max({std::fabs(q.U), std::fabs(q.W), 1.0});
      const double sn = std::max({std::fabs(n.U), std::fabs(n.W), 1.0});
      EXPECT_LT(rel(r.Uq, q.U, sq), 1e-12) << describe(spec) << " t " << t;
      EXPECT_LT(rel(r.Wq, q.W, sq), 1e-12) << describe(spec) << " t " << t;
      EXPECT_LT(rel(r.Wqb, q.Wb, sq), 1e-12) << describe(spec) << " t " << t;
      EXPECT_LT(rel(r.Wb, n.Wb, sn), 1e-12) << describe(spec) << " t " << t;
      EXPECT_LT(rel(r.M1, -n.W, sn), 1e-12) << describe(spec) << " t " << t;
      // The tangential state at depths, interfaces included (W, tau continuous).
      for (double y : {-0.1, -0.3, -0.55, -0.75, -1.0}) {
        const Eigen::Vector4cd z = m->tangential_state(t, y);
        const auto ref = q.at(y);
        for (int k = 0; k < 4; ++k)
          EXPECT_LT(rel(z(k), ref[static_cast<size_t>(k)], sq), 1e-12)
              << describe(spec) << " t " << t << " y " << y << " row " << k;
      }
    }
  }
}

// K identical sublayers: the homogeneous layer's closed forms (DampedLayerModel).
TEST(AsymMedium, IdenticalSublayersTangentialIsTheHomogeneousLayers) {
  for (double kw : {0.3, 2.0, kInf})
    for (double s : {0.0, 0.2, 0.45}) {
      const auto stack = make_medium(springs(identical(3, 0.27), kw, 0.1), s);
      const auto hom = make_medium(homogeneous_medium(kw, 0.27, 0.1), s);
      for (double t : {1e-3, 0.1, 0.49, 0.51, 2.0, 9.0, 30.0}) {
        const FullResponse a = stack->full_response(t), b = hom->full_response(t);
        const double sc = std::max({std::abs(b.Uq), std::abs(b.Wq), 1.0});
        EXPECT_LT(std::abs(a.Uq - b.Uq) / sc, 1e-12) << kw << " " << s << " " << t;
        EXPECT_LT(std::abs(a.Wq - b.Wq) / sc, 1e-12) << kw << " " << s << " " << t;
        EXPECT_LT(std::abs(a.Wqb - b.Wqb) / sc, 1e-12) << kw << " " << s << " " << t;
        EXPECT_LT(std::abs(a.Wb - b.Wb), 1e-12) << kw << " " << s << " " << t;
        EXPECT_LT(std::abs(a.M1 - b.M1), 1e-12 * std::abs(b.M1) + 1e-15) << kw << " " << t;
      }
      EXPECT_EQ(stack->tangential().Uq, hom->tangential().Uq);
      EXPECT_NEAR(stack->bar_compliance(), hom->bar_compliance(), 1e-14 * hom->bar_compliance());
    }
}

// The bar pole: t Uq(t) -> bar_compliance() (bar theory: the stack carries
// the net horizontal force in proportion to its sublayers' dynamic plane-strain
// stiffnesses) on shear-free bases, linearly in t; bounded on a bonded half-space.
TEST(AsymMedium, TangentialBarPoleIsTheStacksBarCompliance) {
  const double s = 0.1;
  std::vector<Sublayer> graded = mixed();
  graded[2].gamma = 1.5;
  for (const MediumSpec& spec : {springs(mixed(), 1.3), springs(graded, kInf),
                                 half_space(mixed(), BaseKind::half_space_smooth, 2.0, 0.3, 1.0)}) {
    const auto m = make_medium(spec, s);
    const double bar = m->bar_compliance();
    ASSERT_GT(bar, 0.0);
    const double e1 = std::fabs(1e-4 * m->full_response(1e-4).Uq.real() - bar);
    const double e2 = std::fabs(1e-5 * m->full_response(1e-5).Uq.real() - bar);
    EXPECT_LT(e2, 2e-4 * bar) << describe(spec);
    EXPECT_LT(e2, 0.2 * e1) << describe(spec);  // O(t)
  }
  const auto b = make_medium(half_space(mixed(), BaseKind::half_space_bonded, 2.0, 0.3, 1.0), s);
  EXPECT_EQ(b->bar_compliance(), 0.0);
  EXPECT_LT(std::fabs(1e-6 * b->full_response(1e-6).Uq.real()), 1e-4);
}

// The damped homogeneous layer is a Medium now (real() false), its responses
// DampedLayerModel's bit for bit.
TEST(AsymMedium, DampedHomogeneousLayerIsAMedium) {
  const auto m = make_medium(homogeneous_medium(1.0, 0.2, 0.1, 0.5), 0.3);
  EXPECT_FALSE(m->real());
  const DampedLayerModel d(0.3, 1.0, 0.2, 0.5, 0.1);
  for (double t : {0.2, 1.0, 5.0}) {
    const FullResponse a = m->full_response(t), b = d.response(t);
    EXPECT_EQ(a.M1, b.M1);
    EXPECT_EQ(a.Wb, b.Wb);
    EXPECT_EQ(a.Uq, b.Uq);
    EXPECT_EQ(m->surface_response(t).M1, b.M1);
    EXPECT_EQ(m->mode(t)->state(-0.4).z(1), d.state(t, -0.4)(1));
  }
  EXPECT_DOUBLE_EQ(m->base_damper(), 0.5 * std::sqrt(0.3));
  EXPECT_NE(m->homogeneous_layer(), nullptr);
}

namespace {

AsymmetricParams stack_params(const MediumSpec& spec, double friction) {
  AsymmetricParams p;
  p.vstar = 0.2;
  p.radius = 50.0;
  p.load = 0.004;
  p.friction = friction;
  p.tol = 1e-11;
  p.medium = std::make_shared<const MediumSpec>(spec);
  return p;
}

void expect_same_contact(const AsymmetricSolution& a, const AsymmetricSolution& b,
                         const char* what) {
  const double tol = 1e-10 + 2.0 * (a.error_estimate() + b.error_estimate());
  EXPECT_NEAR(a.left(), b.left(), tol) << what;
  EXPECT_NEAR(a.right(), b.right(), tol) << what;
  EXPECT_NEAR(a.drag(), b.drag(), 1e-9 * std::max(1.0, std::fabs(b.drag()))) << what;
  for (double r : {-0.9, -0.3, 0.2, 0.8}) {
    const double x = b.centre() + r * b.half_width();
    EXPECT_NEAR(a.pressure(x), b.pressure(x),
                1e-9 * b.max_pressure() + 2.0 * b.pressure_error_estimate())
        << what << " r " << r;
  }
}

// int p = P (the series' weight) and p >= 0 on the contact.
void expect_equilibrium(const AsymmetricSolution& s, const char* what) {
  const int m = 4000;
  double sum = 0.0, pmin = kInf;
  for (int i = 0; i < m; ++i) {
    // Gauss-Chebyshev-like midpoint in theta (end singularities integrable).
    const double th = kPi * (i + 0.5) / m, r = -std::cos(th);
    const double x = s.centre() + s.half_width() * r;
    const double p = s.pressure(x);
    pmin = std::min(pmin, p);
    sum += p * s.half_width() * std::sin(th) * kPi / m;
  }
  EXPECT_NEAR(sum, 1.0, 2e-4) << what;  // per P/h: int p dx / (P/h) = 1
  EXPECT_GE(pmin, -1e-9 * s.max_pressure()) << what;
}

}  // namespace

// K identical sublayers with friction 0.3: the homogeneous layer's contact.
TEST(AsymMedium, IdenticalSublayersWithFrictionGiveTheHomogeneousContact) {
  const double kw = 1.0, nu = 0.2;
  AsymmetricParams h = stack_params(homogeneous_medium(kw, nu), 0.3);
  h.medium = nullptr;
  h.kw = kw;
  h.nu = nu;
  const AsymmetricSolution ref = solve_asymmetric(h);
  const AsymmetricSolution st = solve_asymmetric(stack_params(springs(identical(3, nu), kw), 0.3));
  expect_same_contact(st, ref, "cylinder, friction 0.3");
  expect_equilibrium(st, "cylinder, friction 0.3");
  EXPECT_NEAR(st.end_exponents().front, ref.end_exponents().front, 1e-15);
  EXPECT_NEAR(st.surface_stress(st.centre()), ref.surface_stress(ref.centre()),
              1e-8 + 2.0 * ref.stress_error_estimate());
  EXPECT_NEAR(st.indentation(), ref.indentation(), 1e-8 * std::fabs(ref.indentation()));
}

TEST(AsymMedium, IdenticalSublayersRoundedFlatAndTableGiveTheHomogeneousContact) {
  const double kw = 2.0, nu = 0.25;
  // A rounded flat with friction.
  AsymmetricParams p = stack_params(springs(identical(3, nu), kw), 0.3);
  p.profile = ProfileKind::rounded_flat;
  p.half_width = 0.05;
  p.radius = 20.0;
  p.tol = 1e-10;
  AsymmetricParams h = p;
  h.medium = nullptr;
  h.kw = kw;
  h.nu = nu;
  expect_same_contact(solve_asymmetric(p), solve_asymmetric(h), "rounded flat, friction 0.3");
  // An asymmetric table, frictionless and undamped.
  AsymmetricParams q = stack_params(springs(identical(3, nu), kw), 0.0);
  q.profile = ProfileKind::table;
  for (int i = 0; i <= 40; ++i) {
    const double x = -0.6 + 1.2 * i / 40.0;
    q.table_x.push_back(x);
    q.table_y.push_back(x * x / 40.0 + (x > 0 ? x * x * x / 30.0 : 0.0));
  }
  q.load = 0.002;
  q.tol = 1e-10;
  AsymmetricParams g = q;
  g.medium = nullptr;
  g.kw = kw;
  g.nu = nu;
  const AsymmetricSolution a = solve_asymmetric(q), b = solve_asymmetric(g);
  expect_same_contact(a, b, "asymmetric table");
  expect_equilibrium(a, "asymmetric table");
  // The stresses at depth (the stack's mode profiles, an interface and the
  // base face included) are the homogeneous layer's closed-form modes'.
  const Eigen::VectorXd xs = Eigen::Vector3d(b.centre() - 0.5, b.centre(), b.centre() + 0.3);
  const Eigen::VectorXd ys = Eigen::Vector4d(-0.1, -0.37, -0.6, -1.0);
  const StressField fa = a.stress_field(xs, ys), fb = b.stress_field(xs, ys);
  const double scale = fb.sigma_y.cwiseAbs().maxCoeff();
  EXPECT_LT((fa.sigma_x - fb.sigma_x).cwiseAbs().maxCoeff(), 1e-8 * scale);
  EXPECT_LT((fa.sigma_y - fb.sigma_y).cwiseAbs().maxCoeff(), 1e-8 * scale);
  EXPECT_LT((fa.tau_xy - fb.tau_xy).cwiseAbs().maxCoeff(), 1e-8 * scale);
}

// The flat punch with friction on identical sublayers: the homogeneous layer's
// end coefficients.
TEST(AsymMedium, IdenticalSublayersFlatWithFrictionGiveTheHomogeneousEnds) {
  AsymmetricParams p = stack_params(springs(identical(2, 0.2), 1.0), 0.3);
  p.profile = ProfileKind::flat;
  p.half_width = 0.3;
  p.tol = 1e-10;
  AsymmetricParams h = p;
  h.medium = nullptr;
  const AsymmetricSolution a = solve_asymmetric(p), b = solve_asymmetric(h);
  const double tol = 1e-9 + 2.0 * b.end_coefficient_error();
  EXPECT_NEAR(a.end_coefficient_back(), b.end_coefficient_back(), tol);
  EXPECT_NEAR(a.end_coefficient_front(), b.end_coefficient_front(), tol);
}

// A bonded half-space of the layer's own material is the moving half-plane:
// with friction f the contact (-b, a) of a cylinder is the closed form
// p = K (a - x)^front (x + b)^back, half-width w^2 = phi1 R P/(2 pi front
// back), centre w (back - front), drag (4/3) w (back - front)/R (the
// Muskhelishvili solution of (phi1/pi) PV int p/(x - xi) - f Phi phi1 p = x/R;
// Johnson, Contact Mechanics, sec. 7.2), front = 1/2 + atan(f Phi)/pi.
TEST(AsymMedium, BondedHalfSpaceOfTheOwnMaterialIsTheFrictionalHalfPlane) {
  const double nu = 0.2, s = 0.3, f = 0.3;
  const MediumSpec spec =
      half_space({{1.0, 1.0, nu, 1.0, 0.0}}, BaseKind::half_space_bonded, 1.0, nu, 1.0);
  const WaveConstants c = wave_constants(s, nu);
  const EndExponents e = end_exponents(f, tangential_half_plane(c).Phi);
  for (double load : {1e-4, 4e-3}) {
    AsymmetricParams p = stack_params(spec, f);
    p.vstar = s;
    p.load = load;
    p.tol = 1e-11;
    const AsymmetricSolution sol = solve_asymmetric(p);
    const double w = std::sqrt(c.phi1 * p.radius * load / (2.0 * kPi * e.front * e.back));
    const double centre = w * (e.back - e.front);
    EXPECT_NEAR(sol.half_width(), w, 1e-9 * w) << load;
    EXPECT_NEAR(sol.centre(), centre, 1e-9 * w) << load;
    EXPECT_NEAR(sol.drag(), 4.0 / 3.0 * centre / p.radius, 1e-8 * std::fabs(centre) / p.radius)
        << load;
    expect_equilibrium(sol, "bonded half-space");
    EXPECT_THROW((void)sol.indentation(), std::invalid_argument);  // a log far field
  }
}

// A smooth half-space with friction runs (a shear-free interface: the bar
// pole), equilibrium holds; a stiff smooth half-space approaches the rigid
// base's contact.
TEST(AsymMedium, SmoothHalfSpaceWithFrictionRuns) {
  const std::vector<Sublayer> two{{0.4, 1.0, 0.2, 1.0, 0.0}, {0.6, 0.5, 0.3, 1.0, 0.0}};
  const AsymmetricSolution a = solve_asymmetric(
      stack_params(half_space(two, BaseKind::half_space_smooth, 2.0, 0.3, 1.0), 0.3));
  expect_equilibrium(a, "smooth half-space");
  EXPECT_TRUE(a.warnings().empty());
  EXPECT_GT(a.right(), 0.0);
  EXPECT_LT(a.left(), 0.0);
}

// What the asymmetric solver refuses on a medium, by name.
TEST(AsymMedium, RefusesUnsupportedCombinationsByName) {
  MediumSpec damped = springs(identical(2, 0.2), 1.0);
  damped.base.damping = 0.5;
  try {
    (void)solve_asymmetric(stack_params(damped, 0.3));
    FAIL() << "a damped base under a stack was accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.name(), "damping");
  }
  MediumSpec graded = springs(identical(2, 0.2), 1.0);
  graded.layers[0].gamma = 0.5;
  try {
    (void)solve_asymmetric(stack_params(graded, 0.3));
    FAIL() << "a graded top sublayer was accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.name(), "layers");
  }
  // Depth outputs on a stack: refused, naming what.
  const AsymmetricSolution s = solve_asymmetric(stack_params(springs(identical(2, 0.2), 1.0), 0.3));
  EXPECT_THROW((void)s.stress_x(0.0, -0.5), std::invalid_argument);
  EXPECT_TRUE(std::isfinite(s.surface_stress(0.0)));
  EXPECT_TRUE(std::isfinite(s.surface_slope(0.0)));
}

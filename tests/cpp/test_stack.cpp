// Layered media (cpp/src/stack.hpp), each against an independent anchor:
// the homogeneous layer (LayerModel), a naive long-double product of
// transfer matrices, the half-plane, Winkler springs of the substrate's
// stiffness, the rigid base, and the critical speed of dispersion.hpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "media_reference.hpp"
#include "movingpunch/dispersion.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/layer_response.hpp"
#include "stack.hpp"

using namespace movingpunch;
using namespace movingpunch::testing;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

double rel(double a, double b) { return std::fabs(a - b) / std::max(std::fabs(b), 1e-300); }

// M1 and U0 of the medium by the naive product of the sublayers' transfer
// matrices applied to the bottom condition (z(0) = [U0, W0, 0, -1]).
std::array<double, 2> naive(const MediumSpec& m, double vstar, double t, bool clamped = false) {
  M4 P{};
  for (int i = 0; i < 4; ++i) P[i][i] = 1;
  for (const Sublayer& l : m.layers) {
    const LD s = static_cast<LD>(vstar) * l.rho / l.mu;
    M4 B = state_matrix(s, l.nu);
    for (auto& r : B)
      for (LD& x : r) x *= -static_cast<LD>(t) * l.thickness;  // from top to bottom
    B[2][2] += static_cast<LD>(l.gamma) * l.thickness;
    B[3][3] += static_cast<LD>(l.gamma) * l.thickness;
    M4 E = expm(B);
    // unscaled -> scaled at the top (1/mu_top), scaled -> unscaled at the bottom.
    const LD mt = l.mu, mb = l.mu * std::exp(-static_cast<LD>(l.gamma) * l.thickness);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        E[i][j] *= (i >= 2 ? mb : 1.0L);
        E[i][j] /= (j >= 2 ? mt : 1.0L);
      }
    P = mul(E, P);
  }
  // z0 = [U0, W0, 0, -1].
  const auto x = naive_top_unknowns(P, m, vstar, t, 0.0L, -1.0L, clamped);
  return {static_cast<double>(-x[1]), static_cast<double>(x[0])};
}

}  // namespace

TEST(Stack, IdenticalSublayersMatchLayerModel) {
  const double nu = 0.2;
  struct Base {
    double kw, kp;
  };
  for (const Base b : {Base{1.0, 0.0}, Base{1.0, 0.3}, Base{kInf, 0.0}})
    for (int K : {1, 2, 5})
      for (double s : {0.0, 0.2, 0.5}) {
        const MediumSpec spec = springs(identical(K, nu), b.kw, b.kp);
        const auto med = make_stack_medium(spec, s);
        const LayerModel ref(s, b.kw, nu, b.kp);
        for (double t :
             {1e-6, 1e-3, 0.1, 0.3, 0.49, 0.5, 0.7, 1.0, 1.7, 3.0, 10.0, 40.0, 200.0, 1e3}) {
          const Response r = ref.response(t);
          const MediumResponse m = med->surface_response(t);
          const std::string at = "K = " + std::to_string(K) + ", kw = " + std::to_string(b.kw) +
                                 ", kp = " + std::to_string(b.kp) + ", s = " + std::to_string(s) +
                                 ", t = " + std::to_string(t);
          EXPECT_LE(rel(m.M1.real(), r.M1), 1e-12) << at;
          // M2 = (c2 - 2)/c2 - 4 (c2 - 1)/c2 U0 cancels to O(t^2) as t -> 0 at
          // vstar = 0 (the squeezed layer has sigma_x ~ 0): relative to its terms.
          const WaveConstants& c = ref.constants();
          const double terms = (c.c2 - 2.0) / c.c2 + 4.0 * (c.c2 - 1.0) / c.c2 * std::fabs(r.U0);
          EXPECT_LE(std::fabs(m.M2.real() - r.M2), 1e-12 * std::max(std::fabs(r.M2), terms)) << at;
          EXPECT_LE(rel(m.U0.real(), r.U0), 1e-12) << at;
          EXPECT_LE(rel(m.W0.real(), r.W0), 1e-12) << at;
          EXPECT_EQ(m.M1.imag(), 0.0);
        }
      }
}

TEST(Stack, IdenticalSublayersModeStatesMatchLayerModel) {
  const double nu = 0.2;
  for (double kw : {1.0, kInf})
    for (int K : {2, 5})
      for (double s : {0.0, 0.5}) {
        const MediumSpec spec = springs(identical(K, nu), kw);
        const auto med = make_stack_medium(spec, s);
        const LayerModel ref(s, kw, nu);
        std::vector<double> depths{0.0, -0.05, -0.5, -0.77, -1.0};
        for (double y : med->interfaces()) depths.push_back(y);
        for (double t : {1e-4, 0.3, 1.0, 3.0, 12.0}) {
          const ModeField f = ref.mode_field(t);
          const auto p = med->mode(t);
          const double scale = f.state(0.0).cwiseAbs().maxCoeff();
          for (double y : depths)
            for (bool below : {false, true}) {
              const Eigen::Vector4d zr = f.state(y), hp = f.half_plane_state(y);
              const ModeState st = p->remainder(y, below);
              const double tol = 1e-12 * std::max(zr.cwiseAbs().maxCoeff(), 1e-8 * scale);
              for (int i = 0; i < 4; ++i)
                EXPECT_NEAR(st.z(i).real(), zr(i) - hp(i), tol)
                    << "K " << K << " kw " << kw << " s " << s << " t " << t << " y " << y << " i "
                    << i;
              const double sx = sigma_x_hat(ref.constants(), zr) - sigma_x_hat(ref.constants(), hp);
              EXPECT_NEAR(st.sx.real(), sx, 4.0 * tol) << "t " << t << " y " << y;
              const ModeState h = p->half_plane(y);
              for (int i = 0; i < 4; ++i) EXPECT_NEAR(h.z(i).real(), hp(i), 1e-14);
            }
        }
      }
}

TEST(Stack, MixedStackMatchesNaiveLongDoubleProduct) {
  // Different materials, a graded sublayer, every base, moderate t.
  const std::vector<Sublayer> layers{
      {0.3, 1.0, 0.25, 1.0, 0.0}, {0.45, 0.4, 0.3, 0.8, 1.7}, {0.25, 2.5, 0.2, 1.3, 0.0}};
  const std::vector<Sublayer> graded_top{{0.6, 1.0, 0.2, 1.0, -2.3}, {0.4, 0.3, 0.35, 0.9, 0.0}};
  std::vector<MediumSpec> specs{springs(layers, 0.7),
                                springs(layers, 2.0, 0.4),
                                springs(layers, kInf),
                                springs(graded_top, 1.3),
                                half_space(layers, BaseKind::half_space_bonded, 0.5, 0.3, 1.1),
                                half_space(graded_top, BaseKind::half_space_bonded, 3.0, 0.25, 2.0),
                                half_space(layers, BaseKind::half_space_smooth, 0.5, 0.3, 1.1)};
  for (const MediumSpec& spec : specs)
    for (double s : {0.05, 0.15})
      for (double t : {0.01, 0.2, 0.6, 1.3, 3.0}) {
        const auto med = make_stack_medium(spec, s);
        const auto ref = naive(spec, s, t);
        const MediumResponse m = med->surface_response(t);
        EXPECT_LE(rel(m.M1.real(), ref[0]), 1e-12) << "s " << s << " t " << t;
        EXPECT_LE(rel(m.U0.real(), ref[1]), 1e-12) << "s " << s << " t " << t;
      }
}

TEST(Stack, GradedSublayerWithTinyGammaIsTheHomogeneousOne) {
  for (double s : {0.0, 0.3})
    for (double kw : {0.5, kInf}) {
      const std::vector<Sublayer> hom{{0.4, 1.0, 0.2, 1.0, 0.0}, {0.6, 0.5, 0.3, 0.7, 0.0}};
      std::vector<Sublayer> gr = hom;
      gr[0].gamma = 1e-9;
      gr[1].gamma = -1e-9;
      const auto a = make_stack_medium(springs(hom, kw), s);
      const auto b = make_stack_medium(springs(gr, kw), s);
      for (double t : {1e-5, 0.2, 1.0, 5.0, 30.0, 300.0}) {
        const MediumResponse ra = a->surface_response(t), rb = b->surface_response(t);
        EXPECT_LE(rel(rb.M1.real(), ra.M1.real()), 3e-9) << "s " << s << " t " << t;
        EXPECT_LE(rel(rb.U0.real(), ra.U0.real()), 3e-9) << "s " << s << " t " << t;
        // ... and is not the same computation: gamma = 1e-3 moves it.
      }
      std::vector<Sublayer> g3 = hom;
      g3[0].gamma = 1e-3;
      EXPECT_GT(rel(make_stack_medium(springs(g3, kw), s)->surface_response(1.0).M1.real(),
                    a->surface_response(1.0).M1.real()),
                1e-6);
    }
}

TEST(Stack, BondedHalfSpaceOfTheOwnMaterialIsTheHalfPlane) {
  for (double nu : {0.0, 0.2, 0.45})
    for (double s : {0.0, 0.2, 0.6}) {
      for (int K : {1, 3}) {
        const auto med = make_stack_medium(
            half_space(identical(K, nu), BaseKind::half_space_bonded, 1.0, nu, 1.0), s);
        for (double t : {1e-300, 1e-8, 1e-3, 0.3, 1.0, 4.0, 50.0, 1e4}) {
          const MediumResponse r = med->surface_response(t);
          EXPECT_LE(rel(r.M1.real(), med->phi1()), 1e-12)
              << "nu " << nu << " s " << s << " t " << t;
          EXPECT_LE(rel(r.M2.real(), med->phi2()), 1e-12)
              << "nu " << nu << " s " << s << " t " << t;
        }
      }
    }
}

TEST(Stack, SmoothHalfSpaceIsSpringsOfItsStiffnessPerMode) {
  const double mu2 = 0.3, nu2 = 0.3, rho2 = 0.8;
  for (double s : {0.0, 0.1, 0.2}) {
    const auto med = make_stack_medium(half_space({Sublayer{1.0, 1.0, 0.2, 1.0, 0.0}},
                                                  BaseKind::half_space_smooth, mu2, nu2, rho2),
                                       s);
    const double ph2 = phi1(s * rho2 / mu2, nu2);
    for (double t : {1e-6, 1e-2, 0.4, 0.6, 2.0, 9.0, 100.0}) {
      const LayerModel ref(s, t * mu2 / ph2, 0.2);
      const Response r = ref.response(t);
      const MediumResponse m = med->surface_response(t);
      EXPECT_LE(rel(m.M1.real(), r.M1), 1e-12) << "s " << s << " t " << t;
      EXPECT_LE(rel(m.U0.real(), r.U0), 1e-12) << "s " << s << " t " << t;
    }
  }
}

TEST(Stack, StiffHalfSpaceTendsToTheRigidBase) {
  // Bonded: the clamped base (u = v = 0, naive product); smooth: the smooth
  // rigid base (LayerModel, kw = inf). The difference falls like 1/mu2.
  const double nu = 0.25, s = 0.2;
  const LayerModel rigid(s, kInf, nu);
  const std::vector<Sublayer> one{Sublayer{1.0, 1.0, nu, 1.0, 0.0}};
  for (BaseKind kind : {BaseKind::half_space_bonded, BaseKind::half_space_smooth})
    for (double t : {0.05, 0.7, 3.0}) {
      const double ref = kind == BaseKind::half_space_smooth
                             ? rigid.response(t).M1
                             : naive(springs(one, kInf), s, t, /*clamped=*/true)[0];
      std::vector<double> diff;
      for (double mu2 : {1e4, 1e5}) {
        const auto med = make_stack_medium(half_space(one, kind, mu2, 0.3, mu2), s);
        diff.push_back(std::fabs(med->surface_response(t).M1.real() - ref));
      }
      EXPECT_LT(diff[1], 1e-3 * std::fabs(ref)) << "t " << t;
      EXPECT_NEAR(diff[0] / diff[1], 10.0, 0.05) << "t " << t;  // ~ 1/mu2
    }
}

TEST(Stack, HalfSpaceBaseM1TendsToTheSubstrateHalfPlane) {
  for (BaseKind kind : {BaseKind::half_space_bonded, BaseKind::half_space_smooth}) {
    const MediumSpec spec =
        half_space({Sublayer{0.5, 1.0, 0.2, 1.0, 0.0}, Sublayer{0.5, 2.0, 0.3, 1.5, 0.8}}, kind,
                   0.2, 0.35, 0.9);
    const double s = 0.1;
    const auto med = make_stack_medium(spec, s);
    const double lim = phi1(s * 0.9 / 0.2, 0.35) / 0.2;
    EXPECT_DOUBLE_EQ(stack_small_t_m1(spec, s), lim);
    double prev = kInf;
    for (double t : {1e-2, 1e-4, 1e-6, 1e-8}) {
      const double e = std::fabs(med->surface_response(t).M1.real() - lim);
      EXPECT_LT(e, prev);
      prev = e;
    }
    EXPECT_LT(prev, 1e-6 * lim);
  }
}

TEST(Stack, ResponsesAreFiniteForEveryKindAndWavenumber) {
  const std::vector<Sublayer> mixed{
      {0.2, 1.0, 0.2, 1.0, 3.0}, {0.5, 0.3, 0.3, 0.5, 0.0}, {0.3, 4.0, 0.25, 2.0, -1.5}};
  const std::vector<MediumSpec> specs{springs(mixed, 1.0),
                                      springs(mixed, 0.01, 2.0),
                                      springs(mixed, kInf),
                                      half_space(mixed, BaseKind::half_space_bonded, 0.2, 0.3, 0.4),
                                      half_space(mixed, BaseKind::half_space_smooth, 5.0, 0.3, 1.0),
                                      springs({Sublayer{1.0, 1.0, 0.3, 1.0, kMaxGamma}}, 1.0),
                                      springs({Sublayer{1.0, 1.0, 0.3, 1.0, -kMaxGamma}}, kInf)};
  for (const MediumSpec& spec : specs)
    for (double s : {0.0, 0.1}) {
      const auto med = make_stack_medium(spec, s);
      for (double t : {0.0, 1e-300, 1e-12, 1.0, 1e3, 1e300}) {
        const MediumResponse r = med->surface_response(t);
        EXPECT_TRUE(std::isfinite(r.M1.real()) && std::isfinite(r.M2.real()) &&
                    std::isfinite(r.U0.real()) && std::isfinite(r.W0.real()))
            << "t " << t;
        if (t >= 1e300) {
          EXPECT_NEAR(r.M1.real(), med->phi1(), 1e-14);
          EXPECT_NEAR(r.M2.real(), med->phi2(), 1e-14);
        }
      }
      for (double t : {1e-12, 1.0, 1e3, 1e300}) {
        const auto p = med->mode(t);
        for (double y : {0.0, -0.2, -0.5, -1.0}) {
          const ModeState st = p->remainder(y, true);
          for (int i = 0; i < 4; ++i) EXPECT_TRUE(std::isfinite(st.z(i).real()));
          EXPECT_TRUE(std::isfinite(st.sx.real()));
        }
      }
      EXPECT_TRUE(std::isfinite(med->dispersion(1.0)));
    }
}

TEST(Stack, StaircaseConvergesToTheGradedSublayerAsKToTheMinus2) {
  const double gamma = 1.5, nu = 0.25, s = 0.1, kw = 2.0;
  const auto graded = make_stack_medium(springs({Sublayer{1.0, 1.0, nu, 1.0, gamma}}, kw), s);
  auto staircase = [&](int K) {
    std::vector<Sublayer> l;
    for (int j = 0; j < K; ++j) {
      const double m = std::exp(-gamma * (j + 0.5) / K);  // the midpoint value
      l.push_back({1.0 / K, j == 0 ? 1.0 : m, nu, j == 0 ? 1.0 : m, 0.0});
    }
    // The top step is the reference material (mu = rho = 1): scale the others.
    const double m0 = std::exp(-gamma * 0.5 / K);
    for (size_t j = 1; j < l.size(); ++j) {
      l[j].mu /= m0;
      l[j].rho /= m0;
    }
    double sum = 0.0;
    for (size_t j = 0; j + 1 < l.size(); ++j) sum += l[j].thickness;
    l.back().thickness = 1.0 - sum;
    return l;
  };
  for (double t : {0.5, 2.0}) {
    std::vector<double> err;
    for (int K : {16, 32, 64}) {
      // The staircase's units are its top step's (mu = exp(-gamma/(2K))):
      // M1 is per unit mu_1, so M1_graded = M1_stair * mu_stair_top / mu_graded_top.
      const double m0 = std::exp(-gamma * 0.5 / K);
      MediumSpec st = springs(staircase(K), kw / m0);
      const auto med = make_stack_medium(st, s / m0 * m0);
      const double M1 = med->surface_response(t).M1.real() / m0;
      err.push_back(std::fabs(M1 - graded->surface_response(t).M1.real()));
    }
    EXPECT_NEAR(err[0] / err[1], 4.0, 0.2) << "t " << t;
    EXPECT_NEAR(err[1] / err[2], 4.0, 0.1) << "t " << t;
  }
}

TEST(Stack, CriticalSpeedOfOneSublayerIsTheLayersOne) {
  for (double kw : {0.1, 1.0, 10.0}) {
    const CriticalSpeed ref = critical_speed(kw, 0.2);
    const CriticalSpeed one =
        stack_critical_speed(springs({Sublayer{1.0, 1.0, 0.2, 1.0, 0.0}}, kw));
    EXPECT_NEAR(one.vstar, ref.vstar, 1e-12 * ref.vstar) << "kw " << kw;
    EXPECT_NEAR(one.t, ref.t, 1e-3 * ref.t);
    const CriticalSpeed three = stack_critical_speed(springs(identical(3, 0.2), kw));
    EXPECT_NEAR(three.vstar, ref.vstar, 1e-12 * ref.vstar) << "kw " << kw;
  }
  const CriticalSpeed rig = stack_critical_speed(springs(identical(2, 0.2), kInf));
  EXPECT_EQ(rig.vstar, rayleigh_vstar(0.2))
      << (rig.vstar / rayleigh_vstar(0.2) - 1.0) << " t " << rig.t;
  EXPECT_TRUE(std::isinf(rig.t));
}

TEST(Stack, CriticalSpeedInfimaOfSoftSublayersAndSubstrate) {
  // A soft bottom sublayer on a rigid base: its shear speed (t -> inf).
  const MediumSpec soft_bottom =
      springs({Sublayer{0.6, 1.0, 0.2, 1.0, 0.0}, Sublayer{0.4, 0.2, 0.3, 1.0, 0.0}}, kInf);
  const CriticalSpeed a = stack_critical_speed(soft_bottom);
  EXPECT_NEAR(a.vstar, 0.2, 1e-14);
  EXPECT_TRUE(std::isinf(a.t));
  EXPECT_EQ(stack_max_vstar(soft_bottom), 0.2);
  // A soft half-space substrate: its Rayleigh speed (t -> 0).
  const MediumSpec soft_sub =
      half_space({Sublayer{1.0, 1.0, 0.2, 1.0, 0.0}}, BaseKind::half_space_bonded, 0.1, 0.3, 1.2);
  const CriticalSpeed b = stack_critical_speed(soft_sub);
  EXPECT_NEAR(b.vstar, 0.1 / 1.2 * rayleigh_vstar(0.3), 1e-14);
  EXPECT_EQ(b.t, 0.0);
  // A soft bottom sublayer over Winkler springs: its bottom face's Rayleigh speed
  // bounds the critical speed from above.
  const MediumSpec over_springs =
      springs({Sublayer{0.5, 1.0, 0.2, 1.0, 0.0}, Sublayer{0.5, 0.3, 0.2, 1.0, 0.0}}, 1e3);
  const CriticalSpeed c = stack_critical_speed(over_springs);
  EXPECT_LE(c.vstar, 0.3 * rayleigh_vstar(0.2) * (1.0 + 1e-14));
  // The critical speed is a free wave: the dispersion changes sign across it at c.t.
  const MediumSpec soft =
      springs({Sublayer{0.5, 1.0, 0.2, 1.0, 0.0}, Sublayer{0.5, 0.5, 0.3, 1.0, 0.0}}, 0.3);
  const CriticalSpeed d = stack_critical_speed(soft);
  ASSERT_TRUE(std::isfinite(d.t) && d.t > 0.0);
  const double lo = make_stack_medium(soft, d.vstar * (1 - 1e-6))->dispersion(d.t);
  const double hi = make_stack_medium(soft, d.vstar * (1 + 1e-6))->dispersion(d.t);
  EXPECT_LT(lo * hi, 0.0);
}

TEST(Stack, RejectsInvalidInput) {
  const MediumSpec ok = springs(identical(2, 0.2), 1.0);
  try {
    make_stack_medium(ok, rayleigh_vstar(0.2));
    FAIL() << "vstar at the bound accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.name(), "vstar");
  }
  MediumSpec damped = ok;
  damped.base.damping = 0.1;
  EXPECT_THROW(make_stack_medium(damped, 0.1), std::invalid_argument);
  MediumSpec bad = ok;
  bad.layers[1].thickness += 0.1;
  EXPECT_THROW(make_stack_medium(bad, 0.1), InvalidParameter);
  bad = ok;
  bad.layers[0].mu = 2.0;
  EXPECT_THROW(make_stack_medium(bad, 0.1), InvalidParameter);
  bad = ok;
  bad.layers[1].gamma = 60.0;
  EXPECT_THROW(make_stack_medium(bad, 0.1), InvalidParameter);
  const auto med = make_stack_medium(ok, 0.1);
  EXPECT_THROW(med->surface_response(std::nan("")), std::invalid_argument);
  EXPECT_THROW(med->mode(-1.0), std::invalid_argument);
}

TEST(Stack, DispersionChangesSignWhereTheLayersDoes) {
  // Above the critical speed of kw = 1 (0.5717) free waves exist at some t:
  // K identical sublayers change sign exactly where LayerModel does, and
  // nowhere else (no spurious sign change where the propagation switches
  // from transfer to modal maps, t d = 0.5).
  const double nu = 0.2;
  for (double s : {0.62, 0.75})
    for (int K : {1, 3, 5}) {
      const auto med = make_stack_medium(springs(identical(K, nu), 1.0), s);
      const LayerModel ref(s, 1.0, nu);
      std::vector<double> roots_ref, roots;
      const int n = 4000;
      double tp = 0.0, dp = 0.0, rp = 0.0;
      for (int i = 0; i <= n; ++i) {
        const double t = std::exp(std::log(0.05) + (std::log(60.0) - std::log(0.05)) * i / n);
        const double d = med->dispersion(t), r = ref.dispersion(t);
        if (i > 0) {
          if ((d < 0) != (dp < 0)) roots.push_back(std::sqrt(t * tp));
          if ((r < 0) != (rp < 0)) roots_ref.push_back(std::sqrt(t * tp));
        }
        tp = t;
        dp = d;
        rp = r;
      }
      // LayerModel::dispersion itself changes sign where it switches from
      // its transfer to its modal evaluation (t = kSmallT = 0.5): not a wave.
      std::vector<double> waves;
      for (double r : roots_ref)
        if (std::fabs(r / LayerModel::kSmallT - 1.0) > 2e-3) waves.push_back(r);
      ASSERT_FALSE(waves.empty());
      EXPECT_EQ(roots, waves) << "s " << s << " K " << K;
    }
}

TEST(Stack, GradedTopApproachesItsHalfPlaneLikeGammaOverT) {
  // The graded response tends to the top's half-plane value as a series in
  // gamma/t (docs/theory.md §16): t (M1 - phi1) -> c1 gamma, with the
  // next term O(1/t), across the depth where the deeper structure is cut.
  for (double gamma : {2.0, -3.0}) {
    const auto med = make_stack_medium(
        springs({Sublayer{0.5, 1.0, 0.25, 1.0, gamma}, Sublayer{0.5, 0.5, 0.3, 1.0, 0.0}}, 1.0),
        0.2);
    std::vector<double> q;
    for (double t : {250.0, 500.0, 1000.0, 2000.0})
      q.push_back(t * (med->surface_response(t).M1.real() - med->phi1()));
    const double r1 = (q[1] - q[0]) / (q[2] - q[1]), r2 = (q[2] - q[1]) / (q[3] - q[2]);
    EXPECT_NEAR(r1, 2.0, 0.05) << "gamma " << gamma;
    EXPECT_NEAR(r2, 2.0, 0.05) << "gamma " << gamma;
    EXPECT_GT(std::fabs(q[3]), 1e-3);  // a real 1/t term, proportional to gamma
    // decay_rate() is the reflection's; the slow series is the kernel's
    // asymptotics (test_graded_kernel.cpp checks its coefficients).
    EXPECT_NEAR(med->decay_rate(), 2.0 * std::sqrt(1.0 - 0.2) * 0.5, 1e-15);
    EXPECT_EQ(med->kernel_asymptotics().gamma, gamma);
    EXPECT_NEAR(med->kernel_asymptotics().a[0] * gamma, q[3] / med->phi1(), 1e-2 * std::fabs(q[3]));
  }
}

TEST(Stack, GeometryOfTheMedium) {
  const auto med = make_stack_medium(springs(identical(3, 0.2), 1.0, 0.5), 0.3);
  const std::vector<double> ifc = med->interfaces();
  ASSERT_EQ(ifc.size(), 2u);
  EXPECT_NEAR(ifc[0], -med->spec().layers[0].thickness, 1e-15);
  EXPECT_GT(ifc[0], ifc[1]);
  EXPECT_NEAR(med->decay_rate(), 2.0 * std::sqrt(1.0 - 0.3) * med->spec().layers[0].thickness,
              1e-15);
  EXPECT_EQ(med->first_panel_edges(10.0),
            std::vector<double>({0.0, 0.25 * std::sqrt(2.0), 0.5 * std::sqrt(2.0),
                                 1.0 * std::sqrt(2.0), 2.0 * std::sqrt(2.0), 10.0}));
  const auto hs = make_stack_medium(
      half_space(identical(2, 0.2), BaseKind::half_space_bonded, 0.5, 0.3, 1.0), 0.1);
  const std::vector<double> e = hs->first_panel_edges(8.0);
  EXPECT_EQ(e.front(), 0.0);
  EXPECT_EQ(e.back(), 8.0);
  EXPECT_LE(e[1], 8.0 / 1000.0);
  EXPECT_TRUE(med->real());
  EXPECT_EQ(med->vstar(), 0.3);
  EXPECT_EQ(med->top().nu, 0.2);
}

TEST(Stack, GradedTopAsymptoticExpansionLeavesATMinus3Remainder) {
  // M1 - phi1 - c1 g/t - c2 (g/t)^2 falls like t^-3 (ratio 8 per doubling)
  // for the full propagation of a graded top sublayer; with c2 = 0 it would
  // fall like t^-2 only.
  for (double s : {0.0, 0.3})
    for (double gamma : {2.0, -1.5}) {
      const auto med = make_stack_medium(
          springs({Sublayer{0.5, 1.0, 0.25, 1.0, gamma}, Sublayer{0.5, 0.5, 0.3, 1.0, 0.0}}, 1.0),
          s);
      const GradedAsymptotics a = graded_top_asymptotics(s, 0.25);
      std::vector<double> rem, rem1;
      for (double t : {200.0, 400.0, 800.0}) {
        const double e = gamma / t;
        const double d = med->surface_response(t).M1.real() - med->phi1() - a.c1 * e;
        rem1.push_back(d);
        rem.push_back(d - a.c2 * e * e);
      }
      EXPECT_NEAR(rem[0] / rem[1], 8.0, 0.4) << "s " << s << " gamma " << gamma;
      EXPECT_NEAR(rem[1] / rem[2], 8.0, 0.4) << "s " << s << " gamma " << gamma;
      EXPECT_NEAR(rem1[1] / rem1[2], 4.0, 0.2);  // c1 alone leaves (g/t)^2
    }
}

TEST(Stack, MixedStackModeStatesMatchTheNaiveProduct) {
  // The state at every interface (both sides) and at the base, against the
  // naive long-double product started from the naive surface state; sigma_x
  // jumps by each material's Hooke law, the state is continuous.
  const std::vector<Sublayer> layers{
      {0.3, 1.0, 0.25, 1.0, 0.0}, {0.45, 0.4, 0.3, 0.8, 1.7}, {0.25, 2.5, 0.2, 1.3, 0.0}};
  for (const MediumSpec& spec :
       {springs(layers, 0.7), half_space(layers, BaseKind::half_space_bonded, 0.5, 0.3, 1.1)})
    for (double t : {0.2, 1.3, 3.0}) {
      const double s = 0.1;
      const auto ref = naive(spec, s, t);
      const auto med = make_stack_medium(spec, s);
      const auto prof = med->mode(t);
      std::array<LD, 4> z{static_cast<LD>(ref[1]), static_cast<LD>(-ref[0]), 0, -1};
      double y = 0.0;
      for (const Sublayer& l : spec.layers) {
        // Propagate through the sublayer to its bottom (in 4 steps, checking each).
        for (int step = 1; step <= 4; ++step) {
          const double dy = l.thickness / 4;
          const LD m_top = l.mu * std::exp(-static_cast<LD>(l.gamma) * (step - 1) * dy);
          const LD m_bot = l.mu * std::exp(-static_cast<LD>(l.gamma) * step * dy);
          M4 B = state_matrix(static_cast<LD>(s) * l.rho / l.mu, l.nu);
          for (auto& r : B)
            for (LD& x : r) x *= -static_cast<LD>(t) * dy;
          B[2][2] += static_cast<LD>(l.gamma) * dy;
          B[3][3] += static_cast<LD>(l.gamma) * dy;
          const M4 E = expm(B);
          std::array<LD, 4> zs{z[0], z[1], z[2] / m_top, z[3] / m_top}, zn{};
          for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
              zn[static_cast<size_t>(i)] += E[i][j] * zs[static_cast<size_t>(j)];
          zn[2] *= m_bot;
          zn[3] *= m_bot;
          z = zn;
          const double yy = step == 4 ? y - l.thickness : y - step * dy;
          const ModeState st = prof->remainder(yy, false);
          const ModeState hp = prof->half_plane(yy);
          for (int i = 0; i < 4; ++i)
            EXPECT_NEAR(st.z(i).real() + hp.z(i).real(),
                        static_cast<double>(z[static_cast<size_t>(i)]), 1e-12)
                << "t " << t << " y " << yy << " i " << i;
          // sigma_x of this sublayer's material (at its bottom: above the interface).
          const double kappa = 3 - 4 * l.nu, c2 = (kappa + 1) / (kappa - 1);
          const double m = static_cast<double>(m_bot);
          const double sx = m * 4 * (c2 - 1) / c2 * static_cast<double>(z[0]) +
                            (c2 - 2) / c2 * static_cast<double>(z[3]);
          EXPECT_NEAR(st.sx.real() + hp.sx.real(), sx, 1e-11) << "t " << t << " y " << yy;
        }
        y -= l.thickness;
      }
    }
}

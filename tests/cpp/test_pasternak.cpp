// The two-parameter (Pasternak) foundation, kp: the base's stiffness
// kw + kp t^2 per mode. kp = 0 is the Winkler model bit for bit; kp is
// validated, keys the caches, lifts the critical speed, and the damped
// model's foundation carries it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "layer_basis.hpp"
#include "movingpunch/asymmetric.hpp"
#include "movingpunch/contact.hpp"
#include "movingpunch/dispersion.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/kernel.hpp"
#include "movingpunch/layer_response.hpp"
#include "solve_skeleton.hpp"

using namespace movingpunch;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

TEST(Pasternak, ZeroKpIsWinklerBitForBit) {
  for (double kw : {1e-3, 1.0, 30.0, kInf}) {
    const LayerModel w(0.3, kw, 0.2), p(0.3, kw, 0.2, 0.0);
    for (double t : {0.0, 1e-6, 0.1, 0.49, 0.5, 2.0, 40.0, 500.0}) {
      EXPECT_EQ(w.response(t).M1, p.response(t).M1) << kw << " " << t;
      EXPECT_EQ(w.response(t).M2, p.response(t).M2) << kw << " " << t;
      if (t > 0.0) {
        EXPECT_EQ(w.dispersion(t), p.dispersion(t)) << kw << " " << t;
      }
    }
  }
  EXPECT_EQ(critical_speed(1.0, 0.2).vstar, critical_speed(1.0, 0.2, 0.0).vstar);
  EXPECT_EQ(critical_speed(1.0, 0.2).t, critical_speed(1.0, 0.2, 0.0).t);
  const DampedLayerModel dw(0.3, 1.0, 0.2, 0.5), dp(0.3, 1.0, 0.2, 0.5, 0.0);
  for (double t : {0.1, 0.7, 5.0}) EXPECT_EQ(dw.response(t).M1, dp.response(t).M1);
}

TEST(Pasternak, ResponseIsWinklerWithTheModeStiffness) {
  // Per mode the base is springs of stiffness kw + kp t^2: a Winkler model
  // of that stiffness gives the same response at that t (both evaluations).
  const double kw = 0.3, kp = 0.7;
  const LayerModel p(0.25, kw, 0.2, kp);
  for (double t : {0.05, 0.3, 0.49, 0.5, 1.5, 6.0}) {
    const LayerModel w(0.25, kw + kp * t * t, 0.2);
    EXPECT_NEAR(p.response(t).M1, w.response(t).M1, 1e-15 * std::fabs(w.response(t).M1)) << t;
    EXPECT_NEAR(p.response(t).M2, w.response(t).M2, 1e-15 * std::fabs(w.response(t).M2)) << t;
    if (t <= 4.0) {
      EXPECT_NEAR(p.response_modal(t).M1, p.response_transfer(t).M1, 1e-12) << t;
    }
  }
  // The damped foundation: kw + kp t^2 - i damping sqrt(vstar) t.
  const DampedLayerModel d(0.25, kw, 0.2, 0.4, kp);
  EXPECT_DOUBLE_EQ(d.foundation(2.0).real(), kw + 4.0 * kp);
  EXPECT_DOUBLE_EQ(d.foundation(2.0).imag(), -0.4 * 0.5 * 2.0);
  // kp on a rigid base is irrelevant.
  const LayerModel r0(0.25, kInf, 0.2), r1(0.25, kInf, 0.2, 5.0);
  EXPECT_EQ(r0.response(1.0).M1, r1.response(1.0).M1);
  EXPECT_EQ(critical_speed(kInf, 0.2, 3.0).vstar, rayleigh_vstar(0.2));
}

TEST(Pasternak, RejectsBadKpNamingIt) {
  for (double bad : {-1e-300, -1.0, std::nan(""), kInf, 2.0 * kMaxKp}) {
    try {
      LayerModel(0.1, 1.0, 0.2, bad);
      ADD_FAILURE() << "accepted kp = " << bad;
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.name(), "kp");
      EXPECT_NE(std::string(e.what()).find("kp must be in [0, 1e+12]"), std::string::npos)
          << e.what();
    }
    EXPECT_THROW(critical_speed(1.0, 0.2, bad), InvalidParameter);
    EXPECT_THROW(DampedLayerModel(0.1, 1.0, 0.2, 0.1, bad), InvalidParameter);
    ContactParams c;
    c.kp = bad;
    EXPECT_THROW(validate(c), InvalidParameter);
    AsymmetricParams d;
    d.damping = 0.1;
    d.kp = bad;
    EXPECT_THROW(validate(d), InvalidParameter);
  }
  EXPECT_NO_THROW(LayerModel(0.1, 1.0, 0.2, kMaxKp));
}

TEST(Pasternak, CriticalSpeedGrowsWithKpUpToRayleigh) {
  const double vr = rayleigh_vstar(0.2);
  for (double kw : {1e-3, 0.1, 1.0, 10.0}) {
    double prev = critical_vstar(kw, 0.2);
    for (double kp : {1e-6, 1e-3, 0.01, 0.1, 0.3, 1.0, 10.0, 1e6}) {
      const CriticalSpeed c = critical_speed(kw, 0.2, kp);
      EXPECT_GE(c.vstar, prev) << kw << " " << kp;
      EXPECT_LE(c.vstar, vr) << kw << " " << kp;
      // The minimum is a minimum of the first free wave's speed.
      if (std::isfinite(c.t)) {
        for (double f : {0.8, 1.25}) {
          EXPECT_GE(first_wave_vstar(c.t * f, kw, 0.2, kp), c.vstar - 1e-13) << kw << " " << kp;
        }
      } else {
        EXPECT_EQ(c.vstar, vr);
      }
      prev = c.vstar;
    }
    // A stiff shear layer: no free wave slower than the Rayleigh wave.
    EXPECT_EQ(critical_speed(kw, 0.2, 10.0).vstar, vr);
  }
}

TEST(Pasternak, SolveRefusesAtTheCriticalSpeedNamingKp) {
  ContactParams p;
  p.kw = 1.0;
  p.kp = 0.2;
  p.vstar = critical_vstar(1.0, 0.2, 0.2);
  EXPECT_GT(p.vstar, critical_vstar(1.0, 0.2));
  try {
    solve_contact(p);
    ADD_FAILURE() << "solved at V*_cr";
  } catch (const SupercriticalSpeedError& e) {
    EXPECT_EQ(e.critical(), p.vstar);
    EXPECT_NE(std::string(e.what()).find("kp = 0.2"), std::string::npos) << e.what();
  }
  // Below it, and above the Winkler V*_cr, it solves.
  p.vstar *= 1.0 - 1e-3;
  EXPECT_GT(p.vstar, critical_vstar(1.0, 0.2));
  EXPECT_GT(solve_contact(p).a(), 0.0);
}

TEST(Pasternak, KpKeysTheKernelCaches) {
  clear_kernel_cache();
  bool built = false;
  cached_kernel(LayerModel(0.2, 1.0, 0.2), 1e-10, 2.0, 4.0, &built);
  EXPECT_TRUE(built);
  cached_kernel(LayerModel(0.2, 1.0, 0.2, 0.0), 1e-10, 2.0, 4.0, &built);
  EXPECT_FALSE(built);  // kp = 0: the Winkler table
  cached_kernel(LayerModel(0.2, 1.0, 0.2, 0.1), 1e-10, 2.0, 4.0, &built);
  EXPECT_TRUE(built);
  cached_kernel(LayerModel(0.2, 1.0, 0.2, 0.1), 1e-10, 2.0, 4.0, &built);
  EXPECT_FALSE(built);
  cached_kernel(LayerModel(0.2, kInf, 0.2, 0.0), 1e-10, 2.0, 4.0, &built);
  EXPECT_TRUE(built);
  cached_kernel(LayerModel(0.2, kInf, 0.2, 7.0), 1e-10, 2.0, 4.0, &built);
  EXPECT_FALSE(built);  // rigid base: kp irrelevant, one table
  cached_damped_kernel(0.2, 1.0, 0.2, 0.3, 1.0, 2.0, &built);
  EXPECT_TRUE(built);
  cached_damped_kernel(0.2, 1.0, 0.2, 0.3, 1.0, 2.0, &built, 0.0);
  EXPECT_FALSE(built);
  cached_damped_kernel(0.2, 1.0, 0.2, 0.3, 1.0, 2.0, &built, 0.1);
  EXPECT_TRUE(built);
  EXPECT_EQ(cached_damped_kernel(0.2, 1.0, 0.2, 0.3, 1.0, 2.0, &built, 0.1)->model().spec().base.kp,
            0.1);
  clear_kernel_cache();
}

TEST(Pasternak, FirstPanelsReachTheBaseLongWaveScale) {
  // Springs alone: one panel. kp: panels from sqrt(kw/kp)/4, doubling.
  EXPECT_EQ(detail::foundation_panel_edges(1.0, 0.0, 0.5), (std::vector<double>{0.0, 0.5}));
  EXPECT_EQ(detail::foundation_panel_edges(kInf, 3.0, 0.5), (std::vector<double>{0.0, 0.5}));
  const std::vector<double> e = detail::foundation_panel_edges(1.0, 1e6, 1.0);
  ASSERT_GE(e.size(), 3u);
  EXPECT_DOUBLE_EQ(e[1], 0.25e-3);
  EXPECT_EQ(e.back(), 1.0);
  for (std::size_t i = 2; i + 1 < e.size(); ++i) EXPECT_DOUBLE_EQ(e[i], 2.0 * e[i - 1]);
  // The quadrature then integrates M1/alpha ~ 1/(kw + kp t^2) near 0, the
  // membrane's sinking: beside the layer on a rigid base,
  // int (M1 - M1_rigid)/alpha = pi/(2 sqrt(kw kp)) + O(sqrt(kw/kp)).
  const LayerModel rigid(0.0, kInf, 0.2);
  const AlphaQuadrature q =
      build_alpha_quadrature(*make_medium(homogeneous_medium(1.0, 0.2, 1e6), 0.0), 1e-12, 1.0);
  double sinking = 0.0;
  for (std::size_t i = 0; i < q.alpha.size(); ++i)
    sinking += q.weight[i] * (q.m1[i] - rigid.response(q.alpha[i]).M1) / q.alpha[i];
  const double membrane = 3.14159265358979323846 / (2.0 * std::sqrt(1.0 * 1e6));
  EXPECT_NEAR(sinking, membrane, 3e-3 * membrane);
}

TEST(Pasternak, WideContactGuessFollowsKp) {
  const double lambda = 1.0, phi1 = 0.8;
  const detail::WidthGuess w = detail::width_guess(phi1, lambda, 0.01, 0.2);
  const detail::WidthGuess w0 = detail::width_guess(phi1, lambda, 0.01, 0.2, 0.0);
  EXPECT_EQ(w.wide, w0.wide);  // kp = 0: the Winkler guess, unchanged
  // The fixed point a^3 = 1.5 lambda (1/(kw + 9 kp/a^2) + (1 - nu)/2).
  const detail::WidthGuess p = detail::width_guess(phi1, lambda, 0.01, 0.2, 0.1);
  const double a = p.wide;
  EXPECT_NEAR(a * a * a, 1.5 * lambda * (1.0 / (0.01 + 0.9 / (a * a)) + 0.4), 1e-2 * a * a * a);
  EXPECT_LT(p.wide, w.wide);
  // Solved widths (kw = 0.01, lambda = 1, nu = 0.2, V* = 0): 2.78 (kp = 0),
  // 1.85 (kp = 0.1): the guess is within the factor the Winkler one has.
  EXPECT_LT(p.wide / 1.85, w.wide / 2.78);
}

// Layer response: closed forms, limits, the two independent evaluations.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "movingpunch/layer_response.hpp"

using namespace movingpunch;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// Classical moving half-plane factor, well conditioned away from s = 0.
double half_plane_factor(double s, double nu) {
  const double kappa = 3.0 - 4.0 * nu, c2 = (kappa + 1.0) / (kappa - 1.0);
  const double nT = std::sqrt(1.0 - s), nL = std::sqrt(1.0 - s / c2);
  return (1.0 - nT * nT) * nL / (4.0 * nL * nT - (1.0 + nT * nT) * (1.0 + nT * nT));
}
}  // namespace

TEST(LayerResponse, StaticRigidBaseClosedForm) {
  const double nu = 0.2;
  const LayerModel m(0.0, kInf, nu);
  for (double t : {0.01, 0.3, 0.49, 0.51, 1.0, 2.5, 7.0, 20.0}) {
    const double exact = (1.0 - nu) * (std::cosh(2 * t) - 1.0) / (std::sinh(2 * t) + 2 * t);
    EXPECT_NEAR(m.response(t).M1, exact, 1e-12) << "t = " << t;
  }
}

TEST(LayerResponse, HalfPlaneLimitsAtZeroSpeed) {
  for (double nu : {0.0, 0.2, 0.3, 0.49, 0.4999}) {
    EXPECT_NEAR(phi1(0.0, nu), 1.0 - nu, 1e-15);
    EXPECT_NEAR(phi2(0.0, nu), 1.0, 1e-14);
  }
  EXPECT_NEAR(phi2(0.2, 0.2), 1.2395847348537, 1e-12);
}

TEST(LayerResponse, Phi1IsTheMovingHalfPlaneFactor) {
  for (double s : {0.05, 0.2, 0.4, 0.6, 0.8})
    EXPECT_NEAR(phi1(s, 0.2), half_plane_factor(s, 0.2), 1e-12 * half_plane_factor(s, 0.2));
}

TEST(LayerResponse, LargeWavenumberApproachesHalfPlaneWithoutOverflow) {
  for (double kw : {0.01, 1.0, kInf})
    for (double s : {0.0, 0.2, 0.6}) {
      const LayerModel m(s, kw, 0.2);
      for (double t : {50.0, 350.0, 1e3, 1e5, 1e300}) {
        const Response r = m.response(t);
        ASSERT_TRUE(std::isfinite(r.M1) && std::isfinite(r.M2));
        EXPECT_NEAR(r.M1, m.phi1(), 1e-14);
        EXPECT_NEAR(r.M2, m.phi2(), 1e-14);
      }
    }
}

TEST(LayerResponse, SmallWavenumberLimit) {
  // M1 ~ t [1/kw + (1 - nu)/2] at V = 0 (layer sinks into the springs).
  const double nu = 0.2;
  for (double kw : {0.1, 1.0, 10.0}) {
    const LayerModel m(0.0, kw, nu);
    for (double t : {1e-8, 1e-6}) {
      const double want = 1.0 / kw + 0.5 * (1.0 - nu);
      EXPECT_NEAR(m.response(t).M1 / t, want, 1e-6 * want) << "kw " << kw << " t " << t;
    }
  }
  const LayerModel rigid(0.0, kInf, nu);
  EXPECT_NEAR(rigid.response(1e-8).M1 / 1e-8, 0.5 * (1.0 - nu), 1e-7);
}

TEST(LayerResponse, TransferAndModalEvaluationsAgree) {
  for (double kw : {0.01, 0.1, 1.0, 10.0, kInf})
    for (double s : {0.0, 1e-12, 1e-3, 0.3, 0.8})
      for (double nu : {0.0, 0.2, 0.45}) {
        if (s >= 0.8 && nu < 0.1) continue;  // above this Rayleigh speed
        const LayerModel m(s, kw, nu);
        for (double t : {0.2, 0.5, 1.0, 2.0}) {
          const Response a = m.response_modal(t), b = m.response_transfer(t);
          EXPECT_NEAR(a.M1, b.M1, 1e-11 * (1.0 + std::fabs(a.M1)))
              << "kw " << kw << " s " << s << " nu " << nu << " t " << t;
          EXPECT_NEAR(a.M2, b.M2, 1e-11 * (1.0 + std::fabs(a.M2)));
        }
      }
}

TEST(LayerResponse, ContinuousAtZeroSpeed) {
  for (double kw : {0.1, 1.0, kInf}) {
    const LayerModel m0(0.0, kw, 0.2), m1(1e-14, kw, 0.2), m2(1e-3, kw, 0.2), m3(2e-3, kw, 0.2);
    for (double t : {0.1, 0.7, 3.0, 30.0}) {
      EXPECT_NEAR(m0.response(t).M1, m1.response(t).M1, 1e-13 * (1 + m0.response(t).M1));
      // Linear in s for small s: the second difference is tiny.
      const double d1 = m2.response(t).M1 - m0.response(t).M1;
      const double d2 = m3.response(t).M1 - m2.response(t).M1;
      EXPECT_NEAR(d1, d2, 1e-2 * std::fabs(d1) + 1e-14);
    }
  }
}

TEST(LayerResponse, ContinuousDownToSubnormalSpeeds) {
  // The divided difference (e^{d x} - 1)/d with d ~ vstar: expm1(d x)/d lost
  // every digit once d was subnormal (M1 off by 0.3 relative at 1e-322).
  for (double kw : {0.1, 1.0, kInf}) {
    const LayerModel m0(0.0, kw, 0.2);
    for (double v : {4.9e-324, 1e-322, 1e-320, 1e-310, 2.3e-308, 1e-300, 1e-200, 1e-20}) {
      const LayerModel mv(v, kw, 0.2);
      for (double t : {0.01, 0.1, 0.7, 3.0, 30.0}) {
        const double r0 = m0.response(t).M1, rv = mv.response(t).M1;
        EXPECT_NEAR(rv, r0, 4e-16 * std::fabs(r0) + 1e-300) << "vstar " << v << " t " << t;
      }
    }
  }
}

TEST(LayerResponse, RayleighSpeeds) {
  EXPECT_NEAR(rayleigh_vstar(0.2), 0.8299135134, 1e-9);
  EXPECT_NEAR(rayleigh_vstar(0.25), 0.84530, 1e-5);
  EXPECT_NEAR(rayleigh_vstar(0.3), 0.86009, 1e-5);
  // The Rayleigh equation holds there.
  const double s = rayleigh_vstar(0.2), kappa = 3.0 - 0.8, c2 = (kappa + 1) / (kappa - 1);
  EXPECT_NEAR((2 - s) * (2 - s), 4 * std::sqrt(1 - s) * std::sqrt(1 - s / c2), 1e-12);
}

TEST(LayerResponse, RejectsInvalidInput) {
  EXPECT_THROW(LayerModel(-0.1, 1.0, 0.2), std::invalid_argument);
  EXPECT_THROW(LayerModel(std::nan(""), 1.0, 0.2), std::invalid_argument);
  EXPECT_THROW(LayerModel(0.1, -1.0, 0.2), std::invalid_argument);
  EXPECT_THROW(LayerModel(0.1, 0.0, 0.2), std::invalid_argument);
  EXPECT_THROW(LayerModel(0.1, 1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(LayerModel(0.1, 1.0, -0.1), std::invalid_argument);
  const LayerModel m(0.1, 1.0, 0.2);
  EXPECT_THROW(m.response(std::nan("")), std::invalid_argument);
  EXPECT_THROW(m.response(-1.0), std::invalid_argument);
  try {
    LayerModel(0.1, 1.0, 0.7);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("nu must be in [0, 0.5)"), std::string::npos) << e.what();
  }
}

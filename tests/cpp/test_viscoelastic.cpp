// Viscoelastic layers (movingpunch/viscoelastic.hpp, docs/theory.md section
// 17): the material, its retardation spectrum, the memory kernel's moments
// against an independent quadrature of the kernel in closed form, and the
// layer's responses (the elastic limits, positive dissipation).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <vector>

#include "movingpunch/asymmetric.hpp"
#include "movingpunch/collocation.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/medium.hpp"
#include "movingpunch/viscoelastic.hpp"

namespace mp = movingpunch;

namespace {

constexpr double kPi = 3.14159265358979323846;

mp::Viscoelastic prony3() {
  mp::Viscoelastic v;
  v.weights = {0.5, 2.0, 4.0};
  v.deborahs = {0.02, 0.3, 5.0};
  v.shift = 1.5;
  return v;
}

// e^z E1(z) continued to z < 0 as -e^z Ei(-z) (the principal value): the
// Hilbert transform of the causal exponential, (1/beta) F(u/beta) = pi H[e](u).
// (Beyond z = 30 by E1's continued fraction, e^z E1(z) = 1/(z + 1 - 1/(z +
// 3 - 4/(z + 5 - ...))): libstdc++'s expint(-z) is its truncated asymptotic
// series there, e^z E1(z) = 1/z exactly at z = 100.)
double F(double z) {
  if (z > 30.0) {
    double f = 0.0;
    for (int k = 80; k >= 1; --k) f = k * k / (z + 2.0 * k + 1.0 - f);
    return 1.0 / (z + 1.0 - f);
  }
  return -std::exp(z) * std::expint(-z);
}

// tanh-sinh quadrature of f on [a, b] (end singularities of log type).
double tanh_sinh(const std::function<double(double)>& f, double a, double b) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  const double step = 1.0 / 128.0;
  double sum = 0.0;
  for (int k = -6 * 128; k <= 6 * 128; ++k) {
    const double t = k * step;
    const double u = 0.5 * kPi * std::sinh(t);
    const double x = std::tanh(u);
    const double wgt = 0.5 * kPi * std::cosh(t) / (std::cosh(u) * std::cosh(u));
    const double r = c + h * x;
    if (!(r > a && r < b)) continue;
    sum += wgt * f(r);
  }
  return h * sum * step;
}

}  // namespace

TEST(Viscoelastic, ZenerModulusAndSpectrum) {
  const mp::Viscoelastic z = mp::zener(3.0, 0.2);
  EXPECT_DOUBLE_EQ(z.ratio(), 3.0);
  for (double t : {0.0, 0.1, 1.0, 7.0, 1e3}) {
    const std::complex<double> m = z.modulus(t);
    const std::complex<double> want =
        std::complex<double>(1.0, -3.0 * 0.2 * t) / std::complex<double>(1.0, -0.2 * t);
    EXPECT_NEAR(std::abs(m - want), 0.0, 1e-15 * std::abs(want));
    if (t > 0.0) EXPECT_LT(m.imag(), 0.0);  // e^{-i omega t}: a loss
  }
  const mp::RetardationSpectrum sp = mp::retardation_spectrum(z);
  ASSERT_EQ(sp.c.size(), 1u);
  EXPECT_DOUBLE_EQ(sp.c[0], 2.0);
  EXPECT_DOUBLE_EQ(sp.beta[0], 3.0 * 0.2);
  // ratio 1 or deborah 0: elastic (no branch).
  EXPECT_TRUE(mp::zener(1.0, 0.5).empty());
  EXPECT_TRUE(mp::zener(2.0, 0.0).empty());
  // A branch of deborah 0 relaxes at once: no stiffness at any frequency,
  // not in the ratio, not in the spectrum.
  mp::Viscoelastic v;
  v.weights = {1.0, 2.0};
  v.deborahs = {0.0, 0.1};
  EXPECT_FALSE(v.empty());
  EXPECT_DOUBLE_EQ(v.ratio(), 3.0);
  EXPECT_DOUBLE_EQ(mp::retardation_spectrum(v).ratio, 3.0);
  v.deborahs = {0.0, 0.0};
  EXPECT_TRUE(v.empty());
  EXPECT_DOUBLE_EQ(v.ratio(), 1.0);
}

TEST(Viscoelastic, PronySpectrumIsThePartialFractionsOfTheCompliance) {
  const mp::Viscoelastic v = prony3();
  const mp::RetardationSpectrum sp = mp::retardation_spectrum(v);
  ASSERT_EQ(sp.c.size(), 3u);
  double csum = 0.0;
  for (std::size_t k = 0; k < sp.c.size(); ++k) {
    EXPECT_GT(sp.c[k], 0.0);
    EXPECT_GT(sp.beta[k], 0.0);
    if (k > 0) EXPECT_GT(sp.beta[k], sp.beta[k - 1]);
    csum += sp.c[k];
  }
  EXPECT_NEAR(csum, v.ratio() - 1.0, 1e-13 * v.ratio());
  for (double t : {1e-3, 0.05, 0.7, 3.0, 40.0, 1e4}) {
    const std::complex<double> want = v.ratio() / v.modulus(t) - 1.0;
    EXPECT_NEAR(std::abs(sp.memory(t) - want), 0.0, 1e-13 * (1.0 + std::abs(want))) << t;
  }
}

TEST(Viscoelastic, BadMaterialsAreRefusedByName) {
  mp::Viscoelastic v = prony3();
  v.deborahs.pop_back();
  EXPECT_THROW(mp::validate(v, "layers[0].viscoelastic"), mp::InvalidParameter);
  v = prony3();
  v.weights[1] = -1.0;
  try {
    mp::validate(v, "layers[0].viscoelastic");
    FAIL();
  } catch (const mp::InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("layers[0].viscoelastic[1].weight"), std::string::npos);
  }
  v = prony3();
  v.deborahs[0] = std::nan("");
  EXPECT_THROW(mp::validate(v, "v"), mp::InvalidParameter);
  v = prony3();
  v.shift = 0.0;
  EXPECT_THROW(mp::validate(v, "v"), mp::InvalidParameter);
  EXPECT_THROW(mp::zener(0.5, 0.1), mp::InvalidParameter);
  EXPECT_THROW(mp::zener(2.0, -0.1), mp::InvalidParameter);
}

// The moments l J_n(s, l) against (w/pi) int sqrt(1 - r^2) U_n(r) K(w (s - r)) dr
// with K(u) = (1/beta) F(u/beta) in closed form (exponential integrals),
// integrated by tanh-sinh on both sides of the logarithmic point r = s: the
// Hilbert transform taken by hand on one side, the kernel on the other.
TEST(Viscoelastic, MemoryMomentsAreTheKernelsIntegrals) {
  for (double beta : {0.07, 0.6, 4.0}) {
    for (double w : {0.3, 1.1}) {
      for (double s : {-0.93, -0.2, 0.0, 0.55, 0.99}) {
        const int count = 9;
        std::vector<double> got(count);
        mp::memory_moments(s, w / beta, count, got.data());
        const double ts = std::acos(s);
        for (int n = 0; n < count; ++n) {
          auto f = [&](double th) {
            const double u = w * (s - std::cos(th));
            return std::sin(th) * std::sin((n + 1) * th) * F(u / beta) / beta;
          };
          const double want = (w / kPi) * (tanh_sinh(f, 0.0, ts) + tanh_sinh(f, ts, kPi));
          EXPECT_NEAR(got[static_cast<std::size_t>(n)], want, 2e-11 * (1.0 + std::fabs(want)))
              << "beta " << beta << " w " << w << " s " << s << " n " << n;
        }
      }
    }
  }
}

TEST(Viscoelastic, MemoryMomentsBesideTheContactAndInTheLimits) {
  // Beside the contact (|s| > 1): against the same kernel integral (no
  // singular point inside).
  const double beta = 0.5, w = 0.8;
  for (double s : {-2.5, -1.2, 1.05, 1.7, 6.0}) {
    std::vector<double> got(6);
    mp::memory_moments(s, w / beta, 6, got.data());
    for (int n = 0; n < 6; ++n) {
      auto f = [&](double th) {
        return std::sin(th) * std::sin((n + 1) * th) * F(w * (s - std::cos(th)) / beta) / beta;
      };
      const double want = (w / kPi) * tanh_sinh(f, 0.0, kPi);
      EXPECT_NEAR(got[static_cast<std::size_t>(n)], want, 2e-11 * (1.0 + std::fabs(want)))
          << s << " " << n;
    }
  }
  // l -> inf: h_n(s) (the relaxed limit: T_{n+1}(s) on the contact, the
  // Cauchy term's image beside it), with an error O(1/l).
  for (double s : {-0.7, 0.3, 1.4, -3.0}) {
    const int count = 12;
    std::vector<double> got(count);
    mp::memory_moments(s, 1e11, count, got.data());
    for (int n = 0; n < count; ++n) {
      const double want = std::fabs(s) <= 1.0
                              ? std::cos((n + 1) * std::acos(s))
                              : std::pow(s - std::copysign(std::sqrt(s * s - 1.0), s), n + 1);
      EXPECT_NEAR(got[static_cast<std::size_t>(n)], want, 1e-9) << s << " " << n;
    }
  }
  // l -> 0: l J_n -> 0 (like l ln(1/l) for n = 0).
  std::vector<double> tiny(4);
  mp::memory_moments(0.2, 1e-10, 4, tiny.data());
  for (double v : tiny) EXPECT_LT(std::fabs(v), 1e-8);
}

TEST(Viscoelastic, MemoryMomentsOfAFlatFacesBasis) {
  // The T basis T_n(r)/sqrt(1 - r^2) (a flat face's square-root edges):
  // against the kernel's integral in closed form, (w/pi) int_0^pi cos(n th)
  // F(w (s - cos th)/beta)/beta d th, on and beside the face.
  for (double beta : {0.07, 0.6, 4.0}) {
    for (double w : {0.3, 1.1}) {
      for (double s : {-2.5, -1.2, -0.93, -0.2, 0.0, 0.55, 0.99, 1.05, 1.7, 6.0}) {
        const int count = 9;
        std::vector<double> got(count);
        mp::memory_moments(s, w / beta, count, got.data(), mp::MemoryBasis::T);
        for (int n = 0; n < count; ++n) {
          auto f = [&](double th) {
            return std::cos(n * th) * F(w * (s - std::cos(th)) / beta) / beta;
          };
          const double want =
              std::fabs(s) < 1.0
                  ? (w / kPi) * (tanh_sinh(f, 0.0, std::acos(s)) + tanh_sinh(f, std::acos(s), kPi))
                  : (w / kPi) * tanh_sinh(f, 0.0, kPi);
          EXPECT_NEAR(got[static_cast<std::size_t>(n)], want, 2e-11 * (1.0 + std::fabs(want)))
              << "beta " << beta << " w " << w << " s " << s << " n " << n;
        }
      }
    }
  }
  // sqrt(1 - r^2) U_n = (T_n - T_{n+2})/(2 sqrt(1 - r^2)): the U basis'
  // moments (tested above) from the T basis', to round-off.
  for (double l : {1e-3, 0.4, 7.0, 300.0}) {
    for (double s : {-3.0, -1.0, -0.6, 0.2, 1.0, 1.3}) {
      const int count = 24;
      std::vector<double> u(count), t(count + 2);
      mp::memory_moments(s, l, count, u.data());
      mp::memory_moments(s, l, count + 2, t.data(), mp::MemoryBasis::T);
      for (int n = 0; n < count; ++n) {
        const auto k = static_cast<std::size_t>(n);
        EXPECT_NEAR(u[k], 0.5 * (t[k] - t[k + 2]), 1e-13 * (1.0 + std::fabs(u[k])))
            << "l " << l << " s " << s << " n " << n;
      }
    }
  }
  // At the face's front edge, n = 0: l int_1^inf e^{-l (x - 1)}/sqrt(x^2 - 1)
  // dx = l e^l K_0(l).
  for (double l : {0.01, 0.5, 3.0, 40.0}) {
    double got = 0.0;
    mp::memory_moments(1.0, l, 1, &got, mp::MemoryBasis::T);
    EXPECT_NEAR(got, l * std::exp(l) * std::cyl_bessel_k(0.0, l), 1e-13) << l;
  }
  // Descending rows and a cluster of nearby times (the kernel's own paths)
  // are each point's moments.
  mp::RetardationSpectrum sp;
  sp.c = {0.3, 0.5, 0.2, 1.0};
  sp.beta = {0.2, 0.21, 0.25, 3.0};
  sp.ratio = 3.0;
  const mp::MemoryKernel mem(sp);
  const std::vector<double> pts{2.0, 0.9, 0.3, -0.4, -0.99, -1.5};
  const int count = 10;
  std::vector<double> rows(pts.size() * count), one(count);
  mem.moments_descending(pts.data(), static_cast<int>(pts.size()), 0.7, count, rows.data(),
                         mp::MemoryBasis::T);
  for (std::size_t k = 0; k < pts.size(); ++k) {
    mem.moments(pts[k], 0.7, count, one.data(), mp::MemoryBasis::T);
    for (int n = 0; n < count; ++n)
      EXPECT_NEAR(rows[k * count + static_cast<std::size_t>(n)], one[static_cast<std::size_t>(n)],
                  1e-13)
          << pts[k] << " " << n;
  }
}

TEST(Viscoelastic, CollocationBlockIsTheCauchyTermInTheRelaxedLimit) {
  // c lambda J_n -> c T_{n+1}(s_k) as lambda -> inf: the block becomes c
  // W_i/(r_i - s_k), exactly the discrete Cauchy term (Gauss-Chebyshev).
  mp::RetardationSpectrum sp;
  sp.c = {1.5};
  sp.beta = {1e-11};
  sp.ratio = 2.5;
  const mp::MemoryKernel mk(sp);
  const mp::ChebyshevNodes nd = mp::chebyshev_nodes(16);
  const Eigen::MatrixXd B = mk.collocation_block(nd, 0.7);
  for (int k = 0; k <= nd.n; ++k)
    for (int i = 0; i < nd.n; ++i)
      EXPECT_NEAR(B(k, i), 1.5 * nd.w(i) / (nd.r(i) - nd.s(k)), 1e-8) << k << " " << i;
}

TEST(Viscoelastic, LayerResponseLimitsAndPositiveDissipation) {
  mp::MediumSpec spec = mp::homogeneous_medium(1.0, 0.25);
  spec.layers[0].visco = mp::zener(4.0, 0.3);
  const auto m = mp::make_medium(spec, 0.0);
  EXPECT_FALSE(m->real());
  ASSERT_NE(m->memory(), nullptr);
  EXPECT_NEAR(m->phi1(), 0.75 / 4.0, 1e-15);
  // The relaxed and the unrelaxed elastic layers (mu_0 = 1 and mu_inf = 4:
  // the compliance over 4, the springs relatively 4 times softer).
  const auto relaxed = mp::make_medium(mp::homogeneous_medium(1.0, 0.25), 0.0);
  const auto unrelaxed = mp::make_medium(mp::homogeneous_medium(0.25, 0.25), 0.0);
  for (double t : {1e-4, 0.01, 0.2, 1.0, 3.0, 12.0}) {
    const mp::FullResponse r = m->full_response(t);
    // Positive dissipation mode by mode: Im M1 > 0.
    EXPECT_GT(r.M1.imag(), 0.0) << t;
    // Stresses per unit pressure: those of the elastic layer on springs kw/m(t).
    EXPECT_TRUE(std::isfinite(r.M2.real()));
    (void)relaxed;
  }
  // deborah -> 0 and -> inf: the relaxed and unrelaxed layers' M1.
  mp::MediumSpec fast = spec, slow = spec;
  slow.layers[0].visco = mp::zener(4.0, 1e-12);
  fast.layers[0].visco = mp::zener(4.0, 1e12);
  const auto ms = mp::make_medium(slow, 0.0), mf = mp::make_medium(fast, 0.0);
  for (double t : {0.05, 0.5, 2.0, 8.0}) {
    EXPECT_NEAR(std::abs(ms->full_response(t).M1 - relaxed->full_response(t).M1), 0.0, 1e-10) << t;
    EXPECT_NEAR(std::abs(mf->full_response(t).M1 - 0.25 * unrelaxed->full_response(t).M1), 0.0,
                1e-10)
        << t;
  }
  // The whole half-plane part: M1 - (1 - nu)/m(t) decays exponentially.
  for (double t : {20.0, 30.0}) {
    const std::complex<double> rem = m->full_response(t).M1 - m->half_plane_m1(t);
    EXPECT_LT(std::abs(rem), 1e-6 * std::exp(-2.0 * (t - 20.0)) + 1e-15) << t;
  }
}

TEST(Viscoelastic, TheUnrelaxedConstantsAndEachRefusalNamesItsParameter) {
  mp::MediumSpec spec = mp::homogeneous_medium(1.0, 0.25);
  spec.layers[0].visco = mp::zener(2.0, 0.1);
  // With inertia: the unrelaxed half-plane's phi1 and phi2 (vstar/m_inf).
  const auto moving = mp::make_medium(spec, 0.1);
  EXPECT_NEAR(moving->phi1(), mp::phi1(0.05, 0.25) / 2.0, 1e-15);
  EXPECT_NEAR(moving->phi2(), mp::phi2(0.05, 0.25), 1e-15);
  ASSERT_NE(moving->memory(), nullptr);
  ASSERT_NE(moving->stress_memory(), nullptr);
  // A graded sublayer is elastic: a material there is refused by its index.
  mp::MediumSpec graded = spec;
  graded.layers = {mp::Sublayer(0.5, 1.0, 0.25), mp::Sublayer(0.5, 2.0, 0.3, 1.0, 1.5)};
  graded.layers[1].visco = mp::zener(2.0, 0.1);
  try {
    mp::make_medium(graded, 0.0);
    FAIL();
  } catch (const mp::InvalidParameter& e) {
    EXPECT_EQ(e.name(), "layers[1].viscoelastic");
  }
  // Dashpots under a viscoelastic stack: refused by name too.
  mp::MediumSpec damped = spec;
  damped.layers = {mp::Sublayer(0.5, 1.0, 0.25), mp::Sublayer(0.5, 2.0, 0.3)};
  damped.layers[1].visco = mp::zener(2.0, 0.1);
  damped.base.damping = 0.3;
  try {
    mp::make_medium(damped, 0.0);
    FAIL();
  } catch (const mp::InvalidParameter& e) {
    EXPECT_EQ(e.name(), "damping");
  }
  // Keys tell materials apart.
  mp::MediumSpec other = spec;
  other.layers[0].visco = mp::zener(2.0, 0.2);
  EXPECT_NE(spec.key(), other.key());
  EXPECT_NE(spec.key(), mp::homogeneous_medium(1.0, 0.25).key());
}

TEST(Viscoelastic, DescendingRowsAreEachRowsMoments) {
  // The recursion over the collocation points against each point's own
  // moments (small, moderate and large l; the rows of N = 24).
  const mp::ChebyshevNodes nd = mp::chebyshev_nodes(24);
  const int rows = nd.n + 1, count = nd.n;
  for (double l : {1e-6, 0.3, 4.0, 90.0, 3e4}) {
    std::vector<double> all(static_cast<std::size_t>(rows) * count), one(count);
    mp::memory_moments_descending(nd.s.data(), rows, l, count, all.data());
    for (int k = 0; k < rows; ++k) {
      mp::memory_moments(nd.s(k), l, count, one.data());
      for (int n = 0; n < count; ++n)
        EXPECT_NEAR(all[static_cast<std::size_t>(k) * count + n], one[n], 1e-13)
            << "l " << l << " k " << k << " n " << n;
    }
  }
  const double bad[] = {0.1, 0.3};
  std::vector<double> out(4);
  EXPECT_THROW(mp::memory_moments_descending(bad, 2, 1.0, 2, out.data()), std::invalid_argument);
}

// ---------------------------------------------------------------------------
// With inertia (docs/theory.md section 17.6)

TEST(Viscoelastic, ComplexWaveConstantsAtARealSpeedAreTheRealOnes) {
  // The templated closed forms: complex s on the real axis gives the real
  // constants, the modal columns and the transfer matrix to round-off.
  for (double s : {1e-9, 0.1, 0.5, 0.85})
    for (double nu : {0.0, 0.25, 0.49}) {
      if (!(s < mp::rayleigh_vstar(nu))) continue;
      const mp::WaveConstants r = mp::wave_constants(s, nu);
      const mp::ComplexWaveConstants c = mp::complex_wave_constants({s, 0.0}, nu);
      for (auto [a, b] :
           {std::pair{r.phi1, c.phi1}, std::pair{r.phi2, c.phi2}, std::pair{r.nT, c.nT},
            std::pair{r.nL, c.nL}, std::pair{r.dW, c.dW}, std::pair{r.dT, c.dT},
            std::pair{r.dS, c.dS}, std::pair{r.hp1, c.hp1}, std::pair{r.hp2, c.hp2}}) {
        EXPECT_NEAR(b.real(), a, 1e-14 * std::max(1.0, std::fabs(a))) << s << " " << nu;
        EXPECT_EQ(b.imag(), 0.0);
      }
    }
  EXPECT_THROW(mp::complex_wave_constants({1.5, 0.0}, 0.3), std::invalid_argument);
  EXPECT_THROW(mp::complex_wave_constants({std::nan(""), 0.1}, 0.3), std::invalid_argument);
}

TEST(Viscoelastic, TheMovingLayersResponseIsTheElasticOneInTheLimits) {
  // deborah 1e-12: m = 1 to 1e-12 t, the elastic layer at vstar; the
  // response's displacements per mu_0 m (the damped model's units).
  const mp::DampedLayerModel el(0.3, 2.0, 0.25, 0.0),
      ve(0.3, 2.0, 0.25, 0.0, 0.0, mp::zener(3.0, 1e-12));
  for (double t : {0.05, 0.4, 0.6, 2.0, 30.0}) {
    const mp::DampedResponse a = el.response(t), b = ve.response(t);
    EXPECT_NEAR(std::abs(a.M1 - b.M1), 0.0, 1e-10) << t;
    EXPECT_NEAR(std::abs(a.M2 - b.M2), 0.0, 1e-10) << t;
    EXPECT_NEAR(std::abs(a.Wb - b.Wb), 0.0, 1e-10) << t;
    // Positive dissipation with a real material: Im M1 >= 0 once divided by m.
    const mp::DampedLayerModel lossy(0.3, 2.0, 0.25, 0.0, 0.0, mp::zener(3.0, 0.5));
    EXPECT_GE((lossy.response(t).M1 / mp::zener(3.0, 0.5).modulus(t)).imag(), 0.0) << t;
  }
}

TEST(Viscoelastic, InertialSpectrumMatchesTheSymbolOffItsGrid) {
  // The sum of the pole and the cut against phi1(vstar/m)/m (and phi2) at
  // real t between the construction's check points (a factor 1.0123 off its
  // grid) and far beyond it; its size and its reported error.
  std::vector<mp::Viscoelastic> materials;
  for (double ratio : {2.0, 10.0, 1000.0})
    for (double D : {1e-12, 1e-3, 1.0, 1e12}) materials.push_back(mp::zener(ratio, D));
  materials.push_back(prony3());
  for (const mp::Viscoelastic& v : materials)
    for (double vs : {1e-6, 0.3, 0.6})
      for (auto which : {mp::HalfPlaneSymbol::compliance, mp::HalfPlaneSymbol::stress}) {
        const bool stress = which == mp::HalfPlaneSymbol::stress;
        const mp::InertialSpectrum sp = mp::inertial_spectrum(v, vs, 0.3, 1e-12, which);
        ASSERT_LE(sp.spectrum.c.size(), 64u);
        auto exact = [&](double t) {
          return (stress ? mp::half_plane_stress(v, vs, 0.3, t)
                         : mp::half_plane_compliance(v, vs, 0.3, t)) /
                     sp.h_inf -
                 1.0;
        };
        double scale = 1.0, worst = 0.0;
        for (double t = 1e-16; t < 1e16; t *= 1.0123 * 3.7) {
          const std::complex<double> f = exact(t);
          scale = std::max(scale, std::abs(f));
          worst = std::max(worst, std::abs(sp.spectrum.memory(t) - f));
        }
        EXPECT_LE(worst, 2e-12 * scale)
            << "ratio " << v.ratio() << " vstar " << vs << " " << stress;
        EXPECT_LE(sp.error, 1e-12 * scale);
        // The unrelaxed limit: f -> 0 like 1/t (the sum's too).
        EXPECT_LT(std::abs(sp.spectrum.memory(1e18)), 1e-6 * scale);
      }
  // At rest: the retardation spectrum, and no stress memory.
  const mp::InertialSpectrum rest = mp::inertial_spectrum(prony3(), 0.0, 0.3);
  EXPECT_EQ(rest.spectrum.beta, mp::retardation_spectrum(prony3()).beta);
  EXPECT_TRUE(mp::inertial_spectrum(prony3(), 0.0, 0.3, 1e-13, mp::HalfPlaneSymbol::stress)
                  .spectrum.c.empty());
  EXPECT_THROW(mp::inertial_spectrum(prony3(), 0.9, 0.3), std::invalid_argument);
  // Near the Rayleigh speed (0.99 v_R, ratio 1000): the round-off of the cut's
  // density limits the sum to about 5e-14 of max |f|; 1e-13 is not met and
  // says so.
  EXPECT_THROW(mp::inertial_spectrum(mp::zener(1000.0, 10.0), 0.85, 0.3, 1e-13),
               mp::ConvergenceError);
  EXPECT_NO_THROW(mp::inertial_spectrum(mp::zener(1000.0, 10.0), 0.85, 0.3));
}

// A viscoelastic layer cut into identical sublayers: the stack's complex
// propagation against the single layer's closed form (the damped layer's
// modes at vstar/m(t)), at rest and moving, every response of the
// asymmetric solver, the states at depth and the half-plane parts.
TEST(ViscoelasticStack, IdenticalSublayersAreTheClosedFormLayer) {
  for (double vstar : {0.0, 0.3}) {
    mp::MediumSpec one = mp::homogeneous_medium(2.0, 0.25);
    one.layers[0].visco = mp::zener(3.0, 0.5);
    mp::MediumSpec cut = one;
    cut.layers = {mp::Sublayer(0.35, 1.0, 0.25), mp::Sublayer(0.65, 1.0, 0.25)};
    for (auto& l : cut.layers) l.visco = mp::zener(3.0, 0.5);
    const auto a = mp::make_medium(one, vstar), b = mp::make_medium(cut, vstar);
    EXPECT_FALSE(b->real());
    ASSERT_NE(b->memory(), nullptr);
    EXPECT_EQ(a->phi1(), b->phi1());
    EXPECT_EQ(a->phi2(), b->phi2());
    EXPECT_EQ(b->spec().viscoelastic(), true);
    for (double t : {1e-3, 0.05, 0.4, 0.7, 2.0, 9.0, 30.0}) {
      const mp::FullResponse r = a->full_response(t), s = b->full_response(t);
      const double scale = std::abs(r.M1);
      EXPECT_LT(std::abs(r.M1 - s.M1), 1e-13 * scale) << vstar << " " << t;
      EXPECT_LT(std::abs(r.M2 - s.M2), 1e-12 * (1.0 + std::abs(r.M2))) << vstar << " " << t;
      EXPECT_LT(std::abs(r.Wb - s.Wb), 1e-12 * scale) << vstar << " " << t;
      EXPECT_LT(std::abs(r.Uq - s.Uq), 1e-12 * std::abs(r.Uq)) << vstar << " " << t;
      EXPECT_LT(std::abs(r.Wq - s.Wq), 1e-12 * std::abs(r.Wq) + 1e-15) << vstar << " " << t;
      EXPECT_EQ(a->half_plane_m1(t), b->half_plane_m1(t));
      EXPECT_EQ(a->half_plane_m2(t), b->half_plane_m2(t));
      for (double y : {-0.2, -0.35, -0.8, -1.0}) {
        const Eigen::Vector4cd za = a->normal_state(t, y), zb = b->normal_state(t, y);
        EXPECT_LT((za - zb).norm(), 1e-12 * za.norm() + 1e-300) << vstar << " " << t << " " << y;
        const mp::ModeState ra = a->mode(t)->remainder(y), rb = b->mode(t)->remainder(y);
        EXPECT_LT(std::abs(ra.sx - rb.sx), 1e-11 * (std::abs(ra.sx) + za.norm()))
            << vstar << " " << t << " " << y;
      }
    }
  }
}

// An elastic top on a viscoelastic sublayer: the kernel's remainder M1 -
// phi1 decays like the elastic stack's (no memory: the top is elastic), the
// loss is positive mode by mode, and the limits are the elastic stacks of
// mu_0 and mu_inf (the real propagation).
TEST(ViscoelasticStack, ADeepSublayerMeetsTheElasticStacksAndDissipates) {
  auto stack = [](double mu2, const mp::Viscoelastic& v, mp::BaseKind base) {
    mp::MediumSpec m;
    m.layers = {mp::Sublayer(0.3, 1.0, 0.25), mp::Sublayer(0.7, mu2, 0.3, 0.8)};
    m.layers[1].visco = v;
    m.base.kind = base;
    m.base.kw = 2.0;
    m.base.mu = 3.0;
    m.base.nu = 0.25;
    m.base.rho = 1.5;
    return m;
  };
  for (mp::BaseKind base : {mp::BaseKind::springs, mp::BaseKind::half_space_bonded}) {
    for (double vstar : {0.0, 0.2}) {
      const auto m = mp::make_medium(stack(0.5, mp::zener(4.0, 0.3), base), vstar);
      EXPECT_EQ(m->memory(), nullptr);
      EXPECT_EQ(m->half_plane_m1(5.0), m->phi1());
      EXPECT_NEAR(m->phi1(), mp::phi1(vstar, 0.25), 1e-15);
      const auto relaxed = mp::make_medium(stack(0.5, {}, base), vstar);
      const auto unrelaxed = mp::make_medium(stack(2.0, {}, base), vstar);
      const auto slow = mp::make_medium(stack(0.5, mp::zener(4.0, 1e-12), base), vstar);
      const auto fast = mp::make_medium(stack(0.5, mp::zener(4.0, 1e12), base), vstar);
      for (double t : {1e-3, 0.1, 1.0, 4.0, 15.0}) {
        EXPECT_GT(m->full_response(t).M1.imag(), 0.0) << t;  // e^{-i omega t}: a loss
        const double r = std::abs(relaxed->surface_response(t).M1);
        EXPECT_LT(std::abs(slow->surface_response(t).M1 - relaxed->surface_response(t).M1),
                  1e-10 * r)
            << t;
        EXPECT_LT(std::abs(fast->surface_response(t).M1 - unrelaxed->surface_response(t).M1),
                  1e-10 * r)
            << t;
      }
      // M1 - phi1: the reflection off the top sublayer's bottom, e^{-2 nT 0.3 t}.
      const double t = 60.0, rem = std::abs(m->surface_response(t).M1 - m->phi1());
      EXPECT_LT(rem, 1e3 * std::exp(-2.0 * 0.3 * t * std::sqrt(1.0 - vstar)));
      EXPECT_EQ(m->dispersion(2.0), relaxed->dispersion(2.0));
    }
  }
}

// The memory block at another zone's points (any descending s, beside the
// density's zone or across it) against the moments point by point.
TEST(ViscoelasticZones, BlockAtIsTheMomentsAtEachPoint) {
  mp::Viscoelastic v = prony3();
  const mp::MemoryKernel mem(mp::retardation_spectrum(v));
  const mp::ChebyshevNodes nd = mp::chebyshev_nodes(12);
  const std::shared_ptr<const Eigen::MatrixXd> U = mp::MemoryKernel::basis_weights(nd);
  for (double start : {6.0, 1.3, 0.7, -1.2, -9.0}) {
    std::vector<double> s;
    for (int k = 0; k <= 12; ++k) s.push_back(start - 0.17 * k);
    const double w = 0.4;
    const Eigen::MatrixXd B = mem.block_at(s.data(), 13, nd, w);
    std::vector<double> mom(12);
    for (int k = 0; k <= 12; ++k) {
      mem.moments(s[static_cast<std::size_t>(k)], w, 12, mom.data());
      for (int i = 0; i < 12; ++i) {
        double want = 0.0;
        for (int q = 0; q < 12; ++q) want += mom[static_cast<std::size_t>(q)] * (*U)(q, i);
        EXPECT_NEAR(B(k, i), want, 1e-13 * (1.0 + std::fabs(want)))
            << start << " " << k << " " << i;
      }
    }
  }
  // The collocation block is block_at at the nodes' own points.
  const Eigen::MatrixXd own = mem.collocation_block(nd, 0.4);
  EXPECT_EQ((own - mem.block_at(nd.s.data(), 13, nd, 0.4)).cwiseAbs().maxCoeff(), 0.0);
}

// The gap check's memory at many points in one downward sweep is apply at
// each point (beside the contact on both sides, a long series: a profile's).
TEST(Viscoelastic, ApplyDescendingIsApplyAtEachPoint) {
  const mp::MemoryKernel mem(mp::retardation_spectrum(prony3()));
  Eigen::VectorXd b(40);
  for (Eigen::Index q = 0; q < b.size(); ++q) b(q) = std::cos(0.7 * q) / (1.0 + q);
  for (double start : {9.0, -1.05}) {
    std::vector<double> s, out(17);
    for (int k = 0; k < 17; ++k) s.push_back(start - 0.5 * std::pow(k / 4.0, 2.0));
    const double w = 0.3;
    mem.apply_descending(b, s.data(), 17, w, out.data());
    for (int k = 0; k < 17; ++k) {
      const double want = mem.apply(b, s[static_cast<std::size_t>(k)], w);
      EXPECT_NEAR(out[static_cast<std::size_t>(k)], want, 1e-13 * (1.0 + std::fabs(want)))
          << start << " " << k;
    }
  }
}

// Media are built once per (vstar, spec): a warm solve reuses the one its
// kernel was built for; another material or speed is another medium, and a
// refused spec is refused as make_medium refuses it.
TEST(Viscoelastic, MediaAreCachedByTheirSpecAndSpeed) {
  mp::MediumSpec spec = mp::homogeneous_medium(1.0, 0.25);
  spec.layers[0].visco = prony3();
  const auto a = mp::cached_medium(spec, 0.1), b = mp::cached_medium(spec, 0.1);
  EXPECT_EQ(a.get(), b.get());
  EXPECT_NE(mp::cached_medium(spec, 0.2).get(), a.get());
  mp::MediumSpec other = spec;
  other.layers[0].visco.shift = 2.0;
  const auto c = mp::cached_medium(other, 0.1);
  EXPECT_NE(c.get(), a.get());
  EXPECT_NE(c->key(), a->key());
  EXPECT_EQ(a->key(), mp::make_medium(spec, 0.1)->key());
  other.base.damping = 0.5;  // dashpots under a viscoelastic layer
  EXPECT_THROW(mp::cached_medium(other, 0.1), mp::InvalidParameter);
}

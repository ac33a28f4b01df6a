// The memory kernel's sum over its retardation spectrum (MemoryKernel,
// movingpunch/viscoelastic.hpp): the terms, grouped in clusters of nearby
// retardation times, share their quadrature nodes (and, where the cluster is
// narrow for the segment, a Taylor expansion of their exponentials). Checked
// against the term-by-term sum of the one-term moments (memory_moments,
// memory_moments_descending), which is how the kernel summed them before.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <Eigen/Dense>

#include "movingpunch/collocation.hpp"
#include "movingpunch/viscoelastic.hpp"

namespace mp = movingpunch;

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The collocation block term by term: each term's descending sweep, summed.
Eigen::MatrixXd block_by_terms(const mp::RetardationSpectrum& sp, const mp::ChebyshevNodes& nd,
                               double w) {
  const int n = nd.n;
  RowMajor mom = RowMajor::Zero(n + 1, n), one(n + 1, n);
  for (std::size_t k = 0; k < sp.c.size(); ++k) {
    mp::memory_moments_descending(nd.s.data(), n + 1, w / sp.beta[k], n, one.data());
    mom += sp.c[k] * one;
  }
  return mom * *mp::MemoryKernel::basis_weights(nd);
}

// The moments at one point term by term.
std::vector<double> moments_by_terms(const mp::RetardationSpectrum& sp, double s, double w,
                                     int count) {
  std::vector<double> sum(static_cast<std::size_t>(count), 0.0), one(sum.size());
  for (std::size_t k = 0; k < sp.c.size(); ++k) {
    mp::memory_moments(s, w / sp.beta[k], count, one.data());
    for (std::size_t n = 0; n < sum.size(); ++n) sum[n] += sp.c[k] * one[n];
  }
  return sum;
}

// K terms with betas spread at random over [1, span] (log-uniform) and c_k of
// both signs, a third of them negative: the sum does not cancel wholesale
// (where it does, the term-by-term sum itself loses the digits).
mp::RetardationSpectrum random_spectrum(std::mt19937_64& rng, int K, double span) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  mp::RetardationSpectrum sp;
  for (int k = 0; k < K; ++k) {
    sp.beta.push_back(std::pow(span, u(rng)));
    sp.c.push_back((k % 3 == 2 ? -1.0 : 1.0) * (0.1 + 0.9 * u(rng)));
  }
  return sp;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::fabs(x));
  return m;
}

// The largest difference of the moments at s, relative to their largest.
double moments_difference(const mp::MemoryKernel& mk, double s, double w, int count) {
  std::vector<double> got(static_cast<std::size_t>(count));
  mk.moments(s, w, count, got.data());
  const std::vector<double> want = moments_by_terms(mk.spectrum(), s, w, count);
  double d = 0.0;
  for (std::size_t n = 0; n < got.size(); ++n) d = std::max(d, std::fabs(got[n] - want[n]));
  return d / max_abs(want);
}

// The points of the moments' check: far and near both branch points, inside.
constexpr double kPoints[] = {-40.0, -3.0, -1.2, -1.0, -0.5, 0.3, 0.999, 1.0, 1.05, 4.0};

// Pointwise the term-by-term moments are themselves only this good near s =
// -1, where the recurrence of T_{n+1}(x) (x near -1) loses some n^2 eps: 2e-13
// of the largest at n = 128 against a long-double evaluation (3e-15 at n = 16).
double moments_tolerance(int count) {
  const double n = count / 64.0;
  return 1e-13 * std::max(1.0, 4.0 * n * n);
}

}  // namespace

// Random spectra of 1 to 40 terms, their betas within a factor 1.01 (one
// cluster) or spread over 1e4 (several), every lambda = w/beta within
// [1e-6, 1e6], N from 8 to 128: the block to 1e-13 of its largest entry.
TEST(MemorySum, BlockMatchesTheTermByTermSum) {
  std::mt19937_64 rng(20240611);
  for (int K : {1, 6, 22, 40}) {
    for (double span : {1.01, 1e4}) {
      const mp::RetardationSpectrum sp = random_spectrum(rng, K, span);
      const mp::MemoryKernel mk(sp);
      for (int N : {8, 16, 64, 128}) {
        const mp::ChebyshevNodes nd = mp::chebyshev_nodes(N);
        for (double w : {1e-6 * span, 1e-3 * span, 1.0, 1e3, 1e6}) {
          const Eigen::MatrixXd want = block_by_terms(sp, nd, w);
          const Eigen::MatrixXd got = mk.collocation_block(nd, w);
          ASSERT_EQ(got.rows(), N + 1);
          ASSERT_EQ(got.cols(), N);
          const double scale = want.cwiseAbs().maxCoeff();
          EXPECT_LE((got - want).cwiseAbs().maxCoeff(), 1e-13 * scale)
              << "K = " << K << ", span " << span << ", N = " << N << ", w = " << w;
        }
      }
    }
  }
}

// The same spectra's moments at single points (MemoryKernel::moments, apply).
TEST(MemorySum, MomentsMatchTheTermByTermSum) {
  std::mt19937_64 rng(7);
  for (int K : {1, 6, 22, 40}) {
    for (double span : {1.01, 1e4}) {
      const mp::RetardationSpectrum sp = random_spectrum(rng, K, span);
      const mp::MemoryKernel mk(sp);
      for (int count : {8, 16, 64, 128}) {
        for (double w : {1e-6 * span, 1e-3 * span, 1.0, 1e3, 1e6}) {
          for (double s : kPoints)
            EXPECT_LE(moments_difference(mk, s, w, count), moments_tolerance(count))
                << "K = " << K << ", span " << span << ", count " << count << ", w = " << w
                << ", s = " << s;
        }
      }
    }
  }
}

// The spectra the layers make: a Zener solid moving (the Rayleigh pole and
// the cut, 6 terms within a factor 1.07), a three-branch Prony series moving
// (30 terms in three groups far apart) and at rest; at the half-widths and
// sizes their solutions take.
TEST(MemorySum, LayerSpectraMatchTheTermByTermSum) {
  mp::Viscoelastic prony;
  prony.weights = {1.0, 3.0, 0.5};
  prony.deborahs = {0.01, 1.0, 30.0};
  const mp::RetardationSpectrum spectra[] = {
      mp::inertial_spectrum(mp::zener(2.0, 0.3), 0.1, 0.3).spectrum,
      mp::inertial_spectrum(prony, 0.3, 0.3).spectrum,
      mp::retardation_spectrum(prony),
  };
  for (const mp::RetardationSpectrum& sp : spectra) {
    ASSERT_FALSE(sp.c.empty());
    const mp::MemoryKernel mk(sp);
    for (double w : {0.165, 0.665, 5.0}) {
      for (int N : {24, 32}) {
        const mp::ChebyshevNodes nd = mp::chebyshev_nodes(N);
        const Eigen::MatrixXd want = block_by_terms(sp, nd, w);
        EXPECT_LE((mk.collocation_block(nd, w) - want).cwiseAbs().maxCoeff(),
                  1e-13 * want.cwiseAbs().maxCoeff())
            << sp.c.size() << " terms, w = " << w << ", N = " << N;
        for (double s : kPoints)
          EXPECT_LE(moments_difference(mk, s, w, N), 1e-13) << sp.c.size() << " terms, s = " << s;
        // apply: the moments against a series.
        Eigen::VectorXd b(N);
        for (int q = 0; q < N; ++q) b(q) = 1.0 / (1.0 + q);
        const std::vector<double> mom = moments_by_terms(sp, -2.0, w, N);
        double want_apply = 0.0, scale = 0.0;
        for (int q = 0; q < N; ++q) {
          want_apply += b(q) * mom[static_cast<std::size_t>(q)];
          scale += std::fabs(b(q) * mom[static_cast<std::size_t>(q)]);
        }
        EXPECT_NEAR(mk.apply(b, -2.0, w), want_apply, 1e-13 * scale);
      }
    }
  }
}

// Terms given in any order, equal betas (a cluster of zero width), zero
// coefficients: the same sums.
TEST(MemorySum, UnsortedAndRepeatedTermsSumAlike) {
  mp::RetardationSpectrum sp;
  sp.beta = {3.0, 0.5, 0.5, 2.9, 0.51, 40.0, 3.0};
  sp.c = {0.7, 1.2, -0.3, 0.0, 0.4, 2.0, 0.1};
  const mp::MemoryKernel mk(sp);
  const mp::ChebyshevNodes nd = mp::chebyshev_nodes(16);
  for (double w : {0.01, 0.8, 30.0}) {
    const Eigen::MatrixXd want = block_by_terms(sp, nd, w);
    EXPECT_LE((mk.collocation_block(nd, w) - want).cwiseAbs().maxCoeff(),
              1e-13 * want.cwiseAbs().maxCoeff());
    for (double s : kPoints) EXPECT_LE(moments_difference(mk, s, w, 16), 1e-13) << s;
  }
}

// A retardation time that is not positive and finite is refused as the
// one-term moments refuse it.
TEST(MemorySum, BadTermsAreRefused) {
  const mp::ChebyshevNodes nd = mp::chebyshev_nodes(8);
  std::vector<double> out(8);
  for (double bad : {-1.0, 0.0, std::numeric_limits<double>::quiet_NaN()}) {
    mp::RetardationSpectrum sp;
    sp.beta = {1.0, 1.1, bad, 1.2};
    sp.c = {1.0, 1.0, 1.0, 1.0};
    const mp::MemoryKernel mk(sp);
    EXPECT_THROW(mk.collocation_block(nd, 1.0), std::invalid_argument) << bad;
    EXPECT_THROW(mk.moments(0.3, 1.0, 8, out.data()), std::invalid_argument) << bad;
  }
}

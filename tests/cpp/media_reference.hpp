// Shared by the C++ tests of the media (test_stack.cpp, test_asym_medium.cpp):
// media on springs, K identical sublayers, and the pieces of an independent
// naive long-double evaluation of a stack (the transfer matrices by a Taylor
// series with scaling and squaring, Gaussian elimination, eigenvectors).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "movingpunch/medium.hpp"

namespace movingpunch::testing {

inline MediumSpec springs(std::vector<Sublayer> layers, double kw, double kp = 0.0) {
  MediumSpec m;
  m.layers = std::move(layers);
  m.base.kind = BaseKind::springs;
  m.base.kw = kw;
  m.base.kp = kp;
  return m;
}

inline MediumSpec half_space(std::vector<Sublayer> layers, BaseKind kind, double mu, double nu,
                             double rho) {
  MediumSpec m;
  m.layers = std::move(layers);
  m.base.kind = kind;
  m.base.mu = mu;
  m.base.nu = nu;
  m.base.rho = rho;
  return m;
}

// K identical sublayers of unequal thicknesses.
inline std::vector<Sublayer> identical(int K, double nu) {
  const std::vector<double> w{0.37, 0.11, 0.23, 0.19, 0.1};
  std::vector<Sublayer> out;
  double sum = 0.0;
  for (int i = 0; i < K; ++i) sum += w[static_cast<size_t>(i)];
  for (int i = 0; i < K; ++i) out.push_back({w[static_cast<size_t>(i)] / sum, 1.0, nu, 1.0, 0.0});
  double total = 0.0;
  for (int i = 0; i + 1 < K; ++i) total += out[static_cast<size_t>(i)].thickness;
  out.back().thickness = 1.0 - total;
  return out;
}

// ---- a naive long-double evaluation --------------------------------------
using LD = long double;
using M4 = std::array<std::array<LD, 4>, 4>;
using V4 = std::array<LD, 4>;

inline M4 mul(const M4& a, const M4& b) {
  M4 c{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      LD s = 0;
      for (int k = 0; k < 4; ++k) s += a[i][k] * b[k][j];
      c[i][j] = s;
    }
  return c;
}

// exp(B) by scaling and squaring with a Taylor series.
inline M4 expm(M4 B) {
  LD norm = 0;
  for (auto& r : B) {
    LD s = 0;
    for (LD x : r) s += std::fabs(x);
    norm = std::max(norm, s);
  }
  int sq = 0;
  while (norm > 0.125L) {
    norm /= 2;
    ++sq;
  }
  const LD f = std::ldexp(1.0L, -sq);
  for (auto& r : B)
    for (LD& x : r) x *= f;
  M4 P{}, term{};
  for (int i = 0; i < 4; ++i) P[i][i] = term[i][i] = 1;
  for (int k = 1; k < 40; ++k) {
    term = mul(term, B);
    for (auto& r : term)
      for (LD& x : r) x /= k;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) P[i][j] += term[i][j];
  }
  for (int i = 0; i < sq; ++i) P = mul(P, P);
  return P;
}

// The state matrix of a material (stresses over its own modulus) at local speed s.
inline M4 state_matrix(LD s, LD nu) {
  const LD kappa = 3 - 4 * nu, c2 = (kappa + 1) / (kappa - 1);
  M4 A{};
  A[0] = {0, 1, 1, 0};
  A[1] = {-(c2 - 2) / c2, 0, 0, 1 / c2};
  A[2] = {4 * (c2 - 1) / c2 - s, 0, 0, (c2 - 2) / c2};
  A[3] = {0, -s, -1, 0};
  return A;
}

// Solves the 4 x 4 system a x = b (Gaussian elimination, partial pivoting).
inline std::array<LD, 4> solve4(M4 a, std::array<LD, 4> b) {
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[p][c])) p = r;
    std::swap(a[c], a[p]);
    std::swap(b[c], b[p]);
    for (int r = c + 1; r < 4; ++r) {
      const LD f = a[r][c] / a[c][c];
      for (int k = c; k < 4; ++k) a[r][k] -= f * a[c][k];
      b[r] -= f * b[c];
    }
  }
  std::array<LD, 4> x{};
  for (int r = 3; r >= 0; --r) {
    LD s = b[r];
    for (int k = r + 1; k < 4; ++k) s -= a[r][k] * x[k];
    x[r] = s / a[r][r];
  }
  return x;
}

// An eigenvector [1, v1, v2, v3] of A for the eigenvalue lam (distinct roots).
inline std::array<LD, 4> eigvec(const M4& A, LD lam) {
  // Rows 1..3 of (A - lam I) v = 0 with v0 = 1.
  M4 a{};
  std::array<LD, 4> b{};
  for (int r = 1; r < 4; ++r) {
    for (int k = 1; k < 4; ++k) a[r - 1][k - 1] = A[r][k] - (r == k ? lam : 0);
    b[r - 1] = -A[r][0];
  }
  a[3][3] = 1;
  const auto x = solve4(a, b);
  return {1, x[0], x[1], x[2]};
}

// The top state's unknowns under the top load (T0, S0) = (tau/alpha,
// sigma_y/alpha) at y = 0, given the product P of the sublayers' transfer
// matrices (z(-1) = P z(0)): x[0], x[1] = U0, W0 (x[2], x[3]: the bonded
// half-space's decaying amplitudes), from the base's conditions (clamped:
// U = W = 0 at y = -1, whatever the base).
inline std::array<LD, 4> naive_top_unknowns(const M4& P, const MediumSpec& m, double vstar,
                                            double t, LD T0, LD S0, bool clamped = false) {
  auto zrow = [&](int r, std::array<LD, 4>& row, LD& rhs) {
    row = {P[r][0], P[r][1], 0, 0};
    rhs = -(P[r][2] * T0 + P[r][3] * S0);
  };
  M4 a{};
  std::array<LD, 4> b{};
  const BaseSpec& base = m.base;
  if (clamped) {
    std::array<LD, 4> row;
    LD rhs;
    zrow(0, row, rhs);
    a[0] = row;
    b[0] = rhs;
    zrow(1, row, rhs);
    a[1] = row;
    b[1] = rhs;
    a[2][2] = a[3][3] = 1;
  } else if (base.kind == BaseKind::half_space_bonded) {
    const LD s2 = static_cast<LD>(vstar) * base.rho / base.mu;
    const M4 A2 = state_matrix(s2, base.nu);
    const LD c2 = (4 - 4 * static_cast<LD>(base.nu)) / (2 - 4 * static_cast<LD>(base.nu));
    auto vT = eigvec(A2, std::sqrt(1 - s2)), vL = eigvec(A2, std::sqrt(1 - s2 / c2));
    for (int r = 0; r < 4; ++r) {
      std::array<LD, 4> row;
      LD rhs;
      zrow(r, row, rhs);
      const LD sc = r >= 2 ? static_cast<LD>(base.mu) : 1.0L;
      row[2] = -vT[static_cast<size_t>(r)] * sc;
      row[3] = -vL[static_cast<size_t>(r)] * sc;
      a[r] = row;
      b[r] = rhs;
    }
  } else {
    std::array<LD, 4> row;
    LD rhs;
    zrow(2, row, rhs);  // tau(-1) = 0
    a[0] = row;
    b[0] = rhs;
    LD k;  // sigma/alpha t = k W
    if (base.kind == BaseKind::springs) {
      k = base.kw + base.kp * static_cast<LD>(t) * t;
    } else {
      const LD s2 = static_cast<LD>(vstar) * base.rho / base.mu;
      const LD kap = 3 - 4 * static_cast<LD>(base.nu), c2 = (kap + 1) / (kap - 1);
      const LD nT = std::sqrt(1 - s2), nL = std::sqrt(1 - s2 / c2);
      const LD phi = (1 - nT * nT) * nL / (4 * nL * nT - (1 + nT * nT) * (1 + nT * nT));
      k = static_cast<LD>(t) * base.mu / phi;
    }
    if (std::isinf(k)) {
      zrow(1, row, rhs);
    } else {
      std::array<LD, 4> r3, r1;
      LD h3, h1;
      zrow(3, r3, h3);
      zrow(1, r1, h1);
      for (int j = 0; j < 4; ++j)
        row[static_cast<size_t>(j)] =
            t * r3[static_cast<size_t>(j)] - k * r1[static_cast<size_t>(j)];
      rhs = t * h3 - k * h1;
    }
    a[1] = row;
    b[1] = rhs;
    a[2][2] = a[3][3] = 1;
  }
  return solve4(a, b);
}

}  // namespace movingpunch::testing

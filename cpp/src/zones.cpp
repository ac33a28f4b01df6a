// Several contact zones (zones.hpp; docs/theory.md section 15).
#include "movingpunch/zones.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "chebyshev.hpp"
#include "gap_scan.hpp"
#include "gauss_kronrod.hpp"
#include "ladder.hpp"
#include "movingpunch/collocation.hpp"
#include "movingpunch/dispersion.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/interrupt.hpp"
#include "movingpunch/viscoelastic.hpp"
#include "solve_skeleton.hpp"

namespace movingpunch {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = 2.220446049250313e-16;

// Gauss-Legendre rule of n points on [-1, 1] (Newton on P_n from the
// Chebyshev guesses).
struct Legendre {
  std::vector<double> x, w;
};
const Legendre& gauss_legendre8() {
  static const Legendre rule = [] {
    Legendre g;
    constexpr int m = 8;
    for (int i = 0; i < m; ++i) {
      double z = std::cos(kPi * (i + 0.75) / (m + 0.5)), dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = z;
        for (int k = 2; k <= m; ++k) {
          const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = m * (z * p1 - p0) / (z * z - 1.0);
        const double dz = p1 / dp;
        z -= dz;
        if (std::fabs(dz) < 1e-16) break;
      }
      g.x.push_back(z);
      g.w.push_back(2.0 / ((1.0 - z * z) * dp * dp));
    }
    return g;
  }();
  return rule;
}

// The regular kernel K of the zones' equations: the shared table on |u| <=
// range() and, beyond it, degree-24 Chebyshev pieces of width kWidth built
// on first use from direct Filon sums. Zones far apart then cost the few
// pieces their distances touch, never a table spanning the distance. A piece
// whose last coefficients are not at the round-off of its values is
// evaluated by direct sums instead.
class ZoneKernel {
 public:
  explicit ZoneKernel(std::shared_ptr<const AsymmetricKernel> k) : k_(std::move(k)) {
    const AsymmetricQuadrature& q = k_->quadrature();
    const double phi1 = std::fabs(k_->model().phi1());
    for (std::size_t i = 0; i < q.m1.size(); ++i)
      abs_f_ += q.panels.weight[i] * std::abs(q.m1[i] - k_->model().phi1()) / phi1;
  }
  const std::shared_ptr<const AsymmetricKernel>& table() const noexcept { return k_; }
  const Medium& model() const noexcept { return k_->model(); }
  double range() const noexcept { return k_->range(); }
  double operator()(double u) const { return std::fabs(u) <= k_->range() ? (*k_)(u) : far(u); }
  void many(const double* u, double* out, std::size_t n) const {
    const double range = k_->range();
    bool inside = true;
    for (std::size_t i = 0; i < n && inside; ++i) inside = std::fabs(u[i]) <= range;
    if (inside) {
      k_->many(u, out, n);
      return;
    }
    for (std::size_t i = 0; i < n; ++i) out[i] = (*this)(u[i]);
  }
  std::size_t pieces() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return pieces_.size();
  }

 private:
  static constexpr double kWidth = 0.25;
  static constexpr int kDegree = 24;
  std::shared_ptr<const AsymmetricKernel> k_;
  double abs_f_ = 0.0;
  mutable std::mutex mutex_;
  mutable std::unordered_map<long long, std::vector<double>> pieces_;

  double far(double u) const {
    const double s = std::floor(u / kWidth);
    if (!(std::fabs(s) < 1e15)) return k_->direct(u);
    const auto idx = static_cast<long long>(s);
    const std::vector<double>* c = nullptr;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      auto it = pieces_.find(idx);
      if (it == pieces_.end()) it = pieces_.emplace(idx, build(idx)).first;
      c = &it->second;  // stable: unordered_map never moves its elements
    }
    if (c->empty()) return k_->direct(u);
    const double x = 2.0 * (u - (static_cast<double>(idx) + 0.5) * kWidth) / kWidth;
    return detail::chebyshev_sum(c->data(), kDegree, x);
  }
  std::vector<double> build(long long idx) const {
    constexpr int D = kDegree;
    const double c0 = (static_cast<double>(idx) + 0.5) * kWidth;
    double vals[D + 1], vmax = 0.0;
    for (int j = 0; j <= D; ++j) {
      vals[j] = k_->direct(c0 + 0.5 * kWidth * std::cos(kPi * (j + 0.5) / (D + 1)));
      vmax = std::max(vmax, std::fabs(vals[j]));
    }
    std::vector<double> c(D + 1);
    for (int m = 0; m <= D; ++m) {
      double sum = 0.0;
      for (int j = 0; j <= D; ++j) sum += vals[j] * std::cos(kPi * m * (j + 0.5) / (D + 1));
      c[static_cast<std::size_t>(m)] = (m == 0 ? 1.0 : 2.0) * sum / (D + 1);
    }
    const double tail = std::fabs(c[D - 1]) + std::fabs(c[D]);
    if (!(tail <= 16.0 * kEps * (abs_f_ + vmax))) c.clear();  // not at round-off: direct sums
    return c;
  }
};

// The layer's total kernel T(u) = 1/u + K(u) (the whole slope response,
// (phi1/pi) int p T(x - t) dt, at a distance u from a load) decays on a
// Winkler or Pasternak foundation: exponentially, at the rate of the
// response's complex poles nearest the real axis (slowly near the critical
// speed, where they approach it). Sampled maxima of |T| on the windows
// [2^k, 2^(k+1)] h, k = -1..kWindows - 2 (spacing 1/8 h, at most 2048
// samples a window), memoised per layer: zones whose distances all lie in
// windows where |T| stays below a bound interact below it.
constexpr int kWindows = 15;  // up to 2^13 = 8192 h
std::vector<double> kernel_windows(const ZoneKernel& K) {
  using Key = std::vector<double>;
  static std::mutex mutex;
  static std::vector<std::pair<Key, std::vector<double>>> memo;
  const Key key = K.model().key();
  {
    const std::lock_guard<std::mutex> lock(mutex);
    for (const auto& [k, v] : memo)
      if (k == key) return v;
  }
  const AsymmetricKernel& table = *K.table();
  std::vector<double> out;
  for (int k = -1; k < kWindows - 1; ++k) {
    const double lo = std::ldexp(1.0, k), hi = 2.0 * lo;
    const int samples = static_cast<int>(std::min(2048.0, std::ceil((hi - lo) * 8.0)));
    double mx = 0.0;
    for (int i = 0; i <= samples; ++i) {
      const double u = lo + (hi - lo) * i / samples;
      mx = std::max(mx, std::fabs(1.0 / u + table.direct(u)));
    }
    out.push_back(mx);
  }
  const std::lock_guard<std::mutex> lock(mutex);
  if (memo.size() >= 16) memo.erase(memo.begin());
  memo.emplace_back(key, out);
  return out;
}

// The distance beyond which |T| stays below eps (infinite when the sampled
// windows do not show it: the zones are then solved together): the start of
// the first window from which every later one (at least the last two) is
// below eps/8.
double quiet_distance(const ZoneKernel& K, double eps) {
  // A viscoelastic top: 1/u + K(u) keeps the memory's 1/u tail (the memory
  // part, taken apart, cancels it): the zones are solved together.
  if (K.model().memory() != nullptr) return kInf;
  const std::vector<double> w = kernel_windows(K);
  const int m = static_cast<int>(w.size());
  int first = m;
  while (first > 0 && w[static_cast<std::size_t>(first - 1)] <= eps / 8.0) --first;
  if (first > m - 2) return kInf;
  return std::ldexp(1.0, first - 1);
}

// The collocation system of one topology at one size N, and its state after
// eval(): per zone the nodal values G (p = sqrt(1 - r^2) G(r), absolute:
// units mu), the consistency constants and the loads.
class System {
 public:
  System(const ZonesParams& p, const std::vector<PunchProfile>& prof, const ZoneKernel& K, int n,
         double slope_scale)
      : p_(p),
        prof_(prof),
        K_(K),
        n_(n),
        nz_(static_cast<int>(p.zones.size())),
        np_(static_cast<int>(p.punches.size())),
        nd_(chebyshev_nodes(n)),
        S_(slope_scale),
        phi1_(K.model().phi1()),
        mem_(K.model().memory()) {
    // b = C G: b_m = 2 sum_i W_i U_m(r_i) G_i (exact for the degree-(N - 1) G).
    C_.resize(n, n);
    for (int i = 0; i < n; ++i) {
      double um1 = 0.0, u = 1.0;
      for (int m = 0; m < n; ++m) {
        C_(m, i) = 2.0 * nd_.w(i) * u;
        const double un = 2.0 * nd_.r(i) * u - um1;
        um1 = u;
        u = un;
      }
    }
    // Pairs of consecutive zones of one punch (the rigid-indentation conditions).
    for (int k = 0; k < np_; ++k) {
      int last = -1;
      for (int j = 0; j < nz_; ++j) {
        if (p.zones[static_cast<std::size_t>(j)].punch != k) continue;
        if (last >= 0) pairs_.emplace_back(last, j);
        last = j;
      }
    }
  }

  int unknowns() const { return 2 * nz_; }
  double phi1() const { return phi1_; }
  int n() const { return n_; }
  double centre(int j) const { return c_[static_cast<std::size_t>(j)]; }
  double half(int j) const { return w_[static_cast<std::size_t>(j)]; }
  const std::vector<std::pair<int, int>>& pairs() const { return pairs_; }
  int punch_of(int j) const { return p_.zones[static_cast<std::size_t>(j)].punch; }
  double slope(int k, double x) const {
    return prof_[static_cast<std::size_t>(k)].slope(x - p_.punches[static_cast<std::size_t>(k)].at);
  }
  double height(int k, double x) const {
    return prof_[static_cast<std::size_t>(k)].height(x -
                                                     p_.punches[static_cast<std::size_t>(k)].at);
  }
  // Coefficients b (U series) of zone j's G.
  Eigen::VectorXd coefficients(int j) const { return C_ * G_.col(j); }
  // A rounded flat's zone: its slope's kinks (the face's ends) leave G's
  // series a slow tail, b_m ~ m^-2, that the collocated terms do not hold.
  // Beyond them the series is the half-plane's, b_m = d_{m+1}/phi1 (the
  // zone's own Cauchy integral maps U_m onto T_{m+1}, d the slope's
  // T-coefficients on the zone), up to the layer's and the other zones'
  // coupling, negligible that far out, as on the single contact
  // (docs/theory.md sections 13 and 15.2).
  bool kinked(int j) const {
    return prof_[static_cast<std::size_t>(punch_of(j))].kind() == ProfileKind::rounded_flat;
  }
  // Zone j's slope coefficients d_0 .. d_{count-1} on the zone (relative to
  // its punch's axis; slope_chebyshev_at's convention, d_0 not halved).
  std::vector<double> slope_coefficients(int j, int count) const {
    const int k = punch_of(j);
    return prof_[static_cast<std::size_t>(k)].slope_chebyshev_at(
        centre(j) - p_.punches[static_cast<std::size_t>(k)].at, half(j), count);
  }
  // Zone j's series extended by that tail to `len` terms (a kinked zone's;
  // the collocated one otherwise), from its slope's coefficients d.
  static constexpr int kTailTerms = 4096;
  Eigen::VectorXd extended(int j, int len, const std::vector<double>& d) const {
    Eigen::VectorXd b = b_[static_cast<std::size_t>(j)].head(n_);
    if (!kinked(j) || n_ >= len) return b;
    b.conservativeResize(len);
    for (int m = n_; m < len; ++m) b(m) = d[static_cast<std::size_t>(m + 1)] / phi1_;
    return b;
  }
  Eigen::VectorXd extended(int j) const {
    return kinked(j) ? extended(j, kTailTerms, slope_coefficients(j, kTailTerms + 1))
                     : b_[static_cast<std::size_t>(j)];
  }
  // Zone j's series for the outputs: extended to kTailTerms after
  // extend_all (a kinked zone's), the collocated one otherwise.
  const Eigen::VectorXd& series(int j) const {
    const Eigen::VectorXd& e = ext_[static_cast<std::size_t>(j)];
    return e.size() > 0 ? e : b_[static_cast<std::size_t>(j)];
  }
  // After extend_all: a kinked zone's slope coefficients d_0 .. d_{4 kTailTerms}
  // (its drag's), and a bound on what its extended series leaves out,
  // sum |b_m| beyond kTailTerms (|sqrt(1 - r^2) U_m| <= 1): d summed to
  // 4 kTailTerms, the closed-form bound beyond (PunchProfile::slope_chebyshev_tail).
  const std::vector<double>& slope_coefficients(int j) const {
    return dl_[static_cast<std::size_t>(j)];
  }
  double truncation(int j) const { return trunc_[static_cast<std::size_t>(j)]; }
  void extend_all() {
    ext_.assign(static_cast<std::size_t>(nz_), Eigen::VectorXd());
    dl_.assign(static_cast<std::size_t>(nz_), std::vector<double>());
    trunc_.assign(static_cast<std::size_t>(nz_), 0.0);
    for (int j = 0; j < nz_; ++j) {
      if (!kinked(j) || n_ >= kTailTerms) continue;
      const auto ju = static_cast<std::size_t>(j);
      dl_[ju] = slope_coefficients(j, 4 * kTailTerms + 1);
      ext_[ju] = extended(j, kTailTerms, dl_[ju]);
      const int k = punch_of(j);
      double sum = prof_[static_cast<std::size_t>(k)].slope_chebyshev_tail(
          centre(j) - p_.punches[static_cast<std::size_t>(k)].at, half(j), 4 * kTailTerms);
      for (std::size_t m = kTailTerms + 1; m < dl_[ju].size(); ++m) sum += std::fabs(dl_[ju][m]);
      trunc_[ju] = sum / std::fabs(phi1_);
    }
  }
  double load(int j) const { return loads_(j); }
  // A kinked zone's Cauchy integral beyond its collocated terms at a point
  // beside it, sum_{m >= n} b_m q^(m+1) = (1/phi1) sum_{k > n} d_k q^k (the
  // whole tail, not only kTailTerms): for |q| > 1/2 from the slope's Poisson
  // sum in closed form less its first terms, else from d_{n+1} ..
  // d_{n+kShort} (what is left below 2^-70 of sum |d|). qn = q^(n+1).
  static constexpr int kShort = 64;
  double kinked_tail(int j, double q, double qn) const {
    const std::vector<double>& d = d_[static_cast<std::size_t>(j)];
    double tail = 0.0;
    if (std::fabs(q) > 0.5) {
      const int k = punch_of(j);
      tail = prof_[static_cast<std::size_t>(k)].slope_chebyshev_poisson(
          centre(j) - p_.punches[static_cast<std::size_t>(k)].at, half(j), q);
      double qk = 1.0, head = 0.0;  // d_0/2 + sum_{k <= n} d_k q^k (d_0 halved in d_)
      for (int m = 0; m <= n_; ++m) {
        head += d[static_cast<std::size_t>(m)] * qk;
        qk *= q;
      }
      tail -= head;
    } else {
      double qk = qn;
      for (std::size_t m = static_cast<std::size_t>(n_) + 1; m < d.size(); ++m) {
        tail += d[m] * qk;
        qk *= q;
      }
    }
    return tail / phi1_;
  }

  // Sets the ends e = (l_0, r_0, l_1, ...) and solves; F the scaled end
  // conditions. False when the ends are not admissible (a zone inverted,
  // zones overlapping, a zone beyond its table) or the system is singular.
  bool eval(const Eigen::VectorXd& e, Eigen::VectorXd& F) {
    check_interrupt();  // Ctrl-C (interrupt.hpp): a solve per evaluation
    c_.assign(static_cast<std::size_t>(nz_), 0.0);
    w_.assign(static_cast<std::size_t>(nz_), 0.0);
    for (int j = 0; j < nz_; ++j) {
      const double l = e(2 * j), r = e(2 * j + 1);
      if (!(r > l) || !std::isfinite(l) || !std::isfinite(r)) return false;
      if (j > 0 && !(l > e(2 * j - 1))) return false;
      const int k = punch_of(j);
      const PunchProfile& pf = prof_[static_cast<std::size_t>(k)];
      const double at = p_.punches[static_cast<std::size_t>(k)].at;
      if (l - at < pf.lower() || r - at > pf.upper()) return false;
      c_[static_cast<std::size_t>(j)] = 0.5 * (l + r);
      w_[static_cast<std::size_t>(j)] = 0.5 * (r - l);
    }
    const int n = n_, rows = nz_ * (n + 1), cols = nz_ * (n + 1);
    // (A zone's last matrix blocks stand when its centre and half-width are
    // those of the last evaluation that built the matrix, bit for bit.)
    auto same_zone = [&](int i) {
      const auto ui = static_cast<std::size_t>(i);
      return M_.rows() == rows && mc_.size() == c_.size() && mc_[ui] == c_[ui] && mw_[ui] == w_[ui];
    };
    d_.assign(static_cast<std::size_t>(nz_), std::vector<double>());
    ext_.assign(static_cast<std::size_t>(nz_), Eigen::VectorXd());
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(rows, cols);
    Eigen::VectorXd rhs(rows);
    // The kernel's values, zone pair by zone pair, in one batch each.
    std::vector<double> u(static_cast<std::size_t>(n) * (n + 1)), kv(u.size());
    Eigen::MatrixXd Z(n + 1, n);
    for (int j = 0; j < nz_; ++j) {
      const double cj = c_[static_cast<std::size_t>(j)], wj = w_[static_cast<std::size_t>(j)];
      const int pj = punch_of(j);
      const PunchProfile& pf = prof_[static_cast<std::size_t>(pj)];
      if (kinked(j)) {
        // The slope's projection onto T_0 .. T_n: its kinks at the face's
        // ends would alias its Chebyshev tail onto the values (as on the
        // single contact, docs/theory.md section 13). d_0 .. d_{n + kShort}
        // are kept for vslope.
        std::vector<double>& d = d_[static_cast<std::size_t>(j)];
        d = pf.slope_chebyshev_at(cj - p_.punches[static_cast<std::size_t>(pj)].at, wj,
                                  n + kShort + 1);
        d[0] *= 0.5;
        for (int k = 0; k <= n; ++k)
          rhs(j * (n + 1) + k) = detail::chebyshev_sum(d.data(), n, nd_.s(k));
      } else {
        for (int k = 0; k <= n; ++k) rhs(j * (n + 1) + k) = slope(pj, cj + wj * nd_.s(k));
      }
      for (int i = 0; i < nz_; ++i) {
        const double ci = c_[static_cast<std::size_t>(i)], wi = w_[static_cast<std::size_t>(i)];
        auto block = M.block(j * (n + 1), i * (n + 1), n + 1, n);
        // A block depends on zones i and j alone: kept from the last
        // evaluation when neither moved (a finite-difference Jacobian moves
        // one end at a time).
        if (same_zone(i) && same_zone(j)) {
          block = M_.block(j * (n + 1), i * (n + 1), n + 1, n);
          continue;
        }
        for (int q = 0; q < n; ++q)
          for (int k = 0; k <= n; ++k)
            u[static_cast<std::size_t>(q) * (n + 1) + k] = cj + wj * nd_.s(k) - ci - wi * nd_.r(q);
        K_.many(u.data(), kv.data(), u.size());
        for (int q = 0; q < n; ++q)
          for (int k = 0; k <= n; ++k)
            block(k, q) = phi1_ * nd_.w(q) * wi * kv[static_cast<std::size_t>(q) * (n + 1) + k];
        if (i == j) {
          for (int q = 0; q < n; ++q)
            for (int k = 0; k <= n; ++k) block(k, q) += phi1_ * nd_.w(q) / (nd_.s(k) - nd_.r(q));
        } else {
          // (1/pi) int sqrt(1 - r^2) U_m(r)/(z - r) dr = q^(m+1), q = z - sgn(z) sqrt(z^2 - 1).
          for (int k = 0; k <= n; ++k) {
            const double z = (cj + wj * nd_.s(k) - ci) / wi;
            if (!(std::fabs(z) > 1.0)) return false;
            const double qz = z - std::copysign(std::sqrt((z - 1.0) * (z + 1.0)), z);
            double qm = qz;
            for (int m = 0; m < n; ++m) {
              Z(k, m) = qm;
              qm *= qz;
            }
          }
          block.noalias() += phi1_ * (Z * C_);
        }
        if (mem_ != nullptr) {
          // The memory of the material ahead: zone i's density at zone j's
          // points in zone i's frame (the single contact's block, negated as
          // the zones' equation is: -phi1 times the asymmetric row).
          if (i == j) {
            block.noalias() -= phi1_ * mem_->collocation_block(nd_, wi);
          } else {
            std::vector<double> at(static_cast<std::size_t>(n) + 1);
            for (int k = 0; k <= n; ++k)
              at[static_cast<std::size_t>(k)] = (cj + wj * nd_.s(k) - ci) / wi;
            block.noalias() -= phi1_ * mem_->block_at(at.data(), n + 1, nd_, wi);
          }
        }
      }
      M.block(j * (n + 1), j * (n + 1) + n, n + 1, 1).setOnes();
    }
    M_ = M;
    mc_ = c_;
    mw_ = w_;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
    const Eigen::VectorXd x = lu.solve(rhs);
    if (!x.allFinite()) return false;
    G_.resize(n, nz_);
    eps_.resize(nz_);
    loads_.resize(nz_);
    for (int j = 0; j < nz_; ++j) {
      G_.col(j) = x.segment(j * (n + 1), n);
      eps_(j) = x(j * (n + 1) + n);
      loads_(j) = kPi * w_[static_cast<std::size_t>(j)] * nd_.w.dot(G_.col(j));
    }
    b_.resize(nz_);
    for (int j = 0; j < nz_; ++j) b_[static_cast<std::size_t>(j)] = C_ * G_.col(j);
    F.resize(2 * nz_);
    int row = 0;
    for (int j = 0; j < nz_; ++j) F(row++) = eps_(j) / S_;
    for (int k = 0; k < np_; ++k) {
      double sum = 0.0;
      for (int j = 0; j < nz_; ++j)
        if (punch_of(j) == k) sum += loads_(j);
      const double P = p_.punches[static_cast<std::size_t>(k)].load;
      F(row++) = (sum - P) / P;
    }
    for (const auto& [j, jn] : pairs_) {
      const double a = e(2 * j + 1), b = e(2 * jn);
      const int k = punch_of(j);
      const double jump = gap_integral(a, b) - (height(k, b) - height(k, a));
      F(row++) = jump / (S_ * (w_[static_cast<std::size_t>(j)] + w_[static_cast<std::size_t>(jn)]));
    }
    return F.allFinite();
  }

  // v'(x, 0) of the current state, any x (inside a zone: the principal
  // value): phi1 sum_i [Cauchy_i(x) + w_i kern_i(x)] over the zones. Without
  // `kernel` the kernel's part is left out: kernel_part, smooth (the gap
  // checks interpolate it).
  double vslope(double x, bool kernel = true) const {
    double sum = 0.0;
    for (int i = 0; i < nz_; ++i) {
      const double ci = c_[static_cast<std::size_t>(i)], wi = w_[static_cast<std::size_t>(i)];
      const Eigen::VectorXd& b = b_[static_cast<std::size_t>(i)];
      const double z = (x - ci) / wi;
      double cauchy = 0.0;
      if (std::fabs(z) <= 1.0) {
        // (Inside a zone: the collocated terms; a kinked zone's extended
        // series once extend_all has run.)
        const Eigen::VectorXd& bs = series(i);
        double tkm1 = 1.0, tk = z;
        for (Eigen::Index m = 0; m < bs.size(); ++m) {
          cauchy += bs(m) * tk;
          const double tn = 2.0 * z * tk - tkm1;
          tkm1 = tk;
          tk = tn;
        }
      } else {
        const double qz = z - std::copysign(std::sqrt((z - 1.0) * (z + 1.0)), z);
        double qm = qz;
        for (int m = 0; m < n_; ++m) {
          cauchy += b(m) * qm;
          qm *= qz;
        }
        if (kinked(i)) cauchy += kinked_tail(i, qz, qm);
      }
      sum += kernel ? cauchy + wi * zone_kernel(i, x) : cauchy;
      // A viscoelastic top's memory of zone i (exact; not in kernel_part:
      // it has the pressure's square root at the zone's ends).
      if (mem_ != nullptr) sum += mem_->apply(b, z, wi);
    }
    return phi1_ * sum;
  }
  // sum_i w_i kern_i(x): the kernel's part of v'(x)/phi1 (the regular kernel
  // K is analytic in a strip about the real axis: smooth on every zone).
  double kernel_part(double x) const {
    double sum = 0.0;
    for (int i = 0; i < nz_; ++i) sum += w_[static_cast<std::size_t>(i)] * zone_kernel(i, x);
    return sum;
  }
  // kern_i(x) = sum_q W_q G_qi K(x - c_i - w_i r_q): zone i's Gauss-Chebyshev
  // sum of its density against the regular kernel.
  double zone_kernel(int i, double x) const {
    thread_local std::vector<double> u, kv;
    u.resize(static_cast<std::size_t>(n_));
    kv.resize(u.size());
    const double ci = c_[static_cast<std::size_t>(i)], wi = w_[static_cast<std::size_t>(i)];
    for (int q = 0; q < n_; ++q) u[static_cast<std::size_t>(q)] = x - ci - wi * nd_.r(q);
    K_.many(u.data(), kv.data(), u.size());
    double kern = 0.0;
    for (int q = 0; q < n_; ++q) kern += nd_.w(q) * G_(q, i) * kv[static_cast<std::size_t>(q)];
    return kern;
  }

  // int_a^b v'(x) dx between two zone ends (v' has square-root cusps at
  // both: x = m - h cos(theta), 16 panels of 8 Gauss points in theta).
  double gap_integral(double a, double b) const {
    const double mid = 0.5 * (a + b), hh = 0.5 * (b - a);
    const Legendre& gl = gauss_legendre8();
    double sum = 0.0;
    constexpr int panels = 16;
    for (int pnl = 0; pnl < panels; ++pnl) {
      const double t0 = kPi * pnl / panels, th = 0.5 * kPi / panels;
      for (std::size_t g = 0; g < gl.x.size(); ++g) {
        const double t = t0 + th * (1.0 + gl.x[g]);
        sum += th * gl.w[g] * hh * std::sin(t) * vslope(mid - hh * std::cos(t));
      }
    }
    return sum;
  }

 private:
  const ZonesParams& p_;
  const std::vector<PunchProfile>& prof_;
  const ZoneKernel& K_;
  int n_, nz_, np_;
  ChebyshevNodes nd_;
  double S_, phi1_;
  // A viscoelastic top's memory (null: none), taken exactly against every
  // zone's density at every zone's points (MemoryKernel::block_at).
  const MemoryKernel* mem_;
  Eigen::MatrixXd C_, G_;
  Eigen::VectorXd eps_, loads_;
  std::vector<Eigen::VectorXd> b_, ext_;  // collocated; a kinked zone's extended (extend_all)
  std::vector<std::vector<double>> d_;    // a kinked zone's slope coefficients (d_0 halved)
  std::vector<std::vector<double>> dl_;   // the same to 4 kTailTerms (extend_all; d_0 whole)
  std::vector<double> trunc_;             // extend_all's truncation bounds
  std::vector<double> c_, w_;
  // The last matrix built and the zones it was built for (eval's cache).
  Eigen::MatrixXd M_;
  std::vector<double> mc_, mw_;
  std::vector<std::pair<int, int>> pairs_;
};

// Newton's method on the ends from e (in place); evaluations counted. J: the
// Jacobian of the scaled conditions (in the ends), reused from the previous
// size when `have_j` (the conditions are scaled alike at every size) and
// updated by Broyden's rule after each step; recomputed by forward
// differences when a step fails with an updated one.
// `mirror`: the problem and the start are symmetric about x = 0 (one
// symmetric punch at 0 without damping): every step is made symmetric (the
// ends' mirror images move alike), so that the iteration cannot wander to
// an asymmetric spurious root of the end conditions.
// Returns the ends' uncertainty left by the iteration: twice the next step,
// |J^-1 F| at the accepted ends (J the last Jacobian, maybe updated; the
// residual is accepted up to 1e-9, or 1e-8 at a measured round-off floor,
// and an ill-conditioned J carries that into the ends).
double newton(System& sys, Eigen::VectorXd& e, int& evaluations, Eigen::MatrixXd& J, bool& have_j,
              int max_iterations, bool mirror = false) {
  const int m = sys.unknowns();
  auto symmetric = [&](Eigen::VectorXd& v) {
    if (mirror) v = (0.5 * (v - v.reverse())).eval();
  };
  symmetric(e);
  Eigen::VectorXd F, Ft;
  if (!sys.eval(e, F))
    throw ConvergenceError("several contact zones: the starting zones are not admissible (N = " +
                           std::to_string(sys.n()) + ")");
  ++evaluations;
  double norm = F.lpNorm<Eigen::Infinity>();
  if (J.rows() != m) have_j = false;
  bool fresh = false;
  bool at_e = true;  // the system's state is that of the ends e
  auto jacobian = [&] {
    J.resize(m, m);
    for (int q = 0; q < m; ++q) {
      const int j = q / 2;
      const double h = 1e-7 * std::max(0.5 * (e(2 * j + 1) - e(2 * j)), 1e-9);
      const double out = q % 2 == 0 ? -h : h;  // widen the zone: stays admissible
      Eigen::VectorXd et = e;
      et(q) += out;
      if (!sys.eval(et, Ft)) {
        et(q) = e(q) - out;
        if (!sys.eval(et, Ft))
          throw ConvergenceError("several contact zones: no admissible Jacobian step (N = " +
                                 std::to_string(sys.n()) + ")");
        J.col(q) = (F - Ft) / out;
      } else {
        J.col(q) = (Ft - F) / out;
      }
      ++evaluations;
    }
    have_j = true;
    fresh = true;
    at_e = false;
  };
  // The conditions' round-off floor at e: how far F moves beyond its
  // linear change J d when the ends move by a few ulps of the hull (the
  // noise of the dense solve, the kernel's evaluation and the gap's
  // quadrature at this N), the larger of two such moves. Needs a fresh J.
  auto noise_floor = [&] {
    if (!at_e) {
      if (!sys.eval(e, F)) return kInf;
      ++evaluations;
      at_e = true;
    }
    const double step = 64.0 * kEps * (e(m - 1) - e(0));
    double noise = 0.0;
    for (int k = 0; k < 2; ++k) {
      Eigen::VectorXd d(m);
      for (int q = 0; q < m; ++q) d(q) = (q + k) % 2 == 0 ? step : -step;
      symmetric(d);
      at_e = false;
      if (!sys.eval(e + d, Ft)) return kInf;
      ++evaluations;
      noise = std::max(noise, (Ft - F - J * d).lpNorm<Eigen::Infinity>());
    }
    return noise;
  };
  // Progress: the residual halves at least once every kStallWindow
  // iterations, or the topology is refused (a stiff foundation's wrong
  // topology wandered for its 200 iterations at N = 24: 104 s to refuse).
  constexpr int kStallWindow = 30;
  bool at_floor = false;
  double best = norm;
  int since_best = 0;
  for (int it = 0; it < max_iterations; ++it) {
    if (norm < 1e-14) break;
    if (norm < 0.5 * best) {
      best = norm;
      since_best = 0;
    } else if (++since_best > kStallWindow && !(norm < 1e-8)) {
      // (Below 1e-8 the line search's own stall test, at the measured
      // round-off floor, decides.)
      std::ostringstream msg;
      msg << "several contact zones: the end conditions were not met (residual " << norm
          << " after " << kStallWindow << " iterations without halving it, N = " << sys.n() << ")";
      throw ConvergenceError(msg.str());
    }
    if (!have_j) jacobian();
    Eigen::VectorXd dx = J.fullPivLu().solve(-F);
    symmetric(dx);
    if (!dx.allFinite()) {
      if (!fresh) {
        have_j = false;
        continue;
      }
      throw ConvergenceError(
          "several contact zones: singular Jacobian (N = " + std::to_string(sys.n()) + ")");
    }
    // Keep every zone and every gap above a tenth of its present size.
    double t = 1.0;
    for (int j = 0; j < m / 2; ++j) {
      const double w = e(2 * j + 1) - e(2 * j), dw = dx(2 * j + 1) - dx(2 * j);
      if (dw < 0.0) t = std::min(t, 0.9 * w / -dw);
      if (j > 0) {
        const double g = e(2 * j) - e(2 * j - 1), dg = dx(2 * j) - dx(2 * j - 1);
        if (dg < 0.0) t = std::min(t, 0.9 * g / -dg);
      }
    }
    bool accepted = false;
    for (int bt = 0; bt < 40; ++bt, t *= 0.5) {
      const Eigen::VectorXd en = e + t * dx;
      at_e = false;
      if (!sys.eval(en, Ft)) continue;
      ++evaluations;
      const double nn = Ft.lpNorm<Eigen::Infinity>();
      if (nn < (1.0 - 1e-4 * t) * norm || nn < 1e-14) {
        const Eigen::VectorXd s = t * dx;
        J += ((Ft - F) - J * s) * s.transpose() / s.squaredNorm();  // Broyden
        fresh = false;
        // A short or weak step: the next one from a new Jacobian.
        if (t < 1.0 || nn > 0.25 * norm) have_j = false;
        e = en;
        F = Ft;
        norm = nn;
        accepted = true;
        at_e = true;
        break;
      }
    }
    if (accepted) {
      // A zone or a gap shrinking to nothing: this topology is not the
      // contact set (the zones merge, or one vanishes); said at once, not
      // after the ladder's largest sizes at an ill-conditioned solution.
      const double hull = e(m - 1) - e(0);
      for (int j = 0; j < m / 2; ++j) {
        if (!(e(2 * j + 1) - e(2 * j) > 1e-7 * hull))
          throw ConvergenceError("several contact zones: zone " + std::to_string(j + 1) +
                                 " closed (N = " + std::to_string(sys.n()) + ")");
        if (j > 0 && !(e(2 * j) - e(2 * j - 1) > 1e-7 * hull))
          throw ConvergenceError("several contact zones: the gap between zones " +
                                 std::to_string(j) + " and " + std::to_string(j + 1) +
                                 " closed: they merge (N = " + std::to_string(sys.n()) + ")");
      }
    }
    if (!accepted) {
      if (!fresh) {  // an updated Jacobian misled: a new one
        have_j = false;
        continue;
      }
      if (norm < 1e-10) break;  // at the round-off floor of the conditions
      // Above 1e-10 (stiff foundations, large N): at the floor measured
      // here, within 1e-8 (the final check below).
      const double noise = norm < 1e-8 ? noise_floor() : kInf;
      if (norm <= 16.0 * noise) {
        at_floor = true;
        break;
      }
      std::ostringstream msg;
      msg << "several contact zones: Newton's method stalled at residual " << norm;
      if (std::isfinite(noise)) msg << " (its round-off floor " << noise << ")";
      msg << " (N = " << sys.n() << ")";
      throw ConvergenceError(msg.str());
    }
    if (t == 1.0 && dx.lpNorm<Eigen::Infinity>() <= 4.0 * kEps * e.lpNorm<Eigen::Infinity>()) break;
  }
  // The state of the solution (the last evaluation may have been a trial).
  if (!at_e) {
    if (!sys.eval(e, F)) throw ConvergenceError("several contact zones: lost the solution");
    ++evaluations;
  }
  // Met: below 1e-9, or at the floor measured above (a stiff foundation's
  // conditions at N = 48 stopped at 1.0016e-9, their round-off).
  if (!(F.lpNorm<Eigen::Infinity>() < (at_floor ? 1e-8 : 1e-9))) {
    std::ostringstream msg;
    msg << "several contact zones: the end conditions were not met (residual "
        << F.lpNorm<Eigen::Infinity>() << ", N = " << sys.n() << ")";
    throw ConvergenceError(msg.str());
  }
  // At the conditions' round-off (the iteration's own first test) the step
  // is round-off too; otherwise a Jacobian is at hand or made.
  if (!(F.lpNorm<Eigen::Infinity>() >= 1e-14)) return 0.0;
  if (J.rows() != m) jacobian();
  Eigen::VectorXd dx = J.fullPivLu().solve(-F);
  symmetric(dx);
  const double step = 2.0 * dx.lpNorm<Eigen::Infinity>();
  return std::isfinite(step) ? step : kInf;
}

}  // namespace

namespace {

// A viscoelastic medium's power over P V for one group of zones (its loads
// `loads`, their sum `total`): by Parseval, (total/pi) int_0^inf Im M1 |p^|^2,
// p^ = sum_j (P_j/total) p_j^. Im (M1 - H) on the kernel's panels (split
// to resolve the group's span: it decays exponentially); a viscoelastic
// top's Im H = phi1 sum_k c_k beta_k t/(1 + beta_k^2 t^2), slow, to T (from
// 2000 over the narrowest zone, doubled until the total with the tail beyond
// T changes by less than 1e-12 of it) by zones: each zone's |P_j|^2 and each
// pair's cross term (Filon in the phase of their distance; below), and
// beyond T each zone's |p_j^|^2 by its leading term (pi/4)(A_a^2 +
// A_b^2)/t^3 (the single contact's, AsymmetricSolution::dissipation; the
// cross terms oscillate with the zones' distances and leave 1/(T^3
// distance) there).
double viscoelastic_group_power(const AsymmetricKernel& K,
                                const std::vector<AsymmetricSolution>& parts,
                                const std::vector<const ZoneResult*>& zones,
                                const std::vector<double>& loads, double total, double lo,
                                double hi) {
  const Medium& model = K.model();
  const Legendre& gl = gauss_legendre8();
  const double width = std::min(0.5, 1.5 / std::max(hi - lo, 1e-300));
  auto transform = [&](double a) {
    cplx ph = 0.0;
    for (std::size_t j = 0; j < parts.size(); ++j)
      ph += (loads[j] / total) * parts[j].pressure_transform(a);
    return ph;
  };
  const auto& P = K.quadrature().panels;
  double sum = 0.0;
  for (std::size_t p = 0; p < P.panel_centre.size(); ++p) {
    const double a0 = P.panel_centre[p] - P.panel_half[p], len = 2.0 * P.panel_half[p];
    const int m = std::max(1, static_cast<int>(std::ceil(len / width)));
    for (int q = 0; q < m; ++q) {
      check_interrupt();
      const double c = a0 + (q + 0.5) * len / m, h = 0.5 * len / m;
      for (std::size_t gg = 0; gg < gl.x.size(); ++gg) {
        const double a = c + h * gl.x[gg];
        sum += h * gl.w[gg] * (model.full_response(a).M1 - model.half_plane_m1(a)).imag() *
               std::norm(transform(a));
      }
    }
  }
  const MemoryKernel* mem = model.memory();
  if (mem == nullptr) return total * sum / kPi;
  const RetardationSpectrum& sp = mem->spectrum();
  const double phi1 = model.phi1();
  auto im_h = [&](double t) {
    double v = 0.0;
    for (std::size_t k = 0; k < sp.c.size(); ++k)
      v += sp.c[k] * sp.beta[k] * t / (1.0 + sp.beta[k] * sp.beta[k] * t * t);
    return phi1 * v;
  };
  double wmin = kInf, ends = 0.0;
  for (std::size_t j = 0; j < zones.size(); ++j) {
    const ZoneResult& z = *zones[j];
    wmin = std::min(wmin, z.half);
    double ga = 0.0, gb = 0.0;  // g(1), g(-1) of the zone's unit-load series
    for (Eigen::Index n = 0; n < z.b.size(); ++n) {
      ga += z.b(n) * static_cast<double>(n + 1);
      gb += z.b(n) * static_cast<double>(n + 1) * ((n % 2) ? -1.0 : 1.0);
    }
    const double f = loads[j] / total;
    ends += f * f * 0.25 * kPi * (2.0 / z.half) * (ga * ga + gb * gb);
  }
  auto tail_beyond = [&](double T) {
    double t = 0.0;
    for (std::size_t k = 0; k < sp.c.size(); ++k)
      t += sp.c[k] * memory_tail_integral(sp.beta[k], T);
    return t * phi1 * ends;
  };
  // The memory part by zones: each zone's |P_j|^2 (P_j = p_j^ e^{i alpha c_j},
  // centred: it oscillates only with the zone's own width) by Gauss-Kronrod
  // panels, and each pair's P_j conj(P_k) e^{-i alpha (c_j - c_k)} by Filon
  // on the same panels (exact in the phase of their distance, however far
  // apart the zones lie).
  const double beta_max = *std::max_element(sp.beta.begin(), sp.beta.end());
  double wmax = 0.0;
  for (const ZoneResult* z : zones) wmax = std::max(wmax, z->half);
  const double zone_width = std::min(0.5, 1.5 / (2.0 * wmax));
  const std::size_t nzone = parts.size();
  std::vector<double> centres(nzone);
  for (std::size_t j = 0; j < nzone; ++j) centres[j] = parts[j].centre();
  // The panels and each zone's P_j at their nodes, extended as T doubles
  // (the nodes already evaluated are kept).
  AlphaQuadrature q;
  std::vector<std::vector<cplx>> pz(nzone);
  std::vector<double> ih;
  double a0 = 0.0, a1 = std::min(zone_width, 1e-3 / beta_max);
  auto memory_sum = [&](double T) {
    while (a0 < T) {
      const double c = 0.5 * (a0 + a1), h = 0.5 * (a1 - a0);
      q.panel_centre.push_back(c);
      q.panel_half.push_back(h);
      check_interrupt();
      for (int j = 0; j < 15; ++j) {
        const double t = detail::gk_node(j, c, h);
        q.alpha.push_back(t);
        q.weight.push_back(detail::gk_weight(j, h));
        ih.push_back(im_h(t));
        for (std::size_t z = 0; z < nzone; ++z)
          pz[z].push_back((loads[z] / total) * parts[z].pressure_transform(t) *
                          std::exp(cplx(0.0, t * centres[z])));
      }
      a0 = a1;
      a1 = std::min({T, 2.0 * a0, a0 + zone_width});
    }
    const std::size_t nq = q.alpha.size();
    double sum_mem = 0.0;
    for (std::size_t i = 0; i < nq; ++i) {
      double d = 0.0;
      for (std::size_t j = 0; j < nzone; ++j) d += std::norm(pz[j][i]);
      sum_mem += q.weight[i] * ih[i] * d;
    }
    if (nzone > 1) {
      const FilonIntegrator filon(q);
      std::vector<double> gr(nq), gi(nq);
      for (std::size_t j = 0; j < nzone; ++j)
        for (std::size_t k = j + 1; k < nzone; ++k) {
          for (std::size_t i = 0; i < nq; ++i) {
            const cplx g = ih[i] * pz[j][i] * std::conj(pz[k][i]);
            gr[i] = g.real();
            gi[i] = g.imag();
          }
          // 2 Re int g e^{-i alpha d}, d = c_j - c_k: int gr cos(alpha d) + int gi sin(alpha d).
          const double d = centres[j] - centres[k];
          const cplx ir = filon.integral(d, filon.coefficients(gr));
          const cplx ii = filon.integral(d, filon.coefficients(gi));
          sum_mem += 2.0 * (ir.real() + ii.imag());
        }
    }
    return sum_mem;
  };
  double T = 2000.0 / wmin, last = std::numeric_limits<double>::quiet_NaN();
  for (;;) {
    const double now = memory_sum(T) + tail_beyond(T);
    const auto panels = static_cast<long>(q.panel_centre.size());
    const double change = std::fabs(now - last) / std::fabs(sum + now);
    if (change <= (panels > (1L << 16) ? 1e-10 : 1e-12)) return total * (sum + now) / kPi;
    if (panels > (1L << 16)) {
      std::ostringstream m;
      m << "dissipation: the Parseval integral of the viscoelastic memory over the zones did "
           "not settle within 2^16 panels (reach alpha h = "
        << T << ", last change " << change << " of the total); the drag, from the pressure, stands";
      throw ConvergenceError(m.str());
    }
    last = now;
    T *= 2.0;
  }
}

}  // namespace

double zones_dissipation(const ZonesSolution& s) {
  if (s.zones.empty()) return 0.0;
  const bool visco = s.zones.front().params.medium && s.zones.front().params.medium->viscoelastic();
  if (!visco && !(s.zones.front().params.damping > 0.0)) return 0.0;
  // Groups solved apart (too far apart to interact) dissipate apart: the
  // cross terms of |sum p^|^2 are those of their interaction.
  double all = 0.0;
  int groups = 0;
  for (const ZoneResult& z : s.zones) {
    all += z.load;
    groups = std::max(groups, z.group + 1);
  }
  double out = 0.0;
  for (int g = 0; g < groups; ++g) {
    const ZoneResult* first = nullptr;
    std::vector<AsymmetricSolution> parts;
    std::vector<const ZoneResult*> members;
    std::vector<double> loads;
    double total = 0.0, lo = kInf, hi = -kInf;
    for (const ZoneResult& z : s.zones) {
      if (z.group != g) continue;
      if (first == nullptr) first = &z;
      // Each zone relative to the group's first (its phases e^{-i alpha x} small).
      const double c = (z.origin - first->origin) + z.offset;
      parts.push_back(zone_solution(z.params, z.kernel, c, z.half, z.b, z.head));
      members.push_back(&z);
      loads.push_back(z.load);
      total += z.load;
      lo = std::min(lo, c - z.half);
      hi = std::max(hi, c + z.half);
    }
    if (first == nullptr) continue;
    const AsymmetricKernel& K = *first->kernel;
    if (visco) {
      out += (total / all) * viscoelastic_group_power(K, parts, members, loads, total, lo, hi);
      continue;
    }
    const Medium& model = K.model();
    // |p^|^2 oscillates with the distances between the zones: pieces of at
    // most 1.5/(hi - lo) (and 0.5) in alpha, 8 Gauss points each.
    const Legendre& gl = gauss_legendre8();
    const auto& P = K.quadrature().panels;
    const double width = std::min(0.5, 1.5 / std::max(hi - lo, 1e-300));
    double sum = 0.0;
    for (std::size_t p = 0; p < P.panel_centre.size(); ++p) {
      const double a0 = P.panel_centre[p] - P.panel_half[p], len = 2.0 * P.panel_half[p];
      const int m = std::max(1, static_cast<int>(std::ceil(len / width)));
      for (int q = 0; q < m; ++q) {
        const double c = a0 + (q + 0.5) * len / m, h = 0.5 * len / m;
        for (std::size_t gg = 0; gg < gl.x.size(); ++gg) {
          const double a = c + h * gl.x[gg];
          cplx ph = 0.0;
          for (std::size_t j = 0; j < parts.size(); ++j)
            ph += (loads[j] / total) * parts[j].pressure_transform(a);
          sum += h * gl.w[gg] * std::norm(model.full_response(a).Wb * ph);
        }
      }
    }
    out += (total / all) * model.base_damper() * total * sum / kPi;
  }
  return out;
}

AsymmetricSolution ZoneResult::solution() const {
  return zone_solution(params, kernel, offset, half, b, head);
}

namespace {

// The spacing of doubles at |x| (its unit in the last place).
double ulp(double x) {
  x = std::fabs(x);
  return std::nextafter(x, kInf) - x;
}

// The checks of solve_zones' input; the punches' profiles.
std::vector<PunchProfile> validate_zones(const ZonesParams& prm) {
  if (prm.layer.medium) {
    // The medium's own checks and refusals (as solve_asymmetric's), then its
    // scalars as the homogeneous layer's below.
    validate_asymmetric_medium(*prm.layer.medium);
  }
  const AsymmetricParams L = with_medium_scalars(prm.layer);
  require_in_range("vstar", L.vstar, 0.0, 1.0, false, true);
  require_in_range("kw", L.kw, 1e-12, kInf, false, false, true);
  require_in_range("nu", L.nu, 0.0, 0.5, false, true);
  require_in_range("damping", L.damping, 0.0, kInf, false, true);
  require_in_range("kp", L.kp, 0.0, kMaxKp, false, false);
  require_in_range("tol", L.tol, 1e-14, 1e-2, false, false);
  if (L.friction != 0.0)
    throw InvalidParameter(
        "friction", "0 (several zones are frictionless)",
        "several contact zones: friction must be 0, got " + std::to_string(L.friction));
  if (L.n != 0 && (L.n < 8 || L.n > 256 || L.n % 2 != 0))
    throw InvalidParameter("n", "0 (automatic) or an even integer in [8, 256]",
                           "n must be 0 (automatic) or an even integer in [8, 256] for several "
                           "zones, got " +
                               std::to_string(L.n));
  if (prm.punches.empty()) throw InvalidParameter("punches", "at least one", "no punches given");
  std::vector<PunchProfile> prof;
  for (const ZonePunch& pk : prm.punches) {
    require_in_range("load", pk.load, 0.0, kInf, true, true);
    if (!std::isfinite(pk.at))
      throw InvalidParameter("at", "finite", "a punch's position `at` must be finite");
    prof.push_back(pk.punch());
    if (prm.layer.medium && prm.layer.medium->viscoelastic() &&
        prof.back().kind() == ProfileKind::rounded_flat)
      throw InvalidParameter("profile",
                             "a smooth punch (cylinder or convex table) on a viscoelastic medium",
                             "several contact zones: a rounded flat punch on a viscoelastic "
                             "medium is not solved yet (the memory at the face's kinks is not "
                             "resolved); cylinders and convex tables are");
    if (prof.back().singular_ends())
      throw InvalidParameter("profile", "a profile with bounded ends (not a flat punch)",
                             "several contact zones: a flat punch's contact is its face; trains "
                             "take cylinders, rounded flats and tables");
  }
  const int nz = static_cast<int>(prm.zones.size());
  std::vector<int> count(prm.punches.size(), 0);
  for (int j = 0; j < nz; ++j) {
    const ZoneSpan& z = prm.zones[static_cast<std::size_t>(j)];
    if (z.punch < 0 || z.punch >= static_cast<int>(prm.punches.size()))
      throw InvalidParameter("zones", "punch indices in range", "a zone names no punch");
    // Far from x = 0 the doubles are too sparse for a zone (its ends within
    // 1e-3 of its half-width): refused, naming the position.
    const double at = prm.punches[static_cast<std::size_t>(z.punch)].at;
    const double x = std::max({std::fabs(z.left), std::fabs(z.right), std::fabs(at)});
    const double w = 0.5 * (z.right - z.left);
    if (std::isfinite(z.left) && std::isfinite(z.right) && std::fabs(at) > 1.0 &&
        !(w >= 1e3 * ulp(x))) {
      const double need = w > 0.0 ? w : 0.5 * (prm.zones[0].right - prm.zones[0].left);
      std::ostringstream m;
      m.precision(6);
      m << "punches[" << z.punch << "] at x/h = " << at << ": positions there are resolved only to "
        << ulp(x) << " h (the spacing of doubles), too coarse for its contact zone";
      if (need > 0.0) {
        const double limit =
            std::ldexp(1.0, static_cast<int>(std::floor(std::log2(1e-3 * need))) + 53);
        m << " (half-width " << need << " h): |at| must be below " << limit << " here";
      }
      m << "; a train's result does not depend on where it is: place it near x = 0";
      throw InvalidParameter("at", "positions where a zone's ends are resolved", m.str());
    }
    if (!(z.right > z.left) ||
        (j > 0 && !(z.left > prm.zones[static_cast<std::size_t>(j - 1)].right)))
      throw InvalidParameter("zones", "disjoint intervals sorted from left to right",
                             "the starting zones must be disjoint and sorted");
    ++count[static_cast<std::size_t>(z.punch)];
  }
  for (int c : count)
    if (c == 0) throw InvalidParameter("zones", "at least one per punch", "a punch has no zone");
  return prof;
}

// One group of punches that interact (all of them, or one of the groups
// solve_zones splits a train into), in its own coordinates.
ZonesSolution solve_connected(const ZonesParams& prm, const std::vector<PunchProfile>& prof) {
  const auto t0 = std::chrono::steady_clock::now();
  const AsymmetricParams L = with_medium_scalars(prm.layer);
  const int nz = static_cast<int>(prm.zones.size());
  ZonesSolution out;
  out.rayleigh_vstar = rayleigh_vstar(L.nu);
  out.critical_vstar = critical_vstar_of(L);
  require_steady_speed(L, out.critical_vstar, out.rayleigh_vstar);
  out.phi1 = cauchy_phi1_of(L);

  Eigen::VectorXd e(2 * nz);
  for (int j = 0; j < nz; ++j) {
    e(2 * j) = prm.zones[static_cast<std::size_t>(j)].left;
    e(2 * j + 1) = prm.zones[static_cast<std::size_t>(j)].right;
  }
  // The widest punch's hull: the span from the left end of a punch's first
  // zone to the right end of its last, largest over the punches.
  auto widest_hull = [&](const Eigen::VectorXd& ends) {
    double hull = 0.0;
    for (std::size_t k = 0; k < prm.punches.size(); ++k) {
      double lo = kInf, hi = -kInf;
      for (int j = 0; j < nz; ++j)
        if (prm.zones[static_cast<std::size_t>(j)].punch == static_cast<int>(k)) {
          lo = std::min(lo, ends(2 * j));
          hi = std::max(hi, ends(2 * j + 1));
        }
      hull = std::max(hull, hi - lo);
    }
    return hull;
  };
  // The kernel on the span of the zones and the checks beside them.
  // |x - t| for x on a zone or in a punch's checked surroundings (2 hull
  // widths beside its zones) and t on any zone.
  auto range_need = [&](const Eigen::VectorXd& ends) {
    return ends(2 * nz - 1) - ends(0) + 2.0 * widest_hull(ends) + 1.0;
  };
  // The table covers the distances within each punch's surroundings (and a
  // train's span up to 256 h); longer distances take the kernel's pieces
  // built where they are needed (ZoneKernel), so the cost does not grow
  // with the distance between punches.
  auto table_need = [&](const Eigen::VectorXd& ends) {
    return std::min(range_need(ends), std::max(4.0 * widest_hull(ends) + 2.0, 256.0));
  };
  std::shared_ptr<const AsymmetricKernel> kern;
  std::shared_ptr<const Medium> medium;
  std::unique_ptr<ZoneKernel> zk;
  auto kernel = [&](double need) -> const ZoneKernel& {
    if (!kern || kern->range() < need) {
      bool built = false;
      if (!medium) medium = cached_medium(medium_of(L), L.vstar);
      kern = cached_damped_kernel(medium, need, 2.0 * need, &built, 0.0);
      out.kernel_builds += built ? 1 : 0;
      zk = std::make_unique<ZoneKernel>(kern);
    }
    return *zk;
  };
  double S = 0.0;
  for (int j = 0; j < nz; ++j) {
    const int k = prm.zones[static_cast<std::size_t>(j)].punch;
    const double at = prm.punches[static_cast<std::size_t>(k)].at;
    S = std::max({S, std::fabs(prof[static_cast<std::size_t>(k)].slope(e(2 * j) - at)),
                  std::fabs(prof[static_cast<std::size_t>(k)].slope(e(2 * j + 1) - at))});
  }
  if (!(S > 0.0)) S = 1e-3;

  // Symmetric about x = 0: one symmetric punch there, no damping, a
  // symmetric start (Newton's steps are kept symmetric).
  bool mirror = prm.punches.size() == 1 && prm.punches[0].at == 0.0 && !(L.damping > 0.0) &&
                prof[0].symmetric();
  for (int i = 0; i < 2 * nz && mirror; ++i)
    mirror = std::fabs(e(i) + e(2 * nz - 1 - i)) <= 1e-9 * (e(2 * nz - 1) - e(0));

  // The N ladder (or the given N, with N/2 for the estimate).
  std::vector<int> sizes;
  if (L.n != 0) {
    // The estimate's second size: about half, at least 6 (a size 8 compares with 6).
    sizes = {std::max(6, 2 * (L.n / 4)), L.n};
  } else {
    for (int n : detail::kSizes)
      if (n >= std::clamp(prm.first_n, 8, 256) && n <= 256) sizes.push_back(n);
  }
  std::unique_ptr<System> sys;
  Eigen::MatrixXd jac;
  bool have_jac = false;
  RefinementEstimate est_e, est_p;
  double pmax = 0.0;
  // The ladder (ladder.hpp). Per size: the ends and each zone's
  // U-coefficients. The first size from the start (a long way, maybe); a
  // larger one from the last size's ends, a few steps away. When a larger
  // size fails (the finer discretisation has no root near the coarser
  // one's), the ladder stops at the last size that solved, with a warning
  // below.
  struct Member {
    Eigen::VectorXd e;
    std::vector<Eigen::VectorXd> b;
    double step = 0.0;  // Newton's uncertainty in the ends (newton())
    int n = 0;
  };
  // The head of a size-n series whose sampled maximum stands for the
  // whole (a kinked zone's tail is bounded by sum |b|: head_sine_bound).
  auto head_of = [](int n) { return 4 * n + 64; };
  std::string failure_text;  // a larger size's failure (it stops the ladder)
  std::exception_ptr failure;
  const detail::LadderRun<Member, 2> run = detail::run_ladder<2, Member>(
      sizes,
      [&](int n) {
        const bool first = !sys;  // no size solved yet
        const int max_it = first ? 200 : 16;
        sys = std::make_unique<System>(prm, prof, kernel(table_need(e)), n, S);
        double step = newton(*sys, e, out.iterations, jac, have_jac, max_it, mirror);
        if (kern->range() < table_need(e)) {  // the ends moved out: a longer table
          sys = std::make_unique<System>(prm, prof, kernel(table_need(e)), n, S);
          step = newton(*sys, e, out.iterations, jac, have_jac, max_it, mirror);
        }
        Member m{e, std::vector<Eigen::VectorXd>(static_cast<std::size_t>(nz)), step, n};
        pmax = 0.0;
        for (int j = 0; j < nz; ++j) {
          m.b[static_cast<std::size_t>(j)] = sys->extended(j);
          pmax = std::max(pmax, head_sine_bound(m.b[static_cast<std::size_t>(j)], head_of(n)));
        }
        return m;
      },
      [&](const Member& prev, const Member& cur) {
        // A kinked zone's change bounded on the head of the larger size's
        // series (beyond it both tails are the half-plane's: they differ
        // only as the ends do).
        double dp = 0.0;
        for (int j = 0; j < nz; ++j) {
          const Eigen::VectorXd& bj = cur.b[static_cast<std::size_t>(j)];
          const Eigen::VectorXd& bp = prev.b[static_cast<std::size_t>(j)];
          Eigen::VectorXd db = Eigen::VectorXd::Zero(std::max(bj.size(), bp.size()));
          db.head(bj.size()) += bj;
          db.head(bp.size()) -= bp;
          dp = std::max(dp, head_sine_bound(db, head_of(cur.n)));
        }
        return std::array<double, 2>{(cur.e - prev.e).lpNorm<Eigen::Infinity>(), dp};
      },
      [&](const detail::LadderChain<Member, 2>& c) {
        if (c.size() < 2) return detail::Verdict::go_on;
        double wmax = 0.0;
        for (int j = 0; j < nz; ++j) wmax = std::max(wmax, 0.5 * (e(2 * j + 1) - e(2 * j)));
        const double span = std::max(std::fabs(e(0)), std::fabs(e(2 * nz - 1))) + wmax;
        const std::vector<double>& d_ends = c.changes[0];
        const std::vector<double>& d_p = c.changes[1];
        // The floor of a change: round-off, and both sizes' Newton
        // uncertainty (each size's ends are solved to an accepted residual).
        const std::size_t k = c.size();
        const double floor_e = 256.0 * kEps * span + c.states[k - 1].step + c.states[k - 2].step;
        est_e = refinement_estimate(c.sizes, d_ends, floor_e);
        // Several zones converge irregularly, and the error can grow from
        // one size to the next (a stiff Pasternak foundation near V*_cr:
        // N = 48, 64, 96 were 2.1e-10, 3.5e-9, 5.4e-11 off; the extrapolation
        // from changes shrinking by 3.5e-3 claimed 1.3e-10 at 64): the ends'
        // estimate is never below twice the last change (the last change
        // bounds the error only where the previous size's is smaller; as a
        // profile's and the flat punch's, asymmetric.cpp and asymmetric_flat.cpp).
        est_e.estimate = std::max(est_e.estimate, 2.0 * d_ends.back() + floor_e);
        est_p = refinement_estimate(c.sizes, d_p, 64.0 * kEps * pmax);
        return detail::ladder_verdict(
            ladder_stop(L.tol, est_e, d_ends.back(), wmax, est_p, d_p.back(), pmax));
      },
      [&](const std::exception& err, const detail::LadderAt& at) {
        if (dynamic_cast<const ConvergenceError*>(&err) == nullptr || at.solved == 0)
          return detail::OnFailure::rethrow;
        failure_text = err.what();
        failure = std::current_exception();
        return detail::OnFailure::stop;
      });
  const bool converged = run.verdict == detail::Verdict::converged;
  const std::vector<double>& d_ends = run.chain.changes[0];
  const std::vector<double>& d_p = run.chain.changes[1];
  if (run.failed) {
    // Back to the last size that solved (its ends, a system at its size).
    std::ostringstream w;
    w << "the zone ends did not converge at N = " << run.failed_n << " (" << failure_text
      << "); the result is that of N = " << run.chain.sizes.back();
    out.warnings.push_back(w.str());
    e = run.chain.last().e;
    sys = std::make_unique<System>(prm, prof, kernel(table_need(e)), run.chain.sizes.back(), S);
    Eigen::VectorXd F;
    if (!sys->eval(e, F)) std::rethrow_exception(failure);
  }
  out.collocation_n = sys->n();
  // One size alone (a larger one failed): no estimate. The result's ends
  // carry their own Newton uncertainty beside the ladder's.
  out.error_estimate = d_ends.empty() ? kInf : est_e.estimate + run.chain.last().step;
  out.pressure_error_estimate = d_p.empty() ? kInf : est_p.estimate;
  double wmax = 0.0;
  for (int j = 0; j < nz; ++j) wmax = std::max(wmax, 0.5 * (e(2 * j + 1) - e(2 * j)));
  if (!converged) {
    std::ostringstream w;
    w << "zone ends: error estimate " << out.error_estimate << " h exceeds tol * (largest zone "
      << "half-width) = " << L.tol * wmax << " h at the largest size N = " << out.collocation_n
      << " per zone";
    if (out.pressure_error_estimate > L.tol * pmax)
      w << "; pressure error estimate " << out.pressure_error_estimate << " above tol * max p";
    out.warnings.push_back(w.str());
  }
  {
    Eigen::VectorXd F;
    sys->eval(e, F);
    out.residual = F.lpNorm<Eigen::Infinity>();
  }
  // The kinked zones' tails (for the checks and the outputs) and what they
  // leave out: added to the pressure's estimate; above 1e-3 of the largest
  // pressure a warning names the profile (as the single contact's).
  sys->extend_all();
  {
    // (The largest pressure reported: the whole series' (the ladder's
    // scale bounds a kinked zone's tail by sum |b_n|).)
    double trunc = 0.0, pbig = 0.0;
    int worst = -1;
    for (int j = 0; j < nz; ++j) {
      if (!sys->kinked(j)) {
        pbig = std::max(pbig, max_abs_sine_series(sys->series(j)));
        continue;
      }
      const double t = sys->truncation(j);
      pbig = std::max(pbig, max_abs_sine_series_long(sys->series(j), head_of(sys->n())));
      if (t > trunc || worst < 0) {
        trunc = t;
        worst = j;
      }
    }
    if (worst >= 0) {
      pmax = pbig;
      out.pressure_error_estimate += trunc;
      const int k = sys->punch_of(worst);
      const PunchProfile& pf = prof[static_cast<std::size_t>(k)];
      double all = 0.0;  // the total load: the message's P
      for (const ZonePunch& q : prm.punches) all += q.load;
      const std::string kinks = kink_truncation_warning(
          trunc / all, u_series(sys->series(worst), 0.0) / all, pf.describe(),
          std::fabs(sys->centre(worst) - prm.punches[static_cast<std::size_t>(k)].at) +
              sys->half(worst) - pf.face());
      if (!kinks.empty()) out.warnings.push_back(kinks);
    }
  }

  // The zones (their solutions are built on demand: ZoneResult::solution).
  for (int j = 0; j < nz; ++j) {
    ZoneResult z;
    z.punch = sys->punch_of(j);
    z.left = e(2 * j);
    z.right = e(2 * j + 1);
    z.origin = prm.punches[static_cast<std::size_t>(z.punch)].at;
    z.offset = sys->centre(j) - z.origin;
    z.half = sys->half(j);
    z.load = sys->load(j);
    z.params = L;
    z.params.load = z.load;
    z.params.profile = ProfileKind::cylinder;
    z.params.radius = 1.0;
    z.params.half_width = 0.0;
    z.params.table_x.clear();
    z.params.table_y.clear();
    z.kernel = kern;
    const double scale = z.load != 0.0 ? z.load : 1.0;
    z.b = sys->series(j) / scale;
    z.head = sys->n();
    const double sign = z.load < 0 ? -1.0 : 1.0;
    double rmin = 0.0;
    // (A kinked zone's margin on its collocated head, as the single
    // contact's: the tail's kink is resolved only to its truncation anyway.)
    z.margin =
        u_series_minimum(z.b.head(std::min<Eigen::Index>(z.b.size(), head_of(z.head))), &rmin) *
        sign;
    z.margin_x = sys->centre(j) + sys->half(j) * rmin;
    z.min_pressure = min_pressure_on_grid(z.b, sign);
    out.zones.push_back(std::move(z));
  }
  // Per punch: where the indentation is taken, and the drag.
  const int np = static_cast<int>(prm.punches.size());
  out.drag.assign(static_cast<std::size_t>(np), 0.0);
  double total = 0.0;
  for (int k = 0; k < np; ++k) {
    int best = -1;
    for (int j = 0; j < nz; ++j)
      if (out.zones[static_cast<std::size_t>(j)].punch == k &&
          (best < 0 || out.zones[static_cast<std::size_t>(j)].load >
                           out.zones[static_cast<std::size_t>(best)].load))
        best = j;
    const double xc = sys->centre(best);
    out.indentation_x.push_back(xc);
    out.indentation_height.push_back(sys->height(k, xc));
    double drag = 0.0;
    for (int j = 0; j < nz; ++j) {
      if (out.zones[static_cast<std::size_t>(j)].punch != k) continue;
      const Eigen::VectorXd& b = sys->series(j);
      const double c = sys->centre(j), w = sys->half(j);
      if (!sys->slope_coefficients(j).empty()) {  // a kinked zone (extend_all)
        // int sqrt(1 - r^2) U_n T_m dr = (pi/4)(delta_nm (1 + delta_m0) - delta_m,n+2),
        // f'(c + w r) = d_0/2 + sum d_m T_m: w (pi/4) sum_n b_n (d_n - d_{n+2}).
        const std::vector<double>& d = sys->slope_coefficients(j);  // to 4 kTailTerms + 1
        double sum = 0.0;
        for (Eigen::Index n = 0; n < b.size(); ++n)
          sum += b(n) * (d[static_cast<std::size_t>(n)] - d[static_cast<std::size_t>(n + 2)]);
        drag += w * 0.25 * kPi * sum;
        continue;
      }
      const int m = std::max(64, 2 * sys->n() + 2);
      for (int i = 1; i <= m; ++i) {
        const double th = i * kPi / (m + 1), r = std::cos(th);
        drag += kPi * w * std::sin(th) * std::sin(th) / (m + 1) * u_series(b, r) *
                sys->slope(k, c + w * r);
      }
    }
    out.drag_total += drag;
    total += prm.punches[static_cast<std::size_t>(k)].load;
    out.drag[static_cast<std::size_t>(k)] = drag / prm.punches[static_cast<std::size_t>(k)].load;
  }
  out.drag_total /= total;
  // The surface stress's error: sigma_x = -phi2 p - (1/pi) Re int (M2 -
  // phi2) p^ e^{i alpha x} d alpha is linear in p, and |dp^| <= int |dp| <=
  // 2 w max |dp| per zone: |d sigma_x| <= (|phi2| + (2 w/pi) int |M2 - phi2|)
  // max |dp| summed over the zones, with dp the pressure's error (the
  // ladder's estimate) plus the ends' error moving p by about pmax (da/w)(1 +
  // 1/sqrt(2 d)) at a relative distance d >= 1e-3 from an end; plus round-off.
  {
    out.max_pressure = pmax / total;
    const AsymmetricQuadrature& quad = kern->quadrature();
    const double phi2 = kern->model().phi2();
    double im2 = 0.0;
    for (std::size_t i = 0; i < quad.m2.size(); ++i)
      im2 += quad.panels.weight[i] * std::abs(quad.m2[i] - phi2);
    double bound = 0.0;
    for (int j = 0; j < nz; ++j) {
      const double gain = std::fabs(phi2) + 2.0 * sys->half(j) * im2 / kPi;
      const double ends =
          pmax * (out.error_estimate / sys->half(j)) * (1.0 + 1.0 / std::sqrt(2e-3));
      bound += gain * (out.pressure_error_estimate + ends);
    }
    out.stress_error_estimate =
        bound / total + 64.0 * kEps * (1.0 + std::fabs(phi2)) * out.max_pressure * nz;
  }
  // Complementarity beside the zones: each punch's gap
  // f_k(x) - delta_k - v(x), from its nearest zone end (where it is 0), on
  // its contact's hull and 2 hull widths beyond it on both sides.
  out.min_gap = kInf;
  // The sampling step: the surface's band (gap_scan.hpp) from the kernel's
  // quadrature of |M1 - phi1|.
  // (A viscoelastic top's whole half-plane part H(alpha): its memory is
  // taken exactly in vslope.)
  const double step = detail::gap_step(kern->surface_band());
  const double phi1m = sys->phi1();
  for (int k = 0; k < np; ++k) {
    std::vector<int> mine;
    for (int j = 0; j < nz; ++j)
      if (sys->punch_of(j) == k) mine.push_back(j);
    const double lo = e(2 * mine.front()), hi = e(2 * mine.back() + 1);
    const double reach = 2.0 * (hi - lo);
    const PunchProfile& pf = prof[static_cast<std::size_t>(k)];
    const double at = prm.punches[static_cast<std::size_t>(k)].at;
    for (int j : mine)
      out.gap_scale =
          std::max(out.gap_scale, sys->half(j) * std::max(std::fabs(sys->slope(k, e(2 * j))),
                                                          std::fabs(sys->slope(k, e(2 * j + 1)))));
    // gap' = f_k' - v': the kernel's part of v' from its interpolant on
    // the scanned interval (when it reaches round-off there; directly
    // otherwise), the Cauchy integrals directly.
    std::unique_ptr<detail::SmoothInterpolant> smooth;
    auto gap_slope = [&](double x) {
      if (smooth) return sys->slope(k, x) - (sys->vslope(x, false) + phi1m * (*smooth)(x));
      return sys->slope(k, x) - sys->vslope(x);
    };
    auto interpolate = [&](double from, double to) {
      smooth = std::make_unique<detail::SmoothInterpolant>(
          [&](double x) { return sys->kernel_part(x); }, std::min(from, to), std::max(from, to));
      if (!smooth->ok()) smooth.reset();
    };
    auto note = [&](double gap, double x, int after) {
      if (!std::isfinite(gap))
        throw ConvergenceError(
            "several contact zones: the gap beside the zones came out non-finite; "
            "the solution is not trusted");
      if (gap < out.min_gap) {
        out.min_gap = gap;
        out.min_gap_x = x;
        out.min_gap_after_zone = after;
      }
    };
    // Outward from an end (up to the reach, the table's end or the next
    // zone) and between its consecutive zones: gap' = f_k' - v', sampled
    // to resolve the surface's shortest wave and refined at every dip
    // (gap_scan.hpp).
    for (int side = -1; side <= 1; side += 2) {
      const double edge = side < 0 ? lo : hi;
      // Up to the table's end and to the next zone (another punch's: its
      // cusps would spoil the integral; that punch checks there).
      double room = side < 0 ? edge - at - pf.lower() : pf.upper() - (edge - at);
      for (int j = 0; j < nz; ++j) {
        const double gap_to = side < 0 ? edge - e(2 * j + 1) : e(2 * j) - edge;
        if (gap_to > 0.0) room = std::min(room, gap_to);
      }
      const double len = std::min(reach, room);
      if (!(len > 0.0)) continue;
      interpolate(edge, edge + side * len);
      const detail::GapMinimum m =
          detail::scan_gap_slope(gap_slope, edge, edge + side * len, 0.0, step, 32, true, false);
      note(m.gap, m.x, -1);
    }
    for (const auto& [j, jn] : sys->pairs()) {
      if (sys->punch_of(j) != k) continue;
      const double a = e(2 * j + 1), b = e(2 * jn);
      interpolate(a, b);
      const detail::GapMinimum m =
          detail::scan_gap_slope(gap_slope, a, b, 0.0, step, 32, true, true);
      note(m.gap, m.x, j);
    }
  }
  out.elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

// Moves a solution computed in coordinates relative to `origin` back.
void shift(ZonesSolution& s, double origin) {
  for (ZoneResult& z : s.zones) {
    z.left += origin;
    z.right += origin;
    z.margin_x += origin;
  }
  for (double& x : s.indentation_x) x += origin;
  s.min_gap_x += origin;
}

// Whether two groups' inputs (relative to their origins) are the same to
// 1e-12 of the group's length: one solve serves both.
bool same_group(const ZonesParams& a, const ZonesParams& b) {
  if (a.punches.size() != b.punches.size() || a.zones.size() != b.zones.size()) return false;
  const double scale = 1e-12 * std::max(1.0, a.zones.back().right - a.zones.front().left);
  auto near = [&](double x, double y) { return std::fabs(x - y) <= scale; };
  for (std::size_t k = 0; k < a.punches.size(); ++k) {
    const ZonePunch &p = a.punches[k], &q = b.punches[k];
    if (p.profile != q.profile || p.radius != q.radius || p.half_width != q.half_width ||
        p.table_x != q.table_x || p.table_y != q.table_y || p.load != q.load || !near(p.at, q.at))
      return false;
  }
  for (std::size_t j = 0; j < a.zones.size(); ++j) {
    const ZoneSpan &z = a.zones[j], &y = b.zones[j];
    if (z.punch != y.punch || !near(z.left, y.left) || !near(z.right, y.right)) return false;
  }
  return true;
}

}  // namespace

ZonesSolution solve_zones(const ZonesParams& prm) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<PunchProfile> prof = validate_zones(prm);
  const AsymmetricParams L = with_medium_scalars(prm.layer);
  {
    const double vr = rayleigh_vstar(L.nu), vcr = critical_vstar_of(L);
    require_steady_speed(L, vcr, vr);
  }
  const int nz = static_cast<int>(prm.zones.size());
  const int np = static_cast<int>(prm.punches.size());
  // Per punch: the hull of its starting zones; the narrowest zone; where
  // the positions are largest.
  std::vector<double> lo(static_cast<std::size_t>(np), kInf), hi(lo.size(), -kInf);
  double wmin = kInf, xmax = 0.0;
  for (const ZoneSpan& z : prm.zones) {
    const auto k = static_cast<std::size_t>(z.punch);
    lo[k] = std::min(lo[k], z.left);
    hi[k] = std::max(hi[k], z.right);
    wmin = std::min(wmin, 0.5 * (z.right - z.left));
    xmax = std::max({xmax, std::fabs(z.left), std::fabs(z.right)});
  }
  // The order of the punches along x, and the groups that interact: on a
  // foundation the layer's response decays with the distance, and punches
  // whose zones (and the surroundings their checks cover) lie farther apart
  // than where the total kernel has decayed below eps interact below the
  // tolerance: each group is solved alone. eps: a slope error (phi1/pi) P
  // eps moves a zone end by about that over the slope f' at the end,
  // relative to the zone; kept at 1e-2 tol of it.
  std::vector<int> order(static_cast<std::size_t>(np));
  for (int k = 0; k < np; ++k) order[static_cast<std::size_t>(k)] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return lo[static_cast<std::size_t>(a)] < lo[static_cast<std::size_t>(b)];
  });
  std::vector<std::vector<int>> groups;  // punch indices, along x
  double apart = kInf;                   // the distance beyond which groups are independent
  bool built = false;                    // the decay's kernel table was built here
  if (np > 1) {
    const ZoneKernel K(
        cached_damped_kernel(cached_medium(medium_of(L), L.vstar), 1.0, 4.0, &built, 0.0));
    double slope = kInf, total = 0.0;
    for (const ZoneSpan& z : prm.zones) {
      const auto k = static_cast<std::size_t>(z.punch);
      const double at = prm.punches[k].at;
      slope = std::min(slope, std::max(std::fabs(prof[k].slope(z.left - at)),
                                       std::fabs(prof[k].slope(z.right - at))));
    }
    for (const ZonePunch& p : prm.punches) total += p.load;
    if (!(slope > 0.0)) slope = 1e-3;
    const double phi1 = std::fabs(wave_constants(L.vstar, L.nu).phi1);
    apart = quiet_distance(K, 1e-2 * L.tol * slope * kPi / (phi1 * total));
  }
  {
    double ghi = -kInf, ghull = 0.0;
    for (int k : order) {
      const auto q = static_cast<std::size_t>(k);
      const double hull = hi[q] - lo[q];
      const double reach = 3.0 * std::max(ghull, hull);
      if (groups.empty() || !(lo[q] - ghi - reach > apart)) {
        if (groups.empty()) groups.emplace_back();
        groups.back().push_back(k);
        ghull = std::max(ghull, hull);
      } else {
        groups.push_back({k});
        ghull = hull;
      }
      ghi = std::max(ghi, hi[q]);
    }
  }
  // Each group is solved relative to its first punch's axis (the problem is
  // translation invariant; far from x = 0 the ends would lose digits), and
  // moved back: the positions then carry the spacing of doubles there,
  // part of the error estimate (and a warning above tol).
  const double spacing = ulp(xmax);
  std::vector<ZonesSolution> parts, raws;
  std::vector<ZonesParams> inputs;
  std::vector<std::vector<int>> zone_of;  // per group: its zones' global indices
  for (const std::vector<int>& g : groups) {
    ZonesParams sub;
    sub.layer = prm.layer;
    sub.first_n = prm.first_n;
    std::vector<int> local(static_cast<std::size_t>(np), -1);
    std::vector<int> members = g;
    std::sort(members.begin(), members.end());  // the punches' own order within the group
    const double origin = prm.punches[static_cast<std::size_t>(g.front())].at;
    for (int k : members) {
      local[static_cast<std::size_t>(k)] = static_cast<int>(sub.punches.size());
      ZonePunch p = prm.punches[static_cast<std::size_t>(k)];
      p.at -= origin;
      sub.punches.push_back(p);
    }
    zone_of.emplace_back();
    for (int j = 0; j < nz; ++j) {
      const ZoneSpan& z = prm.zones[static_cast<std::size_t>(j)];
      if (local[static_cast<std::size_t>(z.punch)] < 0) continue;
      sub.zones.push_back(
          {local[static_cast<std::size_t>(z.punch)], z.left - origin, z.right - origin});
      zone_of.back().push_back(j);
    }
    std::vector<PunchProfile> sub_prof;
    for (int k : members) sub_prof.push_back(prof[static_cast<std::size_t>(k)]);
    ZonesSolution part;
    bool reused = false;
    for (std::size_t i = 0; i < inputs.size() && !reused; ++i)
      if (same_group(inputs[i], sub)) {  // a train of equal punches: solved once
        part = raws[i];
        part.iterations = 0;
        part.kernel_builds = 0;
        part.elapsed = 0.0;
        reused = true;
      }
    if (!reused) part = solve_connected(sub, sub_prof);
    raws.push_back(part);
    shift(part, origin);
    // Back to the global punch indices (and their axes).
    for (ZoneResult& z : part.zones) {
      z.punch = members[static_cast<std::size_t>(z.punch)];
      z.origin = prm.punches[static_cast<std::size_t>(z.punch)].at;
    }
    inputs.push_back(std::move(sub));
    parts.push_back(std::move(part));
  }
  ZonesSolution out;
  out.kernel_builds = built ? 1 : 0;
  const ZonesSolution& first = parts.front();
  out.critical_vstar = first.critical_vstar;
  out.rayleigh_vstar = first.rayleigh_vstar;
  out.phi1 = first.phi1;
  out.drag.assign(static_cast<std::size_t>(np), 0.0);
  out.indentation_x.assign(static_cast<std::size_t>(np), 0.0);
  out.indentation_height.assign(static_cast<std::size_t>(np), 0.0);
  double total = 0.0;
  for (const ZonePunch& p : prm.punches) total += p.load;
  out.min_gap = kInf;
  double worst = kInf;  // the smallest gap relative to its group's scale
  std::vector<std::pair<double, ZoneResult>> zones;
  for (std::size_t gi = 0; gi < parts.size(); ++gi) {
    const ZonesSolution& s = parts[gi];
    std::vector<int> members = groups[gi];
    std::sort(members.begin(), members.end());
    double load = 0.0;
    for (int k : members) load += prm.punches[static_cast<std::size_t>(k)].load;
    for (std::size_t i = 0; i < members.size(); ++i) {
      const auto k = static_cast<std::size_t>(members[i]);
      out.drag[k] = s.drag[i];
      out.indentation_x[k] = s.indentation_x[i];
      out.indentation_height[k] = s.indentation_height[i];
    }
    const std::size_t offset = out.zones.size();
    for (ZoneResult z : s.zones) {
      z.group = static_cast<int>(gi);
      out.zones.push_back(std::move(z));
    }
    out.error_estimate = std::max(out.error_estimate, s.error_estimate);
    out.pressure_error_estimate = std::max(out.pressure_error_estimate, s.pressure_error_estimate);
    out.stress_error_estimate += s.stress_error_estimate * load / total;
    out.max_pressure = std::max(out.max_pressure, s.max_pressure * load / total);
    out.drag_total += s.drag_total * load / total;
    out.residual = std::max(out.residual, s.residual);
    out.collocation_n = std::max(out.collocation_n, s.collocation_n);
    out.iterations += s.iterations;
    out.kernel_builds += s.kernel_builds;
    const double rel = s.min_gap / std::max(s.gap_scale, 1e-300);
    if (rel < worst) {
      worst = rel;
      out.min_gap = s.min_gap;
      out.min_gap_x = s.min_gap_x;
      out.gap_scale = s.gap_scale;
      out.min_gap_after_zone =
          s.min_gap_after_zone < 0 ? -1 : static_cast<int>(offset) + s.min_gap_after_zone;
    }
    for (const std::string& w : s.warnings) {
      if (parts.size() == 1) {
        out.warnings.push_back(w);
        continue;
      }
      std::ostringstream m;
      m << "punches";
      for (int k : members) m << " " << k;
      m << ": " << w;
      out.warnings.push_back(m.str());
    }
  }
  if (parts.size() > 1) {
    // The groups' interaction left out: below 1e-2 tol of the zones' ends.
    double wmax = 0.0;
    for (const ZoneResult& z : out.zones) wmax = std::max(wmax, 0.5 * (z.right - z.left));
    out.error_estimate += 1e-2 * L.tol * wmax;
  }
  // The positions' spacing at |x| (the groups moved back there).
  out.error_estimate = std::max(out.error_estimate, spacing);
  if (spacing > L.tol * wmin) {
    std::ostringstream w;
    w << "positions near x/h = " << xmax << " are resolved only to " << spacing
      << " h (the spacing of doubles there), above tol * (narrowest zone half-width) = "
      << L.tol * wmin << " h: place the punches nearer x = 0 (the result does not depend on "
      << "where they are)";
    out.warnings.push_back(w.str());
  }
  out.elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace movingpunch

// The medium under the punch: one interface behind every solver.
//
// A medium is what lies under the surface y = 0: a stack of sublayers (total
// thickness h = 1; homogeneous or exponentially graded) on a base (springs,
// Winkler/Pasternak with or without damping, rigid, or an elastic half-space,
// bonded or in frictionless contact). Units are those of the TOP sublayer's
// top: mu = rho = 1, vstar = rho V^2 / mu (docs/theory.md section 16).
//
// A solver never sees a concrete medium. It reads, per wavenumber t = alpha h:
//  * surface_response(t): the surface responses to unit transformed pressure
//    (M1 = -alpha v^/p^, M2 = -sigma_x^/p^, alpha u^ and alpha v^ at the top;
//    complex in general: damping, viscoelasticity; real for elastic media);
//  * mode(t): the mode field at any depth (stresses and displacements) and
//    its top material's half-plane part, which the stresses take in closed form;
//  * top(): the half-plane constants of the top material (phi1, phi2, the
//    Cauchy term of the kernel), and the decay rate of M1 - phi1 (where the
//    kernel's alpha quadrature may stop) and the long-wave scales of the base
//    (where its first panels must be split);
//  * dispersion(t): a real function changing sign where a free steady wave of
//    wavenumber t exists at this speed (the critical-speed search);
//  * for the asymmetric solver (friction, damping, asymmetric profiles,
//    several zones): full_response(t), the normal and the unit tangential
//    load's responses at the surface and at the base face together,
//    normal_state/tangential_state(t, y) at any depth, tangential() (the
//    top material's tangential half-plane constants), bar_compliance() (the
//    tangential response's long-wave pole) and base_damper() (the dashpots).
// The kernel tables are cached per medium (key()).
#pragma once

#include <complex>
#include <iterator>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "movingpunch/dispersion.hpp"
#include "movingpunch/jacobi.hpp"
#include "movingpunch/layer_response.hpp"
#include "movingpunch/viscoelastic.hpp"

namespace movingpunch {

// ---------------------------------------------------------------------------
// The description of a medium, independent of the speed.

// One sublayer: thickness (a fraction of h; the thicknesses sum to 1), shear
// modulus and density relative to the top sublayer's top (the top sublayer
// has mu = rho = 1), Poisson's ratio, and gamma_h: mu(y) and rho(y) vary as
// exp(gamma_h (y - y_top)) from the sublayer's top value (y up, h = 1; 0:
// homogeneous; the wave speeds stay constant).
struct Sublayer {
  Sublayer() = default;
  // The elastic scalars in their table's order (kSublayerFields).
  Sublayer(double thickness_, double mu_, double nu_ = 0.2, double rho_ = 1.0, double gamma_ = 0.0)
      : thickness(thickness_), mu(mu_), nu(nu_), rho(rho_), gamma(gamma_) {}
  double thickness = 1.0;
  double mu = 1.0;
  double nu = 0.2;
  double rho = 1.0;
  double gamma = 0.0;
  // A viscoelastic material (viscoelastic.hpp; empty: elastic): mu is then
  // the relaxed modulus mu_0, the shear modulus at frequency omega is
  // mu m(alpha h) (docs/theory.md section 17).
  Viscoelastic visco;
};

// The largest |gamma_h| of a graded sublayer (the modulus changes by e^50
// across the layer at most), the most sublayers, and the largest ratio of a
// sublayer's (or the substrate's) mu or rho to the top's.
inline constexpr double kMaxGamma = 50.0;
inline constexpr std::size_t kMaxSublayers = 64;
inline constexpr double kMaxModulusRatio = 1e12;

// The sublayer's scalars, in the order of a sublayer's row in the bindings
// (Python's movingpunch.media.SUBLAYER_ROW, the same names): validate(),
// MediumSpec::key() and the bindings' rows loop over this table, so a new
// scalar of a sublayer is a member above and a row here.
template <class T>
struct ScalarField {
  const char* name;
  double T::* member;
  double lo, hi;  // its range (require_in_range, errors.hpp)
  bool lo_open, hi_open;
};
using SublayerField = ScalarField<Sublayer>;
inline constexpr SublayerField kSublayerFields[] = {
    {"thickness", &Sublayer::thickness, 0.0, 1.0, true, false},
    {"mu", &Sublayer::mu, 0.0, kMaxModulusRatio, true, false},
    {"nu", &Sublayer::nu, 0.0, 0.5, false, true},
    {"rho", &Sublayer::rho, 0.0, kMaxModulusRatio, true, false},
    {"gamma_h", &Sublayer::gamma, -kMaxGamma, kMaxGamma, false, false},
};
inline constexpr std::size_t kSublayerRow = std::size(kSublayerFields);

enum class BaseKind {
  springs,  // sigma_y = (kw + kp t^2 - i damping sqrt(vstar) t) v, tau = 0; kw = inf: rigid
  half_space_bonded,  // an elastic substrate, u, v, tau, sigma_y continuous
  half_space_smooth,  // an elastic substrate in frictionless contact: tau = 0 on both faces
};

struct BaseSpec {
  BaseKind kind = BaseKind::springs;
  double kw = 1.0;  // springs: k_w h / mu_1 in (0, inf]
  double kp = 0.0;  // springs: k_p / (mu_1 h) in [0, kMaxKp]
  double damping = 0.0;
  double mu = 1.0, nu = 0.2, rho = 1.0;  // half-space: relative to the top sublayer
};

// The half-space's scalars, in the order of its row in the bindings
// (`half_space=`; Python's movingpunch.media.HALF_SPACE_ROW): validate() (as
// "base.<name>"), MediumSpec::key(), describe() and the bindings loop over
// this table, so a new scalar of the substrate is a member above and a row
// here.
using HalfSpaceField = ScalarField<BaseSpec>;
inline constexpr HalfSpaceField kHalfSpaceFields[] = {
    {"mu", &BaseSpec::mu, 0.0, kMaxModulusRatio, true, false},
    {"nu", &BaseSpec::nu, 0.0, 0.5, false, true},
    {"rho", &BaseSpec::rho, 0.0, kMaxModulusRatio, true, false},
};
inline constexpr std::size_t kHalfSpaceRow = std::size(kHalfSpaceFields);

struct MediumSpec {
  std::vector<Sublayer> layers{Sublayer{}};
  BaseSpec base;
  // One homogeneous sublayer on springs: the paper's layer (LayerModel).
  bool homogeneous() const noexcept {
    return layers.size() == 1 && layers[0].gamma == 0.0 && layers[0].visco.empty() &&
           base.kind == BaseKind::springs;
  }
  // True when a sublayer is viscoelastic.
  bool viscoelastic() const noexcept;
  // The numbers that identify the medium (cache keys).
  std::vector<double> key() const;
};

// The paper's medium: one homogeneous sublayer of Poisson's ratio nu on springs.
MediumSpec homogeneous_medium(double kw, double nu, double kp = 0.0, double damping = 0.0);

// The medium as messages name it: "kw = 1" (one homogeneous sublayer on
// springs), "3 sublayers on kw = 1, kp = 0.2", "2 sublayers on a bonded
// half-space (mu 10, nu 0.3, rho 2)".
std::string describe(const MediumSpec& m);

// Throws InvalidParameter (errors.hpp) naming the parameter and its range:
// thicknesses > 0 summing to 1 (to 1e-12), the top sublayer's mu = rho = 1,
// every mu, rho > 0 finite, nu in [0, 0.5), |gamma_h| <= kMaxGamma, the
// base's own ranges.
void validate(const MediumSpec& m);

// ---------------------------------------------------------------------------
// The medium at one speed.

using cplx = std::complex<double>;

// Per unit transformed pressure at t = alpha h > 0 (as Response in
// layer_response.hpp; complex in general; alpha < 0: the conjugates).
struct MediumResponse {
  cplx M1{0.0, 0.0};
  cplx M2{0.0, 0.0};
  cplx U0{0.0, 0.0};
  cplx W0{0.0, 0.0};
};

// The asymmetric solver's responses at t = alpha h > 0 (alpha < 0: the
// conjugates), per unit transformed load:
//  * the normal load (sigma_y/alpha = -1, tau = 0 at y = 0): M1, M2, U0, W0
//    as MediumResponse, and Wb = alpha v^(alpha, -1)/p^, the base face's
//    deflection: on springs it is what the springs and dashpots compress
//    (the foundation's reaction kw v, the dashpots' dissipation
//    base_damper() int |Wb p^|^2); on a rigid base 0; under a half-space the
//    interface's deflection (no dashpot: no dissipation);
//  * the unit tangential load (state [Uq, Wq, 1, 0] at y = 0: tau/alpha = 1,
//    sigma_y = 0; the physical amplitudes of tau_xy = q^ e^{i alpha x} are
//    i q^ times these; docs/theory.md section 14): Uq, Wq at the surface and
//    Wqb, its W at the base face.
struct FullResponse {
  cplx M1{0.0, 0.0};
  cplx M2{0.0, 0.0};
  cplx U0{0.0, 0.0};
  cplx W0{0.0, 0.0};
  cplx Wb{0.0, 0.0};
  cplx Uq{0.0, 0.0};
  cplx Wq{0.0, 0.0};
  cplx Wqb{0.0, 0.0};
};

class DampedLayerModel;  // asymmetric.hpp: the homogeneous layer on damped springs

// The state of one mode at a depth: [U, W, tau/alpha, sigma_y/alpha] and
// sigma_x/alpha (of the material on the chosen side of an interface), for the
// top load sigma_y/alpha = -1, tau = 0 (layer_response.hpp's normalisation).
struct ModeState {
  Eigen::Vector4cd z = Eigen::Vector4cd::Zero();
  cplx sx{0.0, 0.0};
};

// The field of one wavenumber (built once, evaluated at many depths).
class ModeProfile {
 public:
  virtual ~ModeProfile() = default;
  // The state minus the top material's half-plane state at depth y in
  // [-1, 0] (below: at an interface, the material below it; sigma_x/alpha
  // of the remainder is that material's sigma_x of the state minus the top
  // material's of the half-plane state).
  virtual ModeState remainder(double y, bool below = false) const = 0;
  // The half-plane part alone (the top material's, closed form).
  virtual ModeState half_plane(double y) const = 0;
  // The whole state (default: remainder + half_plane).
  virtual ModeState state(double y, bool below = false) const;
};

// The kernel's slow asymptotics of a medium whose top material is graded
// (docs/theory.md section 16.5): f(t) = (M1(t) - phi1)/phi1 tends to 0 only
// as the series sum_k a[k-1] (gamma/t)^k (t = alpha h -> inf), plus terms
// below exp(-margin - rate t) (rate = Medium::decay_rate()). Empty (a = {}):
// f decays exponentially (every homogeneous top). `next` bounds |a_{K+1}|
// (the first coefficient not in a); `radius` is the radius in gamma/t
// within which the series converges (the coefficients grow like
// radius^-k).
struct KernelAsymptotics {
  double gamma = 0.0;
  std::vector<double> a;
  double next = 0.0;
  double radius = 1.0;
  double margin = 0.0;
};

class Medium {
 public:
  virtual ~Medium() = default;

  virtual double vstar() const noexcept = 0;
  // The top material's half-plane constants (wave_constants(vstar, nu_1)).
  virtual const WaveConstants& top() const noexcept = 0;
  double phi1() const noexcept { return top().phi1; }
  double phi2() const noexcept { return top().phi2; }
  double nu() const noexcept { return top().nu; }

  // True when every response is real (no damping, no viscoelasticity): the
  // symmetric solver applies.
  virtual bool real() const noexcept = 0;
  virtual MediumResponse surface_response(double t) const = 0;
  virtual std::unique_ptr<const ModeProfile> mode(double t) const = 0;
  // A function changing sign exactly where a free wave of wavenumber t exists,
  // as the speed varies at a fixed t (arbitrary sign convention, which may
  // differ between wavenumbers: compare values at one t only).
  virtual double dispersion(double t) const = 0;

  // M1 - phi1 decays at least like exp(-decay_rate() t) (times a polynomial):
  // 2 nT for the homogeneous layer (a reflection off its bottom).
  virtual double decay_rate() const noexcept = 0;
  // The widest alpha panel the surface quadrature starts from
  // (build_alpha_quadrature, which then splits where M1 needs it): 1 for the
  // homogeneous layer, as always. A stack's M1 - phi1 is a sum of decaying
  // exponentials beyond its long waves (every sublayer subsonic), falling
  // by e^8 over 8 / decay_rate(): a thin top sublayer's slow tail needs no
  // unit panels (3-5x fewer nodes, and every displacement sums over them).
  virtual double panel_scale() const noexcept { return 1.0; }
  // The slowest decay of the mode's remainder at any depth of the stack
  // (nT for the homogeneous layer: the field at its bottom).
  virtual double field_decay_rate() const noexcept = 0;
  // Edges of the first alpha panels on [0, w] (at least {0, w}): the base's
  // long-wave scales (layer_basis.hpp's foundation_panel_edges).
  virtual std::vector<double> first_panel_edges(double w) const = 0;
  // lim M1 as t -> 0: 0 on springs (the layer's slope response vanishes at
  // long waves), finite under a half-space (plane strain: its surface
  // displacement grows like ln|x| far away, so displacements are measured
  // relative to a reference point, kDisplacementReference).
  virtual double long_wave_m1() const noexcept { return 0.0; }
  // The relative round-off of a/h per eps |phi1| that the responses carry
  // near the top's Rayleigh speed (phi1 grows like 1/(V*_R - V*) there):
  // 2e-3 for the homogeneous layer, whose M1 and phi1 share their closed
  // form's errors (measured scatter 0.5e-3 ... 1.6e-3); a stack's M1 is
  // propagated, its error about 2.5 eps phi1 apart from phi1's, carried to
  // a/h with a gain of about 10 (measured: 1.8e-12 relative at 0.999 V*_R,
  // phi1 = 333, on a stiff bonded half-space): 50.
  virtual double roundoff_gain() const noexcept { return 2e-3; }
  // A graded top's slow asymptotics of M1 (KernelAsymptotics); the default,
  // an empty one, for every medium whose M1 - phi1 decays exponentially.
  virtual const KernelAsymptotics& kernel_asymptotics() const noexcept;
  // Depths of the interfaces between sublayers (descending, strictly inside
  // (-1, 0)); empty for one sublayer.
  virtual std::vector<double> interfaces() const { return {}; }

  // --- The asymmetric solver's reads (asymmetric.hpp, zones.hpp).
  // The normal and tangential loads' responses (FullResponse), t >= 0 (t = 0:
  // the limits; Uq, Wq are NaN there on a shear-free base, the bar pole).
  virtual FullResponse full_response(double t) const = 0;
  // The whole state [U, W, tau/alpha, sigma_y/alpha] at -1 <= y <= 0 (an
  // interface: the side above; continuous there) of the normal load
  // (layer_response.hpp's normalisation) and of the unit tangential load
  // (top tau/alpha = 1, sigma_y = 0), t > 0 finite.
  virtual Eigen::Vector4cd normal_state(double t, double y) const = 0;
  virtual Eigen::Vector4cd tangential_state(double t, double y) const = 0;
  // The moving half-plane's tangential response of the top material.
  virtual const TangentialHalfPlane& tangential() const noexcept = 0;
  // lim_{t -> 0} t Uq(t): on a shear-free base (springs, rigid, a smooth
  // half-space) the stack carries the net horizontal force as a bar, Uq ~
  // 1/(t sum_i int (Ep_i mu_i - vstar rho_i) dy) (Ep = 2/(1 - nu), the
  // plane-strain modulus over mu); a bonded half-space takes the force: 0.
  virtual double bar_compliance() const noexcept = 0;
  // The dashpots' coefficient damping sqrt(vstar) (springs with damping; 0
  // otherwise): the base dissipates base_damper() int |v(x, -1)_x|^2 dx.
  virtual double base_damper() const noexcept { return 0.0; }
  // A viscoelastic top's half-plane surface compliance H(t), which the
  // kernel's quadrature subtracts from M1 (the rest decays exponentially):
  // phi1() (a constant) for an elastic top; for a quasi-static viscoelastic
  // one (1 - nu)/m(t) = phi1 (1 + memory(t)) (viscoelastic.hpp), whose
  // slow part the collocation takes exactly (memory()).
  virtual cplx half_plane_m1(double /*t*/) const { return phi1(); }
  // The memory part of the kernel of a viscoelastic top (null: none).
  virtual const MemoryKernel* memory() const noexcept { return nullptr; }
  // The top's half-plane surface sigma_x symbol, which the surface stress's
  // quadrature subtracts from M2: phi2() (a constant) but for a viscoelastic
  // top with inertia, phi2(vstar/m(t)) = phi2 (1 + sum_k d_k/(1 - i beta_k t)),
  // whose memory (d_k, beta_k) stress_memory() gives (null: none).
  virtual cplx half_plane_m2(double /*t*/) const { return phi2(); }
  virtual const RetardationSpectrum* stress_memory() const noexcept { return nullptr; }
  // A viscoelastic top's material compliance, m_inf/m(t) - 1 = sum_k c_k/(1 -
  // i beta_k t) (its retardation spectrum; the memory() of the quasi-static
  // layer, not of one with inertia); null for an elastic top.
  virtual const RetardationSpectrum* compliance_memory() const noexcept { return nullptr; }
  // The homogeneous layer on springs as DampedLayerModel (its closed-form
  // modal fields are the fast path of the asymmetric solver's depth
  // outputs); null for any other medium.
  virtual const DampedLayerModel* homogeneous_layer() const noexcept { return nullptr; }

  // The description and speed this medium was built from; the cache key.
  virtual const MediumSpec& spec() const noexcept = 0;
  std::vector<double> key() const;
};

// Where displacements are measured from when long_wave_m1() != 0 (a
// half-space base): the surface point at |x| = kDisplacementReference h
// (v(x, y) is then v(x, y) - v(kDisplacementReference, 0); 0 elsewhere).
inline constexpr double kDisplacementReference = 100.0;

// The medium of `spec` at speed vstar. Throws InvalidParameter (errors.hpp)
// for an invalid spec or a speed the medium cannot carry (vstar in [0,
// max_vstar(spec))), std::invalid_argument for a combination not supported.
// A damped homogeneous layer (damping > 0) has real() == false: the
// asymmetric solver's only.
std::shared_ptr<const Medium> make_medium(const MediumSpec& spec, double vstar);
// make_medium through a cache of the kMediumCacheCapacity most recent media
// (by vstar and MediumSpec::key(); immutable, shared; thread-safe): the warm
// solves of a medium build it once.
inline constexpr std::size_t kMediumCacheCapacity = 16;
std::shared_ptr<const Medium> cached_medium(const MediumSpec& spec, double vstar);

// The critical speed of a medium: the lowest vstar of a free steady wave,
// including infima approached only as t -> inf or t -> 0 (t = inf or 0 then).
// The homogeneous layer's is critical_speed(kw, nu, kp) (dispersion.hpp).
CriticalSpeed critical_speed(const MediumSpec& spec);

}  // namespace movingpunch

// The medium interface (medium.hpp): the description's checks and keys, the
// paper's homogeneous layer as one implementation, and the factory.
#include "movingpunch/medium.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>

#include "layer_basis.hpp"
#include "movingpunch/asymmetric.hpp"
#include "movingpunch/errors.hpp"
#include "stack.hpp"

namespace movingpunch {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// The softest springs any solve accepts (contact.cpp's kMinKw).
constexpr double kMinKw = 1e-12;

// A real mode state of the homogeneous layer and its sigma_x (Hooke's law).
ModeState real_state(const WaveConstants& c, const Eigen::Vector4d& z) {
  ModeState s;
  s.z = z.cast<cplx>();
  s.sx = sigma_x_hat(c, z);
  return s;
}

// The homogeneous layer on springs (LayerModel) behind the interface.
class HomogeneousMode final : public ModeProfile {
 public:
  HomogeneousMode(const LayerModel& m, double t) : field_(m.mode_field(t)), c_(&m.constants()) {}
  ModeState remainder(double y, bool /*below*/) const override {
    // As the stresses always took it: the state minus the half-plane state,
    // then Hooke's law on the difference (one material).
    return real_state(*c_, field_.state(y) - field_.half_plane_state(y));
  }
  ModeState half_plane(double y) const override {
    return real_state(*c_, field_.half_plane_state(y));
  }
  ModeState state(double y, bool /*below*/) const override {
    return real_state(*c_, field_.state(y));
  }

 private:
  ModeField field_;
  const WaveConstants* c_;
};

// The damped layer's mode (complex): DampedLayerModel::state, the same
// half-plane part (the base does not enter it). A quasi-static viscoelastic
// layer's too (ViscoelasticLayerMedium): the layer in units of its modulus
// mu_0 m(t), so that its displacements (both the state's and the half-plane
// part's) are divided by m(t); 1 for an elastic layer.
class DampedHomogeneousMode final : public ModeProfile {
 public:
  DampedHomogeneousMode(const LayerModel& m, const DampedLayerModel& d, double t,
                        cplx modulus = 1.0)
      : field_(m.mode_field(t)), damped_(&d), c_(&m.constants()), t_(t), m_(modulus) {}
  ModeState remainder(double y, bool below) const override {
    const ModeState z = state(y, below), h = half_plane(y);
    ModeState s;
    s.z = z.z - h.z;
    s.sx = z.sx - h.sx;
    return s;
  }
  ModeState half_plane(double y) const override {
    ModeState s = real_state(*c_, field_.half_plane_state(y));
    if (m_ != 1.0) s.z.head<2>() /= m_;
    return s;
  }
  ModeState state(double y, bool /*below*/) const override {
    ModeState s;
    s.z = damped_->state(t_, y);
    // sigma_x by Hooke's law at the modulus of the state's units.
    s.sx = 4.0 * (c_->c2 - 1.0) / c_->c2 * s.z(0) + (c_->c2 - 2.0) / c_->c2 * s.z(3);
    if (m_ != 1.0) s.z.head<2>() /= m_;
    return s;
  }

 private:
  ModeField field_;
  const DampedLayerModel* damped_;
  const WaveConstants* c_;
  double t_;
  cplx m_;
};

class HomogeneousMedium final : public Medium {
 public:
  HomogeneousMedium(const MediumSpec& spec, double vstar)
      : spec_(spec),
        model_(vstar, spec.base.kw, spec.layers[0].nu, spec.base.kp),
        damped_(vstar, spec.base.kw, spec.layers[0].nu, spec.base.damping, spec.base.kp) {}
  double vstar() const noexcept override { return model_.vstar(); }
  const WaveConstants& top() const noexcept override { return model_.constants(); }
  bool real() const noexcept override { return !(spec_.base.damping > 0.0); }
  MediumResponse surface_response(double t) const override {
    if (!real()) {
      const FullResponse r = damped_.response(t);
      return MediumResponse{r.M1, r.M2, r.U0, r.W0};
    }
    const Response r = model_.response(t);
    return MediumResponse{r.M1, r.M2, r.U0, r.W0};
  }
  std::unique_ptr<const ModeProfile> mode(double t) const override {
    if (!real()) return std::make_unique<DampedHomogeneousMode>(model_, damped_, t);
    return std::make_unique<HomogeneousMode>(model_, t);
  }
  // The asymmetric solver's: the damped layer's closed forms (damping 0:
  // the same layer's, as that solver always evaluated it).
  FullResponse full_response(double t) const override { return damped_.response(t); }
  Eigen::Vector4cd normal_state(double t, double y) const override { return damped_.state(t, y); }
  Eigen::Vector4cd tangential_state(double t, double y) const override {
    return damped_.tangential_state(t, y);
  }
  const TangentialHalfPlane& tangential() const noexcept override { return damped_.tangential(); }
  // The bar: Ep - vstar (Ep = 4 (c2 - 1)/c2, the plane-strain modulus over mu).
  double bar_compliance() const noexcept override {
    const WaveConstants& c = model_.constants();
    return 1.0 / (4.0 * (c.c2 - 1.0) / c.c2 - c.s);
  }
  double base_damper() const noexcept override {
    return spec_.base.damping * std::sqrt(model_.vstar());
  }
  const DampedLayerModel* homogeneous_layer() const noexcept override { return &damped_; }
  double dispersion(double t) const override { return model_.dispersion(t); }
  // M1 - phi1 ~ (1 + 4t) exp(-2 nT t); the field at the bottom, exp(-nT t).
  double decay_rate() const noexcept override { return 2.0 * model_.constants().nT; }
  double field_decay_rate() const noexcept override { return model_.constants().nT; }
  std::vector<double> first_panel_edges(double w) const override {
    return detail::foundation_panel_edges(model_.kw(), model_.kp(), w);
  }
  const MediumSpec& spec() const noexcept override { return spec_; }

 private:
  MediumSpec spec_;
  LayerModel model_;
  DampedLayerModel damped_;
};

// A viscoelastic homogeneous layer on springs (docs/theory.md section 17):
// the elastic layer in units of its modulus at each frequency, mu_0 m(t), on
// springs kw(t)/m(t) at the speed vstar/m(t) (DampedLayerModel with the
// material; complex wave constants when vstar > 0), its displacements
// divided by m(t). The half-plane part of M1, H(t) = phi1(vstar/m(t))/m(t)
// ((1 - nu)/m(t) at rest), reaches its unrelaxed value only like 1/t: the
// kernel's quadrature subtracts it whole (half_plane_m1) and the collocation
// takes its memory exactly (memory(): the retardation spectrum at rest, the
// inertial spectrum of poles and cut otherwise, viscoelastic.hpp).
class ViscoelasticLayerMedium final : public Medium {
 public:
  ViscoelasticLayerMedium(const MediumSpec& spec, double vstar)
      : spec_(spec),
        model_(vstar, spec.base.kw, spec.layers[0].nu, spec.base.kp),
        damped_(vstar, spec.base.kw, spec.layers[0].nu, 0.0, spec.base.kp, spec.layers[0].visco),
        visco_(spec.layers[0].visco, vstar, spec.layers[0].nu) {
    top_ = model_.constants();
    // The Cauchy term's coefficient and the surface sigma_x's local one: the
    // unrelaxed half-plane's (phi2 = 1 at rest whatever the modulus).
    top_.phi1 = visco_.h_inf();
    top_.phi2 = visco_.phi2_inf();
  }
  double vstar() const noexcept override { return model_.vstar(); }
  const WaveConstants& top() const noexcept override { return top_; }
  bool real() const noexcept override { return false; }
  MediumResponse surface_response(double t) const override {
    const FullResponse r = full_response(t);
    return MediumResponse{r.M1, r.M2, r.U0, r.W0};
  }
  std::unique_ptr<const ModeProfile> mode(double t) const override {
    return std::make_unique<DampedHomogeneousMode>(model_, damped_, t, visco_.modulus(t));
  }
  FullResponse full_response(double t) const override {
    FullResponse r = damped_.response(t);
    const cplx m = visco_.modulus(t);
    for (cplx* v : {&r.M1, &r.U0, &r.W0, &r.Wb, &r.Uq, &r.Wq, &r.Wqb}) *v /= m;
    return r;
  }
  Eigen::Vector4cd normal_state(double t, double y) const override {
    Eigen::Vector4cd z = damped_.state(t, y);
    z.head<2>() /= visco_.modulus(t);
    return z;
  }
  Eigen::Vector4cd tangential_state(double t, double y) const override {
    Eigen::Vector4cd z = damped_.tangential_state(t, y);
    z.head<2>() /= visco_.modulus(t);
    return z;
  }
  const TangentialHalfPlane& tangential() const noexcept override { return damped_.tangential(); }
  double bar_compliance() const noexcept override {
    return 1.0 / (4.0 * (top_.c2 - 1.0) / top_.c2 - top_.s);
  }
  double dispersion(double t) const override { return model_.dispersion(t); }
  double decay_rate() const noexcept override { return 2.0 * top_.nT; }
  double field_decay_rate() const noexcept override { return top_.nT; }
  std::vector<double> first_panel_edges(double w) const override {
    return detail::foundation_panel_edges(model_.kw(), model_.kp(), w);
  }
  cplx half_plane_m1(double t) const override { return visco_.m1(t); }
  const MemoryKernel* memory() const noexcept override { return &visco_.memory(); }
  cplx half_plane_m2(double t) const override { return visco_.m2(t); }
  const RetardationSpectrum* stress_memory() const noexcept override {
    return visco_.stress_memory();
  }
  const RetardationSpectrum* compliance_memory() const noexcept override {
    return &visco_.compliance_memory();
  }
  const MediumSpec& spec() const noexcept override { return spec_; }

 private:
  MediumSpec spec_;
  LayerModel model_;
  DampedLayerModel damped_;
  ViscoelasticTop visco_;
  WaveConstants top_;
};

std::string str(double x) {
  std::ostringstream o;
  o << x;
  return o.str();
}

}  // namespace

ModeState ModeProfile::state(double y, bool below) const {
  const ModeState r = remainder(y, below), h = half_plane(y);
  ModeState s;
  s.z = r.z + h.z;
  s.sx = r.sx + h.sx;
  return s;
}

std::vector<double> MediumSpec::key() const {
  if (homogeneous())
    // As the homogeneous tables were always keyed: kp is irrelevant on a
    // rigid base.
    return {layers[0].nu, base.kw, std::isinf(base.kw) ? 0.0 : base.kp, base.damping};
  std::vector<double> k;
  k.reserve(kSublayerRow * layers.size() + 8);
  k.push_back(static_cast<double>(layers.size()));
  for (const Sublayer& l : layers)
    for (const SublayerField& f : kSublayerFields) k.push_back(l.*f.member);
  k.push_back(static_cast<double>(static_cast<int>(base.kind)));
  if (base.kind == BaseKind::springs) {
    k.push_back(base.kw);
    k.push_back(std::isinf(base.kw) ? 0.0 : base.kp);
    k.push_back(base.damping);
  } else {
    for (const HalfSpaceField& f : kHalfSpaceFields) k.push_back(base.*f.member);
  }
  // Each sublayer's material (its branches' count, weights, deborah numbers
  // and shift): empty for elastic stacks, so their keys are unchanged.
  if (viscoelastic())
    for (const Sublayer& l : layers) {
      k.push_back(static_cast<double>(l.visco.weights.size()));
      k.insert(k.end(), l.visco.weights.begin(), l.visco.weights.end());
      k.insert(k.end(), l.visco.deborahs.begin(), l.visco.deborahs.end());
      k.push_back(l.visco.shift);
    }
  return k;
}

bool MediumSpec::viscoelastic() const noexcept {
  return std::any_of(layers.begin(), layers.end(),
                     [](const Sublayer& l) { return !l.visco.empty(); });
}

const KernelAsymptotics& Medium::kernel_asymptotics() const noexcept {
  static const KernelAsymptotics none{};
  return none;
}

std::vector<double> Medium::key() const {
  std::vector<double> k{vstar()};
  const std::vector<double> s = spec().key();
  k.insert(k.end(), s.begin(), s.end());
  return k;
}

std::string describe(const MediumSpec& m) {
  std::ostringstream o;
  o.precision(6);
  const std::size_t graded = static_cast<std::size_t>(std::count_if(
      m.layers.begin(), m.layers.end(), [](const Sublayer& l) { return l.gamma != 0.0; }));
  auto material = [&o](const Viscoelastic& v) {
    if (v.weights.size() == 1)
      o << "Zener, ratio " << v.ratio() << ", deborah " << v.shift * v.deborahs[0];
    else
      o << "Prony, " << v.weights.size() << " branches, ratio " << v.ratio();
  };
  if (m.viscoelastic() && m.layers.size() == 1) {
    o << "a viscoelastic layer (";
    material(m.layers[0].visco);
    o << ") on ";
  }
  if (m.layers.size() > 1 || graded > 0) {
    o << m.layers.size() << (m.layers.size() == 1 ? " sublayer" : " sublayers");
    if (graded > 0) o << " (" << graded << " graded)";
    if (m.layers.size() > 1 && m.viscoelastic()) {
      // Each viscoelastic sublayer's material, by its index.
      const char* sep = " (";
      for (std::size_t i = 0; i < m.layers.size(); ++i) {
        if (m.layers[i].visco.empty()) continue;
        o << sep << "layers[" << i << "]: ";
        material(m.layers[i].visco);
        sep = "; ";
      }
      o << ")";
    }
    o << " on ";
  }
  const BaseSpec& b = m.base;
  if (b.kind == BaseKind::springs) {
    o << "kw = " << b.kw;
    if (b.kp != 0.0) o << ", kp = " << b.kp;
    if (b.damping != 0.0) o << ", damping = " << b.damping;
  } else {
    o << "a " << (b.kind == BaseKind::half_space_bonded ? "bonded" : "smooth") << " half-space (";
    const char* sep = "";
    for (const HalfSpaceField& f : kHalfSpaceFields) {
      o << sep << f.name << " " << b.*f.member;
      sep = ", ";
    }
    o << ")";
  }
  return o.str();
}

MediumSpec homogeneous_medium(double kw, double nu, double kp, double damping) {
  MediumSpec m;
  m.layers = {Sublayer{1.0, 1.0, nu, 1.0, 0.0}};
  m.base.kind = BaseKind::springs;
  m.base.kw = kw;
  m.base.kp = kp;
  m.base.damping = damping;
  return m;
}

void validate(const MediumSpec& m) {
  if (m.layers.empty())
    throw InvalidParameter("layers", "at least one sublayer", "layers: at least one sublayer");
  if (m.layers.size() > kMaxSublayers)
    throw InvalidParameter("layers", "at most " + std::to_string(kMaxSublayers) + " sublayers",
                           "layers: " + std::to_string(m.layers.size()) +
                               " sublayers given, at most " + std::to_string(kMaxSublayers));
  double total = 0.0;
  for (std::size_t i = 0; i < m.layers.size(); ++i) {
    const Sublayer& l = m.layers[i];
    const std::string at = "layers[" + std::to_string(i) + "].";
    for (const SublayerField& f : kSublayerFields)
      require_in_range((at + f.name).c_str(), l.*f.member, f.lo, f.hi, f.lo_open, f.hi_open);
    validate(l.visco, at + "viscoelastic");
    total += l.thickness;
  }
  if (m.layers[0].mu != 1.0 || m.layers[0].rho != 1.0)
    throw InvalidParameter("layers[0].mu", "1 (the top sublayer is the unit of mu and rho)",
                           "layers[0]: the top sublayer's mu and rho are the units (1 by "
                           "definition); given mu = " +
                               str(m.layers[0].mu) + ", rho = " + str(m.layers[0].rho) +
                               ": divide every sublayer's mu and rho by the top's");
  if (!(std::fabs(total - 1.0) <= 1e-12))
    throw InvalidParameter("layers", "thicknesses summing to 1 (the total thickness h)",
                           "layers: the thicknesses sum to " + str(total) +
                               "; they must sum to 1 (lengths are in the total thickness h)");
  const BaseSpec& b = m.base;
  switch (b.kind) {
    case BaseKind::springs:
      require_in_range("kw", b.kw, kMinKw, kInf, false, false, true);
      require_in_range("kp", b.kp, 0.0, kMaxKp, false, false);
      require_in_range("damping", b.damping, 0.0, kInf, false, true);
      break;
    case BaseKind::half_space_bonded:
    case BaseKind::half_space_smooth:
      for (const HalfSpaceField& f : kHalfSpaceFields)
        require_in_range((std::string("base.") + f.name).c_str(), b.*f.member, f.lo, f.hi,
                         f.lo_open, f.hi_open);
      break;
  }
}

std::shared_ptr<const Medium> make_medium(const MediumSpec& spec, double vstar) {
  validate(spec);
  if (spec.viscoelastic()) {
    for (std::size_t i = 0; i < spec.layers.size(); ++i)
      if (!spec.layers[i].visco.empty() && spec.layers[i].gamma != 0.0)
        throw InvalidParameter(
            "layers[" + std::to_string(i) + "].viscoelastic",
            "an elastic graded sublayer or a homogeneous viscoelastic one",
            "layers[" + std::to_string(i) +
                "]: a graded sublayer is elastic (a viscoelastic material takes a homogeneous "
                "sublayer; a staircase of them grades it); given " +
                describe(spec));
    if (spec.base.kind == BaseKind::springs && spec.base.damping != 0.0)
      throw InvalidParameter(
          "damping", "0 under a viscoelastic layer",
          "damping: dashpots under a viscoelastic layer are not built; give damping = 0 (the "
          "layer's material dissipates)");
    // One homogeneous layer on springs: its closed form; any other medium
    // with a viscoelastic sublayer: the stack, propagated at complex moduli.
    if (spec.layers.size() == 1 && spec.base.kind == BaseKind::springs)
      return std::make_shared<const ViscoelasticLayerMedium>(spec, vstar);
    return make_stack_medium(spec, vstar);
  }
  if (spec.homogeneous()) return std::make_shared<const HomogeneousMedium>(spec, vstar);
  return make_stack_medium(spec, vstar);
}

std::shared_ptr<const Medium> cached_medium(const MediumSpec& spec, double vstar) {
  // The most recent media, newest last (a viscoelastic medium with inertia
  // fits its memory's spectra when built: milliseconds a Prony material,
  // more than a warm solve; a solve asks for its medium before its kernel).
  static std::mutex mutex;
  static std::vector<std::pair<std::vector<double>, std::shared_ptr<const Medium>>> recent;
  std::vector<double> key{vstar};
  const std::vector<double> sk = spec.key();
  key.insert(key.end(), sk.begin(), sk.end());
  {
    const std::lock_guard<std::mutex> lock(mutex);
    for (auto it = recent.begin(); it != recent.end(); ++it)
      if (it->first == key) {
        auto hit = std::move(*it);
        recent.erase(it);
        recent.push_back(std::move(hit));
        return recent.back().second;
      }
  }
  std::shared_ptr<const Medium> m = make_medium(spec, vstar);  // (throws as make_medium)
  const std::lock_guard<std::mutex> lock(mutex);
  if (recent.size() >= kMediumCacheCapacity) recent.erase(recent.begin());
  recent.emplace_back(std::move(key), m);
  return m;
}

CriticalSpeed critical_speed(const MediumSpec& spec) {
  validate(spec);
  // A viscoelastic layer: its relaxed (softest, slowest) elastic layer's.
  if (spec.viscoelastic() && spec.layers.size() == 1 && spec.base.kind == BaseKind::springs)
    return critical_speed(spec.base.kw, spec.layers[0].nu, spec.base.kp);
  if (spec.homogeneous()) return critical_speed(spec.base.kw, spec.layers[0].nu, spec.base.kp);
  return stack_critical_speed(spec);
}

}  // namespace movingpunch

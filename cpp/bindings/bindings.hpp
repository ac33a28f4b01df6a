// Private to the binding layer: one bind_<area>() per cpp/bindings/bind_<area>.cpp,
// wired together by module.cpp.
#pragma once

#include <array>
#include <atomic>
#include <memory>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <Eigen/Dense>

#include "movingpunch/contact.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/interrupt.hpp"
#include "movingpunch/medium.hpp"
#include "movingpunch/profile.hpp"
#include "movingpunch/stresses.hpp"

namespace movingpunch::bindings {

// A cancellation token (Python: movingpunch.Cancel). cancel() may be called
// from any thread; computations on a thread the token is bound to (the
// Python `with token:` block, or a solve's cancel= keyword) stop at their next
// check and raise movingpunch.errors.Cancelled. A cancelled token stays
// cancelled. Reading it needs no GIL (an atomic flag).
class CancelToken {
 public:
  void cancel() noexcept { flag_.store(true, std::memory_order_relaxed); }
  bool cancelled() const noexcept { return flag_.load(std::memory_order_relaxed); }

 private:
  std::atomic<bool> flag_{false};
};

// Thrown (at a call's entry, or by CancelToken.check()) when a token bound to
// this thread is cancelled; the translator (bind_errors) raises Cancelled.
struct CancelledByToken {};

// The tokens bound to this thread, innermost last (a copy).
std::vector<std::shared_ptr<CancelToken>> bound_tokens();
// Whether any token bound to this thread is cancelled.
bool bound_token_cancelled() noexcept;

// The call guard of a long computation (a solve): releases the GIL and lets
// it be stopped. On the main thread, every ~50 ms the core's loops
// (check_interrupt) take the GIL back for PyErr_CheckSignals(); when a
// Python signal handler raises (KeyboardInterrupt from the default SIGINT
// handler, or the CLI's own), the computation unwinds with Interrupted and
// the exception translator (bind_errors) raises that very Python exception.
// On every thread the tokens bound to it (CancelToken) are polled too, an
// atomic read without the GIL: a cancelled one unwinds the computation and
// the translator raises movingpunch.errors.Cancelled. A token already
// cancelled stops the call at its entry. On a thread other than the main one
// with no token bound nothing is polled: Python runs signal handlers on the
// main thread only, and taking the GIL there would only slow the solve.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  bool main_thread_;
  pybind11::gil_scoped_release release_;  // after main_thread_: computed with the GIL
  std::unique_ptr<InterruptScope> scope_;
};
using Interruptible = pybind11::call_guard<InterruptGuard>;

// The call guard of a short computation (a result's pressure, stresses,
// maps): a cancellation point, then the GIL released. Raises Cancelled at
// the call's entry when a token bound to this thread is cancelled, so a
// Python loop over such calls (peaks, maps, sweeps) stops at its next call.
class CancelPoint {
 public:
  CancelPoint();
  CancelPoint(const CancelPoint&) = delete;
  CancelPoint& operator=(const CancelPoint&) = delete;

 private:
  pybind11::gil_scoped_release release_;
};
using Released = pybind11::call_guard<CancelPoint>;

// Raises the Python exception that stopped a computation on this thread
// (Cancelled if a token did, else the signal handler's, else
// KeyboardInterrupt). Under the GIL; the translator's part.
void raise_interrupted();
// Raises movingpunch.errors.Cancelled. Under the GIL.
void raise_cancelled();

// The stage times of a solve (either solver) as {stage: seconds}.
inline pybind11::dict stage_dict(const SymmetricSolution::StageSeconds& t) {
  pybind11::dict d;
  d["critical_speed"] = t.critical_speed;
  d["kernel"] = t.kernel;
  d["width"] = t.width;
  d["checks"] = t.checks;
  return d;
}

template <class T>
void bind_result_common(pybind11::class_<T>& cls);

// A result class with the members every contact result has (below).
template <class T>
pybind11::class_<T> bind_result_class(pybind11::module_& m, const char* name, const char* doc) {
  pybind11::class_<T> cls(m, name, doc);
  bind_result_common(cls);
  return cls;
}

// The profile kind from its API name ('cylinder', 'flat', 'rounded_flat',
// 'table'); InvalidParameter naming profile otherwise.
ProfileKind profile_kind(const std::string& name);

// The punch's shape of either solver's parameters (the same names).
template <class P>
void set_profile(P& p, const std::string& profile, double half_width,
                 const std::vector<double>& table_x, const std::vector<double>& table_y) {
  p.profile = profile_kind(profile);
  p.half_width = half_width;
  p.table_x = table_x;
  p.table_y = table_y;
}

// A medium from Python: sublayers as (thickness, mu, nu, rho, gamma_h) rows
// top to bottom, the base's kind ("springs", "bonded", "smooth"), the
// springs' (kw, kp, damping) and the half-space's row (kHalfSpaceFields). Null for no
// sublayers and springs: the homogeneous layer of the solve's kw, nu, kp.
// A sublayer's row: its scalars in the order of kSublayerFields (medium.hpp).
using LayerRows = std::vector<std::array<double, kSublayerRow>>;
// The half-space's row: its scalars in the order of kHalfSpaceFields.
using HalfSpaceRow = std::array<double, kHalfSpaceRow>;
// The row of BaseSpec's defaults (the bindings' default `half_space=`).
inline HalfSpaceRow default_half_space_row() {
  const BaseSpec b;
  HalfSpaceRow r{};
  for (std::size_t i = 0; i < kHalfSpaceRow; ++i) r[i] = b.*kHalfSpaceFields[i].member;
  return r;
}
// The sublayers' materials (viscoelastic.hpp), one per row or none: (the
// branches' weights, their deborah numbers, the shift factor); empty weights:
// elastic.
using MaterialRows = std::vector<std::tuple<std::vector<double>, std::vector<double>, double>>;
inline std::shared_ptr<const MediumSpec> medium_spec(const LayerRows& layers,
                                                     const std::string& base, double kw, double kp,
                                                     double damping, const HalfSpaceRow& half_space,
                                                     const MaterialRows& materials = {}) {
  if (!materials.empty() && materials.size() != layers.size())
    throw InvalidParameter("materials", "one per sublayer",
                           "materials: " + std::to_string(materials.size()) + " given for " +
                               std::to_string(layers.size()) + " sublayers");
  if (layers.empty() && base == "springs") return nullptr;
  if (layers.empty())
    throw InvalidParameter("layers", "at least one sublayer",
                           "layers: a half-space base needs the sublayers above it");
  auto m = std::make_shared<MediumSpec>();
  m->layers.clear();
  for (const auto& r : layers) {
    Sublayer l;
    for (std::size_t i = 0; i < kSublayerRow; ++i) l.*kSublayerFields[i].member = r[i];
    if (!materials.empty()) {
      const auto& [weights, deborahs, shift] = materials[m->layers.size()];
      l.visco.weights = weights;
      l.visco.deborahs = deborahs;
      l.visco.shift = shift;
    }
    m->layers.push_back(l);
  }
  if (base == "springs")
    m->base.kind = BaseKind::springs;
  else if (base == "bonded")
    m->base.kind = BaseKind::half_space_bonded;
  else if (base == "smooth")
    m->base.kind = BaseKind::half_space_smooth;
  else
    throw InvalidParameter("base", "'springs', 'bonded' or 'smooth'",
                           "base must be 'springs', 'bonded' or 'smooth', got '" + base + "'");
  m->base.kw = kw;
  m->base.kp = kp;
  m->base.damping = damping;
  for (std::size_t i = 0; i < kHalfSpaceRow; ++i)
    m->base.*kHalfSpaceFields[i].member = half_space[i];
  validate(*m);
  return m;
}

// The inputs every solve takes (ContactParams, AsymmetricParams: the same names),
// from the keyword arguments of solve_contact / solve_asymmetric.
template <class P>
P solve_params(double vstar, double kw, double radius, double load, double nu, double tol,
               bool allow_unphysical, int n) {
  P p;
  p.vstar = vstar;
  p.kw = kw;
  p.radius = radius;
  p.load = load;
  p.nu = nu;
  p.tol = tol;
  p.allow_unphysical = allow_unphysical;
  p.n = n;
  return p;
}

// The members every contact result binds alike (SymmetricSolution,
// AsymmetricSolution: the same C++ names and signatures), bound once here; each
// bind_<area>() adds what only its result has. Docstrings say "the contact
// ends" for both (-a, a) and (-b, a).
template <class T>
void bind_result_common(pybind11::class_<T>& cls) {
  namespace py = pybind11;
  using namespace pybind11::literals;
  using VectorRef = Eigen::Ref<const Eigen::VectorXd>;
  using Release = Released;  // a cancellation point (CancelPoint)
  cls.def_property_readonly("critical_vstar", &T::critical_vstar,
                            "Critical speed V*_cr(kw, nu) of the undamped layer.")
      .def_property_readonly("rayleigh_vstar", &T::rayleigh_vstar, "Rayleigh speed V*_R(nu).")
      .def_property_readonly("phi1", &T::phi1, "Moving half-plane factor phi1(vstar, nu).")
      .def_property_readonly("error_estimate", &T::error_estimate,
                             "Absolute error estimate (in h) of the contact ends.")
      .def_property_readonly("elapsed", &T::elapsed, "Wall-clock time of the solve in seconds.")
      .def_property_readonly("iterations", &T::iterations,
                             "Width (load) evaluations over all collocation sizes.")
      .def_property_readonly("collocation_n", &T::collocation_n,
                             "Number N of collocation nodes of the final solve.")
      .def_property_readonly(
          "stage_seconds", [](const T& s) { return stage_dict(s.stage_seconds()); },
          "Seconds per stage: critical_speed, kernel (fetching or building the kernel "
          "table), width (the iteration on the contact's width), checks (the rest: "
          "indentation or the scan for other steady states, estimates, validity).")
      .def_property_readonly("kernel_builds", &T::kernel_builds,
                             "Kernel tables this solve built (0: reused from the "
                             "process-wide cache).")
      .def_property_readonly("valid", &T::valid,
                             "True if p >= 0 on the contact and the punch does not "
                             "penetrate the surface beside it.")
      .def_property_readonly("validity", &T::validity,
                             "Human-readable account of the validity checks.")
      .def_property_readonly("min_pressure", &T::min_pressure, "Minimum of p/(P/h) on the contact.")
      .def_property_readonly("pressure_margin", &T::pressure_margin,
                             "min over r in (-1, 1) of p/((P/h) sqrt(1 - r^2)), r the "
                             "position scaled to the contact: the margin before separation.")
      .def_property_readonly("min_gap", &T::min_gap,
                             "Minimum gap/h between punch and surface beside the contact.")
      .def_property_readonly(
          "warnings", [](const T& s) { return py::list(py::cast(s.warnings())); },
          "One line per requested accuracy that was not met (empty: none).")
      .def_property_readonly("indentation", &T::indentation, "Indentation delta/h of the punch.")
      .def_property_readonly(
          "g_coefficients", [](const T& s) -> Eigen::VectorXd { return s.g_coefficients(); },
          "Chebyshev-U coefficients of g(r) = p(c + w r)/((P/h) sqrt(1 - r^2)) (a copy; "
          "c = 0, w = a for a symmetric contact).")
      .def(
          "pressure",
          [](const T& s, const VectorRef& x) -> Eigen::VectorXd { return s.pressure(x); }, "x"_a,
          Release(),
          "Contact pressure p/(P/h) at each x/h (0 outside the contact). x: 1-D float64.")
      .def(
          "surface_displacement",
          [](const T& s, const VectorRef& x) -> Eigen::VectorXd {
            return s.surface_displacement(x);
          },
          "x"_a, Release(),
          "Vertical surface displacement v(x, 0)/h at each x/h (negative under the punch).")
      .def(
          "surface_stress",
          [](const T& s, const VectorRef& x) -> Eigen::VectorXd { return s.surface_stress(x); },
          "x"_a, Release(), "sigma_x(x, 0)/(P/h) at each x/h.")
      .def(
          "displacement",
          [](const T& s, const VectorRef& x, const VectorRef& y) -> Eigen::MatrixXd {
            return s.displacement(x, y);
          },
          "x"_a, "y"_a, Release(),
          "Vertical displacement v/h on the grid x/h by y/h (-1 <= y <= 0), shaped "
          "(len(y), len(x)).")
      .def(
          "stress_field",
          [](const T& s, const VectorRef& x, const VectorRef& y, bool below) {
            StressField f;
            f = s.stress_field(x, y, below);
            return std::make_tuple(std::move(f.sigma_x), std::move(f.sigma_y), std::move(f.tau_xy));
          },
          "x"_a, "y"_a, "below"_a = false, Release(),
          "(sigma_x, sigma_y, tau_xy)/(P/h) on the grid x/h by y/h, each shaped (len(y), "
          "len(x)) (the damped solver: -1 <= y <= -1e-3); below: at an interface, sigma_x "
          "of the material below it.");
}

void bind_errors(pybind11::module_& m);
void bind_interrupt(pybind11::module_& m);
void bind_layer(pybind11::module_& m);
void bind_contact(pybind11::module_& m);
void bind_asymmetric(pybind11::module_& m);
void bind_zones(pybind11::module_& m);

}  // namespace movingpunch::bindings

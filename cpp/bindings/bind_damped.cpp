// The damped-foundation solve (Kelvin-Voigt base) and its result. Adapters only.
#include <complex>
#include <string>
#include <tuple>
#include <utility>

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <Eigen/Dense>

#include "bindings.hpp"
#include "movingpunch/damped.hpp"

namespace py = pybind11;
using namespace py::literals;

namespace movingpunch::bindings {

namespace {

using VectorRef = Eigen::Ref<const Eigen::VectorXd>;

template <class F>
Eigen::VectorXd each(const VectorRef& x, F f) {
  Eigen::VectorXd out(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) out(i) = f(x(i));
  return out;
}

}  // namespace

void bind_damped(py::module_& m) {
  using Release = py::call_guard<py::gil_scoped_release>;

  py::class_<DampedSolution>(
      m, "DampedSolution",
      "Result of solve_damped (dimensionless: h = 1, mu = 1, pressures per P/h). "
      "Not constructible from Python.")
      .def_property_readonly("left", &DampedSolution::left,
                             "Trailing end -b/h of the contact (-b, a).")
      .def_property_readonly("right", &DampedSolution::right,
                             "Leading end a/h of the contact (-b, a).")
      .def_property_readonly("centre", &DampedSolution::centre, "Centre (a - b)/(2h).")
      .def_property_readonly("half_width", &DampedSolution::half_width, "Half-width (a + b)/(2h).")
      .def_property_readonly("drag", &DampedSolution::drag,
                             "Horizontal force on the punch over P, int p x/R dx / P "
                             "(positive: opposes the motion).")
      .def_property_readonly("critical_vstar", &DampedSolution::critical_vstar,
                             "Critical speed V*_cr(kw, nu) of the undamped layer.")
      .def_property_readonly("rayleigh_vstar", &DampedSolution::rayleigh_vstar,
                             "Rayleigh speed V*_R(nu).")
      .def_property_readonly("phi1", &DampedSolution::phi1,
                             "Moving half-plane factor phi1(vstar, nu).")
      .def_property_readonly("error_estimate", &DampedSolution::error_estimate,
                             "Bound on the absolute error of each contact end (in h).")
      .def_property_readonly("pressure_error_estimate", &DampedSolution::pressure_error_estimate,
                             "Bound on the error of p/(P/h) at a fixed relative position "
                             "r = (x - c)/w in the contact.")
      .def_property_readonly("stress_error_estimate", &DampedSolution::stress_error_estimate,
                             "Bound on the error of the surface sigma_x/(P/h) more than "
                             "1e-3 (a + b)/2 from the contact ends.")
      .def_property_readonly("max_pressure", &DampedSolution::max_pressure,
                             "Maximum of p/(P/h) on the contact.")
      .def_property_readonly("pressure_margin", &DampedSolution::pressure_margin,
                             "min over r in (-1, 1) of p/((P/h) sqrt(1 - r^2)), r the "
                             "position scaled to the contact: the margin before separation.")
      .def_property_readonly(
          "warnings", [](const DampedSolution& s) { return py::list(py::cast(s.warnings())); },
          "One line per requested accuracy that was not met; empty when tol was met.")
      .def_property_readonly("iterations", &DampedSolution::iterations,
                             "Width evaluations over all collocation sizes.")
      .def_property_readonly("kernel_builds", &DampedSolution::kernel_builds,
                             "Kernel tables this solve built (0: reused from the "
                             "process-wide cache).")
      .def_property_readonly(
          "stage_seconds", [](const DampedSolution& s) { return stage_dict(s.stage_seconds()); },
          "Seconds per stage: critical_speed, kernel (fetching or building the kernel "
          "table), width (the iteration on the ends over the N ladder), checks (the "
          "scan for other steady states, the estimates and validity).")
      .def_property_readonly("collocation_n", &DampedSolution::collocation_n,
                             "Number N of collocation nodes of the final solve.")
      .def_property_readonly("elapsed", &DampedSolution::elapsed,
                             "Wall-clock time of the solve in seconds.")
      .def_property_readonly("valid", &DampedSolution::valid,
                             "True if p >= 0 on the contact and the punch does not "
                             "penetrate the surface beside it.")
      .def_property_readonly("validity", &DampedSolution::validity,
                             "Human-readable account of the validity checks.")
      .def_property_readonly("min_pressure", &DampedSolution::min_pressure,
                             "Minimum of p/(P/h) on the contact.")
      .def_property_readonly("min_gap", &DampedSolution::min_gap,
                             "Minimum gap/h within 2(a + b) beside the contact.")
      .def_property_readonly(
          "other_half_widths",
          [](const DampedSolution& s) { return py::tuple(py::cast(s.other_half_widths())); },
          "Half-widths (a+b)/(2h) of other contacts carrying the same load (above "
          "V*_cr the steady solution need not be unique); empty when unique.")
      .def_property_readonly(
          "g_coefficients",
          [](const DampedSolution& s) -> Eigen::VectorXd { return s.g_coefficients(); },
          "Chebyshev-U coefficients of g(r) = p(c + w r)/((P/h) sqrt(1 - r^2)).")
      .def(
          "dissipation", [](const DampedSolution& s) { return s.dissipation(); }, Release(),
          "Power dissipated in the dashpots over P V (equals drag by the energy balance).")
      .def(
          "pressure",
          [](const DampedSolution& s, const VectorRef& x) {
            return each(x, [&](double v) { return s.pressure(v); });
          },
          "x"_a, Release(), "Contact pressure p/(P/h) at each x/h (0 outside).")
      .def(
          "surface_slope",
          [](const DampedSolution& s, const VectorRef& x) {
            return each(x, [&](double v) { return s.surface_slope(v); });
          },
          "x"_a, Release(), "Surface slope dv/dx(x, 0) at each x/h.")
      .def(
          "bottom_slope",
          [](const DampedSolution& s, const VectorRef& x) {
            return each(x, [&](double v) { return s.bottom_slope(v); });
          },
          "x"_a, Release(), "Slope dv/dx(x, -h) of the bottom face at each x/h.")
      .def(
          "surface_stress",
          [](const DampedSolution& s, const VectorRef& x) {
            return each(x, [&](double v) { return s.surface_stress(v); });
          },
          "x"_a, Release(), "sigma_x(x, 0)/(P/h) at each x/h.")
      .def(
          "stress_x",
          [](const DampedSolution& s, double x, const VectorRef& y) {
            return each(y, [&](double v) { return s.stress_x(x, v); });
          },
          "x"_a, "y"_a, Release(),
          "sigma_x(x, y)/(P/h) at one x/h and each y/h in [-1, -1e-3] or 0.")
      .def(
          "bottom_displacement",
          [](const DampedSolution& s, const VectorRef& x) {
            return each(x, [&](double v) { return s.bottom_displacement(v); });
          },
          "x"_a, Release(), "Displacement v(x, -h)/h of the bottom face at each x/h.")
      .def_property_readonly("indentation", &DampedSolution::indentation,
                             "Indentation delta/h of the punch (computed on first use).")
      .def(
          "surface_displacement",
          [](const DampedSolution& s, const VectorRef& x) {
            return each(x, [&](double v) { return s.surface_displacement(v); });
          },
          "x"_a, Release(),
          "Vertical surface displacement v(x, 0)/h at each x/h (negative under the punch).")
      .def(
          "displacement",
          [](const DampedSolution& s, const VectorRef& x, const VectorRef& y) -> Eigen::MatrixXd {
            return s.displacement(x, y);
          },
          "x"_a, "y"_a, Release(),
          "Vertical displacement v/h on the grid x/h by y/h, shaped (len(y), len(x)).")
      .def(
          "stress_field",
          [](const DampedSolution& s, const VectorRef& x, const VectorRef& y) {
            DampedStressGrid g = s.stress_grid(x, y);
            return std::make_tuple(std::move(g.sigma_x), std::move(g.sigma_y), std::move(g.tau_xy));
          },
          "x"_a, "y"_a, Release(),
          "(sigma_x, sigma_y, tau_xy)/(P/h) on the grid x/h by y/h (-1 <= y <= -1e-3), "
          "each shaped (len(y), len(x)).")
      .def("__repr__", [](const DampedSolution& s) {
        return py::str("<movingpunch._core.DampedSolution left={!r} right={!r} drag={!r}>")
            .format(s.left(), s.right(), s.drag());
      });

  m.def(
      "solve_damped",
      [](double vstar, double kw, double radius, double load, double nu, double damping, double tol,
         bool allow_unphysical, int n) {
        DampedParams p;
        p.vstar = vstar;
        p.kw = kw;
        p.radius = radius;
        p.load = load;
        p.nu = nu;
        p.damping = damping;
        p.tol = tol;
        p.allow_unphysical = allow_unphysical;
        p.n = n;
        return solve_damped(p);
      },
      py::kw_only(), "vstar"_a, "kw"_a, "radius"_a, "load"_a, "nu"_a, "damping"_a, "tol"_a,
      "allow_unphysical"_a, "n"_a = 0, Release(),
      "Solves the contact problem on a damped (Kelvin-Voigt) foundation, damping = "
      "c_w c_T/mu > 0. Raises InvalidParameterError, SupercriticalSpeedError (vstar >= "
      "V*_R), UnphysicalContactError (unless allow_unphysical) or ConvergenceError.");

  m.def(
      "damped_layer_response",
      [](double t, double vstar, double kw, double nu, double damping) {
        const DampedResponse r = DampedLayerModel(vstar, kw, nu, damping).response(t);
        return py::make_tuple(r.M1, r.M2, r.Wb);
      },
      "t"_a, "vstar"_a, "kw"_a, "nu"_a, "damping"_a,
      "(M1, M2, Wb) of the damped layer at t = alpha h >= 0 (complex; alpha < 0 gives "
      "the conjugates).");
}

}  // namespace movingpunch::bindings

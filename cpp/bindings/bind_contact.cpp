// The contact solve and its result. Adapters only.
#include <string>
#include <tuple>
#include <utility>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <Eigen/Dense>

#include "bindings.hpp"
#include "movingpunch/contact.hpp"

namespace py = pybind11;
using namespace py::literals;

namespace movingpunch::bindings {

void bind_contact(py::module_& m) {
  using VectorRef = Eigen::Ref<const Eigen::VectorXd>;
  using Release = py::call_guard<py::gil_scoped_release>;

  py::class_<ContactSolution>(
      m, "ContactSolution",
      "Result of solve_contact (dimensionless: h = 1, mu = 1, pressures per P/h). "
      "Not constructible from Python.")
      .def_property_readonly("a", &ContactSolution::a, "Contact half-width a/h.")
      .def_property_readonly("p0", &ContactSolution::p0, "Central pressure p(0)/(P/h).")
      .def_property_readonly("indentation", &ContactSolution::indentation,
                             "Indentation delta/h of the punch.")
      .def_property_readonly("critical_vstar", &ContactSolution::critical_vstar,
                             "Critical speed V*_cr(kw, nu).")
      .def_property_readonly("rayleigh_vstar", &ContactSolution::rayleigh_vstar,
                             "Rayleigh speed V*_R(nu).")
      .def_property_readonly("phi1", &ContactSolution::phi1,
                             "Moving half-plane factor phi1(vstar, nu).")
      .def_property_readonly("error_estimate", &ContactSolution::error_estimate,
                             "Absolute error estimate of a/h.")
      .def_property_readonly("elapsed", &ContactSolution::elapsed,
                             "Wall-clock time of the solve in seconds.")
      .def_property_readonly("iterations", &ContactSolution::iterations,
                             "Load evaluations over all collocation sizes.")
      .def_property_readonly("collocation_n", &ContactSolution::collocation_n,
                             "Number N of collocation nodes of the final solve.")
      .def_property_readonly(
          "stage_seconds", [](const ContactSolution& s) { return stage_dict(s.stage_seconds()); },
          "Seconds per stage: critical_speed, kernel (fetching or building the k1 "
          "table), width (the iteration on a), checks (indentation and validity).")
      .def_property_readonly("kernel_builds", &ContactSolution::kernel_builds,
                             "k1 kernel tables this solve built (0: reused from the "
                             "process-wide cache).")
      .def_property_readonly("valid", &ContactSolution::valid,
                             "True if p >= 0 on (-a, a) and the punch does not "
                             "penetrate the surface outside it.")
      .def_property_readonly("validity", &ContactSolution::validity,
                             "Human-readable account of the validity checks.")
      .def_property_readonly("min_pressure", &ContactSolution::min_pressure,
                             "Minimum of p/(P/h) on [-a, a].")
      .def_property_readonly("pressure_margin", &ContactSolution::pressure_margin,
                             "Minimum over -1 < r < 1 of p(a r)/((P/h) sqrt(1 - r^2)): "
                             "the margin before the contact separates.")
      .def_property_readonly(
          "warnings", [](const ContactSolution& s) { return py::list(py::cast(s.warnings())); },
          "One line per requested accuracy that was not met (empty: none).")
      .def_property_readonly(
          "error_budget",
          [](const ContactSolution& s) {
            const auto& b = s.error_budget();
            py::dict d;
            d["collocation"] = b.collocation;
            d["root"] = b.root;
            d["kernel"] = b.kernel;
            d["roundoff"] = b.roundoff;
            return d;
          },
          "The parts of error_estimate (absolute, of a/h): collocation, root, kernel, "
          "roundoff.")
      .def_property_readonly("min_gap", &ContactSolution::min_gap,
                             "Minimum gap/h between punch and surface on "
                             "a < |x| <= 3a.")
      .def_property_readonly(
          "g_coefficients",
          [](const ContactSolution& s) -> Eigen::VectorXd { return s.g_coefficients(); },
          "Chebyshev-U coefficients of g(r) = p(a r)/((P/h) sqrt(1 - r^2)) (a copy).")
      .def(
          "pressure",
          [](const ContactSolution& s, const VectorRef& x) -> Eigen::VectorXd {
            return s.pressure(x);
          },
          "x"_a, Release(),
          "Contact pressure p/(P/h) at each x/h (0 outside the contact). x: 1-D "
          "float64.")
      .def(
          "surface_displacement",
          [](const ContactSolution& s, const VectorRef& x) -> Eigen::VectorXd {
            return s.surface_displacement(x);
          },
          "x"_a, Release(),
          "Vertical surface displacement v(x, 0)/h at each x/h (negative under "
          "the punch). x: 1-D float64.")
      .def(
          "stress_field",
          [](const ContactSolution& s, const VectorRef& x, const VectorRef& y) {
            StressField f = s.stress_field(x, y);
            return std::make_tuple(std::move(f.sigma_x), std::move(f.sigma_y), std::move(f.tau_xy));
          },
          "x"_a, "y"_a, Release(),
          "(sigma_x, sigma_y, tau_xy)/(P/h) on the grid x/h by y/h (-1 <= y <= 0), each "
          "shaped (len(y), len(x)).")
      .def(
          "surface_stress",
          [](const ContactSolution& s, const VectorRef& x) -> Eigen::VectorXd {
            return s.surface_stress(x);
          },
          "x"_a, Release(), "sigma_x(x, 0)/(P/h) at each x/h.")
      .def(
          "depth_stress",
          [](const ContactSolution& s, const VectorRef& y) -> Eigen::VectorXd {
            return s.depth_stress(y);
          },
          "y"_a, Release(), "sigma_x(0, y)/(P/h) at each y/h in [-1, 0].")
      .def(
          "displacement",
          [](const ContactSolution& s, const VectorRef& x, const VectorRef& y) -> Eigen::MatrixXd {
            return s.displacement(x, y);
          },
          "x"_a, "y"_a, Release(),
          "Vertical displacement v/h on the grid x/h by y/h, shaped (len(y), len(x)).")
      .def(
          "foundation_reaction",
          [](const ContactSolution& s, const VectorRef& x) -> Eigen::VectorXd {
            return s.foundation_reaction(x);
          },
          "x"_a, Release(), "Pressure of the base on the layer, -sigma_y(x, -h)/(P/h).")
      .def("__repr__", [](const ContactSolution& s) {
        return py::str("<movingpunch._core.ContactSolution a={!r} valid={}>")
            .format(s.a(), s.valid());
      });

  m.def(
      "kernel_cache_info",
      []() {
        const KernelCacheInfo i = kernel_cache_info();
        py::dict d;
        d["size"] = i.size;
        d["hits"] = i.hits;
        d["misses"] = i.misses;
        return d;
      },
      "Process-wide k1 kernel cache: tables held (size), requests served (hits), "
      "tables built (misses).");
  m.def("clear_kernel_cache", &clear_kernel_cache, Release(),
        "Empties the process-wide k1 kernel cache and resets its counters.");

  m.def(
      "solve_contact",
      [](double vstar, double kw, double radius, double load, double nu, double tol,
         bool allow_unphysical, int n) {
        ContactParams p;
        p.vstar = vstar;
        p.kw = kw;
        p.radius = radius;
        p.load = load;
        p.nu = nu;
        p.tol = tol;
        p.allow_unphysical = allow_unphysical;
        p.n = n;
        return solve_contact(p);
      },
      py::kw_only(), "vstar"_a, "kw"_a, "radius"_a, "load"_a, "nu"_a, "tol"_a, "allow_unphysical"_a,
      "n"_a = 0, Release(),
      "Solves the moving-punch contact problem (dimensionless inputs: vstar = "
      "rho V^2/mu, kw = k_w h/mu, radius = R/h, load = P/(mu h), nu, tol on a/h). "
      "Raises InvalidParameterError, SupercriticalSpeedError, "
      "UnphysicalContactError (unless allow_unphysical) or ConvergenceError.");
}

}  // namespace movingpunch::bindings

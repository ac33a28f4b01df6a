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

  auto cls = bind_result_class<ContactSolution>(
      m, "ContactSolution",
      "Result of solve_contact (dimensionless: h = 1, mu = 1, pressures per P/h). "
      "Not constructible from Python.");
  cls.def_property_readonly("a", &ContactSolution::a, "Contact half-width a/h.")
      .def_property_readonly("p0", &ContactSolution::p0, "Central pressure p(0)/(P/h).")
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
      .def(
          "depth_stress",
          [](const ContactSolution& s, const VectorRef& y) -> Eigen::VectorXd {
            return s.depth_stress(y);
          },
          "y"_a, Release(), "sigma_x(0, y)/(P/h) at each y/h in [-1, 0].")
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
         bool allow_unphysical, int n, double kp) {
        auto p = solve_params<ContactParams>(vstar, kw, radius, load, nu, tol, allow_unphysical, n);
        p.kp = kp;
        return solve_contact(p);
      },
      py::kw_only(), "vstar"_a, "kw"_a, "radius"_a, "load"_a, "nu"_a, "tol"_a, "allow_unphysical"_a,
      "n"_a = 0, "kp"_a = 0.0, Release(),
      "Solves the moving-punch contact problem (dimensionless inputs: vstar = "
      "rho V^2/mu, kw = k_w h/mu, radius = R/h, load = P/(mu h), nu, tol on a/h, "
      "kp = k_p/(mu h) the Pasternak shear layer, 0: springs alone). "
      "Raises InvalidParameterError, SupercriticalSpeedError, "
      "UnphysicalContactError (unless allow_unphysical) or ConvergenceError.");
}

}  // namespace movingpunch::bindings

// The contact solve and its result. Adapters only.
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <Eigen/Dense>

#include "bindings.hpp"
#include "movingpunch/asymmetric.hpp"
#include "movingpunch/contact.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/profile.hpp"

namespace py = pybind11;
using namespace py::literals;

namespace movingpunch::bindings {

// The profile kind from its API name.
ProfileKind profile_kind(const std::string& name) {
  for (ProfileKind k :
       {ProfileKind::cylinder, ProfileKind::flat, ProfileKind::rounded_flat, ProfileKind::table})
    if (name == profile_kind_name(k)) return k;
  throw InvalidParameter(
      "profile", "'cylinder', 'flat', 'rounded_flat' or 'table'",
      "profile must be 'cylinder', 'flat', 'rounded_flat' or 'table', got '" + name + "'");
}

void bind_contact(py::module_& m) {
  using VectorRef = Eigen::Ref<const Eigen::VectorXd>;
  using Release = py::call_guard<py::gil_scoped_release>;

  auto cls = bind_result_class<SymmetricSolution>(
      m, "SymmetricSolution",
      "Result of solve_contact (dimensionless: h = 1, mu = 1, pressures per P/h). "
      "Not constructible from Python.");
  cls.def_property_readonly("a", &SymmetricSolution::a, "Contact half-width a/h.")
      .def_property_readonly("p0", &SymmetricSolution::p0, "Central pressure p(0)/(P/h).")
      .def_property_readonly(
          "series_kind",
          [](const SymmetricSolution& s) {
            return std::string(s.series_kind() == SeriesKind::T ? "T" : "U");
          },
          "'U': g_coefficients are Chebyshev-U of p(a r)/((P/h) sqrt(1 - r^2)) (bounded "
          "ends); 'T' (flat punch): Chebyshev-T of p(a r) sqrt(1 - r^2)/(P/h).")
      .def_property_readonly("end_coefficient", &SymmetricSolution::end_coefficient,
                             "K = lim sqrt(2 pi (a - x)) p(x) over (P/h) sqrt(h) at each end of "
                             "a flat punch (0 for bounded ends).")
      .def_property_readonly("end_coefficient_error", &SymmetricSolution::end_coefficient_error,
                             "Estimated absolute error of end_coefficient.")
      .def_property_readonly("series_truncation", &SymmetricSolution::series_truncation,
                             "Bound on the pressure's error over P/h from the truncation of "
                             "its Chebyshev series (0 for the cylinder and the flat punch).")
      .def_property_readonly("profile_description", &SymmetricSolution::profile_description,
                             "The punch's shape, one line.")
      .def_property_readonly(
          "error_budget",
          [](const SymmetricSolution& s) {
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
          [](const SymmetricSolution& s, const VectorRef& y) -> Eigen::VectorXd {
            return s.depth_stress(y);
          },
          "y"_a, Release(), "sigma_x(0, y)/(P/h) at each y/h in [-1, 0].")
      .def(
          "foundation_reaction",
          [](const SymmetricSolution& s, const VectorRef& x) -> Eigen::VectorXd {
            return s.foundation_reaction(x);
          },
          "x"_a, Release(), "Pressure of the base on the layer, -sigma_y(x, -h)/(P/h).")
      .def("__repr__", [](const SymmetricSolution& s) {
        return py::str("<movingpunch._core.SymmetricSolution a={!r} valid={}>")
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
        const KernelCacheInfo j = asymmetric_kernel_cache_info();
        d["asymmetric_size"] = j.size;
        d["asymmetric_hits"] = j.hits;
        d["asymmetric_misses"] = j.misses;
        return d;
      },
      "Process-wide k1 kernel cache: tables held (size), requests served (hits), "
      "tables built (misses).");
  m.def("clear_kernel_cache", &clear_kernel_cache, Release(),
        "Empties the process-wide k1 kernel cache and resets its counters.");

  m.def("check_profile_table", &check_profile_table, "x"_a, "y"_a, "require_symmetric"_a = false,
        "Raises InvalidParameterError unless (x, y) is a valid profile table: at least 5 "
        "points, finite, x strictly ascending with x_0 < 0 < x_{n-1}, convex (and symmetric "
        "about x = 0 with require_symmetric).");
  m.def("profile_table_symmetric", &profile_table_symmetric, "x"_a, "y"_a,
        "True when the table is symmetric about x = 0 (to 1e-9 of max |x| and of the range "
        "of y).");
  m.def(
      "profile_shape",
      [](const std::string& kind, double radius, double half_width, const std::vector<double>& tx,
         const std::vector<double>& ty, const VectorRef& x) {
        const PunchProfile prof(profile_kind(kind), radius, half_width, tx, ty);
        Eigen::VectorXd f(x.size()), df(x.size());
        for (Eigen::Index i = 0; i < x.size(); ++i) {
          f(i) = prof.height(x(i));
          df(i) = prof.slope(x(i));
        }
        return std::make_tuple(f, df);
      },
      py::kw_only(), "kind"_a, "radius"_a, "half_width"_a, "table_x"_a, "table_y"_a, "x"_a,
      "The profile's height f(x) - f(0) and slope f'(x) at each x/h, as the solver uses them "
      "(a table through its not-a-knot cubic spline).");

  m.def(
      "solve_contact",
      [](double vstar, double kw, double radius, double load, double nu, double tol,
         bool allow_unphysical, int n, double kp, const std::string& profile, double half_width,
         const std::vector<double>& table_x, const std::vector<double>& table_y,
         const LayerRows& layers, const std::string& base, const HalfSpaceRow& half_space) {
        ContactParams p =
            solve_params<ContactParams>(vstar, kw, radius, load, nu, tol, allow_unphysical, n);
        p.kp = kp;
        set_profile(p, profile, half_width, table_x, table_y);
        p.medium = medium_spec(layers, base, kw, kp, 0.0, half_space);
        return solve_contact(p);
      },
      py::kw_only(), "vstar"_a, "kw"_a, "radius"_a, "load"_a, "nu"_a, "tol"_a, "allow_unphysical"_a,
      "n"_a = 0, "kp"_a = 0.0, "profile"_a = "cylinder", "half_width"_a = 0.0,
      "table_x"_a = std::vector<double>{}, "table_y"_a = std::vector<double>{},
      "layers"_a = LayerRows{}, "base"_a = "springs", "half_space"_a = default_half_space_row(),
      Interruptible(),
      "Solves the moving-punch contact problem (dimensionless inputs: vstar = "
      "rho V^2/mu, kw = k_w h/mu, radius = R/h, load = P/(mu h), nu, tol on a/h, "
      "kp = k_p/(mu h) the Pasternak shear layer, 0: springs alone; profile: the "
      "punch's shape, 'cylinder' (radius), 'flat' (half_width), 'rounded_flat' "
      "(half_width, radius) or 'table' (table_x, table_y); layers: the sublayers as "
      "(thickness, mu, nu, rho, gamma_h) rows, top to bottom (empty: one homogeneous layer of "
      "nu), on the base 'springs' (kw, kp), 'bonded' or 'smooth' (a half-space: half_space = its "
      "row, HALF_SPACE_FIELDS). "
      "Raises InvalidParameterError, SupercriticalSpeedError, "
      "UnphysicalContactError (unless allow_unphysical) or ConvergenceError.");
}

}  // namespace movingpunch::bindings

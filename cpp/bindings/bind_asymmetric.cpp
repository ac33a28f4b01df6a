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
#include "movingpunch/asymmetric.hpp"
#include "movingpunch/jacobi.hpp"

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

void bind_asymmetric(py::module_& m) {
  using Release = py::call_guard<py::gil_scoped_release>;

  auto cls = bind_result_class<AsymmetricSolution>(
      m, "AsymmetricSolution",
      "Result of solve_asymmetric (dimensionless: h = 1, mu = 1, pressures per P/h). "
      "Not constructible from Python.");
  cls.def_property_readonly("left", &AsymmetricSolution::left,
                            "Trailing end -b/h of the contact (-b, a).")
      .def_property_readonly("right", &AsymmetricSolution::right,
                             "Leading end a/h of the contact (-b, a).")
      .def_property_readonly("centre", &AsymmetricSolution::centre, "Centre (a - b)/(2h).")
      .def_property_readonly("half_width", &AsymmetricSolution::half_width,
                             "Half-width (a + b)/(2h).")
      .def_property_readonly("drag", &AsymmetricSolution::drag,
                             "Horizontal force on the punch over P, int p x/R dx / P "
                             "(positive: opposes the motion).")
      .def_property_readonly("friction", &AsymmetricSolution::friction,
                             "Coulomb friction f: the shear traction on the layer is f p, "
                             "towards +x (the direction of motion).")
      .def_property_readonly("tangential_force", &AsymmetricSolution::tangential_force,
                             "Tangential (friction) force on the punch over P, f "
                             "(positive: opposes the motion).")
      .def_property_readonly(
          "end_exponents",
          [](const AsymmetricSolution& s) {
            return std::make_tuple(s.end_exponents().back, s.end_exponents().front);
          },
          "(gamma_back, gamma_front): p ~ (x + b)^gamma_back (a - x)^gamma_front.")
      .def_property_readonly(
          "end_coefficients",
          [](const AsymmetricSolution& s) {
            return std::make_tuple(s.end_coefficient_back(), s.end_coefficient_front());
          },
          "(K_back, K_front) of a flat punch: lim sqrt(2 pi) d^(-gamma) p over (P/h) "
          "h^(-gamma) as the distance d to that end goes to 0; (0, 0) for bounded ends.")
      .def_property_readonly("end_coefficient_error", &AsymmetricSolution::end_coefficient_error,
                             "Estimated absolute error of each of end_coefficients.")
      .def_property_readonly("coupling", &AsymmetricSolution::coupling,
                             "Coupling constant Phi(vstar, nu) of the local term f Phi p.")
      .def_property_readonly("series_truncation", &AsymmetricSolution::series_truncation,
                             "Bound on the pressure's error over P/h from the truncation of "
                             "its (tail-extended) series: a profile's kinks (0 for the "
                             "cylinder).")
      .def_property_readonly("pressure_error_estimate",
                             &AsymmetricSolution::pressure_error_estimate,
                             "Bound on the error of p/(P/h) at a fixed relative position "
                             "r = (x - c)/w in the contact.")
      .def_property_readonly(
          "stress_error_estimate",
          py::cpp_function([](const AsymmetricSolution& s) { return s.stress_error_estimate(); },
                           Release()),
          "Bound on the error of the surface sigma_x/(P/h) more than 1e-3 (a + b)/2 from the "
          "contact ends (computed on first read).")
      .def_property_readonly("max_pressure", &AsymmetricSolution::max_pressure,
                             "Maximum of p/(P/h) on the contact.")
      .def_property_readonly(
          "other_half_widths",
          [](const AsymmetricSolution& s) { return py::tuple(py::cast(s.other_half_widths())); },
          "Half-widths (a+b)/(2h) of other contacts carrying the same load (above "
          "V*_cr the steady solution need not be unique); empty when unique.")
      .def(
          "compliance_stress_field",
          [](const AsymmetricSolution& s, const VectorRef& x, const VectorRef& y, bool below) {
            StressField f = s.compliance_stress_field(x, y, below);
            return std::make_tuple(std::move(f.sigma_x), std::move(f.sigma_y), std::move(f.tau_xy));
          },
          "x"_a, "y"_a, "below"_a = false, Release(),
          "The stresses through the compliance of the material at each depth, (1/m_inf) [sigma + "
          "sum_k c_k (e_k * sigma)] along x/h in a viscoelastic sublayer, on the grid x/h by y/h: "
          "their Hooke strains at its relaxed modulus are its strains (the stresses in an elastic "
          "one); below: at an interface, the material below it.")
      .def(
          "dissipation", [](const AsymmetricSolution& s) { return s.dissipation(); }, Release(),
          "Power dissipated in the dashpots over P V (equals drag by the energy balance).")
      .def(
          "surface_slope",
          [](const AsymmetricSolution& s, const VectorRef& x) {
            return each(x, [&](double v) { return s.surface_slope(v); });
          },
          "x"_a, Release(), "Surface slope dv/dx(x, 0) at each x/h.")
      .def(
          "bottom_slope",
          [](const AsymmetricSolution& s, const VectorRef& x) {
            return each(x, [&](double v) { return s.bottom_slope(v); });
          },
          "x"_a, Release(), "Slope dv/dx(x, -h) of the bottom face at each x/h.")
      .def(
          "stress_x",
          [](const AsymmetricSolution& s, double x, const VectorRef& y) {
            return each(y, [&](double v) { return s.stress_x(x, v); });
          },
          "x"_a, "y"_a, Release(),
          "sigma_x(x, y)/(P/h) at one x/h and each y/h in [-1, -1e-3] or 0.")
      .def(
          "bottom_displacement",
          [](const AsymmetricSolution& s, const VectorRef& x) {
            return each(x, [&](double v) { return s.bottom_displacement(v); });
          },
          "x"_a, Release(), "Displacement v(x, -h)/h of the bottom face at each x/h.")
      .def("__repr__", [](const AsymmetricSolution& s) {
        return py::str("<movingpunch._core.AsymmetricSolution left={!r} right={!r} drag={!r}>")
            .format(s.left(), s.right(), s.drag());
      });

  m.def(
      "solve_asymmetric",
      [](double vstar, double kw, double radius, double load, double nu, double damping, double tol,
         bool allow_unphysical, int n, double kp, double friction, const std::string& profile,
         double half_width, const std::vector<double>& table_x, const std::vector<double>& table_y,
         const LayerRows& layers, const std::string& base, const HalfSpaceRow& half_space,
         const MaterialRows& materials) {
        auto p =
            solve_params<AsymmetricParams>(vstar, kw, radius, load, nu, tol, allow_unphysical, n);
        p.damping = damping;
        p.kp = kp;
        p.friction = friction;
        set_profile(p, profile, half_width, table_x, table_y);
        p.medium = medium_spec(layers, base, kw, kp, damping, half_space, materials);
        return solve_asymmetric(p);
      },
      py::kw_only(), "vstar"_a, "kw"_a, "radius"_a, "load"_a, "nu"_a, "damping"_a, "tol"_a,
      "allow_unphysical"_a, "n"_a = 0, "kp"_a = 0.0, "friction"_a = 0.0, "profile"_a = "cylinder",
      "half_width"_a = 0.0, "table_x"_a = std::vector<double>{},
      "table_y"_a = std::vector<double>{}, "layers"_a = LayerRows{}, "base"_a = "springs",
      "half_space"_a = default_half_space_row(), "materials"_a = MaterialRows{}, Interruptible(),
      "Solves the contact problem on a damped (Kelvin-Voigt) foundation, damping = "
      "c_w c_T/mu > 0. Raises InvalidParameterError, SupercriticalSpeedError (vstar >= "
      "V*_R), UnphysicalContactError (unless allow_unphysical) or ConvergenceError. "
      "friction = f >= 0: Coulomb friction (damping may then be 0). profile: the punch's "
      "shape as solve_contact's ('cylinder', 'rounded_flat' or 'table'; an asymmetric table "
      "solves here with damping = 0 and friction = 0 too). layers, base, half_space: the medium, "
      "as solve_contact's (damping > 0: the homogeneous layer only); materials: per sublayer "
      "(weights, deborahs, shift) of a viscoelastic material (empty weights: elastic).");

  m.def(
      "tangential_half_plane",
      [](double vstar, double nu) {
        const TangentialHalfPlane t = tangential_half_plane(wave_constants(vstar, nu));
        return py::make_tuple(t.Uq, t.Wq, t.Phi);
      },
      "vstar"_a, "nu"_a,
      "(Uq, Wq, Phi) of the moving half-plane under a unit tangential surface load: Phi = "
      "Wq/phi1 = (2 - s - 2 nL nT)/(s nL) couples friction into the normal problem.");
  m.def(
      "end_exponents",
      [](double friction, double coupling) {
        const EndExponents e = end_exponents(friction, coupling);
        return py::make_tuple(e.back, e.front);
      },
      "friction"_a, "coupling"_a, "(gamma_back, gamma_front) with cot(pi gamma_back) = f Phi.");
  m.def(
      "damped_tangential_response",
      [](double t, double vstar, double kw, double nu, double damping, double kp) {
        const DampedResponse r = DampedLayerModel(vstar, kw, nu, damping, kp).response(t);
        return py::make_tuple(r.Uq, r.Wq);
      },
      "t"_a, "vstar"_a, "kw"_a, "nu"_a, "damping"_a, "kp"_a = 0.0,
      "(Uq, Wq): the top state [Uq, Wq, 1, 0] of a unit tangential load at t = alpha h > 0.");

  m.def(
      "damped_layer_response",
      [](double t, double vstar, double kw, double nu, double damping, double kp) {
        const DampedResponse r = DampedLayerModel(vstar, kw, nu, damping, kp).response(t);
        return py::make_tuple(r.M1, r.M2, r.Wb);
      },
      "t"_a, "vstar"_a, "kw"_a, "nu"_a, "damping"_a, "kp"_a = 0.0,
      "(M1, M2, Wb) of the damped layer at t = alpha h >= 0 (complex; alpha < 0 gives "
      "the conjugates).");
}

}  // namespace movingpunch::bindings

// Several contact zones and trains of punches (zones.hpp). Adapters only.
#include <string>
#include <tuple>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "movingpunch/zones.hpp"

namespace py = pybind11;
using namespace py::literals;

namespace movingpunch::bindings {

void bind_zones(py::module_& m) {
  using Release = py::call_guard<py::gil_scoped_release>;
  py::class_<ZoneResult>(m, "ZoneResult", "One contact zone of solve_zones.")
      .def_readonly("punch", &ZoneResult::punch, "Index of the punch the zone lies under.")
      .def_readonly("left", &ZoneResult::left, "Left end x/h.")
      .def_readonly("right", &ZoneResult::right, "Right end x/h.")
      .def_readonly("load", &ZoneResult::load, "The zone's load, int p dx/(mu h).")
      .def_readonly("b", &ZoneResult::b, "U-series coefficients of p/(P_zone/h)/sqrt(1 - r^2).")
      .def_property_readonly(
          "solution", [](const ZoneResult& z) { return z.solution(); },
          "The zone as a AsymmetricSolution of its own load (its pressure and the layer's response "
          "to it; the whole response is the sum over the zones).")
      .def_readonly("min_pressure", &ZoneResult::min_pressure, "min p/(P_zone/h) on the zone.")
      .def_readonly("margin", &ZoneResult::margin,
                    "min over the open zone of p/((P_zone/h) sqrt(1 - r^2)).")
      .def_readonly("margin_x", &ZoneResult::margin_x, "Where the margin is smallest, x/h.");
  py::class_<ZonesSolution>(m, "ZonesSolution", "Result of solve_zones.")
      .def_readonly("zones", &ZonesSolution::zones)
      .def_readonly("indentation_x", &ZonesSolution::indentation_x,
                    "Per punch: where its indentation is taken (x/h).")
      .def_readonly("indentation_height", &ZonesSolution::indentation_height,
                    "Per punch: f_k at indentation_x (delta_k = it - v(x, 0)).")
      .def_readonly("drag_total", &ZonesSolution::drag_total)
      .def_readonly("drag", &ZonesSolution::drag, "Per punch: int p f_k' dx / P_k.")
      .def_readonly("error_estimate", &ZonesSolution::error_estimate)
      .def_readonly("pressure_error_estimate", &ZonesSolution::pressure_error_estimate)
      .def_readonly("stress_error_estimate", &ZonesSolution::stress_error_estimate)
      .def_readonly("max_pressure", &ZonesSolution::max_pressure)
      .def_readonly("residual", &ZonesSolution::residual)
      .def_readonly("collocation_n", &ZonesSolution::collocation_n)
      .def_readonly("iterations", &ZonesSolution::iterations)
      .def_readonly("kernel_builds", &ZonesSolution::kernel_builds)
      .def_readonly("min_gap", &ZonesSolution::min_gap)
      .def_readonly("min_gap_x", &ZonesSolution::min_gap_x)
      .def_readonly("gap_scale", &ZonesSolution::gap_scale)
      .def_readonly("min_gap_after_zone", &ZonesSolution::min_gap_after_zone)
      .def_readonly("warnings", &ZonesSolution::warnings)
      .def_readonly("elapsed", &ZonesSolution::elapsed)
      .def_readonly("critical_vstar", &ZonesSolution::critical_vstar)
      .def_readonly("rayleigh_vstar", &ZonesSolution::rayleigh_vstar)
      .def_readonly("phi1", &ZonesSolution::phi1)
      .def("dissipation", &zones_dissipation, Release(),
           "Power dissipated over P V: in the dashpots (Parseval on the bottom face) or in the "
           "viscoelastic materials (Parseval on the surface, from Im M1); equals the drag by the "
           "energy balance.");

  using PunchTuple = std::tuple<std::string, double, double, std::vector<double>,
                                std::vector<double>, double, double>;
  m.def(
      "solve_zones",
      [](double vstar, double kw, double nu, double damping, double kp, double tol, int n,
         const std::vector<PunchTuple>& punches,
         const std::vector<std::tuple<int, double, double>>& zones, int first_n,
         const LayerRows& layers, const std::string& base, const HalfSpaceRow& half_space,
         const MaterialRows& materials) {
        ZonesParams p;
        p.layer.medium = medium_spec(layers, base, kw, kp, damping, half_space, materials);
        p.layer.vstar = vstar;
        p.layer.kw = kw;
        p.layer.nu = nu;
        p.layer.damping = damping;
        p.layer.kp = kp;
        p.layer.tol = tol;
        p.layer.n = n;
        for (const auto& [profile, radius, half_width, tx, ty, load, at] : punches) {
          ZonePunch z;
          z.profile = profile_kind(profile);
          z.radius = radius;
          z.half_width = half_width;
          z.table_x = tx;
          z.table_y = ty;
          z.load = load;
          z.at = at;
          p.punches.push_back(z);
        }
        for (const auto& [k, l, r] : zones) p.zones.push_back(ZoneSpan{k, l, r});
        p.first_n = first_n;
        return solve_zones(p);
      },
      py::kw_only(), "vstar"_a, "kw"_a, "nu"_a, "damping"_a, "kp"_a, "tol"_a, "n"_a, "punches"_a,
      "zones"_a, "first_n"_a = 24, "layers"_a = LayerRows{}, "base"_a = "springs",
      "half_space"_a = default_half_space_row(), "materials"_a = MaterialRows{}, Interruptible(),
      "Solves one contact set (zones: (punch, left, right) from left to right, disjoint) "
      "under punches ((profile, radius, half_width, table_x, table_y, load, at)) by Newton's "
      "method on the zone ends; frictionless. layers, base, half_space, materials: the "
      "medium, as solve_asymmetric's (a viscoelastic top's memory is taken exactly). Raises "
      "InvalidParameterError, "
      "SupercriticalSpeedError or ConvergenceError.");
}

}  // namespace movingpunch::bindings

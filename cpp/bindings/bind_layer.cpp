// Layer response, half-plane limits, dispersion, kernel and collocation nodes.
// Adapters only: every number is computed by the core.
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <Eigen/Dense>

#include "bindings.hpp"
#include "movingpunch/collocation.hpp"
#include "movingpunch/dispersion.hpp"
#include "movingpunch/kernel.hpp"
#include "movingpunch/layer_response.hpp"
#include "movingpunch/medium.hpp"

namespace py = pybind11;
using namespace py::literals;

namespace movingpunch::bindings {
namespace {

using Vector = Eigen::VectorXd;
using VectorRef = Eigen::Ref<const Eigen::VectorXd>;
using Release = py::call_guard<py::gil_scoped_release>;

const LayerRows& require_layers(const LayerRows& layers) {
  if (layers.empty())
    throw InvalidParameter("layers", "at least one sublayer", "layers: at least one sublayer");
  return layers;
}

std::pair<Vector, Vector> layer_response(const VectorRef& t, double vstar, double kw, double nu,
                                         const std::string& method, double kp) {
  Response (LayerModel::*evaluate)(double) const = nullptr;
  if (method == "auto") {
    evaluate = &LayerModel::response;
  } else if (method == "modal") {
    evaluate = &LayerModel::response_modal;
  } else if (method == "transfer") {
    evaluate = &LayerModel::response_transfer;
  } else {
    throw std::invalid_argument("method must be 'auto', 'modal' or 'transfer', got '" + method +
                                "'");
  }
  const LayerModel model(vstar, kw, nu, kp);
  Vector m1(t.size());
  Vector m2(t.size());
  for (Eigen::Index i = 0; i < t.size(); ++i) {
    const Response r = (model.*evaluate)(t[i]);
    m1[i] = r.M1;
    m2[i] = r.M2;
  }
  return {std::move(m1), std::move(m2)};
}

Vector kernel_k1(const VectorRef& u, double vstar, double kw, double nu, double tol, double range,
                 bool direct, double kp) {
  const KernelK1 kernel(LayerModel(vstar, kw, nu, kp), tol, range);
  Vector out(u.size());
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    out[i] = direct ? kernel.direct(u[i]) : kernel(u[i]);
  }
  return out;
}

}  // namespace

void bind_layer(py::module_& m) {
  m.def("rayleigh_vstar", &rayleigh_vstar, "nu"_a, Release(),
        "Rayleigh speed rho c_R^2 / mu for Poisson's ratio nu.");

  m.def("phi1", &phi1, "vstar"_a, "nu"_a, Release(),
        "Moving half-plane factor phi1 = lim M1 (phi1(0) = 1 - nu); requires "
        "vstar < rayleigh_vstar(nu).");

  m.def("phi2", &phi2, "vstar"_a, "nu"_a, Release(),
        "Half-plane limit phi2 = lim M2 of the surface sigma_x response "
        "(phi2(0) = 1); requires vstar < rayleigh_vstar(nu).");

  m.def(
      "critical_speed",
      [](double kw, double nu, double kp) {
        const CriticalSpeed c = critical_speed(kw, nu, kp);
        return std::make_tuple(c.vstar, c.t);
      },
      "kw"_a, "nu"_a, "kp"_a = 0.0, Release(),
      "Critical speed of the layer on springs (and a Pasternak shear layer kp): "
      "(V*_cr, alpha h at the minimum). For kw = inf, or when no free wave is "
      "slower than the Rayleigh wave, it is (rayleigh_vstar(nu), inf).");

  {
    py::tuple names(kSublayerRow);
    for (std::size_t i = 0; i < kSublayerRow; ++i) names[i] = kSublayerFields[i].name;
    m.attr("SUBLAYER_FIELDS") = names;  // a sublayer's row (medium.hpp kSublayerFields)
  }
  {
    py::tuple names(kHalfSpaceRow);
    for (std::size_t i = 0; i < kHalfSpaceRow; ++i) names[i] = kHalfSpaceFields[i].name;
    m.attr("HALF_SPACE_FIELDS") = names;  // a half-space's row (medium.hpp kHalfSpaceFields)
  }

  m.def(
      "first_wave_vstar",
      [](double t, double kw, double nu, double kp) { return first_wave_vstar(t, kw, nu, kp); },
      "t"_a, "kw"_a, "nu"_a, "kp"_a = 0.0, Release(),
      "Lowest vstar in (0, V*_R) at which a free wave of wavenumber t = alpha h "
      "exists; rayleigh_vstar(nu) when there is none below it.");

  m.def(
      "medium_critical_speed",
      [](const LayerRows& layers, const std::string& base, double kw, double kp,
         const HalfSpaceRow& half_space) {
        const auto spec = medium_spec(require_layers(layers), base, kw, kp, 0.0, half_space);
        const CriticalSpeed c = critical_speed(*spec);
        return std::make_pair(c.vstar, c.t);
      },
      py::kw_only(), "layers"_a, "base"_a = "springs", "kw"_a = 1.0, "kp"_a = 0.0,
      "half_space"_a = default_half_space_row(), Release(),
      "(V*_cr, t) of a medium (see solve_contact for its arguments): the lowest speed of a "
      "free steady wave and its wavenumber alpha h (inf or 0: an infimum approached as "
      "alpha h -> inf or 0).");
  m.def(
      "medium_response",
      [](const VectorRef& t, double vstar, const LayerRows& layers, const std::string& base,
         double kw, double kp, const HalfSpaceRow& half_space) {
        const auto spec = medium_spec(require_layers(layers), base, kw, kp, 0.0, half_space);
        const std::shared_ptr<const Medium> med = make_medium(*spec, vstar);
        Eigen::MatrixXcd out(t.size(), 4);
        for (Eigen::Index i = 0; i < t.size(); ++i) {
          const MediumResponse r = med->surface_response(t(i));
          out.row(i) << r.M1, r.M2, r.U0, r.W0;
        }
        return out;
      },
      "t"_a, py::kw_only(), "vstar"_a, "layers"_a, "base"_a = "springs", "kw"_a = 1.0, "kp"_a = 0.0,
      "half_space"_a = default_half_space_row(), Release(),
      "The surface responses (M1, M2, alpha u^, alpha v^ per unit transformed pressure; "
      "columns, complex) of a medium at each t = alpha h > 0 (see solve_contact).");
  m.def("layer_response", &layer_response, "t"_a, "vstar"_a, "kw"_a, "nu"_a, "method"_a = "auto",
        "kp"_a = 0.0, Release(),
        "Surface responses (M1, M2) per unit transformed pressure at each "
        "t = alpha h. method: 'auto', 'modal' or 'transfer' (force one "
        "evaluation, for cross-checks).");

  m.def(
      "layer_dispersion",
      [](double t, double vstar, double kw, double nu, double kp) {
        return LayerModel(vstar, kw, nu, kp).dispersion(t);
      },
      "t"_a, "vstar"_a, "kw"_a, "nu"_a, "kp"_a = 0.0, Release(),
      "A function of (t, vstar) that changes sign where a free wave of "
      "wavenumber t exists, as vstar varies at a fixed t (arbitrary sign "
      "convention, different for t < 0.5 and t >= 0.5).");

  m.def("kernel_k1", &kernel_k1, "u"_a, "vstar"_a, "kw"_a, "nu"_a, "tol"_a, "range"_a,
        "direct"_a = false, "kp"_a = 0.0, Release(),
        "Regular kernel k1(u) of the singular integral equation at each u "
        "(|u| <= range), from a KernelK1 tabulated to absolute tolerance tol; "
        "direct=True sums the alpha quadrature instead of the Chebyshev table.");

  m.def(
      "chebyshev_nodes",
      [](int n) {
        ChebyshevNodes nodes = chebyshev_nodes(n);
        return std::make_tuple(std::move(nodes.r), std::move(nodes.s), std::move(nodes.w));
      },
      "n"_a, Release(),
      "Gauss-Chebyshev collocation nodes for even n >= 2: (r, s, w) with "
      "r_i = cos(i pi/(n+1)), s_k = cos(pi (2k-1)/(2(n+1))), "
      "w_i = (1 - r_i^2)/(n+1).");
}

}  // namespace movingpunch::bindings

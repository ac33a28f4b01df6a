// Private to the binding layer: one bind_<area>() per cpp/bindings/bind_<area>.cpp,
// wired together by module.cpp.
#pragma once

#include <pybind11/pybind11.h>

#include "movingpunch/contact.hpp"

namespace movingpunch::bindings {

// The stage times of a solve (either solver) as {stage: seconds}.
inline pybind11::dict stage_dict(const ContactSolution::StageSeconds& t) {
  pybind11::dict d;
  d["critical_speed"] = t.critical_speed;
  d["kernel"] = t.kernel;
  d["width"] = t.width;
  d["checks"] = t.checks;
  return d;
}

void bind_errors(pybind11::module_& m);
void bind_layer(pybind11::module_& m);
void bind_contact(pybind11::module_& m);
void bind_damped(pybind11::module_& m);

}  // namespace movingpunch::bindings

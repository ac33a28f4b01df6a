// Private to the binding layer: one bind_<area>() per cpp/bindings/bind_<area>.cpp,
// wired together by module.cpp.
#pragma once

#include <pybind11/pybind11.h>

namespace movingpunch::bindings {

void bind_errors(pybind11::module_& m);
void bind_layer(pybind11::module_& m);
void bind_contact(pybind11::module_& m);
void bind_damped(pybind11::module_& m);

}  // namespace movingpunch::bindings

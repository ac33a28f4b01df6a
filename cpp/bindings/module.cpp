// movingpunch._core: wires the per-area bindings together. No logic here.
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "movingpunch/medium.hpp"

#ifndef MOVINGPUNCH_VERSION
#define MOVINGPUNCH_VERSION "unknown"
#endif

PYBIND11_MODULE(_core, m) {
  m.doc() =
      "Private compiled core of movingpunch (rigid punch sliding over an elastic "
      "layer on a Winkler foundation). Use the public API in `movingpunch`.";
  m.attr("__version__") = MOVINGPUNCH_VERSION;
  // Under a half-space displacements are measured from the surface at x = this (h).
  m.attr("DISPLACEMENT_REFERENCE") = movingpunch::kDisplacementReference;

  movingpunch::bindings::bind_errors(m);
  movingpunch::bindings::bind_interrupt(m);
  movingpunch::bindings::bind_layer(m);
  movingpunch::bindings::bind_contact(m);
  movingpunch::bindings::bind_asymmetric(m);
  movingpunch::bindings::bind_zones(m);
}

// Maps the core's C++ exceptions onto the Python classes of the pure-Python
// module movingpunch.errors (which never imports _core).
#include <exception>
#include <stdexcept>

#include <pybind11/gil_safe_call_once.h>
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "movingpunch/errors.hpp"
#include "movingpunch/interrupt.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace movingpunch::bindings {
namespace {

// movingpunch.errors, imported once (under the GIL) and kept for the
// interpreter's lifetime.
const py::object& errors_module() {
  PYBIND11_CONSTINIT static py::gil_safe_call_once_and_store<py::object> storage;
  return storage
      .call_once_and_store_result(
          [] { return py::object(py::module_::import("movingpunch.errors")); })
      .get_stored();
}

void raise(const char* class_name, const char* message) {
  py::object cls = errors_module().attr(class_name);
  PyErr_SetObject(cls.ptr(), py::str(message).ptr());
}

}  // namespace

void bind_errors(py::module_& m) {
  // Import now: a broken package fails at import time, not at the first error.
  m.attr("_errors") = errors_module();

  // Translators run with the GIL held; the most specific types come first
  // (SupercriticalSpeedError and UnphysicalContactError are domain_errors).
  // Anything not caught here falls through to pybind11's own translators.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const movingpunch::Interrupted&) {
      raise_interrupted();  // a token's Cancelled or the signal handler's exception
    } catch (const CancelledByToken&) {
      raise_cancelled();  // a token cancelled before the call (InterruptGuard, CancelPoint)
    } catch (const movingpunch::SupercriticalSpeedError& e) {
      py::object cls = errors_module().attr("SupercriticalSpeedError");
      py::object exc = cls(e.what());
      exc.attr("vstar") = e.vstar();
      exc.attr("critical_vstar") = e.critical();
      exc.attr("rayleigh_vstar") = e.rayleigh();
      PyErr_SetObject(cls.ptr(), exc.ptr());
    } catch (const movingpunch::UnphysicalContactError& e) {
      raise("UnphysicalContactError", e.what());
    } catch (const movingpunch::ConvergenceError& e) {
      raise("ConvergenceError", e.what());
    } catch (const movingpunch::InvalidParameter& e) {
      py::object cls = errors_module().attr("InvalidParameterError");
      py::object exc = cls(e.what(), "parameter"_a = e.name(), "allowed"_a = e.allowed());
      PyErr_SetObject(cls.ptr(), exc.ptr());
    } catch (const std::invalid_argument& e) {
      raise("InvalidParameterError", e.what());
    } catch (const std::domain_error& e) {
      raise("MovingPunchError", e.what());
    }
  });
}

}  // namespace movingpunch::bindings

// Ctrl-C during a solve: the InterruptGuard call guard (bindings.hpp).
#include <memory>

#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "movingpunch/interrupt.hpp"

namespace py = pybind11;

namespace movingpunch::bindings {
namespace {

// The Python exception a signal handler raised during this thread's
// computation, kept from the poll (which throws Interrupted through the
// core) until the translator raises it. Owned references.
struct Pending {
  PyObject* type = nullptr;
  PyObject* value = nullptr;
  PyObject* traceback = nullptr;
};
Pending& pending() {
  thread_local Pending p;
  return p;
}

bool on_main_thread() {
  // threading.main_thread() is the thread Python runs signal handlers on.
  static const unsigned long main_ident =
      py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
  return PyThread_get_thread_ident() == main_ident;
}

}  // namespace

InterruptGuard::InterruptGuard() : main_thread_(on_main_thread()) {
  if (!main_thread_) return;
  scope_ = std::make_unique<InterruptScope>([] {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() == 0) return false;
    Pending& p = pending();
    Py_XDECREF(p.type);
    Py_XDECREF(p.value);
    Py_XDECREF(p.traceback);
    PyErr_Fetch(&p.type, &p.value, &p.traceback);
    return true;
  });
}

InterruptGuard::~InterruptGuard() = default;

void raise_interrupted() {
  Pending& p = pending();
  if (p.type == nullptr) {
    PyErr_SetString(PyExc_KeyboardInterrupt, "interrupted");
    return;
  }
  PyErr_Restore(p.type, p.value, p.traceback);  // steals the references
  p = Pending{};
}

}  // namespace movingpunch::bindings

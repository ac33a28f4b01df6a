// Stopping a computation: Ctrl-C on the main thread and cancellation tokens
// on any thread (InterruptGuard, CancelPoint, CancelToken: bindings.hpp).
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "movingpunch/interrupt.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace movingpunch::bindings {
namespace {

// Why this thread's computation stopped, kept from the poll (which throws
// Interrupted through the core) until the translator raises it: the Python
// exception a signal handler raised (owned references), or a token.
struct Pending {
  PyObject* type = nullptr;
  PyObject* value = nullptr;
  PyObject* traceback = nullptr;
  bool cancelled = false;
};
Pending& pending() {
  thread_local Pending p;
  return p;
}

// The tokens bound to this thread by `with token:`, innermost last.
std::vector<std::shared_ptr<CancelToken>>& bound() {
  thread_local std::vector<std::shared_ptr<CancelToken>> tokens;
  return tokens;
}

bool any_cancelled(const std::vector<std::shared_ptr<CancelToken>>& tokens) noexcept {
  for (const auto& t : tokens) {
    if (t->cancelled()) return true;
  }
  return false;
}

bool on_main_thread() {
  // threading.main_thread() is the thread Python runs signal handlers on.
  static const unsigned long main_ident =
      py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
  return PyThread_get_thread_ident() == main_ident;
}

// Whether a pending signal's handler raised (then kept in pending()). With the GIL.
bool signal_raised() {
  if (PyErr_CheckSignals() == 0) return false;
  Pending& p = pending();
  Py_XDECREF(p.type);
  Py_XDECREF(p.value);
  Py_XDECREF(p.traceback);
  PyErr_Fetch(&p.type, &p.value, &p.traceback);
  return true;
}

}  // namespace

std::vector<std::shared_ptr<CancelToken>> bound_tokens() { return bound(); }

bool bound_token_cancelled() noexcept { return any_cancelled(bound()); }

InterruptGuard::InterruptGuard() : main_thread_(on_main_thread()) {
  // With the GIL released (release_); the poll below never touches bound():
  // it polls its own copy of the tokens.
  std::vector<std::shared_ptr<CancelToken>> tokens = bound_tokens();
  if (any_cancelled(tokens)) throw CancelledByToken{};
  if (main_thread_) {
    scope_ = std::make_unique<InterruptScope>([tokens = std::move(tokens)] {
      if (any_cancelled(tokens)) {
        pending().cancelled = true;
        return true;
      }
      py::gil_scoped_acquire gil;
      return signal_raised();
    });
  } else if (!tokens.empty()) {
    scope_ = std::make_unique<InterruptScope>([tokens = std::move(tokens)] {
      if (!any_cancelled(tokens)) return false;
      pending().cancelled = true;
      return true;
    });
  }
}

InterruptGuard::~InterruptGuard() = default;

CancelPoint::CancelPoint() {
  if (bound_token_cancelled()) throw CancelledByToken{};
}

void raise_cancelled() {
  py::object cls = py::module_::import("movingpunch.errors").attr("Cancelled");
  PyErr_SetObject(cls.ptr(), py::str("cancelled").ptr());
}

void raise_interrupted() {
  Pending& p = pending();
  if (p.cancelled) {
    // A token stopped it; a signal's exception kept earlier goes with it.
    Py_XDECREF(p.type);
    Py_XDECREF(p.value);
    Py_XDECREF(p.traceback);
    p = Pending{};
    raise_cancelled();
    return;
  }
  if (p.type == nullptr) {
    PyErr_SetString(PyExc_KeyboardInterrupt, "interrupted");
    return;
  }
  PyErr_Restore(p.type, p.value, p.traceback);  // steals the references
  p = Pending{};
}

void bind_interrupt(py::module_& m) {
  py::class_<CancelToken, std::shared_ptr<CancelToken>>(
      m, "Cancel",
      "A cancellation token. cancel() (from any thread) stops the computations "
      "on the threads the token is bound to: `with token:` binds it to the "
      "current thread for the block (solve(cancel=token) does the same). A "
      "stopped computation raises movingpunch.Cancelled within about 50 ms "
      "(a dense factorisation in progress finishes first). A cancelled token "
      "stays cancelled; an unused one costs nothing.")
      .def(py::init<>())
      .def("cancel", &CancelToken::cancel, py::call_guard<py::gil_scoped_release>(),
           "Asks the computations bound to this token to stop (idempotent, any thread).")
      .def_property_readonly("cancelled", &CancelToken::cancelled, "True once cancel() was called.")
      .def(
          "check",
          [](const CancelToken& t) {
            if (t.cancelled()) throw CancelledByToken{};
          },
          "Raises movingpunch.Cancelled if cancel() was called.")
      .def(
          "__enter__",
          [](const std::shared_ptr<CancelToken>& t) {
            bound().push_back(t);
            return t;
          },
          "Binds the token to the current thread until the block ends.")
      .def(
          "__exit__",
          [](const std::shared_ptr<CancelToken>& t, const py::object&, const py::object&,
             const py::object&) {
            auto& tokens = bound();
            if (tokens.empty() || tokens.back() != t) {
              throw std::logic_error(
                  "Cancel: the block ends on a thread (or in an order) where it did not begin");
            }
            tokens.pop_back();
            return false;
          },
          "exc_type"_a, "exc_value"_a, "traceback"_a, "Unbinds the token (exceptions propagate).")
      .def("__repr__", [](const CancelToken& t) {
        return std::string("<movingpunch.Cancel ") + (t.cancelled() ? "cancelled" : "active") + ">";
      });
  m.def(
      "check_cancelled",
      [] {
        if (bound_token_cancelled()) throw CancelledByToken{};
      },
      "Raises movingpunch.Cancelled if a token bound to this thread is cancelled (for "
      "Python loops between calls of the core).");
}

}  // namespace movingpunch::bindings

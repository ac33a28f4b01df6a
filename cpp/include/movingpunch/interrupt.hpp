// Cooperative cancellation of long computations (Ctrl-C in Python, an
// abandoned solve in the TUI).
//
// A caller that may want to stop a computation installs an InterruptScope on
// the thread that runs it, with a poll() saying whether to stop. The core's
// long loops (quadrature panels, kernel tables, root finding, collocation
// ladders) call check_interrupt(), which calls poll() at most once per
// interval of wall time and throws Interrupted when it returns true.
// Without a scope check_interrupt() is a test of a thread-local pointer.
//
// Interrupted deliberately does not derive from std::exception: no
// `catch (const std::exception&)` that moves a ladder on to its next size
// can swallow it, so it always unwinds to the caller that installed the scope.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <utility>

namespace movingpunch {

// Thrown by check_interrupt() when the installed poll asked to stop.
struct Interrupted {};

class InterruptScope {
 public:
  using Poll = std::function<bool()>;
  // poll() is called from check_interrupt() on this thread, at most once per
  // interval; returning true makes that check_interrupt() throw Interrupted
  // (and every later one in this scope: a stopped computation stays stopped).
  explicit InterruptScope(
      Poll poll, std::chrono::steady_clock::duration interval = std::chrono::milliseconds(50));
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

  // The number of times poll() was called (tests).
  std::uint64_t polls() const noexcept { return polls_; }

 private:
  friend void check_interrupt();
  void check();
  Poll poll_;
  std::chrono::steady_clock::duration interval_;
  std::chrono::steady_clock::time_point next_;
  InterruptScope* previous_;
  std::uint64_t polls_ = 0;
  bool stopped_ = false;
};

namespace detail {
// The scope installed on this thread (nullptr: none).
inline InterruptScope*& current_interrupt_scope() noexcept {
  thread_local InterruptScope* scope = nullptr;
  return scope;
}
}  // namespace detail

// Throws Interrupted if the scope installed on this thread asks to stop;
// nothing without a scope. Cheap enough for loops whose body costs a
// microsecond or more (one clock read with a scope).
inline void check_interrupt() {
  InterruptScope* s = detail::current_interrupt_scope();
  if (s != nullptr) s->check();
}

inline InterruptScope::InterruptScope(Poll poll, std::chrono::steady_clock::duration interval)
    : poll_(std::move(poll)),
      interval_(interval),
      next_(std::chrono::steady_clock::now() + interval),
      previous_(detail::current_interrupt_scope()) {
  detail::current_interrupt_scope() = this;
}

inline InterruptScope::~InterruptScope() { detail::current_interrupt_scope() = previous_; }

inline void InterruptScope::check() {
  if (stopped_) throw Interrupted{};
  if (std::chrono::steady_clock::now() < next_) return;
  ++polls_;
  if (poll_ && poll_()) {
    stopped_ = true;
    throw Interrupted{};
  }
  // From the end of the poll: a slow poll (waiting for a lock) is not
  // repeated back to back.
  next_ = std::chrono::steady_clock::now() + interval_;
}

}  // namespace movingpunch

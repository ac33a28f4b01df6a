// Exceptions thrown by the numerical core. Only the binding layer knows Python types.
#pragma once

#include <stdexcept>
#include <string>

namespace movingpunch {

// vstar at or above the critical speed: no bounded steady solution exists.
class SupercriticalSpeedError : public std::domain_error {
 public:
  SupercriticalSpeedError(double vstar, double critical, double rayleigh);
  // The same naming the foundation in the message, e.g. "kw = 1, kp = 0.2"
  // (a Pasternak base: V*_cr depends on kp too).
  SupercriticalSpeedError(double vstar, double critical, double rayleigh,
                          const std::string& foundation);
  double vstar() const noexcept { return vstar_; }
  double critical() const noexcept { return critical_; }
  double rayleigh() const noexcept { return rayleigh_; }

 private:
  double vstar_, critical_, rayleigh_;
};

// The single-contact solution violates p >= 0 or non-penetration outside (-a, a).
class UnphysicalContactError : public std::domain_error {
 public:
  using std::domain_error::domain_error;
};

// An iteration failed to meet its tolerance within its budget.
class ConvergenceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A named input outside its valid range: name() is the parameter as the
// Python API spells it ("nu", "vstar", ...), allowed() its valid range as
// text ("[0, 0.5)"); what() is the whole message. The bindings turn it into
// movingpunch.InvalidParameterError with .parameter and .allowed set.
class InvalidParameter : public std::invalid_argument {
 public:
  InvalidParameter(std::string name, std::string allowed, const std::string& message);
  const std::string& name() const noexcept { return name_; }
  const std::string& allowed() const noexcept { return allowed_; }

 private:
  std::string name_, allowed_;
};

// Throws InvalidParameter naming `name` and the valid range unless
// lo <= value <= hi (open ends when the flags say so). NaN always fails.
void require_in_range(const char* name, double value, double lo, double hi, bool lo_open,
                      bool hi_open, bool allow_inf_hi = false);

}  // namespace movingpunch

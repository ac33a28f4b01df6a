#include "movingpunch/errors.hpp"

#include <cmath>
#include <sstream>
#include <utility>

namespace movingpunch {

namespace {
std::string supercritical_message(double vstar, double critical, double rayleigh,
                                  const std::string& foundation = "") {
  std::ostringstream m;
  m.precision(10);
  m << "vstar = " << vstar << " is at or above the critical speed V*_cr = " << critical
    << " of this layer on its foundation";
  if (!foundation.empty()) m << " (" << foundation << ")";
  m << " (Rayleigh value V*_R = " << rayleigh
    << "); no bounded steady solution exists there: vstar must be in [0, " << critical << ")";
  return m.str();
}
}  // namespace

SupercriticalSpeedError::SupercriticalSpeedError(double vstar, double critical, double rayleigh)
    : std::domain_error(supercritical_message(vstar, critical, rayleigh)),
      vstar_(vstar),
      critical_(critical),
      rayleigh_(rayleigh) {}

SupercriticalSpeedError::SupercriticalSpeedError(double vstar, double critical, double rayleigh,
                                                 const std::string& foundation)
    : std::domain_error(supercritical_message(vstar, critical, rayleigh, foundation)),
      vstar_(vstar),
      critical_(critical),
      rayleigh_(rayleigh) {}

InvalidParameter::InvalidParameter(std::string name, std::string allowed,
                                   const std::string& message)
    : std::invalid_argument(message), name_(std::move(name)), allowed_(std::move(allowed)) {}

void require_in_range(const char* name, double value, double lo, double hi, bool lo_open,
                      bool hi_open, bool allow_inf_hi) {
  const bool inf_ok = allow_inf_hi && std::isinf(value) && value > 0;
  bool ok = !std::isnan(value) && (inf_ok || std::isfinite(value));
  if (ok && !inf_ok) {
    ok = (lo_open ? value > lo : value >= lo) && (hi_open ? value < hi : value <= hi);
  }
  if (ok) return;
  std::ostringstream range;
  range.precision(10);
  range << (lo_open ? "(" : "[") << lo << ", ";
  if (allow_inf_hi)
    range << "inf]";
  else
    range << hi << (hi_open ? ")" : "]");
  std::ostringstream m;
  m.precision(10);
  m << name << " must be in " << range.str() << ", got " << value;
  throw InvalidParameter(name, range.str(), m.str());
}

}  // namespace movingpunch

#include "option_builders.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "partreg/core/geometry/part_selection.hpp"

namespace partreg::core::detail {

// The shortest text that reads back as exactly `value` (0.03, not 0.029999999999999999).
std::string text_of(double value) {
  for (int digits = 6;; ++digits) {
    std::ostringstream out;
    out.precision(digits);
    out << value;
    if (digits >= 17 || std::strtod(out.str().c_str(), nullptr) == value) return out.str();
  }
}

double real_in(const std::string& text, const std::string& what, double low, double high) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value))
    throw UsageError(what + " must be a number, not '" + text + "'");
  if (value < low || value > high)
    throw UsageError(what + " must be in [" + text_of(low) + ", " + text_of(high) + "], not " + text);
  return value;
}

int integer_in(const std::string& text, const std::string& what, int low, int high) {
  const double value = real_in(text, what, low, high);
  if (value != std::floor(value)) throw UsageError(what + " must be a whole number, not '" + text + "'");
  return static_cast<int>(value);
}

bool boolean(const std::string& text, const std::string& what) {
  if (text == "true" || text == "1" || text == "on" || text == "yes") return true;
  if (text == "false" || text == "0" || text == "off" || text == "no") return false;
  throw UsageError(what + " must be true or false, not '" + text + "'");
}

Eigen::Vector3d finite_vector(const std::string& text, const std::string& what) {
  const Eigen::Vector3d v = parse_vector3(text, what);
  if (!v.allFinite()) throw UsageError(what + " must be finite, not '" + text + "'");
  return v;
}

Eigen::Vector3d up_axis_in(const std::string& text) {
  const Eigen::Vector3d up = finite_vector(text, "up");
  if (!(up.norm() > 1e-12)) throw UsageError("up axis " + text + " has zero length");
  return up;
}

std::string vector_text(const Eigen::Vector3d& v) {
  return text_of(v.x()) + "," + text_of(v.y()) + "," + text_of(v.z());
}

}  // namespace partreg::core::detail
